// Motion overlays on the drawing, each toggled by a check box: traces of chosen points, velocity
// and acceleration vectors of points (the solve's P.vx/P.vy/P.ax/P.ay columns), joint-force arrows
// (a dynamics solve's J.A>B.Fx/Fy columns), links coloured by their peak von Mises stress with the
// peak marked (/api/stress), and a line with each four-bar loop's Grashof class (/api/check) and
// its transmission angle at the pose shown (the solve's LOOP.mu column). The sweep's warnings and
// its stop are listed with their step and flagged on the drawing when the pose shown is there.
// Every number comes from the server; this module only scales and draws them.
import { t, translatePage } from './i18n.js';

const $ = (s) => document.querySelector(s);
const SVGNS = 'http://www.w3.org/2000/svg';
const kinds = ['traces', 'velocity', 'acceleration', 'forces', 'stress'];
const colours = { velocity: '#0e9384', acceleration: '#c11574', forces: '#b54708' };

let app = null;
const ov = {
  on: new Set(), traced: new Set(), forces: null, stress: null, model: null, busy: {},
};

// ------------------------------------------------------------------------------ controls

function buildControls() {
  const box = document.createElement('div');
  box.className = 'overlays';
  box.innerHTML = `<div class="ov-checks">${kinds.map((k) => `<label class="check"><input type="checkbox" data-overlay="${k}"><span data-i18n="ov_${k}">${t(`ov_${k}`)}</span></label>`).join('')}</div>`
    + '<div id="ov-traced" class="ov-chips" hidden></div>'
    + '<div id="ov-legend" class="ov-legend"></div>'
    + '<div id="motion-info" class="motion-info"></div>'
    + '<div id="motion-facts" class="motion-info"></div>'
    + '<ul id="warnings" class="warnings"></ul>'
    + '<div id="stress-table" class="stress-table" hidden></div>';
  $('.stage .controls').after(box);
  for (const c of box.querySelectorAll('[data-overlay]')) {
    c.addEventListener('change', () => {
      if (c.checked) ov.on.add(c.dataset.overlay); else ov.on.delete(c.dataset.overlay);
      $('#ov-traced').hidden = !ov.on.has('traces');
      refresh();
    });
  }
  translatePage();
}

function chips() {
  const g = app.state.geometry;
  const moving = g.points.filter((p) => !g.ground.has(p));
  for (const p of [...ov.traced]) if (!moving.includes(p)) ov.traced.delete(p);
  if (!ov.traced.size && moving.length) ov.traced.add(moving.at(-1));
  $('#ov-traced').innerHTML = moving.map((p) => `<label class="chip"><input type="checkbox" data-trace="${app.esc(p)}" ${ov.traced.has(p) ? 'checked' : ''}>${app.esc(p)}</label>`).join('');
  for (const c of document.querySelectorAll('[data-trace]')) {
    c.addEventListener('change', () => {
      if (c.checked) ov.traced.add(c.dataset.trace); else ov.traced.delete(c.dataset.trace);
      drawTraces();
    });
  }
}

// What a share link keeps of the overlays (main.js): the boxes ticked and the points traced.
export function overlayView() { return { on: [...ov.on], traced: [...ov.traced] }; }
export function setOverlayView({ on = [], traced = [] }) {
  if (traced.length) ov.traced = new Set(traced);
  for (const c of document.querySelectorAll('[data-overlay]')) {
    const wanted = on.includes(c.dataset.overlay);
    if (c.checked !== wanted) { c.checked = wanted; c.dispatchEvent(new Event('change')); }
  }
  if (app.state.solve) { chips(); drawTraces(); }
}

// ------------------------------------------------------------------------------ data from the server

// The dynamics solve (joint forces) and the stresses are asked for only when their box is on,
// once per model text. Only answers are kept: an error ("the server is busy") is shown until the
// next try, which ticking the box again makes at once and moving through the sweep makes at
// most every `retryAfterMs` (a slider sends many frames; a busy server needs no more load).
const retryAfterMs = 3000;
function fetchIfNeeded({ eager = true } = {}) {
  const model = app.state.lastOk;
  // The joint forces and stresses are the sweep's (solve --dynamics, stress): none is drawn on a
  // simulation's rows, which are other poses at other speeds.
  const key = app.state.simulation ? `simulate\n${model}` : model;
  if (ov.model !== key) { ov.model = key; ov.forces = null; ov.stress = null; }
  if (app.state.simulation) return undefined;
  // In the browser's engine, an edit cancels these with the analysis they belong to.
  const stale = { key: 'analysis', label: t('analysing') };
  const jobs = [
    fetchOne('forces', () => app.api('/api/solve', { model, dynamics: true, order: 2, columns: ['*.Fx', '*.Fy'] }, 'json', stale), eager),
    fetchOne('stress', () => app.api('/api/stress', { model }, 'json', { ...stale, label: t('jobStress') }), eager),
  ].filter(Boolean);
  if (!jobs.length) return undefined;
  return Promise.all(jobs).then(() => { if (ov.model === app.state.lastOk) { drawFrame(); legend(); } });
}

