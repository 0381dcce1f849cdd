// Browser check of Simulate mode (simulate.js), run by browser.mjs (with `nbar serve`) and by
// static-site.mjs (the in-browser engine) at a laptop's and a phone's viewport: the released
// crank-rocker simulated for 3 s with a row every 10 ms, played, and the crank's angle and the
// drawn pin A at t = 3 s checked against the command line's `nbar simulate --format json` (or,
// without a native nbar, against the engine's own /api/simulate answer taken by the page); back to
// the sweep; a tolerance the core refuses is said by name; a long run cancelled from the job bar
// keeps its rows so far (cancelKeepsRows). The CSV and JSON downloads are the rows on screen with
// no second run (/api/simulate requests counted, on the network and to the engine's worker): a
// complete run's are `nbar simulate --format csv|json`'s, a cancelled run's hold its rows so far;
// a resize by over 25 % runs nothing either (resizedWithoutARun).
// run(page, ctx) with ctx = {mobile, tag, shot, click, openExample, reference, referenceText,
// exact}: reference() gives the simulation's JSON to compare with, referenceText(format) the
// command line's text in that format; `exact`: the page's engine is the command line's own (a
// server of the same build), so its downloads are that text byte for byte (the in-browser
// engine's are compared number by number).
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { spawnSync } from 'node:child_process';

export const example = 'crank-rocker-released';
export const simulateArgs = ['--to', '3', '--dt', '0.01'];

// The command line's simulation of the bundled example, as it writes it in `format`.
export function cliSimulationText(nbar, examples, format) {
  const args = ['simulate', `${examples}/${example}.yaml`, ...simulateArgs, '--format', format];
  const run = spawnSync(nbar, args, { encoding: 'utf8', maxBuffer: 1 << 28 });
  assert.equal(run.status, 0, `nbar ${args.join(' ')}: ${run.stderr}`);
  return run.stdout;
}

// The command line's simulation of the bundled example, parsed.
export function cliSimulation(nbar, examples) {
  return JSON.parse(cliSimulationText(nbar, examples, 'json'));
}

// Counts the page's /api/simulate requests from now on: to a server (the network) and to the
// in-browser engine (its worker's request messages, engine.js). count() gives how many so far.
async function simulationRequests(page) {
  let network = 0;
  page.on('request', (r) => { if (new URL(r.url()).pathname === '/api/simulate') network++; });
  await page.evaluate(() => {
    if (window.simulationsAsked !== undefined) return;
    window.simulationsAsked = 0;
    const post = Worker.prototype.postMessage;
    Worker.prototype.postMessage = function (message, ...rest) {
      if (message?.type === 'request' && message.path === '/api/simulate') window.simulationsAsked++;
      return post.call(this, message, ...rest);
    };
  });
  return { count: async () => network + await page.evaluate(() => window.simulationsAsked) };
}

// A download of the Downloads tab: its file's text.
async function downloaded(page, { mobile, click }, kind) {
  await click(page, mobile, '[data-tab="downloads"]');
  const [file] = await Promise.all([page.waitForEvent('download'), click(page, mobile, `[data-download="${kind}"]`)]);
  assert.match(file.suggestedFilename(), new RegExp(`-simulation\\.${kind}$`));
  return readFileSync(await file.path(), 'utf8');
}

// Two CSV texts of the same run: the same header and rows, and the same numbers, byte for byte
// when `exact`, else each to 1e-6 of its size (the engine in WebAssembly against the native
// program).
function sameCsv(got, want, exact) {
  if (exact) { assert.equal(got, want, 'the CSV download is `nbar simulate --format csv`, byte for byte'); return; }
  const [a, b] = [got, want].map((text) => text.trimEnd().split('\n'));
  assert.equal(a.length, b.length, 'the CSV has the rows of `nbar simulate --format csv`');
  assert.equal(a[0], b[0], 'the CSV has the columns of `nbar simulate --format csv`');
  for (let i = 1; i < a.length; i++) {
    const [x, y] = [a[i], b[i]].map((line) => line.split(',').map(Number));
    x.forEach((v, k) => assert.ok(Math.abs(v - y[k]) <= 1e-6 * Math.max(1, Math.abs(y[k])), `row ${i}, column ${a[0].split(',')[k]}: ${v}, ${y[k]}`));
  }
}

