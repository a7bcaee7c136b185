//! Regression tests for what fuzzing the C ABI found (`docs/src/fuzzing.md` lists each finding).
//! Each case is the smallest input found that reached `HIBI_ERROR_PANIC`, called through the C
//! ABI as the fuzz target called it.

use hibi::*;

/// Finding 1: a skin level whose stretch is tiny (`FLT_MIN`) asks for about 1e39 centre
/// points across an axis. Its lattice count saturated at `i64::MAX`, and sizing the memory
/// overflowed (a panic in `hibi_skin_memory_size` and `hibi_skin_create`). It is refused by
/// the field's name, `HIBI_ERROR_SKIN_STRETCH`, on every level, periodic or not.
#[test]
fn a_tiny_skin_stretch_is_too_large_not_a_panic() {
    for periodic in [0, 1] {
        for level in 0..4 {
            for axis in 0..2 {
                let mut params = hibi_skin_params_default();
                params.periodic = periodic;
                params.width = 4;
                params.height = 5;
                params.levels = 4;
                params.level[level].stretch[axis] = f32::MIN_POSITIVE;
                let mut size = usize::MAX;
                // SAFETY: valid pointers.
                let status = unsafe { hibi_skin_memory_size(&params, &mut size) };
                assert_eq!(status, HIBI_ERROR_SKIN_STRETCH, "periodic {periodic}, level {level}, axis {axis}");
                assert_eq!(size, usize::MAX, "nothing written");
                let mut skin = core::ptr::null_mut();
                // SAFETY: valid pointers.
                let status = unsafe { hibi_skin_create(&params, &mut skin) };
                assert_eq!(status, HIBI_ERROR_SKIN_STRETCH);
                assert!(skin.is_null());
            }
        }
    }
}

/// Finding 2: a mud lattice whose element counts fit in `size_t` but whose bytes do not
/// (16 711 680 × 4 282 449 664 nodes, square, periodic) got the generic
/// `HIBI_ERROR_SIZE_OVERFLOW` from `hibi_mud_memory_size` and `hibi_mud_create`, which by
/// the header's contract names an argument, and it named none. It is now the lattice-too-large
/// parameter status, like the larger lattice of the bad-input table.
#[test]
fn a_mud_lattice_too_large_for_memory_is_its_parameter_status() {
    let mut params = hibi_mud_params_default();
    (params.topology, params.boundary, params.solver) = (HIBI_MUD_SQUARE, HIBI_MUD_PERIODIC, HIBI_MUD_EXPLICIT);
    (params.columns, params.rows) = (16_711_680, 4_282_449_664);
    let mut size = usize::MAX;
    // SAFETY: valid pointers.
    let status = unsafe { hibi_mud_memory_size(&params, &mut size) };
    assert_eq!(status, HIBI_ERROR_MUD_SIZE_OVERFLOW);
    assert_eq!(size, usize::MAX, "nothing written");
    let mut mud = core::ptr::null_mut();
    // SAFETY: valid pointers.
    assert_eq!(unsafe { hibi_mud_create(&params, &mut mud) }, HIBI_ERROR_MUD_SIZE_OVERFLOW);
    assert!(mud.is_null());
}

fn argument() -> String {
    // SAFETY: a static C string.
    unsafe { core::ffi::CStr::from_ptr(hibi_error_argument()) }.to_str().expect("ASCII").to_owned()
}

/// Finding 3: a NULL `rgb` (`hibi_skin_shade`) or `normal` (`hibi_skin_shade`, and
/// `hibi_skin_render` when it took every map at once) whose length is 1 or 2, too short for
/// one pixel, was accepted as an empty buffer; the header allows NULL only with length 0. Now
/// `HIBI_ERROR_NULL_POINTER`, naming the buffer, like every other NULL buffer with a length
/// (the render's normal layer, now one layer per call, names `pixels`).
#[test]
fn a_null_buffer_shorter_than_one_pixel_is_refused() {
    let shade = hibi_skin_shade_params_default();
    let (height, normal) = ([0.5f32; 1], [0.0f32, 0.0, 1.0]);
    let mut rgb = [7u8; 3];
    for len in [1, 2] {
        // SAFETY: every non-null pointer is valid for its length.
        unsafe {
            let status =
                hibi_skin_shade(core::ptr::null(), 0, core::ptr::null(), 0, &shade, core::ptr::null_mut(), len);
            assert_eq!((status, argument().as_str()), (HIBI_ERROR_NULL_POINTER, "rgb"));
            let status = hibi_skin_shade(core::ptr::null(), 0, core::ptr::null(), len, &shade, rgb.as_mut_ptr(), 3);
            assert_eq!((status, argument().as_str()), (HIBI_ERROR_NULL_POINTER, "normal"));
        }
    }
    // The same inputs with their buffers are accepted.
    // SAFETY: valid pointers and lengths.
    let status = unsafe { hibi_skin_shade(height.as_ptr(), 1, normal.as_ptr(), 3, &shade, rgb.as_mut_ptr(), 3) };
    assert_eq!(status, HIBI_OK);

    let mut params = hibi_skin_params_default();
    (params.width, params.height) = (16, 16);
    let mut skin = core::ptr::null_mut();
    // SAFETY: valid pointers.
    unsafe {
        assert_eq!(hibi_skin_create(&params, &mut skin), HIBI_OK);
        let render = hibi_skin_render_params_default();
        for len in [1, 2] {
            let status = hibi_skin_render(skin, &render, HIBI_SKIN_LAYER_NORMAL, core::ptr::null_mut(), len);
            assert_eq!((status, argument().as_str()), (HIBI_ERROR_NULL_POINTER, "pixels"));
        }
        hibi_skin_destroy(skin);
    }
}

