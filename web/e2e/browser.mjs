// What the end-to-end scripts share: their arguments (URL DIR), how a check fails, and the
// headless Chromium they drive (CHROMIUM: the browser, default /usr/bin/chromium).
import { chromium } from 'playwright-core';

/** Prints the failed check and exits non-zero. */
export const fail = (message) => { console.error(`e2e: ${message}`); process.exit(1); };

/** The page's URL and the folder for screenshots, from the command line of `script`. */
export function urlAndShots(script) {
  const [url, shots] = process.argv.slice(2);
  if (!url || !shots) fail(`usage: node e2e/${script} URL DIR`);
  return [url, shots];
}

/** Chromium without a GPU or network services of its own, drawing WebGL in software. */
export function launch() {
  return chromium.launch({
    executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
    args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
      '--disable-background-networking', '--disable-component-update', '--disable-sync',
      '--use-gl=angle', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
  });
}
