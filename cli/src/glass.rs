//! `hibi glass`: Model B, a glass plate hit by a ball, through `hibi_core::glass`'s public
//! API.

use hibi_core::Spread;
use hibi_core::glass::{Glass, GlassBuffers, GlassParamError, GlassParams, GlassRender, ImpactCounts};

use crate::Failure;
use crate::args::Layer;
use crate::args::{GlassOptions, SpreadArg};
use crate::image::{Image, crack_pictures};
use crate::mud::degrees;
use crate::progress::Progress;

/// The parameters (the preset's or the defaults, then every option given) and the impact
/// points (the first is `params.impact`).
pub fn params(preset: Option<&str>, seed: Option<u64>, o: &GlassOptions) -> (GlassParams, Vec<[f32; 2]>) {
    let mut p = preset.and_then(hibi_core::glass::preset).unwrap_or_default();
    let set = |field: &mut f32, value: Option<f32>| {
        if let Some(v) = value {
            *field = v;
        }
    };
    p.seed = seed.unwrap_or(p.seed);
    let plate = [p.width, p.height];
    set(&mut p.width, o.width);
    set(&mut p.height, o.height);
    if [p.width, p.height] != plate {
        p.impact = [0.5 * p.width, 0.5 * p.height];
    }
    set(&mut p.radial_mean, o.radial_mean);
    set(&mut p.ring_threshold, o.ring_threshold);
    set(&mut p.large_slope, o.large_slope);
    set(&mut p.large_offset, o.large_offset);
    set(&mut p.ring_slope, o.ring_slope);
    set(&mut p.ring_offset, o.ring_offset);
    set(&mut p.ring_radius_slope, o.ring_radius_slope);
    set(&mut p.ring_radius_offset, o.ring_radius_offset);
    set(&mut p.large_speed, o.large_speed);
    set(&mut p.radial_speed, o.radial_speed);
    set(&mut p.ring_speed, o.ring_speed);
    set(&mut p.spread_ratio, o.spread_ratio);
    if let Some(s) = o.spread {
        p.spread = match s {
            SpreadArg::Normal => Spread::Normal,
            SpreadArg::Uniform => Spread::Uniform,
        };
    }
    set(&mut p.turn_limit, o.turn_limit.map(f32::to_radians));
    set(&mut p.turn_delay, o.turn_delay);
    set(&mut p.sector_angle, o.sector_angle.map(f32::to_radians));
    set(&mut p.sector_radius, o.sector_radius);
    set(&mut p.tip_repulsion, o.tip_repulsion);
    set(&mut p.crack_attraction, o.crack_attraction);
    set(&mut p.wander, o.wander.map(f32::to_radians));
    set(&mut p.ring_adherence, o.ring_adherence);
    p.max_cracks = o.max_cracks.unwrap_or(p.max_cracks);
    p.max_vertices = o.max_vertices.unwrap_or(p.max_vertices);
    if let Some(&first) = o.impact.first() {
        p.impact = first;
    }
    let impacts = if o.impact.is_empty() { vec![p.impact] } else { o.impact.clone() };
    (p, impacts)
}

/// The raster: `size`, or the plate's size.
pub fn view(params: &GlassParams, size: Option<[u32; 2]>, o: &GlassOptions) -> GlassRender {
    let plate = [params.width, params.height].map(|v| (v.round() as u32).clamp(1, 32_768));
    let [width, height] = size.unwrap_or(plate);
    GlassRender {
        width,
        height,
        line_width: o.line_width.unwrap_or(GlassRender::default().line_width),
        ..GlassRender::default()
    }
}

/// The options a parameter error is about.
fn option(e: GlassParamError) -> &'static str {
    use GlassParamError::*;
    match e {
        Size => "--width/--height",
        Impact => "--impact",
        RadialMean => "--radial-mean",
        RingThreshold => "--ring-threshold",
        CountFormula => "--large-slope/--large-offset/--ring-slope/--ring-offset",
        RingRadius => "--ring-radius-slope/--ring-radius-offset",
        Speed => "--large-speed/--radial-speed/--ring-speed",
        SpreadRatio => "--spread-ratio",
        TurnLimit => "--turn-limit",
        TurnDelay => "--turn-delay",
        Sector => "--sector-angle/--sector-radius",
        Forces => "--tip-repulsion/--crack-attraction/--wander/--ring-adherence",
        Capacity => "--max-cracks/--max-vertices",
    }
}

/// Checks the parameters, every impact and the raster; a usage error names the option.
pub fn check(params: &GlassParams, impacts: &[[f32; 2]], render: &GlassRender) -> Result<(), Failure> {
    let message = |e: GlassParamError| {
        // The core's messages are in radians; the command line takes degrees.
        match e {
            GlassParamError::TurnLimit => "glass: turn_limit must be within [0, 180] degrees".to_string(),
            GlassParamError::Sector => {
                "glass: sector_angle must be within (0, 360] degrees and sector_radius finite and > 0".to_string()
            }
            _ => e.to_string(),
        }
    };
    params.memory().map_err(|e| Failure::invalid("glass", option(e), message(e)))?;
    let inside = |[x, y]: [f32; 2]| x > 0.0 && x < params.width && y > 0.0 && y < params.height;
    if let Some(at) = impacts.iter().find(|&&at| !inside(at)) {
        let why = format!("{},{} is not inside the {}x{} plate", at[0], at[1], params.width, params.height);
        return Err(Failure::invalid("glass", "--impact", why));
    }
    if !(render.line_width.is_finite() && render.line_width > 0.0) {
        return Err(Failure::invalid("glass", "--line-width", "must be finite and > 0".into()));
    }
    Ok(())
}

