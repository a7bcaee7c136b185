// Runs web/bench/index.html in headless Chromium and prints its times beside the native
// bench's (the JSON lines file given), with the ratios; then renderAsync's speed-up on workers
// for 2048-pixel pictures (index.html?threads), in Chromium and in Node, with the machine's
// load average before and after. Used by web/bench/run (`--threads`: the speed-up only).
import { readFileSync } from 'node:fs';
import { cpus, loadavg } from 'node:os';
import { serve } from '../serve.mjs';
import { launch } from '../tests/browser.mjs';
import { benchThreads } from './bench.js';

const threadsOnly = process.argv[2] === '--threads';
const native = threadsOnly ? [] : readFileSync(process.argv[2], 'utf8').trim().split('\n').map((l) => JSON.parse(l));
const load = () => loadavg().map((l) => l.toFixed(2)).join(' ');

function threadsTable(rows) {
  console.log('case                                pixels     memory MB  1 thread ms  1 worker ms  2 workers ms  speed-up  2 workers, memory sent ms  speed-up');
  for (const r of rows) {
    const cells = [
      r.case.padEnd(35),
      `${r.width}×${r.height}`.padEnd(10),
      (r.memory_bytes / 1e6).toFixed(0).padStart(9),
      r.one_ms.toFixed(1).padStart(12),
      r.warm1_ms.toFixed(1).padStart(12),
      r.warm2_ms.toFixed(1).padStart(13),
      (r.one_ms / r.warm2_ms).toFixed(2).padStart(9),
      r.cold2_ms.toFixed(1).padStart(27),
      (r.one_ms / r.cold2_ms).toFixed(2).padStart(9),
    ];
    console.log(cells.join(' '));
  }
}

const { url, server } = await serve(0);
// (The page's thread is busy for many seconds at a time: the protocol waits as long.)
const browser = await launch({ protocolTimeout: 1_800_000 });
try {
  const version = await browser.version();
  if (!threadsOnly) {
    const page = await browser.newPage();
    await page.goto(`${url}/bench/`);
    await page.waitForFunction('window.results', { timeout: 600_000 });
    const chromium = await page.evaluate(() => window.results);
    if (chromium.error) throw new Error(chromium.error);
    await page.close();
    console.log(`${version} vs native x86_64 (release), medians of 5 runs`);
    console.log('case                              what       native ms  Chromium ms  Chromium ÷ native');
    for (const c of chromium) {
      const n = native.find((x) => x.case === c.case);
      for (const what of ['generate', 'render']) {
        const a = n[`${what}_ms`], b = c[`${what}_ms`];
        console.log(`${c.case.padEnd(33)} ${what.padEnd(9)} ${a.toFixed(1).padStart(10)} ${b.toFixed(1).padStart(12)} ${(b / a).toFixed(2).padStart(18)}`);
      }
    }
    console.log();
  }
  console.log(`renderAsync, the preview layer: render() on one thread against renderAsync on workers, the fastest of 5 runs each, taken in turn (${cpus().length} cores)`);
  console.log(`load average (1, 5, 15 min) before: ${load()}`);
  const page = await browser.newPage();
  await page.goto(`${url}/bench/?threads`);
  await page.waitForFunction('window.results', { timeout: 900_000 });
  const chromium = await page.evaluate(() => window.results);
  if (chromium.error) throw new Error(chromium.error);
  console.log(`${version}, Web Workers:`);
  threadsTable(chromium);
  console.log(`load average after Chromium: ${load()}`);
  console.log(`Node ${process.version}, worker_threads:`);
  threadsTable(await benchThreads());
  console.log(`load average after Node: ${load()}`);
} finally {
  await browser.close();
  server.close();
}
