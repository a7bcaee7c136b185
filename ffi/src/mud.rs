//! `hibi_mud`: model A, the drying-mud spring lattice (Hirota et al.), from C.
//!
//! ```c
//! hibi_mud_params params = hibi_mud_params_default();
//! params.columns = params.rows = 128;
//! hibi_mud *mud = NULL;
//! if (hibi_mud_create(&params, &mud) != HIBI_OK) { ... }
//! hibi_mud_progress progress;
//! do { hibi_mud_step(mud, 1000000, &progress); } while (!progress.finished);
//! hibi_mud_render(mud, &render, HIBI_MUD_LAYER_MASK, pixels, width * height);
//! hibi_mud_destroy(mud);
//! ```
//!
//! An object is one block: the header, then the model's scalar and word arrays. With
//! `hibi_mud_memory_size` and `hibi_mud_create_in` the block is the caller's.

use core::ffi::c_void;
use core::mem::{align_of, size_of};

use hibi_core::mud::{Boundary, CrackSegment, Drive, Mud, MudError, MudLayer, MudParams, MudRender, Solver, Topology};
use hibi_core::raster::RasterError;

use crate::guard::{buffer, check_pointer, guard, object, write_out};
use crate::memory::{Origin, caller_block, library_block, release_block, round_up};
use crate::status::{
    HIBI_ERROR_BUFFER_TOO_SMALL, HIBI_ERROR_MUD_ENUM, HIBI_ERROR_MUD_PARAMS_NOT_INITIALISED, HIBI_ERROR_RENDER_LAYER,
    HIBI_ERROR_SIZE_OVERFLOW, hibi_status, mud_param_status, raster_status,
};

/// Square elements: 4 neighbours, axis-aligned short cracks.
pub const HIBI_MUD_SQUARE: u32 = 0;
/// Hexagonal elements (a triangular lattice of nodes): 6 neighbours, isotropic cracks.
pub const HIBI_MUD_HEXAGONAL: u32 = 1;
/// Free edges.
pub const HIBI_MUD_OPEN: u32 = 0;
/// The lattice wraps around: tileable patterns.
pub const HIBI_MUD_PERIODIC: u32 = 1;
/// The paper's explicit loop (reference; slow).
pub const HIBI_MUD_EXPLICIT: u32 = 0;
/// Quasi-static equilibrium with event-driven breaking (fast; the default).
pub const HIBI_MUD_QUASI_STATIC: u32 = 1;
/// The surface shrinks (drying mud).
pub const HIBI_MUD_SHRINK: u32 = 0;
/// The deep layer grows (tree bark).
pub const HIBI_MUD_GROWTH: u32 = 1;
/// Render layer: crack coverage, `uint8_t` per pixel, 0 (none) to 255.
pub const HIBI_MUD_LAYER_MASK: u32 = 0;
/// Render layer: height, `float` per pixel, 1 on the surface, lower in the cracks.
pub const HIBI_MUD_LAYER_HEIGHT: u32 = 1;
/// Render layer: break time in long steps, `float` per pixel, +infinity where no crack is.
pub const HIBI_MUD_LAYER_TIME: u32 = 2;

const _: () = assert!(
    HIBI_MUD_SQUARE == Topology::Square as u32
        && HIBI_MUD_HEXAGONAL == Topology::Hexagonal as u32
        && HIBI_MUD_OPEN == Boundary::Open as u32
        && HIBI_MUD_PERIODIC == Boundary::Periodic as u32
        && HIBI_MUD_EXPLICIT == Solver::Explicit as u32
        && HIBI_MUD_QUASI_STATIC == Solver::QuasiStatic as u32
        && HIBI_MUD_SHRINK == Drive::Shrink as u32
        && HIBI_MUD_GROWTH == Drive::Growth as u32
        && HIBI_MUD_LAYER_MASK == MudLayer::Mask as u32
        && HIBI_MUD_LAYER_HEIGHT == MudLayer::Height as u32
        && HIBI_MUD_LAYER_TIME == MudLayer::Time as u32
);

