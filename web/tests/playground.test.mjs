// The playground in headless Chromium, driven as a user would: every model grows and draws
// every layer with no console error, the page's thread never blocks for 50 ms while a model
// grows, a screenshot shows cracks in the share of pixels each model makes, the SVG export
// parses and has the network's edge count, PNG and SVG downloads, a click on the glass adds
// an impact, and the link restores the same picture.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { mkdtempSync, readdirSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { serve } from '../serve.mjs';
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

/** A playground page at `query`, its long tasks recorded from the start. */
async function open(query, errors) {
  const p = await page(browser, errors);
  await p.setViewport({ width: 1200, height: 800 });
  await p.evaluateOnNewDocument(() => {
    window.longTasks = [];
    new PerformanceObserver((list) => {
      for (const e of list.getEntries()) window.longTasks.push({ start: e.startTime, duration: e.duration });
    }).observe({ type: 'longtask', buffered: true });
  });
  await p.goto(`${base}/playground/?${query}`);
  await done(p);
  return p;
}

const done = (p) => p.waitForFunction('window.playground && window.playground.done', { timeout: 180_000, polling: 100 });

/** The canvas's pixels: an FNV-1a 32 hash and how many distinct colours. */
function pixels(p) {
  return p.evaluate(() => {
    const c = document.getElementById('canvas');
    const data = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let h = 0x811c9dc5;
    const colours = new Set();
    for (let i = 0; i < data.length; i += 4) {
      const v = data[i] | (data[i + 1] << 8) | (data[i + 2] << 16);
      colours.add(v);
      h = Math.imul(h ^ v, 0x01000193) >>> 0;
    }
    return { hash: h, colours: colours.size, width: c.width, height: c.height };
  });
}

const MODELS = {
  // model: [layers, the share of dark pixels in a screenshot of the mask layer]
  mud: [['preview', 'mask', 'height', 'normal', 'time', 'cells'], [0.05, 0.25]],
  glass: [['preview', 'mask', 'height', 'normal', 'time', 'cells'], [0.005, 0.05]],
  skin: [['preview', 'mask', 'height', 'normal', 'cells'], [0.08, 0.35]],
};

for (const [model, [layers, [low, high]]] of Object.entries(MODELS)) {
  test(`playground: ${model} grows without blocking the page, draws every layer, shows its cracks`, async () => {
    const errors = [];
    const p = await open(`model=${model}`, errors);
    // A new seed: the growth from the start, the long tasks counted from here.
    await p.evaluate(() => (window.longTasks = []));
    await p.$eval('#seed', (input) => {
      input.value = '2';
      input.dispatchEvent(new Event('change'));
    });
    const t0 = Date.now();
    await done(p);
    const grown = Date.now() - t0;
    const frames = await p.evaluate(() => window.playground.frames);
    assert.ok(frames >= 5, `${model}: the growth is shown live (${frames} frames)`);
    const long = await p.evaluate(() => window.longTasks);
    assert.deepEqual(long, [], `no task of 50 ms or more on the page's thread during ${grown} ms of growth`);
    // The observer sees a task that blocks: 80 ms of busy loop is one.
    await p.evaluate(() =>
      setTimeout(() => {
        const t = performance.now();
        while (performance.now() - t < 80) {}
      }, 0),
    );
    await p.waitForFunction(() => window.longTasks.some((e) => e.duration >= 80), { timeout: 5000 });
    const seen = new Set();
    for (const layer of layers) {
      await p.evaluate((layer) => [...document.querySelectorAll('#layers button')].find((b) => b.textContent === layer).click(), layer);
      await done(p);
      const px = await pixels(p);
      assert.ok(px.colours >= 2, `${model} ${layer}: a picture, not a flat colour`);
      assert.ok(!seen.has(px.hash), `${model} ${layer}: differs from the other layers`);
      seen.add(px.hash);
    }
    // The mask on screen: cracks dark on white.
    await p.evaluate(() => [...document.querySelectorAll('#layers button')].find((b) => b.textContent === 'mask').click());
    await done(p);
    const canvas = await p.$('#canvas');
    const shot = await canvas.screenshot({ encoding: 'base64' });
    const share = await p.evaluate(async (png) => {
      const image = new Image();
      image.src = `data:image/png;base64,${png}`;
      await image.decode();
      const c = new OffscreenCanvas(image.width, image.height);
      const g = c.getContext('2d');
      g.drawImage(image, 0, 0);
      const d = g.getImageData(0, 0, image.width, image.height).data;
      let dark = 0;
      for (let i = 0; i < d.length; i += 4) if (0.3 * d[i] + 0.59 * d[i + 1] + 0.11 * d[i + 2] < 128) dark++;
      return dark / (d.length / 4);
    }, shot);
    console.log(`# ${model}: grew in ${grown} ms over ${frames} frames, no long task; cracks ${(100 * share).toFixed(1)} % of the screenshot's pixels`);
    assert.ok(share >= low && share <= high, `${model}: cracks cover ${share} of the screenshot, expected ${low} to ${high}`);
    assert.deepEqual(errors, []);
    await p.close();
  });
}

