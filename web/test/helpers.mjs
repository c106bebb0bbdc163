// What the Node tests share: the test files, the native CLI's answers with
// its report and its refusals, bitwise mesh comparison, a seeded PRNG, CRC-32
// and a reader of the .srm header's fields (for mutations that keep the
// header's checksum valid).
import assert from 'node:assert/strict';
import { execFileSync, spawnSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';

import { parseObj, repository, srcodecBinary } from '../tools/native.mjs';

export { repository };

export function dataPath(name) {
  return join(repository, 'tests/data', name);
}

export function readData(name) {
  return new Uint8Array(readFileSync(dataPath(name)));
}

// A scratch folder for the files the native CLI reads and writes.
export function scratch() {
  const dir = mkdtempSync(join(tmpdir(), 'srcodec-web-test-'));
  return {
    dir,
    write(name, bytes) {
      const path = join(dir, name);
      writeFileSync(path, bytes);
      return path;
    },
    remove() { rmSync(dir, { recursive: true, force: true }); },
  };
}

// The CLI prints "srcodec CMD: error: FILE: MESSAGE"; the decoder's Status
// message is what follows the file name.
function refusalMessage(stderr, path) {
  const text = stderr.trim();
  const at = text.indexOf(`${path}: `);
  return at >= 0 ? text.slice(at + path.length + 2) : text;
}

// `srcodec decode` of the native build: { ok: true, positions (doubles),
// indices, report (its --json line) } or { ok: false, status, message }.
export function nativeRun(srmPath, { level = -1, bytes = 0, maxVertices = 0 } = {}) {
  const dir = mkdtempSync(join(tmpdir(), 'srcodec-native-'));
  try {
    const out = join(dir, 'mesh.obj');
    const args = ['decode', srmPath, '-o', out, '--single-thread', '--json'];
    if (level >= 0) args.push('--level', String(level));
    if (bytes > 0) args.push('--bytes', String(bytes));
    if (maxVertices > 0) args.push('--max-vertices', String(maxVertices));
    const run = spawnSync(srcodecBinary(), args, { encoding: 'utf8' });
    if (run.error) throw run.error;
    if (run.status !== 0) return { ok: false, status: run.status, message: refusalMessage(run.stderr, srmPath) };
    const mesh = parseObj(readFileSync(out, 'utf8'));
    return { ok: true, ...mesh, report: JSON.parse(run.stdout) };
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
}

// `srcodec info FILE --json`.
export function nativeInfo(srmPath) {
  return JSON.parse(execFileSync(srcodecBinary(), ['info', srmPath, '--json'], { encoding: 'utf8' }));
}

// Float32 bits of the native doubles, rounded as Math.fround (and C++'s
// double-to-float conversion) rounds: to nearest, ties to even.
export function float32BitsOf(doubles) {
  return new Uint32Array(Float32Array.from(doubles, Math.fround).buffer);
}

// The WebAssembly mesh has exactly the native mesh's float32-rounded
// positions (compared as bits, so -0 and 0 differ) and its indices.
export function assertSameMesh(wasm, native, what) {
  assert.equal(wasm.positions.length, native.positions.length, `${what}: position count`);
  const got = new Uint32Array(wasm.positions.buffer, wasm.positions.byteOffset, wasm.positions.length);
  const want = float32BitsOf(native.positions);
  for (let i = 0; i < want.length; ++i) {
    if (got[i] !== want[i]) {
      assert.fail(`${what}: coordinate ${i} (vertex ${Math.floor(i / 3)}) is ${wasm.positions[i]}, ` +
        `expected fround(${native.positions[i]}) = ${Math.fround(native.positions[i])}`);
    }
  }
  assert.equal(wasm.indices.length, native.indices.length, `${what}: index count`);
  for (let i = 0; i < native.indices.length; ++i) {
    if (wasm.indices[i] !== native.indices[i]) {
      assert.fail(`${what}: index ${i} is ${wasm.indices[i]}, expected ${native.indices[i]}`);
    }
  }
}

// Two meshes of the WebAssembly decoder are the same, bit for bit.
export function assertSameDecode(a, b, what) {
  assert.equal(a.level, b.level, `${what}: level`);
  assert.equal(a.bytesUsed, b.bytesUsed, `${what}: bytesUsed`);
  assert.equal(a.lastCompletePlane, b.lastCompletePlane, `${what}: lastCompletePlane`);
  assert.equal(a.baseCut, b.baseCut, `${what}: baseCut`);
  assert.equal(a.creasesCut, b.creasesCut, `${what}: creasesCut`);
  assert.deepEqual(a.creaseEdges, b.creaseEdges, `${what}: creaseEdges`);
  assert.deepEqual(new Uint32Array(a.positions.buffer, a.positions.byteOffset, a.positions.length),
    new Uint32Array(b.positions.buffer, b.positions.byteOffset, b.positions.length), `${what}: positions`);
  assert.deepEqual(a.indices, b.indices, `${what}: indices`);
}

// Why a mesh is not a valid one (null when it is): whole counts matching the
// arrays, finite positions, every index below the vertex count.
export function meshProblem(mesh) {
  const { positions, indices, vertexCount, triangleCount } = mesh;
  if (!(positions instanceof Float32Array) || !(indices instanceof Uint32Array)) return 'arrays of the wrong type';
  if (!Number.isInteger(vertexCount) || vertexCount * 3 !== positions.length) return `vertexCount ${vertexCount}`;
  if (!Number.isInteger(triangleCount) || triangleCount * 3 !== indices.length) return `triangleCount ${triangleCount}`;
  for (let i = 0; i < positions.length; ++i) {
    if (!Number.isFinite(positions[i])) return `coordinate ${i} is ${positions[i]}`;
  }
  for (let i = 0; i < indices.length; ++i) {
    if (indices[i] >= vertexCount) return `index ${i} is ${indices[i]}, not below ${vertexCount} vertices`;
  }
  if (!Number.isInteger(mesh.level) || mesh.level < 0 || mesh.level > 12) return `level ${mesh.level}`;
  if (!Number.isInteger(mesh.bytesUsed) || mesh.bytesUsed < 0) return `bytesUsed ${mesh.bytesUsed}`;
  return null;
}

// mulberry32: a small seeded PRNG, so that every run mutates the same bytes.
export function prng(seed) {
  let a = seed >>> 0;
  const next = () => {
    a = (a + 0x6d2b79f5) >>> 0;
    let t = a;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 2 ** 32;
  };
  next.int = (n) => Math.floor(next() * n);  // 0 .. n-1
  return next;
}

const CRC_TABLE = (() => {
  const table = new Uint32Array(256);
  for (let n = 0; n < 256; ++n) {
    let c = n;
    for (let k = 0; k < 8; ++k) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
    table[n] = c >>> 0;
  }
  return table;
})();

// CRC-32 (IEEE, as zlib's crc32), the .srm file's checksum.
export function crc32(bytes) {
  let c = 0xffffffff;
  for (const b of bytes) c = CRC_TABLE[(c ^ b) & 0xff] ^ (c >>> 8);
  return (c ^ 0xffffffff) >>> 0;
}

function readVarint(bytes, at) {
  let value = 0n;
  for (let shift = 0n, i = at; i < bytes.length && i < at + 10; ++i, shift += 7n) {
    value |= BigInt(bytes[i] & 0x7f) << shift;
    if ((bytes[i] & 0x80) === 0) return { value, size: i + 1 - at };
  }
  throw new Error(`bad varint at byte ${at}`);
}

export function encodeVarint(value) {
  let v = BigInt(value);
  const out = [];
  do {
    const low = Number(v & 0x7fn);
    v >>= 7n;
    out.push(v > 0n ? low | 0x80 : low);
  } while (v > 0n);
  return Uint8Array.from(out);
}

// The header's fields (format/srm/README.md), each as { name, at, size,
// kind: 'varint' | 'u8', value (BigInt for varints) }, and where the body ends.
export function headerFields(bytes) {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const version = bytes[4];
  const fields = [];
  let at = 10;
  const varint = (name) => {
    const { value, size } = readVarint(bytes, at);
    fields.push({ name, at, size, kind: 'varint', value });
    at += size;
    return Number(value);
  };
  const u8 = (name) => {
    fields.push({ name, at, size: 1, kind: 'u8', value: bytes[at] });
    return bytes[at++];
  };
  varint('input_vertices');
  varint('input_triangles');
  at += 24;  // bounding box
  const levels = u8('levels');
  u8('base_bits');
  at += 4;  // grid step
  varint('base_vertices');
  varint('base_triangles');
  for (let l = 0; l <= levels; ++l) varint(`level_vertices[${l}]`);
  at += 8;  // quantizer step, tangential factor
  u8('top_plane+1');
  if (version >= 2) u8('raw_planes');
  varint('base_length');
  at += 4;
  for (let l = 0; l < levels; ++l) {
    varint(`flag_length[${l}]`);
    at += 4;
  }
  const segments = varint('segment_count');
  for (let s = 0; s < segments; ++s) {
    if (varint(`segment_length[${s}]`) > 0) at += 2;
  }
  return { version, bodyEnd: 10 + view.getUint32(6, true), parsedEnd: at, fields };
}

// The file with one header field rewritten and the header's size and CRC
// made right again, so that the decoder gets past the checksum to the value.
export function withHeaderField(bytes, field, value) {
  const replacement = field.kind === 'varint' ? encodeVarint(value) : Uint8Array.of(Number(value) & 0xff);
  const out = new Uint8Array(bytes.length - field.size + replacement.length);
  out.set(bytes.subarray(0, field.at));
  out.set(replacement, field.at);
  out.set(bytes.subarray(field.at + field.size), field.at + replacement.length);
  const view = new DataView(out.buffer);
  const body = view.getUint32(6, true) + replacement.length - field.size;
  view.setUint32(6, body, true);
  view.setUint32(10 + body, crc32(out.subarray(0, 10 + body)), true);
  return out;
}