/// Marks a params struct that came from `hibi_mud_params_default` ("MUD1").
const PARAMS_COOKIE: u32 = 0x4D55_4431;

/// The parameters of a drying-mud run, in the paper's units (cm, g, s). Get them from
/// `hibi_mud_params_default` (the paper's values), then change fields; `hibi_mud_create`
/// rejects a struct that did not come from there.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct hibi_mud_params {
    /// Set by `hibi_mud_params_default`; leave it alone.
    pub cookie: u32,
    /// `HIBI_MUD_SQUARE` or `HIBI_MUD_HEXAGONAL` (default).
    pub topology: u32,
    /// `HIBI_MUD_OPEN` or `HIBI_MUD_PERIODIC` (default).
    pub boundary: u32,
    /// `HIBI_MUD_EXPLICIT` or `HIBI_MUD_QUASI_STATIC` (default).
    pub solver: u32,
    /// `HIBI_MUD_SHRINK` (default) or `HIBI_MUD_GROWTH`.
    pub drive: u32,
    /// Nodes per row (default 128).
    pub columns: u32,
    /// Rows of nodes (default 128; even for periodic hexagonal lattices).
    pub rows: u32,
    /// Seed of every random draw.
    pub seed: u64,
    /// H, surface layer thickness [cm] (default 1).
    pub layer_thickness: f32,
    /// W, element size [cm] (default 1).
    pub element_size: f32,
    /// T, long time step [s] (default 1).
    pub long_step: f32,
    /// τ, short time step [s] (paper: 0.001).
    pub short_step: f32,
    /// γ, shrink ratio per long step (paper: 0.9999).
    pub shrink_ratio: f32,
    /// δx, allowed displacement error [cm] (paper: 1e-4).
    pub displacement_tolerance: f32,
    /// α, damping factor (paper: 20).
    pub damping_factor: f32,
    /// ρ, density [g/cm³] (default 1.8).
    pub density: f32,
    /// E, Young's modulus [g/(cm·s²)] (paper: 1e6).
    pub young_modulus: f32,
    /// G, shear modulus [g/(cm·s²)] (paper: 2e5).
    pub shear_modulus: f32,
    /// κ̄, mean break stretch (paper: 1.02).
    pub break_stretch_mean: f32,
    /// σ, break stretch spread per unit area [1/cm] (paper: 0.001).
    pub break_stretch_spread: f32,
    /// Direction cracks prefer [radians] (default 0).
    pub anisotropy_direction: f32,
    /// How much weaker springs across that direction are (1 = isotropic, default).
    pub anisotropy_ratio: f32,
    /// Stiffness anisotropy ratio (1 = none, default).
    pub stiffness_anisotropy_ratio: f32,
    /// End at this shrink (default 0.022; 0 = no limit).
    pub target_shrink: f32,
    /// End at this crack length per area [1/cm] (default 0 = no limit).
    pub target_crack_density: f32,
}

/// Where a run stands.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct hibi_mud_progress {
    /// Shrink 1 − r (growth: 1/r − 1).
    pub shrink: f32,
    /// Time in long steps.
    pub time: f32,
    /// Springs broken so far.
    pub broken_springs: u32,
    /// Crack length per area [1/cm].
    pub crack_density: f32,
    /// Work done since the run began (units of the step budget).
    pub work: u64,
    /// 1 when the run reached its end, else 0.
    pub finished: u32,
}

/// One straight piece of crack, in lattice units (× element_size for cm). Each end carries
/// the crack width and break time (long steps) of the spring it sits on.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct hibi_mud_segment {
    /// First end (x, y).
    pub start: [f32; 2],
    /// Second end (x, y).
    pub end: [f32; 2],
    /// Width at each end.
    pub width: [f32; 2],
    /// Break time at each end.
    pub time: [f32; 2],
}

