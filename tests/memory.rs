//! Memory that follows the work: each model's memory need is a function of its parameters, the
//! one `new` (Rust) and `*_create_in` (C) check, and it is exact: one element (one byte) less
//! is refused with a clear status, the need itself suffices to build and render. A 64×64
//! one-level skin needs 8.4 KiB (8 608 bytes of arrays, `cargo test --release --test
//! memory -- --nocapture`), and a render nothing more: cells, vertices and their wedges only
//! for the centre points that can reach the surface, its vertices bounded by the planar
//! Delaunay graph's edges and by the faces of the divided surface, a neighbour window of the
//! centre points within twice the covering radius (25 of them at jitter 0.5), clip buffers for
//! a clipped outline among them, and of the per-level records only what level 0 reads; not the
//! 12 960 bytes with a whole level record (profile table, shared edges, edge grid and edge
//! scratch, 6.4 KB), the 19 296 of a fixed 81-point window, the 110 KB it needed at first, nor
//! the 434 KB of fixed capacities before that. Most of it (4.7 KB) does not grow with the
//! image: the level's profile table (2.1 KB), the window (1.2 KB) and two clip buffers
//! (1.4 KB). A finer level adds its division (edge grid and crossing scratch), and a level that
//! keeps edges for its cells' neighbours its shared edges.
use core::ffi::c_void;

use hibi::*;
use hibi_core::skin::{Skin, SkinBuffers, SkinError, SkinLayers, SkinMemory, SkinParams, SkinRender, preset};

/// Bytes of a skin's arrays (all a build and a render need; a render's working memory is a few
/// KiB of stack).
fn skin_bytes(m: &SkinMemory) -> usize {
    use hibi_core::skin::{ClipVertex, Site, SkinCell, SkinDivision, SkinLevel, SkinSharedEdges};
    m.cells * size_of::<SkinCell>()
        + m.vertices * 16
        + m.sites * size_of::<Site>()
        + m.clip * size_of::<ClipVertex>()
        + m.words * 4
        + m.levels * size_of::<SkinLevel>()
        + m.divisions * size_of::<SkinDivision>()
        + m.shared_edges * size_of::<SkinSharedEdges>()
        + m.boxes * 32
        + m.wedges * size_of::<hibi_core::skin::Wedge>()
}

/// Builds and renders `params` in buffers of exactly `m` elements, or with the array `short`
/// (0 to 9, in `SkinBuffers` order) one element short.
fn skin_in(params: &SkinParams, m: &SkinMemory, short: Option<usize>) -> Result<(), SkinError> {
    let less = |k: usize, n: usize| if short == Some(k) { n - 1 } else { n };
    let mut cells = vec![Default::default(); less(0, m.cells)];
    let mut vertices = vec![[0; 2]; less(1, m.vertices)];
    let mut sites = vec![Default::default(); less(2, m.sites)];
    let mut clip = vec![Default::default(); less(3, m.clip)];
    let mut words = vec![0; less(4, m.words)];
    let mut levels = vec![Default::default(); less(5, m.levels)];
    let mut divisions = vec![Default::default(); less(6, m.divisions)];
    let mut shared_edges = vec![Default::default(); less(7, m.shared_edges)];
    let mut boxes = vec![[0; 4]; less(8, m.boxes)];
    let mut wedges = vec![Default::default(); less(9, m.wedges)];
    let buffers = SkinBuffers {
        cells: &mut cells,
        vertices: &mut vertices,
        sites: &mut sites,
        clip: &mut clip,
        words: &mut words,
        levels: &mut levels,
        divisions: &mut divisions,
        shared_edges: &mut shared_edges,
        boxes: &mut boxes,
        wedges: &mut wedges,
    };
    let mut skin = Skin::<f32>::new(params, buffers)?;
    assert!(!skin.run().capacity_reached, "the capacities suffice");
    let pixels = (params.width * params.height) as usize;
    let (mut height, mut cell) = (vec![0.0; pixels], vec![0u32; pixels]);
    let layers = SkinLayers { height: Some(&mut height), cell: Some(&mut cell), ..SkinLayers::default() };
    skin.render(&SkinRender { cell_level: params.levels - 1, ..SkinRender::default() }, layers)?;
    assert!(cell.iter().all(|&c| c != hibi_core::skin::NO_CELL), "every pixel lies in a cell");
    Ok(())
}

