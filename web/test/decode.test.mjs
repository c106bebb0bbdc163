// The WebAssembly decoder against the C++ one (the native `srcodec` CLI):
// positions are the C++ doubles rounded to float32 (Math.fround), bit for
// bit; indices, level, bytes used, last complete plane and base cut are
// identical; where C++ refuses the bytes, the WebAssembly decoder throws the
// same message. Also `inspect` against `srcodec info --json`.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { test } from 'node:test';

import { BufferAttribute, BufferGeometry } from 'three';

import { createDecoder } from '../dist/index.js';
import { SRMLoader } from '../dist/SRMLoader.js';
import { assertSameDecode, assertSameMesh, dataPath, nativeInfo, nativeRun, readData, scratch } from './helpers.mjs';
import { parseObj } from '../tools/native.mjs';

const decoder = await createDecoder();

function tryDecode(bytes, options) {
  try {
    return { mesh: decoder.decode(bytes, options) };
  } catch (error) {
    return { error };
  }
}

// Decodes `bytes` (the file at `path`) at `level` from its first `prefix`
// bytes (0: all) both ways and compares. Returns the WebAssembly mesh, or
// null when both refused.
function compareWithNative(path, bytes, { level = -1, prefix = 0 } = {}) {
  const what = `${path} level ${level}${prefix ? `, first ${prefix} bytes` : ''}`;
  const native = nativeRun(path, { level, bytes: prefix });
  const viaOption = tryDecode(bytes, { level, maxBytes: prefix, cornerNormals: true });
  // A prefix handed over as shorter bytes decodes as the maxBytes option does.
  const viaCut = prefix ? tryDecode(bytes.subarray(0, prefix), { level }) : viaOption;
  if (!native.ok) {
    assert.ok(viaOption.error, `${what}: C++ refused (${native.message}) but WebAssembly gave a mesh`);
    assert.equal(viaOption.error.message, native.message, `${what}: the refusal's message`);
    assert.ok(viaCut.error, `${what}: the cut bytes gave a mesh`);
    assert.equal(viaCut.error.message, native.message, `${what}: the cut bytes' refusal`);
    return null;
  }
  for (const { error } of [viaOption, viaCut]) {
    if (error) assert.fail(`${what}: C++ decoded it, WebAssembly threw "${error.message}"`);
  }
  const mesh = viaOption.mesh;
  assertSameMesh(mesh, native, what);
  const r = native.report;
  assert.equal(mesh.level, r.level, `${what}: level`);
  assert.equal(mesh.vertexCount, r.vertices, `${what}: vertices`);
  assert.equal(mesh.triangleCount, r.triangles, `${what}: triangles`);
  assert.equal(mesh.bytesUsed, r.bytes_used, `${what}: bytesUsed`);
  assert.equal(mesh.lastCompletePlane, r.last_complete_plane, `${what}: lastCompletePlane`);
  assert.equal(mesh.baseCut, r.base_cut, `${what}: baseCut`);
  assert.equal(mesh.creasesCut, r.creases_cut, `${what}: creasesCut`);
  assert.equal(mesh.creaseEdges.length, 2 * r.crease_edges, `${what}: creaseEdges`);
  assertSameCornerNormals(mesh.cornerNormals, native, what);
  assertSameDecode(viaCut.mesh, mesh, `${what}, as cut bytes`);
  return mesh;
}

