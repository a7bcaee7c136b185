// The playground's worker: it owns the model, grows it one budgeted step per frame the page
// asks for, draws the chosen layer as RGBA and writes the SVG export. The page's thread only
// puts pixels on the canvas.
import { init, Mud, Glass, Skin } from '../hibi.js';

const MODELS = { mud: Mud, glass: Glass, skin: Skin };
/** Work per step at the start, then adjusted so that a step takes about STEP_MS. */
const FIRST_BUDGET = { mud: 200_000, glass: 4_000, skin: 5_000 };
/** At most this much work per step, so that a fast model's growth still spans many frames
 * (glass's default plate is about 270,000 units, skin's fig19a about 210,000). */
const MAX_BUDGET = { mud: Infinity, glass: 10_000, skin: 10_000 };
const STEP_MS = 12;
/** Mud's raster width (the lattice's aspect sets its height). */
const MUD_WIDTH = 640;

let run = null; // { id, name, model, view, layer, budget, hits, hitsDone, dirty }

const ready = init();

onmessage = async (e) => {
  await ready;
  const m = e.data;
  try {
    if (m.type === 'start') start(m);
    else if (m.type === 'frame') frame();
    else if (m.type === 'layer') {
      run.layer = m.layer;
      run.dirty = true;
      frame();
    } else if (m.type === 'impact') {
      run.hits.push([m.x, m.y]);
      run.dirty = true;
    } else if (m.type === 'svg') postMessage({ type: 'svg', text: svg() });
  } catch (error) {
    postMessage({ type: 'error', message: error.message, id: run?.id });
  }
};

function start({ id, name, params, layer, hits }) {
  run?.model.free();
  run = null;
  const model = new MODELS[name](params);
  const view = name === 'mud' ? model.view(MUD_WIDTH) : model.view();
  run = { id, name, model, view, layer, budget: FIRST_BUDGET[name], hits: hits.slice(), hitsDone: 0, dirty: true };
  const [width, height] = size();
  postMessage({ type: 'started', id, params: model.params, width, height, extent: name === 'mud' ? model.extent : null });
}

function size() {
  const { name, model, view } = run;
  return name === 'skin' ? [model.params.width, model.params.height] : [view.width, view.height];
}

/** One frame: a budgeted step (or the next queued impact), then the layer. */
function frame() {
  if (!run) return;
  const { model } = run;
  let progress = model.progress;
  if (progress.finished && run.hitsDone < run.hits.length) {
    const [x, y] = run.hits[run.hitsDone++];
    model.impact(x, y);
    progress = model.progress;
  }
  const growing = !progress.finished;
  if (growing) {
    const t = performance.now();
    progress = model.step(run.budget);
    const ms = performance.now() - t;
    const adjusted = Math.round(run.budget * Math.min(2, Math.max(0.5, STEP_MS / Math.max(ms, 0.5))));
    run.budget = Math.min(MAX_BUDGET[run.name], Math.max(1000, adjusted));
  }
  if (!growing && !run.dirty) {
    postMessage({ type: 'idle', id: run.id, progress, fraction: 1, finished: true, pending: run.hits.length - run.hitsDone });
    return;
  }
  run.dirty = false;
  const rgba = draw();
  const [width, height] = size();
  const finished = progress.finished && run.hitsDone === run.hits.length;
  postMessage(
    { type: 'frame', id: run.id, width, height, rgba, progress, fraction: fraction(progress), finished, pending: run.hits.length - run.hitsDone },
    [rgba.buffer],
  );
}

function fraction(p) {
  if (p.finished) return 1;
  const params = run.model.params;
  if (run.name === 'mud') {
    const f = params.target_shrink > 0 ? p.shrink / params.target_shrink : 0;
    return Math.min(1, Math.max(0, f));
  }
  if (run.name === 'skin') return p.root_total ? p.roots / p.root_total : 0;
  return null; // glass: no known end
}

// --- Layers as pictures ----------------------------------------------------------------------

