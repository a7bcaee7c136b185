//! `hibi mud`: Model A, drying mud, through `hibi_core::mud`'s public API.

use hibi_core::mud::{
    Boundary, CrackStatistics, Drive, Mud, MudBuffers, MudError, MudParamError, MudParams, MudRender, Solver, Topology,
};

use crate::Failure;
use crate::args::{BoundaryArg, DriveArg, Layer, MudOptions, SolverArg, TopologyArg};
use crate::image::{Image, crack_pictures};
use crate::progress::Progress;

/// The parameters: the preset's (or the defaults), then every option given.
pub fn params(preset: Option<&str>, seed: Option<u64>, o: &MudOptions) -> MudParams {
    let mut p = preset.and_then(hibi_core::mud::preset).unwrap_or_default();
    if let Some(v) = o.topology {
        p.topology = match v {
            TopologyArg::Hexagonal => Topology::Hexagonal,
            TopologyArg::Square => Topology::Square,
            TopologyArg::Irregular => Topology::Irregular,
        };
    }
    if let Some(v) = o.boundary {
        p.boundary = match v {
            BoundaryArg::Open => Boundary::Open,
            BoundaryArg::Periodic => Boundary::Periodic,
        };
    }
    if let Some(v) = o.solver {
        p.solver = match v {
            SolverArg::QuasiStatic => Solver::QuasiStatic,
            SolverArg::Explicit => Solver::Explicit,
        };
    }
    if let Some(v) = o.drive {
        p.drive = match v {
            DriveArg::Shrink => Drive::Shrink,
            DriveArg::Growth => Drive::Growth,
        };
    }
    let set = |field: &mut f32, value: Option<f32>| {
        if let Some(v) = value {
            *field = v;
        }
    };
    p.seed = seed.unwrap_or(p.seed);
    p.columns = o.columns.unwrap_or(p.columns);
    p.rows = o.rows.unwrap_or(p.rows);
    set(&mut p.layer_thickness, o.layer_thickness);
    set(&mut p.element_size, o.element_size);
    set(&mut p.long_step, o.long_step);
    set(&mut p.short_step, o.short_step);
    set(&mut p.shrink_ratio, o.shrink_ratio);
    set(&mut p.displacement_tolerance, o.displacement_tolerance);
    set(&mut p.damping_factor, o.damping_factor);
    set(&mut p.density, o.density);
    set(&mut p.young_modulus, o.young_modulus);
    set(&mut p.shear_modulus, o.shear_modulus);
    set(&mut p.break_stretch_mean, o.break_stretch_mean);
    set(&mut p.break_stretch_spread, o.break_stretch_spread);
    set(&mut p.break_stretch_size_exponent, o.break_stretch_size_exponent);
    set(&mut p.anisotropy_direction, o.anisotropy_direction.map(f32::to_radians));
    set(&mut p.anisotropy_ratio, o.anisotropy_ratio);
    set(&mut p.stiffness_anisotropy_ratio, o.stiffness_anisotropy_ratio);
    set(&mut p.target_shrink, o.target_shrink);
    set(&mut p.target_crack_density, o.target_crack_density);
    p
}

/// The raster: `size`, or 4 pixels per lattice spacing (256 to 2048 wide) at the domain's
/// aspect; the narrowest stroke the library's fit for the width; stroke options as given.
pub fn view(params: &MudParams, size: Option<[u32; 2]>, o: &MudOptions) -> MudRender {
    let width = size.map_or((params.columns * 4).clamp(256, 2048), |s| s[0]);
    let fit = MudRender::fit(params.extent(), width);
    let [width, height] = size.unwrap_or([fit.width, fit.height]);
    MudRender {
        width,
        height,
        width_scale: o.width_scale.unwrap_or(fit.width_scale),
        min_width: o.min_width.unwrap_or(fit.min_width),
        groove_depth: o.groove_depth.unwrap_or(fit.groove_depth),
        offset: o.offset.unwrap_or(fit.offset),
        ..fit
    }
}

/// The option a parameter error is about.
fn option(e: MudParamError) -> &'static str {
    use MudParamError::*;
    match e {
        Columns => "--columns",
        Rows => "--rows",
        LayerThickness => "--layer-thickness",
        ElementSize => "--element-size",
        LongStep => "--long-step",
        ShortStep => "--short-step",
        ShrinkRatio => "--shrink-ratio",
        DisplacementTolerance => "--displacement-tolerance",
        DampingFactor => "--damping-factor",
        Density => "--density",
        YoungModulus => "--young-modulus",
        ShearModulus => "--shear-modulus",
        BreakStretchMean => "--break-stretch-mean",
        BreakStretchSpread => "--break-stretch-spread",
        AnisotropyDirection => "--anisotropy-direction",
        AnisotropyRatio => "--anisotropy-ratio",
        StiffnessAnisotropyRatio => "--stiffness-anisotropy-ratio",
        TargetShrink => "--target-shrink",
        TargetCrackDensity => "--target-crack-density",
        SizeOverflow => "--columns/--rows",
        ShearScale => "--shear-modulus/--young-modulus/--element-size/--layer-thickness",
        BreakStretchSizeExponent => "--break-stretch-size-exponent",
        DampingScale => "--damping-factor",
        ShortStepScale => "--short-step/--element-size/--density/--young-modulus",
        ToleranceScale => "--displacement-tolerance/--element-size",
        SpreadScale => "--break-stretch-spread/--element-size/--layer-thickness",
        ShortStepStability => "--short-step/--damping-factor/--solver",
    }
}

