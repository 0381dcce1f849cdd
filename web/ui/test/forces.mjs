// Browser checks of motion and forces in the web app (issue 39), run by browser.mjs at a laptop's
// and a phone's viewport (`--only forces`): the dynamics columns in Plot and Table and several
// curves on one plot, each read out; the per-link stress table with each link's peak and safety
// factor, a row going to its step; Explain's forces and stresses at the pose and its instant
// centres on the drawing; joint handles above the force arrows; a point grabbed at a later pose;
// labels and line widths that keep their screen size when zoomed; a one-finger pan at the
// drawing's bottom edge on a phone. Numbers are checked against the command line's.
// run(page, ctx) with ctx = {mobile, tag, nbar, base, shot, click, openExample, retype}.
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { mkdtempSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';

const fmt = (v) => {
  const a = Math.abs(v);
  if (a !== 0 && (a >= 1e6 || a < 1e-3)) return v.toExponential(3);
  return String(+v.toFixed(a >= 100 ? 2 : 4));
};
const close = (a, b, tol, what) => assert.ok(Math.abs(a - b) <= tol, `${what}: ${a} vs ${b} (tolerance ${tol})`);

// `nbar ARGS FILE` on an example's text (the server's copy, written to a file): its JSON answer.
const dir = mkdtempSync(join(tmpdir(), 'nbar-forces-'));
async function cli(ctx, name, args) {
  const file = join(dir, `${name}.yaml`);
  writeFileSync(file, await (await fetch(new URL(`api/examples/${name}`, ctx.base))).text());
  const r = spawnSync(ctx.nbar, [...args, file, '--format', 'json'], { encoding: 'utf8', maxBuffer: 1 << 28 });
  assert.equal(r.status, 0, `nbar ${args.join(' ')}: ${r.stderr}`);
  return JSON.parse(r.stdout);
}

async function scrollToDrawing(page) {
  await page.evaluate(() => document.querySelector('#drawing').scrollIntoView({ block: 'center', behavior: 'instant' }));
}

// The steel four-bar's crank torque and a joint force plotted together: both in the column
// choices once the dynamics are in, two curves (the crank angle on x) in the legend, each read
// out at the sample the plot is touched at, to the CLI's `solve --dynamics` numbers; the Table
// has both columns.
async function curves(page, ctx) {
  const { mobile, click } = ctx;
  await ctx.openExample(page, mobile, 'fourbar-steel-bars');
  await page.waitForSelector('#ycol option[value="crank.torque"]', { state: 'attached' });
  assert.ok(await page.locator('#ycol option[value="A.crank>coupler.Fx"]').count(), 'the joint forces are offered');
  assert.ok(await page.locator('#ycol option[value="energy.kinetic"]').count(), 'the energies are offered');
  await page.selectOption('#ycol', 'crank.torque');
  await page.selectOption('#ycol-add', 'A.crank>coupler.Fx');
  await page.waitForSelector('#ycurves [data-curve="A.crank>coupler.Fx"]');
  await click(page, mobile, '[data-rtab="plot"]');
  const labels = await page.locator('#plot .u-legend .u-series .u-label').allTextContents();
  assert.deepEqual(labels, ['crank (deg)', 'crank.torque (N m)', 'A.crank>coupler.Fx (N)']);
  const over = page.locator('#plot .u-over');
  await over.scrollIntoViewIfNeeded();
  const box = await over.boundingBox();
  if (mobile) await over.tap({ position: { x: box.width * 0.25, y: box.height / 2 } });
  else { await page.mouse.move(box.x + box.width * 0.25, box.y + box.height / 2); await page.mouse.down(); await page.mouse.up(); }
  const step = +(await page.locator('#scrub').inputValue());
  const values = await page.locator('#plot .u-legend .u-value').allTextContents();
  const ref = await cli(ctx, 'fourbar-steel-bars', ['solve', '--dynamics']);
  const at = (c) => ref.rows[step][ref.columns.indexOf(c)];
  assert.deepEqual(values, [fmt(at('crank')), fmt(at('crank.torque')), fmt(at('A.crank>coupler.Fx'))], `the read-out at step ${step}`);
  await ctx.shot(page, `${ctx.tag}-f1-curves`);
  await click(page, mobile, '[data-rtab="table"]');
  const head = await page.locator('#table thead th').allTextContents();
  assert.ok(head.some((h) => h.startsWith('crank.torque')) && head.some((h) => h.startsWith('A.crank>coupler.Fx')), `table columns: ${head}`);
  const row = page.locator(`#table tbody tr[data-i="${step}"]`);
  if (await row.count()) {
    const cells = await row.locator('td').allTextContents();
    assert.ok(cells.includes(fmt(at('crank.torque'))), `the table's row ${step}: ${cells}`);
  }
  await click(page, mobile, '[data-rtab="plot"]');
  await click(page, mobile, '#ycurves [data-uncurve="A.crank>coupler.Fx"]');
  assert.equal(await page.locator('#plot .u-legend .u-series').count(), 2);
}

// Every link's peak, step, place and safety factor, as `nbar stress` gives them; a row tapped
// goes to its step.
async function stressTable(page, ctx) {
  const { mobile, click } = ctx;
  await ctx.openExample(page, mobile, 'fourbar-steel-bars');
  await click(page, mobile, '[data-overlay="stress"]');
  await page.waitForSelector('#stress-table tr[data-body]');
  const ref = await cli(ctx, 'fourbar-steel-bars', ['stress']);
  assert.equal(await page.locator('#stress-table tr[data-body]').count(), ref.links.length);
  for (const l of ref.links) {
    const row = page.locator(`#stress-table tr[data-body="${l.body}"]`);
    assert.equal(await row.locator('[data-col="von_mises"]').textContent(), fmt(l.von_mises));
    assert.equal(await row.locator('[data-col="step"]').textContent(), String(l.step));
    assert.equal(await row.locator('[data-col="where"]').textContent(), `${fmt(l.x)}, ${fmt(l.y)}`);
    assert.equal(await row.locator('[data-col="safety_factor"]').textContent(), fmt(l.safety_factor));
  }
  // The crank's safety factor, yield over peak: steel's 250 MPa over the crank's 36.0 MPa.
  close(ref.links[0].safety_factor, 250 / ref.links[0].von_mises, 0.05, 'the CLI safety factor is yield / peak');
  const coupler = ref.links.find((l) => l.body === 'coupler');
  await page.locator('#stress-table').scrollIntoViewIfNeeded();
  await ctx.shot(page, `${ctx.tag}-f2-stress-table`);
  await click(page, mobile, '#stress-table tr[data-body="coupler"] button');
  assert.equal(await page.locator('#scrub').inputValue(), String(coupler.step));
  await click(page, mobile, '[data-overlay="stress"]');
  assert.ok(await page.locator('#stress-table').isHidden());
}

// Explain at step 90 lists the forces at that pose (the CLI's dynamics row 90) and each link's
// largest section stress (the CLI's section profile at step 90); its instant centres are marked
// on the drawing, where the CLI's explain puts them.
async function explainAtPose(page, ctx) {
  const { mobile, click } = ctx;
  await ctx.openExample(page, mobile, 'fourbar-steel-bars');
  await page.waitForFunction(() => document.body.dataset.dynamics === '1');
  await page.locator('#scrub').fill('90');
  await click(page, mobile, '[data-tab="explain"]');
  await click(page, mobile, '#explain-run');
  await page.waitForFunction(() => document.querySelector('#explain-out').dataset.pose === '90');
  const dyn = await cli(ctx, 'fourbar-steel-bars', ['solve', '--dynamics']);
  for (const c of ['crank.torque', 'A.crank>coupler.Fx', 'O4.ground>rocker.Fy']) {
    const cell = page.locator(`#explain-out table.forces tr[data-column="${c}"] td`).first();
    assert.equal(await cell.textContent(), fmt(dyn.rows[90][dyn.columns.indexOf(c)]), c);
  }
  const profile = await cli(ctx, 'fourbar-steel-bars', ['stress', '--section-profile', 'rocker', '--step', '90']);
  const vm = profile.columns.indexOf('von_mises');
  const peak = Math.max(...profile.rows.map((r) => Math.abs(r[vm])));
  assert.match(await page.locator('#explain-out table.stresses tr[data-body="rocker"] td').first().textContent(), new RegExp(`^${fmt(peak).replace('.', '\\.')} MPa$`));
  const ex = await cli(ctx, 'fourbar-steel-bars', ['explain', '--step', '90']);
  const finite = ex.centres.filter((c) => !c.at_infinity && !c.indeterminate);
  assert.equal(await page.locator('#drawing .ov-centres [data-centre]').count(), finite.length);
  const c13 = finite.find((c) => c.name === 'I(crank,coupler)');
  const mark = page.locator(`#drawing .ov-centres [data-centre="${c13.name}"] circle`);
  close(+(await mark.getAttribute('cx')), c13.position[0], 1e-3, 'I(crank,coupler) x');
  close(-(await mark.getAttribute('cy')), c13.position[1], 1e-3, 'I(crank,coupler) y');
  await scrollToDrawing(page);
  await ctx.shot(page, `${ctx.tag}-f3-explain-centres`);
  await page.locator('#explain-pose').scrollIntoViewIfNeeded();
  await ctx.shot(page, `${ctx.tag}-f3b-explain-forces`);
  // Another pose: the marks are of step 90's explanation, so they go.
  await page.locator('#scrub').fill('91');
  assert.equal(await page.locator('#drawing .ov-centres').count(), 0);
}

// With the joint forces drawn, each joint's centre is its handle (the arrows start there), and
// a press there grabs the point: the drag moves it, no pan.
async function handlesOverArrows(page, ctx) {
  const { mobile, click } = ctx;
  await ctx.openExample(page, mobile, 'fourbar-steel-bars');
  await click(page, mobile, '[data-overlay="forces"]');
  await page.waitForSelector('#drawing .ov-forces line', { state: 'attached' });
  await scrollToDrawing(page);
  const covered = await page.evaluate(() => [...document.querySelectorAll('#drawing circle.pt[data-point]')].map((c) => {
    const r = c.getBoundingClientRect();
    const hit = document.elementFromPoint(r.left + r.width / 2, r.top + r.height / 2);
    return hit?.closest('[data-point]')?.dataset.point === c.dataset.point ? null : `${c.dataset.point}: ${hit?.tagName}.${hit?.getAttribute('class') ?? ''}`;
  }).filter(Boolean));
  assert.deepEqual(covered, [], 'every joint handle is above the arrows');
  await ctx.shot(page, `${ctx.tag}-f4-forces-handles`);
  {
    await page.locator('#scrub').fill('0');
    const perPixel = await page.evaluate(() => 1 / document.querySelector('#drawing svg').getScreenCTM().a);
    const a = await page.locator('#drawing circle.pt[data-point="A"]').boundingBox();
    const from = { x: a.x + a.width / 2, y: a.y + a.height / 2 };
    await drag(page, mobile, from, { x: from.x + 30, y: from.y });
    await page.waitForFunction(() => !/A: +\[80, 0\]/.test(document.querySelector('.cm-content').textContent) && !document.body.dataset.busy);
    // Dragged, not panned: A moved 30 px right in the model.
    const line = await page.locator('.cm-line', { hasText: /^ *A: / }).first().textContent();
    const [x, y] = line.match(/\[([-\d.]+), ([-\d.]+)\]/).slice(1).map(Number);
    close(x, 80 + 30 * perPixel, 1.5 * perPixel, 'A.x after the drag');
    close(y, 0, 1.5 * perPixel, 'A.y after the drag');
    await page.waitForSelector('#drawing .ov-forces line', { state: 'attached' });
  }
  await click(page, mobile, '[data-overlay="forces"]');
}

// A screen point in the drawing's model coordinates (y up).
const toModel = (page, x, y) => page.evaluate(([sx, sy]) => {
  const p = new DOMPoint(sx, sy).matrixTransform(document.querySelector('#drawing svg').getScreenCTM().inverse());
  return { x: p.x, y: -p.y };
}, [x, y]);

// A one-finger drag by CDP touch events (Playwright's touchscreen only taps).
async function touchDrag(page, from, to, steps = 6) {
  const client = await page.context().newCDPSession(page);
  await client.send('Input.dispatchTouchEvent', { type: 'touchStart', touchPoints: [{ x: from.x, y: from.y }] });
  for (let k = 1; k <= steps; k++) {
    const x = from.x + ((to.x - from.x) * k) / steps; const y = from.y + ((to.y - from.y) * k) / steps;
    await client.send('Input.dispatchTouchEvent', { type: 'touchMove', touchPoints: [{ x, y }] });
  }
  await client.send('Input.dispatchTouchEvent', { type: 'touchEnd', touchPoints: [] });
  await client.detach();
}
async function drag(page, mobile, from, to) {
  if (mobile) { await touchDrag(page, from, to); return; }
  await page.mouse.move(from.x, from.y);
  await page.mouse.down();
  await page.mouse.move(to.x, to.y, { steps: 6 });
  await page.mouse.up();
}

// The crank-rocker's A grabbed at crank 90 deg: the drawing goes back to the start pose and says
// so, the model unchanged (A had ended at [119.06, 0], far from the finger); dragged there, A
// ends under the finger.
async function dragAtPose(page, ctx) {
  const { mobile } = ctx;
  await ctx.openExample(page, mobile, 'fourbar-crank-rocker');
  await page.locator('#scrub').fill('90');
  await scrollToDrawing(page);
  const text = () => page.locator('.cm-content').textContent();
  const before = await text();
  const a90 = await page.locator('#drawing circle.pt[data-point="A"]').boundingBox();
  const from = { x: a90.x + a90.width / 2, y: a90.y + a90.height / 2 };
  await drag(page, mobile, from, { x: from.x + 40, y: from.y });
  assert.equal(await page.locator('#scrub').inputValue(), '0', 'back at the start pose');
  assert.match(await page.locator('#status').textContent(), /^Points are edited at the start pose \(sample 0\)/);
  await page.waitForTimeout(300);
  assert.equal(await text(), before, 'the model is not edited by a drag at another pose');
  await ctx.shot(page, `${ctx.tag}-f5-drag-back-to-start`);
  const a0 = await page.locator('#drawing circle.pt[data-point="A"]').boundingBox();
  const start = { x: a0.x + a0.width / 2, y: a0.y + a0.height / 2 };
  const finger = { x: start.x + 30, y: start.y - 25 };
  const wanted = await toModel(page, finger.x, finger.y);
  const perPixel = await page.evaluate(() => 1 / document.querySelector('#drawing svg').getScreenCTM().a);
  await drag(page, mobile, start, finger);
  await page.waitForFunction((b) => document.querySelector('.cm-content').textContent !== b && !document.body.dataset.busy, before);
  const line = await page.locator('.cm-line', { hasText: /^ *A: / }).first().textContent();
  const [x, y] = line.match(/\[([-\d.]+), ([-\d.]+)\]/).slice(1).map(Number);
  close(x, wanted.x, 1.5 * perPixel, 'A.x under the finger');
  close(y, wanted.y, 1.5 * perPixel, 'A.y under the finger');
  await ctx.shot(page, `${ctx.tag}-f5b-dragged-at-start`);
}

// Zoomed in 4x, a label is as tall on screen and a link's line as wide as at the fitted view.
async function zoomKeepsSizes(page, ctx) {
  const { mobile } = ctx;
  await ctx.openExample(page, mobile, 'fourbar-crank-rocker');
  await scrollToDrawing(page);
  const sizes = () => page.evaluate(() => {
    const svg = document.querySelector('#drawing svg');
    const label = svg.querySelector('g[data-group="labels"] text');
    const line = [...svg.querySelectorAll('.scene [stroke-width]')].find((e) => +e.getAttribute('stroke-width') >= 4);
    const k = svg.getScreenCTM().a;
    const lineCtm = line.getScreenCTM().a;
    const width = getComputedStyle(line).vectorEffect === 'non-scaling-stroke' ? +line.getAttribute('stroke-width') : +line.getAttribute('stroke-width') * lineCtm;
    return { label: label.getBoundingClientRect().height, line: width, k };
  });
  const fitted = await sizes();
  // The button's click (on a phone the tool bar scrolls sideways; pinching is the phone's way).
  for (let i = 0; i < 6; i++) await page.locator('#edit-tools [data-tool="zoom-in"]').dispatchEvent('click');
  const zoomed = await sizes();
  assert.ok(zoomed.k / fitted.k > 3, `zoomed in: ${zoomed.k / fitted.k}x`);
  close(zoomed.label, fitted.label, 0.15 * fitted.label, 'a label keeps its height on screen');
  close(zoomed.line, fitted.line, 0.01, "a link's line keeps its width on screen");
  await ctx.shot(page, `${ctx.tag}-f6-zoomed`);
  await page.locator('#edit-tools [data-tool="fit"]').dispatchEvent('click');
}

// On a phone, one finger drawn across the drawing's bottom 38 px pans it, as anywhere else: also
// while a failed analysis's "Not updated" label lies over that edge (it took the finger).
async function bottomPan(page, ctx) {
  await ctx.openExample(page, true, 'fourbar-crank-rocker');
  await panAtBottom(page, ctx);
  // A tap right after the test's touch drags can be taken as the second of a double tap.
  await page.waitForTimeout(500);
  await ctx.click(page, true, '[data-tab="editor"]');
  await ctx.retype(page, true, 'O4: [200, 0]', '0]', '0');
  await page.waitForSelector('#stale:not([hidden])');
  await panAtBottom(page, ctx);
  await ctx.click(page, true, '[data-tab="editor"]');
  await ctx.retype(page, true, 'O4: [200, 0 ', '0 ', '0] ');
  await page.waitForSelector('#stale', { state: 'hidden' });
}
async function panAtBottom(page, ctx) {
  await scrollToDrawing(page);
  const box = await page.locator('#drawing').boundingBox();
  const view = () => page.evaluate(() => document.querySelector('#drawing svg').viewBox.baseVal.x);
  // Across the width: the scale bar and its label are at the bottom left.
  for (const fromBottom of [36, 25, 10, 3]) {
    for (const along of [0.05, 0.12, 0.3, 0.9]) {
      const x0 = await view();
      const x = box.x + box.width * along; const y = box.y + box.height - fromBottom;
      const hit = await page.evaluate(([xx, yy]) => { const e = document.elementFromPoint(xx, yy); return `${e?.tagName}.${e?.getAttribute('class') ?? ''}`; }, [x, y]);
      const dx = along > 0.5 ? -40 : 40;
      await touchDrag(page, { x, y }, { x: x + dx, y });
      const x1 = await view();
      assert.ok(Math.abs(x1 - x0) > 1e-6 && Math.sign(x0 - x1) === Math.sign(dx), `a pan ${fromBottom} px above the drawing's bottom, ${along} along (on ${hit}), moved the view: ${x0} -> ${x1}`);
    }
  }
  // Upwards from the bottom edge too (a pan that starts as a swipe up).
  const viewY = () => page.evaluate(() => document.querySelector('#drawing svg').viewBox.baseVal.y);
  for (const fromBottom of [30, 5]) {
    const y0 = await viewY();
    const x = box.x + box.width * 0.5; const y = box.y + box.height - fromBottom;
    await touchDrag(page, { x, y }, { x, y: y - 50 });
    const y1 = await viewY();
    assert.ok(y1 > y0 + 1e-6, `a pan upwards from ${fromBottom} px above the drawing's bottom moved the view: ${y0} -> ${y1}`);
  }
  await ctx.shot(page, `${ctx.tag}-f7-bottom-pan${await page.locator('#stale').isVisible() ? '-stale' : ''}`);
  await page.locator('#edit-tools [data-tool="fit"]').dispatchEvent('click');
  await page.locator('#edit-tools [data-tool="fit"]').dispatchEvent('click');
}

export async function run(page, ctx) {
  const only = process.env.NBAR_FORCES_ONLY;  // while working on one check
  const checks = { curves, stressTable, explainAtPose, handlesOverArrows, dragAtPose, zoomKeepsSizes };
  if (ctx.mobile) checks.bottomPan = bottomPan;
  for (const [name, check] of Object.entries(checks)) {
    if (only && !only.split(',').includes(name)) continue;
    await check(page, ctx);
  }
}