/// Crack statistics of the traced network: density and the cells it encloses.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct hibi_mud_statistics {
    /// Crack length per area [1/cm].
    pub crack_density: f32,
    /// Cells the network's separating cracks enclose.
    pub cells: u32,
    /// Mean cell area [cm²].
    pub mean_cell_area: f32,
}

/// How to draw a raster: its size and the stroke widths. Defaults from
/// `hibi_mud_render_params_default`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct hibi_mud_render_params {
    /// Raster width in pixels (default 512); the lattice's domain is stretched over it.
    pub width: u32,
    /// Raster height in pixels (default 512).
    pub height: u32,
    /// Crack widths are multiplied by this (default 1).
    pub width_scale: f32,
    /// The narrowest stroke in pixels (default 1).
    pub min_width: f32,
    /// Depth of the widest groove in the height layer (default 1).
    pub groove_depth: f32,
    /// Where the raster's top-left corner sits in the domain, lattice units (default 0, 0).
    pub offset: [f32; 2],
}

impl crate::guard::Outcome for hibi_mud_params {
    type C = hibi_mud_params;
    fn into_c(self) -> Self {
        self
    }
    /// A struct without the cookie, which every function rejects.
    fn on_panic() -> Self {
        let mut p = hibi_mud_params_default_values();
        p.cookie = 0;
        p
    }
}

impl crate::guard::Outcome for hibi_mud_render_params {
    type C = hibi_mud_render_params;
    fn into_c(self) -> Self {
        self
    }
    /// A zero-sized raster, which rendering rejects.
    fn on_panic() -> Self {
        hibi_mud_render_params {
            width: 0,
            height: 0,
            width_scale: 0.0,
            min_width: 0.0,
            groove_depth: 0.0,
            offset: [0.0; 2],
        }
    }
}

/// A drying-mud run. Opaque.
pub struct hibi_mud {
    mud: Mud<'static, f32>,
    origin: Origin,
}

/// Alignment of a run's block.
const BLOCK_ALIGN: usize = if align_of::<hibi_mud>() > 8 { align_of::<hibi_mud>() } else { 8 };
/// Bytes of the header before the arrays.
const HEADER: usize = round_up(size_of::<hibi_mud>(), BLOCK_ALIGN);

fn enumeration<T>(value: u32, choices: [T; 2]) -> Result<T, hibi_status> {
    choices.into_iter().nth(value as usize).ok_or(HIBI_ERROR_MUD_ENUM)
}

/// The core parameters of a C params struct: cookie, enums, fields.
fn core_params(p: &hibi_mud_params) -> Result<MudParams, hibi_status> {
    if p.cookie != PARAMS_COOKIE {
        return Err(HIBI_ERROR_MUD_PARAMS_NOT_INITIALISED);
    }
    let params = MudParams {
        topology: enumeration(p.topology, [Topology::Square, Topology::Hexagonal])?,
        boundary: enumeration(p.boundary, [Boundary::Open, Boundary::Periodic])?,
        solver: enumeration(p.solver, [Solver::Explicit, Solver::QuasiStatic])?,
        drive: enumeration(p.drive, [Drive::Shrink, Drive::Growth])?,
        columns: p.columns,
        rows: p.rows,
        seed: p.seed,
        layer_thickness: p.layer_thickness,
        element_size: p.element_size,
        long_step: p.long_step,
        short_step: p.short_step,
        shrink_ratio: p.shrink_ratio,
        displacement_tolerance: p.displacement_tolerance,
        damping_factor: p.damping_factor,
        density: p.density,
        young_modulus: p.young_modulus,
        shear_modulus: p.shear_modulus,
        break_stretch_mean: p.break_stretch_mean,
        break_stretch_spread: p.break_stretch_spread,
        anisotropy_direction: p.anisotropy_direction,
        anisotropy_ratio: p.anisotropy_ratio,
        stiffness_anisotropy_ratio: p.stiffness_anisotropy_ratio,
        target_shrink: p.target_shrink,
        target_crack_density: p.target_crack_density,
    };
    Ok(params)
}

