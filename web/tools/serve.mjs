// A small static server for the viewer: web/ as the root, plus the .srm
// files it is given under /file/NAME. Node's standard library only.
//
//   node web/tools/serve.mjs FILE.srm [--port N] [--rate BYTES_PER_SECOND] [--chunk BYTES] [--drop-after BYTES]
//
// --rate sends the .srm files slowly, in chunks, to watch them refine;
// --drop-after breaks the connection after that many bytes of an .srm file
// (what a viewer must survive). Everything else is sent at full speed.
import { createReadStream, existsSync, realpathSync, statSync } from 'node:fs';
import { createServer } from 'node:http';
import { basename, extname, join, relative, resolve, sep } from 'node:path';
import { fileURLToPath } from 'node:url';

export const webRoot = fileURLToPath(new URL('../', import.meta.url));

const MIME = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.mjs': 'text/javascript; charset=utf-8',
  '.css': 'text/css; charset=utf-8',
  '.json': 'application/json; charset=utf-8',
  '.map': 'application/json; charset=utf-8',
  '.wasm': 'application/wasm',
  '.png': 'image/png',
  '.svg': 'image/svg+xml',
  '.txt': 'text/plain; charset=utf-8',
  '.md': 'text/plain; charset=utf-8',
  '.ts': 'text/plain; charset=utf-8',
  '.srm': 'application/octet-stream',
};

// The file under `root` that a URL path names, or null: decoded, normalised
// and resolved through symbolic links, so that nothing outside root is served.
function fileInRoot(root, urlPath) {
  let path;
  try {
    path = decodeURIComponent(urlPath);
  } catch {
    return null;
  }
  if (path.includes('\0')) return null;
  let full = resolve(root, '.' + path);
  try {
    if (statSync(full).isDirectory()) full = join(full, 'index.html');
    full = realpathSync(full);
    if (!statSync(full).isFile()) return null;
  } catch {
    return null;
  }
  const inside = relative(root, full);
  if (inside === '' || inside.startsWith('..' + sep) || inside === '..' || resolve(root, inside) !== full) return null;
  return full;
}

// Sends `size` bytes of a file: at once, or `chunkBytes` at a time at `rate`
// bytes per second; with dropAfter, destroys the socket after that many.
function sendFile(request, response, path, size, { rate = 0, chunkBytes = 0, dropAfter = 0 } = {}) {
  if (request.method === 'HEAD') {
    response.end();
    return;
  }
  if (!(rate > 0) && !(dropAfter > 0)) {
    createReadStream(path).on('error', () => response.destroy()).pipe(response);
    return;
  }
  // Slow or breaking: the .srm files are small enough to hold in memory.
  const stream = createReadStream(path);
  const parts = [];
  stream.on('data', (part) => parts.push(part));
  stream.on('error', () => response.destroy());
  stream.on('end', () => {
    const bytes = Buffer.concat(parts);
    const chunk = chunkBytes > 0 ? chunkBytes : rate > 0 ? Math.max(1, Math.round(rate / 20)) : 1024;
    const delay = rate > 0 ? (1000 * chunk) / rate : 0;
    let sent = 0;
    const next = () => {
      if (response.destroyed) return;
      if (dropAfter > 0 && sent >= dropAfter) {
        // Without flushing the promised Content-Length: the browser sees a broken body.
        response.socket?.destroy();
        return;
      }
      const end = Math.min(bytes.length, sent + chunk, dropAfter > 0 ? dropAfter : Infinity);
      response.write(bytes.subarray(sent, end));
      sent = end;
      if (sent >= bytes.length) {
        response.end();
        return;
      }
      setTimeout(next, delay);
    };
    next();
  });
  request.on('close', () => stream.destroy());
}

