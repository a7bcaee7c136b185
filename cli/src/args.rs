//! The command line: subcommands, options and their value parsers.
//!
//! Every model parameter is an option named after its field (`young_modulus` is
//! `--young-modulus`); an option left out keeps the preset's value, or the paper's default
//! without a preset. Angles are in degrees on the command line (the core takes radians).

use std::num::NonZeroUsize;
use std::path::PathBuf;

use clap::builder::PossibleValuesParser;
use clap::{Args, Parser, Subcommand, ValueEnum};

const EXIT_STATUS: &str = "\
Exit status: 0 on success, 1 when the run or writing the output fails (the message says
why), 2 on a usage error (a bad option or value; the message names it). Outputs are written
to a temporary file beside the target and renamed into place, so a failed run leaves no
partial file.";

/// hibi: crack and cell patterns from three graphics papers, rendered to PNG.
#[derive(Parser, Debug)]
#[command(name = "hibi", version, after_help = EXIT_STATUS, propagate_version = true)]
#[command(long_about = "\
hibi: crack and cell patterns from three graphics papers, rendered to PNG.

  mud      Model A, drying mud (Hirota, Hoshino, Kaneko): a spring lattice that shrinks and cracks
  glass    Model B, a glass plate hit by a ball (Agui, Moriyama, Nagao, Nakajima)
  skin     Model C, skin from hierarchical Voronoi cells (Ishii, Yasuda, Yokoi, Toriwaki)
  gallery  every paper figure as a picture, with an index page

Start with `hibi gallery gallery/` and open gallery/index.html.")]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Subcommand, Debug)]
pub enum Command {
    /// Model A: drying mud, a shrinking two-layer spring lattice (Hirota et al.).
    #[command(after_help = EXIT_STATUS, allow_negative_numbers = true)]
    Mud(MudArgs),
    /// Model B: a glass plate hit by a ball, a stochastic crack grower (Agui et al.).
    #[command(after_help = EXIT_STATUS, allow_negative_numbers = true)]
    Glass(GlassArgs),
    /// Model C: skin, hierarchical perturbed Voronoi cells (Ishii et al.).
    #[command(after_help = EXIT_STATUS, allow_negative_numbers = true)]
    Skin(SkinArgs),
    /// Renders every preset that reproduces a paper figure into DIR, with an index.html.
    #[command(after_help = EXIT_STATUS)]
    Gallery(GalleryArgs),
}

/// What every model writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Layer {
    /// Crack coverage (skin: the furrow net), 8-bit grey, 255 on a crack.
    Mask,
    /// Height, 16-bit grey: mud and glass 1 (white) on the surface, lower in the cracks;
    /// skin scaled so that its highest point is white.
    Height,
    /// Tangent-space normal map, RGB (x right, y up, z out; OpenGL convention).
    Normal,
    /// Break time (mud, glass), 16-bit grey: the first crack black, the last 65534, 65535
    /// where nothing breaks.
    Time,
    /// A lit preview in colour.
    Shaded,
}

impl Layer {
    /// The name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Layer::Mask => "mask",
            Layer::Height => "height",
            Layer::Normal => "normal",
            Layer::Time => "time",
            Layer::Shaded => "shaded",
        }
    }
}

/// Output options every model takes.
#[derive(Args, Debug, Clone)]
#[command(next_help_heading = "Output")]
pub struct Output {
    /// Seed of every random draw [default: the preset's, else 1].
    #[arg(long, value_name = "N")]
    pub seed: Option<u64>,
    /// Raster size in pixels, WxH or N for NxN [default: mud 4 px per lattice spacing,
    /// glass the plate's size, skin 400x400].
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    pub size: Option<[u32; 2]>,
    /// The PNG to write [default: MODEL.png].
    #[arg(short, long, value_name = "FILE.png")]
    pub output: Option<PathBuf>,
    /// Which map to write.
    #[arg(long, value_enum, default_value_t = Layer::Shaded)]
    pub layer: Layer,
    /// Depth of the widest crack in pixels, for the normal map and the shading (mud and
    /// glass; skin normals come from its profiles' slopes).
    #[arg(long, value_name = "PX", default_value_t = 2.0, value_parser = parse_non_negative)]
    pub bump: f32,
    /// No summary line on stderr and no progress bar.
    #[arg(short, long)]
    pub quiet: bool,
    /// Threads that draw the picture, each a band of rows; the picture is the same on any
    /// number [default: the machine's cores].
    #[arg(long, value_name = "N")]
    pub threads: Option<NonZeroUsize>,
}

