// The playground's page: controls, the URL, the canvas. The model lives in worker.js; this
// thread asks it for one frame per animation frame and puts the pixels it sends on the canvas.
import { init, Mud, Glass, Skin } from '../hibi.js';

const MODELS = { mud: Mud, glass: Glass, skin: Skin };
const DEFAULT_PRESET = { mud: 'fig6a', glass: 'fig14b', skin: 'fig19a' };
/** Sizes the playground starts from (the presets' own are for print). */
const SIZE = { mud: { columns: 96, rows: 96 }, glass: {}, skin: { width: 480, height: 480 } };

// The parameters that matter, labelled with the papers' names: [path, label, min, max, step].
const SLIDERS = {
  mud: [
    ['columns', 'Lattice nodes across', 16, 192, 2],
    ['break_stretch_mean', 'Mean break stretch κ̄', 1.005, 1.05, 0.001],
    ['break_stretch_spread', 'Break stretch spread σ', 0, 0.01, 0.0005],
    ['shear_modulus', 'Shear modulus G', 25000, 500000, 5000],
    ['target_shrink', 'Final shrink 1 − r', 0.005, 0.06, 0.001],
    ['anisotropy_ratio', 'Anisotropy of κ (Fig. 7)', 1, 3, 0.05],
    ['anisotropy_direction', 'Anisotropy direction [rad]', 0, 3.14, 0.01],
  ],
  glass: [
    ['radial_mean', 'Radial cracks M_ave', 10, 200, 1],
    ['large_speed', 'Large crack speed V1_ave', 5, 80, 1],
    ['radial_speed', 'Radial crack speed V2_ave', 1, 40, 1],
    ['turn_limit', 'Turn limit θ_th [rad]', 0.05, 1.5, 0.01],
    ['sector_angle', 'Sector angle φ [rad]', 0.2, 3, 0.01],
    ['sector_radius', 'Sector radius B [px]', 5, 150, 1],
    ['spread_ratio', 'Spread z of Rand(x)', 0, 0.9, 0.01],
  ],
  skin: [
    ['levels', 'Hierarchy levels (parameter 4)', 1, 4, 1],
    ['jitter_ratio', 'Jitter (parameter 1)', 0, 1, 0.01],
    ['level.0.spacing', 'Cell spacing L [px]', 10, 120, 1],
    ['level.0.perturbation', 'Edge perturbation A (parameter 2)', 0, 0.5, 0.01],
    ['level.0.stretch.0', 'Stretch Sx (parameter 3)', 0.3, 3, 0.05],
    ['level.0.stretch.1', 'Stretch Sy (parameter 3)', 0.3, 3, 0.05],
    ['level.0.roundness', 'Roundness (parameter 6)', 0, 1, 0.01],
  ],
};
const LAYERS = {
  mud: ['preview', 'mask', 'height', 'normal', 'time', 'cells'],
  glass: ['preview', 'mask', 'height', 'normal', 'time', 'cells'],
  skin: ['preview', 'mask', 'height', 'normal', 'cells'],
};
const HINTS = {
  mud: 'A surface layer shrinks on a deep layer; springs past their break stretch snap, and cracks close into cells.',
  glass: 'Click on the plate to hit it again: new radial and ring cracks grow from each impact.',
  skin: 'Voronoi cells in a hierarchy of levels; each cell is raised by its cross-section profile.',
};

const $ = (id) => document.getElementById(id);
const canvas = $('canvas');
const context = canvas.getContext('2d');

/** The state the URL holds. */
const state = { model: 'mud', preset: 'fig6a', seed: 1, layer: 'preview', overrides: {}, hits: [] };
let runId = 0;
let current = null; // what the worker runs: { id, params, width, height, finished, progress }
let waiting = false; // a frame was asked for and has not come back
let idle = false; // the run is finished and nothing changed
let frames = 0; // frames drawn since the run started
const worker = new Worker(new URL('./worker.js', import.meta.url), { type: 'module' });

const get = (object, path) => path.split('.').reduce((o, k) => o?.[k], object);
function set(object, path, value) {
  const keys = path.split('.');
  let o = object;
  for (const k of keys.slice(0, -1)) o = o[k];
  o[keys[keys.length - 1]] = value;
}

// --- The URL -------------------------------------------------------------------------------

