// The Model tab: the model's points, bodies, joints, drivers and loads as tables of fields, and
// the selected body's properties (bar or shape, thickness, material, mass). The tables are read
// from the editor's text and every change is written back into it (model-edit.js); a value the
// server rejects is marked in its field with the server's message.
import { t } from './i18n.js';
import { setIn, deleteIn, parseModel, renamePoint, deletePoint } from './yaml-text.js';
import { applyEdit, modelText, editContext } from './model-edit.js';
import { selectBody } from './canvas-tools.js';
import { addSliderOn } from './build-model.js';

const $ = (s) => document.querySelector(s);
const builtInMaterials = ['steel', 'stainless-steel', 'aluminium', 'brass', 'cast-iron', 'titanium', 'abs', 'acrylic', 'nylon'];
let selected = null;
let lastError = null;
let lastRefusal = null;  // a structured edit refused (a rename that cannot be done safely)
let lastRefusalAt = null;
// The field last written from the tables (its data-path), until an analysis succeeds: an error
// the server places at no field (a length that does not assemble) is marked there, and the
// marked field is brought into view below the sticky header.
let lastEdited = null;
let reveal = false;

const esc = (s) => String(s ?? '').replace(/[&<>"]/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' }[c]));
const isObj = (v) => v && typeof v === 'object' && !Array.isArray(v);

// A field's text as typed, back to a YAML value: '' removes the key; numbers stay numbers;
// 'list' fields are comma-separated names; anything else is written as text for the server to
// judge (a bad value then gets its located error).
function parseField(kind, s) {
  const v = s.trim();
  if (v === '') return undefined;
  if (kind === 'list') return v.replace(/^\[|\]$/g, '').split(',').map((x) => x.trim()).filter(Boolean);
  if (kind === 'pair') {
    const parts = v.replace(/^\[|\]$/g, '').split(',').map((x) => x.trim());
    return parts.map((x) => (/^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$/.test(x) ? Number(x) : x));
  }
  if (/^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$/.test(v)) return Number(v);
  return v;
}
function showValue(v) {
  if (v === undefined || v === null) return '';
  if (Array.isArray(v)) return v.map(showValue).join(', ');
  if (isObj(v)) return JSON.stringify(v);
  return String(v);
}

// <input> for the value at `path`; `kind` says how to read it back.
function field(path, value, kind = 'num', label = '') {
  const attrs = `data-path="${esc(JSON.stringify(path))}" data-kind="${kind}" aria-label="${esc(label || path.join(' '))}"`;
  const mode = kind === 'num' ? ' inputmode="decimal"' : '';
  return `<input class="cell" ${attrs}${mode} value="${esc(showValue(value))}" spellcheck="false" autocomplete="off">`;
}

// A number typed past a double's range (1e400) reads as Infinity, which would be written into
// the YAML as such: the typed text, when it holds one, else null.
function overflowing(value, typed) {
  const bad = (v) => (typeof v === 'number' && !Number.isFinite(v)) || (Array.isArray(v) && v.some(bad));
  return bad(value) ? typed.trim() : null;
}

// Refuses a field's value without touching the YAML: the message beside the field (and above the
// tables), the field marked and left holding what was typed, so that it can be corrected.
function refuseField(input, message) {
  const typed = input.value;
  const sel = input.dataset.path ? `.cell[data-path="${CSS.escape(input.dataset.path)}"]`
    : input.dataset.bodyProp ? `.cell[data-body-prop="${input.dataset.bodyProp}"]` : `.cell[data-bar-prop="${input.dataset.barProp}"]`;
  lastRefusal = t('editFailed', message);
  lastRefusalAt = sel;
  editContext().status(lastRefusal, true);
  renderTables();
  const cell = document.querySelector(`#model-tables ${sel}`);
  if (!cell) return;
  cell.value = typed;
  cell.classList.add('bad');
  cell.title = message;
}

// A field edited to a value that changes nothing takes back a refusal shown for it.
function clearRefusal() {
  if (!lastRefusal) return;
  lastRefusal = null;
  renderTables();
}

function commit(input) {
  const path = JSON.parse(input.dataset.path);
  const value = parseField(input.dataset.kind, input.value);
  const huge = overflowing(value, input.value);
  if (huge !== null) { refuseField(input, t('numberOutOfRange', huge)); return; }
  lastEdited = input.dataset.path;
  reveal = true;
  if (!applyEdit((text) => (value === undefined ? deleteIn(text, path) : setIn(text, path, value)))) clearRefusal();
}

// ------------------------------------------------------------------------------ sections

function section(title, head, rows, empty, adder = '') {
  const body = rows.length ? rows.join('') : `<tr><td colspan="${head.length}" class="none">${esc(empty)}</td></tr>`;
  return `<h3>${esc(title)}</h3><div class="mtable"><table><thead><tr>${head.map((h) => `<th>${esc(h)}</th>`).join('')}</tr></thead><tbody>${body}</tbody></table></div>${adder}`;
}

// A row's × button: deletes the entry at `path` (a list item or a mapping's pair).
function removeButton(path, label) {
  return `<td class="acts"><button type="button" class="ghost" data-delete-path="${esc(JSON.stringify(path))}" aria-label="${esc(label)}" title="${esc(label)}">×</button></td>`;
}
// A <select> of names for an adder form.
function picker(role, names, label, chosen = names[0]) {
  return `<label class="add-field"><small>${esc(label)}</small><select data-add="${role}" aria-label="${esc(label)}">${names.map((n) => `<option value="${esc(n)}"${n === chosen ? ' selected' : ''}>${esc(n || t('newBlock'))}</option>`).join('')}</select></label>`;
}
function adder(kind, parts, label) {
  return `<div class="adder" data-adder="${kind}">${parts.join('')}<button type="button" data-add-go="${kind}">${esc(label)}</button></div>`;
}
const pointNames = (m) => Object.keys(isObj(m.points) ? m.points : {});
const bodyNames = (m) => Object.keys(isObj(m.bodies) ? m.bodies : {});

function pointsSection(m) {
  const ground = new Set(Array.isArray(m.ground) ? m.ground : []);
  const rows = Object.entries(isObj(m.points) ? m.points : {}).map(([p, xy]) => {
    const pair = Array.isArray(xy);
    return `<tr data-row-point="${esc(p)}"><th><input class="cell pname" data-rename="${esc(p)}" value="${esc(p)}" spellcheck="false" autocomplete="off" aria-label="${esc(t('nameOf', p))}"></th>`
      + `<td>${pair ? field(['points', p, 0], xy[0], 'num', `${p} x`) : field(['points', p], xy, 'pair', p)}</td>`
      + `<td>${pair ? field(['points', p, 1], xy[1], 'num', `${p} y`) : ''}</td>`
      + `<td><label class="tap"><input type="checkbox" class="ground" data-point="${esc(p)}" aria-label="${esc(t('groundOf', p))}"${ground.has(p) ? ' checked' : ''}></label></td>`
      + `<td class="acts"><button type="button" class="ghost" data-delete-point="${esc(p)}" aria-label="${esc(t('deletePoint', p))}" title="${esc(t('deletePoint', p))}">×</button></td></tr>`;
  });
  return section(t('points'), [t('name'), 'x', 'y', t('ground'), ''], rows, t('none'));
}

function bodiesSection(m) {
  const lengths = isObj(m.lengths) ? m.lengths : {};
  const rows = Object.entries(isObj(m.bodies) ? m.bodies : {}).map(([b, v]) => {
    const long = isObj(v);
    const pts = long ? v.points : v;
    const path = long ? ['bodies', b, 'points'] : ['bodies', b];
    const two = Array.isArray(pts) && pts.length === 2;
    return `<tr data-row-body="${esc(b)}"><th><button type="button" class="link" data-select-body="${esc(b)}">${esc(b)}</button></th>`
      + `<td>${field(path, pts, 'list', `${b} ${t('bodyPoints')}`)}</td>`
      + `<td>${two ? field(['lengths', b], lengths[b], 'num', `${b} ${t('length')}`) : ''}</td></tr>`;
  });
  return section(t('bodies'), [t('name'), t('bodyPoints'), t('length')], rows, t('none'));
}

// Revolute joints are implicit (bodies sharing a point), listed from the server's check; sliders
// and slots are written in the model and edited here.
function jointsSection(m) {
  // The joints of the text on screen (the check's, or while it cannot be solved the outline's):
  // never the last model that solved.
  // The core lists the revolutes first, then one line per slider and per slot; the lines come in
  // the language asked, so the revolutes are told by their place, not by their words.
  const joints = editContext().state.joints ?? [];
  const written = ['sliders', 'slots'].reduce((n, kind) => n + (Array.isArray(m[kind]) ? m[kind].length : 0), 0);
  const rows = joints.slice(0, Math.max(joints.length - written, 0)).map((j) => `<tr><td colspan="4" class="note">${esc(j)}</td></tr>`);
  for (const kind of ['sliders', 'slots']) {
    (Array.isArray(m[kind]) ? m[kind] : []).forEach((s, i) => {
      if (!isObj(s)) return;
      rows.push(`<tr><th>${kind === 'sliders' ? t('slider') : t('slot')}${s.body ? ` ${esc(s.body)}` : ''}</th>`
        + `<td>${field([kind, i, 'point'], s.point, 'text', `${t(kind === 'sliders' ? 'slider' : 'slot')} ${i + 1}: ${t('point')}`)}</td>`
        + `<td>${field([kind, i, 'along'], s.along, 'list', `${t(kind === 'sliders' ? 'slider' : 'slot')} ${i + 1}: ${t('along')}`)}</td>${removeButton([kind, i], t('deleteRow'))}</tr>`);
    });
  }
  // A new slider: a body, its sliding point, and the two points of its guide.
  const pts = pointNames(m); const bs = bodyNames(m);
  const add = pts.length >= 3 ? adder('slider', [
    picker('body', ['', ...bs], t('body'), ''), picker('point', pts, t('point'), pts.at(-1)),
    picker('along0', pts, `${t('along')} 1`, pts[0]), picker('along1', pts, `${t('along')} 2`, pts[1]),
  ], t('addSlider')) : '';
  return section(t('joints'), [t('joint'), t('point'), t('along'), ''], rows, t('none'), add);
}

function driversSection(m) {
  const rows = (Array.isArray(m.drivers) ? m.drivers : []).map((d, i) => {
    if (!isObj(d)) return '';
    const what = ['angle', 'distance', 'slide'].find((k) => k in d);
    const label = what ? `${what}: ${showValue(d[what])}${d.relative_to ? ` / ${d.relative_to}` : ''}` : '?';
    const cells = d.law !== undefined
      ? `<td colspan="4">${field(['drivers', i, 'law'], d.law, 'text', `${t('driver')} ${i + 1}: ${t('law')}`)}</td>`
      : ['from', 'to', 'speed'].map((k) => `<td>${field(['drivers', i, k], d[k], 'num', `${t('driver')} ${i + 1}: ${t(k)}`)}</td>`).join('')
        + `<td>${field(['drivers', i, 'at_limits'], d.at_limits, 'text', `${t('driver')} ${i + 1}: ${t('atLimits')}`)}</td>`;
    return `<tr><th>${esc(label)}</th>${cells}${removeButton(['drivers', i], t('deleteRow'))}</tr>`;
  });
  // A new driver: the angle of a body, a full turn at 60 rpm (edit the numbers after).
  const bs = bodyNames(m);
  const add = bs.length ? adder('driver', [picker('body', bs, t('body'))], t('addDriver')) : '';
  // `at_limits`: stop (the default) or reverse, which rocks the input between its limits.
  return section(t('drivers'), [t('driver'), t('from'), t('to'), t('speed'), t('atLimits'), ''], rows, t('none'), add);
}

function loadsSection(m) {
  const rows = [];
  (Array.isArray(m.forces) ? m.forces : []).forEach((f, i) => {
    if (!isObj(f)) return;
    const comps = Array.isArray(f.force)
      ? `<td>${field(['forces', i, 'force', 0], f.force[0], 'num', `${t('load')} ${i + 1}: Fx`)}</td><td>${field(['forces', i, 'force', 1], f.force[1], 'num', `${t('load')} ${i + 1}: Fy`)}</td>`
      : `<td>${field(['forces', i, 'fx'], f.fx, 'num', `${t('load')} ${i + 1}: Fx`)}</td><td>${field(['forces', i, 'fy'], f.fy, 'num', `${t('load')} ${i + 1}: Fy`)}</td>`;
    rows.push(`<tr><th>${t('force')} ${esc(f.point)}</th>${comps}${removeButton(['forces', i], t('deleteRow'))}</tr>`);
  });
  (Array.isArray(m.torques) ? m.torques : []).forEach((q, i) => {
    if (!isObj(q)) return;
    rows.push(`<tr><th>${t('torque')} ${esc(q.body)}</th><td colspan="2">${field(['torques', i, 'torque'], q.torque, 'num', `${t('torque')} ${esc(q.body)}`)}</td>${removeButton(['torques', i], t('deleteRow'))}</tr>`);
  });
  (Array.isArray(m.springs) ? m.springs : []).forEach((s, i) => {
    if (!isObj(s)) return;
    rows.push(`<tr><th>${t('spring')} ${esc(showValue(s.between))}</th><td>${field(['springs', i, 'stiffness'], s.stiffness, 'num', `${t('spring')} ${i + 1}: ${t('stiffness')}`)}</td>`
      + `<td>${field(['springs', i, 'free_length'], s.free_length, 'num', `${t('spring')} ${i + 1}: ${t('freeLength')}`)}</td>${removeButton(['springs', i], t('deleteRow'))}</tr>`);
  });
  // A new force at a point (N, pointing down) or torque on a body (N m): edit the values after.
  const pts = pointNames(m); const bs = bodyNames(m);
  const add = (pts.length ? adder('force', [picker('point', pts, t('point'), pts.at(-1))], t('addForce')) : '')
    + (bs.length ? adder('torque', [picker('body', bs, t('body'), bs.at(-1))], t('addTorque')) : '');
  return section(t('loads'), [t('load'), t('value1'), t('value2'), ''], rows, t('noLoads'), add);
}

// ------------------------------------------------------------------------------ body panel

// The path of a body property: the long form's key; a short-form body is rewritten in long form
// ({points: [...], key: value}) by the first property set on it.
function setBodyProperty(name, key, value) {
  applyEdit((text) => {
    const body = parseModel(text).toJS()?.bodies?.[name];
    if (value === undefined) return isObj(body) ? deleteIn(text, ['bodies', name, key]) : text;
    if (isObj(body)) return setIn(text, ['bodies', name, key], value);
    return setIn(text, ['bodies', name], { points: body ?? [], [key]: value });
  });
}

function bodyPanel(m) {
  const body = m.bodies?.[selected];
  if (body === undefined) return '';
  const b = isObj(body) ? body : { points: body };
  const form = b.shape ? 'shape' : (b.bar ? 'bar' : 'none');
  const mats = [...builtInMaterials, ...Object.keys(isObj(m.materials) ? m.materials : {})];
  const opt = (v, label) => `<option value="${v}"${form === v ? ' selected' : ''}>${esc(label)}</option>`;
  const bar = isObj(b.bar) ? b.bar : {};
  const row = (label, html) => `<label class="prop"><span>${esc(label)}</span>${html}</label>`;
  const prop = (key, label) => row(label, `<input class="cell" data-body-prop="${key}" inputmode="decimal" value="${esc(showValue(b[key]))}" aria-label="${esc(label)}">`);
  const barField = (key, label) => row(label, `<input class="cell" data-bar-prop="${key}" inputmode="decimal" value="${esc(showValue(bar[key]))}" aria-label="${esc(label)}">`);
  return `<div class="bodypanel" data-body-panel="${esc(selected)}">
    <div class="row"><h3>${esc(t('bodyTitle', selected))}</h3><button type="button" class="ghost" data-close-body aria-label="${esc(t('close'))}">×</button></div>
    ${row(t('bodyPoints'), `<input class="cell" data-body-prop="points" data-kind="list" value="${esc(showValue(b.points))}" aria-label="${esc(t('bodyPoints'))}">`)}
    ${row(t('form'), `<select data-body-form aria-label="${esc(t('form'))}">${opt('none', t('formNone'))}${opt('bar', t('formBar'))}${opt('shape', t('formShape'))}</select>`)}
    ${form === 'bar' ? barField('width', t('barWidth')) + barField('margin', t('barMargin')) + barField('hole', t('barHole')) : ''}
    ${form === 'shape' ? `<p class="hint">${esc(t('shapeInYaml'))}</p>` : ''}
    ${prop('thickness', t('thickness'))}
    ${row(t('material'), `<input class="cell" data-body-prop="material" data-kind="text" list="nbar-materials" value="${esc(isObj(b.material) ? '' : showValue(b.material))}" aria-label="${esc(t('material'))}"><datalist id="nbar-materials">${mats.map((x) => `<option value="${esc(x)}">`).join('')}</datalist>`)}
    ${prop('mass', t('mass'))}
    ${prop('inertia', t('inertia'))}
    <div class="row"><button type="button" data-delete-body>${esc(t('deleteBody'))}</button></div>
  </div>`;
}

function commitBody(input) {
  if (input.dataset.bodyProp || input.dataset.barProp) {
    const huge = overflowing(parseField(input.dataset.kind || 'num', input.value), input.value);
    if (huge !== null) { refuseField(input, t('numberOutOfRange', huge)); return; }
  }
  if (input.dataset.bodyProp) {
    setBodyProperty(selected, input.dataset.bodyProp, parseField(input.dataset.kind || 'num', input.value));
  } else if (input.dataset.barProp) {
    const v = parseField('num', input.value);
    applyEdit((text) => (v === undefined ? deleteIn(text, ['bodies', selected, 'bar', input.dataset.barProp]) : setIn(text, ['bodies', selected, 'bar', input.dataset.barProp], v)));
  } else if (input.dataset.bodyForm !== undefined) {
    const form = input.value;
    applyEdit((text) => {
      const m = parseModel(text).toJS();
      const body = m.bodies?.[selected];
      let out = text;
      if (form === 'none') {
        if (isObj(body)) for (const k of ['bar', 'shape']) out = deleteIn(out, ['bodies', selected, k]);
        return out;
      }
      // A first guess for the user to adjust: the server's width for a new bar of this body (the
      // check's default_bar_width), or a plate outline around the body's drawn points, half that
      // width clear of them.
      const pts = (isObj(body) ? body.points : body) ?? [];
      const xy = pts.map((n) => m.points?.[n]).filter((v) => Array.isArray(v) && v.every(Number.isFinite));
      const checked = editContext().state.check?.bodies?.find((b) => b.name === selected);
      const width = checked?.default_bar_width ?? 1;
      const other = form === 'bar' ? 'shape' : 'bar';
      if (isObj(body)) out = deleteIn(out, ['bodies', selected, other]);
      let value = { width };
      if (form === 'shape') {
        const r = width / 2;
        const xs = xy.map((v) => v[0]); const ys = xy.map((v) => v[1]);
        const [x0, x1, y0, y1] = [Math.min(...xs) - r, Math.max(...xs) + r, Math.min(...ys) - r, Math.max(...ys) + r].map((v) => +v.toPrecision(6));
        value = { outline: [[x0, y0], [x1, y0], [x1, y1], [x0, y1]] };
      }
      if (!isObj(body)) return setIn(out, ['bodies', selected], { points: pts, [form]: value });
      return setIn(out, ['bodies', selected, form], value);
    });
  }
}

// ------------------------------------------------------------------------------ rendering

// Marks the field whose value the server's error points at (its line and column).
function markError() {
  for (const x of document.querySelectorAll('#model-tables .cell.bad')) { x.classList.remove('bad'); x.removeAttribute('title'); }
  for (const x of document.querySelectorAll('#model-tables .cell-error')) x.remove();
  const note = $('#model-problem');
  if (!note) return;
  // A refusal is what the student did last: it is said, before the error of the text on screen.
  note.textContent = lastRefusal ?? (lastError ? `${lastError.line ? t('errorAt', lastError.line, lastError.column ?? 1) : ''}${lastError.message}` : '');
  note.hidden = !lastError && !lastRefusal;
  if (lastRefusal) {
    const near = lastRefusalAt && document.querySelector(`#model-tables ${lastRefusalAt}`);
    const row = near?.closest('tr');
    if (row) row.insertAdjacentHTML('afterend', `<tr class="refusal"><td colspan="9"><small class="cell-error" role="alert">${esc(lastRefusal)}</small></td></tr>`);
    else near?.insertAdjacentHTML('afterend', `<small class="cell-error" role="alert">${esc(lastRefusal)}</small>`);
  }
  if (!lastError) return;
  const best = errorField();
  const edited = lastEdited && document.querySelector(`#model-tables .cell[data-path="${CSS.escape(lastEdited)}"]`);
  const cell = best ?? edited;
  if (cell) {
    cell.classList.add('bad');
    cell.title = lastError.message;
    // The message beside the field too: on a phone the panel's top may be scrolled away.
    cell.insertAdjacentHTML('afterend', `<small class="cell-error" role="alert">${esc(lastError.message)}</small>`);
  }
  // Once, after an edit from the tables: the field (or the note) scrolled into view under the
  // header (scroll-margin-top in style.css), not while the student types in the editor.
  // The field in the middle, so that its message below it shows too.
  if (reveal && document.querySelector('#panel-model.active')) {
    if (cell) cell.scrollIntoView({ block: 'center' }); else note.scrollIntoView({ block: 'nearest' });
  }
  reveal = false;
}

// The table field holding the place the server's error points at (its line and column).
function errorField() {
  if (!lastError?.line) return null;
  const text = modelText();
  const lines = text.split('\n');
  let at = 0;
  for (let i = 0; i < Math.min(lastError.line - 1, lines.length); i++) at += lines[i].length + 1;
  at += Math.max((lastError.column ?? 1) - 1, 0);
  let doc;
  try { doc = parseModel(text); } catch { return null; }
  let best = null;
  for (const input of document.querySelectorAll('#model-tables .cell[data-path]')) {
    const node = doc.getIn(JSON.parse(input.dataset.path), true);
    if (node?.range && at >= node.range[0] && at <= node.range[1] && (!best || node.range[1] - node.range[0] < best.size)) {
      best = { input, size: node.range[1] - node.range[0] };
    }
  }
  return best?.input ?? null;
}

// ------------------------------------------------------------------------------ adding, renaming

// Adds what an adder form describes at the end of its list (the list is created if missing).
function addEntry(form) {
  const pick = (role) => form.querySelector(`[data-add="${role}"]`)?.value;
  const kind = form.dataset.adder;
  const m = parseModel(modelText()).toJS() ?? {};
  const count = (key) => (Array.isArray(m[key]) ? m[key].length : 0);
  const entry = {
    driver: () => ['drivers', { angle: pick('body'), from: 0, to: 360, speed: '60 rpm' }],
    force: () => ['forces', { point: pick('point'), force: [0, -10] }],
    torque: () => ['torques', { body: pick('body'), torque: 1 }],
  }[kind];
  if (kind === 'slider') {
    // A refusal (the core's reason) is said beside the form too: on a phone the status is far.
    addSliderOn(pick('body') || null, pick('point'), [pick('along0'), pick('along1')]).then((result) => {
      if (typeof result !== 'string') return;
      lastRefusal = result;
      lastRefusalAt = '[data-add-go="slider"]';
      renderTables();
    });
    return;
  }
  if (!entry) return;
  const [key, value] = entry();
  applyEdit((text) => setIn(text, [key, count(key)], value));
}

// A refused structured edit (yaml-text.js's EditError) is said in the Model tab, beside the
// tables, as well as in the status line.
// `at` is the selector of the field or button the edit came from: the message goes beside it
// too, for on a phone the top of the tab may be scrolled away.
function refusable(change, at) {
  lastRefusal = null;
  try {
    change(modelText());
  } catch (e) {
    lastRefusal = t('editFailed', e.message);
    lastRefusalAt = at;
    editContext().status(lastRefusal, true);
    renderTables();
    return;
  }
  applyEdit(change);
}
function rename(input) {
  const from = input.dataset.rename;
  const to = input.value.trim();
  if (to === from) return;
  refusable((text) => renamePoint(text, from, to), `[data-rename="${CSS.escape(from)}"]`);
}

export function renderTables() {
  const host = $('#model-tables');
  if (!host) return;
  const focused = document.activeElement?.closest?.('#model-tables') ? document.activeElement : null;
  const keep = focused && (focused.dataset.path || focused.dataset.bodyProp || focused.dataset.barProp) && !focused.dataset.rename;
  const m = (() => { try { return parseModel(modelText()).toJS() ?? {}; } catch { return null; } })();
  if (!m) {
    host.innerHTML = `<p id="model-problem" class="problems bad"></p><p class="hint">${esc(t('fixYamlFirst'))}</p>`;
    markError();
    return;
  }
  if (selected && m.bodies?.[selected] === undefined) selected = null;
  host.innerHTML = `<p id="model-problem" class="problems bad" hidden></p>${selected ? bodyPanel(m) : `<p class="hint">${esc(t('modelHint'))}</p>`}`
    + pointsSection(m) + bodiesSection(m) + jointsSection(m) + driversSection(m) + loadsSection(m);
  markError();
  if (keep) {
    const sel = focused.dataset.path ? `[data-path="${CSS.escape(focused.dataset.path)}"]`
      : focused.dataset.bodyProp ? `[data-body-prop="${focused.dataset.bodyProp}"]` : `[data-bar-prop="${focused.dataset.barProp}"]`;
    const field = host.querySelector(sel);
    if (field) carryTyping(focused, field);
  }
}

// The tables are drawn again when an analysis ends, which may be while the next field is being
// typed in (the last one's edit was being solved): what is typed there, not yet committed, and
// the caret go over to the field drawn in its place, with the focus. The focus first: a value set
// after it counts as typed, so that leaving the field or Enter still commits it.
function carryTyping(from, to) {
  const typing = from instanceof HTMLInputElement && to instanceof HTMLInputElement && from.value !== from.defaultValue;
  to.focus();
  if (!typing) return;
  to.value = from.value;
  if (from.selectionStart !== null) to.setSelectionRange(from.selectionStart, from.selectionEnd);
}

export function showBody(name) {
  selected = name;
  selectBody(name);
  renderTables();
  if (name) {
    editContext().showTab('model');
    $('#model-tables .bodypanel')?.scrollIntoView({ block: 'nearest' });
  }
}

export function initTables() {
  const host = $('#model-tables');
  // A field is written when it is left or Enter is pressed, not at each keystroke.
  host.addEventListener('change', (e) => {
    const x = e.target;
    if (x.matches('input.ground')) {
      const name = x.dataset.point;
      applyEdit((text) => {
        const g = parseModel(text).toJS()?.ground;
        const list = Array.isArray(g) ? g : [];
        const i = list.indexOf(name);
        if (x.checked && i < 0) return setIn(text, ['ground', list.length], name);
        if (!x.checked && i >= 0) return deleteIn(text, ['ground', i]);
        return text;
      });
    } else if (x.dataset.rename !== undefined) {
      rename(x);
    } else if (x.dataset.path) commit(x);
    else if (!x.dataset.add) commitBody(x);
  });
  host.addEventListener('keydown', (e) => { if (e.key === 'Enter' && e.target.matches('input.cell')) e.target.blur(); });
  host.addEventListener('click', (e) => {
    const go = e.target.closest('[data-add-go]');
    if (go) addEntry(go.closest('[data-adder]'));
    const del = e.target.closest('[data-delete-path]');
    if (del) applyEdit((text) => deleteIn(text, JSON.parse(del.dataset.deletePath)));
    const delPoint = e.target.closest('[data-delete-point]');
    if (delPoint) refusable((text) => deletePoint(text, delPoint.dataset.deletePoint), `[data-delete-point="${CSS.escape(delPoint.dataset.deletePoint)}"]`);
    const b = e.target.closest('[data-select-body]');
    if (b) showBody(b.dataset.selectBody);
    if (e.target.closest('[data-close-body]')) showBody(null);
    // The body and its exact length go; its points stay (the server says if one is left unattached).
    if (e.target.closest('[data-delete-body]')) {
      const name = selected;
      showBody(null);
      applyEdit((text) => deleteIn(deleteIn(text, ['lengths', name]), ['bodies', name]));
    }
  });
  document.addEventListener('nbar:analysed', (e) => {
    lastError = e.detail?.error ?? null;
    if (!lastError) lastEdited = null;
    lastRefusal = null;
    renderTables();
    reveal = false;
  });
  document.addEventListener('nbar:opened', () => { selected = null; lastError = null; lastRefusal = null; lastEdited = null; reveal = false; });
  $('#lang')?.addEventListener('change', () => renderTables());
}
