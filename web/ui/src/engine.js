// Where the app's API requests are answered. The static site (index.html names the engine in
// <meta name="nbar-engine">) answers them in the browser: nbar's core in WebAssembly in a Web
// Worker (engine-worker.js), the same handle_api as `nbar serve`, so the same answers and errors.
// When the .wasm cannot load (an old browser, a blocked file) the page says so and falls back
// to the server's /api when there is one. A page from `nbar serve` (no meta) uses its server.
//
// The worker runs one request at a time; the rest wait here, so that a stale request (a new edit
// made it so) is dropped before it starts, and the running one is cancelled by ending the worker
// and starting another from the same .wasm bytes (the engine is single-threaded: nothing could
// ask it to stop mid-run). Every answer is a fetch Response, so callers read it as they read the
// server's.
import { addStrings, t } from './i18n.js';

addStrings({
  en: {
    engineFailed: (why) => `The in-browser engine could not load (${why}).`,
    engineUsesServer: 'Analyses run on the nbar server of this page instead.',
    engineNoServer: 'There is no nbar server here either: reload the page, or open it in a recent browser (Chrome, Edge, Firefox or Safari of the last two years).',
    cancelled: 'Cancelled',
    needsServer: (what) => `${what}: needs \`nbar serve\` (ffmpeg is not in the browser)`,
    progressOf: (stage, done, total) => (total > 0 ? `${stage} ${done}/${total}` : stage),
    cancel: 'Cancel', reload: 'Reload', jobStress: 'Stresses',
    offlineInBrowser: 'Offline: everything still works here, computed in this browser.',
  },
  es: {
    engineFailed: (why) => `El motor del navegador no se pudo cargar (${why}).`,
    engineUsesServer: 'Los análisis se hacen en el servidor nbar de esta página.',
    engineNoServer: 'Aquí tampoco hay servidor nbar: recargue la página o ábrala en un navegador reciente (Chrome, Edge, Firefox o Safari de los dos últimos años).',
    cancelled: 'Cancelado',
    needsServer: (what) => `${what}: necesita \`nbar serve\` (ffmpeg no está en el navegador)`,
    progressOf: (stage, done, total) => (total > 0 ? `${stage} ${done}/${total}` : stage),
    cancel: 'Cancelar', reload: 'Recargar', jobStress: 'Tensiones',
    offlineInBrowser: 'Sin conexión: todo sigue funcionando, calculado en este navegador.',
  },
});

// How long a request asked to stop (cancelRunning) may take to answer with what it has.
const stopWaitMs = 3000;

const engineMeta = () => document.querySelector('meta[name="nbar-engine"]')?.content;

function jsonResponse(status, error) {
  return new Response(JSON.stringify({ error }), { status, headers: { 'Content-Type': 'application/json' } });
}

class WorkerEngine {
  constructor(wasmUrl) {
    this.wasmUrl = new URL(wasmUrl, location.href);
    this.queue = [];       // requests not started: {id, message, resolve, key, onProgress}
    this.running = null;   // the request the worker is answering
    this.nextId = 1;
    this.listeners = new Set();
  }

  // Fetches the .wasm once (kept for restarts) and starts a worker; rejects with the reason.
  async load() {
    if (typeof WebAssembly !== 'object') throw new Error('this browser has no WebAssembly');
    const file = this.wasmUrl.pathname.split('/').pop();
    const r = await fetch(this.wasmUrl).catch((e) => { throw new Error(`${file} did not arrive: ${e.message}`); });
    if (!r.ok) throw new Error(`${file}: ${r.status} ${r.statusText}`);
    this.wasm = await r.arrayBuffer();
    this.version = await this.startWorker();
  }

  startWorker() {
    this.worker = new Worker(new URL('engine-worker.js', this.wasmUrl), { type: 'module' });
    const ready = new Promise((resolve, reject) => {
      this.worker.onerror = (e) => reject(new Error(e.message || 'the engine worker did not start'));
      this.worker.onmessage = ({ data }) => {
        if (data.type === 'ready') { resolve(data.version); this.worker.onmessage = (m) => this.onMessage(m.data); }
        else if (data.type === 'failed') reject(new Error(data.message));
      };
    });
    // A copy each time: the bytes stay here for the next worker.
    this.worker.postMessage({ type: 'load', wasm: this.wasm, moduleUrl: new URL('nbar-engine.js', this.wasmUrl).href });
    return ready;
  }

