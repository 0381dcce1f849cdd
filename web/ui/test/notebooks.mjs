// The notebooks as a student reads them on a phone (390 px) and a laptop (1366 px): each one
// executed to HTML by nbconvert (scripts/notebook-pages.sh), opened in Debian's Chromium through
// playwright-core. Asserts what a reader would trip over: the page scrolling sideways, an output
// wider than its cell that is cut instead of scrolling (explain's equations and tables), a
// picture wider than the screen, and an animation whose frame hides its controls or read-out.
// Saves a full-page screenshot per notebook and size, and each animation's frame.
// Exit 77 (ctest's SKIP_RETURN_CODE) when playwright-core or Chromium is missing.
//   node web/ui/test/notebooks.mjs --pages build/notebook-pages --out build/notebook-screenshots
import { mkdirSync, readdirSync } from 'node:fs';
import { join, resolve } from 'node:path';
import { pathToFileURL } from 'node:url';
import { arg, launchChromium, watchdog as startWatchdog } from './harness.mjs';

const pages = resolve(arg('--pages', 'build/notebook-pages'));
const out = resolve(arg('--out', 'build/notebook-screenshots'));
const notebooks = readdirSync(pages).filter((f) => f.endsWith('.html')).sort();

const browser = await launchChromium();
mkdirSync(out, { recursive: true });
const watchdog = startWatchdog(170000);
const failures = [];
const check = (ok, what) => { if (!ok) failures.push(what); };
check(notebooks.length >= 6, `only ${notebooks.length} notebook pages in ${pages}`);

// In the page: what is too wide and whether it can be scrolled to.
function pageFacts() {
  const width = document.documentElement.clientWidth;
  const scrolls = (e) => ['auto', 'scroll'].includes(getComputedStyle(e).overflowX);
  const cut = [];
  for (const output of document.querySelectorAll('.jp-OutputArea-output')) {
    const cell = output.closest('.jp-Cell');
    if (output.scrollWidth <= cell.clientWidth + 1 && output.getBoundingClientRect().right <= width + 1) continue;
    let scroller = null;
    for (let e = output; e && e !== cell; e = e.parentElement) if (scrolls(e) && e.scrollWidth > e.clientWidth) scroller = e;
    if (!scroller || scroller.getBoundingClientRect().right > width + 1)
      cut.push(output.textContent.trim().slice(0, 60));
  }
  const wideImages = [...document.querySelectorAll('.jp-OutputArea-output img')]
    .filter((i) => i.getBoundingClientRect().right > width + 1).map((i) => Math.round(i.getBoundingClientRect().width));
  return { pageWidth: document.documentElement.scrollWidth, width, cut, wideImages,
           explains: [...document.querySelectorAll('.jp-OutputArea-output h2')].filter((h) => h.textContent.startsWith('Step by step')).length };
}

// In an animation's frame: the page must fit it, controls and read-out included.
function frameFacts() {
  const controls = [...document.querySelectorAll('button, input, select')];
  return {
    height: innerHeight, width: innerWidth, content: document.documentElement.scrollHeight,
    lowestControl: Math.max(...controls.map((c) => c.getBoundingClientRect().bottom)), controls: controls.length,
  };
}

let explains = 0, animations = 0;
for (const file of notebooks) {
  for (const [name, viewport, mobile] of [['phone', { width: 390, height: 844 }, true],
                                          ['laptop', { width: 1366, height: 768 }, false]]) {
    const context = await browser.newContext({ viewport, isMobile: mobile, hasTouch: mobile, deviceScaleFactor: mobile ? 2 : 1 });
    const page = await context.newPage();
    const errors = [];
    page.on('pageerror', (e) => errors.push(e.message));
    await page.goto(pathToFileURL(join(pages, file)).href, { waitUntil: 'load' });
    const where = `${file} at ${viewport.width} px`;
    const facts = await page.evaluate(pageFacts);
    check(errors.length === 0, `${where}: script errors ${errors.join('; ')}`);
    check(facts.pageWidth <= viewport.width, `${where}: the page is ${facts.pageWidth} px wide`);
    check(facts.cut.length === 0, `${where}: outputs cut off instead of scrolling: ${facts.cut.join(' | ')}`);
    check(facts.wideImages.length === 0, `${where}: pictures wider than the screen: ${facts.wideImages.join(', ')} px`);
    if (name === 'phone') explains += facts.explains;
    const frames = page.locator('.jp-OutputArea-output iframe');
    for (let i = 0; i < await frames.count(); ++i) {
      const frame = frames.nth(i);
      await frame.scrollIntoViewIfNeeded();
      const inner = await (await frame.elementHandle()).contentFrame();
      await inner.waitForLoadState('load');
      const f = await inner.evaluate(frameFacts);
      if (f.controls === 0) continue;  // not an animation
      if (name === 'phone') ++animations;
      check(f.content <= f.height + 1, `${where}: animation ${i + 1} needs ${f.content} px in a ${f.height} px frame`);
      check(f.lowestControl <= f.height, `${where}: animation ${i + 1}'s controls end at ${f.lowestControl} px, below its ${f.height} px frame`);
      check(f.height - f.content < 0.25 * f.height, `${where}: animation ${i + 1}'s frame is ${f.height} px for ${f.content} px`);
      await page.waitForTimeout(300);
      await frame.screenshot({ path: join(out, `${file.replace('.html', '')}-animation${i + 1}-${name}.png`) });
    }
    await page.screenshot({ path: join(out, `${file.replace('.html', '')}-${name}.png`), fullPage: true });
    await context.close();
  }
}
await browser.close();
clearTimeout(watchdog);
check(explains >= 1, 'no explain output found in the notebooks');
check(animations >= 1, 'no animation found in the notebooks');
if (failures.length) {
  for (const f of failures) console.error(`FAIL: ${f}`);
  process.exit(1);
}
console.log(`notebooks: ${notebooks.length} pages, ${explains} explanations and ${animations} animations read at 390 and 1366 px; screenshots in ${out}`);