/// Growth as animation (mud and glass).
#[derive(Args, Debug, Clone)]
#[command(next_help_heading = "Animation")]
pub struct Animation {
    /// Write the growth as N frames of the break-time map (an animated PNG, or a numbered
    /// sequence with --sequence) instead of one picture.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=1000))]
    pub frames: Option<u32>,
    /// Write the frames as FILE-001.png, FILE-002.png, ... instead of one animated PNG.
    #[arg(long, requires = "frames")]
    pub sequence: bool,
    /// Time each frame of the animated PNG is shown, in milliseconds.
    #[arg(long, value_name = "MS", default_value_t = 80, requires = "frames")]
    pub frame_delay: u16,
}

/// `hibi mud`.
#[derive(Args, Debug, Clone)]
pub struct MudArgs {
    /// Start from a paper figure's parameters (see `hibi gallery`).
    #[arg(long, value_name = "NAME", value_parser = PossibleValuesParser::new(hibi_core::mud::PRESETS))]
    pub preset: Option<String>,
    #[command(flatten)]
    pub output: Output,
    #[command(flatten)]
    pub animation: Animation,
    /// Write the run as an engine shows it while it runs: an animated PNG of one frame per
    /// step of UNITS units of work, from the step in which the first spring breaks to the
    /// end, each drawn from the crack network the run shows then (traced live), at most
    /// 1000 frames.
    #[arg(long, value_name = "UNITS", help_heading = "Animation", conflicts_with = "frames",
          value_parser = clap::value_parser!(u64).range(1..))]
    pub live: Option<u64>,
    #[command(flatten)]
    pub model: MudOptions,
}

/// Lattice topology.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum TopologyArg {
    /// Hexagonal elements (a triangular lattice of nodes, 6 neighbours): isotropic cracks.
    #[value(alias = "hex")]
    Hexagonal,
    /// Square elements (4 neighbours): axis-aligned, short, fine cracks.
    Square,
    /// Jittered nodes joined by their Delaunay triangulation (beyond the paper): cracks run in
    /// any direction.
    Irregular,
}

/// Lattice edges.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum BoundaryArg {
    /// Free edges.
    Open,
    /// The lattice wraps around: a tileable texture.
    Periodic,
}

/// Equilibrium solver.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum SolverArg {
    /// Linear equilibrium with event-driven breaking: same statistics, 100x faster.
    QuasiStatic,
    /// The paper's loop exactly (damped short steps): slow.
    Explicit,
}

/// What drives the misfit.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum DriveArg {
    /// The surface dries and shrinks.
    Shrink,
    /// The deep layer grows (tree bark).
    Growth,
}