/// The validated core parameters and the block they need: (params, scalars, words, bytes).
///
/// # Safety
/// `params` must be NULL or point to a readable `hibi_mud_params`.
unsafe fn plan(params: *const hibi_mud_params) -> Result<(MudParams, usize, usize, usize), hibi_status> {
    check_pointer(params)?;
    // SAFETY: non-null and aligned (checked); readable by the caller's contract.
    let params = core_params(unsafe { &*params })?;
    let memory = params.memory().map_err(mud_param_status)?;
    let bytes = memory
        .scalars
        .checked_add(memory.words)
        .and_then(|n| n.checked_mul(4))
        .and_then(|n| n.checked_add(HEADER))
        .filter(|&n| n <= isize::MAX as usize)
        .ok_or(HIBI_ERROR_SIZE_OVERFLOW)?;
    Ok((params, memory.scalars, memory.words, bytes))
}

/// Builds a run in `block` (already checked: `bytes` long, aligned to `BLOCK_ALIGN`).
///
/// # Safety
/// `block` must be valid for writes of the planned size and outlive the run.
unsafe fn build(
    block: *mut u8,
    (params, scalars, words, bytes): (MudParams, usize, usize, usize),
    origin: Origin,
) -> Result<*mut hibi_mud, hibi_status> {
    // SAFETY: the block holds `bytes`; zeroing makes every array element a valid value.
    unsafe { block.add(HEADER).write_bytes(0, bytes - HEADER) };
    // SAFETY: the arrays lie inside the block, aligned (HEADER is a multiple of 8, elements are
    // 4 bytes), disjoint, initialised; they live as long as the block, which outlives the run.
    let (scalars, words) = unsafe {
        let s = block.add(HEADER).cast::<f32>();
        let w = block.add(HEADER + scalars * 4).cast::<u32>();
        (core::slice::from_raw_parts_mut(s, scalars), core::slice::from_raw_parts_mut(w, words))
    };
    let mud = Mud::new(&params, scalars, words).map_err(|e| match e {
        MudError::Param(p) => mud_param_status(p),
        MudError::BufferTooSmall { .. } => HIBI_ERROR_BUFFER_TOO_SMALL,
    })?;
    let ptr = block.cast::<hibi_mud>();
    // SAFETY: the header fits at the block's start, aligned.
    unsafe { ptr.write(hibi_mud { mud, origin }) };
    Ok(ptr)
}

/// The paper's parameters (and ours where it gives none), with the cookie set.
#[unsafe(no_mangle)]
pub extern "C" fn hibi_mud_params_default() -> hibi_mud_params {
    guard(hibi_mud_params_default_values)
}

/// The defaults, converted.
fn hibi_mud_params_default_values() -> hibi_mud_params {
    let p = MudParams::default();
    hibi_mud_params {
        cookie: PARAMS_COOKIE,
        topology: p.topology as u32,
        boundary: p.boundary as u32,
        solver: p.solver as u32,
        drive: p.drive as u32,
        columns: p.columns,
        rows: p.rows,
        seed: p.seed,
        layer_thickness: p.layer_thickness,
        element_size: p.element_size,
        long_step: p.long_step,
        short_step: p.short_step,
        shrink_ratio: p.shrink_ratio,
        displacement_tolerance: p.displacement_tolerance,
        damping_factor: p.damping_factor,
        density: p.density,
        young_modulus: p.young_modulus,
        shear_modulus: p.shear_modulus,
        break_stretch_mean: p.break_stretch_mean,
        break_stretch_spread: p.break_stretch_spread,
        anisotropy_direction: p.anisotropy_direction,
        anisotropy_ratio: p.anisotropy_ratio,
        stiffness_anisotropy_ratio: p.stiffness_anisotropy_ratio,
        target_shrink: p.target_shrink,
        target_crack_density: p.target_crack_density,
    }
}

