//! Model A benchmark: the explicit solver (the paper's loop) against the quasi-static one on
//! hexagonal lattices, each run to the default end state. Reports time, spring updates per
//! second and crack statistics, so that the speed ratio is read at equal statistics.
//!
//!     cargo bench --bench mud                # 128² and 256²
//!     cargo bench --bench mud -- 64 128      # other sizes

use std::time::Instant;

use hibi_core::mud::{CrackStatistics, Mud, MudParams, Solver};

struct Run {
    seconds: f64,
    work: u64,
    stats: CrackStatistics,
}

fn run(size: u32, solver: Solver) -> Run {
    let params = MudParams { columns: size, rows: size, solver, ..MudParams::default() };
    let memory = params.memory().expect("valid parameters");
    let (mut scalars, mut words) = (vec![0.0f32; memory.scalars], vec![0u32; memory.words]);
    let start = Instant::now();
    let mut mud = Mud::new(&params, &mut scalars, &mut words).expect("memory suffices");
    let progress = mud.run();
    let seconds = start.elapsed().as_secs_f64();
    let stats = mud.statistics();
    Run { seconds, work: progress.work, stats }
}

fn main() {
    let sizes: Vec<u32> = std::env::args().skip(1).filter_map(|a| a.parse().ok()).collect();
    let sizes = if sizes.is_empty() { vec![128, 256] } else { sizes };
    println!("| lattice | solver | time | spring updates/s | crack density (1/cm) | cells | mean cell area (cm²) |");
    println!("|---|---|---|---|---|---|---|");
    for size in sizes {
        let fast = run(size, Solver::QuasiStatic);
        let explicit = run(size, Solver::Explicit);
        for (name, r) in [("explicit", &explicit), ("quasi-static", &fast)] {
            println!(
                "| {size}² hex | {name} | {:.2} s | {:.3e} | {:.3} | {} | {:.1} |",
                r.seconds,
                r.work as f64 / r.seconds,
                r.stats.crack_density,
                r.stats.cells,
                r.stats.mean_cell_area
            );
        }
        println!("| {size}² hex | speed ratio | {:.1}× | | | | |", explicit.seconds / fast.seconds);
    }
}
