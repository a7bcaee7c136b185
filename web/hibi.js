// hibi for JavaScript: the three crack models of hibi-core (drying mud, a glass plate hit by a
// ball, skin) compiled to WebAssembly, for browsers (main thread and Web Workers) and Node.
//
//   import { init, Mud, Glass, Skin } from 'hibi';
//   await init();
//   using mud = new Mud({ columns: 64, rows: 64, seed: 7 });
//   while (!mud.step(1_000_000).finished) {}
//   const { layers } = mud.render(['preview']);
//
// The models keep their memory inside the WebAssembly instance: call free() (or declare them
// with `using`) when done. `await model.renderAsync(layers, view, { threads })` draws the same
// bytes as render() in bands of rows on Web Workers (worker_threads in Node), hibi-worker.js.
// Parameters are the Rust and C structs' fields, by the same names.
// Errors are HibiError exceptions whose message names the field, as the C API's do.

let wasm = null; // the instance's exports
let wasmModule = null; // the compiled module (each render worker instantiates it)
let NodeWorker = null; // node:worker_threads' Worker, where there is no global Worker
let slotsPtr = 0; // SLOTS f64 values of scratch for parameter records
const SLOTS = 1024;
const records = new Map(); // kind -> { fields: [{ path, kind, names }], count }
const decoder = new TextDecoder();
const encoder = new TextEncoder();

/** An error of hibi: its message names the parameter field or argument that is wrong. */
export class HibiError extends Error {
  constructor(message) {
    super(message);
    this.name = 'HibiError';
  }
}

/**
 * Loads the WebAssembly module. `source` is optional: a URL or path of hibi.wasm, a Response,
 * its bytes, or a compiled WebAssembly.Module; by default hibi.wasm beside this file. Calling
 * it again returns the same instance.
 */
export async function init(source) {
  if (wasm) return;
  if (source === undefined) source = new URL('./hibi.wasm', import.meta.url);
  let instance;
  let module = source;
  if (source instanceof WebAssembly.Module) {
    instance = await WebAssembly.instantiate(source, {});
  } else {
    let bytes = source;
    if (typeof source === 'string' || source instanceof URL) {
      const url = source instanceof URL ? source : new URL(source, import.meta.url);
      if (url.protocol === 'file:') {
        const { readFile } = await import('node:fs/promises');
        bytes = await readFile(url);
      } else {
        bytes = await fetch(url);
      }
    }
    if (typeof Response !== 'undefined' && bytes instanceof Response) {
      if (!bytes.ok) throw new HibiError(`hibi: could not load ${bytes.url} (HTTP ${bytes.status})`);
      bytes = await bytes.arrayBuffer();
    }
    ({ instance, module } = await WebAssembly.instantiate(bytes, {}));
  }
  if (typeof Worker === 'undefined' && typeof process !== 'undefined' && process.versions?.node) {
    ({ Worker: NodeWorker } = await import('node:worker_threads'));
  }
  if (wasm) return; // (another init() finished first)
  wasmModule = module;
  wasm = instance.exports;
  slotsPtr = wasm.hibi_web_alloc(SLOTS * 8);
}

function exports() {
  if (!wasm) throw new HibiError('hibi: call `await init()` before using the models');
  return wasm;
}

// Views are made afresh at each use: memory.buffer changes whenever the memory grows.
const f64s = (ptr, n) => new Float64Array(wasm.memory.buffer, ptr, n);
const text = () => decoder.decode(new Uint8Array(wasm.memory.buffer, wasm.hibi_web_text_ptr(), wasm.hibi_web_text_len()));
const failure = () => new HibiError(text());

/** The outputs of the last call, each copied out as an ArrayBuffer, then freed. */
function outputs() {
  const n = wasm.hibi_web_out_count();
  const list = [];
  for (let i = 0; i < n; i++) {
    const ptr = wasm.hibi_web_out_ptr(i);
    list.push(wasm.memory.buffer.slice(ptr, ptr + wasm.hibi_web_out_bytes(i)));
  }
  wasm.hibi_web_out_clear();
  return list;
}

// Record kinds (web/wasm/src/lib.rs).
const KIND = {
  mudParams: 0, glassParams: 1, skinParams: 2, mudView: 3, glassView: 4, skinView: 5,
  mudProgress: 6, glassProgress: 7, skinProgress: 8, mudStatistics: 9, impactCounts: 10,
};