/// The drying-mud parameters (`MudParams`) and how to draw them (`MudRender`).
#[derive(Args, Debug, Clone, Default)]
#[command(next_help_heading = "Model A parameters (MudParams)")]
pub struct MudOptions {
    /// Mesh topology [default: hexagonal].
    #[arg(long, value_enum)]
    pub topology: Option<TopologyArg>,
    /// Lattice edges [default: periodic].
    #[arg(long, value_enum)]
    pub boundary: Option<BoundaryArg>,
    /// Equilibrium solver [default: quasi-static].
    #[arg(long, value_enum)]
    pub solver: Option<SolverArg>,
    /// Shrinking surface or growing deep layer [default: shrink].
    #[arg(long, value_enum)]
    pub drive: Option<DriveArg>,
    /// Nodes per row [default: 128].
    #[arg(long, value_name = "N")]
    pub columns: Option<u32>,
    /// Rows of nodes; periodic hexagonal lattices need an even number [default: 128].
    #[arg(long, value_name = "N")]
    pub rows: Option<u32>,
    /// H: thickness of the surface layer [cm] [default: 1].
    #[arg(long, value_name = "CM")]
    pub layer_thickness: Option<f32>,
    /// W: element size, the lattice spacing [cm] [default: 1].
    #[arg(long, value_name = "CM")]
    pub element_size: Option<f32>,
    /// T: the long time step [s] [default: 1].
    #[arg(long, value_name = "S")]
    pub long_step: Option<f32>,
    /// τ: the explicit solver's short time step [s] [default: 0.001].
    #[arg(long, value_name = "S")]
    pub short_step: Option<f32>,
    /// γ: shrink ratio per long step, in [FLT_MIN, 1); 1 never shrinks; with --drive growth at
    /// least 1/101 (a long step grows the deep layer at most 101-fold) [default: 0.9999].
    #[arg(long, value_name = "RATIO")]
    pub shrink_ratio: Option<f32>,
    /// δx: allowed displacement error [cm] [default: 0.0001].
    #[arg(long, value_name = "CM")]
    pub displacement_tolerance: Option<f32>,
    /// α: damping factor [default: 20].
    #[arg(long, value_name = "ALPHA")]
    pub damping_factor: Option<f32>,
    /// ρ: density [g/cm³] [default: 1.8].
    #[arg(long, value_name = "G/CM3")]
    pub density: Option<f32>,
    /// E: Young's modulus [g/(cm·s²)] [default: 1e6].
    #[arg(long, value_name = "E")]
    pub young_modulus: Option<f32>,
    /// G: shear modulus [g/(cm·s²)] [default: 2e5].
    #[arg(long, value_name = "G")]
    pub shear_modulus: Option<f32>,
    /// κ̄: mean break stretch, > 1 [default: 1.02].
    #[arg(long, value_name = "KAPPA")]
    pub break_stretch_mean: Option<f32>,
    /// σ: spread of the break stretch per unit area [1/cm] [default: 0.001].
    #[arg(long, value_name = "SIGMA")]
    pub break_stretch_spread: Option<f32>,
    /// Beyond the paper, for mesh-scale independence: κ̄ − 1 is scaled by (1 cm / W)^X, so
    /// finer meshes get stronger springs; 0.25 keeps cell size within 15 % from W = 2 to
    /// 0.5 cm [default: 0, the paper's rule].
    #[arg(long, value_name = "X")]
    pub break_stretch_size_exponent: Option<f32>,
    /// φ: the direction cracks prefer to run along [degrees from the x axis towards y; y runs
    /// down the picture] [default: 0].
    #[arg(long, value_name = "DEGREES")]
    pub anisotropy_direction: Option<f32>,
    /// Springs across φ keep 1/RATIO of the break margin κ − 1 of springs along it, so cracks
    /// run along φ; ≥ 1 [default: 1].
    #[arg(long, value_name = "RATIO")]
    pub anisotropy_ratio: Option<f32>,
    /// Springs across φ are RATIO times less stiff than along it; ≥ 1 [default: 1].
    #[arg(long, value_name = "RATIO")]
    pub stiffness_anisotropy_ratio: Option<f32>,
    /// The run ends at this shrink 1 − r; 0 = no limit [default: 0.023].
    #[arg(long, value_name = "SHRINK")]
    pub target_shrink: Option<f32>,
    /// The run also ends at this crack length per area [1/cm]; 0 = no limit [default: 0].
    #[arg(long, value_name = "PER_CM")]
    pub target_crack_density: Option<f32>,
    /// Crack widths are multiplied by this before drawing [default: 1].
    #[arg(long, value_name = "SCALE", help_heading = "Model A drawing (MudRender)")]
    pub width_scale: Option<f32>,
    /// The narrowest crack stroke [px] [default: 0.2 lattice spacing, at least 1 px, so that
    /// the youngest cracks stay visible; the statistics do not depend on it].
    #[arg(long, value_name = "PX", help_heading = "Model A drawing (MudRender)")]
    pub min_width: Option<f32>,
    /// Depth of the widest groove in the height map [default: 1].
    #[arg(long, value_name = "DEPTH", help_heading = "Model A drawing (MudRender)")]
    pub groove_depth: Option<f32>,
    /// Where the raster's top-left corner sits, in lattice spacings (pans a periodic tile)
    /// [default: 0,0].
    #[arg(long, value_name = "X,Y", value_parser = parse_pair, allow_hyphen_values = true,
          help_heading = "Model A drawing (MudRender)")]
    pub offset: Option<[f32; 2]>,
}

