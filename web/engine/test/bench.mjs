// Times the WebAssembly engine against the native CLI on the same machine, in the same run (issue
// 35's targets), each the median of several runs, the engine's and the CLI's runs taking turns so
// that a machine busy with something else slows both alike:
//   - a 361-step solve of the crank-rocker with dynamics (target: at most 2x native);
//   - the five-point synthesis of examples/synthesis (at most 3x), against the CLI on one thread
//     (the engine has one) and, for the record, on all of them;
//   - an FE stress sweep of the steel four-bar, its 361 samples (at most 3x).
// The native time is the CLI's whole run (start, read, compute, write the JSON); the engine's is
// one request (read the model from the request, compute, write the JSON), once the module is
// loaded (its load is timed on its own; the first request, on code V8 has not optimised yet, is
// given apart). For the record, the same request to the native `nbar serve` (the same handle_api
// as the engine's, without the CLI's start, with a round trip on 127.0.0.1) is timed as well. It
// also gives the .wasm's size, raw and gzipped.
//
//   node bench.mjs --engine build-wasm/web/engine/nbar.mjs --native build/apps/nbar/nbar --examples examples [--check]
// With --check it fails when a ratio is over its target.
import { spawn, spawnSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { request as httpRequest } from 'node:http';
import { cpus, loadavg } from 'node:os';
import { dirname, join, resolve } from 'node:path';
import { performance } from 'node:perf_hooks';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { gzipSync } from 'node:zlib';
import { benchCases } from './bench-cases.mjs';

const args = { runs: '7' };
for (let i = 2; i < process.argv.length; ++i) {
  const key = process.argv[i].replace(/^--/, '');
  if (key === 'check') args.check = true;
  else args[key] = process.argv[++i];
}

function median(values) {
  const sorted = [...values].sort((a, b) => a - b);
  return sorted[Math.floor(sorted.length / 2)];
}

function timed(run) {
  const start = performance.now();
  run();
  return performance.now() - start;
}

const examples = resolve(args.examples);
const native = resolve(args.native);
const cases = benchCases(examples, Number(args.runs));

const loadStart = performance.now();
const { loadNbar } = await import(pathToFileURL(resolve(args.engine)).href);
const nbar = await loadNbar();
const loadMs = performance.now() - loadStart;

const wasmFile = join(dirname(fileURLToPath(pathToFileURL(resolve(args.engine)))), 'nbar-engine.wasm');
const wasmBytes = readFileSync(wasmFile);
console.log(`nbar ${nbar.version}; ${cpus().length} cores, load average ${loadavg()[0].toFixed(1)}; Node ${process.version}`);
console.log(`nbar-engine.wasm: ${wasmBytes.length} bytes, ${gzipSync(wasmBytes, { level: 9 }).length} gzipped (level 9)`);
console.log(`engine load (import, compile and start the .wasm): ${loadMs.toFixed(1)} ms`);

// `nbar serve --port 0`; resolves with its port once it listens.
function startNativeServer() {
  const server = spawn(native, ['serve', '--port', '0'], { stdio: ['ignore', 'ignore', 'pipe'] });
  return new Promise((ready, reject) => {
    let said = '';
    server.stderr.on('data', (chunk) => {
      said += chunk;
      const found = said.match(/http:\/\/127\.0\.0\.1:(\d+)\//);
      if (found) ready({ server, port: Number(found[1]) });
    });
    server.on('exit', (code) => reject(new Error(`nbar serve exited (${code}): ${said}`)));
  });
}

// One request on a connection of its own (the CLI's runs in between outlast a kept-alive one).
function timedServerRequest(port, each) {
  const body = JSON.stringify(each.serverBody ?? each.body);
  const start = performance.now();
  return new Promise((done, fail) => {
    const request = httpRequest({ host: '127.0.0.1', port, path: `/api/${each.path}`, method: 'POST', agent: false }, (response) => {
      response.on('data', () => {});
      response.on('end', () => {
        if (response.statusCode !== 200) fail(new Error(`${each.name}: nbar serve answered ${response.statusCode}`));
        else done(performance.now() - start);
      });
    });
    request.on('error', fail);
    request.end(body);
  });
}

function timedEngineRequest(each) {
  return timed(() => {
    const answer = nbar.requestBytes(each.path, each.body);
    if (answer.status !== 200) throw new Error(`${each.name}: the engine answered ${answer.status}`);
  });
}

function timedCli(each) {
  return timed(() => {
    const run = spawnSync(native, each.cli, { maxBuffer: 1 << 28 });
    if (run.status !== 0) throw new Error(`${each.name}: the CLI failed: ${run.stderr}`);
  });
}

const { server, port } = await startNativeServer();
let over = 0;
try {
  for (const each of cases) {
    const firstMs = timedEngineRequest(each);
    const times = { wasm: [], cli: [], server: [] };
    for (let i = 0; i < each.runs; ++i) {
      times.wasm.push(timedEngineRequest(each));
      times.cli.push(timedCli(each));
      times.server.push(await timedServerRequest(port, each));
    }
    const [wasmMs, cliMs, serverMs] = [median(times.wasm), median(times.cli), median(times.server)];
    const ratio = wasmMs / cliMs;
    const verdict = each.target === undefined ? '' : ` (target ${each.target}x: ${ratio <= each.target ? 'met' : 'NOT met'})`;
    if (each.target !== undefined && ratio > each.target) over += 1;
    console.log(`${each.name}, median of ${each.runs}: WebAssembly in Node ${wasmMs.toFixed(1)} ms ` +
                `(its first request ${firstMs.toFixed(1)} ms), native CLI ${cliMs.toFixed(1)} ms: ratio ${ratio.toFixed(2)}` +
                `${verdict}; native nbar serve ${serverMs.toFixed(1)} ms: ratio ${(wasmMs / serverMs).toFixed(2)}`);
  }
} finally {
  server.kill();
}
process.exit(args.check && over > 0 ? 1 : 0);