// The corner normals are those the native OBJ has (a file with creases), or
// there are none on either side. The normals agree to 1e-6: where a
// component is near zero, the native build's and the WebAssembly build's
// last bits differ (by up to 3e-15 on cube_creases_v3.srm).
function assertSameCornerNormals(split, native, what) {
  if (native.normals.length === 0) {
    assert.equal(split, null, `${what}: corner normals where C++ wrote none`);
    return;
  }
  assert.ok(split !== null, `${what}: no corner normals where C++ wrote them`);
  assert.deepEqual(split.corners, native.normalIndices, `${what}: corners' normals`);
  assert.equal(split.normals.length, native.normals.length, `${what}: normals`);
  for (let i = 0; i < split.normals.length; ++i) {
    const off = Math.abs(split.normals[i] - native.normals[i]);
    if (!(off <= 1e-6)) assert.fail(`${what}: normal ${Math.floor(i / 3)} is ${off} from the native one`);
  }
  for (let i = 0; i < split.corners.length; ++i) {
    assert.equal(split.vertices[split.corners[i]], native.indices[i], `${what}: corner ${i}'s normal's vertex`);
  }
}

for (const version of [1, 2]) {
  test(`golden_v${version}.srm decodes as C++ decodes it at every level`, () => {
    const path = dataPath(`golden_v${version}.srm`);
    const bytes = readData(`golden_v${version}.srm`);
    const { levels } = decoder.inspect(bytes);
    for (let level = -1; level <= levels; ++level) compareWithNative(path, bytes, { level });
    // A level above the file's finest: both refuse it alike.
    compareWithNative(path, bytes, { level: levels + 1 });
  });

  // The committed OBJs pin the format; the C++ golden test (tests/codec/
  // golden_test.cpp) holds the decoder to them within 1e-6 per vertex, since
  // they are allowed to differ from today's doubles in their last digits.
  test(`golden_v${version}.srm matches its committed OBJs at every level`, () => {
    const bytes = readData(`golden_v${version}.srm`);
    for (let level = 0; level <= 2; ++level) {
      const pinned = parseObj(readFileSync(dataPath(`golden_v${version}_l${level}.obj`), 'utf8'));
      const mesh = decoder.decode(bytes, { level });
      assert.equal(mesh.level, level);
      assert.deepEqual(mesh.indices, pinned.indices, `level ${level}: indices`);
      assert.equal(mesh.positions.length, pinned.positions.length, `level ${level}: vertex count`);
      // 1e-6, plus float32's rounding of coordinates below 2 (under 1.2e-7 a coordinate).
      const tolerance = 1e-6 + Math.sqrt(3) * 2 ** -23;
      let worst = 0;
      for (let v = 0; v < pinned.positions.length; v += 3) {
        const dx = mesh.positions[v] - pinned.positions[v];
        const dy = mesh.positions[v + 1] - pinned.positions[v + 1];
        const dz = mesh.positions[v + 2] - pinned.positions[v + 2];
        worst = Math.max(worst, Math.hypot(dx, dy, dz));
      }
      assert.ok(worst < tolerance, `level ${level}: a vertex ${worst} from its pinned position`);
    }
  });
}

for (const name of ['spot_default', 'bunny_npm_default', 'creases_v3', 'cube_creases_v3']) {
  test(`the bundled sample ${name}.srm decodes as C++ decodes it at every level`, () => {
    const path = dataPath(`${name}.srm`);
    const bytes = readData(`${name}.srm`);
    const { levels } = decoder.inspect(bytes);
    for (let level = -1; level <= levels; ++level) compareWithNative(path, bytes, { level });
  });
}

// Twenty prefix lengths over the whole file: the landmarks where what the
// bytes hold changes (inside the 10 fixed bytes, the header, the base mesh,
// the flags, each side of a plane's end) and even steps between them.
function prefixLengths(info) {
  const n = info.fileBytes;
  const header = info.headerBytes;
  const base = info.levelInfo[0].drawableFrom;
  const finest = info.levelInfo[info.levels].drawableFrom;
  const planeEnd = info.planes[Math.floor(info.planes.length / 3)].end;
  const landmarks = [5, 10, header >> 1, header - 1, header, header + 1, (header + base) >> 1, base - 1, base,
    (base + finest) >> 1, finest, planeEnd - 1, planeEnd, n - 1];
  const wanted = new Set(landmarks.filter((p) => p > 0 && p < n));
  for (let k = 0; k < 20 && wanted.size < 20; ++k) wanted.add(Math.round((n * (k + 0.5)) / 20));
  return [...wanted].sort((a, b) => a - b);
}

