// The synthesis panel: path synthesis through five points (both fixed pivots given), through nine
// points (Alt's problem) and the best fit through ten or more (points typed in the task or tapped
// on the drawing), Burmester motion generation from poses (a form, or poses tapped on the drawing)
// and function generation (a form). Every task goes to the server's /api/synth/* with "models": true, so each
// design comes with the model file the core writes for it (`nbar synth --export`'s): the browser
// writes task text from the form, never a model. A design can be previewed animating through the
// targets, and opened in the editor.
import { t, translatePage } from './i18n.js';
import { drawingSvg, poseDrawing, markScale } from './drawing.js';

const $ = (s) => document.querySelector(s);
const num = (v) => String(+(+v).toFixed(6));
const methods = ['five-point', 'nine-point', 'path', 'burmester', 'function'];
// The methods whose task is the text area's (points tapped into it): how many taps make the
// task, its hint, and the example it starts from (five-point's is first loaded by main.js).
const textMethods = {
  'five-point': { taps: 5, hint: 'synthHint', tap: 'tapFive', example: 'five-point-crank-rocker' },
  'nine-point': { taps: 9, hint: 'nineHint', tap: 'tapNine', example: 'nine-point-crank-rocker' },
  path: { taps: Infinity, hint: 'pathHint', tap: 'tapPath', example: 'crank-rocker-measured' },
};

let app = null;
const synth = { method: 'five-point', tapping: null, taps: [], targets: [], preview: null, texts: {}, run: 0 };

// ------------------------------------------------------------------------------ forms

function field(key, id, value, attrs = '') {
  return `<label class="field"><span data-i18n="${key}">${t(key)}</span><input id="${id}" value="${value}" ${attrs}></label>`;
}

function burmesterForm() {
  return `<div id="synth-burmester" class="synth-form" hidden>
    <p class="hint" data-i18n="burmesterHint">${t('burmesterHint')}</p>
    <table class="poses"><thead><tr><th>#</th><th>x</th><th>y</th><th data-i18n="angleDeg">${t('angleDeg')}</th><th></th></tr></thead><tbody id="poses"></tbody></table>
    <div class="row wrap">
      <button id="pose-add" type="button" data-i18n="addPose">${t('addPose')}</button>
      <button id="pose-tap" type="button" class="tap" data-i18n="tapPoses">${t('tapPoses')}</button>
      <label class="check"><input type="checkbox" id="bm-fixed" checked><span data-i18n="fixedPivots">${t('fixedPivots')}</span></label>
    </div>
    <div class="grid4" id="bm-pivots">
      ${field('pivotAx', 'bm-ax', '0', 'inputmode="decimal"')}${field('pivotAy', 'bm-ay', '0', 'inputmode="decimal"')}
      ${field('pivotBx', 'bm-bx', '200', 'inputmode="decimal"')}${field('pivotBy', 'bm-by', '0', 'inputmode="decimal"')}
    </div>
  </div>`;
}

function functionForm() {
  return `<div id="synth-function" class="synth-form" hidden>
    <p class="hint" data-i18n="functionHint">${t('functionHint')}</p>
    ${field('fnExpr', 'fn-expr', 'log10(x)', 'spellcheck="false" autocapitalize="off"')}
    <div class="grid4">
      ${field('fnX0', 'fn-x0', '1', 'inputmode="decimal"')}${field('fnX1', 'fn-x1', '2', 'inputmode="decimal"')}
      ${field('fnIn0', 'fn-in0', '90', 'inputmode="decimal"')}${field('fnIn1', 'fn-in1', '150', 'inputmode="decimal"')}
      ${field('fnOut0', 'fn-out0', '60', 'inputmode="decimal"')}${field('fnOut1', 'fn-out1', '120', 'inputmode="decimal"')}
      ${field('fnPoints', 'fn-points', '3', 'inputmode="numeric"')}${field('fnFrame', 'fn-frame', '100', 'inputmode="decimal"')}
    </div>
    <label class="field"><span data-i18n="fnSpacing">${t('fnSpacing')}</span><select id="fn-spacing"><option value="chebyshev">Chebyshev</option><option value="even" data-i18n="even">${t('even')}</option></select></label>
  </div>`;
}

