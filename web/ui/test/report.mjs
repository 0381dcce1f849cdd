// The HTML report (`nbar report`) read on a phone, 390 px wide, and on a desktop: Debian's
// Chromium (never a downloaded one) through playwright-core. Asserts what a reader would trip
// over: the page or a table scrolling sideways, the animation's frame taller or shorter than
// the animation (an empty block, or a frame that scrolls inside), a table cell squeezed to a
// word's width, plot and drawing text too small to read. Saves full-page screenshots.
// Exit 77 (ctest's SKIP_RETURN_CODE) when playwright-core or Chromium is missing.
//   node web/ui/test/report.mjs --nbar build/apps/nbar/nbar --examples examples --out build/report-screenshots
import { execFileSync } from 'node:child_process';
import { mkdirSync } from 'node:fs';
import { join, resolve } from 'node:path';
import { pathToFileURL } from 'node:url';
import { arg, launchChromium, watchdog as startWatchdog } from './harness.mjs';

const nbar = arg('--nbar', 'build/apps/nbar/nbar');
const examples = arg('--examples', 'examples');
const out = resolve(arg('--out', 'build/report-screenshots'));

const browser = await launchChromium();
mkdirSync(out, { recursive: true });
const watchdog = startWatchdog(110000);

const failures = [];
const check = (ok, what) => { if (!ok) failures.push(what); };

for (const example of ['fourbar-steel-bars', 'crank-rocker-gravity-spring']) {
  const page_file = join(out, `${example}.html`);
  execFileSync(nbar, ['report', join(examples, `${example}.yaml`), '--steps', '73', '--frames', '12', '-o', page_file]);
  for (const [name, viewport, mobile] of [['phone', { width: 390, height: 844 }, true],
                                          ['desktop', { width: 1000, height: 900 }, false]]) {
    const context = await browser.newContext({ viewport, isMobile: mobile, hasTouch: mobile, deviceScaleFactor: mobile ? 2 : 1 });
    const page = await context.newPage();
    const errors = [];
    page.on('pageerror', (e) => errors.push(e.message));
    await page.goto(pathToFileURL(page_file).href, { waitUntil: 'load' });
    await page.waitForTimeout(300);  // the frame fitting runs on load and on the frame's load
    const facts = await page.evaluate(() => {
      const f = document.querySelector('iframe');
      const main = f.contentDocument.querySelector('main');
      const visible = (e) => e.getClientRects().length > 0 && getComputedStyle(e).display !== 'none';
      const texts = (selector) => [...document.querySelectorAll(selector)].filter(visible)
        .map((t) => ({ text: t.textContent, height: t.getBoundingClientRect().height }));
      const grashof = [...document.querySelectorAll('th')].find((th) => th.textContent === 'Grashof');
      return {
        pageWidth: document.documentElement.scrollWidth,
        scrolling: [...document.querySelectorAll('.scroll')].filter((s) => s.scrollWidth > s.clientWidth + 1)
          .map((s) => s.querySelector('th')?.textContent),
        frame: f.getBoundingClientRect().height,
        frameContent: main.getBoundingClientRect().height,
        frameScrolls: f.contentDocument.documentElement.scrollHeight > f.clientHeight + 1,
        grashofCell: grashof ? grashof.nextElementSibling.getBoundingClientRect().width : null,
        plotText: texts('#kinematics svg text'),
        drawingText: texts('#motion > div svg text, #stresses svg text'),
      };
    });
    const where = `${example} at ${viewport.width} px`;
    check(errors.length === 0, `${where}: script errors ${errors.join('; ')}`);
    check(facts.pageWidth <= viewport.width, `${where}: the page is ${facts.pageWidth} px wide`);
    check(facts.scrolling.length === 0, `${where}: tables scroll sideways: ${facts.scrolling.join(', ')}`);
    check(!facts.frameScrolls, `${where}: the animation scrolls inside its frame`);
    check(facts.frame >= facts.frameContent && facts.frame <= facts.frameContent + 12,
          `${where}: the animation's frame is ${facts.frame} px high for ${facts.frameContent} px of animation`);
    if (facts.grashofCell !== null)
      check(facts.grashofCell >= 0.45 * viewport.width - 40, `${where}: the Grashof cell is ${facts.grashofCell} px wide`);
    check(facts.plotText.length > 20, `${where}: no plot text found`);
    // 12 px text drawn at 1:1 is about 14 px high; below 9 px it is hard to read on a phone.
    const small = facts.plotText.concat(facts.drawingText).filter((t) => t.height < 9);
    check(small.length === 0, `${where}: text too small: ${small.slice(0, 5).map((t) => `"${t.text}" ${t.height.toFixed(1)} px`).join(', ')}`);
    await page.screenshot({ path: join(out, `${example}-${name}.png`), fullPage: true });
    await context.close();
  }
}
await browser.close();
clearTimeout(watchdog);
if (failures.length) {
  for (const f of failures) console.error(`FAIL: ${f}`);
  process.exit(1);
}
console.log(`report: phone and desktop checks passed; screenshots in ${out}`);
