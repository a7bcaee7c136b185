//! `hibi_mud_network_build` and `hibi_mud_cell_build`: a run's crack network and cells built
//! in budgeted steps into caller memory, then read in ranges, so that no call walks the whole
//! lattice (`hibi_mud_network` and `hibi_mud_cells` do, in one call).

#![allow(non_camel_case_types)]

use core::ffi::c_void;

use hibi_core::mud::{
    CellBuild, CellBuildBuffers, CellBuildMemory, CellBuildProgress, MudError, NetworkBuild, NetworkBuildBuffers,
    NetworkBuildMemory, NetworkBuildProgress, NetworkEdge, NetworkPoint, NetworkVertex,
};
use hibi_core::polygon::Ring;

use crate::glass::hibi_vec2;
use crate::guard::{check_pointer, copy_from, guard, object_ref, query, update, write_out};
use crate::mud::hibi_mud;
use crate::object::{self, AnyBits, Arena};
use crate::status::{HIBI_ERROR_BUFFER_TOO_SMALL, hibi_status, refuse_argument};

// SAFETY: two f32 and two u32 (16 bytes, no padding, checked below).
unsafe impl AnyBits for NetworkVertex {}
// SAFETY: four u32.
unsafe impl AnyBits for NetworkEdge {}
// SAFETY: four f32.
unsafe impl AnyBits for NetworkPoint {}
const _: () = assert!(size_of::<NetworkVertex>() == 16 && size_of::<NetworkEdge>() == 16);
const _: () = assert!(size_of::<NetworkPoint>() == 16);

/// The status of a build's error: its buffers are carved to the run's memory, so a short one
/// means a run of a larger lattice than the build was made for.
fn build_status(_: MudError) -> hibi_status {
    HIBI_ERROR_BUFFER_TOO_SMALL
}

/// A budgeted build of a run's crack network, in caller memory
/// (`hibi_mud_network_build_create_in`). Opaque; nothing to free (the memory stays the
/// caller's).
pub struct hibi_mud_network_build {
    build: NetworkBuild<'static>,
}

/// Where a network build stands.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct hibi_mud_network_build_progress {
    /// Vertices written so far (all of them once finished).
    pub vertices: u32,
    /// Edges written so far.
    pub edges: u32,
    /// Edge points written so far.
    pub points: u32,
    /// 1 when the network is written: its vertices, edges and points can then be read
    /// (`hibi_mud_network_build_vertices`, `_edges`, `_points`).
    pub finished: u32,
    /// Work done since the build (re)started, in the units of the step's budget.
    pub work: u64,
}

impl hibi_mud_network_build_progress {
    /// A core progress as the C struct (the counts are below the lattice's springs, which
    /// `hibi_mud_memory_size` keeps below 2^32).
    fn of(p: &NetworkBuildProgress) -> Self {
        hibi_mud_network_build_progress {
            vertices: p.counts.vertices as u32,
            edges: p.counts.edges as u32,
            points: p.counts.points as u32,
            finished: u32::from(p.finished),
            work: p.work,
        }
    }
}

/// A network build's block: its header, then its vertices, edges and points, taken as they
/// are (the build reads no element it has not written).
fn network_build_arrays(
    m: &NetworkBuildMemory,
    arena: &mut Arena,
) -> (*mut hibi_mud_network_build, NetworkBuildBuffers<'static>) {
    let header = arena.reserve::<hibi_mud_network_build>();
    let buffers = NetworkBuildBuffers {
        vertices: arena.take_as_is(m.vertices),
        edges: arena.take_as_is(m.edges),
        points: arena.take_as_is(m.points),
    };
    (header, buffers)
}

