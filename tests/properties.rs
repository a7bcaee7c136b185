//! Property tests over random valid parameters of small size, through the C ABI as a C caller
//! drives it, for each model:
//!
//! - glass fragments cover the plate: their signed ring areas sum to width × height (within
//!   10⁻⁴, in f64);
//! - the pieces for a physics engine (`hibi_triangulate`, `hibi_convex_pieces`) of glass
//!   fragments and mud cells: counter-clockwise triangles, strictly convex pieces of 3 to 8
//!   points, each polygon's adding up to its area (outer ring minus holes; within 10⁻⁶), a
//!   glass plate's to width × height (within 10⁻⁴);
//! - no NaN or infinity in any output (mud segments, network and cells; glass polylines and
//!   fragments; skin cells and outlines; every float raster, except the break-time layers'
//!   documented +infinity where no crack is);
//! - every raster in its documented range, drawn with random render parameters: the masks'
//!   coverage and the break-time layers agree (a pixel has a break time exactly where a crack
//!   covers at least half of it, mask ≥ 128), break times lie in [0, the run's end time]; mud
//!   heights in [1 − `groove_depth`, 1]; skin heights within the sums over the levels of the
//!   profiles' lowest and highest control points (a Bézier curve stays in its control
//!   points' hull, and the table between samples is linear), normals of unit length (within
//!   2·10⁻⁶: the `f32` reciprocal square root is within 3·10⁻⁷) pointing out of the surface,
//!   and the cell map naming cells of the level asked for, every pixel once the build is
//!   complete;
//! - every index in an output points at something that exists: mud network edges' vertices
//!   and points (and each vertex's degree is the number of edge ends at it), mud cell and
//!   glass fragment rings' points and `hole_of`; glass cracks' kind, end and impact;
//! - every `step(budget)` call's work is bounded by its budget plus one indivisible piece
//!   (mud: a row of a short step, a node's relaxation, a break event or a piece of the
//!   network's tracing; glass: a cell or entry of a query, a crack looked at or a step of a
//!   face walk, at most `HIBI_GLASS_STEP_PIECE` units;
//!   skin: one cell at any level, or one unit of a division: a centre point tried or a
//!   piece of bucketing). The largest piece is measured by a run with budget 1,
//!   whose calls each do exactly one piece; the run under test must then end in the same
//!   state (the models do not depend on the budgets), so its pieces are the same ones;
//! - the memory need is exact: `*_create_in` accepts `*_memory_size` bytes and refuses one
//!   byte less with `HIBI_ERROR_BUFFER_TOO_SMALL`; likewise the query scratches.
//!
//! Glass's budget property runs the Rust API (`GlassProgress::work`, which
//! `hibi_glass_progress.work` copies), to compare a run with the budget-1 run in one process
//! without the C objects' bookkeeping.

use core::ffi::c_void;

use hibi::*;
use hibi_core::glass::{CrackPoint, Glass, GlassParams, GlassProgress};
use hibi_core::mud::{CrackSegment, NetworkEdge, NetworkPoint, NetworkVertex};
use hibi_core::polygon::{ConvexPiece, Ring, Triangle};
use proptest::prelude::*;

fn config() -> ProptestConfig {
    // Half as many in the test command's debug run, whose model code checks every overflow.
    let cases = if cfg!(debug_assertions) { 24 } else { 48 };
    ProptestConfig { cases, failure_persistence: None, ..ProptestConfig::default() }
}

/// Caller memory: `len` bytes aligned to 8.
fn block(len: usize) -> Vec<u64> {
    vec![0; len.div_ceil(8).max(1)]
}

/// Checks that `create_in` takes exactly `size` bytes: one byte less is refused with
/// `HIBI_ERROR_BUFFER_TOO_SMALL` and writes nothing.
fn memory_is_exact<P, O>(
    params: &P,
    memory_size: unsafe extern "C" fn(*const P, *mut usize) -> hibi_status,
    create_in: unsafe extern "C" fn(*const P, *mut c_void, usize, *mut *mut O) -> hibi_status,
) {
    let mut size = 0;
    // SAFETY: valid pointers.
    assert_eq!(unsafe { memory_size(params, &mut size) }, HIBI_OK);
    let mut memory = block(size);
    let mut object: *mut O = core::ptr::null_mut();
    // SAFETY: `memory` holds at least `size - 1` bytes.
    let status = unsafe { create_in(params, memory.as_mut_ptr().cast(), size - 1, &mut object) };
    assert_eq!(status, HIBI_ERROR_BUFFER_TOO_SMALL, "one byte short");
    assert!(object.is_null());
    // SAFETY: `memory` holds `size` bytes, aligned to 8 (the models' alignment).
    let status = unsafe { create_in(params, memory.as_mut_ptr().cast(), size, &mut object) };
    assert_eq!(status, HIBI_OK, "exactly the size");
    assert!(!object.is_null());
}

fn finite(values: &[f32]) -> bool {
    values.iter().all(|v| v.is_finite())
}

// ---------------------------------------------------------------------------------------
// Model A: mud

