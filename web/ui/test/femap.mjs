// Browser check of the FE stress map and its read-out (stress-map.js), run by browser.mjs at a
// desktop and a phone viewport: the ANSYS plate four-bar's map at a step, the pointer (a mouse, or
// a finger held on the map) on a point of the coupler, and the number shown against the command
// line's `nbar stress --method fe --at X,Y --coordinates model` at the point the read-out names;
// a point off every link; the peaks' table with its flat_from, flat_to and flat_arc columns; a
// model without plates, whose error the read-out gives at its line and column.
// run(page, ctx) with ctx = {mobile, tag, base, nbar, shot, click, openExample}.
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { mkdtempSync, writeFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';

const example = async (base, name) => (await fetch(new URL(`api/examples/${name}`, base))).text();
async function post(base, path, body) {
  const r = await fetch(new URL(path, base), { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(body) });
  assert.ok(r.ok, `${path}: ${r.status}`);
  return r.json();
}

// The command line's von Mises stress of `link` at (x, y), model coordinates, at `step`.
function cliVonMises(nbar, file, link, step, x, y) {
  const args = ['stress', file, '--method', 'fe', '--format', 'json', '--section-profile', link,
    '--step', String(step), '--coordinates', 'model', `--at=${x},${y}`];
  const run = spawnSync(nbar, args, { encoding: 'utf8' });
  assert.equal(run.status, 0, `nbar ${args.join(' ')}: ${run.stderr}`);
  const t = JSON.parse(run.stdout);
  return t.rows[0][t.columns.indexOf('von_mises')];
}

// The screen point of a model point (y up) on the map's drawing.
async function screenPoint(page, x, y) {
  return page.locator('#femap-drawing svg').evaluate((svg, [mx, my]) => {
    const p = new DOMPoint(mx, -my).matrixTransform(svg.getScreenCTM());
    return { x: p.x, y: p.y };
  }, [x, y]);
}

// A mouse moved there, or a finger put down there and held.
async function pointAt(page, mobile, at) {
  if (mobile) {
    const client = await page.context().newCDPSession(page);
    const touch = [{ x: at.x, y: at.y }];
    await client.send('Input.dispatchTouchEvent', { type: 'touchStart', touchPoints: touch });
    await page.waitForTimeout(150);
    await client.send('Input.dispatchTouchEvent', { type: 'touchEnd', touchPoints: [] });
    await client.detach();
  } else {
    await page.mouse.move(at.x - 3, at.y - 3);
    await page.mouse.move(at.x, at.y);
  }
}

export async function run(page, ctx) {
  const { mobile, tag, base, nbar } = ctx;
  const name = 'fourbar-ansys-plates';
  await ctx.openExample(page, mobile, name);
  const step = 6;
  await page.locator('#scrub').fill(String(step));
  await ctx.click(page, mobile, '[data-overlay="femap"]');
  await page.waitForSelector(`#femap-drawing svg[data-step="${step}"]`);
  // The map and its read-out in view together (the screenshot shows both).
  await page.locator('#probe').evaluate((el) => el.scrollIntoView({ block: 'end' }));
  const box = await page.locator('#femap-drawing').boundingBox();

  // The coupler's middle at this step: halfway from A to B, where the solve has them.
  const model = await example(base, name);
  const solve = await post(base, '/api/solve', { model, columns: ['A.x', 'A.y', 'B.x', 'B.y'] });
  const [ax, ay, bx, by] = solve.rows[step];
  const seen = { x: (ax + bx) / 2 + 0.1 * (by - ay) / 1.5, y: (ay + by) / 2 - 0.1 * (bx - ax) / 1.5 };
  await pointAt(page, mobile, await screenPoint(page, seen.x, seen.y));
  await page.waitForSelector('#probe[data-state="on"]');
  const shown = await page.locator('#probe').evaluate((el) => ({ text: el.textContent, ...el.dataset }));
  assert.equal(shown.link, 'coupler', `${tag}: the read-out names the coupler: ${shown.text}`);
  // The map never moved under the pointer.
  assert.deepEqual(await page.locator('#femap-drawing').boundingBox(), box, `${tag}: the map stayed where it was`);

  const dir = mkdtempSync(join(tmpdir(), 'nbar-femap-'));
  try {
    const file = join(dir, `${name}.yaml`);
    writeFileSync(file, model);
    const expected = cliVonMises(nbar, file, 'coupler', step, shown.modelX, shown.modelY);
    assert.ok(expected > 0);
    assert.ok(Math.abs(+shown.vonMises - expected) <= 1e-9 * expected, `${tag}: ${shown.vonMises} MPa shown, the CLI says ${expected}`);
    // The number on screen is that value to four significant digits, with its unit.
    const text = `${Number(expected.toPrecision(4))} MPa von Mises`;
    assert.ok(shown.text.includes(text), `${tag}: "${shown.text}" shows "${text}"`);
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
  // The point where the model draws the coupler: its middle as drawn, 0.1 m to its right.
  const [a0, b0] = [[0.5, 0.8660254038], [1.8623724357, 1.4936742197]];
  assert.ok(Math.abs(+shown.modelX - ((a0[0] + b0[0]) / 2 + 0.1 * (b0[1] - a0[1]) / 1.5)) < 1e-6, `${tag}: model x ${shown.modelX}`);
  assert.ok(Math.abs(+shown.modelY - ((a0[1] + b0[1]) / 2 - 0.1 * (b0[0] - a0[0]) / 1.5)) < 1e-6, `${tag}: model y ${shown.modelY}`);
  await ctx.shot(page, `${tag}-femap-1-coupler`);

  // Off every link: the read-out says so, with no number.
  const corner = await screenPoint(page, ...(await page.locator('#femap-drawing svg').evaluate((svg) => {
    const v = svg.viewBox.baseVal;
    return [v.x + 0.02 * v.width, -(v.y + v.height * 0.98)];
  })));
  await pointAt(page, mobile, corner);
  await page.waitForSelector('#probe[data-state="off"]');
  assert.match(await page.locator('#probe').textContent(), /not on a link$/);

  // Each link's FE peak with the arc where it is flat (the core's numbers), every column in view.
  const peaks = await post(base, '/api/stress', { model, method: 'fe' });
  await page.waitForSelector('.femap-table');
  for (const k of ['flat_from', 'flat_to', 'flat_arc']) {
    assert.equal(await page.locator(`.femap-table thead th:has-text("${k}")`).count(), 1, `${tag}: a ${k} column`);
  }
  const crank = peaks.links.find((l) => l.body === 'crank');
  const arc = await page.locator('.femap-table tbody tr:has(th:text-is("crank")) td[data-col="flat_arc"]').textContent();
  assert.equal(arc, Number.isFinite(crank.flat_arc) ? String(+crank.flat_arc.toFixed(crank.flat_arc >= 100 ? 2 : 4)) : '–');
  await page.locator('.femap-table').scrollIntoViewIfNeeded();
  const sideways = await page.locator('#femap-peaks').evaluate((el) => el.scrollWidth - el.clientWidth);
  assert.ok(sideways <= 1, `${tag}: the peaks' table fits its width (${sideways} px over)`);
  await ctx.shot(page, `${tag}-femap-2-peaks`);
  const width = await page.evaluate(() => document.documentElement.scrollWidth);
  assert.ok(width <= page.viewportSize().width, `${tag}: no sideways scrolling (page is ${width} px wide)`);

  // A model without plates: the core's error at its line and column, in the read-out.
  await ctx.openExample(page, mobile, 'fourbar-crank-rocker');
  await page.waitForSelector('#probe[data-state="error"]');
  assert.match(await page.locator('#probe').textContent(), /^line 16, column 3: no link has a shape/);
  assert.equal(await page.locator('#femap-drawing svg').count(), 0, `${tag}: no map of the plates before`);
  await ctx.click(page, mobile, '[data-overlay="femap"]');
}