function readUrl() {
  const q = new URLSearchParams(location.search);
  if (MODELS[q.get('model')]) state.model = q.get('model');
  state.preset = q.get('preset') ?? DEFAULT_PRESET[state.model];
  if (q.has('seed') && /^\d+$/.test(q.get('seed'))) state.seed = Number(q.get('seed'));
  if (q.has('layer')) state.layer = q.get('layer');
  if (!LAYERS[state.model].includes(state.layer)) state.layer = 'preview';
  state.overrides = {};
  for (const [key, value] of q) {
    if (key.startsWith('p.') && SLIDERS[state.model].some((s) => s[0] === key.slice(2)) && Number.isFinite(Number(value))) {
      state.overrides[key.slice(2)] = Number(value);
    }
  }
  state.hits = (q.get('hits') ?? '').split(';').filter(Boolean).map((h) => h.split(',').map(Number)).filter((h) => h.length === 2 && h.every(Number.isFinite));
}

/** The link that restores the picture. */
function link() {
  const q = new URLSearchParams();
  q.set('model', state.model);
  q.set('preset', state.preset);
  q.set('seed', String(state.seed));
  q.set('layer', state.layer);
  for (const [k, v] of Object.entries(state.overrides)) q.set(`p.${k}`, String(v));
  if (state.hits.length) q.set('hits', state.hits.map(([x, y]) => `${Math.round(x)},${Math.round(y)}`).join(';'));
  return `${location.origin}${location.pathname}?${q}`;
}

function writeUrl() {
  history.replaceState(null, '', link());
}

// --- Controls ------------------------------------------------------------------------------

function params() {
  const Model = MODELS[state.model];
  const p = structuredClone(Model.preset(state.preset, SIZE[state.model]));
  p.seed = state.seed;
  for (const [path, value] of Object.entries(state.overrides)) set(p, path, value);
  if (state.model === 'mud') p.rows = p.columns;
  return p;
}

function buildControls() {
  const Model = MODELS[state.model];
  $('model').value = state.model;
  $('preset').replaceChildren(...Model.presets.map((name) => new Option(name, name)));
  if (!Model.presets.includes(state.preset)) state.preset = DEFAULT_PRESET[state.model];
  $('preset').value = state.preset;
  $('seed').value = state.seed;
  $('hint').textContent = HINTS[state.model];
  const base = params();
  const sliders = SLIDERS[state.model].map(([path, label, min, max, step]) => {
    const div = document.createElement('div');
    div.className = 'slider';
    const id = `s-${path.replaceAll('.', '-')}`;
    const value = get(base, path);
    div.innerHTML = `<label class="name" for="${id}"><span></span><output></output></label><input id="${id}" type="range">`;
    div.querySelector('span').textContent = label;
    const input = div.querySelector('input');
    Object.assign(input, { min, max, step, value });
    input.dataset.path = path;
    const output = div.querySelector('output');
    output.textContent = format(value);
    input.addEventListener('input', () => (output.textContent = format(Number(input.value))));
    input.addEventListener('change', () => {
      state.overrides[path] = Number(input.value);
      restart();
    });
    return div;
  });
  $('sliders').replaceChildren(Object.assign(document.createElement('legend'), { textContent: 'Parameters' }), ...sliders);
  $('layers').replaceChildren(...LAYERS[state.model].map((layer) => {
    const b = document.createElement('button');
    b.textContent = layer;
    b.setAttribute('role', 'radio');
    b.setAttribute('aria-checked', String(layer === state.layer));
    b.addEventListener('click', () => chooseLayer(layer));
    return b;
  }));
  canvas.classList.toggle('clickable', state.model === 'glass');
}

function format(v) {
  return Math.abs(v) >= 1000 ? v.toExponential(2) : String(Math.round(v * 10000) / 10000);
}

function chooseLayer(layer) {
  state.layer = layer;
  for (const b of $('layers').children) b.setAttribute('aria-checked', String(b.textContent === layer));
  writeUrl();
  worker.postMessage({ type: 'layer', layer });
  idle = false;
}

/** Starts the model afresh from the state. */
function restart() {
  writeUrl();
  runId += 1;
  current = null;
  frames = 0;
  idle = false;
  waiting = true;
  $('text').textContent = 'starting…';
  worker.postMessage({ type: 'start', id: runId, name: state.model, params: params(), layer: state.layer, hits: state.hits });
}

