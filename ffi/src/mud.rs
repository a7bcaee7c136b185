//! `hibi_mud`: model A, the drying-mud spring lattice (Hirota et al.), from C.
//!
//! ```c
//! hibi_mud_params params = hibi_mud_params_default();
//! hibi_mud *mud = NULL;
//! if (hibi_mud_create(&params, &mud) != HIBI_OK) { ... }
//! hibi_mud_progress progress;
//! hibi_status status;
//! do { status = hibi_mud_step(mud, 100000, &progress); } while (status == HIBI_OK && !progress.finished);
//! hibi_mud_render_params render = hibi_mud_render_params_default();
//! hibi_mud_render(mud, &render, HIBI_MUD_LAYER_MASK, pixels, render.width * render.height);
//! hibi_mud_destroy(mud);
//! ```
//!
//! The same sequence drives glass and skin but for the names (a skin renders at its params'
//! size). The cells come by count, then write: `hibi_mud_cell_counts`, then `hibi_mud_cells`
//! into buffers of those sizes.
//!
//! An object is one block: the header, then the model's scalar and word arrays. With
//! `hibi_mud_memory_size` and `hibi_mud_create_in` the block is the caller's.

use core::ffi::{c_char, c_void};

use hibi_core::mud::{
    CrackSegment, CrackStatistics, Mud, MudBuffers, MudError, MudLayers, MudMemory, MudParams, MudProgress, MudRender,
    NO_VERTEX, NetworkEdge, NetworkPoint, NetworkVertex, preset,
};

use crate::constants::param_status;
use crate::fields::{Field, convert};

use crate::glass::hibi_vec2;
use crate::guard::{Outs, buffer, check_pointer, guard, object_ref, query, update, write_out};
use crate::object::{Arena, Object, Origin, lifecycle};
use crate::polygons::polygon_query;
use crate::raster::{Pixels, render};
use crate::status::{HIBI_ERROR_BUFFER_TOO_SMALL, HIBI_ERROR_RENDER_LAYER, first_short, hibi_status, short_buffer};

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
    /// Nodes per row (default 128; `columns` × `rows` <= 2^28, and irregular `columns` <= 2^20).
    pub columns: u32,
    /// Rows of nodes (default 128; even for periodic hexagonal lattices; irregular <= 2^21).
    pub rows: u32,
    /// Seed of every random draw.
    pub seed: u64,
    /// H, surface layer thickness [cm] (default 1).
    pub layer_thickness: f32,
    /// W, element size [cm] (default 1).
    pub element_size: f32,
    /// T, long time step [s] (default 1).
    pub long_step: f32,
    /// τ, short time step [s] (paper: 0.001). The explicit solver refuses one that fails the
    /// stability test of its damped step (`HIBI_ERROR_MUD_SHORT_STEP_STABILITY`; about ten
    /// times the paper's at the defaults).
    pub short_step: f32,
    /// γ, shrink ratio per long step, within [FLT_MIN, 1) (paper: 0.9999); 1 would never shrink
    /// and is rejected (`HIBI_ERROR_MUD_SHRINK_RATIO`); with `HIBI_MUD_GROWTH` the deep layer
    /// grows by 1/γ per long step, at most 101-fold (γ >= 1/101).
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
    /// Beyond the paper: κ̄ − 1 is scaled by (1 cm / element_size)^x, for mesh-scale
    /// independence; 0 (default) is the paper's rule, 0.25 keeps crack density and cell size
    /// within 15 % from W = 2 to 1 to 0.5 cm. Within [0, 1].
    pub break_stretch_size_exponent: f32,
    /// Direction cracks prefer [radians] (default 0).
    pub anisotropy_direction: f32,
    /// How much weaker springs across that direction are (1 = isotropic, default).
    pub anisotropy_ratio: f32,
    /// Stiffness anisotropy ratio (1 = none, default).
    pub stiffness_anisotropy_ratio: f32,
    /// End at this shrink (default 0.023; 0 = at the largest the model follows, shrink 0.99
    /// or growth 100). Both solvers end there too, uncracked, when no spring can break before
    /// it (a very large `break_stretch_mean`, say).
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
    /// Always 0: the struct has no padding, so every byte a call writes is defined (an
    /// output can be hashed or compared as bytes).
    pub reserved: u32,
}

/// Crack statistics of the traced network: density, the cells it encloses, and its vertices.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct hibi_mud_crack_statistics {
    /// Crack length per area [1/cm]: the network's length (branches included) over the
    /// plate's area.
    pub crack_density: f32,
    /// Cells the network's separating cracks enclose (outer rings), wrapping ones included.
    pub cells: u32,
    /// Mean cell area [cm²]: the plate's area over `cells`.
    pub mean_cell_area: f32,
    /// Standard deviation of the cells' areas [cm²] over their outer rings; holes (islands,
    /// rare) are taken off all cells evenly, and cells that wrap around a periodic lattice
    /// are left out.
    pub cell_area_spread: f32,
    /// Network vertices where three or more cracks meet.
    pub junctions: u32,
    /// Cracks that end inside a cell (vertices of degree 1 off the border).
    pub dead_ends: u32,
    /// T junctions: one crack runs on and another meets it (the widest angle between
    /// neighbouring cracks' courses, taken 3 spacings out, is at least 150°); the rest are Y.
    pub t_junctions: u32,
    /// Mean over junctions of the widest angle between neighbouring cracks' courses
    /// [degrees]: 180 for a perfect T, 120 for a symmetric Y.
    pub mean_widest_junction_angle: f32,
}

