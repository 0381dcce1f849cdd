// The step-by-step panel: /api/explain for the model on screen at the pose shown (the same
// explanation as `nbar explain --format json`, built once in the core), rendered as HTML: the
// Gruebler-Kutzbach count, q, the equations Φ, the Jacobian Φq as a table, Newton-Raphson's
// iterations with their residual norms, and the velocity and acceleration solutions. The maths
// is the core's plain-text form set with HTML sub- and superscripts: no maths library, no network.
// After it, the forces and stresses at that pose (the core's inverse dynamics of the sweep at that
// sample, and each shaped link's largest stress there, from the explanation), and the instant centres are marked on
// the drawing while it shows that pose.
import { t } from './i18n.js';

const $ = (s) => document.querySelector(s);
let app = null;

// "x_A^2 + th_crank" -> x<sub>A</sub><sup>2</sup> + θ<sub>crank</sub>, escaped first.
export function maths(text) {
  return app.esc(text)
    .replace(/\bth_(\w+)/g, 'θ<sub>$1</sub>')
    .replace(/\b([A-Za-z])_(\w+)/g, '<i>$1</i><sub>$2</sub>')
    .replace(/\^(\(?-?[\w.]+\)?)/g, '<sup>$1</sup>')
    .replace(/\*/g, '·');
}

const num = (v) => (Number.isFinite(v) ? app.fmt(Math.abs(v) < 1e-12 ? 0 : v) : '–');

function matrixTable(cls, rowHeads, colHeads, rows) {
  const head = `<thead><tr><th></th>${colHeads.map((c) => `<th>${c}</th>`).join('')}</tr></thead>`;
  const body = rows.map((r, i) => `<tr><th>${rowHeads[i]}</th>${r.map((v) => `<td class="${Math.abs(v) < 1e-12 ? 'zero' : ''}">${num(v)}</td>`).join('')}</tr>`).join('');
  return `<div class="mwrap"><table class="matrix ${cls}">${head}<tbody>${body}</tbody></table></div>`;
}

// The instant centres as the CLI's explain lists them (its section 9): name, x, y, and what kind.
function centresSection(centres, length) {
  const kind = (c) => (c.indeterminate ? t('exIndeterminate') : c.at_infinity ? t('exAtInfinity') : c.primary ? t('exPrimary') : '');
  const rows = centres.map((c) => `<tr data-centre="${app.esc(c.name)}"><th>${app.esc(c.name)}</th>`
    + `<td>${c.indeterminate ? '–' : num(c.position[0])}</td><td>${c.indeterminate ? '–' : num(c.position[1])}</td><td>${kind(c)}</td></tr>`).join('');
  const unit = (axis) => (length ? `${axis} (${length})` : axis);
  return `<section><h4>8. ${t('exCentres')}</h4><p class="hint">${t('exCentresHint')}</p>`
    + `<div class="mwrap"><table class="matrix centres"><thead><tr><th>${t('exCentre')}</th><th>${unit('x')}</th><th>${unit('y')}</th><th></th></tr></thead>`
    + `<tbody>${rows}</tbody></table></div></section>`;
}