/// Finding 4: a huge perturbation ratio (1e30, valid: finite and >= 0) overflowed the box of
/// parent edges a bisector's perturbation can reach, a panic in `hibi_skin_step`
/// (`HIBI_ERROR_PANIC`; the skin fuzz target and `tests/bounded.rs` found it). The box now
/// saturates and takes in every edge; the build ends, finished or out of capacity.
#[test]
fn a_huge_skin_perturbation_builds() {
    for level in 0..2 {
        let mut params = hibi_skin_params_default();
        (params.width, params.height, params.levels) = (48, 48, 2);
        params.level[0].spacing = 16.0;
        params.level[1].spacing = 16.0 / 3.0;
        params.level[level].perturbation = 1e30;
        let mut skin = core::ptr::null_mut();
        let mut progress = hibi_skin_progress::default();
        // SAFETY: valid pointers.
        unsafe {
            assert_eq!(hibi_skin_create(&params, &mut skin), HIBI_OK);
            let mut calls = 0;
            let status = loop {
                let status = hibi_skin_step(skin, 1000, &mut progress);
                calls += 1;
                if status != HIBI_OK || progress.finished == 1 || calls == 10_000 {
                    break status;
                }
            };
            assert!(status == HIBI_OK || status == HIBI_ERROR_SKIN_CAPACITY, "level {level}: status {status}");
            assert!(status != HIBI_OK || progress.finished == 1, "level {level}: unfinished");
            hibi_skin_destroy(skin);
        }
    }
}

/// Findings 5 and 10: the explicit solver with a short step 1000 times the paper's (1 s; valid
/// then, within the short-step scale check) diverges. In finding 5 (hexagonal, open) the
/// bit-level first guess of `inverse_sqrt` then took a NaN or negative length², whose bits
/// overflowed the subtraction from the magic constant (`HIBI_ERROR_PANIC` with overflow
/// checks; the subtraction now wraps in every build, as it did in release). In finding 10
/// (square, open, growth drive, 5 × 12 nodes) the positions turned NaN and
/// `hibi_mud_segments` wrote NaN ends and widths. Such a step is now refused, with the status
/// naming it, before anything runs: it fails the stability test of the damped step (Eq. 4; a
/// sufficient test, 1 s is a hundred times past it). The irregular lattice is checked node by
/// node on its mesh, which the first steps build, so the `hibi_mud_step` that finds the failing
/// node tells (and every later one). (The wrap itself is tested in `core/src/scalar.rs`.)
#[test]
fn explicit_short_steps_failing_the_stability_test_are_refused() {
    let unstable = |topology, drive, columns, rows, short_step| {
        let mut params = hibi_mud_params_default();
        (params.topology, params.boundary, params.solver, params.drive) =
            (topology, HIBI_MUD_OPEN, HIBI_MUD_EXPLICIT, drive);
        (params.columns, params.rows, params.short_step) = (columns, rows, short_step);
        params
    };
    let mut mud = core::ptr::null_mut();
    let mut size = 0;
    for params in [
        unstable(HIBI_MUD_HEXAGONAL, HIBI_MUD_SHRINK, 11, 11, 1.0),
        unstable(HIBI_MUD_SQUARE, HIBI_MUD_GROWTH, 5, 12, 0.999_999_94),
    ] {
        // SAFETY: valid pointers.
        unsafe {
            assert_eq!(hibi_mud_memory_size(&params, &mut size), HIBI_ERROR_MUD_SHORT_STEP_STABILITY);
            assert_eq!(hibi_mud_create(&params, &mut mud), HIBI_ERROR_MUD_SHORT_STEP_STABILITY);
        }
        assert!(mud.is_null());
    }
    let params = unstable(HIBI_MUD_IRREGULAR, HIBI_MUD_SHRINK, 12, 12, 1.0);
    // SAFETY: valid pointers; the run is live until destroyed.
    unsafe {
        assert_eq!(hibi_mud_memory_size(&params, &mut size), HIBI_OK);
        assert_eq!(hibi_mud_create(&params, &mut mud), HIBI_OK);
        assert_eq!(hibi_mud_step(mud, u64::MAX, core::ptr::null_mut()), HIBI_ERROR_MUD_SHORT_STEP_STABILITY);
        assert_eq!(hibi_mud_step(mud, 1, core::ptr::null_mut()), HIBI_ERROR_MUD_SHORT_STEP_STABILITY);
        hibi_mud_destroy(mud);
    }
    // SAFETY: a static C string.
    let message = unsafe { core::ffi::CStr::from_ptr(hibi_status_string(HIBI_ERROR_MUD_SHORT_STEP_STABILITY)) };
    assert!(message.to_str().unwrap().contains("short_step"), "{message:?}");
}

