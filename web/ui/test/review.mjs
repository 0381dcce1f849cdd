// Browser checks from a student's use of the app on a phone (run by browser.mjs at each
// viewport): what happens is said where it is seen (the status line, under the header on a
// phone, with a busy mark); Share never claims a copy that did not happen; a failed analysis
// dims the drawing and plot it did not update and offers Retry when the server was busy; an
// overlay's failed request is tried again; the legend follows the language; an unclosed bracket
// is reported at the bracket; a Model-tab error marks the field edited, in view below the header.
import assert from 'node:assert/strict';

const busy = { status: 503, contentType: 'application/json',
  body: JSON.stringify({ error: { kind: 'too_many_jobs', message: 'the server is busy: try again in a moment' } }) };
const statusText = (page) => page.locator('#status').textContent();
const headerBottom = (page) => page.evaluate(() => document.querySelector('header.top').getBoundingClientRect().bottom);

// The status line is on screen (not hidden, inside the viewport, below nothing).
async function statusShown(page) {
  const box = await page.locator('#status').boundingBox();
  assert.ok(box && box.height > 0 && box.width > 40, `the status line is shown: ${JSON.stringify(box)}`);
  const vw = page.viewportSize().width;
  assert.ok(box.x >= 0 && box.x + box.width <= vw + 1 && box.y >= 0, `the status line is inside the viewport: ${JSON.stringify(box)}`);
}

// A busy server during an edit's analysis: stale drawing and plot, the reason, Retry.
async function staleAndRetry(page, ctx) {
  const { mobile, click } = ctx;
  await ctx.openExample(page, mobile, 'fourbar-crank-rocker');
  await click(page, mobile, '[data-tab="editor"]');
  await page.route('**/api/check', (route) => route.fulfill(busy));
  const drawingTop = () => page.evaluate(() => document.querySelector('#drawing').getBoundingClientRect().top + window.scrollY);
  const before = { top: await drawingTop(), header: await headerBottom(page) };
  await ctx.retype(page, mobile, 'O4: [200, 0]', '200', '210');
  await page.waitForSelector('#stale:not([hidden])');
  // The label and the longer status move nothing: the drawing stays under the finger.
  assert.equal(await drawingTop(), before.top, 'the drawing has not moved');
  assert.equal(await headerBottom(page), before.header, 'the header has not grown');
  assert.match(await page.locator('#stale').textContent(), /^Not updated: the server is busy: try again in a moment/);
  assert.ok(await page.locator('#stale button').isVisible(), 'Retry on the stage');
  assert.ok(await page.locator('#retry').isVisible(), 'Retry beside the status');
  assert.ok(await page.evaluate(() => document.body.classList.contains('results-stale')), 'the old drawing is dimmed');
  assert.match(await statusText(page), /^Failed: the server is busy/);
  await statusShown(page);
  await page.evaluate(() => window.scrollTo(0, 0));
  await ctx.shot(page, `${ctx.tag}-r1-stale`);
  await page.unroute('**/api/check');
  const opened = await page.evaluate(() => document.querySelector('#model-name').textContent);
  await click(page, mobile, '#stale button');
  await page.waitForSelector('#stale', { state: 'hidden' });
  assert.equal(await page.evaluate(() => document.body.classList.contains('results-stale')), false);
  assert.ok(await page.locator('#retry').isHidden());
  assert.equal(await page.locator('#model-name').textContent(), opened);
  assert.match(await statusText(page), /^1 DOF · \d+ samples$/);
  // A model error (not a busy server) is stale too, without Retry: at the bracket left open.
  await ctx.retype(page, mobile, 'O4: [210, 0]', '0]', '0');
  await page.waitForSelector('#stale:not([hidden])');
  assert.ok(await page.locator('#stale button').isHidden(), 'no Retry for a mistake in the model');
  assert.match(await page.locator('#problems').textContent(), /^line 10, column 7: invalid YAML: this '\[' is never closed by a '\]'/);
  await statusShown(page);
  await ctx.retype(page, mobile, 'O4: [210, 0 ', '0 ', '0] ');
  await page.waitForSelector('#stale', { state: 'hidden' });
}