function render(ex) {
  const sym = ex.coordinates.map((c) => maths(c.symbol));
  const c = ex.count;
  const rowsHead = ex.equations.map((_, i) => `${i + 1}`);
  const iters = ex.newton?.iterations ?? [];
  const units = ex.units ?? {};
  const parts = [];
  parts.push(`<h3>${t('exTitle', app.esc(ex.model), ex.step, app.fmt(ex.time))}</h3>`);
  parts.push(`<section><h4>1. ${t('exDof')}</h4><p class="eq">G = 3(n − 1) − 2P<sub>I</sub> − P<sub>II</sub> = 3(${c.links} − 1) − 2·${c.lower_pairs} − ${c.higher_pairs} = <b>${c.dof}</b></p>`
    + `<p class="hint">${t('exMobility', c.mobility)}</p></section>`);
  parts.push(`<section><h4>2. q</h4>${matrixTable('q', ['q'], sym, [ex.q])}<p class="hint">${t('exUnits', app.esc(units.length ?? ''))}</p></section>`);
  parts.push(`<section><h4>3. Φ(q, t) = 0</h4><ol class="eqs">${ex.equations.map((e) => `<li><span class="lbl">${app.esc(e.label)}</span><span class="eq">${maths(e.text)}</span></li>`).join('')}</ol></section>`);
  parts.push(`<section><h4>4. Φ<sub>q</sub></h4>${matrixTable('jac', rowsHead, sym, ex.jacobian)}<p class="hint">${t('exJacobian')}</p></section>`);
  const newton = iters.map((it) => `<tr><td>${it.iteration}</td><td>${num(it.residual)}</td><td>${it.dq ? num(Math.hypot(...it.dq)) : '–'}</td></tr>`).join('');
  parts.push(`<section><h4>5. Newton–Raphson</h4><p class="hint">${t('exNewton', app.esc(ex.newton?.start ?? ''))}</p>`
    + `<div class="mwrap"><table class="matrix newton"><thead><tr><th>k</th><th>‖Φ(q<sub>k</sub>)‖</th><th>‖Δq‖</th></tr></thead><tbody>${newton}</tbody></table></div>`
    + `<p class="hint">${ex.newton?.converged ? t('exConverged', iters.length) : t('exNotConverged')}</p></section>`);
  const length = app.esc(units.length ?? ''); const time = app.esc(units.time ?? 's');
  if (ex.velocity) {
    parts.push(`<section><h4>6. Φ<sub>q</sub> q̇ = −Φ<sub>t</sub></h4>${matrixTable('vel', ['q̇'], sym, [ex.velocity.solution])}`
      + `<p class="hint">${t('exVelocityUnits', length, time)}</p></section>`);
  }
  if (ex.acceleration) {
    parts.push(`<section><h4>7. Φ<sub>q</sub> q̈ = γ</h4>${matrixTable('acc', ['q̈'], sym, [ex.acceleration.solution])}`
      + `<p class="hint">${t('exAccelerationUnits', length, time)}</p></section>`);
  }
  if (ex.centres?.length) parts.push(centresSection(ex.centres, length), `<p class="hint">${t('exCentresDrawn')}</p>`);
  parts.push('<div id="explain-pose"></div>');
  if (ex.notes?.length) parts.push(`<p class="hint">${ex.notes.map(app.esc).join('<br>')}</p>`);
  return parts.join('');
}

// The step field's sample, within the sweep: a step past either end is shown at that end, and
// the note under the field says so (it was clamped silently); a field that holds no whole number
// is an error at the field, and nothing is asked.
function stepAsked(last) {
  const input = $('#explain-step');
  const note = $('#explain-note');
  const typed = input.value.trim();
  const say = (text, bad = false) => {
    note.textContent = text;
    note.hidden = !text;
    note.classList.toggle('bad', bad);
    input.classList.toggle('bad', bad);
  };
  const asked = typed === '' ? 0 : Number(typed);
  if (input.validity?.badInput || !Number.isInteger(asked)) { say(t('exStepNotWhole', typed, last), true); return null; }
  const step = Math.max(0, Math.min(asked, last));
  say(asked > last ? t('exStepPast', asked, last) : asked < 0 ? t('exStepBefore', asked) : '');
  if (step !== asked) input.value = String(step);
  return step;
}

// ------------------------------------------------------------------------------ at the pose

// The inverse dynamics' columns (main.js's takeDynamics: what `solve --dynamics` adds to the
// sweep's) at sample `step`: the joints' reactions, the drivers' efforts, the energies.
function forcesSection(step) {
  const { state } = app;
  const names = state.dynamicsColumns ?? [];
  const row = state.solve?.rows[step];
  if (!names.length || !row) return `<section data-at-pose="forces"><h4>9. ${t('exForces')}</h4><p class="hint">${t('exForcesNone')}</p></section>`;
  const rows = names.map((c) => `<tr data-column="${app.esc(c)}"><th>${app.esc(c)}</th><td>${num(row[app.col(c)])}</td><td>${app.esc(app.unitOf(c))}</td></tr>`).join('');
  return `<section data-at-pose="forces"><h4>9. ${t('exForces')}</h4><p class="hint">${t('exForcesHint')}</p>`
    + `<div class="mwrap"><table class="matrix forces"><thead><tr><th>${t('exForceCol')}</th><th>${t('exValue')}</th><th></th></tr></thead><tbody>${rows}</tbody></table></div></section>`;
}

