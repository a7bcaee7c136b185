//! Instruction-count benches that gate regressions: each bench's work counted by Callgrind
//! (instructions, so the same on every run of the same build), compared with its committed
//! baseline in [`BASELINE`]. A count more than [`TOLERANCE`] above its baseline fails the test,
//! as does a bench missing from the baseline or a baseline without its bench. The gate passes
//! again only when the baseline file itself is updated, in the commit that explains the rise:
//!
//!     cargo test --release --test instructions -- --nocapture     # the table and the check
//!     HIBI_BLESS=1 cargo test --release --test instructions       # rewrite the baseline
//!
//! The benches: mud (the default parameters at 64², f32, quasi-static) run, trace, network,
//! cells and each render layer at 256²; glass (the paper's 640² plate, M_ave = 100) generation,
//! fragments and each render layer; skin (the fig19a preset, 400²) build, each render layer and
//! one render of height and normal together (as `benches/skin.rs` times it); and the baseline
//! Model C is compared with, FastNoiseLite's cellular noise with a normal map by central
//! differences on the same 400² grid (`benches/support/cellular.rs`). The performance page's
//! table ends with the ratio of the two: skin's build and render of both maps over
//! FastNoiseLite's.
//! Every seed is fixed; buffers are allocated outside the counted calls. Counts are the release
//! profile's (the test is ignored in debug) and depend on the compiler and on Valgrind: the
//! baseline names both, and a machine with others fails with a message saying so. They leave
//! out the C library's `memset`, `memcpy` and `memmove`, whose code glibc picks by the CPU's
//! features (collection is toggled off inside `__mem*`), so that they are the same on every
//! x86_64 CPU.
//!
//! The whole run is one Callgrind run of this test binary, counting inside the functions
//! `hibi_bench_*` only (one per bench, what it calls included but the C library's `__mem*`).

use std::collections::BTreeMap;
use std::hint::black_box;
use std::path::PathBuf;

use hibi_core::glass::{Glass, GlassParams, GlassRender};
use hibi_core::mud::{Mud, MudParams, MudRender, NetworkEdge, NetworkPoint, NetworkVertex};
use hibi_core::polygon::Ring;
use hibi_core::raster::Layers;
use hibi_core::skin::{Skin, SkinLayers, SkinRender, preset};
use hibi_tests::EveryLayer;

#[path = "../benches/support/cellular.rs"]
mod cellular;

/// The committed baseline: one line per bench, `name count`, after a header naming the
/// compiler and Valgrind that counted it.
const BASELINE: &str = "benches/baselines/instructions.txt";
/// The performance page's table of the baseline's counts, written with the baseline.
const PAGE_TABLE: &str = "docs/src/generated/instructions.md";
/// How far above its baseline a count may be: 3 %.
const TOLERANCE: f64 = 0.03;
/// The environment variable that makes the test, run again under Callgrind, do the benches'
/// work (`all`), or the perturbed run that proves the gate can fail (`perturbed`).
const RUN: &str = "HIBI_INSTRUCTIONS_RUN";

/// A bench's counted call: the only functions Callgrind counts (found by their unmangled
/// names; each keeps its own body, so none is merged with another).
macro_rules! benches {
    ($($k:literal $name:ident $label:literal),* $(,)?) => {
        $(
            #[unsafe(no_mangle)]
            #[inline(never)]
            fn $name(work: &mut dyn FnMut()) {
                black_box($k);
                work();
            }
        )*
        /// Each bench's name (as in the baseline) and its counted call.
        const BENCHES: &[(&str, &str, fn(&mut dyn FnMut()))] = &[$(($label, stringify!($name), $name)),*];
    };
}

