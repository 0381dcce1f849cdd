// Bundles the web app into OUTDIR (default dist/): index.html, app.js, app.css and sw.js, the files
// web/server embeds into the nbar program. Run by CMake (web/ui/build-ui.cmake) or by hand:
//   npm ci && node build.mjs [OUTDIR]
import { build } from 'esbuild';
import { copyFileSync, mkdirSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const out = resolve(process.argv[2] ?? join(here, 'dist'));
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
copyFileSync(join(here, 'src/index.html'), join(out, 'index.html'));
// The service worker is its own script, served at the root so that its scope is the whole app.
copyFileSync(join(here, 'src/sw.js'), join(out, 'sw.js'));
