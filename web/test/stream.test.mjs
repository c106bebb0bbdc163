// Progressive decoding of a file as it arrives: ProgressiveDecoder fed in
// chunks of several sizes, and decodeStream over ReadableStreams that end,
// fail, stall or carry damaged or foreign bytes. Every refinement is checked
// against a direct decode of the same prefix at the same level.
import assert from 'node:assert/strict';
import { test } from 'node:test';

import { createDecoder, decodeStream, ProgressiveDecoder } from '../dist/index.js';
import {
  assertSameDecode, headerFields, meshProblem, nativeRun, prng, readData, scratch, withHeaderField,
} from './helpers.mjs';

const decoder = await createDecoder();
const FILES = ['spot_default.srm', 'golden_v2.srm', 'creases_v3.srm'];

function errorOf(run) {
  try {
    run();
  } catch (error) {
    return error;
  }
  return null;
}

// A pull stream over `bytes` in chunks of `chunk`, read only on demand
// (highWaterMark 0), so that `stats.pulled` counts the bytes the reader asked
// for. It may end early (endAt), fail (errorAt) or stop sending (stallAt).
function streamOf(bytes, { chunk = 100, endAt = bytes.length, errorAt = -1, stallAt = -1 } = {}) {
  const stats = { pulled: 0, cancelled: false, cancelReason: undefined };
  const stops = [endAt, errorAt, stallAt].filter((s) => s >= 0);
  const stream = new ReadableStream({
    pull(controller) {
      if (stats.pulled === errorAt) {
        controller.error(new Error('connection reset'));
        return undefined;
      }
      if (stats.pulled === stallAt) return new Promise(() => {});
      if (stats.pulled >= endAt) {
        controller.close();
        return undefined;
      }
      const next = Math.min(stats.pulled + chunk, ...stops.filter((s) => s > stats.pulled));
      controller.enqueue(bytes.slice(stats.pulled, next));
      stats.pulled = next;
      return undefined;
    },
    cancel(reason) {
      stats.cancelled = true;
      stats.cancelReason = reason;
    },
  }, { highWaterMark: 0 });
  return { stream, stats };
}

// The refinements a ProgressiveDecoder reports while `bytes` arrive in
// chunks of `chunk`, and its end() mesh.
function feed(bytes, chunk, options = {}) {
  const refinements = [];
  const progressive = new ProgressiveDecoder(decoder, {
    ...options, onRefine: (mesh, event) => refinements.push({ mesh, bytesReceived: event.bytesReceived }),
  });
  for (let at = 0; at < bytes.length; at += chunk) progressive.push(bytes.subarray(at, at + chunk));
  return { refinements, final: progressive.end(), progressive };
}

// The length of the bytes received when the push that brings byte `at`
// (counting from 1) ends.
function arrivedWith(at, chunk, length) {
  return Math.min(length, Math.ceil(at / chunk) * chunk);
}

// What every run over intact bytes must show: each refinement the mesh of
// its prefix at its level; levels 0..L coarse to fine, each at the chunk
// where its flags complete; one at the chunk where each bit plane ends;
// never two at the same prefix length and level.
function checkRefinements(bytes, chunk, refinements) {
  const info = decoder.inspect(bytes);
  const what = (r) => `chunks of ${chunk}: refinement at ${r.bytesReceived} bytes, level ${r.mesh.level}`;
  const seen = new Set();
  let previous = null;
  for (const r of refinements) {
    const key = `${r.bytesReceived}:${r.mesh.level}`;
    assert.ok(!seen.has(key), `${what(r)}: twice`);
    seen.add(key);
    assertSameDecode(r.mesh, decoder.decode(bytes.subarray(0, r.bytesReceived), { level: r.mesh.level }), what(r));
    if (previous !== null) {
      assert.ok(r.mesh.level >= previous.mesh.level, `${what(r)}: after level ${previous.mesh.level}`);
      assert.ok(r.mesh.triangleCount >= previous.mesh.triangleCount, `${what(r)}: fewer triangles than before`);
      assert.ok(r.bytesReceived >= previous.bytesReceived, `${what(r)}: fewer bytes than before`);
    }
    previous = r;
  }
  for (let level = 0; level <= info.levels; ++level) {
    const at = arrivedWith(info.levelInfo[level].drawableFrom, chunk, bytes.length);
    assert.ok(refinements.some((r) => r.bytesReceived === at && r.mesh.level === level),
      `chunks of ${chunk}: no refinement to level ${level} at ${at} bytes`);
  }
  for (const plane of info.planes) {
    const at = arrivedWith(plane.end, chunk, bytes.length);
    assert.ok(refinements.some((r) => r.bytesReceived === at && r.mesh.level === info.levels),
      `chunks of ${chunk}: no refinement at ${at} bytes, where plane ${plane.plane} ends (${plane.end})`);
  }
}

