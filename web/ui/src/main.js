// The web app of nbar, as a static site and in `nbar serve`: a gallery of the bundled models, a
// YAML editor whose errors the engine's check and solve place at their line and column, the
// mechanism drawn and animated as the core draws it (the engine's scene), a plot and a table of
// any column, synthesis whose designs open as models, and downloads. Every number comes from the
// core, in the browser (WebAssembly in a worker, engine.js) or on the nbar server.
import './style.css';
import 'uplot/dist/uPlot.min.css';
import uPlot from 'uplot';
import { EditorView, basicSetup } from 'codemirror';
import { yaml } from '@codemirror/lang-yaml';
import { setDiagnostics, lintGutter } from '@codemirror/lint';
import { t, setLang, getLang, translatePage } from './i18n.js';
import { drawingSvg, sceneGroup, poseDrawing, handlesSvg, markScale } from './drawing.js';
import { encodeModel, decodeModel } from './share.js';
import { initModelEdit, applyEdit } from './model-edit.js';
import { initCanvasTools, snapPoint } from './canvas-tools.js';
import { initTables, showBody } from './tables.js';
import { setIn } from './yaml-text.js';
import './i18n-motion.js';
import './i18n-files.js';
import './i18n-forces.js';
import './i18n-build.js';
import { galleryEs } from './i18n-gallery.js';
import { initSynthesis } from './synthesis.js';
import { initOverlays, overlayView, setOverlayView } from './overlays.js';
import { initStressMap } from './stress-map.js';
import { initExplain } from './explain.js';
import { initOffline, serverFetch, whenServerBack } from './offline.js';
import { startEngine, serverOnly } from './engine.js';
import { initJobBar, showServerJob } from './job-bar.js';
import { initSimulate, simulationAnswer, simulationBody, simulationFile, simulationRate, simulationStatus } from './simulate.js';
import { pngFromSvg, gifFromScene } from './pictures.js';
import { initBuild, outlineOf, sketchSvg, buildingText } from './build-model.js';

const $ = (s) => document.querySelector(s);
const state = {
  seq: 0, text: '', check: null, solve: null, scene: null, sceneSize: null, frame: 0, playing: false,
  xcol: 't', ycol: null, geometry: null, plot: null, current: null, lastOk: null,
  ycols: [],  // the plot's further curves (the Column picker's is the first)
  dynamics: null,  // the sweep's inverse dynamics (/api/solve with dynamics), once it has come
  simulation: false,  // Simulate mode (simulate.js): the rows are a simulation's, not the sweep's
  simulationTexts: null,  // the CSV and JSON texts of the simulation shown (simulate.js); null for a sweep
};

// ------------------------------------------------------------------------------ API

// Where requests go: the in-browser engine, the server, or nowhere (with the reason); start()
// settles it before the first request.
let backend;
const backendReady = new Promise((resolve) => { backend = resolve; });

// One API request, answered as the server would answer it. options.key names what it is for, so
// that a newer one cancels it (engine.js); options.label is shown while it runs.
async function send(path, init, options) {
  const where = await backendReady;
  if (where.mode === 'server') return serverFetch(path, init);
  if (where.mode === 'none') {
    const e = new Error(where.reason);
    e.info = { kind: 'no_engine', message: where.reason };
    throw e;
  }
  const r = await where.engine.request(init.method ?? 'GET', path, init.body ?? '', options);
  // What only a server makes (MP4): to the server when there is one, else said plainly.
  return r.status === 501 ? serverOnly(path, init, r, options.label ?? path) : r;
}

async function api(path, body, as = 'json', options = {}) {
  // Every answer's messages come from the core in the app's language (`lang`, docs/web-api.md).
  const init = body === undefined ? {} : {
    method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify({ ...body, lang: getLang() }),
  };
  const r = await send(path, init, options);
  if (!r.ok) {
    let info;
    try { info = (await r.json()).error; } catch { info = { message: `${r.status} ${r.statusText}` }; }
    const e = new Error(info.message);
    e.info = info;
    e.status = r.status;
    throw e;
  }
  if (as === 'json') return r.json();
  if (as === 'text') return r.text();
  return r.blob();
}

// The status line: in the header on a desktop, a row of its own under the header on a phone
// (styles.css), so that what happens is said wherever the page is scrolled. `working` shows the
// busy mark until the next status; the whole text is in the title when it is cut short.
// `text` may be a function of the language, so that a change of language says it again.
let statusShown = () => '';
function status(text, bad = false, working = false) {
  const el = $('#status');
  statusShown = typeof text === 'function' ? text : () => text;
  el.textContent = statusShown();
  el.title = el.textContent;
  el.classList.toggle('bad', bad);
  el.classList.toggle('working', working);
}
function sayStatusAgain() {
  const el = $('#status');
  el.textContent = statusShown();
  el.title = el.textContent;
}

// A busy server (429, 503), an analysis cancelled (499, engine.js) or no answer at all: worth
// trying again as it is. Anything else is the model's or the request's fault, and the same
// request would fail the same way.
function retryable(e) { return e.status === 429 || e.status === 499 || e.status === 503 || e.status === undefined; }
// No answer from the server, or the service worker's word that there is none (offline.js).
function unreached(e) { return e.info?.kind === 'offline'; }

// After a failed analysis the drawing, plot and table still show the last model that worked:
// they are dimmed and labelled "not updated" with the reason (and Retry when the server was
// busy), on the stage and in the status line, so no one takes them for the text's.
let staleShown = null;
function showStale(e) {
  staleShown = e;
  const box = $('#stale');
  box.classList.remove('building');
  if (!e || !state.solve) {
    box.hidden = true;
    document.body.classList.remove('results-stale');
    $('#retry').hidden = true;
    return;
  }
  const again = retryable(e);
  const label = box.querySelector('span');
  label.textContent = t('notUpdated', e.message);
  label.title = label.textContent;
  box.querySelector('button').hidden = !again;
  $('#retry').hidden = !again;
  box.hidden = false;
  document.body.classList.add('results-stale');
}

function setTitle(name) {
  const h = $('#model-name');
  if (name) { h.textContent = name; h.dataset.named = '1'; } else { delete h.dataset.named; h.textContent = t('noModel'); }
  document.title = name ? `${name} · nbar` : 'nbar';
}

// ------------------------------------------------------------------------------ tabs