benches!(
    0 hibi_bench_mud_run "mud/run",
    1 hibi_bench_mud_trace "mud/trace",
    2 hibi_bench_mud_network "mud/network",
    3 hibi_bench_mud_cells "mud/cells",
    4 hibi_bench_mud_render_mask "mud/render/mask",
    5 hibi_bench_mud_render_height "mud/render/height",
    6 hibi_bench_mud_render_height16 "mud/render/height16",
    7 hibi_bench_mud_render_normal "mud/render/normal",
    8 hibi_bench_mud_render_normal_rgb8 "mud/render/normal_rgb8",
    9 hibi_bench_mud_render_time "mud/render/time",
    10 hibi_bench_mud_render_preview "mud/render/preview",
    11 hibi_bench_glass_generation "glass/generation",
    12 hibi_bench_glass_fragments "glass/fragments",
    13 hibi_bench_glass_render_mask "glass/render/mask",
    14 hibi_bench_glass_render_height "glass/render/height",
    15 hibi_bench_glass_render_height16 "glass/render/height16",
    16 hibi_bench_glass_render_normal "glass/render/normal",
    17 hibi_bench_glass_render_normal_rgb8 "glass/render/normal_rgb8",
    18 hibi_bench_glass_render_time "glass/render/time",
    19 hibi_bench_glass_render_preview "glass/render/preview",
    20 hibi_bench_skin_build "skin/build",
    21 hibi_bench_skin_render_mask "skin/render/mask",
    22 hibi_bench_skin_render_height "skin/render/height",
    23 hibi_bench_skin_render_height16 "skin/render/height16",
    24 hibi_bench_skin_render_normal "skin/render/normal",
    25 hibi_bench_skin_render_normal_rgb8 "skin/render/normal_rgb8",
    26 hibi_bench_skin_render_cell "skin/render/cell",
    27 hibi_bench_skin_render_preview "skin/render/preview",
    28 hibi_bench_skin_render_height_normal "skin/render/height_normal",
    29 hibi_bench_fastnoise_cellular_normal "fastnoise/cellular_normal",
);

/// Runs bench `name`'s work in its counted call.
fn bench(name: &str, mut work: impl FnMut()) {
    let (_, _, call) = BENCHES.iter().find(|b| b.0 == name).expect("a bench of the list");
    call(&mut work);
}

/// The layers a render can write, one at a time: the layer's name and the [`Layers`] holding
/// only it (and the scratch, which the derived layers need).
const LAYERS: [&str; 8] = ["mask", "height", "height16", "normal", "normal_rgb8", "time", "cell", "preview"];

fn one_layer<'a>(every: &'a mut EveryLayer, layer: &str) -> Layers<'a> {
    let mut layers = Layers { scratch: Some(&mut every.scratch), ..Layers::default() };
    match layer {
        "mask" => layers.mask = Some(&mut every.mask),
        "height" => layers.height = Some(&mut every.height),
        "height16" => layers.height16 = Some(&mut every.height16),
        "normal" => layers.normal = Some(&mut every.normal),
        "normal_rgb8" => layers.normal_rgb8 = Some(&mut every.normal_rgb8),
        "time" => layers.time = Some(&mut every.time),
        "cell" => layers.cell = Some(&mut every.cell),
        "preview" => layers.preview = Some(&mut every.preview),
        _ => unreachable!("a layer of LAYERS"),
    }
    layers
}

/// Whether bench `name` exists (a model's render has only some layers).
fn has(name: &str) -> bool {
    BENCHES.iter().any(|b| b.0 == name)
}

fn mud_benches() {
    let params = MudParams { columns: 64, rows: 64, ..MudParams::default() };
    let mut store = params.memory().expect("valid parameters").allocate::<f32>();
    let mut buffers = Some(store.buffers());
    let mut mud = None;
    bench("mud/run", || {
        let mut m = Mud::new(&params, buffers.take().expect("once")).expect("memory suffices");
        m.run().expect("a stable run");
        mud = Some(m);
    });
    let mut mud = mud.expect("the run");
    bench("mud/trace", || mud.trace());
    let n = mud.network_counts();
    let (mut vertices, mut edges, mut points) = (
        vec![NetworkVertex::default(); n.vertices],
        vec![NetworkEdge::default(); n.edges],
        vec![NetworkPoint::default(); n.points],
    );
    bench("mud/network", || {
        black_box(mud.network(&mut vertices, &mut edges, &mut points).expect("buffers suffice"));
    });
    let c = mud.cell_counts();
    let (mut rings, mut ring_points) = (vec![Ring::default(); c.rings], vec![[0.0f32; 2]; c.points]);
    bench("mud/cells", || {
        black_box(mud.cells(&mut rings, &mut ring_points).expect("buffers suffice"));
    });
    let render = MudRender::fit(mud.extent(), 256);
    let mut every = EveryLayer::new(render.width, render.height);
    for layer in LAYERS.into_iter().filter(|l| has(&format!("mud/render/{l}"))) {
        bench(&format!("mud/render/{layer}"), || {
            mud.render(&render, one_layer(&mut every, layer)).expect("buffers suffice");
        });
    }
}

