//! How each model's cost grows with its work, counted in instructions (Callgrind), so that the
//! figures are the same on every run of the same build whatever the machine's load:
//!
//! - mud, the default parameters (hexagonal, periodic, quasi-static, `f32`), lattices 32² to
//!   256²: set-up, the run to the end (tracing its network) and the cells, over the nodes;
//! - glass, the paper's 640² plate at `radial_mean` 25, 50, 100 and 200, eight seeds each: the
//!   generation per plate, over the mean M (radial cracks) the plates drew;
//! - skin, the `fig19a` preset at 100² to 800² with its spacings kept (so four times the cells
//!   per doubling): the build and a render of the height and normal maps, over the cells.
//!
//! It prints a Markdown table with the growth exponent of each model's cost in its work, and
//! writes that table to `docs/src/generated/cost-growth.md` and a log-log plot of it to
//! `docs/src/images/cost-growth.svg`, which the performance page shows. Valgrind must be
//! installed; the whole run takes a few minutes.
//!
//!     cargo bench --bench growth

use std::fmt::Write as _;
use std::hint::black_box;

use hibi_core::glass::{Glass, GlassParams};
use hibi_core::mud::{Mud, MudBuffers, MudParams};
use hibi_core::polygon::Ring;
use hibi_core::skin::{Skin, SkinLayers, SkinRender, preset};
use plotters::prelude::*;

/// The environment variable naming the case a re-run under Callgrind does.
const CASE: &str = "HIBI_GROWTH_CASE";
/// The table, included by the performance page.
const TABLE: &str = "docs/src/generated/cost-growth.md";
/// The plot, shown by the performance page.
const PLOT: &str = "docs/src/images/cost-growth.svg";

const MUD_SIZES: [u32; 4] = [32, 64, 128, 256];
const GLASS_MEANS: [f32; 4] = [25.0, 50.0, 100.0, 200.0];
const GLASS_SEEDS: u64 = 8;
const SKIN_SIZES: [u32; 4] = [100, 200, 400, 800];

/// The counted call: Callgrind counts only inside it.
#[unsafe(no_mangle)]
#[inline(never)]
fn hibi_growth_counted(work: &mut dyn FnMut()) {
    black_box(0);
    work();
}

/// One model at one size: its work (nodes, M or cells) and what the run printed.
struct Point {
    work: f64,
    instructions: f64,
}

/// Mud at `size`²: set-up, run and cells; prints the node count.
fn mud(size: u32) {
    let params = MudParams { columns: size, rows: size, ..MudParams::default() };
    let memory = params.memory().expect("valid parameters");
    let (mut scalars, mut words) = (vec![0.0f32; memory.scalars], vec![0u32; memory.words]);
    let mut counts = None;
    hibi_growth_counted(&mut || {
        let mut mud = Mud::new(&params, MudBuffers { scalars: &mut scalars, words: &mut words }).expect("memory");
        mud.run().expect("a stable run");
        let c = mud.cell_counts();
        let (mut rings, mut points) = (vec![Ring::default(); c.rings], vec![[0.0f32; 2]; c.points]);
        mud.cells(&mut rings, &mut points).expect("buffers suffice");
        counts = Some(c.rings);
    });
    black_box(counts);
    println!("work {}", u64::from(size) * u64::from(size));
}

/// Glass plates at `radial_mean`, one per seed; prints the mean M.
fn glass(mean: f32) {
    let mut radial = 0u64;
    for seed in 1..=GLASS_SEEDS {
        let params = GlassParams { radial_mean: mean, seed, ..GlassParams::default() };
        let mut store = params.memory().expect("valid parameters").allocate();
        let mut buffers = Some(store.buffers());
        hibi_growth_counted(&mut || {
            let mut g = Glass::new(&params, buffers.take().expect("once")).expect("memory suffices");
            while !g.step(u64::MAX).finished {}
            radial += u64::from(g.impact_counts().radial);
        });
    }
    println!("work {}", radial as f64 / GLASS_SEEDS as f64);
}