test('20 prefixes of spot_default.srm decode as C++ decodes them, and refuse as it does', () => {
  const path = dataPath('spot_default.srm');
  const bytes = readData('spot_default.srm');
  const info = decoder.inspect(bytes);
  const lengths = prefixLengths(info);
  assert.equal(lengths.length, 20);
  const regions = { header: 0, base: 0, flags: 0, coefficients: 0 };
  for (const prefix of lengths) {
    const mesh = compareWithNative(path, bytes, { prefix });
    // Also one coarser level: a prefix serves every level up to what it holds.
    compareWithNative(path, bytes, { prefix, level: 1 });
    if (prefix < info.headerBytes) {
      ++regions.header;
      assert.equal(mesh, null, `${prefix} bytes (inside the header) gave a mesh`);
    } else if (prefix < info.levelInfo[0].drawableFrom) {
      ++regions.base;
      assert.ok(mesh.baseCut, `${prefix} bytes (inside the base mesh): not a base cut`);
    } else if (prefix < info.levelInfo[info.levels].drawableFrom) {
      ++regions.flags;
      assert.ok(mesh.level < info.levels, `${prefix} bytes (inside the flags): level ${mesh.level}`);
    } else {
      ++regions.coefficients;
    }
  }
  for (const [region, count] of Object.entries(regions)) assert.ok(count > 0, `no prefix ends inside the ${region}`);
});

// `srcodec info --json`'s names for FileInfo's fields.
function assertSameInfo(info, native, what) {
  const same = [['version', 'version'], ['rawPlanes', 'raw_planes'], ['fileBytes', 'file_bytes'],
    ['declaredBytes', 'declared_bytes'], ['headerBytes', 'header_bytes'], ['baseBytes', 'base_mesh_bytes'],
    ['creaseBytes', 'crease_bytes'], ['creaseEdges', 'crease_edges'],
    ['inputVertices', 'input_vertices'], ['inputTriangles', 'input_triangles'], ['baseVertices', 'base_vertices'],
    ['baseTriangles', 'base_triangles'], ['baseBits', 'base_bits'], ['topPlane', 'top_plane']];
  for (const [ours, theirs] of same) assert.equal(info[ours], native[theirs], `${what}: ${ours}`);
  // The CLI prints these with 10 significant digits.
  assert.ok(Math.abs(info.bitsPerVertex - native.bpv) <= 1e-9 * native.bpv, `${what}: bitsPerVertex`);
  assert.ok(Math.abs(info.quantizerStep - native.quantizer_step) <= 1e-9 * native.quantizer_step,
    `${what}: quantizerStep`);
  assert.equal(info.levels, native.levels.length - 1, `${what}: levels`);
  assert.deepEqual(info.levelInfo, native.levels.map((l) => ({
    vertices: l.vertices, flagBytes: l.flag_bytes, coefficientBytes: l.coefficient_bytes, drawableFrom: l.drawable_from,
  })), `${what}: levels`);
  assert.deepEqual(info.planes, native.planes.map((p) => ({ plane: p.plane, bytes: p.bytes, end: p.end })),
    `${what}: planes`);
}

