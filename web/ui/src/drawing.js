// The mechanism drawn as SVG from a solve's point columns: the frame (traces of coupler points,
// drawn once) and, for each sample, the bodies, pivots and labels.
const palette = ['#2563eb', '#059669', '#9333ea', '#db2777', '#0891b2', '#ca8a04', '#4f46e5', '#dc2626'];

function columns(solve) {
  const index = new Map(solve.columns.map((c, i) => [c, i]));
  return (p) => [index.get(`${p}.x`), index.get(`${p}.y`)];
}

// Points traced: moving points of exactly one body that has three points or more (coupler points).
function tracedPoints(g) {
  return g.points.filter((p) => {
    if (g.ground.has(p)) return false;
    const on = g.bodies.filter((b) => b.points.includes(p));
    return on.length === 1 && on[0].points.length >= 3;
  });
}

function bounds(g, solve) {
  const at = columns(solve);
  let x0 = Infinity; let y0 = Infinity; let x1 = -Infinity; let y1 = -Infinity;
  for (const p of g.points) {
    const [i, j] = at(p);
    for (const r of solve.rows) {
      const x = r[i]; const y = r[j];
      if (!Number.isFinite(x) || !Number.isFinite(y)) continue;
      x0 = Math.min(x0, x); x1 = Math.max(x1, x); y0 = Math.min(y0, y); y1 = Math.max(y1, y);
    }
  }
  if (!Number.isFinite(x0)) return { x0: -1, y0: -1, x1: 1, y1: 1 };
  const pad = Math.max(x1 - x0, y1 - y0, 1e-9) * 0.12;
  return { x0: x0 - pad, y0: y0 - pad, x1: x1 + pad, y1: y1 + pad };
}

const n = (v) => (Number.isFinite(v) ? +v.toFixed(4) : 0);

export function drawingSvg(g, solve) {
  const b = bounds(g, solve);
  const w = b.x1 - b.x0; const h = b.y1 - b.y0;
  g.scale = Math.max(w, h) / 100;
  const at = columns(solve);
  const traces = tracedPoints(g).map((p) => {
    const [i, j] = at(p);
    const pts = solve.rows.map((r) => `${n(r[i])},${n(-r[j])}`).join(' ');
    return `<polyline class="trace" points="${pts}" fill="none" stroke="#f97316" stroke-width="1.5" stroke-dasharray="4 3" vector-effect="non-scaling-stroke"/>`;
  }).join('');
  return `<svg xmlns="http://www.w3.org/2000/svg" viewBox="${n(b.x0)} ${n(-b.y1)} ${n(w)} ${n(h)}" preserveAspectRatio="xMidYMid meet" role="img">`
    + `<g class="traces">${traces}</g><g class="frame"></g></svg>`;
}

// `moved` overrides one point's position while it is dragged: {name, x, y} in model coordinates.
export function frameGroup(g, solve, row, moved = null) {
  const at = columns(solve);
  const s = g.scale;
  const pos = new Map(g.points.map((p) => { const [i, j] = at(p); return [p, [n(row[i]), n(-row[j])]]; }));
  if (moved && pos.has(moved.name)) pos.set(moved.name, [n(moved.x), n(-moved.y)]);
  let out = '';
  // Slider guides (dashed, through the axis points) and blocks along them.
  for (const sl of g.sliders ?? []) {
    const [a, b] = sl.along.map((p) => pos.get(p));
    const c = pos.get(sl.point);
    const len = Math.hypot(b[0] - a[0], b[1] - a[1]);
    if (!len) continue;
    const ux = (b[0] - a[0]) / len; const uy = (b[1] - a[1]) / len;
    const far = 1e3 * s;  // the guide drawn well past its points, clipped by the view
    out += `<line class="guide" x1="${n(a[0] - ux * far)}" y1="${n(a[1] - uy * far)}" x2="${n(b[0] + ux * far)}" y2="${n(b[1] + uy * far)}" stroke="#98a2b3" stroke-width="1.5" stroke-dasharray="6 4" vector-effect="non-scaling-stroke"/>`;
    const angle = n(Math.atan2(uy, ux) * 180 / Math.PI);
    out += `<rect class="block" x="${n(c[0] - 5 * s)}" y="${n(c[1] - 3 * s)}" width="${n(10 * s)}" height="${n(6 * s)}" rx="${n(s)}" transform="rotate(${angle} ${c[0]} ${c[1]})" fill="#fef0c7" stroke="#b54708" stroke-width="2" vector-effect="non-scaling-stroke"/>`;
  }
  // Ground pivots (ground points of a body): a triangle under the point and a base line.
  const pivots = new Set(g.bodies.flatMap((b) => b.points));
  for (const p of g.ground) {
    const q = pos.get(p);
    if (!q || !pivots.has(p)) continue;
    const [x, y] = q;
    out += `<path d="M${x},${y} l${-2.4 * s},${4 * s} h${4.8 * s} z" fill="#e4e7ec" stroke="#475467" stroke-width="1.5" vector-effect="non-scaling-stroke"/>`
      + `<line x1="${x - 3.4 * s}" y1="${y + 4 * s}" x2="${x + 3.4 * s}" y2="${y + 4 * s}" stroke="#475467" stroke-width="2" vector-effect="non-scaling-stroke"/>`;
  }
  g.bodies.forEach((body, k) => {
    const c = palette[k % palette.length];
    const pts = body.points.map((p) => pos.get(p)).filter(Boolean);
    if (pts.length < 2) return;
    const list = pts.map(([x, y]) => `${x},${y}`).join(' ');
    if (pts.length >= 3) {
      out += `<polygon class="body" data-body="${body.name}" points="${list}" fill="${c}" fill-opacity=".14" stroke="${c}" stroke-width="4" stroke-linejoin="round" vector-effect="non-scaling-stroke"/>`;
    } else {
      out += `<polyline class="body" data-body="${body.name}" points="${list}" fill="none" stroke="${c}" stroke-width="5" stroke-linecap="round" vector-effect="non-scaling-stroke"/>`;
    }
  });
  for (const [p, [x, y]] of pos) {
    out += `<circle class="hit" data-point="${p}" cx="${x}" cy="${y}" r="${3 * s}" fill="transparent"/>`
      + `<circle class="pt" data-point="${p}" cx="${x}" cy="${y}" r="${1.1 * s}" fill="#fff" stroke="#1d2330" stroke-width="1.5" vector-effect="non-scaling-stroke"/>`
      + `<text x="${x + 1.8 * s}" y="${y - 1.8 * s}" font-size="${3.2 * s}" fill="#344054" font-family="system-ui, sans-serif">${p}</text>`;
  }
  return out;
}
