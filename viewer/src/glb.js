// glb.js — a recording from impulse's io::gltf_recorder: the scene, its
// animation "run" held at any time, and the two overlays (bounding boxes of
// the moving bodies, and the contact points when the file carries them).
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';

/// A player (see main.js for what one offers) for the .glb bytes in `buffer`.
export async function loadGlb(buffer) {
  const gltf = await new GLTFLoader().parseAsync(buffer, '');
  const root = gltf.scene;
  const json = gltf.parser.json;

  // The recorder writes one animation, sampled at every recorded frame;
  // LINEAR keys, so the mixer interpolates between frames as the run did.
  const clip = gltf.animations[0];
  let mixer = null;
  let action = null;
  let start = 0;
  let end = 0;
  if (clip) {
    mixer = new THREE.AnimationMixer(root);
    action = mixer.clipAction(clip);
    // We set the clip's time ourselves (setTime below), so it must neither
    // wrap around nor switch itself off at its end.
    action.setLoop(THREE.LoopOnce, 1);
    action.clampWhenFinished = true;
    action.play();
    start = Math.min(...clip.tracks.map((track) => track.times[0]));
    end = clip.duration;
  }

  // glTF node index -> three.js object, to find the moving bodies.
  const byIndex = new Map();
  root.traverse((object) => {
    const index = gltf.parser.associations.get(object)?.nodes;
    if (index !== undefined) byIndex.set(index, object);
  });
  const channels = json.animations?.[0]?.channels ?? [];
  const moving = [...new Set(channels.map((c) => c.target.node))].map((i) => byIndex.get(i)).filter(Boolean);

  // One box per moving body, recomputed from its vertices at every time
  // shown ("precise"), so that a turning box gets its true AABB rather than
  // the box around its turned local box.
  const boxes = new THREE.Group();
  const bodyBoxes = moving.map((node) => {
    const box = new THREE.Box3();
    boxes.add(new THREE.Box3Helper(box, 0x1f7a3a));
    return { node, box };
  });
  boxes.visible = false;

  const contacts = await readContacts(gltf, json);

  const object = new THREE.Group();
  object.add(root, boxes);
  if (contacts) object.add(contacts.points);

  const setTime = (t) => {
    if (mixer) {
      action.time = Math.min(start + t, end);
      mixer.update(0); // applies the clip at action.time
    }
    root.updateMatrixWorld(true);
    if (boxes.visible) for (const { node, box } of bodyBoxes) box.setFromObject(node, true);
    if (contacts) contacts.show(start + t);
  };

  return {
    kind: 'glb',
    object,
    duration: Math.max(0, end - start),
    setTime,
    frameBox: () => frameBox(root, moving, setTime, end - start),
    setBoxes(on) {
      boxes.visible = on;
    },
    hasContacts: Boolean(contacts),
    setContacts(on) {
      if (contacts) contacts.points.visible = on;
    },
    info: {
      kind: 'glb',
      nodes: json.nodes?.length ?? 0,
      movingNodes: moving.length,
      meshes: json.meshes?.length ?? 0,
      frames: clip ? json.accessors[json.animations[0].samplers[0].input].count : 1,
      hasContacts: Boolean(contacts),
      contactPoints: contacts ? contacts.count : 0,
    },
  };
}

/// The contact points that the recorder may add to the root's extras:
/// points (VEC3 float, all frames one after the other) and offsets
/// (frame_count + 1 unsigned ints: frame i's points are points[offsets[i] ..
/// offsets[i + 1])); frame i is at the time of the animation's i-th key.
/// Returns null when the file has none.
async function readContacts(gltf, json) {
  const spec = json.extras?.impulse?.contacts;
  if (!spec || spec.points === undefined || spec.offsets === undefined) return null;
  const points = await gltf.parser.getDependency('accessor', spec.points);
  const offsets = (await gltf.parser.getDependency('accessor', spec.offsets)).array;
  const sampler = json.animations?.[0]?.samplers?.[0];
  const times = sampler ? (await gltf.parser.getDependency('accessor', sampler.input)).array : [0];
  const frames = Math.min(times.length, offsets.length - 1);

  // All frames live in one buffer on the GPU; a frame is a draw range of it.
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(points.array, 3));
  geometry.setDrawRange(0, 0);
  // Drawn over the bodies (no depth test): a contact is on a surface, and
  // half of them would otherwise hide inside it.
  const material = new THREE.PointsMaterial({ color: 0xe01010, size: 7, sizeAttenuation: false, depthTest: false });
  const cloud = new THREE.Points(geometry, material);
  cloud.renderOrder = 1;
  cloud.frustumCulled = false; // its bounding sphere would be all frames'
  cloud.visible = false;

  return {
    points: cloud,
    count: points.count,
    show(time) {
      // The last frame at or before `time`: contacts are not interpolated.
      let i = 0;
      while (i + 1 < frames && times[i + 1] <= time + 1e-6) ++i;
      if (frames === 0) return geometry.setDrawRange(0, 0);
      geometry.setDrawRange(offsets[i], offsets[i + 1] - offsets[i]);
    },
  };
}

/// The box to point the camera at: where the moving bodies go over the run,
/// with the still parts of about that size. A ground slab many times larger
/// than the action would otherwise leave the bodies a few pixels big.
function frameBox(root, moving, setTime, duration) {
  const all = new THREE.Box3().setFromObject(root);
  if (moving.length === 0) return all;
  const around = new THREE.Box3();
  const samples = 8;
  for (let s = 0; s <= samples; ++s) {
    setTime((duration * s) / samples);
    for (const node of moving) around.union(new THREE.Box3().setFromObject(node));
  }
  setTime(0);
  const size = around.getSize(new THREE.Vector3()).length();
  const movers = new Set(moving);
  root.traverse((object) => {
    if (!object.isMesh || movers.has(object)) return;
    for (let p = object.parent; p; p = p.parent) if (movers.has(p)) return;
    const box = new THREE.Box3().setFromObject(object);
    if (box.getSize(new THREE.Vector3()).length() <= 2 * size) around.union(box);
  });
  return around;
}
