//! What one unit of `step(budget)`'s work costs, in instructions (Callgrind, so the same on any
//! machine), in every phase of every model's run, at ordinary and at extreme valid parameters.
//! A unit is meant to stand for a bounded time: an engine that spreads a run over frames by its
//! budget must not meet a unit forty times the cost of another.
//!
//! Each case (a model's parameters) is run by this test binary itself under Callgrind (the case
//! named by [`CASE`]), stepped with budgets of at most [`BUDGET`] units, each call made through
//! the `hibi_unit_cost_phase_*` function of the phase it is in, the only functions Callgrind
//! counts. Which units belong to which phase is found first by a run of the case outside
//! Callgrind (the phase schedule); the runs do not depend on the budgets, so the run under
//! Callgrind passes the same phases at the same units. At most [`LIMIT`] units of each phase
//! are counted, and a case is run to at most [`CAP`] units. For each model, every case's
//! instructions per unit, phase by phase, must be within [`SPREAD`] times the median of the
//! ordinary cases' (the defaults and presets), either way (in the debug profile, above it
//! only).
//!
//!     cargo test --release --test unit_cost -- --nocapture
//!
//! prints each model's table (and its summary for the guide's Bounded work section).

use std::hint::black_box;
use std::path::PathBuf;

use hibi_core::glass::{FragmentBuild, Glass, GlassParams};
use hibi_core::mud::{Mud, MudParams, MudProgress, Solver, Topology};
use hibi_core::scalar::{Q16, Scalar};
use hibi_core::skin::{Skin, SkinParams};

/// The environment variable that makes a test, run again under Callgrind by itself, run one
/// case (its index) instead of measuring them all.
const CASE: &str = "HIBI_UNIT_COST_CASE";
/// The largest budget of a call: an engine's frame.
const BUDGET: u64 = 1_000;
/// Units of a phase counted per case, at most (the debug profile runs its instructions more
/// slowly under Callgrind).
const LIMIT: u64 = if cfg!(debug_assertions) { 10_000 } else { 50_000 };
/// Units a case is run to, at most.
const CAP: u64 = if cfg!(debug_assertions) { 600_000 } else { 2_000_000 };
/// A phase counted over fewer units than this must have been counted whole.
const MEANINGFUL: u64 = 1_000;
/// How far a case's instructions per unit may be from the median of the ordinary cases' (above
/// it in either profile, below it in release).
const SPREAD: f64 = 10.0;

/// What a `step` call reports: the run's work so far and whether it is finished.
type Stepped = (u64, bool);

/// A model stepped by the test: its `step`, and what the phase schedule reads after each call.
trait Stepper {
    fn step(&mut self, budget: u64) -> Stepped;
    /// Glass: the time step; mud: whether the network's tracing is under way; skin: the cells
    /// built (high 32 bits) and the level-0 centre points done (low), and the newest cell's
    /// level (`u32::MAX` while the setup is under way).
    fn observe(&self) -> (u64, u32);
}

/// A glass plate grown to its end, then its fragments built in steps ([`FragmentBuild`]): the
/// work is the plate's and the build's together.
struct GlassRun<'g, 'b> {
    glass: Glass<'g>,
    fragments: FragmentBuild<'b>,
}

impl Stepper for GlassRun<'_, '_> {
    fn step(&mut self, budget: u64) -> Stepped {
        if !self.glass.progress().finished {
            return (self.glass.step(budget).work, false);
        }
        let f = self.fragments.step(&self.glass, budget).expect("the plate it was made for");
        (self.glass.progress().work + f.work, f.finished)
    }
    /// The time step, and whether the plate has finished growing (the fragment build's calls).
    fn observe(&self) -> (u64, u32) {
        let p = self.glass.progress();
        (u64::from(p.time), u32::from(p.finished))
    }
}

/// What [`Mud::step`] reports, as [`Stepped`] (a refusal fails the test).
trait MudReport {
    fn stepped(self) -> Stepped;
}

impl MudReport for MudProgress {
    fn stepped(self) -> Stepped {
        (self.work, self.finished)
    }
}

impl<E: std::fmt::Debug> MudReport for Result<MudProgress, E> {
    fn stepped(self) -> Stepped {
        self.expect("the run steps").stepped()
    }
}

