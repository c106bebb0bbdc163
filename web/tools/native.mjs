// The C++ decoder's answers, for the tests to compare the WebAssembly
// decoder with: `srcodec decode` of the native build, written as OBJ (which
// keeps every bit of each double).
import { execFileSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';

export const repository = fileURLToPath(new URL('../../', import.meta.url));

export function srcodecBinary() {
  const binary = process.env.SRCODEC_BIN ?? join(repository, 'build/tools/srcodec');
  if (!existsSync(binary)) {
    throw new Error(`${binary} is missing: build the native srcodec first (bash tools/setup.sh), or set SRCODEC_BIN`);
  }
  return binary;
}

// Positions (doubles) and indices of `srcodec decode FILE --level L --bytes N`;
// throws with the command's message when it refuses the bytes.
export function nativeDecode(srmPath, { level = -1, bytes = 0 } = {}) {
  const dir = mkdtempSync(join(tmpdir(), 'srcodec-native-'));
  try {
    const out = join(dir, 'mesh.obj');
    const args = ['decode', srmPath, '-o', out, '--single-thread'];
    if (level >= 0) args.push('--level', String(level));
    if (bytes > 0) args.push('--bytes', String(bytes));
    execFileSync(srcodecBinary(), args, { stdio: ['ignore', 'ignore', 'pipe'] });
    return parseObj(readFileSync(out, 'utf8'));
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
}

// The vertices and triangles of an OBJ that `srcodec decode` wrote, and its
// normals (`vn`) and each corner's normal (`f v//vn`), empty when it has none.
export function parseObj(text) {
  const positions = [];
  const indices = [];
  const normals = [];
  const normalIndices = [];
  for (const line of text.split('\n')) {
    if (line.startsWith('v ') || line.startsWith('vn ')) {
      const [, x, y, z] = line.trim().split(/\s+/);
      (line[1] === 'n' ? normals : positions).push(Number(x), Number(y), Number(z));
    } else if (line.startsWith('f ')) {
      for (const corner of line.trim().split(/\s+/).slice(1)) {
        const [v, , n] = corner.split('/');
        indices.push(Number(v) - 1);
        if (n !== undefined) normalIndices.push(Number(n) - 1);
      }
    }
  }
  return {
    positions: Float64Array.from(positions), indices: Uint32Array.from(indices),
    normals: Float64Array.from(normals), normalIndices: Uint32Array.from(normalIndices),
  };
}