/// Checks the parameters and the raster; a usage error names the option.
pub fn check(params: &MudParams, render: &MudRender) -> Result<(), Failure> {
    params.memory().map_err(|e| Failure::invalid("mud", option(e), e.to_string()))?;
    let raster = [
        (render.width_scale.is_finite() && render.width_scale >= 0.0, "--width-scale", "finite and >= 0"),
        (render.min_width.is_finite() && render.min_width >= 0.0, "--min-width", "finite and >= 0"),
        (render.groove_depth.is_finite() && render.groove_depth >= 0.0, "--groove-depth", "finite and >= 0"),
        (render.offset.iter().all(|v| v.is_finite()), "--offset", "finite"),
    ];
    match raster.iter().find(|(ok, _, _)| !ok) {
        Some(&(_, name, why)) => Err(Failure::invalid("mud", name, format!("must be {why}"))),
        None => Ok(()),
    }
}

/// A picture to draw of a finished run: the view, the layer, and a still (None) or that many
/// frames of the growth.
pub type Want = (MudRender, Layer, Option<u32>);

/// A finished run's pictures and what to say about it.
pub struct MudRun {
    /// The pictures, one list (a still, or the frames) per [`Want`].
    pub pictures: Vec<Vec<Image>>,
    /// Crack statistics of the run.
    pub statistics: CrackStatistics,
    /// The misfit the run ended at.
    pub shrink: f32,
}

impl MudRun {
    /// One line about the run.
    pub fn summary(&self) -> String {
        let s = &self.statistics;
        let cells = match s.cells {
            0 | 1 => "no closed cells".to_string(),
            n => format!("{n} cells of {:.0} cm² on average", s.mean_cell_area),
        };
        format!("shrink {:.2} %, crack density {:.3}/cm, {cells}", 100.0 * self.shrink, s.crack_density)
    }
}

/// How far a run is, 0 to 1, if its end is known.
fn fraction(params: &MudParams, shrink: f32, density: f32) -> f32 {
    let by_shrink = if params.target_shrink > 0.0 { shrink / params.target_shrink } else { 0.0 };
    let by_density = if params.target_crack_density > 0.0 { density / params.target_crack_density } else { 0.0 };
    by_shrink.max(by_density).clamp(0.0, 1.0)
}

/// Runs `params` to its end, reporting to `progress`, and draws every picture wanted. The
/// parameters and views must have passed [`check`]. Fails, naming the options, when the
/// explicit solver's short step fails its stability test on an irregular lattice (known only
/// once the first steps have built the lattice). Each picture is drawn on up to `threads` threads.
pub fn simulate(params: &MudParams, wants: &[Want], threads: usize, progress: &Progress) -> Result<MudRun, Failure> {
    let memory = params.memory().expect("checked parameters");
    let (mut scalars, mut words) = (vec![0.0f32; memory.scalars], vec![0u32; memory.words]);
    let failure = |error: MudError| match error {
        MudError::Param(e) => Failure::invalid("mud", option(e), e.to_string()),
        e => Failure::Runtime(e.to_string()),
    };
    let mut mud = Mud::new(params, MudBuffers { scalars: &mut scalars, words: &mut words }).map_err(failure)?;
    // With no bar to move, one call: it makes no live trace, which nothing here would show.
    if progress.is_hidden() {
        mud.run().map_err(failure)?;
    }
    loop {
        let p = mud.step(2_000_000).map_err(failure)?;
        progress.set_fraction(fraction(params, p.shrink, p.crack_density));
        if p.finished {
            break;
        }
    }
    let pictures = wants
        .iter()
        .map(|&(view, layer, frames)| {
            crack_pictures((view.width, view.height), layer, frames, threads, |until, tile, layers| {
                mud.render_tile(&MudRender { until, ..view }, tile, layers).expect("the view was checked")
            })
        })
        .collect();
    let statistics = mud.statistics();
    Ok(MudRun { pictures, statistics, shrink: mud.progress().shrink })
}

/// The most frames [`simulate_live`] draws.
pub const LIVE_FRAMES: usize = 1000;

