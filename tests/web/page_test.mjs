// The web page (build-web/phonglab.html) in headless Chromium, from file://, with real input
// events through the DevTools protocol (puppeteer-core over Debian's chromium):
//
//   node tests/web/page_test.mjs PAGE CLI OUT_DIR
//
// PAGE: build-web/phonglab.html; CLI: a native phonglab-cli (the reference image); OUT_DIR: where
// screenshots and images go. Checks: the page loads and its first image arrives; the image at
// spp=4 equals the native CLI's PNG of the same scene and size within 1 code per channel on 99.9 %
// of the pixels; a kd slider drag changes the diffuse term and not the specular one; an orbit drag
// moves the image; a light's marker dragged moves the light, a shift-drag pans, M shows all five;
// a shift-click draws the pixel's ray tree, the depth cut gives the CLI's --max-depth image;
// Take A and the wipe show A and the live image side by side, bit for bit; a click picks the material under it; a broken scene file shows its positioned
// error and keeps the last good scene; served cross-origin isolated (as tools/dev.sh serve does),
// the page starts its threaded module, renders on every core and gives the same bits as from
// file:// on one thread. Exit 0 when every check passes.
import { execFileSync } from 'node:child_process';
import { existsSync, mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import puppeteer from 'puppeteer-core';

const [page_path, cli, out] = process.argv.slice(2);
mkdirSync(out, { recursive: true });
let failures = 0;
function check(ok, what) {
  console.log(`  ${ok ? 'ok  ' : 'FAIL'}  ${what}`);
  if (!ok) failures++;
}

// Raw RGB bytes of a PNG, through ImageMagick.
function png_rgb(file) { return execFileSync('convert', [file, '-depth', '8', 'rgb:-'], { maxBuffer: 1 << 26 }); }

const browser = await puppeteer.launch({
  executablePath: '/usr/bin/chromium', headless: 'new',
  args: ['--no-sandbox', '--allow-file-access-from-files', '--disable-gpu'] });
const url = (query) => 'file://' + path.resolve(page_path) + '?' + query;

async function open(query, address = url(query)) {
  const page = await browser.newPage();
  page.on('pageerror', (e) => console.log('  page error: ' + e.message));
  await page.setViewport({ width: 1280, height: 720 });
  await page.goto(address);
  await page.waitForFunction('window.phonglab && window.phonglab.ready', { timeout: 60000 });
  return page;
}
// Waits until the page's image is of the view as it is now, at full resolution with `spp`
// samples; returns its RGB bytes.
async function image_at(page, spp) {
  await page.waitForFunction(`(() => { const s = window.phonglab.state(); return s.current && s.divisor === 1 && !s.quads && s.spp >= ${spp}; })()`,
                             { timeout: 120000 });
  const rgba = await page.evaluate(() => Array.from(window.phonglab.view.pixels()));
  const rgb = Buffer.alloc(rgba.length / 4 * 3);
  for (let i = 0, j = 0; i < rgba.length; i += 4, j += 3) rgb[j] = rgba[i], rgb[j + 1] = rgba[i + 1], rgb[j + 2] = rgba[i + 2];
  return rgb;
}
// The RGB bytes on the page's canvas: what the user sees.
async function canvas_rgb(page) {
  const rgba = await page.evaluate(() => {
    const c = document.getElementById('image');
    return Array.from(c.getContext('2d').getImageData(0, 0, c.width, c.height).data);
  });
  const rgb = Buffer.alloc(rgba.length / 4 * 3);
  for (let i = 0, j = 0; i < rgba.length; i += 4, j += 3) rgb[j] = rgba[i], rgb[j + 1] = rgba[i + 1], rgb[j + 2] = rgba[i + 2];
  return rgb;
}
function differing(a, b, tolerance) {
  let count = 0;
  for (let i = 0; i < a.length; i += 3) {
    if (Math.abs(a[i] - b[i]) > tolerance || Math.abs(a[i + 1] - b[i + 1]) > tolerance ||
        Math.abs(a[i + 2] - b[i + 2]) > tolerance) count++;
  }
  return count;
}

// 1. The first image, and the image at 4 spp against the native CLI's.
let one_thread_image;
{
  const page = await open('scene=lecture&size=320x180&spp=4');
  await page.waitForFunction('window.phonglab.frames > 0', { timeout: 60000 });
  check(true, 'the page loads from file:// and its first image arrives');
  const web = await image_at(page, 4);
  await page.screenshot({ path: path.join(out, 'lecture.png') });
  execFileSync(cli, ['render', 'lecture', '-o', path.join(out, 'cli.png'), '--width', '320', '--height', '180', '--spp', '4']);
  const native = png_rgb(path.join(out, 'cli.png'));
  const pixels = native.length / 3;
  const off = web.length === native.length ? differing(web, native, 1) : pixels;
  check(off <= pixels / 1000, `spp=4 equals phonglab-cli render's PNG within 1 code on 99.9 % of pixels (${off} of ${pixels} differ)`);
  const state = await page.evaluate(() => window.phonglab.state());
  check(!state.isolated && state.threads === 1, 'from file:// the page is not cross-origin isolated and renders on one thread');
  const status = await page.$eval('#status', (e) => e.textContent);
  check(state.simd === 'SIMD128' && status.includes('SIMD128, one thread'),
        `the page traces in packets with its SIMD128 kernels and says so (${state.simd}: "${status}")`);
  one_thread_image = web;
  await page.close();
}

// 2. A kd slider drag changes the diffuse term, not the specular one; an orbit drag moves the image.
{
  const page = await open('scene=lecture&size=320x180&spp=1');
  const term_image = async (key) => {
    await page.keyboard.press(key);
    const term = await page.evaluate(() => window.phonglab.state().term);
    if (term !== Number(key) - 1) throw new Error(`key ${key} did not choose term ${Number(key) - 1} (term ${term})`);
    return image_at(page, 1);
  };
  // The plastic sphere's material, picked by a click on it.
  const box = await (await page.$('#image')).boundingBox();
  await page.mouse.click(box.x + box.width * 0.44, box.y + box.height * 0.6);
  const picked = await page.evaluate(() => window.phonglab.state().material);
  check(picked >= 0, `a click picks the material under it (material ${picked})`);
  const diffuse_before = await term_image('3'), specular_before = await term_image('4');
  const slider = await (await page.$('#slider-kd')).boundingBox();
  await page.mouse.move(slider.x + slider.width * 0.8, slider.y + slider.height / 2);
  await page.mouse.down();
  await page.mouse.move(slider.x + slider.width * 0.2, slider.y + slider.height / 2, { steps: 8 });
  await page.waitForFunction('(() => { const s = window.phonglab.state(); return s.current && s.live; })()', { timeout: 30000 });
  const held = await page.evaluate(() => window.phonglab.state());
  check(held.divisor === 1, `while the hand is on the kd slider the image is at full resolution, recombined from the ray trees (1/${held.divisor})`);
  await page.mouse.up();
  const specular_after = await image_at(page, 1);
  const let_go = await page.evaluate(() => window.phonglab.state());
  check(!let_go.live && let_go.reshaded, '... and when it lets go, the exact re-shade replaces it');
  const diffuse_after = await term_image('3');
  check(differing(diffuse_before, diffuse_after, 0) > 100, 'a kd slider drag changes the diffuse term');
  check(differing(specular_before, specular_after, 0) === 0, '... and not the specular term');
  const full_before = await term_image('1');
  writeFileSync(path.join(out, 'edited.json'), await page.evaluate(() => window.phonglab.view.sceneJson()));
  execFileSync(cli, ['render', path.join(out, 'edited.json'), '-o', path.join(out, 'edited.png'), '--width', '320',
                     '--height', '180', '--spp', '1']);
  const edited_off = differing(full_before, png_rgb(path.join(out, 'edited.png')), 0);
  check(edited_off === 0, `the re-shaded image after the drag has the bits of the CLI's image of the edited scene (${edited_off} pixels differ)`);
  await page.mouse.move(box.x + box.width * 0.5, box.y + box.height * 0.5);
  await page.mouse.down();
  await page.mouse.move(box.x + box.width * 0.7, box.y + box.height * 0.5, { steps: 6 });
  await page.waitForFunction('window.phonglab.state().current', { timeout: 30000 });
  const dragging = await page.evaluate(() => window.phonglab.state());
  check(dragging.divisor <= 4, `while the hand orbits, each edit's image is one pass at the live level (1/${dragging.divisor}: its pass fits a 24th of a second)`);
  await page.mouse.up();
  const full_after = await image_at(page, 1);
  check(differing(full_before, full_after, 0) > 1000, 'an orbit drag moves the image');
  await page.screenshot({ path: path.join(out, 'after-drags.png') });
  await page.close();
}

// 2b. A light's marker dragged moves the light in the view plane; a shift-drag pans; M shows the
// five terms and the full image side by side.
{
  const page = await open('scene=lecture&size=320x180&spp=1');
  const before = await image_at(page, 1);
  const state = await page.evaluate(() => window.phonglab.state());
  const l = state.markers.findIndex((m) => m);
  check(l >= 0, `a point light's marker is drawn over the image, at its edge when out of it (${JSON.stringify(state.markers)})`);
  const box = await (await page.$('#image')).boundingBox();
  const [mx, my] = state.markers[Math.max(l, 0)];
  const light_of = async () => JSON.parse(await page.evaluate(() => window.phonglab.view.sceneJson())).lights[Math.max(l, 0)].position;
  const position_before = await light_of();
  await page.mouse.move(box.x + mx, box.y + my);
  await page.mouse.down();
  await page.mouse.move(box.x + mx - 60, box.y + my + 40, { steps: 5 });
  await page.mouse.up();
  const after = await image_at(page, 1);
  await page.screenshot({ path: path.join(out, 'light-drag.png') });
  const moved = (await page.evaluate(() => window.phonglab.state())).markers[Math.max(l, 0)];
  const position_after = await light_of();
  check(moved && !moved[2] && Math.abs(moved[0] - mx + 60) < 1.5 && Math.abs(moved[1] - my - 40) < 1.5,
        `dragging the marker moves the light under the pointer (${mx.toFixed(1)}, ${my.toFixed(1)} -> ${moved && moved.map((v) => +v).join(', ')})`);
  check(JSON.stringify(position_before) !== JSON.stringify(position_after) && differing(before, after, 0) > 100,
        `... the scene's light moves (${position_before} -> ${position_after}) and the shading with it`);
  const camera = async () => JSON.parse(await page.evaluate(() => window.phonglab.view.sceneJson())).camera;
  const c0 = await camera();
  await page.keyboard.down('Shift');
  await page.mouse.move(box.x + 160, box.y + 150);
  await page.mouse.down();
  await page.mouse.move(box.x + 200, box.y + 150, { steps: 5 });
  await page.mouse.up();
  await page.keyboard.up('Shift');
  const c1 = await camera();
  const offset = (c) => c.position.map((p, i) => p - c.look_at[i]);
  const same_offset = offset(c0).every((v, i) => Math.abs(v - offset(c1)[i]) < 1e-9);
  check(same_offset && JSON.stringify(c0.look_at) !== JSON.stringify(c1.look_at),
        `a shift-drag pans: look_at moves, the view direction stays (${c0.look_at} -> ${c1.look_at})`);
  // Two fingers (touch events through the DevTools protocol): moving together they pan, apart
  // they dolly.
  const cdp = await page.target().createCDPSession();
  const touch = async (type, points) => cdp.send('Input.dispatchTouchEvent', {
    type, touchPoints: points.map(([x, y], id) => ({ x: box.x + x, y: box.y + y, id })) });
  const fingers = async (from, to) => {
    await touch('touchStart', from);
    for (let k = 1; k <= 5; ++k) {
      await touch('touchMove', from.map(([x, y], i) => [x + (to[i][0] - x) * k / 5, y + (to[i][1] - y) * k / 5]));
    }
    await touch('touchEnd', []);
  };
  const distance = (c) => Math.hypot(...offset(c));
  await fingers([[120, 90], [200, 90]], [[90, 90], [170, 90]]);
  const c2 = await camera();
  check(Math.abs(distance(c2) - distance(c1)) < 1e-6 && JSON.stringify(c1.look_at) !== JSON.stringify(c2.look_at),
        'two fingers moving together pan (the distance to look_at stays)');
  await fingers([[140, 90], [180, 90]], [[100, 90], [220, 90]]);
  const c3 = await camera();
  check(distance(c3) < distance(c2) - 1e-3, `two fingers moving apart dolly closer (${distance(c2).toFixed(3)} -> ${distance(c3).toFixed(3)})`);
  await (await page.$('#image')).click({ offset: { x: 5, y: 5 } });
  await page.keyboard.press('m');
  await page.waitForFunction('(() => { const s = window.phonglab.state(); return s.multiples && s.current && s.divisor === 1 && !s.quads; })()', { timeout: 60000 });
  const grid = await page.evaluate(() => window.phonglab.state());
  check(grid.width === 3 * Math.floor(320 / 3) && grid.height === 180, `M shows the five terms and the full image, 3 x 2 (${grid.width}x${grid.height})`);
  await page.screenshot({ path: path.join(out, 'multiples.png') });
  await page.close();
}

// 2c. The ray tree of a shift-clicked pixel over the image; the depth cut.
{
  const page = await open('scene=lecture&size=320x180&spp=1');
  await image_at(page, 1);
  const box = await (await page.$('#image')).boundingBox();
  const tree_at = async (x, y) => {
    await page.keyboard.down('Shift');
    await page.mouse.click(box.x + x, box.y + y);
    await page.keyboard.up('Shift');
    return page.evaluate(() => window.phonglab.tree.map((s) => s.kind));
  };
  const mirror = await tree_at(235, 70), glass = await tree_at(190, 125);
  check(mirror.includes('primary') && mirror.includes('reflection') && ['N', 'L', 'R', 'V'].every((k) => mirror.includes(k)),
        `a shift-click on the mirror draws its ray tree: the primary ray, a reflection, N, L, R, V (${[...new Set(mirror)]})`);
  check(glass.includes('refraction'), `... on the glass, a refracted ray (${[...new Set(glass)]})`);
  const probe_text = await page.evaluate(() => document.getElementById('probe').textContent);
  check(probe_text.length > 100, 'and the probe prints its numbers');
  await page.screenshot({ path: path.join(out, 'ray-tree.png') });
  await page.keyboard.press('h');
  const heat = await image_at(page, 1);
  execFileSync(cli, ['render', 'lecture', '-o', path.join(out, 'rays.png'), '--width', '320', '--height', '180', '--spp', '1',
                     '--term', 'rays']);
  const heat_off = differing(heat, png_rgb(path.join(out, 'rays.png')), 0);
  check(heat_off === 0, `H shows the heat map, the bits of phonglab-cli render --term rays (${heat_off} pixels differ)`);
  await page.keyboard.press('h');
  await page.keyboard.press('t');
  const hidden = await page.evaluate(() => window.phonglab.tree.length);
  check(hidden === 0, 'T hides the ray tree');
  const slider = await page.$('#cut');
  await slider.focus();
  await page.keyboard.press('ArrowRight');
  const cut = await page.evaluate(() => window.phonglab.view.depthCut());
  const web = await image_at(page, 1);
  execFileSync(cli, ['render', 'lecture', '-o', path.join(out, 'cut1.png'), '--width', '320', '--height', '180', '--spp', '1',
                     '--max-depth', '1']);
  const off = differing(web, png_rgb(path.join(out, 'cut1.png')), 0);
  check(cut === 1 && off === 0, `the depth cut at 1 has the bits of phonglab-cli render --max-depth 1 (${off} pixels differ)`);
  await page.close();
}

// 2d. The A/B compare: A taken of the finished image, a kd edit, then the wipe shows A's columns
// on the left and the live image's on the right, bit for bit; the difference is black where
// nothing changed.
{
  const page = await open('scene=lecture&size=320x180&spp=2');
  const a = await image_at(page, 2);
  await (await page.$('#take-a')).click();
  await page.waitForFunction('window.phonglab.view.hasA()', { timeout: 30000 });
  const box = await (await page.$('#image')).boundingBox();
  await page.mouse.click(box.x + box.width * 0.44, box.y + box.height * 0.6);  // the plastic sphere
  const slider = await (await page.$('#slider-kd')).boundingBox();
  await page.mouse.click(slider.x + slider.width * 0.15, slider.y + slider.height / 2);
  const live = await image_at(page, 2);
  const drawn = async () => { await image_at(page, 2); await page.waitForTimeout(200); return canvas_rgb(page); };
  await page.select('#compare', '1');
  const wiped = await drawn();
  let wipe_off = 0;
  for (let i = 0; i < wiped.length; i += 3) {
    const x = (i / 3) % 320, source = x < 160 ? a : live;
    if (wiped[i] !== source[i] || wiped[i + 1] !== source[i + 1] || wiped[i + 2] !== source[i + 2]) wipe_off++;
  }
  check(differing(a, live, 0) > 100 && wipe_off === 0,
        `Take A, a kd edit, the wipe on the canvas: A's columns left of the middle, the live image's right of it (${wipe_off} pixels off)`);
  await page.select('#compare', '2');
  const difference = await drawn();
  const black = difference[0] === 0 && difference[1] === 0 && difference[2] === 0;
  check(black && difference.some((v) => v > 0), '|live - A| is black where nothing changed and bright where kd did');
  await page.screenshot({ path: path.join(out, 'compare.png') });
  await page.close();
}

// 3. A lesson: its address opens a step, the Right key goes on, a compare's A is taken and shown.
{
  const page = await open('size=320x180&spp=1#lesson=shading&step=1');
  await page.waitForFunction('window.phonglab.lesson && window.phonglab.lesson.lesson === "shading"', { timeout: 30000 });
  const first = await page.evaluate(() => window.phonglab.lesson);
  check(first.step === 0 && first.steps >= 10, `#lesson=shading&step=1 opens the lesson at its first step (of ${first.steps})`);
  await image_at(page, 1);
  await (await page.$('#image')).click();  // the page has the focus, not a control
  await page.keyboard.press('ArrowRight');
  const second = await page.evaluate(() => window.phonglab.lesson);
  check(second.step === 1, `the Right key goes on to step 2 (${second.step_title})`);
  await page.goto(url('size=320x180&spp=1#lesson=shading&step=7'));
  await page.waitForFunction('window.phonglab.ready && window.phonglab.lesson && window.phonglab.lesson.step === 6', { timeout: 30000 });
  await page.waitForFunction('JSON.parse(window.phonglab.view.lessonState()).compare === true', { timeout: 120000 });
  await image_at(page, 1);
  check(true, 'step 7 takes its A (the head not moved) and shows |live - A|');
  await page.screenshot({ path: path.join(out, 'lesson-step7.png') });
  await page.close();
}

// 4. A broken scene file shows its positioned error; the last good scene stays.
{
  const page = await open('scene=lecture&size=160x90&spp=1');
  const broken = path.join(out, 'broken.json');
  writeFileSync(broken, '{"camera": {"position": [0, 1, 5], "look_at": [0, 0, 0], "fov": "wide"}}\n');
  const input = await page.$('#file');
  await input.uploadFile(broken);
  await page.waitForFunction('window.phonglab.error !== ""', { timeout: 30000 });
  const error = await page.evaluate(() => window.phonglab.error);
  check(/^broken\.json:\d+:\d+: /.test(error), `a broken scene file shows its positioned error (${error.split('\n')[0]})`);
  const kept = await page.evaluate(() => window.phonglab.view.materialCount());
  check(kept === 6, 'the last good scene is kept');
  await page.screenshot({ path: path.join(out, 'broken.png') });
  await page.close();
}

// 6. The page as a student meets it (each shown sharp once with the bug put back).
// 6a. M: every cell is the CLI's term image of the same view (cells a third of the width, two
// rows), bit for bit; the cells are labelled.
{
  const page = await open('scene=lecture&size=480x270&spp=1');
  await image_at(page, 1);
  await (await page.$('#image')).click({ offset: { x: 5, y: 5 } });
  await page.keyboard.press('3');  // the single view's trees recorded first: the grid must not re-shade them
  await image_at(page, 1);
  await page.keyboard.press('m');
  await page.waitForFunction('(() => { const s = window.phonglab.state(); return s.multiples && s.current && s.divisor === 1 && !s.quads; })()', { timeout: 60000 });
  const grid = await image_at(page, 1);
  const state = await page.evaluate(() => window.phonglab.state());
  const cw = 160, ch = 135;
  const names = ['ambient', 'diffuse', 'specular', 'reflection', 'refraction', 'full'];
  let worst = 0;
  const offs = [];
  for (let cell = 0; cell < 6; ++cell) {
    const file = path.join(out, `cell-${names[cell]}.png`);
    execFileSync(cli, ['render', 'lecture', '-o', file, '--width', String(cw), '--height', String(ch), '--spp', '1', '--term', names[cell]]);
    const ref = png_rgb(file);
    let off = 0;
    for (let y = 0; y < ch; ++y) {
      for (let x = 0; x < cw; ++x) {
        const g = ((Math.floor(cell / 3) * ch + y) * state.width + (cell % 3) * cw + x) * 3, r = (y * cw + x) * 3;
        if (grid[g] !== ref[r] || grid[g + 1] !== ref[r + 1] || grid[g + 2] !== ref[r + 2]) off++;
      }
    }
    offs.push(off);
    worst = Math.max(worst, off);
  }
  check(state.width === 480 && state.height === 270 && worst === 0,
        `M's six cells equal phonglab-cli render --term of the same view, bit for bit (${offs.join(', ')} pixels differ)`);
  const labels = await page.evaluate(() => {
    const g = document.getElementById('markers').getContext('2d');
    const d = g.getImageData(0, 0, g.canvas.width, g.canvas.height).data;
    let drawn = 0;
    for (let i = 3; i < d.length; i += 4) drawn += d[i] > 0 ? 1 : 0;
    return drawn;
  });
  check(labels > 500, `... and its cells are labelled (${labels} label pixels over the grid)`);
  await page.screenshot({ path: path.join(out, 'multiples-labelled.png') });
  await page.close();
}

// 6b. A scene file loaded: the Lights panel is its lights'; the scene list names the file; a
// lesson under way ends (its caption goes, the address forgets it).
{
  const page = await open('size=320x180&spp=1#lesson=shading&step=3');
  await page.waitForFunction('window.phonglab.lesson && window.phonglab.lesson.step === 2', { timeout: 30000 });
  const listed = await page.evaluate(() => document.getElementById('scene').value);
  const one_light = path.join(out, 'one-light.json');
  writeFileSync(one_light, JSON.stringify({
    camera: { position: [0, 1, 5], look_at: [0, 0.5, 0], fov_y: 40 },
    lights: [{ type: 'point', position: [2, 4, 3], intensity: 1 }],
    materials: { red: { ka: 0.1, kd: [0.8, 0.1, 0.1], ks: 0.3, n: 20 } },
    objects: [{ type: 'sphere', center: [0, 0.5, 0], radius: 0.5, material: 'red' }] }));
  await (await page.$('#file')).uploadFile(one_light);
  await page.waitForFunction('window.phonglab.view.lightCount() === 1', { timeout: 30000 });
  await page.waitForTimeout(200);
  const panel = await page.evaluate(() => ({
    sliders: document.querySelectorAll('#lights input').length,
    value: Number(document.querySelector('#lights input').value),
    scene: document.getElementById('scene').value,
    caption: getComputedStyle(document.getElementById('caption')).display,
    hash: location.hash, lesson: window.phonglab.lesson }));
  check(listed === 'lecture', `during a lesson the scene list names the step's scene (${listed})`);
  check(panel.sliders === 1 && panel.value === 1, `a one-light file's Lights panel shows its one light at its intensity (${panel.sliders} sliders, ${panel.value})`);
  check(panel.scene === 'one-light.json', `... the scene list names the file (${panel.scene})`);
  check(panel.caption === 'none' && panel.hash === '' && !panel.lesson,
        `... and the lesson ends: no caption over it, the address forgets it (${panel.caption}, '${panel.hash}')`);
  await page.close();
}

// 6c. Leave lesson (the button, and Esc) ends a lesson and clears the address; a reload does not
// bring it back; the term buttons follow a lesson's step.
{
  const page = await open('size=320x180&spp=1#lesson=raytracing&step=8');
  await page.waitForFunction('window.phonglab.lesson && window.phonglab.lesson.step === 7', { timeout: 30000 });
  await page.goto(url('size=320x180&spp=1#lesson=shading&step=3'));
  await page.waitForFunction('window.phonglab.ready && window.phonglab.lesson && window.phonglab.lesson.step === 2', { timeout: 30000 });
  const on = await page.evaluate(() => [...document.querySelectorAll('#terms button')].filter((b) => b.classList.contains('on')).map((b) => b.textContent));
  check(on.length === 1 && on[0] === '4 specular', `a lesson step's term lights its button, and only it (${on})`);
  await (await page.$('#leave-lesson')).click();
  const left = await page.evaluate(() => ({ lesson: window.phonglab.lesson, hash: location.hash,
                                            caption: getComputedStyle(document.getElementById('caption')).display }));
  check(!left.lesson && left.hash === '' && left.caption === 'none', `Leave lesson ends it and clears the address ('${left.hash}')`);
  await page.reload();
  await page.waitForFunction('window.phonglab && window.phonglab.ready', { timeout: 60000 });
  await page.waitForTimeout(300);
  check(!(await page.evaluate(() => window.phonglab.lesson)), '... a reload does not bring it back');
  await page.goto(url('size=320x180&spp=1#lesson=shading&step=2'));
  await page.waitForFunction('window.phonglab.ready && window.phonglab.lesson && window.phonglab.lesson.step === 1', { timeout: 30000 });
  await (await page.$('#image')).click({ offset: { x: 5, y: 5 } });
  await page.keyboard.press('Escape');
  check(!(await page.evaluate(() => window.phonglab.lesson)), 'Esc ends a lesson too');
  await page.close();
}

// 6d. Orbiting upwards never takes the eye under the floor; R brings the file's camera back.
{
  const page = await open('scene=lecture&size=320x180&spp=1');
  await image_at(page, 1);
  const box = await (await page.$('#image')).boundingBox();
  const camera = async () => JSON.parse(await page.evaluate(() => window.phonglab.view.sceneJson())).camera;
  const c0 = await camera();
  for (let k = 0; k < 3; ++k) {
    await page.mouse.move(box.x + 160, box.y + 150);
    await page.mouse.down();
    await page.mouse.move(box.x + 160, box.y + 20, { steps: 8 });
    await page.mouse.up();
  }
  const c1 = await camera();
  check(c1.position[1] > 0, `three upward drags leave the eye above the floor (y ${c0.position[1]} -> ${c1.position[1].toFixed(3)})`);
  await page.keyboard.press('r');
  const c2 = await camera();
  check(JSON.stringify(c2.position) === JSON.stringify(c0.position), `R brings the file's camera back (${c2.position})`);
  await page.close();
}

// 6d'. raytracing step 3, "Is this point lit?": the point is ringed while the question is asked;
// in the answer its L arrows are grey, not the yellow of "light seen".
{
  const page = await open('size=480x270&spp=1#lesson=raytracing&step=3');
  await page.waitForFunction('window.phonglab.lesson && window.phonglab.lesson.step === 2', { timeout: 30000 });
  await image_at(page, 1);
  const asked = await page.evaluate(() => ({ probed: window.phonglab.probed, revealed: window.phonglab.lesson.revealed }));
  check(asked.probed && !asked.revealed, `the question's point is marked while it is asked (${JSON.stringify(asked.probed)})`);
  await (await page.$('#image')).click({ offset: { x: 5, y: 5 } });
  await page.keyboard.press('ArrowRight');
  await page.waitForFunction('window.phonglab.lesson.revealed && window.phonglab.tree.length > 0', { timeout: 30000 });
  const arrows = await page.evaluate(() => window.phonglab.tree.filter((s) => s.kind === 'L'));
  check(arrows.length > 0 && arrows.every((s) => s.blocked && s.colour === '#969696'),
        `the answer's L arrows towards the blocked lights are grey, not yellow (${arrows.map((s) => s.colour)})`);
  await page.screenshot({ path: path.join(out, 'shadow-step.png') });
  await page.close();
}

// 6f. Save image: the image as shown, as PNG, has the bits of the CLI's PNG of the downloaded
// scene at its size and samples; the 1 spp switch shows the pixel centres.
{
  const page = await open('scene=lecture&size=320x180&spp=3');
  await image_at(page, 3);
  await (await page.$('#one-spp')).click();
  await page.waitForFunction('(() => { const s = window.phonglab.state(); return s.current && s.divisor === 1 && !s.quads && s.spp === 1; })()', { timeout: 60000 });
  await page.waitForTimeout(300);
  const downloads = path.join(out, 'downloads');
  mkdirSync(downloads, { recursive: true });
  const cdp = await page.target().createCDPSession();
  await cdp.send('Page.setDownloadBehavior', { behavior: 'allow', downloadPath: downloads });
  await (await page.$('#save-image')).click();
  const saved = path.join(downloads, 'lecture-320x180-1spp.png');
  for (let t = 0; t < 100 && !existsSync(saved); ++t) await new Promise((resolve) => setTimeout(resolve, 100));
  writeFileSync(path.join(out, 'saved-scene.json'), await page.evaluate(() => window.phonglab.view.sceneJson()));
  execFileSync(cli, ['render', path.join(out, 'saved-scene.json'), '-o', path.join(out, 'saved-cli.png'), '--width', '320',
                     '--height', '180', '--spp', '1']);
  const off = existsSync(saved) ? differing(png_rgb(saved), png_rgb(path.join(out, 'saved-cli.png')), 0) : -1;
  check(off === 0, `Save image at the 1 spp switch: the PNG has the bits of phonglab-cli render --spp 1 of the downloaded scene (${off} pixels differ)`);
  await page.close();
}

// 6h. Download scene of a Cornell box: a zip of the scene and the OBJ and MTL files it names,
// read by Python's zipfile (its CRCs checked); unpacked anywhere, phonglab-cli renders it with the
// bits of the embedded scene's image. A scene without meshes downloads as its JSON alone.
{
  const downloads = path.join(out, 'scene-downloads');
  mkdirSync(downloads, { recursive: true });
  for (const [scene, file] of [['cornell-sphere', 'cornell-sphere.zip'], ['lecture', 'lecture.json']]) {
    const page = await open(`scene=${scene}&size=160x90&spp=1`);
    const cdp = await page.target().createCDPSession();
    await cdp.send('Page.setDownloadBehavior', { behavior: 'allow', downloadPath: downloads });
    await (await page.$('#download')).click();
    const saved = path.join(downloads, file);
    for (let t = 0; t < 100 && !existsSync(saved); ++t) await new Promise((resolve) => setTimeout(resolve, 100));
    await new Promise((resolve) => setTimeout(resolve, 200));  // the file complete
    check(existsSync(saved), `Download scene of ${scene} gives ${file}`);
    await page.close();
  }
  const zip = path.join(downloads, 'cornell-sphere.zip'), unpacked = path.join(downloads, 'unpacked');
  let names = '';
  try {
    names = execFileSync('python3', ['-c', `import sys, zipfile
z = zipfile.ZipFile(sys.argv[1])
bad = z.testzip()
if bad: sys.exit('bad CRC: ' + bad)
z.extractall(sys.argv[2])
print(' '.join(z.namelist()))`, zip, unpacked]).toString().trim();
  } catch (e) { names = 'unreadable: ' + e.message; }
  check(names === 'cornell-sphere.json cornell/CornellBox-Sphere.obj cornell/CornellBox-Sphere.mtl',
        `the zip holds the scene and its mesh's files, CRCs right (${names})`);
  let off = -1;
  try {
    const render = (scene, png) => execFileSync(cli, ['render', scene, '-o', png, '--width', '96', '--height', '96', '--spp', '1'],
                                                { stdio: 'pipe' });  // (the MTL's warnings are the CLI's, not the page's)
    render(path.join(unpacked, 'cornell-sphere.json'), path.join(downloads, 'unpacked.png'));
    render('cornell-sphere', path.join(downloads, 'embedded.png'));
    off = differing(png_rgb(path.join(downloads, 'unpacked.png')), png_rgb(path.join(downloads, 'embedded.png')), 0);
  } catch (e) { console.log('  ' + e.message); }
  check(off === 0, `the unpacked download renders as the embedded cornell-sphere, bit for bit (${off} pixels differ)`);
}

// 6g. A phone (390x844, touch): the page is no wider than the screen, the panel below the image;
// one finger orbits, two pinch.
{
  const page = await browser.newPage();
  page.on('pageerror', (e) => console.log('  page error: ' + e.message));
  await page.setViewport({ width: 390, height: 844, deviceScaleFactor: 3, isMobile: true, hasTouch: true });
  await page.goto(url('scene=lecture&spp=1'));
  await page.waitForFunction('window.phonglab && window.phonglab.ready', { timeout: 60000 });
  await image_at(page, 1);
  const fit = await page.evaluate(() => {
    const image = document.getElementById('image').getBoundingClientRect(), panel = document.getElementById('panel').getBoundingClientRect();
    return { page: document.documentElement.scrollWidth, image: [image.width, image.bottom], panel_top: panel.top };
  });
  check(fit.page <= 390 && fit.image[0] <= 390 && fit.panel_top >= fit.image[1],
        `on a phone the page fits its width and the panel is below the image (page ${fit.page} px, image ${fit.image[0]} px wide)`);
  const box = await (await page.$('#image')).boundingBox();
  const camera = async () => JSON.parse(await page.evaluate(() => window.phonglab.view.sceneJson())).camera;
  const cdp = await page.target().createCDPSession();
  const touch = async (type, points) => cdp.send('Input.dispatchTouchEvent', {
    type, touchPoints: points.map(([x, y], id) => ({ x: box.x + x, y: box.y + y, id })) });
  const c0 = await camera();
  await touch('touchStart', [[150, 100]]);
  for (let k = 1; k <= 6; ++k) await touch('touchMove', [[150 + 10 * k, 100]]);
  await touch('touchEnd', []);
  const c1 = await camera();
  check(JSON.stringify(c0.position) !== JSON.stringify(c1.position) && JSON.stringify(c0.look_at) === JSON.stringify(c1.look_at),
        'one finger orbits about look_at');
  const distance = (c) => Math.hypot(...c.position.map((p, i) => p - c.look_at[i]));
  await touch('touchStart', [[170, 100], [210, 100]]);
  for (let k = 1; k <= 5; ++k) await touch('touchMove', [[170 - 8 * k, 100], [210 + 8 * k, 100]]);
  await touch('touchEnd', []);
  const c2 = await camera();
  check(distance(c2) < distance(c1) - 1e-3, `two fingers apart dolly closer (${distance(c1).toFixed(3)} -> ${distance(c2).toFixed(3)})`);
  await page.screenshot({ path: path.join(out, 'phone.png') });
  await page.close();
}

// 6h. Your formula: typed with the real keyboard into the specular box, the wrong sign of R is
// named; a misspelt name is positioned under the box while the last good formula keeps its
// verdict; the reference's own term matches. Then the shading lesson's specular exercise: its
// starter in the box, a hint from the caption's button, and the verdict in the caption. On a
// laptop (1366x768) and a phone (390x844, the keyboard typed into the same box).
for (const [width, height, name] of [[1366, 768, 'laptop'], [390, 844, 'phone']]) {
  const page = await browser.newPage();
  page.on('pageerror', (e) => console.log('  page error: ' + e.message));
  await page.setViewport({ width, height, deviceScaleFactor: name === 'phone' ? 3 : 1, isMobile: name === 'phone',
                           hasTouch: name === 'phone' });
  await page.goto(url('scene=lecture&spp=1&size=320x180'));
  await page.waitForFunction('window.phonglab && window.phonglab.ready', { timeout: 60000 });
  await image_at(page, 1);
  const verdict = async () => {
    await page.waitForFunction(() => window.phonglab.formulaCheck && document.getElementById('formula-verdict').textContent !== 'checking...',
                               { timeout: 60000 });
    return page.evaluate(() => ({ ...window.phonglab.formulaCheck, shown: document.getElementById('formula-verdict').textContent }));
  };
  const box = await page.$('#formula-specular');
  await box.click();
  await page.keyboard.type('R = reflect(L, N); ks * pow(max(0, dot(R, V)), n)');
  const wrong = await verdict();
  check(wrong.verdict === 'differs' && wrong.mistake === 'reflect-sign or view-reversed',
        `${name}: typed, reflect(L, N) is named (${wrong.shown})`);
  await page.keyboard.type(' + nrm');
  const error = await page.evaluate(() => document.getElementById('formula-error-specular').textContent);
  check(error === 'formula:1:53: unknown name "nrm" (did you mean "N"?)', `${name}: a misspelt name is positioned under its box (${error})`);
  const typed = await page.evaluate(() => document.getElementById('formula-specular').value);
  check(typed.endsWith(' + nrm') && !typed.includes('11'), `${name}: keys typed into the box are the box's, not the page's shortcuts`);
  if (name === 'laptop') {
    // A shift-click probes: yours against the reference at the hit, with R's value.
    await page.$eval('#image', (e) => e.scrollIntoView({ block: 'center' }));
    const ibox = await (await page.$('#image')).boundingBox();
    await page.keyboard.down('Shift');
    await page.mouse.click(ibox.x + ibox.width * 0.5, ibox.y + ibox.height * 0.8);
    await page.keyboard.up('Shift');
    const probed = await page.evaluate(() => document.getElementById('probe').textContent);
    const mine = probed.slice(probed.indexOf('at the primary hit'));
    check(/^at the primary hit[\s\S]*specular: yours \([^)]*\), reference \([^)]*\)\n +R = \(/.test(mine),
          `${name}: the probe gives yours against the reference with R's value (${mine.split('\n').slice(0, 4).join(' | ')})`);
  }
  await page.evaluate(() => { window.phonglab.formulaCheck = null; });
  const select_all = async () => {
    await page.keyboard.down('Control');
    await page.keyboard.press('KeyA');
    await page.keyboard.up('Control');
  };
  await box.click();
  await select_all();
  await page.keyboard.type('R = reflect(-L, N); ks * pow(max(0, dot(R, V)), n)');
  const right = await verdict();
  check(right.verdict === 'match' && right.differing === 0, `${name}: the reference's own term matches (${right.shown})`);
  await page.screenshot({ path: path.join(out, `formula-${name}.png`), fullPage: true });
  if (name === 'laptop') {
    // The formulas' own file, through the page's file chooser: a bad one changes nothing and says
    // where; a good one fills the boxes; the page saves the same text.
    const bad = path.join(out, 'bad.formulas.json'), good = path.join(out, 'mine.formulas.json');
    writeFileSync(bad, '{\n  "difuse": "kd"\n}\n');
    writeFileSync(good, JSON.stringify({ diffuse: 'kd * dot(N, L)', specular: 'R = reflect(L, N)\nks * pow(max(0, dot(R, V)), n)' }));
    const opener = await page.$('#open-formulas');
    await opener.uploadFile(bad);
    await page.waitForFunction(() => document.getElementById('formulas-status').textContent !== '', { timeout: 10000 });
    const refused = await page.evaluate(() => [document.getElementById('formulas-status').textContent, document.getElementById('formula-specular').value]);
    check(refused[0] === 'bad.formulas.json:2:3: difuse: unknown slot (did you mean "diffuse"?)' && refused[1].startsWith('R = reflect(-L, N)'),
          `${name}: a bad formula file changes nothing and says where (${refused[0]})`);
    await page.evaluate(() => { window.phonglab.formulaCheck = null; });
    await opener.uploadFile(good);
    const opened = await verdict();
    const boxes = await page.evaluate(() => [document.getElementById('formula-diffuse').value, document.getElementById('formula-specular').value,
                                             window.phonglab.view.formulasFileText()]);
    check(boxes[0] === 'kd * dot(N, L)' && boxes[1].startsWith('R = reflect(L, N)\n') && opened.mistake === 'reflect-sign or view-reversed',
          `${name}: a formula file opened fills the boxes and is checked (${opened.shown})`);
    check(JSON.stringify(JSON.parse(boxes[2])) === JSON.stringify(JSON.parse(readFileSync(good, 'utf8'))), `${name}: and saves back to the same formulas`);
    await page.evaluate(() => document.activeElement && document.activeElement.blur());
    await page.keyboard.down('Control');
    await page.keyboard.press('KeyZ');
    await page.keyboard.up('Control');
    const undone = await page.evaluate(() => document.getElementById('formula-specular').value);
    check(undone.startsWith('R = reflect(-L, N)'), `${name}: Ctrl+Z takes the opened file back in one step`);
  }
  // The lesson's specular exercise (step 15 of shading).
  await page.goto(url('scene=lecture&spp=1&size=320x180#lesson=shading&step=15'));
  await page.waitForFunction('window.phonglab && window.phonglab.ready && window.phonglab.lesson', { timeout: 60000 });
  const starter = await page.evaluate(() => document.getElementById('formula-specular').value);
  const lesson = await page.evaluate(() => window.phonglab.lesson);
  check(lesson.exercise && lesson.exercise.slot === 'specular' && starter.startsWith('R = '),
        `${name}: the exercise step puts its starter in the specular box (${JSON.stringify(starter)})`);
  await (await page.$('#lesson-hint')).click();
  const hints = await page.evaluate(() => [...document.querySelectorAll('#caption .hint')].map((h) => h.textContent));
  check(hints.length === 1 && hints[0].startsWith('Hint 1: '), `${name}: the caption's button shows the first hint`);
  await page.evaluate(() => { window.phonglab.formulaCheck = null; });
  const lbox = await page.$('#formula-specular');
  await lbox.click();
  await select_all();
  await page.keyboard.type('R = reflect(-L, N)\nks * pow(max(0, dot(R, V)), n)');
  await verdict();
  const said = await page.evaluate(() => document.getElementById('lesson-verdict').textContent);
  check(said.startsWith('\u2713 Your formula matches'), `${name}: the caption says the exercise is done (${said})`);
  await page.screenshot({ path: path.join(out, `exercise-${name}.png`), fullPage: true });
  await page.close();
}

