// The web page's speed against the native tracers, side by side: rounds of the page's scalar
// renderer (WebAssembly in headless Chromium, one thread) and the native phonglab-bench on one
// thread, scalar and packet, alternating, on the same scene and size.
//
//   node tools/web-speed.mjs PAGE BENCH [SCENE] [WxH] [ROUNDS]
//
// PAGE: build-web/phonglab.html; BENCH: build/bin/phonglab-bench. Prints each round's medians
// and the medians of the rounds, as Mrays/s and as ratios to the native scalar renderer.
import { execFileSync } from 'node:child_process';
import path from 'node:path';
import { createRequire } from 'node:module';

const require = createRequire(path.resolve('tests/web/package.json'));
const puppeteer = require('puppeteer-core');
const [page_path, bench, scene = 'lecture', size = '640x360', rounds_arg = '5'] = process.argv.slice(2);
const [width, height] = size.split('x').map(Number);
const rounds = Number(rounds_arg);
const median = (v) => [...v].sort((a, b) => a - b)[Math.floor(v.length / 2)];

const browser = await puppeteer.launch({ executablePath: '/usr/bin/chromium', headless: 'new',
                                         args: ['--no-sandbox', '--disable-gpu'] });
const page = await browser.newPage();
await page.goto(`file://${path.resolve(page_path)}?scene=${scene}&size=${size}&spp=1&view=only`);
await page.waitForFunction('window.phonglab && window.phonglab.ready', { timeout: 60000 });
function native(scalar) {
  const args = [scene, '--frames', '7', '--threads', '1', '--width', String(width), '--height', String(height)];
  const out = execFileSync(bench, scalar ? [...args, '--scalar'] : args).toString();
  const ms = Number(/median frame: ([0-9.]+) ms/.exec(out)[1]);
  const rays = Number(/rays per frame: (\d+)/.exec(out)[1]);
  return { ms, rays };
}
const rows = { web: [], scalar: [], packet: [] };
let rays = 0;
for (let r = 0; r < rounds; ++r) {
  const web = JSON.parse(await page.evaluate(() => window.phonglab.view.bench(7)));
  rows.web.push(median(web.ms));
  rays = web.rays;
  rows.scalar.push(native(true).ms);
  rows.packet.push(native(false).ms);
  console.log(`round ${r + 1}: web ${rows.web[r].toFixed(1)} ms, native scalar ${rows.scalar[r].toFixed(1)} ms, ` +
              `native packet ${rows.packet[r].toFixed(1)} ms`);
}
await browser.close();
const mrays = (ms) => (rays / ms / 1e3).toFixed(1);
const web = median(rows.web), scalar = median(rows.scalar), packet = median(rows.packet);
console.log(`${scene} ${size}, one thread, ${rays} rays a frame, medians of ${rounds} rounds:`);
console.log(`  web page (WebAssembly, scalar)  ${web.toFixed(1)} ms  ${mrays(web)} Mrays/s  ${(scalar / web).toFixed(2)}x native scalar`);
console.log(`  native scalar                   ${scalar.toFixed(1)} ms  ${mrays(scalar)} Mrays/s  1.00x`);
console.log(`  native packet (AVX2)            ${packet.toFixed(1)} ms  ${mrays(packet)} Mrays/s  ${(scalar / packet).toFixed(2)}x native scalar`);