// One overlay's request, unless its box is off, it has its answer, one is under way, or (not
// `eager`) its last error is too recent to try again.
function fetchOne(kind, request, eager) {
  const held = ov[kind];
  if (!ov.on.has(kind) || held?.ok || ov.busy[kind]) return null;
  if (held?.error && !eager && Date.now() - held.at < retryAfterMs) return null;
  const model = ov.model;
  ov.busy[kind] = true;
  if (held?.error) { held.retrying = true; legend(); }
  return request()
    .then((r) => { if (ov.model === model) ov[kind] = { ok: r }; },
      (e) => { if (ov.model === model) ov[kind] = { error: e.message, at: Date.now() }; })
    .finally(() => { ov.busy[kind] = false; });
}

// ------------------------------------------------------------------------------ scales

function niceStep(v) {
  if (!(v > 0)) return 1;
  const e = 10 ** Math.floor(Math.log10(v));
  const m = v / e;
  return (m >= 5 ? 5 : m >= 2 ? 2 : 1) * e;
}

// Vectors of a set of columns (x, y) at points: the scale puts the largest over the whole
// sweep at a fifth of the drawing, so arrows stay readable and comparable between poses.
function vectorScale(solve, pairs, s) {
  let max = 0;
  for (const [i, j] of pairs) {
    for (const r of solve.rows) {
      const m = Math.hypot(r[i], r[j]);
      if (Number.isFinite(m)) max = Math.max(max, m);
    }
  }
  if (!(max > 0)) return null;
  const perUnit = (20 * s) / max;
  const legendValue = niceStep(max / 2);
  return { perUnit, max, legendValue, legendLength: legendValue * perUnit };
}

function pointVectors(kind) {
  const { solve, geometry } = app.state;
  const [a, b] = kind === 'velocity' ? ['vx', 'vy'] : ['ax', 'ay'];
  return geometry.points.filter((p) => !geometry.ground.has(p))
    .map((p) => ({ at: p, i: app.col(`${p}.${a}`), j: app.col(`${p}.${b}`), unit: app.unitOf(`${p}.${a}`) }))
    .filter((v) => v.i >= 0 && v.j >= 0);
}

// "A.crank>coupler.Fx": the force at point A, between crank and coupler.
function forceVectors() {
  const r = ov.forces?.ok;
  if (!r) return [];
  const idx = new Map(r.columns.map((c, k) => [c, k]));
  return r.columns.filter((c) => c.endsWith('.Fx')).map((c) => {
    const base = c.slice(0, -3);
    return { at: base.split('.')[0], label: base, i: idx.get(c), j: idx.get(`${base}.Fy`), unit: r.column_units[idx.get(c)] };
  }).filter((v) => v.j !== undefined);
}

// ------------------------------------------------------------------------------ drawing

function arrow(x, y, dx, dy, colour, s) {
  const len = Math.hypot(dx, dy);
  if (!(len > 1e-9)) return '';
  const ux = dx / len; const uy = dy / len;
  const h = Math.min(2.2 * s, len * 0.6);
  const bx = x + dx - ux * h; const by = y + dy - uy * h;
  const w = h * 0.45;
  const f = (v) => +v.toFixed(4);
  return `<line x1="${f(x)}" y1="${f(y)}" x2="${f(bx)}" y2="${f(by)}" stroke="${colour}" stroke-width="2.5" stroke-linecap="round" vector-effect="non-scaling-stroke"/>`
    + `<path d="M${f(x + dx)},${f(y + dy)} L${f(bx - uy * w)},${f(by + ux * w)} L${f(bx + uy * w)},${f(by - ux * w)} z" fill="${colour}"/>`;
}

function position(p, row) {
  const i = app.col(`${p}.x`); const j = app.col(`${p}.y`);
  return i >= 0 && j >= 0 ? [row[i], row[j]] : null;
}

