// The viewer in headless Chromium over a slow server: it refines coarse to
// fine, ends on the C++ decoder's mesh, draws something visible, and says
// what went wrong on damaged files, broken connections and refusals.
// Waits on the page's state (window.srcodecViewer), never on fixed delays.
import assert from 'node:assert/strict';
import { mkdirSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { after, before, test } from 'node:test';
import { fileURLToPath } from 'node:url';

import { createDecoder } from '../dist/index.js';
import { launchChromium } from '../tools/chromium.mjs';
import { startServer } from '../tools/serve.mjs';
import { nativeDecode, repository } from '../tools/native.mjs';

// 128 bytes every 50 ms: the 2 kB sample arrives in about 16 chunks.
const SLOW = { rate: 2560, chunkBytes: 128 };
const WAIT = { timeout: 30_000 };

const sample = join(repository, 'tests/data/spot_default.srm');
const cube = join(repository, 'tests/data/cube_creases_v3.srm');  // creased at its 12 edges, flat faces
const output = fileURLToPath(new URL('../test-output/', import.meta.url));

let browser;
let workDir;
let damaged;
let hostile;
const servers = [];

// The bytes of an .srm with part of its coefficients flipped: the header and
// the levels' flags intact, one bit plane's segment corrupt.
async function damagedCopy(bytes) {
  const decoder = await createDecoder();
  const info = decoder.inspect(bytes);
  const copy = Uint8Array.from(bytes);
  const start = info.levelInfo.at(-1).drawableFrom;
  const from = start + Math.floor((info.declaredBytes - start) / 3);
  for (let i = from; i < from + 16; ++i) copy[i] ^= 0xa5;
  return copy;
}

function crc32(bytes) {
  let crc = ~0;
  for (const byte of bytes) {
    crc ^= byte;
    for (let k = 0; k < 8; ++k) crc = (crc >>> 1) ^ (0xedb88320 & -(crc & 1));
  }
  return ~crc >>> 0;
}

// A hostile .srm: its header (CRC-valid) says every coefficient segment is
// 4 GB long, so that it declares far more bytes than the file holds
// (format/srm/README.md gives the header's fields).
function hugeDeclaredCopy(bytes) {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.length);
  const bodyEnd = 10 + view.getUint32(6, true);
  let at = 10;
  const varint = () => {
    let value = 0;
    for (let shift = 0; ; shift += 7) {
      const byte = bytes[at++];
      value += (byte & 127) * 2 ** shift;
      if (byte < 128) return value;
    }
  };
  varint(); varint();
  at += 24;
  const levels = bytes[at];
  at += 2 + 4;
  varint(); varint();
  for (let l = 0; l <= levels; ++l) varint();
  at += 4 + 4 + 1 + (bytes[4] >= 2 ? 1 : 0);
  varint();
  at += 4;
  for (let l = 0; l < levels; ++l) { varint(); at += 4; }
  const segments = varint();
  const parts = [bytes.subarray(10, at)];
  for (let s = 0; s < segments; ++s) {
    const start = at;
    const length = varint();
    if (length === 0) {
      parts.push(bytes.subarray(start, at));
    } else {
      parts.push(Uint8Array.of(0xff, 0xff, 0xff, 0xff, 0x0f), bytes.subarray(at, at + 2));
      at += 2;
    }
  }
  parts.push(bytes.subarray(at, bodyEnd));
  const body = Buffer.concat(parts);
  const head = Buffer.concat([bytes.subarray(0, 6), Buffer.alloc(4), body]);
  head.writeUInt32LE(body.length, 6);
  const crc = Buffer.alloc(4);
  crc.writeUInt32LE(crc32(head));
  return Buffer.concat([head, crc, bytes.subarray(bodyEnd + 4)]);
}

async function serve(files, options = {}) {
  const server = await startServer({ files, ...options });
  servers.push(server);
  return (name) => `http://127.0.0.1:${server.port}${name}`;
}

// A fresh page on the viewer; page errors are collected for the caller.
async function openViewer(url, { width = 800, height = 600 } = {}) {
  const page = await browser.newPage({ viewport: { width, height } });
  const errors = [];
  page.on('pageerror', (error) => errors.push(error.message));
  await page.goto(url);
  await page.waitForFunction(() => window.srcodecViewer?.done === true, null, WAIT);
  return { page, errors };
}

