// The golden scenes of targets/scenes (the list `targets/run` checks on every target), made
// through the JavaScript API: each scene's FNV-1a 64 hash over the same bytes, in the same
// order, as targets/scenes/src/lib.rs hashes them. Runs in Node, in a page and in a Worker.

/** FNV-1a 64 over bytes fed piece by piece (two 32-bit halves: no BigInt in the loop). */
export class Fnv {
  constructor() {
    this.hi = 0xcbf29ce4;
    this.lo = 0x84222325;
    this.scratch = new DataView(new ArrayBuffer(8));
  }
  bytes(bytes) {
    let { hi, lo } = this;
    for (let i = 0; i < bytes.length; i++) {
      lo ^= bytes[i];
      // (hi, lo) *= 0x100000001b3: lo·0x1b3, hi·0x1b3 + lo·0x100 (mod 2^64).
      const l = lo >>> 0;
      const lLow = (l & 0xffff) * 0x1b3;
      const lHigh = (l >>> 16) * 0x1b3;
      const low = lLow + ((lHigh & 0xffff) << 16) >>> 0;
      const carry = Math.floor((lLow + (lHigh & 0xffff) * 65536) / 4294967296) + Math.floor(lHigh / 65536);
      hi = (Math.imul(hi, 0x1b3) + Math.imul(l, 0x100) + carry) >>> 0;
      lo = low;
    }
    this.hi = hi;
    this.lo = lo;
  }
  u32(v) {
    this.scratch.setUint32(0, v, true);
    this.bytes(new Uint8Array(this.scratch.buffer, 0, 4));
  }
  f32(v) {
    this.scratch.setFloat32(0, v, true);
    this.bytes(new Uint8Array(this.scratch.buffer, 0, 4));
  }
  f64(v) {
    this.scratch.setFloat64(0, v, true);
    this.bytes(new Uint8Array(this.scratch.buffer, 0, 8));
  }
  /** An array's bytes as they lie in memory (little-endian on every platform JS runs on). */
  array(typed) {
    this.bytes(new Uint8Array(typed.buffer, typed.byteOffset, typed.byteLength));
  }
  finish() {
    return ((BigInt(this.hi) << 32n) | BigInt(this.lo)).toString();
  }
}

const hashOf = (typed) => {
  const h = new Fnv();
  h.array(typed);
  return h.finish();
};

function finish(model, budget) {
  while (!model.step(budget).finished) {}
  return model;
}

function segments(mud) {
  return hashOf(mud.segments());
}

function network(mud) {
  const { vertices, edges, points } = mud.network();
  const h = new Fnv();
  for (let i = 0; i < vertices.count; i++) {
    h.f32(vertices.at[2 * i]);
    h.f32(vertices.at[2 * i + 1]);
    h.u32(vertices.degree[i]);
    h.u32(vertices.onBorder[i]);
  }
  for (let i = 0; i < edges.count; i++) {
    for (const v of [edges.from[i], edges.to[i], edges.firstPoint[i], edges.pointCount[i]]) h.u32(v);
  }
  for (let i = 0; i < points.count; i++) {
    for (const v of [points.at[2 * i], points.at[2 * i + 1], points.width[i], points.time[i]]) h.f32(v);
  }
  return h.finish();
}

function rings(h, { rings, points }) {
  for (let i = 0; i < rings.count; i++) {
    h.f64(rings.area[i]);
    for (const v of [rings.firstPoint[i], rings.pointCount[i], rings.holeOf[i]]) h.u32(v);
  }
  h.array(points);
  return h;
}

function cracks(glass) {
  const { ends, pointCounts, points } = glass.cracks();
  const h = new Fnv();
  let p = 0;
  for (let i = 0; i < ends.length; i++) {
    h.u32(ends[i]);
    h.array(points.subarray(p, p + 3 * pointCounts[i]));
    p += 3 * pointCounts[i];
  }
  return h.finish();
}

function outlines(skin) {
  const c = skin.cells();
  const h = new Fnv();
  let v = 0;
  for (let i = 0; i < c.count; i++) {
    h.u32(c.site[i]);
    h.array(c.vertices.subarray(2 * v, 2 * (v + c.vertexCount[i])));
    v += c.vertexCount[i];
  }
  return h.finish();
}

/** Runs every scene the JavaScript API can make; returns { name: hash as a decimal string }. */
export function runScenes({ Mud, Glass, Skin }) {
  const out = {};
  const mudRun = (params) => finish(new Mud(params), 1_000_000);
  const use = (model, f) => {
    try {
      return f(model);
    } finally {
      model.free();
    }
  };
  use(mudRun({ columns: 64, rows: 64 }), (m) => (out['mud.hex64.f32.segments'] = segments(m)));
  use(mudRun({ columns: 32, rows: 32 }), (m) => {
    out['mud.hex32.f32.segments'] = segments(m);
    out['mud.hex32.f32.network'] = network(m);
    const c = m.cells();
    const h = rings(new Fnv(), c);
    h.u32(c.wrapping);
    out['mud.hex32.f32.cells'] = h.finish();
    const view = { width: 128, height: 128 };
    out['mud.hex32.f32.mask'] = hashOf(m.render(['mask'], view).layers.mask);
    out['mud.hex32.f32.time'] = hashOf(m.render(['time'], view).layers.time);
    out['mud.hex32.f32.height'] = hashOf(m.render(['height'], view).layers.height);
  });
  use(mudRun({ columns: 32, rows: 32, topology: 'irregular' }), (m) => (out['mud.irregular32.f32.segments'] = segments(m)));
  use(finish(new Glass({ width: 160, height: 160, impact: [80, 80], seed: 7 }), 100_000), (g) => {
    out['glass.plate160.cracks'] = cracks(g);
    out['glass.plate160.fragments'] = rings(new Fnv(), g.fragments()).finish();
    const view = { width: 160, height: 160 };
    out['glass.plate160.mask'] = hashOf(g.render(['mask'], view).layers.mask);
    out['glass.plate160.time'] = hashOf(g.render(['time'], view).layers.time);
  });
  use(finish(new Skin(Skin.preset('fig19a', { width: 64, height: 64 })), 1_000_000), (s) => {
    out['skin.fig19a64.outlines'] = outlines(s);
    const maps = s.render(['height', 'normal']).layers;
    const h = new Fnv();
    h.array(maps.height);
    h.array(maps.normal);
    out['skin.fig19a64.f32.maps'] = h.finish();
    const cells = new Fnv();
    for (let level = 0; level < s.params.levels; level++) cells.array(s.render(['cell'], { cell_level: level }).layers.cell);
    out['skin.fig19a64.cell_maps'] = cells.finish();
  });
  use(mudRun({ columns: 16, rows: 16 }), (m) => (out['small.mud.hex16.f32.segments'] = segments(m)));
  const small = { width: 128, height: 128, impact: [64, 64], seed: 7, radial_mean: 40, max_cracks: 44, max_vertices: 175 };
  use(finish(new Glass(small), 100_000), (g) => {
    out['small.glass128.cracks'] = cracks(g);
    out['small.glass128.mask'] = hashOf(g.render(['mask'], { width: 128, height: 128 }).layers.mask);
  });
  use(finish(new Skin(Skin.preset('fig13a', { width: 64, height: 64 })), 1_000_000), (s) => {
    out['small.skin64.outlines'] = outlines(s);
    out['small.skin64.f32.height'] = hashOf(s.render(['height']).layers.height);
  });
  return out;
}
