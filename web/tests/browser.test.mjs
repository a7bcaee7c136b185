// The JavaScript package in headless Chromium: the golden scenes on the main thread and in a
// module Worker hash as natively; renderAsync on Web Workers draws render()'s bytes, on a page
// that is cross-origin isolated and on one that is not, and free() ends its workers.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { serve } from '../serve.mjs';
import { goldens } from './goldens.mjs';
import { launch, page } from './browser.mjs';

let browser, server, base;
before(async () => {
  ({ url: base, server } = await serve(0));
  browser = await launch();
});
after(async () => {
  await browser?.close();
  server?.close();
});

test('Chromium: the golden scenes hash as natively, on the main thread and in a module Worker', async () => {
  const errors = [];
  const p = await page(browser, errors);
  await p.goto(`${base}/tests/page.html`);
  await p.waitForFunction('window.report', { timeout: 120_000 });
  const report = await p.evaluate(() => window.report);
  assert.equal(report.error, undefined, report.error);
  const want = goldens();
  for (const where of ['main', 'worker']) {
    assert.ok(Object.keys(report[where]).length >= 20, `${where}: the scenes ran`);
    for (const [name, hash] of Object.entries(report[where])) assert.equal(hash, want[name], `${where}: ${name}`);
  }
  assert.deepEqual(errors, []);
  const version = await browser.version();
  console.log(`# ${version}: ${Object.keys(report.main).length} scenes match on the main thread and in a Worker`);
  await p.close();
});

test('Chromium: the bench page (web/bench/run) times every model', async () => {
  const errors = [];
  const p = await page(browser, errors);
  await p.goto(`${base}/bench/`);
  await p.waitForFunction('window.results', { timeout: 300_000 });
  const results = await p.evaluate(() => window.results);
  assert.equal(results.error, undefined, results.error);
  assert.deepEqual(results.map((r) => r.case), ['mud fig6a 96² (render 512 px)', 'glass defaults 640²', 'skin fig19a 400²']);
  for (const r of results) assert.ok(r.generate_ms > 0 && r.render_ms > 0, r.case);
  assert.deepEqual(errors, []);
  await p.close();
});

/** Waits until the page runs at most `most` dedicated workers (or 5 s have passed). */
async function workersDown(p, most) {
  for (let i = 0; i < 100 && p.workers().length > most; i++) await new Promise((r) => setTimeout(r, 50));
  return p.workers().length;
}

for (const where of ['', '/isolated']) {
  const shared = where !== '';
  test(`Chromium${shared ? ', cross-origin isolated' : ''}: renderAsync on 1, 2 and 3 Web Workers draws the bytes of render(); free() ends the workers`, async () => {
    const errors = [];
    const p = await page(browser, errors);
    await p.goto(`${base}${where}/tests/bands.html`);
    await p.waitForFunction('window.report', { timeout: 120_000 });
    const report = await p.evaluate(() => window.report);
    assert.equal(report.error, undefined, report.error);
    assert.equal(report.isolated, shared);
    assert.equal(report.shared, shared, 'SharedArrayBuffer exists where the page is isolated only');
    assert.deepEqual(report.mismatches, []);
    assert.equal(report.compared, 2 * 3 * 7 * 3);
    // After 100 create/renderAsync/free cycles no worker is left; three run while a model holds them.
    assert.equal(await workersDown(p, 0), 0, 'the cycles left no worker');
    await p.evaluate(async () => {
      window.held = new window.hibi.Skin({ width: 64, height: 64 });
      window.held.step(1_000_000);
      await window.held.renderAsync(['mask'], undefined, { threads: 3 });
    });
    assert.equal(p.workers().length, 3);
    await p.evaluate(() => window.held.free());
    assert.equal(await workersDown(p, 0), 0, 'free() ended them');
    assert.deepEqual(errors, []);
    await p.close();
  });
}