function buildForms() {
  const task = $('#task');
  const bar = document.createElement('div');
  bar.className = 'row wrap';
  bar.innerHTML = `<label class="field inline"><span data-i18n="method">${t('method')}</span><select id="synth-method">
      <option value="five-point" data-i18n="mFive">${t('mFive')}</option>
      <option value="nine-point" data-i18n="mNine">${t('mNine')}</option>
      <option value="path" data-i18n="mPath">${t('mPath')}</option>
      <option value="burmester" data-i18n="mBurmester">${t('mBurmester')}</option>
      <option value="function" data-i18n="mFunction">${t('mFunction')}</option></select></label>
    <button id="five-tap" type="button" class="tap" data-i18n="tapFive">${t('tapFive')}</button>`;
  task.before(bar);
  task.insertAdjacentHTML('afterend', burmesterForm() + functionForm());
  for (const p of [[-74.772, 20.544, 65.248], [22.802, 111.483, 55.771], [44.303, 194.508, 26.642]]) addPose(...p);
}

function addPose(x = 0, y = 0, angle = 0) {
  const tr = document.createElement('tr');
  const n = $('#poses').children.length + 1;
  tr.innerHTML = `<td>${n}</td><td><input class="px" inputmode="decimal" value="${num(x)}"></td><td><input class="py" inputmode="decimal" value="${num(y)}"></td>`
    + `<td><input class="pa" inputmode="decimal" value="${num(angle)}"></td><td><button type="button" class="ghost x" aria-label="${t('remove')}">×</button></td>`;
  tr.querySelector('.x').addEventListener('click', () => { tr.remove(); renumber(); });
  $('#poses').append(tr);
}
function renumber() { [...$('#poses').children].forEach((tr, i) => { tr.firstChild.textContent = String(i + 1); }); }
function poses() {
  return [...$('#poses').children].map((tr) => ['.px', '.py', '.pa'].map((c) => tr.querySelector(c).value.trim()));
}

// Each text method keeps its own task text while another is shown (an emptied one starts again
// from its example).
function showMethod(m) {
  if (textMethods[synth.method]) synth.texts[synth.method] = $('#task').value || undefined;
  // The designs listed are the last method's answer: they go with it (and a run still under
  // way for it is not listed when it answers).
  if (m !== synth.method) {
    stopPreview();
    $('#designs').replaceChildren();
    $('#synth-status').textContent = '';
    synth.run += 1;
  }
  synth.method = m;
  stopTapping();
  const textual = textMethods[m];
  $('#task').hidden = !textual;
  $('#five-tap').hidden = !textual;
  $('#synth-hint').hidden = !textual;
  if (textual) {
    for (const [el, key] of [[$('#five-tap'), textual.tap], [$('#synth-hint'), textual.hint]]) {
      el.dataset.i18n = key;
      el.textContent = t(key);
    }
    if (synth.texts[m] !== undefined) $('#task').value = synth.texts[m];
    else if (m !== 'five-point' || !/^task: five-point/m.test($('#task').value)) {
      $('#task').value = '';
      app.api(`/api/examples/${textual.example}`, undefined, 'text').then((txt) => {
        if (synth.method === m && !$('#task').value) { $('#task').value = txt; drawMarks(); }
      }).catch(() => {});
    }
  }
  setTimeout(drawMarks);
  $('#synth-burmester').hidden = m !== 'burmester';
  $('#synth-function').hidden = m !== 'function';
}

// ------------------------------------------------------------------------------ task text

