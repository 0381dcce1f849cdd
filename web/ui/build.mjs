// Bundles the web app into OUTDIR (default dist/): index.html, app.js, app.css and sw.js, the files
// web/server embeds into the nbar program. Run by CMake (web/ui/build-ui.cmake) or by hand:
//   npm ci && node build.mjs [OUTDIR]
// With --engine DIR (the WebAssembly build's web/engine) it writes the static site instead: the
// same app with the engine beside it (engine-worker.js, nbar-engine.js, nbar-engine.wasm), the
// bundled examples in examples/, and index.html naming the engine, so that any static web server
// serves the whole app (scripts/build-wasm.sh --site; docs/web.md):
//   node build.mjs SITEDIR --engine build-wasm/web/engine [--examples ../../examples]
import { build } from 'esbuild';
import { createHash } from 'node:crypto';
import { copyFileSync, mkdirSync, readdirSync, readFileSync, statSync, writeFileSync } from 'node:fs';
import { dirname, join, relative, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const option = (name) => { const i = process.argv.indexOf(name); return i > 0 ? process.argv[i + 1] : undefined; };
const positional = process.argv.slice(2).filter((a, i, all) => !a.startsWith('--') && !all[i - 1]?.startsWith('--'));
const out = resolve(positional[0] ?? join(here, 'dist'));
const engine = option('--engine');
const examples = option('--examples') ?? join(here, '../../examples');

mkdirSync(out, { recursive: true });
await build({
  entryPoints: { app: join(here, 'src/main.js') },
  bundle: true,
  minify: true,
  format: 'esm',
  target: ['es2020'],
  outdir: out,
  legalComments: 'none',
  logLevel: 'warning',
});

let index = readFileSync(join(here, 'src/index.html'), 'utf8');
// What the service worker keeps at install, relative to the site's root.
const shell = ['./', 'index.html', 'app.js', 'app.css'];
if (engine) {
  // The engine's files beside the app; the worker is not bundled (it imports the engine module).
  // The module is named .js: every static host serves that as JavaScript, which a module must
  // be (some serve .mjs as bytes).
  copyFileSync(join(here, 'src/engine-worker.js'), join(out, 'engine-worker.js'));
  copyFileSync(join(engine, 'nbar-engine.mjs'), join(out, 'nbar-engine.js'));
  copyFileSync(join(engine, 'nbar-engine.wasm'), join(out, 'nbar-engine.wasm'));
  shell.push('engine-worker.js', 'nbar-engine.js', 'nbar-engine.wasm');
  mkdirSync(join(out, 'examples'), { recursive: true });
  for (const file of yamlFiles(examples)) {
    const target = join(out, 'examples', relative(examples, file));
    mkdirSync(dirname(target), { recursive: true });
    copyFileSync(file, target);
  }
  // The .wasm is asked for with the page (a preload the engine's fetch then takes up), not once
  // app.js has run: it arrives about 400 ms sooner, and the first analysis about 120 ms.
  index = index.replace('<meta name="generator" content="nbar web app">',
    '<meta name="generator" content="nbar web app">\n<meta name="nbar-engine" content="nbar-engine.wasm">\n' +
    '<link rel="preload" href="nbar-engine.wasm" as="fetch" type="application/wasm" crossorigin="anonymous">');
  if (!index.includes('name="nbar-engine"')) throw new Error('index.html: no generator meta to put the engine after');
} else {
  // nbar serve's examples list, for opening the gallery offline.
  shell.push('api/examples');
}
writeFileSync(join(out, 'index.html'), index);

// The service worker, versioned by a digest of every file it keeps: any change to the app or the
// engine makes a new sw.js, which replaces the cached site on the next visit.
const digest = createHash('sha256');
for (const name of shell.filter((p) => !p.endsWith('/') && !p.startsWith('api/'))) digest.update(name).update(readFileSync(join(out, name)));
const sw = readFileSync(join(here, 'src/sw.js'), 'utf8')
  .replace("'@VERSION@'", `'${digest.digest('hex').slice(0, 16)}'`)
  .replace("['@SHELL@']", JSON.stringify(shell));
writeFileSync(join(out, 'sw.js'), sw);

function yamlFiles(folder) {
  return readdirSync(folder).flatMap((name) => {
    const path = join(folder, name);
    if (statSync(path).isDirectory()) return yamlFiles(path);
    return name.endsWith('.yaml') ? [path] : [];
  });
}