/// `hibi_mud_network_edge.from` and `.to` of a closed crack, which has no vertex on it.
pub const HIBI_MUD_NO_VERTEX: u32 = u32::MAX;

const _: () = assert!(HIBI_MUD_NO_VERTEX == NO_VERTEX);

/// `hibi_ring.hole_of` of a hole in a mud cell that wraps around a periodic lattice:
/// that cell has no outline in the plane (it is counted in `hibi_mud_cell_counts`'s
/// `wrapping`, or it is the whole plate less its islands), so there is no ring to name.
pub const HIBI_MUD_IN_WRAPPING_CELL: u32 = 0xFFFF_FFFE;

const _: () = assert!(HIBI_MUD_IN_WRAPPING_CELL == hibi_core::mud::IN_WRAPPING_CELL);

/// The most work one piece of a mud run's network tracing does, in `hibi_mud_step`'s units:
/// a call that traces does at most max(budget, 1) − 1 + this.
pub const HIBI_MUD_TRACE_PIECE: u64 = 64;

const _: () = assert!(HIBI_MUD_TRACE_PIECE == hibi_core::mud::TRACE_PIECE);

/// A live trace of a mud run's network gets one unit of work for every this many units of
/// the physics (see `hibi_mud_step`): the live traces add at most 1/this to a run's work.
pub const HIBI_MUD_LIVE_SHARE: u64 = 8;

const _: () = assert!(HIBI_MUD_LIVE_SHARE == hibi_core::mud::LIVE_SHARE);

/// The most work one piece of a mud run's setup does, in `hibi_mud_step`'s units (a block of
/// the quasi-static solver's tree): a call that sets up does at most max(budget, 1) − 1 + this.
pub const HIBI_MUD_SETUP_PIECE: u64 = 32;

const _: () = assert!(HIBI_MUD_SETUP_PIECE == hibi_core::mud::SETUP_PIECE);

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
    /// Depth of the widest groove in pixels, for the normals and the preview (default 2).
    pub bump: f32,
    /// Draw the cracks as far as they had broken at this time, long steps (default
    /// +infinity: all of them).
    pub until: f32,
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
            bump: 0.0,
            until: 0.0,
        }
    }
}

/// A drying-mud run. Opaque.
pub struct hibi_mud {
    pub(crate) mud: Mud<'static, f32>,
    origin: Origin,
}

convert!(hibi_mud_params <=> MudParams, cookie: PARAMS_COOKIE {
    topology, boundary, solver, drive, columns, rows, seed, layer_thickness, element_size, long_step, short_step,
    shrink_ratio, displacement_tolerance, damping_factor, density, young_modulus, shear_modulus, break_stretch_mean,
    break_stretch_spread, break_stretch_size_exponent, anisotropy_direction, anisotropy_ratio,
    stiffness_anisotropy_ratio, target_shrink, target_crack_density,
});
convert!(hibi_mud_progress <=> MudProgress, reserved: reserved { shrink, time, broken_springs, crack_density, work, finished });
convert!(hibi_mud_crack_statistics <=> CrackStatistics {
    crack_density, cells, mean_cell_area, cell_area_spread, junctions, dead_ends, t_junctions,
    mean_widest_junction_angle,
});
convert!(hibi_mud_render_params <=> MudRender { width, height, width_scale, min_width, groove_depth, offset, bump, until });

lifecycle!(
    hibi_mud (mud: "run", "ready to step, in time independent of the lattice's size (the first steps set it up: see `hibi_mud_step`)"),
    hibi_mud_params <=> MudParams, cookie PARAMS_COOKIE,
    errors (HIBI_ERROR_MUD_PARAMS_NOT_INITIALISED, HIBI_ERROR_MUD_ENUM, HIBI_ERROR_MUD_UNKNOWN_PRESET),
    presets "`\"fig6a\"` … `\"fig10\"`" in hibi_core::mud::PRESETS,
    hibi_mud_params_default, hibi_mud_params_preset, hibi_mud_preset_name, hibi_mud_memory_size, hibi_mud_memory_align,
    hibi_mud_create, hibi_mud_create_in, hibi_mud_destroy,
    only create: "One refusal comes later: an irregular lattice's explicit run is tested for \
        `HIBI_ERROR_MUD_SHORT_STEP_STABILITY` on its mesh, which the first `hibi_mud_step` calls \
        build, so `hibi_mud_step` returns it and creation accepts such parameters.",
);

impl Object for hibi_mud {
    type Input = *const hibi_mud_params;
    type Plan = (MudParams, MudMemory);
    type Arrays = MudBuffers<'static, f32>;
    const TOO_LARGE: hibi_status = crate::constants::HIBI_ERROR_MUD_SIZE_OVERFLOW;

