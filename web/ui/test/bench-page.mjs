// The static site's benchmark (issue 35's targets), run in Debian's Chromium against the native
// program on the same machine, in the same run. The site is served by `python3 -m http.server`
// with no nbar process, and every request to /api is refused.
//   - Download: every file of the site gzipped (level 9), the whole app and the .wasm alone.
//   - First analysis: a fresh browser context each time (cold cache), from the page's request
//     to the first analysis shown (body[data-ready="1"]), the median of three.
//   - Speed: the engine loaded in a page of the site (its .wasm compiled by Chromium) answers the
//     requests of web/engine/test/bench-cases.mjs; each is timed against the native CLI doing the
//     same work, the two taking turns so that a busy machine slows both alike.
//   - Dragging: the crank-rocker's coupler point dragged in the app, 2 px a move; a frame is
//     the time from the pointer's move to the mechanism, its trace and the plot redrawn for it.
// It prints the figures (and writes them as JSON with --json FILE); with --check it fails when a
// target is not met. It asserts nothing else: a benchmark, not a test.
//   node test/bench-page.mjs --site build-wasm/site --native build/apps/nbar/nbar --examples examples [--runs 5] [--check]
import { spawnSync } from 'node:child_process';
import { readdirSync, readFileSync, statSync, writeFileSync } from 'node:fs';
import { cpus, loadavg } from 'node:os';
import { join, resolve } from 'node:path';
import { performance } from 'node:perf_hooks';
import { gzipSync } from 'node:zlib';
import { benchCases } from '../../engine/test/bench-cases.mjs';
import { arg, launchChromium, serveStatic, watchdog } from './harness.mjs';

const site = resolve(arg('--site', 'build-wasm/site'));
const native = resolve(arg('--native', 'build/apps/nbar/nbar'));
const examples = resolve(arg('--examples', 'examples'));
const runs = Number(arg('--runs', '5'));
const check = process.argv.includes('--check');
const jsonOut = arg('--json');

const median = (values) => [...values].sort((a, b) => a - b)[Math.floor(values.length / 2)];
const quantile = (values, q) => [...values].sort((a, b) => a - b)[Math.min(values.length - 1, Math.floor(q * values.length))];
const figures = { cores: cpus().length, load: loadavg()[0] };
const verdicts = [];
// `value` against its target (at most), recorded for --check; `said` is the target as printed.
const judge = (what, value, target, said) => {
  const met = value <= target;
  verdicts.push({ what, met });
  return `(target ${said}: ${met ? 'met' : 'NOT met'})`;
};

function files(folder) {
  return readdirSync(folder).flatMap((name) => {
    const path = join(folder, name);
    return statSync(path).isDirectory() ? files(path) : [path];
  });
}

function downloadSizes() {
  let raw = 0, gzipped = 0;
  for (const file of files(site)) {
    const bytes = readFileSync(file);
    raw += bytes.length;
    gzipped += gzipSync(bytes, { level: 9 }).length;
  }
  const wasm = readFileSync(join(site, 'nbar-engine.wasm'));
  return { raw, gzipped, wasm: wasm.length, wasmGzipped: gzipSync(wasm, { level: 9 }).length };
}

const { base, stop } = await serveStatic(site, arg('--python', 'python3'));
const browser = await launchChromium();
const timer = watchdog(900000, () => { stop(); browser.close(); });

async function freshPage(viewport = { width: 1366, height: 768 }) {
  const context = await browser.newContext({ viewport, locale: 'en-US' });
  await context.route(/\/api(\/|$)/, (route) => route.abort());
  const page = await context.newPage();
  page.setDefaultTimeout(60000);
  return { context, page };
}

async function firstAnalysis() {
  const { context, page } = await freshPage();
  const started = performance.now();
  await page.goto(base);
  await page.waitForSelector('body[data-ready="1"]');
  const ms = performance.now() - started;
  await context.close();
  return ms;
}

// The engine in a page of the site, on the page's thread: the worker's code without the worker,
// so that the time is the computation's and not the messages'.
async function enginePage() {
  const { context, page } = await freshPage();
  await page.goto(base);
  await page.waitForSelector('body[data-ready="1"]');
  const loadMs = await page.evaluate(async () => {
    const start = performance.now();
    const wasm = await (await fetch('nbar-engine.wasm')).arrayBuffer();
    const { default: createNbarEngine } = await import(new URL('nbar-engine.js', location.href).href);
    window.benchEngine = await createNbarEngine({ wasmBinary: new Uint8Array(wasm) });
    return performance.now() - start;
  });
  return { context, page, loadMs };
}

function timedCli(each) {
  const start = performance.now();
  const run = spawnSync(native, each.cli, { maxBuffer: 1 << 28 });
  if (run.status !== 0) throw new Error(`${each.name}: the CLI failed: ${run.stderr}`);
  return performance.now() - start;
}

async function timedInPage(page, each) {
  const { ms, status } = await page.evaluate(({ path, body }) => {
    const start = performance.now();
    const reply = window.benchEngine.request('POST', `/api/${path}`, JSON.stringify(body));
    return { ms: performance.now() - start, status: reply.status };
  }, { path: each.path, body: each.body });
  if (status !== 200) throw new Error(`${each.name}: the engine in Chromium answered ${status}`);
  return ms;
}

