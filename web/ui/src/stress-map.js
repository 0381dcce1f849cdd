// The finite-element stress map at the pose shown, under the drawing when its box is ticked: the
// core's drawing of every plate coloured by its von Mises stress at that step (/api/render,
// `stress: true`, as a scene), the value under the pointer (/api/stress/probe: the core finds the
// link drawn there and reads its field, the same number as `nbar stress --method fe --at X,Y
// --coordinates model`), and each link's FE peak over the sweep with the arc where it is flat
// (/api/stress, method fe). The page only turns the pointer into the drawing's coordinates.
//
// The probe runs one request at a time: while one is under way only the pointer's latest place is
// kept, sent when the answer comes; an answer for a place the pointer has left, or for another
// step or model, is dropped. The read-out is one line of fixed height, so the map never moves.
import { t } from './i18n.js';
import { drawingSvg } from './drawing.js';

const $ = (s) => document.querySelector(s);
let app = null;

const map = {
  on: false,
  model: null, step: null, scene: null, sceneKey: '', loadingKey: '', peaks: null,
  probe: { seq: 0, busy: false, pending: null },
};

// An API error as the status line gives it: at its line and column in the model, when it has them.
function failure(e) {
  const where = e.info?.line ? t('errorAt', e.info.line, e.info.column ?? 1) : '';
  return `<span class="bad">${app.esc(`${where}${e.message}`)}</span>`;
}

function readout(html, state = '') {
  const el = $('#probe');
  el.innerHTML = html;
  el.dataset.state = state;
}

// ------------------------------------------------------------------------------ the map

function mapSize() {
  const w = Math.max(260, Math.round($('#femap').clientWidth || 600));
  return [w, Math.round(Math.min(w * 0.62, window.innerHeight * 0.5, 420))];
}

async function loadMap() {
  if (!map.on || !app.state.solve || app.state.simulation) return;  // the sweep's stresses, not a simulation's
  const model = app.state.lastOk;
  const step = app.state.frame;
  const [width, height] = mapSize();
  const key = `${step}/${width}x${height}`;
  if (map.model !== model) { map.model = model; map.scene = null; map.sceneKey = ''; map.peaks = null; $('#femap-peaks').innerHTML = ''; }
  if (map.sceneKey === key || map.loadingKey === key) return;
  // One map at a time: the frame shown when this one is drawn asks for its own next.
  if (map.loadingKey) return;
  map.loadingKey = key;
  $('#femap').dataset.loading = '';
  try {
    const scene = await app.api('/api/render', { model, kind: 'draw', format: 'scene', stress: true, step, width, height },
      'json', { key: 'femap', label: t('jobStress') });
    if (map.model !== model) return;
    map.scene = scene; map.sceneKey = key; map.step = step;
    $('#femap-drawing').innerHTML = drawingSvg(scene);
    $('#femap-drawing svg').dataset.step = String(step);
    readout(t('probeHint', step));
    if (!map.peaks) loadPeaks(model);
  } catch (e) {
    // Not asked again for this frame and size (a model without plates would fail every time).
    if (map.model === model) { map.sceneKey = key; map.scene = null; $('#femap-drawing').innerHTML = ''; readout(failure(e), 'error'); }
  } finally {
    map.loadingKey = '';
    delete $('#femap').dataset.loading;
    if (map.model === app.state.lastOk) loadMap();
  }
}

// Each link's FE peak over the sweep: where, when, and the arc of a round hole's edge over which
// the stress stays within 0.5 % of it (flat_from, flat_to, flat_arc: the core's).
async function loadPeaks(model) {
  map.peaks = { loading: true };
  try {
    const r = await app.api('/api/stress', { model, method: 'fe' }, 'json', { key: 'femap', label: t('jobStress') });
    if (map.model !== model) return;
    map.peaks = r;
    peaksTable();
  } catch (e) {
    if (map.model === model) { map.peaks = { error: true }; $('#femap-peaks').innerHTML = `<p>${failure(e)}</p>`; }
  }
}

// The link, its peak and step, and the flat arc: what fits a phone's width (the peak's place is
// marked on the map at its step).
function peaksTable() {
  const r = map.peaks;
  if (!r?.links) return;
  const u = r.units ?? {};
  const cell = (v) => (Number.isFinite(v) ? app.fmt(v) : '–');
  const head = ['link', 'von_mises', 'step', 'flat_from', 'flat_to', 'flat_arc'];
  const unit = { von_mises: u.stress, flat_from: 'deg', flat_to: 'deg', flat_arc: u.length };
  const rows = r.links.map((l) => `<tr><th>${app.esc(l.body)}</th>${head.slice(1).map((k) => `<td data-col="${k}">${cell(l[k])}</td>`).join('')}</tr>`);
  $('#femap-peaks').innerHTML = `<p class="femap-caption">${app.esc(t('fePeaks'))}</p>`
    + `<table class="femap-table"><thead><tr>${head.map((k) => `<th>${k.replace('_', '_<wbr>')}${unit[k] ? `<small>${app.esc(unit[k])}</small>` : ''}</th>`).join('')}</tr></thead><tbody>${rows.join('')}</tbody></table>`;
}