/// Writes the bytes of caller memory a network build of `mud` needs (for
/// `hibi_mud_network_build_create_in`; aligned to `hibi_mud_memory_align()`): room for the
/// most vertices, edges and points its lattice's network can have, so one block serves the run
/// at any point.
///
/// # Safety
/// `mud` must be NULL or a live run; `size` NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_mud_network_build_size(mud: *const hibi_mud, size: *mut usize) -> hibi_status {
    let read = |mud: &hibi_mud| {
        let m = mud.mud.network_build_memory();
        object::scratch_size(|arena| network_build_arrays(&m, arena))
    };
    // SAFETY: the caller's contract.
    guard(|| unsafe { query(mud, c"mud", (size, c"size"), read) })
}

/// Makes a build of `mud`'s crack network in caller memory of at least
/// `hibi_mud_network_build_size` bytes aligned to `hibi_mud_memory_align()`, in the same
/// work at any size (nothing is written but the build's header); `hibi_mud_network_build_step`
/// does the work. The build yields the vertices, edges and points `hibi_mud_network` writes,
/// bit for bit, read in ranges once finished. Nothing is written on failure; there is nothing
/// to destroy.
///
/// # Safety
/// `mud` must be NULL or a live run; `memory` NULL or writable for `memory_size` bytes and
/// untouched while the build is used; `out` NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_mud_network_build_create_in(
    mud: *const hibi_mud,
    memory: *mut c_void,
    memory_size: usize,
    out: *mut *mut hibi_mud_network_build,
) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let mud = unsafe { object_ref(mud, c"mud") }?;
        check_pointer(out, c"out")?;
        let m = mud.mud.network_build_memory();
        // SAFETY: the caller's contract.
        let (header, buffers) =
            unsafe { object::caller_arrays(memory, memory_size, |arena| network_build_arrays(&m, arena)) }?;
        let build = NetworkBuild::new(&mud.mud, buffers).map_err(build_status)?;
        // SAFETY: the header's room at the block's start, aligned (`caller_arrays` checked the
        // block against this layout).
        unsafe { header.write(hibi_mud_network_build { build }) };
        // SAFETY: checked; the caller's contract.
        unsafe { write_out(out, c"out", header) }
    })
}

/// Goes on with `build` on `mud` until about `budget` units of work are done in this call,
/// or it is finished; writes where it stands to `*progress` unless it is NULL. A unit is a
/// mesh cell or a spring looked at, a vertex written, or a point an edge's walk passes (each
/// edge is walked twice: to find its far end, then for its points); a call does at least one
/// piece (one mesh cell's vertices or edges, or one spring's closed crack) and overruns the
/// budget by less than one: the points of the cracks leaving one mesh cell, twice. The result
/// does not depend on the budgets. A run whose network shown changed since the build began (a
/// trace finished in a step, or `hibi_mud_trace`) starts the build over (its work from 0).
/// `HIBI_ERROR_BUFFER_TOO_SMALL` (naming `build`) for a run whose lattice needs a larger
/// block than the build's. Steps of one build must not run at once; the run is only read.
///
/// # Safety
/// `build` must be NULL or a live build; `mud` NULL or a live run not changed during the call;
/// `progress` optional: NULL (not written) or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_mud_network_build_step(
    build: *mut hibi_mud_network_build,
    mud: *const hibi_mud,
    budget: u64,
    progress: *mut hibi_mud_network_build_progress,
) -> hibi_status {
    let step = |build: &mut hibi_mud_network_build| {
        // SAFETY: the caller's contract.
        let mud = unsafe { object_ref(mud, c"mud") }?;
        let p = build.build.step(&mud.mud, budget).map_err(|_| too_small(c"build"))?;
        Ok(hibi_mud_network_build_progress::of(&p))
    };
    // SAFETY: the caller's contract.
    guard(|| unsafe { update(build, c"build", (progress, c"progress"), step) })
}

/// A short buffer, naming the argument.
fn too_small(name: &'static core::ffi::CStr) -> hibi_status {
    refuse_argument(name, HIBI_ERROR_BUFFER_TOO_SMALL)
}

