// The requests the engine's benchmarks time against the native CLI (issue 35's targets), shared
// by bench.mjs (the engine in Node) and web/ui/test/bench-page.mjs (the engine in Chromium):
// each with its API path and body, the CLI's arguments for the same work, its target ratio (none:
// for the record) and how many runs to take the median of.
import { readFileSync } from 'node:fs';
import { join } from 'node:path';

export function benchCases(examples, runs) {
  const read = (file) => readFileSync(join(examples, file), 'utf8');
  return [
    {
      name: '361-step crank-rocker solve with dynamics',
      path: 'solve', body: { model: read('fourbar-crank-rocker.yaml'), steps: 361, dynamics: true },
      cli: ['solve', join(examples, 'fourbar-crank-rocker.yaml'), '--steps', '361', '--dynamics', '--format', 'json'],
      target: 2, runs,
    },
    {
      name: 'five-point synthesis (native on 1 thread)',
      path: 'synth/five-point', body: { task: read('synthesis/five-point-crank-rocker.yaml') },
      cli: ['synth', 'five-point', join(examples, 'synthesis/five-point-crank-rocker.yaml'), '--format', 'json', '--threads', '1'],
      serverBody: { task: read('synthesis/five-point-crank-rocker.yaml'), threads: 1 },
      target: 3, runs,
    },
    {
      name: 'five-point synthesis (native on every core)',
      path: 'synth/five-point', body: { task: read('synthesis/five-point-crank-rocker.yaml') },
      cli: ['synth', 'five-point', join(examples, 'synthesis/five-point-crank-rocker.yaml'), '--format', 'json'],
      runs,
    },
    {
      name: 'FE stress sweep of the steel four-bar (361 samples)',
      path: 'stress', body: { model: read('fourbar-steel-bars.yaml'), method: 'fe' },
      cli: ['stress', join(examples, 'fourbar-steel-bars.yaml'), '--method', 'fe', '--format', 'json'],
      target: 3, runs: Math.max(3, Math.ceil(runs / 2)),
    },
  ];
}
