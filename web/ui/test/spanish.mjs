// The app in Spanish, run by browser.mjs (`--only spanish`) at a laptop's and a phone's viewport.
// First, without a page: the core's messages a student commonly meets (the model errors of
// typical slips, the stop of a sweep at a toggle, the dynamics' warnings, the Grashof class and
// joints of every bundled example, the Newton start) are asked of the running server in English
// and in Spanish (`lang`), and each must come back in Spanish from the core's catalogue
// (src/request/language.cpp), differing from the English and holding none of its words; every
// bundled example and template must have its Spanish title (i18n-gallery.js). Then the page: the
// language switched to Español, several examples opened, a stop and two model errors typed in
// the editor, Model and Explain tabs shown; at each step no visible text may hold a word of the
// English list below, outside the model's own names (points, bodies, drivers, loops, the
// model's title), the YAML editor, units and numbers.
// run(page, ctx) with ctx = {mobile, tag, base, shot, click, retype}.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { galleryEs } from '../src/i18n-gallery.js';

// Words that are English and not Spanish (nor units, nor names the model format fixes): any of
// them on screen in Spanish is a string left untranslated.
const english = new Set(`the and of from with is are not has have this that by on at was were be
  samples sample step steps failed unknown point points key revolute prismatic drawn pose sweep
  stopped between cannot invalid degree degrees freedom dof loading analysing link links body bodies
  gallery joint joints drivers driver loads speed length crossed warning did you mean top level
  new undo redo plot table forces force torque stress change tab here your whole should
  crank-rocker rocker-crank double-crank double-rocker triple-rocker four-bar slider-crank
  converged evaluation evaluations residual below until tolerance mobility coordinates every
  downloads synthesis explain retry updated offline open play pause drawing language`.split(/\s+/).filter(Boolean));

async function post(base, path, body) {
  const r = await fetch(new URL(path, base), { method: 'POST', headers: { 'content-type': 'application/json' }, body: JSON.stringify(body) });
  return r.json();
}

// The same request's answer in English and in Spanish.
async function both(base, path, body) {
  return Promise.all(['en', 'es'].map((lang) => post(base, path, { ...body, lang })));
}