/** The fields of record `kind`, from the core's own structs. */
function record(kind) {
  let r = records.get(kind);
  if (r) return r;
  const count = exports().hibi_web_describe(kind);
  const fields = text().trim().split('\n').map((line) => {
    const [path, type] = line.split(' ');
    const names = type.startsWith('enum:') ? type.slice(5).split('|') : null;
    return { path: path.split('.'), type: names ? 'enum' : type, names };
  });
  r = { fields, count };
  records.set(kind, r);
  return r;
}

/** The record in the slots at slotsPtr as a plain object (nested as the Rust struct). */
function read(kind) {
  const { fields, count } = record(kind);
  const slots = f64s(slotsPtr, count);
  const object = {};
  let i = 0;
  for (const f of fields) {
    let value;
    if (f.type === 'u64') {
      const big = BigInt(slots[i]) | (BigInt(slots[i + 1]) << 32n);
      value = big <= BigInt(Number.MAX_SAFE_INTEGER) ? Number(big) : big;
      i += 2;
    } else {
      const v = slots[i++];
      value = f.type === 'bool' ? v === 1 : f.type === 'enum' ? f.names[v] : f.type === 'f32' ? shortest(v) : v;
    }
    let o = object;
    for (let k = 0; k < f.path.length - 1; k++) {
      const key = f.path[k];
      if (o[key] === undefined) o[key] = /^\d+$/.test(f.path[k + 1]) ? [] : {};
      o = o[key];
    }
    o[f.path[f.path.length - 1]] = value;
  }
  return object;
}

/** The shortest decimal that is the same f32 as `v` (0.001, not 0.0010000000474974513). */
function shortest(v) {
  if (!Number.isFinite(v)) return v;
  for (let p = 1; p < 9; p++) {
    const d = Number(v.toPrecision(p));
    if (Math.fround(d) === v) return d;
  }
  return v;
}

/** Writes `object` (complete: made from read() and merged) into the slots at slotsPtr. */
function write(kind, object, model) {
  const { fields, count } = record(kind);
  const values = new Float64Array(count);
  let i = 0;
  for (const f of fields) {
    let v = object;
    for (const key of f.path) v = v?.[key];
    const name = `${model}: ${f.path.map((k) => (/^\d+$/.test(k) ? `[${k}]` : `.${k}`)).join('').slice(1)}`;
    switch (f.type) {
      case 'f32':
        if (typeof v !== 'number') throw new HibiError(`${name} must be a number`);
        values[i++] = v;
        break;
      case 'u32':
        if (!Number.isInteger(v) || v < 0 || v > 0xffffffff) throw new HibiError(`${name} must be an integer in 0..=4294967295`);
        values[i++] = v;
        break;
      case 'bool':
        if (typeof v !== 'boolean') throw new HibiError(`${name} must be true or false`);
        values[i++] = v ? 1 : 0;
        break;
      case 'enum': {
        const n = f.names.indexOf(v);
        if (n < 0) throw new HibiError(`${name} must be one of ${f.names.join(', ')}`);
        values[i++] = n;
        break;
      }
      case 'u64': {
        let big;
        if (typeof v === 'bigint') big = v;
        else if (Number.isSafeInteger(v)) big = BigInt(v);
        if (big === undefined || big < 0n || big >= 1n << 64n) throw new HibiError(`${name} must be an integer in 0..2^64 (a BigInt above 2^53)`);
        values[i++] = Number(big & 0xffffffffn);
        values[i++] = Number(big >> 32n);
        break;
      }
    }
  }
  f64s(slotsPtr, count).set(values);
}

/** `overrides` laid over `base` (plain objects and arrays, deeply). */
function merge(base, overrides) {
  if (overrides === undefined) return base;
  if (overrides === null || typeof overrides !== 'object' || typeof base !== 'object' || base === null) return overrides;
  const out = Array.isArray(base) ? base.slice() : { ...base };
  for (const key of Object.keys(overrides)) out[key] = merge(base[key], overrides[key]);
  return out;
}

function defaults(kind) {
  exports().hibi_web_defaults(kind, slotsPtr);
  return read(kind);
}

function presetNames(fn) {
  exports()[fn]();
  return Object.freeze(text().split('\n'));
}