function showTab(name) {
  for (const b of document.querySelectorAll('[data-tab]')) b.setAttribute('aria-selected', String(b.dataset.tab === name));
  for (const p of document.querySelectorAll('.panel')) p.classList.toggle('active', p.id === `panel-${name}`);
  if (name === 'editor') editor.requestMeasure();
  // On a phone the tab bar scrolls sideways: the tab shown is brought into it (not the page).
  const tab = document.querySelector(`[data-tab="${name}"]`);
  const bar = tab?.parentElement;
  if (bar && bar.scrollWidth > bar.clientWidth) {
    const b = tab.getBoundingClientRect(); const r = bar.getBoundingClientRect();
    if (b.left < r.left || b.right > r.right) bar.scrollLeft += b.left - r.left - (r.width - b.width) / 2;
  }
}

// A tab bar wider than its box scrolls sideways, which a phone shows no scroll bar for: the side
// where more tabs are hidden fades out (style.css, .more-left and .more-right), so the cut tab
// reads as "more this way".
function trackTabOverflow(bar) {
  const update = () => {
    const more = bar.scrollWidth - bar.clientWidth;
    bar.classList.toggle('more-left', more > 1 && bar.scrollLeft > 1);
    bar.classList.toggle('more-right', more > 1 && bar.scrollLeft < more - 1);
  };
  bar.addEventListener('scroll', update, { passive: true });
  new ResizeObserver(update).observe(bar);
  document.addEventListener('nbar:lang', update);
  update();
}
function showResultTab(name) {
  for (const b of document.querySelectorAll('[data-rtab]')) b.setAttribute('aria-selected', String(b.dataset.rtab === name));
  for (const p of document.querySelectorAll('.rpanel')) p.classList.toggle('active', p.id === `rpanel-${name}`);
  if (name === 'plot') resizePlot();
}

// ------------------------------------------------------------------------------ editor

let timer = 0;
let quiet = false;
const editor = new EditorView({
  parent: $('#editor'),
  extensions: [
    basicSetup, yaml(), lintGutter(), EditorView.lineWrapping,
    EditorView.updateListener.of((u) => {
      if (!u.docChanged || quiet) return;
      clearTimeout(timer);
      timer = setTimeout(analyse, 600);
    }),
  ],
});

let opens = 0;
function setText(text) {
  quiet = true;
  editor.dispatch({ changes: { from: 0, to: editor.state.doc.length, insert: text } });
  quiet = false;
  clearTimeout(timer);
  document.body.dataset.opened = String(++opens);
  state.justOpened = true;
  state.nameWhenOpened = undefined;  // the model's own name, once analysed (slug())
  document.dispatchEvent(new Event('nbar:opened'));
  return analyse();
}

let problemShown = null;
function showProblem(info) {
  problemShown = info;
  const el = $('#problems');
  if (!info) {
    editor.dispatch(setDiagnostics(editor.state, []));
    el.textContent = t('noErrors');
    el.classList.remove('bad');
    return;
  }
  const doc = editor.state.doc;
  const where = info.line ? t('errorAt', info.line, info.column ?? 1) : '';
  const message = info.message;
  el.textContent = where + message;
  el.classList.add('bad');
  if (!info.line || info.file === 'request') { editor.dispatch(setDiagnostics(editor.state, [])); return; }
  const line = doc.line(Math.min(Math.max(info.line, 1), doc.lines));
  const from = Math.min(line.from + Math.max((info.column ?? 1) - 1, 0), line.to);
  const word = /^[\w.+-]+/.exec(doc.sliceString(from, line.to));
  const to = word ? from + word[0].length : Math.min(from + 1, line.to);
  editor.dispatch(setDiagnostics(editor.state, [{ from, to: Math.max(to, from), severity: 'error', message }]));
}

async function analyse() {
  const seq = ++state.seq;
  const text = editor.state.doc.toString();
  state.text = text;
  // The analysis of the text before this edit is stale: stopped, not waited for.
  (await backendReady).engine?.cancel('analysis');
  if (seq !== state.seq) return;
  // An empty document is analysed too: the server says it holds no model, at line 1, and the
  // results on screen are marked as not the text's (they were kept and called current).
  status(t('analysing'), false, true);
  document.body.dataset.busy = '1';
  try {
    const analysis = { key: 'analysis', label: t('analysing') };
    const check = await api('/api/check', { model: text }, 'json', analysis);
    if (seq !== state.seq) return;
    const size = sceneSize();
    const { solve, scene, downloads } = state.simulation ? await simulation(text, size) : await sweep(text, size, analysis);
    if (seq !== state.seq) return;
    state.check = check;
    state.solve = solve;
    state.scene = scene;
    state.simulationTexts = downloads ?? null;
    state.sceneSize = size;
    state.lastOk = text;
    state.sketch = null;
    state.joints = check.joints ?? [];
    state.drawnUnit = check.units?.length;
    document.body.classList.remove('sketching');
    if (state.nameWhenOpened === undefined) state.nameWhenOpened = solve.model ?? '';
    showProblem(null);
    showStale(null);
    setTitle(solve.model || check.name);
    const why = () => (solve.complete ? '' : ` · ${t('incomplete', solve.stop_reason ?? '')}`);
    if (state.simulation) status(() => simulationStatus(solve), !solve.complete && !solve.cancelled);
    else status(() => `${t('dof', solve.dof?.mobility ?? '?')} · ${t('samples', solve.rows.length)}${why()}`, !solve.complete);
    state.dynamics = null;
    state.dynamicsColumns = [];
    if (!state.simulation) takeDynamics(solve);
    onSolved();
    if (state.dynamics) {
      document.body.dataset.dynamics = '1';
      document.dispatchEvent(new CustomEvent('nbar:dynamics'));
    }
    updateHash(text);
    document.dispatchEvent(new CustomEvent('nbar:analysed', { detail: { error: null } }));
  } catch (e) {
    if (seq !== state.seq) return;
    // A model the core can read but not solve yet (one being built) is drawn as it is written,
    // with its mobility: never the last model that solved, dimmed, under the new one.
    const outline = retryable(e) ? null : await outlineOf(text);
    if (seq !== state.seq) return;
    state.joints = outline?.joints ?? [];
    showProblem(e.info ?? { message: e.message });
    const where = e.info?.line ? t('errorAt', e.info.line, e.info.column ?? 1) : '';
    status(() => `${t('failed')}: ${where}${e.message}`, true);
    if (outline) showSketch(outline, text);
    else showStale(e);
    // For want of the server: analysed again by itself when it answers, unless edited since.
    if (unreached(e)) whenServerBack(() => { if (seq === state.seq) analyse(); });
    document.dispatchEvent(new CustomEvent('nbar:analysed', { detail: { error: e.info ?? { message: e.message } } }));
  } finally {
    // The text on screen is analysed and drawn (tests wait for this rather than for a title,
    // which a model opened again over an edited copy of itself already shows).
    if (seq === state.seq) { delete document.body.dataset.busy; state.justOpened = false; }
  }
}