/// A finished plate's pictures and what to say about it.
pub struct GlassRun {
    /// The pictures, one list (a still, or the frames of the growth) per picture wanted.
    pub pictures: Vec<Vec<Image>>,
    /// The counts each impact drew.
    pub counts: Vec<ImpactCounts>,
    /// Cracks on the plate.
    pub cracks: usize,
}

impl GlassRun {
    /// One line about the plate.
    pub fn summary(&self) -> String {
        let counts: Vec<String> =
            self.counts.iter().map(|c| format!("M = {}, N = {}, R = {}", c.radial, c.large, c.rings)).collect();
        format!("{}; {} cracks", counts.join(" / "), self.cracks)
    }
}

/// Grows every impact to its end, reporting to `progress`, and draws every picture wanted (a
/// layer, and a still or that many frames of the growth). The
/// parameters and raster must have passed [`check`]. Fails when a capacity runs out. Each
/// picture is drawn on up to `threads` threads.
pub fn simulate(
    params: &GlassParams,
    impacts: &[[f32; 2]],
    render: &GlassRender,
    (wants, threads): (&[(Layer, Option<u32>)], usize),
    progress: &Progress,
) -> Result<GlassRun, Failure> {
    let m = params.memory().expect("checked parameters");
    let (mut cracks, mut vertices) = (vec![Default::default(); m.cracks], vec![Default::default(); m.vertices]);
    let (mut edges, mut words) = (vec![Default::default(); m.edges], vec![0u32; m.words]);
    let buffers = GlassBuffers { cracks: &mut cracks, vertices: &mut vertices, edges: &mut edges, words: &mut words };
    let mut glass = Glass::new(params, buffers).expect("memory of the size asked for");
    let mut counts = vec![glass.impact_counts()];
    for (k, &at) in impacts.iter().enumerate() {
        if k > 0 {
            counts.push(glass.impact(at).expect("checked impact"));
        }
        loop {
            let p = glass.step(10_000);
            if p.capacity_reached {
                return Err(Failure::Runtime(format!(
                    "glass: the plate ran out of room for cracks ({} cracks, {} vertices): raise --max-cracks or \
                     --max-vertices",
                    p.cracks, p.vertices
                )));
            }
            // Progress: impacts done, and within one the share of cracks that stopped.
            let within = if p.cracks == 0 { 1.0 } else { 1.0 - p.growing as f32 / p.cracks as f32 };
            progress.set_fraction((k as f32 + within) / impacts.len() as f32);
            if p.finished {
                break;
            }
        }
    }
    let pictures = wants
        .iter()
        .map(|&(layer, frames)| {
            crack_pictures((render.width, render.height), layer, frames, threads, |until, tile, layers| {
                glass.render_tile(&GlassRender { until, ..*render }, tile, layers).expect("the raster was checked")
            })
        })
        .collect();
    Ok(GlassRun { pictures, counts, cracks: glass.crack_count() })
}

/// Every parameter as (option, value), in the order of `--help`.
pub fn options(p: &GlassParams, impacts: &[[f32; 2]], r: &GlassRender) -> Vec<(&'static str, String)> {
    let spread = match p.spread {
        Spread::Normal => "normal",
        Spread::Uniform => "uniform",
    };
    let mut out = vec![
        ("--seed", p.seed.to_string()),
        ("--size", format!("{}x{}", r.width, r.height)),
        ("--width", p.width.to_string()),
        ("--height", p.height.to_string()),
    ];
    out.extend(impacts.iter().map(|at| ("--impact", format!("{},{}", at[0], at[1]))));
    out.extend([
        ("--radial-mean", p.radial_mean.to_string()),
        ("--ring-threshold", p.ring_threshold.to_string()),
        ("--large-slope", p.large_slope.to_string()),
        ("--large-offset", p.large_offset.to_string()),
        ("--ring-slope", p.ring_slope.to_string()),
        ("--ring-offset", p.ring_offset.to_string()),
        ("--ring-radius-slope", p.ring_radius_slope.to_string()),
        ("--ring-radius-offset", p.ring_radius_offset.to_string()),
        ("--large-speed", p.large_speed.to_string()),
        ("--radial-speed", p.radial_speed.to_string()),
        ("--ring-speed", p.ring_speed.to_string()),
        ("--spread-ratio", p.spread_ratio.to_string()),
        ("--spread", spread.to_string()),
        ("--turn-limit", degrees(p.turn_limit)),
        ("--turn-delay", p.turn_delay.to_string()),
        ("--sector-angle", degrees(p.sector_angle)),
        ("--sector-radius", p.sector_radius.to_string()),
        ("--tip-repulsion", p.tip_repulsion.to_string()),
        ("--crack-attraction", p.crack_attraction.to_string()),
        ("--wander", degrees(p.wander)),
        ("--ring-adherence", p.ring_adherence.to_string()),
        ("--max-cracks", p.max_cracks.to_string()),
        ("--max-vertices", p.max_vertices.to_string()),
        ("--line-width", r.line_width.to_string()),
    ]);
    out
}
