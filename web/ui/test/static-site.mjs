// The static site (scripts/build-wasm.sh --site) as a student gets it: served by
// `python3 -m http.server` with no nbar process, opened in Debian's Chromium at a phone's and a
// laptop's size with every request to /api blocked (and none in the server's log). The
// in-browser engine must analyse an example, place a bad model's error at its line and column,
// make the downloads (CSV, PNG and GIF drawn in the browser, the HTML report, DXF plates), say
// that MP4 needs `nbar serve`, show a synthesis's progress and cancel it, and, once the page has
// been opened, analyse an edit offline, and simulate the released crank-rocker (simulate.mjs; its
// numbers against `nbar simulate` when --native names the native program). Then 30 pages opened at
// once must all get their analysis.
//   node test/static-site.mjs --site build-wasm/site [--python python3] [--out DIR] [--pages 30]
//        [--native build/apps/nbar/nbar --examples examples] [--only simulate]
import assert from 'node:assert/strict';
import { existsSync, mkdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { arg, launchChromium, serveStatic, watchdog } from './harness.mjs';
import * as simulate from './simulate.mjs';

const site = arg('--site');
const python = arg('--python', 'python3');
const out = arg('--out', 'site-screenshots');
const pages = +arg('--pages', '30');
const native = arg('--native', '');
const examples = arg('--examples', '../../examples');
const onlySimulate = arg('--only', '') === 'simulate';
if (!site || !existsSync(join(site, 'nbar-engine.wasm'))) {
  console.error(`no static site with an engine at ${site} (scripts/build-wasm.sh --site)`);
  process.exit(1);
}
mkdirSync(out, { recursive: true });

const { base, log, stop } = await serveStatic(site, python);
const browser = await launchChromium();
const timer = watchdog(540000, () => { stop(); browser.close(); });
const errors = [];
const blocked = [];
let probingServer = false;  // the MP4 download's request to a server, refused: not an error

async function open(name, viewport, mobile) {
  const context = await browser.newContext({
    viewport, hasTouch: mobile, isMobile: mobile, deviceScaleFactor: mobile ? 2 : 1, acceptDownloads: true, locale: 'en-US',
  });
  // No nbar server: any request to /api is refused before it leaves the browser.
  await context.route(/\/api(\/|$)/, (route) => { blocked.push(route.request().url()); return route.abort(); });
  const page = await context.newPage();
  page.on('pageerror', (e) => errors.push(`${name}: ${e.message}`));
  page.on('console', (m) => {
    if (m.type() === 'error' && !(probingServer && /Failed to load resource/.test(m.text()))) errors.push(`${name}: console: ${m.text()}`);
  });
  page.setDefaultTimeout(30000);
  const started = Date.now();
  await page.goto(base);
  await page.waitForSelector('body[data-ready="1"]');
  return { context, page, firstAnalysisMs: Date.now() - started };
}

const shot = (page, name) => page.screenshot({ path: join(out, `${name}.png`) });
const click = (page, mobile, selector) => (mobile ? page.locator(selector).first().tap() : page.locator(selector).first().click());

// As browser.mjs types: the cursor at the line's start, moved right, the text selected and typed over.
async function retype(page, mobile, line, from, to) {
  const target = page.locator('.cm-line', { hasText: line }).first();
  const text = await target.textContent();
  const at = text.lastIndexOf(from);
  assert.ok(at >= 0, `"${from}" in "${text}"`);
  if (mobile) await target.tap({ position: { x: 1, y: 4 } }); else await target.click({ position: { x: 1, y: 4 } });
  for (let i = 0; i < at; i++) await page.keyboard.press('ArrowRight');
  for (let i = 0; i < from.length; i++) await page.keyboard.press('Shift+ArrowRight');
  await page.keyboard.type(to);
}

async function opened(page, tag) {
  assert.equal(await page.evaluate(() => document.body.dataset.engine), 'engine', 'the in-browser engine is used');
  assert.equal(await page.locator('#model-name').textContent(), 'Crank-rocker four-bar');
  assert.match(await page.locator('#status').textContent(), /^1 DOF · 361 samples/);
  assert.ok(await page.locator('#drawing svg .body').count() > 0, 'the drawing has bodies');
  assert.ok(await page.locator('#engine-note').isHidden(), 'no note about the engine');
  await shot(page, `${tag}-1-opened`);
}

// The same located error as the server gives (browser.mjs's errorInEditor).
async function badModel(page, mobile, tag) {
  await click(page, mobile, '[data-tab="editor"]');
  await retype(page, mobile, 'crank:   [O2, A]', 'A]', 'Q]');
  await page.waitForSelector('.cm-lintRange-error');
  assert.match(await page.locator('#problems').textContent(), /^line 16, column 17: unknown point 'Q'/);
  assert.equal(await page.locator('.cm-lintRange-error').first().textContent(), 'Q');
  await shot(page, `${tag}-2-error`);
  await retype(page, mobile, 'crank:   [O2, Q]', 'Q]', 'A]');
  await page.waitForFunction(() => document.querySelector('#problems').textContent === 'No errors.');
  // Over a limit of the server: refused the same way, at the same place.
  await retype(page, mobile, 'sweep: {steps: 361}', '361', '999999');
  await page.waitForFunction(() => /^line 22, column 16: the number of samples of the sweep is 999999; this server allows at most 100001/
    .test(document.querySelector('#problems').textContent));
  await retype(page, mobile, 'sweep: {steps: 999999}', '999999', '361');
  await page.waitForFunction(() => document.querySelector('#problems').textContent === 'No errors.');
}

async function downloaded(page, mobile, kind) {
  const [download] = await Promise.all([
    page.waitForEvent('download').catch(async (e) => { throw new Error(`${kind}: no download; the status says "${await page.locator('#status').textContent()}" (${e.message})`); }),
    click(page, mobile, `[data-download="${kind}"]`)]);
  return { name: download.suggestedFilename(), bytes: readFileSync(await download.path()) };
}

async function downloads(page, mobile, tag) {
  await click(page, mobile, '[data-tab="downloads"]');
  const csv = await downloaded(page, mobile, 'csv');
  assert.equal(csv.name, 'fourbar-crank-rocker.csv');
  const lines = csv.bytes.toString().trim().split('\n');
  assert.equal(lines.length, 362, 'a header and 361 samples');
  assert.match(lines[0], /^step,/);
  const png = await downloaded(page, mobile, 'png');
  assert.equal(png.bytes.subarray(1, 4).toString(), 'PNG');
  assert.equal(png.bytes.readUInt32BE(16), 900, 'the PNG is the engine\'s SVG drawing\'s width');
  const gif = await downloaded(page, mobile, 'gif');
  assert.equal(gif.bytes.subarray(0, 6).toString(), 'GIF89a');
  assert.equal(gif.bytes.readUInt16LE(6), 640);
  // A frame's graphic control extension (21 F9 04) each, its delay with it.
  const controls = gif.bytes.reduce((n, b, i) => n + (b === 0x21 && gif.bytes[i + 1] === 0xf9 && gif.bytes[i + 2] === 4 ? 1 : 0), 0);
  assert.equal(controls, 36, '36 frames');
  const report = await downloaded(page, mobile, 'report');
  assert.match(report.bytes.toString(), /^<!DOCTYPE html>/i);
  // MP4 needs ffmpeg, which only a server has: the app asks this page's server (the one request
  // to /api the app makes, blocked here) and, with none, says plainly what it needs.
  const before = blocked.length;
  probingServer = true;
  await click(page, mobile, '[data-download="mp4"]');
  await page.waitForFunction(() => document.querySelector('#status').textContent
    === 'Failed: Animation (MP4): needs `nbar serve` (ffmpeg is not in the browser)');
  probingServer = false;
  assert.deepEqual(blocked.splice(before).map((u) => new URL(u).pathname), ['/api/render']);
  await shot(page, `${tag}-3-downloads`);
  // The plates for cutting, of a model whose links have shapes.
  await click(page, mobile, '[data-tab="gallery"]');
  const opens = await page.evaluate(() => +document.body.dataset.opened);
  await click(page, mobile, '[data-example="fourbar-rounded-crank"]');
  await page.waitForFunction((n) => +document.body.dataset.opened > n && !document.body.dataset.busy, opens);
  await click(page, mobile, '[data-tab="downloads"]');
  const dxf = await downloaded(page, mobile, 'plates-dxf');
  assert.match(dxf.bytes.toString(), /^\s*0\s*\r?\n\s*SECTION/);
  const plates = await downloaded(page, mobile, 'plates-svg');
  assert.match(plates.bytes.toString(), /<svg/);
  await click(page, mobile, '[data-tab="gallery"]');
  const again = await page.evaluate(() => +document.body.dataset.opened);
  await click(page, mobile, '[data-example="fourbar-crank-rocker"]');
  await page.waitForFunction((n) => +document.body.dataset.opened > n && !document.body.dataset.busy, again);
  return { csv: csv.bytes.length, png: png.bytes.length, gif: gif.bytes.length, report: report.bytes.length, dxf: dxf.bytes.length, plates: plates.bytes.length };
}

// A nine-point synthesis (seconds of path tracking) shows its progress, and Cancel stops it; a
// five-point one then runs to its designs in the restarted engine.
async function synthesisProgressAndCancel(page, mobile, tag) {
  await click(page, mobile, '[data-tab="synthesis"]');
  await page.selectOption('#synth-method', 'nine-point');
  await page.waitForFunction(() => /task: nine-point/.test(document.querySelector('#task').value));
  await click(page, mobile, '#synth-run');
  await page.waitForSelector('#job:not([hidden])');
  await page.waitForFunction(() => document.querySelector('#job progress').value > 0);
  const progress = await page.locator('#job span').textContent();
  assert.match(progress, /^Synthesis paths \d+\/1442$/);
  await shot(page, `${tag}-4-progress`);
  await click(page, mobile, '#job button');
  await page.waitForFunction(() => /Cancelled/.test(document.querySelector('#synth-status').textContent));
  assert.ok(await page.locator('#job').isHidden());
  await page.selectOption('#synth-method', 'five-point');
  await click(page, mobile, '#synth-run');
  await page.waitForSelector('[data-design="1"]:not([disabled])', { timeout: 60000 });
  assert.match(await page.locator('#synth-status').textContent(), /^\d+ designs? \(\d+ solutions?\)/);
  return progress;
}

const firstRow = (page) => page.evaluate(() => document.querySelector('#table tbody tr').textContent);

// Reloaded without a network: the service worker serves the site and its engine, and an edit is
// analysed as online.
async function offline(context, page, mobile, tag) {
  await page.evaluate(() => navigator.serviceWorker.ready);
  await page.waitForFunction(() => navigator.serviceWorker.controller !== null);
  await context.setOffline(true);
  try {
    await page.reload();
    await page.waitForSelector('body[data-ready="1"]');
    assert.equal(await page.evaluate(() => document.body.dataset.engine), 'engine');
    assert.ok(await page.locator('#offline').isVisible(), 'the header says offline');
    await click(page, mobile, '[data-tab="editor"]');
    const before = await firstRow(page);
    const analysed = page.evaluate(() => new Promise((resolve) => {
      document.addEventListener('nbar:analysed', (e) => resolve(e.detail.error), { once: true });
    }));
    await retype(page, mobile, 'O4: [200, 0]', '200', '210');
    assert.equal(await analysed, null, 'the edit is analysed offline');
    assert.match(await page.locator('#status').textContent(), /^1 DOF · 361 samples/);
    // The rocker's pivot moved 10 mm: its angle at the first sample is another.
    assert.notEqual(await firstRow(page), before);
    await shot(page, `${tag}-5-offline`);
  } finally {
    await context.setOffline(false);
  }
}

// A .wasm that does not load (blocked here), on a static host (no server either): the page says
// so plainly and offers Reload; nothing is computed anywhere else.
async function engineMissing() {
  const context = await browser.newContext({ viewport: { width: 390, height: 844 }, isMobile: true, hasTouch: true, deviceScaleFactor: 2 });
  await context.route(/\/api(\/|$)|nbar-engine\.wasm$/, (route) => route.abort());
  const page = await context.newPage();
  page.on('pageerror', (e) => errors.push(`no engine: ${e.message}`));
  await page.goto(base);
  await page.waitForSelector('#engine-note:not([hidden])');
  await page.waitForSelector('body[data-ready="1"]');
  assert.match(await page.locator('#status').textContent(), /^Failed: The in-browser engine could not load/);
  const note = await page.locator('#engine-note span').textContent();
  assert.match(note, /^The in-browser engine could not load \(.*nbar-engine\.wasm.*\)\. There is no nbar server here either: reload the page/);
  assert.ok(await page.locator('#engine-note button').isVisible(), 'Reload is offered');
  assert.equal(await page.evaluate(() => document.body.dataset.engine), 'none');
  await shot(page, 'phone-6-no-engine');
  await context.close();
  return note;
}

// A file of the app that does not arrive (a server too busy to send it) leaves no blank page.
async function appFileMissing() {
  const context = await browser.newContext({ viewport: { width: 390, height: 844 }, isMobile: true, hasTouch: true });
  await context.route(/\/app\.js$/, (route) => route.abort());
  const page = await context.newPage();
  await page.goto(base);
  await page.waitForSelector('#load-failed');
  const text = await page.locator('#load-failed').textContent();
  assert.equal(text, 'A file of the app did not load (app.js). Reload');
  await context.close();
  return text;
}

// Every page opened at the same moment from the one static server: each gets its analysis.
async function manyAtOnce(count) {
  const context = await browser.newContext({ viewport: { width: 1366, height: 768 } });
  await context.route(/\/api(\/|$)/, (route) => { blocked.push(route.request().url()); return route.abort(); });
  const all = await Promise.all(Array.from({ length: count }, () => context.newPage()));
  const started = Date.now();
  const results = await Promise.allSettled(all.map(async (page) => {
    page.setDefaultTimeout(240000);
    await page.goto(base);
    await page.waitForSelector('body[data-ready="1"]');
    assert.match(await page.locator('#status').textContent(), /^1 DOF/);
    return Date.now() - started;
  }));
  await context.close();
  const ok = results.filter((r) => r.status === 'fulfilled').map((r) => r.value);
  return { ok: ok.length, slowestMs: Math.max(...ok), failures: results.filter((r) => r.status === 'rejected').map((r) => r.reason.message) };
}

// Simulate mode in the browser's engine, its numbers against the command line's (--native).
async function simulated(page, mobile, tag) {
  if (!native || !existsSync(native)) { console.log(`${tag}: Simulate mode not checked (no --native program)`); return; }
  const openExample = async (p, m, name) => {
    await click(p, m, '[data-tab="gallery"]');
    const before = await p.evaluate(() => +(document.body.dataset.opened ?? 0));
    await click(p, m, `[data-example="${name}"]`);
    await p.waitForFunction((n) => +(document.body.dataset.opened ?? 0) > n && !document.body.dataset.busy, before);
  };
  const reference = simulate.cliSimulation(native, examples);
  const referenceText = (format) => simulate.cliSimulationText(native, examples, format);
  // The engine in WebAssembly against the native program: the downloads' numbers compared, not their bytes.
  const seen = await simulate.run(page, { mobile, tag, shot: (p, name) => shot(p, name), click, openExample, reference: () => reference, referenceText, exact: false });
  console.log(`${tag}: simulated in the browser, crank at t = 3 s ${seen.crank} deg (the CLI's)`);
}

let failed = false;
try {
  for (const [tag, viewport, mobile] of [['phone', { width: 390, height: 844 }, true], ['desktop', { width: 1366, height: 768 }, false]]) {
    const { context, page, firstAnalysisMs } = await open(tag, viewport, mobile);
    await opened(page, tag);
    if (onlySimulate) {
      await simulated(page, mobile, tag);
      await context.close();
      continue;
    }
    await badModel(page, mobile, tag);
    const sizes = await downloads(page, mobile, tag);
    const progress = await synthesisProgressAndCancel(page, mobile, tag);
    await offline(context, page, mobile, tag);
    await simulated(page, mobile, tag);
    console.log(`${tag}: first analysis ${firstAnalysisMs} ms after opening; downloads (bytes) ${JSON.stringify(sizes)}; progress "${progress}"`);
    await context.close();
  }
  if (!onlySimulate) {
    console.log(`no engine: "${await engineMissing()}"`);
    console.log(`no app.js: "${await appFileMissing()}"`);
  }
  if (pages > 0 && !onlySimulate) {
    const many = await manyAtOnce(pages);
    console.log(`${pages} pages at once: ${many.ok} analysed, the slowest after ${many.slowestMs} ms`);
    assert.equal(many.ok, pages, many.failures.join('\n'));
  }
  assert.deepEqual(blocked, [], 'no request to /api');
  assert.deepEqual(log.filter((l) => /"(GET|POST) \/api/.test(l)), [], 'no /api request reached the server');
  assert.deepEqual(errors, []);
  console.log(`OK: the static site works with no server; screenshots in ${out}`);
} catch (e) {
  failed = true;
  console.error('FAIL:', e);
  if (errors.length) console.error(errors.join('\n'));
} finally {
  clearTimeout(timer);
  await browser.close();
  stop();
}
process.exit(failed ? 1 : 0);