// The words of the English list in a message, outside its quoted names.
// A name with digits or underscores (link5, theta_left) is one word, never English.
const englishWords = (text) => (text.replace(/`[^`]*`|'[^']*'|«[^»]*»/g, ' ').match(/[\wÀ-ÿ]+(?:-[\wÀ-ÿ]+)*/g) ?? [])
  .filter((w) => english.has(w.toLowerCase()));
// A check's descriptions of its loops, rockers, slider-cranks and quick-returns, in order.
const descriptionsOf = (check) => [
  ...(check.loops ?? []).flatMap((l) => [l.description, l.rocker?.description]),
  ...(check.slider_cranks ?? []).map((f) => f.description),
  ...(check.quick_returns ?? []).map((f) => f.description),
].filter(Boolean);
// The tooltips of the motion line and of the facts line under the drawing.
const motionTips = (page) => page.locator('#motion-info .loop, #motion-facts .loop').evaluateAll((els) => els.map((el) => el.getAttribute('title')));
// A bundled example's text.
const exampleText = (examples, name) => readFileSync(`${examples}/${name}.yaml`, 'utf8');

// The slips a student makes most, each a one-line change of the crank-rocker's text.
const slips = [
  ['crank:   [O2, A]', 'crank:   [O2, Q]'],  // a point not defined
  ['units: {length: mm', 'unitz: {length: mm'],  // a key misspelt
  ['speed: 120 rpm', 'spead: 120 rpm'],  // a driver's key misspelt
  ['speed: 120 rpm', 'speed: 120 rpn'],  // a unit misspelt
  ['units: {length: mm', 'units: {length: mn'],
  ['crank:   [O2, A]', 'crank:   [O2, A'],  // a bracket left open
  ['lengths: {crank: 80, rocker: 150}', 'lengths: {crank: 80, rocker: 10}'],  // cannot assemble
  ['  - {angle: crank, from: 0, to: 360, speed: 120 rpm}\n', ''],  // no driver
  ['{angle: crank,', '{angle: crankk,'],  // a body misspelt
  ['  O2: [0, 0]', '  O2: [0, x]'],  // not a number
  ['  O2: [0, 0]', '\tO2: [0, 0]'],  // a tab
  ['lengths: {crank: 80', 'lengths: {crank: 140'],  // the sweep stops at a toggle
];

// Every message of the core listed above, asked of the server in both languages; returns how many
// were checked. A message is left in English when its Spanish is the English itself, or holds an
// English word outside the model's names (quoted) and the words `skip` allows (a point's names).
export async function checkCatalogue(base, examples) {
  const missing = [];
  const need = (en, es, what, skip = []) => {
    if (!en) return;
    const left = englishWords(es ?? '').filter((w) => !skip.includes(w.toLowerCase()));
    if (es === en || left.length) missing.push(`${what}: ${es}${left.length ? ` (${left.join(', ')})` : ''}`);
  };
  const crankRocker = exampleText(examples, 'fourbar-crank-rocker');
  let checked = 0;
  for (const [from, to] of slips) {
    assert.ok(crankRocker.includes(from), `the crank-rocker holds ${JSON.stringify(from)}`);
    const [en, es] = await both(base, 'api/solve', { model: crankRocker.replace(from, to), steps: 73 });
    const message = (a) => a.error?.message ?? a.stop_reason;
    assert.ok(message(en), `${to}: an error or a stop`);
    assert.deepEqual({ ...es.error, message: undefined }, { ...en.error, message: undefined }, `${to}: the error's place is the same in Spanish`);
    need(message(en), message(es), `slip ${JSON.stringify(to)}`);
    checked++;
  }
  // The dynamics' warnings: no loads, and redundant constraints.
  const warningsOf = (a) => [...(a.warnings ?? []), ...(a.dynamics?.warnings ?? [])].map((w) => (typeof w === 'string' ? w : w.message));
  for (const name of ['fourbar-crank-rocker', 'parallelogram-redundant']) {
    const [en, es] = await both(base, 'api/solve', { model: exampleText(examples, name), steps: 5, dynamics: true });
    warningsOf(en).forEach((w, k) => { need(w, warningsOf(es)[k], name); checked++; });
  }
  // Every bundled example: its title, its loops' Grashof classes, its joints and warnings.
  const { examples: listed } = await (await fetch(new URL('api/examples', base))).json();
  for (const e of listed) {
    if (e.kind === 'task') continue;  // synthesis tasks are not in the gallery
    if (!galleryEs[e.name]?.[0]) missing.push(`gallery: no Spanish title for ${e.name}`);
    if (e.description && !galleryEs[e.name]?.[1]) missing.push(`gallery: no Spanish description for ${e.name}`);
    if (e.kind !== 'model') continue;
    const text = await (await fetch(new URL(`api/examples/${e.name}`, base))).text();
    const [en, es] = await both(base, 'api/check', { model: text });
    (en.loops ?? []).forEach((l, k) => { need(l.grashof, es.loops[k].grashof, `${e.name}: Grashof class`, [l.grashof]); checked++; });
    (en.joints ?? []).forEach((j, k) => { if (j.startsWith('revolute')) { need(j, es.joints[k], e.name, [...namesOf(text)]); checked++; } });
    (en.warnings ?? []).forEach((w, k) => { need(w.message ?? w, es.warnings[k].message ?? es.warnings[k], e.name, [...namesOf(text)]); checked++; });
    // The descriptions the app shows as tooltips (a loop's, a rocker's, a slider-crank's).
    descriptionsOf(en).forEach((d, k) => { need(d, descriptionsOf(es)[k], `${e.name}: description`, [...namesOf(text)]); checked++; });
  }
  for (const step of [0, 5]) {
    const [en, es] = await both(base, 'api/explain', { model: crankRocker, step });
    need(en.newton?.start, es.newton?.start, `explain step ${step}`);
    checked++;
  }
  assert.deepEqual(missing, [], 'core messages a student meets, left in English in Spanish answers');
  return checked;
}

