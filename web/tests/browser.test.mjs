// The JavaScript package in headless Chromium: the golden scenes on the main thread and in a
// module Worker hash as natively.
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
