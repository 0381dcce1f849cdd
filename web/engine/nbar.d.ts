// Types of nbar.mjs, nbar's engine in WebAssembly (docs/javascript.md).

/** How the engine finds its .wasm; both are optional. */
export interface LoadOptions {
  /** The bytes of nbar-engine.wasm, when the caller has them (no file is read or fetched). */
  wasmBinary?: ArrayBuffer | ArrayBufferView;
  /** Where a browser finds a file of the engine (nbar-engine.wasm) when it is not beside nbar.mjs. */
  locateFile?: (name: string) => string;
  /** The wall time one request may compute before it is answered 504 (default 30 s, as `nbar serve --time-budget`). */
  timeBudgetSeconds?: number;
}

/** One answer, as the web API (`nbar serve`) would give it. */
export interface Answer {
  /** 200, or the server's error status: 400, 413, 422, 501, 504. */
  status: number;
  contentType: string;
  headers: [string, string][];
  /** Parsed JSON for a JSON answer (an error is {error: {kind, message, line?, column?, ...}}),
   *  the text of a text answer (SVG, HTML, CSV, DXF), the bytes of any other. */
  body: any;
}

/** An answer's body as the server's bytes. */
export interface ByteAnswer {
  status: number;
  contentType: string;
  body: Uint8Array;
}

export interface Nbar {
  /** The version of nbar the engine was built from (the C++ project's, and this package's). */
  readonly version: string;
  /** One request: `path` is the endpoint without `/api/` ('solve', 'simulate', 'synth/five-point', 'examples');
   *  `body` its JSON object or text; none makes it a GET. A simulation ('simulate', `nbar simulate`)
   *  answers {model, free_drivers, complete, events, integrator, constraint_drift, columns, rows, ...};
   *  with `scene: {width, height}` in the body, {simulation, scene}: the web app's drawing of its motion. */
  request(path: string, body?: object | string): Answer;
  requestBytes(path: string, body?: object | string): ByteAnswer;
}

/** Loads and starts the engine. */
export function loadNbar(options?: LoadOptions): Promise<Nbar>;
export default loadNbar;