for (const name of FILES) {
  test(`ProgressiveDecoder over ${name} in chunks of 1, 7, 100 bytes and all at once`, () => {
    const bytes = readData(name);
    const whole = decoder.decode(bytes);
    for (const chunk of [1, 7, 100, bytes.length]) {
      const { refinements, final, progressive } = feed(bytes, chunk);
      checkRefinements(bytes, chunk, refinements);
      assertSameDecode(final, whole, `chunks of ${chunk}: the final mesh`);
      assert.equal(progressive.error, null);
      assert.equal(progressive.bytesReceived, bytes.length);
    }
  });

  test(`decodeStream over a ReadableStream of ${name} gives the same refinements`, async () => {
    const bytes = readData(name);
    const whole = decoder.decode(bytes);
    for (const chunk of [7, 100, bytes.length]) {
      const refinements = [];
      const progress = [];
      const { stream } = streamOf(bytes, { chunk });
      const result = await decodeStream(decoder, stream, {
        onRefine: (mesh, event) => refinements.push({ mesh, bytesReceived: event.bytesReceived }),
        onProgress: (received) => progress.push(received),
      });
      checkRefinements(bytes, chunk, refinements);
      const pushed = feed(bytes, chunk).refinements;
      assert.deepEqual(refinements.map((r) => [r.bytesReceived, r.mesh.level, r.mesh.bytesUsed]),
        pushed.map((r) => [r.bytesReceived, r.mesh.level, r.mesh.bytesUsed]), `chunks of ${chunk}`);
      assertSameDecode(result.mesh, whole, `chunks of ${chunk}: the stream's mesh`);
      assert.equal(result.error, null);
      assert.equal(result.bytesReceived, bytes.length);
      // The header of the whole file, its size included.
      assert.deepEqual(result.info, decoder.inspect(bytes));
      assert.deepEqual(progress, Array.from({ length: Math.ceil(bytes.length / chunk) },
        (_, i) => Math.min(bytes.length, (i + 1) * chunk)));
    }
  });
}

test('a stream that fails midway rejects with the last refinement as .mesh', async () => {
  const bytes = readData('spot_default.srm');
  const info = decoder.inspect(bytes);
  const cut = info.planes[4].end + 33;  // inside the coefficients
  const refinements = [];
  const { stream } = streamOf(bytes, { chunk: 100, errorAt: cut });
  const error = await decodeStream(decoder, stream, { onRefine: (mesh) => refinements.push(mesh) }).then(
    () => assert.fail('the stream failed, yet decodeStream resolved'), (e) => e);
  assert.ok(error instanceof Error);
  assert.match(error.message, /connection reset/);
  assert.equal(error.cause?.message, 'connection reset');
  assert.equal(error.bytesReceived, cut);
  assert.ok(refinements.length > 0);
  assert.equal(error.mesh, refinements.at(-1), '.mesh is the last refinement');
  // And it is the best the bytes that arrived give.
  assertSameDecode(error.mesh, decoder.decode(bytes.subarray(0, cut)), 'the failed stream\'s mesh');

  // Failing inside the header: no mesh to give.
  const early = streamOf(bytes, { chunk: 7, errorAt: info.headerBytes - 20 });
  const inHeader = await decodeStream(decoder, early.stream).then(() => null, (e) => e);
  assert.ok(inHeader instanceof Error, 'a stream failing in the header resolved');
  assert.equal(inHeader.mesh, null);
});