#[test]
fn a_skin_needs_exactly_its_memory() {
    let one = SkinParams { width: 64, height: 64, ..SkinParams::default() };
    let three = SkinParams { width: 64, height: 64, ..preset("fig19a").expect("a preset") };
    // Neighbour windows of other shapes (`Lattice::columns_within`): a square lattice of full
    // jitter, perturbed (to depth 2: level 0 keeps its edges); a periodic random layout,
    // stretched.
    let mut square = SkinParams { width: 72, height: 50, layout: hibi_core::skin::SiteLayout::Square, ..one };
    square.jitter_ratio = 1.0;
    (square.level[0].perturbation, square.level[0].spacing) = (0.2, 12.0);
    square.level[0].perturbation_depth = 2;
    let mut random = SkinParams { periodic: true, layout: hibi_core::skin::SiteLayout::Random, ..one };
    (random.level[0].stretch, random.level[0].spacing) = ([1.5, 0.8], 9.0);
    for params in [one, three, square, random] {
        let m = params.memory().expect("valid");
        skin_in(&params, &m, None).expect("the exact need suffices");
        let needs =
            [m.cells, m.vertices, m.sites, m.clip, m.words, m.levels, m.divisions, m.shared_edges, m.boxes, m.wedges];
        for (k, &needed) in needs.iter().enumerate().filter(|(_, n)| **n > 0) {
            assert_eq!(skin_in(&params, &m, Some(k)), Err(SkinError::BufferTooSmall { needed }), "array {k} short");
        }
    }
}

#[test]
fn a_64_by_64_one_level_skin_needs_its_own_capacities_only() {
    let params = SkinParams { width: 64, height: 64, ..SkinParams::default() };
    assert_eq!(params.levels, 1);
    let bytes = skin_bytes(&params.memory().expect("valid"));
    let fig19a = SkinParams { width: 64, height: 64, ..preset("fig19a").expect("a preset") };
    let three = skin_bytes(&fig19a.memory().expect("valid"));
    println!("skin 64x64: one level (default) {bytes} bytes; fig19a (three levels) {three} bytes");
    use hibi_core::skin::{SkinDivision, SkinLevel, SkinSharedEdges};
    let records = [size_of::<SkinLevel>(), size_of::<SkinDivision>(), size_of::<SkinSharedEdges>()];
    println!("skin records: level, division, shared edges {records:?} bytes");
    assert!(bytes < 9 * 1024, "{bytes} bytes");
    // The C library's need: the arrays, the object's header and alignment.
    let mut c = hibi_skin_params_default();
    (c.width, c.height) = (64, 64);
    let mut size = 0;
    // SAFETY: valid pointers.
    assert_eq!(unsafe { hibi_skin_memory_size(&c, &mut size) }, HIBI_OK);
    assert!(size >= bytes && size < bytes + 4096, "{size} bytes for {bytes} of arrays");
}

#[test]
fn a_one_level_skin_never_outgrows_its_need() {
    // The need is a bound proven for every valid parameter set (`SkinParams::memory`): across
    // layouts, jitters, stretches, perturbations, sizes and periodic or not, a build in exactly
    // that memory never reaches a capacity.
    use hibi_core::{Spread, skin::SiteLayout};
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut unit = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f32 / (1u64 << 53) as f32
    };
    for case in 0..300 {
        let mut p = SkinParams { seed: case, ..SkinParams::default() };
        (p.width, p.height) = (1 + (unit() * 96.0) as u32, 1 + (unit() * 96.0) as u32);
        p.layout = [SiteLayout::Triangular, SiteLayout::Square, SiteLayout::Random][(unit() * 3.0) as usize % 3];
        p.jitter = if unit() < 0.5 { Spread::Uniform } else { Spread::Normal };
        p.jitter_ratio = if unit() < 0.2 { 1.0 } else { unit() };
        p.periodic = unit() < 0.25;
        let l = &mut p.level[0];
        l.spacing = 3.0 + unit() * unit() * 60.0;
        l.stretch = [0.5 + unit() * 2.0, 0.5 + unit() * 2.0];
        l.perturbation = if unit() < 0.5 { 0.0 } else { unit() * 0.4 };
        l.perturbation_depth = (unit() * 6.0) as u32 % 6;
        let m = p.memory().expect("valid");
        let mut store = m.allocate();
        let mut skin: Skin = Skin::new(&p, store.buffers()).expect("its need");
        let progress = skin.run();
        assert!(progress.finished && !progress.capacity_reached, "case {case}: {p:?}");
    }
}

