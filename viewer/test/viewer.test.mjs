// viewer.test.mjs — opens recordings made here (fixtures.mjs) in the viewer,
// in headless Debian Chromium, and checks the pixels it draws.
//
//   npm test --prefix viewer        (needs: apt-get install chromium)
//
// Each frame is read from the WebGL canvas itself and compared with the
// background color; the pictures are also written to viewer/test/out/ to
// look at when a check fails.
import assert from 'node:assert/strict';
import { mkdir, mkdtemp, rm, writeFile } from 'node:fs/promises';
import { get } from 'node:http';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { after, before, test } from 'node:test';
import { fileURLToPath } from 'node:url';
import { canvasPng, openPage, openViewer } from '../browser.mjs';
import { startServer } from '../serve.mjs';
import { makeGlb, makeIpr } from './fixtures.mjs';

const WIDTH = 480;
const HEIGHT = 320;
const BACKGROUND = [0xdf, 0xe8, 0xf0];
const outDir = join(dirname(fileURLToPath(import.meta.url)), 'out');

let fixtures, server, url, page, closeBrowser;
const pageErrors = [];

before(async () => {
  fixtures = await mkdtemp(join(tmpdir(), 'impulse-viewer-fixtures-'));
  await writeFile(join(fixtures, 'box.glb'), makeGlb());
  await writeFile(join(fixtures, 'contacts.glb'), makeGlb({ contacts: true }));
  // 201 particles: 603 color bytes, so each frame's padding is exercised.
  await writeFile(join(fixtures, 'particles.ipr'), makeIpr({ count: 201, frames: 3, interval: 0.5, step: 1 }));
  await writeFile(join(fixtures, 'neither.bin'), Buffer.from('this is not a recording'));
  await mkdir(outDir, { recursive: true });
  ({ server, url } = await startServer(0, { mounts: { '/fixtures/': fixtures } }));
  ({ page, close: closeBrowser } = await openPage({ width: WIDTH, height: HEIGHT }));
  page.on('pageerror', (error) => pageErrors.push(error.message));
  page.on('console', (message) => message.type() === 'error' && pageErrors.push(message.text()));
});

after(async () => {
  await closeBrowser?.();
  server?.close();
  if (fixtures) await rm(fixtures, { recursive: true, force: true });
});

/// The canvas's pixels after a fresh render: {width, height, data (RGBA)}.
async function grab(name) {
  if (name) await writeFile(join(outDir, name + '.png'), await canvasPng(page));
  const { width, height, base64 } = await page.evaluate(() => {
    window.viewer.renderNow();
    const source = window.viewer.canvas;
    const copy = document.createElement('canvas');
    copy.width = source.width;
    copy.height = source.height;
    const context = copy.getContext('2d');
    context.drawImage(source, 0, 0);
    const bytes = context.getImageData(0, 0, copy.width, copy.height).data;
    let text = '';
    for (let i = 0; i < bytes.length; i += 0x8000) text += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
    return { width: copy.width, height: copy.height, base64: btoa(text) };
  });
  return { width, height, data: Buffer.from(base64, 'base64') };
}

const pixel = (image, x, y) => {
  const i = 4 * (Math.round(y) * image.width + Math.round(x));
  return [image.data[i], image.data[i + 1], image.data[i + 2]];
};
const isBackground = (rgb) => rgb.every((c, k) => Math.abs(c - BACKGROUND[k]) <= 3);
const isDrawn = (rgb) => !isBackground(rgb);
const isVivid = (rgb) => Math.max(...rgb) - Math.min(...rgb) > 80; // particles, not the grey grid
const isRed = ([r, g, b]) => r > 180 && g < 70 && b < 70;
const isBoxGreen = ([r, g, b]) => Math.abs(r - 0x1f) < 40 && Math.abs(g - 0x7a) < 40 && Math.abs(b - 0x3a) < 40;

/// How many pixels pass `keep`, and their centroid.
function survey(image, keep) {
  let count = 0;
  let sx = 0;
  let sy = 0;
  for (let y = 0; y < image.height; ++y)
    for (let x = 0; x < image.width; ++x)
      if (keep(pixel(image, x, y))) ++count, (sx += x), (sy += y);
  return { count, x: sx / count, y: sy / count };
}

