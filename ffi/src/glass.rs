//! `hibi_glass`: model B, a glass plate hit by a ball (Agui et al.), from C.
//!
//! ```c
//! hibi_glass_params params = hibi_glass_params_default();
//! hibi_glass *glass = NULL;
//! if (hibi_glass_create(&params, &glass) != HIBI_OK) { ... }
//! hibi_glass_progress progress;
//! hibi_status status;
//! do { status = hibi_glass_step(glass, 100000, &progress); } while (status == HIBI_OK && !progress.finished);
//! hibi_glass_render_params render = hibi_glass_render_params_default();
//! hibi_glass_render(glass, &render, HIBI_GLASS_LAYER_MASK, pixels, render.width * render.height);
//! hibi_glass_destroy(glass);
//! ```
//!
//! The same sequence drives mud and skin but for the names (a skin renders at its params'
//! size).
//!
//! An object is one block: the header, then the plate's crack, vertex, edge and word arrays.

use core::ffi::{CStr, c_char, c_void};
use core::mem::{align_of, size_of};

use hibi_core::glass::{
    Crack, CrackPoint, CrackSlot, Edge, FragmentBuild, FragmentBuildBuffers, FragmentBuildMemory, FragmentProgress,
    Glass, GlassBuffers, GlassError, GlassLayers, GlassMemory, GlassParams, GlassProgress, GlassRender, ImpactCounts,
    Vertex, preset,
};

use crate::constants::param_status;
use crate::fields::{Field, convert};
use crate::guard::{Outcome, Outs, buffer, check_pointer, copy_from, guard, object_ref, query, update, write_out};
use crate::object::{self, AnyBits, Arena, Object, Origin, lifecycle};
use crate::polygons::polygon_query;
use crate::raster::{Pixels, render};
use crate::status::{
    HIBI_ERROR_BUFFER_TOO_SMALL, HIBI_ERROR_GLASS_CAPACITY, HIBI_ERROR_GLASS_CRACK_INDEX, HIBI_ERROR_GLASS_IMPACT,
    HIBI_ERROR_GLASS_RENDER_LAYER, hibi_status,
};

/// Marks a params struct that came from `hibi_glass_params_default` ("GLS1").
const PARAMS_COOKIE: u32 = 0x474C_5331;

/// The parameters of a glass plate, in pixels. Get them from `hibi_glass_params_default`
/// (the paper's values), then change fields; `hibi_glass_create` rejects a struct that did
/// not come from there.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct hibi_glass_params {
    /// Set by `hibi_glass_params_default`; leave it alone.
    pub cookie: u32,
    /// Plate width [px], within [1, 65536] (default 640; wider, f32 positions could not place
    /// a crack's shortest move, and the fragments would not cover the plate).
    pub width: f32,
    /// Plate height [px], within [1, 65536] (default 640).
    pub height: f32,
    /// The first impact point (default the centre).
    pub impact: [f32; 2],
    /// Seed of every random draw.
    pub seed: u64,
    /// M_ave, mean number of radial cracks (default 100).
    pub radial_mean: f32,
    /// A: rings appear when M > A (paper: 70).
    pub ring_threshold: f32,
    /// e in the number of large cracks N = floor(e·M + f) (paper: 0.0606).
    pub large_slope: f32,
    /// f in N = floor(e·M + f) (paper: 3.293).
    pub large_offset: f32,
    /// a in the number of ring start points R = floor(a·M + b) (0.05).
    pub ring_slope: f32,
    /// b in R = floor(a·M + b) (0.5). Whatever a and b hold, creation and each impact are
    /// bounded by the capacities: at most `max_cracks` ring start points are looked at, and a
    /// larger R (each grows two cracks) counts as running out of capacity (`hibi_glass_step`
    /// then returns `HIBI_ERROR_GLASS_CAPACITY`; the plate stays usable).
    pub ring_offset: f32,
    /// g in the mean ring radius d_ave = g·M + h (paper: 0.470).
    pub ring_radius_slope: f32,
    /// h in d_ave = g·M + h [px] (paper: 13.90).
    pub ring_radius_offset: f32,
    /// V1_ave, the large cracks' mean speed [px per step] (default 40).
    pub large_speed: f32,
    /// V2_ave, the other radial cracks' mean speed (default 10).
    pub radial_speed: f32,
    /// V3_ave, the ring cracks' mean speed (default 10). Any finite speed > 0 is valid and
    /// every run ends: an impact's generation stops after at most 32 768 time steps (sooner,
    /// once the slowest speed drawn crosses the plate twice); cracks still growing then end
    /// where they are.
    pub ring_speed: f32,
    /// z of Rand(x) (paper: 0.3).
    pub spread_ratio: f32,
    /// `HIBI_SPREAD_NORMAL` (default) or `HIBI_SPREAD_UNIFORM`: the shape of Rand(x).
    pub spread: u32,
    /// θ_th, the largest turn per update (at most 10 px) [radians] (paper: 30°).
    pub turn_limit: f32,
    /// T in weight(t) = 1 − exp(−t/T) (paper: 10).
    pub turn_delay: f32,
    /// φ, the sector angle [radians] (paper: 100°).
    pub sector_angle: f32,
    /// B, the sector radius [px] (paper: 50).
    pub sector_radius: f32,
    /// k1 of F1 = k1/r², tips pushing apart [px²] (default 400).
    pub tip_repulsion: f32,
    /// k2 of F2 = k2/d², the pull to meet a crack or edge at a right angle [px²] (default 400).
    pub crack_attraction: f32,
    /// Spread of F3's direction per 10 px of growth at weight(t) = 1 [radians] (default 45°).
    pub wander: f32,
    /// How hard ring cracks keep to their circle (default 2).
    pub ring_adherence: f32,
    /// Most cracks the plate holds, within [1, 2^28] (default 512).
    pub max_cracks: u32,
    /// Most crack vertices the plate holds, within [2, 2^28] (default 16384).
    pub max_vertices: u32,
}

