// Types of hibi.js: the three crack models of hibi-core in WebAssembly.

/** An error of hibi: its message names the parameter field or argument that is wrong. */
export class HibiError extends Error {
  name: 'HibiError';
}

/**
 * Loads the WebAssembly module (once; later calls return at once). `source`: a URL or path
 * of hibi.wasm, a Response, its bytes, or a compiled module; by default hibi.wasm beside
 * hibi.js. The models' constructors throw until it has resolved.
 */
export function init(source?: string | URL | Response | BufferSource | WebAssembly.Module): Promise<void>;

/** Bytes of WebAssembly memory (it grows as models need and never shrinks). */
export function memoryBytes(): number;

/** A render's preview layer as an ImageData (browsers and workers). */
export function toImageData(render: Render): ImageData;

/** Deeply partial parameters: fields given are laid over the defaults. */
export type Partial2<T> = { [K in keyof T]?: T[K] extends object ? Partial2<T[K]> : T[K] };

/** A seed: an integer below 2^53, or a BigInt up to 2^64 − 1. */
export type Seed = number | bigint;

/** Model A's parameters (the Rust `MudParams`, the C `hibi_mud_params`). */
export interface MudParams {
  topology: 'square' | 'hexagonal' | 'irregular';
  boundary: 'open' | 'periodic';
  solver: 'quasi_static' | 'explicit';
  drive: 'shrink' | 'growth';
  columns: number;
  rows: number;
  seed: Seed;
  layer_thickness: number;
  element_size: number;
  long_step: number;
  short_step: number;
  shrink_ratio: number;
  displacement_tolerance: number;
  damping_factor: number;
  density: number;
  young_modulus: number;
  shear_modulus: number;
  break_stretch_mean: number;
  break_stretch_spread: number;
  break_stretch_size_exponent: number;
  anisotropy_direction: number;
  anisotropy_ratio: number;
  stiffness_anisotropy_ratio: number;
  target_shrink: number;
  target_crack_density: number;
}

/** Model B's parameters (the Rust `GlassParams`, the C `hibi_glass_params`). */
export interface GlassParams {
  width: number;
  height: number;
  impact: [number, number];
  seed: Seed;
  radial_mean: number;
  ring_threshold: number;
  large_slope: number;
  large_offset: number;
  ring_slope: number;
  ring_offset: number;
  ring_radius_slope: number;
  ring_radius_offset: number;
  large_speed: number;
  radial_speed: number;
  ring_speed: number;
  spread_ratio: number;
  spread: 'uniform' | 'normal';
  turn_limit: number;
  turn_delay: number;
  sector_angle: number;
  sector_radius: number;
  tip_repulsion: number;
  crack_attraction: number;
  wander: number;
  ring_adherence: number;
  max_cracks: number;
  max_vertices: number;
}

/** A height profile: Bezier segments through control points (x, y). */
export interface Profile {
  segments: number;
  points: [number, number][];
}

/** One level of the skin's hierarchy. */
export interface LevelParams {
  spacing: number;
  perturbation: number;
  perturbation_decay: number;
  perturbation_depth: number;
  stretch: [number, number];
  profile: Profile;
  roundness: number;
}

/** Model C's parameters (the Rust `SkinParams`, the C `hibi_skin_params`). */
export interface SkinParams {
  width: number;
  height: number;
  seed: Seed;
  layout: 'triangular' | 'square' | 'random';
  jitter: 'uniform' | 'normal';
  jitter_ratio: number;
  periodic: boolean;
  levels: number;
  level: LevelParams[];
}

/** How mud is drawn (the Rust `MudRender`). */
export interface MudView {
  width: number;
  height: number;
  width_scale: number;
  min_width: number;
  groove_depth: number;
  offset: [number, number];
  bump: number;
  until: number;
}

/** How glass is drawn (the Rust `GlassRender`). */
export interface GlassView {
  width: number;
  height: number;
  line_width: number;
  bump: number;
  until: number;
}

/** Light and palette of the skin's preview (the Rust `ShadeParams`). */
export interface ShadeParams {
  light: [number, number, number];
  ridge: [number, number, number];
  furrow: [number, number, number];
  ambient: number;
  specular: number;
}

/** How skin is drawn (the Rust `SkinRender`); the rasters are the skin's own size. */
export interface SkinView {
  cell_level: number;
  shade: ShadeParams;
}

export type LayerName = 'mask' | 'height' | 'normal' | 'time' | 'cell' | 'preview' | 'height16' | 'normal_rgb8';

/** Options of `renderAsync`. */
export interface RenderOptions {
  /** How many workers draw bands of rows at once: an integer in 1..=64 (1 by default). */
  threads?: number;
}

/** What `render` returns: the raster size and the layers asked for. */
export interface Render {
  width: number;
  height: number;
  layers: {
    /** Coverage, 0 to 255. */
    mask?: Uint8Array;
    /** Height per pixel. */
    height?: Float32Array;
    /** Unit normal (x, y, z) per pixel. */
    normal?: Float32Array;
    /** Mud: break time in long steps; glass: the step the crack front passed; +∞ where no crack. */
    time?: Float32Array;
    /** Skin: the cell index at the view's cell_level. */
    cell?: Uint32Array;
    /** A shaded preview, RGBA (ImageData's layout). */
    preview?: Uint8ClampedArray;
    /** Height in 16 bits over the model's height range. */
    height16?: Uint16Array;
    /** The normal as 8-bit RGB, (c + 1) / 2 · 255 per component. */
    normal_rgb8?: Uint8Array;
  };
}