function assertCornersEmpty(image, corners = ['top left', 'top right']) {
  const at = { 'top left': [2, 2], 'top right': [image.width - 3, 2], 'bottom left': [2, image.height - 3] };
  for (const corner of corners) {
    const rgb = pixel(image, ...at[corner]);
    assert.ok(isBackground(rgb), `the ${corner} corner should be background ${BACKGROUND}, is ${rgb}`);
  }
}

const viewer = (f, ...args) => page.evaluate(f, ...args);
const setSlider = (value) =>
  viewer((v) => {
    const slider = document.getElementById('slider');
    slider.value = v;
    slider.dispatchEvent(new Event('input'));
  }, value);

test('the server serves the viewer, three.js and the repository, read-only', async () => {
  const status = (path, method = 'GET') =>
    new Promise((done, failed) => {
      // node's http client, not fetch: fetch would fold the "..".
      const request = get(new URL(url), { path, method }, (response) => {
        response.resume();
        done(response.statusCode);
      });
      request.on('error', failed);
    });
  assert.equal(await status('/'), 200);
  assert.equal(await status('/node_modules/three/build/three.module.js'), 200);
  assert.equal(await status('/node_modules/three/examples/jsm/loaders/GLTFLoader.js'), 200);
  assert.equal(await status('/repo/include/impulse/io/gltf.hpp'), 200);
  assert.equal(await status('/fixtures/box.glb'), 200);
  assert.equal(await status('/repo/..%2f..%2fetc%2fpasswd'), 403, 'a path out of the repository is refused');
  // Plain ".." segments are folded by the URL parser first: this asks for viewer/etc/passwd.
  assert.equal(await status('/repo/../../etc/passwd'), 404, 'dot segments stay inside the served folders');
  assert.equal(await status('/no/such/file'), 404);
  assert.equal(await status('/', 'POST'), 405, 'only GET and HEAD');
  console.log('# checked: server paths, ".." refused, GET only');
});

test('a .glb: the box is drawn, the corners are background, info and contacts toggle', async () => {
  await openViewer(page, `${url}?file=/fixtures/box.glb`);
  const info = await viewer(() => window.viewer.info);
  assert.equal(info.kind, 'glb');
  assert.equal(info.nodes, 1);
  assert.equal(info.movingNodes, 1);
  assert.equal(info.frames, 2);
  assert.equal(info.hasContacts, false);
  assert.ok(Math.abs((await viewer(() => window.viewer.duration)) - 2) < 1e-6, 'duration is the last key, 2 s');
  assert.equal(await viewer(() => document.getElementById('contacts').disabled), true, 'no contacts: toggle disabled');

  await viewer(() => (window.viewer.pause(), window.viewer.setTime(0)));
  const image = await grab('box-start');
  assertCornersEmpty(image, ['top left', 'top right', 'bottom left']);
  const [x, y] = await viewer(() => window.viewer.toScreen([-1, 0, 0]));
  assert.ok(!isBackground(pixel(image, x, y)), `the box's center (${x | 0}, ${y | 0}) should be drawn`);
  const drawn = survey(image, isDrawn);
  assert.ok(drawn.count > 500, `the box should cover a good part of the picture, covers ${drawn.count} px`);
  console.log(`# checked: glb info, background corners, box at (${x | 0}, ${y | 0}), ${drawn.count} px drawn`);
});

test('a .glb: the time slider moves the box from its first key to its last', async () => {
  await setSlider(0);
  const start = survey(await grab(), isDrawn);
  await setSlider(2);
  const end = survey(await grab('box-end'), isDrawn);
  assert.equal(await viewer(() => document.getElementById('time').textContent), '2.00 / 2.00 s');
  const [from, to] = await viewer(() => [window.viewer.toScreen([-1, 0, 0]), window.viewer.toScreen([1, 0, 0])]);
  assert.ok(start.count > 500 && end.count > 500, 'the box is drawn at both ends');
  // The centroid follows the box: near each key's projection, and far apart.
  assert.ok(Math.hypot(start.x - from[0], start.y - from[1]) < 25, `t=0: box at ${start.x | 0},${start.y | 0}, key at ${from}`);
  assert.ok(Math.hypot(end.x - to[0], end.y - to[1]) < 25, `t=2: box at ${end.x | 0},${end.y | 0}, key at ${to}`);
  assert.ok(Math.hypot(end.x - start.x, end.y - start.y) > WIDTH / 5, 'the box moved across the picture');
  await setSlider(1);
  const middle = survey(await grab(), isDrawn);
  assert.ok(Math.abs(middle.x - (start.x + end.x) / 2) < 25, 'halfway in time, halfway across (LINEAR keys)');
  console.log(`# checked: slider moves the box from x=${start.x | 0} to x=${end.x | 0} px`);
});