// 6i. A student's own image, chosen with the page's file chooser: phonglab-cli's render with no
// shadows (the sign mistake of a student's light loop) at the page's size is named; one of
// another size is refused with both sizes; the difference view marks it.
{
  const page = await open('scene=lecture&spp=1&size=320x180');
  await image_at(page, 1);
  const mine = path.join(out, 'mine.png'), small = path.join(out, 'small.png');
  execFileSync(cli, ['render', 'lecture', '--width', '320', '--height', '180', '--spp', '1', '-o', mine,
                     '--formula', 'specular=R = reflect(-L, N); ks * pow(dot(R, V), n)']);
  execFileSync(cli, ['render', 'lecture', '--width', '64', '--height', '36', '--spp', '1', '-o', small]);
  const chooser = await page.$('#check-image');
  await chooser.uploadFile(small);
  await page.waitForFunction(() => window.phonglab.imageCheck, { timeout: 60000 });
  const refused = await page.evaluate(() => window.phonglab.imageCheck);
  check(refused.error && refused.error.includes('is 64x36, the view renders 320x180'), `an image of another size is refused (${refused.error})`);
  await page.evaluate(() => { window.phonglab.imageCheck = null; });
  await chooser.uploadFile(mine);
  await page.waitForFunction(() => window.phonglab.imageCheck, { timeout: 60000 });
  const named = await page.evaluate(() => window.phonglab.imageCheck);
  check(named.verdict === 'differs' && (named.mistake || '').split(' or ').includes('specular-unclamped'), `a student's image is checked and its mistake named (${named.mistake}: ${named.summary})`);
  await new Promise((resolve) => setTimeout(resolve, 500));  // the next animation frame draws it
  const rgb = await canvas_rgb(page);
  let orange = 0;
  for (let i = 0; i + 2 < rgb.length; i += 3) if (rgb[i] > 230 && rgb[i + 2] < 60) ++orange;
  check(orange > 50, `the difference view marks the differing pixels (${orange} orange)`);
  await page.screenshot({ path: path.join(out, 'image-check.png'), fullPage: true });
  await page.close();
}