    unsafe fn plan(params: *const hibi_mud_params) -> Result<Self::Plan, hibi_status> {
        // SAFETY: the caller's contract.
        let params = from_c(unsafe { object_ref(params, c"params") }?)?;
        let memory = params.memory().map_err(param_status)?;
        Ok((params, memory))
    }

    fn arrays((_, memory): &Self::Plan, arena: &mut Arena) -> Self::Arrays {
        MudBuffers { scalars: arena.take_as_is(memory.scalars), words: arena.take_as_is(memory.words) }
    }

    fn make((params, _): &Self::Plan, buffers: Self::Arrays, origin: Origin) -> Result<Self, hibi_status> {
        Ok(hibi_mud { mud: Mud::new(params, buffers).map_err(output_status)?, origin })
    }

    fn origin(&self) -> Origin {
        self.origin
    }
}

/// Advances the run by about `budget` units of work (one unit: one spring or node visited):
/// it does pieces until their work reaches the budget, so a call on an unfinished run does at
/// least one piece and does at most max(budget, 1) − 1 + one piece. The first calls set the
/// run up, item by item (a spring, a node or a mesh cell: 1 unit; an irregular node's jitter
/// into its mesh or its constants: 16; a block of the quasi-static solver's tree: 32, at most
/// `HIBI_MUD_SETUP_PIECE`); until then the run is an uncracked plate at shrink 0 and every
/// output describes that. An irregular lattice's explicit run is tested for stability node by
/// node there: a node that fails gives `HIBI_ERROR_MUD_SHORT_STEP_STABILITY` (the status
/// names the field; nothing is written to `*progress`), and so does every later call. The
/// explicit solver's short steps are resumed where the last call stopped; its piece is one
/// row of the lattice in one direction and its rescan for breaks, at most 2·columns (the irregular lattice goes
/// spring by spring and node by node: no overrun). The quasi-static solver's piece is one
/// node's springs (4 square, 6 hexagonal, at most 16 irregular). The crack network is traced
/// live within the same budgets, in pieces of at most `HIBI_MUD_TRACE_PIECE` units (its walks
/// along cracks and cell boundaries resume where they stopped): once springs have broken, a
/// trace of those broken so far begins; it gets one unit for every `HIBI_MUD_LIVE_SHARE`
/// units of the physics, and writes a second copy of the network, which is shown once it is
/// done. So the network, the cells, the statistics and the rasters always show one whole
/// trace, of `hibi_mud_shown_broken_springs` springs, drawn at the displacements of now. When
/// the physics ends, the cracks as they end are traced in the same way, and the run is
/// finished when that trace is done. The run (its physics, its final network, its work) does
/// not depend on the budgets; which live network a call shows does. A budget of `UINT64_MAX`
/// runs to the end in the one call, where no live network could be seen: it makes none, and
/// ends with the same outputs, bit for bit, in less work (the physics and the final trace). Writes where it stands
/// to `*progress` unless it is NULL. Call until `progress.finished`.
///
/// # Safety
/// `mud` must be NULL or a live run; `progress` optional: NULL (not written) or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_mud_step(
    mud: *mut hibi_mud,
    budget: u64,
    progress: *mut hibi_mud_progress,
) -> hibi_status {
    let step =
        |mud: &mut hibi_mud| mud.mud.step(budget).map(|p| hibi_mud_progress::from_core(&p)).map_err(output_status);
    // SAFETY: the caller's contract.
    guard(|| unsafe { update(mud, c"mud", (progress, c"progress"), step) })
}

/// Writes how many springs had broken when the network shown (by the network, the cells, the
/// statistics and the rasters) was traced: 0 before the first trace; it never falls, and once
/// the run is finished it is `progress.broken_springs`.
///
/// # Safety
/// `mud` must be NULL or a live run; `count` NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_mud_shown_broken_springs(mud: *const hibi_mud, count: *mut u32) -> hibi_status {
    let read = |mud: &hibi_mud| Ok(mud.mud.shown_broken_springs());
    // SAFETY: the caller's contract.
    guard(|| unsafe { query(mud, c"mud", (count, c"count"), read) })
}

/// Writes the number of crack segments `hibi_mud_segments` would write now.
///
/// # Safety
/// `mud` must be NULL or a live run; `count` NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_mud_segment_count(mud: *const hibi_mud, count: *mut usize) -> hibi_status {
    let read = |mud: &hibi_mud| Ok(mud.mud.segment_count());
    // SAFETY: the caller's contract.
    guard(|| unsafe { query(mud, c"mud", (count, c"count"), read) })
}

/// Writes the crack segments (paper Fig. 5) into `segments[0..len]` and their number into
/// `*written`. If `len` is smaller than `hibi_mud_segment_count`, nothing is written and the
/// status is `HIBI_ERROR_BUFFER_TOO_SMALL`.
///
/// # Safety
/// `mud` must be NULL or a live run; `segments` NULL (only with `len` 0) or writable for
/// `len` segments; `written` NULL (refused) or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_mud_segments(
    mud: *const hibi_mud,
    segments: *mut CrackSegment,
    len: usize,
    written: *mut usize,
) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let mud = unsafe { object_ref(mud, c"mud") }?;
        check_pointer(written, c"written")?;
        // SAFETY: the caller's contract.
        let out = unsafe { buffer(segments, len, c"segments") }?;
        let n = mud.mud.segments(out).map_err(|e| short_buffer(output_status(e), c"segments"))?;
        // SAFETY: checked; the caller's contract.
        unsafe { write_out(written, c"written", n) }
    })
}

