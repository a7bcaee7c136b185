// Serves web/ over HTTP for the playground, the bench page and the browser tests:
//   node web/serve.mjs [PORT]     (default 8080; then open http://localhost:8080/playground/;
//                                 web/serve builds hibi.wasm first when it is missing)
// Static files under web/ only (not node_modules). Under /isolated/ the same files come with
// the headers that make a page cross-origin isolated (COOP and COEP), where SharedArrayBuffer
// exists: /isolated/tests/bands.html runs renderAsync's shared-memory path in a browser.
import { createServer } from 'node:http';
import { readFile } from 'node:fs/promises';
import { extname, join, normalize, sep } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = fileURLToPath(new URL('.', import.meta.url));
const types = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.mjs': 'text/javascript; charset=utf-8',
  '.css': 'text/css; charset=utf-8',
  '.wasm': 'application/wasm',
  '.json': 'application/json',
  '.png': 'image/png',
  '.svg': 'image/svg+xml',
  '.ts': 'text/plain; charset=utf-8',
};

/** Starts the server on `port` (0: any free port); resolves to its base URL. */
export function serve(port = 8080, host = '127.0.0.1') {
  const server = createServer(async (req, res) => {
    let path = decodeURIComponent(new URL(req.url, 'http://x').pathname);
    const isolation = path.startsWith('/isolated/')
      ? { 'cross-origin-opener-policy': 'same-origin', 'cross-origin-embedder-policy': 'require-corp' }
      : {};
    if (path.startsWith('/isolated/')) path = path.slice('/isolated'.length);
    let file = normalize(join(root, path));
    if (!file.startsWith(root) || file.split(sep).includes('node_modules')) {
      res.writeHead(403).end();
      return;
    }
    if (path.endsWith('/')) file = join(file, 'index.html');
    try {
      const body = await readFile(file);
      res.writeHead(200, { 'content-type': types[extname(file)] ?? 'application/octet-stream', 'cache-control': 'no-cache', ...isolation });
      res.end(body);
    } catch {
      res.writeHead(404, { 'content-type': 'text/plain' }).end(`not found: ${path}\n`);
    }
  });
  return new Promise((resolve) => {
    server.listen(port, host, () => resolve({ url: `http://${host}:${server.address().port}`, server }));
  });
}

if (process.argv[1] && fileURLToPath(import.meta.url) === normalize(process.argv[1])) {
  const { url } = await serve(Number(process.argv[2] ?? 8080));
  console.log(`hibi: serving web/ at ${url}/ — the playground: ${url}/playground/`);
}