/// Writes the vertices of a finished `build` from vertex `first` on into
/// `vertices[0..vertices_len]`: as many as there are, at most `vertices_len` (none before the
/// build is finished, or from a `first` at or past the vertex count), and how many into
/// `*written`. The vertices `[first, first + vertices_len)` of `hibi_mud_network`: ranges read
/// one after another concatenate to its vertices.
///
/// # Safety
/// `build` must be NULL or a live build; `vertices` NULL (only with `vertices_len` 0) or
/// writable for `vertices_len` vertices; `written` NULL (refused) or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_mud_network_build_vertices(
    build: *const hibi_mud_network_build,
    first: usize,
    vertices: *mut NetworkVertex,
    vertices_len: usize,
    written: *mut usize,
) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let build = unsafe { object_ref(build, c"build") }?;
        // SAFETY: the caller's contract.
        unsafe { copy_from(build.build.vertices(), first, (vertices, vertices_len, c"vertices"), written) }
    })
}

/// Writes the edges of a finished `build` from edge `first` on into `edges[0..edges_len]`, as
/// `hibi_mud_network_build_vertices` writes vertices; each edge's `first_point` indexes the
/// whole points list (`hibi_mud_network_build_points`).
///
/// # Safety
/// `build` must be NULL or a live build; `edges` NULL (only with `edges_len` 0) or writable for
/// `edges_len` edges; `written` NULL (refused) or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_mud_network_build_edges(
    build: *const hibi_mud_network_build,
    first: usize,
    edges: *mut NetworkEdge,
    edges_len: usize,
    written: *mut usize,
) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let build = unsafe { object_ref(build, c"build") }?;
        // SAFETY: the caller's contract.
        unsafe { copy_from(build.build.edges(), first, (edges, edges_len, c"edges"), written) }
    })
}

/// Writes the edge points of a finished `build` from point `first` on into
/// `points[0..points_len]`, as `hibi_mud_network_build_vertices` writes vertices.
///
/// # Safety
/// `build` must be NULL or a live build; `points` NULL (only with `points_len` 0) or writable
/// for `points_len` points; `written` NULL (refused) or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_mud_network_build_points(
    build: *const hibi_mud_network_build,
    first: usize,
    points: *mut NetworkPoint,
    points_len: usize,
    written: *mut usize,
) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let build = unsafe { object_ref(build, c"build") }?;
        // SAFETY: the caller's contract.
        unsafe { copy_from(build.build.points(), first, (points, points_len, c"points"), written) }
    })
}

/// A budgeted build of a run's cells, in caller memory (`hibi_mud_cell_build_create_in`).
/// Opaque; nothing to free (the memory stays the caller's).
pub struct hibi_mud_cell_build {
    build: CellBuild<'static>,
}

/// Where a cell build stands.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct hibi_mud_cell_build_progress {
    /// Rings written so far (all of them once finished).
    pub rings: u32,
    /// Their points.
    pub points: u32,
    /// Boundaries that wrap around a periodic lattice found so far (not written).
    pub wrapping: u32,
    /// 1 when every ring is written and every hole knows its outer ring: the rings and points
    /// can then be read (`hibi_mud_cell_build_rings`, `hibi_mud_cell_build_points`).
    pub finished: u32,
    /// Work done since the build (re)started, in the units of the step's budget.
    pub work: u64,
}

impl hibi_mud_cell_build_progress {
    /// A core progress as the C struct (the counts are below four times the lattice's
    /// springs and three times its cells, which `hibi_mud_memory_size` keeps below 2^32).
    fn of(p: &CellBuildProgress) -> Self {
        hibi_mud_cell_build_progress {
            rings: p.counts.rings as u32,
            points: p.counts.points as u32,
            wrapping: p.counts.wrapping as u32,
            finished: u32::from(p.finished),
            work: p.work,
        }
    }
}

/// A cell build's block: its header, then its rings and points, taken as they are.
fn cell_build_arrays(m: &CellBuildMemory, arena: &mut Arena) -> (*mut hibi_mud_cell_build, CellBuildBuffers<'static>) {
    let header = arena.reserve::<hibi_mud_cell_build>();
    let buffers = CellBuildBuffers { rings: arena.take_as_is::<Ring>(m.rings), points: arena.take_as_is(m.points) };
    (header, buffers)
}