test('playground: the SVG export parses and has the network edge, fragment, crack and cell counts', async () => {
  const errors = [];
  for (const model of ['mud', 'glass', 'skin']) {
    const p = await open(`model=${model}&seed=4`, errors);
    const result = await p.evaluate(async (model) => {
      const text = await window.playground.svg();
      const doc = new DOMParser().parseFromString(text, 'image/svg+xml');
      const parsed = !doc.querySelector('parsererror') && doc.documentElement.nodeName === 'svg';
      const count = (selector) => doc.querySelectorAll(selector).length;
      // The same parameters through hibi.js on this thread: the counts to expect.
      const hibi = await import('../hibi.js');
      await hibi.init();
      const params = window.playground.current.params;
      const Model = { mud: hibi.Mud, glass: hibi.Glass, skin: hibi.Skin }[model];
      const m = new Model(params);
      while (!m.step(1_000_000).finished) {}
      let want, got;
      if (model === 'mud') {
        want = { edges: m.network().edges.count };
        got = { edges: count('polyline.edge') };
      } else if (model === 'glass') {
        want = { fragments: m.fragments().rings.count, cracks: m.cracks().ends.length };
        got = { fragments: count('polygon.fragment'), cracks: count('polyline.crack') };
      } else {
        want = { cells: m.cells().count };
        got = { cells: count('polygon.cell') };
      }
      m.free();
      return { parsed, want, got, bytes: text.length };
    }, model);
    assert.ok(result.parsed, `${model}: the SVG parses`);
    assert.ok(Object.values(result.want).every((n) => n > 0), `${model}: something to draw`);
    assert.deepEqual(result.got, result.want, `${model}: the SVG's elements`);
    console.log(`# ${model} SVG: ${JSON.stringify(result.got)}, ${result.bytes} bytes`);
    await p.close();
  }
  assert.deepEqual(errors, []);
});

test('playground: PNG and SVG export download files', async () => {
  const errors = [];
  const p = await open('model=glass&seed=3', errors);
  const dir = mkdtempSync(join(tmpdir(), 'hibi-downloads-'));
  try {
    const cdp = await p.createCDPSession();
    await cdp.send('Browser.setDownloadBehavior', { behavior: 'allow', downloadPath: dir });
    await p.click('#png');
    await p.click('#svg');
    const wait = Date.now() + 20_000;
    const complete = () => readdirSync(dir).filter((f) => !f.endsWith('.crdownload'));
    while (complete().length < 2 && Date.now() < wait) await new Promise((r) => setTimeout(r, 100));
    const files = complete().sort();
    assert.deepEqual(files, ['hibi-glass-fig14b-seed3.png', 'hibi-glass-fig14b-seed3.svg']);
    const png = readFileSync(join(dir, files[0]));
    assert.deepEqual([...png.subarray(0, 8)], [0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]);
    assert.equal(png.readUInt32BE(16), 640, 'the PNG is the plate, 1:1');
    assert.match(readFileSync(join(dir, files[1]), 'utf8'), /^<svg xmlns="http:\/\/www.w3.org\/2000\/svg" viewBox="0 0 640 640"/);
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
  assert.deepEqual(errors, []);
  await p.close();
});

test('playground: a click on the glass adds an impact, and the link restores the same picture', async () => {
  const errors = [];
  const p = await open('model=glass&seed=9', errors);
  const cracks = async () => Number((await p.$eval('#text', (e) => e.textContent)).match(/(\d+) cracks/)[1]);
  const before = await cracks();
  const box = await (await p.$('#canvas')).boundingBox();
  await p.mouse.click(box.x + box.width * 0.25, box.y + box.height * 0.3);
  assert.equal(await p.evaluate(() => window.playground.state.hits.length), 1);
  await done(p);
  assert.ok((await cracks()) > before, 'the impact grew new cracks');
  // A slider moved, then the link.
  await p.$eval('#s-radial_mean', (input) => {
    input.value = '60';
    input.dispatchEvent(new Event('change'));
  });
  await done(p);
  const link = await p.evaluate(() => window.playground.link());
  assert.match(link, /model=glass&preset=fig14b&seed=9&layer=preview&p\.radial_mean=60&hits=160%2C192/);
  assert.equal(await p.evaluate(() => location.href), link, 'the address bar holds the link');
  const shown = await pixels(p);
  const q = await open(link.slice(link.indexOf('?') + 1), errors);
  assert.deepEqual(await pixels(q), shown, 'the link draws the same pixels');
  assert.equal(await q.$eval('#s-radial_mean', (i) => i.value), '60');
  assert.deepEqual(errors, []);
  await p.close();
  await q.close();
});

test('playground: every preset of every model starts and grows', async () => {
  const errors = [];
  const p = await open('model=skin&preset=fig13a', errors);
  for (const model of ['mud', 'glass', 'skin']) {
    await p.select('#model', model);
    const presets = await p.$$eval('#preset option', (o) => o.map((x) => x.value));
    for (const preset of presets) {
      await p.select('#preset', preset);
      // Each preset's first frame: the run started and drew (not its end: that is minutes).
      await p.waitForFunction(() => window.playground.current && window.playground.current.progress, { timeout: 60_000 });
    }
  }
  assert.deepEqual(errors, []);
  await p.close();
});
