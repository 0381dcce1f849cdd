// Offline use: registers the service worker (sw.js, which keeps the app shell and the last
// answers), says "Offline" in the header while this page's server cannot be reached, and offers
// the MP4 download only when /api/health says the server has ffmpeg (or, in the browser's engine,
// says that MP4 needs the server).
//
// Whether the server answers is learned from the requests themselves: navigator.onLine says only
// whether the device has a network, and a server that stopped (or a laptop's `nbar serve` closed)
// leaves it true. A request that gets no answer, or the service worker's answer from its copy
// (X-Nbar-Offline), marks the server unreachable; from then on /api/health is asked every few
// seconds, and when it answers again whatever failed for want of it runs again by itself.
import { addStrings, t } from './i18n.js';

addStrings({
  en: { noAnswerIn: (s) => `No answer from the nbar server in ${s} s.` },
  es: { noAnswerIn: (s) => `El servidor nbar no respondió en ${s} s.` },
});

const $ = (s) => document.querySelector(s);

const reach = {
  unreachable: false,
  probe: 0,                  // the timer of the next /api/health while unreachable
  backAgain: new Set(),      // what to run again once the server answers
  budgetSeconds: 60,         // the server's time budget and queue wait (/api/health), for timeouts
  queueSeconds: 10,
};
const probeEveryMs = 3000;
const getTimeoutMs = 10000;

// How long a request may go unanswered before the page stops waiting: a GET (an example, the
// list) is small; a computation may take the server's whole time budget after waiting its turn.
export function timeoutOf(init) {
  return (init.method ?? 'GET') === 'GET' ? getTimeoutMs : (reach.budgetSeconds + reach.queueSeconds + 10) * 1000;
}

// fetch() to this page's server, with the timeout above, noting whether the server answered.
// A request with no answer throws an Error whose `info.kind` is 'offline' and that has no status
// (main.js's retryable()).
export async function serverFetch(path, init) {
  const ms = timeoutOf(init);
  let answer;
  try {
    answer = await fetch(path, { ...init, signal: AbortSignal.timeout(ms) });
  } catch (e) {
    markReachable(false);
    const message = e.name === 'TimeoutError' ? t('noAnswerIn', Math.round(ms / 1000)) : t('offlineNote');
    const error = new Error(message);
    error.info = { kind: 'offline', message };
    throw error;
  }
  markReachable(!answer.headers.get('X-Nbar-Offline'));
  return answer;
}

// Runs `again` once when the server answers after having been unreachable (it is dropped if the
// server was never unreachable by then: the caller's own request will have said what happened).
export function whenServerBack(again) {
  if (reach.unreachable) reach.backAgain.add(again);
}

function markReachable(reachable) {
  if (reachable === !reach.unreachable) return;
  reach.unreachable = !reachable;
  showOnline();
  if (reach.unreachable) {
    scheduleProbe();
    return;
  }
  clearTimeout(reach.probe);
  const again = [...reach.backAgain];
  reach.backAgain.clear();
  for (const f of again) f();
}

function scheduleProbe() {
  clearTimeout(reach.probe);
  reach.probe = setTimeout(async () => {
    if (!reach.unreachable) return;
    try {
      const r = await fetch('api/health', { signal: AbortSignal.timeout(probeEveryMs), cache: 'no-store' });
      if (r.ok && !r.headers.get('X-Nbar-Offline')) { markReachable(true); return; }
    } catch { /* still unreachable */ }
    scheduleProbe();
  }, probeEveryMs);
}

// In the browser's engine nothing needs the network: offline is said, not a limit.
function showOnline() {
  const engine = document.body.dataset.engine === 'engine';
  const off = engine ? !navigator.onLine : reach.unreachable;
  const note = t(engine ? 'offlineInBrowser' : 'offlineNote');
  const badge = $('#offline');
  badge.hidden = !off;
  badge.title = note;
  document.body.classList.toggle('is-offline', off);
  if (off) $('#status').textContent = note;
}

export function initOffline(app) {
  // Service workers need a secure context: http://127.0.0.1 and localhost are, a classroom's
  // http://192.168.x.y is not (the app then simply works online only).
  if ('serviceWorker' in navigator && window.isSecureContext) {
    navigator.serviceWorker.register('sw.js').catch(() => { /* no offline copy: still works online */ });
  }
  // The browser's own word is a hint: when it says the network is back, ask the server at once.
  window.addEventListener('online', () => { showOnline(); if (reach.unreachable) scheduleProbe(); });
  window.addEventListener('offline', showOnline);
  showOnline();
  // In the browser's engine the MP4 button stays, and says that MP4 needs `nbar serve`.
  app.backendReady.then(async (where) => {
    const h = await app.api('/api/health');
    if (h.limits?.time_budget_seconds > 0) reach.budgetSeconds = h.limits.time_budget_seconds;
    if (h.limits?.queue_wait_seconds >= 0) reach.queueSeconds = h.limits.queue_wait_seconds;
    const mp4 = $('[data-download="mp4"]');
    mp4.hidden = !h.mp4 && where.mode !== 'engine';
    if (where.mode === 'engine') mp4.title = t('needsServer', mp4.textContent);
    showOnline();
  }).catch(() => {});
}