impl<S: Scalar> Stepper for Mud<'_, S> {
    fn step(&mut self, budget: u64) -> Stepped {
        Mud::step(self, budget).stepped()
    }
    fn observe(&self) -> (u64, u32) {
        (u64::from(self.is_tracing()), u32::from(self.is_setting_up()))
    }
}

impl Stepper for Skin<'_> {
    fn step(&mut self, budget: u64) -> Stepped {
        let p = Skin::step(self, budget);
        (p.work, p.finished)
    }
    fn observe(&self) -> (u64, u32) {
        let p = self.progress();
        let level = if self.is_setting_up() { u32::MAX } else { self.cells().last().map_or(0, |c| c.level) };
        ((u64::from(p.cells) << 32) | u64::from(p.roots), level)
    }
}

/// The step of a call made in phase `k` of its model: the only functions Callgrind counts
/// (found by their unmangled names; each keeps its own body, so none is merged with another).
macro_rules! phase_steps {
    ($($k:literal $name:ident),*) => {
        $(
            #[unsafe(no_mangle)]
            #[inline(never)]
            fn $name(model: &mut dyn Stepper, budget: u64) -> Stepped {
                black_box($k);
                model.step(budget)
            }
        )*
        /// Phase `k`'s step.
        const PHASE_STEPS: [fn(&mut dyn Stepper, u64) -> Stepped; PHASES] = [$($name),*];
    };
}

/// The most phases a model's run has.
const PHASES: usize = 5;

phase_steps!(
    0 hibi_unit_cost_phase_0,
    1 hibi_unit_cost_phase_1,
    2 hibi_unit_cost_phase_2,
    3 hibi_unit_cost_phase_3,
    4 hibi_unit_cost_phase_4
);

/// What a case runs.
#[derive(Clone, Debug)]
enum Params {
    Glass(GlassParams),
    /// Mud in f32 (false) or Q16.16 (true).
    Mud(MudParams, bool),
    /// (Boxed: a skin's parameters are far larger than the others'.)
    Skin(Box<SkinParams>),
}

/// One case: its name, whether it is an ordinary one (defaults, presets) and its parameters.
struct Case {
    name: String,
    ordinary: bool,
    params: Params,
}