/// Writes the bytes of caller memory a cell build of `mud` needs (for
/// `hibi_mud_cell_build_create_in`; aligned to `hibi_mud_memory_align()`): room for the most
/// rings and points its lattice's cells can have, so one block serves the run at any point.
///
/// # Safety
/// `mud` must be NULL or a live run; `size` NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_mud_cell_build_size(mud: *const hibi_mud, size: *mut usize) -> hibi_status {
    let read = |mud: &hibi_mud| {
        let m = mud.mud.cell_build_memory();
        object::scratch_size(|arena| cell_build_arrays(&m, arena))
    };
    // SAFETY: the caller's contract.
    guard(|| unsafe { query(mud, c"mud", (size, c"size"), read) })
}

/// Makes a build of `mud`'s cells in caller memory of at least `hibi_mud_cell_build_size`
/// bytes aligned to `hibi_mud_memory_align()`, in the same work at any size;
/// `hibi_mud_cell_build_step` does the work. The build yields the rings and points
/// `hibi_mud_cells` writes, bit for bit, read in ranges once finished. Nothing is written on
/// failure; there is nothing to destroy.
///
/// # Safety
/// `mud` must be NULL or a live run; `memory` NULL or writable for `memory_size` bytes and
/// untouched while the build is used; `out` NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_mud_cell_build_create_in(
    mud: *const hibi_mud,
    memory: *mut c_void,
    memory_size: usize,
    out: *mut *mut hibi_mud_cell_build,
) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let mud = unsafe { object_ref(mud, c"mud") }?;
        check_pointer(out, c"out")?;
        let m = mud.mud.cell_build_memory();
        // SAFETY: the caller's contract.
        let (header, buffers) =
            unsafe { object::caller_arrays(memory, memory_size, |arena| cell_build_arrays(&m, arena)) }?;
        let build = CellBuild::new(&mud.mud, buffers).map_err(build_status)?;
        // SAFETY: the header's room at the block's start, aligned.
        unsafe { header.write(hibi_mud_cell_build { build }) };
        // SAFETY: checked; the caller's contract.
        unsafe { write_out(out, c"out", header) }
    })
}

/// Goes on with `build` on `mud` until about `budget` units of work are done in this call,
/// or it is finished; writes where it stands to `*progress` unless it is NULL. A unit is a
/// mesh cell looked at, a ring point written, or a point of an outer ring tested for a hole
/// (at each periodic shift); a call does at least one piece (one mesh cell's rings, or one
/// outer ring tested for one hole) and overruns the budget by less than one: the points of the
/// rings starting from one mesh cell, or nine times one ring's points. The result does not
/// depend on the budgets. A run whose network shown changed since the build began starts the
/// build over (its work from 0). `HIBI_ERROR_BUFFER_TOO_SMALL` (naming `build`) for a run
/// whose lattice needs a larger block than the build's. Steps of one build must not run at
/// once; the run is only read.
///
/// # Safety
/// `build` must be NULL or a live build; `mud` NULL or a live run not changed during the call;
/// `progress` optional: NULL (not written) or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_mud_cell_build_step(
    build: *mut hibi_mud_cell_build,
    mud: *const hibi_mud,
    budget: u64,
    progress: *mut hibi_mud_cell_build_progress,
) -> hibi_status {
    let step = |build: &mut hibi_mud_cell_build| {
        // SAFETY: the caller's contract.
        let mud = unsafe { object_ref(mud, c"mud") }?;
        let p = build.build.step(&mud.mud, budget).map_err(|_| too_small(c"build"))?;
        Ok(hibi_mud_cell_build_progress::of(&p))
    };
    // SAFETY: the caller's contract.
    guard(|| unsafe { update(build, c"build", (progress, c"progress"), step) })
}

