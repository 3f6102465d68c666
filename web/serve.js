// A tiny static server for the demo and its test: serves this folder (three.js from its
// node_modules, no CDN) on 127.0.0.1 only.
//   node web/serve.js [--port N] [--for SECONDS] [--file /baked.glb=PATH]
// --for stops it after that many seconds (default: until Ctrl-C); --file serves one more file
// under a fixed name (the test's baked file). Port 0 picks a free one; the URL is printed.
import { createServer } from 'node:http';
import { readFile } from 'node:fs/promises';
import { extname, join, normalize, resolve, sep, dirname } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const TYPES = {
  '.html': 'text/html; charset=utf-8', '.js': 'text/javascript; charset=utf-8', '.mjs': 'text/javascript; charset=utf-8',
  '.json': 'application/json', '.glb': 'model/gltf-binary', '.gltf': 'model/gltf+json', '.png': 'image/png',
  '.css': 'text/css', '.wasm': 'application/wasm',
};

/** Starts the server; resolves to {url, close()}. extra: {'/name': '/absolute/path'}. */
export function startServer({ root = here, port = 0, extra = {} } = {}) {
  const base = resolve(root);
  const server = createServer(async (request, response) => {
    try {
      const path = decodeURIComponent(new URL(request.url, 'http://127.0.0.1').pathname);
      let file = extra[path];
      if (!file) {
        file = normalize(join(base, path.endsWith('/') ? path + 'index.html' : path));
        if (file !== base && !file.startsWith(base + sep)) throw Object.assign(new Error('outside'), { code: 'EACCES' });
      }
      const body = await readFile(file);
      response.writeHead(200, { 'Content-Type': TYPES[extname(file)] ?? 'application/octet-stream',
                                'Cache-Control': 'no-store' });
      response.end(body);
    } catch (error) {
      const status = error.code === 'EACCES' ? 403 : 404;
      response.writeHead(status, { 'Content-Type': 'text/plain' });
      response.end(`${status}: ${request.url}\n`);
    }
  });
  return new Promise((ready, fail) => {
    server.once('error', fail);
    server.listen(port, '127.0.0.1', () => {
      const { port: actual } = server.address();
      ready({ url: `http://127.0.0.1:${actual}/`, close: () => new Promise((done) => server.close(done)) });
    });
  });
}

if (process.argv[1] && resolve(process.argv[1]) === fileURLToPath(import.meta.url)) {
  const args = process.argv.slice(2);
  const option = (name) => { const i = args.indexOf(name); return i >= 0 ? args[i + 1] : undefined; };
  const extra = {};
  for (let i = 0; i < args.length; ++i)
    if (args[i] === '--file') {
      const [name, path] = (args[i + 1] ?? '').split('=');
      if (!name?.startsWith('/') || !path) { console.error('serve.js: --file wants /NAME=PATH'); process.exit(2); }
      extra[name] = resolve(path);
    }
  const port = Number(option('--port') ?? 8173);
  const seconds = option('--for') === undefined ? undefined : Number(option('--for'));
  const { url, close } = await startServer({ port, extra });
  console.log(`jade web demo: ${url} (127.0.0.1 only; Ctrl-C stops it)`);
  // Open keep-alive connections would hold close() up: exit once the time is up.
  if (seconds !== undefined) setTimeout(() => process.exit(0), seconds * 1000);
}
