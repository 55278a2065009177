// The camera drag in the web page, as a student's hand makes it: a real mouse drag across the
// image (60 moves, one a frame, for about a second), with every image the page shows counted by
// level (full, the quad-shaded rung, 1/2, 1/4, 1/8). Several pages side by side, alternating rounds, so a
// change of the machine's load hits them alike.
//
//   node tools/web-drag.mjs [--size WxH] [--scene NAME] [--rounds N] PAGE...
//
// Prints, per page, the shown images by level summed over the rounds, the share exact at full
// resolution, and the images shown a second.
import path from 'node:path';
import { createRequire } from 'node:module';

const require = createRequire(path.resolve('tests/web/package.json'));
const puppeteer = require('puppeteer-core');
const args = process.argv.slice(2);
const option = (name, fallback) => {
  const at = args.indexOf(name);
  if (at < 0) return fallback;
  const [value] = args.splice(at, 2).slice(1);
  return value;
};
const size = option('--size', '640x360'), scene = option('--scene', 'lecture'), rounds = Number(option('--rounds', '3'));
const [width, height] = size.split('x').map(Number);
const pages = args;
const browser = await puppeteer.launch({ executablePath: '/usr/bin/chromium', headless: 'new',
                                         args: ['--no-sandbox', '--disable-gpu'] });
const totals = pages.map(() => ({ levels: {}, images: 0, seconds: 0 }));
for (let r = 0; r < rounds; ++r) {
  for (const [i, file] of pages.entries()) {
    const page = await browser.newPage();
    await page.setViewport({ width: width + 420, height: height + 200 });
    await page.goto(`file://${path.resolve(file)}?scene=${scene}&size=${size}&view=only`);
    await page.waitForFunction('window.phonglab && window.phonglab.ready', { timeout: 60000 });
    await page.waitForFunction('(() => { const s = window.phonglab.state(); return s.current && s.divisor === 1 && !s.quads; })()', { timeout: 60000 });
    // Every image shown while the hand moves, by its level (the page counts frames it draws).
    await page.evaluate(() => {
      window.dragLog = [];
      let seen = window.phonglab.frames;
      const watch = () => {
        if (window.phonglab.frames !== seen) {
          seen = window.phonglab.frames;
          const s = window.phonglab.state();
          window.dragLog.push(s.quads ? 0 : s.divisor);  // 0: the quad-shaded rung
        }
        if (!window.dragDone) requestAnimationFrame(watch);
      };
      requestAnimationFrame(watch);
    });
    const box = await (await page.$('#image')).boundingBox();
    const x0 = box.x + box.width * 0.3, y = box.y + box.height * 0.5;
    await page.mouse.move(x0, y);
    await page.mouse.down();
    const start = Date.now();
    for (let k = 1; k <= 60; ++k) {
      await page.mouse.move(x0 + k * box.width * 0.006, y + Math.sin(k / 9) * box.height * 0.05);
      await new Promise((resolve) => setTimeout(resolve, 16));
    }
    const seconds = (Date.now() - start) / 1000;
    const log = await page.evaluate(() => { window.dragDone = true; return window.dragLog; });
    await page.mouse.up();
    const t = totals[i];
    for (const d of log) t.levels[d] = (t.levels[d] || 0) + 1;
    t.images += log.length;
    t.seconds += seconds;
    await page.close();
  }
}
await browser.close();
console.log(`${scene} ${size}, one thread (file://), ${rounds} rounds of a 60-move drag:`);
for (const [i, file] of pages.entries()) {
  const t = totals[i];
  const levels = [1, 0, 2, 4, 8].map((d) => `${d === 1 ? 'full' : d === 0 ? 'quads' : `1/${d}`}=${t.levels[d] || 0}`).join(' ');
  const full = t.images ? (100 * (t.levels[1] || 0)) / t.images : 0;
  console.log(`  ${file}: ${levels}; full on ${full.toFixed(0)} % of ${t.images} images, ${(t.images / t.seconds).toFixed(1)} images/s`);
}
