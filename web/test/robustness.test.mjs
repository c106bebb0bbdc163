// Hostile bytes: every truncation of a small .srm and 1000 seeded mutations
// each end in an Error with a message or a valid mesh, never a trap of the
// WebAssembly instance (after each failure the same decoder still decodes
// the good file to the same bits) and never a hang. The loops run in a
// worker thread, so that a decode that never returns is stopped and named.
// Also maxVertices (refused before allocating) and invalid options.
import assert from 'node:assert/strict';
import { isMainThread, parentPort, Worker, workerData } from 'node:worker_threads';

import { createDecoder, DEFAULT_MAX_VERTICES, MAX_VERTICES_LIMIT } from '../dist/index.js';
import {
  assertSameDecode, dataPath, headerFields, meshProblem, nativeRun, prng, readData, scratch, withHeaderField,
} from './helpers.mjs';

const STATUS_NAMES = new Set(['invalid_argument', 'not_found', 'io_error', 'parse_error', 'invalid_mesh',
  'unsupported', 'internal']);
// One decode of these few-kB files takes milliseconds; the margin is for
// garbage collection on a busy machine.
const SLOW_MS = 2000;

// The decoder's answer to one case: { mesh: whether it gave one, problem:
// why the answer is wrong, or null }. Right answers are an Error of the
// decoder's (not a trap it was restarted after) with a message, or a valid
// mesh; after an Error, the good file still decodes to the same bits.
function judge(decoder, bytes, options, good) {
  let mesh;
  try {
    mesh = decoder.decode(bytes, options);
  } catch (error) {
    const refused = (problem) => ({ mesh: false, problem });
    if (!(error instanceof Error)) return refused(`threw ${String(error)}, not an Error`);
    if (typeof error.message !== 'string' || error.message.length === 0) return refused('an Error without a message');
    if (/restarted/.test(error.message)) return refused(`the instance trapped: ${error.message}`);
    if (!STATUS_NAMES.has(error.code)) return refused(`an Error with code ${error.code}: ${error.message}`);
    try {
      assertSameDecode(decoder.decode(good.bytes), good.mesh, 'the good file');
    } catch (broken) {
      return refused(`after "${error.message}" the good file no longer decodes right: ${broken.message}`);
    }
    return refused(null);
  }
  const problem = meshProblem(mesh);
  return { mesh: true, problem: problem === null ? null : `an invalid mesh: ${problem}` };
}

// The cases of one job, generated the same way on every run.
function* truncations(file) {
  for (let n = 0; n <= file.length; ++n) {
    yield { kind: 'truncated', label: `first ${n} bytes`, bytes: file.subarray(0, n), options: {} };
  }
}

function* mutations(file, count, seed) {
  const random = prng(seed);
  const { fields } = headerFields(file);
  const levels = file[fields.find((f) => f.name === 'levels').at];
  // Most targeted mutations go to the counts, not the many segment lengths.
  const counts = fields.filter((f) => !f.name.startsWith('segment_length'));
  for (let trial = 0; trial < count; ++trial) {
    const slot = trial % 10;  // which kind of mutation
    let bytes = Array.from(file);
    let label;
    let what;
    const edits = 1 + random.int(8);
    if (slot === 9) {
      // A header field rewritten with the header's CRC made right, so that
      // the value itself reaches the decoder.
      const field = random() < 0.75 ? counts[random.int(counts.length)] : fields[random.int(fields.length)];
      const choices = [0n, 1n, BigInt(field.value) + 1n, 2n ** 21n + 1n, 2n ** 40n,
        2n ** 62n, 2n ** 64n - 1n, BigInt(random.int(2 ** 31)), 255n];
      const value = field.kind === 'u8' ? BigInt(random.int(256)) : choices[random.int(choices.length)];
      bytes = Array.from(withHeaderField(file, field, value));
      label = `${field.name} = ${value}`;
      what = 'header field';
    } else if (slot < 2) {
      for (let k = 0; k < edits; ++k) bytes[random.int(bytes.length)] = random.int(256);
      label = `${edits} bytes replaced`;
      what = 'bytes replaced';
    } else if (slot < 5) {
      for (let k = 0; k < edits; ++k) bytes[random.int(bytes.length)] ^= 1 << random.int(8);
      label = `${edits} bits flipped`;
      what = 'bits flipped';
    } else if (slot < 7) {
      for (let k = 0; k < edits; ++k) bytes.splice(random.int(bytes.length + 1), 0, random.int(256));
      label = `${edits} bytes inserted`;
      what = 'bytes inserted';
    } else {
      for (let k = 0; k < edits; ++k) bytes.splice(random.int(bytes.length), 1);
      label = `${edits} bytes deleted`;
      what = 'bytes deleted';
    }
    // Some at a coarser level or from a prefix: other paths through the decoder.
    const options = {};
    if (trial % 3 === 0) options.level = random.int(levels + 1);
    if (trial % 7 === 0) options.maxBytes = 1 + random.int(bytes.length);
    yield { kind: what, label: `mutation ${trial}: ${label} ${JSON.stringify(options)}`, bytes: Uint8Array.from(bytes),
      options };
  }
}