async function speed() {
  const { context, page, loadMs } = await enginePage();
  figures.engineLoadMs = loadMs;
  console.log(`engine load in Chromium (fetch, compile and start the .wasm): ${loadMs.toFixed(0)} ms`);
  figures.speed = [];
  for (const each of benchCases(examples, runs)) {
    const firstMs = await timedInPage(page, each);
    const browserMs = [], cliMs = [];
    for (let i = 0; i < each.runs; ++i) {
      browserMs.push(await timedInPage(page, each));
      cliMs.push(timedCli(each));
    }
    const ratio = median(browserMs) / median(cliMs);
    const verdict = each.target === undefined ? '' : ` ${judge(each.name, ratio, each.target, `${each.target}x`)}`;
    figures.speed.push({ name: each.name, browserMs: median(browserMs), cliMs: median(cliMs), firstMs, ratio });
    console.log(`${each.name}, median of ${each.runs}: Chromium ${median(browserMs).toFixed(1)} ms (first ` +
                `${firstMs.toFixed(1)} ms), native CLI ${median(cliMs).toFixed(1)} ms: ratio ${ratio.toFixed(2)}${verdict}`);
  }
  await context.close();
}

// Drags the coupler point P of the app's first model, waiting after each move until the drawing
// shows it; the page records when each move arrived and when the drawing, the trace and the plot
// next changed, and the frame the browser painted them in.
async function dragFrames(moves = 40) {
  const { context, page } = await freshPage();
  await page.goto(base);
  await page.waitForSelector('body[data-ready="1"]');
  await page.waitForSelector('#drawing circle.pt[data-point="P"]');
  await page.evaluate(() => {
    window.dragTimes = { moves: [], drawn: [] };
    const drawing = document.querySelector('#drawing');
    drawing.addEventListener('pointermove', (e) => window.dragTimes.moves.push(e.timeStamp), true);
    // The drawing's, the trace's and the plot's changes that one move causes, seen after layout.
    new MutationObserver(() => requestAnimationFrame((painted) => window.dragTimes.drawn.push(painted)))
      .observe(drawing, { subtree: true, childList: true, attributes: true, attributeFilter: ['points', 'd', 'cx', 'cy', 'transform'] });
  });
  const p = await page.locator('#drawing circle.pt[data-point="P"]').boundingBox();
  let x = p.x + p.width / 2, y = p.y + p.height / 2;
  await page.mouse.move(x, y);
  await page.mouse.down();
  const frames = [];
  const coupler = () => page.evaluate(() => document.querySelector('#drawing g[data-link="coupler"] > .body')?.getAttribute('points'));
  for (let i = 0; i < moves; ++i) {
    const before = await coupler();
    const drawnBefore = await page.evaluate(() => window.dragTimes.drawn.length);
    x += 2; y += i % 2 ? 1 : 0;
    await page.mouse.move(x, y);
    await page.waitForFunction((b) => document.querySelector('#drawing g[data-link="coupler"] > .body')?.getAttribute('points') !== b, before);
    await page.waitForFunction((n) => window.dragTimes.drawn.length > n, drawnBefore);
    await page.waitForTimeout(30);  // let the plot and the trace, redrawn for the same move, land
    frames.push(await page.evaluate(() => {
      const t = window.dragTimes;
      const moved = t.moves[t.moves.length - 1];
      return Math.max(...t.drawn.filter((d) => d >= moved)) - moved;
    }));
  }
  await page.mouse.up();
  await context.close();
  return frames;
}

try {
  const sizes = downloadSizes();
  figures.download = sizes;
  console.log(`nbar static site; ${figures.cores} cores, load average ${figures.load.toFixed(1)}`);
  console.log(`download: the whole app ${sizes.gzipped} bytes gzipped (${(sizes.gzipped / 1048576).toFixed(2)} MiB; ` +
              `${sizes.raw} as files) ${judge('download', sizes.gzipped / 1e6, 3, '3 MB')}; the .wasm ${sizes.wasmGzipped} gzipped, ${sizes.wasm} as a file`);
  const first = [];
  for (let i = 0; i < 3; ++i) first.push(await firstAnalysis());
  figures.firstAnalysisMs = first;
  console.log(`first analysis, cold cache: ${first.map((ms) => ms.toFixed(0)).join(', ')} ms; median ${median(first).toFixed(0)} ms ` +
              `${judge('first analysis', median(first) / 1000, 1.5, '1.5 s')}`);
  await speed();
  const frames = await dragFrames();
  figures.dragFrameMs = { median: median(frames), p90: quantile(frames, 0.9), max: Math.max(...frames), moves: frames.length };
  console.log(`dragging the crank-rocker's P: frame ${median(frames).toFixed(1)} ms median, ${quantile(frames, 0.9).toFixed(1)} ms ` +
              `at the 90th percentile, ${Math.max(...frames).toFixed(1)} ms at most over ${frames.length} moves: ` +
              `${(1000 / median(frames)).toFixed(0)} frames a second ${judge('drag', median(frames), 1000 / 30, '30 frames a second')}`);
} finally {
  clearTimeout(timer);
  await browser.close();
  stop();
}
if (jsonOut) writeFileSync(jsonOut, JSON.stringify(figures, null, 2));
const missed = verdicts.filter((v) => !v.met).map((v) => v.what);
console.log(missed.length ? `targets not met: ${missed.join(', ')}` : 'every target met');
process.exit(check && missed.length ? 1 : 0);