/// The glass benches; `perturbed` renders the mask twice in its counted call (the run that
/// proves the gate fails on a rise).
fn glass_benches(perturbed: bool) {
    let params = GlassParams::default();
    let mut store = params.memory().expect("valid parameters").allocate();
    let mut buffers = Some(store.buffers());
    let mut glass = None;
    bench("glass/generation", || {
        let mut g = Glass::new(&params, buffers.take().expect("once")).expect("memory suffices");
        while !g.step(u64::MAX).finished {}
        glass = Some(g);
    });
    let glass = glass.expect("the plate");
    let mut scratch = vec![0u32; params.memory().expect("valid parameters").scratch];
    let (rings, points) = glass.fragment_counts(&mut scratch).expect("scratch suffices");
    let (mut rings, mut points) = (vec![Ring::default(); rings], vec![[0.0f32; 2]; points]);
    bench("glass/fragments", || {
        black_box(glass.fragments(&mut scratch, &mut rings, &mut points).expect("buffers suffice"));
    });
    let render = GlassRender::default();
    let mut every = EveryLayer::new(render.width, render.height);
    for layer in LAYERS.into_iter().filter(|l| has(&format!("glass/render/{l}"))) {
        if perturbed && layer != "mask" {
            continue;
        }
        bench(&format!("glass/render/{layer}"), || {
            for _ in 0..if perturbed { 2 } else { 1 } {
                glass.render(&render, one_layer(&mut every, layer)).expect("buffers suffice");
            }
        });
    }
}

fn skin_benches() {
    let params = preset("fig19a").expect("the preset");
    let mut store = params.memory().expect("valid parameters").allocate();
    let mut buffers = Some(store.buffers());
    let mut skin = None;
    bench("skin/build", || {
        let mut s = Skin::<f32>::new(&params, buffers.take().expect("once")).expect("memory suffices");
        s.run();
        skin = Some(s);
    });
    let skin = skin.expect("the skin");
    let render = SkinRender::default();
    let mut every = EveryLayer::new(params.width, params.height);
    for layer in LAYERS.into_iter().filter(|l| has(&format!("skin/render/{l}"))) {
        bench(&format!("skin/render/{layer}"), || {
            skin.render(&render, one_layer(&mut every, layer)).expect("buffers suffice");
        });
    }
    bench("skin/render/height_normal", || {
        let layers =
            SkinLayers { height: Some(&mut every.height), normal: Some(&mut every.normal), ..SkinLayers::default() };
        skin.render(&render, layers).expect("buffers suffice");
    });
}

/// FastNoiseLite's cellular noise, value and normal by central differences, on the skin
/// benches' 400² grid (Model C's speed is stated as a ratio to it).
fn fastnoise_benches() {
    let (w, h) = (400, 400);
    let noise = black_box(cellular::cellular());
    let mut grid = vec![0.0f32; (w + 2) * (h + 2)];
    let (mut height, mut normals) = (vec![0.0f32; w * h], vec![[0.0f32; 3]; w * h]);
    bench("fastnoise/cellular_normal", || cellular::on_grid(&noise, w, h, &mut grid, &mut height, &mut normals));
}

/// The compiler and Valgrind this machine counts with: the baseline's header.
fn toolchain() -> String {
    let version = |program: &str, arg: &str| {
        let out = hibi_tests::tool(program).arg(arg).output().expect("runs");
        String::from_utf8_lossy(&out.stdout).trim().to_owned()
    };
    let rustc = std::env::var("RUSTC").unwrap_or_else(|_| "rustc".to_owned());
    format!("{} | {}", version(&rustc, "-V"), version("valgrind", "--version"))
}