/// The stability test is not too loose: on each lattice, an explicit run at the largest short
/// step `hibi_mud_create` and the run's first steps accept (found by bisection) keeps every segment finite, and its
/// springs do not all break at once as a diverging run's do.
#[test]
fn an_explicit_run_at_the_largest_accepted_step_stays_finite() {
    for topology in [HIBI_MUD_SQUARE, HIBI_MUD_HEXAGONAL, HIBI_MUD_IRREGULAR] {
        let mut params = hibi_mud_params_default();
        (params.topology, params.boundary, params.solver) = (topology, HIBI_MUD_OPEN, HIBI_MUD_EXPLICIT);
        (params.columns, params.rows) = (12, 12);
        let accepted = |short_step: f32| {
            let mut p = params;
            p.short_step = short_step;
            let mut mud = core::ptr::null_mut();
            // SAFETY: valid pointers; the irregular mesh is tested by the first steps (a
            // stable run's whole run, at this size).
            let status = unsafe {
                match hibi_mud_create(&p, &mut mud) {
                    HIBI_OK => hibi_mud_step(mud, u64::MAX, core::ptr::null_mut()),
                    status => status,
                }
            };
            // SAFETY: created above, or NULL.
            unsafe { hibi_mud_destroy(mud) };
            assert!(status == HIBI_OK || status == HIBI_ERROR_MUD_SHORT_STEP_STABILITY, "{status}");
            status == HIBI_OK
        };
        let (mut low, mut high) = (params.short_step, 10.0f32);
        assert!(accepted(low) && !accepted(high), "topology {topology}");
        for _ in 0..40 {
            let middle = 0.5 * (low + high);
            if accepted(middle) { low = middle } else { high = middle }
        }
        params.short_step = low;
        let mut mud = core::ptr::null_mut();
        let mut progress = hibi_mud_progress::default();
        // SAFETY: valid pointers, buffers of the lengths passed.
        unsafe {
            assert_eq!(hibi_mud_create(&params, &mut mud), HIBI_OK);
            for _ in 0..20 {
                assert_eq!(hibi_mud_step(mud, 1 << 16, &mut progress), HIBI_OK);
            }
            let mut count = 0;
            assert_eq!(hibi_mud_segment_count(mud, &mut count), HIBI_OK);
            let mut segments = vec![hibi_core::mud::CrackSegment::default(); count];
            let mut written = 0;
            assert_eq!(hibi_mud_segments(mud, segments.as_mut_ptr(), count, &mut written), HIBI_OK);
            hibi_mud_destroy(mud);
            for s in &segments {
                assert!(
                    s.start.iter().chain(&s.end).chain(&s.width).all(|v| v.is_finite()),
                    "topology {topology}: {s:?}"
                );
            }
            assert!(progress.crack_density.is_finite(), "topology {topology}");
            // A 12 × 12 open lattice has 264 (square) to 363 springs; past the limit (with a
            // bound four times looser) every one of them breaks within these steps.
            assert!(progress.broken_springs < 100, "topology {topology}: {} springs broken", progress.broken_springs);
        }
        println!(
            "topology {topology}: largest stable short_step {low} s ({}x the paper's): {} springs broken, shrink {}, crack density {}",
            low / 0.001,
            progress.broken_springs,
            progress.shrink,
            progress.crack_density
        );
    }
}

/// Finding 6: `tip_repulsion` and `crack_attraction` of `FLT_MAX` (valid: finite) made the
/// force sum inf − inf on a 86 × 2 plate, and the tip's heading and every later vertex NaN
/// (the glass target's finite-output check). A force with no direction now turns the tip
/// nowhere; every crack point is finite.
#[test]
fn glass_forces_of_flt_max_keep_the_cracks_finite() {
    let mut params = hibi_glass_params_default();
    (params.width, params.height, params.impact) = (86.0, 2.0, [43.0, 1.0]);
    params.seed = 69_231_806_036_407_797;
    (params.tip_repulsion, params.crack_attraction) = (f32::MAX, f32::MAX);
    (params.max_cracks, params.max_vertices) = (245, 488);
    let mut glass = core::ptr::null_mut();
    let mut progress = hibi_glass_progress::default();
    // SAFETY: valid pointers, buffers of the lengths passed.
    unsafe {
        assert_eq!(hibi_glass_create(&params, &mut glass), HIBI_OK);
        while progress.finished == 0 {
            let status = hibi_glass_step(glass, 10_000, &mut progress);
            assert!(status == HIBI_OK || status == HIBI_ERROR_GLASS_CAPACITY, "{status}");
            if status != HIBI_OK {
                break;
            }
        }
        cracks_are_finite(glass);
        hibi_glass_destroy(glass);
    }
}

