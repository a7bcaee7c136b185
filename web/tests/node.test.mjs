// The JavaScript package under Node: the golden scenes hash as on every native target, bad
// input throws HibiError with the core's message naming the field, free() gives memory back,
// and renderAsync on worker threads draws render()'s bytes. Run by `npm test` (web/test runs
// it with the browser tests).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { existsSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { execFileSync } from 'node:child_process';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import * as hibi from '../hibi.js';
import { Mud, Glass, Skin, HibiError } from '../hibi.js';
import { runScenes } from './scenes.mjs';
import { goldens } from './goldens.mjs';
import { compareBands, cycles } from './bands.mjs';

await hibi.init();

/** The core's messages of an error list: `Variant => c"message"` in `file`. */
function messages(file) {
  const source = readFileSync(new URL(`../../core/src/${file}`, import.meta.url), 'utf8');
  return [...source.matchAll(/=> c"([^"]+)"/g)].map((m) => m[1]);
}

test('every golden scene the API makes hashes as natively (targets/scenes GOLDENS)', () => {
  const want = goldens();
  const got = runScenes(hibi);
  assert.ok(Object.keys(got).length >= 20, 'the scenes ran');
  for (const [name, hash] of Object.entries(got)) {
    assert.ok(name in want, `${name} is a golden scene`);
    assert.equal(hash, want[name], name);
  }
});

test('a parameter out of its range throws the core message naming the field', () => {
  const mud = messages('mud/params.rs');
  const glass = messages('glass/params.rs');
  const skin = messages('skin/params.rs');
  const raster = messages('raster/mod.rs');
  const cases = [
    [() => new Mud({ columns: 0 }), mud, 'columns'],
    [() => new Mud({ layer_thickness: NaN }), mud, 'layer_thickness'],
    [() => new Mud({ break_stretch_spread: -1 }), mud, 'break_stretch_spread'],
    [() => new Glass({ radial_mean: -5 }), glass, 'radial_mean'],
    [() => new Glass({ width: 0 }), glass, 'width'],
    [() => new Skin({ levels: 9 }), skin, 'levels'],
    [() => new Skin({ jitter_ratio: 2 }), skin, 'jitter_ratio'],
  ];
  for (const [make, list, field] of cases) {
    assert.throws(make, (e) => {
      assert.ok(e instanceof HibiError, `${field}: a HibiError`);
      assert.ok(list.includes(e.message), `${field}: the core's message, got "${e.message}"`);
      assert.match(e.message, new RegExp(field), `${field}: the message names the field`);
      return true;
    });
  }
  const mudRun = new Mud({ columns: 8, rows: 8 });
  try {
    assert.throws(() => mudRun.render(['mask'], { width_scale: -1 }), (e) => raster.includes(e.message) && /width_scale/.test(e.message));
    assert.throws(() => mudRun.render(['cell']), /^HibiError: render: this model has no cell layer$/);
    assert.throws(() => mudRun.render(['mask'], { width: 0 }), (e) => raster.includes(e.message));
  } finally {
    mudRun.free();
  }
});