// The viewer's state without its images and with the mesh as plain arrays.
function viewerState(page) {
  return page.evaluate(() => {
    const { lastMesh, refinements, info, ...rest } = window.srcodecViewer;
    return {
      ...rest,
      info,
      refinements: refinements.map(({ image, ...numbers }) => numbers),
      lastMesh: lastMesh && {
        level: lastMesh.level,
        positions: Array.from(lastMesh.positions),
        indices: Array.from(lastMesh.indices),
        cornerNormals: lastMesh.cornerNormals && {
          normals: Array.from(lastMesh.cornerNormals.normals),
          vertices: Array.from(lastMesh.cornerNormals.vertices),
          corners: Array.from(lastMesh.cornerNormals.corners),
        },
        drawnVertices: lastMesh.drawnVertices,
      },
    };
  });
}

async function messageShown(page) {
  const message = page.locator('#message');
  assert.ok(await message.isVisible(), 'the message is visible');
  return message.textContent();
}

before(async () => {
  mkdirSync(output, { recursive: true });
  workDir = mkdtempSync(join(tmpdir(), 'srcodec-viewer-'));
  damaged = join(workDir, 'damaged.srm');
  writeFileSync(damaged, await damagedCopy(readFileSync(sample)));
  hostile = join(workDir, 'hostile.srm');
  writeFileSync(hostile, hugeDeclaredCopy(readFileSync(sample)));
  browser = await launchChromium();
});

after(async () => {
  await browser?.close();
  await Promise.all(servers.map((server) => server.close()));
  if (workDir) rmSync(workDir, { recursive: true, force: true });
});

test('streams coarse to fine and ends on the C++ decoder\'s mesh', async () => {
  const url = await serve([sample], SLOW);
  const { page, errors } = await openViewer(url('/viewer/?src=/file/spot_default.srm&snapshots=1'));
  const state = await viewerState(page);
  const size = readFileSync(sample).length;

  assert.equal(state.status, 'done');
  assert.equal(state.error, null);
  assert.equal(state.bytesReceived, size);
  const drawn = state.refinements;
  assert.ok(drawn.length >= 3, `${drawn.length} refinements drawn`);
  assert.ok(drawn[0].bytesReceived < size, 'the first refinement came before the whole file');
  const triangles = drawn.map((r) => r.triangles);
  for (let i = 1; i < drawn.length; ++i) {
    assert.ok(triangles[i] >= triangles[i - 1], `triangles rise: ${triangles}`);
    assert.ok(drawn[i].frame > drawn[i - 1].frame, 'one refinement per animation frame');
    assert.ok(drawn[i].level >= drawn[i - 1].level, 'coarse to fine');
  }
  assert.ok(new Set(triangles).size >= 3, `at least three triangle counts: ${triangles}`);
  // Every level is drawn, though the flags of all of them come in one chunk.
  const levels = state.info.levelInfo.length;
  assert.deepEqual([...new Set(drawn.map((r) => r.level))], [...Array(levels).keys()]);
  assert.equal(drawn.at(-1).bytesReceived, size);
  // The camera frames the header's box from the start, and stays.
  for (const r of drawn) assert.deepEqual(r.camera, drawn[0].camera, 'the camera does not move');

  // The last refinement is the C++ decode of the whole file, to the bit.
  const native = nativeDecode(sample);
  const mesh = state.lastMesh;
  assert.equal(mesh.positions.length, native.positions.length);
  const expected = Float32Array.from(native.positions, Math.fround);
  const got = Float32Array.from(mesh.positions);
  assert.ok(Buffer.from(got.buffer).equals(Buffer.from(expected.buffer)), 'positions are the C++ doubles as float32');
  assert.deepEqual(mesh.indices, Array.from(native.indices));
  // No creases: the mesh's own vertices, drawn with smooth normals.
  assert.equal(mesh.cornerNormals, null);
  assert.equal(mesh.drawnVertices, mesh.positions.length / 3);

  // The first and the last refinement as drawn, and not blank.
  const images = await page.evaluate(() => {
    const r = window.srcodecViewer.refinements;
    return [r[0].image, r.at(-1).image];
  });
  for (const [name, image, entry] of [['first', images[0], drawn[0]], ['last', images[1], drawn.at(-1)]]) {
    writeFileSync(join(output, `viewer-${name}.png`), Buffer.from(image.split(',')[1], 'base64'));
    assert.ok(entry.coverage > 0.05, `the ${name} refinement covers ${(100 * entry.coverage).toFixed(1)}% of the canvas`);
  }
  await page.screenshot({ path: join(output, 'viewer-page.png') });
  assert.equal(await page.locator('#message').isVisible(), false, 'no message after a clean load');
  assert.equal(await page.locator('#triangles').textContent(), drawn.at(-1).triangles.toLocaleString('en'));

  // The slider decodes a prefix: the first level's bytes give what the C++ decoder gives.
  const prefixBytes = state.info.planes[2].end;
  await page.evaluate((n) => {
    const slider = document.getElementById('prefix');
    slider.value = String(n);
    slider.dispatchEvent(new Event('input'));
  }, prefixBytes);
  await page.waitForFunction((n) => window.srcodecViewer.prefix?.maxBytes === n, prefixBytes, WAIT);
  const prefix = await page.evaluate(() => window.srcodecViewer.prefix);
  const nativePrefix = nativeDecode(sample, { bytes: prefixBytes });
  assert.equal(prefix.error, null);
  assert.equal(prefix.triangles, nativePrefix.indices.length / 3);
  const prefixMesh = await page.evaluate(() => Array.from(window.srcodecViewer.lastMesh.positions));
  assert.ok(Buffer.from(Float32Array.from(prefixMesh).buffer)
    .equals(Buffer.from(Float32Array.from(nativePrefix.positions, Math.fround).buffer)), 'the prefix\'s positions');
  assert.deepEqual(errors, []);
  await page.close();
});