/// `hibi glass`.
#[derive(Args, Debug, Clone)]
pub struct GlassArgs {
    /// Start from a paper figure's parameters (see `hibi gallery`).
    #[arg(long, value_name = "NAME", value_parser = PossibleValuesParser::new(hibi_core::glass::PRESETS))]
    pub preset: Option<String>,
    #[command(flatten)]
    pub output: Output,
    #[command(flatten)]
    pub animation: Animation,
    #[command(flatten)]
    pub model: GlassOptions,
}

/// Rand(x): normal or uniform.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum SpreadArg {
    /// Normal, ±3σ spanning [(1 − z)x, (1 + z)x].
    Normal,
    /// Uniform over [(1 − z)x, (1 + z)x].
    Uniform,
}

/// The glass parameters (`GlassParams`) and how to draw them (`GlassRender`).
#[derive(Args, Debug, Clone, Default)]
#[command(next_help_heading = "Model B parameters (GlassParams)")]
pub struct GlassOptions {
    /// Plate width [px] [default: 640] (the raster is `--size`, by default the plate's).
    #[arg(long, value_name = "PX", alias = "plate-width")]
    pub width: Option<f32>,
    /// Plate height [px] [default: 640].
    #[arg(long, value_name = "PX", alias = "plate-height")]
    pub height: Option<f32>,
    /// L: an impact point [px]; repeat for several impacts on one plate (each grows on its
    /// own clock: its time map starts at 0) [default: the plate's centre].
    #[arg(long, value_name = "X,Y", value_parser = parse_pair)]
    pub impact: Vec<[f32; 2]>,
    /// M_ave: mean number of radial cracks [default: 100].
    #[arg(long, value_name = "M")]
    pub radial_mean: Option<f32>,
    /// A: ring cracks appear only when M > A [default: 70].
    #[arg(long, value_name = "A")]
    pub ring_threshold: Option<f32>,
    /// e in N = ⌊e·M + f⌋, the number of large cracks [default: 0.0606].
    #[arg(long, value_name = "E")]
    pub large_slope: Option<f32>,
    /// f in N = ⌊e·M + f⌋ [default: 3.293].
    #[arg(long, value_name = "F")]
    pub large_offset: Option<f32>,
    /// a in R = ⌊a·M + b⌋, the number of ring start points [default: 0.05].
    #[arg(long, value_name = "A")]
    pub ring_slope: Option<f32>,
    /// b in R = ⌊a·M + b⌋ [default: 0.5].
    #[arg(long, value_name = "B")]
    pub ring_offset: Option<f32>,
    /// g in d_ave = g·M + h, the mean ring radius [px] [default: 0.47].
    #[arg(long, value_name = "G")]
    pub ring_radius_slope: Option<f32>,
    /// h in d_ave = g·M + h [px] [default: 13.9].
    #[arg(long, value_name = "H")]
    pub ring_radius_offset: Option<f32>,
    /// V1_ave: mean speed of the large cracks [px/step] [default: 40].
    #[arg(long, value_name = "V1")]
    pub large_speed: Option<f32>,
    /// V2_ave: mean speed of the other radial cracks [px/step] [default: 10].
    #[arg(long, value_name = "V2")]
    pub radial_speed: Option<f32>,
    /// V3_ave: mean speed of the ring cracks [px/step] [default: 10].
    #[arg(long, value_name = "V3")]
    pub ring_speed: Option<f32>,
    /// z of Rand(x): values within [(1 − z)x, (1 + z)x] [default: 0.3].
    #[arg(long, value_name = "Z")]
    pub spread_ratio: Option<f32>,
    /// Rand(x) normal or uniform [default: normal].
    #[arg(long, value_enum)]
    pub spread: Option<SpreadArg>,
    /// θ_th: the largest turn per update (at most 10 px) [degrees] [default: 30].
    #[arg(long, value_name = "DEGREES")]
    pub turn_limit: Option<f32>,
    /// T in weight(t) = 1 − exp(−t/T) [steps] [default: 10].
    #[arg(long, value_name = "T")]
    pub turn_delay: Option<f32>,
    /// φ: angle of the sector ahead of a tip [degrees] [default: 100].
    #[arg(long, value_name = "DEGREES")]
    pub sector_angle: Option<f32>,
    /// B: radius of the sector [px] [default: 50].
    #[arg(long, value_name = "PX")]
    pub sector_radius: Option<f32>,
    /// k1 of F1, the push from other tips [px²] [default: 400].
    #[arg(long, value_name = "K1")]
    pub tip_repulsion: Option<f32>,
    /// k2 of F2, the pull towards cracks and edges [px²] [default: 400].
    #[arg(long, value_name = "K2")]
    pub crack_attraction: Option<f32>,
    /// Standard deviation of F3's direction per 10 px of growth at weight(t) = 1 [degrees] [default: 45].
    #[arg(long, value_name = "DEGREES")]
    pub wander: Option<f32>,
    /// How hard a ring crack keeps to its circle [default: 2].
    #[arg(long, value_name = "K")]
    pub ring_adherence: Option<f32>,
    /// Most cracks the plate can hold [default: 512].
    #[arg(long, value_name = "N")]
    pub max_cracks: Option<u32>,
    /// Most crack vertices the plate can hold [default: 16384].
    #[arg(long, value_name = "N")]
    pub max_vertices: Option<u32>,
    /// Width of a crack line [raster px] [default: 1.2].
    #[arg(long, value_name = "PX", help_heading = "Model B drawing (GlassRender)")]
    pub line_width: Option<f32>,
}