// The analysing status carries a busy mark while the server works.
async function busyMark(page, ctx) {
  const { mobile } = ctx;
  let release;
  const held = new Promise((r) => { release = r; });
  await page.route('**/api/solve', async (route) => { await held; await route.continue(); });
  await ctx.retype(page, mobile, 'O4: [210, 0]', '210', '200');
  await page.waitForFunction(() => document.querySelector('#status').classList.contains('working'));
  assert.match(await statusText(page), /^Analysing/);
  await statusShown(page);
  await page.evaluate(() => window.scrollTo(0, 400));
  await ctx.shot(page, `${ctx.tag}-r0-busy`);
  release();
  await page.waitForFunction(() => !document.body.dataset.busy);
  await page.unroute('**/api/solve');
  assert.equal(await page.locator('#status.working').count(), 0);
}

// Share over http from another machine: no navigator.clipboard. With execCommand failing too,
// the link is shown to copy by hand; with it working, the copy is said.
async function share(page, ctx) {
  const { mobile, click } = ctx;
  await page.evaluate(() => {
    Object.defineProperty(navigator, 'clipboard', { value: undefined, configurable: true });
    document.execCommand = () => false;
  });
  await click(page, mobile, '#share');
  await page.waitForSelector('#share-box:not([hidden])');
  assert.notEqual(await statusText(page), 'Link copied');
  assert.equal(await page.locator('#share-box input').inputValue(), page.url());
  assert.match(page.url(), /#m=/);
  const box = await page.locator('#share-box').boundingBox();
  assert.ok(box.y >= (await headerBottom(page)) - 1, 'the link is below the header, not under it');
  await ctx.shot(page, `${ctx.tag}-r2-share-by-hand`);
  await click(page, mobile, '#share-box button');
  await page.waitForSelector('#share-box', { state: 'hidden' });
  await page.evaluate(() => { document.execCommand = (c) => c === 'copy'; });
  await page.evaluate(() => { document.querySelector('#status').textContent = ''; });
  await click(page, mobile, '#share');
  await page.waitForFunction(() => document.querySelector('#status').textContent !== '');
  assert.equal(await statusText(page), 'Link copied');
  assert.ok(await page.locator('#share-box').isHidden());
}

// The Stress overlay's request answered 503: the error is shown, and ticking the box again, or
// moving through the sweep a while later, asks again.
async function overlayRetry(page, ctx) {
  const { mobile, click } = ctx;
  await ctx.openExample(page, mobile, 'fourbar-steel-bars');
  await page.route('**/api/stress', (route) => route.fulfill(busy));
  await click(page, mobile, '[data-overlay="stress"]');
  await page.waitForSelector('[data-failed="stress"]');
  await page.unroute('**/api/stress');
  await click(page, mobile, '[data-overlay="stress"]');
  await click(page, mobile, '[data-overlay="stress"]');
  await page.waitForSelector('[data-legend="stress"]');
  await click(page, mobile, '[data-overlay="stress"]');
  // The joint forces, failed, then the slider moved after the pause between tries.
  await page.route('**/api/solve', (route) => (route.request().postData()?.includes('"dynamics":true') ? route.fulfill(busy) : route.continue()));
  await click(page, mobile, '[data-overlay="forces"]');
  await page.waitForSelector('[data-failed="forces"]');
  await page.unroute('**/api/solve');
  await page.waitForTimeout(3100);
  await page.locator('#scrub').fill('20');
  await page.waitForSelector('[data-legend="forces"]');
  await click(page, mobile, '[data-overlay="forces"]');
}

// The overlays' legend in the language chosen, at once.
async function legendLanguage(page, ctx) {
  const { mobile, click } = ctx;
  await click(page, mobile, '[data-overlay="velocity"]');
  await page.waitForSelector('[data-legend="velocity"]');
  assert.match(await page.locator('[data-legend="velocity"]').textContent(), /\(largest /);
  await page.selectOption('#lang', 'es');
  assert.match(await page.locator('[data-legend="velocity"]').textContent(), /\(máxima /);
  await page.selectOption('#lang', 'en');
  assert.match(await page.locator('[data-legend="velocity"]').textContent(), /\(largest /);
  await click(page, mobile, '[data-overlay="velocity"]');
}

// A length in the Model tab that cannot assemble: the field edited is marked with the message,
// in view below the sticky header.
async function modelTabError(page, ctx) {
  const { mobile, click } = ctx;
  await ctx.openExample(page, mobile, 'fourbar-crank-rocker');
  await click(page, mobile, '[data-tab="model"]');
  const cell = page.locator('#model-tables input.cell[data-path=\'["lengths","rocker"]\']');
  assert.equal(await cell.inputValue(), '150');
  await cell.fill('15');
  await cell.press('Enter');
  await page.waitForSelector('#model-tables input.cell.bad');
  await page.waitForFunction(() => !document.body.dataset.busy);
  const bad = page.locator('#model-tables input.cell.bad');
  assert.equal(await bad.getAttribute('data-path'), '["lengths","rocker"]');
  const box = await bad.boundingBox();
  const top = await headerBottom(page);
  assert.ok(box.y >= top, `the marked field (y ${box.y}) is below the header (${top})`);
  assert.ok(box.y + box.height <= page.viewportSize().height, `and on screen: ${JSON.stringify(box)}`);
  const note = await page.locator('#model-tables .cell-error').first().boundingBox();
  assert.ok(note.y + note.height <= page.viewportSize().height, `its message on screen too: ${JSON.stringify(note)}`);
  await ctx.shot(page, `${ctx.tag}-r3-model-error`);
  await page.locator('#model-tables input.cell.bad').fill('150');
  await page.locator('#model-tables input.cell.bad').press('Enter');
  await page.waitForFunction(() => !document.querySelector('#model-tables input.cell.bad') && !document.body.dataset.busy);
}

// A phone turned sideways: the drawing is short and wide (about 808 x 175), and the mechanism
// still takes a good part of its height (fixed margins once left it a third).
async function landscape(page, ctx) {
  await ctx.openExample(page, ctx.mobile, 'fourbar-crank-rocker');
  await page.setViewportSize({ width: 844, height: 390 });
  await page.waitForFunction(() => {
    const d = document.querySelector('#drawing').getBoundingClientRect();
    const boxes = [...document.querySelectorAll('#drawing svg .scene .body')].map((b) => b.getBoundingClientRect());
    const vb = document.querySelector('#drawing svg')?.viewBox.baseVal;
    // The scene drawn again for the new size (not the portrait one letterboxed).
    if (!boxes.length || d.width < 2 * d.height || !vb || Math.abs(vb.width / vb.height - d.width / d.height) > 0.1 * (d.width / d.height)) return false;
    const top = Math.min(...boxes.map((b) => b.top)); const bottom = Math.max(...boxes.map((b) => b.bottom));
    return (bottom - top) / d.height > 0.4;
  }, undefined, { timeout: 10000 });
  await page.locator('#drawing').scrollIntoViewIfNeeded();
  await ctx.shot(page, `${ctx.tag}-r4-landscape`);
  await page.setViewportSize({ width: 390, height: 844 });
}

// ctx: {mobile, tag, shot, click, openExample, retype}.
// The server gone while the network is up (navigator.onLine stays true): the header says Offline
// from the failed requests themselves; a gallery click says it failed at once rather than leave
// "Loading…" spinning; and when the server answers again, the edit is analysed and the example
// opened by themselves, without Retry.
async function serverGone(page, ctx) {
  const { mobile, click } = ctx;
  await ctx.openExample(page, mobile, 'fourbar-crank-rocker');
  await click(page, mobile, '[data-tab="editor"]');
  await page.route('**/api/**', (route) => route.abort('connectionrefused'));
  await ctx.retype(page, mobile, 'O4: [200, 0]', '200', '205');
  await page.waitForSelector('#offline:not([hidden])', { timeout: 5000 });
  assert.equal(await page.evaluate(() => navigator.onLine), true, 'the browser itself is online');
  await page.waitForSelector('#stale:not([hidden])');
  await page.evaluate(() => window.scrollTo(0, 0));
  await ctx.shot(page, `${ctx.tag}-r7-server-gone`);
  await click(page, mobile, '[data-tab="gallery"]');
  const started = Date.now();
  await click(page, mobile, '[data-example="five-bar"]');
  await page.waitForFunction(() => /^Failed: /.test(document.querySelector('#status').textContent) &&
    !document.querySelector('#status').classList.contains('working'), null, { timeout: 5000 });
  assert.ok(Date.now() - started < 5000, 'no spinner left running');
  // Back: the example asked for opens by itself (the probe asks /api/health every 3 s).
  await page.unroute('**/api/**');
  await page.waitForSelector('#offline', { state: 'hidden', timeout: 10000 });
  await page.waitForFunction(() => /^Five-bar/.test(document.querySelector('#model-name').textContent) &&
    !document.body.dataset.busy && document.querySelector('#stale').hidden, null, { timeout: 10000 });
  // Gone during an edit only: the edit is analysed by itself once the server is back.
  await click(page, mobile, '[data-tab="editor"]');
  await page.route('**/api/**', (route) => route.abort('connectionrefused'));
  await ctx.retype(page, mobile, 'name: "Five-bar linkage', '(2 DOF)', '(two)');
  await page.waitForSelector('#stale:not([hidden])');
  await page.unroute('**/api/**');
  await page.waitForSelector('#stale', { state: 'hidden', timeout: 10000 });
  assert.ok(await page.locator('#offline').isHidden());
  assert.match(await page.locator('#model-name').textContent(), /\(two\)/);
}

// Touch first: at a phone's width every control on every tab is at least 44 x 44 CSS px to the
// finger (a check box counts with its label), and a point of the drawing is grabbed 20 px from
// its centre in every direction (its look is smaller; its hit area is not).
async function touchTargets(page, ctx) {
  const { click } = ctx;
  await ctx.openExample(page, true, 'fourbar-crank-rocker');
  const small = [];
  for (const tab of ['gallery', 'editor', 'model', 'synthesis', 'downloads', 'explain']) {
    await click(page, true, `[data-tab="${tab}"]`);
    small.push(...await page.evaluate((tabName) => {
      const out = [];
      const seen = new Set();
      for (const el of document.querySelectorAll('button, [role=tab], input, select, summary, label')) {
        const target = el.closest('label') ?? el;
        if (seen.has(target) || target.closest('.cm-editor')) continue;
        seen.add(target);
        const r = target.getBoundingClientRect();
        if (r.width === 0 || r.height === 0 || getComputedStyle(target).visibility === 'hidden') continue;
        const name = (target.textContent || target.getAttribute('aria-label') || target.id || target.tagName).trim().slice(0, 24);
        if (r.width < 44 || r.height < 44) out.push(`${tabName}: ${name} ${Math.round(r.width)}x${Math.round(r.height)}`);
      }
      return out;
    }, tab));
  }
  assert.deepEqual([...new Set(small)], [], 'every control at least 44 x 44 px');
  await page.evaluate(() => document.querySelector('#drawing').scrollIntoView({ block: 'center' }));
  const missed = await page.evaluate(() => {
    const out = [];
    for (const c of document.querySelectorAll('#drawing circle.hit[data-point]')) {
      const r = c.getBoundingClientRect();
      const x = r.left + r.width / 2; const y = r.top + r.height / 2;
      for (const [dx, dy] of [[20, 0], [-20, 0], [0, 20], [0, -20]]) {
        const hit = document.elementFromPoint(x + dx, y + dy)?.closest('[data-point]');
        if (hit?.dataset.point !== c.dataset.point) {
          const other = document.elementFromPoint(x + dx, y + dy);
          out.push(`${c.dataset.point} at (${dx}, ${dy}): ${other?.tagName ?? 'nothing'}.${other?.getAttribute('class') ?? ''}`);
        }
      }
    }
    return out;
  });
  assert.deepEqual(missed, [], 'every point grabbed 20 px from its centre');
}

// A tap on the plot on a phone poses the mechanism at that sample and the legend reads its
// values (uPlot's cursor follows only a mouse: it read "–").
async function plotTouch(page, ctx) {
  await ctx.openExample(page, true, 'fourbar-crank-rocker');
  await ctx.click(page, true, '[data-rtab="plot"]');
  const over = page.locator('#plot .u-over');
  await over.scrollIntoViewIfNeeded();
  const box = await over.boundingBox();
  await over.tap({ position: { x: box.width * 0.25, y: box.height / 2 } });
  const values = await page.locator('#plot .u-legend .u-value').allTextContents();
  assert.equal(values.length, 2);
  for (const v of values) assert.match(v, /^-?\d/, `the legend reads a number: ${values}`);
  const step = +(await page.locator('#scrub').inputValue());
  // 25 % along the crank's 0-360 deg axis: about sample 90 of 361.
  assert.ok(Math.abs(step - 90) <= 12, `posed at sample ${step}`);
  assert.equal(Number(values[0]), Number((await page.locator('#readout').textContent()).match(/= (-?[\d.]+)/)[1]));
  await ctx.shot(page, `${ctx.tag}-r8-plot-touch`);
}

// A shared link opens what was on screen: the model, and the overlays ticked, the point traced,
// the column plotted and the sample shown (the link kept only the model).
async function shareView(page, ctx) {
  const { mobile, click } = ctx;
  await ctx.openExample(page, mobile, 'fourbar-crank-rocker');
  await click(page, mobile, '[data-overlay="traces"]');
  await click(page, mobile, '[data-overlay="velocity"]');
  await page.selectOption('#ycol', 'coupler.angle');
  await page.locator('#scrub').fill('100');
  await page.evaluate(() => { document.execCommand = (c) => c === 'copy'; });
  await click(page, mobile, '#share');
  await page.waitForFunction(() => document.querySelector('#status').textContent === 'Link copied');
  const link = page.url();
  assert.match(link, /#m=[^&]+&o=traces%2Cvelocity&t=P&y=coupler.angle&f=100$/);
  const other = await page.context().newPage();
  await other.goto(link);
  await other.waitForSelector('body[data-ready="1"]');
  await other.waitForFunction(() => document.querySelector('#scrub').value === '100');
  assert.equal(await other.locator('[data-overlay="traces"]').isChecked(), true);
  assert.equal(await other.locator('[data-overlay="velocity"]').isChecked(), true);
  assert.equal(await other.locator('[data-overlay="stress"]').isChecked(), false);
  assert.equal(await other.locator('#ycol').inputValue(), 'coupler.angle');
  await other.waitForSelector('#drawing polyline[data-traced="P"]', { state: 'attached' });
  await other.close();
  for (const k of ['traces', 'velocity']) await click(page, mobile, `[data-overlay="${k}"]`);
}

// Downloads are named after the example opened until the model is renamed in the editor, then
// after the model on screen (they kept the first example's name).
async function downloadNames(page, ctx) {
  const { mobile, click } = ctx;
  await ctx.openExample(page, mobile, 'fourbar-crank-rocker');
  const fileName = async () => {
    await click(page, mobile, '[data-tab="downloads"]');
    const [file] = await Promise.all([page.waitForEvent('download'), click(page, mobile, '[data-download="json"]')]);
    return file.suggestedFilename();
  };
  assert.equal(await fileName(), 'fourbar-crank-rocker.json');
  await click(page, mobile, '[data-tab="editor"]');
  const opened = await page.evaluate(() => +document.body.dataset.opened);
  await ctx.retype(page, mobile, 'name: "Crank-rocker four-bar"', 'Crank-rocker four-bar', 'My press');
  await page.waitForFunction(() => document.querySelector('#model-name').textContent === 'My press' && !document.body.dataset.busy);
  assert.equal(await page.evaluate(() => +document.body.dataset.opened), opened);
  assert.equal(await fileName(), 'my-press.json');
}

export async function run(page, ctx) {
  await staleAndRetry(page, ctx);
  await busyMark(page, ctx);
  await share(page, ctx);
  await shareView(page, ctx);
  await downloadNames(page, ctx);
  await overlayRetry(page, ctx);
  await legendLanguage(page, ctx);
  await modelTabError(page, ctx);
  await serverGone(page, ctx);
  if (ctx.mobile) await landscape(page, ctx);
  if (ctx.mobile) await touchTargets(page, ctx);
  if (ctx.mobile) await plotTouch(page, ctx);
}
