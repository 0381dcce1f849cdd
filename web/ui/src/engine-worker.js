// The in-browser engine's Web Worker (engine.js starts it): nbar's core in WebAssembly
// (nbar-engine.js, emscripten's module, and the .wasm bytes the page hands over) answering the web API's requests off
// the page's thread, with the core's progress posted back while a request runs. Not bundled:
// it is copied beside nbar-engine.js into the static site (web/ui/build.mjs --engine).
//
// Messages in:  {type: 'load', wasm: ArrayBuffer, moduleUrl}
//               {type: 'request', id, method, path, body, alive}
// Messages out: {type: 'ready', version} or {type: 'failed', message}
//               {type: 'progress', id, stage, done, total} (at most every 100 ms)
//               {type: 'answer', id, status, contentType, headers, body: ArrayBuffer}
let engine = null;

// Whether the page still wants the request: `alive` is a blob: URL the page made for it and
// revokes to stop it (engine.js, stop()). The engine's run is synchronous, so no message could
// reach this worker before it ends; a synchronous read of the URL can, and the core then ends
// the run as a cancel does, with what it has (a simulation's rows so far).
function stillWanted(alive) {
  try {
    const xhr = new XMLHttpRequest();
    xhr.open('GET', alive, false);
    xhr.send();
    return xhr.status === 200;
  } catch {
    return false;
  }
}

async function load({ wasm, moduleUrl }) {
  try {
    if (typeof WebAssembly !== 'object') throw new Error('this browser has no WebAssembly');
    const { default: createNbarEngine } = await import(moduleUrl);
    engine = await createNbarEngine({ wasmBinary: new Uint8Array(wasm) });
    postMessage({ type: 'ready', version: engine.version() });
  } catch (e) {
    postMessage({ type: 'failed', message: String(e?.message ?? e) });
  }
}

function answer({ id, method, path, body, alive }) {
  let last = performance.now();
  // A browser that cannot read a blob: URL from a worker leaves the request to the worker's end.
  let watched = alive && stillWanted(alive) ? alive : null;
  let wanted = true;
  const progress = (stage, done, total) => {
    const now = performance.now();
    if (now - last < 100) return wanted;
    last = now;
    postMessage({ type: 'progress', id, stage, done, total });
    if (watched && !stillWanted(watched)) { wanted = false; watched = null; }
    return wanted;
  };
  let reply;
  try {
    reply = engine.requestWithProgress
      ? engine.requestWithProgress(method, path, body, progress)
      : engine.request(method, path, body);
  } catch (e) {
    // handle_api never throws; an abort (out of memory) does, and leaves the module unusable.
    const error = { kind: 'engine', message: `the in-browser engine stopped: ${e?.message ?? e}; reload the page` };
    const bytes = new TextEncoder().encode(JSON.stringify({ error }));
    postMessage({ type: 'answer', id, status: 500, contentType: 'application/json', headers: [], body: bytes.buffer }, [bytes.buffer]);
    return;
  }
  const bytes = reply.body;  // a copy out of the module's memory: ours to hand over
  postMessage({ type: 'answer', id, status: reply.status, contentType: reply.contentType, headers: reply.headers, body: bytes.buffer },
    [bytes.buffer]);
}

self.onmessage = (event) => {
  const message = event.data;
  if (message.type === 'load') load(message);
  else if (message.type === 'request') answer(message);
};
