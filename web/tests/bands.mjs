// renderAsync against render(), for Node (node.test.mjs) and Chromium (bands.html): each
// model's every layer drawn in bands on 1, 2 and 3 workers, compared byte for byte with the
// one-thread render, also after the model steps again (the workers get a new copy of memory)
// and with a view that is not the default.

/** Every layer each model draws. */
const LAYERS = {
  mud: ['mask', 'height', 'normal', 'time', 'preview', 'height16', 'normal_rgb8'],
  glass: ['mask', 'height', 'normal', 'time', 'preview', 'height16', 'normal_rgb8'],
  skin: ['mask', 'height', 'normal', 'cell', 'preview', 'height16', 'normal_rgb8'],
};

/** Work budgets that leave each model part-grown. */
const PART = { mud: 2_000, glass: 2_000, skin: 200 };

const bytes = (typed) => new Uint8Array(typed.buffer, typed.byteOffset, typed.byteLength);

/** The first byte where `a` and `b` differ, or -1 (and -2 for another length). */
function differ(a, b) {
  const x = bytes(a), y = bytes(b);
  if (x.length !== y.length) return -2;
  for (let i = 0; i < x.length; i++) if (x[i] !== y[i]) return i;
  return -1;
}

/** Compares renderAsync on 1, 2 and 3 workers with render(); returns the list of mismatches
 * (empty when every byte is the same) and how many layers were compared. */
export async function compareBands(hibi) {
  const { Mud, Glass, Skin } = hibi;
  // Odd heights: the last band is shorter than the others. Each model is drawn part-grown,
  // then grown to the end (glass hit once more first): the workers draw the new state.
  const cases = [
    ['mud', () => new Mud({ columns: 24, rows: 20, seed: 3 }), (m) => m.view(181), null],
    ['glass', () => new Glass({ width: 150, height: 101, impact: [70, 50], seed: 5 }), () => ({ width: 150, height: 101, bump: 3 }), (g) => g.impact(120, 30)],
    ['skin', () => new Skin({ width: 90, height: 77, levels: 2, seed: 9 }), () => ({ cell_level: 1 }), null],
  ];
  const mismatches = [];
  let compared = 0;
  for (const [name, make, view, more] of cases) {
    const model = make();
    try {
      for (const round of [0, 1]) {
        if (round === 0 && model.step(PART[name]).finished) mismatches.push(`${name}: finished within the part budget`);
        if (round === 1) {
          while (!model.step(1_000_000).finished) {}
          if (more) {
            more(model);
            while (!model.step(1_000_000).finished) {}
          }
        }
        const v = view(model);
        const one = model.render(LAYERS[name], v);
        for (const threads of [1, 2, 3]) {
          const many = await model.renderAsync(LAYERS[name], v, { threads });
          if (many.width !== one.width || many.height !== one.height) mismatches.push(`${name} ${threads}: size`);
          for (const layer of LAYERS[name]) {
            const at = differ(one.layers[layer], many.layers[layer]);
            if (at !== -1) mismatches.push(`${name} round ${round}, ${threads} workers, ${layer}: byte ${at} differs`);
            compared++;
          }
        }
      }
    } finally {
      model.free();
    }
  }
  return { mismatches, compared };
}

/** `count` times: a model, a render on a worker, free(). */
export async function cycles(hibi, count) {
  for (let i = 0; i < count; i++) {
    const skin = new hibi.Skin({ width: 48, height: 40, levels: 1, seed: i });
    skin.step(1_000_000);
    await skin.renderAsync(['mask'], undefined, { threads: 1 });
    skin.free();
  }
}