$('model').addEventListener('change', () => {
  state.model = $('model').value;
  state.preset = DEFAULT_PRESET[state.model];
  state.overrides = {};
  state.hits = [];
  if (!LAYERS[state.model].includes(state.layer)) state.layer = 'preview';
  buildControls();
  restart();
});
$('preset').addEventListener('change', () => {
  state.preset = $('preset').value;
  state.overrides = {};
  state.hits = [];
  buildControls();
  restart();
});
$('seed').addEventListener('change', () => {
  const v = Number($('seed').value);
  if (Number.isSafeInteger(v) && v >= 0) {
    state.seed = v;
    restart();
  }
});
$('reseed').addEventListener('click', () => {
  state.seed = Math.floor(Math.random() * 1e6);
  $('seed').value = state.seed;
  restart();
});
$('restart').addEventListener('click', () => {
  state.hits = [];
  restart();
});
$('png').addEventListener('click', () => canvas.toBlob((blob) => download(blob, 'png'), 'image/png'));
$('svg').addEventListener('click', async () => download(new Blob([await svg()], { type: 'image/svg+xml' }), 'svg'));
$('link').addEventListener('click', async () => {
  const url = link();
  try {
    await navigator.clipboard.writeText(url);
    $('text').textContent = 'link copied';
  } catch {
    prompt('Copy this link:', url);
  }
});

canvas.addEventListener('click', (e) => {
  if (state.model !== 'glass' || !current) return;
  const r = canvas.getBoundingClientRect();
  const x = ((e.clientX - r.left) / r.width) * current.params.width;
  const y = ((e.clientY - r.top) / r.height) * current.params.height;
  state.hits.push([Math.round(x), Math.round(y)]);
  writeUrl();
  worker.postMessage({ type: 'impact', x: Math.round(x), y: Math.round(y) });
  idle = false;
});

function download(blob, extension) {
  const a = document.createElement('a');
  a.href = URL.createObjectURL(blob);
  a.download = `hibi-${state.model}-${state.preset}-seed${state.seed}.${extension}`;
  a.click();
  setTimeout(() => URL.revokeObjectURL(a.href), 1000);
}

/** The SVG export's text (from the worker). */
function svg() {
  return new Promise((resolve, reject) => {
    const listen = (e) => {
      if (e.data.type === 'svg' || e.data.type === 'error') {
        worker.removeEventListener('message', listen);
        if (e.data.type === 'svg') resolve(e.data.text);
        else reject(new Error(e.data.message));
      }
    };
    worker.addEventListener('message', listen);
    worker.postMessage({ type: 'svg' });
  });
}

// --- The loop ------------------------------------------------------------------------------

worker.addEventListener('message', (e) => {
  const m = e.data;
  if (m.id !== undefined && m.id !== runId) return; // a frame of a run since replaced
  if (m.type === 'started') {
    current = { id: m.id, params: m.params, width: m.width, height: m.height, finished: false };
    canvas.width = m.width;
    canvas.height = m.height;
    waiting = false;
  } else if (m.type === 'frame' || m.type === 'idle') {
    waiting = false;
    if (m.type === 'frame') {
      context.putImageData(new ImageData(m.rgba, m.width, m.height), 0, 0);
      frames += 1;
    }
    else idle = true;
    current.finished = m.finished;
    current.progress = m.progress;
    status(m);
  } else if (m.type === 'error') {
    waiting = false;
    idle = true;
    $('text').textContent = `error: ${m.message}`;
  }
});

function status(m) {
  const p = m.progress;
  const bar = $('bar');
  if (m.fraction === null) bar.removeAttribute('value');
  else bar.value = m.fraction;
  let text;
  if (state.model === 'mud') text = `shrink ${(100 * p.shrink).toFixed(2)} %, ${p.broken_springs} springs broken`;
  else if (state.model === 'glass') text = `step ${p.time}, ${p.cracks} cracks (${p.growing} growing)${m.pending ? `, ${m.pending} impact(s) queued` : ''}`;
  else text = `${p.cells} cells`;
  $('text').textContent = `${m.finished ? 'done' : 'growing'} · ${text}`;
}

function tick() {
  if (current && !waiting && !idle) {
    waiting = true;
    worker.postMessage({ type: 'frame' });
  }
  requestAnimationFrame(tick);
}

// For the tests and the curious: the state, the link and the SVG export.
window.playground = {
  state,
  link,
  svg,
  get current() {
    return current;
  },
  /** Frames drawn since the run started (one per step while it grows). */
  get frames() {
    return frames;
  },
  get done() {
    return Boolean(current?.finished && idle);
  },
};

await init();
readUrl();
buildControls();
restart();
requestAnimationFrame(tick);