// Starts the server. files: the .srm files to serve under /file/NAME; slow:
// { rate, chunkBytes, dropAfter } for them. Resolves with
// { server, port, fileUrls: { NAME: '/file/NAME' }, close() }.
export function startServer({ files = [], port = 0, host = '127.0.0.1', root = webRoot, ...slow } = {}) {
  const realRoot = realpathSync(root);
  const served = new Map();
  for (const file of files) {
    const path = resolve(file);
    if (!existsSync(path) || !statSync(path).isFile()) throw new Error(`${file}: no such file`);
    served.set(`/file/${encodeURIComponent(basename(path))}`, path);
  }
  const server = createServer((request, response) => {
    response.setHeader('Cache-Control', 'no-store');
    response.setHeader('X-Content-Type-Options', 'nosniff');
    if (request.method !== 'GET' && request.method !== 'HEAD') {
      response.writeHead(405, { Allow: 'GET, HEAD', 'Content-Type': 'text/plain; charset=utf-8' });
      response.end('method not allowed\n');
      return;
    }
    let url;
    try {
      url = new URL(request.url, 'http://localhost');
    } catch {
      response.writeHead(400).end();
      return;
    }
    if (url.pathname === '/') {
      const first = served.keys().next().value;
      response.writeHead(302, { Location: first ? `/viewer/?src=${first}` : '/viewer/' });
      response.end();
      return;
    }
    const given = served.get(url.pathname);
    const path = given ?? fileInRoot(realRoot, url.pathname);
    if (path === null) {
      response.writeHead(404, { 'Content-Type': 'text/plain; charset=utf-8' });
      response.end('not found\n');
      return;
    }
    let size;
    try {
      size = statSync(path).size;
    } catch {
      response.writeHead(404).end();
      return;
    }
    response.writeHead(200, {
      'Content-Type': MIME[extname(path).toLowerCase()] ?? 'application/octet-stream',
      'Content-Length': size,
    });
    sendFile(request, response, path, size, given ? slow : {});
  });
  return new Promise((resolveStart, rejectStart) => {
    server.once('error', rejectStart);
    server.listen(port, host, () => {
      server.off('error', rejectStart);
      const fileUrls = {};
      for (const [urlPath, path] of served) fileUrls[basename(path)] = urlPath;
      resolveStart({
        server, port: server.address().port, fileUrls,
        close: () => new Promise((done) => { server.closeAllConnections(); server.close(() => done()); }),
      });
    });
  });
}

function usage(message) {
  if (message) console.error(`serve.mjs: ${message}`);
  console.error('usage: serve.mjs FILE.srm [--port N] [--rate BYTES_PER_SECOND] [--chunk BYTES] [--drop-after BYTES]');
  process.exit(2);
}

function parseArgs(argv) {
  const options = { files: [], port: 8080, rate: 0, chunkBytes: 0, dropAfter: 0 };
  const number = (name, text) => {
    const value = Number(text);
    if (text === undefined || !Number.isInteger(value) || value < 0) usage(`${name} needs a whole number, not ${text}`);
    return value;
  };
  for (let i = 0; i < argv.length; ++i) {
    const arg = argv[i];
    if (arg === '--port') options.port = number(arg, argv[++i]);
    else if (arg === '--rate') options.rate = number(arg, argv[++i]);
    else if (arg === '--chunk') options.chunkBytes = number(arg, argv[++i]);
    else if (arg === '--drop-after') options.dropAfter = number(arg, argv[++i]);
    else if (arg === '-h' || arg === '--help') usage();
    else if (arg.startsWith('-')) usage(`unknown option ${arg}`);
    else options.files.push(arg);
  }
  if (options.files.length === 0) usage('give the .srm file to serve');
  if (options.port > 65535) usage(`port ${options.port} is out of range`);
  for (const file of options.files) {
    if (!existsSync(file) || !statSync(file).isFile()) {
      console.error(`serve.mjs: ${file}: no such file`);
      process.exit(1);
    }
  }
  return options;
}

if (process.argv[1] && resolve(process.argv[1]) === fileURLToPath(import.meta.url)) {
  const options = parseArgs(process.argv.slice(2));
  if (!existsSync(join(webRoot, 'dist/index.js'))) {
    console.error('serve.mjs: web/dist is missing: run bash web/build.sh (or use web/serve.sh)');
    process.exit(1);
  }
  startServer(options).then(({ port, fileUrls }) => {
    const speed = options.rate > 0 ? ` at ${options.rate} bytes/s` : '';
    for (const urlPath of Object.values(fileUrls)) {
      console.log(`http://localhost:${port}/viewer/?src=${urlPath}`);
    }
    console.error(`serving ${webRoot} and ${options.files.join(', ')}${speed}; Ctrl-C stops`);
  }, (error) => {
    console.error(`serve.mjs: ${error.code === 'EADDRINUSE' ? `port ${options.port} is in use: pick another with --port` : error.message}`);
    process.exit(1);
  });
}
