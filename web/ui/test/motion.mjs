// Browser checks of the synthesis forms, the motion overlays, the step-by-step panel and offline
// use (synthesis.js, overlays.js, explain.js, sw.js), run by browser.mjs at a desktop and a
// phone viewport: run(page, ctx) with ctx = {mobile, tag, base, context, shot, click,
// openExample, retype}. Numbers are checked against the server's own answers.
import assert from 'node:assert/strict';

async function post(base, path, body) {
  const r = await fetch(new URL(path, base), { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(body) });
  assert.ok(r.ok, `${path}: ${r.status}`);
  return r.json();
}
const example = async (base, name) => (await fetch(new URL(`api/examples/${name}`, base))).text();
const fmt = (v) => String(+v.toFixed(Math.abs(v) >= 100 ? 2 : 4));

async function tapAt(page, mobile, x, y) {
  if (mobile) await page.touchscreen.tap(x, y); else await page.mouse.click(x, y);
}

// Five points tapped on the drawing, on the coupler curve of the crank-rocker on screen (the
// positions of its point P at five samples); the synthesis with the task's pivots, which are the
// crank-rocker's, must find designs; one is previewed, then opened from the server's model.
// Taps P at five samples on the drawing; returns where P was drawn at each.
async function tapFivePoints(page, mobile) {
  const wanted = [];
  for (const frame of [270, 330, 30, 100, 170]) {
    await page.locator('#scrub').fill(String(frame));
    // The drawing is at the top of the page on a phone: in full view, not under the sticky header.
    if (mobile) {
      await page.evaluate(() => window.scrollTo({ top: 0, left: 0, behavior: 'instant' }));
      await page.waitForFunction(() => window.scrollY === 0);
    }
    const c = page.locator('#drawing circle.pt[data-point="P"]');
    wanted.push([+(await c.getAttribute('cx')), -(await c.getAttribute('cy'))]);
    const b = await c.boundingBox();
    await tapAt(page, mobile, b.x + b.width / 2, b.y + b.height / 2);
    // The tap is taken (marked on the drawing) before the next sample is shown.
    await page.waitForFunction((n) => document.querySelectorAll('#drawing .synth-marks .target').length >= n, wanted.length);
  }
  return wanted;
}

