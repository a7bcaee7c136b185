// Type-checked by web/tests/node.test.mjs (tsc --noEmit --strict): the calls a TypeScript
// user writes, against hibi.d.ts. Compiling is the test; it is not run.
import { init, Mud, Glass, Skin, HibiError, toImageData, memoryBytes } from '../hibi.js';
import type { MudParams, Render, Rings, GlassProgress, RenderOptions } from '../hibi.js';

await init();
const params: MudParams = Mud.preset('fig7a', { columns: 48, rows: 48, topology: 'square' });
const mud = new Mud(params);
const progress = mud.step(1_000_000);
const finished: boolean = progress.finished;
const shrink: number = mud.progress.shrink;
const render: Render = mud.render(['mask', 'preview'], { width: 256, height: 256, until: Infinity });
const mask: Uint8Array | undefined = render.layers.mask;
const network = mud.network();
const firstEdge: number = network.edges.from[0];
const cells: Rings & { wrapping: number } = mud.cells();
const [w, h]: [number, number] = mud.extent;
const options: RenderOptions = { threads: 2 };
const banded: Render = await mud.renderAsync(['height16'], { width: 512, height: 512 }, options);
const height16: Uint16Array | undefined = banded.layers.height16;
// @ts-expect-error: threads is a number
void mud.renderAsync(['mask'], undefined, { threads: '2' });
mud.free();

const glass = new Glass({ impact: [100, 120], seed: 2n ** 60n, spread: 'uniform' });
const gp: GlassProgress = glass.step(10_000);
const counts = glass.impact(50, 60);
const radial: number = counts.radial;
const points: Float32Array = glass.cracks().points;
const fragments: Rings = glass.fragments();
glass[Symbol.dispose]();

const skin = new Skin({ levels: 2, level: [{ spacing: 30, stretch: [1, 2] }], layout: 'random' });
skin.step(1_000);
const picture: ImageData = toImageData(skin.render(['preview'], { cell_level: 1, shade: { ambient: 0.5 } }));
const outline: BigInt64Array = skin.cells().vertices;
skin.free();

try {
  new Skin({ periodic: true, jitter: 'normal' });
} catch (e) {
  if (e instanceof HibiError) console.log(e.message);
}
const bytes: number = memoryBytes();
const presets: readonly string[] = [...Mud.presets, ...Glass.presets, ...Skin.presets];

// @ts-expect-error: an enumeration takes its names only
new Mud({ topology: 'round' });
// @ts-expect-error: no such layer
mud.render(['colour']);

export { finished, shrink, mask, height16, firstEdge, cells, w, h, gp, radial, points, fragments, picture, outline, bytes, presets };