function preset(model, kind, name) {
  const w = exports();
  const bytes = encoder.encode(String(name));
  const ptr = w.hibi_web_alloc(bytes.length);
  new Uint8Array(w.memory.buffer, ptr, bytes.length).set(bytes);
  // Length 0 would ask for the defaults: an empty name is no preset's.
  const status = bytes.length === 0 ? -1 : w[`hibi_web_${model}_params`](ptr, bytes.length, slotsPtr);
  w.hibi_web_free(ptr, bytes.length);
  if (status === -1) throw new HibiError(`${model}: no preset has that name`);
  if (status !== 0) throw failure();
  return read(kind);
}

/** Splits records of `stride` bytes into one typed array per field. */
function columns(buffer, stride, spec) {
  const count = buffer.byteLength / stride;
  const view = new DataView(buffer);
  const out = { count };
  let offset = 0;
  for (const [name, Type, n] of spec) {
    const array = new Type(count * n);
    const get = Type === Float32Array ? 'getFloat32' : Type === Float64Array ? 'getFloat64' : 'getUint32';
    const size = Type.BYTES_PER_ELEMENT;
    for (let r = 0; r < count; r++) {
      for (let k = 0; k < n; k++) array[r * n + k] = view[get](r * stride + offset + k * size, true);
    }
    if (name) out[name] = array;
    offset += size * n;
  }
  return out;
}

const RING = [['area', Float64Array, 1], ['firstPoint', Uint32Array, 1], ['pointCount', Uint32Array, 1], ['holeOf', Uint32Array, 1], [null, Uint32Array, 1]];

// Layers: names, bits and array types (the order of the module's outputs).
const LAYERS = [
  ['mask', 1, Uint8Array, 1],
  ['height', 2, Float32Array, 1],
  ['normal', 4, Float32Array, 3],
  ['time', 8, Float32Array, 1],
  ['cell', 16, Uint32Array, 1],
  ['preview', 32, Uint8ClampedArray, 4],
  ['height16', 64, Uint16Array, 1],
  ['normal_rgb8', 128, Uint8Array, 3],
];

const registry = typeof FinalizationRegistry === 'undefined'
  ? null
  : new FinalizationRegistry(({ model, handle, workers }) => {
    for (const w of workers) w.terminate(`${model}: collected while rendering`);
    wasm[`hibi_web_${model}_free`](handle);
  });

/** The bits of the layers named. */
function layerBits(layers) {
  let bits = 0;
  for (const name of layers) {
    const layer = LAYERS.find((l) => l[0] === name);
    if (!layer) throw new HibiError(`render: no layer is named ${name} (${LAYERS.map((l) => l[0]).join(', ')})`);
    bits |= layer[1];
  }
  return bits;
}

/** The most workers renderAsync draws on. */
const MAX_THREADS = 64;
/** One copy of memory can go to every worker where memory can be shared (Node, and pages
 * that are cross-origin isolated); elsewhere each worker is sent its own. */
const SHARED = typeof SharedArrayBuffer === 'function' && globalThis.crossOriginIsolated !== false;

/** A render worker (hibi-worker.js): a module Web Worker, or a worker_threads Worker in Node.
 * It answers its requests in order. */
class RenderWorker {
  #worker;
  #pending = new Map(); // id -> { resolve, reject }
  #next = 0;
  #failure = null;
  /** The model version its copy of memory holds (-1: none). */
  version = -1;

