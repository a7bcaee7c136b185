//! `hibi skin`: Model C, skin from hierarchical Voronoi cells, through `hibi_core::skin`'s
//! public API.

use hibi_core::Spread;
use hibi_core::skin::{
    MAX_SEGMENTS, Profile, ShadeError, ShadeParams, SiteLayout, Skin, SkinError, SkinParamError, SkinParams, SkinRender,
};

use crate::Failure;
use crate::args::{Layer, LayoutArg, PerLevel, SkinOptions, SpreadArg};
use crate::image::{Buffers, Image};

/// The paper's image size; the presets' spacings are meant for it.
pub const PAPER_SIZE: u32 = 400;

/// The parameters (the preset's or the defaults, then every option given) and the light.
pub fn params(
    preset: Option<&str>,
    seed: Option<u64>,
    size: Option<[u32; 2]>,
    o: &SkinOptions,
) -> Result<(SkinParams, ShadeParams), Failure> {
    let mut p = preset.and_then(hibi_core::skin::preset).unwrap_or_default();
    p.seed = seed.unwrap_or(p.seed);
    if let Some([w, h]) = size {
        (p.width, p.height) = (w, h);
    }
    if let Some(layout) = o.layout {
        p.layout = match layout {
            LayoutArg::Triangular => SiteLayout::Triangular,
            LayoutArg::Square => SiteLayout::Square,
            LayoutArg::Random => SiteLayout::Random,
        };
    }
    if let Some(jitter) = o.jitter {
        p.jitter = match jitter {
            SpreadArg::Uniform => Spread::Uniform,
            SpreadArg::Normal => Spread::Normal,
        };
    }
    p.jitter_ratio = o.jitter_ratio.unwrap_or(p.jitter_ratio);
    p.periodic = o.periodic.unwrap_or(p.periodic);
    p.levels = o.levels.unwrap_or(p.levels);
    // Per-level values, each for a level the skin has.
    let levels = p.levels as usize;
    let beyond = |name: &str, level: usize| {
        Failure::invalid("skin", name, format!("level {} is beyond the skin's {levels} level(s) (--levels)", level + 1))
    };
    fn each<T: Clone>(
        values: &[PerLevel<T>],
        name: &'static str,
        levels: usize,
        beyond: &dyn Fn(&str, usize) -> Failure,
        mut apply: impl FnMut(usize, T),
    ) -> Result<(), Failure> {
        for v in values {
            if v.level >= levels {
                return Err(beyond(name, v.level));
            }
            apply(v.level, v.value.clone());
        }
        Ok(())
    }
    let level = &mut p.level;
    each(&o.spacing, "--spacing", levels, &beyond, |l, v| level[l].spacing = v)?;
    each(&o.perturbation, "--perturbation", levels, &beyond, |l, v| level[l].perturbation = v)?;
    each(&o.perturbation_decay, "--perturbation-decay", levels, &beyond, |l, v| level[l].perturbation_decay = v)?;
    each(&o.perturbation_depth, "--perturbation-depth", levels, &beyond, |l, v| level[l].perturbation_depth = v)?;
    each(&o.stretch, "--stretch", levels, &beyond, |l, v| level[l].stretch = v)?;
    each(&o.roundness, "--roundness", levels, &beyond, |l, v| level[l].roundness = v)?;
    each(&o.profile, "--profile", levels, &beyond, |l, points| level[l].profile = profile(&points))?;
    let d = ShadeParams::default();
    let light = ShadeParams {
        light: o.light.unwrap_or(d.light),
        ridge: o.ridge.unwrap_or(d.ridge),
        furrow: o.furrow.unwrap_or(d.furrow),
        ambient: o.ambient.unwrap_or(d.ambient),
        specular: o.specular.unwrap_or(d.specular),
    };
    Ok((p, light))
}

/// A profile from 3k + 1 points (checked by the parser).
fn profile(points: &[[f32; 2]]) -> Profile {
    let mut out = Profile::cubic([points[0], points[1], points[2], points[3]]);
    out.segments = ((points.len() - 1) / 3).min(MAX_SEGMENTS) as u32;
    out.points[..points.len()].copy_from_slice(points);
    out
}

/// A preset at `size`: its spacings scaled from the paper's 400 px, so that the picture shows
/// the paper's field (the finest level no finer than 1 px).
pub fn scaled_preset(name: &str, size: u32) -> SkinParams {
    let mut p = hibi_core::skin::preset(name).expect("a listed preset");
    let scale = size as f32 / PAPER_SIZE as f32;
    (p.width, p.height) = (size, size);
    for l in &mut p.level {
        l.spacing = (l.spacing * scale).max(1.0);
    }
    p
}

/// The option a parameter error is about.
fn option(e: SkinParamError) -> &'static str {
    use SkinParamError::*;
    match e {
        Size => "--size",
        JitterRatio => "--jitter-ratio",
        Levels => "--levels",
        Spacing => "--spacing",
        Perturbation => "--perturbation/--perturbation-decay",
        PerturbationDepth => "--perturbation-depth",
        Stretch => "--stretch",
        ProfileSegments | ProfilePoints => "--profile",
        Roundness => "--roundness",
        Capacity => "--size/--spacing",
    }
}

/// The core's message for a parameter error.
fn message(e: SkinParamError) -> String {
    e.message().to_string_lossy().into_owned()
}

