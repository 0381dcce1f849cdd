// The mechanism as the core draws it, `nbar draw` for this size: the server's scene (/api/render,
// kind draw, format scene; src/render/scene.cpp) is the list of primitives the core's drawing
// gives a canvas at one pose, and for every sample the motion of each body and the shift of each
// point label. This module only writes those primitives as SVG elements (with the attributes the
// core's SVG canvas writes) and moves the groups; every drawing decision (shapes, colours,
// hatching, joints, labels) is the core's. The SVG's units are the model's length units (y
// down): the scene's pixels are mapped there by its `to_model`, so that overlays, taps and drags
// work in model coordinates. The point handles (for dragging and tapping) are invisible.

const num = (v) => (Number.isFinite(v) ? +v.toFixed(4) : 0);
const esc = (s) => String(s).replace(/[&<>"']/g, (c) => `&#${c.charCodeAt(0)};`);

function pairs(flat) {
  let s = '';
  for (let i = 0; i + 1 < flat.length; i += 2) s += `${i ? ' ' : ''}${flat[i]},${flat[i + 1]}`;
  return s;
}

// As SvgCanvas's paint_attributes (src/render/canvas.cpp). A stroke keeps its width on screen
// (non-scaling): the scene is drawn at the drawing's size, so at the fitted view a scene pixel is
// a screen pixel, and zooming in enlarges the mechanism, not its lines.
function paint(it) {
  let s = it.fill ? ` fill="${it.fill}"` : ' fill="none"';
  if (it.fill && it.fill_opacity !== undefined) s += ` fill-opacity="${it.fill_opacity}"`;
  if (it.stroke) {
    s += ` stroke="${it.stroke}" stroke-width="${it.stroke_width}"`;
    if (it.stroke_opacity !== undefined) s += ` stroke-opacity="${it.stroke_opacity}"`;
    if (it.dash) s += ` stroke-dasharray="${it.dash.join(',')}"`;
    s += ' stroke-linejoin="round" stroke-linecap="round" vector-effect="non-scaling-stroke"';
  }
  return s;
}

function ring(flat) {
  let d = '';
  for (let i = 0; i + 1 < flat.length; i += 2) d += `${i ? ' L' : 'M'}${flat[i]} ${flat[i + 1]}`;
  return `${d} Z `;
}

// One primitive; `where` says which group it is in: a body's first item is its shape (class
// "body", data-body), which the stress overlay colours and the body tool selects.
function element(it, where) {
  const shape = where.body && where.first ? ` class="body" data-body="${esc(where.body)}"` : '';
  where.first = false;
  switch (it.type) {
    case 'group': {
      const body = where.bodies.get(it.id);
      const inner = { ...where, body, first: true, labels: it.id === 'labels' };
      const attrs = `${body !== undefined ? ` data-link="${esc(body)}"` : ''} data-group="${esc(it.id)}" class="${esc(it.class)}"`;
      return `<g${attrs}>${it.items.map((x) => element(x, inner)).join('')}</g>`;
    }
    case 'polygon': return `<polygon${shape} points="${pairs(it.points)}"${paint(it)}/>`;
    case 'polyline': return `<polyline${shape} points="${pairs(it.points)}"${paint(it)}/>`;
    case 'circle': return `<circle${shape} cx="${it.cx}" cy="${it.cy}" r="${it.r}"${paint(it)}/>`;
    case 'outline': {
      let d = it.rings.map(ring).join('');
      for (const [cx, cy, r] of it.circles) d += `M${cx + r} ${cy} A${r} ${r} 0 1 0 ${cx - r} ${cy} A${r} ${r} 0 1 0 ${cx + r} ${cy} Z `;
      return `<path${shape} fill-rule="evenodd" d="${d}"${paint(it)}/>`;
    }
    case 'text': {
      const label = where.labels ? ` data-label="${where.label++}"` : '';
      // --fs: the size style.css divides by the drawing's zoom, so that a label keeps its size on screen.
      return `<text${label} x="${it.x}" y="${it.y}" font-size="${it.size}" style="--fs:${it.size}" font-family="sans-serif" text-anchor="${it.anchor}" fill="${it.color}">${esc(it.text)}</text>`;
    }
    default: return '';
  }
}

// The part of the model plane (model units, y down) the scene's canvas covers.
export function sceneBox(scene) {
  const [k, tx, ty] = scene.to_model;
  return { x: tx, y: ty, w: k * scene.width, h: k * scene.height };
}

// The scene's primitives, mapped to model units, in a <g class="scene">.
export function sceneGroup(scene) {
  const [k, tx, ty] = scene.to_model;
  const where = { bodies: new Map(scene.bodies.map((b) => [b.group, b.name])), first: false, label: 0 };
  return `<g class="scene" transform="matrix(${k} 0 0 ${k} ${tx} ${ty})">${scene.items.map((it) => element(it, where)).join('')}</g>`;
}

// The whole drawing: the scene's canvas fills the view; `.handles` takes the point handles.
export function drawingSvg(scene) {
  const b = sceneBox(scene);
  return `<svg xmlns="http://www.w3.org/2000/svg" viewBox="${num(b.x)} ${num(b.y)} ${num(b.w)} ${num(b.h)}" preserveAspectRatio="xMidYMid meet" role="img" data-width="${scene.width}" data-height="${scene.height}" data-reference-step="${scene.reference_step}">`
    + `<g class="frame">${sceneGroup(scene)}<g class="handles"></g></g></svg>`;
}

// The size unit of marks drawn over the drawing (arrows, targets, handles; model units): 4.5
// of the scene's pixels, which are about the screen's, as the scene is drawn at the drawing's size.
export function markScale(scene) {
  return scene.to_model[0] * 4.5;
}

// Poses the scene at sample `step`: each body group moved by its motion, each label shifted.
export function poseDrawing(root, scene, step) {
  const motion = scene.steps[step];
  if (!motion) return;
  for (const [b, body] of scene.bodies.entries()) {
    const el = root.querySelector(`g[data-group="${CSS.escape(body.group)}"]`);
    const [angle, dx, dy] = motion.bodies[b];
    el?.setAttribute('transform', `translate(${dx} ${dy}) rotate(${angle} ${body.pivot[0]} ${body.pivot[1]})`);
  }
  for (const el of root.querySelectorAll('g[data-group="labels"] text[data-label]')) {
    const d = motion.labels[+el.dataset.label];
    if (d) el.setAttribute('transform', `translate(${d[0]} ${d[1]})`);
  }
}

// Invisible handles on the points (model units) at `row` of the solve, to drag and tap them;
// `moved` = {name, x, y} puts the dragged one under the finger.
export function handlesSvg(g, solve, row, moved = null) {
  const index = new Map(solve.columns.map((c, i) => [c, i]));
  const s = g.scale;
  let out = '';
  for (const p of g.points) {
    let x = row[index.get(`${p}.x`)]; let y = row[index.get(`${p}.y`)];
    if (moved?.name === p) ({ x, y } = moved);
    const cx = num(x); const cy = num(-y);
    const cls = moved?.name === p ? 'pt dragged' : 'pt';
    // The hit area is the ring and a transparent stroke of a fixed screen width around it
    // (style.css: wider on a phone), so a finger finds a point at any zoom.
    out += `<circle class="hit" data-point="${esc(p)}" cx="${cx}" cy="${cy}" r="${num(1.1 * s)}" fill="transparent"/>`
      + `<circle class="${cls}" data-point="${esc(p)}" cx="${cx}" cy="${cy}" r="${num(1.1 * s)}" fill="transparent"/>`;
  }
  return out;
}