test('a .glb: the AABB toggle draws the box around the moving body', async () => {
  const off = survey(await grab(), isBoxGreen);
  await page.check('#boxes');
  const on = survey(await grab('box-aabb'), isBoxGreen);
  await page.uncheck('#boxes');
  assert.ok(off.count < 5, `no AABB lines when off (${off.count} px)`);
  assert.ok(on.count > 100, `AABB lines drawn when on (${on.count} px)`);
  console.log(`# checked: AABB toggle, ${on.count} px of box lines`);
});

test('a .glb with contacts: the toggle is enabled and draws each frame\'s points in red', async () => {
  await viewer((u) => window.viewer.load(u), '/fixtures/contacts.glb');
  const info = await viewer(() => window.viewer.info);
  assert.equal(info.hasContacts, true);
  assert.equal(info.contactPoints, 6);
  assert.equal(await viewer(() => document.getElementById('contacts').disabled), false);
  await viewer(() => (window.viewer.pause(), window.viewer.setTime(0)));
  assert.equal(survey(await grab(), isRed).count, 0, 'no red points before the toggle');
  await page.check('#contacts');
  const first = survey(await grab('contacts-start'), isRed);
  await setSlider(2);
  const last = survey(await grab(), isRed);
  assert.ok(first.count > 40, `frame 0's 4 contacts drawn (${first.count} px)`);
  assert.ok(last.count > 20 && last.count < first.count, `frame 1's 2 contacts drawn (${last.count} px)`);
  await page.uncheck('#contacts');
  assert.equal(survey(await grab(), isRed).count, 0, 'no red points after the toggle');
  console.log(`# checked: contacts toggle, ${first.count} px at frame 0, ${last.count} px at frame 1`);
});

test('an .ipr: particles drawn in their colors, info counts, frames advance', async () => {
  await openViewer(page, `${url}?file=/fixtures/particles.ipr`);
  const info = await viewer(() => window.viewer.info);
  assert.equal(info.kind, 'ipr');
  assert.equal(info.frames, 3);
  assert.equal(info.particles, 201);
  assert.equal(info.colored, true);
  assert.ok(Math.abs(info.duration - 1) < 1e-6, 'duration from first to last frame, 1 s');
  assert.equal(await viewer(() => document.getElementById('contacts').disabled), true);

  await viewer(() => (window.viewer.pause(), window.viewer.setTime(0)));
  const image = await grab('particles-start');
  assertCornersEmpty(image);
  const start = survey(image, isVivid);
  const reddish = survey(image, ([r, , b]) => r > b + 80);
  const bluish = survey(image, ([r, , b]) => b > r + 80);
  assert.ok(start.count > 300, `particles drawn (${start.count} px)`);
  assert.ok(reddish.count > 20 && bluish.count > 20, 'per-particle colors, red at -x and blue at +x');
  assert.ok(reddish.x < bluish.x, 'red on the left, blue on the right, as colored along x');

  await setSlider(1);
  const end = survey(await grab('particles-end'), isVivid);
  const [from, to] = await viewer(() => [window.viewer.toScreen([-1, 0, 0]), window.viewer.toScreen([1, 0, 0])]);
  const moved = [end.x - start.x, end.y - start.y];
  const expected = [to[0] - from[0], to[1] - from[1]];
  assert.ok(Math.hypot(moved[0] - expected[0], moved[1] - expected[1]) < 25, `the cloud moved by ${moved}, expected ${expected}`);

  await page.check('#boxes');
  const boxed = survey(await grab('particles-aabb'), isBoxGreen);
  await page.uncheck('#boxes');
  assert.ok(boxed.count > 100, `one AABB around the particles (${boxed.count} px)`);
  console.log(`# checked: ipr info, colors, frame 2 moved the cloud by ${moved.map((v) => v | 0)} px, AABB`);
});

