// Offline use: registers the service worker (sw.js, which keeps the app shell and the last
// answers), shows "Offline" in the header while the browser has no network, and the MP4
// download only when /api/health says the server has ffmpeg.
import { t } from './i18n.js';

const $ = (s) => document.querySelector(s);

function showOnline() {
  const off = !navigator.onLine;
  const badge = $('#offline');
  badge.hidden = !off;
  badge.title = t('offlineNote');
  document.body.classList.toggle('is-offline', off);
  if (off) $('#status').textContent = t('offlineNote');
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
  app.api('/api/health').then((h) => { $('[data-download="mp4"]').hidden = !h.mp4; }).catch(() => {});
}