/// Checks `params` and writes the bytes a run needs in caller memory (for
/// `hibi_mud_create_in`). Every parameter error is reported here.
///
/// # Safety
/// `params` must be NULL or readable; `size` NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_mud_memory_size(params: *const hibi_mud_params, size: *mut usize) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let (_, _, _, bytes) = unsafe { plan(params) }?;
        // SAFETY: the caller's contract.
        unsafe { write_out(size, bytes) }
    })
}

/// Alignment, in bytes, that caller memory for `hibi_mud_create_in` must have (8).
#[unsafe(no_mangle)]
pub extern "C" fn hibi_mud_memory_align() -> usize {
    guard(|| BLOCK_ALIGN)
}

/// Creates a run in library memory: draws every spring's break stretch, ready to step. Free
/// it with `hibi_mud_destroy`. `*out` is written only on success.
///
/// # Safety
/// `params` must be NULL or readable; `out` NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_mud_create(params: *const hibi_mud_params, out: *mut *mut hibi_mud) -> hibi_status {
    guard(|| {
        check_pointer(out)?;
        // SAFETY: the caller's contract.
        let plan = unsafe { plan(params) }?;
        let (block, origin) = library_block(plan.3, BLOCK_ALIGN)?;
        // SAFETY: a fresh block of the planned size and alignment.
        match unsafe { build(block, plan, origin) } {
            // SAFETY: checked above; the caller's contract.
            Ok(mud) => unsafe { write_out(out, mud) },
            Err(status) => {
                // SAFETY: allocated above, never handed out.
                unsafe { release_block(block, origin) };
                Err(status)
            }
        }
    })
}

/// Creates a run in caller memory of at least `hibi_mud_memory_size` bytes aligned to
/// `hibi_mud_memory_align()`. The memory stays the caller's (keep it untouched while the run
/// lives); `hibi_mud_destroy` is optional. Nothing is written on failure.
///
/// # Safety
/// `params` must be NULL or readable; `memory` NULL or writable for `memory_len` bytes;
/// `out` NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_mud_create_in(
    params: *const hibi_mud_params,
    memory: *mut c_void,
    memory_len: usize,
    out: *mut *mut hibi_mud,
) -> hibi_status {
    guard(|| {
        check_pointer(out)?;
        // SAFETY: the caller's contract.
        let plan = unsafe { plan(params) }?;
        let block = caller_block(memory, memory_len, plan.3, BLOCK_ALIGN)?;
        // SAFETY: checked to hold the planned size, aligned; the caller's contract.
        let mud = unsafe { build(block, plan, Origin::Caller) }?;
        // SAFETY: checked above; the caller's contract.
        unsafe { write_out(out, mud) }
    })
}

/// Destroys a run; frees its memory if `hibi_mud_create` allocated it. NULL is ignored.
///
/// # Safety
/// `mud` must be NULL or a live run, not used afterwards.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_mud_destroy(mud: *mut hibi_mud) {
    guard(|| {
        // SAFETY: the caller's contract.
        if let Ok(live) = unsafe { object(mud) } {
            let origin = live.origin;
            // SAFETY: a live run made by hibi_mud_create or hibi_mud_create_in.
            unsafe {
                mud.drop_in_place();
                release_block(mud.cast(), origin);
            }
        }
    })
}

/// Advances the run by at most `budget` units of work (one unit: one spring visited), but
/// always by at least one indivisible piece; writes where it stands to `*progress` unless it
/// is NULL. Call until `progress.finished`.
///
/// # Safety
/// `mud` must be NULL or a live run; `progress` NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_mud_step(
    mud: *mut hibi_mud,
    budget: u64,
    progress: *mut hibi_mud_progress,
) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let mud = unsafe { object(mud) }?;
        if !progress.is_null() {
            check_pointer(progress)?;
        }
        let p = mud.mud.step(budget);
        if !progress.is_null() {
            let value = hibi_mud_progress {
                shrink: p.shrink,
                time: p.time,
                broken_springs: p.broken_springs,
                crack_density: p.crack_density,
                work: p.work,
                finished: u32::from(p.finished),
            };
            // SAFETY: checked; the caller's contract.
            unsafe { write_out(progress, value) }?;
        }
        Ok(())
    })
}

