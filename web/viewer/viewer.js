// srcodec's viewer: draws an .srm file while it arrives, coarse to fine.
//
//   /viewer/?src=URL.srm[&maxVertices=N][&snapshots=1]   or drop a file on the page
//
// A worker (decode-worker.js) reads and decodes; this page queues its
// refinements and draws one per animation frame, so that levels arriving in
// one chunk each get shown; queued refinements of one level collapse to the
// newest.
//
// For tests, window.srcodecViewer holds:
//   status       'idle' | 'loading' | 'streaming' | 'done' | 'failed'
//   done         true once the stream is over and every refinement is drawn
//   info, total, bytesReceived   the header (decoder.inspect) and the byte counts
//   refinements  one per drawn refinement: { bytesReceived, bytesUsed, level,
//                triangles, vertices, milliseconds, drawnAt (performance.now()),
//                frame (animation frame number), camera (its position), and with snapshots=1
//                image (PNG data URL of the canvas) and coverage (the share
//                of pixels not the background) }
//   received     refinements that came from the decoder (drawn or collapsed)
//   error        why the file did not (wholly) decode, or null
//   message, messageKind   the text shown in the panel, and 'info' | 'warning' | 'error'
//   lastMesh     { positions, indices, level, bytesUsed, cornerNormals, drawnVertices } of the mesh on
//                screen (cornerNormals: decode's, for a file with creases; drawnVertices: the geometry's)
//   prefix       after a slider move: { maxBytes, level, triangles, milliseconds, error } (pending: null)
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { DEFAULT_MAX_VERTICES, MAX_VERTICES_LIMIT } from 'srcodec';
import { meshGeometry } from 'srcodec/three';

const BACKGROUND = 0x1e2329;
const params = new URLSearchParams(location.search);
const snapshots = params.get('snapshots') === '1';

const $ = (id) => document.getElementById(id);
const ui = {
  canvas: $('view'), file: $('file'), bytes: $('bytes'), level: $('level'), triangles: $('triangles'),
  milliseconds: $('milliseconds'), progress: $('progress'), prefix: $('prefix'), prefixBytes: $('prefix-bytes'),
  flat: $('flat'), open: $('open'), message: $('message'), drop: $('drop'), panel: $('panel'),
};

const state = {};
window.srcodecViewer = state;

// Scene: one mesh whose geometry each refinement replaces; a light that
// follows the camera, so that the side looked at is lit.
const renderer = new THREE.WebGLRenderer({ canvas: ui.canvas, antialias: true });
renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2));
const scene = new THREE.Scene();
scene.background = new THREE.Color(BACKGROUND);
const camera = new THREE.PerspectiveCamera(35, 1, 0.01, 100);
camera.position.set(0, 0, 4);
scene.add(camera);
scene.add(new THREE.HemisphereLight(0xdde6f0, 0x3a3128, 1.2));
const keyLight = new THREE.DirectionalLight(0xffffff, 2.2);
keyLight.position.set(1, 1.5, 2);
camera.add(keyLight);
const material = new THREE.MeshStandardMaterial({ color: 0xc9b79a, roughness: 0.65, metalness: 0, side: THREE.DoubleSide });
const object = new THREE.Mesh(new THREE.BufferGeometry(), material);
scene.add(object);
const controls = new OrbitControls(camera, ui.canvas);
controls.enableDamping = false;
controls.addEventListener('change', () => requestFrame());

let needsRender = true;
let frame = 0;
let frameRequested = false;
const queue = [];       // refinements waiting for a frame, oldest first, one per level run
let finalEvent = null;  // the stream's end, applied once the queue is drawn
let worker = null;
let prefixBusy = false;
let prefixWanted = 0;   // the slider's value not yet decoded (0: none)

function resize() {
  const width = ui.canvas.clientWidth;
  const height = ui.canvas.clientHeight;
  renderer.setSize(width, height, false);
  camera.aspect = width / Math.max(1, height);
  // The panel covers the canvas's left side: where that leaves room, the
  // view is centred on the rest (the projection's centre moves, the camera
  // does not).
  const covered = ui.panel.offsetLeft + ui.panel.offsetWidth;
  const shift = width > 2.5 * covered ? covered / 2 : 0;
  camera.setViewOffset(width, height, -shift, 0, width, height);
  camera.updateProjectionMatrix();
  requestFrame();
}
window.addEventListener('resize', resize);

