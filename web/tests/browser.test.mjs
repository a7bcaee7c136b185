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