prop_compose! {
    fn mud_params()(
        topology in 0u32..3,
        periodic in any::<bool>(),
        explicit in prop::bool::weighted(0.2),
        growth in any::<bool>(),
        columns in 4u32..=18,
        half_rows in 2u32..=9,
        seed in any::<u64>(),
        mean in 1.001f32..1.3,
        spread in 0.0f32..0.05,
        shrink_ratio in 0.990f32..0.99995,
        direction in -3.2f32..3.2,
        anisotropy in 1.0f32..3.0,
        stiffness in 1.0f32..3.0,
        target_shrink in 0.005f32..0.2,
        exponent in 0.0f32..1.0,
        // Sizes, moduli and the explicit solver's steps about the paper's (an explicit run
        // whose short step is unstable for them is refused, and the case is drawn again).
        sizes in (0.5f32..2.0, 0.5f32..2.0, 0.5f32..2.0),
        moduli in (3e5f32..3e6, 5e4f32..6e5, 1.0f32..3.0),
        steps in (0.0005f32..0.002, 10f32..40.0, 0.5f32..2.0),
        density in prop::option::weighted(0.2, 0.5f32..5.0),
    ) -> hibi_mud_params {
        let mut p = hibi_mud_params_default();
        p.topology = topology;
        p.boundary = if periodic { HIBI_MUD_PERIODIC } else { HIBI_MUD_OPEN };
        p.solver = if explicit { HIBI_MUD_EXPLICIT } else { HIBI_MUD_QUASI_STATIC };
        p.drive = if growth { HIBI_MUD_GROWTH } else { HIBI_MUD_SHRINK };
        p.columns = columns;
        p.rows = 2 * half_rows;
        p.seed = seed;
        p.break_stretch_mean = mean;
        p.break_stretch_spread = spread;
        p.shrink_ratio = shrink_ratio;
        p.anisotropy_direction = direction;
        p.anisotropy_ratio = anisotropy;
        p.stiffness_anisotropy_ratio = stiffness;
        p.target_shrink = target_shrink;
        p.break_stretch_size_exponent = exponent;
        (p.layer_thickness, p.element_size, p.long_step) = sizes;
        (p.young_modulus, p.shear_modulus, p.density) = moduli;
        (p.short_step, p.damping_factor, p.displacement_tolerance) = (steps.0, steps.1, 1e-4 * steps.2);
        p.target_crack_density = density.unwrap_or(0.0);
        if explicit {
            // The explicit solver integrates every short step (T / τ of them per long step, Eq.
            // 4): kept to the paper's steps and a run of at most a few hundred long steps.
            (p.long_step, p.short_step, p.shrink_ratio) = (1.0, 0.001, p.shrink_ratio.min(0.9995));
            p.target_shrink = p.target_shrink.min(0.05);
            (p.columns, p.rows) = (p.columns.min(12), p.rows.min(12));
        }
        p
    }
}

/// Whether the library takes `p` (some random sizes make an explicit short step unstable).
fn mud_accepts(p: &hibi_mud_params) -> bool {
    let mut size = 0;
    // SAFETY: valid pointers.
    unsafe { hibi_mud_memory_size(p, &mut size) == HIBI_OK }
}

/// A run through the C ABI, and whether its lattice is periodic.
struct Mud(*mut hibi_mud, bool);

impl Mud {
    fn new(p: &hibi_mud_params) -> Mud {
        let mut mud = core::ptr::null_mut();
        // SAFETY: valid pointers.
        assert_eq!(unsafe { hibi_mud_create(p, &mut mud) }, HIBI_OK);
        Mud(mud, p.boundary == HIBI_MUD_PERIODIC)
    }

    fn step(&self, budget: u64) -> hibi_mud_progress {
        let mut progress = hibi_mud_progress::default();
        // SAFETY: a live run.
        assert_eq!(unsafe { hibi_mud_step(self.0, budget, &mut progress) }, HIBI_OK);
        progress
    }

    /// Steps with `budget` to the end, each call within the stated bound (`Mud::step`): the
    /// budget less one plus one piece — a row's springs of one direction and their breaks'
    /// rescan (2 · columns, explicit), a node's springs (at most 16, quasi-static), a piece of
    /// the network's tracing (`HIBI_MUD_TRACE_PIECE`). Returns the end.
    fn run(&self, budget: u64, p: &hibi_mud_params) -> hibi_mud_progress {
        let piece = u64::from(2 * p.columns).max(16).max(HIBI_MUD_TRACE_PIECE);
        let mut work = 0;
        loop {
            let progress = self.step(budget);
            let done = progress.work - work;
            let bound = budget.max(1) - 1 + piece;
            assert!(done <= bound, "a step with budget {budget} did {done} work (bound {bound})");
            work = progress.work;
            if progress.finished == 1 {
                return progress;
            }
        }
    }
}

impl Drop for Mud {
    fn drop(&mut self) {
        // SAFETY: a live run, not used afterwards.
        unsafe { hibi_mud_destroy(self.0) };
    }
}

prop_compose! {
    fn mud_render()(
        width in 8u32..=48,
        height in 8u32..=48,
        width_scale in 0f32..3.0,
        min_width in 0f32..2.0,
        groove_depth in 0f32..2.0,
        offset in (-20f32..20.0, -20f32..20.0),
    ) -> hibi_mud_render_params {
        let mut r = hibi_mud_render_params_default();
        (r.width, r.height) = (width, height);
        (r.width_scale, r.min_width, r.groove_depth) = (width_scale, min_width, groove_depth);
        r.offset = [offset.0, offset.1];
        r
    }
}

/// A mask and a break-time layer of the same strokes agree: the mask is each pixel's largest
/// coverage (0 to 255), the time layer has a time where a crack covers at least half of the
/// pixel (rounded, 255 / 2 is 128) and +infinity elsewhere; every time lies in [0, `end`].
fn mask_and_time_agree(mask: &[u8], time: &[f32], end: f32) {
    for (i, (&m, &t)) in mask.iter().zip(time).enumerate() {
        assert!(t == f32::INFINITY || (t >= 0.0 && t <= end), "pixel {i}: time {t} outside [0, {end}]");
        assert_eq!(t.is_finite(), m >= 128, "pixel {i}: mask {m}, time {t}");
    }
}