// A model being built, drawn from the core's outline in the view the drawing had (so that a point
// about to be tapped stays under the finger), its mobility on the drawing and in the status.
function showSketch(outline, text) {
  const svg = $('#drawing svg');
  const b = svg?.viewBox.baseVal;
  const r = $('#drawing').getBoundingClientRect();
  const aspect = r.width > 50 && r.height > 50 ? r.height / r.width : 0.7;
  const sameUnit = svg && (svg.dataset.unit ?? state.drawnUnit) === outline.units.length;
  // A model just opened (New → Empty model) starts from its own view, not the last model's.
  const previous = b && sameUnit && !state.justOpened ? { x: b.x, y: b.y, w: b.width, h: b.height } : null;
  const sketch = sketchSvg(outline, previous, aspect);
  state.sketch = { ...outline, text };
  state.drawnUnit = outline.units.length;
  const points = outline.points.map((p) => p.name);
  state.geometry = { points, ground: new Set(outline.points.filter((p) => p.ground).map((p) => p.name)), bodies: outline.bodies, scale: sketch.scale };
  $('#drawing').innerHTML = sketch.svg;
  document.body.classList.add('sketching');
  setTitle(outline.model);
  const note = buildingText(outline);
  const box = $('#stale');
  const label = box.querySelector('span');
  label.textContent = note;
  label.title = note;
  box.querySelector('button').hidden = true;
  box.classList.add('building');
  box.hidden = false;
  document.body.classList.toggle('results-stale', !!state.solve);
  $('#retry').hidden = true;
  status(() => buildingText(outline), !!(outline.problem || outline.immobile));
}

// The sweep's table, with its inverse dynamics (`nbar solve --dynamics`: every joint's force,
// each driver's torque or force, the energies), and its drawing: one solve an edit (a sweep then
// its dynamics were two, the second solving the sweep again). A model whose dynamics the core
// refuses is solved without them.
async function sweep(text, size, analysis) {
  const solved = api('/api/solve', { model: text, dynamics: true }, 'json', analysis)
    .catch((e) => (retryable(e) ? Promise.reject(e) : api('/api/solve', { model: text }, 'json', analysis)));
  const [solve, scene] = await Promise.all([solved, api('/api/render', sceneRequest(text, size), 'json', analysis)]);
  return { solve, scene };
}

// The dynamics' columns of the sweep just solved join the Plot's and Table's choices and Explain
// reads their row at the pose. The core appends them after the sweep's own columns, and theirs
// are the only units in newtons and joules (dynamics_table.cpp), which tells where they start.
function takeDynamics(solve) {
  if (!solve.dynamics) return;
  const first = solve.column_units.findIndex((u) => u === 'N' || u === 'N m' || u === 'J');
  if (first < 0) return;
  state.dynamics = solve.dynamics;
  state.dynamicsColumns = solve.columns.slice(first);
  if (state.wantedY && col(state.wantedY) >= 0) state.ycol = state.wantedY;
  state.wantedY = undefined;
}

// A simulation's table, the drawing of its motion and its downloads' texts, in one request (one
// run). The job bar's
// Cancel stops the run and keeps its rows so far, which come as the answer (complete false,
// cancelled true): in the browser's engine by asking its worker to stop (engine.js, keepOnCancel),
// on a server by naming the run and asking /api/simulate/cancel to stop it.
async function simulation(text, size) {
  const where = await backendReady;
  const options = { key: 'analysis', label: t('simulating'), keepOnCancel: true };
  if (where.mode !== 'server') return simulationAnswer(await api('/api/simulate', simulationBody(text, size), 'json', options));
  const run = `run-${Date.now().toString(36)}-${Math.random().toString(36).slice(2, 10)}`;
  const stop = () => serverFetch('/api/simulate/cancel', {
    method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify({ run }),
  }).catch(() => {});
  // A run of a text edited since is stopped: its rows would not be shown.
  stopServerRun();
  stopServerRun = stop;
  const hide = showServerJob(t('simulating'), stop);
  try {
    return simulationAnswer(await api('/api/simulate', simulationBody(text, size, { run }), 'json', options));
  } finally {
    if (stopServerRun === stop) stopServerRun = () => {};
    hide();
  }
}
let stopServerRun = () => {};

// The scene is drawn for the drawing's size in CSS pixels, as `nbar draw --width --height`
// would draw it there.
function sceneSize() {
  const r = $('#drawing').getBoundingClientRect();
  if (r.width < 50 || r.height < 50) return [900, 640];
  return [Math.round(Math.min(Math.max(r.width, 100), 2400)), Math.round(Math.min(Math.max(r.height, 100), 2400))];
}
function sceneRequest(model, [width, height]) {
  return { model, kind: 'draw', format: 'scene', labels: true, width, height };
}

// A drawing resized by much (a phone turned, a window resized) is drawn again for its new size. A
// simulation's is not: its scene comes with the run, so a new one would be the whole run again
// (for a drawing already right but for its scale); the SVG's viewBox scales the scene held
// (uniformly, "meet"), and the next run draws at the new size.
let resizeTimer = 0;
function onDrawingResized() {
  const [w, h] = sceneSize();
  const old = state.sceneSize;
  if (!old || !state.scene || state.sketch || state.simulationTexts) return;
  if (Math.abs(w - old[0]) < 0.25 * old[0] && Math.abs(h - old[1]) < 0.25 * old[1]) return;
  clearTimeout(resizeTimer);
  resizeTimer = setTimeout(async () => {
    const seq = state.seq;
    try {
      const scene = await api('/api/render', sceneRequest(state.lastOk, [w, h]));
      if (seq !== state.seq || drag) return;
      state.scene = scene;
      state.sceneSize = [w, h];
      showDrawing();
    } catch { /* the old drawing stays */ }
  }, 250);
}

function showDrawing() {
  state.geometry.scale = markScale(state.scene);
  $('#drawing').innerHTML = drawingSvg(state.scene);
  document.dispatchEvent(new CustomEvent('nbar:drawn'));
  setFrame(state.frame);
}

// ------------------------------------------------------------------------------ results

function col(name) { return state.solve ? state.solve.columns.indexOf(name) : -1; }