async function fivePointByTapping(page, ctx) {
  const { mobile, click } = ctx;
  await ctx.openExample(page, mobile, 'fourbar-crank-rocker');
  await click(page, mobile, '[data-tab="synthesis"]');
  await page.waitForFunction(() => /task: five-point/.test(document.querySelector('#task').value));
  await page.selectOption('#synth-method', 'five-point');
  // The drawing stays as it is while the points are tapped: openExample waited for the model's
  // analysis, so no late answer redraws it with another view.
  const view = () => page.evaluate(() => document.querySelector('#drawing svg')?.getAttribute('viewBox'));
  await click(page, mobile, '#five-tap');
  await page.locator('#drawing').scrollIntoViewIfNeeded();
  const start = await view();
  const wanted = await tapFivePoints(page, mobile);
  assert.equal(await view(), start, "the drawing's view did not change while the points were tapped");
  const task = await page.locator('#task').inputValue();
  const got = [...task.split('points:')[1].matchAll(/\[([-\d.]+), ([-\d.]+)\]/g)].map((m) => [+m[1], +m[2]]);
  assert.equal(got.length, 5, `five tapped points in the task:\n${task}`);
  const scale = mobile ? 3 : 2;  // mm per pixel, about: the taps land within a pixel or two
  got.forEach(([x, y], i) => assert.ok(Math.hypot(x - wanted[i][0], y - wanted[i][1]) < scale, `tap ${i + 1}: ${x},${y} vs ${wanted[i]}`));

  await click(page, mobile, '#synth-run');
  await page.waitForSelector('[data-design="1"]:not([disabled])', { timeout: 60000 });
  assert.match(await page.locator('#synth-status').textContent(), /^\d+ designs? \(36 solutions\)/);
  await click(page, mobile, '[data-preview="1"]');
  await page.waitForSelector('.designs .pv svg .body');
  assert.equal(await page.locator('.designs .pv svg .target').count(), 5, 'the five targets on the preview');
  const f0 = await page.locator('.designs li.previewing .pv').getAttribute('data-frame');
  await page.waitForFunction((f) => document.querySelector('.designs li.previewing .pv')?.dataset.frame !== f, f0);
  await page.locator('.designs li.previewing').scrollIntoViewIfNeeded();
  await ctx.shot(page, `${ctx.tag}-m1-five-point-preview`);
  await click(page, mobile, '[data-design="1"]');
  await page.waitForFunction(() => /design 1$/.test(document.querySelector('#model-name').textContent));
  // The model is the core's design file (nbar synth --export), not one written by the browser.
  assert.match(await page.locator('.cm-content').textContent(), /# Design 1 of nbar synth five-point task/);
  // Its downloads are named after the design on screen, not the example opened before it.
  if (!mobile) {
    await click(page, mobile, '[data-tab="downloads"]');
    const [file] = await Promise.all([page.waitForEvent('download'), page.click('[data-download="model"]')]);
    assert.equal(file.suggestedFilename(), 'five-point-design-1.yaml');
  }
}

async function burmesterAndFunction(page, ctx) {
  const { mobile, click } = ctx;
  await click(page, mobile, '[data-tab="synthesis"]');
  await page.selectOption('#synth-method', 'burmester');
  assert.equal(await page.locator('#poses tr').count(), 3);
  await click(page, mobile, '#synth-run');
  await page.waitForSelector('[data-design="1"]:not([disabled])', { timeout: 60000 });
  // The three poses of the crank-rocker with its pivots: that crank-rocker, frame 200 mm.
  assert.match(await page.locator('.designs li').first().textContent(), /crank-rocker/);
  await ctx.shot(page, `${ctx.tag}-m2-burmester`);
  await page.selectOption('#synth-method', 'function');
  // Burmester's designs go with its method: they stayed listed under the function form.
  assert.equal(await page.locator('#designs li').count(), 0, "the other method's designs are cleared");
  assert.equal(await page.locator('#synth-status').textContent(), '');
  await page.locator('#fn-expr').fill('x^2');
  await click(page, mobile, '#synth-run');
  await page.waitForSelector('[data-design="1"]:not([disabled])', { timeout: 60000 });
  // Three precision points: one solution, said in the singular (it said "1 solutions").
  assert.match(await page.locator('#synth-status').textContent(), /^1 design \(1 solution\)( · |$)/);
  await ctx.shot(page, `${ctx.tag}-m3-function`);
  // An error in f(x) is said at the field and its column, not at the generated task text's
  // line 4 the student never sees.
  await page.locator('#fn-expr').fill('log(x');
  await click(page, mobile, '#synth-run');
  await page.waitForFunction(() => !/Running/.test(document.querySelector('#synth-status').textContent));
  assert.match(await page.locator('#synth-status').textContent(), /^f\(x\), column 6: in the function 'log\(x': expected '\)'$/);
  assert.equal(await page.locator('#fn-expr.bad').count(), 1, 'the f(x) field is marked');
  assert.equal(await page.locator('#fn-expr').evaluate((e) => e.selectionStart), 5, 'the caret at the column');
  await page.locator('#fn-expr').fill('x^2');
  // Poses tapped on the drawing fill the table (their angles are typed).
  await page.selectOption('#synth-method', 'burmester');
  await click(page, mobile, '#pose-tap');
  assert.equal(await page.locator('#poses tr').count(), 0);
  const box = await page.locator('#drawing svg').boundingBox();
  for (const [fx, fy] of [[0.3, 0.3], [0.5, 0.25], [0.7, 0.35]]) await tapAt(page, mobile, box.x + box.width * fx, box.y + box.height * fy);
  assert.equal(await page.locator('#poses tr').count(), 3);
  assert.equal(await page.locator('#drawing .synth-marks .target').count(), 3);
  const xs = await page.locator('#poses .px').evaluateAll((els) => els.map((e) => +e.value));
  assert.ok(xs[0] < xs[1] && xs[1] < xs[2], `tapped left to right: ${xs}`);
  await click(page, mobile, '#pose-tap');
  // Pressing the button again ends the tapping: the status no longer asks for a fourth pose.
  assert.equal(await page.locator('#synth-status').textContent(), 'Points written into the task: press Run.');
  assert.equal(await page.locator('#drawing .synth-marks .target').count(), 3, 'the poses stay marked while the panel is open');
  await click(page, mobile, '[data-tab="gallery"]');
  assert.equal(await page.locator('#drawing .synth-marks').count(), 0, 'and go with it');
  await click(page, mobile, '[data-tab="synthesis"]');
  await page.selectOption('#synth-method', 'five-point');
}

// Velocities and stresses of the steel four-bar, against the server's answers.
async function overlays(page, ctx) {
  const { mobile, click, base } = ctx;
  await ctx.openExample(page, mobile, 'fourbar-steel-bars');
  await page.locator('#scrub').fill('0');
  await click(page, mobile, '[data-overlay="velocity"]');
  await page.waitForSelector('#drawing .ov-velocity line', { state: 'attached' });
  // At sample 0 the crank lies along +x, so A's velocity is straight up (the crank turns
  // counter-clockwise): in the SVG (y down) the arrow goes up from A.
  const a = page.locator('#drawing circle.pt[data-point="A"]');
  const ax = +(await a.getAttribute('cx')); const ay = +(await a.getAttribute('cy'));
  const lines = await page.locator('#drawing .ov-velocity line').evaluateAll((ls) => ls.map((l) => ['x1', 'y1', 'x2', 'y2'].map((k) => +l.getAttribute(k))));
  const fromA = lines.find(([x1, y1]) => Math.hypot(x1 - ax, y1 - ay) < 1e-3);
  assert.ok(fromA, 'an arrow starts at A');
  assert.ok(Math.abs(fromA[2] - fromA[0]) < 1e-3 * Math.abs(fromA[3] - fromA[1]) + 1e-6 && fromA[3] < fromA[1], `A's velocity points up: ${fromA}`);
  const model = await example(base, 'fourbar-steel-bars');
  const solve = await post(base, '/api/solve', { model, columns: ['A.vx', 'A.vy', 'B.vx', 'B.vy'] });
  let max = 0;
  for (const r of solve.rows) max = Math.max(max, Math.hypot(r[0], r[1]), Math.hypot(r[2], r[3]));
  assert.match(await page.locator('[data-legend="velocity"]').textContent(), new RegExp(`mm/s \\(largest ${fmt(max).replace('.', '\\.')}\\)`));

  await click(page, mobile, '[data-overlay="stress"]');
  await page.waitForSelector('#drawing .ov-stress .peak');
  const stress = await post(base, '/api/stress', { model });
  const top = stress.links.reduce((p, l) => (l.von_mises > p.von_mises ? l : p));
  assert.equal(top.body, 'rocker');
  assert.match(await page.locator('#drawing .peak-label').textContent(), new RegExp(`^${fmt(top.von_mises).replace('.', '\\.')} MPa \\(step ${top.step}\\)`));
  // The peak's label goes to its step (the drawing's pan took the click: nothing happened).
  await page.locator('#scrub').fill('0');
  await page.locator('#drawing').scrollIntoViewIfNeeded();
  await click(page, mobile, '#drawing .peak-label');
  await page.waitForFunction((s) => document.querySelector('#scrub').value === String(s), top.step);
  assert.equal(await page.locator('#drawing .frame .body[data-body="rocker"]').getAttribute('stroke'), 'rgb(217,45,32)');
  assert.match(await page.locator('[data-legend="stress"]').textContent(), /0 – 44\.\d+ MPa/);
  assert.match(await page.locator('#motion-info').textContent(), /crank-coupler-rocker: crank-rocker · μ = [\d.]+° \(min\. 41\.4\d*°\)/);
  if (!mobile) {
    await click(page, mobile, '[data-overlay="forces"]');
    await page.waitForSelector('#drawing .ov-forces line', { state: 'attached' });
    assert.match(await page.locator('[data-legend="forces"]').textContent(), / N \(largest/);
  }
  await page.locator('#drawing').scrollIntoViewIfNeeded();
  await ctx.shot(page, `${ctx.tag}-m4-overlays`);
  for (const k of ['velocity', 'stress', 'forces']) if (await page.locator(`[data-overlay="${k}"]`).isChecked()) await click(page, mobile, `[data-overlay="${k}"]`);
}

// A crank too long for a full turn stops at a toggle: the stop is listed with its step, and
// going there flags it on the drawing.
async function toggleStop(page, ctx) {
  const { mobile, click } = ctx;
  await ctx.openExample(page, mobile, 'fourbar-crank-rocker');
  await click(page, mobile, '[data-tab="editor"]');
  await ctx.retype(page, mobile, 'lengths: {crank: 80', '80', '140');
  await page.waitForSelector('#warnings li.stop');
  assert.match(await page.locator('#warnings li.stop').textContent(), /step 151.*toggle/);
  await click(page, mobile, '#warnings li.stop button');
  assert.equal(await page.locator('#scrub').inputValue(), '151');
  await page.waitForSelector('#drawing .ov-warning');
  assert.equal(await page.locator('#scrub-ticks i').count(), 1);
  await ctx.shot(page, `${ctx.tag}-m5-toggle`);
  // A warning with no step (the solve's are plain messages) reads as its text, with no step
  // button and no tick: it showed as "⚠ step 0 undefined".
  await ctx.retype(page, mobile, 'lengths: {crank: 140', '140', '80');
  await ctx.retype(page, mobile, 'from: 0, to: 360', '360', '1800');
  await page.waitForFunction(() => document.querySelector('#warnings li')?.textContent.includes('turns crank 5 times'));
  const warning = await page.locator('#warnings li').first().textContent();
  assert.match(warning, /^⚠ the sweep turns crank 5 times, from 0 deg to 1800 deg$/);
  assert.equal(await page.locator('#warnings li button').count(), 0);
  assert.equal(await page.locator('#scrub-ticks i').count(), 0);
  await ctx.shot(page, `${ctx.tag}-m5-many-turns`);
  // The crank-rocker's swing and time ratio, and a slider-crank's stroke, from the check.
  assert.match(await page.locator('#motion-facts').textContent(), /swing 65\.92\d* deg · time ratio 1\.136/);
  await ctx.openExample(page, mobile, 'slider-crank-offset');
  await page.waitForFunction(() => document.querySelector('#motion-facts')?.textContent.includes('stroke'));
  assert.match(await page.locator('#motion-facts').textContent(), /slider: stroke 101\.06\d* mm · time ratio 1\.055/);
  await ctx.shot(page, `${ctx.tag}-m5-stroke`);
  await ctx.openExample(page, mobile, 'fourbar-crank-rocker');
}

// The step-by-step panel of the crank-rocker at sample 0: Φq as a table, the server's numbers.
async function explainPanel(page, ctx) {
  const { mobile, click, base } = ctx;
  await ctx.openExample(page, mobile, 'fourbar-crank-rocker');
  // The same title as the toggling model before it: wait for the example's own (complete) sweep.
  await page.waitForFunction(() => document.querySelector('#scrub').max === '360');
  await page.locator('#scrub').fill('0');
  await click(page, mobile, '[data-tab="explain"]');
  await page.waitForSelector('#explain-out table.jac');
  const ex = await post(base, '/api/explain', { model: await example(base, 'fourbar-crank-rocker'), step: 0 });
  assert.equal(await page.locator('#explain-out table.jac tbody tr').count(), ex.jacobian.length);
  assert.equal(await page.locator('#explain-out table.jac tbody tr').nth(1).locator('td').first().textContent(), fmt(ex.jacobian[1][0]));
  assert.equal(await page.locator('#explain-out table.newton tbody tr').count(), ex.newton.iterations.length);
  assert.match(await page.locator('#explain-out .eqs').textContent(), /xA2 \+ yA2 − 802 = 0|xA2 \+ yA2 - 802 = 0/);
  assert.ok(await page.locator('#explain-note').isHidden(), 'no note for a step within the sweep');
  // Units on the velocities and accelerations, and the instant centres as the CLI lists them.
  assert.match(await page.locator('#explain-out').textContent(), /velocities of the coordinates, in mm\/s\./);
  assert.match(await page.locator('#explain-out').textContent(), /accelerations of the coordinates, in mm\/s²\./);
  assert.equal(await page.locator('#explain-out table.centres tbody tr').count(), ex.centres.length);
  const centre = ex.centres.find((c) => !c.primary && !c.at_infinity && !c.indeterminate);
  const cells = await page.locator(`#explain-out table.centres tr[data-centre="${centre.name}"] td`).allTextContents();
  assert.deepEqual(cells.slice(0, 2), [fmt(centre.position[0]), fmt(centre.position[1])]);
  assert.equal(await page.locator('#explain-out table.centres tr[data-centre="I(ground,crank)"] td').nth(2).textContent(), 'primary (joint)');
  await ctx.shot(page, `${ctx.tag}-m6-explain`);
  // A step past the sweep's end is shown at the end, and the note says so (it was clamped
  // silently); one that is no whole number is refused at the field.
  await page.locator('#explain-step').fill('999');
  await click(page, mobile, '#explain-run');
  await page.waitForFunction(() => document.querySelector('#explain-out').dataset.step === '360' && document.querySelector('#explain-out table.jac'));
  assert.equal(await page.locator('#explain-note').textContent(), 'Step 999 is past the last step, 360: showing step 360.');
  assert.ok(await page.locator('#explain-note').isVisible());
  assert.equal(await page.locator('#explain-step').inputValue(), '360');
  await ctx.shot(page, `${ctx.tag}-m6b-explain-past-end`);
  await page.locator('#explain-step').fill('2.5');
  await click(page, mobile, '#explain-run');
  assert.equal(await page.locator('#explain-note').textContent(), 'The step must be a whole number from 0 to 360 (not 2.5).');
  assert.ok(await page.locator('#explain-step.bad').count() === 1);
  assert.equal(await page.locator('#explain-out').getAttribute('data-step'), '360', 'nothing else was asked');
  await page.locator('#explain-step').fill('12');
  await click(page, mobile, '#explain-run');
  await page.waitForFunction(() => document.querySelector('#explain-out').dataset.step === '12');
  assert.ok(await page.locator('#explain-note').isHidden());
  assert.equal(await page.locator('#explain-step.bad').count(), 0);
}

// The page reloaded without a network: the service worker serves the app and the last answers;
// a new analysis says it is offline.
async function offline(page, ctx) {
  const { mobile, context, click, base } = ctx;
  // The MP4 download is offered exactly when the server has ffmpeg.
  const health = await (await fetch(new URL('api/health', base))).json();
  assert.equal(await page.locator('[data-download="mp4"]').evaluate((b) => b.hidden), !health.mp4);
  await page.evaluate(() => navigator.serviceWorker.ready);
  await page.waitForFunction(() => navigator.serviceWorker.controller !== null);
  await ctx.openExample(page, mobile, 'five-bar');  // analysed under the worker: its answers kept
  const title = await page.locator('#model-name').textContent();
  await context.setOffline(true);
  try {
    await page.reload();
    await page.waitForSelector('body[data-ready="1"]');
    await page.waitForFunction((tt) => document.querySelector('#model-name').textContent === tt, title);
    assert.ok(await page.locator('#drawing svg .body').count() > 0, 'the last results are drawn offline');
    assert.ok(await page.locator('#offline').isVisible(), 'the header says offline');
    await ctx.shot(page, `${ctx.tag}-m7-offline`);
    // A change cannot be analysed: it says why.
    await click(page, mobile, '[data-tab="editor"]');
    await ctx.retype(page, mobile, 'name: "Five-bar linkage', '(2 DOF)', '(two)');
    await page.waitForFunction(() => /^Offline: the analysis needs the nbar server/.test(document.querySelector('#problems').textContent));
  } finally {
    await context.setOffline(false);
  }
}

// The best fit from the example task (30 measured points of a crank-rocker's curve) finds that
// crank-rocker; points tapped for it go into its own task text, kept apart from the five-point
// one; the nine-point solve from its example finds designs too.
async function ninePointAndPath(page, ctx) {
  const { mobile, click } = ctx;
  await click(page, mobile, '[data-tab="synthesis"]');
  await page.selectOption('#synth-method', 'path');
  await page.waitForFunction(() => /task: path/.test(document.querySelector('#task').value));
  assert.equal(await page.locator('#five-tap').textContent(), 'Tap points');
  assert.equal(await page.locator('#drawing .synth-marks .target').count(), 30, "the example's 30 points marked");
  await click(page, mobile, '#synth-run');
  await page.waitForSelector('[data-design="1"]:not([disabled])', { timeout: 60000 });
  // "1 design (1 solution)": each count agrees with its noun (it said "1 solutions").
  const found = await page.locator('#synth-status').textContent();
  const [, designs, solutions] = /^(\d+) designs? \((\d+) solutions?\)/.exec(found) ?? [];
  assert.ok(designs, found);
  assert.ok(found.startsWith(`${designs} design${designs === '1' ? '' : 's'} (${solutions} solution${solutions === '1' ? '' : 's'})`), found);
  assert.match(await page.locator('.designs li').first().textContent(), /crank-rocker/);
  await ctx.shot(page, `${ctx.tag}-m6-path-fit`);
  // The preview marks the 30 targets but numbers only a few of them, none over another (the 30
  // numbers piled up on one another).
  await click(page, mobile, '[data-preview="1"]');
  await page.waitForSelector('#designs li.previewing .pv svg .target');
  await page.locator('#designs li.previewing .pv').scrollIntoViewIfNeeded();
  const labels = await page.evaluate(() => {
    const targets = document.querySelectorAll('#designs li.previewing .pv svg .target');
    const texts = [...document.querySelectorAll('#designs li.previewing .pv svg .target text')];
    const boxes = texts.map((x) => x.getBoundingClientRect());
    let overlaps = 0;
    for (let i = 0; i < boxes.length; i++) {
      for (let j = i + 1; j < boxes.length; j++) {
        const [a, b] = [boxes[i], boxes[j]];
        if (a.left < b.right && b.left < a.right && a.top < b.bottom && b.top < a.bottom) overlaps++;
      }
    }
    return { targets: targets.length, numbers: texts.map((x) => x.textContent), overlaps };
  });
  assert.equal(labels.targets, 30);
  assert.ok(labels.numbers.length >= 3 && labels.numbers.length <= 8, `numbered: ${labels.numbers}`);
  assert.equal(labels.numbers[0], '1');
  assert.equal(labels.overlaps, 0, `overlapping numbers: ${labels.numbers}`);
  await ctx.shot(page, `${ctx.tag}-m6a-path-preview`);
  await click(page, mobile, '[data-preview="1"]');
  // Twelve points tapped, then the button again: a path task of twelve points.
  await click(page, mobile, '#five-tap');
  if (mobile) {
    await page.evaluate(() => window.scrollTo({ top: 0, left: 0, behavior: 'instant' }));
    await page.waitForFunction(() => window.scrollY === 0);
  } else {
    await page.locator('#drawing').scrollIntoViewIfNeeded();
  }
  const box = await page.locator('#drawing svg').boundingBox();
  for (let k = 0; k < 12; ++k) {
    const a = (2 * Math.PI * k) / 12;
    await tapAt(page, mobile, box.x + box.width * (0.5 + 0.3 * Math.cos(a)), box.y + box.height * (0.5 + 0.3 * Math.sin(a)));
  }
  assert.match(await page.locator('#synth-status').textContent(), /Tap point 13 /);
  await click(page, mobile, '#five-tap');
  const task = await page.locator('#task').inputValue();
  assert.match(task, /^task: path/m);
  assert.equal([...task.split('points:')[1].matchAll(/\[([-\d.]+), ([-\d.]+)\]/g)].length, 12, task);
  assert.equal(await page.locator('#drawing .synth-marks .target').count(), 12);
  await page.selectOption('#synth-method', 'five-point');
  // The path fit's designs went with its method (they stayed listed under another).
  assert.equal(await page.locator('#designs li').count(), 0, "the other method's designs are cleared");
  assert.equal(await page.locator('#synth-status').textContent(), '');
  assert.match(await page.locator('#task').inputValue(), /^task: five-point/m, 'each method keeps its own task');
  await page.selectOption('#synth-method', 'path');
  assert.equal(await page.locator('#task').inputValue(), task);
  await page.selectOption('#synth-method', 'nine-point');
  await page.waitForFunction(() => /task: nine-point/.test(document.querySelector('#task').value));
  assert.equal(await page.locator('#drawing .synth-marks .target').count(), 9);
  await click(page, mobile, '#synth-run');
  await page.waitForSelector('[data-design="1"]:not([disabled])', { timeout: 60000 });
  assert.match(await page.locator('#synth-status').textContent(), /^\d+ designs? \(\d+ solutions?\)/);
  await ctx.shot(page, `${ctx.tag}-m7-nine-point`);
  await page.selectOption('#synth-method', 'five-point');
}

export async function run(page, ctx) {
  await fivePointByTapping(page, ctx);
  if (!ctx.mobile) await burmesterAndFunction(page, ctx);
  await ninePointAndPath(page, ctx);
  await overlays(page, ctx);
  if (!ctx.mobile) await toggleStop(page, ctx);
  await explainPanel(page, ctx);
  await offline(page, ctx);
}