/// Where generation stands.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct hibi_glass_progress {
    /// Steps taken for the current impact.
    pub time: u32,
    /// Cracks on the plate.
    pub cracks: u32,
    /// Cracks still growing.
    pub growing: u32,
    /// Vertices used.
    pub vertices: u32,
    /// 1 when generation of the current impact has ended.
    pub finished: u32,
    /// 1 when a capacity ran out (generation then stopped early, consistently).
    pub capacity_reached: u32,
    /// Work done since the plate was created, in the units of `hibi_glass_step`'s budget.
    pub work: u64,
}

/// The counts an impact drew: M radial cracks, N of them large, R ring start points.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct hibi_glass_counts {
    /// M.
    pub radial: u32,
    /// N.
    pub large: u32,
    /// R.
    pub rings: u32,
}

/// One crack: its kind, why it stopped, its impact and its point count.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct hibi_glass_crack {
    /// A `HIBI_GLASS_KIND_*` constant.
    pub kind: u32,
    /// Why it stopped: a `HIBI_GLASS_END_*` constant.
    pub end: u32,
    /// Which impact started it.
    pub impact: u32,
    /// Points of its polyline.
    pub points: u32,
}

/// How to draw a raster. Defaults from `hibi_glass_render_params_default`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct hibi_glass_render_params {
    /// Raster width in pixels (default 640); the plate is stretched over it.
    pub width: u32,
    /// Raster height in pixels (default 640).
    pub height: u32,
    /// Width of a crack line in pixels (default 1.2).
    pub line_width: f32,
    /// Depth of a fully covered crack in pixels, for the normals (default 2).
    pub bump: f32,
    /// Draw the cracks as far as they had grown at this time step (default +infinity: all
    /// of them).
    pub until: f32,
}

impl Outcome for hibi_glass_render_params {
    type C = hibi_glass_render_params;
    fn into_c(self) -> Self {
        self
    }
    /// A zero-sized raster, which rendering rejects.
    fn on_panic() -> Self {
        hibi_glass_render_params { width: 0, height: 0, line_width: 0.0, bump: 0.0, until: 0.0 }
    }
}

/// A glass plate and its cracks. Opaque.
pub struct hibi_glass {
    glass: Glass<'static>,
    origin: Origin,
    /// `u32` words of a fragment query's scratch.
    scratch: usize,
}

convert!(hibi_glass_params <=> GlassParams, cookie: PARAMS_COOKIE {
    width, height, impact, seed, radial_mean, ring_threshold, large_slope, large_offset, ring_slope, ring_offset,
    ring_radius_slope, ring_radius_offset, large_speed, radial_speed, ring_speed, spread_ratio, spread, turn_limit,
    turn_delay, sector_angle, sector_radius, tip_repulsion, crack_attraction, wander, ring_adherence, max_cracks,
    max_vertices,
});
convert!(hibi_glass_progress <=> GlassProgress { time, cracks, growing, vertices, finished, capacity_reached, work });
convert!(hibi_glass_counts <=> ImpactCounts { radial, large, rings });
convert!(hibi_glass_render_params <=> GlassRender { width, height, line_width, bump, until });

lifecycle!(
    hibi_glass (glass: "plate", "its first impact at `params.impact`, ready to step"),
    hibi_glass_params <=> GlassParams, cookie PARAMS_COOKIE,
    errors (HIBI_ERROR_GLASS_PARAMS_NOT_INITIALISED, HIBI_ERROR_GLASS_ENUM, HIBI_ERROR_GLASS_UNKNOWN_PRESET),
    presets "`\"fig14a\"` … `\"fig16d\"`" in hibi_core::glass::PRESETS,
    hibi_glass_params_default, hibi_glass_params_preset, hibi_glass_preset_name, hibi_glass_memory_size,
    hibi_glass_memory_align,
    hibi_glass_create, hibi_glass_create_in, hibi_glass_destroy,
);

// SAFETY: a vertex is two f32 and a u32 (12 bytes, no padding, checked below): every bit
// pattern is a value.
unsafe impl AnyBits for Vertex {}
// SAFETY: an edge is u32 and f32 fields only (56 bytes, no padding, checked below).
unsafe impl AnyBits for Edge {}
// SAFETY: a crack slot is u32 and f32 fields only (its kind, end and growing flag as u32
// numbers; 88 bytes, no padding, checked below).
unsafe impl AnyBits for CrackSlot {}
const _: () = assert!(
    size_of::<Vertex>() == 12 && size_of::<Edge>() == 56 && size_of::<CrackSlot>() == 88,
    "only u32 and f32 fields"
);

impl Object for hibi_glass {
    type Input = *const hibi_glass_params;
    type Plan = (GlassParams, GlassMemory);
    type Arrays = GlassBuffers<'static>;
    const TOO_LARGE: hibi_status = crate::constants::HIBI_ERROR_GLASS_CAPACITY_PARAMS;

    unsafe fn plan(params: *const hibi_glass_params) -> Result<Self::Plan, hibi_status> {
        // SAFETY: the caller's contract.
        let params = from_c(unsafe { object_ref(params, c"params") }?)?;
        let memory = params.memory().map_err(param_status)?;
        Ok((params, memory))
    }

    /// The plate reads no crack slot, vertex, edge or word it did not write (`Glass::new`), so
    /// every array is taken as it is: neither `hibi_glass_create` nor `hibi_glass_create_in`
    /// writes an array, and their work does not grow with the capacities.
    fn arrays((_, m): &Self::Plan, arena: &mut Arena) -> Self::Arrays {
        GlassBuffers {
            cracks: arena.take_as_is(m.cracks),
            vertices: arena.take_as_is(m.vertices),
            edges: arena.take_as_is(m.edges),
            words: arena.take_as_is(m.words),
        }
    }

    fn make((params, m): &Self::Plan, buffers: Self::Arrays, origin: Origin) -> Result<Self, hibi_status> {
        Ok(hibi_glass { glass: Glass::new(params, buffers).map_err(glass_status)?, origin, scratch: m.scratch })
    }

