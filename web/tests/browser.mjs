// Headless Chromium (Debian's, driven by puppeteer-core) for the browser tests and the bench:
// HIBI_CHROMIUM names another executable.
import puppeteer from 'puppeteer-core';
import { existsSync } from 'node:fs';

export function chromiumPath() {
  const path = process.env.HIBI_CHROMIUM ?? '/usr/bin/chromium';
  if (!existsSync(path)) throw new Error(`no Chromium at ${path} (apt-get install chromium, or set HIBI_CHROMIUM)`);
  return path;
}

export function launch(options = {}) {
  return puppeteer.launch({
    ...options,
    executablePath: chromiumPath(),
    headless: true,
    args: ['--no-sandbox', '--disable-gpu', '--disable-dev-shm-usage', '--use-gl=swiftshader', '--enable-unsafe-swiftshader'],
  });
}

/** A new page that records console errors, page errors and failed requests in `errors`. */
export async function page(browser, errors) {
  const p = await browser.newPage();
  p.on('console', (m) => {
    if (m.type() === 'error') errors.push(`console: ${m.text()}`);
  });
  p.on('pageerror', (e) => errors.push(`page error: ${e.message}`));
  p.on('requestfailed', (r) => errors.push(`request failed: ${r.url()}`));
  p.on('response', (r) => {
    if (r.status() >= 400) errors.push(`HTTP ${r.status()}: ${r.url()}`);
  });
  return p;
}
