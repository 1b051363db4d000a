#!/usr/bin/env node
// viewer_picture.mjs — one frame of a recording, as the web viewer
// (viewer/) draws it, written to a PNG: the README's pictures.
//
//   npm ci --prefix viewer        # once: three and playwright-core
//   apt-get install chromium      # once: the headless browser
//   node tools/viewer_picture.mjs out/rube_goldberg.glb out/rube_goldberg.png --time 3
//
// Options: --time SECONDS (from the first frame; default 0), --width 960
// --height 540 (pixels), --camera X,Y,Z --target X,Y,Z (world coordinates;
// default: the viewer's own 3/4 view of the scene), --boxes and --contacts
// (the viewer's overlays). three.js and playwright-core are resolved from
// viewer/node_modules, through viewer/browser.mjs.
import { existsSync } from 'node:fs';
import { writeFile } from 'node:fs/promises';
import { basename, dirname, resolve } from 'node:path';
import { parseArgs } from 'node:util';

const usage =
  'usage: node tools/viewer_picture.mjs <recording.glb|.ipr> <out.png> [--time s] [--width 960 --height 540]\n' +
  '       [--camera x,y,z --target x,y,z] [--boxes] [--contacts]';

let parsed;
try {
  parsed = parseArgs({
    allowPositionals: true,
    options: {
      time: { type: 'string', default: '0' },
      width: { type: 'string', default: '960' },
      height: { type: 'string', default: '540' },
      camera: { type: 'string' },
      target: { type: 'string' },
      boxes: { type: 'boolean', default: false },
      contacts: { type: 'boolean', default: false },
      help: { type: 'boolean', short: 'h', default: false },
    },
  });
} catch (error) {
  console.error(`${error.message}\n${usage}`);
  process.exit(2);
}
const { values: options, positionals } = parsed;
if (options.help) {
  console.log(usage);
  process.exit(0);
}
if (positionals.length !== 2) {
  console.error(usage);
  process.exit(2);
}

const die = (message) => {
  console.error(`${message}\n${usage}`);
  process.exit(2);
};
const number = (name, text) => {
  const x = Number(text);
  if (text.trim() === '' || !Number.isFinite(x)) die(`--${name} wants a number, not "${text}"`);
  return x;
};
const point = (name, text) => {
  if (text === undefined) return null;
  const xyz = text.split(',').map((t) => number(name, t));
  if (xyz.length !== 3) die(`--${name} wants x,y,z, not "${text}"`);
  return xyz;
};

const recording = resolve(positionals[0]);
if (!existsSync(recording)) die(`no such recording: ${recording}`);
const output = resolve(positionals[1]);
const time = number('time', options.time);
const width = Math.round(number('width', options.width));
const height = Math.round(number('height', options.height));
const camera = point('camera', options.camera);
const target = point('target', options.target);
if ((camera === null) !== (target === null)) die('--camera and --target go together');
if (width < 16 || height < 16) die('--width and --height want at least 16 pixels');

// The viewer's modules are imported only now, so that --help works before
// `npm ci --prefix viewer`, and a missing install says what to do.
let viewer;
try {
  viewer = {
    ...(await import('../viewer/serve.mjs')),
    ...(await import('../viewer/browser.mjs')),
  };
} catch (error) {
  console.error(`${error.message}\nrun "npm ci --prefix viewer" first`);
  process.exit(1);
}

// The recording's folder is served on its own, so any path works, in the
// repository or not.
const { server, url } = await viewer.startServer(0, { mounts: { '/recording/': dirname(recording) } });
const { page, close } = await viewer.openPage({ width, height });
try {
  await viewer.openViewer(page, `${url}?file=/recording/${encodeURIComponent(basename(recording))}`);
  const shown = await page.evaluate(
    ({ time, camera, target, boxes, contacts }) => {
      const v = window.viewer;
      v.pause();
      if (camera) v.setView(camera, target);
      v.setBoxes(boxes);
      v.setContacts(contacts);
      v.setTime(time);
      return { time: v.time, duration: v.duration, info: v.info };
    },
    {
      time,
      camera,
      target,
      boxes: options.boxes,
      contacts: options.contacts,
    },
  );
  if (options.contacts && !shown.info.hasContacts) console.error(`${basename(recording)} has no contacts to show`);
  await writeFile(output, await viewer.canvasPng(page));
  console.log(`${output}: ${width}x${height}, t = ${shown.time.toFixed(3)} of ${shown.duration.toFixed(3)} s`);
} catch (error) {
  console.error(error.message);
  process.exitCode = 1;
} finally {
  await close();
  server.close();
}