test('a stream that ends early resolves with the best mesh of its bytes', async () => {
  const bytes = readData('spot_default.srm');
  const info = decoder.inspect(bytes);
  const cuts = {
    'base mesh': (info.headerBytes + info.levelInfo[0].drawableFrom) >> 1,
    flags: info.levelInfo[info.levels].drawableFrom - 1,
    coefficients: info.planes[5].end + 50,
  };
  for (const [where, endAt] of Object.entries(cuts)) {
    const refinements = [];
    const { stream } = streamOf(bytes, { chunk: 100, endAt });
    const result = await decodeStream(decoder, stream, { onRefine: (mesh) => refinements.push(mesh) });
    assertSameDecode(result.mesh, decoder.decode(bytes.subarray(0, endAt)), `cut inside the ${where} (${endAt})`);
    assert.equal(result.mesh, refinements.at(-1));
    assert.equal(result.error, null);
    assert.equal(result.bytesReceived, endAt);
    assert.equal(result.info.declaredBytes, bytes.length);
  }
  // Ending inside the header: nothing to draw, the decoder's message.
  const { stream } = streamOf(bytes, { chunk: 100, endAt: info.headerBytes - 1 });
  const expected = errorOf(() => decoder.decode(bytes.subarray(0, info.headerBytes - 1)));
  await assert.rejects(decodeStream(decoder, stream), (e) => e.message === expected.message);
});

test('a file damaged in its last bit plane resolves with a mesh and .error (the fallback)', async () => {
  const bytes = readData('golden_v2.srm');
  const info = decoder.inspect(bytes);
  // The last plane's segments, one a level, from the header's table.
  const lengths = headerFields(bytes).fields.filter((f) => f.name.startsWith('segment_length'))
    .map((f) => Number(f.value));
  const last = info.planes.at(-1);
  const before = info.planes.at(-2).end;
  const segments = lengths.slice(-(info.levels + 1));
  assert.equal(segments.reduce((a, b) => a + b, 0), last.end - before);
  let start = before;
  for (const [level, length] of segments.entries()) {
    const damaged = bytes.slice();
    damaged[start + (length >> 1)] ^= 0x10;
    start += length;
    const whole = errorOf(() => decoder.decode(damaged));
    assert.ok(whole, `damage in level ${level}'s segment: the whole file still decodes`);
    for (const chunk of [1, 7, 100, bytes.length]) {
      const what = `damage in level ${level}'s segment of plane ${last.plane}, chunks of ${chunk}`;
      const refinements = [];
      const { stream } = streamOf(damaged, { chunk });
      const result = await decodeStream(decoder, stream, { onRefine: (mesh) => refinements.push(mesh) });
      assert.equal(result.error?.message, whole.message, `${what}: .error`);
      assert.equal(result.mesh, refinements.at(-1), `${what}: the last refinement`);
      // At the finest level, with at least every plane above the damaged one.
      assert.equal(result.mesh.level, info.levels, `${what}: level`);
      assert.ok(result.mesh.bytesUsed >= before, `${what}: ${result.mesh.bytesUsed} bytes used`);
      assertSameDecode(result.mesh, decoder.decode(damaged.subarray(0, result.mesh.bytesUsed)), what);
    }
  }
});

