//! Model A benchmark: what a user waits for on the default preset, one thread: the
//! quasi-static run (tracing its network at the end) and the cells, at 64² to 512², with the
//! growth exponent of the cost in the node count; the explicit solver (the paper's loop) at
//! 128² for the speed ratio; the irregular lattice beside the hexagonal one; each the fastest
//! of [`RUNS`] runs. Crack statistics
//! are printed so that speeds are read at equal statistics. Then the outputs of the default
//! 128² run, each call's median over [`OUTPUT_RUNS`] calls: `network`, `cells` and a 512²
//! `render` of the height map. Prints the times; a run at the default sizes also writes the
//! statistics and the ratios, the performance page's tables, to
//! `docs/src/generated/bench-mud.md`.
//!
//!     cargo bench --bench mud                # the performance page's tables
//!     cargo bench --bench mud -- 64 128      # other sizes (quasi-static only)

use std::time::Instant;

use hibi_core::mud::{
    CrackStatistics, Mud, MudBuffers, MudParams, MudRender, NetworkEdge, NetworkPoint, NetworkVertex, Solver, Topology,
};
use hibi_core::polygon::Ring;
use hibi_core::raster::{Layers, scratch_len};
use hibi_tests::{load_average, write_bench_tables};

/// Calls of each output whose median time is printed.
const OUTPUT_RUNS: usize = 21;

struct Run {
    seconds: f64,
    work: u64,
    stats: CrackStatistics,
}

/// Runs of each lattice and solver; the fastest is kept, so that a slow spell of a shared
/// machine does not bend the growth exponent.
const RUNS: usize = 3;

/// Sets up and runs to the end (the network is traced as the run ends), then writes the cells:
/// the fastest of [`RUNS`] runs (each the same run, bit for bit).
fn run(size: u32, solver: Solver, topology: Topology) -> Run {
    let params = MudParams { columns: size, rows: size, solver, topology, ..MudParams::default() };
    let memory = params.memory().expect("valid parameters");
    let (mut scalars, mut words) = (vec![0.0f32; memory.scalars], vec![0u32; memory.words]);
    let mut fastest: Option<Run> = None;
    for _ in 0..RUNS {
        let start = Instant::now();
        let mut mud =
            Mud::new(&params, MudBuffers { scalars: &mut scalars, words: &mut words }).expect("memory suffices");
        let progress = mud.run().expect("a stable run");
        let counts = mud.cell_counts();
        let (mut rings, mut points) = (vec![Ring::default(); counts.rings], vec![[0.0f32; 2]; counts.points]);
        mud.cells(&mut rings, &mut points).expect("buffers suffice");
        let seconds = start.elapsed().as_secs_f64();
        if fastest.as_ref().is_none_or(|f| seconds < f.seconds) {
            fastest = Some(Run { seconds, work: progress.work, stats: mud.statistics() });
        }
    }
    fastest.expect("RUNS is at least one")
}