/// Writes the rings of a finished `build` from ring `first` on into `rings[0..rings_len]`: as
/// many as there are, at most `rings_len` (none before the build is finished, or from a
/// `first` at or past the ring count), and how many into `*written`. The rings
/// `[first, first + rings_len)` of `hibi_mud_cells`: ranges read one after another
/// concatenate to its rings, and each ring's `first_point` indexes the whole points list
/// (`hibi_mud_cell_build_points`).
///
/// # Safety
/// `build` must be NULL or a live build; `rings` NULL (only with `rings_len` 0) or writable
/// for `rings_len` rings; `written` NULL (refused) or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_mud_cell_build_rings(
    build: *const hibi_mud_cell_build,
    first: usize,
    rings: *mut Ring,
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
/// `points[0..points_len]`, as `hibi_mud_cell_build_rings` writes rings.
///
/// # Safety
/// `build` must be NULL or a live build; `points` NULL (only with `points_len` 0) or writable
/// for `points_len` points; `written` NULL (refused) or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_mud_cell_build_points(
    build: *const hibi_mud_cell_build,
    first: usize,
    points: *mut hibi_vec2,
    points_len: usize,
    written: *mut usize,
) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let build = unsafe { object_ref(build, c"build") }?;
        // SAFETY: hibi_vec2 is laid out as [f32; 2] (asserted in the glass module).
        let points = points.cast::<[f32; 2]>();
        // SAFETY: the caller's contract.
        unsafe { copy_from(build.build.points(), first, (points, points_len, c"points"), written) }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mud::{hibi_mud_create, hibi_mud_destroy, hibi_mud_params_default, hibi_mud_step};
    use crate::status::{HIBI_ERROR_NULL_POINTER, HIBI_OK, hibi_error_argument};
    use core::ffi::CStr;
    use core::ptr::null_mut;

    /// Reads a finished build's elements `range` at a time through `read`, until none is left.
    fn ranges<T: Copy + Default>(
        range: usize,
        mut read: impl FnMut(usize, *mut T, usize, &mut usize) -> hibi_status,
    ) -> Vec<T> {
        let (mut all, mut out) = (Vec::new(), vec![T::default(); range]);
        loop {
            let mut written = usize::MAX;
            assert_eq!(read(all.len(), out.as_mut_ptr(), range, &mut written), HIBI_OK);
            all.extend_from_slice(&out[..written]);
            if written < range {
                return all;
            }
        }
    }

    /// Both builds through the C ABI: short memory refused naming `memory`, nothing written on
    /// failure, steps within the budget and one piece, ranges that concatenate to the one-call
    /// outputs, NULL arguments named.
    #[test]
    fn builds_through_the_c_abi() {
        let mut params = hibi_mud_params_default();
        (params.columns, params.rows, params.seed) = (24, 20, 9);
        let mut mud = null_mut();
        // SAFETY (every call below): valid pointers and lengths; a live run.
        unsafe {
            assert_eq!(hibi_mud_create(&params, &mut mud), HIBI_OK);
            let mut progress = crate::mud::hibi_mud_progress::default();
            while progress.finished == 0 {
                assert_eq!(hibi_mud_step(mud, u64::MAX, &mut progress), HIBI_OK);
            }
            let core = &(*mud).mud;
            let counts = core.network_counts();
            let mut whole = (
                vec![NetworkVertex::default(); counts.vertices],
                vec![NetworkEdge::default(); counts.edges],
                vec![NetworkPoint::default(); counts.points],
            );
            core.network(&mut whole.0, &mut whole.1, &mut whole.2).unwrap();
            let cells = core.cell_counts();
            let mut whole_cells = (vec![Ring::default(); cells.rings], vec![[0.0f32; 2]; cells.points]);
            core.cells(&mut whole_cells.0, &mut whole_cells.1).unwrap();
            assert!(counts.edges > 5 && cells.rings > 5, "{counts:?} {cells:?}");

            let mut size = 0;
            assert_eq!(hibi_mud_network_build_size(mud, &mut size), HIBI_OK);
            let mut memory = vec![0xA5A5_A5A5_A5A5_A5A5u64; size.div_ceil(8)];
            let base = memory.as_mut_ptr().cast::<c_void>();
            let mut build = null_mut();
            assert_eq!(hibi_mud_network_build_create_in(mud, base, size - 1, &mut build), HIBI_ERROR_BUFFER_TOO_SMALL);
            assert_eq!(CStr::from_ptr(hibi_error_argument()), c"memory");
            assert_eq!(hibi_mud_network_build_create_in(null_mut(), base, size, &mut build), HIBI_ERROR_NULL_POINTER);
            assert_eq!(hibi_mud_network_build_create_in(mud, base, size, null_mut()), HIBI_ERROR_NULL_POINTER);
            assert!(build.is_null() && memory.iter().all(|&w| w == 0xA5A5_A5A5_A5A5_A5A5), "nothing written");
            assert_eq!(hibi_mud_network_build_create_in(mud, base, size, &mut build), HIBI_OK);
            let longest = whole.1.iter().map(|e| u64::from(e.point_count)).max().unwrap();
            let (mut p, mut before, mut calls) = (hibi_mud_network_build_progress::default(), 0, 0);
            while p.finished == 0 {
                assert_eq!(hibi_mud_network_build_step(build, mud, 40, &mut p), HIBI_OK);
                assert!(p.work - before < 40 + 1 + 6 * (longest + 2), "{p:?}");
                (before, calls) = (p.work, calls + 1);
            }
            assert!(calls > 10, "{calls} calls");
            let vertices = ranges(5, |first, out, len, w| hibi_mud_network_build_vertices(build, first, out, len, w));
            let edges = ranges(3, |first, out, len, w| hibi_mud_network_build_edges(build, first, out, len, w));
            let points = ranges(7, |first, out, len, w| hibi_mud_network_build_points(build, first, out, len, w));
            assert!(vertices == whole.0 && edges == whole.1 && points == whole.2);
            let mut one = NetworkEdge::default();
            assert_eq!(hibi_mud_network_build_edges(build, 0, &mut one, 1, null_mut()), HIBI_ERROR_NULL_POINTER);
            assert_eq!(CStr::from_ptr(hibi_error_argument()), c"written");
            assert_eq!(hibi_mud_network_build_step(null_mut(), mud, 1, null_mut()), HIBI_ERROR_NULL_POINTER);
            assert_eq!(CStr::from_ptr(hibi_error_argument()), c"build");

            assert_eq!(hibi_mud_cell_build_size(mud, &mut size), HIBI_OK);
            let mut memory = vec![0u64; size.div_ceil(8)];
            let base = memory.as_mut_ptr().cast::<c_void>();
            let mut build = null_mut();
            assert_eq!(hibi_mud_cell_build_create_in(mud, base, size / 2, &mut build), HIBI_ERROR_BUFFER_TOO_SMALL);
            assert_eq!(CStr::from_ptr(hibi_error_argument()), c"memory");
            assert_eq!(hibi_mud_cell_build_create_in(mud, base, size, &mut build), HIBI_OK);
            let largest = whole_cells.0.iter().map(|r| u64::from(r.point_count)).max().unwrap();
            let (mut p, mut before) = (hibi_mud_cell_build_progress::default(), 0);
            while p.finished == 0 {
                assert_eq!(hibi_mud_cell_build_step(build, mud, 40, &mut p), HIBI_OK);
                assert!(p.work - before < 40 + 1 + 9 * largest, "{p:?}");
                before = p.work;
            }
            let rings = ranges(4, |first, out, len, w| hibi_mud_cell_build_rings(build, first, out, len, w));
            let points: Vec<hibi_vec2> =
                ranges(9, |first, out, len, w| hibi_mud_cell_build_points(build, first, out, len, w));
            assert!(rings == whole_cells.0);
            assert!(points.len() == cells.points && points.iter().zip(&whole_cells.1).all(|(a, b)| [a.x, a.y] == *b));
            hibi_mud_destroy(mud);
        }
    }
}
