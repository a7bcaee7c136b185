// Runs web/bench/index.html in headless Chromium and prints its times beside the native
// bench's (the JSON lines file given), with the ratios. Used by web/bench/run.
import { readFileSync } from 'node:fs';
import { serve } from '../serve.mjs';
import { launch } from '../tests/browser.mjs';

const native = readFileSync(process.argv[2], 'utf8').trim().split('\n').map((l) => JSON.parse(l));
const { url, server } = await serve(0);
const browser = await launch();
try {
  const page = await browser.newPage();
  await page.goto(`${url}/bench/`);
  await page.waitForFunction('window.results', { timeout: 600_000 });
  const chromium = await page.evaluate(() => window.results);
  if (chromium.error) throw new Error(chromium.error);
  console.log(`${await browser.version()} vs native x86_64 (release), medians of 5 runs`);
  console.log('case                              what       native ms  Chromium ms  Chromium ÷ native');
  for (const c of chromium) {
    const n = native.find((x) => x.case === c.case);
    for (const what of ['generate', 'render']) {
      const a = n[`${what}_ms`], b = c[`${what}_ms`];
      console.log(`${c.case.padEnd(33)} ${what.padEnd(9)} ${a.toFixed(1).padStart(10)} ${b.toFixed(1).padStart(12)} ${(b / a).toFixed(2).padStart(18)}`);
    }
  }
} finally {
  await browser.close();
  server.close();
}
