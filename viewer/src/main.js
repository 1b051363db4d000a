// main.js — the page: renderer, camera, controls, the bars' buttons, and
// window.viewer, the small API that the test and tools/viewer_picture.mjs
// drive.
//
// A recording is opened into a "player" (glb.js, ipr.js): {kind, object (to
// add to the scene), duration, setTime(t), frameBox(), setBoxes(on),
// hasContacts, setContacts(on), info}. Times here run from 0 at the first
// recorded frame to `duration` at the last.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { loadGlb } from './glb.js';
import { loadIpr } from './ipr.js';

const $ = (id) => document.getElementById(id);
const ui = {
  file: $('file'),
  info: $('info'),
  error: $('error'),
  play: $('play'),
  slider: $('slider'),
  time: $('time'),
  boxes: $('boxes'),
  contacts: $('contacts'),
};

// preserveDrawingBuffer keeps the last frame readable after it is shown,
// so that toDataURL and screenshots see what renderNow() drew.
const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
$('view').appendChild(renderer.domElement);

const scene = new THREE.Scene();
scene.background = new THREE.Color(0xdfe8f0);
scene.add(new THREE.HemisphereLight(0xffffff, 0x4a5360, 1.2));
const sun = new THREE.DirectionalLight(0xffffff, 1.8);
// From above and to the right of the default view, so that the three faces
// of a box seen from there get three different shades.
sun.position.set(5, 10, 2);
scene.add(sun);

const camera = new THREE.PerspectiveCamera(40, 1, 0.01, 1000);
const controls = new OrbitControls(camera, renderer.domElement);

let player = null;
let time = 0;
let playing = false;
// Frames are drawn only when something changed: software GL on a shared
// machine should not redraw a still picture sixty times a second.
let dirty = true;
controls.addEventListener('change', () => (dirty = true));

function resize() {
  renderer.setSize(window.innerWidth, window.innerHeight);
  camera.aspect = window.innerWidth / window.innerHeight;
  camera.updateProjectionMatrix();
  dirty = true;
}
window.addEventListener('resize', resize);
resize();

/// Puts the camera at `position` looking at `target`, with near and far
/// planes for that distance.
function setView(position, target) {
  camera.position.set(...position);
  controls.target.set(...target);
  const distance = Math.max(camera.position.distanceTo(controls.target), 1e-3);
  camera.near = distance / 100;
  camera.far = distance * 100;
  camera.updateProjectionMatrix();
  controls.update();
  dirty = true;
}

/// A 3/4 view from above (45° round from +z towards +x, 30° up; glTF is
/// y-up), at the distance where all eight corners of the box are in view.
function frameView(box) {
  if (box.isEmpty()) box = new THREE.Box3(new THREE.Vector3(-1, -1, -1), new THREE.Vector3(1, 1, 1));
  const center = box.getCenter(new THREE.Vector3());
  const up = Math.PI / 6;
  const back = new THREE.Vector3(Math.SQRT1_2 * Math.cos(up), Math.sin(up), Math.SQRT1_2 * Math.cos(up));
  const right = new THREE.Vector3(0, 1, 0).cross(back).normalize();
  const above = back.clone().cross(right);
  const tanV = Math.tan(THREE.MathUtils.degToRad(camera.fov) / 2);
  const tanH = tanV * camera.aspect;
  // A corner c (from the center) is in view from distance d along `back`
  // when |c·right| <= (d - c·back) tanH, and the same upwards.
  let distance = 1e-3;
  for (let k = 0; k < 8; ++k) {
    const c = new THREE.Vector3(k & 1 ? box.max.x : box.min.x, k & 2 ? box.max.y : box.min.y, k & 4 ? box.max.z : box.min.z).sub(center);
    const depth = c.dot(back);
    distance = Math.max(distance, depth + Math.abs(c.dot(right)) / tanH, depth + Math.abs(c.dot(above)) / tanV);
  }
  distance *= 1.08; // a margin round the edges
  setView(center.clone().addScaledVector(back, distance).toArray(), center.toArray());
}

function setTime(t) {
  if (!player) return;
  time = Math.min(Math.max(Number(t) || 0, 0), player.duration);
  player.setTime(time);
  ui.slider.value = time;
  ui.time.textContent = `${time.toFixed(2)} / ${player.duration.toFixed(2)} s`;
  dirty = true;
}

function setPlaying(on) {
  playing = on && player !== null && player.duration > 0;
  ui.play.textContent = playing ? 'pause' : 'play';
}

function setBoxes(on) {
  ui.boxes.checked = on;
  player?.setBoxes(on);
  setTime(time); // the boxes are computed only while shown
}

