//! What one unit of `step(budget)`'s work costs in time, per model and per phase: each run is
//! stepped to its end with a fixed budget per call, as an engine would spread it over frames,
//! and each call's time and work (`progress.work`) go to the phase the call is in. Runs: mud at
//! its defaults (64², quasi-static, the network's tracing included, then its network and cells
//! built in steps: `NetworkBuild`, `CellBuild`) and with the explicit solver (16², the paper's
//! short step), glass at its defaults (640×640, M_ave = 100) and then
//! its fragments built in steps (`FragmentBuild`), skin at `fig19a` (400×400, three levels).
//! Each model is run once per round, the rounds one after another so that a slow spell of the
//! machine hits every model alike; round 0 warms up and is not counted, and each figure is the
//! median of the rest.
//!
//! A call is counted in one phase: mud's calls while its setup is under way are the setup's
//! (the setup ends a call), those with a trace of the network under way before or after them
//! the tracing's (a call can hold the last physics before a trace), the rest the solver's;
//! glass's calls before the plate finishes growing are growth, the rest the fragment build;
//! skin's setup (the profile tables, 522 units for fig19a) is stepped a piece a call (a budget
//! of one unit) and timed as a whole, then the cells (of every level, and the divisions
//! between them) with the budget.
//!
//!     cargo bench --bench units
//!
//! The nanoseconds depend on the machine; the ratios between models and phases, measured in one
//! run, are the figure to carry to another machine, and "a budget of N units takes N × (ns per
//! unit)" holds on the machine that ran it. The table goes to
//! `docs/src/generated/bench-units.md`, which the engine integration page includes.

use std::hint::black_box;
use std::time::{Duration, Instant};

use hibi_core::glass::{FragmentBuild, Glass, GlassParams};
use hibi_core::mud::{CellBuild, Mud, MudParams, NetworkBuild, Solver};
use hibi_core::skin::{Skin, preset};
use hibi_tests::{load_average, write_bench_tables};

/// Units of work per `step` call: an engine frame's worth.
const BUDGET: u64 = 10_000;
/// Counted rounds (one more warms up).
const ROUNDS: usize = 10;

/// The phases measured, in the order of the table: (model, phase).
const PHASES: [(&str, &str); 11] = [
    (MUD_QUASI_STATIC, "setup"),
    (MUD_QUASI_STATIC, "quasi-static solver (and its live traces)"),
    (MUD_QUASI_STATIC, "network tracing (the final trace)"),
    (MUD_QUASI_STATIC, "network build (`NetworkBuild`)"),
    (MUD_QUASI_STATIC, "cell build (`CellBuild`)"),
    ("mud, 16² hexagonal, explicit", "setup"),
    ("mud, 16² hexagonal, explicit", "explicit solver (and its live traces)"),
    ("mud, 16² hexagonal, explicit", "network tracing (the final trace)"),
    ("glass, 640 × 640, M_ave = 100", "growth"),
    ("glass, 640 × 640, M_ave = 100", "fragment build (`FragmentBuild`)"),
    (SKIN, "setup"),
];
const MUD_QUASI_STATIC: &str = "mud, 64² hexagonal, quasi-static";
const SKIN: &str = "skin, `fig19a`, 400 × 400, three levels";
/// Skin's cells, the last row (kept apart so that the array above stays one type).
const SKIN_CELLS: (&str, &str) = (SKIN, "cells and divisions");

/// The work and time of one phase of one run.
#[derive(Clone, Copy, Default)]
struct Sample {
    work: u64,
    time: Duration,
}

impl Sample {
    fn add(&mut self, work: u64, time: Duration) {
        self.work += work;
        self.time += time;
    }
}

/// Times one call of `step`, which returns the run's work after it.
fn timed(step: impl FnOnce() -> u64, before: u64, phase: &mut Sample) -> u64 {
    let start = Instant::now();
    let work = step();
    phase.add(work - before, start.elapsed());
    work
}

/// Mud: setup, solver, tracing; then the finished run's network and cells built in steps
/// (`NetworkBuild`, `CellBuild`).
fn mud(params: &MudParams) -> ([Sample; 3], [Sample; 2]) {
    let mut memory = params.memory().expect("valid parameters").allocate::<f32>();
    let mut mud: Mud = Mud::new(params, memory.buffers()).expect("memory suffices");
    let mut phases = [Sample::default(); 3];
    let (mut work, mut finished) = (0, false);
    while !finished {
        let (setting_up, tracing) = (mud.is_setting_up(), mud.is_tracing());
        let start = Instant::now();
        let p = mud.step(BUDGET).expect("a stable run");
        let time = start.elapsed();
        let phase = if setting_up {
            0
        } else if tracing || mud.is_tracing() {
            2
        } else {
            1
        };
        phases[phase].add(p.work - work, time);
        (work, finished) = (p.work, p.finished);
    }
    black_box(mud.statistics());
    let mut builds = [Sample::default(); 2];
    let mut network_memory = mud.network_build_memory().allocate();
    let mut network = NetworkBuild::new(&mud, network_memory.buffers()).expect("memory suffices");
    let (mut work, mut finished) = (0, false);
    while !finished {
        let start = Instant::now();
        let p = network.step(&mud, BUDGET).expect("the run it was made for");
        builds[0].add(p.work - work, start.elapsed());
        (work, finished) = (p.work, p.finished);
    }
    black_box(network.points().len());
    let mut cell_memory = mud.cell_build_memory().allocate();
    let mut cells = CellBuild::new(&mud, cell_memory.buffers()).expect("memory suffices");
    let (mut work, mut finished) = (0, false);
    while !finished {
        let start = Instant::now();
        let p = cells.step(&mud, BUDGET).expect("the run it was made for");
        builds[1].add(p.work - work, start.elapsed());
        (work, finished) = (p.work, p.finished);
    }
    black_box(cells.points().len());
    (phases, builds)
}

