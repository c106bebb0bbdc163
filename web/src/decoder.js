// srcodec's WebAssembly decoder, in Node and in browsers.
//
//   import { createDecoder } from 'srcodec';
//   const decoder = await createDecoder();
//   const mesh = decoder.decode(bytes, { level: 2 });   // positions, indices, level, ...
//
// The module is srcodec_decoder.wasm, built from the C++ decoder with
// web/build.sh; this file is all the glue it needs.

const STATUS_NAMES = ['ok', 'invalid_argument', 'not_found', 'io_error', 'parse_error', 'invalid_mesh',
  'unsupported', 'internal'];

// About 500 bytes of the module's memory per vertex while decoding, and a
// 32-bit module addresses 2 GB: 2^21 vertices keep well inside it.
export const DEFAULT_MAX_VERTICES = 2 ** 21;
export const MAX_VERTICES_LIMIT = 2 ** 22;

const isNode = typeof process !== 'undefined' && process.versions != null && process.versions.node != null;

async function fetchBytes(url) {
  const u = url instanceof URL ? url : new URL(String(url), isNode ? `file://${process.cwd()}/` : globalThis.location?.href);
  if (isNode && u.protocol === 'file:') {
    const fs = 'node:fs/promises';  // a variable, so that bundlers for the web leave it alone
    const { readFile } = await import(/* @vite-ignore */ /* webpackIgnore: true */ fs);
    return readFile(u);
  }
  const response = await fetch(u);
  if (!response.ok) throw new Error(`srcodec: cannot load ${u.href}: HTTP ${response.status}`);
  return response.arrayBuffer();
}

let defaultModule = null;

// The compiled module, shared by every decoder made from the same source.
async function compileModule(wasm) {
  if (wasm instanceof WebAssembly.Module) return wasm;
  if (wasm == null) {
    defaultModule ??= fetchBytes(new URL('./srcodec_decoder.wasm', import.meta.url)).then((b) => WebAssembly.compile(b));
    return defaultModule;
  }
  if (wasm instanceof ArrayBuffer || ArrayBuffer.isView(wasm)) return WebAssembly.compile(wasm);
  return WebAssembly.compile(await fetchBytes(wasm));
}

function checkCount(name, value, min, max) {
  if (typeof value !== 'number' || !Number.isInteger(value) || value < min || value > max) {
    throw new RangeError(`srcodec: ${name} ${value}: use a whole number in ${min}..${max}`);
  }
  return value;
}

