//! Stack: every model's scratch that grows with its parameters lives in caller memory (a skin
//! render's fixed 2 KiB of crossing slots is on the stack), and no public function needs more
//! than 16 KiB of stack. A thread with a 32 KiB stack runs every model end to end (create,
//! step, run, every output, render, on both backends; an overflow aborts the test process); the
//! same calls on a larger thread are each measured on their own: the stack is painted below the
//! call, and the deepest painted word it overwrote gives its peak, which must stay within
//! 16 KiB. The golden scenes, whose harness adds frames of its own (about 13 KB in release),
//! run in a thread of 64 KiB and must match. The guide's Platforms page gives the figures (in release: `cargo
//! test --release --test stack -- --nocapture`).

use std::hint::black_box;

use hibi_scenes::{Memory, check};

/// The models' thread's stack: 32 KiB in an optimised build (as glibc counts it: its guard
/// page and the thread's TLS come out of it). A debug build of the library (debug assertions,
/// overflow checks) has larger frames and gets 64 KiB.
const THREAD_STACK: usize = if cfg!(debug_assertions) { 64 * 1024 } else { 32 * 1024 };
/// The golden scenes' thread's stack.
const SCENES_STACK: usize = 64 * 1024;
/// The most stack one public function may use, from its caller's frame.
const LIMIT: usize = 16 * 1024;
#[test]
fn every_golden_scene_runs_in_a_thread_of_64_kib() {
    let report = std::thread::Builder::new()
        .stack_size(SCENES_STACK)
        .spawn(|| {
            let mut memory = Memory::take().expect("the only test that takes the scenes' memory");
            let mut report = String::new();
            let differ = check(&mut memory, "host, 64 KiB thread", &mut report).expect("a String takes every line");
            (differ, report)
        })
        .expect("a thread")
        .join()
        .expect("the scenes ran");
    assert_eq!(report.0, 0, "golden scenes differ:\n{}", report.1);
}