test('a stream that is not an .srm file rejects after its first 10 bytes, reading no more', { timeout: 20000 },
  async () => {
    const html = new TextEncoder().encode(
      '<!DOCTYPE html>\n<html><head><title>Not Found</title></head><body><h1>404</h1></body></html>\n'.repeat(200));
    const files = scratch();
    let native;
    try {
      native = nativeRun(files.write('page.srm', html));
    } finally {
      files.remove();
    }
    assert.equal(native.ok, false);
    for (const chunk of [1, 4]) {
      // The source sends 10 bytes, then nothing: the rejection must not wait for more.
      const { stream, stats } = streamOf(html, { chunk, stallAt: Math.ceil(10 / chunk) * chunk });
      await assert.rejects(decodeStream(decoder, stream), (e) => e.message === native.message);
      assert.equal(stats.pulled, Math.ceil(10 / chunk) * chunk, `chunks of ${chunk}: bytes read`);
      assert.ok(stats.cancelled, `chunks of ${chunk}: the stream was not cancelled`);
    }
    // The same from ProgressiveDecoder: nothing to say before 10 bytes, then the error.
    const progressive = new ProgressiveDecoder(decoder);
    for (let at = 0; at < 9; ++at) assert.equal(progressive.push(html.subarray(at, at + 1)), null);
    assert.throws(() => progressive.push(html.subarray(9, 10)), (e) => e.message === native.message);
  });

test('a header declaring a huge file (valid CRC) streams what arrives without allocating what it claims', async () => {
  const bytes = readData('golden_v2.srm');
  const field = headerFields(bytes).fields.find((f) => f.name === 'flag_length[0]');
  for (const claim of [2n ** 31n, 2n ** 40n]) {
    const hostile = withHeaderField(bytes, field, claim);
    assert.ok(decoder.inspect(hostile).declaredBytes > Number(claim));
    // The bytes end inside the "flag chunk": the decoder draws the base mesh.
    const expected = decoder.decode(hostile);
    const progressive = new ProgressiveDecoder(decoder);
    for (let at = 0; at < hostile.length; at += 100) progressive.push(hostile.subarray(at, at + 100));
    assertSameDecode(progressive.end(), expected, `a claim of ${claim} bytes`);
    assert.ok(progressive.bytes.buffer.byteLength < 1 << 20,
      `a claim of ${claim} bytes: a buffer of ${progressive.bytes.buffer.byteLength} bytes`);
    const { stream } = streamOf(hostile, { chunk: 100 });
    assertSameDecode((await decodeStream(decoder, stream)).mesh, expected, `a stream claiming ${claim} bytes`);
  }
});

// The stream layer on hostile bytes: push and end give meshes or throw the
// decoder's Errors, never one of their own (a RangeError of a buffer, a
// TypeError of a missing header).
test('seeded mutations streamed through ProgressiveDecoder: a valid mesh or the decoder\'s Error', () => {
  const bytes = readData('golden_v2.srm');
  const { fields } = headerFields(bytes);
  const random = prng(7);
  const outcomes = { meshes: 0, errors: 0 };
  for (let trial = 0; trial < 120; ++trial) {
    let mutated = bytes.slice();
    if (trial % 2) {
      const values = [0n, 1n, 2n ** 40n, BigInt(random.int(1e6))];
      mutated = withHeaderField(bytes, fields[random.int(fields.length)], values[random.int(values.length)]);
    } else {
      for (let k = 1 + random.int(8); k > 0; --k) mutated[random.int(mutated.length)] ^= 1 << random.int(8);
    }
    const progressive = new ProgressiveDecoder(decoder);
    try {
      for (let at = 0; at < mutated.length; at += 64) progressive.push(mutated.subarray(at, at + 64));
      const mesh = progressive.end();
      assert.equal(meshProblem(mesh), null, `trial ${trial}`);
      ++outcomes.meshes;
    } catch (error) {
      if (error instanceof assert.AssertionError) throw error;
      assert.ok(typeof error.code === 'string' && error.message.length > 0,
        `trial ${trial}: ${error.constructor.name}: ${error.message}`);
      ++outcomes.errors;
    }
  }
  assert.ok(outcomes.meshes > 0 && outcomes.errors > 0, JSON.stringify(outcomes));
});