// 6e'. "Play with n": n on a logarithmic slider and a box for any value (0 too); a coefficient
// slider's value is saved as shown (0.04, no float noise from keeping a colour's hue).
{
  const page = await open('scene=lecture&size=160x90&spp=1');
  const box = await (await page.$('#image')).boundingBox();
  await page.mouse.click(box.x + box.width * 0.44, box.y + box.height * 0.6);  // the plastic sphere
  const material = await page.evaluate(() => window.phonglab.state().material);
  const n_of = () => page.evaluate((m) => window.phonglab.view.coefficient(m, 'n'), material);
  await page.$eval('#slider-n', (e) => { e.value = '1.5'; e.dispatchEvent(new Event('input')); e.dispatchEvent(new Event('change')); });
  const middle = await n_of();
  await page.click('#n-typed', { clickCount: 3 });
  await page.keyboard.type('0');
  await page.keyboard.press('Enter');
  await page.waitForTimeout(100);
  const zero = await n_of();
  check(Math.abs(middle - 31.6) < 1e-9 && zero === 0, `n's slider is logarithmic (its middle: n = ${middle}) and n = 0 can be typed (${zero})`);
  await page.$eval('#slider-ka', (e) => { e.value = '0.04'; e.dispatchEvent(new Event('input')); e.dispatchEvent(new Event('change')); });
  const text = await page.evaluate(() => window.phonglab.view.sceneJson());
  check(!/\d{9,}/.test(text), `the saved file holds the slider's numbers, no float noise (${(text.match(/"plastic": \{[^}]*"ka": [^\]]*\]/) || [''])[0]})`);
  await page.close();
}