/// Finding 7: a skin level stretched by 4e21 puts its outline's fixed-point corners so far
/// apart that their differences overflowed `i64` in the render (a panic with overflow
/// checks, `HIBI_ERROR_PANIC` from `hibi_skin_render`; release builds wrapped). They wrap in
/// every build now, as in release.
#[test]
fn a_huge_skin_stretch_renders() {
    let mut params = hibi_skin_params_default();
    (params.width, params.height, params.jitter, params.levels) = (14, 14, HIBI_SPREAD_NORMAL, 1);
    params.seed = 11_672_663_176_895_373_729;
    params.level[0].spacing = 1.000_000_1;
    params.level[0].perturbation = 4.892_226e-24;
    params.level[0].perturbation_depth = 2;
    params.level[0].stretch = [4.193_125_7e21, 1.0];
    let mut skin = core::ptr::null_mut();
    // SAFETY: valid pointers.
    unsafe {
        assert_eq!(hibi_skin_create(&params, &mut skin), HIBI_OK);
        assert_eq!(hibi_skin_step(skin, u64::MAX, core::ptr::null_mut()), HIBI_OK);
        let (mut height, mut normal) = (vec![0f32; 196], vec![0f32; 3 * 196]);
        let render = hibi_skin_render_params_default();
        let status = hibi_skin_render(skin, &render, HIBI_SKIN_LAYER_HEIGHT, height.as_mut_ptr().cast(), 196);
        assert_eq!(status, HIBI_OK);
        let status = hibi_skin_render(skin, &render, HIBI_SKIN_LAYER_NORMAL, normal.as_mut_ptr().cast(), 3 * 196);
        assert_eq!(status, HIBI_OK);
        hibi_skin_destroy(skin);
    }
}

/// Finding 8: a large-crack speed of `FLT_MAX` is valid, but Rand((1 + z)·x) drew +inf, and
/// an infinite speed made the crack times NaN (inf − inf). Drawn speeds and radii are now at
/// most `FLT_MAX`; every crack point's time is finite.
#[test]
fn a_glass_speed_of_flt_max_keeps_the_times_finite() {
    let mut params = hibi_glass_params_default();
    (params.width, params.height, params.impact) = (43.0, 43.0, [21.5, 21.5]);
    params.seed = 541_134_543_218_278_400;
    params.large_speed = f32::MAX;
    (params.ring_radius_slope, params.ring_radius_offset) = (f32::MAX, f32::MAX);
    (params.spread, params.sector_angle) = (HIBI_SPREAD_UNIFORM, f32::MIN_POSITIVE);
    (params.max_cracks, params.max_vertices) = (251, 702);
    let mut glass = core::ptr::null_mut();
    let mut progress = hibi_glass_progress::default();
    // SAFETY: valid pointers, buffers of the lengths passed.
    unsafe {
        assert_eq!(hibi_glass_create(&params, &mut glass), HIBI_OK);
        for _ in 0..100 {
            if hibi_glass_step(glass, 10_000, &mut progress) != HIBI_OK || progress.finished == 1 {
                break;
            }
        }
        cracks_are_finite(glass);
        hibi_glass_destroy(glass);
    }
}

/// Findings 9 and 13: with the growth drive the deep layer grows by 1/γ per long step. A
/// subnormal `shrink_ratio` (1e-40, finding 9) made the explicit solver's first long step
/// grow by +inf (an infinite `progress.shrink`, a run that never ended); `FLT_MIN` (finding 13:
/// square, periodic, 8 × 10) grew it 8.5e37-fold and `hibi_mud_segments` wrote ends at +inf.
/// Growth may now take at most the largest misfit the model follows in one long step,
/// 1/γ − 1 <= 100; anything less is refused by name, and a run at the smallest γ accepted
/// ends with every segment finite. The shrink drive still takes any normal γ.
#[test]
fn a_growth_step_past_the_largest_growth_is_refused() {
    let mut params = hibi_mud_params_default();
    (params.columns, params.rows, params.drive, params.solver) = (8, 10, HIBI_MUD_GROWTH, HIBI_MUD_EXPLICIT);
    params.boundary = HIBI_MUD_PERIODIC;
    params.topology = HIBI_MUD_SQUARE;
    let smallest = 1.0f32 / 101.0;
    assert!(1.0 / smallest - 1.0 <= 100.0);
    let mut size = 0;
    for gamma in [1e-40f32, 1e-45, f32::MIN_POSITIVE, 0.001, smallest.next_down()] {
        params.shrink_ratio = gamma;
        // SAFETY: valid pointers.
        assert_eq!(unsafe { hibi_mud_memory_size(&params, &mut size) }, HIBI_ERROR_MUD_SHRINK_RATIO, "{gamma}");
    }
    for (drive, gamma) in [(HIBI_MUD_GROWTH, smallest), (HIBI_MUD_SHRINK, f32::MIN_POSITIVE)] {
        (params.drive, params.shrink_ratio) = (drive, gamma);
        let mut mud = core::ptr::null_mut();
        let mut progress = hibi_mud_progress::default();
        // SAFETY: valid pointers; buffers of the lengths passed.
        unsafe {
            assert_eq!(hibi_mud_create(&params, &mut mud), HIBI_OK, "{gamma}");
            assert_eq!(hibi_mud_step(mud, 1 << 24, &mut progress), HIBI_OK);
            assert!(progress.finished == 1 && progress.shrink.is_finite(), "{progress:?}");
            let mut count = 0;
            assert_eq!(hibi_mud_segment_count(mud, &mut count), HIBI_OK);
            let mut segments = vec![hibi_core::mud::CrackSegment::default(); count];
            assert_eq!(hibi_mud_segments(mud, segments.as_mut_ptr(), count, &mut count), HIBI_OK);
            let finite = |s: &hibi_core::mud::CrackSegment| {
                [s.start, s.end, s.width, s.time].iter().flatten().all(|v| v.is_finite())
            };
            assert!(segments.iter().all(finite), "{gamma}: {segments:?}");
            hibi_mud_destroy(mud);
        }
    }
}

