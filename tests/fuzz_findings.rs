//! Regression tests for what fuzzing the C ABI found (issue 25 item 2; `docs/fuzzing.md`
//! lists each finding). Each case is the smallest input found that reached
//! `HIBI_ERROR_PANIC`, called through the C ABI as the fuzz target called it.

use hibi::*;

/// Finding 1: a skin level whose stretch is tiny (`FLT_MIN`) asks for about 1e39 centre
/// points across an axis. Its lattice count saturated at `i64::MAX`, and sizing the memory
/// overflowed (a panic in `hibi_skin_memory_size` and `hibi_skin_create`). It is now a
/// surface too large for memory, on every level, periodic or not.
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
                assert_eq!(status, HIBI_ERROR_SKIN_CAPACITY_PARAMS, "periodic {periodic}, level {level}, axis {axis}");
                assert_eq!(size, usize::MAX, "nothing written");
                let mut skin = core::ptr::null_mut();
                // SAFETY: valid pointers.
                let status = unsafe { hibi_skin_create(&params, &mut skin) };
                assert_eq!(status, HIBI_ERROR_SKIN_CAPACITY_PARAMS);
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