// A file with creases is drawn with normals split at them: a vertex per
// corner normal, each a face normal of the cube (crease corners too), where
// smooth normals would round the edges off; without creases (above), the
// mesh's own vertices.
test('a cube with creases is drawn with its faces\' normals at the edges', async () => {
  const url = await serve([cube], SLOW);
  const { page, errors } = await openViewer(url('/viewer/?src=/file/cube_creases_v3.srm&snapshots=1'));
  const state = await viewerState(page);
  assert.equal(state.status, 'done');
  assert.equal(state.error, null);
  const mesh = state.lastMesh;
  const native = nativeDecode(cube);
  assert.deepEqual(mesh.indices, Array.from(native.indices));
  assert.ok(mesh.cornerNormals, 'corner normals');
  const { normals, vertices, corners } = mesh.cornerNormals;
  assert.equal(mesh.drawnVertices, vertices.length);
  assert.ok(vertices.length > mesh.positions.length / 3, 'the crease vertices are split');
  assert.deepEqual(corners, Array.from(native.normalIndices));
  const close = Math.cos((0.5 * Math.PI) / 180);  // half a degree
  for (let i = 0; i < normals.length; i += 3) {
    const axis = Math.max(...normals.slice(i, i + 3).map(Math.abs));
    assert.ok(axis > close, `normal ${i / 3} is not a cube face's: ${normals.slice(i, i + 3)}`);
  }
  const image = await page.evaluate(() => window.srcodecViewer.refinements.at(-1).image);
  writeFileSync(join(output, 'viewer-cube.png'), Buffer.from(image.split(',')[1], 'base64'));
  assert.ok(state.refinements.at(-1).coverage > 0.05, 'the cube is drawn');
  assert.deepEqual(errors, []);
  await page.close();
});

test('a damaged file: a visible message and the best mesh its bytes allow', async () => {
  const url = await serve([damaged], SLOW);
  const { page, errors } = await openViewer(url('/viewer/?src=/file/damaged.srm'));
  const state = await viewerState(page);
  assert.ok(state.error, 'the viewer reports an error');
  assert.equal(state.messageKind, 'error');
  assert.match(await messageShown(page), /not all of the file decodes/);
  assert.ok(state.lastMesh && state.lastMesh.indices.length > 0, 'a mesh is still drawn');
  assert.ok(state.refinements.length > 0);
  assert.deepEqual(errors, []);
  await page.close();
});