/// Runs `params` to its end in steps of `budget` units and draws `view`'s `layer` after every
/// step from the one in which the first spring breaks: the frames an engine shows while the
/// run goes on (each from the network the run shows then). Returns them and the finished run
/// (its picture the last frame's). Fails if there would be more than [`LIVE_FRAMES`] frames.
/// Each frame is drawn on up to `threads` threads.
pub fn simulate_live(
    params: &MudParams,
    view: &MudRender,
    (layer, budget, threads): (Layer, u64, usize),
    progress: &Progress,
) -> Result<(Vec<Image>, MudRun), Failure> {
    let memory = params.memory().expect("checked parameters");
    let (mut scalars, mut words) = (vec![0.0f32; memory.scalars], vec![0u32; memory.words]);
    let failure = |error: MudError| match error {
        MudError::Param(e) => Failure::invalid("mud", option(e), e.to_string()),
        e => Failure::Runtime(e.to_string()),
    };
    let mut mud = Mud::new(params, MudBuffers { scalars: &mut scalars, words: &mut words }).map_err(failure)?;
    let draw = |mud: &Mud<'_>| {
        crack_pictures((view.width, view.height), layer, None, threads, |until, tile, layers| {
            mud.render_tile(&MudRender { until, ..*view }, tile, layers).expect("the view was checked")
        })
    };
    let mut frames = Vec::new();
    loop {
        let p = mud.step(budget).map_err(failure)?;
        progress.set_fraction(fraction(params, p.shrink, p.crack_density));
        if p.broken_springs > 0 {
            if frames.len() == LIVE_FRAMES {
                let why = format!("makes more than {LIVE_FRAMES} frames of this run: give more units");
                return Err(Failure::invalid("mud", "--live", why));
            }
            frames.extend(draw(&mud));
        }
        if p.finished {
            break;
        }
    }
    let run = MudRun { pictures: vec![draw(&mud)], statistics: mud.statistics(), shrink: mud.progress().shrink };
    Ok((frames, run))
}

/// Every parameter as (option, value), in the order of `--help`.
pub fn options(p: &MudParams, r: &MudRender) -> Vec<(&'static str, String)> {
    let topology = match p.topology {
        Topology::Hexagonal => "hexagonal",
        Topology::Square => "square",
        Topology::Irregular => "irregular",
    };
    let boundary = match p.boundary {
        Boundary::Open => "open",
        Boundary::Periodic => "periodic",
    };
    let solver = match p.solver {
        Solver::QuasiStatic => "quasi-static",
        Solver::Explicit => "explicit",
    };
    let drive = match p.drive {
        Drive::Shrink => "shrink",
        Drive::Growth => "growth",
    };
    vec![
        ("--seed", p.seed.to_string()),
        ("--size", format!("{}x{}", r.width, r.height)),
        ("--topology", topology.into()),
        ("--boundary", boundary.into()),
        ("--solver", solver.into()),
        ("--drive", drive.into()),
        ("--columns", p.columns.to_string()),
        ("--rows", p.rows.to_string()),
        ("--layer-thickness", p.layer_thickness.to_string()),
        ("--element-size", p.element_size.to_string()),
        ("--long-step", p.long_step.to_string()),
        ("--short-step", p.short_step.to_string()),
        ("--shrink-ratio", p.shrink_ratio.to_string()),
        ("--displacement-tolerance", p.displacement_tolerance.to_string()),
        ("--damping-factor", p.damping_factor.to_string()),
        ("--density", p.density.to_string()),
        ("--young-modulus", p.young_modulus.to_string()),
        ("--shear-modulus", p.shear_modulus.to_string()),
        ("--break-stretch-mean", p.break_stretch_mean.to_string()),
        ("--break-stretch-spread", p.break_stretch_spread.to_string()),
        ("--break-stretch-size-exponent", p.break_stretch_size_exponent.to_string()),
        ("--anisotropy-direction", degrees(p.anisotropy_direction)),
        ("--anisotropy-ratio", p.anisotropy_ratio.to_string()),
        ("--stiffness-anisotropy-ratio", p.stiffness_anisotropy_ratio.to_string()),
        ("--target-shrink", p.target_shrink.to_string()),
        ("--target-crack-density", p.target_crack_density.to_string()),
        ("--width-scale", r.width_scale.to_string()),
        ("--min-width", r.min_width.to_string()),
        ("--groove-depth", r.groove_depth.to_string()),
        ("--offset", format!("{},{}", r.offset[0], r.offset[1])),
    ]
}

/// Radians as degrees, rounded to what the command line would have been given.
pub fn degrees(radians: f32) -> String {
    let d = f64::from(radians).to_degrees();
    format!("{}", (d * 1e4).round() / 1e4)
}