/// Glass: growth, then the fragment build.
fn glass(params: &GlassParams) -> [Sample; 2] {
    let mut memory = params.memory().expect("valid parameters").allocate();
    let mut glass = Glass::new(params, memory.buffers()).expect("memory suffices");
    let mut phases = [Sample::default(); 2];
    let mut work = 0;
    while !glass.progress().finished {
        work = timed(|| glass.step(BUDGET).work, work, &mut phases[0]);
    }
    let mut build_memory = glass.fragment_build_memory().allocate();
    let mut build = FragmentBuild::new(&glass, build_memory.buffers()).expect("memory suffices");
    let (mut work, mut finished) = (0, false);
    while !finished {
        let start = Instant::now();
        let p = build.step(&glass, BUDGET).expect("the plate it was made for");
        phases[1].add(p.work - work, start.elapsed());
        (work, finished) = (p.work, p.finished);
    }
    black_box(build.rings().len());
    phases
}

/// Skin: setup, then the cells.
fn skin(params: &hibi_core::skin::SkinParams) -> [Sample; 2] {
    let mut memory = params.memory().expect("valid parameters").allocate();
    let mut skin: Skin = Skin::new(params, memory.buffers()).expect("memory suffices");
    let mut phases = [Sample::default(); 2];
    // The setup is one call's worth at this budget: stepped a piece a call (one unit's budget)
    // and timed as a whole, so that it ends a call of its own.
    let (mut work, start) = (0, Instant::now());
    while skin.is_setting_up() {
        work = skin.step(1).work;
    }
    phases[0] = Sample { work, time: start.elapsed() };
    let mut finished = false;
    while !finished {
        let start = Instant::now();
        let p = skin.step(BUDGET);
        phases[1].add(p.work - work, start.elapsed());
        (work, finished) = (p.work, p.finished);
    }
    black_box(skin.cells().len());
    phases
}

fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    let n = values.len();
    if n % 2 == 1 { values[n / 2] } else { 0.5 * (values[n / 2 - 1] + values[n / 2]) }
}

fn main() {
    let load = load_average();
    let quasi_static = MudParams { columns: 64, rows: 64, ..MudParams::default() };
    let explicit = MudParams { columns: 16, rows: 16, solver: Solver::Explicit, ..MudParams::default() };
    let plate = GlassParams::default();
    let fig19a = preset("fig19a").expect("preset exists");
    let rows: Vec<(&str, &str)> = PHASES.iter().copied().chain([SKIN_CELLS]).collect();
    let mut ns_per_unit: Vec<Vec<f64>> = vec![Vec::new(); rows.len()];
    let mut last = vec![Sample::default(); rows.len()];
    for round in 0..=ROUNDS {
        let (qs, ex) = (mud(&quasi_static), mud(&explicit));
        let samples: Vec<Sample> = [&qs.0[..], &qs.1[..], &ex.0[..], &glass(&plate)[..], &skin(&fig19a)[..]].concat();
        for (i, s) in samples.into_iter().enumerate() {
            if round > 0 && s.work > 0 {
                ns_per_unit[i].push(s.time.as_secs_f64() * 1e9 / s.work as f64);
            }
            last[i] = s;
        }
    }
    let ns: Vec<f64> = ns_per_unit.into_iter().map(|v| if v.is_empty() { f64::NAN } else { median(v) }).collect();
    // The reference: the quasi-static solver's unit.
    let reference = ns[1];
    let mut tables = format!(
        "`step({BUDGET})` to the end, median of {ROUNDS} rounds:\n\n\
         | run | phase | units | ns per unit | ÷ a quasi-static unit | ms per {BUDGET} units |\n\
         |---|---|---|---|---|---|\n"
    );
    for (i, (run, phase)) in rows.iter().enumerate() {
        let s = &last[i];
        let run = if i > 0 && rows[i - 1].0 == *run { "" } else { run };
        let significant = |v: f64| if v < 10.0 { format!("{v:.2}") } else { format!("{v:.0}") };
        tables.push_str(&format!(
            "| {run} | {phase} | {} | {} | {} | {:.3} |\n",
            s.work,
            significant(ns[i]),
            significant(ns[i] / reference),
            ns[i] * BUDGET as f64 / 1e6
        ));
    }
    write_bench_tables("bench-units.md", "cargo bench --bench units", [load, load_average()], &tables);
}