/// Skin fig19a at `size`²: build, height and normal maps; prints the cell count.
fn skin(size: u32) {
    let params = hibi_core::skin::SkinParams { width: size, height: size, ..preset("fig19a").expect("the preset") };
    let mut store = params.memory().expect("valid parameters").allocate();
    let mut buffers = Some(store.buffers());
    let pixels = size as usize * size as usize;
    let (mut height, mut normal) = (vec![0.0f32; pixels], vec![[0.0f32; 3]; pixels]);
    let mut cells = 0;
    hibi_growth_counted(&mut || {
        let mut s = Skin::<f32>::new(&params, buffers.take().expect("once")).expect("memory suffices");
        s.run();
        let layers = SkinLayers { height: Some(&mut height), normal: Some(&mut normal), ..SkinLayers::default() };
        s.render(&SkinRender::default(), layers).expect("buffers suffice");
        cells = s.cells().len();
    });
    println!("work {cells}");
}

/// Does case `case` (re-run under Callgrind).
fn run_case(case: &str) {
    let (model, at) = case.split_once(':').expect("MODEL:SIZE");
    match model {
        "mud" => mud(at.parse().expect("a size")),
        "glass" => glass(at.parse().expect("a mean")),
        "skin" => skin(at.parse().expect("a size")),
        other => panic!("{other}: not a model"),
    }
}

/// Counts case `case` under Callgrind: its work and its instructions (the C library's
/// `__mem*` left out, as the instruction gate does).
fn count(case: &str) -> Point {
    let (stdout, costs) =
        hibi_tests::callgrind_this_program_by_function(&["growth"], "hibi_growth_counted|__mem*", (CASE, case));
    let work = stdout
        .lines()
        .find_map(|l| l.strip_prefix("work "))
        .and_then(|w| w.trim().parse().ok())
        .unwrap_or_else(|| panic!("{case}: no work printed: {stdout}"));
    let instructions = *costs.get("hibi_growth_counted").unwrap_or_else(|| panic!("{case}: nothing counted"));
    Point { work, instructions: instructions as f64 }
}

/// The least-squares slope of log(instructions) over log(work): the exponent of the growth.
fn exponent(points: &[Point]) -> f64 {
    let xy: Vec<(f64, f64)> = points.iter().map(|p| (p.work.ln(), p.instructions.ln())).collect();
    let n = xy.len() as f64;
    let (mx, my) = (xy.iter().map(|p| p.0).sum::<f64>() / n, xy.iter().map(|p| p.1).sum::<f64>() / n);
    let sxy: f64 = xy.iter().map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = xy.iter().map(|(x, _)| (x - mx) * (x - mx)).sum();
    sxy / sxx
}

/// A model's series: its name, what its work counts, its sizes' labels and its points.
struct Series {
    model: &'static str,
    work: &'static str,
    counted: &'static str,
    labels: Vec<String>,
    points: Vec<Point>,
}

fn table(series: &[Series]) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "<!-- Written by `cargo bench --bench growth`; do not edit. -->\n");
    let _ = writeln!(out, "| model | what is counted | size | work | instructions | per unit of work |");
    let _ = writeln!(out, "|---|---|---|---:|---:|---:|");
    for s in series {
        for (label, p) in s.labels.iter().zip(&s.points) {
            let _ = writeln!(
                out,
                "| {} | {} | {label} | {} {} | {:.3e} | {:.0} |",
                s.model,
                s.counted,
                if p.work.fract() == 0.0 { format!("{:.0}", p.work) } else { format!("{:.1}", p.work) },
                s.work,
                p.instructions,
                p.instructions / p.work
            );
        }
    }
    let _ = writeln!(out, "\n| model | cost grows as |");
    let _ = writeln!(out, "|---|---|");
    for s in series {
        let _ = writeln!(out, "| {} | {}^{:.2} |", s.model, s.work, exponent(&s.points));
    }
    out
}

