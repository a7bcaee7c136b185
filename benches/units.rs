//! What one unit of `step(budget)`'s work costs in time, per model: each run is stepped to
//! its end with a fixed budget per call, as an engine would spread it over frames, and its
//! work total (`progress.work`) is divided into the time spent in those calls. Runs: mud at
//! its defaults (64², quasi-static, the network's tracing included) and with the explicit
//! solver (16², the paper's short step), glass at its defaults (640×640, M_ave = 100), skin
//! at `fig19a` (400×400, three levels). Each model is run once per round, the rounds one
//! after another so that a slow spell of the machine hits every model alike; round 0 warms
//! up and is not counted, and each figure is the median of the rest.
//!
//!     cargo bench --bench units
//!
//! The nanoseconds depend on the machine; the ratios between models, measured in one run,
//! are the figure to carry to another machine.

use std::hint::black_box;
use std::time::{Duration, Instant};

use hibi_core::glass::{Glass, GlassParams};
use hibi_core::mud::{Mud, MudParams, Solver};
use hibi_core::skin::{Skin, preset};

/// Units of work per `step` call: an engine frame's worth.
const BUDGET: u64 = 10_000;
/// Counted rounds (one more warms up).
const ROUNDS: usize = 10;

/// The work a run did and the time its `step` calls took (set-up excluded).
struct Sample {
    work: u64,
    time: Duration,
    calls: u64,
}

/// Steps `step` with [`BUDGET`] until it reports `(finished, work)` with `finished` set.
fn stepped(mut step: impl FnMut(u64) -> (bool, u64)) -> Sample {
    let (mut time, mut calls) = (Duration::ZERO, 0);
    loop {
        let start = Instant::now();
        let (finished, work) = step(BUDGET);
        time += start.elapsed();
        calls += 1;
        if finished {
            return Sample { work, time, calls };
        }
    }
}

fn mud(params: &MudParams) -> Sample {
    let mut memory = params.memory().expect("valid parameters").allocate::<f32>();
    let mut mud: Mud = Mud::new(params, memory.buffers()).expect("memory suffices");
    let sample = stepped(|budget| {
        let p = mud.step(budget).expect("a stable run");
        (p.finished, p.work)
    });
    black_box(mud.statistics());
    sample
}

fn glass(params: &GlassParams) -> Sample {
    let mut memory = params.memory().expect("valid parameters").allocate();
    let mut glass = Glass::new(params, memory.buffers()).expect("memory suffices");
    let sample = stepped(|budget| {
        let p = glass.step(budget);
        (p.finished, p.work)
    });
    black_box(glass.crack_count());
    sample
}

fn skin(params: &hibi_core::skin::SkinParams) -> Sample {
    let mut memory = params.memory().expect("valid parameters").allocate();
    let mut skin: Skin = Skin::new(params, memory.buffers()).expect("memory suffices");
    let sample = stepped(|budget| {
        let p = skin.step(budget);
        (p.finished, p.work)
    });
    black_box(skin.cells().len());
    sample
}

fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    let n = values.len();
    if n % 2 == 1 { values[n / 2] } else { 0.5 * (values[n / 2 - 1] + values[n / 2]) }
}

fn main() {
    let quasi_static = MudParams { columns: 64, rows: 64, ..MudParams::default() };
    let explicit = MudParams { columns: 16, rows: 16, solver: Solver::Explicit, ..MudParams::default() };
    let plate = GlassParams::default();
    let fig19a = preset("fig19a").expect("preset exists");
    let names = [
        "mud, 64² hexagonal, quasi-static (with the tracing)",
        "mud, 16² hexagonal, explicit (with the tracing)",
        "glass, 640×640, M_ave = 100",
        "skin, fig19a, 400×400, 3 levels",
    ];
    let mut ns_per_unit: [Vec<f64>; 4] = Default::default();
    let mut last: [Option<Sample>; 4] = Default::default();
    for round in 0..=ROUNDS {
        let samples = [mud(&quasi_static), mud(&explicit), glass(&plate), skin(&fig19a)];
        for (i, s) in samples.into_iter().enumerate() {
            if round > 0 {
                ns_per_unit[i].push(s.time.as_secs_f64() * 1e9 / s.work as f64);
            }
            last[i] = Some(s);
        }
    }
    let ns: Vec<f64> = ns_per_unit.into_iter().map(median).collect();
    println!("step({BUDGET}) to the end; median of {ROUNDS} rounds");
    println!();
    println!("| run | units of work | calls | time in step | µs per call | ns per unit | ÷ mud quasi-static's |");
    println!("|---|---|---|---|---|---|---|");
    for (i, name) in names.iter().enumerate() {
        let s = last[i].as_ref().expect("a round ran");
        println!(
            "| {name} | {} | {} | {:.2} ms | {:.1} | {:.2} | {:.2} |",
            s.work,
            s.calls,
            ns[i] * s.work as f64 / 1e6,
            ns[i] * s.work as f64 / 1e3 / s.calls as f64,
            ns[i],
            ns[i] / ns[0]
        );
    }
}