  onMessage(data) {
    const job = this.running;
    if (!job || data.id !== job.id) return;
    if (data.type === 'progress') {
      job.onProgress?.(data);
      this.emit({ running: job, ...data });
    } else if (data.type === 'answer') {
      this.running = null;
      clearTimeout(job.stopTimer);
      if (job.alive) URL.revokeObjectURL(job.alive);
      const headers = new Headers(data.headers);
      headers.set('Content-Type', data.contentType);
      job.resolve(new Response(data.body, { status: data.status, headers }));
      this.emit({ running: null });
      this.next();
    }
  }

  // options.key names what the request is for ('analysis'); options.label what to show while it
  // runs; options.keepOnCancel that the job bar's Cancel should stop it and take what it has (a
  // simulation's rows so far) rather than end the worker: the worker watches a blob: URL made for
  // the request (engine-worker.js, stillWanted), which Cancel revokes.
  request(method, path, body, options = {}) {
    return new Promise((resolve) => {
      const id = this.nextId++;
      const alive = options.keepOnCancel ? URL.createObjectURL(new Blob(['go on'])) : undefined;
      this.queue.push({ id, resolve, key: options.key, label: options.label, onProgress: options.onProgress, alive,
        message: { type: 'request', id, method, path, body, alive } });
      this.next();
    });
  }

  next() {
    if (this.running || !this.queue.length || this.restarting) return;
    this.running = this.queue.shift();
    this.running.started = performance.now();
    this.worker.postMessage(this.running.message);
    this.emit({ running: this.running, stage: '', done: 0, total: 0 });
  }

  // Cancels the requests with this key (every request when none): the waiting ones are answered
  // "cancelled" at once, and a running one by ending the worker.
  cancel(key) {
    const matches = (job) => key === undefined || job.key === key;
    for (const job of this.queue.filter(matches)) {
      if (job.alive) URL.revokeObjectURL(job.alive);
      job.resolve(jsonResponse(499, { kind: 'cancelled', message: t('cancelled') }));
    }
    this.queue = this.queue.filter((job) => !matches(job));
    if (this.running && matches(this.running)) this.restart();
  }

  // Cancel for the job bar: the request running now, whatever it is for. One that keeps what it
  // has is asked to stop, and answers with it; if it has not answered within stopWaitMs (it does
  // not reach a checkpoint), the worker is ended as for any other.
  cancelRunning() {
    const job = this.running;
    if (!job) return;
    if (!job.alive || job.stopTimer) { this.restart(); return; }
    URL.revokeObjectURL(job.alive);
    job.stopTimer = setTimeout(() => { if (this.running === job) this.restart(); }, stopWaitMs);
  }

  async restart() {
    const job = this.running;
    this.running = null;
    clearTimeout(job.stopTimer);
    if (job.alive) URL.revokeObjectURL(job.alive);
    this.worker.terminate();
    job.resolve(jsonResponse(499, { kind: 'cancelled', message: t('cancelled') }));
    this.emit({ running: null });
    this.restarting = true;
    try {
      await this.startWorker();
    } finally {
      this.restarting = false;
    }
    this.next();
  }

  emit(event) { for (const f of this.listeners) f(event); }
}

// mode: 'engine' (in the browser), 'server' (this page's nbar serve), 'none' (neither: every
// request answers why). note: what the page should say about it, or ''.
export async function startEngine() {
  const wasm = engineMeta();
  if (!wasm) return { mode: 'server', note: '' };
  const engine = new WorkerEngine(wasm);
  try {
    await engine.load();
    return { mode: 'engine', engine, note: '' };
  } catch (e) {
    const failed = t('engineFailed', e.message);
    const health = await fetch('api/health').then((r) => r.ok && r.json()).catch(() => null);
    if (health?.status === 'ok') return { mode: 'server', note: `${failed} ${t('engineUsesServer')}` };
    return { mode: 'none', note: `${failed} ${t('engineNoServer')}`, reason: failed };
  }
}

// Only a server can make these (501 from the engine): MP4 through ffmpeg.
export async function serverOnly(path, init, response, what) {
  try {
    const r = await fetch(path, init);
    if (r.ok) return r;
  } catch { /* no server */ }
  const info = await response.json().catch(() => ({}));
  return jsonResponse(501, { ...(info.error ?? {}), kind: 'not_implemented', message: t('needsServer', what) });
}