// A text task's target points, read back from its text (for the preview's marks).
function fivePointTargets(text) {
  const block = /^points:\s*(?:#.*)?\n((?:[ \t]*-[^\n]*\n?)+)/m.exec(text);
  if (!block) return [];
  return [...block[1].matchAll(/\[\s*([-+\d.eE]+)\s*,\s*([-+\d.eE]+)\s*\]/g)].map((m) => [+m[1], +m[2]]);
}

function setFivePointTargets(points) {
  const ta = $('#task');
  const list = points.map(([x, y]) => `  - [${num(x)}, ${num(y)}]`).join('\n');
  const re = /^points:[^\n]*\n(?:[ \t]*-[^\n]*\n?)*/m;
  ta.value = re.test(ta.value) ? ta.value.replace(re, `points:            # tapped on the drawing\n${list}\n`) : `${ta.value.trimEnd()}\npoints:\n${list}\n`;
}

function lengthUnit() { return app.state.check?.units?.length ?? 'mm'; }

function burmesterTask() {
  const rows = poses();
  const lines = [`task: burmester`, `name: ${JSON.stringify(t('bmName', rows.length))}`, `units: {length: ${lengthUnit()}, angle: deg}`, 'poses:'];
  for (const [x, y, a] of rows) lines.push(`  - {point: [${x}, ${y}], angle: ${a}}`);
  if (rows.length === 3 && $('#bm-fixed').checked) {
    lines.push('fixed_pivots:', `  a: [${$('#bm-ax').value}, ${$('#bm-ay').value}]`, `  b: [${$('#bm-bx').value}, ${$('#bm-by').value}]`);
  }
  synth.targets = rows.map(([x, y, a]) => [+x, +y, +a]);
  return `${lines.join('\n')}\n`;
}

// The function form's task text. Where each field's value lands in it is kept in synth.fields
// ({id, line, column, quoted}), so that an error the server places in this text, which the
// student never sees, is said at the field and the column within it.
function functionTask() {
  const v = (id) => $(`#${id}`).value.trim();
  synth.targets = [];
  synth.fields = [];
  const lines = [];
  // A line of `parts`: literal text, or [field id] whose value is written there.
  const line = (...parts) => {
    let text = '';
    for (const part of parts) {
      if (typeof part === 'string') { text += part; continue; }
      const [id, quoted] = part;
      const value = quoted ? JSON.stringify(v(id)) : v(id);
      synth.fields.push({ id, line: lines.length + 1, column: text.length + 1 + (quoted ? 1 : 0), length: value.length, quoted });
      text += value;
    }
    lines.push(text);
  };
  line('task: function');
  line(`name: ${JSON.stringify(`y = ${v('fn-expr')}`)}`);
  line(`units: {length: ${lengthUnit()}, angle: deg}`);
  line('function: ', ['fn-expr', true]);
  line('x: [', ['fn-x0'], ', ', ['fn-x1'], ']');
  line('input_range: [', ['fn-in0'], ', ', ['fn-in1'], ']');
  line('output_range: [', ['fn-out0'], ', ', ['fn-out1'], ']');
  line('points: ', ['fn-points']);
  line(`spacing: ${$('#fn-spacing').value}`);
  line('frame: ', ['fn-frame']);
  return `${lines.join('\n')}\n`;
}

// The form field an error of the function task's text is about, and the column within the
// field's value (1 at its first character), or null for an error of no field.
function functionField(info) {
  if (synth.method !== 'function' || !info?.line) return null;
  const col = info.column ?? 1;
  const onLine = (synth.fields ?? []).filter((f) => f.line === info.line);
  // The last field starting at or before the column (a closing quote or bracket counts as its end).
  const f = onLine.filter((x) => x.column <= col + (x.quoted ? 1 : 0)).at(-1) ?? onLine[0];
  if (!f) return null;
  const inValue = Math.min(Math.max(col - f.column + 1, 1), $(`#${f.id}`).value.trim().length + 1);
  return { id: f.id, column: inValue };
}

// Says a synthesis error: at a form field (marked, with the caret put at the column) when it is
// about one, else at the task text's line and column.
function showSynthError(e) {
  const i = e.info ?? {};
  for (const x of document.querySelectorAll('#synth-function input.bad')) x.classList.remove('bad');
  const at = functionField(i);
  if (!at) {
    $('#synth-status').textContent = (i.line ? t('errorAt', i.line, i.column ?? 1) : '') + e.message;
    return;
  }
  const input = $(`#${at.id}`);
  const label = input.closest('label')?.querySelector('span')?.textContent ?? at.id;
  const where = at.id === 'fn-expr' ? t('fnFieldError', at.column) : `${label}: `;
  $('#synth-status').textContent = where + e.message;
  input.classList.add('bad');
  input.focus();
  const start = input.value.length - input.value.trimStart().length + at.column - 1;
  try { input.setSelectionRange(start, start); } catch { /* not a text field */ }
}

function taskText() {
  if (synth.method === 'burmester') return burmesterTask();
  if (synth.method === 'function') return functionTask();
  const text = $('#task').value;
  synth.targets = fivePointTargets(text);
  return text;
}

// ------------------------------------------------------------------------------ tapping

function stopTapping() {
  synth.tapping = null;
  synth.taps = [];
  for (const b of document.querySelectorAll('button.tap')) b.classList.remove('on');
  document.querySelector('#drawing')?.classList.remove('tapping');
  drawMarks();
}

function startTapping(kind) {
  if (synth.tapping === kind) {
    // A path takes as many points as tapped: pressing the button again ends the tapping. Any
    // other tapping ends with what was taken; the status says so rather than asking for more.
    const done = kind === 'points' && !Number.isFinite(textMethods[synth.method].taps) && synth.taps.length > 0;
    if (done) setFivePointTargets(synth.taps);
    const taken = kind === 'poses' ? $('#poses').children.length : synth.taps.length;
    stopTapping();
    $('#synth-status').textContent = done || (kind === 'poses' && taken >= 3) ? t('tapped') : t('tapStopped', taken);
    return;
  }
  if (!document.querySelector('#drawing svg')) { $('#synth-status').textContent = t('tapNeedsDrawing'); return; }
  stopTapping();
  synth.tapping = kind;
  $(kind === 'points' ? '#five-tap' : '#pose-tap').classList.add('on');
  $('#drawing').classList.add('tapping');
  $('#synth-status').textContent = kind === 'points' ? tapStatus(0) : t('tapPosesNow', 0);
  if (kind === 'poses') $('#poses').replaceChildren();
  // On a phone the drawing is above the panel: bring it into view.
  $('#drawing').scrollIntoView({ block: 'nearest' });
}

function tapStatus(n) {
  const need = textMethods[synth.method].taps;
  return Number.isFinite(need) ? t('tapPointsNow', n, need) : t('tapPathNow', n);
}

function modelPoint(e) {
  const svg = $('#drawing svg');
  const p = new DOMPoint(e.clientX, e.clientY).matrixTransform(svg.getScreenCTM().inverse());
  return [p.x, -p.y];
}

// Taps are caught before the drawing's own handlers (dragging, creating points).
function onTap(e) {
  if (!synth.tapping || !e.target.closest('#drawing svg')) return;
  e.preventDefault();
  e.stopImmediatePropagation();
  const [x, y] = modelPoint(e);
  const digits = Math.max(0, Math.min(6, 2 - Math.floor(Math.log10(app.state.geometry?.scale || 1))));
  const p = [+x.toFixed(digits), +y.toFixed(digits)];
  if (synth.tapping === 'points') {
    synth.taps.push(p);
    $('#synth-status').textContent = tapStatus(synth.taps.length);
    if (synth.taps.length === textMethods[synth.method].taps) {
      setFivePointTargets(synth.taps);
      stopTapping();
      $('#synth-status').textContent = t('tapped');
    }
  } else {
    addPose(p[0], p[1], 0);
    const n = $('#poses').children.length;
    $('#synth-status').textContent = t('tapPosesNow', n);
    if (n === 5) { stopTapping(); $('#synth-status').textContent = t('tapped'); }
  }
  drawMarks();
}

// The targets over the mechanism while the synthesis panel is open: the points being tapped, a
// text task's points or the Burmester poses (with their angles).
function markedTargets() {
  if (synth.tapping === 'points') return synth.taps;
  if (!document.querySelector('#panel-synthesis.active')) return [];
  if (synth.method === 'burmester') return poses().map(([x, y, a]) => [+x, +y, +a]).filter(([x, y]) => Number.isFinite(x) && Number.isFinite(y));
  if (textMethods[synth.method]) return fivePointTargets($('#task').value);
  return [];
}

function drawMarks() {
  const svg = document.querySelector('#drawing svg');
  if (!svg) return;
  svg.querySelector('.synth-marks')?.remove();
  const pts = markedTargets();
  if (!pts.length) return;
  const s = app.state.geometry?.scale ?? 1;
  const g = document.createElementNS('http://www.w3.org/2000/svg', 'g');
  g.setAttribute('class', 'synth-marks');
  // Taps in progress are all numbered: the count is what the student follows.
  g.innerHTML = synth.tapping === 'points' ? pts.map(([x, y], i) => targetMark(x, y, s, i + 1)).join('') : targetMarks(pts, s);
  svg.append(g);
}

// The numbers of a list of targets: of a few, each; of many (a path fit's 30 measured points,
// at a preview's size), the first, the last and every k-th, about six. A number that would
// cover one already placed (points close together, a closed path's last beside its first) is
// left out, so that the numbers never pile on one another. The set of the indices numbered.
function numbered(pts, s) {
  const n = pts.length;
  const k = Math.ceil(n / 6);
  const order = n <= 9 ? pts.map((_, i) => i)
    : [0, n - 1, ...pts.map((_, i) => i).filter((i) => (i + 1) % k === 0 && i !== n - 1)];
  const size = 3.2 * s;  // targetMark's font size, and where its text is drawn
  const placed = [];
  const shown = new Set();
  for (const i of order) {
    const X = +pts[i][0] + 2 * s; const Y = -pts[i][1] + 4.5 * s;
    // The text's box, a little generous: digits about 0.6 em wide, ascent and descent.
    const box = [X - 0.1 * size, Y - 1.0 * size, X + (0.62 * String(i + 1).length + 0.1) * size, Y + 0.3 * size];
    if (placed.some((b) => box[0] < b[2] && b[0] < box[2] && box[1] < b[3] && b[1] < box[3])) continue;
    placed.push(box);
    shown.add(i);
  }
  return shown;
}

// The marks of a list of targets ([x, y] points or [x, y, angle] poses) at scale s.
function targetMarks(pts, s) {
  const shown = numbered(pts, s);
  return pts.map(([x, y, a], i) => targetMark(x, y, s, shown.has(i) ? i + 1 : '', a)).join('');
}

// A target point, or a pose: the point and a tick along the coupler's angle; its number, if any.
function targetMark(x, y, s, label, angle = undefined) {
  const X = +x; const Y = -y;
  const r = (angle ?? 0) * Math.PI / 180;
  const tick = Number.isFinite(angle) ? `<path d="M${X},${Y}l${+(7 * s * Math.cos(r)).toFixed(4)},${+(-7 * s * Math.sin(r)).toFixed(4)}" stroke="#d92d20" stroke-width="2.5" vector-effect="non-scaling-stroke"/>` : '';
  return `<g class="target">${tick}<circle cx="${X}" cy="${Y}" r="${1.6 * s}" fill="none" stroke="#d92d20" stroke-width="2" vector-effect="non-scaling-stroke"/>`
    + `<path d="M${X - 2.6 * s},${Y}h${5.2 * s}M${X},${Y - 2.6 * s}v${5.2 * s}" stroke="#d92d20" stroke-width="1.5" vector-effect="non-scaling-stroke"/>`
    + (label === '' ? '' : `<text x="${X + 2 * s}" y="${Y + 4.5 * s}" font-size="${3.2 * s}" fill="#d92d20" font-family="system-ui, sans-serif">${label}</text>`) + '</g>';
}

// ------------------------------------------------------------------------------ designs

function tags(d) {
  const out = [];
  if (!d.real) out.push(`<span class="tag warn">${t('complex')}</span>`);
  if (d.grashof) out.push(`<span class="tag">${app.esc(d.grashof)}</span>`);
  if (d.real && d.valid === false) out.push(`<span class="tag warn">${t('invalidDesign')}</span>`);
  if (d.defect_free) out.push(`<span class="tag">${t('defectFree')}</span>`);
  else if (d.defects) {
    for (const k of ['circuit', 'branch', 'order', 'unreached']) if (d.defects[k]) out.push(`<span class="tag warn">${t(`defect_${k}`)}</span>`);
  }
  return out.join('');
}

function designItem(d, res) {
  const li = document.createElement('li');
  li.dataset.rank = d.rank;
  const { fmt, esc } = app;
  const err = d.max_error === undefined ? '' : ` · ${t('maxErr')} ${fmt(d.max_error)} ${esc(res.error_unit ?? '')}`;
  li.innerHTML = `<div class="head"><span class="rank">${d.rank}</span><span class="info">${tags(d)}<br>${t('minMu')} ${fmt(d.min_transmission)}°${err}</span>`
    + `<span class="acts"><button type="button" class="ghost" data-preview="${d.rank}" data-i18n="preview">${t('preview')}</button>`
    + `<button type="button" data-design="${d.rank}" data-i18n="open">${t('open')}</button></span></div><div class="pv"></div>`;
  const ok = Boolean(d.model);
  li.querySelector('[data-design]').disabled = !ok;
  li.querySelector('[data-preview]').disabled = !ok;
  li.querySelector('[data-design]').addEventListener('click', async () => {
    stopPreview();
    for (const x of document.querySelectorAll('[data-example]')) x.classList.remove('current');
    // Its downloads are named after the design, not the example opened before it.
    app.state.current = `${$('#synth-method').value}-design-${d.rank}`;
    app.showTab('editor');
    await app.setText(d.model);
  });
  li.querySelector('[data-preview]').addEventListener('click', () => preview(d, li));
  return li;
}

async function runSynthesis() {
  const list = $('#designs');
  const st = $('#synth-status');
  stopTapping();
  stopPreview();
  list.replaceChildren();
  for (const x of document.querySelectorAll('#synth-function input.bad')) x.classList.remove('bad');
  st.textContent = t('running');
  $('#synth-run').disabled = true;
  const run = ++synth.run;
  try {
    const res = await app.api(`/api/synth/${synth.method}`, { task: taskText(), top: 10, models: true }, 'json', { label: t('synthesis') });
    if (run !== synth.run) return;  // the method changed meanwhile
    st.textContent = t('designsFound', res.designs.length, res.solutions);
    list.replaceChildren(...res.designs.map((d) => designItem(d, res)));
    if (res.notes?.length) st.textContent += ` · ${res.notes.join('; ')}`;
  } catch (e) {
    if (run === synth.run) showSynthError(e);
  } finally {
    $('#synth-run').disabled = false;
  }
}

// ------------------------------------------------------------------------------ preview

function stopPreview() {
  if (!synth.preview) return;
  cancelAnimationFrame(synth.preview.raf);
  synth.preview.el.replaceChildren();
  synth.preview.li.classList.remove('previewing');
  synth.preview = null;
}

// The design's own model, solved by the server, animated in the list with the targets marked.
async function preview(d, li) {
  const same = synth.preview?.li === li;
  stopPreview();
  if (same) return;
  const el = li.querySelector('.pv');
  el.textContent = t('loading');
  try {
    // The core's drawing of the design at the preview's size, moved through its sweep.
    const box = el.getBoundingClientRect();
    const width = Math.round(Math.min(Math.max(box.width || 320, 100), 1200));
    const scene = await app.api('/api/render', { model: d.model, kind: 'draw', format: 'scene', width, height: Math.round(width * 0.62) });
    el.innerHTML = drawingSvg(scene);
    const svg = el.querySelector('svg');
    const marks = document.createElementNS('http://www.w3.org/2000/svg', 'g');
    marks.setAttribute('class', 'synth-marks');
    marks.innerHTML = targetMarks(synth.targets, markScale(scene));
    svg.append(marks);
    const n = scene.steps.length;
    const p = { el, li, raf: 0, start: 0 };
    synth.preview = p;
    li.classList.add('previewing');
    const step = (now) => {
      if (synth.preview !== p) return;
      if (!p.start) p.start = now;
      const i = Math.floor(((now - p.start) / 4000) * n) % n;
      poseDrawing(svg, scene, i);
      el.dataset.frame = String(i);
      p.raf = requestAnimationFrame(step);
    };
    p.raf = requestAnimationFrame(step);
  } catch (e) {
    el.textContent = `${t('failed')}: ${e.message}`;
  }
}

// ------------------------------------------------------------------------------ start

export function initSynthesis(context) {
  app = context;
  buildForms();
  const hint = document.querySelector('#panel-synthesis .hint');
  hint.id = 'synth-hint';
  translatePage();
  $('#synth-method').addEventListener('change', (e) => showMethod(e.target.value));
  $('#five-tap').addEventListener('click', () => startTapping('points'));
  $('#pose-tap').addEventListener('click', () => startTapping('poses'));
  $('#pose-add').addEventListener('click', () => { if ($('#poses').children.length < 5) addPose(); });
  $('#bm-fixed').addEventListener('change', (e) => { $('#bm-pivots').hidden = !e.target.checked; });
  $('#synth-run').addEventListener('click', runSynthesis);
  $('#drawing').addEventListener('pointerdown', onTap, true);
  document.addEventListener('nbar:solved', drawMarks);
  document.addEventListener('nbar:drawn', drawMarks);
  $('#poses').addEventListener('input', drawMarks);
  $('#task').addEventListener('input', drawMarks);
  for (const b of document.querySelectorAll('[data-tab]')) b.addEventListener('click', drawMarks);
  showMethod(methods[0]);
}
