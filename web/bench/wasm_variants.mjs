// Builds of srcodec_decoder.wasm against each other: the same bits out, and
// their decode times side by side in one process (alternated, medians). For
// trying compile and link flags in web/CMakeLists.txt, and for profiling
// (node --cpu-prof on a long loop of one build).
//
//   node web/bench/wasm_variants.mjs [--runs 51] [--warmup 5]
//       --wasm NAME=PATH [--wasm NAME=PATH ...] FILE.srm...
//
// The first build is the reference: every other build must give, for each
// file, the same positions (bit for bit) and indices at the whole file and at
// every prefix where a level or a bit plane ends; the script stops at the
// first difference. Then it times whole-file decodes (copy-out included) and
// prints each build's median and its ratio to the reference's, with how many
// runs of --runs the build was at least as fast in the same run.
import { readFileSync } from 'node:fs';
import { basename, dirname, resolve } from 'node:path';
import { performance } from 'node:perf_hooks';

import { createDecoder } from '../dist/index.js';

function usage(message) {
  if (message) console.error(`wasm_variants.mjs: ${message}`);
  console.error('usage: node web/bench/wasm_variants.mjs [--runs N] [--warmup N] --wasm NAME=PATH... FILE.srm...');
  process.exit(2);
}

const options = { runs: 51, warmup: 5, builds: [], files: [] };
const argv = process.argv.slice(2);
for (let i = 0; i < argv.length; ++i) {
  const a = argv[i];
  if (a === '--runs' || a === '--warmup') {
    const n = Number(argv[++i]);
    if (!Number.isInteger(n) || n < (a === '--runs' ? 1 : 0)) usage(`${a} ${argv[i]}: use a whole number`);
    options[a.slice(2)] = n;
  } else if (a === '--wasm') {
    const [name, path] = String(argv[++i]).split(/=(.*)/s);
    if (!path) usage('--wasm takes NAME=PATH');
    options.builds.push({ name, path: resolve(path) });
  } else if (a.startsWith('--')) usage(`unknown option ${a}`);
  else options.files.push(resolve(a));
}
if (options.builds.length === 0) usage('no --wasm builds');
if (options.files.length === 0) usage('no .srm files');

for (const b of options.builds) b.decoder = await createDecoder({ wasm: readFileSync(b.path) });
// prepare.mjs's cache holds every mesh's file as <mesh>/srcodec.srm: the
// folder names it.
const files = options.files.map((path) => ({
  path, name: `${basename(dirname(path))}/${basename(path)}`, bytes: new Uint8Array(readFileSync(path)),
}));

// Float32 positions compared as their bits, so that -0 and NaN count too.
function sameMesh(a, b) {
  const pa = new Uint32Array(a.positions.buffer, a.positions.byteOffset, a.positions.length);
  const pb = new Uint32Array(b.positions.buffer, b.positions.byteOffset, b.positions.length);
  if (pa.length !== pb.length || a.indices.length !== b.indices.length || a.level !== b.level) return false;
  for (let i = 0; i < pa.length; ++i) if (pa[i] !== pb[i]) return false;
  for (let i = 0; i < a.indices.length; ++i) if (a.indices[i] !== b.indices[i]) return false;
  return true;
}

const reference = options.builds[0];
for (const f of files) {
  const info = reference.decoder.inspect(f.bytes);
  const cuts = new Set([f.bytes.length, ...info.levelInfo.map((l) => l.drawableFrom), ...info.planes.map((p) => p.end)]);
  let checked = 0;
  for (const cut of [...cuts].filter((c) => c > 0 && c <= f.bytes.length).sort((x, y) => x - y)) {
    const prefix = f.bytes.subarray(0, cut);
    const want = reference.decoder.decode(prefix);
    for (const b of options.builds.slice(1)) {
      if (!sameMesh(want, b.decoder.decode(prefix))) {
        console.error(`wasm_variants.mjs: ${b.name} differs from ${reference.name} on ${f.name} at ${cut} bytes`);
        process.exit(1);
      }
    }
    ++checked;
  }
  f.triangles = reference.decoder.decode(f.bytes).triangleCount;
  f.checked = checked;
}

const times = files.map(() => options.builds.map(() => []));
for (const f of files) for (const b of options.builds) for (let i = 0; i < options.warmup; ++i) b.decoder.decode(f.bytes);
for (let run = 0; run < options.runs; ++run) {
  files.forEach((f, fi) => {
    for (let j = 0; j < options.builds.length; ++j) {
      const bi = (run + j) % options.builds.length;
      const start = performance.now();
      options.builds[bi].decoder.decode(f.bytes);
      times[fi][bi].push(performance.now() - start);
    }
  });
}

const median = (values) => {
  const s = [...values].sort((a, b) => a - b);
  return s.length % 2 ? s[(s.length - 1) / 2] : (s[s.length / 2 - 1] + s[s.length / 2]) / 2;
};
const names = options.builds.map((b) => b.name);
console.log(`${options.runs} runs after ${options.warmup} warm-up decodes; median ms of a whole-file decode; ` +
  'in brackets: the reference\'s median over the build\'s (above 1: faster), and the runs where it was at least as fast.');
console.log('');
console.log(`| file | triangles | prefixes checked equal | ${names.join(' | ')} |`);
console.log(`|---|---|---|${names.map(() => '---|').join('')}`);
files.forEach((f, fi) => {
  const ref = median(times[fi][0]);
  const cells = options.builds.map((b, bi) => {
    const m = median(times[fi][bi]);
    if (bi === 0) return m.toFixed(2);
    const ahead = times[fi][bi].filter((t, r) => t <= times[fi][0][r]).length;
    return `${m.toFixed(2)} (${(ref / m).toFixed(2)}x, ${ahead})`;
  });
  console.log(`| ${f.name} | ${f.triangles} | ${f.checked} | ${cells.join(' | ')} |`);
});
console.log('');
for (const b of options.builds) console.log(`${b.name}: ${b.path} (${readFileSync(b.path).length} bytes)`);
