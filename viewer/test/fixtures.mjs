// fixtures.mjs — small recordings made at test time, laid out as impulse
// writes them, so that the test needs no file from a C++ build.

/// A .glb like io::gltf_recorder's: one box node (half extent 0.5, orange)
/// whose animation "run" moves it from `from` to `to` in `seconds`, turning
/// it 45° about y, with two LINEAR keys. With `contacts`, the root's extras
/// carry contact points as the recorder may: 4 points at frame 0, 2 at 1.
export function makeGlb({ from = [-1, 0, 0], to = [1, 0, 0], seconds = 2, contacts = false } = {}) {
  const chunks = [];
  let length = 0;
  const views = [];
  const accessors = [];
  const add = (typed, accessor) => {
    const bytes = new Uint8Array(typed.buffer, typed.byteOffset, typed.byteLength);
    views.push({ buffer: 0, byteOffset: length, byteLength: bytes.length });
    chunks.push(bytes);
    length += bytes.length;
    const pad = (4 - (length % 4)) % 4;
    if (pad) chunks.push(new Uint8Array(pad)), (length += pad);
    accessors.push({ bufferView: views.length - 1, ...accessor });
    return accessors.length - 1;
  };

  // A unit cube, 4 vertices per face so that each face has its own normal.
  const positions = [];
  const normals = [];
  const indices = [];
  for (const axis of [0, 1, 2])
    for (const sign of [-1, 1]) {
      const u = (axis + 1) % 3;
      const v = (axis + 2) % 3;
      const base = positions.length / 3;
      for (const [a, b] of [[-1, -1], [1, -1], [1, 1], [-1, 1]]) {
        const p = [0, 0, 0];
        p[axis] = 0.5 * sign;
        p[u] = 0.5 * a;
        p[v] = 0.5 * b;
        positions.push(...p);
        const n = [0, 0, 0];
        n[axis] = sign;
        normals.push(...n);
      }
      const quad = sign > 0 ? [0, 1, 2, 0, 2, 3] : [0, 2, 1, 0, 3, 2];
      indices.push(...quad.map((i) => base + i));
    }
  const position = add(new Float32Array(positions), {
    componentType: 5126, count: 24, type: 'VEC3', min: [-0.5, -0.5, -0.5], max: [0.5, 0.5, 0.5],
  });
  const normal = add(new Float32Array(normals), { componentType: 5126, count: 24, type: 'VEC3' });
  const index = add(new Uint32Array(indices), { componentType: 5125, count: indices.length, type: 'SCALAR' });
  const times = add(new Float32Array([0, seconds]), {
    componentType: 5126, count: 2, type: 'SCALAR', min: [0], max: [seconds],
  });
  const moved = add(new Float32Array([...from, ...to]), { componentType: 5126, count: 2, type: 'VEC3' });
  const s = Math.sin(Math.PI / 8);
  const c = Math.cos(Math.PI / 8);
  const turned = add(new Float32Array([0, 0, 0, 1, 0, s, 0, c]), { componentType: 5126, count: 2, type: 'VEC4' });

  const json = {
    asset: { version: '2.0', generator: 'impulse viewer test' },
    scene: 0,
    scenes: [{ nodes: [0] }],
    nodes: [{ name: 'body 0', mesh: 0, translation: from, rotation: [0, 0, 0, 1] }],
    meshes: [{ primitives: [{ attributes: { POSITION: position, NORMAL: normal }, indices: index, material: 0 }] }],
    materials: [{ name: 'dynamic', doubleSided: true,
      pbrMetallicRoughness: { baseColorFactor: [0.92, 0.55, 0.25, 1], metallicFactor: 0, roughnessFactor: 0.8 } }],
    animations: [{ name: 'run',
      channels: [{ sampler: 0, target: { node: 0, path: 'translation' } }, { sampler: 1, target: { node: 0, path: 'rotation' } }],
      samplers: [{ input: times, output: moved, interpolation: 'LINEAR' }, { input: times, output: turned, interpolation: 'LINEAR' }] }],
  };
  if (contacts) {
    // Under the box's bottom face: its corners at frame 0, two at frame 1.
    const corners = (at) => [[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]].map(([x, z]) => [at[0] + x, at[1] - 0.5, at[2] + z]);
    const points = [...corners(from), ...corners(to).slice(0, 2)].flat();
    json.extras = { impulse: { contacts: {
      points: add(new Float32Array(points), { componentType: 5126, count: points.length / 3, type: 'VEC3' }),
      offsets: add(new Uint32Array([0, 4, 6]), { componentType: 5125, count: 3, type: 'SCALAR' }),
    } } };
  }
  json.accessors = accessors;
  json.bufferViews = views;
  json.buffers = [{ byteLength: length }];

  let text = JSON.stringify(json);
  while (text.length % 4 !== 0) text += ' ';
  const jsonBytes = Buffer.from(text, 'utf8');
  const bin = Buffer.concat(chunks);
  const header = Buffer.alloc(12);
  header.writeUInt32LE(0x46546c67, 0); // "glTF"
  header.writeUInt32LE(2, 4);
  header.writeUInt32LE(12 + 8 + jsonBytes.length + 8 + bin.length, 8);
  const chunk = (bytes, type) => {
    const head = Buffer.alloc(8);
    head.writeUInt32LE(bytes.length, 0);
    head.writeUInt32LE(type, 4);
    return [head, bytes];
  };
  return Buffer.concat([header, ...chunk(jsonBytes, 0x4e4f534a), ...chunk(bin, 0x004e4942)]);
}

/// An .ipr of `frames` frames `interval` s apart, `count` particles each in
/// a cube of half size 0.5 around (-1, 0, 0) that moves by `step` each
/// frame along x; colors per particle when `colors` (red to blue along x).
export function makeIpr({ count = 200, frames = 2, interval = 0.5, step = 2, colors = true } = {}) {
  let seed = 12345;
  const random = () => ((seed = (seed * 1103515245 + 12345) >>> 0) / 2 ** 32) - 0.5;
  const base = Array.from({ length: count }, () => [random() - 1, random(), random()]);

  const parts = [];
  const header = Buffer.alloc(48);
  header.write('IMPULSEP', 0, 'ascii');
  header.writeUInt32LE(1, 8);
  header.writeUInt32LE(colors ? 1 : 0, 12);
  header.writeUInt32LE(frames, 16);
  header.writeFloatLE(interval, 20);
  const bounds = [-1.5, -0.5, -0.5, -0.5 + step * (frames - 1), 0.5, 0.5];
  bounds.forEach((b, i) => header.writeFloatLE(b, 24 + 4 * i));
  parts.push(header);
  for (let f = 0; f < frames; ++f) {
    const head = Buffer.alloc(8);
    head.writeFloatLE(f * interval, 0);
    head.writeUInt32LE(count, 4);
    const xyz = Buffer.alloc(12 * count);
    base.forEach(([x, y, z], i) => {
      xyz.writeFloatLE(x + step * f, 12 * i);
      xyz.writeFloatLE(y, 12 * i + 4);
      xyz.writeFloatLE(z, 12 * i + 8);
    });
    parts.push(head, xyz);
    if (colors) {
      const rgb = Buffer.alloc(3 * count + ((4 - ((3 * count) % 4)) % 4));
      base.forEach(([x], i) => {
        const k = x + 1.5; // 0 .. 1 across the cube
        rgb[3 * i] = Math.round(230 * (1 - k));
        rgb[3 * i + 1] = 40;
        rgb[3 * i + 2] = Math.round(230 * k);
      });
      parts.push(rgb);
    }
  }
  return Buffer.concat(parts);
}
