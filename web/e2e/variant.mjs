// End-to-end: the editor page on a design surface made with quads. Loads it in headless
// Chromium, waits for the first state, reads the variant's row of the panel, turns a node axis
// and reads the row again once the re-solve has ended. Screenshot variant.png into DIR.
// Usage: node e2e/variant.mjs URL DIR   (CHROMIUM: the browser, default /usr/bin/chromium).
// Prints one JSON line of findings; exits non-zero on a failed check.
import { fail, launch, urlAndShots } from './browser.mjs';

const [url, shots] = urlAndShots('variant.mjs');
const browser = await launch();
try {
  const page = await (await browser.newContext({ viewport: { width: 1280, height: 800 } })).newPage();
  const errors = [];
  page.on('pageerror', (e) => errors.push(e.message));
  await page.goto(url);
  const row = () => page.evaluate(() => ({
    hidden: document.getElementById('variant-row').hidden,
    name: document.getElementById('variant-name').textContent,
    text: document.getElementById('variant').textContent,
    unit: document.getElementById('variant-unit').textContent,
  }));
  await page.waitForFunction(() => document.getElementById('variant').textContent !== '-',
    null, { timeout: 60000 }).catch(() => fail('the variant row was never filled'));
  const first = await row();
  // Turn the axis at the middle vertex by a message, as the page's drag sends it.
  await page.evaluate(() => {
    const h = window.honeycomb, s = h.lastState, v = Math.floor(s.base.length / 6);
    const a = [0, 1, 2].map((k) => s.offset[3 * v + k] - s.base[3 * v + k]);
    h.send({ type: 'drag_axis', vertex: v, direction: [a[0] + 0.3 * a[2], a[1], a[2]], radius: 2, stroke: 7 });
  });
  await page.waitForFunction(() => {
    const s = window.honeycomb.lastState;
    return s && s.stroke === 7 && s.done && document.getElementById('status').textContent === 'ready';
  }, null, { timeout: 60000 }).catch(() => fail('the turned axis was never solved'));
  const after = await row();
  await page.screenshot({ path: `${shots}/variant.png` });
  console.log(JSON.stringify({ first, after, errors }));
  if (errors.length) fail(`page errors: ${errors.join(' | ')}`);
} finally {
  await browser.close();
}