// The words of visible text not in Spanish (or of `given` texts, a tooltip's say). `names` are
// the model's own (exempt).
export async function englishOnScreen(page, names, given = null) {
  const texts = given ?? await page.evaluate(() => {
    const out = [];
    const skip = (el) => el.closest('.cm-editor, #model-name, select, script, style, title, [hidden]');
    const walker = document.createTreeWalker(document.body, NodeFilter.SHOW_TEXT);
    for (let n = walker.nextNode(); n; n = walker.nextNode()) {
      const el = n.parentElement;
      if (!el || !n.textContent.trim() || skip(el)) continue;
      if (!el.checkVisibility({ checkOpacity: true, checkVisibilityCSS: true })) continue;
      const r = el.getBoundingClientRect();
      if (r.width === 0 || r.height === 0) continue;
      out.push(n.textContent.trim());
    }
    return out;
  });
  const found = [];
  for (const text of texts) {
    // Quoted and backquoted parts are the model's names and keys, written as in the YAML; a
    // dotted name (crank.torque, A.crank>coupler.Fx) is a column's, as the CSV and API name it.
    const plain = text.replace(/`[^`]*`|'[^']*'|«[^»]*»|“[^”]*”/g, ' ').replace(/[\w-]+(?:\.[\w>-]+)+/g, ' ');
    for (const word of plain.match(/[A-Za-zÀ-ÿ]+(?:-[A-Za-zÀ-ÿ]+)*/g) ?? []) {
      const w = word.toLowerCase();
      if (english.has(w) && !names.has(w)) found.push(`"${word}" in "${text.slice(0, 120)}"`);
    }
  }
  return found;
}

export function namesOf(yamlText) {
  const names = new Set();
  // Every identifier before a colon or inside a flow list of the model's text is one of its names.
  for (const m of yamlText.matchAll(/^\s*-?\s*\{?\s*([\w-]+)\s*:/gm)) names.add(m[1].toLowerCase());
  for (const m of yamlText.matchAll(/\[([^\]]*)\]/g)) for (const n of m[1].split(',')) names.add(n.trim().toLowerCase());
  for (const m of yamlText.matchAll(/(?:angle|distance|slide|relative)\s*:\s*([\w-]+)/g)) names.add(m[1].toLowerCase());
  for (const n of [...names]) for (const part of n.split('-')) names.add(part);
  return names;
}

async function editorText(page) {
  return page.evaluate(() => [...document.querySelectorAll('.cm-line')].map((l) => l.textContent).join('\n'));
}

async function assertSpanish(page, where, shot, tag, shotName) {
  await shot(page, `${tag}-es-${shotName}`);
  const names = namesOf(await editorText(page));
  // The model's title is its own text, wherever it is repeated (Explain's heading).
  const title = await page.locator('#model-name').textContent();
  for (const w of title.toLowerCase().match(/[a-zà-ÿ]+(?:-[a-zà-ÿ]+)*/g) ?? []) { names.add(w); for (const p of w.split('-')) names.add(p); }
  const found = await englishOnScreen(page, names);
  assert.deepEqual(found, [], `${tag}, ${where}: English left on screen`);
}

const settled = (page) => page.waitForFunction(() => !document.body.dataset.busy && !/…$/.test(document.querySelector('#status').textContent));

async function openFromGallery(page, mobile, click, name) {
  await click(page, mobile, '[data-tab="gallery"]');
  const opened = await page.evaluate(() => +(document.body.dataset.opened ?? 0));
  await click(page, mobile, `[data-example="${name}"]`);
  await page.waitForFunction((n) => +(document.body.dataset.opened ?? 0) > n && !document.body.dataset.busy, opened);
  await settled(page);
}

export async function run(page, ctx) {
  const { mobile, tag, shot, click, retype } = ctx;
  await page.selectOption('#lang', 'es');
  assert.equal(await page.locator('[data-tab="gallery"]').textContent(), 'Galería');
  await click(page, mobile, '[data-tab="gallery"]');
  await settled(page);
  assert.equal((await page.locator('[data-example="fourbar-crank-rocker"] b').textContent()).trim(), 'Cuadrilátero manivela-balancín');
  await assertSpanish(page, 'gallery', shot, tag, '1-gallery');

  await openFromGallery(page, mobile, click, 'fourbar-crank-rocker');
  assert.match(await page.locator('#status').textContent(), /^1 GDL · 361 muestras$/);
  assert.match(await page.locator('#motion-info').textContent(), /manivela-balancín/);
  await assertSpanish(page, 'crank-rocker', shot, tag, '2-crank-rocker');
  // The core's descriptions as tooltips, said by the server in Spanish (none held back as English).
  const tips = await motionTips(page);
  assert.ok(tips.some((tip) => tip.startsWith('manivela-balancín: bastidor ground 200, entrada crank 80')), `the loop's tooltip: ${tips}`);
  assert.ok(tips.some((tip) => tip.startsWith('el balancín rocker oscila 65.921 deg')), `the rocker's tooltip: ${tips}`);
  assert.deepEqual(await englishOnScreen(page, namesOf(await editorText(page)), tips), [], `${tag}: English left in the tooltips`);
  await click(page, mobile, '[data-tab="model"]');
  assert.match(await page.locator('#panel-model').textContent(), /par de rotación O2 \(ground\/crank\)/);
  await assertSpanish(page, 'Model tab', shot, tag, '3-model');
  await click(page, mobile, '[data-tab="explain"]');
  await page.waitForSelector('#explain-out section');
  assert.match(await page.locator('#explain-out').textContent(), /Newton–Raphson desde la posición dibujada/);
  await assertSpanish(page, 'Explain tab', shot, tag, '4-explain');

  for (const [name, grashof] of [['fourbar-double-crank', 'doble manivela'], ['fourbar-double-rocker', 'triple balancín'], ['slider-crank-offset', null]]) {
    await openFromGallery(page, mobile, click, name);
    if (grashof) assert.match(await page.locator('#motion-info').textContent(), new RegExp(grashof));
    if (!grashof) assert.ok((await motionTips(page)).some((tip) => tip.startsWith('biela-manivela crank-rod-slider: manivela 50 mm')), `${name}: the slider-crank's tooltip`);
    await assertSpanish(page, name, shot, tag, `5-${name}`);
  }

  // A sweep that stops at a toggle: its warning, in Spanish.
  await openFromGallery(page, mobile, click, 'fourbar-crank-rocker');
  await click(page, mobile, '[data-tab="editor"]');
  await retype(page, mobile, 'lengths: {crank: 80', '80', '140');
  await page.waitForSelector('#warnings li.stop');
  await settled(page);
  assert.match(await page.locator('#warnings').textContent(), /barrido detenido entre los pasos \d+ y \d+ en crank = /);
  assert.match(await page.locator('#status').textContent(), /^1 GDL · \d+ muestras · detenido: barrido detenido/);
  await assertSpanish(page, 'a stopped sweep', shot, tag, '6-stopped');
  await retype(page, mobile, 'lengths: {crank: 140', '140', '80');
  await page.waitForFunction(() => !document.querySelector('#warnings li.stop'));
  await settled(page);

  // Model errors typed in the editor: a point not defined, a key misspelt.
  await retype(page, mobile, 'crank:   [O2, A]', 'A]', 'Q]');
  await page.waitForSelector('.cm-lintRange-error');
  await settled(page);
  assert.match(await page.locator('#problems').textContent(), /^línea 16, columna 17: punto desconocido 'Q' \(los puntos son: O2, O4, A, B, P\)$/);
  assert.match(await page.locator('#status').textContent(), /^Error: línea 16, columna 17: punto desconocido 'Q'/);
  assert.match(await page.locator('#stale span').textContent(), /^Sin actualizar: punto desconocido 'Q'/);
  await assertSpanish(page, 'an unknown point', shot, tag, '7-unknown-point');
  await retype(page, mobile, 'crank:   [O2, Q]', 'Q]', 'A]');
  await page.waitForFunction(() => document.querySelector('#problems').textContent === 'Sin errores.');
  await retype(page, mobile, 'units: {length: mm', 'units', 'unitz');
  await page.waitForSelector('.cm-lintRange-error');
  await settled(page);
  assert.match(await page.locator('#problems').textContent(), /clave desconocida 'unitz' en el nivel superior; ¿quería decir 'units'\?/);
  await assertSpanish(page, 'a key misspelt', shot, tag, '8-unknown-key');
  // Back to English: the model analysed again, its error now said by the core in English.
  await page.selectOption('#lang', 'en');
  await page.waitForFunction(() => /unknown key 'unitz' at the top level; did you mean 'units'\?/.test(document.querySelector('#problems').textContent));
  await settled(page);
  await retype(page, mobile, 'unitz: {length: mm', 'unitz', 'units');
  await page.waitForFunction(() => document.querySelector('#problems').textContent === 'No errors.');
  await settled(page);
}