function drawVectors(kind, row, s) {
  const { solve } = app.state;
  const vs = kind === 'forces' ? forceVectors() : pointVectors(kind);
  const source = kind === 'forces' ? ov.forces?.ok : solve;
  if (!vs.length || !source) return { svg: '', scale: null };
  const scale = vectorScale(source, vs.map((v) => [v.i, v.j]), s);
  if (!scale) return { svg: '', scale: { zero: true } };
  const srow = source.rows[app.state.frame];
  if (!srow) return { svg: '', scale };
  let out = '';
  for (const v of vs) {
    const p = position(v.at, row);
    if (!p) continue;
    const dx = srow[v.i] * scale.perUnit; const dy = srow[v.j] * scale.perUnit;
    if (Number.isFinite(dx) && Number.isFinite(dy)) out += arrow(p[0], -p[1], dx, -dy, colours[kind], s);
  }
  return { svg: `<g class="ov-${kind}">${out}</g>`, scale: { ...scale, unit: vs[0].unit } };
}

function stressColour(f) {
  // blue (low) - amber - red (the peak)
  const stops = [[37, 99, 235], [245, 158, 11], [217, 45, 32]];
  const x = Math.min(Math.max(f, 0), 1) * 2;
  const k = Math.min(Math.floor(x), 1);
  const u = x - k;
  const c = stops[k].map((v, n) => Math.round(v + (stops[k + 1][n] - v) * u));
  return `rgb(${c.join(',')})`;
}

function drawStress(row, s, svg) {
  const links = ov.stress?.ok?.links ?? [];
  if (!links.length) return '';
  const max = Math.max(...links.map((l) => l.von_mises));
  const top = links.find((l) => l.von_mises === max);
  let out = '';
  for (const l of links) {
    const colour = stressColour(max > 0 ? l.von_mises / max : 0);
    for (const el of svg.querySelectorAll(`.frame .body[data-body="${CSS.escape(l.body)}"]`)) {
      el.setAttribute('stroke', colour);
      if (el.tagName !== 'polyline') el.setAttribute('fill', colour);
    }
    // The peak's place: x along the body's axis (its first point to its second), y to its left.
    const body = app.state.geometry.bodies.find((b) => b.name === l.body);
    const [p0, p1] = (body?.points ?? []).map((p) => position(p, row));
    if (!p0 || !p1) continue;
    const len = Math.hypot(p1[0] - p0[0], p1[1] - p0[1]) || 1;
    const ux = (p1[0] - p0[0]) / len; const uy = (p1[1] - p0[1]) / len;
    const x = p0[0] + ux * l.x - uy * l.y; const y = p0[1] + uy * l.x + ux * l.y;
    const big = l === top;
    out += `<circle class="${big ? 'peak' : 'lpeak'}" data-step="${l.step}" cx="${+x.toFixed(4)}" cy="${+(-y).toFixed(4)}" r="${(big ? 1.8 : 1.1) * s}" fill="${colour}" stroke="#fff" stroke-width="1.5" vector-effect="non-scaling-stroke"/>`;
    if (big) {
      // The label on the side of the peak facing the middle of the drawing, so that it stays in view.
      const vb = svg.viewBox.baseVal;
      const right = x > vb.x + vb.width / 2;
      const lx = x + (right ? -2.5 : 2.5) * s;
      out += `<text class="peak-label" data-step="${l.step}" x="${+lx.toFixed(4)}" y="${+(-y - 2.5 * s).toFixed(4)}" text-anchor="${right ? 'end' : 'start'}" font-size="${3.4 * s}" style="--fs:${+(3.4 * s).toFixed(4)}" font-weight="700" fill="#b42318" stroke="#fff" stroke-width="4" paint-order="stroke" vector-effect="non-scaling-stroke" font-family="system-ui, sans-serif">${app.fmt(l.von_mises)} ${app.esc(ov.stress.ok.units?.stress ?? '')} (${t('atStep', l.step)})</text>`;
    }
  }
  return `<g class="ov-stress">${out}</g>`;
}