test('a header that declares gigabytes more than the file holds: a message and the mesh of the bytes that came', async () => {
  const decoder = await createDecoder();
  assert.ok(decoder.inspect(readFileSync(hostile)).declaredBytes > 2 ** 36, 'the crafted header is read');
  const url = await serve([hostile], SLOW);
  const { page, errors } = await openViewer(url('/viewer/?src=/file/hostile.srm'));
  const state = await viewerState(page);
  assert.equal(state.status, 'done');
  // The bytes end far before the size the header declares: a cut file.
  assert.match(await messageShown(page), /its header declares/);
  assert.ok(state.lastMesh && state.lastMesh.indices.length > 0, 'a mesh is drawn');
  assert.deepEqual(errors, []);
  await page.close();
});

test('a connection dropped mid-stream leaves the last refinement and says so', async () => {
  const size = readFileSync(sample).length;
  const url = await serve([sample], { ...SLOW, dropAfter: Math.floor(size * 0.55) });
  const { page, errors } = await openViewer(url('/viewer/?src=/file/spot_default.srm'));
  const state = await viewerState(page);
  assert.equal(state.status, 'failed');
  assert.match(await messageShown(page), /connection broke after .* showing the last refinement/);
  assert.ok(state.bytesReceived < size);
  assert.ok(state.lastMesh && state.lastMesh.indices.length > 0, 'the last refinement stays');
  assert.equal(state.refinements.at(-1).triangles, state.lastMesh.indices.length / 3);
  assert.deepEqual(errors, []);
  await page.close();
});

test('maxVertices refuses a large level with a visible message', async () => {
  const url = await serve([sample], SLOW);
  const { page, errors } = await openViewer(url('/viewer/?src=/file/spot_default.srm&maxVertices=100'));
  const state = await viewerState(page);
  assert.equal(state.status, 'failed');
  assert.equal(state.refinements.length, 0);
  assert.match(await messageShown(page), /over the limit of 100/);
  assert.deepEqual(errors, []);
  await page.close();
});

test('a missing file and a file that is not an .srm: visible messages', async () => {
  const url = await serve([sample]);
  for (const [src, reason] of [['/file/missing.srm', /HTTP 404/], ['/viewer/index.html', /not an \.srm file/]]) {
    const { page, errors } = await openViewer(url(`/viewer/?src=${src}`));
    assert.equal(await page.evaluate(() => window.srcodecViewer.status), 'failed');
    assert.match(await messageShown(page), reason);
    assert.deepEqual(errors, []);
    await page.close();
  }
});

test('a dropped file that is cut short: a warning and the mesh of its bytes', async () => {
  const url = await serve([sample]);
  const page = await browser.newPage({ viewport: { width: 800, height: 600 } });
  const errors = [];
  page.on('pageerror', (error) => errors.push(error.message));
  await page.goto(url('/viewer/'));
  await page.waitForFunction(() => window.srcodecViewer?.status === 'idle', null, WAIT);
  const bytes = readFileSync(sample);
  const cut = Math.floor(bytes.length * 0.6);
  await page.evaluate((numbers) => {
    const transfer = new DataTransfer();
    transfer.items.add(new File([Uint8Array.from(numbers)], 'cut.srm'));
    window.dispatchEvent(new DragEvent('drop', { dataTransfer: transfer, bubbles: true, cancelable: true }));
  }, Array.from(bytes.subarray(0, cut)));
  await page.waitForFunction(() => window.srcodecViewer.done === true, null, WAIT);
  const state = await viewerState(page);
  assert.equal(state.status, 'done');
  assert.equal(state.messageKind, 'warning');
  assert.match(await messageShown(page), /the file is cut/);
  const native = nativeDecode(sample, { bytes: cut });
  assert.deepEqual(state.lastMesh.indices, Array.from(native.indices));
  assert.ok(Buffer.from(Float32Array.from(state.lastMesh.positions).buffer)
    .equals(Buffer.from(Float32Array.from(native.positions, Math.fround).buffer)));
  assert.deepEqual(errors, []);
  await page.close();
});
