// A new user's run (run by browser.mjs at a phone's 390×844 by touch and a laptop's 1366×768):
// a slider-crank built from New → Empty model with the drawing tools alone, no typing in the YAML.
// Checked on the way: the blank model says `units: mm` and its drawing's scale bar says mm; each
// link is drawn as soon as it is made, with the mobility the core counts, and no dimmed old model
// beneath; the Model tab's joints are the new model's, never the last one that solved; a slider on
// the connecting rod is refused with the core's reason; the ground tool toggles a point between a
// revolute and a ground pivot; the slider tool makes the block and its guide in one gesture; with
// a driver added the model solves, and its stroke is the closed form 2r for a centred slider-crank.
// Then the editor emptied under a drawing in mm: a point tapped there is written in mm; and the
// five-point task's pivot at the origin with a target point put there is noted.
import assert from 'node:assert/strict';

const yamlText = (page) => page.evaluate(() => [...document.querySelectorAll('#editor .cm-line')].map((l) => l.textContent).join('\n'));
const settled = (page) => page.waitForFunction(() => !document.body.dataset.busy);
const note = (page) => page.locator('#stale span').textContent();

// Where model point (x, y) is on the screen, from the drawing's own transform (newuser.mjs taps
// through it too).
export function screenOf(page, x, y) {
  return page.evaluate(([mx, my]) => {
    const svg = document.querySelector('#drawing svg');
    const p = new DOMPoint(mx, -my).matrixTransform(svg.getScreenCTM());
    return [p.x, p.y];
  }, [x, y]);
}

// One tap (a finger on the phone, the mouse on the laptop) at model point (x, y), then the
// analysis of the edit it makes waited for.
async function tapModel(page, mobile, x, y) {
  const [cx, cy] = await screenOf(page, x, y);
  if (mobile) await page.touchscreen.tap(cx, cy); else await page.mouse.click(cx, cy);
  await page.waitForTimeout(50);
  await settled(page);
}

async function tool(page, ctx, name) {
  await ctx.click(page, ctx.mobile, `#edit-tools [data-tool="${name}"]`);
  assert.equal(await page.locator(`#edit-tools [data-tool="${name}"]`).getAttribute('aria-pressed'), 'true');
}

// Waits for the text to change from `before` and its analysis to end.
async function edited(page, before) {
  await page.waitForFunction((b) => [...document.querySelectorAll('#editor .cm-line')].map((l) => l.textContent).join('\n') !== b, before);
  await settled(page);
}

