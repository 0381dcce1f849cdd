// The WebAssembly engine answers as the native program does (issue 35): for every bundled example
// (examples/*.yaml), check, solve to order 3, solve with dynamics, beam and FE stresses, and the
// explanation, sent to the engine under Node and to the native `nbar serve`, must give the same
// status and JSON: the same keys and strings, every number within 1e-12 relative (below). Bad requests
// (a model with a syntax error, an unknown point, an option out of range, a body that is not
// JSON) must give the same error, at the same line and column. The solve is also checked against
// the native CLI's `--format json`, and so is every bundled synthesis task (examples/synthesis:
// five-point, nine-point, Burmester, function, path; a path fit by its best fit, below), and so is a
// simulation (forward dynamics) of the released crank-rocker, to the server and the CLI. It prints
// how many answers were bit for bit the native ones, and where the numbers beyond 1e-12 are.
//
//   node equality.mjs --engine build-wasm/web/engine/nbar.mjs --native build/apps/nbar/nbar --examples examples
import { spawn, spawnSync } from 'node:child_process';
import { readFileSync, readdirSync } from 'node:fs';
import { request as httpRequest } from 'node:http';
import { dirname, join, resolve } from 'node:path';
import { pathToFileURL } from 'node:url';

// Issue 35's target: every number within 1e-12 relative, on the scale of what it belongs to (below).
// Not bit for bit, because musl's sin, cos, atan2, hypot and acos (the engine's) round differently
// from glibc's in the last bit for 3 to 18 % of arguments and Eigen sums in another order without
// x86's SSE2 (docs/javascript.md); those last bits stay under 1e-12 where what follows is well
// conditioned, which is why a four-bar's transmission angle is no longer the acos of a cosine near
// 1 (src/model/triangle.hpp). A difference under 1e-12 in the model's own units (mm, deg, s) passes
// whatever the number: a Newton step's 2e-13 mm on an ill-conditioned Jacobian, an angular
// acceleration that is zero but for round-off.
const kRelative = 1e-12;
const kTarget = kRelative;
const kAbsolute = 1e-12;
const kZeroScale = 1e-6;

function parseArguments(argv) {
  const args = {};
  for (let i = 0; i < argv.length; i += 2) args[argv[i].replace(/^--/, '')] = argv[i + 1];
  for (const key of ['engine', 'native', 'examples'])
    if (!args[key]) throw new Error(`missing --${key}`);
  return args;
}

