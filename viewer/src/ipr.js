// ipr.js — an impulse particle recording (.ipr): particles drawn as points,
// one recorded frame at a time. The format is in viewer/README.md.
import * as THREE from 'three';

const HEADER_BYTES = 48;

/// The frames of an .ipr file: {flags, interval, boundsMin, boundsMax,
/// frames: [{time, count, positions: Float32Array, colors: Uint8Array|null}]}.
/// Positions and colors are views into `buffer`, not copies.
export function parseIpr(buffer) {
  const view = new DataView(buffer);
  const fail = (why) => {
    throw new Error(`not a readable .ipr file: ${why}`);
  };
  if (buffer.byteLength < HEADER_BYTES) fail('shorter than its header');
  const magic = new TextDecoder().decode(new Uint8Array(buffer, 0, 8));
  if (magic !== 'IMPULSEP') fail('no IMPULSEP magic');
  const version = view.getUint32(8, true);
  if (version !== 1) fail(`version ${version}, this viewer reads 1`);
  const flags = view.getUint32(12, true);
  const frameCount = view.getUint32(16, true);
  const interval = view.getFloat32(20, true);
  const f32 = (offset) => view.getFloat32(offset, true);
  const boundsMin = [f32(24), f32(28), f32(32)];
  const boundsMax = [f32(36), f32(40), f32(44)];
  const colored = (flags & 1) !== 0;

  const frames = [];
  let at = HEADER_BYTES;
  for (let i = 0; i < frameCount; ++i) {
    if (at + 8 > buffer.byteLength) fail(`frame ${i} is cut off`);
    const time = view.getFloat32(at, true);
    const count = view.getUint32(at + 4, true);
    at += 8;
    const colorBytes = colored ? 3 * count + ((4 - ((3 * count) % 4)) % 4) : 0;
    if (at + 12 * count + colorBytes > buffer.byteLength) fail(`frame ${i} is cut off`);
    // Every frame starts on a 4-byte boundary (the colors are padded), so
    // the positions can be read in place as floats: little-endian, as every
    // machine a browser runs on is.
    const positions = new Float32Array(buffer, at, 3 * count);
    at += 12 * count;
    const colors = colored ? new Uint8Array(buffer, at, 3 * count) : null;
    at += colorBytes;
    frames.push({ time, count, positions, colors });
  }
  return { flags, interval, boundsMin, boundsMax, frames };
}

/// A player (see main.js) for the .ipr bytes in `buffer`.
export function loadIpr(buffer) {
  const recording = parseIpr(buffer);
  const { frames } = recording;
  const most = Math.max(1, ...frames.map((f) => f.count));
  const colored = frames.length > 0 && frames[0].colors !== null;

  // One buffer of the largest frame's size, refilled at each frame shown; a
  // draw range says how much of it the frame uses.
  const geometry = new THREE.BufferGeometry();
  const position = new THREE.BufferAttribute(new Float32Array(3 * most), 3).setUsage(THREE.DynamicDrawUsage);
  geometry.setAttribute('position', position);
  let color = null;
  if (colored) {
    color = new THREE.BufferAttribute(new Uint8Array(3 * most), 3, true).setUsage(THREE.DynamicDrawUsage);
    geometry.setAttribute('color', color);
  }

  // Particles carry no radius: size them from the spacing they would have
  // filling the bounds evenly, which suits a cloud as much as a pile.
  const min = new THREE.Vector3(...recording.boundsMin);
  const max = new THREE.Vector3(...recording.boundsMax);
  const diagonal = Math.max(max.clone().sub(min).length(), 1e-3);
  const material = new THREE.PointsMaterial({
    size: (0.6 * diagonal) / Math.cbrt(most),
    color: colored ? 0xffffff : 0x2f6fb0,
    vertexColors: colored,
    map: discTexture(),
    alphaTest: 0.5, // round points, and no sorting needed
  });
  const points = new THREE.Points(geometry, material);
  points.frustumCulled = false; // the geometry's bounding sphere would be stale

  // One box around all the particles of the frame shown.
  const box = new THREE.Box3();
  const helper = new THREE.Box3Helper(box, 0x1f7a3a);
  helper.visible = false;

  // A grid under the particles: with nothing else in the scene it is what
  // shows which way is down and how far things are.
  const size = Math.max(max.x - min.x, max.z - min.z, 1e-3) * 1.5;
  const grid = new THREE.GridHelper(size, 10, 0x8899aa, 0xb8c4d0);
  grid.position.set((min.x + max.x) / 2, min.y, (min.z + max.z) / 2);

  const object = new THREE.Group();
  object.add(points, helper, grid);

  const first = frames.length > 0 ? frames[0].time : 0;
  const last = frames.length > 0 ? frames[frames.length - 1].time : 0;
  let shown = -1;

  const setTime = (t) => {
    // The last frame at or before t; frames are shown as recorded, not
    // interpolated, since a frame may hold other particles than the next.
    let i = 0;
    while (i + 1 < frames.length && frames[i + 1].time <= first + t + 1e-6) ++i;
    if (i === shown || frames.length === 0) return;
    shown = i;
    const frame = frames[i];
    position.array.set(frame.positions);
    position.needsUpdate = true;
    if (color) {
      color.array.set(frame.colors);
      color.needsUpdate = true;
    }
    geometry.setDrawRange(0, frame.count);
    box.setFromArray(frame.positions);
  };

  return {
    kind: 'ipr',
    object,
    duration: Math.max(0, last - first),
    setTime,
    frameBox: () => new THREE.Box3(min, max),
    setBoxes(on) {
      helper.visible = on;
    },
    hasContacts: false,
    setContacts() {},
    info: {
      kind: 'ipr',
      frames: frames.length,
      particles: frames.length > 0 ? frames[0].count : 0,
      maxParticles: most,
      colored,
      interval: recording.interval,
      hasContacts: false,
    },
  };
}

/// A white disc on a clear square, to draw points round.
function discTexture() {
  const n = 32;
  const data = new Uint8Array(n * n * 4);
  for (let y = 0; y < n; ++y)
    for (let x = 0; x < n; ++x) {
      const dx = x + 0.5 - n / 2;
      const dy = y + 0.5 - n / 2;
      data.set([255, 255, 255, dx * dx + dy * dy <= (n / 2) * (n / 2) ? 255 : 0], 4 * (y * n + x));
    }
  const texture = new THREE.DataTexture(data, n, n);
  texture.magFilter = THREE.LinearFilter; // smooth edges on large points
  texture.needsUpdate = true;
  return texture;
}