function onSolved() {
  const { solve, check } = state;
  const driver = (check.drivers?.[0] ?? '').split(':')[0];
  const xs = solve.rows.map((r) => r[col(driver)]);
  const ascending = col(driver) >= 0 && xs.every((v, i) => i === 0 || v >= xs[i - 1]);
  state.xcol = state.simulation && col('t') >= 0 ? 't' : ascending ? driver : (col('t') >= 0 && solve.rows.every((r, i, a) => i === 0 || r[col('t')] >= a[i - 1][col('t')]) ? 't' : 'step');
  const points = [...(check.points?.ground ?? []), ...(check.points?.moving ?? [])].filter((p) => col(`${p}.x`) >= 0);
  state.geometry = {
    points, ground: new Set(check.points?.ground ?? []),
    bodies: (check.bodies ?? []).map((b) => ({ name: b.name, points: b.points.filter((p) => points.includes(p)) })),
  };
  delete document.body.dataset.dynamics;
  fillColumnPicker();
  const scrub = $('#scrub');
  scrub.max = String(Math.max(solve.rows.length - 1, 0));
  state.frame = Math.min(state.frame, solve.rows.length - 1);
  state.geometry.scale = markScale(state.scene);
  $('#drawing').innerHTML = drawingSvg(state.scene);
  buildPlot();
  buildTable();
  document.dispatchEvent(new CustomEvent('nbar:solved'));
  setFrame(state.frame);
}

// The column pickers: every column but step; keep the choices across edits (a column the new
// model lacks is dropped, or waits in the share link's list until the dynamics bring it).
function fillColumnPicker() {
  const { solve } = state;
  const names = solve.columns.filter((c) => c !== 'step');
  const pick = $('#ycol');
  pick.replaceChildren(...names.map((c) => new Option(c, c)));
  if (!names.includes(state.ycol)) {
    const angles = names.filter((c) => c.endsWith('.angle'));
    state.ycol = angles.at(-1) ?? names.find((c) => c !== state.xcol) ?? names[0];
  }
  pick.value = state.ycol;
  const add = $('#ycol-add');
  add.replaceChildren(new Option(t('addCurve'), ''), ...names.map((c) => new Option(c, c)));
  add.value = '';
  showCurves();
}

// The further curves, each a chip with × to take it off the plot.
function showCurves() {
  const shown = state.ycols.filter((c) => col(c) >= 0);
  $('#ycurves').hidden = !shown.length;
  $('#ycurves').innerHTML = shown.map((c) => `<span class="chip curve" data-curve="${esc(c)}"><i style="background:${curveColour(plotCurves().indexOf(c))}"></i>${esc(c)}`
    + `<button type="button" class="ghost" data-uncurve="${esc(c)}" aria-label="${esc(t('removeCurve', c))}" title="${esc(t('removeCurve', c))}">×</button></span>`).join('');
}
function curvesChanged() {
  showCurves();
  buildPlot();
  buildTable();
  setFrame(state.frame);
}

function fmt(v) {
  if (v === null || v === undefined || Number.isNaN(v)) return '–';
  const a = Math.abs(v);
  if (a !== 0 && (a >= 1e6 || a < 1e-3)) return v.toExponential(3);
  return String(+v.toFixed(a >= 100 ? 2 : 4));
}
function unitOf(name) { const i = col(name); return i >= 0 ? (state.solve.column_units[i] ?? '') : ''; }

function setFrame(i) {
  const { solve } = state;
  if (!solve || !solve.rows.length) return;
  const n = solve.rows.length;
  state.frame = ((Math.round(i) % n) + n) % n;
  const row = solve.rows[state.frame];
  const svg = document.querySelector('#drawing svg');
  if (svg && !svg.dataset.sketch && state.scene?.steps.length === n) {
    poseDrawing(svg, state.scene, state.frame);
    svg.querySelector('.handles').innerHTML = handlesSvg(state.geometry, solve, row);
  }
  $('#scrub').value = String(state.frame);
  $('#readout').textContent = `${state.xcol} = ${fmt(row[col(state.xcol)])} ${unitOf(state.xcol)}`;
  state.plot?.redraw(false, false);
  document.dispatchEvent(new CustomEvent('nbar:frame'));
  markTableRow();
}
// The Table's row of the sample shown (when the table lists it).
function markTableRow() {
  const tr = $('#table tbody')?.children;
  if (!tr) return;
  $('#table tr.current')?.classList.remove('current');
  const k = Math.round(state.frame / state.tableStride);
  if (state.frame % state.tableStride === 0 && tr[k]) tr[k].classList.add('current');
}

// ------------------------------------------------------------------------------ dragging

