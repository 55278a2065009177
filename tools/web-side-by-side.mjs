// Two builds of the web page side by side in one headless Chromium, alternating: rounds of each
// page's bench (7 passes of 1 spp on one thread, the median) on the same scene and size, and
// whether their images have the same bits.
//
//   node tools/web-side-by-side.mjs PAGE_A PAGE_B [SCENE] [WxH] [ROUNDS]
//
// Prints each round's medians and the median of the rounds' ratios B / A of the frame times.
import path from 'node:path';
import { createRequire } from 'node:module';

const require = createRequire(path.resolve('tests/web/package.json'));
const puppeteer = require('puppeteer-core');
const [page_a, page_b, scene = 'lecture', size = '640x360', rounds_arg = '5'] = process.argv.slice(2);
const rounds = Number(rounds_arg);
const median = (v) => [...v].sort((a, b) => a - b)[Math.floor(v.length / 2)];

const browser = await puppeteer.launch({ executablePath: '/usr/bin/chromium', headless: 'new',
                                         args: ['--no-sandbox', '--disable-gpu'] });
async function open(file) {
  const page = await browser.newPage();
  await page.goto(`file://${path.resolve(file)}?scene=${scene}&size=${size}&spp=1&view=only`);
  await page.waitForFunction('window.phonglab && window.phonglab.ready', { timeout: 60000 });
  await page.waitForFunction('(() => { const s = window.phonglab.state(); return s.current && s.divisor === 1 && !s.quads; })()',
                             { timeout: 120000 });
  return page;
}
const pages = [await open(page_a), await open(page_b)];
const [image_a, image_b] = await Promise.all(pages.map((p) => p.evaluate(() => Array.from(window.phonglab.view.pixels()))));
const same = image_a.length === image_b.length && image_a.every((v, i) => v === image_b[i]);
const ratios = [];
for (let r = 0; r < rounds; ++r) {
  const ms = [];
  for (const page of pages) ms.push(median(JSON.parse(await page.evaluate(() => window.phonglab.view.bench(7))).ms));
  ratios.push(ms[1] / ms[0]);
  console.log(`round ${r + 1}: A ${ms[0].toFixed(1)} ms, B ${ms[1].toFixed(1)} ms, B/A ${ratios[r].toFixed(3)}`);
}
await browser.close();
console.log(`${scene} ${size}, one thread: B/A ${median(ratios).toFixed(3)} (median of ${rounds} rounds); ` +
            `images ${same ? 'the same bits' : 'DIFFERENT'}`);