/// Crack density, the cells of the traced crack network (count, mean and spread of area) and
/// its junctions and dead ends (the statistics the tests compare solvers and meshes by),
/// measured on the network itself, not on a drawing.
///
/// # Safety
/// `mud` must be NULL or a live run; `out` NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_mud_statistics(mud: *const hibi_mud, out: *mut hibi_mud_crack_statistics) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let mud = unsafe { object_ref(mud, c"mud") }?;
        check_pointer(out, c"out")?;
        let value = hibi_mud_crack_statistics::from_core(&mud.mud.statistics());
        // SAFETY: checked; the caller's contract.
        unsafe { write_out(out, c"out", value) }
    })
}

/// The status of a core error: a parameter's (from creating, or the stability test of an
/// irregular explicit run's first steps), or a short buffer (from writing an output).
fn output_status(error: MudError) -> hibi_status {
    match error {
        MudError::Param(p) => param_status(p),
        MudError::BufferTooSmall { .. } => HIBI_ERROR_BUFFER_TOO_SMALL,
    }
}

/// Writes how many vertices, edges and points `hibi_mud_network` will write for the network
/// as last traced (live while the run goes on, of its last cracks once it is finished).
///
/// # Safety
/// `mud` must be NULL or a live run; `vertices`, `edges` and `points` NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_mud_network_counts(
    mud: *const hibi_mud,
    vertices: *mut usize,
    edges: *mut usize,
    points: *mut usize,
) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let mud = unsafe { object_ref(mud, c"mud") }?;
        let outs = Outs::check([(vertices, c"vertices"), (edges, c"edges"), (points, c"points")])?;
        let counts = mud.mud.network_counts();
        // SAFETY: checked; the caller's contract.
        unsafe { outs.write([counts.vertices, counts.edges, counts.points]) }
    })
}

/// Writes the traced crack network, one line per physical crack, as a plane graph: its
/// vertices (junctions and ends) into `vertices[0..vertices_len]`, its edges (the cracks
/// between them) into `edges[0..edges_len]`, the edges' polyline points into
/// `points[0..points_len]`, and the counts into `*vertices_written`, `*edges_written` and
/// `*points_written`. If a buffer is too small (see `hibi_mud_network_counts`), nothing is
/// written and the status is `HIBI_ERROR_BUFFER_TOO_SMALL`.
///
/// # Safety
/// `mud` must be NULL or a live run; `vertices`, `edges` and `points` NULL (only with length
/// 0) or writable for their lengths, not overlapping; the `*_written` pointers NULL
/// (refused) or writable.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn hibi_mud_network(
    mud: *const hibi_mud,
    vertices: *mut NetworkVertex,
    vertices_len: usize,
    edges: *mut NetworkEdge,
    edges_len: usize,
    points: *mut NetworkPoint,
    points_len: usize,
    vertices_written: *mut usize,
    edges_written: *mut usize,
    points_written: *mut usize,
) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let mud = unsafe { object_ref(mud, c"mud") }?;
        let outs = Outs::check([
            (vertices_written, c"vertices_written"),
            (edges_written, c"edges_written"),
            (points_written, c"points_written"),
        ])?;
        // SAFETY: the caller's contract; the C structs are laid out as the core's (asserted
        // above).
        let vertex_out = unsafe { buffer(vertices, vertices_len, c"vertices") }?;
        // SAFETY: as above.
        let edge_out = unsafe { buffer(edges, edges_len, c"edges") }?;
        // SAFETY: as above.
        let point_out = unsafe { buffer(points, points_len, c"points") }?;
        let lengths = [vertex_out.len(), edge_out.len(), point_out.len()];
        let counts = mud.mud.network(vertex_out, edge_out, point_out).map_err(|e| match e {
            MudError::BufferTooSmall { .. } => {
                let c = mud.mud.network_counts();
                first_short(&[
                    (c"vertices", lengths[0], c.vertices),
                    (c"edges", lengths[1], c.edges),
                    (c"points", lengths[2], c.points),
                ])
            }
            e => output_status(e),
        })?;
        // SAFETY: checked; the caller's contract.
        unsafe { outs.write([counts.vertices, counts.edges, counts.points]) }
    })
}

/// Writes how many rings and ring points `hibi_mud_cells` will write for the network as last
/// traced, and into `*wrapping` the number of cell boundaries that wrap around a periodic
/// lattice (which have no outline in the plane and are not written).
///
/// # Safety
/// `mud` must be NULL or a live run; `rings`, `points` and `wrapping` NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_mud_cell_counts(
    mud: *const hibi_mud,
    rings: *mut usize,
    points: *mut usize,
    wrapping: *mut usize,
) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let mud = unsafe { object_ref(mud, c"mud") }?;
        let outs = Outs::check([(rings, c"rings"), (points, c"points"), (wrapping, c"wrapping")])?;
        let counts = mud.mud.cell_counts();
        // SAFETY: checked; the caller's contract.
        unsafe { outs.write([counts.rings, counts.points, counts.wrapping]) }
    })
}