export interface MudProgress {
  shrink: number;
  time: number;
  broken_springs: number;
  crack_density: number;
  finished: boolean;
  work: number;
}

export interface GlassProgress {
  time: number;
  cracks: number;
  growing: number;
  vertices: number;
  finished: boolean;
  capacity_reached: boolean;
  work: number;
}

export interface SkinProgress {
  cells: number;
  roots: number;
  root_total: number;
  finished: boolean;
  capacity_reached: boolean;
  work: number;
}

export interface CrackStatistics {
  crack_density: number;
  cells: number;
  mean_cell_area: number;
  cell_area_spread: number;
  junctions: number;
  t_junctions: number;
  mean_widest_junction_angle: number;
  dead_ends: number;
}

/** Polygons: rings of points (glass fragments, mud cells). */
export interface Rings {
  rings: {
    count: number;
    /** Signed area (px² for glass, lattice units² for mud). */
    area: Float64Array;
    firstPoint: Uint32Array;
    pointCount: Uint32Array;
    /** For a hole, the outer ring it lies in; 0xffffffff for an outer ring. */
    holeOf: Uint32Array;
  };
  /** Points (x, y). */
  points: Float32Array;
}

export interface Network {
  vertices: { count: number; at: Float32Array; degree: Uint32Array; onBorder: Uint32Array };
  edges: { count: number; from: Uint32Array; to: Uint32Array; firstPoint: Uint32Array; pointCount: Uint32Array };
  points: { count: number; at: Float32Array; width: Float32Array; time: Float32Array };
}

declare abstract class Model<Params, View, Progress> {
  /** The parameters the model was made with (complete). */
  readonly params: Params;
  /** Runs at most `budget` units of work; returns the progress. */
  step(budget: number): Progress;
  /** Where the run stands. */
  readonly progress: Progress;
  /** The view `render` uses when given none. */
  view(): View;
  /** Draws the layers; a view given is laid over the render defaults. */
  render(layers?: LayerName[], view?: Partial2<View>): Render;
  /**
   * What render() draws, the same bytes, in bands of rows on `options.threads` workers at once
   * (module Web Workers; in Node, worker_threads). Each worker holds a copy of the module's
   * memory, sent when the model has stepped since; the workers stay for the next call and end
   * with free(). Rejects with a HibiError naming what is wrong.
   */
  renderAsync(layers?: LayerName[], view?: Partial2<View>, options?: RenderOptions): Promise<Render>;
  /** Frees the model's WebAssembly memory and ends its render workers; the model cannot be used after. */
  free(): void;
  [Symbol.dispose](): void;
}

/** Model A: a drying-mud spring lattice (Hirota et al.). */
export class Mud extends Model<MudParams, MudView, MudProgress> {
  static readonly presets: readonly string[];
  static defaults(): MudParams;
  static preset(name: string, overrides?: Partial2<MudParams>): MudParams;
  constructor(params?: Partial2<MudParams>);
  /** The lattice's extent in lattice units (the network's and cells' coordinates). */
  readonly extent: [number, number];
  /** The default view `width` pixels wide at the domain's aspect. */
  view(width?: number): MudView;
  statistics(): CrackStatistics;
  /** 8 floats per broken spring: start x, y, end x, y, width at each end, time at each end. */
  segments(): Float32Array;
  network(): Network;
  cells(): Rings & { wrapping: number };
}

/** Model B: a glass plate hit by a ball (Agui et al.). */
export class Glass extends Model<GlassParams, GlassView, GlassProgress> {
  static readonly presets: readonly string[];
  static defaults(): GlassParams;
  static preset(name: string, overrides?: Partial2<GlassParams>): GlassParams;
  constructor(params?: Partial2<GlassParams>);
  /** Another impact at (x, y) px: its radial, large and ring crack counts. */
  impact(x: number, y: number): { radial: number; large: number; rings: number };
  /** How each crack ended, its point count, and every point (x, y, time), crack after crack. */
  cracks(): { ends: Uint32Array; pointCounts: Uint32Array; points: Float32Array };
  fragments(): Rings;
}

/** Model C: hierarchical Voronoi cells of skin (Ishii et al.). */
export class Skin extends Model<SkinParams, SkinView, SkinProgress> {
  static readonly presets: readonly string[];
  static defaults(): SkinParams;
  static preset(name: string, overrides?: Partial2<SkinParams>): SkinParams;
  constructor(params?: Partial2<SkinParams>);
  /** The cells and their outlines in fixed point (a pixel is 2^fixedPointBits units). */
  cells(): {
    count: number;
    level: Uint32Array;
    parent: Uint32Array;
    site: Uint32Array;
    vertexCount: Uint32Array;
    vertices: BigInt64Array;
    fixedPointBits: number;
  };
}
