//! Time is bounded by what the caller asked, measured as work, not time.
//!
//! Extreme values (glass ring counts of 1e30, a mud `shrink_ratio` just below 1,
//! `break_stretch_mean` 1e30, speeds of 1e30 and 1e-30, huge perturbations, `u64::MAX`
//! budgets) are valid parameters: for each, the memory (what creation lays out and fills) is
//! the same as for ordinary values of those fields, every step call's work (the models' own
//! `work` counters, in the units of the budget) stays within its budget plus one indivisible
//! piece bounded by the model's size and capacities, and a render of a fixed size completes.
//! NaN and infinity in every float field, and the out-of-range ends, are refused through the C
//! ABI with the field's status, nothing written.
//!
//! Each glass plate's fragments are then built in steps of the same budgets (`FragmentBuild`),
//! each call within its budget and one step of a face walk.
//!
//! Create and render report no work count: `tests/c_examples.rs`
//! (`c_create_and_render_work_does_not_grow_with_extreme_floats`) counts their instructions
//! under Callgrind instead, extreme values against moderate twins of the same sizes.

use hibi::*;
use hibi_core::glass::{FragmentBuild, Glass, GlassLayers, GlassParams, GlassRender};
use hibi_core::mud::{Mud, MudLayers, MudParams, MudRender, Solver};
use hibi_core::polygon::Ring;
use hibi_core::skin::{Skin, SkinLayers, SkinParams, SkinRender};