function setContacts(on) {
  ui.contacts.checked = on && Boolean(player?.hasContacts);
  player?.setContacts(ui.contacts.checked);
  setTime(time);
}

function renderNow() {
  renderer.render(scene, camera);
  dirty = false;
}

let last = null;
renderer.setAnimationLoop((now) => {
  // Real time, but no leap after the tab was hidden for a while.
  const dt = last === null ? 0 : Math.min((now - last) / 1000, 0.1);
  last = now;
  if (playing) setTime(time >= player.duration ? 0 : Math.min(time + dt, player.duration));
  if (dirty) renderNow();
});

function dispose(object) {
  object.traverse((o) => {
    o.geometry?.dispose();
    for (const m of [o.material ?? []].flat()) {
      m.map?.dispose();
      m.dispose();
    }
  });
}

/// Opens a recording's bytes: .glb or .ipr, told apart by their first bytes.
async function open(buffer, name = 'recording') {
  viewer.ready = false;
  viewer.error = null;
  ui.error.textContent = '';
  ui.info.textContent = `opening ${name}…`;
  setPlaying(false);
  try {
    const magic = new TextDecoder().decode(new Uint8Array(buffer, 0, Math.min(8, buffer.byteLength)));
    let next;
    if (magic.startsWith('glTF')) next = await loadGlb(buffer);
    else if (magic === 'IMPULSEP') next = loadIpr(buffer);
    else throw new Error(`${name} is neither a .glb (glTF binary) nor an .ipr file`);

    if (player) {
      scene.remove(player.object);
      dispose(player.object);
    }
    player = next;
    scene.add(player.object);
    frameView(player.frameBox());
    ui.slider.max = player.duration;
    ui.slider.disabled = ui.play.disabled = player.duration === 0;
    ui.contacts.disabled = !player.hasContacts;
    setBoxes(ui.boxes.checked);
    setContacts(ui.contacts.checked);
    setTime(0);

    viewer.info = { name, duration: player.duration, ...player.info };
    const i = viewer.info;
    ui.info.textContent =
      i.kind === 'glb'
        ? `${name}: ${i.nodes} bodies (${i.movingNodes} moving), ${i.frames} frames` +
          (i.hasContacts ? `, ${i.contactPoints} contact points` : ', no contacts recorded')
        : `${name}: ${i.particles} particles, ${i.frames} frames`;
    viewer.ready = true;
    setPlaying(true);
  } catch (error) {
    viewer.error = String(error?.message ?? error);
    ui.error.textContent = viewer.error;
    ui.info.textContent = '';
    throw error;
  }
}

async function load(url) {
  let response;
  try {
    response = await fetch(url);
    if (!response.ok) throw new Error(`${url}: HTTP ${response.status}`);
  } catch (error) {
    viewer.error = String(error?.message ?? error);
    ui.error.textContent = viewer.error;
    throw error;
  }
  return open(await response.arrayBuffer(), decodeURIComponent(url.split('/').pop().split('?')[0]));
}

ui.file.addEventListener('change', async () => {
  const file = ui.file.files[0];
  if (file) await open(await file.arrayBuffer(), file.name).catch(() => {});
});
ui.play.addEventListener('click', () => setPlaying(!playing));
ui.slider.addEventListener('input', () => setTime(ui.slider.value));
ui.boxes.addEventListener('change', () => setBoxes(ui.boxes.checked));
ui.contacts.addEventListener('change', () => setContacts(ui.contacts.checked));
window.addEventListener('keydown', (event) => {
  if (event.key === ' ' && event.target === document.body) {
    setPlaying(!playing);
    event.preventDefault();
  }
});

const viewer = {
  ready: false,
  error: null,
  info: null,
  canvas: renderer.domElement,
  get duration() {
    return player ? player.duration : 0;
  },
  get time() {
    return time;
  },
  get playing() {
    return playing;
  },
  load,
  open,
  setTime,
  play: () => setPlaying(true),
  pause: () => setPlaying(false),
  renderNow,
  setBoxes,
  setContacts,
  setView,
  /// Where a world point lands on the canvas, in CSS pixels from its top left.
  toScreen(point) {
    camera.updateMatrixWorld();
    const p = new THREE.Vector3(...point).project(camera);
    const { width, height } = renderer.domElement.getBoundingClientRect();
    return [((p.x + 1) / 2) * width, ((1 - p.y) / 2) * height];
  },
};
window.viewer = viewer;

const file = new URLSearchParams(window.location.search).get('file');
if (file) load(file).catch(() => {}); // shown on the page and in viewer.error