function draw() {
  const { model, layer } = run;
  const view = run.name === 'skin' ? undefined : run.view;
  if (layer === 'cells') return cells();
  const r = model.render([layer], view);
  const n = r.width * r.height;
  const out = new Uint8ClampedArray(4 * n);
  const data = r.layers[layer];
  if (layer === 'preview') {
    out.set(data);
  } else if (layer === 'mask') {
    for (let i = 0; i < n; i++) gray(out, i, 255 - data[i]);
  } else if (layer === 'height') {
    let lo = Infinity, hi = -Infinity;
    for (const v of data) if (Number.isFinite(v)) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
    const k = hi > lo ? 255 / (hi - lo) : 0;
    // Low (grooves) dark brown to high cream.
    for (let i = 0; i < n; i++) {
      const v = (data[i] - lo) * k;
      out.set([30 + 0.9 * v, 22 + 0.85 * v, 16 + 0.75 * v, 255], 4 * i);
    }
  } else if (layer === 'normal') {
    for (let i = 0; i < n; i++) {
      for (let c = 0; c < 3; c++) out[4 * i + c] = (data[3 * i + c] + 1) * 127.5;
      out[4 * i + 3] = 255;
    }
  } else if (layer === 'time') {
    // First crack dark blue, last yellow.
    let lo = Infinity, hi = -Infinity;
    for (const v of data) if (Number.isFinite(v)) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
    for (let i = 0; i < n; i++) {
      if (Number.isFinite(data[i])) ramp(out, i, hi > lo ? (data[i] - lo) / (hi - lo) : 0);
      else out.set([250, 248, 244, 255], 4 * i);
    }
  }
  return out;
}

function gray(out, i, v) {
  out[4 * i] = out[4 * i + 1] = out[4 * i + 2] = v;
  out[4 * i + 3] = 255;
}

/** Early (dark blue) to late (yellow). */
function ramp(out, i, t) {
  const stops = [[68, 1, 84], [59, 82, 139], [33, 145, 140], [94, 201, 98], [253, 231, 37]];
  const x = Math.min(0.9999, Math.max(0, t)) * (stops.length - 1);
  const k = Math.floor(x), f = x - k;
  for (let c = 0; c < 3; c++) out[4 * i + c] = stops[k][c] + (stops[k + 1][c] - stops[k][c]) * f;
  out[4 * i + 3] = 255;
}

/** A colour per index, steady from frame to frame. */
function colour(i) {
  let h = Math.imul(i + 1, 0x9e3779b1) >>> 0;
  h ^= h >>> 15;
  h = Math.imul(h, 0x85ebca6b) >>> 0;
  return [110 + (h & 127), 110 + ((h >>> 8) & 127), 110 + ((h >>> 16) & 127)];
}

/** Skin: the coarsest level's cell map; mud's cells and glass's fragments: their polygons. */
function cells() {
  const [width, height] = size();
  if (run.name === 'skin') {
    const cell = run.model.render(['cell'], { cell_level: 0 }).layers.cell;
    const out = new Uint8ClampedArray(4 * width * height);
    for (let i = 0; i < cell.length; i++) {
      out.set(colour(cell[i]), 4 * i);
      out[4 * i + 3] = 255;
    }
    return out;
  }
  const canvas = new OffscreenCanvas(width, height);
  const g = canvas.getContext('2d');
  g.fillStyle = '#2a2826';
  g.fillRect(0, 0, width, height);
  const { rings, points } = run.name === 'mud' ? run.model.cells() : run.model.fragments();
  const scale = run.name === 'mud' ? width / run.model.extent[0] : 1;
  const [ox, oy] = run.name === 'mud' ? run.view.offset : [0, 0];
  // A periodic lattice's cells that cross its edges are drawn on both sides.
  const wrap = run.name === 'mud' && run.model.params.boundary === 'periodic' ? [-1, 0, 1] : [0];
  const [ew, eh] = run.name === 'mud' ? run.model.extent : [0, 0];
  for (let r = 0; r < rings.count; r++) {
    const first = rings.firstPoint[r], count = rings.pointCount[r];
    if (count < 3) continue;
    g.beginPath();
    for (const i of wrap) {
      for (const j of wrap) {
        for (let k = 0; k < count; k++) {
          const x = (points[2 * (first + k)] + i * ew - ox) * scale, y = (points[2 * (first + k) + 1] + j * eh - oy) * scale;
          if (k === 0) g.moveTo(x, y);
          else g.lineTo(x, y);
        }
        g.closePath();
      }
    }
    const hole = rings.holeOf[r] !== 0xffffffff && rings.holeOf[r] < rings.count;
    const [cr, cg, cb] = hole ? [42, 40, 38] : colour(r);
    g.fillStyle = `rgb(${cr},${cg},${cb})`;
    g.fill();
  }
  return g.getImageData(0, 0, width, height).data;
}