/// The rings of a cell or fragment outline index points that exist; a hole names an outer
/// ring (or, where `wrapping_cells` — mud on a periodic lattice —, a cell that wraps around
/// it) and has a negative area, an outer ring a positive one.
fn rings_are_consistent(rings: &[Ring], points: usize, wrapping_cells: bool) {
    for (i, ring) in rings.iter().enumerate() {
        let end = ring.first_point as usize + ring.point_count as usize;
        assert!(ring.point_count >= 3 && end <= points, "ring {i}: {ring:?} of {points} points");
        if ring.hole_of == HIBI_RING_NOT_A_HOLE {
            assert!(ring.area > 0.0, "outer ring {i}: {ring:?}");
        } else if ring.hole_of == HIBI_MUD_IN_WRAPPING_CELL {
            assert!(wrapping_cells && ring.area < 0.0, "hole {i} in a wrapping cell: {ring:?}");
        } else {
            let outer = rings.get(ring.hole_of as usize).unwrap_or_else(|| panic!("ring {i}: {ring:?}"));
            assert!(ring.area < 0.0 && outer.hole_of == HIBI_RING_NOT_A_HOLE, "hole {i}: {ring:?} in {outer:?}");
        }
    }
}

/// The pieces a physics engine takes, cut from `rings` over `points` through the C API: every
/// triangle counter-clockwise, every convex piece strictly convex with 3 to 8 points, and each
/// polygon's triangles and pieces adding up to its outer ring's area minus its holes' (within
/// 10⁻⁶ of the outer ring's area, or 10⁻⁹ of the plate's for a sliver); returns the pieces'
/// total area.
fn pieces_add_up(rings: &[Ring], points: &[hibi_vec2], plate: f64, may_cross: bool) -> f64 {
    let (rp, pp) = (rings.as_ptr(), points.as_ptr());
    let (mut words, mut triangles, mut pieces, mut written) = (0, 0, 0, 0);
    // SAFETY: valid buffers of the lengths passed.
    unsafe {
        assert_eq!(hibi_pieces_scratch_size(rp, rings.len(), pp, points.len(), &mut words), HIBI_OK);
        let mut scratch = vec![0u32; words];
        let s = scratch.as_mut_ptr();
        let status = hibi_pieces_counts(rp, rings.len(), pp, points.len(), s, words, &mut triangles, &mut pieces);
        // A polygon whose rings cross (`may_cross`: mud's cells can where a strongly deformed
        // lattice folds over, a mesh cell turned inside out, a known defect of the cells) or
        // pass the same point twice (a ring run out and back along a crack) has no proper
        // interior for pieces to cover: it may be refused, and only then; every simple
        // polygon's pieces must add up.
        let at = |i: u32| [f64::from(points[i as usize].x), f64::from(points[i as usize].y)];
        let twice =
            |a: [f64; 2], b: [f64; 2], c: [f64; 2]| (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        let simple = |r: &Ring| {
            let q: Vec<[f64; 2]> = (r.first_point..r.first_point + r.point_count).map(at).collect();
            let n = q.len();
            let crosses = |a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]| {
                let (d1, d2) = (twice(a, b, c), twice(a, b, d));
                let (d3, d4) = (twice(c, d, a), twice(c, d, b));
                d1 * d2 < 0.0 && d3 * d4 < 0.0
            };
            let twice_through = (0..n).any(|i| (i + 1..n).any(|j| q[i] == q[j]));
            !twice_through
                && (0..n).all(|i| {
                    (i + 2..n).all(|j| (i == 0 && j == n - 1) || !crosses(q[i], q[(i + 1) % n], q[j], q[(j + 1) % n]))
                })
        };
        if status == HIBI_ERROR_RING_CROSSES && may_cross {
            assert!(!rings.iter().all(simple), "pieces refused rings none of which crosses itself");
            return plate;
        }
        assert_eq!(status, HIBI_OK);
        let mut tri = vec![Triangle::default(); triangles];
        let status =
            hibi_triangulate(rp, rings.len(), pp, points.len(), s, words, tri.as_mut_ptr(), triangles, &mut written);
        assert_eq!((status, written), (HIBI_OK, triangles));
        let mut convex = vec![ConvexPiece::default(); pieces];
        let status =
            hibi_convex_pieces(rp, rings.len(), pp, points.len(), s, words, convex.as_mut_ptr(), pieces, &mut written);
        assert_eq!((status, written), (HIBI_OK, pieces));
        let (mut by_triangle, mut by_piece) = (vec![0.0; rings.len()], vec![0.0; rings.len()]);
        for t in &tri {
            let [a, b, c] = t.points.map(at);
            assert!(twice(a, b, c) > 0.0, "{t:?}");
            by_triangle[t.ring as usize] += twice(a, b, c) / 2.0;
        }
        for piece in &convex {
            let n = piece.point_count as usize;
            assert!((3..=HIBI_PIECE_MAX_POINTS as usize).contains(&n), "{piece:?}");
            let q: Vec<[f64; 2]> = piece.points[..n].iter().map(|&i| at(i)).collect();
            for j in 0..n {
                assert!(twice(q[j], q[(j + 1) % n], q[(j + 2) % n]) > 0.0, "not strictly convex: {q:?}");
                by_piece[piece.ring as usize] += twice([0.0; 2], q[j], q[(j + 1) % n]) / 2.0;
            }
        }
        for (i, ring) in rings.iter().enumerate().filter(|(_, r)| r.hole_of == HIBI_RING_NOT_A_HOLE) {
            if !simple(ring) || rings.iter().any(|h| h.hole_of as usize == i && !simple(h)) {
                continue;
            }
            let want = ring.area + rings.iter().filter(|h| h.hole_of as usize == i).map(|h| h.area).sum::<f64>();
            let tolerance = 1e-6 * ring.area.abs() + 1e-9 * plate;
            assert!((by_triangle[i] - want).abs() <= tolerance, "ring {i}: triangles {} of {want}", by_triangle[i]);
            assert!((by_piece[i] - want).abs() <= tolerance, "ring {i}: pieces {} of {want}", by_piece[i]);
        }
        by_piece.iter().sum()
    }
}

