// srcodec's WebAssembly decoder against Draco's, in one Node process, on the
// files prepare.mjs made (each mesh's srcodec default file and the Draco file
// of the nearest PSNR):
//
//   node web/bench/decode_bench.mjs --cache DIR [--runs 51] [--warmup 5]
//       [--rate 1000000] [--json OUT] MESH...
//
// Measures, per mesh, side by side and alternated (each run decodes every
// file once, the order rotating from run to run, so that a burst of load
// elsewhere on the machine falls on all of them alike):
//   - decode throughput, output triangles per second, from the median decode
//     time; each decode includes copying the mesh out into a Float32Array of
//     positions and a Uint32Array of indices, as a loader does;
//   - srcodec's decode of its first drawable prefix (level 0's drawableFrom
//     bytes), for the time to the first mesh on screen when the file arrives
//     at --rate bytes per second: that prefix's arrival plus its decode,
//     against Draco's whole file's arrival plus its decode;
//   - the size of each decoder as shipped: raw, gzip -9 and brotli.
// Prints Markdown tables; --json writes every figure and the per-run times.
//
// Two Draco decoders are timed: the draco3d npm package's (its Node build,
// draco_decoder_nodejs.js + draco_decoder.wasm) and the copy three.js ships
// for DRACOLoader (examples/jsm/libs/draco: draco_wasm_wrapper.js +
// draco_decoder.wasm), each driven the way DRACOLoader drives it.
// Run web/build.sh first (web/dist and node_modules).
import { createHash } from 'node:crypto';
import { readFileSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { cpus, loadavg } from 'node:os';
import { basename, dirname, join, resolve } from 'node:path';
import { performance } from 'node:perf_hooks';
import { fileURLToPath } from 'node:url';
import { brotliCompressSync, constants as zlibConstants, gzipSync } from 'node:zlib';

import { createDecoder } from '../dist/index.js';
import { parseObj } from '../tools/native.mjs';

const web = fileURLToPath(new URL('../', import.meta.url));
const require = createRequire(import.meta.url);
// The packages web/build.sh installed (npm ci): read from their folders, as
// three's exports map hides its examples and package.json from require.
const threeRoot = join(web, 'node_modules/three');
const dracoNpmRoot = join(web, 'node_modules/draco3d');
const threeDraco = join(threeRoot, 'examples/jsm/libs/draco');
const packageVersion = (root) => JSON.parse(readFileSync(join(root, 'package.json'), 'utf8')).version;

function usage(message) {
  if (message) console.error(`decode_bench.mjs: ${message}`);
  console.error('usage: node web/bench/decode_bench.mjs --cache DIR [--runs N] [--warmup N] [--rate BYTES_PER_S] ' +
    '[--json OUT] MESH...');
  process.exit(2);
}

function parseArguments(argv) {
  const options = { cache: null, runs: 51, warmup: 5, rate: 1e6, json: null, meshes: [] };
  const number = (name, text, min) => {
    const value = Number(text);
    if (!Number.isFinite(value) || value < min) usage(`${name} ${text}: use a number >= ${min}`);
    return value;
  };
  for (let i = 0; i < argv.length; ++i) {
    const a = argv[i];
    if (a === '--cache') options.cache = resolve(argv[++i]);
    else if (a === '--runs') options.runs = Math.round(number(a, argv[++i], 1));
    else if (a === '--warmup') options.warmup = Math.round(number(a, argv[++i], 0));
    else if (a === '--rate') options.rate = number(a, argv[++i], 1);
    else if (a === '--json') options.json = resolve(argv[++i]);
    else if (a.startsWith('--')) usage(`unknown option ${a}`);
    else options.meshes.push(resolve(a));
  }
  if (!options.cache) usage('--cache DIR is required');
  if (options.meshes.length === 0) usage('no meshes');
  return options;
}

// ---- Draco, driven as DRACOLoader drives it ----

// The draco3d npm package's decoder (its Node build).
async function dracoFromNpm() {
  const draco3d = require(dracoNpmRoot);
  return draco3d.createDecoderModule({});
}

// The copy three.js ships for DRACOLoader: an emscripten wrapper script that
// defines DracoDecoderModule, given the .wasm's bytes. The script expects
// CommonJS's module, require and __dirname in Node.
async function dracoFromThree() {
  const folder = threeDraco;
  const source = readFileSync(join(folder, 'draco_wasm_wrapper.js'), 'utf8');
  const module = { exports: {} };
  new Function('module', 'exports', 'require', '__dirname', source)(module, module.exports, require, folder);
  return module.exports({ wasmBinary: readFileSync(join(folder, 'draco_decoder.wasm')) });
}

// Decodes a .drc file into typed arrays the way a loader does: a decoder and
// mesh per file, the positions as float32 and the triangles as uint32 copied
// out of the module's heap, then everything freed.
function dracoDecode(draco, bytes) {
  const decoder = new draco.Decoder();
  const mesh = new draco.Mesh();
  try {
    const status = decoder.DecodeArrayToMesh(bytes, bytes.byteLength, mesh);
    if (!status.ok() || mesh.ptr === 0) throw new Error(`Draco: ${status.error_msg()}`);
    const attribute = decoder.GetAttribute(mesh, decoder.GetAttributeId(mesh, draco.POSITION));
    const valueCount = mesh.num_points() * attribute.num_components();
    let byteLength = valueCount * 4;
    let p = draco._malloc(byteLength);
    decoder.GetAttributeDataArrayForAllPoints(mesh, attribute, draco.DT_FLOAT32, byteLength, p);
    // The heap may have grown during the call: its view is read afterwards.
    const positions = new Float32Array(draco.HEAPF32.buffer, p, valueCount).slice();
    draco._free(p);
    const indexCount = mesh.num_faces() * 3;
    byteLength = indexCount * 4;
    p = draco._malloc(byteLength);
    decoder.GetTrianglesUInt32Array(mesh, byteLength, p);
    const indices = new Uint32Array(draco.HEAPU32.buffer, p, indexCount).slice();
    draco._free(p);
    return { positions, indices, triangleCount: indexCount / 3 };
  } finally {
    draco.destroy(mesh);
    draco.destroy(decoder);
  }
}

// ---- Sizes as shipped ----

function sizesOf(files) {
  const each = files.map((path) => {
    const bytes = readFileSync(path);
    return {
      file: path.slice(web.length),
      raw: bytes.length,
      gzip9: gzipSync(bytes, { level: 9 }).length,
      brotli: brotliCompressSync(bytes, {
        params: { [zlibConstants.BROTLI_PARAM_QUALITY]: zlibConstants.BROTLI_MAX_QUALITY,
          [zlibConstants.BROTLI_PARAM_SIZE_HINT]: bytes.length },
      }).length,
    };
  });
  // Each file is served (and compressed) on its own, so the totals are sums.
  const total = (key) => each.reduce((sum, f) => sum + f[key], 0);
  return { files: each, raw: total('raw'), gzip9: total('gzip9'), brotli: total('brotli') };
}

// The JavaScript srcodec's entry point loads, followed from dist/index.js's
// imports, so that the size counts what an application importing 'srcodec'
// actually fetches.
function srcodecShippedFiles() {
  const dist = join(web, 'dist');
  const seen = new Set();
  const visit = (name) => {
    if (seen.has(name)) return;
    seen.add(name);
    const text = readFileSync(join(dist, name), 'utf8');
    for (const m of text.matchAll(/^\s*(?:import|export)\b[^'"]*?from\s+['"]\.\/([^'"]+)['"]/gm)) visit(m[1]);
  };
  visit('index.js');
  return [join(dist, 'srcodec_decoder.wasm'), ...[...seen].map((name) => join(dist, name))];
}

// ---- Statistics ----

function median(values) {
  const s = [...values].sort((a, b) => a - b);
  const n = s.length;
  return n % 2 ? s[(n - 1) / 2] : (s[n / 2 - 1] + s[n / 2]) / 2;
}

function quantile(values, q) {
  const s = [...values].sort((a, b) => a - b);
  return s[Math.min(s.length - 1, Math.max(0, Math.round(q * (s.length - 1))))];
}

// ---- The benchmark ----

function loadMesh(cache, manifest, meshPath) {
  const key = basename(meshPath);
  const entry = manifest.meshes[key];
  if (!entry) usage(`${key} is not in ${cache}/manifest.json: run prepare.mjs --cache ${cache} ${meshPath}`);
  const sha = createHash('sha256').update(readFileSync(meshPath)).digest('hex');
  if (sha !== entry.inputSha256) usage(`${meshPath} changed since prepare.mjs encoded it: run prepare.mjs again`);
  return { key, entry, srm: new Uint8Array(readFileSync(entry.srcodec.file)), drc: new Int8Array(readFileSync(entry.draco.file)) };
}

// The mesh of the OBJ `srcodec decode` wrote, in float32, to check that the
// WebAssembly decoder gives the mesh whose PSNR prepare.mjs measured.
function readObj(path) {
  const { positions, indices } = parseObj(readFileSync(path, 'utf8'));
  return { positions: Float32Array.from(positions), indices };
}

function sameArrays(a, b) {
  if (a.length !== b.length) return false;
  for (let i = 0; i < a.length; ++i) if (a[i] !== b[i] && !(Number.isNaN(a[i]) && Number.isNaN(b[i]))) return false;
  return true;
}

const options = parseArguments(process.argv.slice(2));
const manifest = JSON.parse(readFileSync(join(options.cache, 'manifest.json'), 'utf8'));
const meshes = options.meshes.map((m) => loadMesh(options.cache, manifest, m));
const srcodec = await createDecoder();
const dracoNpm = await dracoFromNpm();
const dracoThree = await dracoFromThree();
const loadBefore = loadavg();

// The timed decodes of each mesh, checked once before any timing.
for (const m of meshes) {
  const info = srcodec.inspect(m.srm);
  m.info = info;
  m.firstBytes = info.levelInfo[0].drawableFrom;
  m.prefix = m.srm.subarray(0, m.firstBytes);
  const whole = srcodec.decode(m.srm);
  const first = srcodec.decode(m.prefix);
  const npm = dracoDecode(dracoNpm, m.drc);
  const three = dracoDecode(dracoThree, m.drc);
  // The native doubles rounded to float32, as the WebAssembly module rounds them.
  const native = readObj(m.entry.srcodec.file.replace(/\.srm$/, '.obj'));
  if (!sameArrays(whole.positions, native.positions) || !sameArrays(whole.indices, native.indices)) {
    throw new Error(`${m.key}: the WebAssembly decode is not the native one (srcodec.obj) rounded to float32`);
  }
  if (!sameArrays(npm.positions, three.positions) || !sameArrays(npm.indices, three.indices)) {
    throw new Error(`${m.key}: the two Draco decoders disagree`);
  }
  m.output = {
    srcodec: { vertices: whole.vertexCount, triangles: whole.triangleCount, level: whole.level },
    first: { vertices: first.vertexCount, triangles: first.triangleCount, level: first.level },
    draco: { vertices: npm.positions.length / 3, triangles: npm.triangleCount },
  };
  m.tasks = {
    srcodec: () => srcodec.decode(m.srm),
    srcodecFirst: () => srcodec.decode(m.prefix),
    dracoNpm: () => dracoDecode(dracoNpm, m.drc),
    dracoThree: () => dracoDecode(dracoThree, m.drc),
  };
  m.times = Object.fromEntries(Object.keys(m.tasks).map((k) => [k, []]));
}

const taskNames = ['srcodec', 'srcodecFirst', 'dracoNpm', 'dracoThree'];
for (const m of meshes) for (const name of taskNames) for (let i = 0; i < options.warmup; ++i) m.tasks[name]();

let sink = 0;  // keeps each decode's result observably used
for (let run = 0; run < options.runs; ++run) {
  for (const m of meshes) {
    for (let j = 0; j < taskNames.length; ++j) {
      const name = taskNames[(run + j) % taskNames.length];
      const start = performance.now();
      const result = m.tasks[name]();
      const ms = performance.now() - start;
      sink += result.indices.length;
      m.times[name].push(ms);
    }
  }
}
const loadAfter = loadavg();
if (sink === 0) throw new Error('no decode produced triangles');

// ---- Figures ----

const rate = options.rate;
const results = meshes.map((m) => {
  const t = Object.fromEntries(taskNames.map((k) => [k, median(m.times[k])]));
  const spread = Object.fromEntries(taskNames.map((k) => [k, [quantile(m.times[k], 0.25), quantile(m.times[k], 0.75)]]));
  const perSecond = (triangles, ms) => triangles / (ms / 1000);
  const throughput = {
    srcodec: perSecond(m.output.srcodec.triangles, t.srcodec),
    dracoNpm: perSecond(m.output.draco.triangles, t.dracoNpm),
    dracoThree: perSecond(m.output.draco.triangles, t.dracoThree),
  };
  // The ratio within each run (the decodes run next to each other), counted
  // at 1.0x or more: how steady the median ratio is.
  const runsAhead = (draco) => m.times.srcodec.filter((ts, r) =>
    perSecond(m.output.srcodec.triangles, ts) >= perSecond(m.output.draco.triangles, m.times[draco][r])).length;
  const arrival = (bytes) => bytes / rate * 1000;
  const firstMesh = {
    srcodecFirstMs: arrival(m.firstBytes) + t.srcodecFirst,
    srcodecWholeMs: arrival(m.srm.length) + t.srcodec,
    dracoNpmWholeMs: arrival(m.drc.length) + t.dracoNpm,
    dracoThreeWholeMs: arrival(m.drc.length) + t.dracoThree,
  };
  return {
    mesh: m.key,
    input: m.entry.input,
    inputVertices: m.entry.inputVertices,
    inputTriangles: m.entry.inputTriangles,
    files: {
      srcodec: { ...m.entry.srcodec, file: basename(m.entry.srcodec.file) },
      draco: { ...m.entry.draco, file: basename(m.entry.draco.file) },
      above: m.entry.srcodec.psnr >= m.entry.draco.psnr ? 'srcodec' : 'draco',
      dracoTried: m.entry.dracoTried,
    },
    output: m.output,
    firstBytes: m.firstBytes,
    medianMs: t,
    quartilesMs: spread,
    trianglesPerSecond: throughput,
    ratio: {
      srcodecOverDracoNpm: throughput.srcodec / throughput.dracoNpm,
      srcodecOverDracoThree: throughput.srcodec / throughput.dracoThree,
      runsAheadOfDracoNpm: runsAhead('dracoNpm'),
      runsAheadOfDracoThree: runsAhead('dracoThree'),
    },
    firstMesh: {
      ...firstMesh,
      dracoNpmOverSrcodecFirst: firstMesh.dracoNpmWholeMs / firstMesh.srcodecFirstMs,
      dracoThreeOverSrcodecFirst: firstMesh.dracoThreeWholeMs / firstMesh.srcodecFirstMs,
    },
    timesMs: m.times,
  };
});

const sizes = {
  srcodec: sizesOf(srcodecShippedFiles()),
  dracoThree: sizesOf([join(threeDraco, 'draco_decoder.wasm'), join(threeDraco, 'draco_wasm_wrapper.js')]),
  dracoThreeGltf: sizesOf([join(threeDraco, 'gltf/draco_decoder.wasm'), join(threeDraco, 'gltf/draco_wasm_wrapper.js')]),
  dracoNpm: sizesOf([join(dracoNpmRoot, 'draco_decoder.wasm'), join(dracoNpmRoot, 'draco_decoder_nodejs.js')]),
};

// ---- Printing ----

const f1 = (x) => x.toFixed(1);
const f2 = (x) => x.toFixed(2);
const mtri = (x) => (x / 1e6).toFixed(2);
const kB = (x) => (x / 1000).toFixed(1);
const out = [];
const runs = options.runs;
out.push(`Node ${process.version}, ${cpus().length} cores (${cpus()[0].model}); load average before ` +
  `${loadBefore.map(f2).join(' ')}, after ${loadAfter.map(f2).join(' ')}; ${runs} runs after ${options.warmup} warm-up decodes; ` +
  `medians. Draco: draco3d ${packageVersion(dracoNpmRoot)} (npm) and three.js ` +
  `${packageVersion(threeRoot)}'s DRACOLoader copy.`, '');

out.push('Files at equal PSNR (srcodec: the default file; Draco -cl 10: the qp whose PSNR is nearest):', '');
out.push('| mesh | srcodec bytes | srcodec PSNR dB | Draco qp | Draco bytes | Draco PSNR dB | above |');
out.push('|---|---|---|---|---|---|---|');
for (const r of results) {
  out.push(`| ${r.mesh} | ${r.files.srcodec.bytes} | ${f2(r.files.srcodec.psnr)} | ${r.files.draco.qp} | ` +
    `${r.files.draco.bytes} | ${f2(r.files.draco.psnr)} | ${r.files.above} |`);
}

out.push('', 'Decode throughput (output triangles per second, from the median decode time, copy-out included; ' +
  `in brackets, runs of ${runs} where srcodec's rate was at least Draco's in the same run):`, '');
out.push('| mesh | srcodec triangles | srcodec ms | srcodec Mtri/s | Draco triangles | draco3d ms | draco3d Mtri/s | ' +
  'ratio vs draco3d | three.js Draco ms | ratio vs three.js Draco |');
out.push('|---|---|---|---|---|---|---|---|---|---|');
for (const r of results) {
  out.push(`| ${r.mesh} | ${r.output.srcodec.triangles} | ${f2(r.medianMs.srcodec)} | ${mtri(r.trianglesPerSecond.srcodec)} | ` +
    `${r.output.draco.triangles} | ${f2(r.medianMs.dracoNpm)} | ${mtri(r.trianglesPerSecond.dracoNpm)} | ` +
    `**${f2(r.ratio.srcodecOverDracoNpm)}x** (${r.ratio.runsAheadOfDracoNpm}) | ${f2(r.medianMs.dracoThree)} | ` +
    `${f2(r.ratio.srcodecOverDracoThree)}x (${r.ratio.runsAheadOfDracoThree}) |`);
}

out.push('', 'Decoder size as shipped (bytes; each file compressed on its own, totals summed):', '');
out.push('| decoder | files | raw | gzip -9 | brotli |');
out.push('|---|---|---|---|---|');
const sizeRow = (name, s) => out.push(`| ${name} | ${s.files.map((f) => `${basename(f.file)} ${f.raw}`).join(' + ')} | ` +
  `${s.raw} | **${s.gzip9}** (${kB(s.gzip9)} kB) | ${s.brotli} |`);
sizeRow('srcodec', sizes.srcodec);
sizeRow('Draco, three.js DRACOLoader', sizes.dracoThree);
sizeRow('Draco, three.js DRACOLoader gltf/', sizes.dracoThreeGltf);
sizeRow('Draco, draco3d npm (Node build)', sizes.dracoNpm);

out.push('', `Time to the first drawable mesh, the file arriving at ${rate / 1e6} MB/s (arrival + median decode, ms):`, '');
out.push('| mesh | srcodec first prefix bytes | first mesh (level, triangles) | its decode ms | srcodec first mesh ms | ' +
  'srcodec whole file ms | Draco whole file ms (draco3d) | ratio Draco / srcodec first |');
out.push('|---|---|---|---|---|---|---|---|');
for (const r of results) {
  out.push(`| ${r.mesh} | ${r.firstBytes} | ${r.output.first.level}, ${r.output.first.triangles} | ` +
    `${f2(r.medianMs.srcodecFirst)} | ${f1(r.firstMesh.srcodecFirstMs)} | ${f1(r.firstMesh.srcodecWholeMs)} | ` +
    `${f1(r.firstMesh.dracoNpmWholeMs)} | **${f1(r.firstMesh.dracoNpmOverSrcodecFirst)}x** |`);
}

// The package's goals, each judged on every mesh given.
const goals = {
  throughput: results.every((r) => r.ratio.srcodecOverDracoNpm >= 1 && r.ratio.srcodecOverDracoThree >= 1),
  size: sizes.srcodec.gzip9 < 100_000,
  firstMesh: results.every((r) => r.firstMesh.dracoNpmOverSrcodecFirst >= 10),
};
const yes = (ok) => (ok ? 'met' : 'NOT met');
out.push('', 'Goals:', '');
out.push(`- decode throughput at least Draco's on every mesh: ${yes(goals.throughput)} (lowest ratio ` +
  `${f2(Math.min(...results.map((r) => Math.min(r.ratio.srcodecOverDracoNpm, r.ratio.srcodecOverDracoThree))))}x)`);
out.push(`- decoder .wasm + JavaScript under 100 kB gzip -9: ${yes(goals.size)} (${kB(sizes.srcodec.gzip9)} kB)`);
out.push(`- first mesh at least 10x sooner than Draco's whole file at ${rate / 1e6} MB/s on every mesh: ` +
  `${yes(goals.firstMesh)} (lowest ${f1(Math.min(...results.map((r) => r.firstMesh.dracoNpmOverSrcodecFirst)))}x)`);
console.log(out.join('\n'));

if (options.json) {
  const report = {
    node: process.version, cpu: cpus()[0].model, cores: cpus().length,
    loadAverageBefore: loadBefore, loadAverageAfter: loadAfter,
    runs, warmup: options.warmup, rateBytesPerSecond: rate,
    draco: { npm: packageVersion(dracoNpmRoot), three: packageVersion(threeRoot) },
    sizes, goals, meshes: results,
  };
  writeFileSync(options.json, `${JSON.stringify(report, null, 1)}\n`);
}
