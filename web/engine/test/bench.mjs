// Times the WebAssembly engine against the native CLI on the same machine, in the same run: a
// 361-step solve of the crank-rocker with dynamics (issue 35's first target), the median of
// several runs each. The native time is the CLI's whole run (start, read, solve, write the JSON);
// the engine's is one request, once the module is loaded (its load is timed on its own).
//
//   node bench.mjs --engine build-wasm/web/engine/nbar.mjs --native build/apps/nbar/nbar --examples examples
import { spawnSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { join, resolve } from 'node:path';
import { performance } from 'node:perf_hooks';
import { pathToFileURL } from 'node:url';

const kRuns = 7;

function parseArguments(argv) {
  const args = {};
  for (let i = 0; i < argv.length; i += 2) args[argv[i].replace(/^--/, '')] = argv[i + 1];
  return args;
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

const args = parseArguments(process.argv.slice(2));
const file = join(args.examples, 'fourbar-crank-rocker.yaml');
const model = readFileSync(file, 'utf8');

const loadStart = performance.now();
const { loadNbar } = await import(pathToFileURL(resolve(args.engine)).href);
const nbar = await loadNbar();
const loadMs = performance.now() - loadStart;

const body = { model, steps: 361, dynamics: true };
const wasmMs = median(Array.from({ length: kRuns }, () => timed(() => {
  const answer = nbar.requestBytes('solve', body);
  if (answer.status !== 200) throw new Error(`the engine answered ${answer.status}`);
})));
const nativeMs = median(Array.from({ length: kRuns }, () => timed(() => {
  const run = spawnSync(resolve(args.native), ['solve', file, '--steps', '361', '--dynamics', '--format', 'json']);
  if (run.status !== 0) throw new Error(`the CLI failed: ${run.stderr}`);
})));
console.log(`engine load (import, compile and start the .wasm): ${loadMs.toFixed(1)} ms`);
console.log(`361-step crank-rocker solve with dynamics, median of ${kRuns}: WebAssembly in Node ${wasmMs.toFixed(2)} ms, ` +
            `native CLI ${nativeMs.toFixed(2)} ms: ratio ${(wasmMs / nativeMs).toFixed(2)}`);