/// Checks the parameters, the light and the layer; a usage error names the option.
pub fn check(params: &SkinParams, light: &ShadeParams, layer: Layer) -> Result<(), Failure> {
    params.memory().map_err(|e| Failure::invalid("skin", option(e), message(e)))?;
    light.validate().map_err(shade_failure)?;
    if layer == Layer::Time {
        return Err(Failure::invalid(
            "skin",
            "--layer",
            "skin does not grow, so it has no time layer (mask, height, normal, shaded)".into(),
        ));
    }
    Ok(())
}

/// A shading parameter error as a usage error naming its option.
fn shade_failure(e: ShadeError) -> Failure {
    let name = match e {
        ShadeError::Light => "--light",
        ShadeError::Ridge => "--ridge",
        ShadeError::Furrow => "--furrow",
        ShadeError::Ambient => "--ambient",
        ShadeError::Specular => "--specular",
    };
    Failure::invalid("skin", name, e.message().to_string_lossy().into_owned())
}

/// A built skin's picture and what to say about it.
pub struct SkinRun {
    /// The layer asked for.
    pub image: Image,
    /// Cells per level.
    pub cells: Vec<usize>,
}

impl SkinRun {
    /// One line about the skin.
    pub fn summary(&self) -> String {
        let cells: Vec<String> = self.cells.iter().map(usize::to_string).collect();
        format!("{} cells per level", cells.join(" / "))
    }
}

/// Builds the skin and renders `layer` on up to `threads` threads. The parameters must have
/// passed [`check`].
pub fn render(params: &SkinParams, light: &ShadeParams, layer: Layer, threads: usize) -> Result<SkinRun, Failure> {
    let memory = params.memory().expect("checked parameters");
    let mut store = memory.allocate();
    let mut skin = Skin::<f32>::new(params, store.buffers()).map_err(failure)?;
    if skin.run().capacity_reached {
        return Err(Failure::Runtime(
            "skin: a cell outline or a cell's centre points outgrew their fixed capacity: lower \
             --perturbation-depth, or make finer levels less fine (--spacing)"
                .into(),
        ));
    }
    let (width, height) = (params.width, params.height);
    let mut counts = vec![0usize; params.levels as usize];
    for c in skin.cells() {
        counts[c.level as usize] += 1;
    }
    if layer == Layer::Time {
        unreachable!("refused by check");
    }
    let mut buffers = Buffers::new(layer, width, height);
    let render = SkinRender { shade: *light, ..SkinRender::default() };
    let failed = std::sync::Mutex::new(None);
    buffers.draw(threads, |tile, layers| {
        if let Err(e) = skin.render_tile(&render, tile, layers) {
            *failed.lock().expect("a band panicked") = Some(e);
        }
    });
    if let Some(e) = failed.into_inner().expect("a band panicked") {
        return Err(failure(e));
    }
    let image = buffers.picture();
    Ok(SkinRun { image, cells: counts })
}

/// A build or render failure.
fn failure(e: SkinError) -> Failure {
    match e {
        SkinError::Param(p) => Failure::invalid("skin", option(p), message(p)),
        SkinError::Shade(e) => shade_failure(e),
        other => Failure::Runtime(format!("skin: internal error: {other:?}")),
    }
}

/// A profile as its points, `x,z x,z ...`.
fn points(profile: &Profile) -> String {
    let points: Vec<String> = profile.used().iter().map(|p| format!("{},{}", p[0], p[1])).collect();
    points.join(" ")
}

/// Every parameter as (option, value), in the order of `--help`; per-level options once per
/// level the skin has.
pub fn options(p: &SkinParams, light: &ShadeParams) -> Vec<(&'static str, String)> {
    let layout = match p.layout {
        SiteLayout::Triangular => "triangular",
        SiteLayout::Square => "square",
        SiteLayout::Random => "random",
    };
    let jitter = match p.jitter {
        Spread::Uniform => "uniform",
        Spread::Normal => "normal",
    };
    let mut out = vec![
        ("--seed", p.seed.to_string()),
        ("--size", format!("{}x{}", p.width, p.height)),
        ("--layout", layout.into()),
        ("--jitter", jitter.into()),
        ("--jitter-ratio", p.jitter_ratio.to_string()),
        ("--periodic", p.periodic.to_string()),
        ("--levels", p.levels.to_string()),
    ];
    for (k, l) in p.level.iter().enumerate().take(p.levels as usize) {
        let at = |v: String| if k == 0 { v } else { format!("{}={v}", k + 1) };
        out.extend([
            ("--spacing", at(format!("{}", (l.spacing * 1e4).round() / 1e4))),
            ("--perturbation", at(l.perturbation.to_string())),
            ("--perturbation-decay", at(l.perturbation_decay.to_string())),
            ("--perturbation-depth", at(l.perturbation_depth.to_string())),
            ("--stretch", at(format!("{},{}", l.stretch[0], l.stretch[1]))),
            ("--profile", at(points(&l.profile))),
            ("--roundness", at(l.roundness.to_string())),
        ]);
    }
    let triple = |v: [f32; 3]| format!("{},{},{}", v[0], v[1], v[2]);
    out.extend([
        ("--light", triple(light.light)),
        ("--ridge", triple(light.ridge)),
        ("--furrow", triple(light.furrow)),
        ("--ambient", light.ambient.to_string()),
        ("--specular", light.specular.to_string()),
    ]);
    out
}
