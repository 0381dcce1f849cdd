// The drawing in the browser is `nbar draw`'s (run by browser.mjs at each viewport): for a few
// examples and samples, the app's drawing (the server's scene, drawn by drawing.js and posed by
// the scene's motions) and the SVG of /api/render (what `nbar draw --step K --labels --width W
// --height H` writes) are rasterised alike in the page and compared pixel by pixel. At the pose
// the scene is drawn at they must agree but for antialiasing; at other samples too, leaving out
// the point labels (the app moves them with their points, `nbar draw` places them anew). A
// drawing of another sample must differ by far more, so that the comparison can fail.
import assert from 'node:assert/strict';
import { writeFileSync } from 'node:fs';
import { join } from 'node:path';

// Share of the pixels whose colour differs by more than 64 in a channel.
async function difference(page, model, step, labels) {
  return page.evaluate(async ({ model, step, labels }) => {
    const svg = document.querySelector('#drawing svg');
    const width = +svg.dataset.width; const height = +svg.dataset.height;
    const mine = svg.cloneNode(true);
    for (const el of mine.querySelectorAll('.handles, .ov, .ov-traces, .synth-marks, .tool-overlay')) el.remove();
    if (!labels) mine.querySelector('g[data-group="labels"]')?.remove();
    mine.setAttribute('width', width); mine.setAttribute('height', height);
    const r = await fetch('/api/render', {
      method: 'POST', headers: { 'Content-Type': 'application/json' },
      body: JSON.stringify({ model, kind: 'draw', format: 'svg', labels: true, width, height, step }),
    });
    let theirs = await r.text();
    if (!labels) theirs = theirs.replace(/<g id="labels"[\s\S]*?<\/g>/, '');
    async function pixels(text) {
      const img = new Image();
      img.src = `data:image/svg+xml;charset=utf-8,${encodeURIComponent(text)}`;
      await img.decode();
      const c = document.createElement('canvas');
      c.width = width; c.height = height;
      const g = c.getContext('2d');
      g.fillStyle = '#fff'; g.fillRect(0, 0, width, height);
      g.drawImage(img, 0, 0, width, height);
      return [g.getImageData(0, 0, width, height).data, c];
    }
    const [a, ca] = await pixels(new XMLSerializer().serializeToString(mine));
    const [b, cb] = await pixels(theirs);
    let differ = 0; let inked = 0;
    for (let i = 0; i < a.length; i += 4) {
      if (Math.max(Math.abs(a[i] - b[i]), Math.abs(a[i + 1] - b[i + 1]), Math.abs(a[i + 2] - b[i + 2])) > 64) differ++;
      if (b[i] + b[i + 1] + b[i + 2] < 3 * 230) inked++;
    }
    // Both pictures, to look at when they differ.
    return { differ: differ / (a.length / 4), inked: inked / (a.length / 4), pictures: [ca.toDataURL(), cb.toDataURL()] };
  }, { model, step, labels });
}

// Keeps the app's and nbar draw's pictures as test artifacts.
function keep(ctx, name, d) {
  d.pictures.forEach((url, i) => writeFileSync(join(ctx.out, `${name}-${i ? 'nbar-draw' : 'app'}.png`), Buffer.from(url.split(',')[1], 'base64')));
}

// ctx: {mobile, tag, base, out, shot, click, openExample}.
export async function run(page, ctx) {
  const examples = ctx.mobile ? ['slider-crank-offset'] : ['fourbar-crank-rocker', 'slider-crank-offset', 'inverted-slider-crank-shaper', 'dump-truck-tipper'];
  for (const name of examples) {
    await ctx.openExample(page, ctx.mobile, name);
    const model = await (await fetch(`${ctx.base}api/examples/${name}`)).text();
    const reference = +(await page.locator('#drawing svg').getAttribute('data-reference-step'));
    const samples = +(await page.locator('#scrub').getAttribute('max')) + 1;
    const other = (reference + Math.floor(samples / 3)) % samples;
    await page.locator('#scrub').fill(String(reference));
    const same = await difference(page, model, reference, true);
    assert.ok(same.inked > 0.01, `${name}: the drawing has ink (${same.inked})`);
    assert.ok(same.differ < 0.0005, `${name} at sample ${reference}: ${(same.differ * 100).toFixed(3)} % of the pixels differ from nbar draw's`);
    await page.locator('#scrub').fill(String(other));
    const moved = await difference(page, model, other, false);
    keep(ctx, `${ctx.tag}-draw-${name}-${other}`, moved);
    assert.ok(moved.differ < 0.0005, `${name} at sample ${other}: ${(moved.differ * 100).toFixed(3)} % of the pixels differ from nbar draw's`);
    const wrong = await difference(page, model, reference, false);
    assert.ok(wrong.differ > 10 * Math.max(moved.differ, 0.0005), `${name}: sample ${other} drawn against sample ${reference} differs by ${(wrong.differ * 100).toFixed(3)} % only`);
    console.log(`${ctx.tag} ${name}: ${(same.differ * 100).toFixed(3)} % at sample ${reference}, ${(moved.differ * 100).toFixed(3)} % at sample ${other} (labels left out); another sample ${(wrong.differ * 100).toFixed(2)} %`);
    await ctx.shot(page, `${ctx.tag}-draw-${name}`);
    await page.locator('#scrub').fill('0');
  }
  if (ctx.mobile) return;
  // A window made much narrower: the drawing is drawn again for its new size, still nbar draw's.
  const size = page.viewportSize();
  const width = () => page.locator('#drawing svg').getAttribute('data-width');
  const wide = await width();
  await page.setViewportSize({ width: 480, height: size.height });
  await page.waitForFunction((w) => document.querySelector('#drawing svg')?.dataset.width !== w, wide);
  const name = examples.at(-1);
  const model = await (await fetch(`${ctx.base}api/examples/${name}`)).text();
  const reference = +(await page.locator('#drawing svg').getAttribute('data-reference-step'));
  await page.locator('#scrub').fill(String(reference));
  const narrow = await difference(page, model, reference, true);
  assert.ok(narrow.differ < 0.0005, `${name} at ${await width()} px: ${(narrow.differ * 100).toFixed(3)} % of the pixels differ from nbar draw's`);
  await ctx.shot(page, `${ctx.tag}-draw-narrow`);
  await page.setViewportSize(size);
  await page.waitForFunction((w) => document.querySelector('#drawing svg')?.dataset.width === w, wide);
  await page.locator('#scrub').fill('0');
}