/// The median time of `OUTPUT_RUNS` calls of `f`, milliseconds.
fn median_ms(mut f: impl FnMut()) -> f64 {
    let mut times: Vec<f64> = (0..OUTPUT_RUNS)
        .map(|_| {
            let start = Instant::now();
            f();
            start.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[OUTPUT_RUNS / 2]
}

/// The outputs of the default 128² run, one call each: their median times, and the rows of the
/// page's table of them (each time divided by `run`, seconds).
fn outputs(run: f64) -> String {
    let params = MudParams { columns: 128, rows: 128, ..MudParams::default() };
    let memory = params.memory().expect("valid parameters");
    let (mut scalars, mut words) = (vec![0.0f32; memory.scalars], vec![0u32; memory.words]);
    let mut mud = Mud::new(&params, MudBuffers { scalars: &mut scalars, words: &mut words }).expect("memory suffices");
    mud.run().expect("a stable run");
    let n = mud.network_counts();
    let (mut vertices, mut edges, mut points) = (
        vec![NetworkVertex::default(); n.vertices],
        vec![NetworkEdge::default(); n.edges],
        vec![NetworkPoint::default(); n.points],
    );
    let c = mud.cell_counts();
    let (mut rings, mut ring_points) = (vec![Ring::default(); c.rings], vec![[0.0f32; 2]; c.points]);
    let render = MudRender::fit(mud.extent(), 512);
    let pixels = render.width as usize * render.height as usize;
    let mut height = vec![0.0f32; pixels];
    let mut scratch = vec![0u32; scratch_len(render.width, render.height).expect("a small raster")];
    let network = median_ms(|| {
        std::hint::black_box(mud.network(&mut vertices, &mut edges, &mut points).expect("buffers suffice"));
    });
    let cells = median_ms(|| {
        std::hint::black_box(mud.cells(&mut rings, &mut ring_points).expect("buffers suffice"));
    });
    let rendered = median_ms(|| {
        let layers = Layers { height: Some(&mut height), scratch: Some(&mut scratch), ..Layers::default() };
        mud.render(&render, layers).expect("buffers suffice");
    });
    println!("\n| 128² default run, one call (median of {OUTPUT_RUNS}) | time |");
    println!("|---|---|");
    println!("| `network` ({} vertices, {} edges, {} points) | {network:.2} ms |", n.vertices, n.edges, n.points);
    println!("| `cells` ({} rings, {} points) | {cells:.2} ms |", c.rings, c.points);
    println!("| `render`, height map {}×{} | {rendered:.2} ms |", render.width, render.height);
    let ratio = |ms: f64| ms / (run * 1e3);
    format!(
        "| `network` ({} vertices, {} edges, {} points) | {:.3}× |\n\
         | `cells` ({} rings, {} points) | {:.3}× |\n\
         | `render` of the height map, {} × {} | {:.3}× |\n",
        n.vertices,
        n.edges,
        n.points,
        ratio(network),
        c.rings,
        c.points,
        ratio(cells),
        render.width,
        render.height,
        ratio(rendered)
    )
}

fn row(size: u32, name: &str, r: &Run) {
    println!(
        "| {size}² | {name} | {:.3} s | {:.3e} | {:.3} | {} | {:.1} |",
        r.seconds,
        r.work as f64 / r.seconds,
        r.stats.crack_density,
        r.stats.cells,
        r.stats.mean_cell_area
    );
}

fn main() {
    let load = load_average();
    let sizes: Vec<u32> = std::env::args().skip(1).filter_map(|a| a.parse().ok()).collect();
    let custom = !sizes.is_empty();
    let sizes = if custom { sizes } else { vec![64, 128, 256, 512] };
    println!(
        "| lattice | solver (run, trace, cells) | time | spring updates/s | crack density (1/cm) | cells | mean cell area (cm²) |"
    );
    println!("|---|---|---|---|---|---|---|");
    // Each run's lattice, solver (the page's words) and figures, in the order run.
    let mut runs: Vec<(u32, &str, Run)> = Vec::new();
    for &size in &sizes {
        let fast = run(size, Solver::QuasiStatic, Topology::Hexagonal);
        row(size, "hex, quasi-static", &fast);
        runs.push((size, "hexagonal, quasi-static", fast));
        if !custom && (size == 128 || size == 256) {
            let irregular = run(size, Solver::QuasiStatic, Topology::Irregular);
            row(size, "irregular, quasi-static", &irregular);
            runs.push((size, "irregular, quasi-static", irregular));
        }
        if !custom && size == 128 {
            let explicit = run(size, Solver::Explicit, Topology::Hexagonal);
            row(size, "hex, explicit", &explicit);
            runs.push((size, "hexagonal, explicit", explicit));
        }
    }
    let seconds = |size: u32, solver: &str| runs.iter().find(|r| r.0 == size && r.1 == solver).map(|r| r.2.seconds);
    let hexagonal = "hexagonal, quasi-static";
    let times: Vec<(u32, f64)> = runs.iter().filter(|r| r.1 == hexagonal).map(|r| (r.0, r.2.seconds)).collect();
    let exponent =
        |(a, ta): (u32, f64), (b, tb): (u32, f64)| (tb / ta).ln() / ((f64::from(b) / f64::from(a)).powi(2)).ln();
    if let (Some(&first), Some(&last)) = (times.first(), times.last())
        && last.0 > first.0
    {
        println!("\ncost grows as nodes^{:.2} from {}² to {}²", exponent(first, last), first.0, last.0);
    }
    if custom {
        return;
    }
    let mut tables = String::from(
        "| lattice | solver | crack density (1/cm) | cells | mean cell area (cm²) |\n|---|---|---|---|---|\n",
    );
    for (size, solver, r) in &runs {
        let s = &r.stats;
        tables += &format!("| {size}² | {solver} | {:.3} | {} | {:.1} |\n", s.crack_density, s.cells, s.mean_cell_area);
    }
    let ratio = |a: Option<f64>, b: Option<f64>| a.zip(b).map_or(f64::NAN, |(a, b)| a / b);
    tables += &format!(
        "\nThe speed ratios:\n\n| comparison | ratio |\n|---|---|\n\
         | explicit solver (the paper's damped short steps) ÷ quasi-static, 128² | **{:.0}×** the time |\n\
         | cost growth from 64² to 512² (quasi-static), as a power of the node count | nodes^{:.2} |\n\
         | 512² ÷ 256² | {:.2}× the time for 4× the nodes |\n\
         | irregular lattice ÷ hexagonal, 128² | {:.2}× the time |\n\
         | irregular lattice ÷ hexagonal, 256² | {:.2}× the time |\n",
        ratio(seconds(128, "hexagonal, explicit"), seconds(128, hexagonal)),
        exponent(times[0], times[times.len() - 1]),
        ratio(seconds(512, hexagonal), seconds(256, hexagonal)),
        ratio(seconds(128, "irregular, quasi-static"), seconds(128, hexagonal)),
        ratio(seconds(256, "irregular, quasi-static"), seconds(256, hexagonal)),
    );
    let run_128 = seconds(128, hexagonal).expect("the 128² run is among the default sizes");
    tables += &format!(
        "\nWhat an engine calls once the run is done, each call's time ÷ the run's:\n\n| one call, 128² default run, median of {OUTPUT_RUNS} | ÷ the quasi-static run, trace and cells |\n|---|---|\n{}",
        outputs(run_128)
    );
    write_bench_tables("bench-mud.md", "cargo bench --bench mud", [load, load_average()], &tables);
}