// Recordings written by impulse itself, named (relative to the repository)
// in IMPULSE_VIEWER_RECORDINGS, separated by ':'. CI names the one that
// tests/consumer's single-header program writes: a ground and a box dropped
// on it, so two nodes, one of them moving.
const recordings = (process.env.IMPULSE_VIEWER_RECORDINGS ?? '').split(':').filter((p) => p);
for (const recording of recordings) {
  test(`a recording written by impulse opens and is drawn: ${recording}`, async () => {
    await openViewer(page, `${url}?file=/repo/${recording}`);
    const info = await viewer(() => window.viewer.info);
    assert.equal(info.kind, 'glb');
    assert.equal(info.nodes, 2, 'the ground and the box');
    assert.equal(info.movingNodes, 1, 'the box falls, the ground does not move');
    assert.ok(info.frames > 100, `one frame per step (${info.frames})`);
    // The dynamic box is orange (docs/recording.md), the static ground grey.
    const isOrange = ([r, g, b]) => r > g + 20 && g > b + 20 && r - b > 60;
    await viewer(() => (window.viewer.pause(), window.viewer.setTime(0)));
    const start = survey(await grab('recording-start'), isOrange);
    await viewer(() => window.viewer.setTime(window.viewer.duration));
    const end = survey(await grab('recording-end'), isOrange);
    assert.ok(start.count > 500 && end.count > 500, `the box is drawn (${start.count} and ${end.count} px)`);
    assert.ok(end.y > start.y + 20, `the box falls down the picture (from y = ${start.y | 0} to ${end.y | 0} px)`);
    console.log(`# checked: ${recording}: ${info.nodes} nodes, ${info.frames} frames, the box falls from y = ` +
      `${start.y | 0} to ${end.y | 0} px`);
  });
}

// The examples' recordings, named in IMPULSE_VIEWER_SCENES (':'-separated,
// relative to the repository): whole scenes (examples/character's course,
// examples/gameplay's platform, belt, gate and chair), so the checks are
// what any of them must show: it opens, has several bodies of which some
// move, one frame per recorded step, its dynamic bodies drawn orange at the
// start and at the end, and the picture changes as they move.
const scenes = (process.env.IMPULSE_VIEWER_SCENES ?? '').split(':').filter((p) => p);
for (const recording of scenes) {
  test(`an example's recording opens and plays: ${recording}`, async () => {
    await openViewer(page, `${url}?file=/repo/${recording}`);
    const info = await viewer(() => window.viewer.info);
    assert.equal(info.kind, 'glb');
    assert.ok(info.nodes >= 3, `several bodies (${info.nodes} nodes)`);
    assert.ok(info.movingNodes >= 1 && info.movingNodes < info.nodes, `some move (${info.movingNodes})`);
    assert.ok(info.frames > 100, `one frame per recorded step (${info.frames})`);
    const isOrange = ([r, g, b]) => r > g + 20 && g > b + 20 && r - b > 60;
    await viewer(() => (window.viewer.pause(), window.viewer.setTime(0)));
    const start = survey(await grab(), isOrange);
    await viewer(() => window.viewer.setTime(window.viewer.duration));
    const end = survey(await grab(), isOrange);
    assert.ok(start.count > 100 && end.count > 100, `dynamic bodies drawn (${start.count} and ${end.count} px)`);
    assert.ok(start.count !== end.count || start.x !== end.x || start.y !== end.y, 'the picture changes as they move');
    console.log(`# checked: ${recording}: ${info.nodes} nodes, ${info.movingNodes} moving, ${info.frames} frames`);
  });
}

test('a file that is no recording, or is missing, is reported', async () => {
  const message = (u) => viewer((u) => window.viewer.load(u).then(() => null, () => window.viewer.error), u);
  assert.match(await message('/fixtures/neither.bin'), /neither a \.glb/);
  assert.match(await message('/fixtures/missing.glb'), /404/);
  // The two failed loads' own console messages are expected; none other.
  const unexpected = pageErrors.filter((e) => !/404|Not Found/i.test(e));
  assert.deepEqual(unexpected, [], 'no errors in the page');
  console.log('# checked: bad and missing files reported, no page errors');
});