// `nbar serve --port 0` on this machine only; resolves with its port once it listens.
function startNativeServer(native) {
  const server = spawn(native, ['serve', '--port', '0'], { stdio: ['ignore', 'ignore', 'pipe'] });
  return new Promise((resolvePort, reject) => {
    let said = '';
    server.stderr.on('data', (chunk) => {
      said += chunk;
      const found = said.match(/http:\/\/127\.0\.0\.1:(\d+)\//);
      if (found) resolvePort({ server, port: Number(found[1]) });
    });
    server.on('exit', (code) => reject(new Error(`nbar serve exited (${code}): ${said}`)));
  });
}

// One request on a connection of its own: `nbar serve` closes a kept-alive connection after 5 s
// idle, and the engine's and the CLI's work between two requests can take longer on a busy
// machine (fetch then sent the next request into a closed socket: "other side closed").
function nativeAnswer(port, path, body) {
  const text = typeof body === 'string' ? body : JSON.stringify(body);
  return new Promise((done, fail) => {
    const request = httpRequest({ host: '127.0.0.1', port, path: `/api/${path}`, method: 'POST', agent: false }, (response) => {
      const chunks = [];
      response.on('data', (chunk) => chunks.push(chunk));
      response.on('end', () => done({
        status: response.statusCode,
        contentType: response.headers['content-type'],
        body: new Uint8Array(Buffer.concat(chunks)),
      }));
    });
    request.on('error', fail);
    request.end(text);
  });
}

// Numbers that measure round-off itself (a residual, an FE link's unbalance and reaction, an exact
// synthesis's distance from a target it passes through): no two platforms' round-off agree, so
// when both are at the level of round-off they are equal; otherwise they are compared as any other.
const kRoundOffKeys = new Set(['max_residual', 'unbalance', 'reaction', 'error', 'solver_residual']);
const kRoundOff = 1e-6;

// A simulation's smallest and largest integration steps are the step-size controller's choices
// from its error estimate, the difference of two solutions that agree to about rtol: that estimate
// has about eps / rtol relative precision (1e-6 at rtol 1e-10), so a last bit of difference in sin
// or cos moves a step by 1e-7 relative (measured on the released crank-rocker) while every row,
// the step counts and the energy error agree within the tolerances above. They agree to 1e-6.
const kStepSizeKeys = new Set(['smallest_step', 'largest_step']);
const kStepSize = 1e-6;

// A simulation's output row ends with one more Newton step on the positions than the tolerance
// needs, so its |Phi| is at rounding on both platforms: its rows are held to kRelative as every
// other number (before, a row whose |Phi| landed within a rounding of the projection's tolerance
// took one more step on one platform: row 45 of the released crank-rocker, 8.4e-12 of its column).

// A number is compared on the scale of what it belongs to: a table's column (the largest value in
// it), a field of a list of records (the same key's largest value over the list: a list of
// designs is a table whose columns have names), a vector (its largest entry), or itself. A
// velocity that is 1e-15 instead of -1e-15 at a dead centre is the same velocity when the column
// reaches 100; a design's 0.96 deg minimum transmission, near its toggle, where the angle
// magnifies the last bits of the design's lengths some 3 500 times, is compared on the 41 deg of
// the best design's.
function scaleOf(values) {
  return values.reduce((m, v) => (typeof v === 'number' ? Math.max(m, Math.abs(v)) : m), 0);
}
const isRecord = (v) => v !== null && typeof v === 'object' && !Array.isArray(v);
function fieldScalesOf(records) {
  const scales = {};
  for (const key of Object.keys(records[0])) scales[key] = scaleOf(records.map((r) => r[key]));
  return scales;
}

function compareNumber(a, b, scale, path, tally, differences) {
  tally.numbers += 1;
  if (Object.is(a, b)) return;
  tally.inexact += 1;
  const difference = Math.abs(a - b);
  tally.maxRelative = Math.max(tally.maxRelative, difference / Math.max(Math.abs(a), Math.abs(b)));
  if (difference <= kAbsolute) return;
  // A column that is zero but for round-off throughout (the angular accelerations of a
  // parallelogram driven at constant speed, whose jerks reach 1e-9 deg/s^3): both must stay
  // round-off, under 1e-6 in the model's units.
  if (scale > 0 && scale < kZeroScale && Math.abs(a) < kZeroScale && Math.abs(b) < kZeroScale) {
    tally.roundOff += 1;
    return;
  }
  const relative = difference / Math.max(Math.abs(a), Math.abs(b), scale);
  tally.maxScaled = Math.max(tally.maxScaled, relative);
  if (relative > kTarget) {
    tally.overTarget += 1;
    // Where: the request and, in a table, the column's name.
    const column = path.match(/^\$\.rows\[\d+\]\[(\d+)\]$/);
    const where = `${tally.request}: ${column ? tally.columns?.[Number(column[1])] ?? path : path.replace(/\[\d+\]/g, '[]')}`;
    tally.overTargetWhere.set(where, (tally.overTargetWhere.get(where) ?? 0) + 1);
  }
  if (!(relative <= kRelative)) differences.push(`${path}: ${a} (wasm) vs ${b} (native), relative ${relative}`);
}

// Round-off printed in a formula (explain's Jacobian: "1.22465e-16*(x_D - 1500)", on one platform
// -1.2e-16 and on another 3.2e-16, each a sine of pi) reads the same as any other: +-eps.
function withoutRoundOff(text) {
  return text
    .replace(/\d+(\.\d+)?e-(1[3-9]|[2-9]\d)/g, 'eps')
    .replace(/\d+(\.\d+)? \\times 10\^\{-(1[3-9]|[2-9]\d)\}/g, 'eps')
    .replace(/(- |\+ |-)?eps/g, '+-eps');
}

// Walks two JSON values side by side; every difference beyond the tolerance is listed by path. A
// step where a minimum or maximum is reached may differ when the value there agrees: a tie within
// rounding (a periodic sweep's first and last samples are the same pose).
function compareJson(a, b, path, tally, differences, scale = 0, fieldScales = null) {
  if (typeof a === 'number' && typeof b === 'number') {
    compareNumber(a, b, scale, path, tally, differences);
    return;
  }
  if (Array.isArray(a) && Array.isArray(b)) {
    if (a.length !== b.length) differences.push(`${path}: ${a.length} items (wasm) vs ${b.length} (native)`);
    const table = b.every((row) => Array.isArray(row));
    const columnScales = table ? (b[0] ?? []).map((_, j) => scaleOf(b.map((row) => row[j]))) : [];
    const vectorScale = scaleOf(b);
    const fieldScales = b.length > 0 && b.every(isRecord) ? fieldScalesOf(b) : null;
    for (let i = 0; i < Math.min(a.length, b.length); ++i) {
      if (table) {
        for (let j = 0; j < Math.min(a[i].length, b[i].length); ++j)
          compareJson(a[i][j], b[i][j], `${path}[${i}][${j}]`, tally, differences, columnScales[j]);
        if (a[i].length !== b[i].length) differences.push(`${path}[${i}]: rows of different lengths`);
      } else {
        compareJson(a[i], b[i], `${path}[${i}]`, tally, differences, vectorScale, fieldScales);
      }
    }
    return;
  }
  if (a && b && typeof a === 'object' && typeof b === 'object' && !Array.isArray(a) && !Array.isArray(b)) {
    const keysA = Object.keys(a).join(',');
    const keysB = Object.keys(b).join(',');
    if (keysA !== keysB) differences.push(`${path}: keys ${keysA} (wasm) vs ${keysB} (native)`);
    for (const key of Object.keys(a)) {
      if (!(key in b)) continue;
      const at = `${path}.${key}`;
      if (kRoundOffKeys.has(key) && typeof a[key] === 'number' && typeof b[key] === 'number' &&
          Math.abs(a[key]) <= kRoundOff && Math.abs(b[key]) <= kRoundOff) {
        tally.roundOff += 1;
        continue;
      }
      // A simulation's constraint drift (|Phi|, |Phi_q q' + Phi_t|, |Phi_q q'' - gamma| over its rows)
      // measures round-off itself, as a residual does: both at round-off are equal.
      if (key === 'constraint_drift' && a[key] && b[key] && typeof a[key] === 'object' &&
          [...Object.values(a[key]), ...Object.values(b[key])].every((v) => typeof v === 'number' && Math.abs(v) <= kRoundOff)) {
        tally.roundOff += Object.keys(b[key]).length;
        continue;
      }
      if (kStepSizeKeys.has(key) && typeof a[key] === 'number' && typeof b[key] === 'number' &&
          Math.abs(a[key] - b[key]) <= kStepSize * Math.max(Math.abs(a[key]), Math.abs(b[key]))) {
        tally.stepSizes += 1;
        continue;
      }
      const tiedStep = key.endsWith('_step') && key.slice(0, -'_step'.length) in b;
      if (tiedStep && a[key] !== b[key]) {
        const value = key.slice(0, -'_step'.length);
        tally.ties += 1;
        compareJson(a[value], b[value], `${path}.${value} (tied, at steps ${a[key]} and ${b[key]})`, tally, differences,
          fieldScales?.[value] ?? 0);
        continue;
      }
      compareJson(a[key], b[key], at, tally, differences, fieldScales?.[key] ?? 0);
    }
    return;
  }
  if (typeof a === 'string' && typeof b === 'string' && a !== b && withoutRoundOff(a) === withoutRoundOff(b)) {
    tally.roundOffTexts += 1;
    return;
  }
  if (a !== b) differences.push(`${path}: ${JSON.stringify(a)} (wasm) vs ${JSON.stringify(b)} (native)`);
}

const decoder = new TextDecoder();
const sameBytes = (a, b) => a.length === b.length && a.every((x, i) => x === b[i]);

// One request's two answers compared; returns the differences (none: equal).
function compareAnswers(wasm, native, tally) {
  const differences = [];
  if (wasm.status !== native.status) differences.push(`status ${wasm.status} (wasm) vs ${native.status} (native)`);
  if (wasm.contentType !== native.contentType)
    differences.push(`content type ${wasm.contentType} (wasm) vs ${native.contentType} (native)`);
  tally.answers += 1;
  if (sameBytes(wasm.body, native.body)) {
    tally.bitForBit += 1;
    if (wasm.status < 400) {
      const kind = tally.request?.replace(/^.*?: /, '').replace(/^synthesis .*/, 'synthesis') ?? '';
      tally.bitForBitKinds.set(kind, (tally.bitForBitKinds.get(kind) ?? 0) + 1);
    }
  } else if (native.contentType.startsWith('application/json')) {
    const nativeJson = JSON.parse(decoder.decode(native.body));
    tally.columns = nativeJson.columns;
    compareJson(JSON.parse(decoder.decode(wasm.body)), nativeJson, '$', tally, differences);
  } else {
    differences.push('the bodies differ (not JSON)');
  }
  if (wasm.status >= 400) tally.errors += 1;
  // An error is the same error: kind, message, line and column, byte for byte.
  if (wasm.status >= 400 && sameBytes(wasm.body, native.body)) tally.errorsBitForBit += 1;
  else if (wasm.status >= 400 || native.status >= 400) differences.push('the errors differ');
  return differences;
}

function exampleRequests(model) {
  return [
    ['check', 'check', { model }],
    ['solve order 3', 'solve', { model, order: 3 }],
    ['solve with dynamics', 'solve', { model, dynamics: true }],
    ['beam stress peaks', 'stress', { model, method: 'beam' }],
    ['FE stress peaks', 'stress', { model, method: 'fe' }],
    ['explain', 'explain', { model }],
  ];
}

// Requests the server refuses, each with its located error.
function badRequests(model) {
  const lines = model.split('\n');
  const unknownPoint = model.replace(/crank:\s*\[O2, A\]/, 'crank: [O2, nowhere]');
  return [
    ['a YAML syntax error', 'check', { model: `${lines.slice(0, 3).join('\n')}\n  : [unclosed\n${lines.slice(3).join('\n')}` }],
    ['an unknown point', 'solve', { model: unknownPoint }],
    ['steps out of range', 'solve', { model, steps: 0 }],
    ['an unknown option', 'solve', { model, colour: 'red' }],
    ['a body that is not JSON', 'solve', '{"model": "x", }'],
    ['an empty model', 'check', { model: '' }],
  ];
}

// The bundled synthesis tasks (examples/synthesis, its folders too), each with its method (`task:`).
function synthesisTasks(folder) {
  return readdirSync(folder, { recursive: true })
    .filter((file) => file.endsWith('.yaml'))
    .sort()
    .map((file) => {
      const text = readFileSync(join(folder, file), 'utf8');
      return { file, path: join(folder, file), method: text.match(/^task:\s*([\w-]+)/m)[1], text };
    });
}

// A task sent as text reads no file (the server refuses `curve: FILE.csv`), so a task whose targets
// are in a CSV file goes to the engine with them written in as `points:`, the numbers as the
// file spells them; the CLI reads the file itself.
function withCurveInline(task) {
  return task.text.replace(/^curve:\s*(\S+).*$/m, (_, csv) => {
    const rows = readFileSync(join(dirname(task.path), csv), 'utf8').trim().split('\n').slice(1);
    return `points:\n${rows.map((row) => `  - [${row.split(',').join(', ')}]`).join('\n')}`;
  });
}

// A path fit is a local optimisation from random starts, each stopped at its own tolerance: a last
// bit of difference between the platforms (their sin and cos) sends a start down another way, so
// the lists differ in their far designs, in the order of designs that tie, and in the number of
// evaluations. What must agree is the fit: the best design of each is in the other's list (its
// pivots and lengths within kFit relative to their largest, its rms error within kFit).
const kFit = 1e-6;

function designVector(design) {
  const pivots = Object.values(design.pivots ?? {}).flat();
  return [...pivots, ...Object.values(design.lengths ?? {})].filter((v) => typeof v === 'number');
}

function sameDesign(a, b) {
  const [u, v] = [designVector(a), designVector(b)];
  const scale = Math.max(scaleOf(u), scaleOf(v));
  return u.length === v.length && u.every((x, i) => Math.abs(x - v[i]) <= kFit * scale) &&
         Math.abs(a.rms_error - b.rms_error) <= kFit * Math.max(a.rms_error, b.rms_error);
}

function comparePathFits(wasm, native, tally) {
  tally.answers += 1;
  if (wasm.status !== 200 || native.status !== 200) return [`status ${wasm.status} (wasm) vs ${native.status} (native)`];
  const [a, b] = [JSON.parse(decoder.decode(wasm.body)), JSON.parse(decoder.decode(native.body))];
  const differences = [];
  const header = (answer) => Object.fromEntries(Object.entries(answer).filter(([key]) => !['notes', 'designs', 'solutions'].includes(key)));
  compareJson(header(a), header(b), '$', tally, differences);
  if (!a.designs.length || !b.designs.length) return [...differences, 'no design'];
  if (!b.designs.some((design) => sameDesign(a.designs[0], design))) differences.push("the engine's best fit is not in the native list");
  if (!a.designs.some((design) => sameDesign(b.designs[0], design))) differences.push("the native best fit is not in the engine's list");
  const shared = b.designs.filter((design) => a.designs.some((other) => sameDesign(design, other))).length;
  tally.pathFits.push(`${shared} of ${b.designs.length}`);
  return differences;
}

// The native CLI's `synth METHOD FILE --format json`.
function cliSynthesis(native, task) {
  const run = spawnSync(native, ['synth', task.method, task.path, '--format', 'json'], { maxBuffer: 1 << 28 });
  if (run.status !== 0) return { status: run.status, text: run.stderr.toString() };
  return { status: 0, body: new Uint8Array(run.stdout) };
}

// Forward dynamics (issue 38): the released crank-rocker let go for 3 s, a row every 10 ms, with the
// options the CLI spells as flags; and a tolerance out of range, refused the same way.
const kSimulation = { to: 3, dt: 0.01, rtol: 1e-10 };
const kSimulateFile = 'crank-rocker-released.yaml';

function cliSimulate(native, file) {
  const flags = Object.entries(kSimulation).flatMap(([key, value]) => [`--${key}`, String(value)]);
  const run = spawnSync(native, ['simulate', file, ...flags, '--format', 'json'], { maxBuffer: 1 << 28 });
  if (run.status !== 0) return { status: run.status, text: run.stderr.toString() };
  return { status: 0, body: new Uint8Array(run.stdout) };
}

// The native CLI's `solve --order 3 --format json` for a model file, parsed.
function cliSolve(native, file) {
  const run = spawnSync(native, ['solve', file, '--order', '3', '--format', 'json'], { maxBuffer: 1 << 28 });
  if (run.status !== 0) return { status: run.status, text: run.stderr.toString() };
  return { status: 0, body: new Uint8Array(run.stdout) };
}

async function main() {
  const args = parseArguments(process.argv.slice(2));
  const { loadNbar } = await import(pathToFileURL(resolve(args.engine)).href);
  // A nine-point synthesis on the engine's one thread takes longer than the server's 30 s budget
  // on a busy machine (the native program tracks its paths on every core).
  const nbar = await loadNbar({ timeBudgetSeconds: 600 });
  const { server, port } = await startNativeServer(resolve(args.native));
  const tally = {
    answers: 0, bitForBit: 0, errors: 0, numbers: 0, inexact: 0, maxRelative: 0, maxScaled: 0, overTarget: 0,
    roundOff: 0, ties: 0, roundOffTexts: 0, stepSizes: 0, errorsBitForBit: 0, pathFits: [], overTargetWhere: new Map(), bitForBitKinds: new Map(),
  };
  let failures = 0;
  let passed = 0;
  // Names the request whose answers the next compareAnswers sees (for the list of numbers over 1e-12).
  const sending = (name) => {
    tally.request = name;
    return name;
  };
  const check = (name, differences) => {
    if (differences.length === 0) {
      passed += 1;
      return;
    }
    failures += 1;
    console.log(`FAIL ${name}:\n  ${differences.slice(0, 10).join('\n  ')}`);
  };
  try {
    const files = readdirSync(args.examples).filter((f) => f.endsWith('.yaml')).sort();
    for (const file of files) {
      const model = readFileSync(join(args.examples, file), 'utf8');
      const requests = exampleRequests(model);
      if (file === 'fourbar-crank-rocker.yaml') requests.push(...badRequests(model));
      for (const [what, path, body] of requests) {
        const wasm = nbar.requestBytes(path, body);
        const native = await nativeAnswer(port, path, body);
        check(sending(`${file}: ${what}`), compareAnswers(wasm, native, tally));
      }
      const cli = cliSolve(resolve(args.native), join(args.examples, file));
      const wasm = nbar.requestBytes('solve', { model, order: 3 });
      if (cli.status === 0)
        check(sending(`${file}: solve order 3 against the CLI`),
              compareAnswers(wasm, { status: 200, contentType: 'application/json', body: cli.body }, tally));
      else if (wasm.status === 200)
        check(`${file}: solve order 3 against the CLI`, [`the CLI failed (${cli.status}): ${cli.text}`]);
    }
    const released = readFileSync(join(args.examples, kSimulateFile), 'utf8');
    for (const [what, body] of [['simulate', { model: released, ...kSimulation }], ['simulate with rtol out of range', { model: released, to: 1, rtol: 1 }]]) {
      const wasm = nbar.requestBytes('simulate', body);
      check(sending(`${kSimulateFile}: ${what}`), compareAnswers(wasm, await nativeAnswer(port, 'simulate', body), tally));
    }
    const simulatedByCli = cliSimulate(resolve(args.native), join(args.examples, kSimulateFile));
    if (simulatedByCli.status !== 0) check(`${kSimulateFile}: simulate against the CLI`, [`the CLI failed (${simulatedByCli.status}): ${simulatedByCli.text}`]);
    else check(sending(`${kSimulateFile}: simulate against the CLI`), compareAnswers(nbar.requestBytes('simulate', { model: released, ...kSimulation }),
      { status: 200, contentType: 'application/json', body: simulatedByCli.body }, tally));
    // Every bundled synthesis task, to the engine and to the CLI (the server answers as the CLI
    // does: tests/cross_frontend).
    for (const task of synthesisTasks(join(args.examples, 'synthesis'))) {
      const wasm = nbar.requestBytes(`synth/${task.method}`, { task: withCurveInline(task) });
      const cli = cliSynthesis(resolve(args.native), task);
      const native = { status: 200, contentType: 'application/json', body: cli.body };
      if (cli.status !== 0) check(`synthesis ${task.file}`, [`the CLI failed (${cli.status}): ${cli.text}`]);
      else if (task.method === 'path') check(sending(`synthesis ${task.file} (the fit)`), comparePathFits(wasm, native, tally));
      else check(sending(`synthesis ${task.file}`), compareAnswers(wasm, native, tally));
    }
  } finally {
    server.kill();
  }
  console.log(`${tally.answers} answers compared (${tally.errors} of them errors): ${tally.bitForBit} bit for bit ` +
              `(${tally.errorsBitForBit} of the errors); ` +
              `${tally.numbers} numbers in the others, ${tally.inexact} not bit for bit: largest difference over ` +
              `${kAbsolute} ${tally.maxScaled.toExponential(2)} relative to its column's or vector's scale ` +
              `(${tally.overTarget} over ${kTarget}); ${tally.roundOff} round-off values ` +
              `(residuals, unbalances, reactions, columns that are zero but for round-off) both round-off; ${tally.ties} minima or maxima tied at ` +
              `other steps; ${tally.roundOffTexts} formulas differing only in round-off coefficients; ` +
              `${tally.stepSizes} integration step sizes within ${kStepSize}; ` +
              `path fits: the same best fit, and ${tally.pathFits.join(' and ')} of the native designs in the engine's lists`);
  console.log(`answers (not errors) bit for bit: ${[...tally.bitForBitKinds].map(([kind, count]) => `${count} ${kind}`).join(', ')}`);
  const where = [...tally.overTargetWhere].sort((a, b) => b[1] - a[1]);
  if (where.length)
    console.log(`numbers over ${kTarget}, by request and column (the first 20 of ${where.length}):\n  ` +
                where.slice(0, 20).map(([name, count]) => `${count} ${name}`).join('\n  '));
  console.log(`${passed} passed, ${failures} failed`);
  process.exit(failures === 0 ? 0 : 1);
}

await main();