// The worker: runs one job's cases, reporting each case before decoding it.
async function runJob({ job, fileName, goodName, count, seed }) {
  const decoder = await createDecoder();
  const file = readData(fileName);
  const goodBytes = readData(goodName);
  const good = { bytes: goodBytes, mesh: decoder.decode(goodBytes) };
  const cases = job === 'truncations' ? truncations(file) : mutations(file, count, seed);
  const result = { cases: 0, meshes: 0, failures: [], slowest: 0, slowestLabel: '', kinds: {} };
  const started = performance.now();
  for (const c of cases) {
    parentPort.postMessage({ at: c.label });
    const t = performance.now();
    const { mesh, problem } = judge(decoder, c.bytes, c.options, good);
    const ms = performance.now() - t;
    if (problem !== null) result.failures.push(`${c.label}: ${problem}`);
    if (ms > result.slowest) Object.assign(result, { slowest: ms, slowestLabel: c.label });
    ++result.cases;
    if (mesh) ++result.meshes;
    const kind = (result.kinds[c.kind] ??= { cases: 0, meshes: 0 });
    ++kind.cases;
    if (mesh) ++kind.meshes;
  }
  result.milliseconds = performance.now() - started;
  parentPort.postMessage({ result });
}

// Runs a job in a worker; rejects, naming the case, when one case takes
// longer than `stallMs` (the worker is then stopped).
function inWorker(job, stallMs = 20000) {
  return new Promise((resolve, reject) => {
    const worker = new Worker(new URL(import.meta.url), { workerData: job });
    let at = 'the start';
    let timer;
    const arm = () => {
      clearTimeout(timer);
      timer = setTimeout(() => {
        worker.terminate();
        reject(new Error(`${job.job}: ${at} did not finish within ${stallMs} ms: the decoder hangs`));
      }, stallMs);
    };
    arm();
    worker.on('message', (m) => {
      if (m.result) {
        clearTimeout(timer);
        resolve(m.result);
        worker.terminate();
      } else {
        at = m.at;
        arm();
      }
    });
    worker.on('error', (e) => {
      clearTimeout(timer);
      reject(e);
    });
    worker.on('exit', (code) => {
      clearTimeout(timer);
      reject(new Error(`${job.job}: the worker exited (${code}) at ${at}`));  // ignored once resolved
    });
  });
}

function reportJob(t, name, r) {
  t.diagnostic(`${name}: ${r.cases} cases, ${r.meshes} meshes, ${r.cases - r.meshes} errors, ` +
    `${(r.milliseconds / 1000).toFixed(2)} s; slowest ${r.slowest.toFixed(1)} ms (${r.slowestLabel})`);
  const kinds = Object.entries(r.kinds).map(([kind, n]) => `${kind} ${n.meshes}/${n.cases}`);
  t.diagnostic(`  meshes / cases: ${kinds.join(', ')}`);
  assert.deepEqual(r.failures.slice(0, 10), [], `${r.failures.length} cases went wrong`);
  assert.ok(r.slowest < SLOW_MS, `${r.slowestLabel} took ${r.slowest.toFixed(0)} ms`);
}

