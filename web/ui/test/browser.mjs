// Browser test of the web app: starts `nbar serve` on a free port of 127.0.0.1, drives Debian's
// Chromium (never a downloaded one) through playwright-core at a desktop and a phone viewport,
// and saves screenshots. Exit 77 (ctest's SKIP_RETURN_CODE) when playwright-core, Chromium or
// the built web app is missing.
//   node web/ui/test/browser.mjs --nbar build/apps/nbar/nbar --out build/web-screenshots [--only draw|review]
import { spawnSync } from 'node:child_process';
import { mkdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import assert from 'node:assert/strict';
import { SKIP, arg, launchChromium, startServer, watchdog as startWatchdog } from './harness.mjs';
import { run as runEditing } from './edit.mjs';
import * as motion from './motion.mjs';
import * as files from './files.mjs';
import * as draw from './draw.mjs';
import * as review from './review.mjs';
import * as build from './build.mjs';
import * as femap from './femap.mjs';
import * as simulate from './simulate.mjs';
import * as forces from './forces.mjs';
import * as spanish from './spanish.mjs';
import * as newuser from './newuser.mjs';

const nbar = arg('--nbar', 'build/apps/nbar/nbar');
const out = arg('--out', 'build/web-screenshots');
// `--only draw`: only the comparison of the drawing with nbar draw's, at both viewports;
// `--only review`: only review.mjs's checks (status, share, stale results, retries), at both;
// `--only femap`: only femap.mjs's (the FE stress map's read-out against the CLI), at both;
// `--only simulate`: only simulate.mjs's (Simulate mode against `nbar simulate`), at both;
// `--only forces`: only forces.mjs's (dynamics columns, stress table, Explain at the pose, handles
// over arrows, a drag at a later pose, zoom, the phone's bottom edge), at both: ctest's
// Web.Forces, apart from the full run so that Web.Browser stays inside its watchdog;
// `--only build`: build.mjs's (a slider-crank built from an empty model by taps), at both: ctest's
// Web.BrowserBuild, apart from the full run as Web.Forces is;
// `--only spanish`: only spanish.mjs's (the core's messages in the catalogue, no English in Español), at both: ctest's
// Web.Spanish, apart from the full run as Web.Forces is;
// `--only newuser`: newuser.mjs's (issue 39's whole new-user run: the lab slider-crank built by
// taps, its peak slider speed and stress peak read by touch, then all again in Spanish), at both:
// ctest's Web.NewUser.
const only = arg('--only', '');
const onlyDraw = only === 'draw';
const onlyReview = only === 'review';
const onlyFemap = only === 'femap';
const onlySimulate = only === 'simulate';
const onlyForces = only === 'forces';
const onlyBuild = only === 'build';
const onlySpanish = only === 'spanish';
const onlyNewUser = only === 'newuser';
const examples = arg('--examples', '../../examples');

const browser = await launchChromium();
mkdirSync(out, { recursive: true });
const { base, stop } = await startServer(nbar);
const watchdog = startWatchdog(420000, stop);

const index = await (await fetch(base)).text();
if (!index.includes('app.js')) { console.log('SKIP: this nbar carries the placeholder page, not the web app'); stop(); await browser.close(); process.exit(SKIP); }

const errors = [];
let failed = false;

async function open(name, viewport, mobile, options = {}) {
  const context = await browser.newContext({
    viewport, hasTouch: mobile, isMobile: mobile, deviceScaleFactor: mobile ? 2 : 1, acceptDownloads: true, locale: 'en-US', ...options,
  });
  const page = await context.newPage();
  page.on('pageerror', (e) => errors.push(`${name}: ${e.message}`));
  // The API's 4xx answers (the model errors the test makes, and the tolerance simulate.mjs has
  // refused) and the refused connections of a server made to vanish (review.mjs) are logged by
  // Chromium: not errors.
  page.on('console', (m) => {
    if (m.type() === 'error' && !/Failed to load resource: (.* (400|422|503)|net::ERR_CONNECTION_REFUSED)/.test(m.text())) errors.push(`${name}: console: ${m.text()}`);
  });
  page.setDefaultTimeout(20000);
  await page.goto(base);
  await page.waitForSelector('body[data-ready="1"]');
  return { context, page };
}

const shot = (page, name, fullPage = false) => page.screenshot({ path: join(out, `${name}.png`), fullPage });
const click = (page, mobile, selector) => (mobile ? page.locator(selector).first().tap() : page.locator(selector).first().click());
const bodies = (page) => page.locator('#drawing svg .body').count();

// Waits until a model opened after `opened` others is analysed and drawn: the title alone is no
// sign, when the model opened is the one on screen (perhaps edited), whose late answer would
// then redraw the drawing in the middle of the next step.
async function analysedAfter(page, opened) {
  await page.waitForFunction((n) => +(document.body.dataset.opened ?? 0) > n && !document.body.dataset.busy, opened);
}

async function openExample(page, mobile, name) {
  const title = (await page.locator(`[data-example="${name}"] b`).textContent()).trim();
  await click(page, mobile, '[data-tab="gallery"]');
  const opened = await page.evaluate(() => +(document.body.dataset.opened ?? 0));
  await click(page, mobile, `[data-example="${name}"]`);
  await analysedAfter(page, opened);
  assert.equal(await page.locator('#model-name').textContent(), title);
  assert.ok(await bodies(page) > 0, `${name}: the drawing has bodies`);
  return title;
}

// Replaces the text `from` of the editor's line holding `line` by `to`, typed as a user would:
// the cursor put at the line's start, moved right, the text selected and typed over.
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

async function errorInEditor(page, mobile, tag) {
  await openExample(page, mobile, 'fourbar-crank-rocker');
  await click(page, mobile, '[data-tab="editor"]');
  await retype(page, mobile, 'crank:   [O2, A]', 'A]', 'Q]');
  await page.waitForSelector('.cm-lintRange-error');
  const problem = await page.locator('#problems').textContent();
  assert.match(problem, /line 16, column 17: unknown point 'Q'/);
  assert.equal(await page.locator('.cm-lintRange-error').first().textContent(), 'Q');
  await shot(page, `${tag}-3-error`);
  await retype(page, mobile, 'crank:   [O2, Q]', 'Q]', 'A]');
  await page.waitForFunction(() => document.querySelector('#problems').textContent === 'No errors.');
  assert.equal(await page.locator('.cm-lintRange-error').count(), 0);
}

// On a phone a stop's warning is read whole (it was cut at a few lines, in a box that scrolled
// with no sign of it), and the tab bar shows it scrolls sideways: its cut side fades out.
async function phoneFits(page) {
  await openExample(page, true, 'fourbar-crank-rocker');
  await click(page, true, '[data-tab="editor"]');
  await retype(page, true, 'lengths: {crank: 80', '80', '140');
  await page.waitForSelector('#warnings li.stop');
  await page.waitForFunction(() => !document.body.dataset.busy);
  await page.locator('#warnings').scrollIntoViewIfNeeded();
  const box = await page.evaluate(() => {
    const w = document.querySelector('#warnings');
    const r = w.getBoundingClientRect();
    return { left: r.left, right: r.right, height: r.height, scroll: w.scrollHeight, client: w.clientHeight, vw: innerWidth, vh: innerHeight };
  });
  assert.ok(box.left >= 0 && box.right <= box.vw, `the warnings within the screen's width: ${box.left} to ${box.right} of ${box.vw}`);
  assert.ok(box.scroll <= box.client + 1, `the stop's message shown whole: ${box.scroll} px of it in ${box.client} px`);
  assert.ok(box.height <= box.vh / 2, `the warnings take at most half the screen: ${box.height} px`);
  await shot(page, 'phone-2a-warnings');
  const bar = page.locator('.side .tabs');
  const classes = () => bar.evaluate((b) => [...b.classList].filter((c) => c.startsWith('more-')).join(' '));
  await bar.scrollIntoViewIfNeeded();
  await bar.evaluate((b) => { b.scrollLeft = 0; });
  await page.waitForFunction(() => document.querySelector('.side .tabs').scrollLeft === 0);
  assert.ok(await bar.evaluate((b) => b.scrollWidth > b.clientWidth), 'the tabs are wider than the phone');
  await page.waitForFunction(() => document.querySelector('.side .tabs').classList.contains('more-right'));
  assert.equal(await classes(), 'more-right');
  assert.notEqual(await bar.evaluate((b) => getComputedStyle(b).maskImage || getComputedStyle(b).webkitMaskImage), 'none', 'the cut side fades');
  await shot(page, 'phone-2b-tabs');
  await bar.evaluate((b) => { b.scrollLeft = b.scrollWidth; });
  await page.waitForFunction(() => document.querySelector('.side .tabs').classList.contains('more-left'));
  assert.equal(await classes(), 'more-left');
  // A tab chosen (here without the test's own scrolling to it) is brought into the bar's view.
  await page.locator('[data-tab="gallery"]').dispatchEvent('click');
  const seen = await page.evaluate(() => {
    const b = document.querySelector('[data-tab="gallery"]').getBoundingClientRect();
    const r = document.querySelector('.side .tabs').getBoundingClientRect();
    return b.left >= r.left - 1 && b.right <= r.right + 1;
  });
  assert.ok(seen, 'the tab shown is in view');
  await click(page, true, '[data-tab="editor"]');
  await retype(page, true, 'lengths: {crank: 140', '140', '80');
  await page.waitForFunction(() => !document.querySelector('#warnings li') && !document.body.dataset.busy);
}

async function synthesis(page, mobile, tag) {
  await click(page, mobile, '[data-tab="synthesis"]');
  assert.match(await page.locator('#task').inputValue(), /task: five-point/);
  await click(page, mobile, '#synth-run');
  await page.waitForSelector('[data-design]', { timeout: 60000 });
  const n = await page.locator('[data-design]').count();
  assert.ok(n >= 1, 'at least one design');
  assert.match(await page.locator('#synth-status').textContent(), /^\d+ designs? \(36 solutions\)$/);
  await shot(page, `${tag}-5-synthesis`);
  await click(page, mobile, '[data-design="1"]');
  await page.waitForFunction(() => / design 1$/.test(document.querySelector('#model-name').textContent));
  await page.waitForSelector('#drawing svg .body');
  assert.match(await page.locator('#status').textContent(), /1 DOF · 361 samples$/);
  await shot(page, `${tag}-6-design`);
}

// review.mjs's checks in a page of their own at a viewport, without the service worker: the
// requests it makes for the page would pass by the test's page.route() (a busy server faked).
async function reviewAt(tag, viewport, mobile) {
  const { context, page } = await open(tag, viewport, mobile, { serviceWorkers: 'block' });
  await review.run(page, { mobile, tag, shot, click, openExample, retype });
  await context.close();
}

// The FE stress map's read-out (femap.mjs) at a laptop's and a phone's viewport.
async function femapAt(tag, viewport, mobile) {
  const { context, page } = await open(tag, viewport, mobile);
  await femap.run(page, { mobile, tag, base, nbar, shot, click, openExample });
  await context.close();
}

// A slider-crank built from an empty model by taps alone (build.mjs) at a laptop's and a phone's
// viewport.
async function buildAt(tag, viewport, mobile) {
  const { context, page } = await open(tag, viewport, mobile);
  await build.run(page, { mobile, tag, shot, click, openExample });
  await context.close();
}

// Simulate mode (simulate.mjs) at a laptop's and a phone's viewport, against the command line.
async function simulateAt(tag, viewport, mobile) {
  const { context, page } = await open(tag, viewport, mobile);
  const reference = simulate.cliSimulation(nbar, examples);
  const referenceText = (format) => simulate.cliSimulationText(nbar, examples, format);
  // The server is the same build as the command line: its downloads are byte for byte the CLI's.
  const seen = await simulate.run(page, { mobile, tag, shot, click, openExample, reference: () => reference, referenceText, exact: true });
  console.log(`${tag}: simulated crank at t = 3 s ${seen.crank} deg (the CLI's), played to row ${seen.played}, cancelled at t = ${seen.cancelledAt} s with its rows kept`);
  await context.close();
}

// Motion and forces (forces.mjs) at a laptop's and a phone's viewport, against the command line.
async function forcesAt(tag, viewport, mobile) {
  const { context, page } = await open(tag, viewport, mobile);
  await forces.run(page, { mobile, tag, base, nbar, shot, click, openExample, retype });
  await context.close();
}

// The app in Spanish (spanish.mjs): the catalogue against the core's messages, then no English
// on screen at a laptop's and a phone's viewport.
async function spanishAt(tag, viewport, mobile) {
  const { context, page } = await open(tag, viewport, mobile);
  await spanish.run(page, { mobile, tag, base, shot, click, retype });
  await context.close();
}

// Issue 39's new-user run (newuser.mjs) at a laptop's and a phone's viewport, against the CLI.
async function newUserAt(tag, viewport, mobile) {
  const { context, page } = await open(tag, viewport, mobile);
  await newuser.run(page, { mobile, tag, nbar, examples, shot, click });
  await context.close();
}

async function desktop() {
  const { context, page } = await open('desktop', { width: 1280, height: 800 }, false);
  assert.ok(await page.locator('[data-example]').count() >= 10, 'the gallery lists the examples');
  assert.equal(await page.locator('.side .tabs.more-left, .side .tabs.more-right').count(), 0, 'the tabs fit: no fade');
  await shot(page, 'desktop-1-gallery');
  await draw.run(page, { mobile: false, tag: 'desktop', base, out, shot, click, openExample });
  if (onlyDraw) { await context.close(); return; }

  // A model from the gallery, drawn and animated.
  await openExample(page, false, 'slider-crank-offset');
  assert.equal(await page.locator('#drawing svg g[data-link="slider"] > polygon.body').count(), 1, 'the slider block is drawn');
  assert.equal(await page.locator('#drawing svg .guide').count(), 1, 'the slider guide is drawn');
  await openExample(page, false, 'fourbar-crank-rocker');
  assert.equal(await page.locator('#scrub').inputValue(), '0');
  const before = await page.locator('#drawing svg .frame').innerHTML();
  await page.click('#play');
  await page.waitForTimeout(800);
  await page.click('#play');
  assert.ok(+(await page.locator('#scrub').inputValue()) > 0, 'the animation moved the slider');
  assert.notEqual(await page.locator('#drawing svg .frame').innerHTML(), before, 'the animation moved the mechanism');
  await page.locator('#scrub').fill('60');
  assert.match(await page.locator('#readout').textContent(), /^crank = 60 deg$/);

  // Clicking the plot poses the mechanism at that sample; a hover read-out in the legend.
  await page.selectOption('#ycol', 'coupler.omega');
  await page.locator('#plot .u-over').scrollIntoViewIfNeeded();
  const plot = await page.locator('#plot .u-over').boundingBox();
  await page.mouse.move(plot.x + plot.width * 0.75, plot.y + plot.height / 2);
  await page.mouse.down(); await page.mouse.up();
  const pose = +(await page.locator('#scrub').inputValue());
  assert.ok(pose > 240 && pose < 300, `plot click at 3/4 poses near sample 270, not ${pose}`);
  assert.match(await page.locator('.u-legend').textContent(), /coupler\.omega/);
  await shot(page, 'desktop-2-model');
  await click(page, false, '[data-tab="editor"]');
  await shot(page, 'desktop-app');  // the README's picture, docs/images/web-desktop.png

  await errorInEditor(page, false, 'desktop');

  // A number changed in the editor changes the table.
  await click(page, false, '[data-rtab="table"]');
  const cell = () => page.locator('#table tbody tr').first().locator('td').last().textContent();
  assert.equal(await cell(), '121.23');
  await retype(page, false, 'P:  [77.81169, 121.227931]', '121.227931]', '150]');
  await page.waitForFunction(() => document.querySelector('#table tbody tr td:last-child')?.textContent === '150');
  await shot(page, 'desktop-4-table');

  // The model in the link opens the same model elsewhere.
  const link = page.url();
  assert.match(link, /#m=[A-Za-z0-9_-]+(&[^#]*)?$/);  // the model, and what is on screen (review.mjs shareView)
  const other = await context.newPage();
  await other.goto(link);
  await other.waitForSelector('body[data-ready="1"]');
  assert.match(await other.locator('.cm-content').textContent(), /P: {2}\[77\.81169, 150\]/);
  await other.close();

  // A point dragged in the drawing moves in the model and the numbers follow. Grabbed at sample
  // 180, P does not move: the drawing goes back to sample 0 (forces.mjs checks what is said), where
  // it is dragged.
  await page.locator('#scrub').fill('180');
  const at180 = await page.locator('#drawing circle.pt[data-point="P"]').boundingBox();
  await page.mouse.click(at180.x + at180.width / 2, at180.y + at180.height / 2);
  assert.equal(await page.locator('#scrub').inputValue(), '0');
  const p = await page.locator('#drawing circle.pt[data-point="P"]').boundingBox();
  // Model units per pixel of the view the drag happens in (the new model's view may differ).
  const perPixel = await page.evaluate(() => 1 / document.querySelector('#drawing svg').getScreenCTM().a);
  await page.mouse.move(p.x + p.width / 2, p.y + p.height / 2);
  await page.mouse.down();
  const coupler = () => page.locator('#drawing g[data-link="coupler"] > .body').getAttribute('points');
  const couplerBefore = await coupler();
  await page.mouse.move(p.x + p.width / 2 + 40, p.y + p.height / 2 + 20, { steps: 5 });
  // While the finger is down, the server's drawing of the edited model follows it.
  await page.waitForFunction((b) => document.querySelector('#drawing g[data-link="coupler"] > .body')?.getAttribute('points') !== b, couplerBefore);
  await shot(page, 'desktop-4a-dragging');
  await page.mouse.up();
  await page.waitForFunction(() => document.querySelector('#table tbody tr td:nth-last-child(2)')?.textContent !== '77.8117');
  assert.equal(await page.locator('#scrub').inputValue(), '0');
  const moved = await page.locator('.cm-line', { hasText: '# coupler point' }).textContent();
  assert.match(moved, /^ {2}P: {2}\[\d+\.?\d*, \d+\.?\d*\]/);
  assert.doesNotMatch(moved, /77\.81169/);
  // P moved from its place at sample 0 (77.81169, 150) by the finger's 40 px right and 20 px down.
  const [px, py] = moved.match(/\[([-\d.]+), ([-\d.]+)\]/).slice(1).map(Number);
  assert.ok(Math.abs(px - (77.81169 + 40 * perPixel)) < 2 * perPixel, `P.x ${px}, ${perPixel} mm/px`);
  assert.ok(Math.abs(py - (150 - 20 * perPixel)) < 2 * perPixel, `P.y ${py}, ${perPixel} mm/px`);
  assert.equal(await page.locator('#problems').textContent(), 'No errors.');
  await shot(page, 'desktop-4b-dragged');

  await synthesis(page, false, 'desktop');

  // Downloads: the CSV built from the solve, and the server's SVG.
  await click(page, false, '[data-tab="downloads"]');
  const [csv] = await Promise.all([page.waitForEvent('download'), page.click('[data-download="csv"]')]);
  const csvText = readFileSync(await csv.path(), 'utf8').split('\n');
  assert.match(csvText[0], /^step,t,input,O2\.x,O2\.y/);  // the design opened: its model names the crank "input"
  assert.equal(csvText.filter(Boolean).length, 362);
  const [svg] = await Promise.all([page.waitForEvent('download'), page.click('[data-download="svg"]')]);
  assert.match(readFileSync(await svg.path(), 'utf8'), /<svg/);
  // The MP4, when the server has ffmpeg: an H.264 video of the 72 frames the button asks for.
  const health = await (await fetch(new URL('api/health', base))).json();
  if (health.mp4) {
    const [mp4] = await Promise.all([page.waitForEvent('download', { timeout: 60000 }), page.click('[data-download="mp4"]')]);
    assert.match(mp4.suggestedFilename(), /\.mp4$/);
    const file = await mp4.path();
    assert.equal(readFileSync(file).subarray(4, 8).toString('latin1'), 'ftyp', 'the download is an MP4 file');
    const probe = spawnSync('ffprobe', ['-v', 'error', '-count_frames', '-select_streams', 'v:0', '-show_entries',
      'stream=nb_read_frames,codec_name', '-of', 'csv=p=0', file], { encoding: 'utf8' });
    if (probe.status === 0) assert.equal(probe.stdout.trim(), 'h264,72', 'ffprobe: the MP4 has the 72 frames asked for');
  }
  await shot(page, 'desktop-7-downloads');

  // Spanish.
  await page.selectOption('#lang', 'es');
  assert.equal(await page.locator('[data-tab="gallery"]').textContent(), 'Galería');
  await page.selectOption('#lang', 'en');
  await runEditing(page, { base, out, viewport: 'desktop', mobile: false });
  await motion.run(page, { mobile: false, tag: 'desktop', base, context, shot, click, openExample, retype });
  await files.run(page, { mobile: false, tag: 'desktop', base, shot, click });
  // A model with plates: its cutting drawing is `nbar export --dxf`'s, arcs and holes included.
  await openExample(page, false, 'fourbar-rounded-crank');
  await click(page, false, '[data-tab="downloads"]');
  const [dxf] = await Promise.all([page.waitForEvent('download'), page.click('[data-download="plates-dxf"]')]);
  assert.match(dxf.suggestedFilename(), /-plates\.dxf$/);
  const dxfText = readFileSync(await dxf.path(), 'utf8');
  assert.match(dxfText, /^ {0,2}0\r?\nSECTION/);
  assert.match(dxfText, /\nCIRCLE\r?\n/, 'the pin holes are circles');
  await context.close();
}

async function phone() {
  const { context, page } = await open('phone', { width: 390, height: 844 }, true);
  assert.ok(await page.locator('[data-example]').count() >= 10);
  const width = await page.evaluate(() => document.documentElement.scrollWidth);
  assert.ok(width <= 390, `no sideways scrolling at 390 px (page is ${width} px wide)`);
  await shot(page, 'phone-1-gallery');
  await draw.run(page, { mobile: true, tag: 'phone', base, out, shot, click, openExample });
  if (onlyDraw) { await context.close(); return; }
  await openExample(page, true, 'five-bar');
  await page.locator('#play').tap();
  await page.waitForTimeout(600);
  await page.locator('#play').tap();
  assert.ok(+(await page.locator('#scrub').inputValue()) > 0);
  await shot(page, 'phone-2-model', true);
  await phoneFits(page);
  await errorInEditor(page, true, 'phone');
  await synthesis(page, true, 'phone');
  await runEditing(page, { base, out, viewport: 'phone', mobile: true });
  await motion.run(page, { mobile: true, tag: 'phone', base, context, shot, click, openExample, retype });
  await files.run(page, { mobile: true, tag: 'phone', base, shot, click });
  await context.close();
}

try {
  if (onlyReview) {
    await reviewAt('desktop', { width: 1280, height: 800 }, false);
    await reviewAt('phone', { width: 390, height: 844 }, true);
  } else if (onlyBuild) {
    await buildAt('laptop', { width: 1366, height: 768 }, false);
    await buildAt('phone', { width: 390, height: 844 }, true);
  } else if (onlySimulate) {
    await simulateAt('laptop', { width: 1366, height: 768 }, false);
    await simulateAt('phone', { width: 390, height: 844 }, true);
  } else if (onlyForces) {
    await forcesAt('laptop', { width: 1366, height: 768 }, false);
    await forcesAt('phone', { width: 390, height: 844 }, true);
  } else if (onlySpanish) {
    console.log(`the catalogue holds the Spanish of ${await spanish.checkCatalogue(base, examples)} core messages a student meets`);
    await spanishAt('laptop', { width: 1366, height: 768 }, false);
    await spanishAt('phone', { width: 390, height: 844 }, true);
  } else if (onlyNewUser) {
    await newUserAt('phone', { width: 390, height: 844 }, true);
    await newUserAt('laptop', { width: 1366, height: 768 }, false);
  } else if (onlyFemap) {
    await femapAt('laptop', { width: 1366, height: 768 }, false);
    await femapAt('phone', { width: 390, height: 844 }, true);
  } else {
    await desktop();
    await reviewAt('desktop', { width: 1280, height: 800 }, false);
    await phone();
    await reviewAt('phone', { width: 390, height: 844 }, true);
    await femapAt('laptop', { width: 1366, height: 768 }, false);
    await femapAt('phone', { width: 390, height: 844 }, true);
    await simulateAt('laptop', { width: 1366, height: 768 }, false);
    await simulateAt('phone', { width: 390, height: 844 }, true);
  }
  assert.deepEqual(errors, [], 'no errors in the page');
  console.log(`OK: screenshots in ${out}`);
} catch (e) {
  failed = true;
  console.error('FAIL:', e);
  if (errors.length) console.error(errors.join('\n'));
} finally {
  clearTimeout(watchdog);
  await browser.close();
  stop();
}
process.exit(failed ? 1 : 0);