    fn origin(&self) -> Origin {
        self.origin
    }
}

/// The status of a core glass error.
fn glass_status(error: GlassError) -> hibi_status {
    match error {
        GlassError::Param(p) => param_status(p),
        GlassError::BufferTooSmall { .. } => HIBI_ERROR_BUFFER_TOO_SMALL,
        GlassError::Impact => HIBI_ERROR_GLASS_IMPACT,
        GlassError::Capacity => HIBI_ERROR_GLASS_CAPACITY,
    }
}

/// Adds an impact at (x, y): its cracks grow on the next steps and stop where they meet the
/// earlier ones. Writes the counts it drew unless `counts` is NULL. It starts at most M + 2R
/// cracks, and looks at no more than `max_cracks` ring start points. Refused, with nothing
/// written or changed: a point not inside the plate (`HIBI_ERROR_GLASS_IMPACT`), and any
/// impact once a capacity has run out (`HIBI_ERROR_GLASS_CAPACITY`, as every later
/// `hibi_glass_step` returns). An impact that runs out of capacity while starting its cracks
/// returns `HIBI_OK` and its counts; the next `hibi_glass_step` returns
/// `HIBI_ERROR_GLASS_CAPACITY`.
///
/// # Safety
/// `glass` must be NULL or a live plate; `counts` optional: NULL (not written) or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_glass_impact(
    glass: *mut hibi_glass,
    x: f32,
    y: f32,
    counts: *mut hibi_glass_counts,
) -> hibi_status {
    let impact = |glass: &mut hibi_glass| {
        glass.glass.impact([x, y]).map(|c| hibi_glass_counts::from_core(&c)).map_err(glass_status)
    };
    // SAFETY: the caller's contract.
    guard(|| unsafe { update(glass, c"glass", (counts, c"counts"), impact) })
}

/// The most work one piece of glass growth does, in `hibi_glass_step`'s units: a call does at
/// most max(budget, 1) − 1 + this.
pub const HIBI_GLASS_STEP_PIECE: u64 = 2;

const _: () = assert!(HIBI_GLASS_STEP_PIECE == hibi_core::glass::STEP_PIECE);

/// Advances growth by `budget` units of work (at least one; a unit is a grid cell, segment or
/// tip a query examines, a crack looked at by the step loop, the filing of the tips, the check
/// at the end of a time step or stop condition 2, a step of a face walk of stop condition 2
/// when a crack closes a cycle, or 64 grid cells emptied: a new plate's first units, at most
/// 2048, which creation leaves to this call). The budget is checked before every unit, and
/// every query and face walk resumes where it stopped, so a call does at most
/// max(budget, 1) − 1 + `HIBI_GLASS_STEP_PIECE` units, and the plate does not depend on the
/// budgets; writes where it stands to `*progress` unless it is NULL. Returns
/// `HIBI_ERROR_GLASS_CAPACITY` (and writes nothing) once a capacity has run out; the plate
/// then stays as it was drawn, usable.
///
/// # Safety
/// `glass` must be NULL or a live plate; `progress` optional: NULL (not written) or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_glass_step(
    glass: *mut hibi_glass,
    budget: u64,
    progress: *mut hibi_glass_progress,
) -> hibi_status {
    let step = |glass: &mut hibi_glass| match glass.glass.step(budget) {
        p if p.capacity_reached => Err(HIBI_ERROR_GLASS_CAPACITY),
        p => Ok(hibi_glass_progress::from_core(&p)),
    };
    // SAFETY: the caller's contract.
    guard(|| unsafe { update(glass, c"glass", (progress, c"progress"), step) })
}

/// Writes the number of cracks.
///
/// # Safety
/// `glass` must be NULL or a live plate; `count` NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_glass_crack_count(glass: *const hibi_glass, count: *mut usize) -> hibi_status {
    let read = |glass: &hibi_glass| Ok(glass.glass.crack_count());
    // SAFETY: the caller's contract.
    guard(|| unsafe { query(glass, c"glass", (count, c"count"), read) })
}

/// The plate behind `glass` and its crack `index` (else `HIBI_ERROR_GLASS_CRACK_INDEX`), once
/// the query's required out-parameter `out` is checked.
///
/// # Safety
/// As [`object_ref`].
unsafe fn crack_of<'a, O>(
    glass: *const hibi_glass,
    index: usize,
    (out, name): (*mut O, &'static CStr),
) -> Result<(&'a Glass<'static>, Crack), hibi_status> {
    // SAFETY: the caller's contract.
    let glass = &unsafe { object_ref(glass, c"glass") }?.glass;
    check_pointer(out, name)?;
    Ok((glass, glass.crack(index).ok_or(HIBI_ERROR_GLASS_CRACK_INDEX)?))
}

/// Describes crack `index` (below `hibi_glass_crack_count`).
///
/// # Safety
/// `glass` must be NULL or a live plate; `crack` NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_glass_crack_info(
    glass: *const hibi_glass,
    index: usize,
    crack: *mut hibi_glass_crack,
) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let (glass, c) = unsafe { crack_of(glass, index, (crack, c"crack")) }?;
        let value = hibi_glass_crack {
            kind: c.kind as u32,
            end: c.end as u32,
            impact: c.impact,
            points: glass.point_count(index) as u32,
        };
        // SAFETY: checked; the caller's contract.
        unsafe { write_out(crack, c"crack", value) }
    })
}

/// Writes crack `index`'s polyline into `points[0..len]` and its length into `*written`.
/// If `len` is too small, nothing is written and the status is `HIBI_ERROR_BUFFER_TOO_SMALL`.
///
/// # Safety
/// `glass` must be NULL or a live plate; `points` NULL (only with `len` 0) or writable for
/// `len` points; `written` NULL (refused) or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_glass_points(
    glass: *const hibi_glass,
    index: usize,
    points: *mut CrackPoint,
    len: usize,
    written: *mut usize,
) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let (glass, _) = unsafe { crack_of(glass, index, (written, c"written")) }?;
        // SAFETY: the caller's contract.
        let out = unsafe { buffer(points, len, c"points") }?;
        let n = glass.points(index, out).map_err(|e| crate::status::short_buffer(glass_status(e), c"points"))?;
        // SAFETY: checked; the caller's contract.
        unsafe { write_out(written, c"written", n) }
    })
}

