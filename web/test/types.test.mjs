// The TypeScript declarations (dist/*.d.ts) compile with --strict against a
// use of every part of the API as README.md shows it, and refuse misuse.
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { test } from 'node:test';
import { fileURLToPath } from 'node:url';

const web = fileURLToPath(new URL('../', import.meta.url));
const tsc = join(web, 'node_modules/typescript/bin/tsc');

function compile(file) {
  const dir = mkdtempSync(join(tmpdir(), 'srcodec-types-'));
  try {
    const config = join(dir, 'tsconfig.json');
    writeFileSync(config, JSON.stringify({
      extends: join(web, 'test/types/tsconfig.json'),
      files: [join(web, 'test/types', file)],
    }));
    const run = spawnSync(process.execPath, [tsc, '-p', config], { cwd: web, encoding: 'utf8' });
    return { status: run.status, output: run.stdout + run.stderr };
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
}

test('the declarations compile against the documented use', () => {
  const { status, output } = compile('usage.ts');
  assert.equal(status, 0, output);
});

test('the declarations refuse misuse, line by line', () => {
  const { status, output } = compile('misuse.ts');
  assert.notEqual(status, 0);
  for (const line of [7, 8, 9]) assert.match(output, new RegExp(`misuse\\.ts\\(${line},`), output);
});
