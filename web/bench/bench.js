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

/** Medians of RUNS calls of `f` (which may be async), in milliseconds. */
async function timeAsync(f) {
  const times = [];
  for (let i = 0; i < RUNS; i++) {
    const t = performance.now();
    await f();
    times.push(performance.now() - t);
  }
  return median(times);
}

/** Skin preset `name` at `size`² with its spacings scaled from the paper's 400 px, as the
 * CLI's `hibi skin --size` does: the paper's field, in more pixels. */
function scaled(name, size) {
  const p = Skin.preset(name, { width: size, height: size });
  for (const l of p.level) l.spacing = Math.max(1, Math.fround(l.spacing * Math.fround(size / 400)));
  return p;
}

/**
 * renderAsync's speed-up: each model's 2048-pixel preview drawn by render() on this thread,
 * then by renderAsync on 1 and 2 workers: warm (the workers hold the model's memory) and
 * cold (the model stepped since: each call sends a copy of memory first). Medians of RUNS.
 */
export async function benchThreads() {
  await init();
  const cases = [
    ['mud fig6a 96², 2048 px wide', () => new Mud(Mud.preset('fig6a', { columns: 96, rows: 96 })), (m) => m.view(2048)],
    ['glass defaults on a 2048² plate', () => new Glass({ width: 2048, height: 2048, impact: [1024, 1024] }), (g) => g.view()],
    ['skin fig19a at 2048² (spacings × 5.12)', () => new Skin(scaled('fig19a', 2048)), (s) => s.view()],
  ];
  const results = [];
  for (const [name, make, view] of cases) {
    const model = make();
    try {
      while (!model.step(BUDGET).finished) {}
      const v = view(model);
      const layers = ['preview'];
      const one = await timeAsync(() => model.render(layers, v));
      const row = { case: name, width: v.width ?? model.params.width, height: v.height ?? model.params.height, memory_bytes: memoryBytes(), one_ms: one };
      for (const threads of [1, 2]) {
        await model.renderAsync(layers, v, { threads }); // the workers start and take a copy
        row[`warm${threads}_ms`] = await timeAsync(() => model.renderAsync(layers, v, { threads }));
        row[`cold${threads}_ms`] = await timeAsync(() => {
          model.step(0); // a step, even of no work, makes the workers' copies stale
          return model.renderAsync(layers, v, { threads });
        });
      }
      results.push(row);
    } finally {
      model.free();
    }
  }
  return results;
}