/// A point of a fragment's outline [px].
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct hibi_vec2 {
    /// x.
    pub x: f32,
    /// y.
    pub y: f32,
}

const _: () =
    assert!(size_of::<hibi_vec2>() == size_of::<[f32; 2]>() && align_of::<hibi_vec2>() == align_of::<[f32; 2]>());

/// Writes the bytes of scratch (aligned to `hibi_glass_memory_align()`) that
/// `hibi_glass_fragment_counts` and `hibi_glass_fragments` work in. The scratch is the
/// caller's so that those queries only read the plate: several threads may query one plate
/// at once, each with its own scratch.
///
/// # Safety
/// `glass` must be NULL or a live plate; `size` NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_glass_scratch_size(glass: *const hibi_glass, size: *mut usize) -> hibi_status {
    let read = |glass: &hibi_glass| object::scratch_size(|arena| arena.take::<u32>(glass.scratch));
    // SAFETY: the caller's contract.
    guard(|| unsafe { query(glass, c"glass", (size, c"size"), read) })
}

/// The plate's fragment scratch, checked (after everything else of the call's, so that a
/// refused call leaves it untouched).
///
/// # Safety
/// As `hibi_glass_fragment_counts`.
unsafe fn fragment_scratch<'a>(
    glass: &hibi_glass,
    scratch: *mut c_void,
    scratch_size: usize,
) -> Result<&'a mut [u32], hibi_status> {
    // SAFETY: the caller's contract.
    unsafe { object::scratch(scratch, scratch_size, |arena| arena.take::<u32>(glass.scratch)) }
}

/// Writes how many fragment rings and ring points `hibi_glass_fragments` will write for the
/// network as it stands. Works in `scratch` (`scratch_size` bytes, at least
/// `hibi_glass_scratch_size`); the plate is only read.
///
/// # Safety
/// `glass` must be NULL or a live plate; `scratch` NULL or writable for `scratch_size` bytes
/// and used by no other call meanwhile; `rings` and `points` NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_glass_fragment_counts(
    glass: *const hibi_glass,
    scratch: *mut c_void,
    scratch_size: usize,
    rings: *mut usize,
    points: *mut usize,
) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let glass = unsafe { object_ref(glass, c"glass") }?;
        let outs = Outs::check([(rings, c"rings"), (points, c"points")])?;
        // SAFETY: the caller's contract.
        let scratch = unsafe { fragment_scratch(glass, scratch, scratch_size) }?;
        let (r, p) = glass.glass.fragment_counts(scratch).map_err(glass_status)?;
        // SAFETY: checked; the caller's contract.
        unsafe { outs.write([r, p]) }
    })
}

polygon_query! {
    /// Writes the fragments the cracks cut the plate into, as polygons for a physics engine:
    /// one `hibi_ring` per ring into `rings[0..rings_len]`, their points into
    /// `points[0..points_len]`, and the counts into `*rings_written` and `*points_written`.
    /// Cracks that end inside a fragment do not cut it. If a buffer is too small (see `hibi_glass_fragment_counts`), nothing is
    /// written and the status is `HIBI_ERROR_BUFFER_TOO_SMALL`. Works in `scratch` as
    /// `hibi_glass_fragment_counts` does; the plate is only read.
    ///
    /// # Safety
    /// `glass` must be NULL or a live plate; `scratch` as in `hibi_glass_fragment_counts`;
    hibi_glass_fragments(glass: hibi_glass, scratch: *mut c_void, scratch_size: usize);
    {
        // SAFETY: the caller's contract.
        let glass = unsafe { object_ref(glass, c"glass") }?;
    }
    // SAFETY: the caller's contract.
    |rings, points| {
        let lengths = (rings.len(), points.len());
        // SAFETY: the caller's contract.
        let words = unsafe { fragment_scratch(glass, scratch, scratch_size) }?;
        match glass.glass.fragments(words, rings, points) {
            Err(GlassError::BufferTooSmall { .. }) => {
                // Only on the failure path: count again to name the short buffer.
                let (r, p) = glass.glass.fragment_counts(words).map_err(glass_status)?;
                Err(crate::status::first_short(&[(c"rings", lengths.0, r), (c"points", lengths.1, p)]))
            }
            result => result.map_err(glass_status),
        }
    }
}

/// A budgeted build of a plate's fragments, in caller memory
/// (`hibi_glass_fragment_build_create_in`). Opaque; nothing to free (the memory stays the
/// caller's).
pub struct hibi_glass_fragment_build {
    build: FragmentBuild<'static>,
}

/// Where a fragment build stands.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct hibi_glass_fragment_progress {
    /// Rings found so far (all of them once finished).
    pub rings: u32,
    /// Their points.
    pub points: u32,
    /// 1 when every ring is found and every hole knows its outer ring: the rings and points
    /// can then be read (`hibi_glass_fragment_build_rings`, `hibi_glass_fragment_build_points`).
    pub finished: u32,
    /// Always 0: the struct has no padding, so every byte a call writes is defined.
    pub reserved: u32,
    /// Work done since the build (re)started, in the units of the step's budget.
    pub work: u64,
}

impl hibi_glass_fragment_progress {
    /// A core progress as the C struct (the counts are below 2^31: a plate's rings and
    /// points are bounded by four times its vertex capacity of at most 2^28, and eight more).
    fn of(p: &FragmentProgress) -> Self {
        hibi_glass_fragment_progress {
            rings: p.rings as u32,
            points: p.points as u32,
            finished: u32::from(p.finished),
            reserved: 0,
            work: p.work,
        }
    }
}