function requestFrame() {
  needsRender = true;
  if (!frameRequested) {
    frameRequested = true;
    requestAnimationFrame(onFrame);
  }
}

function onFrame() {
  frameRequested = false;
  ++frame;
  if (queue.length > 0) {
    const refinement = queue.shift();
    showMesh(refinement.mesh);
    renderer.render(scene, camera);
    needsRender = false;
    record(refinement);
  } else if (needsRender) {
    renderer.render(scene, camera);
    needsRender = false;
  }
  if (queue.length > 0) requestFrame();
  else if (finalEvent !== null) {
    const event = finalEvent;
    finalEvent = null;
    finish(event);
  }
}

// Replaces the drawn geometry; .srm files carry no normals, so they are
// computed (smooth but split at the file's creases; the flat-shading switch
// lets the material derive them).
function showMesh(mesh) {
  const geometry = meshGeometry(mesh);
  const old = object.geometry;
  object.geometry = geometry;
  old.dispose();
  state.lastMesh = {
    positions: mesh.positions, indices: mesh.indices, level: mesh.level, bytesUsed: mesh.bytesUsed,
    cornerNormals: mesh.cornerNormals, drawnVertices: geometry.getAttribute('position').count,
  };
  ui.level.textContent = levelText(mesh.level);
  ui.triangles.textContent = mesh.triangleCount.toLocaleString('en');
}

function levelText(level) {
  const levels = state.info?.levelInfo.length;
  return levels ? `${level} of ${levels - 1}` : String(level);
}

function record({ mesh, bytesReceived, milliseconds }) {
  const entry = {
    bytesReceived, bytesUsed: mesh.bytesUsed, level: mesh.level, triangles: mesh.triangleCount,
    vertices: mesh.vertexCount, milliseconds, drawnAt: performance.now(), frame, camera: camera.position.toArray(),
  };
  if (snapshots) {
    // Read right after rendering, while the drawing buffer still holds the frame.
    entry.image = ui.canvas.toDataURL('image/png');
    entry.coverage = coverage();
  }
  state.refinements.push(entry);
  ui.milliseconds.textContent = `${milliseconds.toFixed(1)} ms`;
}

// The share of the canvas's pixels that differ from the background.
function coverage() {
  const small = document.createElement('canvas');
  small.width = 160;
  small.height = Math.max(1, Math.round((160 * ui.canvas.height) / Math.max(1, ui.canvas.width)));
  const context = small.getContext('2d', { willReadFrequently: true });
  context.drawImage(ui.canvas, 0, 0, small.width, small.height);
  const pixels = context.getImageData(0, 0, small.width, small.height).data;
  const [r, g, b] = [(BACKGROUND >> 16) & 255, (BACKGROUND >> 8) & 255, BACKGROUND & 255];
  let differ = 0;
  for (let i = 0; i < pixels.length; i += 4) {
    if (Math.abs(pixels[i] - r) + Math.abs(pixels[i + 1] - g) + Math.abs(pixels[i + 2] - b) > 24) ++differ;
  }
  return differ / (pixels.length / 4);
}

// Frames the header's bounding box, once per file, so that the camera stays
// put while the mesh refines.
function frameBox(info) {
  const min = new THREE.Vector3(...info.bboxMin);
  const max = new THREE.Vector3(...info.bboxMax);
  const center = min.clone().add(max).multiplyScalar(0.5);
  let radius = max.distanceTo(min) / 2;
  if (!Number.isFinite(radius) || !Number.isFinite(center.length()) || radius <= 0) {
    center.set(0, 0, 0);
    radius = 1;
  }
  const distance = (radius / Math.sin(THREE.MathUtils.degToRad(camera.fov / 2))) * 1.05;
  const direction = new THREE.Vector3(0.35, 0.25, 1).normalize();
  camera.position.copy(center).addScaledVector(direction, distance);
  camera.near = distance / 100;
  camera.far = distance * 10;
  camera.updateProjectionMatrix();
  controls.target.copy(center);
  controls.minDistance = radius * 0.05;
  controls.maxDistance = distance * 5;
  controls.update();
  requestFrame();
}