/// An extreme case: its name and what it changes in the ordinary parameters.
type Extreme<P> = (&'static str, fn(&mut P));

fn case(name: impl Into<String>, ordinary: bool, params: Params) -> Case {
    Case { name: name.into(), ordinary, params }
}

/// Runs `f` on a new model of `params`, in memory of its own.
fn with_model<R>(params: &Params, f: impl FnOnce(&mut dyn Stepper) -> R) -> R {
    match params {
        Params::Glass(p) => {
            let mut memory = p.memory().expect("valid parameters").allocate();
            let glass = Glass::new(p, memory.buffers()).expect("memory suffices");
            let mut build_memory = glass.fragment_build_memory().allocate();
            let fragments = FragmentBuild::new(&glass, build_memory.buffers()).expect("memory suffices");
            f(&mut GlassRun { glass, fragments })
        }
        Params::Mud(p, false) => {
            let mut memory = p.memory().expect("valid parameters").allocate::<f32>();
            f(&mut Mud::<f32>::new(p, memory.buffers()).expect("memory suffices"))
        }
        Params::Mud(p, true) => {
            let mut memory = p.memory().expect("valid parameters").allocate::<Q16>();
            f(&mut Mud::<Q16>::new(p, memory.buffers()).expect("memory suffices"))
        }
        Params::Skin(p) => {
            let mut memory = p.memory().expect("valid parameters").allocate();
            f(&mut Skin::new(p, memory.buffers()).expect("memory suffices"))
        }
    }
}

/// Where a run's phases lie: `(phase, end)`, each phase until the run's work reaches `end`.
type Schedule = Vec<(usize, u64)>;

/// Appends the units up to `end` to `schedule` as phase `phase`.
fn extend(schedule: &mut Schedule, phase: usize, end: u64) {
    match schedule.last_mut() {
        Some(last) if last.0 == phase => last.1 = end,
        _ => schedule.push((phase, end)),
    }
}

/// Glass's phases.
const GLASS_PHASES: [&str; 5] = ["emptying the grids", "growth", "sleeping steps", "end of impact", "fragment build"];

/// Glass: the grids' cells are emptied 64 a unit (the grid as `Glass::new` lays it out: cells
/// of 16 px, at most 256 a side); then the time steps. A time step that no crack was awake in
/// ends with the clock moved on past the steps that would do the same nothing: the calls of
/// such a step are the sleeping steps. The calls from the last time step's start are the end
/// of the impact (the check that every driving crack has stopped, and the stop of the rest).
/// The calls after the plate has finished growing build its fragments.
fn glass_schedule(p: &GlassParams, model: &mut dyn Stepper) -> Schedule {
    let cell = 16f32.max(p.width / 256.0).max(p.height / 256.0).max(1.0);
    let cells = ((p.width / cell).ceil() as u64).max(1) * ((p.height / cell).ceil() as u64).max(1);
    let clear = 2 * cells.div_ceil(64);
    let (mut work, mut finished) = model.step(clear);
    assert_eq!(work, clear, "the grids' cells take {clear} units");
    let mut schedule = vec![(0, clear)];
    // Per call: the work after it and the time step it rose to (0 if it did not).
    let mut calls = Vec::new();
    let mut time = 0;
    let mut building = Vec::new();
    while !finished && work < CAP {
        building.push(model.observe().1 == 1);
        (work, finished) = model.step(64);
        let now = model.observe().0;
        calls.push((work, now - time));
        time = now;
    }
    let mut phases = vec![1; calls.len()];
    for i in 0..calls.len() {
        if calls[i].1 > 1 {
            // This call's time step was asleep: it and the calls back to that step's start.
            phases[i] = 2;
            let mut k = i;
            while k > 0 {
                k -= 1;
                phases[k] = 2;
                if calls[k].1 != 0 {
                    break;
                }
            }
        }
    }
    let grown = building.iter().position(|&b| b).unwrap_or(calls.len());
    if grown < calls.len()
        && let Some(last) = calls[..grown].iter().rposition(|c| c.1 > 0)
    {
        phases[last..grown].fill(3);
    }
    phases[grown..].fill(4);
    for (&(end, _), &phase) in calls.iter().zip(&phases) {
        extend(&mut schedule, phase, end);
    }
    schedule
}

/// Mud's phases.
const MUD_PHASES: [&str; 4] = ["explicit solver", "quasi-static solver", "network tracing", "setup"];

/// Mud: the setup (the calls after which it is still under way, and the call that ends it:
/// the budget ends a call there, before any physics), the solver's units, then the network's
/// tracing (the calls after which a trace is under way, and the call that ends it).
fn mud_schedule(p: &MudParams, model: &mut dyn Stepper) -> Schedule {
    let solver = if p.solver == Solver::Explicit { 0 } else { 1 };
    let mut schedule = Vec::new();
    let (mut work, mut finished, mut tracing, mut set_up) = (0, false, false, false);
    while !finished && work < CAP {
        (work, finished) = model.step(16);
        let (trace, setting_up) = model.observe();
        tracing |= trace == 1;
        let phase = if !set_up {
            3
        } else if tracing {
            2
        } else {
            solver
        };
        set_up |= setting_up == 0;
        extend(&mut schedule, phase, work);
    }
    schedule
}

/// Skin's phases.
const SKIN_PHASES: [&str; 4] = ["level-0 cells", "finer cells", "divisions", "setup"];

/// Skin: one piece a call (a budget of one unit). A call made while the setup is under way is
/// the setup's (a sample of the profile tables, or a table's completion); a call that builds
/// a cell is of its level's phase (level 0, or finer); one that builds none is a level-0
/// cell's when it finishes a level-0 centre point (one whose cell misses the surface), else a
/// division's (a centre point tried in a parent being divided, or a piece of its children's
/// bucketing).
fn skin_schedule(model: &mut dyn Stepper) -> Schedule {
    let mut schedule = Vec::new();
    let (mut work, mut finished, mut seen) = (0, false, 0);
    while !finished && work < CAP {
        let setting_up = model.observe().1 == u32::MAX;
        (work, finished) = model.step(1);
        let (now, level) = model.observe();
        let phase = if setting_up {
            3
        } else if now >> 32 > seen >> 32 {
            if level == 0 { 0 } else { 1 }
        } else if now > seen {
            0
        } else {
            2
        };
        extend(&mut schedule, phase, work);
        seen = now;
    }
    schedule
}

fn schedule_of(params: &Params) -> Schedule {
    with_model(params, |model| match params {
        Params::Glass(p) => glass_schedule(p, model),
        Params::Mud(p, _) => mud_schedule(p, model),
        Params::Skin(_) => skin_schedule(model),
    })
}

/// Where the schedule of case `k` of `test` is kept for its run under Callgrind.
fn schedule_file(test: &str, k: usize) -> PathBuf {
    std::env::current_exe().expect("the test binary").with_file_name(format!("{test}_{k}.schedule"))
}

/// Under Callgrind: runs the case along its schedule, each call through its phase's step
/// while the phase has been counted for fewer than [`LIMIT`] units, and prints per phase the
/// units counted and whether they were all of the phase's.
fn run_case(test: &str, k: usize, params: &Params) {
    let text = std::fs::read_to_string(schedule_file(test, k)).expect("the case's schedule");
    let schedule: Schedule = text
        .lines()
        .map(|l| {
            let (phase, end) = l.split_once(' ').expect("phase end");
            (phase.parse().expect("a phase"), end.parse().expect("an end"))
        })
        .collect();
    let mut counted = [0u64; PHASES];
    let mut whole = [true; PHASES];
    with_model(params, |model| {
        let mut work = 0;
        let mut finished = false;
        for (s, &(phase, end)) in schedule.iter().enumerate() {
            if schedule[s..].iter().all(|&(p, _)| counted[p] >= LIMIT) {
                break;
            }
            while work < end && !finished {
                let budget = (end - work).min(BUDGET);
                let before = work;
                if counted[phase] < LIMIT {
                    (work, finished) = PHASE_STEPS[phase](model, budget);
                    counted[phase] += work - before;
                } else {
                    whole[phase] = false;
                    (work, finished) = model.step(end - work);
                }
            }
        }
        for &(phase, _) in &schedule {
            if counted[phase] >= LIMIT {
                whole[phase] = false;
            }
        }
    });
    for phase in 0..PHASES {
        if counted[phase] > 0 {
            println!("\nunit_cost phase {phase} units {} whole {}", counted[phase], whole[phase]);
        }
    }
}

/// One phase of one case, measured.
struct Measured {
    case: String,
    ordinary: bool,
    phase: usize,
    units: u64,
    whole: bool,
    instructions: u64,
}

impl Measured {
    fn per_unit(&self) -> f64 {
        self.instructions as f64 / self.units as f64
    }
}

/// The median of `values` (the upper one of an even count).
fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

/// Measures every case of a model (the cases of test `test`), prints its table and checks
/// the spread of its instructions per unit; under Callgrind, runs the case named by [`CASE`].
fn measure(test: &str, model: &str, phases: &[&str], cases: Vec<Case>) {
    if let Ok(k) = std::env::var(CASE) {
        let k: usize = k.parse().expect("a case index");
        run_case(test, k, &cases[k].params);
        return;
    }
    let mut measured = Vec::new();
    for (k, c) in cases.iter().enumerate() {
        let schedule = schedule_of(&c.params);
        let text: String = schedule.iter().map(|(phase, end)| format!("{phase} {end}\n")).collect();
        std::fs::write(schedule_file(test, k), text).expect("write the schedule");
        let (stdout, costs) =
            hibi_tests::callgrind_this_test_by_function(test, "hibi_unit_cost_phase_*", (CASE, &k.to_string()));
        for line in stdout.lines().filter_map(|l| l.strip_prefix("unit_cost phase ")) {
            let fields: Vec<&str> = line.split_whitespace().collect();
            let phase: usize = fields[0].parse().expect("a phase");
            let units: u64 = fields[2].parse().expect("units");
            let whole = fields[4] == "true";
            let instructions = costs.get(&format!("hibi_unit_cost_phase_{phase}")).copied().unwrap_or(0);
            measured.push(Measured { case: c.name.clone(), ordinary: c.ordinary, phase, units, whole, instructions });
        }
        let total: u64 = measured.iter().filter(|m| m.case == c.name).map(|m| m.units).sum();
        let finished = schedule.last().is_some_and(|&(_, end)| end < CAP);
        assert!(total >= MEANINGFUL || finished, "{model}, {}: {total} units counted, and the run did not end", c.name);
    }
    let median_all = median(measured.iter().filter(|m| m.ordinary).map(Measured::per_unit).collect());
    println!("\n{model} (median of the ordinary cases: {median_all:.0} instructions a unit)");
    println!("| case | phase | units | instructions | a unit | / median |\n|---|---|---|---|---|---|");
    for m in &measured {
        let whole = if m.whole { " (all)" } else { "" };
        println!(
            "| {}{} | {} | {}{whole} | {} | {:.0} | {:.2} |",
            m.case,
            if m.ordinary { "" } else { " *" },
            phases[m.phase],
            m.units,
            m.instructions,
            m.per_unit(),
            m.per_unit() / median_all
        );
    }
    println!(
        "\n{model}: per phase, the ordinary cases' median a unit, and the extreme farthest from the model's median"
    );
    for (phase, name) in phases.iter().enumerate() {
        let of_phase: Vec<&Measured> = measured.iter().filter(|m| m.phase == phase).collect();
        let ordinary: Vec<f64> = of_phase.iter().filter(|m| m.ordinary).map(|m| m.per_unit()).collect();
        let worst = of_phase
            .iter()
            .filter(|m| !m.ordinary)
            .max_by(|a, b| (a.per_unit() / median_all).ln().abs().total_cmp(&(b.per_unit() / median_all).ln().abs()));
        let ordinary = if ordinary.is_empty() { "-".to_owned() } else { format!("{:.0}", median(ordinary)) };
        let worst = worst.map_or("-".to_owned(), |m| format!("{} ({:.2}x)", m.case, m.per_unit() / median_all));
        println!("| {model} | {name} | {ordinary} | {worst} |");
    }
    let mut failures = Vec::new();
    for m in &measured {
        if m.units < MEANINGFUL && !m.whole {
            failures.push(format!("{}, {}: {} units counted, not the whole phase", m.case, phases[m.phase], m.units));
        }
        let ratio = m.per_unit() / median_all;
        // (A unit far cheaper than the median is no risk to a budget's time; it is checked in
        // release only: the debug profile does not optimise the `fixed` crate, whose Q16 units
        // then cost several times their release count and lift mud's median.)
        let cheapest = if cfg!(debug_assertions) { 0.0 } else { 1.0 / SPREAD };
        if !(cheapest..=SPREAD).contains(&ratio) {
            failures.push(format!(
                "{}, {}: {:.0} instructions a unit, {ratio:.2} times the median {median_all:.0}",
                m.case,
                phases[m.phase],
                m.per_unit()
            ));
        }
    }
    assert!(failures.is_empty(), "{model}:\n{}", failures.join("\n"));
}

// ---------------------------------------------------------------------------------------
// Glass

fn glass_cases() -> Vec<Case> {
    let base = GlassParams::default();
    let with = |f: fn(&mut GlassParams)| {
        let mut p = base;
        f(&mut p);
        Params::Glass(p)
    };
    let mut cases = vec![case("default", true, Params::Glass(base))];
    for name in ["fig14a", "fig15c", "fig16b"] {
        cases.push(case(name, true, Params::Glass(hibi_core::glass::preset(name).expect("a preset"))));
    }
    let extremes: [Extreme<GlassParams>; 10] = [
        ("large_speed 1e-30", |p| p.large_speed = 1e-30),
        ("large_speed 1e-6", |p| p.large_speed = 1e-6),
        ("no large crack, rings asleep (large_speed 1e-6)", |p| {
            (p.large_slope, p.large_offset, p.large_speed) = (0.0, 0.0, 1e-6);
        }),
        ("radial_speed 1e8", |p| p.radial_speed = 1e8),
        ("radial_speed 1e30", |p| p.radial_speed = 1e30),
        ("fast cracks (every speed 1e30)", |p| (p.large_speed, p.radial_speed, p.ring_speed) = (1e30, 1e30, 1e30)),
        ("widest plate (65 536 px)", |p| {
            (p.width, p.height, p.impact) = (65_536.0, 65_536.0, [32_768.0, 32_768.0]);
            p.max_vertices = 1 << 20;
        }),
        ("max_vertices 10^7", |p| p.max_vertices = 10_000_000),
        ("radial_mean 10 000", |p| {
            (p.radial_mean, p.max_cracks, p.max_vertices) = (10_000.0, 16_384, 1 << 20);
        }),
        ("sector_angle 2 pi", |p| p.sector_angle = 2.0 * std::f32::consts::PI),
    ];
    cases.extend(extremes.into_iter().map(|(name, f)| case(name, false, with(f))));
    cases
}

#[test]
fn glass_units_cost_about_the_same_in_every_phase_at_any_valid_parameters() {
    measure(
        "glass_units_cost_about_the_same_in_every_phase_at_any_valid_parameters",
        "glass",
        &GLASS_PHASES,
        glass_cases(),
    );
}

// ---------------------------------------------------------------------------------------
// Mud

fn mud_cases() -> Vec<Case> {
    let base = MudParams { columns: 32, rows: 32, ..MudParams::default() };
    let mut cases = Vec::new();
    for topology in [Topology::Square, Topology::Hexagonal, Topology::Irregular] {
        for solver in [Solver::QuasiStatic, Solver::Explicit] {
            for q16 in [false, true] {
                let p = MudParams { topology, solver, ..base };
                let name = format!("{topology:?}, {solver:?}, {}", if q16 { "Q16" } else { "f32" });
                cases.push(case(name, true, Params::Mud(p, q16)));
            }
        }
    }
    let extremes: [Extreme<MudParams>; 3] = [
        ("shrink_ratio just below 1", |p| p.shrink_ratio = 0.999_999_94),
        ("break_stretch_mean 1e30", |p| p.break_stretch_mean = 1e30),
        ("break_stretch_mean just above 1", |p| p.break_stretch_mean = 1.000_000_1),
    ];
    for (name, f) in extremes {
        for topology in [Topology::Hexagonal, Topology::Irregular] {
            for solver in [Solver::QuasiStatic, Solver::Explicit] {
                let mut p = MudParams { topology, solver, ..base };
                f(&mut p);
                cases.push(case(format!("{name}, {topology:?}, {solver:?}"), false, Params::Mud(p, false)));
            }
        }
    }
    cases
}

#[test]
fn mud_units_cost_about_the_same_in_every_phase_at_any_valid_parameters() {
    measure("mud_units_cost_about_the_same_in_every_phase_at_any_valid_parameters", "mud", &MUD_PHASES, mud_cases());
}

// ---------------------------------------------------------------------------------------
// Skin

fn skin_cases() -> Vec<Case> {
    let mut cases = vec![case("default", true, Params::Skin(Box::default()))];
    for name in ["fig13a", "fig17b", "fig19a"] {
        let p = hibi_core::skin::preset(name).expect("a preset");
        cases.push(case(name, true, Params::Skin(Box::new(SkinParams { width: 160, height: 160, ..p }))));
    }
    let two = {
        let mut p = SkinParams { width: 120, height: 120, levels: 2, ..SkinParams::default() };
        p.level[0].spacing = 40.0;
        p.level[1].spacing = 1.0;
        p
    };
    let extremes: [Extreme<SkinParams>; 5] = [
        ("level 1 at 1 px under 40", |_| {}),
        ("level 1 at 1 px, stretch 1e30", |p| p.level[0].stretch = [1e30, 1e30]),
        ("level 1 at 1 px, stretch 1e30 on level 1", |p| p.level[1].stretch = [1e30, 1e30]),
        ("level 1 at 1 px, perturbation 1e30", |p| (p.level[0].perturbation, p.level[1].perturbation) = (1e30, 1e30)),
        ("level 1 at 1 px, perturbation_decay 1e30", |p| {
            (p.level[0].perturbation, p.level[0].perturbation_decay) = (0.5, 1e30);
            (p.level[1].perturbation, p.level[1].perturbation_decay) = (0.5, 1e30);
        }),
    ];
    for (name, f) in extremes {
        let mut p = two;
        f(&mut p);
        cases.push(case(name, false, Params::Skin(Box::new(p))));
    }
    cases
}

#[test]
fn skin_units_cost_about_the_same_in_every_phase_at_any_valid_parameters() {
    measure(
        "skin_units_cost_about_the_same_in_every_phase_at_any_valid_parameters",
        "skin",
        &SKIN_PHASES,
        skin_cases(),
    );
}