// A point dragged in the drawing moves it in the model: its `NAME: [x, y]` line is rewritten and
// the model analysed again. The model's points are its start pose (sample 0), so only that pose
// is edited: a point grabbed at a later pose does not move; the drawing goes back to the start
// pose at once and the status says to drag it there, where the point stays under the finger
// (moved from there by the finger's way, it had ended far from the finger at the pose shown).
// While the finger moves, the server draws the edited model's scene (one request at a time, the
// latest position next), shown at sample 0 in the same view: it re-assembles live.
let drag = null;
function svgPoint(e) {
  const svg = $('#drawing svg');
  const p = new DOMPoint(e.clientX, e.clientY).matrixTransform(svg.getScreenCTM().inverse());
  return { x: p.x, y: -p.y };
}
function startDrag(e) {
  const c = e.target.closest('circle[data-point]');
  if (c && state.sketch) { startSketchDrag(e, c); return; }
  if (!c || !state.solve) return;
  e.preventDefault();
  play(false);
  if (state.frame !== 0) {
    setFrame(0);
    status(t('dragAtStart', c.dataset.point));
    return;
  }
  const press = svgPoint(e);
  const start = pointAt(state.solve, 0, c.dataset.point) ?? press;
  drag = { name: c.dataset.point, id: e.pointerId, moved: false, dx: start.x - press.x, dy: start.y - press.y };
  $('#drawing svg').setPointerCapture(e.pointerId);
}
// A point of a model being built (drawn from the core's outline: it cannot be solved yet) is
// dragged on the sketch as drawn, its links following with no request, and written where it is
// let go.
function startSketchDrag(e, c) {
  const p = state.sketch.points.find((q) => q.name === c.dataset.point);
  if (!p) return;
  e.preventDefault();
  const press = svgPoint(e);
  drag = { name: p.name, id: e.pointerId, moved: false, dx: p.x - press.x, dy: p.y - press.y, sketch: true };
  $('#drawing svg').setPointerCapture(e.pointerId);
}
function redrawSketch(d) {
  const svg = $('#drawing svg');
  const b = svg.viewBox.baseVal;
  const outline = { ...state.sketch, points: state.sketch.points.map((q) => (q.name === d.name ? { ...q, x: d.x, y: d.y } : q)) };
  const fresh = document.createElement('div');
  fresh.innerHTML = sketchSvg(outline, { x: b.x, y: b.y, w: b.width, h: b.height }, b.height / b.width).svg;
  // The svg element stays (it holds the pointer capture and the view): only its content is new.
  svg.replaceChildren(...fresh.firstElementChild.childNodes);
}
function moveDrag(e) {
  if (!drag || e.pointerId !== drag.id) return;
  // With snap on, the preview sits on the grid where the point will be written.
  const finger = svgPoint(e);
  const raw = { x: finger.x + drag.dx, y: finger.y + drag.dy };
  const snapped = snapPoint(raw.x, raw.y);
  const p = snapped ? { x: snapped[0], y: snapped[1] } : raw;
  drag.moved = true;
  drag.x = p.x; drag.y = p.y;
  if (drag.sketch) { redrawSketch(drag); return; }
  $('#drawing svg .handles').innerHTML = handlesSvg(state.geometry, state.solve, state.solve.rows[0], { name: drag.name, ...p });
  redrawDragged(drag);
}
function endDrag(e) {
  if (!drag || e.pointerId !== drag.id) return;
  const d = drag;
  drag = null;
  if (!d.moved) return;
  // The point's value in the YAML is replaced where it is, the rest of the text kept as written.
  if (!applyEdit((text) => setIn(text, ['points', d.name], draggedValue(d)))) {
    if (d.sketch) analyse();
    else if (d.scene) showDrawing();
    else setFrame(0);
  }
}
// Point `name` at sample `row` of a solve, in model units, or null when the solve lacks it.
function pointAt(solve, row, name) {
  const x = solve.columns.indexOf(`${name}.x`), y = solve.columns.indexOf(`${name}.y`);
  return x >= 0 && y >= 0 && solve.rows[row] ? { x: solve.rows[row][x], y: solve.rows[row][y] } : null;
}
function draggedValue(d) {
  const digits = Math.max(0, Math.min(6, 2 - Math.floor(Math.log10(state.geometry.scale || 1))));
  return snapPoint(d.x, d.y) ?? [+d.x.toFixed(digits), +d.y.toFixed(digits)];
}
async function redrawDragged(d) {
  if (d.busy) { d.again = true; return; }
  d.busy = true;
  try {
    const text = setIn(state.text, ['points', d.name], draggedValue(d));
    const scene = typeof text === 'string' ? await api('/api/render', sceneRequest(text, state.sceneSize)) : null;
    const svg = $('#drawing svg');
    if (scene && drag === d && svg && scene.steps.length) {
      d.scene = true;  // the drawing no longer is the model's: drawn again when the drag ends
      const old = svg.querySelector('.scene');
      old.insertAdjacentHTML('afterend', sceneGroup(scene));
      old.remove();
      poseDrawing(svg, scene, 0);
    }
  } catch { /* a pose that does not assemble: the last drawing stays */ }
  d.busy = false;
  if (d.again && drag === d) { d.again = false; redrawDragged(d); }
}

// ------------------------------------------------------------------------------ animation

// The play head is kept in fractions of a row apart from the row shown (setFrame rounds
// state.frame to a row): a slow play (a simulation of 400 rows in 20 s moves a third of a row in a
// 60 Hz frame) would otherwise lose its fraction at every frame and never leave its row.
let last = 0;
let head = 0;
function tick(now) {
  if (!state.playing) return;
  const n = state.solve?.rows.length ?? 0;
  // A sweep plays in 4 s; a simulation at its own time (simulate.js).
  const rate = state.simulation && n > 1 ? simulationRate(state.solve) : n / 4000;
  // The row moved from elsewhere (new rows, a shorter table): play on from there.
  if (Math.floor(head) !== state.frame) head = state.frame;
  if (n > 1 && last) head = (head + (now - last) * rate) % n;
  last = now;
  if (n > 1) setFrame(Math.floor(head));
  requestAnimationFrame(tick);
}
function play(on) {
  state.playing = on;
  const b = $('#play');
  b.textContent = on ? '❚❚' : '▶';
  b.dataset.i18nAria = on ? 'pause' : 'play';  // said in the language chosen, now and after a change
  b.setAttribute('aria-label', t(b.dataset.i18nAria));
  last = 0;
  head = state.frame;
  if (on) requestAnimationFrame(tick);
}

// ------------------------------------------------------------------------------ plot and table

const curveColours = ['#2563eb', '#dc6803', '#0e9384', '#c11574', '#7a5af8', '#475467'];
function curveColour(k) { return curveColours[k % curveColours.length]; }
function withUnit(name) { const u = unitOf(name); return `${name}${u ? ` (${u})` : ''}`; }

// The curves plotted: the Column picker's, then the ones added. Curves of one unit share a y
// scale; the first unit's axis is on the left, the second's on the right (others unlabelled).
// uPlot's legend is the read-out: each curve's value at the sample under the cursor.
function plotCurves() {
  return [state.ycol, ...state.ycols].filter((c, k, all) => col(c) >= 0 && all.indexOf(c) === k);
}
function buildPlot() {
  const el = $('#plot');
  state.plot?.destroy();
  state.plot = null;
  const { solve } = state;
  const xi = col(state.xcol);
  const curves = plotCurves();
  if (xi < 0 || !curves.length) return;
  const data = [solve.rows.map((r) => r[xi]), ...curves.map((c) => solve.rows.map((r) => r[col(c)]))];
  const units = [...new Set(curves.map(unitOf))];
  const scaleOf = (c) => `y${units.indexOf(unitOf(c))}`;
  const axisLabel = (k) => curves.filter((c) => unitOf(c) === units[k]).map(withUnit).join(', ');
  const yAxes = units.slice(0, 2).map((u, k) => ({ scale: `y${k}`, label: axisLabel(k), size: 60, side: k ? 1 : 3, grid: { show: k === 0 } }));
  const opts = {
    width: Math.max(el.clientWidth, 200), height: 240,
    scales: { x: { time: false } },
    series: [
      { label: withUnit(state.xcol), value: (u, v) => fmt(v) },
      ...curves.map((c, k) => ({ label: withUnit(c), scale: scaleOf(c), stroke: curveColour(k), width: 2, value: (u, v) => fmt(v) })),
    ],
    axes: [{ label: withUnit(state.xcol), size: 40 }, ...yAxes],
    cursor: { drag: { x: false, y: false } },
    hooks: {
      draw: [(u) => {
        const x = data[0][Math.floor(state.frame)];
        if (x === undefined) return;
        const px = u.valToPos(x, 'x', true);
        const ctx = u.ctx;
        ctx.save();
        ctx.strokeStyle = '#f97316'; ctx.lineWidth = 2 * devicePixelRatio;
        ctx.beginPath(); ctx.moveTo(px, u.bbox.top); ctx.lineTo(px, u.bbox.top + u.bbox.height); ctx.stroke();
        ctx.restore();
      }],
    },
  };
  state.plot = new uPlot(opts, data, el);
  followPointer(state.plot, data);
}

