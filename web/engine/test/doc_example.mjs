// Runs docs/javascript.md's first example against the built engine, as a reader would run it: its
// import of 'nbar-wasm' (the npm package) pointed at the engine, in a file of its own. It fails when the example
// throws (an answer that is not 200) or prints other than what its comments say.
//
//   node doc_example.mjs --engine build-wasm/web/engine/nbar.mjs --doc docs/javascript.md
import { spawnSync } from 'node:child_process';
import { mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { pathToFileURL } from 'node:url';

const args = {};
for (let i = 2; i < process.argv.length; i += 2) args[process.argv[i].replace(/^--/, '')] = process.argv[i + 1];
const doc = readFileSync(args.doc, 'utf8');
const start = doc.indexOf('```js\n') + '```js\n'.length;
const example = doc.slice(start, doc.indexOf('```', start));
const file = join(mkdtempSync(join(tmpdir(), 'nbar-doc-')), 'example.mjs');
writeFileSync(file, example.replace("'nbar-wasm'", `'${pathToFileURL(resolve(args.engine)).href}'`));
const run = spawnSync(process.execPath, [file], { encoding: 'utf8' });
process.stdout.write(run.stdout);
process.stderr.write(run.stderr);
const lines = run.stdout.trim().split('\n');
const expected = [/^62 columns, 361 rows$/, /^422 1 9 invalid YAML: /];
const ok = run.status === 0 && lines.length === expected.length && expected.every((pattern, i) => pattern.test(lines[i]));
console.log(ok ? '1 passed, 0 failed' : '0 passed, 1 failed');
process.exit(ok ? 0 : 1);