function drawTraces() {
  const svg = document.querySelector('#drawing svg');
  if (!svg) return;
  svg.querySelector('.ov-traces')?.remove();
  if (!ov.on.has('traces')) return;
  const { solve } = app.state;
  const g = document.createElementNS(SVGNS, 'g');
  g.setAttribute('class', 'ov-traces');
  g.innerHTML = [...ov.traced].map((p, k) => {
    const i = app.col(`${p}.x`); const j = app.col(`${p}.y`);
    if (i < 0 || j < 0) return '';
    const pts = solve.rows.filter((r) => Number.isFinite(r[i]) && Number.isFinite(r[j])).map((r) => `${+r[i].toFixed(4)},${+(-r[j]).toFixed(4)}`).join(' ');
    return `<polyline data-traced="${app.esc(p)}" points="${pts}" fill="none" stroke="${['#7a5af8', '#0e9384', '#c11574', '#b54708'][k % 4]}" stroke-width="1.8" vector-effect="non-scaling-stroke"/>`;
  }).join('');
  svg.querySelector('.frame').before(g);
}

let scales = {};
function drawFrame() {
  const svg = document.querySelector('#drawing svg');
  const { solve, geometry } = app.state;
  if (!svg || !solve || !geometry) return;
  svg.querySelector('.ov')?.remove();
  svg.querySelector('.ov-peaks')?.remove();
  const row = solve.rows[app.state.frame];
  if (!row) return;
  const s = geometry.scale ?? 1;
  let out = '';
  scales = {};
  // The stress peaks' markers and labels go to their step when clicked: above the handles.
  if (ov.on.has('stress')) {
    const peaks = document.createElementNS(SVGNS, 'g');
    peaks.setAttribute('class', 'ov-peaks');
    peaks.innerHTML = drawStress(row, s, svg);
    svg.append(peaks);
  }
  for (const k of ['velocity', 'acceleration', 'forces']) {
    if (!ov.on.has(k)) continue;
    const d = drawVectors(k, row, s);
    out += d.svg;
    scales[k] = d.scale;
  }
  out += warningFlag(s, svg);
  const g = document.createElementNS(SVGNS, 'g');
  g.setAttribute('class', 'ov');
  g.innerHTML = out;
  // Under the point handles, so that a joint under an arrow is still grabbed.
  const handles = svg.querySelector('.handles');
  if (handles) handles.before(g); else svg.append(g);
  info(row);
}

// ------------------------------------------------------------------------------ legend, info, warnings

function legend() {
  const parts = [];
  for (const k of ['velocity', 'acceleration', 'forces']) {
    if (!ov.on.has(k)) continue;
    const sc = scales[k];
    if (k === 'forces' && ov.forces?.error) { parts.push(failed('forces', ov.forces)); continue; }
    if (sc?.zero) { parts.push(`<span>${t(`ov_${k}`)}: ${t('allZero')}</span>`); continue; }
    if (!sc) { parts.push(`<span>${t(`ov_${k}`)}: ${t(k === 'forces' && !ov.forces ? 'loading' : 'noVectors')}</span>`); continue; }
    // The legend's bar is drawn at the same scale as the arrows, in the drawing's pixels.
    const px = pixelsPerUnit();
    const w = Math.max(8, Math.min(160, sc.legendLength * px));
    const note = k === 'forces' ? ` title="${app.esc(t('forcesNote'))}"` : '';
    parts.push(`<span class="leg" data-legend="${k}"${note}><svg width="${w + 8}" height="10"><line x1="1" y1="5" x2="${w}" y2="5" stroke="${colours[k]}" stroke-width="2.5"/><path d="M${w + 6},5 L${w - 1},1 L${w - 1},9 z" fill="${colours[k]}"/></svg>`
      + ` = ${app.fmt(sc.legendValue)} ${app.esc(sc.unit ?? '')} <small>(${t('maxIs')} ${app.fmt(sc.max)})</small></span>`);
  }
  stressTable();
  if (ov.on.has('stress')) {
    if (ov.stress?.error) parts.push(failed('stress', ov.stress));
    else if (!ov.stress) parts.push(`<span>${t('ov_stress')}: ${t('loading')}</span>`);
    else {
      const links = ov.stress.ok.links;
      const max = Math.max(...links.map((l) => l.von_mises));
      parts.push(`<span class="leg" data-legend="stress">${t('vonMises')} <span class="ramp"></span> 0 – ${app.fmt(max)} ${app.esc(ov.stress.ok.units?.stress ?? '')}</span>`);
    }
  }
  $('#ov-legend').innerHTML = parts.join('');
}