// Clicking the plot, or touching it and moving along it, poses the mechanism at that sample; a
// finger also moves uPlot's cursor, which follows only a mouse by itself, so that the legend reads
// the sample's values on a phone (it read "–"). Vertical swipes still scroll the page.
function followPointer(plot, data) {
  const over = plot.over;
  over.style.touchAction = 'pan-y';
  const follow = (e) => {
    const i = plot.posToIdx(e.clientX - over.getBoundingClientRect().left);
    if (i === null || i === undefined || data[0][i] === undefined) return;
    play(false);
    setFrame(i);
    if (e.pointerType !== 'mouse') plot.setCursor({ left: plot.valToPos(data[0][i], 'x'), top: plot.valToPos(data[1][i], 'y') });
  };
  over.addEventListener('pointerdown', (e) => {
    follow(e);
    if (e.pointerType !== 'mouse') over.setPointerCapture?.(e.pointerId);
  });
  // Held down and moved (a finger, or the mouse with its button down), the pose follows.
  over.addEventListener('pointermove', (e) => { if (e.buttons) follow(e); });
}
function resizePlot() {
  const el = $('#plot');
  if (state.plot && el.clientWidth) state.plot.setSize({ width: el.clientWidth, height: 240 });
}

function buildTable() {
  const { solve, geometry } = state;
  const traced = geometry.points.filter((p) => !geometry.ground.has(p)).slice(-1);
  const names = [...new Set(['step', state.xcol, ...plotCurves(), ...traced.flatMap((p) => [`${p}.x`, `${p}.y`])])].filter((c) => col(c) >= 0);
  const idx = names.map(col);
  const n = solve.rows.length;
  state.tableStride = Math.max(1, Math.ceil(n / 400));
  const head = `<thead><tr>${names.map((c) => `<th>${esc(c)}${unitOf(c) ? ` <small>${esc(unitOf(c))}</small>` : ''}</th>`).join('')}</tr></thead>`;
  let body = '';
  for (let i = 0; i < n; i += state.tableStride) {
    body += `<tr data-i="${i}">${idx.map((k) => `<td>${fmt(solve.rows[i][k])}</td>`).join('')}</tr>`;
  }
  $('#table').innerHTML = `${head}<tbody>${body}</tbody>`;
}

