//! Model A benchmark: what a user waits for on the default preset, one thread: the
//! quasi-static run (tracing its network at the end) and the cells, at 64² to 512², with the
//! growth exponent of the cost in the node count; the explicit solver (the paper's loop) at
//! 128² for the speed ratio; the irregular lattice beside the hexagonal one. Crack statistics
//! are printed so that speeds are read at equal statistics.
//!
//!     cargo bench --bench mud                # the table of the README
//!     cargo bench --bench mud -- 64 128      # other sizes (quasi-static only)

use std::time::Instant;

use hibi_core::mud::{CrackStatistics, Mud, MudBuffers, MudParams, Solver, Topology};
use hibi_core::polygon::Ring;

struct Run {
    seconds: f64,
    work: u64,
    stats: CrackStatistics,
}

/// Sets up and runs to the end (the network is traced as the run ends), then writes the cells.
fn run(size: u32, solver: Solver, topology: Topology) -> Run {
    let params = MudParams { columns: size, rows: size, solver, topology, ..MudParams::default() };
    let memory = params.memory().expect("valid parameters");
    let (mut scalars, mut words) = (vec![0.0f32; memory.scalars], vec![0u32; memory.words]);
    let start = Instant::now();
    let mut mud = Mud::new(&params, MudBuffers { scalars: &mut scalars, words: &mut words }).expect("memory suffices");
    let progress = mud.run().expect("a stable run");
    let counts = mud.cell_counts();
    let (mut rings, mut points) = (vec![Ring::default(); counts.rings], vec![[0.0f32; 2]; counts.points]);
    mud.cells(&mut rings, &mut points).expect("buffers suffice");
    let seconds = start.elapsed().as_secs_f64();
    let stats = mud.statistics();
    Run { seconds, work: progress.work, stats }
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
    let sizes: Vec<u32> = std::env::args().skip(1).filter_map(|a| a.parse().ok()).collect();
    let custom = !sizes.is_empty();
    let sizes = if custom { sizes } else { vec![64, 128, 256, 512] };
    println!(
        "| lattice | solver (run, trace, cells) | time | spring updates/s | crack density (1/cm) | cells | mean cell area (cm²) |"
    );
    println!("|---|---|---|---|---|---|---|");
    let mut times = Vec::new();
    for &size in &sizes {
        let fast = run(size, Solver::QuasiStatic, Topology::Hexagonal);
        row(size, "hex, quasi-static", &fast);
        times.push((size, fast.seconds));
        if !custom && (size == 128 || size == 256) {
            row(size, "irregular, quasi-static", &run(size, Solver::QuasiStatic, Topology::Irregular));
        }
        if !custom && size == 128 {
            let explicit = run(size, Solver::Explicit, Topology::Hexagonal);
            row(size, "hex, explicit", &explicit);
            println!("| {size}² | explicit / quasi-static | {:.1}× | | | | |", explicit.seconds / fast.seconds);
        }
    }
    if let (Some(&(a, ta)), Some(&(b, tb))) = (times.first(), times.last())
        && b > a
    {
        let exponent = (tb / ta).ln() / ((f64::from(b) / f64::from(a)).powi(2)).ln();
        println!("\ncost grows as nodes^{exponent:.2} from {a}² to {b}²");
    }
}