/// Finding 11: an impact on the plate's edge (y = 1.2e-38 on a 51 × 131 plate) made edges of
/// zero length, whose direction (`pseudo_angle`, 0/0) was NaN; the order of a vertex's edges
/// broke, face walks did not come back to their start, and `hibi_glass_fragment_counts`
/// counted each as a ring of as many points as the walk's bound allows (48 rings of 15,358
/// points here), taking seconds under the fuzzer. Now every walk closes: the points number at
/// most the half-edges, and the rings cover the plate.
#[test]
fn fragments_of_an_impact_on_the_edge_close() {
    let mut params = hibi_glass_params_default();
    (params.width, params.height, params.impact) = (51.0, 131.0, [25.5, 1.175_494_4e-38]);
    params.seed = 9_404_340_510_852_330_801;
    (params.ring_threshold, params.ring_offset) = (70.136_72, 0.443_847_66);
    (params.ring_radius_slope, params.ring_radius_offset) = (0.417_216_8, 12.338_964);
    (params.large_speed, params.radial_speed, params.ring_speed) = (35.507_813, 8.876_953, 8.876_953);
    params.spread_ratio = 0.262_500_02;
    (params.max_cracks, params.max_vertices) = (127, 527);
    let mut glass = core::ptr::null_mut();
    let mut progress = hibi_glass_progress::default();
    // SAFETY: valid pointers, buffers of the lengths passed.
    unsafe {
        assert_eq!(hibi_glass_create(&params, &mut glass), HIBI_OK);
        for _ in 0..2 {
            assert_eq!(hibi_glass_step(glass, 16_384, &mut progress), HIBI_OK);
        }
        let mut size = 0;
        assert_eq!(hibi_glass_scratch_size(glass, &mut size), HIBI_OK);
        let mut scratch = vec![0u64; size.div_ceil(8)];
        let (mut rings, mut points) = (0, 0);
        let status = hibi_glass_fragment_counts(glass, scratch.as_mut_ptr().cast(), size, &mut rings, &mut points);
        assert_eq!(status, HIBI_OK);
        // Each vertex has at most two half-edges per crack through it, and the border adds at
        // most two vertices and four half-edges per crack end on it.
        let bound = 4 * (progress.vertices as usize + 4) + 8 * progress.cracks as usize;
        assert!(points <= bound, "{rings} rings of {points} points, bound {bound}");
        // Every face is found: the rings' signed areas (holes negative) add up to the plate's.
        let (written, area) = fragment_area(glass);
        assert_eq!(written, rings);
        assert!((area - 51.0 * 131.0).abs() < 1e-3 * 51.0 * 131.0, "rings cover {area} of {}", 51.0 * 131.0);
        hibi_glass_destroy(glass);
    }
}

/// Finding 12: elements of 1e25 cm (valid: every ratio the scale checks test is in range)
/// make a plate of 1e52 cm², past `f32`; the crack statistics' mean cell area was +inf. The
/// figures in cm now saturate at `FLT_MAX`, and the progress's crack density too.
#[test]
fn crack_statistics_of_huge_elements_are_finite() {
    let mut params = hibi_mud_params_default();
    (params.columns, params.rows) = (16, 16);
    (params.element_size, params.layer_thickness) = (1e25, 1e25);
    (params.short_step, params.displacement_tolerance) = (1e22, 1e21);
    let mut mud = core::ptr::null_mut();
    let mut progress = hibi_mud_progress::default();
    let mut statistics = hibi_mud_crack_statistics::default();
    // SAFETY: valid pointers.
    unsafe {
        assert_eq!(hibi_mud_create(&params, &mut mud), HIBI_OK);
        while progress.finished == 0 {
            assert_eq!(hibi_mud_step(mud, u64::MAX, &mut progress), HIBI_OK);
        }
        assert_eq!(hibi_mud_statistics(mud, &mut statistics), HIBI_OK);
        hibi_mud_destroy(mud);
    }
    let figures = [statistics.crack_density, statistics.mean_cell_area, statistics.cell_area_spread];
    assert!(figures.iter().chain([&progress.crack_density]).all(|f| f.is_finite()), "{statistics:?} {progress:?}");
    assert_eq!(statistics.mean_cell_area, f32::MAX, "{statistics:?}");
}