/// The argument the last refused call named.
fn refused() -> String {
    // SAFETY: hibi_error_argument returns a static NUL-terminated string.
    unsafe { core::ffi::CStr::from_ptr(hibi_error_argument()) }.to_str().unwrap().to_string()
}

/// Creates an object in caller memory of `len` bytes; its status (the object destroyed).
///
/// # Safety
/// `create_in` and `destroy` must be a model's pair.
unsafe fn create_in<P, T>(
    params: &P,
    len: usize,
    create_in: unsafe extern "C" fn(*const P, *mut c_void, usize, *mut *mut T) -> hibi_status,
    destroy: unsafe extern "C" fn(*mut T),
) -> hibi_status {
    let mut memory = vec![0u64; len.div_ceil(8)];
    let mut out = core::ptr::null_mut();
    // SAFETY: `memory` holds `len` bytes, aligned to 8.
    let status = unsafe { create_in(params, memory.as_mut_ptr().cast(), len, &mut out) };
    if !out.is_null() {
        // SAFETY: made above, in `memory`, which is still alive.
        unsafe { destroy(out) };
    }
    status
}

#[test]
fn every_model_in_c_needs_exactly_its_memory_size() {
    let mut mud = hibi_mud_params_default();
    (mud.columns, mud.rows) = (16, 16);
    let mut glass = hibi_glass_params_default();
    (glass.width, glass.height, glass.impact) = (128.0, 128.0, [64.0; 2]);
    let mut skin = hibi_skin_params_default();
    (skin.width, skin.height) = (64, 64);
    let (mut sizes, mut size) = (Vec::new(), 0);
    // SAFETY: valid pointers; each create_in with its destroy.
    unsafe {
        assert_eq!(hibi_mud_memory_size(&mud, &mut size), HIBI_OK);
        assert_eq!(create_in(&mud, size - 1, hibi_mud_create_in, hibi_mud_destroy), HIBI_ERROR_BUFFER_TOO_SMALL);
        assert_eq!(create_in(&mud, size, hibi_mud_create_in, hibi_mud_destroy), HIBI_OK);
        sizes.push(("mud 16x16", size));
        assert_eq!(hibi_glass_memory_size(&glass, &mut size), HIBI_OK);
        let (make, destroy) = (hibi_glass_create_in, hibi_glass_destroy);
        assert_eq!(create_in(&glass, size - 1, make, destroy), HIBI_ERROR_BUFFER_TOO_SMALL);
        assert_eq!(create_in(&glass, size, make, destroy), HIBI_OK);
        sizes.push(("glass 128x128", size));
        assert_eq!(hibi_skin_memory_size(&skin, &mut size), HIBI_OK);
        let (make, destroy) = (hibi_skin_create_in, hibi_skin_destroy);
        assert_eq!(create_in(&skin, size - 1, make, destroy), HIBI_ERROR_BUFFER_TOO_SMALL);
        assert_eq!(create_in(&skin, size, make, destroy), HIBI_OK);
        sizes.push(("skin 64x64, one level", size));
    }
    // The scratch of the read-only queries, exact too: one byte less is refused, naming it.
    // SAFETY: valid pointers; each object destroyed once.
    unsafe {
        let mut g = core::ptr::null_mut();
        assert_eq!(hibi_glass_create(&glass, &mut g), HIBI_OK);
        let mut progress = hibi_glass_progress::default();
        while hibi_glass_step(g, 100_000, &mut progress) == HIBI_OK && progress.finished == 0 {}
        assert_eq!(hibi_glass_scratch_size(g, &mut size), HIBI_OK);
        let mut scratch = vec![0u64; size.div_ceil(8)];
        let (mut rings, mut points) = (0, 0);
        let short = hibi_glass_fragment_counts(g, scratch.as_mut_ptr().cast(), size - 1, &mut rings, &mut points);
        assert_eq!((short, refused()), (HIBI_ERROR_BUFFER_TOO_SMALL, "scratch".into()));
        let fits = hibi_glass_fragment_counts(g, scratch.as_mut_ptr().cast(), size, &mut rings, &mut points);
        assert!(fits == HIBI_OK && rings > 0 && points > 0);
        sizes.push(("glass 128x128 fragment scratch", size));
        hibi_glass_destroy(g);
    }
    println!("{sizes:?}");
}