function toBytes(bytes) {
  if (bytes instanceof Uint8Array) return bytes;
  if (bytes instanceof ArrayBuffer) return new Uint8Array(bytes);
  if (ArrayBuffer.isView(bytes)) return new Uint8Array(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  throw new TypeError('srcodec: the bytes must be a Uint8Array, an ArrayBuffer or another ArrayBuffer view');
}

// The layout srcodec_inspect writes (web/src/wasm_api.cpp).
function fileInfoFrom(n) {
  let i = 0;
  const next = () => n[i++];
  const info = {
    version: next(), fileBytes: next(), declaredBytes: next(), headerBytes: next(),
    inputVertices: next(), inputTriangles: next(),
    bboxMin: [next(), next(), next()], bboxMax: [next(), next(), next()],
    bitsPerVertex: next(), baseVertices: next(), baseTriangles: next(), baseBytes: next(),
    creaseBytes: next(), creaseEdges: next(), baseBits: next(),
    levels: next(), quantizerStep: next(), topPlane: next(), rawPlanes: next(),
    levelInfo: [], planes: [],
  };
  if (info.creaseEdges < 0) info.creaseEdges = null;  // not all present, or damaged (srcodec info's null)
  for (let count = next(); count > 0; --count) {
    info.levelInfo.push({ vertices: next(), flagBytes: next(), coefficientBytes: next(), drawableFrom: next() });
  }
  for (let count = next(); count > 0; --count) {
    info.planes.push({ plane: next(), bytes: next(), end: next() });
  }
  return info;
}

class Decoder {
  #module;
  #instance = null;
  #exports = null;

  constructor(module) {
    this.#module = module;
    this.#start();
  }

  #start() {
    const imports = {
      env: { emscripten_notify_memory_growth() {} },
      wasi_snapshot_preview1: {
        proc_exit(code) { throw new WebAssembly.RuntimeError(`srcodec: the decoder stopped (exit ${code})`); },
      },
    };
    this.#instance = new WebAssembly.Instance(this.#module, imports);
    this.#exports = this.#instance.exports;
    this.#exports._initialize();
  }

  // The library's version, "0.1.0".
  get version() {
    const e = this.#exports;
    const p = e.srcodec_version();
    const bytes = new Uint8Array(e.memory.buffer, p);
    return new TextDecoder().decode(bytes.subarray(0, bytes.indexOf(0)));
  }

  // Decodes a whole .srm file or a prefix of one. Options: level (-1, the
  // finest, or 0..12), maxBytes (decode only the first maxBytes bytes; 0:
  // all), maxVertices (refuse, before allocating, a file whose level has more
  // vertices), cornerNormals (for a mesh with crease edges, normals split at
  // them: README). Throws an Error whose message is the decoder's when the
  // bytes cannot give a mesh.
  decode(bytes, { level = -1, maxBytes = 0, maxVertices = DEFAULT_MAX_VERTICES, cornerNormals = false } = {}) {
    checkCount('level', level, -1, 12);
    checkCount('maxBytes', maxBytes, 0, Number.MAX_SAFE_INTEGER);
    checkCount('maxVertices', maxVertices, 1, MAX_VERTICES_LIMIT);
    const run = (e, p, n) => e.srcodec_decode(p, n, level, maxBytes, maxVertices, cornerNormals ? 1 : 0);
    return this.#call(toBytes(bytes), run, (e) => {
      const numbers = this.#numbers(e);
      const positions = new Float32Array(e.memory.buffer, e.srcodec_positions(), e.srcodec_position_count()).slice();
      const indices = new Uint32Array(e.memory.buffer, e.srcodec_indices(), e.srcodec_index_count()).slice();
      // After the scalars: the crease edges' count, then two vertex ids each (wasm_api.cpp).
      const creaseEdges = Uint32Array.from(numbers.subarray(6, 6 + 2 * numbers[5]));
      return {
        positions, indices,
        level: numbers[0], bytesUsed: numbers[1], lastCompletePlane: numbers[2], baseCut: numbers[3] !== 0,
        creasesCut: numbers[4] !== 0, creaseEdges, cornerNormals: this.#cornerNormals(e, indices.length),
        vertexCount: positions.length / 3, triangleCount: indices.length / 3,
      };
    });
  }

  // The normals srcodec_decode computed (null when it did not: not asked
  // for, or no crease edges), one corner per index.
  #cornerNormals(e, corners) {
    const count = e.srcodec_normal_count();
    if (count === 0) return null;
    const buffer = e.memory.buffer;
    return {
      normals: new Float32Array(buffer, e.srcodec_normals(), 3 * count).slice(),
      vertices: new Uint32Array(buffer, e.srcodec_normal_vertices(), count).slice(),
      corners: new Uint32Array(buffer, e.srcodec_corners(), corners).slice(),
    };
  }

  // The header of a file or of a prefix that holds it: counts, the bounding
  // box, and where each level and bit plane ends (what `srcodec info` prints).
  inspect(bytes) {
    return this.#call(toBytes(bytes), (e, p, n) => e.srcodec_inspect(p, n), (e) => fileInfoFrom(this.#numbers(e)));
  }

  #numbers(e) {
    return new Float64Array(e.memory.buffer, e.srcodec_numbers(), e.srcodec_number_count());
  }

  // Copies the bytes in, runs `run`, reads the result with `read`, and frees
  // everything. A trap (the module out of memory) leaves the instance
  // unusable: it is replaced, and the call throws.
  #call(bytes, run, read) {
    const e = this.#exports;
    let p = 0;
    try {
      p = e.srcodec_alloc(bytes.length);
      if (p === 0) throw new Error(`srcodec: no memory for ${bytes.length} bytes of input`);
      new Uint8Array(e.memory.buffer, p, bytes.length).set(bytes);
      const code = run(e, p, bytes.length);
      if (code !== 0) {
        const text = new Uint8Array(e.memory.buffer, e.srcodec_message(), e.srcodec_message_length());
        const error = new Error(new TextDecoder().decode(text));
        error.code = STATUS_NAMES[code] ?? 'unknown';
        throw error;
      }
      return read(e);
    } catch (error) {
      if (error instanceof WebAssembly.RuntimeError || error instanceof RangeError) {
        this.#start();
        p = 0;
        const failed = new Error(`srcodec: the decoder ran out of memory or failed (${error.message}); it was restarted`);
        failed.code = 'internal';
        throw failed;
      }
      throw error;
    } finally {
      if (p !== 0) {
        e.srcodec_release();
        e.srcodec_free(p);
      }
    }
  }
}

// A decoder over its own instance of the module. `options.wasm` may give the
// module (a URL, its bytes, or a compiled WebAssembly.Module) when it is not
// served beside this file.
export async function createDecoder(options = {}) {
  return new Decoder(await compileModule(options.wasm));
}