test('a value of the wrong type throws naming the field', () => {
  assert.throws(() => new Mud({ columns: 1.5 }), /^HibiError: mud: columns must be an integer/);
  assert.throws(() => new Mud({ columns: '32' }), /mud: columns must be an integer/);
  assert.throws(() => new Mud({ topology: 'round' }), /mud: topology must be one of square, hexagonal, irregular/);
  assert.throws(() => new Glass({ impact: [1, 'x'] }), /glass: impact\[1\] must be a number/);
  assert.throws(() => new Skin({ periodic: 1 }), /skin: periodic must be true or false/);
  assert.throws(() => new Skin({ level: [{ spacing: null }] }), /skin: level\[0\]\.spacing must be a number/);
  assert.throws(() => Mud.preset('no-such'), /mud: no preset has that name/);
  assert.throws(() => new Mud({}).step(-1), /mud: step's budget/);
});

test('presets: every name makes a model, with the paper defaults underneath', () => {
  for (const Model of [Mud, Glass, Skin]) {
    assert.ok(Model.presets.length > 0);
    for (const name of Model.presets) {
      const m = new Model(Model.preset(name));
      assert.deepEqual(m.params, Model.preset(name));
      m.free();
    }
  }
  assert.equal(Mud.defaults().topology, 'hexagonal');
  assert.equal(Glass.defaults().radial_mean, 100);
  const big = new Glass({ seed: 2n ** 63n + 5n });
  assert.equal(big.params.seed, 2n ** 63n + 5n);
  big.free();
});

test('free() gives the memory back: 500 create/step/render/free cycles leave memory flat', () => {
  const cycle = () => {
    const g = new Glass({ width: 96, height: 96, impact: [48, 48], radial_mean: 30 });
    g.step(20_000);
    g.render(['preview', 'mask']);
    g.cracks();
    g.fragments();
    g.free();
    const m = new Mud({ columns: 12, rows: 12 });
    m.step(100_000);
    m.network();
    m.free();
    assert.throws(() => new Skin({ levels: 0 }), HibiError); // the error path frees too
  };
  for (let i = 0; i < 20; i++) cycle();
  const before = hibi.memoryBytes();
  for (let i = 0; i < 500; i++) cycle();
  assert.equal(hibi.memoryBytes(), before);
});

test('a freed model refuses every call; `using` frees at the end of the block', () => {
  const m = new Mud({ columns: 8, rows: 8 });
  m.free();
  m.free(); // twice is harmless
  assert.throws(() => m.step(10), /mud: used after free\(\)/);
  assert.throws(() => m.render(), /mud: used after free\(\)/);
  const s = new Skin({ width: 32, height: 32 });
  s[Symbol.dispose ?? Symbol.for('Symbol.dispose')]();
  assert.throws(() => s.cells(), /skin: used after free\(\)/);
});

test('a glass plate takes further impacts where it is clicked', () => {
  const g = new Glass({ width: 200, height: 120, impact: [60, 60] });
  try {
    while (!g.step(50_000).finished) {}
    const first = g.cracks().ends.length;
    const counts = g.impact(150, 60);
    assert.ok(counts.radial > 0);
    while (!g.step(50_000).finished) {}
    assert.ok(g.cracks().ends.length > first);
    assert.throws(() => g.impact(500, 60), HibiError);
  } finally {
    g.free();
  }
});

/** The ```js blocks of a Markdown file: code, whether a `not run` comment precedes it, and the
 * output it is said to print (a ```text block after a paragraph that is just "prints"). */
function jsBlocks(file) {
  const lines = readFileSync(new URL(`../../${file}`, import.meta.url), 'utf8').split('\n');
  const blocks = [];
  for (let i = 0; i < lines.length; i++) {
    const open = lines[i].match(/^```(\w*)/);
    if (!open) continue;
    let end = i + 1;
    while (!lines[end].startsWith('```')) end++;
    const prev = lines.slice(0, i).reverse().find((l) => l.trim() !== '') ?? '';
    blocks.push({ lang: open[1], code: lines.slice(i + 1, end).join('\n'), notRun: prev.startsWith('<!-- not run:'), at: `${file}:${i + 1}`, before: i, after: end });
    i = end;
  }
  return blocks
    .map((b, k) => {
      const next = blocks[k + 1];
      const between = next ? lines.slice(b.after + 1, next.before).join(' ').trim() : '';
      return { ...b, prints: next && next.lang === 'text' && between === 'prints' ? next.code + '\n' : null };
    })
    .filter((b) => b.lang === 'js');
}

test('the JavaScript blocks of README.md and docs/src/javascript.md run and print what they say', () => {
  const hibi = new URL('../hibi.js', import.meta.url).href;
  const blocks = ['README.md', 'docs/src/javascript.md'].flatMap(jsBlocks);
  const run = blocks.filter((b) => !b.notRun);
  assert.ok(run.length >= 3, 'the quick starts are there');
  for (const b of run) {
    const dir = mkdtempSync(join(tmpdir(), 'hibi-js-block-'));
    try {
      const file = join(dir, 'block.mjs');
      writeFileSync(file, b.code.replaceAll("from 'hibi'", `from '${hibi}'`));
      const out = execFileSync(process.execPath, [file], { cwd: dir, encoding: 'utf8' });
      if (b.prints !== null) assert.equal(out, b.prints, `${b.at}: prints what the page says`);
    } finally {
      rmSync(dir, { recursive: true, force: true });
    }
  }
});

test('hibi.d.ts types what a TypeScript user writes (tsc --strict on tests/types.ts)', () => {
  const tsc = new URL('../node_modules/typescript/bin/tsc', import.meta.url).pathname;
  const types = new URL('./types.ts', import.meta.url).pathname;
  const args = ['--noEmit', '--strict', '--target', 'es2022', '--module', 'esnext', '--moduleResolution', 'bundler'];
  execFileSync(process.execPath, [tsc, ...args, '--lib', 'es2022,dom,esnext.disposable', types], { encoding: 'utf8' });
});

test('every layer: height16 and normal_rgb8 encode height and normal as the core documents', () => {
  for (const model of [new Glass({ width: 96, height: 96, impact: [48, 48] }), new Mud({ columns: 16, rows: 16 }), new Skin({ width: 64, height: 64, levels: 2 })]) {
    try {
      while (!model.step(1_000_000).finished) {}
      const { layers } = model.render(['height', 'height16', 'normal', 'normal_rgb8', 'mask', 'preview']);
      const n = layers.height.length;
      assert.equal(layers.height16.length, n);
      assert.equal(layers.normal_rgb8.length, 3 * n);
      // (c + 1) / 2 · 255 rounded, in f32 arithmetic: within 1 of the same in f64.
      for (let i = 0; i < 3 * n; i++) assert.ok(Math.abs(layers.normal_rgb8[i] - ((layers.normal[i] + 1) / 2) * 255) <= 1, `normal_rgb8[${i}]`);
      for (let i = 1; i < n; i++) {
        if (layers.height[i] < layers.height[i - 1]) assert.ok(layers.height16[i] <= layers.height16[i - 1]);
        if (layers.height[i] > layers.height[i - 1]) assert.ok(layers.height16[i] >= layers.height16[i - 1]);
      }
      assert.ok(new Set(layers.height16).size > 1, 'the heights vary');
    } finally {
      model.free();
    }
  }
});

test('renderAsync on 1, 2 and 3 worker threads draws the bytes of render(), every model and layer', async () => {
  const { mismatches, compared } = await compareBands(hibi);
  assert.deepEqual(mismatches, []);
  assert.equal(compared, 2 * 3 * 7 * 3, 'every model, round, worker count and layer');
});

test('renderAsync: bad options and a bad view reject with a HibiError naming them', async () => {
  const mud = new Mud({ columns: 8, rows: 8 });
  try {
    mud.step(1_000_000);
    for (const threads of [0, 1.5, '2', -1, NaN, 65, Infinity]) {
      await assert.rejects(mud.renderAsync(['mask'], undefined, { threads }), (e) => {
        assert.ok(e instanceof HibiError, `threads ${threads}: a HibiError`);
        assert.equal(e.message, 'mud: threads must be an integer in 1..=64');
        return true;
      });
    }
    await assert.rejects(mud.renderAsync(['mask'], undefined, 2), /^HibiError: mud: renderAsync's options must be an object$/);
    await assert.rejects(mud.renderAsync(['colour'], undefined, { threads: 2 }), /^HibiError: render: no layer is named colour/);
    await assert.rejects(mud.renderAsync(['mask'], { bump: 'x' }, { threads: 2 }), /^HibiError: render: bump must be a number$/);
    // The core's own refusals come back from the workers, by the same message as render()'s.
    for (const [layers, view] of [[['mask'], { width_scale: -1 }], [['cell'], undefined], [['mask'], { width: 0 }]]) {
      let want;
      try {
        mud.render(layers, view);
      } catch (e) {
        want = e.message;
      }
      assert.ok(want, 'render() refuses it');
      await assert.rejects(mud.renderAsync(layers, view, { threads: 2 }), (e) => e instanceof HibiError && e.message === want);
    }
    // The workers still draw after the refusals.
    assert.deepEqual((await mud.renderAsync(['mask'], undefined, { threads: 2 })).layers.mask, mud.render(['mask']).layers.mask);
  } finally {
    mud.free();
  }
});

/** This process's threads (Linux): each worker_threads Worker is one. */
const threadCount = () => Number(readFileSync('/proc/self/status', 'utf8').match(/^Threads:\s+(\d+)/m)[1]);

const pause = (ms) => new Promise((r) => setTimeout(r, ms));

/** The thread count once no thread is ending (two readings 100 ms apart agree). */
async function steady() {
  let n = threadCount();
  for (let i = 0; i < 50; i++) {
    await pause(100);
    if (threadCount() === n) break;
    n = threadCount();
  }
  return n;
}

/** The thread count once it is at most `want` (or 5 s have passed). */
async function settle(want) {
  for (let i = 0; i < 200 && threadCount() > want; i++) await pause(25);
  return threadCount();
}

test('free() ends the render workers: 100 create/renderAsync/free cycles leave no thread behind', { skip: !existsSync('/proc/self/status') }, async () => {
  await cycles(hibi, 3);
  const threads = await steady();
  const memory = hibi.memoryBytes();
  await cycles(hibi, 100);
  assert.ok((await settle(threads)) <= threads, 'the workers ended');
  assert.equal(hibi.memoryBytes(), memory, 'the main memory is flat');
  // free() while the workers draw: the render rejects, the workers end.
  const skin = new Skin({ width: 200, height: 200 });
  skin.step(1_000_000);
  const pending = skin.renderAsync(['preview', 'normal'], undefined, { threads: 3 });
  skin.free();
  await assert.rejects(pending, /^HibiError: skin: freed while rendering$/);
  await assert.rejects(skin.renderAsync(['mask']), /^HibiError: skin: used after free\(\)$/);
  assert.ok((await settle(threads)) <= threads, 'the workers ended');
  // `using` (Symbol.dispose) ends them too.
  {
    const glass = new Glass({ width: 64, height: 64, impact: [32, 32] });
    glass.step(1_000_000);
    await glass.renderAsync(['mask'], undefined, { threads: 2 });
    assert.ok(threadCount() >= threads + 2, 'two workers run');
    glass[Symbol.dispose ?? Symbol.for('Symbol.dispose')]();
  }
  assert.ok((await settle(threads)) <= threads, 'the workers ended');
});

/** The globals hibi.wasm defines: [{ type, mutable }] (its global section). */
function wasmGlobals(bytes) {
  let at = 8; // magic and version
  const leb = () => {
    let value = 0, shift = 0, byte;
    do {
      byte = bytes[at++];
      value += (byte & 0x7f) * 2 ** shift;
      shift += 7;
    } while (byte & 0x80);
    return value;
  };
  while (at < bytes.length) {
    const id = bytes[at++];
    const size = leb();
    const end = at + size;
    if (id === 6) {
      const globals = [];
      for (let n = leb(); n > 0; n--) {
        const type = bytes[at++];
        const mutable = bytes[at++] === 1;
        // The initial value: a constant expression up to `end` (0x0b).
        for (let op = bytes[at++]; op !== 0x0b; op = bytes[at++]) {
          if (op === 0x41 || op === 0x42 || op === 0x23 || op === 0xd2) leb();
          else if (op === 0x43) at += 4;
          else if (op === 0x44) at += 8;
          else if (op === 0xd0) at++;
        }
        globals.push({ type, mutable });
      }
      return globals;
    }
    at = end;
  }
  return [];
}

test('between calls the module state is its memory: the one mutable global is the stack pointer', () => {
  // renderAsync's workers hold copies of the memory in fresh instances of the module: that is
  // the same state only if no other mutable global (thread-local storage, a second stack)
  // holds any of it. The stack pointer is back at its start between calls.
  const globals = wasmGlobals(readFileSync(new URL('../hibi.wasm', import.meta.url)));
  assert.deepEqual(globals.filter((g) => g.mutable), [{ type: 0x7f, mutable: true }]);
});