/// Every point of every crack of `glass` (a live plate) is finite, time included.
///
/// # Safety
/// `glass` must be a live plate.
unsafe fn cracks_are_finite(glass: *mut hibi_glass) {
    let mut cracks = 0;
    // SAFETY (every call below): a live plate, buffers of the lengths passed.
    unsafe {
        assert_eq!(hibi_glass_crack_count(glass, &mut cracks), HIBI_OK);
        for i in 0..cracks {
            let mut info = hibi_glass_crack::default();
            assert_eq!(hibi_glass_crack_info(glass, i, &mut info), HIBI_OK);
            let mut points = vec![hibi_core::glass::CrackPoint::default(); info.points as usize];
            let mut written = 0;
            assert_eq!(hibi_glass_points(glass, i, points.as_mut_ptr(), points.len(), &mut written), HIBI_OK);
            for p in &points {
                assert!(p.at.iter().all(|c| c.is_finite()) && p.time.is_finite(), "crack {i}: {p:?}");
            }
        }
    }
}

/// Finding 14 (a timeout, not a panic): a one-level skin of 33 × 33 pixels stretched
/// 2.26·10¹¹ times along y, perturbed, has two cells whose perturbed shared edge reaches
/// 6.6·10⁷ pixels above and below the surface; the render scanned every row the outline
/// spans (2.5 s in release, 47 s in the fuzz build) to keep the 33 the surface has. A render
/// now scans only the surface's rows (within two periods of the cell's centre on a periodic
/// surface). Here the cells and maps are checked; `c_create_and_render_work_does_not_grow_
/// with_extreme_floats` (`skin-render stretch`, `tests/c/work_counts.c`) counts the
/// render's instructions against a moderate twin.
#[test]
fn a_cell_reaching_far_past_the_surface_renders_its_pixels_only() {
    for periodic in [0, 1] {
        let mut params = hibi_skin_params_default();
        (params.layout, params.jitter, params.periodic) = (HIBI_SKIN_LAYOUT_SQUARE, 0, periodic);
        (params.width, params.height, params.seed) = (33, 33, 6802178615612166738);
        (params.jitter_ratio, params.levels) = (4.1723208e-8, 1);
        let level = &mut params.level[0];
        (level.spacing, level.perturbation, level.perturbation_decay, level.perturbation_depth) = (40.0, 0.1, 1.0, 2);
        level.stretch = [1.0, 225833900000.0];
        level.profile.segments = 1;
        level.roundness = 0.2;
        for (point, at) in level.profile.points.iter_mut().zip([[0.0, 4.0], [5.0, 4.0], [9.0, 3.0], [10.0, 0.0]]) {
            *point = at;
        }
        let pixels = 33 * 33;
        let (mut height, mut cells) = (vec![f32::NAN; pixels], vec![u32::MAX - 1; pixels]);
        let render = hibi_skin_render_params { cell_level: 0, ..hibi_skin_render_params_default() };
        let mut skin = core::ptr::null_mut();
        let mut progress = hibi_skin_progress::default();
        // SAFETY: valid pointers, buffers of the lengths passed.
        unsafe {
            assert_eq!(hibi_skin_create(&params, &mut skin), HIBI_OK);
            assert_eq!(hibi_skin_step(skin, u64::MAX, &mut progress), HIBI_OK);
            let layer = HIBI_SKIN_LAYER_HEIGHT;
            assert_eq!(hibi_skin_render(skin, &render, layer, height.as_mut_ptr().cast(), pixels), HIBI_OK);
            let layer = HIBI_SKIN_LAYER_CELLS;
            assert_eq!(hibi_skin_render(skin, &render, layer, cells.as_mut_ptr().cast(), pixels), HIBI_OK);
            hibi_skin_destroy(skin);
        }
        assert!(progress.finished == 1 && progress.capacity_reached == 0, "{progress:?}");
        assert!(height.iter().all(|h| h.is_finite()), "periodic {periodic}: a height not finite");
        assert!(
            cells.iter().all(|&c| (c as usize) < progress.cells as usize),
            "periodic {periodic}: a pixel in no cell"
        );
    }
}

/// Finding 15: a periodic one-level skin stretched 10³⁰ times along x, its square lattice
/// nearly unjittered: Voronoi vertices of nearly collinear centres lie far past `i64`'s
/// fixed point, whose rounding saturated and then overflowed as each periodic image's
/// offset was added (`HIBI_ERROR_PANIC` in a build with overflow checks, as the test
/// command's debug profile builds hibi-core; in release the sum wrapped). Such a position
/// now saturates, offset included, and the shared edges' keys take the offset off and put it
/// back in two's complement, alike in every build.
#[test]
fn a_periodic_skin_stretched_past_the_fixed_point_builds_and_renders() {
    let mut params = hibi_skin_params_default();
    (params.layout, params.jitter, params.periodic) = (HIBI_SKIN_LAYOUT_SQUARE, HIBI_SPREAD_NORMAL, 1);
    (params.width, params.height, params.seed) = (45, 46, 18404354334592713153);
    (params.jitter_ratio, params.levels) = (1.4397879e-16, 1);
    let level = &mut params.level[0];
    (level.spacing, level.perturbation, level.perturbation_decay, level.perturbation_depth) =
        (40.507813, 0.1, 1.0126953, 1);
    level.stretch = [1e30, 1.0];
    let pixels = 45 * 46;
    let mut height = vec![f32::NAN; pixels];
    let render = hibi_skin_render_params { cell_level: 0, ..hibi_skin_render_params_default() };
    let mut skin = core::ptr::null_mut();
    let mut progress = hibi_skin_progress::default();
    // SAFETY: valid pointers, a buffer of the length passed.
    unsafe {
        assert_eq!(hibi_skin_create(&params, &mut skin), HIBI_OK);
        assert_eq!(hibi_skin_step(skin, u64::MAX, &mut progress), HIBI_OK);
        let layer = HIBI_SKIN_LAYER_HEIGHT;
        assert_eq!(hibi_skin_render(skin, &render, layer, height.as_mut_ptr().cast(), pixels), HIBI_OK);
        hibi_skin_destroy(skin);
    }
    assert!(progress.finished == 1 && progress.cells > 0, "{progress:?}");
    assert!(height.iter().all(|h| h.is_finite()), "a height not finite");
}