/// `hibi skin`.
#[derive(Args, Debug, Clone)]
pub struct SkinArgs {
    /// Start from a paper figure's parameters (Table 1; see `hibi gallery`).
    #[arg(long, value_name = "NAME", value_parser = PossibleValuesParser::new(hibi_core::skin::PRESETS))]
    pub preset: Option<String>,
    #[command(flatten)]
    pub output: Output,
    #[command(flatten)]
    pub model: SkinOptions,
}

/// Centre-point layout.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum LayoutArg {
    /// Triangular lattice.
    Triangular,
    /// Square lattice.
    Square,
    /// Uniform random (one centre per lattice square).
    Random,
}

/// One hierarchy level's value: `VALUE` for level 1, `LEVEL=VALUE` for another.
#[derive(Clone, Debug, PartialEq)]
pub struct PerLevel<T> {
    /// 0-based level.
    pub level: usize,
    /// The value.
    pub value: T,
}

/// The skin parameters (`SkinParams`) and the preview's light (`ShadeParams`).
#[derive(Args, Debug, Clone, Default)]
#[command(next_help_heading = "Model C parameters (SkinParams; per level: VALUE for level 1, LEVEL=VALUE for others)")]
pub struct SkinOptions {
    /// Centre-point layout [default: triangular].
    #[arg(long, value_enum)]
    pub layout: Option<LayoutArg>,
    /// Jitter of lattice centres [default: uniform].
    #[arg(long, value_enum)]
    pub jitter: Option<SpreadArg>,
    /// Largest jitter per axis over the lattice spacing, in [0, 1] [default: 0.5].
    #[arg(long, value_name = "RATIO")]
    pub jitter_ratio: Option<f32>,
    /// Tileable: the surface repeats with period (width, height) [default: false].
    #[arg(long, value_name = "BOOL")]
    pub periodic: Option<bool>,
    /// Hierarchy levels, 1 to 4 [default: 1].
    #[arg(long, value_name = "N")]
    pub levels: Option<u32>,
    /// Lattice spacing of the centre points [px] [default: 40, a third per finer level].
    #[arg(long, value_name = "[LEVEL=]PX", value_parser = parse_level_f32)]
    pub spacing: Vec<PerLevel<f32>>,
    /// A: perturbation ratio of the edges [default: 0].
    #[arg(long, value_name = "[LEVEL=]A", value_parser = parse_level_f32)]
    pub perturbation: Vec<PerLevel<f32>>,
    /// h: decay of the perturbation per subdivision [default: 1].
    #[arg(long, value_name = "[LEVEL=]H", value_parser = parse_level_f32)]
    pub perturbation_decay: Vec<PerLevel<f32>>,
    /// Subdivisions of every edge, 0 to 5 [default: 3, one fewer per finer level].
    #[arg(long, value_name = "[LEVEL=]N", value_parser = parse_level_u32)]
    pub perturbation_depth: Vec<PerLevel<u32>>,
    /// Stretch (Sx, Sy) of the level's polygons [default: 1,1].
    #[arg(long, value_name = "[LEVEL=]SX,SY", value_parser = parse_level_pair)]
    pub stretch: Vec<PerLevel<[f32; 2]>>,
    /// Cross-section: 3k+1 Bézier control points x',z' (k = 1..4 segments), x' from the
    /// centre (0) to the edge, e.g. "0,3 5,3 8,2.5 10,0" [default: Fig. 13 b].
    #[arg(long, value_name = "[LEVEL=]POINTS", value_parser = parse_level_profile)]
    pub profile: Vec<PerLevel<Vec<[f32; 2]>>>,
    /// Roundness of the height contours, 0 (polygonal) to 1 (circular) [default: 0.2].
    #[arg(long, value_name = "[LEVEL=]RATIO", value_parser = parse_level_f32)]
    pub roundness: Vec<PerLevel<f32>>,
    /// Direction towards the light, x right, y up, z out [default: -0.5,0.6,0.62].
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_triple, allow_hyphen_values = true,
          help_heading = "Model C shading (ShadeParams)")]
    pub light: Option<[f32; 3]>,
    /// Ridge-top colour, linear RGB in [0, 1] [default: 0.9,0.68,0.56].
    #[arg(long, value_name = "R,G,B", value_parser = parse_triple, help_heading = "Model C shading (ShadeParams)")]
    pub ridge: Option<[f32; 3]>,
    /// Furrow colour, linear RGB in [0, 1] [default: 0.55,0.33,0.28].
    #[arg(long, value_name = "R,G,B", value_parser = parse_triple, help_heading = "Model C shading (ShadeParams)")]
    pub furrow: Option<[f32; 3]>,
    /// Light that reaches every pixel, in [0, 1] [default: 0.35].
    #[arg(long, value_name = "A", help_heading = "Model C shading (ShadeParams)")]
    pub ambient: Option<f32>,
    /// Strength of the highlight, ≥ 0 [default: 0.12].
    #[arg(long, value_name = "S", help_heading = "Model C shading (ShadeParams)")]
    pub specular: Option<f32>,
}