fn mud_outputs_in_range(mud: &Mud, end: &hibi_mud_progress, render: &hibi_mud_render_params) {
    let mut n = 0;
    // SAFETY (every call below): a live run, buffers of the lengths passed.
    unsafe {
        assert_eq!(hibi_mud_segment_count(mud.0, &mut n), HIBI_OK);
        let mut segments = vec![CrackSegment::default(); n];
        let mut written = 0;
        assert_eq!(hibi_mud_segments(mud.0, segments.as_mut_ptr(), n, &mut written), HIBI_OK);
        let in_time = |t: f32| (0.0..=end.time).contains(&t);
        for s in &segments {
            assert!(finite(&[s.start[0], s.start[1], s.end[0], s.end[1], s.width[0], s.width[1]]), "{s:?}");
            assert!(s.time.iter().all(|&t| in_time(t)), "{s:?} after a run of {}", end.time);
        }
        let (mut v, mut e, mut p) = (0, 0, 0);
        assert_eq!(hibi_mud_network_counts(mud.0, &mut v, &mut e, &mut p), HIBI_OK);
        let mut vertices = vec![NetworkVertex::default(); v];
        let mut edges = vec![NetworkEdge::default(); e];
        let mut points = vec![NetworkPoint::default(); p];
        let (mut a, mut b, mut c) = (0, 0, 0);
        let status = hibi_mud_network(
            mud.0,
            vertices.as_mut_ptr(),
            v,
            edges.as_mut_ptr(),
            e,
            points.as_mut_ptr(),
            p,
            &mut a,
            &mut b,
            &mut c,
        );
        assert_eq!(status, HIBI_OK);
        assert!(vertices.iter().all(|x| finite(&x.at)));
        assert!(points.iter().all(|x| finite(&[x.at[0], x.at[1], x.width]) && in_time(x.time)));
        let mut degree = vec![0u32; v];
        for (i, edge) in edges.iter().enumerate() {
            assert!(edge.point_count >= 2 && (edge.first_point + edge.point_count) as usize <= p, "edge {i}: {edge:?}");
            for end in [edge.from, edge.to] {
                if end != HIBI_MUD_NO_VERTEX {
                    *degree.get_mut(end as usize).unwrap_or_else(|| panic!("edge {i}: {edge:?} of {v} vertices")) += 1;
                }
            }
            assert_eq!(edge.from == HIBI_MUD_NO_VERTEX, edge.to == HIBI_MUD_NO_VERTEX, "edge {i}: {edge:?}");
        }
        for (i, vertex) in vertices.iter().enumerate() {
            assert_eq!(vertex.degree, degree[i], "vertex {i}: {vertex:?}");
            assert!(vertex.degree == 1 || vertex.degree >= 3, "vertex {i}: {vertex:?}");
        }
        let (mut r, mut q, mut wrapping) = (0, 0, 0);
        assert_eq!(hibi_mud_cell_counts(mud.0, &mut r, &mut q, &mut wrapping), HIBI_OK);
        let mut rings = vec![Ring::default(); r];
        let mut ring_points = vec![hibi_vec2::default(); q];
        let status = hibi_mud_cells(mud.0, rings.as_mut_ptr(), r, ring_points.as_mut_ptr(), q, &mut a, &mut b);
        assert_eq!(status, HIBI_OK);
        assert!(rings.iter().all(|x| x.area.is_finite()));
        assert!(ring_points.iter().all(|x| finite(&[x.x, x.y])));
        rings_are_consistent(&rings, q, mud.1);
        let mut extent = hibi_vec2::default();
        assert_eq!(hibi_mud_extent(mud.0, &mut extent), HIBI_OK);
        pieces_add_up(&rings, &ring_points, f64::from(extent.x) * f64::from(extent.y), true);
        let mut stats = hibi_mud_crack_statistics::default();
        assert_eq!(hibi_mud_statistics(mud.0, &mut stats), HIBI_OK);
        let s = stats;
        // Every cell is counted: each outer ring, and a cell that wraps if a hole is in one.
        let outer = rings.iter().filter(|x| x.hole_of == HIBI_RING_NOT_A_HOLE).count();
        let wrapped = usize::from(rings.iter().any(|x| x.hole_of == HIBI_MUD_IN_WRAPPING_CELL) || wrapping > 0);
        assert!(
            s.cells as usize >= outer + wrapped,
            "{} cells counted, {outer} outer rings, {wrapped} wrapping: {rings:?}",
            s.cells
        );
        assert!(finite(&[s.crack_density, s.mean_cell_area, s.cell_area_spread, s.mean_widest_junction_angle]));
        let pixels = (render.width * render.height) as usize;
        let mut mask = vec![0u8; pixels];
        assert_eq!(hibi_mud_render(mud.0, render, HIBI_MUD_LAYER_MASK, mask.as_mut_ptr().cast(), pixels), HIBI_OK);
        let mut height = vec![0f32; pixels];
        let status = hibi_mud_render(mud.0, render, HIBI_MUD_LAYER_HEIGHT, height.as_mut_ptr().cast(), pixels);
        assert_eq!(status, HIBI_OK);
        // 1 on the surface, down to 1 − groove_depth in the widest crack (f32 rounding aside).
        let deepest = 1.0 - render.groove_depth - 1e-5;
        assert!(height.iter().all(|&h| (deepest..=1.0).contains(&h)), "height layer outside [{deepest}, 1]");
        let mut time = vec![0f32; pixels];
        let status = hibi_mud_render(mud.0, render, HIBI_MUD_LAYER_TIME, time.as_mut_ptr().cast(), pixels);
        assert_eq!(status, HIBI_OK);
        mask_and_time_agree(&mask, &time, end.time);
        if n == 0 {
            // No crack: a blank mask, no break times, a flat surface.
            assert!(mask.iter().all(|&m| m == 0) && height.iter().all(|&h| h == 1.0));
        }
    }
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn mud_outputs_in_range_steps_bounded_memory_exact(
        p in mud_params(),
        budget in 0u64..5000,
        render in mud_render(),
    ) {
        prop_assume!(mud_accepts(&p), "refused: {:?}", p);
        memory_is_exact(&p, hibi_mud_memory_size, hibi_mud_create_in);
        // Budget 1 and the random budget each keep to the bound, and end alike.
        let single = Mud::new(&p);
        let end = single.run(1, &p);
        let mud = Mud::new(&p);
        let other = mud.run(budget, &p);
        prop_assert_eq!((other.work, other.broken_springs), (end.work, end.broken_springs), "the budget changed the run");
        mud_outputs_in_range(&mud, &other, &render);
    }
}

