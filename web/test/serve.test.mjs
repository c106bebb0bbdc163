// web/tools/serve.mjs: MIME types and lengths, nothing outside web/ and the
// given file, the slow and breaking modes, and a clear refusal of a missing file.
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { request } from 'node:http';
import { join } from 'node:path';
import { after, before, test } from 'node:test';
import { fileURLToPath } from 'node:url';

import { startServer } from '../tools/serve.mjs';
import { repository } from '../tools/native.mjs';

const sample = join(repository, 'tests/data/spot_default.srm');
const serveScript = fileURLToPath(new URL('../tools/serve.mjs', import.meta.url));
let server;

// A GET with the path sent as written (fetch would normalise the dots away);
// resolves with the status, headers, body and the number of chunks it came in.
function get(port, path) {
  return new Promise((resolve, reject) => {
    const req = request({ host: '127.0.0.1', port, path, method: 'GET' }, (response) => {
      const parts = [];
      response.on('data', (part) => parts.push(part));
      response.on('end', () => resolve({ status: response.statusCode, headers: response.headers, body: Buffer.concat(parts), chunks: parts.length, complete: response.complete }));
      response.on('error', (error) => resolve({ status: response.statusCode, headers: response.headers, body: Buffer.concat(parts), error }));
    });
    req.on('error', reject);
    req.end();
  });
}

before(async () => {
  server = await startServer({ files: [sample] });
});

after(() => server.close());

test('types and lengths', async () => {
  for (const [path, type] of [
    ['/viewer/', 'text/html; charset=utf-8'],
    ['/viewer/viewer.js', 'text/javascript; charset=utf-8'],
    ['/viewer/viewer.css', 'text/css; charset=utf-8'],
    ['/dist/srcodec_decoder.wasm', 'application/wasm'],
    ['/file/spot_default.srm', 'application/octet-stream'],
  ]) {
    const response = await get(server.port, path);
    assert.equal(response.status, 200, path);
    assert.equal(response.headers['content-type'], type, path);
    assert.equal(Number(response.headers['content-length']), response.body.length, path);
  }
  const file = await get(server.port, '/file/spot_default.srm');
  assert.ok(file.body.equals(readFileSync(sample)));
  const root = await get(server.port, '/');
  assert.equal(root.status, 302);
  assert.equal(root.headers.location, '/viewer/?src=/file/spot_default.srm');
});

test('nothing outside web/ and the given file', async () => {
  // codec/ is a folder of the repository beside web/, not in it.
  for (const path of ['/../codec/decoder_api.cpp', '/..%2fcodec%2fdecoder_api.cpp', '/%2e%2e%2fcodec/decoder_api.cpp',
    '/../../etc/passwd', '/%2e%2e/%2e%2e/etc/passwd', '/viewer/..%2f..%2fcodec/decoder_api.cpp',
    '/file/../../codec/decoder_api.cpp', '/file/other.srm', '/%00', '/nope']) {
    const response = await get(server.port, path);
    assert.equal(response.status, 404, path);
  }
});

test('--rate sends in chunks; --drop-after breaks the body', async () => {
  const bytes = readFileSync(sample);
  const slow = await startServer({ files: [sample], rate: 20_000, chunkBytes: 256 });
  const response = await get(slow.port, '/file/spot_default.srm');
  assert.ok(response.body.equals(bytes));
  assert.ok(response.chunks >= Math.ceil(bytes.length / 256), `${response.chunks} chunks`);
  await slow.close();
  const breaking = await startServer({ files: [sample], dropAfter: 1000 });
  const broken = await get(breaking.port, '/file/spot_default.srm');
  assert.ok(broken.body.length <= 1000 && broken.complete !== true, 'the body stops short');
  await breaking.close();
});

test('a missing file: a clear message and a non-zero exit', () => {
  const run = spawnSync(process.execPath, [serveScript, join(repository, 'no/such.srm'), '--port', '0'], { encoding: 'utf8' });
  assert.notEqual(run.status, 0);
  assert.match(run.stderr, /no such file/);
  const usage = spawnSync(process.execPath, [serveScript], { encoding: 'utf8' });
  assert.notEqual(usage.status, 0);
  assert.match(usage.stderr, /usage/);
});