fn plot(series: &[Series], path: &std::path::Path) {
    let root = SVGBackend::new(path, (960, 360)).into_drawing_area();
    root.fill(&WHITE).expect("draw");
    let panels = root.split_evenly((1, 3));
    let colours = [RGBColor(166, 97, 26), RGBColor(31, 119, 180), RGBColor(200, 82, 110)];
    for ((s, panel), colour) in series.iter().zip(panels.iter()).zip(colours) {
        let (x0, x1) = s.points.iter().fold((f64::MAX, 0.0f64), |(a, b), p| (a.min(p.work), b.max(p.work)));
        let (y0, y1) =
            s.points.iter().fold((f64::MAX, 0.0f64), |(a, b), p| (a.min(p.instructions), b.max(p.instructions)));
        let caption = format!("{}: ∝ {}^{:.2}", s.model, s.work, exponent(&s.points));
        let xs: Vec<f64> = s.points.iter().map(|p| p.work).collect();
        let ys: Vec<f64> = s.points.iter().map(|p| p.instructions).collect();
        let mut chart = ChartBuilder::on(panel)
            .caption(caption, ("sans-serif", 18))
            .margin(14)
            .x_label_area_size(40)
            .y_label_area_size(70)
            .build_cartesian_2d(
                (x0 / 1.5..x1 * 1.5).log_scale().with_key_points(xs),
                (y0 / 1.5..y1 * 1.5).log_scale().with_key_points(ys),
            )
            .expect("axes");
        chart
            .configure_mesh()
            .x_desc(s.work)
            .y_desc("instructions")
            .y_label_formatter(&|v| format!("{v:.2e}"))
            .x_label_formatter(&|v| if v.fract() == 0.0 { format!("{v:.0}") } else { format!("{v:.1}") })
            .draw()
            .expect("draw the mesh");
        let line: Vec<(f64, f64)> = s.points.iter().map(|p| (p.work, p.instructions)).collect();
        chart.draw_series(LineSeries::new(line.clone(), colour.stroke_width(2))).expect("draw");
        chart.draw_series(line.iter().map(|&at| Circle::new(at, 4, colour.filled()))).expect("draw");
        // A grey line of slope 1 through the first point: linear growth, for comparison.
        let first = (s.points[0].work, s.points[0].instructions);
        let linear = [first, (x1, first.1 * x1 / first.0)];
        chart.draw_series(LineSeries::new(linear, BLACK.mix(0.35))).expect("draw");
    }
    root.present().expect("write the plot");
}

fn main() {
    if let Ok(case) = std::env::var(CASE) {
        run_case(&case);
        return;
    }
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut series = vec![
        Series {
            model: "mud",
            work: "nodes",
            counted: "`Mud::new`, `run`, `cells`",
            labels: MUD_SIZES.iter().map(|s| format!("{s}²")).collect(),
            points: Vec::new(),
        },
        Series {
            model: "glass",
            work: "M",
            counted: "generation of one 640² plate (mean of 8 seeds)",
            labels: GLASS_MEANS.iter().map(|m| format!("M_ave = {m}")).collect(),
            points: Vec::new(),
        },
        Series {
            model: "skin",
            work: "cells",
            counted: "`Skin::new`, `run`, height and normal render (`fig19a`)",
            labels: SKIN_SIZES.iter().map(|s| format!("{s}²")).collect(),
            points: Vec::new(),
        },
    ];
    let cases: [Vec<String>; 3] = [
        MUD_SIZES.iter().map(|s| format!("mud:{s}")).collect(),
        GLASS_MEANS.iter().map(|m| format!("glass:{m}")).collect(),
        SKIN_SIZES.iter().map(|s| format!("skin:{s}")).collect(),
    ];
    for (s, cases) in series.iter_mut().zip(cases) {
        for case in cases {
            eprintln!("counting {case}");
            let mut p = count(&case);
            if s.model == "glass" {
                p.instructions /= GLASS_SEEDS as f64;
            }
            s.points.push(p);
        }
    }
    let text = table(&series);
    print!("{text}");
    std::fs::write(root.join(TABLE), &text).expect("write the table");
    plot(&series, &root.join(PLOT));
    println!("\nwrote {TABLE} and {PLOT}");
}
