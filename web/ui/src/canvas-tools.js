// The drawing's tool bar and pointer handling: select (and drag, done by main.js), add a point,
// add a link between two points, add or toggle a ground pivot; grid snap; undo/redo; wheel and
// pinch zoom, pan with one finger or the mouse on empty space, and "fit". Only the geometry of
// the edit is computed here (where the tap was, snapped to the grid): positions after an edit
// come from the server's solve.
import { t } from './i18n.js';
import { setIn, deleteIn, roundTo } from './yaml-text.js';
import { applyEdit, modelData, undoEdit, redoEdit, freshName, editContext } from './model-edit.js';
import { addSliderBlock } from './build-model.js';

const SVG = 'http://www.w3.org/2000/svg';
const tool = { name: 'select', snap: false, first: null, selected: null };
let view = null;        // the user's viewBox {x, y, w, h} (svg units, y down) or null: fitted
let pointers = new Map(); // pointerId -> {x, y} client position, for pan and pinch
let gesture = null;
let onSelect = () => {};

const $ = (s) => document.querySelector(s);
const svgEl = () => $('#drawing svg');

// ------------------------------------------------------------------------------ tool bar

const tools = [
  { id: 'select', icon: '↖', key: 'toolSelect' },
  { id: 'point', icon: '•', key: 'toolPoint' },
  { id: 'link', icon: '╱', key: 'toolLink' },
  { id: 'ground', icon: '⊥', key: 'toolGround' },
  { id: 'slider', icon: '▭', key: 'toolSlider' },
];

function button(id, icon, key, onClick) {
  const b = document.createElement('button');
  b.type = 'button';
  b.dataset.tool = id;
  b.dataset.i18nTitle = key;
  b.dataset.i18nAria = key;
  b.title = t(key);
  b.setAttribute('aria-label', t(key));
  b.textContent = icon;
  b.addEventListener('click', onClick);
  return b;
}

function buildToolbar() {
  const bar = $('#edit-tools');
  const items = tools.map((x) => button(x.id, x.icon, x.key, () => setTool(x.id)));
  const snap = button('snap', '#', 'toolSnap', () => { tool.snap = !tool.snap; snap.setAttribute('aria-pressed', String(tool.snap)); redrawOverlay(); });
  snap.setAttribute('aria-pressed', 'false');
  const sep = () => Object.assign(document.createElement('span'), { className: 'sep' });
  bar.replaceChildren(...items, sep(), snap, sep(),
    button('undo', '↶', 'undo', undoEdit), button('redo', '↷', 'redo', redoEdit), sep(),
    button('zoom-in', '+', 'zoomIn', () => zoomBy(1 / 1.25)), button('zoom-out', '−', 'zoomOut', () => zoomBy(1.25)),
    button('fit', '⤢', 'fit', fit));
  setTool('select');
}

export function setTool(name) {
  tool.name = name;
  tool.first = null;
  for (const b of document.querySelectorAll('#edit-tools [data-tool]')) {
    if (tools.some((x) => x.id === b.dataset.tool)) b.setAttribute('aria-pressed', String(b.dataset.tool === name));
  }
  $('#drawing').dataset.tool = name;
  redrawOverlay();
}

// ------------------------------------------------------------------------------ view

function fittedBox(svg) { return svg.dataset.fit ? JSON.parse(svg.dataset.fit) : null; }
function currentBox(svg) { const b = svg.viewBox.baseVal; return { x: b.x, y: b.y, w: b.width, h: b.height }; }
function applyView() {
  const svg = svgEl();
  if (!svg) return;
  const b = view ?? fittedBox(svg);
  if (b) svg.setAttribute('viewBox', `${b.x} ${b.y} ${b.w} ${b.h}`);
  // How much the view is enlarged: labels are drawn that much smaller (style.css, --fs), so
  // that zooming enlarges the mechanism and not its text.
  const fitted = fittedBox(svg);
  if (b && fitted) svg.style.setProperty('--zoom', String(fitted.w / b.w));
  redrawOverlay();
}
export function fit() { view = null; applyView(); }
export function zoomBy(f, clientX, clientY) {
  const svg = svgEl();
  if (!svg) return;
  const b = currentBox(svg);
  const r = svg.getBoundingClientRect();
  const c = toSvg(clientX ?? r.left + r.width / 2, clientY ?? r.top + r.height / 2);
  const fitted = fittedBox(svg);
  const w = Math.min(Math.max(b.w * f, fitted.w / 50), fitted.w * 20);
  const k = w / b.w;
  view = { x: c.x - (c.x - b.x) * k, y: c.y - (c.y - b.y) * k, w: b.w * k, h: b.h * k };
  applyView();
}
// Client pixels to svg units (y down; the model's y is -svg y).
function toSvg(x, y) {
  const svg = svgEl();
  const p = new DOMPoint(x, y).matrixTransform(svg.getScreenCTM().inverse());
  return { x: p.x, y: p.y };
}
function unitsPerPixel() { return 1 / svgEl().getScreenCTM().a; }

