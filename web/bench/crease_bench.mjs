// What splitting normals at creases costs the browser's decode, in Node:
//
//   node web/bench/crease_bench.mjs [--runs 31] [--warmup 3] FILE.srm...
//
// Per file (one with creases, which `srcodec encode` keeps on CAD-like
// meshes), the median time of two ways to go from the bytes to a three.js
// geometry with normals:
//   smooth  decode, then the indexed geometry with computeVertexNormals (what
//           a file without creases gets);
//   split   decode with cornerNormals (the WebAssembly module computes them),
//           then meshGeometry's geometry with a vertex per normal (what
//           SRMLoader makes of a file with creases);
// alternated run by run, so that load elsewhere on the machine falls on
// both alike; and, of each, the decode alone and the geometry alone.
// Run web/build.sh first (web/dist and node_modules).
import { readFileSync } from 'node:fs';
import { basename } from 'node:path';
import { performance } from 'node:perf_hooks';

import { createDecoder } from '../dist/index.js';
import { meshGeometry } from '../dist/SRMLoader.js';

function parseArguments(argv) {
  const options = { runs: 31, warmup: 3, files: [] };
  for (let i = 0; i < argv.length; ++i) {
    if (argv[i] === '--runs') options.runs = Number(argv[++i]);
    else if (argv[i] === '--warmup') options.warmup = Number(argv[++i]);
    else if (argv[i].startsWith('--')) throw new Error(`unknown option ${argv[i]}`);
    else options.files.push(argv[i]);
  }
  if (options.files.length === 0 || !(options.runs >= 1) || !(options.warmup >= 0)) {
    throw new Error('usage: node web/bench/crease_bench.mjs [--runs N] [--warmup N] FILE.srm...');
  }
  return options;
}

const median = (values) => {
  const sorted = [...values].sort((a, b) => a - b);
  return sorted[Math.floor(sorted.length / 2)];
};

function timed(run) {
  const started = performance.now();
  const value = run();
  return [performance.now() - started, value];
}

function measure(decoder, bytes, { runs, warmup }) {
  const times = { smooth: [], split: [], smoothDecode: [], smoothGeometry: [], splitDecode: [], splitGeometry: [] };
  let shape = null;
  for (let run = -warmup; run < runs; ++run) {
    const ways = run % 2 === 0 ? ['smooth', 'split'] : ['split', 'smooth'];
    for (const way of ways) {
      const [decodeMs, mesh] = timed(() => decoder.decode(bytes, { cornerNormals: way === 'split' }));
      const [geometryMs, geometry] = timed(() => meshGeometry(mesh));
      if (run >= 0) {
        times[way].push(decodeMs + geometryMs);
        times[`${way}Decode`].push(decodeMs);
        times[`${way}Geometry`].push(geometryMs);
      }
      if (way === 'split') {
        shape = {
          vertices: mesh.vertexCount, triangles: mesh.triangleCount, creaseEdges: mesh.creaseEdges.length / 2,
          drawn: geometry.getAttribute('position').count,
        };
      }
    }
  }
  return { shape, medians: Object.fromEntries(Object.entries(times).map(([k, v]) => [k, median(v)])) };
}

const options = parseArguments(process.argv.slice(2));
const decoder = await createDecoder();
console.log(`${options.runs} runs each, medians (ms)\n`);
console.log('| file | vertices | triangles | crease edges | drawn vertices | smooth | split | split / smooth | ' +
  'decode: smooth | decode: split (+ normals) | geometry: smooth (computeVertexNormals) | geometry: split |');
console.log('|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|');
for (const file of options.files) {
  const bytes = new Uint8Array(readFileSync(file));
  const { shape, medians: m } = measure(decoder, bytes, options);
  const f = (ms) => ms.toFixed(2);
  const { vertices, triangles, creaseEdges, drawn } = shape;
  console.log(`| ${basename(file)} | ${vertices} | ${triangles} | ${creaseEdges} | ${drawn} | ` +
    `${f(m.smooth)} | ${f(m.split)} | ${(m.split / m.smooth).toFixed(3)} | ${f(m.smoothDecode)} | ` +
    `${f(m.splitDecode)} | ${f(m.smoothGeometry)} | ${f(m.splitGeometry)} |`);
}