polygon_query! {
    /// Writes the cells the separating cracks cut the plate into, as polygons: one `hibi_ring`
    /// per ring into `rings[0..rings_len]`, their points into `points[0..points_len]` (lattice
    /// units, × element_size for cm, not pixels; a hole in a cell that wraps around a periodic
    /// lattice has `hole_of` `HIBI_MUD_IN_WRAPPING_CELL`), and the counts into `*rings_written` and `*points_written`. Cracks that end inside a cell
    /// do not cut it; on an open lattice the plate's border bounds the cells along it; the rings'
    /// signed areas add up to the plate's (less the regions that wrap, see
    /// `hibi_mud_cell_counts`). If a buffer is too small, nothing is written and the status is
    /// `HIBI_ERROR_BUFFER_TOO_SMALL`.
    ///
    /// # Safety
    /// `mud` must be NULL or a live run;
    hibi_mud_cells(mud: hibi_mud);
    {
        // SAFETY: the caller's contract.
        let mud = unsafe { object_ref(mud, c"mud") }?;
    }
    |rings, points| {
        let lengths = (rings.len(), points.len());
        mud.mud.cells(rings, points).map(|c| (c.rings, c.points)).map_err(|e| match e {
            MudError::BufferTooSmall { .. } => {
                let c = mud.mud.cell_counts();
                first_short(&[(c"rings", lengths.0, c.rings), (c"points", lengths.1, c.points)])
            }
            e => output_status(e),
        })
    }
}

/// Render layer: crack coverage, `uint8_t` per pixel, 0 (none) to 255.
pub const HIBI_MUD_LAYER_MASK: u32 = 0;
/// Render layer: height, `float` per pixel, 1 on the surface, lower in the cracks.
pub const HIBI_MUD_LAYER_HEIGHT: u32 = 1;
/// Render layer: break time in long steps, `float` per pixel, +infinity where no crack is.
pub const HIBI_MUD_LAYER_TIME: u32 = 2;

/// Default drawing: 512 × 512, true crack widths, 1-pixel minimum stroke, groove depth 1.
#[unsafe(no_mangle)]
pub extern "C" fn hibi_mud_render_params_default() -> hibi_mud_render_params {
    guard(|| hibi_mud_render_params::from_core(&MudRender::default()))
}

/// Writes into `*out` the default drawing `width` pixels wide at the aspect of the run's
/// domain (`hibi_mud_extent`): its height rounded from the aspect (at least 1), so that
/// nothing is stretched, and its narrowest stroke a fifth of a lattice spacing (at least 1
/// pixel); the rest as `hibi_mud_render_params_default`. A `width` of 0 is
/// `HIBI_ERROR_RENDER_SIZE`, nothing written.
///
/// # Safety
/// `mud` must be NULL or a live run; `out` NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_mud_render_params_fit(
    mud: *const hibi_mud,
    width: u32,
    out: *mut hibi_mud_render_params,
) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        unsafe {
            query(mud, c"mud", (out, c"out"), |mud| {
                if width == 0 {
                    return Err(crate::status::HIBI_ERROR_RENDER_SIZE);
                }
                Ok(hibi_mud_render_params::from_core(&MudRender::fit(mud.mud.extent(), width)))
            })
        }
    })
}

/// Writes the size of the run's domain (one period when periodic) into `*extent`: `x` its
/// width, `y` its height, in lattice units (times `element_size` for cm): columns × rows on
/// the square lattice, columns × rows·√3/2 on the hexagonal one, columns × rows·887/1024 on
/// the irregular one. Every point the run writes (segments, network, cells) lies in it, x
/// along a row and y across the rows, in the raster's own directions: a render stretches the
/// domain over its `width` × `height` pixels, x to the right and y down the rows, row 0 at
/// y = 0 (`hibi_mud_render_params_fit` keeps the aspect).
///
/// # Safety
/// `mud` must be NULL or a live run; `extent` NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_mud_extent(mud: *const hibi_mud, extent: *mut hibi_vec2) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        unsafe {
            query(mud, c"mud", (extent, c"extent"), |mud| {
                let [x, y] = mud.mud.extent();
                Ok(hibi_vec2 { x, y })
            })
        }
    })
}

render! {
    /// Draws `layer` into `pixels` (row-major, `width × height` values; `uint8_t` for
    /// `HIBI_MUD_LAYER_MASK`, `float` for `HIBI_MUD_LAYER_HEIGHT` and `HIBI_MUD_LAYER_TIME`).
    /// `pixels_len` counts values, not bytes. Nothing is written on failure.
    hibi_mud_render(mud: hibi_mud, "run", hibi_mud_render_params) = mud_layers, crate::status::raster_status
}