function say(text, kind = 'info') {
  state.message = text;
  state.messageKind = kind;
  ui.message.textContent = text;
  ui.message.className = kind;
  ui.message.hidden = text === '';
}

const count = (n) => n.toLocaleString('en');

// The bytes the panel shows: those received, or the slider's prefix.
function showBytes(received, total, isPrefix = false) {
  if (!isPrefix) state.bytesReceived = received;
  ui.bytes.textContent = total > 0 ? `${count(received)} / ${count(total)}` : count(received);
  ui.progress.value = total > 0 ? Math.min(1, received / total) : 0;
}

function reset(name) {
  worker?.terminate();
  worker = null;
  queue.length = 0;
  finalEvent = null;
  prefixBusy = false;
  prefixWanted = 0;
  Object.assign(state, {
    src: name, status: 'loading', done: false, info: null, total: 0, bytesReceived: 0,
    refinements: [], received: 0, error: null, message: '', messageKind: 'info', lastMesh: null, prefix: null,
  });
  const old = object.geometry;
  object.geometry = new THREE.BufferGeometry();
  old.dispose();
  ui.file.textContent = shortName(name);
  for (const field of [ui.bytes, ui.level, ui.triangles, ui.milliseconds]) field.textContent = '–';
  ui.progress.value = 0;
  ui.prefix.disabled = true;
  ui.prefixBytes.textContent = '–';
  say(`loading ${name}…`);
  requestFrame();
}

// The last part of a URL path, for the panel.
function shortName(name) {
  const last = name.split('?')[0].split('/').filter(Boolean).at(-1) ?? name;
  try {
    return decodeURIComponent(last);
  } catch {
    return last;
  }
}

function maxVerticesParam() {
  const text = params.get('maxVertices');
  if (text === null) return DEFAULT_MAX_VERTICES;
  const value = Number(text);
  if (!Number.isInteger(value) || value < 1 || value > MAX_VERTICES_LIMIT) {
    throw new Error(`maxVertices=${text}: use a whole number in 1..${MAX_VERTICES_LIMIT}`);
  }
  return value;
}

// Starts reading a URL or a File in a fresh worker (the old one, if any,
// stops where it is).
function load(source) {
  const name = source instanceof File ? source.name : source;
  reset(name);
  let maxVertices;
  try {
    maxVertices = maxVerticesParam();
  } catch (error) {
    fail(error.message);
    return;
  }
  worker = new Worker(new URL('./decode-worker.js', import.meta.url), { type: 'module' });
  const current = worker;
  worker.onmessage = ({ data }) => { if (worker === current) onWorkerMessage(data); };
  worker.onerror = (event) => {
    if (worker !== current) return;
    event.preventDefault();
    fail(`the decoder stopped: ${event.message || 'its script did not load'}`);
    worker.terminate();
  };
  const open = { type: 'open', maxVertices };
  if (source instanceof File) open.file = source;
  else open.url = new URL(source, location.href).href;
  worker.postMessage(open);
}

function fail(text) {
  state.status = 'failed';
  state.error = text;
  state.done = true;
  say(text, 'error');
}

function onWorkerMessage(data) {
  switch (data.type) {
    case 'header':
      state.info = data.info;
      state.total = data.total;
      state.status = 'streaming';
      frameBox(data.info);
      say(`streaming ${state.src}…`);
      break;
    case 'progress':
      state.total = data.total;
      showBytes(data.bytesReceived, data.total);
      if (data.error) say(`the bytes so far do not all decode: ${data.error}`, 'warning');
      break;
    case 'refine':
      // A refinement of the level queued last replaces it: only the newest
      // of a level is drawn, and a hidden tab (no frames) queues at most one
      // mesh per level.
      ++state.received;
      if (queue.length > 0 && queue.at(-1).mesh.level === data.mesh.level) queue[queue.length - 1] = data;
      else queue.push(data);
      requestFrame();
      break;
    case 'done':
    case 'failed':
      finalEvent = data;
      requestFrame();
      break;
    case 'prefixed':
      onPrefix(data);
      break;
    default:
      break;
  }
}