// ------------------------------------------------------------------------------ snapping

// The part of the plane the drawing shows: wider or taller than the viewBox when the element's
// shape differs from the box's (preserveAspectRatio meet).
function visibleBox() {
  const r = svgEl().getBoundingClientRect();
  const a = toSvg(r.left, r.top); const c = toSvg(r.right, r.bottom);
  return { x: a.x, y: a.y, w: c.x - a.x, h: c.y - a.y };
}
function gridStep() {
  const b = visibleBox();
  const raw = b.w / 30;
  const p = 10 ** Math.floor(Math.log10(raw));
  return [1, 2, 5, 10].map((m) => m * p).find((s) => s >= raw) ?? 10 * p;
}
// A model point on the grid when snap is on (for main.js's drag), else null.
export function snapPoint(x, y) {
  if (!tool.snap || !svgEl()) return null;
  const step = gridStep();
  const digits = Math.max(0, -Math.floor(Math.log10(step)) + 1);
  return [roundTo(Math.round(x / step) * step, digits), roundTo(Math.round(y / step) * step, digits)];
}
function modelPoint(clientX, clientY) {
  const s = toSvg(clientX, clientY);
  let x = s.x; let y = -s.y;
  const scale = editContext().state.geometry?.scale || 1;
  let digits = 2 - Math.floor(Math.log10(scale));
  if (tool.snap) {
    const step = gridStep();
    x = Math.round(x / step) * step; y = Math.round(y / step) * step;
    digits = Math.max(0, -Math.floor(Math.log10(step)) + 1);
  }
  return [roundTo(x, digits), roundTo(y, digits)];
}

// ------------------------------------------------------------------------------ overlay

// Points written in the text but not in the last solve (a new point not yet on a body): drawn
// where the text puts them so that they can be tapped, dashed.
function pendingPoints() {
  const m = modelData();
  const solved = new Set(editContext().state.geometry?.points ?? []);
  if (!m || !m.points || typeof m.points !== 'object') return [];
  return Object.entries(m.points)
    .filter(([p, v]) => !solved.has(p) && Array.isArray(v) && v.length === 2 && v.every(Number.isFinite))
    .map(([p, v]) => ({ name: p, x: v[0], y: -v[1] }));
}

function el(name, attrs) {
  const e = document.createElementNS(SVG, name);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, String(v));
  return e;
}

export function redrawOverlay() {
  const svg = svgEl();
  if (!svg) return;
  svg.querySelector('.edit-grid')?.remove();
  svg.querySelector('.edit-overlay')?.remove();
  const s = editContext().state.geometry?.scale || currentBox(svg).w / 100;
  const b = visibleBox();
  if (tool.snap) {
    const step = gridStep();
    const g = el('g', { class: 'edit-grid' });
    for (let x = Math.ceil(b.x / step) * step; x <= b.x + b.w; x += step) g.append(el('line', { x1: x, y1: b.y, x2: x, y2: b.y + b.h }));
    for (let y = Math.ceil(b.y / step) * step; y <= b.y + b.h; y += step) g.append(el('line', { x1: b.x, y1: y, x2: b.x + b.w, y2: y }));
    svg.prepend(g);
  }
  const o = el('g', { class: 'edit-overlay' });
  for (const p of pendingPoints()) {
    o.append(el('circle', { class: 'pending', 'data-pending': p.name, cx: p.x, cy: p.y, r: 1.4 * s }));
    const label = el('text', { x: p.x + 1.8 * s, y: p.y - 1.8 * s, 'font-size': 3.2 * s });
    label.textContent = p.name;
    o.append(label);
  }
  if (tool.first) {
    const at = positionOf(tool.first);
    if (at) o.append(el('circle', { class: 'first', cx: at.x, cy: at.y, r: 2.2 * s }));
  }
  svg.append(o);
  let style = $('#edit-style');
  if (!style) { style = document.createElement('style'); style.id = 'edit-style'; document.head.append(style); }
  style.textContent = tool.selected ? `#drawing .body[data-body="${CSS.escape(tool.selected)}"] { stroke-opacity: .85; filter: drop-shadow(0 0 3px #f97316) drop-shadow(0 0 2px #f97316); }` : '';
}