/// A run the property test found: on an irregular lattice with the explicit solver and growth,
/// a cell's hole runs out and back along a crack, passing the same points twice. Its pieces
/// are refused by name (`HIBI_ERROR_RING_CROSSES`); every other output keeps its bounds.
#[test]
fn a_hole_that_passes_a_point_twice_is_refused_by_the_pieces_by_name() {
    let mut p = hibi_mud_params_default();
    (p.topology, p.boundary, p.solver, p.drive, p.columns, p.rows) = (2, 0, 1, 1, 13, 18);
    p.seed = 11846520712649192639;
    (p.layer_thickness, p.element_size, p.long_step, p.short_step) = (1.472012, 1.2452421, 0.5, 0.001067449);
    (p.shrink_ratio, p.displacement_tolerance, p.damping_factor) = (0.99, 0.00018576381, 12.691394);
    (p.density, p.young_modulus, p.shear_modulus) = (1.6275991, 1153002.9, 361531.47);
    (p.break_stretch_mean, p.break_stretch_spread, p.break_stretch_size_exponent) = (1.2158769, 0.04924649, 0.9566485);
    (p.anisotropy_direction, p.anisotropy_ratio, p.stiffness_anisotropy_ratio) = (-0.42801565, 1.8092309, 1.0918131);
    (p.target_shrink, p.target_crack_density) = (0.100105345, 0.0);
    let render = hibi_mud_render_params {
        width: 47,
        height: 29,
        width_scale: 0.10144923,
        min_width: 1.9324046,
        groove_depth: 0.70342004,
        offset: [19.105711, 19.305775],
        bump: 2.0,
        until: f32::INFINITY,
    };
    let mud = Mud::new(&p);
    let end = mud.run(1044, &p);
    mud_outputs_in_range(&mud, &end, &render);
}

// ---------------------------------------------------------------------------------------
// Model B: glass

prop_compose! {
    fn glass_params()(
        width in 40f32..160.0,
        height in 40f32..160.0,
        impact in (0.05f32..0.95, 0.05f32..0.95),
        seed in any::<u64>(),
        radial_mean in 0f32..150.0,
        speeds in (5f32..60.0, 2f32..20.0, 2f32..20.0),
        spread in 0u32..2,
        wander in 0f32..1.5,
        max_cracks in 8u32..512,
        max_vertices in 64u32..8192,
        // Table 1's fits, the ring threshold and radii, about the paper's.
        counts in (0.03f32..0.12, 0f32..6.0, 0.02f32..0.1, 0f32..1.0, 30f32..120.0),
        radii in (0.2f32..0.8, 5f32..30.0),
        // The turn limit and delay, the sector S, the forces and the ring adherence.
        turns in (0.1f32..1.0, 1f32..20.0, 0.3f32..0.5),
        sector in (0.8f32..2.6, 10f32..100.0),
        forces in (0f32..1000.0, 0f32..1000.0, 0f32..4.0),
    ) -> hibi_glass_params {
        let mut p = hibi_glass_params_default();
        (p.width, p.height) = (width, height);
        p.impact = [impact.0 * width, impact.1 * height];
        p.seed = seed;
        p.radial_mean = radial_mean;
        (p.large_speed, p.radial_speed, p.ring_speed) = speeds;
        p.spread = spread;
        p.wander = wander;
        (p.max_cracks, p.max_vertices) = (max_cracks, max_vertices);
        (p.large_slope, p.large_offset, p.ring_slope, p.ring_offset, p.ring_threshold) = counts;
        (p.ring_radius_slope, p.ring_radius_offset) = radii;
        (p.turn_limit, p.turn_delay, p.spread_ratio) = turns;
        (p.sector_angle, p.sector_radius) = sector;
        (p.tip_repulsion, p.crack_attraction, p.ring_adherence) = forces;
        p
    }
}