crate::raster::render_layers! {
    /// Draws every layer `layers` gives (mask, height, height16, normal, normal_rgb8, time,
    /// preview; see `hibi_layers`) of `tile` (NULL: the whole `width × height` image) in one
    /// pass, each pixel bit for bit as the whole image has it. Nothing is written on failure;
    /// `hibi_error_argument()` names a refused layer (`"layers.normal"`, ...) or `"tile"`.
    hibi_mud_render_layers(mud: hibi_mud, "run", hibi_mud_render_params) =
        |_, r: &MudRender| hibi_core::raster::Tile::whole(r.width, r.height), crate::raster::layers_status
}

/// Mud's layers with `layer` to be drawn into `pixels`.
fn mud_layers(layer: u32, pixels: Pixels<'_>) -> Result<MudLayers<'_>, hibi_status> {
    // SAFETY (every arm): the layer's type, as the header gives it for that layer.
    Ok(match layer {
        HIBI_MUD_LAYER_MASK => MudLayers { mask: Some(unsafe { pixels.values() }?), ..MudLayers::default() },
        HIBI_MUD_LAYER_HEIGHT => MudLayers { height: Some(unsafe { pixels.values() }?), ..MudLayers::default() },
        HIBI_MUD_LAYER_TIME => MudLayers { time: Some(unsafe { pixels.values() }?), ..MudLayers::default() },
        _ => return Err(HIBI_ERROR_RENDER_LAYER),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constants::*;
    use crate::status::*;
    use core::ptr::{null, null_mut};
    use hibi_core::polygon::Ring;

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
            (|p| p.topology = 3, HIBI_ERROR_MUD_ENUM),
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
            let mut segments = vec![CrackSegment::default(); count];
            let mut written = 777;
            assert_eq!(
                hibi_mud_segments(mud, segments.as_mut_ptr(), count - 1, &mut written),
                HIBI_ERROR_BUFFER_TOO_SMALL
            );
            assert_eq!(written, 777);
            assert!(segments.iter().all(|s| *s == CrackSegment::default()));
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
            let mut stats = hibi_mud_crack_statistics::default();
            assert_eq!(hibi_mud_statistics(mud, &mut stats), HIBI_OK);
            assert!(stats.crack_density > 0.0);
            hibi_mud_destroy(mud);
        }
    }

    /// A finished run of `params` in library memory, and the same run made through the core.
    fn finished(params: &hibi_mud_params) -> (*mut hibi_mud, Vec<f32>, Vec<u32>) {
        let mut mud = null_mut();
        // SAFETY: valid pointers.
        unsafe {
            assert_eq!(hibi_mud_create(params, &mut mud), HIBI_OK);
            assert_eq!(hibi_mud_step(mud, u64::MAX, null_mut()), HIBI_OK);
        }
        let core = from_c(params).unwrap();
        let memory = core.memory().unwrap();
        (mud, vec![0.0; memory.scalars], vec![0; memory.words])
    }

    const VERTEX: NetworkVertex = NetworkVertex { at: [-7.0; 2], degree: 77, on_border: 77 };
    const EDGE: NetworkEdge = NetworkEdge { from: 77, to: 77, first_point: 77, point_count: 77 };
    const POINT: NetworkPoint = NetworkPoint { at: [-7.0; 2], width: -7.0, time: -7.0 };
    const RING: Ring = Ring { area: -7.0, first_point: 77, point_count: 77, hole_of: 77, reserved: 77 };
    const VEC: hibi_vec2 = hibi_vec2 { x: -7.0, y: -7.0 };

    #[test]
    fn the_network_comes_in_counted_buffers_and_short_ones_are_left_alone() {
        let mut p = small();
        p.boundary = HIBI_MUD_OPEN;
        let (mud, mut scalars, mut words) = finished(&p);
        let mut core = Mud::new(&from_c(&p).unwrap(), MudBuffers { scalars: &mut scalars, words: &mut words }).unwrap();
        core.run().unwrap();
        let expected = core.network_counts();
        assert!(expected.vertices > 0 && expected.edges > 0 && expected.points > expected.edges);
        let (nv, ne, np) = (expected.vertices, expected.edges, expected.points);
        // One element more than needed: it must keep its sentinel.
        let (mut vertices, mut edges, mut points) = (vec![VERTEX; nv + 1], vec![EDGE; ne + 1], vec![POINT; np + 1]);
        let untouched = |v: &[NetworkVertex], e: &[NetworkEdge], q: &[NetworkPoint]| {
            v.iter().all(|x| *x == VERTEX) && e.iter().all(|x| *x == EDGE) && q.iter().all(|x| *x == POINT)
        };
        let (mut wv, mut we, mut wp) = (5usize, 5usize, 5usize);
        let (v, e, q) = (vertices.as_mut_ptr(), edges.as_mut_ptr(), points.as_mut_ptr());
        // SAFETY: valid pointers and lengths throughout; failing calls write nothing.
        unsafe {
            // Counts: a NULL run or any NULL out-pointer is an error, and nothing is written.
            let (mut cv, mut ce, mut cp) = (5usize, 5usize, 5usize);
            assert_eq!(hibi_mud_network_counts(null(), &mut cv, &mut ce, &mut cp), HIBI_ERROR_NULL_POINTER);
            assert_eq!(hibi_mud_network_counts(mud, null_mut(), &mut ce, &mut cp), HIBI_ERROR_NULL_POINTER);
            assert_eq!(hibi_mud_network_counts(mud, &mut cv, null_mut(), &mut cp), HIBI_ERROR_NULL_POINTER);
            assert_eq!(hibi_mud_network_counts(mud, &mut cv, &mut ce, null_mut()), HIBI_ERROR_NULL_POINTER);
            assert_eq!((cv, ce, cp), (5, 5, 5));
            assert_eq!(hibi_mud_network_counts(mud, &mut cv, &mut ce, &mut cp), HIBI_OK);
            assert_eq!((cv, ce, cp), (nv, ne, np));

            let network = |mud: *const hibi_mud, lens: [usize; 3], out: [*mut usize; 3]| {
                hibi_mud_network(mud, v, lens[0], e, lens[1], q, lens[2], out[0], out[1], out[2])
            };
            let written = [&raw mut wv, &raw mut we, &raw mut wp];
            let full = [nv, ne, np];
            assert_eq!(network(null(), full, written), HIBI_ERROR_NULL_POINTER);
            for i in 0..3 {
                let mut out = written;
                out[i] = null_mut();
                assert_eq!(network(mud, full, out), HIBI_ERROR_NULL_POINTER, "written pointer {i}");
                // Each buffer one short, or NULL with length 0.
                let mut short = full;
                short[i] -= 1;
                assert_eq!(network(mud, short, written), HIBI_ERROR_BUFFER_TOO_SMALL, "buffer {i}");
                // The short buffer is named, as the header spells it.
                let named = core::ffi::CStr::from_ptr(crate::status::hibi_error_argument());
                assert_eq!(named.to_str(), Ok(["vertices", "edges", "points"][i]), "buffer {i}");
                let mut empty = full;
                empty[i] = 0;
                let status = match i {
                    0 => hibi_mud_network(mud, null_mut(), 0, e, ne, q, np, written[0], written[1], written[2]),
                    1 => hibi_mud_network(mud, v, nv, null_mut(), 0, q, np, written[0], written[1], written[2]),
                    _ => hibi_mud_network(mud, v, nv, e, ne, null_mut(), 0, written[0], written[1], written[2]),
                };
                assert_eq!(status, HIBI_ERROR_BUFFER_TOO_SMALL, "NULL buffer {i}");
                assert_eq!(network(mud, empty, written), HIBI_ERROR_BUFFER_TOO_SMALL, "empty buffer {i}");
                let status = match i {
                    0 => hibi_mud_network(mud, null_mut(), nv, e, ne, q, np, written[0], written[1], written[2]),
                    1 => hibi_mud_network(mud, v, nv, null_mut(), ne, q, np, written[0], written[1], written[2]),
                    _ => hibi_mud_network(mud, v, nv, e, ne, null_mut(), np, written[0], written[1], written[2]),
                };
                assert_eq!(status, HIBI_ERROR_NULL_POINTER, "NULL buffer {i} with a length");
            }
            assert_eq!((wv, we, wp), (5, 5, 5));
            assert!(untouched(&vertices, &edges, &points));

            assert_eq!(network(mud, full, written), HIBI_OK);
            assert_eq!((wv, we, wp), (nv, ne, np));
            assert!(untouched(&vertices[nv..], &edges[ne..], &points[np..]), "written past the counts");
        }
        // What C got is what the core writes, field by field.
        let mut want = (vec![NetworkVertex::default(); nv], vec![NetworkEdge::default(); ne]);
        let mut want_points = vec![NetworkPoint::default(); np];
        assert_eq!(core.network(&mut want.0, &mut want.1, &mut want_points), Ok(expected));
        for (c, r) in vertices.iter().zip(&want.0) {
            assert_eq!((c.at, c.degree, c.on_border), (r.at, r.degree, r.on_border));
        }
        for (c, r) in edges.iter().zip(&want.1) {
            assert_eq!((c.from, c.to, c.first_point, c.point_count), (r.from, r.to, r.first_point, r.point_count));
        }
        for (c, r) in points.iter().zip(&want_points) {
            assert_eq!((c.at, c.width, c.time), (r.at, r.width, r.time));
        }
        assert!(vertices.iter().take(nv).any(|v| v.on_border == 1), "an open plate has border vertices");
        // SAFETY: a live run, not used afterwards.
        unsafe { hibi_mud_destroy(mud) };
    }

    #[test]
    fn cells_come_in_counted_buffers_and_short_ones_are_left_alone() {
        for boundary in [HIBI_MUD_OPEN, HIBI_MUD_PERIODIC] {
            let mut p = small();
            p.boundary = boundary;
            p.columns = 24;
            p.rows = 24;
            let (mud, mut scalars, mut words) = finished(&p);
            let mut core =
                Mud::new(&from_c(&p).unwrap(), MudBuffers { scalars: &mut scalars, words: &mut words }).unwrap();
            core.run().unwrap();
            let expected = core.cell_counts();
            let (nr, np) = (expected.rings, expected.points);
            assert!(nr > 1 && np > 3 * nr, "{boundary}: {expected:?}");
            let (mut rings, mut points) = (vec![RING; nr + 1], vec![VEC; np + 1]);
            let untouched = |r: &[Ring], q: &[hibi_vec2]| r.iter().all(|x| *x == RING) && q.iter().all(|x| *x == VEC);
            let (r, q) = (rings.as_mut_ptr(), points.as_mut_ptr());
            let (mut wr, mut wp) = (5usize, 5usize);
            // SAFETY: valid pointers and lengths throughout; failing calls write nothing.
            unsafe {
                let (mut cr, mut cp, mut cw) = (5usize, 5usize, 5usize);
                assert_eq!(hibi_mud_cell_counts(null(), &mut cr, &mut cp, &mut cw), HIBI_ERROR_NULL_POINTER);
                assert_eq!(hibi_mud_cell_counts(mud, null_mut(), &mut cp, &mut cw), HIBI_ERROR_NULL_POINTER);
                assert_eq!(hibi_mud_cell_counts(mud, &mut cr, null_mut(), &mut cw), HIBI_ERROR_NULL_POINTER);
                assert_eq!(hibi_mud_cell_counts(mud, &mut cr, &mut cp, null_mut()), HIBI_ERROR_NULL_POINTER);
                assert_eq!((cr, cp, cw), (5, 5, 5));
                assert_eq!(hibi_mud_cell_counts(mud, &mut cr, &mut cp, &mut cw), HIBI_OK);
                assert_eq!((cr, cp, cw), (nr, np, expected.wrapping));

                assert_eq!(hibi_mud_cells(null(), r, nr, q, np, &mut wr, &mut wp), HIBI_ERROR_NULL_POINTER);
                assert_eq!(hibi_mud_cells(mud, r, nr, q, np, null_mut(), &mut wp), HIBI_ERROR_NULL_POINTER);
                assert_eq!(hibi_mud_cells(mud, r, nr, q, np, &mut wr, null_mut()), HIBI_ERROR_NULL_POINTER);
                assert_eq!(hibi_mud_cells(mud, null_mut(), nr, q, np, &mut wr, &mut wp), HIBI_ERROR_NULL_POINTER);
                for ((rl, pl), name) in
                    [((nr - 1, np), "rings"), ((nr, np - 1), "points"), ((0, np), "rings"), ((nr, 0), "points")]
                {
                    assert_eq!(hibi_mud_cells(mud, r, rl, q, pl, &mut wr, &mut wp), HIBI_ERROR_BUFFER_TOO_SMALL);
                    let named = core::ffi::CStr::from_ptr(crate::status::hibi_error_argument());
                    assert_eq!(named.to_str(), Ok(name), "rings {rl}, points {pl}");
                }
                assert_eq!(hibi_mud_cells(mud, null_mut(), 0, q, np, &mut wr, &mut wp), HIBI_ERROR_BUFFER_TOO_SMALL);
                assert_eq!(hibi_mud_cells(mud, r, nr, null_mut(), 0, &mut wr, &mut wp), HIBI_ERROR_BUFFER_TOO_SMALL);
                assert_eq!((wr, wp), (5, 5));
                assert!(untouched(&rings, &points));

                assert_eq!(hibi_mud_cells(mud, r, nr, q, np, &mut wr, &mut wp), HIBI_OK);
                assert_eq!((wr, wp), (nr, np));
                assert!(untouched(&rings[nr..], &points[np..]), "written past the counts");
            }
            let (mut want, mut want_points) = (vec![Ring::default(); nr], vec![[0.0f32; 2]; np]);
            assert_eq!(core.cells(&mut want, &mut want_points), Ok(expected));
            for (c, w) in rings.iter().zip(&want) {
                assert_eq!(
                    (c.area, c.first_point, c.point_count, c.hole_of),
                    (w.area, w.first_point, w.point_count, w.hole_of)
                );
            }
            assert!(points.iter().zip(&want_points).all(|(c, w)| [c.x, c.y] == *w));
            assert_eq!(rings[..nr].iter().map(|x| x.point_count as usize).sum::<usize>(), np);
            // The statistics C sees are the core's.
            let mut stats = hibi_mud_crack_statistics::default();
            // SAFETY: a live run and a writable struct.
            assert_eq!(unsafe { hibi_mud_statistics(mud, &mut stats) }, HIBI_OK);
            let s = core.statistics();
            assert_eq!(
                (stats.crack_density, stats.cells, stats.mean_cell_area, stats.cell_area_spread),
                (s.crack_density, s.cells, s.mean_cell_area, s.cell_area_spread)
            );
            assert_eq!((stats.junctions, stats.dead_ends), (s.junctions, s.dead_ends));
            assert_eq!(
                (stats.t_junctions, stats.mean_widest_junction_angle),
                (s.t_junctions, s.mean_widest_junction_angle)
            );
            assert!(stats.junctions > 0, "{boundary}: {stats:?}");
            // SAFETY: a live run, not used afterwards.
            unsafe { hibi_mud_destroy(mud) };
        }
    }
}