// SAFETY: a ring is an f64 and four u32 (24 bytes, no padding, checked below).
unsafe impl AnyBits for hibi_core::polygon::Ring {}
const _: () = assert!(size_of::<hibi_core::polygon::Ring>() == 24, "only f64 and u32 fields");

/// A fragment build's block: its header, then its scratch words, rings and points, each taken
/// as it is (the build reads no element it has not written).
fn fragment_build_arrays(
    m: &FragmentBuildMemory,
    arena: &mut Arena,
) -> (*mut hibi_glass_fragment_build, FragmentBuildBuffers<'static>) {
    let header = arena.reserve::<hibi_glass_fragment_build>();
    let buffers = FragmentBuildBuffers {
        words: arena.take_as_is(m.words),
        rings: arena.take_as_is(m.rings),
        points: arena.take_as_is(m.points),
    };
    (header, buffers)
}

/// Writes the bytes of caller memory a fragment build of `glass` needs (for
/// `hibi_glass_fragment_build_create_in`; aligned to `hibi_glass_memory_align()`). It follows
/// the plate's vertex capacity, so one block serves the plate at any point of its growth.
///
/// # Safety
/// `glass` must be NULL or a live plate; `size` NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_glass_fragment_build_size(glass: *const hibi_glass, size: *mut usize) -> hibi_status {
    let read = |glass: &hibi_glass| {
        let m = glass.glass.fragment_build_memory();
        object::scratch_size(|arena| fragment_build_arrays(&m, arena))
    };
    // SAFETY: the caller's contract.
    guard(|| unsafe { query(glass, c"glass", (size, c"size"), read) })
}

/// Makes a build of `glass`'s fragments in caller memory of at least
/// `hibi_glass_fragment_build_size` bytes aligned to `hibi_glass_memory_align()`, in the same
/// work at any size (nothing is written but the build's header); `hibi_glass_fragment_build_step`
/// does the work. The build yields the rings and points `hibi_glass_fragments` writes, bit for
/// bit, read in ranges once finished. Nothing is written on failure; there is nothing to
/// destroy.
///
/// # Safety
/// `glass` must be NULL or a live plate; `memory` NULL or writable for `memory_size` bytes and
/// untouched while the build is used; `out` NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_glass_fragment_build_create_in(
    glass: *const hibi_glass,
    memory: *mut c_void,
    memory_size: usize,
    out: *mut *mut hibi_glass_fragment_build,
) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let glass = unsafe { object_ref(glass, c"glass") }?;
        check_pointer(out, c"out")?;
        let m = glass.glass.fragment_build_memory();
        // SAFETY: the caller's contract.
        let (header, buffers) =
            unsafe { object::caller_arrays(memory, memory_size, |arena| fragment_build_arrays(&m, arena)) }?;
        let build = FragmentBuild::new(&glass.glass, buffers).map_err(glass_status)?;
        // SAFETY: the header's room at the block's start, aligned (`caller_arrays` checked the
        // block against this layout).
        unsafe { header.write(hibi_glass_fragment_build { build }) };
        // SAFETY: checked; the caller's contract.
        unsafe { write_out(out, c"out", header) }
    })
}

/// Goes on with `build` on `glass` until about `budget` units of work are done in this call,
/// or it is finished; writes where it stands to `*progress` unless it is NULL. A unit is an
/// array element counted or tested (16 where a pass only clears or fills), a step of a face
/// walk (and one more per edge at the vertex it reaches), a level of the border's sort, or a
/// point of a ring tested for a hole; a call does at least one piece and overruns the budget
/// by less than one: one unit and one per edge at a vertex. The result does not depend on the
/// budgets. A plate whose network changed since the build began (stepped, or hit again)
/// starts the build over (its work from 0). Steps of one build must not run at once; the plate
/// is only read.
///
/// # Safety
/// `build` must be NULL or a live build; `glass` NULL or a live plate not changed during the
/// call; `progress` optional: NULL (not written) or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_glass_fragment_build_step(
    build: *mut hibi_glass_fragment_build,
    glass: *const hibi_glass,
    budget: u64,
    progress: *mut hibi_glass_fragment_progress,
) -> hibi_status {
    let step = |build: &mut hibi_glass_fragment_build| {
        // SAFETY: the caller's contract.
        let glass = unsafe { object_ref(glass, c"glass") }?;
        let p = build.build.step(&glass.glass, budget).map_err(glass_status)?;
        Ok(hibi_glass_fragment_progress::of(&p))
    };
    // SAFETY: the caller's contract.
    guard(|| unsafe { update(build, c"build", (progress, c"progress"), step) })
}

/// Writes the rings of a finished `build` from ring `first` on into `rings[0..rings_len]`:
/// as many as there are, at most `rings_len` (none before the build is finished, or from a
/// `first` at or past the ring count), and how many into `*written`. The rings
/// `[first, first + rings_len)` of `hibi_glass_fragments`: ranges read one after another
/// concatenate to its rings, and each ring's `first_point` indexes the whole points list
/// (`hibi_glass_fragment_build_points`).
///
/// # Safety
/// `build` must be NULL or a live build; `rings` NULL (only with `rings_len` 0) or writable
/// for `rings_len` rings; `written` NULL (refused) or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_glass_fragment_build_rings(
    build: *const hibi_glass_fragment_build,
    first: usize,
    rings: *mut hibi_core::polygon::Ring,
    rings_len: usize,
    written: *mut usize,
) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let build = unsafe { object_ref(build, c"build") }?;
        // SAFETY: the caller's contract.
        unsafe { copy_from(build.build.rings(), first, (rings, rings_len, c"rings"), written) }
    })
}