test('inspect agrees with srcodec info --json, for whole files and prefixes', () => {
  const files = scratch();
  try {
    for (const name of ['golden_v1', 'golden_v2', 'spot_default', 'bunny_npm_default', 'creases_v3']) {
      const bytes = readData(`${name}.srm`);
      assertSameInfo(decoder.inspect(bytes), nativeInfo(dataPath(`${name}.srm`)), name);
      const info = decoder.inspect(bytes);
      // A prefix: the bytes present and the bytes the table declares differ.
      for (const prefix of [info.headerBytes, info.levelInfo[0].drawableFrom + 1, bytes.length >> 1]) {
        const path = files.write(`${name}_${prefix}.srm`, bytes.subarray(0, prefix));
        const cut = decoder.inspect(bytes.subarray(0, prefix));
        assertSameInfo(cut, nativeInfo(path), `${name}, first ${prefix} bytes`);
        assert.equal(cut.fileBytes, prefix);
        assert.equal(cut.declaredBytes, bytes.length);
      }
      // Inside the header neither reads it, with the same message.
      const inside = files.write(`${name}_header.srm`, bytes.subarray(0, info.headerBytes - 1));
      const native = nativeRun(inside);
      assert.equal(native.ok, false);
      assert.throws(() => decoder.inspect(bytes.subarray(0, info.headerBytes - 1)),
        (e) => e.message === native.message && e.code === 'parse_error');
    }
  } finally {
    files.remove();
  }
});

// tests/data/creases_v3.srm: a sphere with creases on 10 of its 30 base
// edges. Every level has its own crease edges, edges of its mesh that chain
// up into the base's; every prefix decodes as C++ decodes it, and one that
// ends inside the creases gives the base mesh without them.
test('creases_v3.srm: the crease edges at every level and the prefixes around them', () => {
  const path = dataPath('creases_v3.srm');
  const bytes = readData('creases_v3.srm');
  const info = decoder.inspect(bytes);
  assert.equal(info.version, 3);
  assert.equal(info.creaseEdges, 10);
  const atLevel = [];
  for (let level = 0; level <= info.levels; ++level) {
    const mesh = compareWithNative(path, bytes, { level });
    const edges = new Set();
    for (let i = 0; i < mesh.indices.length; i += 3) {
      for (let k = 0; k < 3; ++k) {
        const a = mesh.indices[i + k];
        const b = mesh.indices[i + ((k + 1) % 3)];
        edges.add(`${Math.min(a, b)} ${Math.max(a, b)}`);
      }
    }
    const crease = mesh.creaseEdges;
    for (let k = 0; k < crease.length; k += 2) {
      assert.ok(crease[k] < crease[k + 1], `level ${level}: edge ${k / 2} is not (smaller, larger)`);
      assert.ok(edges.has(`${crease[k]} ${crease[k + 1]}`), `level ${level}: edge ${k / 2} is not an edge of the mesh`);
    }
    assert.ok(crease.length >= (level === 0 ? 20 : atLevel[level - 1].length + 2), `level ${level}: ${crease.length}`);
    atLevel.push(crease);
  }
  assert.equal(atLevel[0].length, 20);
  assert.deepEqual(decoder.decode(bytes).creaseEdges, atLevel.at(-1));
  const creasesEnd = info.levelInfo[1].drawableFrom - info.levelInfo[1].flagBytes;
  const creasesBegin = creasesEnd - info.creaseBytes;
  for (let prefix = info.headerBytes; prefix <= creasesEnd + 1; ++prefix) {
    const mesh = compareWithNative(path, bytes, { prefix });
    const inside = prefix >= creasesBegin && prefix < creasesEnd;
    assert.equal(mesh.creasesCut, inside, `${prefix} bytes: creasesCut`);
    assert.deepEqual(mesh.creaseEdges, prefix >= creasesEnd ? atLevel[mesh.level] : new Uint32Array(0),
      `${prefix} bytes: creaseEdges`);
    if (inside) assert.equal(mesh.triangleCount, info.baseTriangles, `${prefix} bytes: the base mesh`);
  }
  assert.equal(decoder.inspect(bytes.subarray(0, creasesEnd - 1)).creaseEdges, null);
});

