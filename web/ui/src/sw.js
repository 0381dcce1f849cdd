// The web app's service worker (served at the root, as /sw.js by nbar serve or beside
// index.html in the static site, so its scope is the whole app). The app's files are fetched
// from the network first and kept, so that without a network the page, the editor and the last
// results still open; in the static site they include the in-browser engine (the worker, the
// module and the .wasm), so every analysis works offline too. POST answers of a server (check,
// solve, stress, explain, synthesis, simulate, and the drawing's scene) are kept under a digest of the
// request's body: the same model asked again offline gets the answer it had. Anything else asked
// a server offline is a 503 that says so.
//
// web/ui/build.mjs writes VERSION (a digest of the app's files) and SHELL (the files kept at
// install): a new site is a new sw.js, which the browser installs on the next visit, and its
// activation deletes the older version's cache.
const VERSION = '@VERSION@';
const SHELL = ['@SHELL@'];
const CACHE = `nbar-app-${VERSION}`;
const KEPT_POSTS = ['/api/check', '/api/outline', '/api/solve', '/api/stress', '/api/explain', '/api/synth/', '/api/simulate'];
const MAX_POSTS = 60;
// Asked afresh at every move of the pointer over the stress map: kept, they would push the
// model's own answers out of the MAX_POSTS kept.
const PASSING_POSTS = ['/api/stress/probe'];

// Each file on its own: one that is missing (no engine in nbar serve's app) keeps none out.
self.addEventListener('install', (event) => {
  event.waitUntil(caches.open(CACHE)
    .then((c) => Promise.allSettled(SHELL.map((path) => c.add(path))))
    .then(() => self.skipWaiting()));
});
self.addEventListener('activate', (event) => {
  event.waitUntil(caches.keys()
    .then((keys) => Promise.all(keys.filter((k) => k !== CACHE).map((k) => caches.delete(k))))
    .then(() => self.clients.claim()));
});

function offlineAnswer() {
  const error = {
    kind: 'offline',
    message: 'Offline: the analysis needs the nbar server. The editor and the last results still work.',
  };
  return new Response(JSON.stringify({ error }), {
    status: 503, headers: { 'Content-Type': 'application/json', 'X-Nbar-Offline': '1' },
  });
}

async function postKey(request) {
  const body = await request.clone().arrayBuffer();
  const digest = await crypto.subtle.digest('SHA-256', body);
  const hex = [...new Uint8Array(digest)].map((b) => b.toString(16).padStart(2, '0')).join('');
  return new Request(`${new URL(request.url).pathname}?post=${hex}`);
}

async function trim(cache) {
  const posts = (await cache.keys()).filter((r) => new URL(r.url).searchParams.has('post'));
  for (const r of posts.slice(0, Math.max(posts.length - MAX_POSTS, 0))) await cache.delete(r);
}

async function networkFirst(request) {
  const cache = await caches.open(CACHE);
  const isPost = request.method === 'POST';
  const key = isPost ? await postKey(request) : request;
  try {
    const answer = await fetch(request);
    if (answer.ok) {
      // Kept again, so the newest is last (trim removes the oldest).
      if (isPost) await cache.delete(key);
      await cache.put(key, answer.clone());
      if (isPost) await trim(cache);
    }
    return answer;
  } catch {
    const kept = await cache.match(key) ?? (request.mode === 'navigate' ? await cache.match('./') : undefined);
    if (!kept) return offlineAnswer();
    const headers = new Headers(kept.headers);
    headers.set('X-Nbar-Offline', '1');
    return new Response(await kept.blob(), { status: kept.status, headers });
  }
}

// Of the pictures, only the drawing's scene is kept (not the downloads: GIF, MP4, reports, nor
// the stress map's scene at each pose shown).
async function sceneOrPicture(request) {
  let scene = false;
  try {
    const body = JSON.parse(await request.clone().text());
    scene = body.format === 'scene' && !body.stress;
  } catch { /* not JSON */ }
  return scene ? networkFirst(request) : fetch(request).catch(offlineAnswer);
}

self.addEventListener('fetch', (event) => {
  const { request } = event;
  const url = new URL(request.url);
  if (url.origin !== self.location.origin) return;
  const passing = request.method === 'POST' && PASSING_POSTS.includes(url.pathname);
  if (request.method === 'GET' || (!passing && request.method === 'POST' && KEPT_POSTS.some((p) => url.pathname.startsWith(p)))) {
    event.respondWith(networkFirst(request));
  } else if (request.method === 'POST' && url.pathname === '/api/render') {
    event.respondWith(sceneOrPicture(request));
  } else if (request.method === 'POST') {
    event.respondWith(fetch(request).catch(offlineAnswer));
  }
});
