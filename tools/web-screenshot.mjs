// The README's picture of the web page: lecture at 640x360 and 16 spp in headless Chromium, the
// glass sphere shift-clicked (its probe and ray tree shown), the window 1280x720.
//
//   node tools/web-screenshot.mjs build-web/phonglab.html docs/images/web-page.png
import path from 'node:path';
import { createRequire } from 'node:module';

const require = createRequire(path.resolve('tests/web/package.json'));
const puppeteer = require('puppeteer-core');
const [page_path, out] = process.argv.slice(2);
const browser = await puppeteer.launch({ executablePath: '/usr/bin/chromium', headless: 'new',
                                         args: ['--no-sandbox', '--disable-gpu'] });
const page = await browser.newPage();
await page.setViewport({ width: 1280, height: 720 });
await page.goto(`file://${path.resolve(page_path)}?scene=lecture&size=640x360&spp=16`);
await page.waitForFunction('window.phonglab && window.phonglab.ready', { timeout: 60000 });
const box = await (await page.$('#image')).boundingBox();
await page.keyboard.down('Shift');
await page.mouse.click(box.x + 380, box.y + 250);
await page.keyboard.up('Shift');
await page.waitForFunction('(() => { const s = window.phonglab.state(); return s.current && s.divisor === 1 && !s.quads && s.spp >= 16; })()',
                           { timeout: 300000 });
await new Promise((resolve) => setTimeout(resolve, 300));
await page.screenshot({ path: out });
await browser.close();