export async function run(page, ctx) {
  const { mobile, tag, shot, click } = ctx;
  const started = Date.now();
  // The model on screen before: the crank-rocker, whose joints must not linger.
  await ctx.openExample(page, mobile, 'fourbar-crank-rocker');

  // 1. New → Empty model: the unit written, the drawing empty in mm, no old model dimmed.
  await click(page, mobile, '#new-menu summary');
  const opened = await page.evaluate(() => +(document.body.dataset.opened ?? 0));
  await click(page, mobile, '#new-empty');
  await page.waitForFunction((n) => +(document.body.dataset.opened ?? 0) > n && !document.body.dataset.busy, opened);
  let text = await yamlText(page);
  assert.match(text, /^units: \{length: mm, angle: deg\}$/m, 'the blank model says its unit');
  await page.waitForSelector('#drawing svg[data-sketch="1"]');
  assert.equal(await page.locator('#drawing svg .scale-bar text').textContent().then((s) => s.split(' ')[1]), 'mm');
  assert.equal(await page.locator('#drawing svg circle.pt').count(), 0, 'no point yet');
  assert.equal(await page.locator('#drawing svg .scene:not(.sketch)').count(), 0, 'the old drawing is gone, not dimmed beneath');
  assert.equal(await page.evaluate(() => getComputedStyle(document.querySelector('#drawing')).opacity), '1');
  assert.match(await note(page), /^Building · 0 DOF/);
  await shot(page, `${tag}-b1-empty`);

  // 2. The crank: a ground pivot at the origin, then a link from it to (60, 80) (r = 100); snap
  // on, so that the taps land on the grid (20 mm: the new model's view is 400 mm across).
  await click(page, mobile, '#edit-tools [data-tool="snap"]');
  await tool(page, ctx, 'ground');
  text = await yamlText(page);
  await tapModel(page, mobile, 0, 0);
  await edited(page, text);
  text = await yamlText(page);
  assert.match(text, /P1: \[0, 0\]/);
  assert.match(text, /ground:\n\s+- P1|ground: \[P1\]/);
  await tool(page, ctx, 'link');
  await tapModel(page, mobile, 0, 0);
  await tapModel(page, mobile, 60, 80);
  await edited(page, text);
  // Drawn at once, under-constrained: the link, its points, and the core's count of freedoms.
  await page.waitForSelector('#drawing svg[data-sketch="1"] path.body[data-body="link1"]', { state: 'attached' });
  assert.match(await note(page), /^Building · 1 DOF · the mechanism has 1 degree of freedom .* but 0 drivers are given/);
  await shot(page, `${tag}-b2-crank`);

  // 3. The connecting rod to (200, 0): 2 DOF, still drawn.
  text = await yamlText(page);
  await tapModel(page, mobile, 60, 80);
  await tapModel(page, mobile, 200, 0);
  await edited(page, text);
  await page.waitForSelector('#drawing svg[data-sketch="1"] path.body[data-body="link2"]', { state: 'attached' });
  assert.match(await note(page), /^Building · 2 DOF/);
  // The joints listed are this model's, not the crank-rocker's.
  await click(page, mobile, '[data-tab="model"]');
  const joints = await page.locator('#model-tables td.note').allTextContents();
  assert.deepEqual(joints, ['revolute P1 (ground/link1)', 'revolute P2 (link1/link2)']);
  await shot(page, `${tag}-b3-rod-joints`);

  // 4. The ground tool toggles a point: P2 on the ground, then a revolute again.
  await tool(page, ctx, 'ground');
  text = await yamlText(page);
  await tapModel(page, mobile, 60, 80);
  await edited(page, text);
  assert.ok((await page.locator('#drawing svg circle.pt[data-point="P2"]').getAttribute('data-ground')) === 'true', 'P2 grounded');
  text = await yamlText(page);
  await tapModel(page, mobile, 60, 80);
  await edited(page, text);
  assert.ok((await page.locator('#drawing svg circle.pt[data-point="P2"]').getAttribute('data-ground')) === 'false', 'P2 free again');
  assert.match(await note(page), /^Building · 2 DOF/);

  // 5. A slider on the connecting rod (the Model tab's form, along two ground points) leaves
  // nothing free: refused with the core's reason, the text unchanged.
  text = await yamlText(page);
  await tapModel(page, mobile, -40, 0);
  await edited(page, text);
  text = await yamlText(page);
  await tapModel(page, mobile, 300, 0);
  await edited(page, text);
  text = await yamlText(page);
  await click(page, mobile, '[data-tab="model"]');
  await page.selectOption('[data-adder="slider"] [data-add="body"]', 'link2');
  await page.selectOption('[data-adder="slider"] [data-add="point"]', 'P3');
  await page.selectOption('[data-adder="slider"] [data-add="along0"]', 'P4');
  await page.selectOption('[data-adder="slider"] [data-add="along1"]', 'P5');
  await click(page, mobile, '[data-add-go="slider"]');
  await page.waitForFunction(() => /Cannot add this slider/.test(document.querySelector('#status').textContent));
  assert.match(await page.locator('#status').textContent(), /^Cannot add this slider: the joints leave no freedom: 0 degrees of freedom/);
  assert.equal(await yamlText(page), text, 'the refused slider is not written');
  assert.match(await page.locator('[data-adder="slider"] .cell-error').textContent(), /^Cannot add this slider: the joints leave no freedom/);
  await shot(page, `${tag}-b4-rod-refused`);
  // The two guide points go again (undo), for the slider tool's own.
  await click(page, mobile, '#edit-tools [data-tool="undo"]');
  await edited(page, text);
  const withOne = await yamlText(page);
  await click(page, mobile, '#edit-tools [data-tool="undo"]');
  await edited(page, withOne);

  // 6. The slider tool: tap the rod's end, then the guide's direction: block and guide at once.
  await tool(page, ctx, 'slider');
  text = await yamlText(page);
  await tapModel(page, mobile, 200, 0);
  await tapModel(page, mobile, 300, 0);
  await edited(page, text);
  text = await yamlText(page);
  assert.match(text, /block1: \[P3\]/);
  assert.match(text, /sliders:\n\s+- \{ ?body: block1, point: P3, along: \[ ?G1, G2 ?\] ?\}/);
  assert.match(text, /G1: \[100, 0\]/);
  assert.match(text, /G2: \[300, 0\]/);
  assert.match(await note(page), /^Building · 1 DOF · the mechanism has 1 degree of freedom/);
  await shot(page, `${tag}-b5-slider`);

  // 7. A driver on the crank (the Model tab's form): the model solves.
  await click(page, mobile, '[data-tab="model"]');
  await page.selectOption('[data-adder="driver"] [data-add="body"]', 'link1');
  await click(page, mobile, '[data-add-go="driver"]');
  await edited(page, text);
  await page.waitForFunction(() => /^1 DOF · \d+ samples$/.test(document.querySelector('#status').textContent));
  assert.equal(await page.locator('#drawing svg[data-sketch]').count(), 0, 'the solved drawing replaces the sketch');
  assert.ok(await page.locator('#stale').isHidden());
  text = await yamlText(page);
  assert.match(text, /^units: \{length: mm, angle: deg\}$/m, 'still in mm');

  // The stroke: the core's and the sweep's against 2r (a centred slider-crank, r = |P1 P2| = 100).
  assert.match(text, /P2: \[60, 80\]/);
  const r = 100;
  const got = await page.evaluate(async (model) => {
    const post = (path, body) => fetch(path, { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(body) }).then((a) => a.json());
    const check = await post('/api/check', { model });
    const solve = await post('/api/solve', { model, columns: 'P3.x' });
    const xs = solve.rows.map((row) => row[solve.columns.indexOf('P3.x')]);
    return { units: check.units.length, stroke: check.slider_cranks?.[0]?.stroke, swept: Math.max(...xs) - Math.min(...xs) };
  }, text);
  assert.equal(got.units, 'mm');
  assert.ok(Math.abs(got.stroke - 2 * r) < 1e-9, `check's stroke ${got.stroke} = 2r = ${2 * r}`);
  assert.ok(Math.abs(got.swept - 2 * r) < 1e-6, `the sweep's stroke ${got.swept} = 2r = ${2 * r}`);

  // 7b. A field being typed in when an analysis ends (the last field's edit solved while the next
  // is typed) keeps what was typed, the caret and the focus as the tables are drawn again; Enter
  // then commits it.
  const field = page.getByLabel('P2 x', { exact: true });
  await field.scrollIntoViewIfNeeded();
  if (mobile) await field.tap(); else await field.click();
  await field.press('Control+a');
  await page.keyboard.type('61');
  const replaced = await field.elementHandle();
  await page.evaluate(() => document.dispatchEvent(new CustomEvent('nbar:analysed', { detail: { error: null } })));
  assert.ok(await page.evaluate((old) => !old.isConnected, replaced), 'the tables were drawn again');
  const typedAfter = await page.evaluate(() => {
    const f = document.activeElement;
    return { label: f?.getAttribute('aria-label'), value: f?.value, caret: f?.selectionStart };
  });
  assert.deepEqual(typedAfter, { label: 'P2 x', value: '61', caret: 2 }, 'the typing survives the tables drawn again');
  await page.keyboard.press('Enter');
  await edited(page, text);
  text = await yamlText(page);
  assert.match(text, /P2: \[61, 80\]/, 'and Enter commits it');
  await click(page, mobile, '[data-tab="editor"]');
  await shot(page, `${tag}-b6-solved`);
  const took = (Date.now() - started) / 1000;

  // 8. The editor emptied by hand under a drawing in mm: a point tapped on that drawing is
  // written with the drawing's unit, not read as metres (the reader's default).
  await ctx.openExample(page, mobile, 'fourbar-crank-rocker');
  await click(page, mobile, '[data-tab="editor"]');
  const line = page.locator('.cm-line').first();
  if (mobile) await line.tap(); else await line.click();
  await page.keyboard.press('Control+a');
  await page.keyboard.press('Delete');
  await page.waitForFunction(() => document.querySelector('#editor .cm-content').textContent === '');
  await page.waitForFunction(() => /^Failed/.test(document.querySelector('#status').textContent));
  await settled(page);
  assert.match(await page.locator('#status').textContent(), /^Failed: line 1, column 1: the file holds no model/);
  await tool(page, ctx, 'point');
  await tapModel(page, mobile, 50, 50);
  await edited(page, '');
  text = await yamlText(page);
  assert.match(text, /^points:\n {2}P1: \[[-\d.]+, [-\d.]+\]\nunits:\n {2}length: mm\n {2}angle: deg\n?$/, text);
  await page.waitForSelector('#drawing svg[data-sketch="1"][data-unit="mm"] circle.pt[data-point="P1"]');
  assert.equal(await page.locator('#drawing svg .scale-bar text').textContent().then((s) => s.split(' ')[1]), 'mm');
  await shot(page, `${tag}-b7-units-kept`);
  await tool(page, ctx, 'select');

  // 9. The synthesis task's pivot a, at the origin, with a target point put there: the run says so.
  await click(page, mobile, '[data-tab="synthesis"]');
  const task = await page.locator('#task').inputValue();
  assert.match(task, /a: \[0, 0\]/);
  await page.locator('#task').fill(task.replace('[-56.040, 164.598]', '[0, 0]'));
  await click(page, mobile, '#synth-run');
  await page.waitForFunction(() => /designs?|solutions?/.test(document.querySelector('#synth-status').textContent) && !document.querySelector('#synth-run').disabled, null, { timeout: 60000 });
  assert.match(await page.locator('#synth-status').textContent(), /pivot a is at target point 4 \(0, 0 mm\): the coupler point would pass through a fixed pivot/);
  await page.locator('#synth-status').scrollIntoViewIfNeeded();
  await shot(page, `${tag}-b8-pivot-on-target`);

  console.log(`${tag}: slider-crank built from an empty model in ${took.toFixed(1)} s; stroke ${got.stroke} mm (2r = ${2 * r})`);
}
