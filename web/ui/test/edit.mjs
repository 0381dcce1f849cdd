// Browser checks of model editing (run by browser.mjs at each viewport): a number edited in the
// Model tab's points table changes the YAML (its comment kept) and the solved numbers; a bad value
// gets the server's located error in its field; a point and two links added by tapping appear in
// the YAML and solve; undo and redo walk the edits back; a body tapped in the drawing opens its
// panel and becomes a steel bar; wheel or pinch zoom, pan and fit change the view.
import assert from 'node:assert/strict';
import { join } from 'node:path';

const yamlText = (page) => page.evaluate(() => [...document.querySelectorAll('#editor .cm-line')].map((l) => l.textContent).join('\n'));
const viewBox = (page) => page.evaluate(() => document.querySelector('#drawing svg').getAttribute('viewBox').split(' ').map(Number));
const field = (path) => `#model-tables input[data-path='${JSON.stringify(path)}']`;

// ctx: {base, out (screenshot directory), viewport ('desktop' or 'phone'), mobile}.
export async function run(page, ctx) {
  const tag = ctx.viewport;
  const mobile = !!ctx.mobile;
  const press = (selector) => (mobile ? page.locator(selector).first().tap() : page.locator(selector).first().click());
  const shot = (name) => page.screenshot({ path: join(ctx.out, `${tag}-${name}.png`) });
  // A tap (or click) on the drawing at a point given in model coordinates, or at a point's circle.
  const tapAt = async (x, y) => (mobile ? page.touchscreen.tap(x, y) : page.mouse.click(x, y));
  const centre = async (selector) => { const b = await page.locator(selector).first().boundingBox(); return [b.x + b.width / 2, b.y + b.height / 2]; };
  const settled = () => page.waitForFunction(() => !/Analysing/.test(document.querySelector('#status').textContent));

  await press('[data-tab="gallery"]');
  await press('[data-example="fourbar-crank-rocker"]');
  await page.waitForFunction(() => document.querySelector('#model-name').textContent === 'Crank-rocker four-bar');
  await settled();

  // 1. A coordinate typed in the points table: the YAML line changes in place, comment kept, and
  // the results table shows the new position of P.
  await press('[data-tab="model"]');
  await page.waitForSelector(field(['points', 'P', 1]));
  assert.equal(await page.locator(field(['points', 'P', 1])).inputValue(), '121.227931');
  await press('[data-rtab="table"]');
  const firstPy = () => page.locator('#table tbody tr').first().locator('td').last().textContent();
  assert.equal(await firstPy(), '121.23');
  await page.locator(field(['points', 'P', 1])).fill('150');
  await page.locator(field(['points', 'P', 1])).press('Enter');
  await page.waitForFunction(() => document.querySelector('#table tbody tr td:last-child')?.textContent === '150');
  const text = await yamlText(page);
  assert.match(text, /\n {2}P: {2}\[77\.81169, 150\] {21}# coupler point\n/, 'the line is rewritten in place, its comment where it was');
  assert.equal(await page.locator('#status').textContent(), '1 DOF · 361 samples');

  // 2. A bad value: the server's message, located, on the field that holds it.
  await page.locator(field(['points', 'A', 0])).fill('abc');
  await page.locator(field(['points', 'A', 0])).press('Enter');
  await page.waitForSelector(`${field(['points', 'A', 0])}.bad`);
  assert.match(await page.locator('#model-problem').textContent(), /^line 11, column 8: x must be a number, not 'abc'/);
  assert.equal(await page.locator('#model-tables .cell-error').textContent(), "x must be a number, not 'abc'");
  await shot('8-model-error');
  await page.locator(field(['points', 'A', 0])).fill('80');
  await page.locator(field(['points', 'A', 0])).press('Enter');
  await page.waitForFunction(() => !document.querySelector('#model-tables .cell.bad') && /DOF/.test(document.querySelector('#status').textContent));
  const before = await yamlText(page);
  assert.equal(before, text);

  // 2b. A number past a double's range (it wrote `Infinity` into the YAML): refused at its field,
  // which keeps what was typed, and the YAML is left as it was; a good value then takes it back.
  await page.locator(field(['points', 'B', 1])).fill('1e400');
  await page.locator(field(['points', 'B', 1])).press('Enter');
  await page.waitForSelector(`${field(['points', 'B', 1])}.bad`);
  const refusal = 'Cannot edit: 1e400 is beyond the range of a number (at most about 1.8e308 either way); the model is unchanged';
  assert.equal(await page.locator('#model-tables .cell-error').textContent(), refusal);
  assert.equal(await page.locator('#model-problem').textContent(), refusal);
  assert.equal(await page.locator(field(['points', 'B', 1])).inputValue(), '1e400');
  assert.equal(await yamlText(page), before, 'the YAML is unchanged');
  assert.doesNotMatch(await yamlText(page), /Infinity|\.inf/i);
  await shot('8b-number-refused');
  const by = await page.evaluate(() => document.querySelector('#editor .cm-content').textContent.match(/B: {2}\[[^,]+, ([^\]]+)\]/)[1]);
  await page.locator(field(['points', 'B', 1])).fill(by);
  await page.locator(field(['points', 'B', 1])).press('Enter');
  await page.waitForFunction(() => !document.querySelector('#model-tables .cell.bad') && !document.querySelector('#model-tables .cell-error'));
  assert.equal(await yamlText(page), before);

  // 3. A point placed by tapping, then two links from it to A and to B: a rigid triangle on the
  // coupler, so the linkage keeps one degree of freedom.
  // With grid snap on, the point lands on a grid line crossing.
  await press('#edit-tools [data-tool="point"]');
  await press('#edit-tools [data-tool="snap"]');
  const step = await page.evaluate(() => { const l = document.querySelectorAll('#drawing .edit-grid line'); return +l[1].getAttribute('x1') - +l[0].getAttribute('x1'); });
  assert.ok([1, 2, 5].some((m) => Math.abs(step / 10 ** Math.floor(Math.log10(step)) - m) < 1e-9), `grid step ${step}`);
  const box = await page.locator('#drawing').boundingBox();
  await tapAt(box.x + box.width * 0.12, box.y + box.height * 0.12);
  // The model cannot be solved with a point on no body: it is drawn as written (build-model.js),
  // the new point with the others, rather than a dashed mark over the old drawing dimmed.
  await page.waitForSelector('#drawing svg[data-sketch] circle.pt[data-point="P1"]');
  await shot('9a-point-snapped');
  await press('#edit-tools [data-tool="snap"]');
  const p1 = /\n {2}P1: \[(-?\d+(?:\.\d+)?), (-?\d+(?:\.\d+)?)\]\nground:/.exec(await yamlText(page));
  assert.ok(p1, 'P1 written after the other points');
  for (const v of [+p1[1], +p1[2]]) assert.ok(Math.abs(v / step - Math.round(v / step)) < 1e-9, `${v} on the ${step} grid`);
  await press('#edit-tools [data-tool="link"]');
  await tapAt(...await centre('#drawing circle.pt[data-point="P1"]'));
  await tapAt(...await centre('#drawing circle.pt[data-point="A"]'));
  // One link leaves the new point free to turn about A: the server says so, at the link's line.
  await page.waitForFunction(() => /link1/.test(document.querySelector('#problems').textContent));
  assert.match(await page.locator('#problems').textContent(), /^line 20, column 3: the mechanism has 2 degrees of freedom/);
  await tapAt(...await centre('#drawing circle.pt[data-point="P1"]'));
  await tapAt(...await centre('#drawing circle.pt[data-point="B"]'));
  await page.waitForFunction(() => document.querySelector('#drawing polyline.body[data-body="link2"]'));
  await settled();
  const added = await yamlText(page);
  assert.match(added, /\n {2}link1: \[P1, A\]\n {2}link2: \[P1, B\]\nlengths:/);
  assert.equal(await page.locator('#status').textContent(), '1 DOF · 361 samples');
  await shot('9-links-added');

  // 4. Undo three times: back to the text before; redo once: the point again.
  await press('#edit-tools [data-tool="undo"]');
  await page.waitForFunction(() => !/link2/.test(document.querySelector('#editor .cm-content').textContent));
  assert.match(await yamlText(page), /\n {2}link1: \[P1, A\]\nlengths:/);
  if (mobile) await press('#edit-tools [data-tool="undo"]');
  else { await page.locator('#readout').click(); await page.keyboard.press('Control+z'); }
  await page.waitForFunction(() => !/link1/.test(document.querySelector('#editor .cm-content').textContent));
  await press('#edit-tools [data-tool="undo"]');
  await page.waitForFunction((t) => [...document.querySelectorAll('#editor .cm-line')].map((l) => l.textContent).join('\n') === t, before);
  if (mobile) await press('#edit-tools [data-tool="redo"]'); else await page.keyboard.press('Control+Shift+z');
  await page.waitForFunction(() => /\n {2}P1: \[/.test([...document.querySelectorAll('#editor .cm-line')].map((l) => l.textContent).join('\n')));
  await press('#edit-tools [data-tool="undo"]');
  await page.waitForFunction((t) => [...document.querySelectorAll('#editor .cm-line')].map((l) => l.textContent).join('\n') === t, before);
  await settled();

  // 5. A body tapped in the drawing opens its panel; made a steel bar 8 thick, it has a mass.
  await press('#edit-tools [data-tool="select"]');
  const o4 = await centre('#drawing circle.pt[data-point="O4"]');
  const b = await centre('#drawing circle.pt[data-point="B"]');
  await tapAt((o4[0] + b[0]) / 2, (o4[1] + b[1]) / 2);
  await page.waitForSelector('[data-body-panel="rocker"]');
  await page.selectOption('[data-body-form]', 'bar');
  await page.waitForSelector('#model-tables input[data-bar-prop="width"]');
  assert.match(await yamlText(page), /\n {2}rocker:\n {4}points: \[O4, B\]\n {4}bar: \{width: 15\}\nlengths:/);
  await page.locator('[data-body-prop="thickness"]').fill('8');
  await page.locator('[data-body-prop="thickness"]').press('Enter');
  await page.waitForFunction(() => document.querySelector('[data-body-prop="thickness"]')?.value === '8');
  await page.locator('[data-body-prop="material"]').fill('steel');
  await page.locator('[data-body-prop="material"]').press('Enter');
  await page.waitForFunction(() => /material: steel/.test([...document.querySelectorAll('#editor .cm-line')].map((l) => l.textContent).join('\n')));
  await settled();
  assert.match(await yamlText(page), /\n {4}bar: \{width: 15\}\n {4}thickness: 8\n {4}material: steel\nlengths:/);
  assert.equal(await page.locator('#problems').textContent(), 'No errors.');
  // The server's mass of the bar: 7850 kg/m³ × 8 mm × (15 × (150 + 15) mm²) = 0.15543 kg.
  const mass = await page.evaluate(async (model) => (await (await fetch('/api/check', { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify({ model }) })).json()).bodies.find((x) => x.name === 'rocker').mass.mass, await yamlText(page));
  assert.ok(Math.abs(mass - 0.15543) < 1e-5, `rocker mass ${mass}`);
  await shot('10-body');

  // The coupler, opened from its name in the bodies table, made a plate: its outline starts as
  // the rectangle around A, B and P, 9 mm (half of a tenth of A-B = 180) clear of them.
  await press('#model-tables [data-select-body="coupler"]');
  await page.waitForSelector('[data-body-panel="coupler"]');
  await page.selectOption('[data-body-form]', 'shape');
  await page.waitForFunction(() => /shape:/.test(document.querySelector('#editor .cm-content').textContent));
  assert.match(await yamlText(page), /\n {2}coupler:\n {4}points: \[A, B, P\]\n {4}shape: \{outline: \[\[68\.8117, -9\], \[190\.25, -9\], \[190\.25, 159\], \[68\.8117, 159\]\]\}\n/);
  await settled();
  assert.match(await page.locator('#problems').textContent(), /coupler/, 'a plate without thickness is an error the server places');
  await press('[data-close-body]');
  await press('#edit-tools [data-tool="undo"]');
  await page.waitForFunction(() => !/shape:/.test(document.querySelector('#editor .cm-content').textContent));
  await settled();
  assert.equal(await page.locator('#problems').textContent(), 'No errors.');

  // 6. Zoom (wheel on a desktop, pinch on a phone), pan, and fit.
  const fitted = await viewBox(page);
  const d = await page.locator('#drawing').boundingBox();
  const cx = d.x + d.width / 2; const cy = d.y + d.height / 2;
  if (mobile) {
    await page.evaluate(([x, y]) => {
      const target = document.querySelector('#drawing svg');
      const ev = (type, id, px) => target.dispatchEvent(new PointerEvent(type, { pointerId: id, pointerType: 'touch', clientX: px, clientY: y, bubbles: true, isPrimary: id === 11 }));
      ev('pointerdown', 11, x - 40); ev('pointerdown', 12, x + 40);
      ev('pointermove', 11, x - 80); ev('pointermove', 12, x + 80);
      ev('pointerup', 11, x - 80); ev('pointerup', 12, x + 80);
    }, [cx, cy]);
  } else {
    await page.mouse.move(cx, cy);
    await page.mouse.wheel(0, -462);  // exp(-462 × 0.0015) = 1/2
  }
  const zoomed = await viewBox(page);
  assert.ok(Math.abs(zoomed[2] / fitted[2] - 0.5) < 0.02, `zoomed to half the width: ${zoomed[2]} of ${fitted[2]}`);
  await shot('11-zoomed');
  if (!mobile) {
    await page.mouse.move(cx, cy); await page.mouse.down();
    await page.mouse.move(cx + 100, cy, { steps: 4 }); await page.mouse.up();
    const panned = await viewBox(page);
    assert.ok(panned[0] < zoomed[0], 'dragging right shows what is left of the view');
  }
  await press('#edit-tools [data-tool="fit"]');
  assert.deepEqual(await viewBox(page), fitted);

  // 7. A body deleted from its panel goes with its exact length; B is then left on the coupler
  // alone and the four-bar is a free dyad: the server says so. Undo brings it back as it was.
  const whole = await yamlText(page);
  await press('#model-tables [data-select-body="rocker"]');
  await press('[data-delete-body]');
  await page.waitForFunction(() => !/bodies:[^]*\n {2}rocker:/.test([...document.querySelectorAll('#editor .cm-line')].map((l) => l.textContent).join('\n')));
  assert.match(await yamlText(page), /\nlengths: \{crank: 80\}\n/);
  await page.waitForFunction(() => /degrees of freedom/.test(document.querySelector('#problems').textContent));
  await press('#edit-tools [data-tool="undo"]');
  await page.waitForFunction((t) => [...document.querySelectorAll('#editor .cm-line')].map((l) => l.textContent).join('\n') === t, whole);
  await settled();
}