// The normals of a mesh, split at its crease edges, computed here in plain
// JavaScript as the rule says, for each corner: two triangles at a vertex are
// in one sector when they share an edge from it that is not a crease; a
// sector's normal is its triangles' area-weighted normal.
function referenceCornerNormals({ positions, indices, creaseEdges }) {
  const crease = new Set();
  for (let k = 0; k < creaseEdges.length; k += 2) crease.add(`${creaseEdges[k]} ${creaseEdges[k + 1]}`);
  const parent = Int32Array.from(indices, (_, i) => i);
  const find = (c) => {
    while (parent[c] !== c) c = parent[c] = parent[parent[c]];
    return c;
  };
  const cornersAt = new Map();  // "v w": the corners at v whose triangle has the edge (v, w)
  for (let c = 0; c < indices.length; ++c) {
    const t = c - (c % 3);
    const v = indices[c];
    for (const w of [indices[t + ((c + 1) % 3)], indices[t + ((c + 2) % 3)]]) {
      if (crease.has(`${Math.min(v, w)} ${Math.max(v, w)}`)) continue;
      const key = `${v} ${w}`;
      if (cornersAt.has(key)) parent[find(c)] = find(cornersAt.get(key));
      else cornersAt.set(key, c);
    }
  }
  const sums = new Float64Array(3 * indices.length);
  const face = (t) => {
    const [a, b, c] = [0, 1, 2].map((k) => Array.from(positions.subarray(3 * indices[t + k], 3 * indices[t + k] + 3)));
    const u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    const v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    return [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
  };
  for (let t = 0; t < indices.length; t += 3) {
    const n = face(t);
    for (let k = 0; k < 3; ++k) for (let j = 0; j < 3; ++j) sums[3 * find(t + k) + j] += n[j];
  }
  const out = new Float64Array(3 * indices.length);
  for (let c = 0; c < indices.length; ++c) {
    const r = 3 * find(c);
    const length = Math.hypot(sums[r], sums[r + 1], sums[r + 2]);
    for (let j = 0; j < 3; ++j) out[3 * c + j] = sums[r + j] / length;
  }
  return out;
}

// tests/data/cube_creases_v3.srm, a cube creased at its 12 edges (tools/
// make_golden.sh cube), decodes with flat faces: every normal is a face
// normal of the cube, and so is each corner's triangle's, at the creases
// too, but for two slivers folded over at a corner; the normals are the
// rule's.
test('cube_creases_v3.srm: corner normals split at the creases are the faces\' normals', () => {
  const bytes = readData('cube_creases_v3.srm');
  const mesh = decoder.decode(bytes, { cornerNormals: true });
  assert.equal(decoder.decode(bytes).cornerNormals, null, 'not asked for');
  const { normals, vertices, corners } = mesh.cornerNormals;
  assert.equal(corners.length, mesh.indices.length);
  assert.equal(normals.length, 3 * vertices.length);
  assert.ok(vertices.length > mesh.vertexCount, `${vertices.length} normals for ${mesh.vertexCount} vertices`);
  const reference = referenceCornerNormals(mesh);
  const close = Math.cos((0.5 * Math.PI) / 180);  // half a degree
  for (let i = 0; i < normals.length; i += 3) {
    const axis = Math.max(...normals.subarray(i, i + 3).map(Math.abs));
    assert.ok(axis > close, `normal ${i / 3} is not a cube face's: ${normals.subarray(i, i + 3)}`);
  }
  let worstRule = 0;
  let offFace = 0;
  let smoothAtCreases = 1;
  const onCrease = new Set(mesh.creaseEdges);
  const smooth = new Float64Array(3 * mesh.vertexCount);
  for (let c = 0; c < corners.length; c += 3) {
    const p = [0, 1, 2].map((k) => mesh.positions.subarray(3 * mesh.indices[c + k], 3 * mesh.indices[c + k] + 3));
    const u = [0, 1, 2].map((j) => p[1][j] - p[0][j]);
    const v = [0, 1, 2].map((j) => p[2][j] - p[0][j]);
    const f = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
    const length = Math.hypot(...f);
    for (let k = 0; k < 3; ++k) {
      const n = normals.subarray(3 * corners[c + k], 3 * corners[c + k] + 3);
      for (let j = 0; j < 3; ++j) {
        worstRule = Math.max(worstRule, Math.abs(n[j] - reference[3 * (c + k) + j]));
        smooth[3 * mesh.indices[c + k] + j] += f[j];
      }
      if ((n[0] * f[0] + n[1] * f[1] + n[2] * f[2]) / length < close) ++offFace;
    }
  }
  // The smooth normals (computeVertexNormals') are far from the faces' at the creases.
  for (let c = 0; c < corners.length; ++c) {
    const v = mesh.indices[c];
    if (!onCrease.has(v)) continue;
    const s = smooth.subarray(3 * v, 3 * v + 3);
    const n = normals.subarray(3 * corners[c], 3 * corners[c] + 3);
    smoothAtCreases = Math.min(smoothAtCreases, (s[0] * n[0] + s[1] * n[1] + s[2] * n[2]) / Math.hypot(...s));
  }
  assert.ok(worstRule < 1e-6, `a normal ${worstRule} from the rule's`);
  assert.ok(offFace <= 6, `${offFace} corners' normals are off their triangle's`);
  const degrees = (Math.acos(smoothAtCreases) * 180) / Math.PI;
  assert.ok(degrees > 30, `smooth normals at the creases only ${degrees} degrees off`);
});

// SRMLoader's geometry: for a file with creases, a vertex per corner normal
// (meshGeometry); for one without, the mesh's vertices and indices with
// computeVertexNormals.
test('SRMLoader splits the normals at the creases, and only there', async () => {
  const parse = (loader, bytes) => new Promise((resolve, reject) => loader.parse(bytes, resolve, reject));
  const loader = new SRMLoader().setDecoder(decoder);
  const cube = readData('cube_creases_v3.srm');
  const geometry = await parse(loader, cube);
  const mesh = decoder.decode(cube, { cornerNormals: true });
  const { normals, vertices, corners } = mesh.cornerNormals;
  assert.equal(geometry.getAttribute('position').count, vertices.length);
  assert.deepEqual(geometry.getAttribute('normal').array, normals);
  assert.deepEqual(geometry.getIndex().array, corners);
  assert.deepEqual(geometry.userData.srcodec.meshVertices, vertices);
  const positions = geometry.getAttribute('position').array;
  for (let i = 0; i < vertices.length; ++i) {
    for (let j = 0; j < 3; ++j) assert.equal(positions[3 * i + j], mesh.positions[3 * vertices[i] + j]);
  }
  for (const name of ['spot_default', 'creases_v3']) {
    const bytes = readData(`${name}.srm`);
    const plain = decoder.decode(bytes);
    const shaded = await parse(new SRMLoader().setDecoder(decoder), bytes);
    if (name === 'spot_default') {
      assert.equal(decoder.decode(bytes, { cornerNormals: true }).cornerNormals, null, 'no creases: no split');
      assert.equal(shaded.userData.srcodec.meshVertices, null);
      assert.deepEqual(shaded.getAttribute('position').array, plain.positions);
      assert.deepEqual(shaded.getIndex().array, plain.indices);
      const expected = new BufferGeometry();
      expected.setAttribute('position', new BufferAttribute(plain.positions, 3));
      expected.setIndex(new BufferAttribute(plain.indices, 1));
      expected.computeVertexNormals();
      assert.deepEqual(shaded.getAttribute('normal').array, expected.getAttribute('normal').array);
    } else {
      assert.ok(shaded.getAttribute('position').count > plain.vertexCount, `${name}: split`);
    }
  }
  const unlit = new SRMLoader().setDecoder(decoder);
  unlit.computeNormals = false;
  const bare = await parse(unlit, cube);
  assert.equal(bare.getAttribute('normal'), undefined);
  assert.deepEqual(bare.getIndex().array, mesh.indices);
});
