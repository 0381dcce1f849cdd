// Simulate mode: instead of the sweep, the drawing, the plot and the table show how the model
// moves under its loads with its free drivers (`free: true`) released: `nbar simulate` through
// /api/simulate (the server's or the in-browser engine's), whose answer brings the drawing of the
// motion (a scene with one step per row) and the run as the CSV and JSON downloads write it
// (`downloads`), so that a download is the rows on screen, a cancelled run's rows so far, without
// running it again (why there and not kept by the server: web/server/api_simulate.cpp). The
// drawing is not asked again for a new size either: that too would be a whole run; the SVG's
// viewBox scales the scene held. The rows have the sweep's columns (and the energies),
// so the drawing is posed, played, plotted and tabled as a sweep is; playing goes at the
// simulation's own time (slowed down to 2 s a loop at least, sped up to 20 s at most). The core
// reads and checks the options ("to", "dt", the tolerance): a value it refuses is said as any
// error of the model is.
import { addStrings, t } from './i18n.js';

addStrings({
  en: {
    simulate: 'Simulate', simTo: 'to (s)', simDt: 'dt (s)', simRtol: 'tolerance',
    simulating: 'Simulating…',
    simulated: (time, rows) => `simulated ${time} s · ${rows} rows`,
    simCancelled: (time) => `cancelled at t = ${time} s: the rows up to there are shown`,
    simHint: 'Forward dynamics: the drivers marked free: true move under the loads (nbar simulate)',
  },
  es: {
    simulate: 'Simular', simTo: 'hasta (s)', simDt: 'dt (s)', simRtol: 'tolerancia',
    simulating: 'Simulando…',
    simulated: (time, rows) => `simulado ${time} s · ${rows} filas`,
    simCancelled: (time) => `cancelado en t = ${time} s: se muestran las filas hasta ahí`,
    simHint: 'Dinámica directa: los accionamientos marcados free: true se mueven con las cargas (nbar simulate)',
  },
});

const $ = (s) => document.querySelector(s);

// The options as the API reads them: only what is filled in (the core's defaults otherwise);
// a number the browser cannot read is sent as written, for the core to refuse by name.
function options() {
  const out = {};
  for (const [key, id] of [['to', '#sim-to'], ['dt', '#sim-dt'], ['rtol', '#sim-rtol']]) {
    const text = $(id).value.trim();
    if (text === '') continue;
    const v = Number(text);
    out[key] = Number.isFinite(v) ? v : text;
  }
  return out;
}

// The body of a simulation request for `model`: its options, the scene at `size`, and the run's
// CSV and JSON texts for the downloads. The JSON comes once, as a text (the answer then leaves its
// `simulation` out): the page saves that text and shows it parsed.
export function simulationBody(model, size, extra = {}) {
  return { model, ...options(), scene: { width: size[0], height: size[1], labels: true }, downloads: ['csv', 'json'], ...extra };
}

// What the page keeps of a simulation's answer: the rows it shows, their drawing, and the texts
// the downloads save.
export function simulationAnswer(answer) {
  return { solve: JSON.parse(answer.downloads.json), scene: answer.scene, downloads: answer.downloads };
}

// A download of the simulation shown (`downloads`, from simulationAnswer): its CSV or JSON as
// `nbar simulate --format csv|json` wrote it for that run, so no second run and no number
// written here.
export function simulationFile(downloads, kind) {
  return new Blob([downloads[kind]], { type: kind === 'csv' ? 'text/csv' : 'application/json' });
}

// Frames per millisecond of play: the simulation's time, at least 2 s and at most 20 s a loop.
export function simulationRate(solve) {
  const ti = solve.columns.indexOf('t');
  const span = ti >= 0 ? solve.rows.at(-1)[ti] - solve.rows[0][ti] : 0;
  const loop = Math.min(Math.max(span * 1000, 2000), 20000);
  return (solve.rows.length - 1) / loop;
}

// The status line's words for a simulation: its time and rows, its events, why it stopped early
// (a Cancel: where, with the rows up to there kept).
export function simulationStatus(solve) {
  const ti = solve.columns.indexOf('t');
  const end = ti >= 0 ? +solve.rows.at(-1)[ti].toPrecision(6) : 0;
  const events = (solve.events ?? []).map((e) => e.message);
  const stopped = solve.cancelled ? t('simCancelled', end) : t('incomplete', solve.stop_reason ?? '');
  return [t('simulated', end, solve.rows.length), ...events, ...(solve.complete ? [] : [stopped])].join(' · ');
}

export function initSimulate(app) {
  const toggle = $('#simulate');
  const fields = $('#sim-options');
  let timer = 0;
  const apply = () => {
    fields.hidden = !toggle.checked;
    app.state.simulation = toggle.checked;
    document.body.dataset.mode = toggle.checked ? 'simulate' : 'sweep';
    app.play(false);
    app.state.frame = 0;
    app.analyse();
  };
  toggle.addEventListener('change', apply);
  for (const input of fields.querySelectorAll('input')) {
    input.addEventListener('input', () => {
      if (!toggle.checked) return;
      clearTimeout(timer);
      timer = setTimeout(app.analyse, 600);
    });
  }
}