/// The Rust params the C library makes of `p` (field for field).
fn glass_core(p: &hibi_glass_params) -> GlassParams {
    GlassParams {
        width: p.width,
        height: p.height,
        impact: p.impact,
        seed: p.seed,
        radial_mean: p.radial_mean,
        large_speed: p.large_speed,
        radial_speed: p.radial_speed,
        ring_speed: p.ring_speed,
        spread: if p.spread == HIBI_SPREAD_NORMAL { hibi_core::Spread::Normal } else { hibi_core::Spread::Uniform },
        wander: p.wander,
        max_cracks: p.max_cracks,
        max_vertices: p.max_vertices,
        large_slope: p.large_slope,
        large_offset: p.large_offset,
        ring_slope: p.ring_slope,
        ring_offset: p.ring_offset,
        ring_threshold: p.ring_threshold,
        ring_radius_slope: p.ring_radius_slope,
        ring_radius_offset: p.ring_radius_offset,
        turn_limit: p.turn_limit,
        turn_delay: p.turn_delay,
        spread_ratio: p.spread_ratio,
        sector_angle: p.sector_angle,
        sector_radius: p.sector_radius,
        tip_repulsion: p.tip_repulsion,
        crack_attraction: p.crack_attraction,
        ring_adherence: p.ring_adherence,
    }
}

/// Steps `glass` with `budget` to the end; returns the largest work a call did.
fn glass_run(glass: &mut Glass, budget: u64, piece: u64) -> u64 {
    let mut largest = 0;
    loop {
        let before = glass.progress().work;
        let progress = glass.step(budget);
        let done = glass.progress().work - before;
        assert!(
            done <= budget.saturating_sub(1) + piece,
            "a step with budget {budget} did {done} work (largest piece {piece})"
        );
        largest = largest.max(done);
        if progress.finished {
            return largest;
        }
    }
}

prop_compose! {
    fn glass_render()(width in 8u32..=48, height in 8u32..=48, line_width in 0.3f32..3.0) -> hibi_glass_render_params {
        let mut r = hibi_glass_render_params_default();
        (r.width, r.height, r.line_width) = (width, height, line_width);
        r
    }
}

/// Runs the plate of `p` through the C ABI and checks its outputs; `end` is where the same
/// plate ends in the Rust API (`hibi_glass_step` writes no progress once a capacity ran out).
fn glass_outputs_in_range(p: &hibi_glass_params, end: &GlassProgress, render: &hibi_glass_render_params) {
    let mut glass = core::ptr::null_mut();
    // SAFETY (every call below): valid pointers, buffers of the lengths passed.
    unsafe {
        assert_eq!(hibi_glass_create(p, &mut glass), HIBI_OK);
        let mut progress = hibi_glass_progress::default();
        while progress.finished == 0 {
            let status = hibi_glass_step(glass, 100_000, &mut progress);
            if status == HIBI_ERROR_GLASS_CAPACITY {
                assert!(end.capacity_reached, "C ran out of capacity, Rust did not");
                break;
            }
            assert_eq!(status, HIBI_OK);
        }
        if progress.finished == 1 {
            assert_eq!((progress.time, progress.cracks), (end.time, end.cracks), "C and Rust differ");
        }
        // A time step stamps its pieces with times in (t, t + 1] and counts itself once it is
        // complete; a capacity that runs out stops the plate inside a step, whose pieces then
        // reach up to one step past `time`. (Times are f32 sums of steps and fractions: the
        // slack is rounding.)
        let end_time = end.time as f32 + if end.capacity_reached { 1.0 } else { 0.0 };
        let end_time = end_time + 1e-5 * (1.0 + end_time);
        let mut cracks = 0;
        assert_eq!(hibi_glass_crack_count(glass, &mut cracks), HIBI_OK);
        for i in 0..cracks {
            let mut info = hibi_glass_crack::default();
            assert_eq!(hibi_glass_crack_info(glass, i, &mut info), HIBI_OK);
            assert!(info.kind <= HIBI_GLASS_KIND_RING_CLOCKWISE && info.end <= HIBI_GLASS_END_ENCLOSED, "{info:?}");
            assert_eq!(info.impact, 0, "crack {i}: one impact");
            if !end.capacity_reached {
                assert_ne!(info.end, HIBI_GLASS_END_GROWING, "crack {i} still grows after the end");
            }
            let mut points = vec![CrackPoint::default(); info.points as usize];
            let mut written = 0;
            assert_eq!(hibi_glass_points(glass, i, points.as_mut_ptr(), points.len(), &mut written), HIBI_OK);
            assert_eq!(written, points.len());
            assert!(points.iter().all(|x| finite(&[x.at[0], x.at[1]])), "crack {i}");
            let inside = |x: &CrackPoint| (0.0..=p.width).contains(&x.at[0]) && (0.0..=p.height).contains(&x.at[1]);
            assert!(points.iter().all(inside), "crack {i} leaves the plate");
            assert!(
                points.iter().all(|x| (0.0..=end_time).contains(&x.time)),
                "crack {i}: time past {end_time}: {points:?}"
            );
        }
        let mut size = 0;
        assert_eq!(hibi_glass_scratch_size(glass, &mut size), HIBI_OK);
        let mut scratch = block(size);
        let (mut r, mut q) = (0, 0);
        let status = hibi_glass_fragment_counts(glass, scratch.as_mut_ptr().cast(), size - 1, &mut r, &mut q);
        assert_eq!(status, HIBI_ERROR_BUFFER_TOO_SMALL, "scratch one byte short");
        let status = hibi_glass_fragment_counts(glass, scratch.as_mut_ptr().cast(), size, &mut r, &mut q);
        assert_eq!(status, HIBI_OK);
        let mut rings = vec![Ring::default(); r];
        let mut points = vec![hibi_vec2::default(); q];
        let (mut a, mut b) = (0, 0);
        let status = hibi_glass_fragments(
            glass,
            scratch.as_mut_ptr().cast(),
            size,
            rings.as_mut_ptr(),
            r,
            points.as_mut_ptr(),
            q,
            &mut a,
            &mut b,
        );
        assert_eq!(status, HIBI_OK);
        assert!(rings.iter().all(|x| x.area.is_finite()));
        assert!(points.iter().all(|x| finite(&[x.x, x.y])));
        rings_are_consistent(&rings, q, false);
        // The fragments cover the plate: outer rings add their area, holes take theirs off.
        let covered: f64 = rings.iter().map(|x| x.area).sum();
        let plate = f64::from(p.width) * f64::from(p.height);
        assert!(
            ((covered - plate) / plate).abs() <= 1e-4,
            "fragments cover {covered} of a {plate} plate ({} rings)",
            rings.len()
        );
        let pieces = pieces_add_up(&rings, &points, plate, false);
        assert!(((pieces - plate) / plate).abs() <= 1e-4, "the pieces cover {pieces} of a {plate} plate");
        let pixels = (render.width * render.height) as usize;
        let mut mask = vec![0u8; pixels];
        let status = hibi_glass_render(glass, render, HIBI_GLASS_LAYER_MASK, mask.as_mut_ptr().cast(), pixels);
        assert_eq!(status, HIBI_OK);
        let mut time = vec![0f32; pixels];
        let status = hibi_glass_render(glass, render, HIBI_GLASS_LAYER_TIME, time.as_mut_ptr().cast(), pixels);
        assert_eq!(status, HIBI_OK);
        mask_and_time_agree(&mask, &time, end_time);
        hibi_glass_destroy(glass);
    }
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn glass_outputs_in_range_steps_bounded_memory_exact(
        p in glass_params(),
        budget in 0u64..5000,
        render in glass_render(),
    ) {
        memory_is_exact(&p, hibi_glass_memory_size, hibi_glass_create_in);
        let params = glass_core(&p);
        let mut single_memory = params.memory().expect("valid").allocate();
        let mut single = Glass::new(&params, single_memory.buffers()).expect("valid");
        let piece = glass_run(&mut single, 1, u64::MAX);
        // The largest piece, whatever the floats: a grid cell or entry a query examines, a
        // crack looked at, a step of a face walk (two in lockstep).
        prop_assert!(piece <= HIBI_GLASS_STEP_PIECE, "a glass piece did {} work, over {}", piece, HIBI_GLASS_STEP_PIECE);
        glass_outputs_in_range(&p, &single.progress(), &render);
        let mut memory = params.memory().expect("valid").allocate();
        let mut glass = Glass::new(&params, memory.buffers()).expect("valid");
        glass_run(&mut glass, budget, piece);
        prop_assert_eq!(glass.progress().work, single.progress().work, "the budget changed the run");
        prop_assert_eq!(glass.progress(), single.progress());
    }
}

