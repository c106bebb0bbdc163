// The functions that took the most time in a V8 CPU profile (node
// --cpu-prof's .cpuprofile): self time (samples in the function itself) and
// total time (samples with the function anywhere on the stack), as shares of
// all the samples. With a decoder built with --profiling-funcs the
// WebAssembly functions keep their C++ names.
//
//   node web/bench/cpuprofile_top.mjs [--top 25] PROFILE.cpuprofile
import { readFileSync } from 'node:fs';

const argv = process.argv.slice(2);
let top = 25;
let path = null;
for (let i = 0; i < argv.length; ++i) {
  if (argv[i] === '--top') top = Number(argv[++i]);
  else path = argv[i];
}
if (!path || !Number.isInteger(top) || top < 1) {
  console.error('usage: node web/bench/cpuprofile_top.mjs [--top N] PROFILE.cpuprofile');
  process.exit(2);
}

const profile = JSON.parse(readFileSync(path, 'utf8'));
const byId = new Map(profile.nodes.map((n) => [n.id, n]));
const parent = new Map();
for (const n of profile.nodes) for (const c of n.children ?? []) parent.set(c, n.id);

// Wasm frames carry a wasm:// URL; the name alone is what the reader wants.
const nameOf = (n) => {
  const f = n.callFrame;
  const where = f.url.startsWith('wasm://') ? 'wasm' : f.url.split('/').pop() || f.url || 'native';
  return `${f.functionName || '(anonymous)'} [${where}]`;
};

const self = new Map();
const total = new Map();
const samples = profile.samples.length;
for (const id of profile.samples) {
  const leaf = byId.get(id);
  self.set(nameOf(leaf), (self.get(nameOf(leaf)) ?? 0) + 1);
  // Each function counted once per sample, however deep it recurses.
  const seen = new Set();
  for (let at = id; at !== undefined; at = parent.get(at)) {
    const name = nameOf(byId.get(at));
    if (!seen.has(name)) {
      seen.add(name);
      total.set(name, (total.get(name) ?? 0) + 1);
    }
  }
}

const pct = (x) => `${(100 * x / samples).toFixed(1)}%`;
console.log(`${samples} samples`);
console.log('');
console.log('| function | self | total |');
console.log('|---|---|---|');
for (const [name, count] of [...self].sort((a, b) => b[1] - a[1]).slice(0, top)) {
  console.log(`| \`${name.replace(/\|/g, '\\|')}\` | ${pct(count)} | ${pct(total.get(name))} |`);
}