/// `hibi gallery`.
#[derive(Args, Debug, Clone)]
pub struct GalleryArgs {
    /// Directory to write the pictures and index.html into (created if missing).
    #[arg(value_name = "DIR")]
    pub dir: PathBuf,
    /// Width of every picture in pixels (skin spacings scale with it, so that each shows
    /// the field of the paper's 400 px image).
    #[arg(long, value_name = "PX", default_value_t = 400, value_parser = clap::value_parser!(u32).range(128..=2048))]
    pub size: u32,
    /// Frames of the growth animations.
    #[arg(long, value_name = "N", default_value_t = 24, value_parser = clap::value_parser!(u32).range(2..=200))]
    pub frames: u32,
    /// No progress bar and no summary line.
    #[arg(short, long)]
    pub quiet: bool,
    /// Threads that render the figures, each figure on one; the pictures are the same on any
    /// number [default: the machine's cores].
    #[arg(long, value_name = "N")]
    pub threads: Option<NonZeroUsize>,
}

/// `WxH` or `N`.
fn parse_size(s: &str) -> Result<[u32; 2], String> {
    let parse = |v: &str| match v.trim().parse::<u32>() {
        Ok(n) if (1..=32_768).contains(&n) => Ok(n),
        _ => Err(format!("'{v}' is not a size in pixels (1 to 32768)")),
    };
    match s.split_once(['x', 'X']) {
        Some((w, h)) => Ok([parse(w)?, parse(h)?]),
        None => parse(s).map(|n| [n, n]),
    }
}

/// A finite number ≥ 0.
fn parse_non_negative(s: &str) -> Result<f32, String> {
    match s.parse::<f32>() {
        Ok(v) if v.is_finite() && v >= 0.0 => Ok(v),
        _ => Err(format!("'{s}' is not a finite number >= 0")),
    }
}

