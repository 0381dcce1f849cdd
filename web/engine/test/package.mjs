// The npm package as a user gets it (issue 35, item 5): nbar-wasm-<version>.tgz installed with
// `npm install` (offline: a local tarball needs no registry) into a scratch folder, then
//   - its version is the C++ project's, in the tarball's name, its package.json and the engine;
//   - it holds the engine's files and nothing else;
//   - its README's example (docs/javascript.md's), importing 'nbar-wasm', runs under Node and
//     prints what its comments say;
//   - the same example runs in Chromium (headless, through playwright-core, when both are here),
//     the package served as static files and named 'nbar-wasm' by an import map.
//
//   node package.mjs --tarball build-wasm/nbar-wasm-0.1.0.tgz --version 0.1.0 --npm npm
//                    --scratch DIR [--playwright web/ui/node_modules/playwright-core] [--chromium PATH]
import { spawnSync } from 'node:child_process';
import { existsSync, mkdirSync, readFileSync, readdirSync, rmSync, writeFileSync } from 'node:fs';
import { createServer } from 'node:http';
import { basename, extname, join, resolve } from 'node:path';
import { pathToFileURL } from 'node:url';

const args = {};
for (let i = 2; i < process.argv.length; i += 2) args[process.argv[i].replace(/^--/, '')] = process.argv[i + 1];
for (const key of ['tarball', 'version', 'npm', 'scratch'])
  if (!args[key]) throw new Error(`missing --${key}`);

let passed = 0;
let failed = 0;
function expect(ok, what) {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  if (ok) passed += 1;
  else failed += 1;
}

// What the README's example prints, line by line (its comments say the first).
const kExpectedOutput = [/^62 columns, 361 rows$/, /^422 1 9 invalid YAML: /];
const printsWhatItSays = (lines) =>
  lines.length === kExpectedOutput.length && kExpectedOutput.every((pattern, i) => pattern.test(lines[i]));

function install() {
  const scratch = resolve(args.scratch);
  rmSync(scratch, { recursive: true, force: true });
  mkdirSync(scratch, { recursive: true });
  writeFileSync(join(scratch, 'package.json'), JSON.stringify({ name: 'uses-nbar', private: true, type: 'module' }));
  // A cache of its own, so that the test neither reads nor fills the user's.
  const run = spawnSync(args.npm, ['install', '--offline', '--no-audit', '--no-fund', '--loglevel=error',
                                   '--cache', join(scratch, '.npm-cache'), resolve(args.tarball)],
                        { cwd: scratch, encoding: 'utf8' });
  process.stdout.write(run.stdout);
  process.stderr.write(run.stderr);
  expect(run.status === 0, `npm install --offline ${basename(args.tarball)}`);
  return scratch;
}

function readmeExample(installed) {
  const readme = readFileSync(join(installed, 'README.md'), 'utf8');
  const start = readme.indexOf('```js\n') + '```js\n'.length;
  return readme.slice(start, readme.indexOf('```', start));
}

function checkContents(installed) {
  const manifest = JSON.parse(readFileSync(join(installed, 'package.json'), 'utf8'));
  expect(basename(args.tarball) === `nbar-wasm-${args.version}.tgz`, `the tarball is nbar-wasm-${args.version}.tgz`);
  expect(manifest.name === 'nbar-wasm' && manifest.version === args.version,
         `package.json: ${manifest.name} ${manifest.version}, the project's version ${args.version}`);
  const files = readdirSync(installed).sort().join(' ');
  const expected = 'LICENSE README.md nbar-engine.mjs nbar-engine.wasm nbar.d.ts nbar.mjs package.json';
  expect(files === expected, `the package holds ${files}`);
}

function runUnderNode(scratch, example) {
  const file = join(scratch, 'example.mjs');
  writeFileSync(file, example);
  const run = spawnSync(process.execPath, [file], { cwd: scratch, encoding: 'utf8' });
  process.stdout.write(run.stdout);
  process.stderr.write(run.stderr);
  expect(run.status === 0 && printsWhatItSays(run.stdout.trim().split('\n')), "the README's example under Node");
  const version = spawnSync(process.execPath, ['--input-type=module', '-e',
    "import { loadNbar } from 'nbar-wasm'; console.log((await loadNbar()).version);"], { cwd: scratch, encoding: 'utf8' });
  expect(version.stdout.trim() === args.version, `the engine says it is nbar ${version.stdout.trim()}`);
}

const kTypes = { '.html': 'text/html', '.mjs': 'text/javascript', '.wasm': 'application/wasm', '.json': 'application/json' };

// The scratch folder as a static site: GET only, files below it only.
function serve(root, page) {
  const server = createServer((request, response) => {
    const path = decodeURIComponent(new URL(request.url, 'http://localhost').pathname);
    const file = resolve(join(root, path));
    if (path === '/') {
      response.writeHead(200, { 'content-type': 'text/html' }).end(page);
    } else if (file.startsWith(root) && existsSync(file)) {
      response.writeHead(200, { 'content-type': kTypes[extname(file)] ?? 'application/octet-stream' })
        .end(readFileSync(file));
    } else {
      response.writeHead(404).end();
    }
  });
  return new Promise((ready) => server.listen(0, '127.0.0.1', () => ready(server)));
}

async function runInChromium(scratch, example) {
  const chromiumPath = args.chromium ?? process.env.CHROMIUM ?? '/usr/bin/chromium';
  if (!args.playwright || !existsSync(args.playwright) || !existsSync(chromiumPath)) {
    console.log(`SKIP the README's example in Chromium: no playwright-core (${args.playwright}) or no ${chromiumPath}`);
    return;
  }
  const { chromium } = await import(pathToFileURL(join(resolve(args.playwright), 'index.mjs')).href);
  const page = `<!doctype html><link rel="icon" href="data:,"><script type="importmap">{"imports": {"nbar-wasm": "/node_modules/nbar-wasm/nbar.mjs"}}</script>
<script type="module">${example}\nwindow.exampleDone = true;</script>`;
  const server = await serve(scratch, page);
  const browser = await chromium.launch({ executablePath: chromiumPath, args: ['--no-sandbox', '--disable-gpu'] });
  try {
    const tab = await browser.newPage();
    const lines = [];
    tab.on('console', (message) => lines.push(`${message.type() === 'log' ? '' : `${message.type()}: `}${message.text()}`));
    tab.on('pageerror', (error) => lines.push(`page error: ${error.message}`));
    await tab.goto(`http://127.0.0.1:${server.address().port}/`);
    await tab.waitForFunction(() => window.exampleDone === true, null, { timeout: 60000 }).catch(() => {});
    console.log(lines.join('\n'));
    expect(printsWhatItSays(lines), "the README's example in Chromium");
  } finally {
    await browser.close();
    server.close();
  }
}

const scratch = install();
const installed = join(scratch, 'node_modules', 'nbar-wasm');
if (existsSync(installed)) {
  checkContents(installed);
  const example = readmeExample(installed);
  expect(example.includes("from 'nbar-wasm'"), "the README's example imports 'nbar-wasm'");
  runUnderNode(scratch, example);
  await runInChromium(scratch, example);
}
console.log(`${passed} passed, ${failed} failed`);
process.exit(failed === 0 && passed > 0 ? 0 : 1);
