// Browser checks of the files and of the Model tab's adding and renaming (run by browser.mjs at
// each viewport): a template from the New menu opens and solves; a model file given to the Open
// button, or dropped on the app, opens and solves, and a file that is not text, too large or not
// a model file is refused with a message; the JSON download is the /api/solve answer, with the
// CSV's columns and numbers; a driver, a force and a slider added in the tables appear in the
// YAML; a point renamed is renamed in every reference, and a rename that cannot be done safely
// is refused; with snap on, a dragged point's preview sits on the grid.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';

const yamlText = (page) => page.evaluate(() => [...document.querySelectorAll('#editor .cm-line')].map((l) => l.textContent).join('\n'));
const statusText = (page) => page.locator('#status').textContent();
const settled = (page) => page.waitForFunction(() => !/Analysing|Loading/.test(document.querySelector('#status').textContent));

async function openTemplate(page, press, name, title) {
  await press('[data-tab="gallery"]');
  await press('#new-menu > summary');
  await page.waitForSelector(`[data-template="${name}"]`, { state: 'visible' });
  const opened = await page.evaluate(() => +(document.body.dataset.opened ?? 0));
  await press(`[data-template="${name}"]`);
  await page.waitForFunction((n) => +(document.body.dataset.opened ?? 0) > n && !document.body.dataset.busy, opened);
  assert.equal(await page.locator('#model-name').textContent(), title);
  await settled(page);
}