// The downloads of the complete run on screen: the command line's CSV and JSON for the same
// options, with no second run.
async function downloadsOfTheRun(page, ctx, asked) {
  const before = await asked.count();
  const csv = await downloaded(page, ctx, 'csv');
  sameCsv(csv, ctx.referenceText('csv'), ctx.exact);
  assert.equal(csv.trimEnd().split('\n').length, 302, 'the header and the 301 rows shown');
  const json = await downloaded(page, ctx, 'json');
  if (ctx.exact) assert.equal(json, ctx.referenceText('json'), 'the JSON download is `nbar simulate --format json`, byte for byte');
  const table = JSON.parse(json);
  assert.equal(table.rows.length, 301);
  assert.equal(table.complete, true);
  assert.equal(await asked.count(), before, 'the downloads ran no simulation');
  assert.match(await page.locator('#status').textContent(), /^simulated 3 s · 301 rows/, 'the status still says the run');
}

// Resized by over 25 % (a phone turned, a window made narrower) and back: the drawing held is
// scaled, the simulation is not run again for the new size.
async function resizedWithoutARun(page, { mobile, tag, shot }, asked) {
  const before = await asked.count();
  const size = page.viewportSize();
  const box = async () => page.locator('#drawing').boundingBox();
  const drawn = async () => page.locator('#drawing svg g.scene').boundingBox();
  const [from, mechanism, scene] = [await box(), await drawn(), await page.locator('#drawing svg').getAttribute('data-width')];
  await page.setViewportSize(mobile ? { width: size.height, height: size.width } : { width: 900, height: 600 });
  await page.waitForTimeout(1500);  // the resize's own wait is 250 ms
  const to = await box();
  assert.ok(Math.abs(to.width - from.width) >= 0.25 * from.width || Math.abs(to.height - from.height) >= 0.25 * from.height,
    `the drawing resized by over 25 %: ${from.width}x${from.height} to ${to.width}x${to.height}`);
  // Scaled as a whole, as the SVG's viewBox fits the new box ("meet": the smaller of the two ratios).
  const now = await drawn();
  const [sx, sy] = [now.width / mechanism.width, now.height / mechanism.height];
  const fit = Math.min(to.width / from.width, to.height / from.height);
  assert.ok(Math.abs(sx - sy) < 0.02 * sx && Math.abs(sx - fit) < 0.05 * fit,
    `the drawing held is scaled uniformly, by ${sx.toFixed(3)} x ${sy.toFixed(3)} (the box by ${fit.toFixed(3)})`);
  await page.locator('#drawing').scrollIntoViewIfNeeded();
  await shot(page, `${tag}-sim-2b-resized`);
  assert.equal(await page.locator('#drawing svg').getAttribute('data-width'), scene, 'the scene held is drawn, scaled');
  await page.setViewportSize(size);
  await page.waitForTimeout(1500);
  assert.equal(await asked.count(), before, 'a resize ran no simulation');
}

// As the app writes numbers (main.js's fmt).
const fmt = (v) => {
  const a = Math.abs(v);
  if (a !== 0 && (a >= 1e6 || a < 1e-3)) return v.toExponential(3);
  return String(+v.toFixed(a >= 100 ? 2 : 4));
};

const status = (page) => page.locator('#status').textContent();
const frame = (page) => page.locator('#drawing svg .frame').innerHTML();

async function waitAnalysed(page) {
  await page.waitForFunction(() => !document.body.dataset.busy && !/…$/.test(document.querySelector('#status').textContent));
}