// Each shaped link's peak over the sweep, as `nbar stress` gives it (the core's von Mises, step,
// place in the link's frame and safety factor, yield over peak, from the model's material): one
// row a link, each going to its step when tapped. Shown with the Stress overlay.
function stressTable() {
  const box = $('#stress-table');
  const answer = ov.on.has('stress') ? ov.stress?.ok : null;
  box.hidden = !answer?.links?.length;
  if (box.hidden) { box.innerHTML = ''; return; }
  const u = answer.units ?? {};
  const esc = app.esc;
  const head = [t('stLink'), `${t('stPeak')} (${u.stress ?? ''})`, t('stSafety'), t('stStep'), `${t('stWhere')} (${u.length ?? ''})`];
  const rows = answer.links.map((l) => `<tr data-body="${esc(l.body)}" data-step="${l.step}">`
    + `<th><button type="button" class="ghost" data-stress-step="${l.step}" title="${esc(t('stGo', l.body, l.step))}">${esc(l.body)}</button></th>`
    + `<td data-col="von_mises">${app.fmt(l.von_mises)}</td>`
    + `<td data-col="safety_factor">${Number.isFinite(l.safety_factor) ? app.fmt(l.safety_factor) : `– <small>${esc(t('stNoYield'))}</small>`}</td>`
    + `<td data-col="step">${l.step}</td><td data-col="where">${app.fmt(l.x)}, ${app.fmt(l.y)}</td></tr>`).join('');
  box.innerHTML = `<h4>${esc(t('stTitle'))}</h4><div class="tablewrap"><table><thead><tr>${head.map((h) => `<th>${esc(h)}</th>`).join('')}</tr></thead>`
    + `<tbody>${rows}</tbody></table></div><p class="hint">${esc(t('stHint'))}</p>`;
}

// An overlay whose last request failed: the reason, and that it is being tried again.
function failed(kind, held) {
  const again = held.retrying ? ` <small>(${t('retrying')})</small>` : '';
  return `<span class="bad" data-failed="${kind}">${t(`ov_${kind}`)}: ${app.esc(held.error)}${again}</span>`;
}

function pixelsPerUnit() {
  const svg = document.querySelector('#drawing svg');
  const m = svg?.getScreenCTM();
  return m ? Math.hypot(m.a, m.b) : 1;
}

function info(row) {
  const { check } = app.state;
  const loops = check?.loops ?? [];
  const parts = loops.map((l) => {
    const i = app.col(`${l.name}.mu`);
    let mu = '';
    if (i >= 0 && Number.isFinite(row[i])) {
      // The design value over the sweep, min(μ, 180° − μ) at its smallest, is the core's (the
      // solve's branches[].transmission_angle), not worked out here.
      const design = app.state.solve.branches?.find((b) => b.loop === l.name)?.transmission_angle?.design;
      mu = ` · μ = ${app.fmt(row[i])}°` + (Number.isFinite(design) ? ` <small>(${t('minIs')} ${app.fmt(design)}°)</small>` : '');
    }
    return `<span class="loop" title="${app.esc(coreDescription(l.description))}"><b>${app.esc(l.name)}</b>: ${app.esc(l.grashof ?? '')}${mu}</span>`;
  });
  $('#motion-info').innerHTML = parts.join('');
  // The model's facts change with the model, not the frame: a line of their own, rewritten only
  // when they change, so that the plot below never moves while the mechanism plays.
  const facts = motionFacts(check);
  if (facts !== shownFacts) $('#motion-facts').innerHTML = shownFacts = facts;
}
let shownFacts = '';

// A loop's, rocker's or slider-crank's description from the core, as a tooltip, as it comes: the
// check is asked in the app's language and the server says its descriptions in it from the core's
// catalogue (src/request/language.cpp), so nothing is translated or held back here. A change of
// language asks the check again, and the tooltips follow.
function coreDescription(text) {
  return text ?? '';
}

// A crank-rocker's swing and time ratio, and a slider-crank's stroke and time ratio, as
// `nbar check` gives them (the core's numbers; the full description in the tooltip).
function motionFacts(check) {
  const angle = app.esc(check?.units?.angle ?? ''), length = app.esc(check?.units?.length ?? '');
  const rockers = (check?.loops ?? []).filter((l) => l.rocker).map((l) => `<span class="loop" title="${app.esc(coreDescription(l.rocker.description))}">`
    + `<b>${app.esc(l.name)}</b>: ${t('swingIs', app.fmt(l.rocker.swing), angle)} · ${t('timeRatioIs', app.fmt(l.rocker.time_ratio))}</span>`);
  const sliders = (check?.slider_cranks ?? []).map((f) => `<span class="loop" title="${app.esc(coreDescription(f.description))}">`
    + `<b>${app.esc(f.slider)}</b>: ${t('strokeIs', app.fmt(f.stroke), length)} · ${t('timeRatioIs', app.fmt(f.time_ratio))}</span>`);
  return [...rockers, ...sliders].join('');
}