// Where a point is drawn now (svg units): its circle in the frame, or its pending marker.
function positionOf(name) {
  const c = document.querySelector(`#drawing circle.pt[data-point="${CSS.escape(name)}"], #drawing circle.pending[data-pending="${CSS.escape(name)}"]`);
  return c ? { x: +c.getAttribute('cx'), y: +c.getAttribute('cy') } : null;
}
function pointAt(target) {
  const c = target.closest?.('[data-point], [data-pending]');
  return c ? (c.dataset.point ?? c.dataset.pending) : null;
}
// The body nearest a tap (within a few pixels of one of its edges), from the drawn frame.
function bodyAt(clientX, clientY) {
  const p = toSvg(clientX, clientY);
  const tol = 14 * unitsPerPixel();
  let best = null; let bestD = tol;
  for (const b of editContext().state.geometry?.bodies ?? []) {
    const pts = b.points.map(positionOf).filter(Boolean);
    const edges = pts.length > 2 ? pts.map((q, i) => [q, pts[(i + 1) % pts.length]]) : [[pts[0], pts[1]]];
    for (const [a, c] of edges) {
      if (!a || !c) continue;
      const dx = c.x - a.x; const dy = c.y - a.y;
      const u = Math.max(0, Math.min(1, ((p.x - a.x) * dx + (p.y - a.y) * dy) / (dx * dx + dy * dy || 1)));
      const d = Math.hypot(p.x - a.x - u * dx, p.y - a.y - u * dy);
      if (d < bestD) { bestD = d; best = b.name; }
    }
  }
  return best;
}

// ------------------------------------------------------------------------------ edits

function takenPoints(m) { return new Set(Object.keys(m?.points ?? {})); }

function addPoint(xy, ground) {
  const m = modelData();
  const name = freshName('P', takenPoints(m));
  applyEdit((text) => {
    let out = setIn(text, ['points', name], xy);
    if (ground) out = setIn(out, ['ground', (m.ground ?? []).length], name);
    return out;
  });
  return name;
}

function toggleGround(name) {
  const m = modelData();
  const ground = Array.isArray(m?.ground) ? m.ground : [];
  const i = ground.indexOf(name);
  applyEdit((text) => (i >= 0 ? deleteIn(text, ['ground', i]) : setIn(text, ['ground', ground.length], name)));
}

// The link tool: the first tap picks (or places) one end, the second the other; one edit adds
// the new points and the two-point body.
function linkTap(end) {
  if (!tool.first) { tool.first = end; redrawOverlay(); return; }
  const a = tool.first;
  tool.first = null;
  if (typeof a === 'string' && a === end) { redrawOverlay(); return; }
  const m = modelData() ?? {};
  const taken = takenPoints(m);
  const names = [a, end].map((e) => {
    if (typeof e === 'string') return { name: e };
    const name = freshName('P', taken);
    taken.add(name);
    return { name, xy: e };
  });
  const body = freshName('link', new Set(Object.keys(m.bodies ?? {})));
  applyEdit((text) => {
    let out = text;
    for (const n of names) if (n.xy) out = setIn(out, ['points', n.name], n.xy);
    return setIn(out, ['bodies', body], names.map((n) => n.name));
  });
}

// The slider tool: the first tap picks the sliding point, the second gives the guide's direction
// from it; build-model.js makes the block body and its ground guide in one edit, or says why not.
function sliderTap(pt, at) {
  if (!tool.first) {
    if (pt) { tool.first = pt; redrawOverlay(); } else editContext().status(t('sliderTapPoint'), true);
    return;
  }
  const point = tool.first;
  tool.first = null;
  redrawOverlay();
  addSliderBlock(point, at);
}

// `target`: what was under the pointer when it went down (the pointer is captured since).
function tap(e, target) {
  const pt = pointAt(target);
  if (tool.name === 'select') {
    tool.selected = bodyAt(e.clientX, e.clientY);
    redrawOverlay();
    onSelect(tool.selected);
  } else if (tool.name === 'point') {
    if (!pt) addPoint(modelPoint(e.clientX, e.clientY), false);
  } else if (tool.name === 'ground') {
    if (pt) toggleGround(pt); else addPoint(modelPoint(e.clientX, e.clientY), true);
  } else if (tool.name === 'link') {
    linkTap(pt ?? modelPoint(e.clientX, e.clientY));
  } else if (tool.name === 'slider') {
    sliderTap(pt, modelPoint(e.clientX, e.clientY));
  }
}