/// The fragments of a plate as they stand, through the C ABI: the number of rings and the sum
/// of their signed areas (outer rings positive, holes negative) in f64.
///
/// # Safety
///
/// `glass` must be a live plate.
unsafe fn fragment_area(glass: *mut hibi_glass) -> (usize, f64) {
    // SAFETY: as this function's.
    let (rings, _) = unsafe { fragments(glass) };
    (rings.len(), rings.iter().map(|ring| ring.area).sum())
}

/// The fragments of a plate as they stand, through the C ABI: their rings and points.
///
/// # Safety
///
/// `glass` must be a live plate.
unsafe fn fragments(glass: *mut hibi_glass) -> (Vec<hibi_core::polygon::Ring>, Vec<hibi_vec2>) {
    let mut size = 0;
    let (mut rings, mut points) = (0, 0);
    // SAFETY (every call below): a live plate, buffers of the lengths passed.
    unsafe {
        assert_eq!(hibi_glass_scratch_size(glass, &mut size), HIBI_OK);
        let mut scratch = vec![0u64; size.div_ceil(8)];
        let status = hibi_glass_fragment_counts(glass, scratch.as_mut_ptr().cast(), size, &mut rings, &mut points);
        assert_eq!(status, HIBI_OK);
        let mut ring_buf = vec![hibi_core::polygon::Ring::default(); rings];
        let mut point_buf = vec![hibi_vec2::default(); points];
        let (mut r, mut p) = (0, 0);
        let status = hibi_glass_fragments(
            glass,
            scratch.as_mut_ptr().cast(),
            size,
            ring_buf.as_mut_ptr(),
            rings,
            point_buf.as_mut_ptr(),
            points,
            &mut r,
            &mut p,
        );
        assert_eq!((status, r, p), (HIBI_OK, rings, points));
        (ring_buf, point_buf)
    }
}

/// Asserts that the fragments of `glass` and their convex pieces each cover the `plate` px² of
/// the plate (within 10⁻⁴), through the C ABI.
///
/// # Safety
///
/// `glass` must be a live plate.
unsafe fn fragments_and_pieces_cover(glass: *mut hibi_glass, plate: f64) {
    // SAFETY: the caller's.
    let (rings, points) = unsafe { fragments(glass) };
    let area: f64 = rings.iter().map(|ring| ring.area).sum();
    assert!((area - plate).abs() <= 1e-4 * plate, "{} rings cover {area} of {plate} px²", rings.len());
    let pieces = pieces_area(&rings, &points);
    assert!((pieces - plate).abs() <= 1e-4 * plate, "pieces cover {pieces} of {plate} px²");
}

/// The area the convex pieces of `rings` (for a physics engine) cover, through the C ABI.
fn pieces_area(rings: &[hibi_core::polygon::Ring], points: &[hibi_vec2]) -> f64 {
    let (rp, pp) = (rings.as_ptr(), points.as_ptr());
    let (mut words, mut triangles, mut pieces, mut written) = (0, 0, 0, 0);
    // SAFETY: valid buffers of the lengths passed.
    unsafe {
        assert_eq!(hibi_pieces_scratch_size(rp, rings.len(), pp, points.len(), &mut words), HIBI_OK);
        let mut scratch = vec![0u32; words];
        let s = scratch.as_mut_ptr();
        let status = hibi_pieces_counts(rp, rings.len(), pp, points.len(), s, words, &mut triangles, &mut pieces);
        assert_eq!(status, HIBI_OK);
        let mut convex = vec![hibi_core::polygon::ConvexPiece::default(); pieces];
        let status =
            hibi_convex_pieces(rp, rings.len(), pp, points.len(), s, words, convex.as_mut_ptr(), pieces, &mut written);
        assert_eq!((status, written), (HIBI_OK, pieces));
        let mut twice = 0.0;
        for piece in &convex {
            let n = piece.point_count as usize;
            for k in 0..n {
                let [a, b] = [piece.points[k], piece.points[(k + 1) % n]].map(|i| points[i as usize]);
                twice += f64::from(a.x) * f64::from(b.y) - f64::from(b.x) * f64::from(a.y);
            }
        }
        0.5 * twice
    }
}