/// The calls made and, when measuring, each one's stack peak.
struct Calls {
    measure: bool,
    peaks: Vec<(&'static str, usize)>,
}

/// Runs `f` on this thread (with the stack painted below this frame when measuring, and its
/// peak recorded).
#[inline(never)]
fn measured<R>(calls: &mut Calls, name: &'static str, f: impl FnOnce() -> R) -> R {
    if !calls.measure {
        return f();
    }
    // SAFETY: the measuring thread has a stack of 1 MiB, of which this frame's callers use
    // far less than the 512 KiB left below MEASURED.
    let (result, peak) = unsafe { hibi_scenes::stack::measured(MEASURED, f) };
    calls.peaks.push((name, peak));
    result
}

/// Bytes painted below a measured call (its thread has a stack of 1 MiB).
const MEASURED: usize = 512 * 1024;

/// Every public function of every model, each measured on its own (new, run, step, every
/// output, render), on both backends where there are two.
fn every_public_function(peaks: &mut Calls) {
    use hibi_core::glass::{Glass, GlassParams, GlassRender};
    use hibi_core::mud::{Mud, MudParams, MudRender};
    use hibi_core::scalar::Q16;
    use hibi_core::skin::{ShadeParams, Skin, SkinLayers, SkinParams, SkinRender, preset, shade};

    let params = MudParams { columns: 32, rows: 32, ..MudParams::default() };
    let mut store = params.memory().expect("valid").allocate::<f32>();
    let mut mud = measured(peaks, "Mud::new", || Mud::new(&params, store.buffers()).expect("memory suffices"));
    measured(peaks, "Mud::step", || mud.step(1000).expect("stable"));
    measured(peaks, "Mud::run", || mud.run().expect("stable"));
    let counts = mud.network_counts();
    let (mut v, mut e, mut p) = (
        vec![Default::default(); counts.vertices],
        vec![Default::default(); counts.edges],
        vec![Default::default(); counts.points],
    );
    measured(peaks, "Mud::network", || mud.network(&mut v, &mut e, &mut p).expect("sized"));
    let (mut rings, mut points) = (vec![Default::default(); 4096], vec![[0.0; 2]; 65536]);
    measured(peaks, "Mud::cells", || mud.cells(&mut rings, &mut points).expect("sized"));
    measured(peaks, "Mud::statistics", || mud.statistics());
    let mut segments = vec![Default::default(); mud.segment_count()];
    measured(peaks, "Mud::segments", || mud.segments(&mut segments).expect("sized"));
    let mut every = hibi_tests::EveryLayer::new(128, 128);
    let render = MudRender { width: 128, height: 128, ..MudRender::default() };
    measured(peaks, "Mud::render", || mud.render(&render, every.layers(true)).expect("sized"));
    let mut store = params.memory().expect("valid").allocate::<Q16>();
    let mut mud = measured(peaks, "Mud<Q16>::new", || Mud::new(&params, store.buffers()).expect("memory suffices"));
    measured(peaks, "Mud<Q16>::run", || mud.run().expect("stable"));
    let explicit = MudParams { solver: hibi_core::mud::Solver::Explicit, columns: 16, rows: 16, ..params };
    let mut store = explicit.memory().expect("valid").allocate::<f32>();
    let mut mud = measured(peaks, "Mud::new (explicit)", || Mud::new(&explicit, store.buffers()).expect("memory"));
    measured(peaks, "Mud::step (explicit)", || mud.step(100_000).expect("stable"));
    let irregular = MudParams { topology: hibi_core::mud::Topology::Irregular, ..params };
    let mut store = irregular.memory().expect("valid").allocate::<f32>();
    let mut mud = measured(peaks, "Mud::new (irregular)", || Mud::new(&irregular, store.buffers()).expect("memory"));
    measured(peaks, "Mud::run (irregular)", || mud.run().expect("stable"));

    let params = GlassParams { width: 160.0, height: 160.0, impact: [80.0; 2], seed: 7, ..GlassParams::default() };
    let glass_memory = params.memory().expect("valid");
    let (mut store, mut scratch) = (glass_memory.allocate(), vec![0; glass_memory.scratch]);
    let mut glass = measured(peaks, "Glass::new", || Glass::new(&params, store.buffers()).expect("memory suffices"));
    measured(peaks, "Glass::step", || glass.step(1000));
    measured(peaks, "Glass::run", || glass.run());
    measured(peaks, "Glass::impact", || glass.impact([40.0, 60.0]).expect("room for a second impact"));
    measured(peaks, "Glass::run (second impact)", || glass.run());
    let mut crack_points = vec![Default::default(); glass.point_count(0)];
    measured(peaks, "Glass::points", || glass.points(0, &mut crack_points).expect("sized"));
    measured(peaks, "Glass::fragment_counts", || glass.fragment_counts(&mut scratch).expect("sized"));
    measured(peaks, "Glass::fragments", || glass.fragments(&mut scratch, &mut rings, &mut points).expect("sized"));
    let render = GlassRender { width: 160, height: 160, ..GlassRender::default() };
    let mut every = hibi_tests::EveryLayer::new(160, 160);
    measured(peaks, "Glass::render", || glass.render(&render, every.layers(true)).expect("sized"));

    let params = SkinParams { width: 64, height: 64, ..preset("fig19a").expect("a preset") };
    let memory = measured(peaks, "SkinParams::memory", || params.memory().expect("valid"));
    let mut store = memory.allocate();
    let mut skin = measured(peaks, "Skin::new", || Skin::<f32>::new(&params, store.buffers()).expect("memory"));
    measured(peaks, "Skin::step", || skin.step(1000));
    measured(peaks, "Skin::run", || skin.run());
    let mut every = hibi_tests::EveryLayer::new(64, 64);
    let render = SkinRender { cell_level: 2, ..SkinRender::default() };
    measured(peaks, "Skin::render", || skin.render(&render, every.layers(false)).expect("sized"));
    let (mut height, mut normal, mut cell) = (vec![0.0; 64 * 64], vec![[0.0; 3]; 64 * 64], vec![0u32; 64 * 64]);
    let layers = SkinLayers { cell: Some(&mut cell), ..SkinLayers::default() };
    measured(peaks, "Skin::render (cells)", || skin.render(&SkinRender::default(), layers).expect("sized"));
    let longest = *skin.cells().iter().max_by_key(|c| c.vertex_count).expect("cells");
    measured(peaks, "Skin::outline", || black_box(skin.outline(&longest).len()));
    measured(peaks, "Skin::for_each_pixel", || skin.for_each_pixel(&longest, |x, y| _ = black_box((x, y))));
    let mut rgb = vec![[0u8; 3]; 64 * 64];
    measured(peaks, "skin::shade", || shade(&height, &normal, &ShadeParams::default(), &mut rgb).expect("sized"));
    let mut skin = measured(peaks, "Skin<Q16>::new", || Skin::<Q16>::new(&params, store.buffers()).expect("memory"));
    measured(peaks, "Skin<Q16>::run", || skin.run());
    let layers = SkinLayers { height: Some(&mut height), normal: Some(&mut normal), ..SkinLayers::default() };
    measured(peaks, "Skin<Q16>::render", || skin.render(&SkinRender::default(), layers).expect("sized"));
}

/// The C ABI's calls that do a model's work, each measured on its own as a C caller makes it
/// (the entry point's argument checks and panic guard included).
fn every_c_entry_point(peaks: &mut Calls) {
    use hibi::*;
    use std::ffi::c_void;

    // SAFETY (the whole block): every pointer passed is valid for the length given with it,
    // each object is destroyed once, after its last use.
    unsafe {
        let mut mud = hibi_mud_params_default();
        (mud.columns, mud.rows) = (32, 32);
        let mut m = core::ptr::null_mut();
        assert_eq!(measured(peaks, "hibi_mud_create", || hibi_mud_create(&mud, &mut m)), HIBI_OK);
        let mut progress = hibi_mud_progress::default();
        measured(peaks, "hibi_mud_step", || hibi_mud_step(m, u64::MAX, &mut progress));
        assert_ne!(progress.finished, 0);
        let (mut count, mut written) = (0, 0);
        assert_eq!(hibi_mud_segment_count(m, &mut count), HIBI_OK);
        let mut segments = vec![hibi_core::mud::CrackSegment::default(); count];
        let status =
            measured(peaks, "hibi_mud_segments", || hibi_mud_segments(m, segments.as_mut_ptr(), count, &mut written));
        assert_eq!(status, HIBI_OK);
        let (mut rings, mut points, mut wrapping) = (0, 0, 0);
        assert_eq!(hibi_mud_cell_counts(m, &mut rings, &mut points, &mut wrapping), HIBI_OK);
        let mut ring = vec![hibi_core::polygon::Ring::default(); rings];
        let mut point = vec![core::mem::zeroed::<hibi_vec2>(); points];
        let status = measured(peaks, "hibi_mud_cells", || {
            hibi_mud_cells(m, ring.as_mut_ptr(), rings, point.as_mut_ptr(), points, &mut written, &mut count)
        });
        assert_eq!(status, HIBI_OK);
        let mut render = hibi_mud_render_params_default();
        (render.width, render.height) = (128, 128);
        let mut pixels = vec![0f32; 128 * 128];
        let status = measured(peaks, "hibi_mud_render", || {
            hibi_mud_render(m, &render, HIBI_MUD_LAYER_HEIGHT, pixels.as_mut_ptr().cast::<c_void>(), pixels.len())
        });
        assert_eq!(status, HIBI_OK);
        hibi_mud_destroy(m);

        let mut glass = hibi_glass_params_default();
        (glass.width, glass.height, glass.impact, glass.seed) = (160.0, 160.0, [80.0; 2], 7);
        let mut g = core::ptr::null_mut();
        assert_eq!(measured(peaks, "hibi_glass_create", || hibi_glass_create(&glass, &mut g)), HIBI_OK);
        let mut progress = hibi_glass_progress::default();
        measured(peaks, "hibi_glass_step", || hibi_glass_step(g, u64::MAX, &mut progress));
        assert_ne!(progress.finished, 0);
        let mut size = 0;
        assert_eq!(hibi_glass_scratch_size(g, &mut size), HIBI_OK);
        let mut scratch = vec![0u64; size.div_ceil(8)];
        let (mut rings, mut points) = (0, 0);
        let status = measured(peaks, "hibi_glass_fragment_counts", || {
            hibi_glass_fragment_counts(g, scratch.as_mut_ptr().cast(), size, &mut rings, &mut points)
        });
        assert_eq!(status, HIBI_OK);
        let mut ring = vec![hibi_core::polygon::Ring::default(); rings];
        let mut point = vec![core::mem::zeroed::<hibi_vec2>(); points];
        let (mut rings_written, mut points_written) = (0, 0);
        let status = measured(peaks, "hibi_glass_fragments", || {
            let (r, p) = (ring.as_mut_ptr(), point.as_mut_ptr());
            hibi_glass_fragments(
                g,
                scratch.as_mut_ptr().cast(),
                size,
                r,
                rings,
                p,
                points,
                &mut rings_written,
                &mut points_written,
            )
        });
        assert_eq!(status, HIBI_OK);
        let mut render = hibi_glass_render_params_default();
        (render.width, render.height) = (160, 160);
        let mut pixels = vec![0f32; 160 * 160];
        let status = measured(peaks, "hibi_glass_render", || {
            hibi_glass_render(g, &render, HIBI_GLASS_LAYER_TIME, pixels.as_mut_ptr().cast::<c_void>(), pixels.len())
        });
        assert_eq!(status, HIBI_OK);
        hibi_glass_destroy(g);

        let mut skin = core::mem::zeroed::<hibi_skin_params>();
        assert_eq!(hibi_skin_params_preset(c"fig19a".as_ptr(), &mut skin), HIBI_OK);
        (skin.width, skin.height) = (64, 64);
        let mut k = core::ptr::null_mut();
        assert_eq!(measured(peaks, "hibi_skin_create", || hibi_skin_create(&skin, &mut k)), HIBI_OK);
        let mut progress = hibi_skin_progress::default();
        measured(peaks, "hibi_skin_step", || hibi_skin_step(k, u64::MAX, &mut progress));
        assert_ne!(progress.finished, 0);
        let render = hibi_skin_render_params_default();
        let (mut height, mut normal) = (vec![0f32; 64 * 64], vec![0f32; 3 * 64 * 64]);
        let status = measured(peaks, "hibi_skin_render", || {
            hibi_skin_render(k, &render, HIBI_SKIN_LAYER_NORMAL, normal.as_mut_ptr().cast::<c_void>(), normal.len())
        });
        assert_eq!(status, HIBI_OK);
        let status =
            hibi_skin_render(k, &render, HIBI_SKIN_LAYER_HEIGHT, height.as_mut_ptr().cast::<c_void>(), height.len());
        assert_eq!(status, HIBI_OK);
        let shade = hibi_skin_shade_params_default();
        let mut rgb = vec![0u8; 3 * 64 * 64];
        let status = measured(peaks, "hibi_skin_shade", || {
            let (h, n) = (height.as_ptr(), normal.as_ptr());
            hibi_skin_shade(h, height.len(), n, normal.len(), &shade, rgb.as_mut_ptr(), rgb.len())
        });
        assert_eq!(status, HIBI_OK);
        hibi_skin_destroy(k);
    }
}

#[test]
fn every_model_runs_end_to_end_in_a_thread_of_32_kib_in_release() {
    std::thread::Builder::new()
        .stack_size(THREAD_STACK)
        .spawn(|| {
            let mut calls = Calls { measure: false, peaks: Vec::new() };
            every_public_function(&mut calls);
            every_c_entry_point(&mut calls);
        })
        .expect("a thread")
        .join()
        .expect("every model ran");
}

#[test]
fn no_public_function_of_a_model_or_c_entry_point_needs_more_than_16_kib_of_stack() {
    let peaks = std::thread::Builder::new()
        .stack_size(1 << 20)
        .spawn(|| {
            let mut calls = Calls { measure: true, peaks: Vec::new() };
            every_public_function(&mut calls);
            every_c_entry_point(&mut calls);
            calls.peaks
        })
        .expect("a thread")
        .join()
        .expect("every model ran");
    let report: String = peaks.iter().map(|(name, peak)| format!("{name:28} {peak:6} bytes of stack\n")).collect();
    println!("{report}");
    let over: Vec<_> = peaks.iter().filter(|(_, peak)| *peak > LIMIT).collect();
    assert!(over.is_empty(), "functions over {LIMIT} bytes of stack: {over:?}\n{report}");
}