// ------------------------------------------------------------------------------ the probe

// The pointer's place in the map's drawing: model coordinates (y up), the model's length unit.
function modelPoint(e) {
  const svg = $('#femap-drawing svg');
  const m = svg?.getScreenCTM();
  if (!m) return null;
  const p = new DOMPoint(e.clientX, e.clientY).matrixTransform(m.inverse());
  return { x: p.x, y: -p.y };
}

function probeAt(point) {
  if (!map.scene || !point) return;
  const job = { seq: ++map.probe.seq, model: map.model, step: map.step, point };
  if (map.probe.busy) { map.probe.pending = job; return; }
  sendProbe(job);
}

async function sendProbe(job) {
  map.probe.busy = true;
  try {
    const r = await app.api('/api/stress/probe', { model: job.model, step: job.step, x: job.point.x, y: job.point.y },
      'json', { key: 'probe' });
    // Only the answer for the pointer's latest place, at the map shown, is shown.
    if (job.seq === map.probe.seq && job.model === map.model && job.step === map.step) showProbe(r);
  } catch (e) {
    if (job.seq === map.probe.seq) readout(failure(e), 'error');
  } finally {
    map.probe.busy = false;
    const next = map.probe.pending;
    map.probe.pending = null;
    if (next) sendProbe(next);
  }
}

function showProbe(r) {
  const el = $('#probe');
  const u = r.units ?? {};
  if (r.link === null || r.link === undefined) {
    readout(t('probeOff', app.fmt(r.x), app.fmt(r.y), app.esc(u.length ?? '')), 'off');
    return;
  }
  readout(`<b>${app.esc(r.link)}</b>: <span class="vm">${probeNumber(r.von_mises)}</span> ${app.esc(u.stress)} ${t('probeVonMises')}`
    + ` <small>${t('probeAt', app.fmt(r.model_x), app.fmt(r.model_y), app.esc(u.length ?? ''))}</small>`, 'on');
  // The core's numbers in full, for whoever reads the page's data (the browser test).
  Object.assign(el.dataset, { link: r.link, vonMises: r.von_mises, modelX: r.model_x, modelY: r.model_y, step: r.step });
}

// Four significant digits: the map's colours cannot tell more, and the number stays one width.
export function probeNumber(v) {
  return Number.isFinite(v) ? Number(v.toPrecision(4)).toString() : '–';
}

// ------------------------------------------------------------------------------ controls

function build() {
  const label = document.createElement('label');
  label.className = 'check';
  label.innerHTML = `<input type="checkbox" data-overlay="femap"><span data-i18n="ov_femap">${t('ov_femap')}</span>`;
  $('.ov-checks').append(label);
  const box = document.createElement('div');
  box.id = 'femap';
  box.className = 'femap';
  box.hidden = true;
  box.innerHTML = `<div id="femap-drawing" class="femap-drawing" aria-label="${t('ariaStressMap')}" data-i18n-aria="ariaStressMap"></div>`
    + '<p id="probe" class="probe" aria-live="polite"></p><div id="femap-peaks" class="femap-peaks"></div>';
  $('.overlays').append(box);
  label.querySelector('input').addEventListener('change', (e) => {
    map.on = e.target.checked;
    box.hidden = !map.on;
    if (map.on) { readout(t('loading')); loadMap(); }
  });
  const drawing = $('#femap-drawing');
  drawing.addEventListener('pointermove', (e) => probeAt(modelPoint(e)));
  drawing.addEventListener('pointerdown', (e) => probeAt(modelPoint(e)));
  // A finger held on the map reads the stress where it is (the page scrolls elsewhere).
  drawing.addEventListener('contextmenu', (e) => e.preventDefault());
}

export function initStressMap(context) {
  app = context;
  build();
  document.addEventListener('nbar:solved', () => { if (map.on) loadMap(); });
  document.addEventListener('nbar:frame', () => { if (map.on && app.state.frame !== map.step) loadMap(); });
  document.addEventListener('nbar:lang', () => { if (map.on) peaksTable(); });
}