// ---------------------------------------------------------------------------------------
// Model C: skin

prop_compose! {
    fn skin_params()(
        size in (16u32..=64, 16u32..=64),
        layout in 0u32..3,
        jitter in 0u32..2,
        periodic in 0u32..2,
        seed in any::<u64>(),
        jitter_ratio in 0f32..=1.0,
        levels in 1u32..=3,
        spacing in 8f32..30.0,
        perturbation in 0f32..0.5,
        depth in 0u32..=3,
        stretch in (0.7f32..1.5, 0.7f32..1.5),
        roundness in 0f32..=1.0,
        heights in prop::array::uniform13(-4f32..4.0),
    ) -> hibi_skin_params {
        let mut p = hibi_skin_params_default();
        (p.width, p.height) = size;
        (p.layout, p.jitter, p.periodic) = (layout, jitter, periodic);
        p.seed = seed;
        p.jitter_ratio = jitter_ratio;
        p.levels = levels;
        for (k, level) in p.level.iter_mut().enumerate() {
            level.spacing = (spacing / 3f32.powi(k as i32)).max(2.0);
            level.perturbation = perturbation;
            level.perturbation_depth = depth.saturating_sub(k as u32);
            level.stretch = [stretch.0, stretch.1];
            level.roundness = roundness;
            // The default profile's x', random heights (smaller at the finer levels).
            for (point, z) in level.profile.points.iter_mut().zip(heights) {
                point[1] = z / (k + 1) as f32;
            }
        }
        p
    }
}

/// The range the height map keeps to: per level, the lowest and highest z' of the profile's
/// control points (a cubic Bézier stays in the hull of its control points, and the sampled
/// table is linear between samples), summed over the levels.
fn skin_height_bounds(p: &hibi_skin_params) -> (f32, f32) {
    p.level[..p.levels as usize].iter().fold((0.0, 0.0), |(low, high), level| {
        let used = &level.profile.points[..3 * level.profile.segments as usize + 1];
        let z = used.iter().map(|point| point[1]);
        (low + z.clone().fold(f32::INFINITY, f32::min), high + z.fold(f32::NEG_INFINITY, f32::max))
    })
}

struct Skin(*mut hibi_skin);

impl Skin {
    fn new(p: &hibi_skin_params) -> Skin {
        let mut skin = core::ptr::null_mut();
        // SAFETY: valid pointers.
        assert_eq!(unsafe { hibi_skin_create(p, &mut skin) }, HIBI_OK);
        Skin(skin)
    }

