// Browser check of Simulate mode (simulate.js), run by browser.mjs (with `nbar serve`) and by
// static-site.mjs (the in-browser engine) at a laptop's and a phone's viewport: the released
// crank-rocker simulated for 3 s with a row every 10 ms, played, and the crank's angle and the
// drawn pin A at t = 3 s checked against the command line's `nbar simulate --format json` (or,
// without a native nbar, against the engine's own /api/simulate answer taken by the page); back to
// the sweep; a tolerance the core refuses is said by name; a long run cancelled from the job bar
// keeps its rows so far (cancelKeepsRows).
// run(page, ctx) with ctx = {mobile, tag, shot, click, openExample, reference}: reference() gives
// the simulation's JSON to compare with.
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';

export const example = 'crank-rocker-released';
export const simulateArgs = ['--to', '3', '--dt', '0.01'];

// The command line's simulation of the bundled example, parsed.
export function cliSimulation(nbar, examples) {
  const args = ['simulate', `${examples}/${example}.yaml`, ...simulateArgs, '--format', 'json'];
  const run = spawnSync(nbar, args, { encoding: 'utf8', maxBuffer: 1 << 28 });
  assert.equal(run.status, 0, `nbar ${args.join(' ')}: ${run.stderr}`);
  return JSON.parse(run.stdout);
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

  const cancelledAt = await cancelKeepsRows(page, ctx);

  // Back to the sweep.
  await click(page, mobile, '#simulate');
  await page.waitForFunction(() => /^1 DOF · 361 samples/.test(document.querySelector('#status').textContent));
  assert.equal(await page.locator('#scrub').getAttribute('max'), sweepRows);
  return { crank: last[at('crank')], played, cancelledAt };
}

// A long run (1000 s at a tight tolerance: longer than the test waits) cancelled from the job
// bar keeps its rows so far: the status says where it stopped, and the scrubber, the readout, the
// table and the plot have the rows up to there, every 50 ms of simulated time; they play, and
// so does the run to 3 s at that dt, at 20 rows a second (under a row a 60 Hz frame).
async function cancelKeepsRows(page, ctx) {
  const { mobile, tag, shot, click } = ctx;
  await page.locator('#sim-dt').fill('0.05');
  await page.locator('#sim-rtol').fill('1e-13');
  await page.locator('#sim-to').fill('1000');
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
  assert.ok(end > 0 && end < 1000, `stopped before its end (t = ${end} s)`);
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