/// Writes the ring points of a finished `build` from point `first` on into
/// `points[0..points_len]`, as `hibi_glass_fragment_build_rings` writes rings.
///
/// # Safety
/// `build` must be NULL or a live build; `points` NULL (only with `points_len` 0) or writable
/// for `points_len` points; `written` NULL (refused) or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_glass_fragment_build_points(
    build: *const hibi_glass_fragment_build,
    first: usize,
    points: *mut hibi_vec2,
    points_len: usize,
    written: *mut usize,
) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let build = unsafe { object_ref(build, c"build") }?;
        // SAFETY: hibi_vec2 is laid out as [f32; 2] (asserted above).
        let points = points.cast::<[f32; 2]>();
        // SAFETY: the caller's contract.
        unsafe { copy_from(build.build.points(), first, (points, points_len, c"points"), written) }
    })
}

/// Render layer: crack coverage, `uint8_t` per pixel, 0 (none) to 255.
pub const HIBI_GLASS_LAYER_MASK: u32 = 0;
/// Render layer: the step at which the crack front passed, `float` per pixel, +infinity where
/// no crack is.
pub const HIBI_GLASS_LAYER_TIME: u32 = 1;

/// Default drawing: 640 × 640, 1.2-pixel lines.
#[unsafe(no_mangle)]
pub extern "C" fn hibi_glass_render_params_default() -> hibi_glass_render_params {
    guard(|| hibi_glass_render_params::from_core(&GlassRender::default()))
}

render! {
    /// Draws `layer` into `pixels` (row-major, `width × height` values: `uint8_t` for
    /// `HIBI_GLASS_LAYER_MASK`, `float` for `HIBI_GLASS_LAYER_TIME`). `pixels_len` counts values.
    /// Nothing is written on failure.
    hibi_glass_render(glass: hibi_glass, "plate", hibi_glass_render_params) = glass_layers, crate::status::raster_status
}

crate::raster::render_layers! {
    /// Draws every layer `layers` gives (mask, height, height16, normal, normal_rgb8, time,
    /// preview; see `hibi_layers`) of `tile` (NULL: the whole `width × height` image) in one
    /// pass, each pixel bit for bit as the whole image has it. Nothing is written on failure;
    /// `hibi_error_argument()` names a refused layer (`"layers.cell"`, ...) or `"tile"`.
    hibi_glass_render_layers(glass: hibi_glass, "plate", hibi_glass_render_params) =
        |_, r: &GlassRender| hibi_core::raster::Tile::whole(r.width, r.height), crate::raster::layers_status
}