function esc(s) { return String(s).replace(/[&<>"]/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' }[c])); }

// ------------------------------------------------------------------------------ gallery

// An example's title and description in the language chosen (i18n-gallery.js), else its own.
function exampleText(e) {
  const [title, description] = (getLang() === 'es' && galleryEs[e.name]) || [];
  return { title: title || e.title || e.name, description: description ?? e.description ?? '' };
}

let galleryShown = [];
async function loadGallery() {
  const { examples } = await api('/api/examples');
  galleryShown = examples;
  writeGallery(examples);
  return examples;
}
function writeGallery(examples) {
  const models = examples.filter((e) => e.kind === 'model');
  // The "New" menu: the templates (examples/templates/), small models to start from.
  // Simplest first; a template the list does not know goes last.
  const order = ['four-bar', 'slider-crank', 'inverted-slider-crank', 'five-bar', 'watt-six-bar', 'stephenson-six-bar'].map((n) => `template-${n}`);
  const rank = (e) => (order.includes(e.name) ? order.indexOf(e.name) : order.length);
  const templates = examples.filter((e) => e.kind === 'template').sort((a, b) => rank(a) - rank(b));
  $('#templates').replaceChildren(...templates.map((e) => {
    const b = document.createElement('button');
    b.type = 'button';
    b.dataset.template = e.name;
    b.title = exampleText(e).description;
    b.textContent = exampleText(e).title;
    b.addEventListener('click', () => { $('#new-menu').open = false; openExample(e.name).then((ok) => ok && showTab('editor')); });
    return b;
  }));
  $('#gallery').replaceChildren(...models.map((e) => {
    const li = document.createElement('li');
    const b = document.createElement('button');
    b.dataset.example = e.name;
    b.innerHTML = `<b>${esc(exampleText(e).title)}</b><small>${esc(exampleText(e).description)}</small>`;
    b.addEventListener('click', () => openExample(e.name));
    li.append(b);
    return li;
  }));
}

// True when it opened; otherwise the status says why (and, for want of the server, it opens by
// itself when the server answers again), so no "Loading…" is left spinning.
async function openExample(name) {
  status(t('loading'), false, true);
  let text;
  try {
    text = await api(`/api/examples/${encodeURIComponent(name)}`, undefined, 'text');
  } catch (e) {
    status(`${t('failed')}: ${e.message}`, true);
    if (unreached(e)) whenServerBack(() => openExample(name));
    return false;
  }
  for (const b of document.querySelectorAll('[data-example]')) b.classList.toggle('current', b.dataset.example === name);
  state.current = name;
  await setText(text);
  return true;
}

// A new model from its text (New → empty): named "new-model" for downloads until it has a name.
async function newModel(text) {
  for (const b of document.querySelectorAll('[data-example]')) b.classList.remove('current');
  state.current = 'new-model';
  showTab('editor');
  await setText(text);
}

// ------------------------------------------------------------------------------ opening files

// A model file from this computer (the Open button or a file dropped on the app): its text goes
// into the editor and is analysed like typed text. Only text is taken, and no more than the
// server accepts in a request.
const maxFileBytes = 1 << 20;
const modelFile = /\.(ya?ml|json)$/i;

async function openFile(file) {
  if (!file) return;
  if (!modelFile.test(file.name) && !/^(text\/|application\/(json|ya?ml|x-yaml))/.test(file.type)) {
    status(t('fileNotModel', file.name), true);
    return;
  }
  if (file.size > maxFileBytes) {
    status(t('fileTooLarge', file.name, Math.ceil(file.size / 1024), maxFileBytes / 1024), true);
    return;
  }
  let text;
  try {
    text = new TextDecoder('utf-8', { fatal: true }).decode(await file.arrayBuffer());
    if (text.includes('\0')) throw new Error('NUL');
  } catch {
    status(t('fileNotText', file.name), true);
    return;
  }
  for (const b of document.querySelectorAll('[data-example]')) b.classList.remove('current');
  state.current = file.name.replace(/\.[^.]*$/, '');
  showTab('editor');
  await setText(text);
}

function initFiles() {
  const input = $('#open-file');
  $('#open-button').addEventListener('click', () => input.click());
  input.addEventListener('change', () => { const f = input.files?.[0]; input.value = ''; openFile(f); });
  const hasFiles = (e) => [...(e.dataTransfer?.types ?? [])].includes('Files');
  document.addEventListener('dragover', (e) => {
    if (!hasFiles(e)) return;
    e.preventDefault();
    e.dataTransfer.dropEffect = 'copy';
    document.body.classList.add('dropping');
  }, true);
  document.addEventListener('dragleave', (e) => { if (!e.relatedTarget) document.body.classList.remove('dropping'); });
  // Capture phase: the editor would otherwise insert a file dropped on it into its text.
  document.addEventListener('drop', (e) => {
    if (!hasFiles(e)) return;
    e.preventDefault();
    e.stopPropagation();
    document.body.classList.remove('dropping');
    const files = e.dataTransfer.files;
    if (files.length > 1) status(t('fileOneOnly'));
    openFile(files[0]);
  }, true);
}

// ------------------------------------------------------------------------------ synthesis

// The synthesis panel lives in synthesis.js; the designs' models come from the server.

// ------------------------------------------------------------------------------ downloads

// A template's downloads are named after the model it started (four-bar.yaml, not template-...).
// Downloads are named after the file or example opened, until the model is given a name of its
// own in the editor: then after that (a template renamed "My press" downloads as my-press.csv).
function slug() {
  const own = state.solve?.model;
  const renamed = own && state.nameWhenOpened !== undefined && own !== state.nameWhenOpened;
  const name = (renamed ? own : state.current) || own || 'model';
  return name.replace(/^template-/, '').toLowerCase().replace(/[^a-z0-9]+/g, '-').replace(/^-|-$/g, '') || 'model';
}

function save(blob, name) {
  const a = document.createElement('a');
  a.href = URL.createObjectURL(blob);
  a.download = name;
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(a.href), 10000);
}

async function download(kind) {
  // The results' downloads are of the model the results on screen came from, as Explain, the
  // overlays and the stress map are: the editor may hold an edit not analysed yet, or one that
  // does not solve (its CSV was an error, or rows the screen did not show). The model file is the
  // editor's text.
  const text = editor.state.doc.toString();
  const model = state.lastOk ?? text;
  const name = slug();
  if (state.simulationTexts && (kind === 'csv' || kind === 'json')) {
    // The simulation shown, as `nbar simulate --format csv|json` wrote it for that run (its
    // answer's `downloads`): the rows on screen, a cancelled run's so far, with no second run.
    // Nothing to wait for, so the status keeps saying what the run was.
    save(simulationFile(state.simulationTexts, kind), `${name}-simulation.${kind}`);
    return;
  }
  const inBrowser = (await backendReady).mode === 'engine';
  try {
    status(t('loading'), false, true);
    if (kind === 'csv') {
      // The core's CSV writer, as `nbar solve` writes it: the browser writes no numbers of its own.
      save(await api('/api/solve', { model, format: 'csv' }, 'blob'), `${name}.csv`);
    } else if (kind === 'json') {
      // `nbar solve`'s answer as it writes it (the sweep on screen also holds its dynamics).
      save(await api('/api/solve', { model }, 'blob'), `${name}.json`);
    } else if (kind === 'model') {
      save(new Blob([text], { type: 'application/yaml' }), `${name}.yaml`);
    } else if (kind === 'svg' || (kind === 'png' && !inBrowser)) {
      save(await api('/api/render', { model, kind: 'draw', format: kind, labels: true }, 'blob'), `${name}.${kind}`);
    } else if (kind === 'png') {
      // The engine draws no raster pictures: its SVG drawn on a canvas (the browser's own PNG).
      const svg = await api('/api/render', { model, kind: 'draw', format: 'svg', labels: true }, 'text');
      save(await pngFromSvg(svg), `${name}.png`);
    } else if (kind === 'gif' && inBrowser) {
      // The engine's scene posed at 36 samples, each drawn on a canvas, encoded here (gifenc).
      const scene = await api('/api/render', { model, kind: 'draw', format: 'scene', labels: true, steps: 36, width: 640, height: 480 },
        'json', { label: t('dlGif') });
      save(await gifFromScene(scene), `${name}.gif`);
    } else if (kind === 'gif') {
      save(await api('/api/render', { model, kind: 'animate', format: 'gif', frames: 36 }, 'blob'), `${name}.gif`);
    } else if (kind === 'mp4') {
      save(await api('/api/render', { model, kind: 'animate', format: 'mp4', frames: 72 }, 'blob', { label: t('dlMp4') }), `${name}.mp4`);
    } else if (kind === 'report') {
      save(await api('/api/report', { model }, 'blob', { label: t('dlReport') }), `${name}-report.html`);
    } else if (kind === 'plates-dxf' || kind === 'plates-svg') {
      const format = kind.slice(7);  // `nbar export --dxf/--svg`: the plates as drawn in the model file
      save(await api('/api/render', { model, kind: 'plates', format }, 'blob'), `${name}-plates.${format}`);
    }
    status(t('ok'));
  } catch (e) {
    status(`${t('failed')}: ${e.message}`, true);
  }
}

// ------------------------------------------------------------------------------ sharing

// Copies `text`: the Clipboard API where the page may use it (https or localhost), else a
// selected text field and execCommand('copy') (a page on http from another machine has no
// navigator.clipboard). True only when a copy was made.
async function copyText(text) {
  if (navigator.clipboard?.writeText) {
    try { await navigator.clipboard.writeText(text); return true; } catch { /* refused: the fallback */ }
  }
  const ta = document.createElement('textarea');
  ta.value = text;
  ta.setAttribute('readonly', '');
  ta.style.cssText = 'position:fixed;top:0;left:0;opacity:0;';
  document.body.append(ta);
  ta.select();
  ta.setSelectionRange(0, text.length);
  let ok = false;
  try { ok = document.execCommand('copy'); } catch { ok = false; }
  ta.remove();
  return ok;
}

// Share: the link holding the model, copied; when it cannot be, shown selected under the header
// to copy by hand (never "Link copied" for a copy that did not happen).
async function share() {
  await updateHash(editor.state.doc.toString());
  const box = $('#share-box');
  if (await copyText(location.href)) {
    box.hidden = true;
    status(t('copied'));
    return;
  }
  const field = box.querySelector('input');
  field.value = location.href;
  box.hidden = false;
  field.focus();
  field.select();
  status(t('copyByHand'), true);
}

async function updateHash(text) {
  try {
    const view = viewParams().toString();
    history.replaceState(null, '', `#m=${await encodeModel(text)}${view ? `&${view}` : ''}`);
  } catch { /* no CompressionStream: no link */ }
}

// What a link keeps besides the model: the overlays ticked (o) and the points traced (t), the
// plotted column (y) and the sample shown (f); read back by applyView once the model is analysed.
function viewParams() {
  const view = overlayView();
  const params = new URLSearchParams();
  if (view.on.length) params.set('o', view.on.join(','));
  if (view.on.includes('traces') && view.traced.length) params.set('t', view.traced.join(','));
  if (state.ycol) params.set('y', plotCurves().join(',') || state.ycol);
  if (state.frame) params.set('f', String(Math.round(state.frame)));
  return params;
}
function applyView(params) {
  const list = (key) => (params.get(key) ? params.get(key).split(',') : []);
  setOverlayView({ on: list('o'), traced: list('t') });
  const [y, ...more] = list('y');
  // A column the model on screen lacks may come with the next analysis: chosen then (takeDynamics).
  if (y && state.solve && col(y) < 0) state.wantedY = y;
  if (y && state.solve && col(y) >= 0 && (y !== state.ycol || more.length)) {
    state.ycol = y;
    state.ycols = more;
    $('#ycol').value = y;
    curvesChanged();
  }
  const f = Number(params.get('f'));
  if (Number.isInteger(f) && f > 0 && state.solve) setFrame(Math.min(f, state.solve.rows.length - 1));
}

// ------------------------------------------------------------------------------ start

// The sticky header's height as --header-h: what scrolls into view goes below it (its status
// row on a phone makes it taller, and changes with the text).
function trackHeaderHeight() {
  const header = $('header.top');
  const set = () => document.documentElement.style.setProperty('--header-h', `${Math.ceil(header.getBoundingClientRect().height)}px`);
  new ResizeObserver(set).observe(header);
  set();
}

// Where the computations run (engine.js); said under the header when the in-browser engine was
// wanted but could not load, with Reload.
async function settleBackend() {
  const where = await startEngine();
  backend(where);
  document.body.dataset.engine = where.mode;
  if (where.engine) initJobBar(where.engine);
  if (where.note) {
    const box = $('#engine-note');
    box.querySelector('span').textContent = where.note;
    box.hidden = false;
  }
  return where;
}

async function start() {
  $('#lang').value = getLang();
  translatePage();
  settleBackend();
  $('#engine-note button').addEventListener('click', () => location.reload());
  $('#lang').addEventListener('change', (e) => { setLang(e.target.value); });
  document.addEventListener('nbar:lang', () => { if (state.solve) fillColumnPicker(); });
  // What was written from the core's answers is said again in the language chosen.
  document.addEventListener('nbar:lang', () => {
    // The core's messages on screen are in the language they were asked in: asked again.
    if (state.text !== undefined) analyse();
    sayStatusAgain();
    if (problemShown) showProblem(problemShown); else if (state.lastOk) $('#problems').textContent = t('noErrors');
    showStale(staleShown);
    writeGallery(galleryShown);
  });
  for (const b of document.querySelectorAll('[data-tab]')) b.addEventListener('click', () => showTab(b.dataset.tab));
  for (const b of document.querySelectorAll('[data-rtab]')) b.addEventListener('click', () => showResultTab(b.dataset.rtab));
  for (const b of document.querySelectorAll('[data-download]')) b.addEventListener('click', () => download(b.dataset.download));
  $('#play').addEventListener('click', () => play(!state.playing));
  $('#drawing').addEventListener('pointerdown', startDrag);
  $('#drawing').addEventListener('pointermove', moveDrag);
  $('#drawing').addEventListener('pointerup', endDrag);
  $('#drawing').addEventListener('pointercancel', endDrag);
  $('#scrub').addEventListener('input', (e) => { play(false); setFrame(+e.target.value); });
  $('#ycol').addEventListener('change', (e) => { state.ycol = e.target.value; curvesChanged(); });
  $('#ycol-add').addEventListener('change', (e) => {
    const c = e.target.value;
    e.target.value = '';
    if (c && c !== state.ycol && !state.ycols.includes(c)) { state.ycols.push(c); curvesChanged(); }
  });
  $('#ycurves').addEventListener('click', (e) => {
    const b = e.target.closest('[data-uncurve]');
    if (b) { state.ycols = state.ycols.filter((c) => c !== b.dataset.uncurve); curvesChanged(); }
  });
  $('#table').addEventListener('click', (e) => { const tr = e.target.closest('tr[data-i]'); if (tr) { play(false); setFrame(+tr.dataset.i); } });
  const app = { state, api, backendReady, setText, analyse, showTab, esc, fmt, status, play, setFrame, unitOf, col, model: () => editor.state.doc.toString() };
  initSimulate(app);
  initSynthesis(app); initOverlays(app); initStressMap(app); initExplain(app); initOffline(app);
  $('#share').addEventListener('click', share);
  $('#share-box button').addEventListener('click', () => { $('#share-box').hidden = true; });
  for (const b of [$('#retry'), $('#stale button')]) b.addEventListener('click', () => { clearTimeout(timer); analyse(); });
  trackHeaderHeight();
  trackTabOverflow($('.side .tabs'));
  new ResizeObserver(resizePlot).observe($('#plot'));
  new ResizeObserver(onDrawingResized).observe($('#drawing'));
  initFiles();
  initModelEdit({ editor, state, status, showTab, setFrame, api, newModel, analyse: () => { clearTimeout(timer); return analyse(); } });
  initBuild();
  initCanvasTools(showBody);
  initTables();
  showTab('gallery');
  showResultTab('plot');
  $('#drawing').innerHTML = `<div class="empty">${esc(t('nothing'))}</div>`;

  const galleryFailed = (e) => {
    status(e.message, true);
    if (unreached(e)) whenServerBack(() => loadGallery().catch(galleryFailed));
  };
  await loadGallery().catch(galleryFailed);
  api('/api/examples/five-point-crank-rocker', undefined, 'text').then((txt) => { $('#task').value = txt; }).catch(() => {});
  const m = /^#m=([^&]+)(?:&(.*))?$/.exec(location.hash);
  let opened = false;
  if (m) {
    try { await setText(await decodeModel(m[1])); opened = true; showTab('editor'); } catch { /* a bad link: the default */ }
    if (opened) applyView(new URLSearchParams(m[2] ?? ''));
  }
  // With no engine and no server, the first model cannot open: the status says why.
  if (!opened) await openExample('fourbar-crank-rocker');
  document.body.dataset.ready = '1';
}

start();
