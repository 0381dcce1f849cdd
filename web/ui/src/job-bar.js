// The long job's bar under the header: what the in-browser engine is computing (a synthesis, an
// FE stress map, a report), its progress as the core reports it (RunControl's checkpoints, posted
// by the worker), and Cancel, which ends it. Shown only for a job that runs over half a second,
// so that quick analyses do not flash it.
import { t } from './i18n.js';

const $ = (s) => document.querySelector(s);
const showAfterMs = 500;

// Stages as the core names them (nbar::Progress::stage), in the reader's words.
const stageWords = { sweep: 'sweep', dynamics: 'dynamics', stress: 'stress', paths: 'paths', checking: 'checking designs', simulate: 'simulation', render: 'drawing' };

// The bar for a request to this page's server that can be stopped (a simulation named by its
// `run`): shown after half a second with `label`, its Cancel calling `stop`. Returns the function
// that hides it again (the answer has come); a newer job's bar is left as it is.
let serverJob = 0;
export function showServerJob(label, stop) {
  const job = ++serverJob;
  const bar = $('#job');
  const button = bar.querySelector('button');
  bar.querySelector('span').textContent = label;
  bar.querySelector('progress').removeAttribute('value');
  const onClick = () => { button.disabled = true; stop(); };
  button.addEventListener('click', onClick);
  const timer = setTimeout(() => { bar.hidden = false; document.body.dataset.job = label; }, showAfterMs);
  return () => {
    clearTimeout(timer);
    button.removeEventListener('click', onClick);
    if (job !== serverJob) return;
    button.disabled = false;
    bar.hidden = true;
    document.body.removeAttribute('data-job');
  };
}

export function initJobBar(engine) {
  const bar = $('#job');
  const text = bar.querySelector('span');
  const meter = bar.querySelector('progress');
  let timer = 0;
  let current = null;
  const hide = () => { clearTimeout(timer); bar.hidden = true; document.body.removeAttribute('data-job'); };
  bar.querySelector('button').addEventListener('click', () => { engine.cancelRunning(); });
  engine.listeners.add((event) => {
    if (!event.running) { current = null; hide(); return; }
    if (event.running !== current) {
      current = event.running;
      hide();
      timer = setTimeout(() => { bar.hidden = false; document.body.dataset.job = current?.label ?? ''; }, showAfterMs);
    }
    const stage = stageWords[event.stage] ?? event.stage ?? '';
    const what = current.label ?? '';
    text.textContent = stage ? `${what} ${t('progressOf', stage, event.done, event.total)}` : what;
    if (event.total > 0) { meter.max = event.total; meter.value = event.done; } else meter.removeAttribute('value');
  });
}
