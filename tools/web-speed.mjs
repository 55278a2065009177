// The web page's speed against the native tracers, side by side: rounds of the page's renderer
// (WebAssembly in headless Chromium: its packet kernels' SIMD128 instance, or the scalar renderer
// in a page without them) and the native phonglab-bench, scalar and packet,
// alternating, on the same scene, size and thread count. With THREADS > 1 the page is served
// cross-origin isolated from a local server (as tools/dev.sh serve does) and runs its threaded module.
//
//   node tools/web-speed.mjs PAGE BENCH [SCENE] [WxH] [ROUNDS] [THREADS]
//
// PAGE: build-web/phonglab.html; BENCH: build/bin/phonglab-bench. Prints each round's medians
// and the medians of the rounds, as Mrays/s and as ratios to the native scalar renderer.
import { execFileSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import { createRequire } from 'node:module';

const require = createRequire(path.resolve('tests/web/package.json'));
const puppeteer = require('puppeteer-core');
const [page_path, bench, scene = 'lecture', size = '640x360', rounds_arg = '5', threads_arg = '1'] = process.argv.slice(2);
const threads = Number(threads_arg);
const [width, height] = size.split('x').map(Number);
const rounds = Number(rounds_arg);
const median = (v) => [...v].sort((a, b) => a - b)[Math.floor(v.length / 2)];

const browser = await puppeteer.launch({ executablePath: '/usr/bin/chromium', headless: 'new',
                                         args: ['--no-sandbox', '--disable-gpu'] });
const page = await browser.newPage();
const query = `?scene=${scene}&size=${size}&spp=1&view=only&threads=${threads}`;
let server = null;
if (threads > 1) {
  const html = readFileSync(page_path);
  server = http.createServer((request, response) => {
    response.writeHead(200, { 'Content-Type': 'text/html', 'Cross-Origin-Opener-Policy': 'same-origin',
                              'Cross-Origin-Embedder-Policy': 'require-corp' });
    response.end(html);
  });
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  await page.goto(`http://127.0.0.1:${server.address().port}/phonglab.html${query}`);
} else {
  await page.goto(`file://${path.resolve(page_path)}${query}`);
}
await page.waitForFunction('window.phonglab && window.phonglab.ready', { timeout: 60000 });
const page_threads = await page.evaluate(() => window.phonglab.state().threads);
const page_simd = await page.evaluate(() => window.phonglab.state().simd || '');
if (page_threads !== threads) throw new Error(`the page renders on ${page_threads} threads, not ${threads}`);
function native(scalar) {
  const args = [scene, '--frames', '7', '--threads', String(threads), '--width', String(width), '--height', String(height)];
  const out = execFileSync(bench, scalar ? [...args, '--scalar'] : args).toString();
  const ms = Number(/median frame: ([0-9.]+) ms/.exec(out)[1]);
  const rays = Number(/rays per frame: (\d+)/.exec(out)[1]);
  tracer = /, ([^,]*(?:, \d+ lanes\))?) tracer/.exec(out)?.[1] ?? tracer;
  return { ms, rays };
}
const rows = { web: [], scalar: [], packet: [] };
let tracer = 'packet';
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
if (server) server.close();
const mrays = (ms) => (rays / ms / 1e3).toFixed(1);
const web = median(rows.web), scalar = median(rows.scalar), packet = median(rows.packet);
console.log(`${scene} ${size}, ${threads} thread(s), ${rays} rays a frame, medians of ${rounds} rounds:`);
const pad = (text) => text.padEnd(36);
console.log(`  ${pad(`web page (WebAssembly, ${page_simd || 'scalar'})`)}${web.toFixed(1)} ms  ${mrays(web)} Mrays/s  ${(scalar / web).toFixed(2)}x native scalar`);
console.log(`  ${pad('native scalar')}${scalar.toFixed(1)} ms  ${mrays(scalar)} Mrays/s  1.00x`);
console.log(`  ${pad(`native ${tracer}`)}${packet.toFixed(1)} ms  ${mrays(packet)} Mrays/s  ${(scalar / packet).toFixed(2)}x native scalar`);