export async function run(page, ctx) {
  const { mobile, tag, shot, click } = ctx;
  await ctx.openExample(page, mobile, example);
  assert.match(await status(page), /^1 DOF · 361 samples/);
  const sweepRows = await page.locator('#scrub').getAttribute('max');

  // Simulate: the options' defaults are 3 s and 10 ms.
  await click(page, mobile, '#simulate');
  assert.equal(await page.locator('#sim-to').inputValue(), '3');
  assert.equal(await page.locator('#sim-dt').inputValue(), '0.01');
  await page.waitForFunction(() => /^simulated 3 s · 301 rows/.test(document.querySelector('#status').textContent), null, { timeout: 60000 });
  await waitAnalysed(page);
  assert.equal(await page.locator('#scrub').getAttribute('max'), '300');
  assert.equal(await page.evaluate(() => document.body.dataset.mode), 'simulate');
  const asked = await simulationRequests(page);
  await downloadsOfTheRun(page, ctx, asked);
  await resizedWithoutARun(page, ctx, asked);

  // Played at its own time: half a second moves it by about 50 rows.
  const before = await frame(page);
  await click(page, mobile, '#play');
  await page.waitForTimeout(700);
  await shot(page, `${tag}-sim-1-playing`);
  await click(page, mobile, '#play');
  const played = +(await page.locator('#scrub').inputValue());
  assert.ok(played > 10, `the simulation played (row ${played})`);
  assert.notEqual(await frame(page), before, 'playing moved the mechanism');

  // The last row against the reference: the crank's angle in the table and the readout, and pin A
  // where the drawing puts it.
  const reference = await ctx.reference();
  const at = (name) => reference.columns.indexOf(name);
  const last = reference.rows[300];
  assert.equal(reference.rows.length, 301);
  await page.selectOption('#ycol', 'crank');
  await page.locator('#scrub').fill('300');
  assert.match(await page.locator('#readout').textContent(), /^t = 3 s$/);
  await click(page, mobile, '[data-rtab="table"]');
  const row = page.locator('#table tbody tr[data-i="300"]');
  const header = await page.locator('#table thead th').allTextContents();
  const crankCell = header.findIndex((h) => h.startsWith('crank'));
  assert.ok(crankCell >= 0, `a crank column in ${header}`);
  assert.equal(await row.locator('td').nth(crankCell).textContent(), fmt(last[at('crank')]), 'the crank at t = 3 s');
  assert.ok(Math.abs(last[at('crank')] - 6.9145) < 0.05, `the reference's crank at 3 s is ${last[at('crank')]} deg`);
  const pin = page.locator('#drawing circle.pt[data-point="A"]');
  assert.ok(Math.abs(+(await pin.getAttribute('cx')) - last[at('A.x')]) < 1e-3, 'pin A drawn at its x');
  assert.ok(Math.abs(-(await pin.getAttribute('cy')) - last[at('A.y')]) < 1e-3, 'pin A drawn at its y');
  // The scene's pose of the crank's body: its group turned from the start by the crank's angle.
  const turned = await page.evaluate(() => document.querySelector('#drawing g[data-link="crank"]').getAttribute('transform'));
  const angle = +/rotate\(([-\d.e]+)/.exec(turned)[1];
  assert.ok(Math.abs(Math.abs(angle) - Math.abs(last[at('crank')] - reference.rows[0][at('crank')])) < 1e-3, `crank turned ${angle} deg`);
  await row.scrollIntoViewIfNeeded();
  await shot(page, `${tag}-sim-2-table`);
  await click(page, mobile, '[data-rtab="plot"]');
  await page.locator('#plot').scrollIntoViewIfNeeded();
  assert.match(await page.locator('#plot .u-legend').textContent(), /crank/);
  await shot(page, `${tag}-sim-3-plot`);

  // A tolerance the core refuses, said by its name; then a good one runs again.
  await page.locator('#sim-rtol').fill('1');
  await page.waitForFunction(() => /rtol/.test(document.querySelector('#problems').textContent), null, { timeout: 30000 });
  await page.locator('#sim-rtol').fill('1e-10');
  await page.waitForFunction(() => /^simulated 3 s · 301 rows/.test(document.querySelector('#status').textContent), null, { timeout: 60000 });

  const cancelledAt = await cancelKeepsRows(page, ctx, asked);

  // Back to the sweep.
  await click(page, mobile, '#simulate');
  await page.waitForFunction(() => /^1 DOF · 361 samples/.test(document.querySelector('#status').textContent));
  assert.equal(await page.locator('#scrub').getAttribute('max'), sweepRows);
  return { crank: last[at('crank')], played, cancelledAt };
}

// A long run (4000 s at a tight tolerance, near the most rows the server allows at this dt: 8 s,
// four times what the test waits before it cancels; 1000 s took 2 s once the steps away from
// toggles were DOP853's, and a phone's run ended before its cancel) cancelled from the job
// bar keeps its rows so far: the status says where it stopped, and the scrubber, the readout, the
// table and the plot have the rows up to there, every 50 ms of simulated time; they play, and
// so does the run to 3 s at that dt, at 20 rows a second (under a row a 60 Hz frame).
async function cancelKeepsRows(page, ctx, asked) {
  const { mobile, tag, shot, click } = ctx;
  await page.locator('#sim-dt').fill('0.05');
  await page.locator('#sim-rtol').fill('1e-13');
  await page.locator('#sim-to').fill('4000');
  await page.waitForFunction(() => document.body.dataset.job && !document.querySelector('#job').hidden, null, { timeout: 30000 });
  await page.waitForTimeout(1500);
  await shot(page, `${tag}-sim-4-running`);
  await click(page, mobile, '#job button');
  await page.waitForFunction(() => /cancelled at t = /.test(document.querySelector('#status').textContent), null, { timeout: 30000 });
  await waitAnalysed(page);
  const said = await status(page);
  const m = /^simulated ([\d.e+-]+) s · (\d+) rows · .*cancelled at t = ([\d.e+-]+) s/.exec(said);
  assert.ok(m, `the status says where the run was cancelled: ${said}`);
  const [end, rows, at] = [+m[1], +m[2], +m[3]];
  assert.equal(at, end, 'cancelled where the last row is');
  assert.ok(end > 0 && end < 4000, `stopped before its end (t = ${end} s)`);
  assert.equal(rows, Math.round(end / 0.05) + 1, 'a row every 50 ms up to there');
  assert.ok(await page.locator('#job').isHidden(), 'the job bar is gone');
  assert.equal(await page.locator('#scrub').getAttribute('max'), String(rows - 1));
  // The last row kept: its time in the readout and the table.
  await page.locator('#scrub').fill(String(rows - 1));
  assert.equal(await page.locator('#readout').textContent(), `t = ${fmt(end)} s`);
  await click(page, mobile, '[data-rtab="table"]');
  const header = await page.locator('#table thead th').allTextContents();
  const tCell = header.findIndex((h) => /^t\b/.test(h));
  // The table shows every rows/400-th row: its last is within one stride of the last row kept.
  const lastRow = page.locator('#table tbody tr').last();
  const shown = +(await lastRow.getAttribute('data-i'));
  assert.ok(shown <= rows - 1 && shown > rows - 1 - Math.ceil(rows / 400), `the table's last row ${shown} of ${rows}`);
  assert.equal(await lastRow.locator('td').nth(tCell).textContent(), fmt(shown * 0.05), 'the table has the rows kept');
  await lastRow.scrollIntoViewIfNeeded();
  await shot(page, `${tag}-sim-5-cancelled-table`);
  await cancelledDownloads(page, ctx, asked, rows, end);
  await click(page, mobile, '[data-rtab="plot"]');
  await page.locator('#plot').scrollIntoViewIfNeeded();
  assert.ok(await page.locator('#plot canvas').count() > 0, 'the rows are plotted');
  await playsAtOwnTime(page, ctx, rows, end, 'the rows kept');
  await shot(page, `${tag}-sim-6-cancelled-plot`);
  // A play slower than a row a frame whatever the machine's speed (the run above may stop past
  // 60 s, played faster): 3 s at a row every 50 ms, 20 rows a second.
  await page.locator('#sim-to').fill('3');
  await page.waitForFunction(() => /^simulated 3 s · 61 rows/.test(document.querySelector('#status').textContent), null, { timeout: 60000 });
  await waitAnalysed(page);
  await playsAtOwnTime(page, ctx, 61, 3, 'a row every 50 ms');
  // The options of the first run again.
  await page.locator('#sim-dt').fill('0.01');
  await page.locator('#sim-rtol').fill('1e-10');
  await page.waitForFunction(() => /^simulated 3 s · 301 rows/.test(document.querySelector('#status').textContent), null, { timeout: 60000 });
  return end;
}

// The downloads of a cancelled run: its rows so far, as many as shown, the last at the time the
// status says, its JSON cancelled where the run stopped; and no second run (which would hold the
// whole run, or none: the downloads ask the server for nothing).
async function cancelledDownloads(page, ctx, asked, rows, end) {
  const before = await asked.count();
  const csv = (await downloaded(page, ctx, 'csv')).trimEnd().split('\n');
  assert.equal(csv.length - 1, rows, 'the CSV holds the rows shown');
  const t = csv[0].split(',').indexOf('t');
  assert.ok(Math.abs(+csv.at(-1).split(',')[t] - end) <= 1e-5 * end, `the CSV's last row is at t = ${end} s: ${csv.at(-1)}`);
  const json = JSON.parse(await downloaded(page, ctx, 'json'));
  assert.equal(json.rows.length, rows, 'the JSON holds the rows shown');
  assert.equal(json.complete, false);
  assert.equal(json.cancelled, true);
  assert.equal(json.rows.at(-1)[json.columns.indexOf('t')], json.time_reached);
  assert.match(json.stop_reason, /^cancelled at t = /);
  assert.ok(Math.abs(+/t = ([\d.e+-]+) s/.exec(json.stop_reason)[1] - end) <= 1e-5 * end, `stopped at t = ${end} s: ${json.stop_reason}`);
  assert.equal(await asked.count(), before, 'the downloads ran no simulation');
}

// Played from row 0, a simulation of `rows` rows to `end` s moves the drawing at its own time:
// rows - 1 in `end` s, at least 2 s and at most 20 s a loop (simulate.js). 20 rows a second is a
// third of a row a 60 Hz frame, where a play head that lost its fraction every frame stayed on its
// row (it only moved when a slow frame gave it a whole row).
async function playsAtOwnTime(page, { mobile, click }, rows, end, what) {
  await page.locator('#scrub').fill('0');
  const before = await frame(page);
  await click(page, mobile, '#play');
  // Up to 5 s for the first frames on a loaded machine (500 ms was too short beside other builds).
  let moved = false;
  for (let waited = 0; waited < 5000 && !moved; waited += 250) {
    await page.waitForTimeout(250);
    moved = (await frame(page)) !== before;
  }
  if (!moved) await click(page, mobile, '#play');
  assert.ok(moved, `${what} play`);
  // Then a second of play moves it by about the rows of a second (half of them on a loaded
  // machine); a second is under the shortest loop, so the rows it wrapped past are counted.
  const rowsPerMs = (rows - 1) / Math.min(Math.max(end * 1000, 2000), 20000);
  const rowAt = async () => [+(await page.locator('#scrub').inputValue()), Date.now()];
  const [row0, t0] = await rowAt();
  await page.waitForTimeout(1000);
  const [row1, t1] = await rowAt();
  await click(page, mobile, '#play');
  const advanced = (row1 - row0 + rows) % rows;
  const expected = (t1 - t0) * rowsPerMs;
  assert.ok(advanced >= 0.5 * expected && advanced <= 1.5 * expected + 2,
    `${what} play at their own time: ${advanced} rows in ${t1 - t0} ms, ${expected.toFixed(1)} expected`);
}