/// An extreme value: its name and how to set it.
type Extreme<P> = (&'static str, fn(&mut P));

/// The budget of every bounded step call below.
const BUDGET: u64 = 20_000;
/// Step calls per case (a run may need more; each call is what is bounded).
const CALLS: usize = 40;

/// Steps `step` up to [`CALLS`] times with `budget`; asserts each call's work is within
/// `budget` less one plus `piece` (mud's tracing of the network included). Returns the work
/// done and whether the run finished.
fn bounded(name: &str, budget: u64, piece: u64, mut step: impl FnMut(u64) -> (u64, bool)) -> (u64, bool) {
    let (mut total, mut finished) = (0, false);
    for _ in 0..CALLS {
        let (work, done) = step(budget);
        assert!(
            work <= budget.saturating_sub(1) + piece,
            "{name}: a call with budget {budget} did {work} work (piece bound {piece})"
        );
        total += work;
        finished = done;
        if done {
            break;
        }
    }
    (total, finished)
}

// ---------------------------------------------------------------------------------------
// Mud

fn mud_base(solver: Solver) -> MudParams {
    MudParams { columns: 10, rows: 10, solver, ..MudParams::default() }
}

/// Valid extreme values of the mud fields.
fn mud_extremes() -> Vec<Extreme<MudParams>> {
    vec![
        ("shrink_ratio just below 1", |p| p.shrink_ratio = 0.999_999_94),
        ("break_stretch_mean 1e30", |p| p.break_stretch_mean = 1e30),
        ("break_stretch_mean just above 1", |p| p.break_stretch_mean = 1.000_000_1),
        ("target_shrink just below 1", |p| p.target_shrink = 0.999_999_94),
        ("target_crack_density 1e30", |p| p.target_crack_density = 1e30),
        ("anisotropy_ratio 1e30", |p| p.anisotropy_ratio = 1e30),
        ("anisotropy_direction 1e30", |p| p.anisotropy_direction = 1e30),
        ("stiffness_anisotropy_ratio 1e6", |p| p.stiffness_anisotropy_ratio = 1e6),
        ("break_stretch_size_exponent 1 at a tiny element", |p| {
            p.break_stretch_size_exponent = 1.0;
            p.element_size = 1e-3;
            p.layer_thickness = 1e-3;
            p.short_step = 1e-6;
        }),
    ]
}

fn mud_case(name: &str, params: &MudParams, budget: u64) -> (u64, bool) {
    let base = mud_base(params.solver).memory().expect("valid");
    let memory = params.memory().unwrap_or_else(|e| panic!("{name}: {e}"));
    assert_eq!((memory.scalars, memory.words), (base.scalars, base.words), "{name}: the memory follows the size only");
    let mut store = memory.allocate();
    let mut mud = Mud::<f32>::new(params, store.buffers()).unwrap_or_else(|e| panic!("{name}: {e:?}"));
    // One piece: a row's springs in one direction and their rescan for breaks (explicit),
    // one node's springs (quasi-static, 6 on the hexagonal lattice), or a piece of the
    // network's tracing; no call does more.
    let piece = match params.solver {
        Solver::Explicit => 2 * u64::from(params.columns),
        Solver::QuasiStatic => 6,
    }
    .max(hibi_core::mud::TRACE_PIECE);
    let mut work = 0;
    let result = bounded(name, budget, piece, |b| {
        let progress = mud.step(b).unwrap();
        let done = progress.work - work;
        work = progress.work;
        (done, progress.finished)
    });
    let mut mask = vec![0u8; 32 * 32];
    let render = MudRender { width: 32, height: 32, ..MudRender::default() };
    mud.render(&render, MudLayers { mask: Some(&mut mask), ..MudLayers::default() }).expect("renders");
    result
}

#[test]
fn mud_extremes_step_within_their_budgets() {
    for solver in [Solver::QuasiStatic, Solver::Explicit] {
        for (name, set) in mud_extremes() {
            let mut params = mud_base(solver);
            set(&mut params);
            for budget in [0, 1, BUDGET] {
                mud_case(&format!("{solver:?}, {name}"), &params, budget);
            }
        }
    }
}

/// A budget of `u64::MAX` runs to the end, and the end is bounded by the lattice: no spring
/// breaks before the target shrink with `break_stretch_mean` 1e30, so the quasi-static run is
/// a few sweeps of the springs. After the end, any budget does no work.
#[test]
fn mud_huge_budgets_end_within_the_lattice_work() {
    let mut params = mud_base(Solver::QuasiStatic);
    params.break_stretch_mean = 1e30;
    let mut store = params.memory().expect("valid").allocate();
    let mut mud = Mud::<f32>::new(&params, store.buffers()).expect("valid");
    let springs = mud.lattice().spring_count() as u64;
    let end = mud.step(u64::MAX).unwrap();
    assert!(end.finished && end.broken_springs == 0, "{end:?}");
    assert!(end.work <= 64 * springs, "{} work for {springs} springs", end.work);
    for budget in [u64::MAX, 0, 1] {
        assert_eq!(mud.step(budget).unwrap().work, end.work, "a finished run does no more work");
    }
}

// ---------------------------------------------------------------------------------------
// Glass

fn glass_base() -> GlassParams {
    GlassParams {
        width: 128.0,
        height: 128.0,
        impact: [64.0, 64.0],
        max_cracks: 128,
        max_vertices: 2048,
        ..GlassParams::default()
    }
}

fn glass_extremes() -> Vec<Extreme<GlassParams>> {
    vec![
        ("ring_slope 1e30", |p| p.ring_slope = 1e30),
        ("ring_offset 1e30", |p| p.ring_offset = 1e30),
        ("large_slope 1e30", |p| p.large_slope = 1e30),
        ("large_offset 1e30", |p| p.large_offset = 1e30),
        ("radial_mean 10000", |p| p.radial_mean = 10_000.0),
        ("ring_threshold -1e30", |p| p.ring_threshold = -1e30),
        ("ring_radius_slope 1e30", |p| p.ring_radius_slope = 1e30),
        ("speeds 1e30", |p| (p.large_speed, p.radial_speed, p.ring_speed) = (1e30, 1e30, 1e30)),
        ("speeds 1e-30", |p| (p.large_speed, p.radial_speed, p.ring_speed) = (1e-30, 1e-30, 1e-30)),
        ("sector_radius 1e30", |p| p.sector_radius = 1e30),
        ("turn_delay 1e-30", |p| p.turn_delay = 1e-30),
        ("turn_delay 1e30", |p| p.turn_delay = 1e30),
        ("forces 1e30", |p| {
            (p.tip_repulsion, p.crack_attraction, p.wander, p.ring_adherence) = (1e30, 1e30, 1e30, 1e30)
        }),
        ("spread_ratio just below 1", |p| p.spread_ratio = 0.999_999_94),
    ]
}

fn glass_case(name: &str, params: &GlassParams, budget: u64) -> (u64, bool) {
    let base = glass_base().memory().expect("valid");
    let memory = params.memory().unwrap_or_else(|e| panic!("{name}: {e}"));
    assert_eq!(
        (memory.cracks, memory.vertices, memory.edges, memory.words),
        (base.cracks, base.vertices, base.edges, base.words),
        "{name}: the memory follows the plate and the capacities only"
    );
    let mut store = memory.allocate();
    let mut glass = Glass::new(params, store.buffers()).unwrap_or_else(|e| panic!("{name}: {e:?}"));
    // One piece: a grid cell or entry a query examines, a crack looked at, or a step of a face
    // walk (two in lockstep), whatever the floats.
    let piece = hibi_core::glass::STEP_PIECE;
    let result = bounded(name, budget, piece, |b| {
        let before = glass.progress().work;
        let progress = glass.step(b);
        assert!(progress.cracks as usize <= memory.cracks && progress.vertices as usize <= memory.vertices);
        (glass.progress().work - before, progress.finished)
    });
    let mut time = vec![0f32; 32 * 32];
    let render = GlassRender { width: 32, height: 32, ..GlassRender::default() };
    glass.render(&render, GlassLayers { time: Some(&mut time), ..GlassLayers::default() }).expect("renders");
    fragment_build_case(name, &glass, budget);
    result
}

/// The plate's fragments built in steps of `budget` ([`FragmentBuild`]): each call within the
/// budget and one piece (a step of a face walk: one unit, and one per half-edge around the
/// vertex it reaches, at most its crack edges and two border edges), and, once finished, the
/// rings `Glass::fragments` writes.
fn fragment_build_case(name: &str, glass: &Glass, budget: u64) {
    // Edges counted at their ends' positions (vertices sharing a position counted together,
    // which can only raise the bound).
    let mut degree = std::collections::HashMap::<[u32; 2], u64>::new();
    for i in 0..glass.crack_count() {
        let mut last: Option<[f32; 2]> = None;
        glass.for_each_point(i, |q| {
            if let Some(a) = last {
                for end in [a, q.at] {
                    *degree.entry(end.map(f32::to_bits)).or_default() += 1;
                }
            }
            last = Some(q.at);
        });
    }
    let piece = 3 + degree.into_values().max().unwrap_or(0);
    let mut store = glass.fragment_build_memory().allocate();
    let mut build = FragmentBuild::new(glass, store.buffers()).expect("its memory");
    let mut work = 0;
    let (_, finished) = bounded(&format!("{name}, fragment build"), budget, piece, |b| {
        let p = build.step(glass, b).expect("the plate it was made for");
        let done = p.work - work;
        work = p.work;
        (done, p.finished)
    });
    if finished {
        let mut scratch = vec![0u32; glass.params().memory().expect("valid").scratch];
        let (rings, points) = glass.fragment_counts(&mut scratch).expect("scratch fits");
        let mut out = (vec![Ring::default(); rings], vec![[0.0f32; 2]; points]);
        glass.fragments(&mut scratch, &mut out.0, &mut out.1).expect("buffers fit");
        assert!(build.rings() == out.0.as_slice() && build.points() == out.1.as_slice(), "{name}: the fragments");
    }
}

#[test]
fn glass_extremes_step_within_their_budgets() {
    for (name, set) in glass_extremes() {
        let mut params = glass_base();
        set(&mut params);
        for budget in [0, 1, BUDGET] {
            glass_case(name, &params, budget);
        }
    }
}

/// A ring count of 1e30 (R = floor(a·M + b)) is a plate that runs out of capacity, not a loop
/// over 1e30 ring start points; with a `u64::MAX` budget the run ends within the capacities'
/// work.
#[test]
fn glass_ring_count_1e30_ends_within_the_capacities() {
    for set in [|p: &mut GlassParams| p.ring_slope = 1e30, |p: &mut GlassParams| p.ring_offset = 1e30] {
        let mut params = glass_base();
        set(&mut params);
        let memory = params.memory().expect("valid");
        let mut store = memory.allocate();
        let mut glass = Glass::new(&params, store.buffers()).expect("valid");
        let progress = glass.step(u64::MAX);
        assert!(progress.finished && progress.capacity_reached, "{progress:?}");
        let bound = 64 * (memory.words + memory.cracks + memory.vertices + memory.edges) as u64;
        assert!(glass.progress().work <= bound, "{} work, bound {bound}", glass.progress().work);
    }
}

// ---------------------------------------------------------------------------------------
// Skin

fn skin_base() -> SkinParams {
    let mut p = SkinParams { width: 48, height: 48, levels: 2, ..SkinParams::default() };
    p.level[0].spacing = 16.0;
    p.level[1].spacing = 16.0 / 3.0;
    p
}

fn skin_extremes() -> Vec<Extreme<SkinParams>> {
    vec![
        ("perturbation 1e30", |p| p.level[0].perturbation = 1e30),
        ("perturbation 1e30 on the finer level", |p| p.level[1].perturbation = 1e30),
        ("perturbation_decay 1e30", |p| {
            p.level[0].perturbation = 0.5;
            p.level[0].perturbation_decay = 1e30;
        }),
        ("spacing 1e30", |p| {
            p.level[0].spacing = 1e30;
            p.level[1].spacing = 1e29;
        }),
        ("stretch 1e30", |p| p.level[0].stretch = [1e30, 1e30]),
        ("finer level at 1 px (parents of a few hundred children)", |p| p.level[1].spacing = 1.0),
        ("profile reaching x' 1e30", |p| {
            let profile = &mut p.level[0].profile;
            let last = 3 * profile.segments as usize;
            profile.points[last][0] = 1e30;
        }),
    ]
}

fn skin_case(name: &str, params: &SkinParams, budget: u64) -> (u64, bool) {
    let memory = params.memory().unwrap_or_else(|e| panic!("{name}: {e}"));
    let mut store = memory.allocate();
    let mut skin = Skin::<f32>::new(params, store.buffers()).unwrap_or_else(|e| panic!("{name}: {e:?}"));
    // The largest piece: a cell, its outline's vertices (at most MAX_OUTLINE) and one unit
    // for a level-0 centre point (the step checks its budget before each cell and between a
    // division's pieces, one unit each: a centre point tried, a piece of bucketing).
    let piece = hibi_core::skin::MAX_OUTLINE as u64 + 1;
    let mut work = 0;
    let result = bounded(name, budget, piece, |b| {
        let progress = skin.step(b);
        let done = progress.work - work;
        work = progress.work;
        (done, progress.finished)
    });
    let mut height = vec![0f32; (params.width * params.height) as usize];
    let layers = SkinLayers { height: Some(&mut height), ..SkinLayers::default() };
    skin.render(&SkinRender { cell_level: 0, ..SkinRender::default() }, layers).expect("renders");
    assert!(height.iter().all(|h| h.is_finite()), "{name}: height not finite");
    result
}

#[test]
fn skin_extremes_step_within_their_budgets() {
    for (name, set) in skin_extremes() {
        let mut params = skin_base();
        set(&mut params);
        for budget in [0, 1, BUDGET] {
            skin_case(name, &params, budget);
        }
    }
}

// ---------------------------------------------------------------------------------------
// Refusals: NaN and infinities in every float field, through the C ABI

/// Checks that `memory_size` and `create` both refuse `params` with `status`, writing nothing.
fn refused<P: core::fmt::Debug, O>(
    what: &str,
    params: &P,
    status: hibi_status,
    memory_size: unsafe extern "C" fn(*const P, *mut usize) -> hibi_status,
    create: unsafe extern "C" fn(*const P, *mut *mut O) -> hibi_status,
) {
    let mut size = 12345;
    let mut object: *mut O = core::ptr::null_mut();
    // SAFETY: valid pointers.
    let (a, b) = unsafe { (memory_size(params, &mut size), create(params, &mut object)) };
    assert_eq!((a, b), (status, status), "{what}");
    assert!(size == 12345 && object.is_null(), "{what}: written");
}

const NON_FINITE: [f32; 3] = [f32::NAN, f32::INFINITY, f32::NEG_INFINITY];

#[test]
fn non_finite_mud_fields_are_refused_by_name() {
    type Field = (&'static str, fn(&mut hibi_mud_params) -> &mut f32, hibi_status);
    let fields: [Field; 18] = [
        ("layer_thickness", |p| &mut p.layer_thickness, HIBI_ERROR_MUD_LAYER_THICKNESS),
        ("element_size", |p| &mut p.element_size, HIBI_ERROR_MUD_ELEMENT_SIZE),
        ("long_step", |p| &mut p.long_step, HIBI_ERROR_MUD_LONG_STEP),
        ("short_step", |p| &mut p.short_step, HIBI_ERROR_MUD_SHORT_STEP),
        ("shrink_ratio", |p| &mut p.shrink_ratio, HIBI_ERROR_MUD_SHRINK_RATIO),
        ("displacement_tolerance", |p| &mut p.displacement_tolerance, HIBI_ERROR_MUD_DISPLACEMENT_TOLERANCE),
        ("damping_factor", |p| &mut p.damping_factor, HIBI_ERROR_MUD_DAMPING_FACTOR),
        ("density", |p| &mut p.density, HIBI_ERROR_MUD_DENSITY),
        ("young_modulus", |p| &mut p.young_modulus, HIBI_ERROR_MUD_YOUNG_MODULUS),
        ("shear_modulus", |p| &mut p.shear_modulus, HIBI_ERROR_MUD_SHEAR_MODULUS),
        ("break_stretch_mean", |p| &mut p.break_stretch_mean, HIBI_ERROR_MUD_BREAK_STRETCH_MEAN),
        ("break_stretch_spread", |p| &mut p.break_stretch_spread, HIBI_ERROR_MUD_BREAK_STRETCH_SPREAD),
        (
            "break_stretch_size_exponent",
            |p| &mut p.break_stretch_size_exponent,
            HIBI_ERROR_MUD_BREAK_STRETCH_SIZE_EXPONENT,
        ),
        ("anisotropy_direction", |p| &mut p.anisotropy_direction, HIBI_ERROR_MUD_ANISOTROPY_DIRECTION),
        ("anisotropy_ratio", |p| &mut p.anisotropy_ratio, HIBI_ERROR_MUD_ANISOTROPY_RATIO),
        (
            "stiffness_anisotropy_ratio",
            |p| &mut p.stiffness_anisotropy_ratio,
            HIBI_ERROR_MUD_STIFFNESS_ANISOTROPY_RATIO,
        ),
        ("target_shrink", |p| &mut p.target_shrink, HIBI_ERROR_MUD_TARGET_SHRINK),
        ("target_crack_density", |p| &mut p.target_crack_density, HIBI_ERROR_MUD_TARGET_CRACK_DENSITY),
    ];
    for (name, field, status) in fields {
        for value in NON_FINITE {
            let mut params = hibi_mud_params_default();
            (params.columns, params.rows) = (8, 8);
            *field(&mut params) = value;
            refused(&format!("{name} {value}"), &params, status, hibi_mud_memory_size, hibi_mud_create);
        }
    }
}

#[test]
fn non_finite_glass_fields_are_refused_by_name() {
    type Field = (&'static str, fn(&mut hibi_glass_params) -> &mut f32, hibi_status);
    let fields: [Field; 25] = [
        ("width", |p| &mut p.width, HIBI_ERROR_GLASS_SIZE),
        ("height", |p| &mut p.height, HIBI_ERROR_GLASS_SIZE),
        ("impact x", |p| &mut p.impact[0], HIBI_ERROR_GLASS_IMPACT_POINT),
        ("impact y", |p| &mut p.impact[1], HIBI_ERROR_GLASS_IMPACT_POINT),
        ("radial_mean", |p| &mut p.radial_mean, HIBI_ERROR_GLASS_RADIAL_MEAN),
        ("ring_threshold", |p| &mut p.ring_threshold, HIBI_ERROR_GLASS_RING_THRESHOLD),
        ("large_slope", |p| &mut p.large_slope, HIBI_ERROR_GLASS_COUNT_FORMULA),
        ("large_offset", |p| &mut p.large_offset, HIBI_ERROR_GLASS_COUNT_FORMULA),
        ("ring_slope", |p| &mut p.ring_slope, HIBI_ERROR_GLASS_COUNT_FORMULA),
        ("ring_offset", |p| &mut p.ring_offset, HIBI_ERROR_GLASS_COUNT_FORMULA),
        ("ring_radius_slope", |p| &mut p.ring_radius_slope, HIBI_ERROR_GLASS_RING_RADIUS),
        ("ring_radius_offset", |p| &mut p.ring_radius_offset, HIBI_ERROR_GLASS_RING_RADIUS),
        ("large_speed", |p| &mut p.large_speed, HIBI_ERROR_GLASS_SPEED),
        ("radial_speed", |p| &mut p.radial_speed, HIBI_ERROR_GLASS_SPEED),
        ("ring_speed", |p| &mut p.ring_speed, HIBI_ERROR_GLASS_SPEED),
        ("spread_ratio", |p| &mut p.spread_ratio, HIBI_ERROR_GLASS_SPREAD_RATIO),
        ("turn_limit", |p| &mut p.turn_limit, HIBI_ERROR_GLASS_TURN_LIMIT),
        ("turn_delay", |p| &mut p.turn_delay, HIBI_ERROR_GLASS_TURN_DELAY),
        ("sector_angle", |p| &mut p.sector_angle, HIBI_ERROR_GLASS_SECTOR),
        ("sector_radius", |p| &mut p.sector_radius, HIBI_ERROR_GLASS_SECTOR),
        ("tip_repulsion", |p| &mut p.tip_repulsion, HIBI_ERROR_GLASS_FORCES),
        ("crack_attraction", |p| &mut p.crack_attraction, HIBI_ERROR_GLASS_FORCES),
        ("wander", |p| &mut p.wander, HIBI_ERROR_GLASS_FORCES),
        ("ring_adherence", |p| &mut p.ring_adherence, HIBI_ERROR_GLASS_FORCES),
        ("spread_ratio", |p| &mut p.spread_ratio, HIBI_ERROR_GLASS_SPREAD_RATIO),
    ];
    for (name, field, status) in fields {
        for value in NON_FINITE {
            let mut params = hibi_glass_params_default();
            *field(&mut params) = value;
            refused(&format!("{name} {value}"), &params, status, hibi_glass_memory_size, hibi_glass_create);
        }
    }
}

#[test]
fn non_finite_skin_fields_are_refused_by_name() {
    type Field = (&'static str, fn(&mut hibi_skin_params) -> &mut f32, hibi_status);
    let fields: [Field; 8] = [
        ("jitter_ratio", |p| &mut p.jitter_ratio, HIBI_ERROR_SKIN_JITTER_RATIO),
        ("spacing", |p| &mut p.level[1].spacing, HIBI_ERROR_SKIN_SPACING),
        ("perturbation", |p| &mut p.level[1].perturbation, HIBI_ERROR_SKIN_PERTURBATION),
        ("perturbation_decay", |p| &mut p.level[0].perturbation_decay, HIBI_ERROR_SKIN_PERTURBATION),
        ("stretch x", |p| &mut p.level[0].stretch[0], HIBI_ERROR_SKIN_STRETCH),
        ("stretch y", |p| &mut p.level[1].stretch[1], HIBI_ERROR_SKIN_STRETCH),
        ("profile point", |p| &mut p.level[0].profile.points[2][1], HIBI_ERROR_SKIN_PROFILE_POINTS),
        ("roundness", |p| &mut p.level[1].roundness, HIBI_ERROR_SKIN_ROUNDNESS),
    ];
    for (name, field, status) in fields {
        for value in NON_FINITE {
            let mut params = hibi_skin_params_default();
            (params.width, params.height, params.levels) = (64, 48, 2);
            *field(&mut params) = value;
            refused(&format!("{name} {value}"), &params, status, hibi_skin_memory_size, hibi_skin_create);
        }
    }
}

/// Render and shading parameters: NaN and infinities are refused by field, nothing drawn.
#[test]
fn non_finite_render_fields_are_refused_by_name() {
    let mut params = hibi_mud_params_default();
    (params.columns, params.rows) = (8, 8);
    let mut mud = core::ptr::null_mut();
    // SAFETY: valid pointers; every buffer holds the lengths passed.
    unsafe {
        assert_eq!(hibi_mud_create(&params, &mut mud), HIBI_OK);
        type Field = (fn(&mut hibi_mud_render_params) -> &mut f32, hibi_status);
        let fields: [Field; 5] = [
            (|r| &mut r.width_scale, HIBI_ERROR_RENDER_WIDTH_SCALE),
            (|r| &mut r.min_width, HIBI_ERROR_RENDER_MIN_WIDTH),
            (|r| &mut r.groove_depth, HIBI_ERROR_RENDER_GROOVE_DEPTH),
            (|r| &mut r.offset[0], HIBI_ERROR_RENDER_OFFSET),
            (|r| &mut r.offset[1], HIBI_ERROR_RENDER_OFFSET),
        ];
        for (field, status) in fields {
            for value in NON_FINITE {
                let mut render = hibi_mud_render_params_default();
                (render.width, render.height) = (4, 4);
                *field(&mut render) = value;
                let mut pixels = [7f32; 16];
                let got = hibi_mud_render(mud, &render, HIBI_MUD_LAYER_HEIGHT, pixels.as_mut_ptr().cast(), 16);
                assert_eq!(got, status, "{value}");
                assert!(pixels.iter().all(|&p| p == 7.0));
            }
        }
        hibi_mud_destroy(mud);

        let mut glass = core::ptr::null_mut();
        assert_eq!(hibi_glass_create(&hibi_glass_params_default(), &mut glass), HIBI_OK);
        for value in NON_FINITE {
            let mut render = hibi_glass_render_params_default();
            (render.width, render.height, render.line_width) = (4, 4, value);
            let mut pixels = [7u8; 16];
            let got = hibi_glass_render(glass, &render, HIBI_GLASS_LAYER_MASK, pixels.as_mut_ptr().cast(), 16);
            assert_eq!(got, HIBI_ERROR_RENDER_LINE_WIDTH, "{value}");
            assert!(pixels.iter().all(|&p| p == 7));
        }
        hibi_glass_destroy(glass);

        let (height, normal) = ([0.5f32], [0.0f32, 0.0, 1.0]);
        type Shade = (fn(&mut hibi_skin_shade_params) -> &mut f32, hibi_status);
        let fields: [Shade; 5] = [
            (|s| &mut s.light[2], HIBI_ERROR_SKIN_SHADE),
            (|s| &mut s.ridge[0], HIBI_ERROR_SKIN_SHADE_RIDGE),
            (|s| &mut s.furrow[1], HIBI_ERROR_SKIN_SHADE_FURROW),
            (|s| &mut s.ambient, HIBI_ERROR_SKIN_SHADE_AMBIENT),
            (|s| &mut s.specular, HIBI_ERROR_SKIN_SHADE_SPECULAR),
        ];
        for (field, status) in fields {
            for value in NON_FINITE {
                let mut shade = hibi_skin_shade_params_default();
                *field(&mut shade) = value;
                let mut rgb = [7u8; 3];
                let got = hibi_skin_shade(height.as_ptr(), 1, normal.as_ptr(), 3, &shade, rgb.as_mut_ptr(), 3);
                assert_eq!(got, status, "{value}");
                assert_eq!(rgb, [7; 3]);
            }
        }
    }
}