// 6j. A browser without WebAssembly SIMD (its validate refusing the page's probe) is told which
// browsers run the page, instead of a blank page.
{
  const page = await browser.newPage();
  await page.evaluateOnNewDocument(() => {
    const validate = WebAssembly.validate;
    WebAssembly.validate = (bytes) => (bytes.length === 31 ? false : validate(bytes));
  });
  await page.goto(url('scene=lecture&size=160x90&spp=1'));
  await page.waitForTimeout(500);
  const status = await page.$eval('#status', (e) => e.textContent);
  check(/no WebAssembly SIMD/.test(status) && /Safari 16\.4/.test(status), `without SIMD the page says what it needs ("${status}")`);
  await page.close();
}

// 6e. A downloaded scene's numbers read as a person writes them: 40, not 4e+01.
{
  const page = await open('scene=lecture&size=160x90&spp=1');
  const text = await page.evaluate(() => window.phonglab.view.sceneJson());
  check(!/\de[+-]\d/.test(text) && /"fov_y": 40\b/.test(text), `the downloaded scene has no exponents (${(text.match(/"fov_y": [^,\n]*/) || [''])[0]})`);
  await page.close();
}

// 5. Served with COOP/COEP (what tools/dev.sh serve sends): the threaded module on every core,
// the same bits as the one-thread image of section 1.
{
  const html = readFileSync(page_path);
  const server = http.createServer((request, response) => {
    response.writeHead(200, { 'Content-Type': 'text/html', 'Cross-Origin-Opener-Policy': 'same-origin',
                              'Cross-Origin-Embedder-Policy': 'require-corp' });
    response.end(html);
  });
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  const address = `http://127.0.0.1:${server.address().port}/phonglab.html?scene=lecture&size=320x180&spp=4`;
  const page = await open('', address);
  const state = await page.evaluate(() => window.phonglab.state());
  const cores = await page.evaluate(() => navigator.hardwareConcurrency);
  check(state.isolated && state.threads === cores && cores > 1,
        `served cross-origin isolated, the page renders on every core (${state.threads} threads of ${cores})`);
  const threaded = await image_at(page, 4);
  check(threaded.equals(one_thread_image), `... and its image has the same bits as on one thread from file:// (${differing(threaded, one_thread_image, 0)} pixels differ)`);
  await page.screenshot({ path: path.join(out, 'threads.png') });
  await page.close();
  server.close();
}