if (isMainThread) {
  const { test } = await import('node:test');
  const decoder = await createDecoder();

  test('every truncation of spot_default.srm: an Error with a message or a valid mesh', async (t) => {
    const r = await inWorker({ job: 'truncations', fileName: 'spot_default.srm', goodName: 'spot_default.srm' });
    reportJob(t, 'every truncation', r);
    // As the C++ decoder promises: from the end of the header on, every prefix decodes.
    const { headerBytes } = decoder.inspect(readData('spot_default.srm'));
    assert.equal(r.meshes, r.cases - headerBytes);
  });

  test('1000 seeded mutations of golden_v2.srm: an Error with a message or a valid mesh', async (t) => {
    const r = await inWorker({
      job: 'mutations', fileName: 'golden_v2.srm', goodName: 'golden_v2.srm', count: 1000, seed: 2026,
    });
    reportJob(t, '1000 mutations', r);
    assert.equal(r.cases, 1000);
  });

  test('the targeted mutations reach the header fields they name', () => {
    // The mutations rewrite fields where headerFields finds them: check it
    // finds them where the decoder reads them.
    for (const name of ['golden_v1.srm', 'golden_v2.srm', 'spot_default.srm']) {
      const bytes = readData(name);
      const h = headerFields(bytes);
      const info = decoder.inspect(bytes);
      assert.equal(h.parsedEnd, h.bodyEnd, `${name}: the fields fill the header body`);
      assert.equal(h.bodyEnd + 4, info.headerBytes);
      const value = (n) => Number(h.fields.find((f) => f.name === n).value);
      assert.equal(value('levels'), info.levels);
      assert.equal(value('base_vertices'), info.baseVertices);
      assert.equal(value('base_triangles'), info.baseTriangles);
      assert.equal(value('input_vertices'), info.inputVertices);
      let vertices = 0;
      for (let l = 0; l <= info.levels; ++l) {
        vertices += value(`level_vertices[${l}]`);
        assert.equal(vertices, info.levelInfo[l].vertices, `${name}: level ${l}'s vertices`);
      }
      const changed = withHeaderField(bytes, h.fields.find((f) => f.name === 'input_vertices'), 12345);
      assert.equal(decoder.inspect(changed).inputVertices, 12345, 'a rewritten field keeps a valid CRC');
    }
  });

  test('maxVertices: a level with more vertices is refused with the decoder\'s message', () => {
    const path = dataPath('spot_default.srm');
    const bytes = readData('spot_default.srm');
    const { levels, levelInfo } = decoder.inspect(bytes);
    const finest = levelInfo[levels].vertices;
    const native = nativeRun(path, { maxVertices: finest - 1 });
    assert.equal(native.ok, false);
    assert.throws(() => decoder.decode(bytes, { maxVertices: finest - 1 }),
      (e) => e.message === native.message && e.code === 'invalid_argument');
    assert.equal(decoder.decode(bytes, { maxVertices: finest }).vertexCount, finest);
    // The limit is on the level decoded, not on the file's finest.
    assert.equal(decoder.decode(bytes, { level: levels - 1, maxVertices: finest - 1 }).level, levels - 1);
  });

  // A header claiming 2^40 vertices at its finest level, with a valid CRC:
  // refused at once, as C++ refuses it, and the decoder keeps working.
  function hugeHeader() {
    const bytes = readData('golden_v2.srm');
    const { fields } = headerFields(bytes);
    const levels = decoder.inspect(bytes).levels;
    return withHeaderField(bytes, fields.find((f) => f.name === `level_vertices[${levels}]`), 2n ** 40n);
  }

  test('maxVertices: a header claiming 2^40 vertices is refused fast and the decoder keeps working', () => {
    const files = scratch();
    try {
      const huge = hugeHeader();
      const native = nativeRun(files.write('huge.srm', huge), { maxVertices: DEFAULT_MAX_VERTICES });
      assert.equal(native.ok, false);
      const good = readData('golden_v2.srm');
      const before = decoder.decode(good);
      for (const maxVertices of [DEFAULT_MAX_VERTICES, MAX_VERTICES_LIMIT]) {
        const started = performance.now();
        assert.throws(() => decoder.decode(huge, { maxVertices }), (e) => e.code === 'invalid_argument' &&
          /over the limit/.test(e.message) && (maxVertices !== DEFAULT_MAX_VERTICES || e.message === native.message));
        const ms = performance.now() - started;
        assert.ok(ms < 50, `the refusal took ${ms.toFixed(1)} ms`);
        assertSameDecode(decoder.decode(good), before, 'the good file after the refusal');
      }
    } finally {
      files.remove();
    }
  });

  // decoder.js keeps its instance private; the test sees the module's
  // memory by watching the instance being made, without touching the API.
  async function decoderWithMemory() {
    const Instance = WebAssembly.Instance;
    let memory = null;
    WebAssembly.Instance = class extends Instance {
      constructor(module, imports) {
        super(module, imports);
        memory = this.exports.memory;
      }
    };
    try {
      return { decoder: await createDecoder(), memory };
    } finally {
      WebAssembly.Instance = Instance;
    }
  }

  test('maxVertices: refusals happen before allocating (the module\'s memory stays put)', async (t) => {
    const { decoder: fresh, memory } = await decoderWithMemory();
    if (!(memory instanceof WebAssembly.Memory)) {
      t.skip('the module\'s memory is not reachable');
      return;
    }
    const small = readData('golden_v1.srm');
    fresh.decode(small, { level: 0 });
    const before = memory.buffer.byteLength;
    const spot = readData('spot_default.srm');
    const { levels, levelInfo } = fresh.inspect(spot);
    // A real file over the limit, a header claiming 2^40 vertices, and one
    // claiming just over the default limit (about 1 GB if it were allocated).
    const overDefault = withHeaderField(small, headerFields(small).fields.find((f) => f.name === 'level_vertices[2]'),
      BigInt(DEFAULT_MAX_VERTICES));
    const refusals = [[spot, levelInfo[levels].vertices - 1], [hugeHeader(), MAX_VERTICES_LIMIT],
      [overDefault, DEFAULT_MAX_VERTICES]];
    for (const [bytes, maxVertices] of refusals) {
      assert.throws(() => fresh.decode(bytes, { maxVertices }), /over the limit/);
    }
    const grown = memory.buffer.byteLength - before;
    t.diagnostic(`memory: ${before >> 10} kB before the refusals, grown by ${grown >> 10} kB`);
    assert.ok(grown <= 4 << 20, `the memory grew by ${grown} bytes`);
    assert.equal(fresh.decode(small, { level: 0 }).level, 0);
    // The measure sees allocations: the same file within its limit grows the
    // memory (a little: 31k vertices), where 2^21 would take hundreds of MB.
    fresh.decode(spot);
    assert.ok(memory.buffer.byteLength > before, 'decoding spot_default.srm did not grow the memory');
  });

  test('invalid options throw a RangeError naming the option', () => {
    const bytes = readData('golden_v1.srm');
    const cases = [['level', 13], ['level', -2], ['level', 1.5], ['level', '1'], ['level', NaN],
      ['maxVertices', 0], ['maxVertices', -1], ['maxVertices', 2.5], ['maxVertices', MAX_VERTICES_LIMIT + 1],
      ['maxVertices', Infinity], ['maxBytes', -1], ['maxBytes', 0.5], ['maxBytes', 2 ** 53]];
    for (const [name, value] of cases) {
      assert.throws(() => decoder.decode(bytes, { [name]: value }),
        (e) => e instanceof RangeError && e.message.includes(name), `${name}: ${value}`);
    }
    assert.throws(() => decoder.decode('not bytes'), TypeError);
    assert.equal(decoder.decode(bytes).level, decoder.inspect(bytes).levels);
  });
} else {
  await runJob(workerData);
}
