// Offline use: registers the service worker (sw.js, which keeps the app shell and the last
// answers), shows "Offline" in the header while the browser has no network, and the MP4
// download only when /api/health says the server has ffmpeg (or, in the browser's engine, to
// say that MP4 needs the server).
import { t } from './i18n.js';

const $ = (s) => document.querySelector(s);

// In the browser's engine nothing needs the network: offline is said, not a limit.
function showOnline() {
  const off = !navigator.onLine;
  const note = t(document.body.dataset.engine === 'engine' ? 'offlineInBrowser' : 'offlineNote');
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
  window.addEventListener('online', () => { showOnline(); if (app.state.text) app.analyse(); });
  window.addEventListener('offline', showOnline);
  showOnline();
  // In the browser's engine the MP4 button stays, and says that MP4 needs `nbar serve`.
  app.backendReady.then(async (where) => {
    const h = await app.api('/api/health');
    const mp4 = $('[data-download="mp4"]');
    mp4.hidden = !h.mp4 && where.mode !== 'engine';
    if (where.mode === 'engine') mp4.title = t('needsServer', mp4.textContent);
    showOnline();
  }).catch(() => {});
}