// Each shaped link's largest von Mises stress at this pose, where along the link and its safety
// factor: the core's explanation (`stresses`, as `nbar explain` prints them), only drawn here.
function stressesSection(ex) {
  const head = `<section data-at-pose="stresses"><h4>10. ${t('exStresses')}</h4>`;
  const links = ex.stresses ?? [];
  if (!links.length) return `${head}<p class="hint">${t('exStressesNone')}</p></section>`;
  const length = app.esc(ex.units?.length ?? '');
  const rows = links.map((l) => `<tr data-body="${app.esc(l.body)}"><th>${app.esc(l.body)}</th><td>${num(l.von_mises)} ${app.esc(l.unit)}</td>`
    + `<td>${t('exAt')} = ${num(l.at)} ${length}</td><td>${l.safety_factor === null ? t('stNoYield') : `${t('stSafety')} ${num(l.safety_factor)}`}</td></tr>`).join('');
  return `${head}<p class="hint">${t('exStressesHint')}</p><div class="mwrap"><table class="matrix stresses"><tbody>${rows}</tbody></table></div></section>`;
}

// The instant centres of the explanation shown, on the drawing while it shows that pose.
let centresShown = null;  // {step, centres}
function drawCentres() {
  const svg = document.querySelector('#drawing svg');
  svg?.querySelector('.ov-centres')?.remove();
  const onPanel = document.querySelector('#panel-explain.active');
  if (!svg || !centresShown || !onPanel || app.state.frame !== centresShown.step) return;
  const s = app.state.geometry?.scale ?? 1;
  const marks = centresShown.centres.filter((c) => !c.indeterminate && !c.at_infinity && c.position.every(Number.isFinite)).map((c) => {
    const [x, y] = c.position.map((v) => +v.toFixed(4));
    const label = c.name.replace(/^I\(|\)$/g, '');
    return `<g data-centre="${app.esc(c.name)}"><circle cx="${x}" cy="${-y}" r="${+(0.8 * s).toFixed(4)}" fill="#6941c6" stroke="#fff" stroke-width="1.5" vector-effect="non-scaling-stroke"/>`
      + `<text x="${+(x + 1.2 * s).toFixed(4)}" y="${+(-y - 1.2 * s).toFixed(4)}" font-size="${+(2.6 * s).toFixed(4)}" style="--fs:${+(2.6 * s).toFixed(4)}">${app.esc(label)}</text></g>`;
  }).join('');
  const g = document.createElementNS('http://www.w3.org/2000/svg', 'g');
  g.setAttribute('class', 'ov-centres');
  g.innerHTML = marks;
  const handles = svg.querySelector('.handles');
  if (handles) handles.before(g); else svg.append(g);
}

async function explainNow() {
  const out = $('#explain-out');
  const { state } = app;
  if (!state.solve || !state.lastOk) { out.textContent = t('nothing'); return; }
  const step = stepAsked(state.solve.rows.length - 1);
  if (step === null) return;
  out.textContent = t('loading');
  try {
    const model = state.lastOk;
    const ex = await app.api('/api/explain', { model, step });
    out.innerHTML = render(ex);
    out.dataset.step = String(step);
    centresShown = { step, centres: ex.centres ?? [] };
    drawCentres();
    const pose = out.querySelector('#explain-pose');
    pose.innerHTML = forcesSection(step) + stressesSection(ex);
    out.dataset.pose = String(step);
  } catch (e) {
    out.innerHTML = `<p class="bad">${app.esc(e.message)}</p>`;
  }
}

export function initExplain(context) {
  app = context;
  $('#explain-run').addEventListener('click', explainNow);
  // The step follows the pose shown until the panel is asked.
  document.addEventListener('nbar:frame', () => {
    drawCentres();
    $('#explain-step').value = String(app.state.frame);
    $('#explain-step').classList.remove('bad');
    $('#explain-note').hidden = true;
  });
  const tab = document.querySelector('[data-tab="explain"]');
  tab.addEventListener('click', () => { if (!$('#explain-out').dataset.step) explainNow(); });
  // A new model: the explanation shown is of the old one.
  document.addEventListener('nbar:drawn', drawCentres);
  for (const b of document.querySelectorAll('[data-tab]')) b.addEventListener('click', () => setTimeout(drawCentres));
  // The dynamics come after the sweep: the forces at the pose are written when they do.
  document.addEventListener('nbar:dynamics', () => {
    const pose = $('#explain-pose section[data-at-pose="forces"]');
    const step = Number($('#explain-out').dataset.step);
    if (pose && Number.isInteger(step)) pose.outerHTML = forcesSection(step);
  });
  document.addEventListener('nbar:solved', () => {
    centresShown = null;
    delete $('#explain-out').dataset.step;
    delete $('#explain-out').dataset.pose;
    if (tab.getAttribute('aria-selected') === 'true') explainNow();
  });
}