// The stream is over and its refinements drawn: says how it went, and
// opens the slider over the bytes that arrived.
function finish(event) {
  showBytes(event.bytesReceived, event.total);
  const mesh = state.lastMesh;
  const shown = mesh ? `level ${mesh.level}, ${count(mesh.indices.length / 3)} triangles from ${count(mesh.bytesUsed)} bytes` : null;
  if (event.type === 'done' && event.error && !mesh) {
    fail(`cannot show ${state.src}: ${event.error}`);
  } else if (event.type === 'failed') {
    if (event.stage === 'network') {
      const lost = `the connection broke after ${count(event.bytesReceived)} of ${count(event.total)} bytes (${event.message})`;
      fail(mesh ? `${lost}; showing the last refinement (${shown})` : `${lost}; no mesh arrived`);
    } else {
      fail(mesh ? `${event.message}; showing the best mesh (${shown})` : `cannot show ${state.src}: ${event.message}`);
    }
  } else {
    state.status = 'done';
    state.done = true;
    if (event.error) {
      state.error = event.error;
      say(`not all of the file decodes: ${event.error}; showing the best mesh its bytes allow (${shown})`, 'error');
    } else if (!event.complete) {
      state.error = `the file is cut: ${event.bytesReceived} of ${event.declaredBytes} bytes`;
      say(`the file is cut: ${count(event.bytesReceived)} of the ${count(event.declaredBytes)} bytes its header declares; showing what they give (${shown})`, 'warning');
    } else {
      say('');
    }
  }
  if (state.bytesReceived > 0 && mesh) {
    ui.prefix.max = String(state.bytesReceived);
    ui.prefix.value = String(state.bytesReceived);
    ui.prefix.disabled = false;
    ui.prefixBytes.textContent = `${count(state.bytesReceived)} bytes`;
  }
}

// The slider: decodes the prefix it picks; moves made while a decode runs
// collapse into the newest.
function requestPrefix(maxBytes) {
  prefixWanted = maxBytes;
  state.prefix = null;
  ui.prefixBytes.textContent = `${count(maxBytes)} bytes`;
  if (!prefixBusy && worker) {
    prefixBusy = true;
    prefixWanted = 0;
    worker.postMessage({ type: 'prefix', maxBytes, id: maxBytes });
  }
}

function onPrefix(data) {
  prefixBusy = false;
  if (prefixWanted > 0) {
    requestPrefix(prefixWanted);
    return;
  }
  if (data.error) {
    state.prefix = { maxBytes: data.maxBytes, error: data.error };
    say(`the first ${count(data.maxBytes)} bytes give no mesh: ${data.error}`, 'warning');
    return;
  }
  const { mesh } = data;
  showMesh(mesh);
  showBytes(data.maxBytes, state.total, true);
  ui.milliseconds.textContent = `${data.milliseconds.toFixed(1)} ms`;
  state.prefix = {
    maxBytes: data.maxBytes, level: mesh.level, triangles: mesh.triangleCount, milliseconds: data.milliseconds, error: null,
  };
  if (state.messageKind === 'warning' && state.message.startsWith('the first ')) say('');
  requestFrame();
}

ui.prefix.addEventListener('input', () => requestPrefix(Number(ui.prefix.value)));
ui.flat.addEventListener('change', () => {
  material.flatShading = ui.flat.checked;
  material.needsUpdate = true;
  requestFrame();
});
ui.open.addEventListener('change', () => { if (ui.open.files[0]) load(ui.open.files[0]); });

// Dropping a file anywhere on the page opens it.
let dragDepth = 0;
window.addEventListener('dragenter', (event) => { event.preventDefault(); ++dragDepth; ui.drop.hidden = false; });
window.addEventListener('dragleave', () => { if (--dragDepth <= 0) { dragDepth = 0; ui.drop.hidden = true; } });
window.addEventListener('dragover', (event) => event.preventDefault());
window.addEventListener('drop', (event) => {
  event.preventDefault();
  dragDepth = 0;
  ui.drop.hidden = true;
  const file = event.dataTransfer?.files[0];
  if (file) load(file);
});

resize();
const src = params.get('src');
if (src) {
  load(src);
} else {
  reset('none');
  Object.assign(state, { status: 'idle', done: true });
  say('drop an .srm file on the page, or open one with ?src=URL.srm');
}
