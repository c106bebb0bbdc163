// Makes the files that decode_bench.mjs decodes, with the native srcodec
// binary, into a cache folder kept outside the repository (encoding a mesh
// takes from seconds to a minute, and the files do not change between runs):
//
//   node web/bench/prepare.mjs --cache DIR MESH...
//
// For each mesh, in DIR/<mesh file name>/:
//   srcodec.srm  `srcodec encode MESH` with no rate option: the default file
//                (the knee of the stream's rate-distortion curve);
//   draco.drc    `srcodec draco MESH --cl 10` at the quantization whose PSNR
//                is nearest the srcodec file's (each side of it is tried);
// and their PSNRs against the input, both from `srcodec compare` with the
// same samples and seed, so the two figures are measured the same way.
// DIR/manifest.json lists them; a mesh whose input bytes have not changed
// (sha256) is not encoded again.
//
// SRCODEC_BIN names the native binary (default: build/tools/srcodec of this
// checkout).
import { execFileSync } from 'node:child_process';
import { createHash } from 'node:crypto';
import { existsSync, mkdirSync, readFileSync, renameSync, statSync, writeFileSync } from 'node:fs';
import { basename, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const repository = fileURLToPath(new URL('../../', import.meta.url));
const binary = process.env.SRCODEC_BIN ?? join(repository, 'build/tools/srcodec');

function usage(message) {
  if (message) console.error(`prepare.mjs: ${message}`);
  console.error('usage: node web/bench/prepare.mjs --cache DIR MESH...');
  process.exit(2);
}

function parseArguments(argv) {
  let cache = null;
  const meshes = [];
  for (let i = 0; i < argv.length; ++i) {
    if (argv[i] === '--cache') cache = argv[++i];
    else if (argv[i].startsWith('--')) usage(`unknown option ${argv[i]}`);
    else meshes.push(resolve(argv[i]));
  }
  if (!cache) usage('--cache DIR is required');
  if (meshes.length === 0) usage('no meshes');
  return { cache: resolve(cache), meshes };
}

// `srcodec ARGS`'s standard output; exits with srcodec's last message when it fails.
function srcodec(args) {
  try {
    return execFileSync(binary, args, { encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'], maxBuffer: 1 << 26 });
  } catch (error) {
    const last = String(error.stderr ?? '').trim().split('\n').pop() || error.message;
    console.error(`prepare.mjs: srcodec ${args.join(' ')}: ${last}`);
    process.exit(1);
  }
}

const srcodecJson = (args) => JSON.parse(srcodec([...args, '--json']));
const psnrOf = (mesh, decoded) => srcodecJson(['compare', mesh, decoded]).psnr;

function sha256(path) {
  return createHash('sha256').update(readFileSync(path)).digest('hex');
}

function log(text) {
  process.stderr.write(`prepare.mjs: ${text}\n`);
}

// Draco's round trip at `qp` bits, written to dir/draco_qpN.{drc,obj}: its bytes and PSNR.
function dracoPoint(mesh, dir, qp) {
  const drc = join(dir, `draco_qp${qp}.drc`);
  const decoded = join(dir, `draco_qp${qp}.obj`);
  srcodecJson(['draco', mesh, '--qp', String(qp), '--cl', '10', '-o', drc, '--decoded', decoded]);
  return { qp, bytes: statSync(drc).size, psnr: psnrOf(mesh, decoded), file: drc };
}

// The Draco quantization whose PSNR is nearest `target`. PSNR rises with qp
// (about 6 dB a bit), so this walks from qp 11 (a common default) towards the
// target until the two qps either side of it are known, then keeps the nearer.
function nearestDraco(mesh, dir, target) {
  const tried = new Map();
  const at = (qp) => {
    if (!tried.has(qp)) {
      const point = dracoPoint(mesh, dir, qp);
      log(`  draco qp ${qp}: ${point.bytes} B, ${point.psnr.toFixed(2)} dB`);
      tried.set(qp, point);
    }
    return tried.get(qp);
  };
  let qp = 11;
  const step = at(qp).psnr < target ? 1 : -1;
  while (qp + step >= 1 && qp + step <= 30) {
    const next = at(qp + step);
    if ((step > 0) === (next.psnr >= target)) break;
    qp += step;
  }
  const candidates = [...tried.values()];
  candidates.sort((a, b) => Math.abs(a.psnr - target) - Math.abs(b.psnr - target));
  return { chosen: candidates[0], tried: [...tried.values()].sort((a, b) => a.qp - b.qp) };
}

function prepareMesh(mesh, cache, previous) {
  const key = basename(mesh);
  const dir = join(cache, key);
  const inputSha256 = sha256(mesh);
  if (previous && previous.inputSha256 === inputSha256 && existsSync(previous.srcodec.file) &&
      existsSync(previous.draco.file)) {
    log(`${key}: cached`);
    return { ...previous, input: mesh };
  }
  mkdirSync(dir, { recursive: true });
  log(`${key}: srcodec encode (the default rate)`);
  const srm = join(dir, 'srcodec.srm');
  const encoded = srcodecJson(['encode', mesh, '-o', srm, '--quiet']);
  const srmObj = join(dir, 'srcodec.obj');
  srcodec(['decode', srm, '-o', srmObj]);
  const srcodecPsnr = psnrOf(mesh, srmObj);
  log(`  srcodec: ${statSync(srm).size} B, ${srcodecPsnr.toFixed(2)} dB (the encoder's estimate ${encoded.psnr.toFixed(2)})`);
  const { chosen, tried } = nearestDraco(mesh, dir, srcodecPsnr);
  const info = srcodecJson(['info', mesh]);
  return {
    input: mesh, inputSha256,
    inputVertices: info.vertices, inputTriangles: info.triangles ?? info.faces,
    srcodec: { file: srm, bytes: statSync(srm).size, psnr: srcodecPsnr, rate: encoded.rate },
    draco: { file: chosen.file, bytes: chosen.bytes, psnr: chosen.psnr, qp: chosen.qp, compressionLevel: 10 },
    dracoTried: tried.map(({ qp, bytes, psnr }) => ({ qp, bytes, psnr })),
    psnrRule: 'srcodec default file; Draco -cl 10 at the qp whose PSNR is nearest',
  };
}

const { cache, meshes } = parseArguments(process.argv.slice(2));
if (!existsSync(binary)) usage(`${binary} is missing: build the native srcodec, or set SRCODEC_BIN`);
mkdirSync(cache, { recursive: true });
const manifestPath = join(cache, 'manifest.json');
const manifest = existsSync(manifestPath) ? JSON.parse(readFileSync(manifestPath, 'utf8')) : { meshes: {} };
for (const mesh of meshes) {
  const key = basename(mesh);
  manifest.meshes[key] = prepareMesh(mesh, cache, manifest.meshes[key]);
  // Written after each mesh, so that an interrupted run keeps what it made.
  writeFileSync(`${manifestPath}.new`, `${JSON.stringify(manifest, null, 2)}\n`);
  renameSync(`${manifestPath}.new`, manifestPath);
}
for (const key of meshes.map((m) => basename(m))) {
  const m = manifest.meshes[key];
  const above = m.srcodec.psnr >= m.draco.psnr ? 'srcodec' : 'Draco';
  console.log(`${key}: srcodec ${m.srcodec.bytes} B ${m.srcodec.psnr.toFixed(2)} dB, Draco qp ${m.draco.qp} ` +
    `${m.draco.bytes} B ${m.draco.psnr.toFixed(2)} dB (${above} above)`);
}