// ctx: {mobile, tag, base, shot, click}.
export async function run(page, ctx) {
  const { mobile, tag } = ctx;
  const press = (selector) => ctx.click(page, mobile, selector);

  // 1. New from a template: every template is in the menu; the slider-crank opens and solves.
  await press('[data-tab="gallery"]');
  await press('#new-menu > summary');
  const templates = await page.locator('[data-template]').evaluateAll((l) => l.map((b) => b.dataset.template));
  assert.deepEqual(templates, ['template-four-bar', 'template-slider-crank', 'template-inverted-slider-crank',
    'template-five-bar', 'template-watt-six-bar', 'template-stephenson-six-bar']);
  await ctx.shot(page, `${tag}-files-1-new-menu`);
  await press('#new-menu > summary');
  await openTemplate(page, press, 'template-slider-crank', 'Slider-crank');
  assert.equal(await statusText(page), '1 DOF · 181 samples');
  assert.equal(await page.locator('#drawing svg g[data-link="slider"] > polygon.body').count(), 1, 'the slider block is drawn');
  await openTemplate(page, press, 'template-five-bar', 'Five-bar');
  assert.equal(await statusText(page), '2 DOF · 181 samples');
  await ctx.shot(page, `${tag}-files-2-template`);

  // 2. A model file chosen with the Open button: into the editor, analysed.
  const fourBar = await (await fetch(`${ctx.base}api/examples/template-four-bar`)).text();
  const mine = fourBar.replace('name: "Four-bar"', 'name: "My four-bar"');
  await press('[data-tab="gallery"]');
  const [chooser] = await Promise.all([page.waitForEvent('filechooser'), press('#open-button')]);
  await chooser.setFiles({ name: 'my-four-bar.yaml', mimeType: 'application/yaml', buffer: Buffer.from(mine) });
  await page.waitForFunction(() => document.querySelector('#model-name').textContent === 'My four-bar');
  await settled(page);
  assert.equal(await statusText(page), '1 DOF · 181 samples');
  assert.equal(await yamlText(page), mine);
  // An emptied editor is no model: the server says so at line 1, and the results still on screen
  // are marked as not the text's (they stayed, called current, and the CSV was the old model's).
  await press('[data-tab="editor"]');
  await press('#editor .cm-content');
  await page.keyboard.press('Control+a');
  await page.keyboard.press('Delete');
  await page.waitForFunction(() => /holds no model/.test(document.querySelector('#problems').textContent));
  assert.ok(await page.evaluate(() => document.body.classList.contains('results-stale')), 'stale results are marked');
  await page.keyboard.press('Control+z');
  await page.waitForFunction(() => !document.body.classList.contains('results-stale'));
  await settled(page);
  assert.equal(await yamlText(page), mine);
  // Files that are no model: refused, with the reason, and the model on screen stays.
  const refused = async (file, pattern) => {
    await page.setInputFiles('#open-file', file);
    await page.waitForFunction((p) => new RegExp(p).test(document.querySelector('#status').textContent), pattern.source);
    assert.ok(await page.locator('#status.bad').count(), 'the refusal is marked as an error');
    assert.equal(await page.locator('#model-name').textContent(), 'My four-bar');
  };
  await refused({ name: 'binary.yaml', mimeType: 'application/yaml', buffer: Buffer.from([0x6e, 0x61, 0xff, 0xfe, 0x00, 0x01]) },
    /^binary\.yaml is not text \(UTF-8\)/);
  await refused({ name: 'huge.yaml', mimeType: 'application/yaml', buffer: Buffer.alloc(1100 * 1024, 0x61) },
    /^huge\.yaml is too large \(1100 KiB\): a model file is at most 1024 KiB$/);
  await refused({ name: 'photo.png', mimeType: 'image/png', buffer: Buffer.from([0x89, 0x50, 0x4e, 0x47]) },
    /^photo\.png is not a model file/);
  // A file dropped on the drawing opens as well (JSON is a model format too).
  await page.evaluate(() => {
    const model = { name: 'Dropped', points: { O: [0, 0], A: [10, 0] }, ground: ['O'], bodies: { crank: ['O', 'A'] },
      drivers: [{ angle: 'crank', from: 0, to: 90 }], sweep: { steps: 10 } };
    const data = new DataTransfer();
    data.items.add(new File([JSON.stringify(model, null, 2)], 'dropped.json', { type: 'application/json' }));
    document.querySelector('#drawing').dispatchEvent(new DragEvent('drop', { dataTransfer: data, bubbles: true, cancelable: true }));
  });
  await page.waitForFunction(() => document.querySelector('#model-name').textContent === 'Dropped');
  await settled(page);
  assert.equal(await statusText(page), '1 DOF · 10 samples');

  // 3. The JSON download is the solve's answer; its columns and numbers are the CSV's.
  await openTemplate(page, press, 'template-four-bar', 'Four-bar');
  await press('[data-tab="downloads"]');
  const [jsonFile] = await Promise.all([page.waitForEvent('download'), press('[data-download="json"]')]);
  assert.equal(jsonFile.suggestedFilename(), 'four-bar.json');
  const answer = readFileSync(await jsonFile.path(), 'utf8');
  const direct = await (await fetch(`${ctx.base}api/solve`, { method: 'POST', body: JSON.stringify({ model: fourBar }) })).text();
  assert.equal(answer, direct, 'the download is the API\'s answer, byte for byte');
  const solved = JSON.parse(answer);
  const [csvFile] = await Promise.all([page.waitForEvent('download'), press('[data-download="csv"]')]);
  const csvText = readFileSync(await csvFile.path(), 'utf8');
  const directCsv = await (await fetch(`${ctx.base}api/solve`, { method: 'POST', body: JSON.stringify({ model: fourBar, format: 'csv' }) })).text();
  assert.equal(csvText, directCsv, 'the CSV is the core\'s writer\'s, as `nbar solve` writes it');
  const csv = csvText.trim().split('\n').map((l) => l.split(','));
  assert.deepEqual(solved.columns, csv[0]);
  assert.equal(solved.rows.length, 181);
  assert.equal(csv.length - 1, solved.rows.length);
  const k = solved.columns.indexOf('P.y');
  assert.ok(k > 0);
  assert.ok(Math.abs(+csv[91][k] - solved.rows[90][k]) <= 1e-12 * Math.abs(solved.rows[90][k]));
  assert.ok(Math.abs(solved.rows[0][k] - 121.227931) < 1e-6, `P.y at the start: ${solved.rows[0][k]}`);
  // With an editor that holds no model, the results on screen stay (marked stale) and so do their
  // downloads: the CSV is theirs (it was an error, from the editor's text), the model file the
  // editor's text.
  await press('[data-tab="editor"]');
  await page.locator('#editor .cm-content').click();
  await page.keyboard.press('Control+a');
  await page.keyboard.press('Delete');
  await page.waitForFunction(() => /holds no model/.test(document.querySelector('#problems').textContent));
  await press('[data-tab="downloads"]');
  const [staleCsv] = await Promise.all([page.waitForEvent('download'), press('[data-download="csv"]')]);
  assert.equal(readFileSync(await staleCsv.path(), 'utf8'), directCsv, 'the CSV of the results on screen');
  const [emptied] = await Promise.all([page.waitForEvent('download'), press('[data-download="model"]')]);
  assert.equal(readFileSync(await emptied.path(), 'utf8'), '', 'the model file is the editor\'s text');
  await press('[data-tab="editor"]');
  await page.locator('#editor .cm-content').click();
  await page.keyboard.press('Control+z');
  await page.waitForFunction(() => !document.body.classList.contains('results-stale'));
  await settled(page);

  // 4. A driver added in the drivers table (after the template's is deleted): in the YAML, solved.
  await press('[data-tab="model"]');
  await press(`#model-tables [data-delete-path='["drivers",0]']`);
  await page.waitForFunction(() => !/\{angle: crank/.test(document.querySelector('#editor .cm-content').textContent));
  await settled(page);
  await page.selectOption('[data-adder="driver"] [data-add="body"]', 'crank');
  await press('[data-add-go="driver"]');
  await page.waitForFunction(() => /\{angle: crank, from: 0, to: 360, speed: 60 rpm\}/.test(document.querySelector('#editor .cm-content').textContent));
  await settled(page);
  assert.equal(await statusText(page), '1 DOF · 181 samples');
  // A force at P, then a torque on the rocker: appended as the loads section.
  await page.selectOption('[data-adder="force"] [data-add="point"]', 'P');
  await press('[data-add-go="force"]');
  await page.waitForFunction(() => /forces:\s*- \{point: P, force: \[0, -10\]\}/.test(document.querySelector('#editor .cm-content').innerText));
  await settled(page);
  assert.equal(await page.locator('#model-tables input[data-path=\'["forces",0,"force",1]\']').inputValue(), '-10');
  await ctx.shot(page, `${tag}-files-3-added`);

  // 5. A point renamed: every reference follows (ground, bodies, the slider), the model solves.
  await openTemplate(page, press, 'template-slider-crank', 'Slider-crank');
  await press('[data-tab="model"]');
  await page.locator('#model-tables [data-rename="C"]').fill('Pin');
  await page.locator('#model-tables [data-rename="C"]').press('Enter');
  await page.waitForSelector('#model-tables [data-rename="Pin"]');
  await settled(page);
  const renamed = await yamlText(page);
  assert.match(renamed, /\n {2}Pin: {2}\[230, 0\] +# slider pin\n/);
  assert.match(renamed, /\n {2}rod: {4}\[A, Pin\]\n/);
  assert.match(renamed, /\n {2}slider: \[Pin\] +# the slider block\n/);
  assert.match(renamed, /\n {2}- \{body: slider, point: Pin, along: \[Y1, Y2\]\}\n/);
  assert.doesNotMatch(renamed.replace(/#.*$/gm, '').replace(/^description:.*$/m, ''), /\bC\b/, 'no reference to C is left');
  assert.equal(await statusText(page), '1 DOF · 181 samples');
  assert.equal(await page.locator('#drawing circle.pt[data-point="Pin"]').count(), 1);
  // A ground point renamed too: the ground list and the slider's guide follow.
  await page.locator('#model-tables [data-rename="Y1"]').fill('G1');
  await page.locator('#model-tables [data-rename="Y1"]').press('Enter');
  await page.waitForSelector('#model-tables [data-rename="G1"]');
  await settled(page);
  const again = await yamlText(page);
  assert.match(again, /\nground: \[O2, G1, Y2\]\n/);
  assert.match(again, /along: \[G1, Y2\]/);
  // A name that is a body's: refused with the reason, the text untouched.
  await page.locator('#model-tables [data-rename="Pin"]').fill('crank');
  await page.locator('#model-tables [data-rename="Pin"]').press('Enter');
  await page.waitForFunction(() => /crank is the name of a body/.test(document.querySelector('#model-problem')?.textContent ?? ''));
  assert.equal(await yamlText(page), again);
  assert.match(await page.locator('#model-tables tr.refusal').textContent(), /^Cannot edit: crank is the name of a body$/);
  await ctx.shot(page, `${tag}-files-4a-refused`);
  // Deleting the slider's point is refused too: the slider uses it.
  await press('#model-tables [data-delete-point="Pin"]');
  await page.waitForFunction(() => /Pin is used by sliders\.point/.test(document.querySelector('#model-problem')?.textContent ?? ''));
  // A slider added in the joints table on the crank (its end A on the guide) would leave the
  // slider-crank nothing free to move: refused with the core's reason, the text untouched.
  await ctx.shot(page, `${tag}-files-4-renamed`);
  await page.selectOption('[data-adder="slider"] [data-add="body"]', 'crank');
  await page.selectOption('[data-adder="slider"] [data-add="point"]', 'A');
  await page.selectOption('[data-adder="slider"] [data-add="along0"]', 'G1');
  await page.selectOption('[data-adder="slider"] [data-add="along1"]', 'Y2');
  const beforeSlider = await yamlText(page);
  await press('[data-add-go="slider"]');
  await page.waitForSelector('[data-adder="slider"] .cell-error');
  assert.match(await page.locator('[data-adder="slider"] .cell-error').textContent(), /^Cannot add this slider: the joints leave no freedom/);
  assert.equal(await yamlText(page), beforeSlider);

  // The new strings in Spanish too.
  await page.selectOption('#lang', 'es');
  assert.equal(await page.locator('#new-menu > summary').textContent(), 'Nuevo');
  assert.equal(await page.locator('#open-button').textContent(), 'Abrir…');
  assert.equal(await page.locator('[data-download="json"]').textContent(), 'Cálculo (JSON)');
  assert.equal(await page.locator('[data-add-go="driver"]').textContent(), 'Añadir un accionamiento');
  await page.selectOption('#lang', 'en');

  // 6. With snap on, a dragged point's preview is on the grid (desktop: a mouse drag).
  if (!mobile) {
    await openTemplate(page, press, 'template-four-bar', 'Four-bar');
    await press('#edit-tools [data-tool="snap"]');
    const step = await page.evaluate(() => { const l = document.querySelectorAll('#drawing .edit-grid line'); return +l[1].getAttribute('x1') - +l[0].getAttribute('x1'); });
    const p = await page.locator('#drawing circle.pt[data-point="P"]').boundingBox();
    await page.mouse.move(p.x + p.width / 2, p.y + p.height / 2);
    await page.mouse.down();
    await page.mouse.move(p.x + p.width / 2 + 23, p.y + p.height / 2 + 11, { steps: 4 });
    const [cx, cy] = await page.evaluate(() => { const c = document.querySelector('#drawing circle.pt[data-point="P"]'); return [+c.getAttribute('cx'), +c.getAttribute('cy')]; });
    for (const v of [cx, cy]) assert.ok(Math.abs(v / step - Math.round(v / step)) < 1e-6, `preview ${v} on the ${step} grid`);
    await page.mouse.up();
    await settled(page);
    await press('#edit-tools [data-tool="snap"]');
  }
}