  constructor() {
    if (NodeWorker) {
      this.#worker = new NodeWorker(new URL('./hibi-worker.js', import.meta.url));
      this.#worker.on('message', (m) => this.#receive(m));
      this.#worker.on('error', (e) => this.#fail(`render: a worker failed: ${e.message}`));
      this.#worker.on('exit', () => this.#fail('render: a worker ended'));
      this.#worker.unref(); // an idle worker keeps no Node process alive
    } else {
      // (Written so that bundlers see the worker: new Worker(new URL(..., import.meta.url)).)
      this.#worker = new Worker(new URL('./hibi-worker.js', import.meta.url), { type: 'module' });
      this.#worker.onmessage = (e) => this.#receive(e.data);
      this.#worker.onerror = (e) => {
        e.preventDefault();
        this.#fail(`render: a worker failed: ${e.message || 'hibi-worker.js did not start'}`);
      };
    }
    this.#worker.postMessage({ module: wasmModule });
  }

  /** Whether the worker failed or ended (it takes no more requests). */
  get failed() {
    return this.#failure !== null;
  }

  /** Posts `message` (with `transfer`); resolves to the band's layers as ArrayBuffers. */
  request(message, transfer) {
    if (this.#failure) return Promise.reject(new HibiError(this.#failure));
    const id = this.#next++;
    const answer = new Promise((resolve, reject) => this.#pending.set(id, { resolve, reject }));
    if (this.#pending.size === 1) this.#worker.ref?.();
    this.#worker.postMessage({ ...message, id }, transfer);
    return answer;
  }

  #receive(m) {
    const p = this.#pending.get(m.id);
    if (!p) return;
    this.#pending.delete(m.id);
    if (this.#pending.size === 0) this.#worker.unref?.();
    if (m.lost) this.version = -1; // the instance trapped: the next request sends memory again
    if (m.error === undefined) p.resolve(m.layers);
    else p.reject(new HibiError(m.error));
  }

  #fail(text) {
    this.#failure ??= text;
    for (const p of this.#pending.values()) p.reject(new HibiError(text));
    this.#pending.clear();
  }

  /** Ends the worker; requests pending reject with `text`. */
  terminate(text) {
    this.#fail(text);
    this.#worker.terminate();
  }
}

/** What the three models share: the handle, step, progress, render, free. */
class Model {
  #handle = 0;
  #model;
  #kinds;
  #version = 0; // of the model's state, for the render workers' copies
  #workers = []; // RenderWorker, made by renderAsync

  constructor(model, kinds, params) {
    const w = exports();
    this.#model = model;
    this.#kinds = kinds;
    const full = merge(defaults(kinds.params), params);
    write(kinds.params, full, model);
    const handle = w[`hibi_web_${model}_new`](slotsPtr);
    if (handle === 0) throw failure();
    this.#handle = handle;
    /** The parameters the model was made with (complete). */
    this.params = full;
    registry?.register(this, { model, handle, workers: this.#workers }, this);
  }

  /** The handle, or an error if the model was freed. */
  get _handle() {
    if (this.#handle === 0) throw new HibiError(`${this.#model}: used after free()`);
    return this.#handle;
  }

  /** Runs at most `budget` units of work and returns the progress. */
  step(budget) {
    if (!(typeof budget === 'number' && budget >= 0 && Number.isFinite(budget))) {
      throw new HibiError(`${this.#model}: step's budget must be a finite number >= 0`);
    }
    const handle = this._handle;
    this.#version++;
    const status = wasm[`hibi_web_${this.#model}_step`](handle, Math.floor(budget), slotsPtr);
    if (status) throw failure();
    return read(this.#kinds.progress);
  }

  /** Where the run stands. */
  get progress() {
    wasm[`hibi_web_${this.#model}_progress`](this._handle, slotsPtr);
    return read(this.#kinds.progress);
  }

  /** The view `render` draws when given none (complete: a render parameter record). */
  view() {
    return defaults(this.#kinds.view);
  }

  /**
   * Draws `layers` (names among mask, height, normal, time, cell, preview, height16,
   * normal_rgb8) with `view` (a
   * render parameter record: fields given are laid over the model's defaults; omitted, the
   * model's default view). Returns { width, height, layers: { name: typed array } }.
   */
  render(layers = ['preview'], view) {
    const w = exports();
    const full = view === undefined ? this.view() : merge(defaults(this.#kinds.view), view);
    write(this.#kinds.view, full, 'render');
    const bits = layerBits(layers);
    if (w[`hibi_web_${this.#model}_render`](this._handle, slotsPtr, bits)) throw failure();
    const buffers = outputs();
    const [width, height] = this._size(full);
    const result = { width, height, layers: {} };
    for (const [name, bit, Type] of LAYERS) {
      if (bits & bit) result.layers[name] = new Type(buffers.shift());
    }
    return result;
  }

  /**
   * render() in bands of rows drawn at once on `options.threads` workers (Web Workers; in
   * Node, worker_threads): the same bytes as render(). Each worker instantiates the module with
   * a copy of its memory, which it keeps until the model steps again; the workers stay for the
   * next call and end with free(). Resolves to what render() returns.
   */
  async renderAsync(layers = ['preview'], view, options = {}) {
    if (options === null || typeof options !== 'object') throw new HibiError(`${this.#model}: renderAsync's options must be an object`);
    const threads = options.threads ?? 1;
    if (!Number.isInteger(threads) || threads < 1 || threads > MAX_THREADS) {
      throw new HibiError(`${this.#model}: threads must be an integer in 1..=${MAX_THREADS}`);
    }
    const handle = this._handle;
    const full = view === undefined ? this.view() : merge(defaults(this.#kinds.view), view);
    write(this.#kinds.view, full, 'render');
    const slots = f64s(slotsPtr, record(this.#kinds.view).count).slice();
    const bits = layerBits(layers);
    const [width, height] = this._size(full);
    // Bands as the CLI and Python cut them: at most `threads`, of equal rows but the last.
    const rows = Math.max(1, Math.ceil(height / Math.max(1, Math.min(threads, height))));
    const bands = Math.max(1, Math.ceil(height / rows));
    const workers = this.#workers;
    for (let k = 0; k < bands; k++) {
      if (workers[k]?.failed === false) continue;
      workers[k]?.terminate('render: a worker failed');
      workers[k] = new RenderWorker();
    }
    // Workers whose memory is older than the model's last step get a copy of it, taken now.
    const stale = workers.slice(0, bands).filter((w) => w.version !== this.#version);
    const copies = new Map();
    if (stale.length > 0) {
      const memory = new Uint8Array(wasm.memory.buffer);
      const shared = SHARED ? new SharedArrayBuffer(memory.length) : null;
      if (shared) new Uint8Array(shared).set(memory);
      for (const w of stale) {
        copies.set(w, shared ?? memory.slice().buffer);
        w.version = this.#version;
      }
    }
    const answers = [];
    for (let k = 0; k < bands; k++) {
      const memory = copies.get(workers[k]);
      const y = k * rows;
      const tile = [0, y, width, Math.min(rows, height - y)];
      const message = { model: this.#model, handle, slots: slotsPtr, view: slots, bits, tile, memory };
      answers.push(workers[k].request(message, memory instanceof ArrayBuffer ? [memory] : []));
    }
    const parts = await Promise.all(answers);
    const result = { width, height, layers: {} };
    let j = 0;
    for (const [name, bit, Type, channels] of LAYERS) {
      if (!(bits & bit)) continue;
      if (bands === 1) {
        result.layers[name] = new Type(parts[0][j]);
      } else {
        const all = new Type(width * height * channels);
        parts.forEach((part, k) => all.set(new Type(part[j]), k * rows * width * channels));
        result.layers[name] = all;
      }
      j++;
    }
    return result;
  }

  /** The version of the model's state: step() and impact() change it. */
  _changed() {
    this.#version++;
  }

  /** Frees the model's WebAssembly memory and ends its render workers. */
  free() {
    if (this.#handle === 0) return;
    for (const w of this.#workers) w.terminate(`${this.#model}: freed while rendering`);
    this.#workers.length = 0;
    registry?.unregister(this);
    wasm[`hibi_web_${this.#model}_free`](this.#handle);
    this.#handle = 0;
  }

  [Symbol.dispose ?? Symbol.for('Symbol.dispose')]() {
    this.free();
  }
}

/** Model A: a drying-mud spring lattice (Hirota et al.). */
export class Mud extends Model {
  /** The preset names. */
  static get presets() {
    return presetNames('hibi_web_mud_presets');
  }
  /** The paper's defaults. */
  static defaults() {
    return defaults(KIND.mudParams);
  }
  /** The parameters of preset `name`, with `overrides` laid over them. */
  static preset(name, overrides) {
    return merge(preset('mud', KIND.mudParams, name), overrides);
  }

  /** A run of `params` (fields given are laid over the defaults). */
  constructor(params) {
    super('mud', { params: KIND.mudParams, view: KIND.mudView, progress: KIND.mudProgress }, params);
  }

  /** The lattice's extent [width, height] in lattice units (the network's coordinates). */
  get extent() {
    wasm.hibi_web_mud_extent(this._handle, slotsPtr);
    return Array.from(f64s(slotsPtr, 2));
  }

  /** The default view `width` pixels wide at the domain's aspect (MudRender::fit). */
  view(width = Math.min(2048, Math.max(256, this.params.columns * 4))) {
    wasm.hibi_web_mud_view(this._handle, width, slotsPtr);
    return read(KIND.mudView);
  }

  _size(view) {
    return [view.width, view.height];
  }

  /** Crack statistics of the traced network. */
  statistics() {
    wasm.hibi_web_mud_statistics(this._handle, slotsPtr);
    return read(KIND.mudStatistics);
  }

  /** The broken springs' segments: 8 floats each (start x, y, end x, y, widths, times). */
  segments() {
    wasm.hibi_web_mud_segments(this._handle);
    return new Float32Array(outputs()[0]);
  }

  /** The crack network: vertices, edges (polylines between vertices) and their points. */
  network() {
    if (wasm.hibi_web_mud_network(this._handle)) throw failure();
    const [vertices, edges, points] = outputs();
    return {
      vertices: columns(vertices, 16, [['at', Float32Array, 2], ['degree', Uint32Array, 1], ['onBorder', Uint32Array, 1]]),
      edges: columns(edges, 16, [['from', Uint32Array, 1], ['to', Uint32Array, 1], ['firstPoint', Uint32Array, 1], ['pointCount', Uint32Array, 1]]),
      points: columns(points, 16, [['at', Float32Array, 2], ['width', Float32Array, 1], ['time', Float32Array, 1]]),
    };
  }

  /** The closed cells as rings of points, and how many wrap around a periodic lattice. */
  cells() {
    const wrapping = wasm.hibi_web_mud_cells(this._handle);
    if (wrapping === 0xffffffff) throw failure();
    const [rings, points] = outputs();
    return { rings: columns(rings, 24, RING), points: new Float32Array(points), wrapping };
  }
}

/** Model B: a glass plate hit by a ball (Agui et al.). */
export class Glass extends Model {
  static get presets() {
    return presetNames('hibi_web_glass_presets');
  }
  static defaults() {
    return defaults(KIND.glassParams);
  }
  static preset(name, overrides) {
    return merge(preset('glass', KIND.glassParams, name), overrides);
  }

  /** A plate of `params`, hit at `params.impact`. */
  constructor(params) {
    super('glass', { params: KIND.glassParams, view: KIND.glassView, progress: KIND.glassProgress }, params);
  }

  /** The plate's pixels, 1:1. */
  view() {
    const v = defaults(KIND.glassView);
    v.width = Math.max(1, Math.round(this.params.width));
    v.height = Math.max(1, Math.round(this.params.height));
    return v;
  }

  _size(view) {
    return [view.width, view.height];
  }

  /** Another impact at (x, y) on the plate; returns its crack counts. */
  impact(x, y) {
    if (typeof x !== 'number' || typeof y !== 'number') throw new HibiError('glass: impact x and y must be numbers');
    const handle = this._handle;
    this._changed();
    if (wasm.hibi_web_glass_impact(handle, x, y, slotsPtr)) throw failure();
    return read(KIND.impactCounts);
  }

  /** The cracks: how each ended, its point count, and every point (x, y, time). */
  cracks() {
    wasm.hibi_web_glass_cracks(this._handle);
    const [ends, counts, points] = outputs();
    return { ends: new Uint32Array(ends), pointCounts: new Uint32Array(counts), points: new Float32Array(points) };
  }

  /** The fragments the cracks cut the plate into, as polygons (rings of points). */
  fragments() {
    if (wasm.hibi_web_glass_fragments(this._handle)) throw failure();
    const [rings, points] = outputs();
    return { rings: columns(rings, 24, RING), points: new Float32Array(points) };
  }
}

/** Model C: hierarchical Voronoi cells of skin (Ishii et al.). */
export class Skin extends Model {
  static get presets() {
    return presetNames('hibi_web_skin_presets');
  }
  static defaults() {
    return defaults(KIND.skinParams);
  }
  static preset(name, overrides) {
    return merge(preset('skin', KIND.skinParams, name), overrides);
  }

  /** A skin of `params`. */
  constructor(params) {
    super('skin', { params: KIND.skinParams, view: KIND.skinView, progress: KIND.skinProgress }, params);
  }

  _size() {
    return [this.params.width, this.params.height];
  }

  /**
   * The cells: per cell its level, parent, site and vertex count, and every outline vertex
   * (x, y) in fixed point of `fixedPointBits` fractional bits (a pixel is 2^bits units).
   */
  cells() {
    const bits = wasm.hibi_web_skin_cells(this._handle);
    const [records, vertices] = outputs();
    const c = columns(records, 16, [['level', Uint32Array, 1], ['parent', Uint32Array, 1], ['site', Uint32Array, 1], ['vertexCount', Uint32Array, 1]]);
    return { ...c, vertices: new BigInt64Array(vertices), fixedPointBits: bits };
  }
}

/** A render's RGBA preview as an ImageData (browsers and workers). */
export function toImageData(render) {
  const rgba = render.layers.preview;
  if (!rgba) throw new HibiError('render: toImageData needs the preview layer');
  return new ImageData(rgba, render.width, render.height);
}

/** Bytes of WebAssembly memory (it grows as models need and never shrinks). */
export function memoryBytes() {
  return exports().memory.buffer.byteLength;
}
