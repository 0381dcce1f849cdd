// Building a model from nothing: "New → empty", the drawing of a model that cannot be solved yet
// (the core's outline, /api/outline: the points and links as written, the joints' mobility and
// what is still missing), and the slider tool's one gesture that makes a block body and its
// guide. Every rule (what a point's coordinates are in which unit, how many degrees of freedom the
// joints leave, whether a slider leaves anything free to move) is the core's answer; this module
// draws the answer and writes the edit.
import { t } from './i18n.js';
import { setIn, roundTo } from './yaml-text.js';
import { applyEdit, modelData, modelText, editContext, freshName } from './model-edit.js';

const $ = (s) => document.querySelector(s);
const num = (v) => (Number.isFinite(v) ? +v.toFixed(4) : 0);
const esc = (s) => String(s).replace(/[&<>"']/g, (c) => `&#${c.charCodeAt(0)};`);

// The blank model: its unit written, as every model the tools make (mm unless the drawing on
// screen is in another unit); `points:` left empty for the first tap to fill.
export function blankModel(length = 'mm') {
  return `# ${t('blankComment')}\nname: "${t('blankName')}"\nunits: {length: ${length}, angle: deg}\npoints:\n`;
}

// The outline of `text` (the core's reading of a model being built), or null when the core cannot
// read it at all (a syntax error: the editor says where).
export async function outlineOf(text) {
  try {
    return await editContext().api('/api/outline', { model: text });
  } catch {
    return null;
  }
}

// The part of the plane the sketch shows (model units, y down): the box the drawing showed
// before when it still holds every point (nothing jumps under the finger), else the points with
// a margin, else 400 units across about the origin for an empty model.
function sketchBox(outline, previous, aspect) {
  const xs = outline.points.map((p) => p.x); const ys = outline.points.map((p) => -p.y);
  for (const g of outline.guides) { xs.push(g.line[0], g.line[2]); ys.push(-g.line[1], -g.line[3]); }
  const inside = (b) => xs.every((x, i) => x >= b.x && x <= b.x + b.w && ys[i] >= b.y && ys[i] <= b.y + b.h);
  if (previous && previous.w > 0 && inside(previous)) return previous;
  if (!xs.length) {
    const w = 400;
    return { x: -w / 6, y: -w * aspect / 2, w, h: w * aspect };
  }
  const x0 = Math.min(...xs); const x1 = Math.max(...xs); const y0 = Math.min(...ys); const y1 = Math.max(...ys);
  const span = Math.max(x1 - x0, y1 - y0, 50);
  const w = Math.max(x1 - x0 + span * 0.6, (y1 - y0 + span * 0.6) / aspect);
  return { x: (x0 + x1) / 2 - w / 2, y: (y0 + y1) / 2 - w * aspect / 2, w, h: w * aspect };
}

// A round length for the scale bar: about a fifth of the box's width.
function scaleLength(w) {
  const raw = w / 5;
  const p = 10 ** Math.floor(Math.log10(raw));
  return [1, 2, 5, 10].map((m) => m * p).filter((s) => s <= raw).at(-1) ?? p;
}

// The sketch as SVG in model units (y down), with the same point handles as a solved drawing
// (circle.pt[data-point]) so that every tool taps its points.
export function sketchSvg(outline, previous, aspect) {
  const box = sketchBox(outline, previous, aspect);
  const s = box.w / 120;  // mark size: a 120th of the view
  const at = new Map(outline.points.map((p) => [p.name, p]));
  let links = '';
  for (const g of outline.guides) {
    const [x0, y0, x1, y1] = g.line;
    const dx = x1 - x0; const dy = y1 - y0; const k = box.w / Math.hypot(dx, dy || 1e-9);
    links += `<line class="guide" x1="${num(x0 - dx * k)}" y1="${num(-(y0 - dy * k))}" x2="${num(x1 + dx * k)}" y2="${num(-(y1 + dy * k))}" stroke="#64748b" stroke-width="${num(s * 0.35)}" stroke-dasharray="${num(s * 2)},${num(s)}"/>`;
  }
  for (const b of outline.bodies) {
    const pts = b.points.map((n) => at.get(n)).filter(Boolean);
    if (pts.length === 1) {
      const p = pts[0];
      links += `<rect class="body" data-body="${esc(b.name)}" x="${num(p.x - 3 * s)}" y="${num(-p.y - 2 * s)}" width="${num(6 * s)}" height="${num(4 * s)}" fill="#dbeafe" stroke="#1d4ed8" stroke-width="${num(s * 0.5)}"/>`;
    } else if (pts.length >= 2) {
      const d = pts.map((p, i) => `${i ? 'L' : 'M'}${num(p.x)} ${num(-p.y)}`).join(' ') + (pts.length > 2 ? ' Z' : '');
      links += `<path class="body" data-body="${esc(b.name)}" d="${d}" fill="${pts.length > 2 ? '#dbeafe' : 'none'}" stroke="#1d4ed8" stroke-width="${num(s * 1.2)}" stroke-linecap="round" stroke-linejoin="round"/>`;
    }
  }
  let marks = ''; let handles = '';
  for (const p of outline.points) {
    const x = num(p.x); const y = num(-p.y);
    if (p.ground) marks += `<path class="ground-mark" d="M${x} ${y} l${num(-2 * s)} ${num(3 * s)} h${num(4 * s)} Z" fill="#94a3b8" stroke="#334155" stroke-width="${num(s * 0.3)}"/>`;
    marks += `<circle cx="${x}" cy="${y}" r="${num(s)}" fill="#fff" stroke="#0f172a" stroke-width="${num(s * 0.4)}"/>`
      + `<text x="${num(p.x + 1.6 * s)}" y="${num(-p.y - 1.6 * s)}" font-size="${num(3.2 * s)}" font-family="sans-serif" fill="#0f172a">${esc(p.name)}</text>`;
    handles += `<circle class="hit" data-point="${esc(p.name)}" cx="${x}" cy="${y}" r="${num(1.4 * s)}" fill="transparent"/>`
      + `<circle class="pt" data-point="${esc(p.name)}" data-ground="${p.ground}" cx="${x}" cy="${y}" r="${num(1.4 * s)}" fill="transparent"/>`;
  }
  const bar = scaleLength(box.w);
  const bx = box.x + box.w * 0.04; const by = box.y + box.h * 0.1;
  const scale = `<g class="scale-bar" pointer-events="none"><line x1="${num(bx)}" y1="${num(by)}" x2="${num(bx + bar)}" y2="${num(by)}" stroke="#475569" stroke-width="${num(s * 0.35)}"/>`
    + `<text x="${num(bx)}" y="${num(by - 1.2 * s)}" font-size="${num(2.2 * s)}" font-family="sans-serif" fill="#475569">${num(bar)} ${esc(outline.units.length)}</text></g>`;
  const fit = JSON.stringify(box);
  return { scale: s, svg: `<svg xmlns="http://www.w3.org/2000/svg" viewBox="${num(box.x)} ${num(box.y)} ${num(box.w)} ${num(box.h)}" preserveAspectRatio="xMidYMid meet" role="img" data-sketch="1" data-unit="${esc(outline.units.length)}" data-fit='${esc(fit)}'>`
    + `<g class="frame"><g class="scene sketch">${links}${marks}${scale}</g><g class="handles">${handles}</g></g></svg>` };
}

// What the drawing's note and the status say of a model being built: its mobility (the rank's
// once the model is valid, else the Gruebler-Kutzbach count) and what keeps it from solving (or
// from moving at all: a structure).
export function buildingText(outline) {
  const m = outline.mobility;
  const dof = m.dof ?? m.gruebler;
  const count = m.dof === null ? t('buildGruebler', dof) : t('buildDof', dof);
  const why = outline.problem?.message ?? outline.immobile ?? '';
  return `${t('building')} · ${count}${why ? ` · ${why}` : ''}`;
}

// ------------------------------------------------------------------------------ the slider tool

// The slider tool's second tap: a block body on `point` sliding along a ground guide through
// the point towards `toward` (model units); the guide's two ground points are placed either side
// of the point. The core first says whether the block leaves anything free to move: if not, the
// edit is refused with its reason and the text is left as it was.
export async function addSliderBlock(point, toward) {
  const m = modelData() ?? {};
  const c = m.points?.[point];
  if (!Array.isArray(c)) return false;
  const d = [toward[0] - c[0], toward[1] - c[1]];
  if (Math.hypot(d[0], d[1]) === 0) { editContext().status(t('sliderTapAway'), true); return false; }
  const digits = Math.max(0, 2 - Math.floor(Math.log10(Math.max(Math.hypot(...c), Math.hypot(...d), 1e-9))));
  const taken = new Set(Object.keys(m.points ?? {}));
  const g1 = freshName('G', taken); taken.add(g1);
  const g2 = freshName('G', taken);
  const block = freshName('block', new Set(Object.keys(m.bodies ?? {})));
  const ground = Array.isArray(m.ground) ? m.ground.length : 0;
  const sliders = Array.isArray(m.sliders) ? m.sliders.length : 0;
  const change = (text) => {
    let out = setIn(text, ['points', g1], [roundTo(c[0] - d[0], digits), roundTo(c[1] - d[1], digits)]);
    out = setIn(out, ['points', g2], [roundTo(c[0] + d[0], digits), roundTo(c[1] + d[1], digits)]);
    out = setIn(out, ['ground', ground], g1);
    out = setIn(out, ['ground', ground + 1], g2);
    out = setIn(out, ['bodies', block], [point]);
    return setIn(out, ['sliders', sliders], { body: block, point, along: [g1, g2] });
  };
  return refuseImmobile(change, 'sliderRefused');
}

// The Model tab's form: a slider on `body`, or on a new block body of its own when `body` is
// null; the same verdict of the core first (a slider on the connecting rod is refused).
export function addSliderOn(body, point, along) {
  const m = modelData() ?? {};
  const sliders = Array.isArray(m.sliders) ? m.sliders.length : 0;
  const block = body ?? freshName('block', new Set(Object.keys(m.bodies ?? {})));
  return refuseImmobile((text) => {
    const out = body ? text : setIn(text, ['bodies', block], [point]);
    return setIn(out, ['sliders', sliders], { body: block, point, along });
  }, 'sliderRefused');
}

// Applies `change` unless the core says the model it makes cannot move (or cannot be read): then
// the text is left as it was and the refusal, with the core's reason, is said in the status and
// returned (a string; true when applied).
async function refuseImmobile(change, key) {
  let after;
  try { after = change(modelText()); } catch (e) { return refuse(t('editFailed', e.message)); }
  let outline;
  try {
    outline = await editContext().api('/api/outline', { model: after });
  } catch (e) {
    return refuse(t(key, e.message));
  }
  if (outline.immobile) return refuse(t(key, outline.immobile));
  return applyEdit(() => after);
}
function refuse(message) {
  editContext().status(message, true);
  return message;
}

export function initBuild() {
  // New → empty: the blank model in the units of the drawing on screen (mm when none is drawn).
  $('#new-empty')?.addEventListener('click', () => {
    $('#new-menu').open = false;
    editContext().newModel(blankModel(editContext().state.drawnUnit ?? 'mm'));
  });
}