// 7. An ordinary static host (no isolation headers): the page's own service worker (phonglab-sw.js
// beside it) makes it cross-origin isolated after one reload, so it renders on every core with the
// same bits; with the host gone, the page still opens from the worker's copy.
{
  const dir = path.dirname(path.resolve(page_path));
  const types = { '.html': 'text/html', '.js': 'text/javascript', '.webmanifest': 'application/manifest+json', '.svg': 'image/svg+xml' };
  const server = http.createServer((request, response) => {
    const name = path.basename(new URL(request.url, 'http://host').pathname) || 'phonglab.html';
    let body;
    try { body = readFileSync(path.join(dir, name)); } catch { response.writeHead(404); response.end(); return; }
    response.writeHead(200, { 'Content-Type': types[path.extname(name)] || 'application/octet-stream' });
    response.end(body);
  });
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  const address = `http://127.0.0.1:${server.address().port}/phonglab.html?scene=lecture&size=320x180&spp=4`;
  const context = await browser.createIncognitoBrowserContext();
  const page = await context.newPage();
  page.on('pageerror', (e) => console.log('  page error: ' + e.message));
  await page.setViewport({ width: 1280, height: 720 });
  await page.goto(address);
  const settled = async (want) => {
    for (let t = 0; t < 240; ++t) {
      await new Promise((resolve) => setTimeout(resolve, 250));
      try {
        const s = await page.evaluate(() => (window.phonglab && window.phonglab.ready ? window.phonglab.state() : null));
        if (s && want(s)) return s;
      } catch { /* the page reloading */ }
    }
    return null;
  };
  const state = await settled((s) => s.isolated);
  const cores = await page.evaluate(() => navigator.hardwareConcurrency);
  check(state && state.isolated && state.threads === cores && cores > 1,
        `from a static host with no headers, the service worker isolates the page: ${state ? state.threads : 0} threads of ${cores}`);
  const threaded = await image_at(page, 4);
  check(threaded.equals(one_thread_image), `... the same bits as on one thread (${differing(threaded, one_thread_image, 0)} pixels differ)`);
  await new Promise((resolve) => server.close(resolve));
  server.closeAllConnections?.();
  await page.reload();
  const offline = await settled((s) => s.width > 0);
  check(offline !== null, '... and with the host gone, the page opens again from the worker\'s copy');
  await page.screenshot({ path: path.join(out, 'static-host.png') });
  await context.close();
}

await browser.close();
console.log(`web page tests: ${failures} failure(s)`);
process.exit(failures === 0 ? 0 : 1);