/// A baseline: its toolchain line and each bench's count.
#[derive(Debug, PartialEq)]
struct Baseline {
    toolchain: String,
    counts: BTreeMap<String, u64>,
}

fn parse(text: &str) -> Baseline {
    let mut toolchain = String::new();
    let mut counts = BTreeMap::new();
    for line in text.lines() {
        if let Some(t) = line.strip_prefix("# toolchain: ") {
            toolchain = t.to_owned();
        } else if !line.starts_with('#') && !line.trim().is_empty() {
            let (name, count) = line.split_once(' ').expect("a line `name count`");
            counts.insert(name.to_owned(), count.trim().parse().expect("a count"));
        }
    }
    Baseline { toolchain, counts }
}

fn write(baseline: &Baseline) -> String {
    let mut text = String::from(
        "# Instructions per bench (Callgrind, release profile), from tests/instructions.rs.\n\
         # Rewritten by `HIBI_BLESS=1 cargo test --release --test instructions`; a commit that\n\
         # raises a count more than 3 % rewrites this file and says why in its message.\n",
    );
    text.push_str(&format!("# toolchain: {}\n", baseline.toolchain));
    for (name, count) in &baseline.counts {
        text.push_str(&format!("{name} {count}\n"));
    }
    text
}

/// What fails the gate: each bench whose count rose more than [`TOLERANCE`] over its baseline,
/// each bench without a baseline and each baseline without its bench, and a different
/// toolchain.
fn regressions(baseline: &Baseline, measured: &Baseline) -> Vec<String> {
    let mut failures = Vec::new();
    if baseline.toolchain != measured.toolchain {
        failures.push(format!(
            "the baseline was counted with `{}`, this machine counts with `{}`: counts from different \
             compilers or Valgrinds do not compare (count with the baseline's, \
             or bless on purpose)",
            baseline.toolchain, measured.toolchain
        ));
    }
    for (name, &count) in &measured.counts {
        match baseline.counts.get(name) {
            None => failures.push(format!("{name}: no baseline (bless to add it)")),
            Some(&base) if count as f64 > base as f64 * (1.0 + TOLERANCE) => failures.push(format!(
                "{name}: {count} instructions, {:+.2} % over its baseline {base} (limit +{:.0} %)",
                100.0 * (count as f64 / base as f64 - 1.0),
                100.0 * TOLERANCE
            )),
            Some(_) => {}
        }
    }
    for name in baseline.counts.keys().filter(|n| !measured.counts.contains_key(*n)) {
        failures.push(format!("{name}: in the baseline, but no such bench"));
    }
    failures
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Counts the benches of run `which` under Callgrind: each bench's instructions, by name, the
/// C library's `__mem*` functions left out (glibc picks their code by the CPU).
fn count(test: &str, which: &str) -> BTreeMap<String, u64> {
    let (_, costs) = hibi_tests::callgrind_this_test_by_function(test, "hibi_bench_*|__mem*", (RUN, which));
    BENCHES.iter().filter_map(|(label, symbol, _)| costs.get(*symbol).map(|&c| ((*label).to_owned(), c))).collect()
}

/// Does the benches' work when run again under Callgrind; else `None`.
fn rerun() -> Option<()> {
    match std::env::var(RUN).ok()?.as_str() {
        "all" => {
            mud_benches();
            glass_benches(false);
            skin_benches();
            fastnoise_benches();
        }
        "perturbed" => glass_benches(true),
        other => panic!("{RUN}={other}: not a run"),
    }
    Some(())
}

fn table(baseline: &Baseline, measured: &BTreeMap<String, u64>) {
    println!("| bench | instructions | baseline | change |");
    println!("|---|---:|---:|---:|");
    for (name, count) in measured {
        let base = baseline.counts.get(name);
        let change = base.map_or("new".to_owned(), |&b| format!("{:+.2} %", 100.0 * (*count as f64 / b as f64 - 1.0)));
        println!("| {name} | {count} | {} | {change} |", base.map_or("".to_owned(), |b| b.to_string()));
    }
}

/// Every bench counted and checked against the committed baseline (or, with `HIBI_BLESS=1`,
/// written to it).
#[test]
#[cfg_attr(debug_assertions, ignore = "the baseline counts the release profile's instructions")]
fn benches() {
    if rerun().is_some() {
        return;
    }
    let measured = count("benches", "all");
    let path = root().join(BASELINE);
    let fresh = Baseline { toolchain: toolchain(), counts: measured.clone() };
    let committed = std::fs::read_to_string(&path).map(|t| parse(&t));
    table(committed.as_ref().unwrap_or(&Baseline { toolchain: String::new(), counts: BTreeMap::new() }), &measured);
    assert_eq!(measured.len(), BENCHES.len(), "every bench is counted: {measured:?}");
    if std::env::var_os("HIBI_BLESS").is_some() {
        std::fs::create_dir_all(path.parent().expect("a directory")).expect("create the directory");
        std::fs::write(&path, write(&fresh)).expect("write the baseline");
        std::fs::write(root().join(PAGE_TABLE), page_table(&fresh)).expect("write the page's table");
        return;
    }
    let committed = committed.unwrap_or_else(|e| panic!("{BASELINE}: {e} (bless to write it)"));
    let failures = regressions(&committed, &fresh);
    assert!(
        failures.is_empty(),
        "instruction counts over their committed baseline ({BASELINE}):\n  {}\n\
         A rise on purpose: `HIBI_BLESS=1 cargo test --release --test instructions`, and commit \
         the baseline with the reason in the message.",
        failures.join("\n  ")
    );
}

/// The gate fails on a real rise: a run whose glass mask render draws twice is counted under
/// Callgrind and checked against the committed baseline, which it must exceed by far more than
/// the tolerance (and nothing else of that run may).
#[test]
#[cfg_attr(debug_assertions, ignore = "the baseline counts the release profile's instructions")]
fn a_rise_fails_the_gate() {
    if rerun().is_some() {
        return;
    }
    let committed = parse(&std::fs::read_to_string(root().join(BASELINE)).expect("the baseline"));
    let measured = count("a_rise_fails_the_gate", "perturbed");
    let subset = Baseline {
        toolchain: committed.toolchain.clone(),
        counts: committed
            .counts
            .iter()
            .filter(|(n, _)| measured.contains_key(*n))
            .map(|(n, c)| (n.clone(), *c))
            .collect(),
    };
    let failures = regressions(&subset, &Baseline { toolchain: committed.toolchain.clone(), counts: measured.clone() });
    assert_eq!(failures.len(), 1, "only the doubled render fails: {failures:?}");
    assert!(failures[0].starts_with("glass/render/mask: "), "{failures:?}");
    let (base, twice) = (subset.counts["glass/render/mask"], measured["glass/render/mask"]);
    assert!(twice as f64 > 1.9 * base as f64, "drawing twice counts about twice: {twice} against {base}");
}

/// The gate's arithmetic: exactly 3 % over passes, more fails; a fall passes; a bench missing
/// either side fails; a different toolchain fails; and a baseline updated to the new count
/// (what blessing writes) passes again.
#[test]
fn the_gate_is_three_percent_over_the_committed_baseline() {
    let at = |counts: &[(&str, u64)]| Baseline {
        toolchain: "rustc 1 | valgrind-3".to_owned(),
        counts: counts.iter().map(|&(n, c)| (n.to_owned(), c)).collect(),
    };
    let base = at(&[("a", 1_000_000), ("b", 2_000_000)]);
    assert!(regressions(&base, &at(&[("a", 1_030_000), ("b", 1_000_000)])).is_empty());
    let over = at(&[("a", 1_030_001), ("b", 2_000_000)]);
    assert_eq!(regressions(&base, &over).len(), 1);
    assert!(regressions(&base, &over)[0].starts_with("a: 1030001 instructions, +3.00 % over"));
    assert_eq!(regressions(&base, &at(&[("a", 1)])), ["b: in the baseline, but no such bench"]);
    assert_eq!(regressions(&base, &at(&[("a", 1), ("b", 1), ("c", 1)])), ["c: no baseline (bless to add it)"]);
    let other = Baseline { toolchain: "rustc 2 | valgrind-3".to_owned(), ..at(&[("a", 1), ("b", 1)]) };
    assert_eq!(regressions(&base, &other).len(), 1);
    // Blessing writes the new counts; read back, they are the baseline the rise passes.
    let blessed = parse(&write(&over));
    assert_eq!(blessed, over);
    assert!(regressions(&blessed, &over).is_empty());
}

/// The pixels of each model's renders in the benches.
fn render_pixels(model: &str) -> u64 {
    match model {
        "mud" => 256 * 256,
        "glass" => 640 * 640,
        // Skin's, and FastNoiseLite's maps on the same grid (its value grid is 402²).
        _ => 400 * 400,
    }
}

/// The performance page's table of a baseline: each bench's count, and per pixel for renders.
fn page_table(baseline: &Baseline) -> String {
    let mut text = format!(
        "<!-- Written with {BASELINE} by `HIBI_BLESS=1 cargo test --release --test instructions`; do not edit. -->\n\n\
         Counted by {}.\n\n| bench | instructions | per pixel |\n|---|---:|---:|\n",
        // "rustc 1.95.0 (hash date) | valgrind-3.19.0" reads "rustc 1.95.0 and valgrind-3.19.0".
        baseline.toolchain.split(" | ").map(|t| t.split(" (").next().unwrap_or(t)).collect::<Vec<_>>().join(" and ")
    );
    for (name, count) in &baseline.counts {
        let model = name.split('/').next().expect("model/bench");
        let per_pixel = if name.contains("/render/") || model == "fastnoise" {
            format!("{:.0}", *count as f64 / render_pixels(model) as f64)
        } else {
            String::new()
        };
        let grouped = count
            .to_string()
            .as_bytes()
            .rchunks(3)
            .rev()
            .map(|c| std::str::from_utf8(c).unwrap())
            .collect::<Vec<_>>()
            .join(" ");
        text.push_str(&format!("| {name} | {grouped} | {per_pixel} |\n"));
    }
    let count = |name: &str| baseline.counts.get(name).copied().unwrap_or(0) as f64;
    let ours = count("skin/build") + count("skin/render/height_normal");
    text.push_str(&format!(
        "\nSkin's build and one render of height and normal (`skin/build` + `skin/render/height_normal`) \
         take {:.2}× the instructions of FastNoiseLite's cellular noise with its normal by central \
         differences on the same grid (`fastnoise/cellular_normal`).\n",
        ours / count("fastnoise/cellular_normal")
    ));
    text
}

/// The performance page shows the committed baseline's counts. Blessing writes the table (here
/// from the committed baseline; [`benches`] writes it again from the new counts).
#[test]
fn the_performance_page_shows_the_baseline() {
    let committed = parse(&std::fs::read_to_string(root().join(BASELINE)).expect("the baseline"));
    if std::env::var_os("HIBI_BLESS").is_some() {
        std::fs::write(root().join(PAGE_TABLE), page_table(&committed)).expect("write the page's table");
    }
    let page = std::fs::read_to_string(root().join(PAGE_TABLE)).unwrap_or_default();
    assert!(
        page == page_table(&committed),
        "{PAGE_TABLE} is not the table of {BASELINE}: `HIBI_BLESS=1 cargo test --release --test instructions` \
         writes both\n{}",
        hibi_tests::line_diff(&page_table(&committed), &page)
    );
}

/// The committed baseline names every bench, and only them, with a toolchain line.
#[test]
fn the_baseline_lists_every_bench() {
    let committed = parse(&std::fs::read_to_string(root().join(BASELINE)).expect("the baseline"));
    assert!(!committed.toolchain.is_empty(), "{BASELINE} names its toolchain");
    let names: Vec<&str> = committed.counts.keys().map(String::as_str).collect();
    let mut expected: Vec<&str> = BENCHES.iter().map(|b| b.0).collect();
    expected.sort_unstable();
    assert_eq!(names, expected, "{BASELINE} and the benches differ: bless to rewrite it");
}
