// The browser bench's cases (web/bench/native does the same on the host): each model
// generated and rendered RUNS times through hibi.js; the median milliseconds of each.
import { init, Mud, Glass, Skin } from '../hibi.js';

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