/// Writes the number of crack segments `hibi_mud_segments` would write now.
///
/// # Safety
/// `mud` must be NULL or a live run; `count` NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_mud_segment_count(mud: *const hibi_mud, count: *mut usize) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let mud = unsafe { object(mud.cast_mut()) }?;
        // SAFETY: the caller's contract.
        unsafe { write_out(count, mud.mud.segment_count()) }
    })
}

/// Writes the crack segments (paper Fig. 5) into `segments[0..len]` and their number into
/// `*written`. If `len` is smaller than `hibi_mud_segment_count`, nothing is written and the
/// status is `HIBI_ERROR_BUFFER_TOO_SMALL`.
///
/// # Safety
/// `mud` must be NULL or a live run; `segments` NULL (only with `len` 0) or writable for
/// `len` segments; `written` NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_mud_segments(
    mud: *const hibi_mud,
    segments: *mut hibi_mud_segment,
    len: usize,
    written: *mut usize,
) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let mud = unsafe { object(mud.cast_mut()) }?;
        check_pointer(written)?;
        // SAFETY: the caller's contract.
        let out = unsafe { buffer(segments, len) }?;
        let needed = mud.mud.segment_count();
        if out.len() < needed {
            return Err(HIBI_ERROR_BUFFER_TOO_SMALL);
        }
        let mut n = 0;
        mud.mud.for_each_segment(|s: CrackSegment| {
            out[n] = hibi_mud_segment { start: s.start, end: s.end, width: s.width, time: s.time };
            n += 1;
        });
        // SAFETY: checked; the caller's contract.
        unsafe { write_out(written, n) }
    })
}

/// Crack density and the cells of the traced crack network (the statistics the tests compare
/// solvers and meshes by), measured on the network itself, not on a drawing.
///
/// # Safety
/// `mud` must be NULL or a live run; `out` NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_mud_measure(mud: *const hibi_mud, out: *mut hibi_mud_statistics) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let mud = unsafe { object(mud.cast_mut()) }?;
        check_pointer(out)?;
        let s = mud.mud.statistics();
        let value =
            hibi_mud_statistics { crack_density: s.crack_density, cells: s.cells, mean_cell_area: s.mean_cell_area };
        // SAFETY: checked; the caller's contract.
        unsafe { write_out(out, value) }
    })
}

/// Default drawing: 512 × 512, true crack widths, 1-pixel minimum stroke, groove depth 1.
#[unsafe(no_mangle)]
pub extern "C" fn hibi_mud_render_params_default() -> hibi_mud_render_params {
    guard(|| {
        let r = MudRender::default();
        hibi_mud_render_params {
            width: r.width,
            height: r.height,
            width_scale: r.width_scale,
            min_width: r.min_width,
            groove_depth: r.groove_depth,
            offset: r.offset,
        }
    })
}

