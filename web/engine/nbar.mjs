// nbar's engine in WebAssembly, as an ES module for browsers (and their workers) and Node 20:
//
//   import { loadNbar } from './nbar.mjs';
//   const nbar = await loadNbar();
//   const answer = nbar.request('solve', { model: yamlText, steps: 37 });
//   // answer.status 200, answer.body: the JSON the web API (`nbar serve`) would send
//   const run = nbar.request('simulate', { model: yamlText, to: 3, dt: 0.01 });
//   // forward dynamics (`nbar simulate --format json`): the free drivers released under the loads
//
// request(path, body) answers exactly as the server's JSON API does (docs/web-api.md): the same
// endpoints, options, limits and time budget, the same errors with their line and column. It
// runs in the calling thread; a page keeps it in a Web Worker so that long jobs do not block it.
import createNbarEngine from './nbar-engine.mjs';

const isNode = typeof process === 'object' && typeof process.versions?.node === 'string';

// Node 20's fetch cannot read a file: URL, so there the module is handed its bytes. A browser
// fetches the .wasm beside this file (or where options.locateFile says).
async function nodeWasmBytes() {
  const { readFile } = await import('node:fs/promises');
  return readFile(new URL('./nbar-engine.wasm', import.meta.url));
}

// Text content types (JSON, YAML, SVG, HTML, CSV, DXF, LaTeX) come back as strings, JSON parsed;
// the rest (PNG, GIF) as bytes.
function isText(contentType) {
  return /^text\/|json|xml|yaml|latex|dxf/.test(contentType);
}

function decodeBody(contentType, bytes) {
  if (!isText(contentType)) return bytes;
  const text = new TextDecoder().decode(bytes);
  return contentType.startsWith('application/json') ? JSON.parse(text) : text;
}

// 'solve', 'synth/five-point', '/api/solve' and 'api/solve' all name /api/solve.
function apiPath(path) {
  if (path.startsWith('/')) return path;
  return path.startsWith('api/') ? `/${path}` : `/api/${path}`;
}

class Nbar {
  #engine;

  constructor(engine) {
    this.#engine = engine;
  }

  // The version of nbar this engine was built from (the C++ project's).
  get version() {
    return this.#engine.version();
  }

  // One API request. `body` is the request's JSON object (or its text); none makes it a GET
  // (health, examples). Returns {status, contentType, headers, body}: body is the parsed JSON of
  // a JSON answer (an error is {error: {kind, message, line, column, ...}} with status >= 400),
  // the text of a text answer (SVG, HTML, CSV, DXF), the bytes (Uint8Array) of any other.
  request(path, body) {
    const method = body === undefined ? 'GET' : 'POST';
    const text = body === undefined ? '' : typeof body === 'string' ? body : JSON.stringify(body);
    const answer = this.#engine.request(method, apiPath(path), text);
    return {
      status: answer.status,
      contentType: answer.contentType,
      headers: answer.headers,
      body: decodeBody(answer.contentType, answer.body),
    };
  }

  // The answer's body exactly as the server would send it (bytes), for comparing and saving.
  requestBytes(path, body) {
    const method = body === undefined ? 'GET' : 'POST';
    const text = body === undefined ? '' : typeof body === 'string' ? body : JSON.stringify(body);
    const answer = this.#engine.request(method, apiPath(path), text);
    return { status: answer.status, contentType: answer.contentType, body: answer.body };
  }
}

// Loads and starts the engine. options.wasmBinary: the .wasm's bytes (an ArrayBuffer or a
// typed array), when the caller has them; options.locateFile(name): where a browser finds the
// .wasm when it is not beside this file; options.timeBudgetSeconds: the wall time one request may
// compute before it is answered 504 (default 30, as `nbar serve --time-budget`).
export async function loadNbar(options = {}) {
  const moduleOptions = {};
  const bytes = options.wasmBinary ?? (isNode ? await nodeWasmBytes() : undefined);
  if (bytes) moduleOptions.wasmBinary = bytes;
  // The .wasm beside this file, written as `new URL('./file', import.meta.url)` so that bundlers
  // (esbuild, webpack, Vite) see the file and ship it with the page that imports this package.
  const besideThis = new URL('./nbar-engine.wasm', import.meta.url);
  moduleOptions.locateFile = options.locateFile ?? ((name) => (name.endsWith('.wasm') ? besideThis.href : name));
  const budget = options.timeBudgetSeconds;
  if (budget !== undefined && !(typeof budget === 'number' && budget > 0 && Number.isFinite(budget)))
    throw new RangeError(`timeBudgetSeconds: must be a number of seconds over 0, not ${budget}`);
  const engine = await createNbarEngine(moduleOptions);
  if (budget !== undefined) engine.setTimeBudget(budget);
  return new Nbar(engine);
}

export default loadNbar;
