// The browser bench's cases (web/bench/native does the same on the host): each model
// generated and rendered RUNS times through hibi.js; the median milliseconds of each. And
// benchThreads: renderAsync's speed-up on workers for 2048-pixel pictures.
import { init, memoryBytes, Mud, Glass, Skin } from '../hibi.js';

const RUNS = 5;
const BUDGET = 1_000_000_000;
const median = (v) => v.slice().sort((a, b) => a - b)[Math.floor(v.length / 2)];

function time(make, draw) {
  const generate = [], render = [];
  for (let i = 0; i < RUNS; i++) {
    let t = performance.now();
    const model = make();
    while (!model.step(BUDGET).finished) {}
    generate.push(performance.now() - t);
    t = performance.now();
    draw(model);
    render.push(performance.now() - t);
    model.free();
  }
  return { generate_ms: median(generate), render_ms: median(render) };
}

export async function bench() {
  await init();
  return [
    { case: 'mud fig6a 96² (render 512 px)', ...time(() => new Mud(Mud.preset('fig6a', { columns: 96, rows: 96 })), (m) => m.render(['preview'], m.view(512))) },
    { case: 'glass defaults 640²', ...time(() => new Glass(), (g) => g.render(['preview'], { width: 640, height: 640 })) },
    { case: 'skin fig19a 400²', ...time(() => new Skin(Skin.preset('fig19a')), (s) => s.render(['preview'])) },
  ];
}

/** Milliseconds one call of `f` (which may be async) takes. */
async function timeAsync(f) {
  const t = performance.now();
  await f();
  return performance.now() - t;
}

/** Skin preset `name` at `size`² with its spacings scaled from the paper's 400 px, as the
 * CLI's `hibi skin --size` does: the paper's field, in more pixels. */
function scaled(name, size) {
  const p = Skin.preset(name, { width: size, height: size });
  for (const l of p.level) l.spacing = Math.max(1, Math.fround(l.spacing * Math.fround(size / 400)));
  return p;
}

/**
 * renderAsync's speed-up: each model's 2048-pixel preview (and two small ones) drawn by
 * render() on this thread, by renderAsync on 1 worker and on 2, warm (the workers hold the
 * model's memory) and on 2 cold (the model stepped since: the call sends a copy of memory first).
 * The fastest of RUNS runs of each, the four ways taken in turn.
 */
export async function benchThreads() {
  await init();
  const cases = [
    // Small pictures first (memory only grows): the workers' start and the copy of memory weigh more.
    ['mud fig6a 96², 512 px wide', () => new Mud(Mud.preset('fig6a', { columns: 96, rows: 96 })), (m) => m.view(512)],
    ['skin fig19a 400²', () => new Skin(Skin.preset('fig19a')), (s) => s.view()],
    ['mud fig6a 96², 2048 px wide', () => new Mud(Mud.preset('fig6a', { columns: 96, rows: 96 })), (m) => m.view(2048)],
    ['glass defaults on a 2048² plate', () => new Glass({ width: 2048, height: 2048, impact: [1024, 1024] }), (g) => g.view()],
    ['skin fig19a 2048² (spacings ×5.12)', () => new Skin(scaled('fig19a', 2048)), (s) => s.view()],
  ];
  const results = [];
  for (const [name, make, view] of cases) {
    const model = make();
    try {
      while (!model.step(BUDGET).finished) {}
      const v = view(model);
      const layers = ['preview'];
      await model.renderAsync(layers, v, { threads: 2 }); // the workers start
      // The four ways in turn, RUNS times, so that a change of the machine's load falls on all.
      const ways = {
        one: () => model.render(layers, v),
        warm1: () => model.renderAsync(layers, v, { threads: 1 }),
        cold2: () => {
          model.step(0); // a step, even of no work, makes the workers' copies stale
          return model.renderAsync(layers, v, { threads: 2 });
        },
        warm2: () => model.renderAsync(layers, v, { threads: 2 }),
      };
      const times = Object.fromEntries(Object.keys(ways).map((k) => [k, []]));
      for (let i = 0; i < RUNS; i++) {
        for (const [way, f] of Object.entries(ways)) times[way].push(await timeAsync(f));
      }
      const row = { case: name, width: v.width ?? model.params.width, height: v.height ?? model.params.height, memory_bytes: memoryBytes() };
      for (const [way, t] of Object.entries(times)) row[`${way}_ms`] = Math.min(...t);
      results.push(row);
    } finally {
      model.free();
    }
  }
  return results;
}