// --- SVG export ------------------------------------------------------------------------------

const f = (v) => (Math.round(v * 100) / 100).toString();

/** The crack network (mud), the fragments and cracks (glass) or the cell outlines (skin). */
function svg() {
  const { name, model } = run;
  const [width, height] = size();
  const parts = [];
  let viewBox;
  if (name === 'mud') {
    const [w, h] = model.extent;
    viewBox = `0 0 ${f(w)} ${f(h)}`;
    const { edges, points } = model.network();
    parts.push('<rect width="100%" height="100%" fill="#d9c3a3"/>');
    parts.push('<g fill="none" stroke="#3b2a1e" stroke-linecap="round" stroke-linejoin="round">');
    for (let e = 0; e < edges.count; e++) {
      const first = edges.firstPoint[e], count = edges.pointCount[e];
      let sum = 0;
      const xy = [];
      for (let k = 0; k < count; k++) {
        xy.push(`${f(points.at[2 * (first + k)])},${f(points.at[2 * (first + k) + 1])}`);
        sum += points.width[first + k];
      }
      const width = Math.max(0.08, count ? sum / count : 0.08);
      parts.push(`<polyline class="edge" stroke-width="${f(width)}" points="${xy.join(' ')}"/>`);
    }
    parts.push('</g>');
  } else if (name === 'glass') {
    viewBox = `0 0 ${f(model.params.width)} ${f(model.params.height)}`;
    const { rings, points } = model.fragments();
    parts.push('<g stroke="none">');
    for (let r = 0; r < rings.count; r++) {
      const xy = [];
      for (let k = 0; k < rings.pointCount[r]; k++) {
        const p = rings.firstPoint[r] + k;
        xy.push(`${f(points[2 * p])},${f(points[2 * p + 1])}`);
      }
      const [cr, cg, cb] = colour(r);
      parts.push(`<polygon class="fragment" fill="rgb(${cr},${cg},${cb})" points="${xy.join(' ')}"/>`);
    }
    parts.push('</g>');
    const cracks = model.cracks();
    parts.push('<g fill="none" stroke="#111" stroke-width="1" stroke-linecap="round">');
    let p = 0;
    for (let c = 0; c < cracks.ends.length; c++) {
      const xy = [];
      for (let k = 0; k < cracks.pointCounts[c]; k++, p++) xy.push(`${f(cracks.points[3 * p])},${f(cracks.points[3 * p + 1])}`);
      parts.push(`<polyline class="crack" points="${xy.join(' ')}"/>`);
    }
    parts.push('</g>');
  } else {
    viewBox = `0 0 ${width} ${height}`;
    const c = model.cells();
    const unit = 2 ** c.fixedPointBits;
    parts.push('<rect width="100%" height="100%" fill="#5a3a30"/>');
    let v = 0;
    for (let i = 0; i < c.count; i++) {
      const xy = [];
      for (let k = 0; k < c.vertexCount[i]; k++, v++) {
        xy.push(`${f(Number(c.vertices[2 * v]) / unit)},${f(Number(c.vertices[2 * v + 1]) / unit)}`);
      }
      const opacity = Math.max(0.25, 1 - 0.25 * c.level[i]);
      parts.push(`<polygon class="cell" data-level="${c.level[i]}" fill="#e8b9a0" fill-opacity="${opacity}" stroke="#5a3a30" stroke-width="${f(1.5 / (1 + c.level[i]))}" points="${xy.join(' ')}"/>`);
    }
  }
  return [
    `<svg xmlns="http://www.w3.org/2000/svg" viewBox="${viewBox}" width="${width}" height="${height}">`,
    `<title>hibi ${name}</title>`,
    ...parts,
    '</svg>',
  ].join('\n');
}