/// Glass's layers with `layer` to be drawn into `pixels`.
fn glass_layers(layer: u32, pixels: Pixels<'_>) -> Result<GlassLayers<'_>, hibi_status> {
    // SAFETY (every arm): the layer's type, as the header gives it for that layer.
    Ok(match layer {
        HIBI_GLASS_LAYER_MASK => GlassLayers { mask: Some(unsafe { pixels.values() }?), ..GlassLayers::default() },
        HIBI_GLASS_LAYER_TIME => GlassLayers { time: Some(unsafe { pixels.values() }?), ..GlassLayers::default() },
        _ => return Err(HIBI_ERROR_GLASS_RENDER_LAYER),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constants::*;
    use crate::status::*;
    use core::ptr::null_mut;

    #[test]
    fn bad_fields_and_enums_are_specific_statuses_and_nothing_is_created() {
        type Spoil = fn(&mut hibi_glass_params);
        let cases: [(Spoil, hibi_status); 6] = [
            (|p| p.cookie = 1, HIBI_ERROR_GLASS_PARAMS_NOT_INITIALISED),
            (|p| p.spread = 5, HIBI_ERROR_GLASS_ENUM),
            (|p| p.width = f32::NAN, HIBI_ERROR_GLASS_SIZE),
            (|p| p.ring_speed = 0.0, HIBI_ERROR_GLASS_SPEED),
            (|p| p.spread_ratio = 1.0, HIBI_ERROR_GLASS_SPREAD_RATIO),
            (|p| p.max_vertices = 1, HIBI_ERROR_GLASS_CAPACITY_PARAMS),
        ];
        for (spoil, expected) in cases {
            let mut p = hibi_glass_params_default();
            spoil(&mut p);
            let mut out = null_mut();
            let mut size = 99usize;
            // SAFETY: valid pointers; failing calls write nothing.
            unsafe {
                assert_eq!(hibi_glass_create(&p, &mut out), expected);
                assert_eq!(hibi_glass_memory_size(&p, &mut size), expected);
            }
            assert!(out.is_null() && size == 99);
        }
    }

    #[test]
    fn capacity_is_a_status_and_the_plate_stays_usable() {
        let mut p = hibi_glass_params_default();
        p.max_vertices = 80;
        let mut glass = null_mut();
        // SAFETY: valid pointers throughout.
        unsafe {
            assert_eq!(hibi_glass_create(&p, &mut glass), HIBI_OK);
            let mut progress = hibi_glass_progress::default();
            let mut status = HIBI_OK;
            for _ in 0..1000 {
                status = hibi_glass_step(glass, 1000, &mut progress);
                if status != HIBI_OK {
                    break;
                }
            }
            assert_eq!(status, HIBI_ERROR_GLASS_CAPACITY);
            let mut count = 0;
            assert_eq!(hibi_glass_crack_count(glass, &mut count), HIBI_OK);
            let mut crack = hibi_glass_crack::default();
            assert_eq!(hibi_glass_crack_info(glass, 0, &mut crack), HIBI_OK);
            let mut points = vec![CrackPoint::default(); crack.points as usize];
            let mut written = 0;
            if crack.points > 0 {
                let short = crack.points as usize - 1;
                assert_eq!(
                    hibi_glass_points(glass, 0, points.as_mut_ptr(), short, &mut written),
                    HIBI_ERROR_BUFFER_TOO_SMALL
                );
                assert_eq!(written, 0);
            }
            assert_eq!(hibi_glass_points(glass, 0, points.as_mut_ptr(), points.len(), &mut written), HIBI_OK);
            assert_eq!(written, crack.points as usize);
            assert_eq!(hibi_glass_impact(glass, 1.0, -3.0, null_mut()), HIBI_ERROR_GLASS_IMPACT);
            hibi_glass_destroy(glass);
        }
    }

    #[test]
    fn fragments_come_in_counted_buffers_and_short_ones_are_left_alone() {
        let p = hibi_glass_params_default();
        let mut glass = null_mut();
        // SAFETY: valid pointers throughout.
        unsafe {
            assert_eq!(hibi_glass_create(&p, &mut glass), HIBI_OK);
            let mut progress = hibi_glass_progress::default();
            while progress.finished == 0 {
                assert_eq!(hibi_glass_step(glass, 10_000, &mut progress), HIBI_OK);
            }
            let (mut ring_count, mut point_count) = (0usize, 0usize);
            let mut ss = 0;
            assert_eq!(hibi_glass_scratch_size(glass, &mut ss), HIBI_OK);
            let mut scratch = vec![0u64; ss.div_ceil(8)];
            let sp = scratch.as_mut_ptr().cast::<c_void>();
            assert_eq!(hibi_glass_fragment_counts(glass, sp, ss, &mut ring_count, null_mut()), HIBI_ERROR_NULL_POINTER);
            assert_eq!(
                hibi_glass_fragment_counts(null_mut(), sp, ss, &mut ring_count, &mut point_count),
                HIBI_ERROR_NULL_POINTER
            );
            assert_eq!(ring_count, 0);
            assert_eq!(hibi_glass_fragment_counts(glass, sp, ss, &mut ring_count, &mut point_count), HIBI_OK);
            assert!(ring_count > 10 && point_count > 3 * ring_count);
            let mut rings = vec![hibi_core::polygon::Ring::default(); ring_count];
            let mut points = vec![hibi_vec2 { x: 9.0, y: 9.0 }; point_count];
            let (mut r, mut n) = (7usize, 7usize);
            let (ring_ptr, point_ptr) = (rings.as_mut_ptr(), points.as_mut_ptr());
            let fragments = |points_len, r: &mut usize, n: &mut usize| {
                hibi_glass_fragments(glass, sp, ss, ring_ptr, ring_count, point_ptr, points_len, r, n)
            };
            let status = fragments(point_count - 1, &mut r, &mut n);
            assert_eq!(status, HIBI_ERROR_BUFFER_TOO_SMALL);
            let named = core::ffi::CStr::from_ptr(crate::status::hibi_error_argument());
            assert_eq!(named.to_str(), Ok("points"), "the short buffer is named");
            let status =
                hibi_glass_fragments(glass, sp, ss, ring_ptr, ring_count - 1, point_ptr, point_count, &mut r, &mut n);
            assert_eq!(status, HIBI_ERROR_BUFFER_TOO_SMALL);
            let named = core::ffi::CStr::from_ptr(crate::status::hibi_error_argument());
            assert_eq!(named.to_str(), Ok("rings"), "the short buffer is named");
            assert!((r, n) == (7, 7) && rings.iter().all(|x| x.point_count == 0) && points.iter().all(|q| q.x == 9.0));
            let status = fragments(point_count, &mut r, &mut n);
            assert_eq!(status, HIBI_OK);
            assert_eq!((r, n), (ring_count, point_count));
            let area: f64 = rings.iter().map(|x| x.area).sum();
            assert!((area - 640.0 * 640.0).abs() < 1e-3, "{area}");
            assert!(rings.iter().all(|x| x.hole_of == crate::HIBI_RING_NOT_A_HOLE && x.area > 0.0));
            assert_eq!(rings.iter().map(|x| x.point_count as usize).sum::<usize>(), point_count);
            hibi_glass_destroy(glass);
        }
    }

    /// A refused fragment query names the first bad argument in the order plate, counts,
    /// buffers, scratch, and leaves the caller's scratch as it was.
    #[test]
    fn a_refused_fragment_query_names_its_first_bad_argument_and_leaves_the_scratch_alone() {
        let mut p = hibi_glass_params_default();
        (p.width, p.height, p.impact) = (160.0, 160.0, [80.0, 80.0]);
        let mut glass = null_mut();
        let argument = || unsafe { core::ffi::CStr::from_ptr(crate::status::hibi_error_argument()) };
        // SAFETY: valid pointers throughout, buffers of the lengths passed.
        unsafe {
            assert_eq!(hibi_glass_create(&p, &mut glass), HIBI_OK);
            assert_eq!(hibi_glass_step(glass, u64::MAX, null_mut()), HIBI_OK);
            let mut ss = 0;
            assert_eq!(hibi_glass_scratch_size(glass, &mut ss), HIBI_OK);
            let mut scratch = vec![0xA5A5_A5A5_A5A5_A5A5u64; ss.div_ceil(8)];
            let sp = scratch.as_mut_ptr().cast::<c_void>();
            let (mut rings, mut points) = ([hibi_core::polygon::Ring::default(); 4], [hibi_vec2::default(); 4]);
            let (rp, pp) = (rings.as_mut_ptr(), points.as_mut_ptr());
            let (mut r, mut n) = (0usize, 0usize);
            let (r, n) = (&raw mut r, &raw mut n);
            let cases: [(hibi_status, &core::ffi::CStr, &dyn Fn() -> hibi_status); 6] = [
                (HIBI_ERROR_NULL_POINTER, c"glass", &|| hibi_glass_fragment_counts(null_mut(), sp, 8, r, null_mut())),
                (HIBI_ERROR_NULL_POINTER, c"points", &|| hibi_glass_fragment_counts(glass, sp, 8, r, null_mut())),
                (HIBI_ERROR_NULL_POINTER, c"points", &|| hibi_glass_fragment_counts(glass, sp, ss, n, null_mut())),
                (HIBI_ERROR_NULL_POINTER, c"glass", &|| {
                    hibi_glass_fragments(null_mut(), sp, 8, rp, 4, pp, 4, null_mut(), n)
                }),
                (HIBI_ERROR_NULL_POINTER, c"rings_written", &|| {
                    hibi_glass_fragments(glass, sp, 8, rp, 4, pp, 4, null_mut(), n)
                }),
                (HIBI_ERROR_NULL_POINTER, c"points", &|| {
                    hibi_glass_fragments(glass, sp, ss, rp, 4, null_mut(), 4, r, n)
                }),
            ];
            for (k, (status, name, call)) in cases.iter().enumerate() {
                assert_eq!((call(), argument()), (*status, *name), "case {k}");
                assert!(scratch.iter().all(|&w| w == 0xA5A5_A5A5_A5A5_A5A5), "case {k} wrote the scratch");
            }
            assert_eq!(hibi_glass_fragment_counts(glass, sp, ss - 1, r, n), HIBI_ERROR_BUFFER_TOO_SMALL);
            assert_eq!(argument(), c"scratch");
            hibi_glass_destroy(glass);
        }
    }

    /// A fragment build in caller memory of any bytes, stepped with a small budget, gives in
    /// ranges the rings and points `hibi_glass_fragments` writes; refused calls name their
    /// argument and write nothing.
    #[test]
    fn a_fragment_build_gives_the_fragments_in_ranges() {
        let mut p = hibi_glass_params_default();
        (p.width, p.height, p.impact) = (200.0, 200.0, [100.0, 100.0]);
        let mut glass = null_mut();
        // SAFETY: valid pointers throughout; failing calls write nothing.
        unsafe {
            assert_eq!(hibi_glass_create(&p, &mut glass), HIBI_OK);
            assert_eq!(hibi_glass_step(glass, u64::MAX, null_mut()), HIBI_OK);
            let mut ss = 0;
            assert_eq!(hibi_glass_scratch_size(glass, &mut ss), HIBI_OK);
            let mut scratch = vec![0u64; ss.div_ceil(8)];
            let sp = scratch.as_mut_ptr().cast::<c_void>();
            let (mut rc, mut pc) = (0, 0);
            assert_eq!(hibi_glass_fragment_counts(glass, sp, ss, &mut rc, &mut pc), HIBI_OK);
            let mut rings = vec![hibi_core::polygon::Ring::default(); rc];
            let mut points = vec![hibi_vec2::default(); pc];
            let (mut r, mut n) = (0, 0);
            let status =
                hibi_glass_fragments(glass, sp, ss, rings.as_mut_ptr(), rc, points.as_mut_ptr(), pc, &mut r, &mut n);
            assert_eq!(status, HIBI_OK);

            let mut size = 0;
            assert_eq!(hibi_glass_fragment_build_size(glass, &mut size), HIBI_OK);
            let mut memory = vec![0xA5A5_A5A5_A5A5_A5A5u64; size.div_ceil(8)];
            let base = memory.as_mut_ptr().cast::<c_void>();
            let mut build = null_mut();
            assert_eq!(
                hibi_glass_fragment_build_create_in(glass, base, size - 1, &mut build),
                HIBI_ERROR_BUFFER_TOO_SMALL
            );
            assert_eq!(CStr::from_ptr(crate::status::hibi_error_argument()), c"memory");
            assert_eq!(
                hibi_glass_fragment_build_create_in(null_mut(), base, size, &mut build),
                HIBI_ERROR_NULL_POINTER
            );
            assert_eq!(hibi_glass_fragment_build_create_in(glass, base, size, null_mut()), HIBI_ERROR_NULL_POINTER);
            assert!(build.is_null() && memory.iter().all(|&w| w == 0xA5A5_A5A5_A5A5_A5A5), "nothing written");
            assert_eq!(hibi_glass_fragment_build_create_in(glass, base, size, &mut build), HIBI_OK);
            let mut progress = hibi_glass_fragment_progress::default();
            let (mut calls, mut before) = (0, 0);
            while progress.finished == 0 {
                assert_eq!(hibi_glass_fragment_build_step(build, glass, 50, &mut progress), HIBI_OK);
                // (A piece: a unit, and one per edge at a vertex: at most the impact's radial
                // cracks, two border edges, or a few where cracks meet.)
                let radial = (*glass).glass.impact_counts().radial as u64;
                assert!(progress.work - before < 50 + 3 + radial.max(8), "{progress:?}");
                before = progress.work;
                calls += 1;
            }
            assert!(calls > 10 && progress.reserved == 0, "{calls} calls");
            assert_eq!((progress.rings as usize, progress.points as usize), (rc, pc));
            let (mut got_rings, mut got_points) = (Vec::new(), Vec::new());
            let mut out = [hibi_core::polygon::Ring::default(); 5];
            let mut written = 99;
            let mut first = 0;
            loop {
                assert_eq!(hibi_glass_fragment_build_rings(build, first, out.as_mut_ptr(), 5, &mut written), HIBI_OK);
                if written == 0 {
                    break;
                }
                got_rings.extend_from_slice(&out[..written]);
                first += written;
            }
            let mut out = [hibi_vec2::default(); 7];
            first = 0;
            loop {
                assert_eq!(hibi_glass_fragment_build_points(build, first, out.as_mut_ptr(), 7, &mut written), HIBI_OK);
                if written == 0 {
                    break;
                }
                got_points.extend_from_slice(&out[..written]);
                first += written;
            }
            assert!(got_rings == rings);
            assert!(got_points.iter().zip(&points).all(|(a, b)| (a.x, a.y) == (b.x, b.y)) && got_points.len() == pc);
            assert_eq!(
                hibi_glass_fragment_build_rings(build, 0, out.as_mut_ptr().cast(), 1, null_mut()),
                HIBI_ERROR_NULL_POINTER
            );
            assert_eq!(CStr::from_ptr(crate::status::hibi_error_argument()), c"written");
            assert_eq!(hibi_glass_fragment_build_step(null_mut(), glass, 1, null_mut()), HIBI_ERROR_NULL_POINTER);
            assert_eq!(CStr::from_ptr(crate::status::hibi_error_argument()), c"build");
            hibi_glass_destroy(glass);
        }
    }
}
