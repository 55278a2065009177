// The web page at a laptop's and a phone's size (docs/web.md's pictures): lecture with no size in
// the address (the image fills what the panel leaves), at 1366x768, and at 390x844 with a
// device pixel ratio of 3 and touch, in headless Chromium.
//
//   node tools/web-layouts.mjs build-web/phonglab.html OUT_DIR
import path from 'node:path';
import { createRequire } from 'node:module';

const require = createRequire(path.resolve('tests/web/package.json'));
const puppeteer = require('puppeteer-core');
const [page_path, out] = process.argv.slice(2);
const browser = await puppeteer.launch({ executablePath: '/usr/bin/chromium', headless: 'new',
                                         args: ['--no-sandbox', '--disable-gpu', '--allow-file-access-from-files'] });
for (const [name, viewport, hash] of [
  ['web-laptop.png', { width: 1366, height: 768 }, ''],
  ['web-laptop-lesson.png', { width: 1366, height: 768 }, '#lesson=shading&step=6'],
  ['web-phone.png', { width: 390, height: 844, deviceScaleFactor: 3, isMobile: true, hasTouch: true }, ''],
]) {
  const page = await browser.newPage();
  await page.setViewport(viewport);
  await page.goto(`file://${path.resolve(page_path)}?scene=lecture&spp=4${hash}`);
  await page.waitForFunction('window.phonglab && window.phonglab.ready', { timeout: 60000 });
  await page.waitForFunction('(() => { const s = window.phonglab.state(); return s.current && s.divisor === 1 && !s.quads && s.spp >= 4; })()',
                             { timeout: 300000 });
  await new Promise((resolve) => setTimeout(resolve, 300));
  const layout = await page.evaluate(() => {
    const r = document.getElementById('image').getBoundingClientRect();
    return { image: [r.x, r.y, r.width, r.height], render: window.phonglab.state().width + 'x' + window.phonglab.state().height,
             page_width: document.documentElement.scrollWidth };
  });
  console.log(name, JSON.stringify(layout));
  await page.screenshot({ path: path.join(out, name) });
  await page.close();
}
await browser.close();