/// Finding 16: an impact at x = `FLT_MIN` on a 4 × 4 plate. The 53 cracks heading left from it
/// reach the left edge after `FLT_MIN` px, all at (0, 2), each at its own vertex; the border
/// edges between those vertices have no length, and the zero vector's pseudo-angle (0, to the
/// right) put them among the cracks around each vertex. The walk around the outside of the
/// plate left the border there and took the fragment between the left edge and the cracks to
/// (0, 2) and to the top edge with it: 10 rings covered 15.914 of the plate's 16 px². A border
/// edge of no length now runs along its side; the rings' signed areas add up to the plate's.
#[test]
fn fragments_of_an_impact_a_hair_from_the_edge_cover_the_plate() {
    let mut params = hibi_glass_params_default();
    (params.width, params.height, params.impact) = (4.0, 4.0, [f32::MIN_POSITIVE, 2.0]);
    params.seed = 216_269_917_094_150_403;
    (params.large_slope, params.spread) = (f32::MIN_POSITIVE, HIBI_SPREAD_UNIFORM);
    (params.max_cracks, params.max_vertices) = (115, 115);
    let mut glass = core::ptr::null_mut();
    let mut progress = hibi_glass_progress::default();
    // SAFETY: valid pointers; a live plate.
    unsafe {
        assert_eq!(hibi_glass_create(&params, &mut glass), HIBI_OK);
        assert_eq!(hibi_glass_step(glass, 16_384, &mut progress), HIBI_OK);
        let (rings, area) = fragment_area(glass);
        assert!((area - 16.0).abs() <= 1e-4 * 16.0, "{rings} rings cover {area} of 16 px²");
        hibi_glass_destroy(glass);
    }
}

/// Finding 17: a second impact at the first one's point (33.5, 20) on a 67 × 40 plate. The
/// second hub was a vertex of its own at the same place: a crack's move sees no crack at its
/// very start, so the two hubs' cracks crossed near it with no vertex between them, the face
/// walks made a fragment ring that passed the hub five times and crossed itself, and its
/// convex pieces covered 2,945.5 of the plate's 2,680 px² (the rings' signed areas still added
/// up). An impact (or a ring crack's start point) on an earlier crack now starts from its
/// vertex, or splits the segment it lies on.
#[test]
fn a_second_impact_at_the_first_ones_point_keeps_the_fragments_simple() {
    let mut params = hibi_glass_params_default();
    (params.width, params.height, params.impact) = (67.0, 40.0, [33.5, 20.0]);
    params.seed = 15_854_078_063_242_042_368;
    (params.spread, params.sector_radius) = (HIBI_SPREAD_UNIFORM, 6.085_084e-39);
    (params.max_cracks, params.max_vertices) = (252, 319);
    let mut glass = core::ptr::null_mut();
    let mut progress = hibi_glass_progress::default();
    let plate = 67.0 * 40.0;
    // SAFETY: valid pointers; a live plate.
    unsafe {
        assert_eq!(hibi_glass_create(&params, &mut glass), HIBI_OK);
        assert_eq!(hibi_glass_step(glass, 16_384, &mut progress), HIBI_OK);
        assert_eq!(hibi_glass_step(glass, 9_738, &mut progress), HIBI_OK);
        assert_eq!(hibi_glass_impact(glass, 33.5, 20.0, core::ptr::null_mut()), HIBI_OK);
        for _ in 0..2 {
            assert_eq!(hibi_glass_step(glass, 16_384, &mut progress), HIBI_OK);
        }
        fragments_and_pieces_cover(glass, plate);
        hibi_glass_destroy(glass);
    }
}

/// Finding 18: an impact `FLT_MIN` above the bottom edge of a 131 × 129 plate. The fragment
/// around the plate passed the impact three times and had a spike whose tip lay `FLT_MIN`
/// above the plate's corner below the impact. Seen from the spike's other corners, 10 px
/// away, the f64 cross products put that corner on the spike's edge, so the ear clipping saw
/// no ear, clipped the largest corner anyway, and `hibi_pieces_counts` refused the valid ring
/// with `HIBI_ERROR_RING_CROSSES`. The ear tests' orientations are now exact.
#[test]
fn fragments_of_an_impact_flt_min_above_the_edge_cut_into_pieces() {
    let mut params = hibi_glass_params_default();
    (params.width, params.height, params.impact) = (131.0, 129.0, [65.5, f32::MIN_POSITIVE]);
    params.seed = 2_077_957_313_077_646_640;
    (params.max_cracks, params.max_vertices) = (199, 2657);
    let mut glass = core::ptr::null_mut();
    let mut progress = hibi_glass_progress::default();
    let plate = 131.0 * 129.0;
    // SAFETY: valid pointers; a live plate.
    unsafe {
        assert_eq!(hibi_glass_create(&params, &mut glass), HIBI_OK);
        for _ in 0..2 {
            assert_eq!(hibi_glass_step(glass, 16_384, &mut progress), HIBI_OK);
        }
        fragments_and_pieces_cover(glass, plate);
        hibi_glass_destroy(glass);
    }
}