function sweepWarnings() {
  const { solve } = app.state;
  // The solve's JSON gives its warnings as plain messages; a structured one (from the core's
  // Warning) may carry the step it happened at. A warning with no step gets no step button.
  const list = (solve.warnings ?? []).map((w) => (typeof w === 'string'
    ? { step: null, text: w, code: '' }
    : { step: Number.isInteger(w.step) && w.step >= 0 ? w.step : null, text: w.message ?? '', code: w.code }));
  if (!solve.complete) list.push({ step: solve.rows.length - 1, text: solve.stop_reason ?? t('stopped'), code: 'stop' });
  return list;
}

function warnings() {
  const list = sweepWarnings();
  $('#warnings').innerHTML = list.map((w) => `<li class="${w.code === 'stop' ? 'stop' : ''}">${w.step === null ? '⚠' : `<button type="button" class="ghost" data-step="${w.step}">⚠ ${t('atStep', w.step)}</button>`} ${app.esc(w.text)}</li>`).join('');
  for (const b of document.querySelectorAll('#warnings [data-step]')) b.addEventListener('click', () => { app.play(false); app.setFrame(+b.dataset.step); });
  // Ticks on the scrub bar where they happen.
  const n = Math.max(app.state.solve.rows.length - 1, 1);
  let ticks = $('#scrub-ticks');
  if (!ticks) {
    ticks = document.createElement('div');
    ticks.id = 'scrub-ticks';
    $('#scrub').after(ticks);
  }
  placeTicks();
  ticks.innerHTML = list.filter((w) => w.step !== null).map((w) => `<i style="left:${(100 * w.step) / n}%"></i>`).join('');
}

// The ticks lie under the scrub bar's track.
function placeTicks() {
  const ticks = $('#scrub-ticks'); const scrub = $('#scrub');
  if (!ticks) return;
  ticks.style.left = `${scrub.offsetLeft + 8}px`;
  ticks.style.width = `${Math.max(scrub.offsetWidth - 16, 0)}px`;
}

function warningFlag(s, svg) {
  const here = sweepWarnings().filter((w) => w.step === app.state.frame);
  if (!here.length) return '';
  const vb = svg.viewBox.baseVal;
  const text = here.map((w) => w.text).join(' · ');
  // As many characters as fit the drawing's width (about 0.55 of the font size each).
  const size = 2.8 * s;
  const fit = Math.max(12, Math.floor((vb.width - 5 * s) / (size * 0.56)));
  const short = text.length > fit ? `${text.slice(0, fit - 1)}…` : text;
  return `<g class="ov-warning"><title>${app.esc(text)}</title><rect x="${vb.x + s}" y="${vb.y + s}" width="${vb.width - 2 * s}" height="${5.5 * s}" rx="${s}" fill="#fef3f2" stroke="#d92d20" vector-effect="non-scaling-stroke"/>`
    + `<text x="${vb.x + 2.5 * s}" y="${vb.y + 4.7 * s}" font-size="${size}" fill="#b42318" font-family="system-ui, sans-serif">⚠ ${app.esc(short)}</text></g>`;
}

function refresh() {
  if (!app.state.solve) return;
  drawTraces();
  drawFrame();
  legend();
  fetchIfNeeded();
}

export function initOverlays(context) {
  app = context;
  buildControls();
  document.addEventListener('nbar:solved', () => { chips(); warnings(); refresh(); });
  // Moving through the sweep draws the pose, and tries a failed overlay again (not too often).
  document.addEventListener('nbar:frame', () => { drawFrame(); fetchIfNeeded({ eager: false }); });
  // The legend, the loops' line and the warnings are written in the language chosen.
  document.addEventListener('nbar:lang', () => { if (app.state.solve) { warnings(); drawFrame(); legend(); } });
  // The drawing drawn again for a new size: the traces go back on it.
  document.addEventListener('nbar:drawn', drawTraces);
  $('#stress-table').addEventListener('click', (e) => {
    const row = e.target.closest('tr[data-step]');
    if (row) { app.play(false); app.setFrame(+row.dataset.step); }
  });
  document.querySelector('#drawing').addEventListener('click', (e) => {
    const peak = e.target.closest('[data-step].peak, .peak-label');
    if (peak) { app.play(false); app.setFrame(+peak.dataset.step); }
  });
  new ResizeObserver(() => { if (app.state.solve) { legend(); placeTicks(); } }).observe(document.querySelector('#drawing'));
}
