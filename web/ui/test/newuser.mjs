// Issue 39's "done when", as one run (browser.mjs `--only newuser`, ctest Web.NewUser), at a
// phone's 390×844 by touch and a laptop's 1366×768 by mouse: a new user builds the lab
// slider-crank (examples/slider-crank-centred.yaml: crank 50 mm, connecting rod 180 mm, a block
// on a guide through the crank pivot, 3000 rpm) from New → Empty model with taps alone (no typing
// in the YAML; the numbers typed go into the Model tab's own fields), in under 2 minutes; reads
// the peak slider speed by a touch held on the plot (the value shown, the mechanism posed there);
// makes the crank and rod steel bars and finds the stress peak and its safety factor in the
// per-link stress table, a tap on its row going to its step. Then all of it again in Spanish,
// failing on any English word on screen (tooltips included) outside model names and numbers.
// On the way: one edit asks for one solve (the requests counted), the zoom buttons are on
// screen, a point of the building drawing can be dragged, and at 390 px every tap target is at
// least 44×44 CSS px. Every number read from the UI is checked against `nbar solve` and
// `nbar stress` on the same text, to the UI's display precision.
// run(page, ctx) with ctx = {mobile, tag, nbar, examples, shot, click}.
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { mkdtempSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { englishOnScreen, namesOf } from './spanish.mjs';
import { screenOf } from './build.mjs';

// The app's number format (main.js fmt), to compare at the precision shown.
const fmt = (v) => {
  const a = Math.abs(v);
  if (a !== 0 && (a >= 1e6 || a < 1e-3)) return v.toExponential(3);
  return String(+v.toFixed(a >= 100 ? 2 : 4));
};

const yamlText = (page) => page.evaluate(() => [...document.querySelectorAll('#editor .cm-line')].map((l) => l.textContent).join('\n'));
const settled = (page) => page.waitForFunction(() => !document.body.dataset.busy && !/…$/.test(document.querySelector('#status').textContent));

const dir = mkdtempSync(join(tmpdir(), 'nbar-newuser-'));
// `nbar ARGS` on `text` written to a file: its JSON answer.
function cli(nbar, text, args) {
  const file = join(dir, 'model.yaml');
  writeFileSync(file, text);
  const r = spawnSync(nbar, [...args, file, '--format', 'json'], { encoding: 'utf8', maxBuffer: 1 << 28 });
  assert.equal(r.status, 0, `nbar ${args.join(' ')}: ${r.stderr}`);
  return JSON.parse(r.stdout);
}

async function tapModel(page, mobile, x, y) {
  const [cx, cy] = await screenOf(page, x, y);
  if (mobile) await page.touchscreen.tap(cx, cy); else await page.mouse.click(cx, cy);
  await page.waitForTimeout(50);
  await settled(page);
}
async function edited(page, before) {
  await page.waitForFunction((b) => [...document.querySelectorAll('#editor .cm-line')].map((l) => l.textContent).join('\n') !== b, before);
  await settled(page);
}

// A touch (CDP: Playwright's touchscreen only taps) or the mouse pressed at `from`, moved to each
// of `path` in turn, `whilst(move)` called while still pressed, then released.
async function press(page, mobile, from, path, whilst = async () => {}) {
  const client = mobile ? await page.context().newCDPSession(page) : null;
  const down = ({ x, y }) => (mobile ? client.send('Input.dispatchTouchEvent', { type: 'touchStart', touchPoints: [{ x, y }] }) : page.mouse.move(x, y).then(() => page.mouse.down()));
  const move = ({ x, y }) => (mobile ? client.send('Input.dispatchTouchEvent', { type: 'touchMove', touchPoints: [{ x, y }] }) : page.mouse.move(x, y));
  await down(from);
  for (const p of path) await move(p);
  const result = await whilst(move);
  if (mobile) { await client.send('Input.dispatchTouchEvent', { type: 'touchEnd', touchPoints: [] }); await client.detach(); } else await page.mouse.up();
  return result;
}

// Types `value` into the Model tab's field labelled `label` (a tap, select all, the number).
async function typeField(page, ctx, label, value) {
  await settled(page);
  const before = await yamlText(page);
  const field = page.getByLabel(label, { exact: true });
  // On a slow build (the sanitizers') the tap on the Model tab can land while the page is drawn
  // again after an analysis, and the tab stays closed (its fields hidden): it is asked for again.
  for (let attempt = 0; attempt < 20 && !(await field.isVisible()); ++attempt) {
    await page.waitForTimeout(500);
    if (attempt % 4 === 3 && !(await field.isVisible())) await ctx.click(page, ctx.mobile, '[data-tab="model"]');
  }
  await field.scrollIntoViewIfNeeded();
  if (ctx.mobile) await field.tap(); else await field.click();
  await field.fill(String(value));
  await field.press('Enter');
  await edited(page, before);
}

// The words of English on screen, and in the visible controls' tooltips and aria-labels.
async function englishLeft(page) {
  const names = namesOf(await yamlText(page));
  // A name the tools made (link1, block1, G2) is the model's, its letters too.
  // The columns offered are named after the model's points and bodies (the last one solved).
  for (const c of await page.locator('#ycol option').evaluateAll((os) => os.map((o) => o.value))) for (const n of c.split('.')) names.add(n.toLowerCase());
  for (const n of [...names]) { const letters = n.match(/^[a-z]+(?=\d)/); if (letters) names.add(letters[0]); }
  const title = await page.locator('#model-name').textContent();
  for (const w of title.toLowerCase().match(/[a-zà-ÿ]+(?:-[a-zà-ÿ]+)*/g) ?? []) names.add(w);
  const found = await englishOnScreen(page, names);
  // What a screen reader says of a control (aria-label) counts as much as its tooltip.
  const tips = await page.evaluate(() => [...document.querySelectorAll('[title], [aria-label]')]
    .filter((el) => !el.closest('.cm-editor, [hidden]') && el.checkVisibility({ checkVisibilityCSS: true }) && el.getBoundingClientRect().width > 0)
    .flatMap((el) => [el.getAttribute('title'), el.getAttribute('aria-label')]).filter(Boolean));
  return found.concat(await englishOnScreen(page, names, tips));
}

// Every visible control at least 44×44 CSS px (the phone's guideline), the YAML editor's text and
// the plot's canvas apart (they are not buttons).
async function smallTargets(page) {
  return page.evaluate(() => [...document.querySelectorAll('button, select, summary, input, [role=tab], a[href]')]
    .filter((el) => !el.closest('.cm-editor, [hidden], .u-wrap') && el.checkVisibility({ checkVisibilityCSS: true, checkOpacity: true }))
    .map((el) => {
      // A check box's target is its label, when the label is the control's box.
      const box = (el.type === 'checkbox' && el.closest('label')) || el;
      const r = box.getBoundingClientRect();
      return { what: `${el.tagName.toLowerCase()}${el.id ? `#${el.id}` : ''}${el.dataset.tool ? `[tool=${el.dataset.tool}]` : ''} "${(el.getAttribute('aria-label') ?? el.textContent).trim().slice(0, 30)}"`, w: r.width, h: r.height };
    })
    .filter((x) => x.w > 0 && (x.w < 43.5 || x.h < 43.5))
    .map((x) => `${x.what} ${x.w.toFixed(0)}×${x.h.toFixed(0)}`));
}

// The slider-crank of examples/slider-crank-centred.yaml, built by taps: {seconds, text}.
async function buildSliderCrank(page, ctx, stepShot) {
  const { mobile, click } = ctx;
  const started = Date.now();
  await click(page, mobile, '[data-tab="gallery"]');
  await click(page, mobile, '#new-menu summary');
  const opened = await page.evaluate(() => +(document.body.dataset.opened ?? 0));
  await click(page, mobile, '#new-empty');
  await page.waitForFunction((n) => +(document.body.dataset.opened ?? 0) > n && !document.body.dataset.busy, opened);
  await page.waitForSelector('#drawing svg[data-sketch="1"]');
  // The zoom buttons are on screen (they were hidden at 390 px).
  for (const z of ['zoom-in', 'zoom-out', 'fit']) {
    const b = await page.locator(`#edit-tools [data-tool="${z}"]`).boundingBox();
    const width = await page.evaluate(() => document.documentElement.clientWidth);
    assert.ok(b && b.x >= 0 && b.x + b.width <= width, `${z} on screen: ${JSON.stringify(b)}`);
  }
  await stepShot('1-empty');
  await drawLinks(page, ctx, stepShot);
  await finishInModelTab(page, ctx, stepShot);
  const seconds = (Date.now() - started) / 1000;
  const text = await yamlText(page);
  // The lab's dimensions: crank 50, rod 180, centred guide.
  assert.match(text, /P1: \[0, 0\]/);
  assert.match(text, /P2: \[50, 0\]/);
  assert.match(text, /P3: \[230, 0\]/);
  assert.match(text, /G1: \[[-\d.]+, 0\]/);
  assert.match(text, /units: \{length: mm, angle: deg\}/);
  return { seconds, text };
}

// The crank and the rod drawn with the link tool, the crank pin dragged in the building drawing.
async function drawLinks(page, ctx, stepShot) {
  const { mobile, click } = ctx;
  const tool = (name) => click(page, mobile, `#edit-tools [data-tool="${name}"]`);
  // Crank: a ground pivot at the origin, a link to the crank pin; snap on (the grid's taps exact).
  await tool('snap');
  await tool('ground');
  let text = await yamlText(page);
  await tapModel(page, mobile, 0, 0);
  await edited(page, text);
  await tool('link');
  text = await yamlText(page);
  await tapModel(page, mobile, 0, 0);
  await tapModel(page, mobile, 60, 0);
  await edited(page, text);
  // The connecting rod, to the wrist pin.
  text = await yamlText(page);
  await tapModel(page, mobile, 60, 0);
  await tapModel(page, mobile, 240, 0);
  await edited(page, text);
  await page.waitForSelector('#drawing svg[data-sketch="1"] path.body[data-body="link2"]', { state: 'attached' });
  await stepShot('2-links');

  // The crank pin dragged up in the building drawing, with the select tool: it moves.
  await tool('select');
  text = await yamlText(page);
  const [ax, ay] = await screenOf(page, 60, 0);
  await press(page, mobile, { x: ax, y: ay }, [1, 2, 3, 4, 5, 6].map((k) => ({ x: ax, y: ay - 5 * k })));
  await edited(page, text);
  const dragged = (await yamlText(page)).match(/P2: \[([-\d.]+), ([-\d.]+)\]/);
  assert.ok(dragged && +dragged[2] > 5, `P2 dragged up in the building drawing: ${dragged?.[0]}`);
}

// The lab's dimensions typed, the slider tool's block and guide, the driver, the steel bars.
async function finishInModelTab(page, ctx, stepShot) {
  const { mobile, click } = ctx;
  const tool = (name) => click(page, mobile, `#edit-tools [data-tool="${name}"]`);
  let text;

  // The lab's dimensions typed into the Points table: crank pin (50, 0), wrist pin (230, 0).
  await click(page, mobile, '[data-tab="model"]');
  await typeField(page, ctx, 'P2 x', 50);
  await typeField(page, ctx, 'P2 y', 0);
  await typeField(page, ctx, 'P3 x', 230);
  await click(page, mobile, '[data-tab="editor"]');

  // The slider tool: the wrist pin, then the guide's direction: block and guide in one gesture.
  await tool('slider');
  text = await yamlText(page);
  await tapModel(page, mobile, 230, 0);
  await tapModel(page, mobile, 300, 0);
  await edited(page, text);
  text = await yamlText(page);
  assert.match(text, /sliders:\n\s+- \{ ?body: block1, point: P3, along: \[ ?G1, G2 ?\] ?\}/);
  await tool('select');
  await stepShot('3-slider');

  // A driver on the crank at the lab's 3000 rpm.
  await click(page, mobile, '[data-tab="model"]');
  await page.selectOption('[data-adder="driver"] [data-add="body"]', 'link1');
  await click(page, mobile, '[data-add-go="driver"]');
  await edited(page, text);
  // Found by its label as a screen reader says it, in the language on screen.
  await typeField(page, ctx, await page.locator('[data-path=\'["drivers",0,"speed"]\']').getAttribute('aria-label'), '3000 rpm');
  await page.waitForFunction(() => /^1 (DOF|GDL) · \d+ (samples|muestras)$/.test(document.querySelector('#status').textContent));
  assert.equal(await page.locator('#drawing svg[data-sketch]').count(), 0, 'solved: the drawing is the solved one');

  // The crank and rod made steel bars 8 mm thick in their body panels (for the stresses).
  for (const body of ['link1', 'link2']) {
    await click(page, mobile, `[data-select-body="${body}"]`);
    text = await yamlText(page);
    await page.selectOption('[data-body-form]', 'bar');
    await edited(page, text);
    await typeField(page, ctx, await page.locator('[data-body-prop="thickness"]').getAttribute('aria-label'), 8);
    await typeField(page, ctx, await page.locator('[data-body-prop="material"]').getAttribute('aria-label'), 'steel');
  }
  await page.locator('#model-tables').scrollIntoViewIfNeeded();
  await stepShot('4-model-tab');
}

// The peak slider speed: P3.vx on the plot, a touch held at its peak; the value shown there and
// the scrubber's step are the CLI's peak and its step.
async function peakSpeed(page, ctx, text, stepShot) {
  const { mobile, click } = ctx;
  const ref = cli(ctx.nbar, text, ['solve']);
  const vx = ref.columns.indexOf('P3.vx');
  assert.ok(vx >= 0, `P3.vx among ${ref.columns}`);
  let peakStep = 0;
  ref.rows.forEach((r, i) => { if (Math.abs(r[vx]) > Math.abs(ref.rows[peakStep][vx])) peakStep = i; });
  const peak = ref.rows[peakStep][vx];
  await click(page, mobile, '[data-tab="editor"]');
  await page.selectOption('#ycol', 'P3.vx');
  await click(page, mobile, '[data-rtab="plot"]');
  const over = page.locator('#plot .u-over');
  await over.scrollIntoViewIfNeeded();
  const box = await over.boundingBox();
  // The plot's x is the driver's column, the first of the sweep's.
  const xs = ref.rows.map((r) => r[0]);
  // Where the peak's sample is along the plot, then a finger's slide until the posed step is it.
  const x0 = Math.min(...xs); const x1 = Math.max(...xs);
  const at = (step) => box.x + ((ref.rows[step][0] - x0) / (x1 - x0 || 1)) * box.width;
  const y = box.y + box.height / 2;
  const shown = await press(page, mobile, { x: at(peakStep), y }, [], async (move) => {
    let px = at(peakStep);
    for (let k = 0; k < 40; k++) {
      const step = +(await page.locator('#scrub').inputValue());
      if (step === peakStep) break;
      px += (peakStep - step) * (box.width / (ref.rows.length - 1)) * 0.6;
      await move({ x: px, y });
    }
    await stepShot('5-peak-speed');
    return { step: +(await page.locator('#scrub').inputValue()), values: await page.locator('#plot .u-legend .u-value').allTextContents() };
  });
  // The lab's own file gives the same peak: the model built is the lab's slider-crank.
  const lab = JSON.parse(spawnSync(ctx.nbar, ['solve', `${ctx.examples}/slider-crank-centred.yaml`, '--format', 'json'], { encoding: 'utf8', maxBuffer: 1 << 28 }).stdout);
  const labVx = lab.rows.map((r) => r[lab.columns.indexOf('C.vx')]);
  assert.equal(fmt(labVx.reduce((a, b) => (Math.abs(b) > Math.abs(a) ? b : a))), fmt(peak), 'the lab example\'s peak slider speed');
  assert.equal(shown.step, peakStep, 'the mechanism is posed at the peak');
  assert.equal(shown.values[1], fmt(peak), `the read-out at step ${peakStep}`);
  return { peak, peakStep };
}

// The stress peak: the per-link table's largest von Mises, its safety factor; its row tapped
// goes to its step. All against `nbar stress` on the same text.
async function stressPeak(page, ctx, text, stepShot) {
  const { mobile, click } = ctx;
  const ref = cli(ctx.nbar, text, ['stress']);
  const worst = ref.links.reduce((a, b) => (b.von_mises > a.von_mises ? b : a));
  await click(page, mobile, '[data-tab="editor"]');
  await click(page, mobile, '[data-overlay="stress"]');
  await page.waitForSelector('#stress-table tr[data-body]');
  const rows = await page.locator('#stress-table tr[data-body]').evaluateAll((trs) => trs.map((tr) => ({
    body: tr.dataset.body, vm: tr.querySelector('[data-col="von_mises"]').textContent, sf: tr.querySelector('[data-col="safety_factor"]').textContent,
  })));
  const top = rows.reduce((a, b) => (+b.vm > +a.vm ? b : a));
  assert.equal(top.body, worst.body);
  assert.equal(top.vm, fmt(worst.von_mises));
  assert.equal(top.sf, fmt(worst.safety_factor));
  await page.locator('#stress-table').scrollIntoViewIfNeeded();
  await click(page, mobile, `#stress-table tr[data-body="${worst.body}"] button`);
  assert.equal(await page.locator('#scrub').inputValue(), String(worst.step), 'the tap goes to the peak\'s step');
  await stepShot('6-stress-peak');
  await page.evaluate(() => document.querySelector('#drawing').scrollIntoView({ block: 'center', behavior: 'instant' }));
  await stepShot('7-posed-at-peak');
  await click(page, mobile, '[data-overlay="stress"]');
  return worst;
}

async function pass(page, ctx, lang) {
  const { tag, shot } = ctx;
  const spanish = lang === 'es';
  const english = [];
  const stepShot = async (name) => {
    await settled(page);
    await shot(page, `${tag}-${lang}-${name}`);
    if (spanish) english.push(...(await englishLeft(page)).map((w) => `${name}: ${w}`));
  };
  // Requests counted: an edit is analysed once (one /api/check); one the core accepts asks for
  // one solve (a sweep then its dynamics were two).
  const asked = { check: 0, accepted: 0, solve: 0, dynamics: 0 };
  const onRequest = (r) => {
    const path = new URL(r.url()).pathname;
    if (path === '/api/check') asked.check++;
    if (path === '/api/solve') { asked.solve++; if (r.postDataJSON?.()?.dynamics) asked.dynamics++; }
  };
  const onResponse = (r) => { if (new URL(r.url()).pathname === '/api/check' && r.ok()) asked.accepted++; };
  page.on('request', onRequest);
  page.on('response', onResponse);
  const built = await buildSliderCrank(page, ctx, stepShot);
  page.off('request', onRequest);
  page.off('response', onResponse);
  assert.ok(asked.accepted > 0 && asked.solve <= asked.accepted,
    `one solve an edit: ${asked.solve} solves (${asked.dynamics} with dynamics) for ${asked.accepted} models the core accepted`);
  if (ctx.mobile) assert.deepEqual(await smallTargets(page), [], 'tap targets under 44×44 px at 390 px');
  assert.ok(built.seconds < 120, `built in ${built.seconds} s (under 2 minutes)`);
  const speed = await peakSpeed(page, ctx, built.text, stepShot);
  const stress = await stressPeak(page, ctx, built.text, stepShot);
  if (spanish) assert.deepEqual(english, [], `${tag}: English left in the Spanish UI`);
  console.log(`${tag} ${lang}: slider-crank built in ${built.seconds.toFixed(1)} s with ${asked.check} analyses, ${asked.accepted} of models that solve, and ${asked.solve} solve requests; `
    + `peak slider speed ${fmt(speed.peak)} mm/s at step ${speed.peakStep}; stress peak ${fmt(stress.von_mises)} MPa in ${stress.body} at step ${stress.step}, safety factor ${fmt(stress.safety_factor)}`);
}

export async function run(page, ctx) {
  await pass(page, ctx, 'en');
  await page.selectOption('#lang', 'es');
  await pass(page, ctx, 'es');
  await page.selectOption('#lang', 'en');
}