/// Draws `layer` into `pixels` (row-major, `width × height` values; `uint8_t` for
/// `HIBI_MUD_LAYER_MASK`, `float` for `HIBI_MUD_LAYER_HEIGHT` and `HIBI_MUD_LAYER_TIME`).
/// `pixels_len` counts values, not bytes. Nothing is written on failure.
///
/// # Safety
/// `mud` must be NULL or a live run; `render` NULL or readable; `pixels` NULL (only with
/// `pixels_len` 0) or writable for `pixels_len` values of the layer's type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_mud_render(
    mud: *const hibi_mud,
    render: *const hibi_mud_render_params,
    layer: u32,
    pixels: *mut c_void,
    pixels_len: usize,
) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let mud = unsafe { object(mud.cast_mut()) }?;
        check_pointer(render)?;
        // SAFETY: non-null, aligned (checked); readable by the caller's contract.
        let r = unsafe { *render };
        let render = MudRender {
            width: r.width,
            height: r.height,
            width_scale: r.width_scale,
            min_width: r.min_width,
            groove_depth: r.groove_depth,
            offset: r.offset,
        };
        let drawn: Result<(), RasterError> = match layer {
            // SAFETY (all three): the caller's contract on `pixels`.
            HIBI_MUD_LAYER_MASK => mud.mud.render_mask(&render, unsafe { buffer(pixels.cast::<u8>(), pixels_len) }?),
            HIBI_MUD_LAYER_HEIGHT => {
                mud.mud.render_height(&render, unsafe { buffer(pixels.cast::<f32>(), pixels_len) }?)
            }
            HIBI_MUD_LAYER_TIME => mud.mud.render_time(&render, unsafe { buffer(pixels.cast::<f32>(), pixels_len) }?),
            _ => return Err(HIBI_ERROR_RENDER_LAYER),
        };
        drawn.map_err(raster_status)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::status::*;
    use core::ptr::{null, null_mut};

    fn small() -> hibi_mud_params {
        let mut p = hibi_mud_params_default();
        p.columns = 16;
        p.rows = 16;
        p
    }

    #[test]
    fn every_bad_field_and_enum_is_a_specific_status_and_nothing_is_created() {
        type Spoil = fn(&mut hibi_mud_params);
        let cases: [(Spoil, hibi_status); 8] = [
            (|p| p.cookie = 0, HIBI_ERROR_MUD_PARAMS_NOT_INITIALISED),
            (|p| p.topology = 2, HIBI_ERROR_MUD_ENUM),
            (|p| p.solver = 7, HIBI_ERROR_MUD_ENUM),
            (|p| p.young_modulus = f32::NAN, HIBI_ERROR_MUD_YOUNG_MODULUS),
            (|p| p.break_stretch_mean = 0.9, HIBI_ERROR_MUD_BREAK_STRETCH_MEAN),
            (|p| p.shrink_ratio = 1.5, HIBI_ERROR_MUD_SHRINK_RATIO),
            (|p| p.rows = 15, HIBI_ERROR_MUD_ROWS),
            (|p| (p.columns, p.rows) = (u32::MAX, u32::MAX - 1), HIBI_ERROR_MUD_SIZE_OVERFLOW),
        ];
        for (spoil, expected) in cases {
            let mut p = small();
            spoil(&mut p);
            let mut out = null_mut();
            let mut size = 12345usize;
            // SAFETY: valid pointers; failing calls write nothing.
            unsafe {
                assert_eq!(hibi_mud_create(&p, &mut out), expected);
                assert_eq!(hibi_mud_memory_size(&p, &mut size), expected);
            }
            assert!(out.is_null());
            assert_eq!(size, 12345);
        }
    }

    #[test]
    fn caller_memory_is_checked_and_left_untouched_on_failure() {
        let p = small();
        let mut size = 0;
        // SAFETY: valid pointers.
        assert_eq!(unsafe { hibi_mud_memory_size(&p, &mut size) }, HIBI_OK);
        let mut memory = vec![0xA5A5_A5A5_A5A5_A5A5u64; size / 8 + 2];
        let base = memory.as_mut_ptr().cast::<c_void>();
        let mut out = null_mut();
        // SAFETY: `memory` is valid for its length; failing calls write nothing.
        unsafe {
            assert_eq!(hibi_mud_create_in(&p, base, size - 1, &mut out), HIBI_ERROR_BUFFER_TOO_SMALL);
            assert!(memory.iter().all(|&w| w == 0xA5A5_A5A5_A5A5_A5A5), "short");
            let odd = base.cast::<u8>().add(4).cast::<c_void>();
            assert_eq!(hibi_mud_create_in(&p, odd, size, &mut out), HIBI_ERROR_MISALIGNED);
            assert!(memory.iter().all(|&w| w == 0xA5A5_A5A5_A5A5_A5A5), "misaligned");
            let mut bad = p;
            bad.density = 0.0;
            assert_eq!(hibi_mud_create_in(&bad, base, size, &mut out), HIBI_ERROR_MUD_DENSITY);
            assert!(memory.iter().all(|&w| w == 0xA5A5_A5A5_A5A5_A5A5));
            assert_eq!(hibi_mud_create_in(&p, base, size, &mut out), HIBI_OK);
            assert_eq!(out.cast::<c_void>(), base);
            let mut progress = hibi_mud_progress::default();
            while progress.finished == 0 {
                assert_eq!(hibi_mud_step(out, 10_000, &mut progress), HIBI_OK);
            }
            hibi_mud_destroy(out);
        }
    }

    #[test]
    fn outputs_check_their_buffers() {
        let p = small();
        let mut mud = null_mut();
        // SAFETY: valid pointers throughout; failing calls write nothing.
        unsafe {
            assert_eq!(hibi_mud_create(&p, &mut mud), HIBI_OK);
            assert_eq!(hibi_mud_step(mud, u64::MAX, null_mut()), HIBI_OK);
            let mut count = 0;
            assert_eq!(hibi_mud_segment_count(mud, &mut count), HIBI_OK);
            assert!(count > 0);
            let mut segments = vec![hibi_mud_segment::default(); count];
            let mut written = 777;
            assert_eq!(
                hibi_mud_segments(mud, segments.as_mut_ptr(), count - 1, &mut written),
                HIBI_ERROR_BUFFER_TOO_SMALL
            );
            assert_eq!(written, 777);
            assert!(segments.iter().all(|s| *s == hibi_mud_segment::default()));
            assert_eq!(hibi_mud_segments(mud, segments.as_mut_ptr(), count, &mut written), HIBI_OK);
            assert_eq!(written, count);

            let mut render = hibi_mud_render_params_default();
            render.width = 32;
            render.height = 32;
            let mut heights = vec![7.0f32; 32 * 32];
            let h = heights.as_mut_ptr().cast::<c_void>();
            assert_eq!(hibi_mud_render(mud, &render, 3, h, 1024), HIBI_ERROR_RENDER_LAYER);
            assert_eq!(hibi_mud_render(mud, &render, HIBI_MUD_LAYER_HEIGHT, h, 1023), HIBI_ERROR_BUFFER_TOO_SMALL);
            render.min_width = f32::NAN;
            assert_eq!(hibi_mud_render(mud, &render, HIBI_MUD_LAYER_HEIGHT, h, 1024), HIBI_ERROR_RENDER_MIN_WIDTH);
            render.min_width = 1.0;
            render.width = 0;
            assert_eq!(hibi_mud_render(mud, &render, HIBI_MUD_LAYER_HEIGHT, h, 1024), HIBI_ERROR_RENDER_SIZE);
            assert!(heights.iter().all(|&v| v == 7.0));
            render.width = 32;
            let odd = heights.as_mut_ptr().cast::<u8>().add(1).cast::<c_void>();
            assert_eq!(hibi_mud_render(mud, &render, HIBI_MUD_LAYER_TIME, odd, 1000), HIBI_ERROR_MISALIGNED);
            assert_eq!(hibi_mud_render(mud, &render, HIBI_MUD_LAYER_HEIGHT, h, 1024), HIBI_OK);
            assert!(heights.iter().any(|&v| v < 1.0) && heights.iter().all(|&v| (0.0..=1.0).contains(&v)));
            assert_eq!(hibi_mud_render(null(), &render, HIBI_MUD_LAYER_MASK, h, 4096), HIBI_ERROR_NULL_POINTER);
            let mut stats = hibi_mud_statistics::default();
            assert_eq!(hibi_mud_measure(mud, &mut stats), HIBI_OK);
            assert!(stats.crack_density > 0.0);
            hibi_mud_destroy(mud);
        }
    }
}