/// `n` comma-separated numbers.
fn parse_numbers<const N: usize>(s: &str) -> Result<[f32; N], String> {
    let values: Vec<&str> = s.split(',').collect();
    if values.len() != N {
        return Err(format!("expected {N} comma-separated numbers, got '{s}'"));
    }
    let mut out = [0.0; N];
    for (o, v) in out.iter_mut().zip(values) {
        *o = v.trim().parse().map_err(|_| format!("'{v}' is not a number"))?;
    }
    Ok(out)
}

/// `X,Y`.
fn parse_pair(s: &str) -> Result<[f32; 2], String> {
    parse_numbers::<2>(s)
}

/// `X,Y,Z`.
fn parse_triple(s: &str) -> Result<[f32; 3], String> {
    parse_numbers::<3>(s)
}

/// Splits `[LEVEL=]VALUE` into the 0-based level and the value text.
fn split_level(s: &str) -> Result<(usize, &str), String> {
    match s.split_once('=') {
        Some((level, value)) => {
            let max = hibi_core::skin::MAX_LEVELS;
            match level.trim().parse::<usize>() {
                Ok(l) if (1..=max).contains(&l) => Ok((l - 1, value)),
                _ => Err(format!("'{level}' is not a level (1 to {max})")),
            }
        }
        None => Ok((0, s)),
    }
}

fn parse_level_f32(s: &str) -> Result<PerLevel<f32>, String> {
    let (level, v) = split_level(s)?;
    let value = v.trim().parse().map_err(|_| format!("'{v}' is not a number"))?;
    Ok(PerLevel { level, value })
}

fn parse_level_u32(s: &str) -> Result<PerLevel<u32>, String> {
    let (level, v) = split_level(s)?;
    let value = v.trim().parse().map_err(|_| format!("'{v}' is not a whole number >= 0"))?;
    Ok(PerLevel { level, value })
}

fn parse_level_pair(s: &str) -> Result<PerLevel<[f32; 2]>, String> {
    let (level, v) = split_level(s)?;
    Ok(PerLevel { level, value: parse_pair(v)? })
}

/// `[LEVEL=]x,z x,z ...`: 3k + 1 points, k = 1..=MAX_SEGMENTS (separated by spaces or `;`).
fn parse_level_profile(s: &str) -> Result<PerLevel<Vec<[f32; 2]>>, String> {
    let (level, v) = split_level(s)?;
    let points = v.split([' ', ';']).filter(|p| !p.is_empty()).map(parse_pair).collect::<Result<Vec<_>, _>>()?;
    let segments = points.len().saturating_sub(1) / 3;
    let max = hibi_core::skin::MAX_SEGMENTS;
    if points.len() < 4 || points.len() % 3 != 1 || segments > max {
        return Err(format!(
            "a profile is 3k+1 points x',z' for k = 1 to {max} Bezier segments (4, 7, 10 or 13), got {}",
            points.len()
        ));
    }
    Ok(PerLevel { level, value: points })
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    #[test]
    fn the_command_line_is_consistent() {
        Cli::command().debug_assert();
    }

    #[test]
    fn values_parse() {
        assert_eq!(parse_size("320x200"), Ok([320, 200]));
        assert_eq!(parse_size("64"), Ok([64, 64]));
        assert!(parse_size("0x10").is_err());
        assert!(parse_size("axb").is_err());
        assert_eq!(parse_pair("-1.5,2"), Ok([-1.5, 2.0]));
        assert!(parse_pair("1").is_err());
        assert_eq!(parse_level_f32("2=13.5"), Ok(PerLevel { level: 1, value: 13.5 }));
        assert_eq!(parse_level_f32("40"), Ok(PerLevel { level: 0, value: 40.0 }));
        assert!(parse_level_f32("5=1").is_err());
        let profile = parse_level_profile("3=0,3 5,3;8,2.5 10,0").unwrap();
        assert_eq!((profile.level, profile.value.len()), (2, 4));
        assert!(parse_level_profile("0,3 5,3 10,0").is_err());
    }
}
