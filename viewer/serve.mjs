// serve.mjs — the viewer's static file server, with node's own http and fs
// only, so that serving needs nothing from npm.
//
//   node viewer/serve.mjs            # http://127.0.0.1:8080/ (PORT=0: any free port)
//
// It serves viewer/ at / (three.js from viewer/node_modules included) and the
// repository read-only at /repo/, so that ?file=/repo/out/run.glb opens a
// recording made by the examples. It listens on 127.0.0.1 only: it is a
// developer's tool, not a web server.
import { createReadStream } from 'node:fs';
import { stat } from 'node:fs/promises';
import { createServer } from 'node:http';
import { dirname, extname, isAbsolute, join, relative, resolve, sep } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const viewerDir = dirname(fileURLToPath(import.meta.url));
const repoDir = resolve(viewerDir, '..');

const types = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.mjs': 'text/javascript; charset=utf-8',
  '.css': 'text/css; charset=utf-8',
  '.json': 'application/json',
  '.md': 'text/plain; charset=utf-8',
  '.png': 'image/png',
  '.svg': 'image/svg+xml',
  '.glb': 'model/gltf-binary',
};

/// The file a URL path names under one of the mounts, or null. The longest
/// matching prefix wins, so /repo/ is not looked for under viewer/.
function lookup(mounts, urlPath) {
  let path;
  try {
    path = decodeURIComponent(urlPath);
  } catch {
    return null;
  }
  // A NUL byte or a backslash has no business in a path we serve.
  if (path.includes('\0') || path.includes('\\')) return null;
  const prefix = Object.keys(mounts)
    .filter((p) => path.startsWith(p))
    .sort((a, b) => b.length - a.length)[0];
  if (prefix === undefined) return null;
  const root = mounts[prefix];
  const file = resolve(root, '.' + sep + path.slice(prefix.length));
  // resolve() has folded any "..": what is left must still be inside root.
  const inside = relative(root, file);
  if (inside === '..' || inside.startsWith('..' + sep) || isAbsolute(inside)) return null;
  return file;
}

/// Starts serving on 127.0.0.1:port (0: a free port) and resolves to
/// {server, url} once listening. `mounts` adds URL prefixes ("/fixtures/")
/// served from other directories, as the test and the picture tool do.
export function startServer(port = Number(process.env.PORT ?? 8080), { mounts = {} } = {}) {
  const all = { '/': viewerDir, '/repo/': repoDir };
  for (const [prefix, dir] of Object.entries(mounts)) all[prefix] = resolve(dir);

  const server = createServer(async (request, response) => {
    const fail = (code, text) => {
      response.writeHead(code, { 'content-type': 'text/plain; charset=utf-8' });
      response.end(text + '\n');
    };
    if (request.method !== 'GET' && request.method !== 'HEAD') return fail(405, 'read-only: GET and HEAD only');
    const urlPath = new URL(request.url, 'http://localhost').pathname;
    let file = lookup(all, urlPath);
    if (!file) return fail(403, 'forbidden');
    try {
      let info = await stat(file);
      if (info.isDirectory()) {
        file = join(file, 'index.html');
        info = await stat(file);
      }
      response.writeHead(200, {
        'content-type': types[extname(file)] ?? 'application/octet-stream',
        'content-length': info.size,
        // Recordings are rewritten in place by the examples: never cache.
        'cache-control': 'no-store',
      });
      if (request.method === 'HEAD') return response.end();
      createReadStream(file).pipe(response);
    } catch {
      fail(404, 'not found: ' + urlPath);
    }
  });

  return new Promise((done, failed) => {
    server.once('error', failed);
    server.listen(port, '127.0.0.1', () => {
      server.off('error', failed);
      done({ server, url: `http://127.0.0.1:${server.address().port}/` });
    });
  });
}

if (process.argv[1] && import.meta.url === pathToFileURL(resolve(process.argv[1])).href) {
  const { url } = await startServer();
  console.log(`impulse viewer at ${url}`);
  console.log(`  a recording in the repository: ${url}?file=/repo/out/rube_goldberg.glb`);
}