    /// Steps with `budget` to the end; returns the largest work a call did and the end.
    fn run(&self, budget: u64, piece: u64) -> (u64, hibi_skin_progress) {
        let (mut work, mut largest) = (0, 0);
        loop {
            let mut progress = hibi_skin_progress::default();
            // SAFETY: a live skin.
            let status = unsafe { hibi_skin_step(self.0, budget, &mut progress) };
            assert!(status == HIBI_OK || status == HIBI_ERROR_SKIN_CAPACITY, "{status}");
            if status != HIBI_OK {
                return (largest, hibi_skin_progress { capacity_reached: 1, ..progress });
            }
            let done = progress.work - work;
            assert!(
                done <= budget.saturating_sub(1) + piece,
                "a step with budget {budget} did {done} work (largest piece {piece})"
            );
            largest = largest.max(done);
            work = progress.work;
            if progress.finished == 1 {
                return (largest, progress);
            }
        }
    }
}

impl Drop for Skin {
    fn drop(&mut self) {
        // SAFETY: a live skin, not used afterwards.
        unsafe { hibi_skin_destroy(self.0) };
    }
}

fn skin_outputs_in_range(skin: &Skin, p: &hibi_skin_params, end: &hibi_skin_progress, cell_level: u32) {
    // SAFETY (every call below): a live skin, buffers of the lengths passed.
    unsafe {
        let mut cells = 0;
        assert_eq!(hibi_skin_cell_count(skin.0, &mut cells), HIBI_OK);
        let mut levels = vec![0; cells];
        for i in 0..cells {
            let mut cell = hibi_skin_cell::default();
            assert_eq!(hibi_skin_cell_info(skin.0, i, &mut cell), HIBI_OK);
            levels[i] = cell.level;
            assert!(cell.level < p.levels, "cell {i}: {cell:?}");
            if cell.level == 0 {
                assert_eq!(cell.parent, HIBI_SKIN_NO_CELL, "cell {i}: {cell:?}");
            } else {
                // Parents come before their children (Skin::cells).
                assert!((cell.parent as usize) < i && levels[cell.parent as usize] + 1 == cell.level, "{i}: {cell:?}");
            }
            assert!(cell.centre.iter().all(|c| c.is_finite()));
            let mut xy = vec![0f64; 2 * cell.vertex_count as usize];
            let mut written = 0;
            assert_eq!(hibi_skin_outline(skin.0, i, xy.as_mut_ptr(), xy.len(), &mut written), HIBI_OK);
            assert!(xy.iter().all(|c| c.is_finite()), "cell {i}");
        }
        let pixels = (p.width * p.height) as usize;
        let (mut height, mut normal, mut map) = (vec![0f32; pixels], vec![0f32; 3 * pixels], vec![0u32; pixels]);
        let render = hibi_skin_render_params { cell_level, ..hibi_skin_render_params_default() };
        let layers = [
            (HIBI_SKIN_LAYER_HEIGHT, height.as_mut_ptr().cast(), pixels),
            (HIBI_SKIN_LAYER_NORMAL, normal.as_mut_ptr().cast(), 3 * pixels),
            (HIBI_SKIN_LAYER_CELLS, map.as_mut_ptr().cast(), pixels),
        ];
        for (layer, pixels, len) in layers {
            assert_eq!(hibi_skin_render(skin.0, &render, layer, pixels, len), HIBI_OK, "layer {layer}");
        }
        // Pixels in no built cell (a build that ran out of capacity) are flat at height 0.
        let (low, high) = skin_height_bounds(p);
        let (low, high) = if end.finished == 1 { (low, high) } else { (low.min(0.0), high.max(0.0)) };
        let slack = 1e-5 * (1.0 + low.abs().max(high.abs()));
        assert!(
            height.iter().all(|&h| h >= low - slack && h <= high + slack),
            "height map outside [{low}, {high}]: {:?}",
            height.iter().fold((f32::INFINITY, f32::NEG_INFINITY), |(a, b), &h| (a.min(h), b.max(h)))
        );
        for (i, n) in normal.chunks_exact(3).enumerate() {
            let length = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            assert!((length - 1.0).abs() <= 2e-6 && n[2] > 0.0, "pixel {i}: normal {n:?}, length {length}");
        }
        for (i, &c) in map.iter().enumerate() {
            if c == HIBI_SKIN_NO_CELL {
                // Across the cells of one level every pixel is drawn once the build is done.
                assert!(end.finished == 0, "pixel {i} is in no cell of level {cell_level}");
            } else {
                assert!((c as usize) < cells && levels[c as usize] == cell_level, "pixel {i}: cell {c}");
            }
        }
    }
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn skin_outputs_in_range_steps_bounded_memory_exact(
        p in skin_params(),
        budget in 0u64..3000,
        cell_level in 0u32..3,
    ) {
        memory_is_exact(&p, hibi_skin_memory_size, hibi_skin_create_in);
        let single = Skin::new(&p);
        let (piece, end) = single.run(1, u64::MAX);
        // The largest piece is a cell: its outline's vertices and the unit of its centre
        // point (a division's pieces, a centre point tried or a piece of bucketing, are one
        // unit each).
        let bound = hibi_core::skin::MAX_OUTLINE as u64 + 1;
        prop_assert!(piece <= bound, "a skin piece did {} work, over its bound {}", piece, bound);
        let skin = Skin::new(&p);
        let (_, other) = skin.run(budget, piece);
        prop_assert_eq!((other.cells, other.capacity_reached), (end.cells, end.capacity_reached), "the budget changed the build");
        if end.capacity_reached == 0 {
            prop_assert_eq!(other.work, end.work);
        }
        skin_outputs_in_range(&skin, &p, &other, cell_level % p.levels);
    }
}