// ------------------------------------------------------------------------------ pointers

function down(e) {
  if (!svgEl()) return;
  // A stress peak's marker or label goes to its step when clicked (overlays.js): a pan begun on it
  // would capture the pointer and the click would never reach it.
  if (pointers.size === 0 && e.target.closest?.('[data-step]')) return;
  const onPoint = !!pointAt(e.target);
  pointers.set(e.pointerId, { x: e.clientX, y: e.clientY });
  // A point under the pointer in select mode is main.js's drag; two fingers always pinch.
  if (tool.name === 'select' && onPoint && pointers.size === 1) return;
  e.stopPropagation();
  e.preventDefault();
  try { $('#drawing').setPointerCapture(e.pointerId); } catch { /* a synthetic or finished pointer */ }
  const box = currentBox(svgEl());
  if (pointers.size === 2) {
    const [p, q] = [...pointers.values()];
    gesture = { kind: 'pinch', box, dist: Math.hypot(p.x - q.x, p.y - q.y) || 1, mid: toSvg((p.x + q.x) / 2, (p.y + q.y) / 2) };
  } else if (pointers.size === 1) {
    gesture = { kind: 'pan', box, x: e.clientX, y: e.clientY, k: unitsPerPixel(), moved: false, target: e.target };
  }
}
function move(e) {
  if (!pointers.has(e.pointerId) || !gesture) return;
  pointers.set(e.pointerId, { x: e.clientX, y: e.clientY });
  if (gesture.kind === 'pan') {
    const dx = e.clientX - gesture.x; const dy = e.clientY - gesture.y;
    if (!gesture.moved && Math.hypot(dx, dy) < 6) return;
    gesture.moved = true;
    view = { ...gesture.box, x: gesture.box.x - dx * gesture.k, y: gesture.box.y - dy * gesture.k };
    applyView();
  } else if (gesture.kind === 'pinch' && pointers.size >= 2) {
    const [p, q] = [...pointers.values()];
    const f = gesture.dist / (Math.hypot(p.x - q.x, p.y - q.y) || 1);
    const b = gesture.box;
    // Scale about the starting midpoint, then keep it under the fingers' current midpoint.
    const w = b.w * f; const h = b.h * f;
    view = { x: gesture.mid.x - (gesture.mid.x - b.x) * f, y: gesture.mid.y - (gesture.mid.y - b.y) * f, w, h };
    applyView();
    const now = toSvg((p.x + q.x) / 2, (p.y + q.y) / 2);
    view = { ...view, x: view.x + gesture.mid.x - now.x, y: view.y + gesture.mid.y - now.y };
    applyView();
  }
}
function up(e) {
  if (!pointers.has(e.pointerId)) return;
  pointers.delete(e.pointerId);
  const g = gesture;
  if (pointers.size === 0) gesture = null;
  else if (g?.kind === 'pinch') gesture = { kind: 'done' };
  if (e.type === 'pointerup' && g?.kind === 'pan' && !g.moved) tap(e, g.target);
}
function wheel(e) {
  if (!svgEl()) return;
  e.preventDefault();
  zoomBy(Math.exp(e.deltaY * (e.deltaMode === 1 ? 0.05 : 0.0015)), e.clientX, e.clientY);
}

// ------------------------------------------------------------------------------ start

// onBodySelected(name | null) is called when a tap selects a body or clears the selection.
export function initCanvasTools(onBodySelected) {
  onSelect = onBodySelected;
  buildToolbar();
  const drawing = $('#drawing');
  drawing.addEventListener('pointerdown', down, true);
  drawing.addEventListener('pointermove', move, true);
  drawing.addEventListener('pointerup', up, true);
  drawing.addEventListener('pointercancel', up, true);
  drawing.addEventListener('wheel', wheel, { passive: false });
  document.addEventListener('keydown', (e) => { if (e.key === 'Escape' && tool.first) { tool.first = null; redrawOverlay(); } });
  // Every solve redraws the svg: keep its fitted box, put back the user's view and the overlay.
  new MutationObserver(() => {
    const svg = svgEl();
    if (!svg || svg.dataset.fit) return;
    svg.dataset.fit = JSON.stringify(currentBox(svg));
    applyView();
  }).observe(drawing, { childList: true });
  // A model opened anew (gallery, design, link) is shown whole.
  document.addEventListener('nbar:opened', () => { view = null; tool.selected = null; tool.first = null; onSelect(null); });
  document.addEventListener('nbar:analysed', redrawOverlay);
}
export function selectBody(name) { tool.selected = name; redrawOverlay(); }
export function viewBox() { return view; }
