//! The C constants that stand for the core's enumerations: their variants (`HIBI_MUD_SQUARE`,
//! ...) and the models' parameter errors (`HIBI_ERROR_MUD_COLUMNS`, ...), in one table. Each
//! is written once, as a row naming its variant, and checked against it when `hibi` compiles:
//! its number is the variant's own plus its type's `Numbered::BASE`.

use hibi_core::Spread;
use hibi_core::glass::{CrackEnd, CrackKind, GlassParamError};
use hibi_core::mud::{Boundary, Drive, MudParamError, Solver, Topology};
use hibi_core::skin::{SiteLayout, SkinParamError};

use crate::status::hibi_status;

/// A core enumeration as numbers in C: variant `v` is `BASE + v as u32`, and `ALL[i]` is the
/// variant numbered `i`.
pub(crate) trait Numbered: Copy + 'static {
    /// The number of the first variant.
    const BASE: u32;
    /// Every variant, in order.
    const ALL: &'static [Self];
    /// The variant's own number.
    fn number(self) -> u32;
}

/// A model's parameter errors, each reported by the status `BASE + number`.
pub(crate) trait ParamError: Numbered {}

/// [`Numbered`] for each type (and [`ParamError`] for the `errors`), checking when `hibi`
/// compiles that `ALL[i]` is numbered `i`.
macro_rules! numbered {
    ($($t:ty = $base:literal),+ ; errors $($e:ty = $error_base:literal),+ $(,)?) => {
        $(numbered!(@one $t = $base);)+
        $(numbered!(@one $e = $error_base); impl ParamError for $e {})+
    };
    (@one $t:ty = $base:literal) => {
        impl Numbered for $t {
            const BASE: u32 = $base;
            const ALL: &'static [Self] = &<$t>::ALL;
            fn number(self) -> u32 {
                self as u32
            }
        }
        const _: () = {
            let mut i = 0;
            while i < <$t>::ALL.len() {
                assert!(<$t>::ALL[i] as usize == i, "ALL[i] is numbered i");
                i += 1;
            }
        };
    };
}

numbered!(
    Spread = 0, Topology = 0, Boundary = 0, Solver = 0, Drive = 0, CrackKind = 0, CrackEnd = 0, SiteLayout = 0;
    errors MudParamError = 512, GlassParamError = 1024, SkinParamError = 1280,
);

/// The status that reports a model's parameter error.
pub(crate) fn param_status<E: ParamError>(error: E) -> hibi_status {
    E::BASE + error.number()
}

/// The parameter error of type `E` that `status` reports, if it is one.
pub(crate) fn param_error<E: ParamError>(status: hibi_status) -> Option<E> {
    E::ALL.get(status.checked_sub(E::BASE)? as usize).copied()
}

/// The table's rows: a `#define` in the header each, whose number is checked against its
/// variant's.
macro_rules! constants {
    ($( $(#[$doc:meta])* $name:ident: $ty:ident::$variant:ident = $number:literal; )+) => {$(
        $(#[$doc])*
        pub const $name: u32 = $number;
        const _: () = assert!($name == <$ty as Numbered>::BASE + $ty::$variant as u32);
    )+};
}

constants! {
    /// `Rand(x)` spread: uniform over [(1 − z)x, (1 + z)x].
    HIBI_SPREAD_UNIFORM: Spread::Uniform = 0;
    /// `Rand(x)` spread: normal, σ = z·x/3, redrawn until within [(1 − z)x, (1 + z)x].
    HIBI_SPREAD_NORMAL: Spread::Normal = 1;
    /// Square elements: 4 neighbours, axis-aligned short cracks.
    HIBI_MUD_SQUARE: Topology::Square = 0;
    /// Hexagonal elements (a triangular lattice of nodes): 6 neighbours, isotropic cracks.
    HIBI_MUD_HEXAGONAL: Topology::Hexagonal = 1;
    /// Beyond the paper: jittered nodes joined by their Delaunay triangulation, each spring with
    /// its own length and face; cracks run in any direction. Periodic lattices need columns >= 8
    /// and an even rows >= 8.
    HIBI_MUD_IRREGULAR: Topology::Irregular = 2;
    /// Free edges.
    HIBI_MUD_OPEN: Boundary::Open = 0;
    /// The lattice wraps around: tileable patterns.
    HIBI_MUD_PERIODIC: Boundary::Periodic = 1;
    /// The paper's explicit loop (reference; slow).
    HIBI_MUD_EXPLICIT: Solver::Explicit = 0;
    /// Quasi-static equilibrium with event-driven breaking (fast; the default).
    HIBI_MUD_QUASI_STATIC: Solver::QuasiStatic = 1;
    /// The surface shrinks (drying mud).
    HIBI_MUD_SHRINK: Drive::Shrink = 0;
    /// The deep layer grows (tree bark).
    HIBI_MUD_GROWTH: Drive::Growth = 1;
    /// `hibi_glass_crack.kind`: a large radial crack (fast, reaches the edge).
    HIBI_GLASS_KIND_LARGE: CrackKind::Large = 0;
    /// `hibi_glass_crack.kind`: another radial crack.
    HIBI_GLASS_KIND_RADIAL: CrackKind::Radial = 1;
    /// `hibi_glass_crack.kind`: a ring crack growing counter-clockwise from its start point.
    HIBI_GLASS_KIND_RING_COUNTER_CLOCKWISE: CrackKind::RingCounterClockwise = 2;
    /// `hibi_glass_crack.kind`: a ring crack growing clockwise from its start point.
    HIBI_GLASS_KIND_RING_CLOCKWISE: CrackKind::RingClockwise = 3;
    /// `hibi_glass_crack.end`: it still grows.
    HIBI_GLASS_END_GROWING: CrackEnd::Growing = 0;
    /// `hibi_glass_crack.end`: its tip reached the plate's edge.
    HIBI_GLASS_END_EDGE: CrackEnd::Edge = 1;
    /// `hibi_glass_crack.end`: its tip reached another crack.
    HIBI_GLASS_END_CRACK: CrackEnd::Crack = 2;
    /// `hibi_glass_crack.end`: generation of its impact ended, or a later impact began.
    HIBI_GLASS_END_GENERATION: CrackEnd::Generation = 3;
    /// `hibi_glass_crack.end`: other cracks closed a region around its tip.
    HIBI_GLASS_END_ENCLOSED: CrackEnd::Enclosed = 4;
    /// Centre points on a triangular lattice (the default).
    HIBI_SKIN_LAYOUT_TRIANGULAR: SiteLayout::Triangular = 0;
    /// Centre points on a square lattice.
    HIBI_SKIN_LAYOUT_SQUARE: SiteLayout::Square = 1;
    /// Centre points uniformly random, one per lattice square (the jitter fields are ignored).
    HIBI_SKIN_LAYOUT_RANDOM: SiteLayout::Random = 2;
    /// Mud parameters: `columns` must be >= 2 (>= 3 when periodic, >= 8 periodic irregular).
    HIBI_ERROR_MUD_COLUMNS: MudParamError::Columns = 512;
    /// Mud parameters: `rows` must be >= 2 (periodic: >= 3 square, even and >= 4 hexagonal, even
    /// and >= 8 irregular).
    HIBI_ERROR_MUD_ROWS: MudParamError::Rows = 513;
    /// Mud parameters: `layer_thickness` (H) must be finite and > 0.
    HIBI_ERROR_MUD_LAYER_THICKNESS: MudParamError::LayerThickness = 514;
    /// Mud parameters: `element_size` (W) must be finite and > 0.
    HIBI_ERROR_MUD_ELEMENT_SIZE: MudParamError::ElementSize = 515;
    /// Mud parameters: `long_step` (T) must be finite and > 0.
    HIBI_ERROR_MUD_LONG_STEP: MudParamError::LongStep = 516;
    /// Mud parameters: `short_step` (τ) must be finite and > 0.
    HIBI_ERROR_MUD_SHORT_STEP: MudParamError::ShortStep = 517;
    /// Mud parameters: `shrink_ratio` (γ) must be >= FLT_MIN and < 1 (1 would never shrink);
    /// with `HIBI_MUD_GROWTH`, 1/γ − 1 <= 100 (one long step grows the deep layer at most
    /// 101-fold).
    HIBI_ERROR_MUD_SHRINK_RATIO: MudParamError::ShrinkRatio = 518;
    /// Mud parameters: `displacement_tolerance` (δx) must be finite and > 0.
    HIBI_ERROR_MUD_DISPLACEMENT_TOLERANCE: MudParamError::DisplacementTolerance = 519;
    /// Mud parameters: `damping_factor` (α) must be finite and > 0.
    HIBI_ERROR_MUD_DAMPING_FACTOR: MudParamError::DampingFactor = 520;
    /// Mud parameters: `density` (ρ) must be finite and > 0.
    HIBI_ERROR_MUD_DENSITY: MudParamError::Density = 521;
    /// Mud parameters: `young_modulus` (E) must be finite and > 0.
    HIBI_ERROR_MUD_YOUNG_MODULUS: MudParamError::YoungModulus = 522;
    /// Mud parameters: `shear_modulus` (G) must be finite and > 0.
    HIBI_ERROR_MUD_SHEAR_MODULUS: MudParamError::ShearModulus = 523;
    /// Mud parameters: `break_stretch_mean` (κ̄) must be finite and > 1.
    HIBI_ERROR_MUD_BREAK_STRETCH_MEAN: MudParamError::BreakStretchMean = 524;
    /// Mud parameters: `break_stretch_spread` (σ) must be finite and >= 0.
    HIBI_ERROR_MUD_BREAK_STRETCH_SPREAD: MudParamError::BreakStretchSpread = 525;
    /// Mud parameters: `anisotropy_direction` must be finite.
    HIBI_ERROR_MUD_ANISOTROPY_DIRECTION: MudParamError::AnisotropyDirection = 526;
    /// Mud parameters: `anisotropy_ratio` must be finite and >= 1.
    HIBI_ERROR_MUD_ANISOTROPY_RATIO: MudParamError::AnisotropyRatio = 527;
    /// Mud parameters: `stiffness_anisotropy_ratio` must be within [1, 1e6].
    HIBI_ERROR_MUD_STIFFNESS_ANISOTROPY_RATIO: MudParamError::StiffnessAnisotropyRatio = 528;
    /// Mud parameters: `target_shrink` must be finite and within [0, 1).
    HIBI_ERROR_MUD_TARGET_SHRINK: MudParamError::TargetShrink = 529;
    /// Mud parameters: `target_crack_density` must be finite and >= 0.
    HIBI_ERROR_MUD_TARGET_CRACK_DENSITY: MudParamError::TargetCrackDensity = 530;
    /// Mud parameters: the lattice is too large: `columns` × `rows` must be <= 2^28
    /// (268,435,456 nodes; irregular: also `columns` <= 2^20 and `rows` <= 2^21), and its
    /// memory must fit in the address space.
    HIBI_ERROR_MUD_SIZE_OVERFLOW: MudParamError::SizeOverflow = 531;
    /// Mud parameters: (shear_modulus / young_modulus)·(element_size / layer_thickness)² must be
    /// within [1e-6, 1e6].
    HIBI_ERROR_MUD_SHEAR_SCALE: MudParamError::ShearScale = 532;
    /// Mud parameters: `break_stretch_size_exponent` must be within [0, 1].
    HIBI_ERROR_MUD_BREAK_STRETCH_SIZE_EXPONENT: MudParamError::BreakStretchSizeExponent = 533;
    /// Mud parameters: `damping_factor` is out of scale: 2·sqrt(k_max·m)·damping_factor must be
    /// within [1e-6, 1e6].
    HIBI_ERROR_MUD_DAMPING_SCALE: MudParamError::DampingScale = 534;
    /// Mud parameters: short_step / (element_size·sqrt(density / young_modulus)) must be within
    /// [1e-6, 1e6].
    HIBI_ERROR_MUD_SHORT_STEP_SCALE: MudParamError::ShortStepScale = 535;
    /// Mud parameters: `displacement_tolerance` is out of scale: k_min·displacement_tolerance /
    /// element_size must be within [1e-6, 1e6].
    HIBI_ERROR_MUD_TOLERANCE_SCALE: MudParamError::ToleranceScale = 536;
    /// Mud parameters: break_stretch_spread / sqrt(face·element_size·layer_thickness) must be
    /// finite.
    HIBI_ERROR_MUD_SPREAD_SCALE: MudParamError::SpreadScale = 537;
    /// Mud parameters: with the explicit solver, `short_step` fails the stability test of its
    /// damped step (a sufficient bound: past it the run may diverge); make it smaller or
    /// `damping_factor` larger, or use the quasi-static solver.
    /// `HIBI_MUD_IRREGULAR` lattices are checked node by node on their mesh, which only
    /// `hibi_mud_create` and `hibi_mud_create_in` build: for them `hibi_mud_memory_size` cannot
    /// tell, and `hibi_mud_create_in` may have written the memory it was given.
    HIBI_ERROR_MUD_SHORT_STEP_STABILITY: MudParamError::ShortStepStability = 538;
    /// Glass parameters: width and height must be finite and within [1, 65536] px (positions
    /// are f32: on a wider plate a crack tip's shortest moves round away).
    HIBI_ERROR_GLASS_SIZE: GlassParamError::Size = 1024;
    /// Glass parameters: the first impact must lie inside the plate.
    HIBI_ERROR_GLASS_IMPACT_POINT: GlassParamError::Impact = 1025;
    /// Glass parameters: `radial_mean` must be finite and within [0, 10000].
    HIBI_ERROR_GLASS_RADIAL_MEAN: GlassParamError::RadialMean = 1026;
    /// Glass parameters: `ring_threshold` must be finite.
    HIBI_ERROR_GLASS_RING_THRESHOLD: GlassParamError::RingThreshold = 1027;
    /// Glass parameters: the large and ring count formulas' coefficients must be finite and >= 0.
    HIBI_ERROR_GLASS_COUNT_FORMULA: GlassParamError::CountFormula = 1028;
    /// Glass parameters: the ring radius coefficients must be finite and >= 0.
    HIBI_ERROR_GLASS_RING_RADIUS: GlassParamError::RingRadius = 1029;
    /// Glass parameters: the speeds must be finite and > 0.
    HIBI_ERROR_GLASS_SPEED: GlassParamError::Speed = 1030;
    /// Glass parameters: `spread_ratio` (z) must be within [0, 1).
    HIBI_ERROR_GLASS_SPREAD_RATIO: GlassParamError::SpreadRatio = 1031;
    /// Glass parameters: `turn_limit` must be within [0, pi].
    HIBI_ERROR_GLASS_TURN_LIMIT: GlassParamError::TurnLimit = 1032;
    /// Glass parameters: `turn_delay` (T) must be finite and > 0.
    HIBI_ERROR_GLASS_TURN_DELAY: GlassParamError::TurnDelay = 1033;
    /// Glass parameters: `sector_angle` must be within (0, 2 pi] and `sector_radius` finite and > 0.
    HIBI_ERROR_GLASS_SECTOR: GlassParamError::Sector = 1034;
    /// Glass parameters: the force constants, `wander` and `ring_adherence` must be finite and >= 0.
    HIBI_ERROR_GLASS_FORCES: GlassParamError::Forces = 1035;
    /// Glass parameters: `max_cracks` must be within [1, 2^28] and `max_vertices` within
    /// [2, 2^28], within memory.
    HIBI_ERROR_GLASS_CAPACITY_PARAMS: GlassParamError::Capacity = 1036;
    /// Skin parameters: `width` and `height` must be in 1..=32768.
    HIBI_ERROR_SKIN_SIZE: SkinParamError::Size = 1280;
    /// Skin parameters: `jitter_ratio` must be in [0, 1].
    HIBI_ERROR_SKIN_JITTER_RATIO: SkinParamError::JitterRatio = 1281;
    /// Skin parameters: `levels` must be in 1..=4.
    HIBI_ERROR_SKIN_LEVELS: SkinParamError::Levels = 1282;
    /// Skin parameters: a used level's `spacing` must be finite and >= 1 px.
    HIBI_ERROR_SKIN_SPACING: SkinParamError::Spacing = 1283;
    /// Skin parameters: a used level's `perturbation` and `perturbation_decay` must be finite and >= 0.
    HIBI_ERROR_SKIN_PERTURBATION: SkinParamError::Perturbation = 1284;
    /// Skin parameters: a used level's `perturbation_depth` must be <= 5.
    HIBI_ERROR_SKIN_PERTURBATION_DEPTH: SkinParamError::PerturbationDepth = 1285;
    /// Skin parameters: a used level's `stretch` must be finite and > 0.
    HIBI_ERROR_SKIN_STRETCH: SkinParamError::Stretch = 1286;
    /// Skin parameters: a used level's `profile.segments` must be in 1..=4.
    HIBI_ERROR_SKIN_PROFILE_SEGMENTS: SkinParamError::ProfileSegments = 1287;
    /// Skin parameters: a used level's profile points must be finite, start at x' = 0, never
    /// decrease in x' and end at x' > 0.
    HIBI_ERROR_SKIN_PROFILE_POINTS: SkinParamError::ProfilePoints = 1288;
    /// Skin parameters: a used level's `roundness` must be in [0, 1].
    HIBI_ERROR_SKIN_ROUNDNESS: SkinParamError::Roundness = 1289;
    /// Skin parameters: the surface needs more memory than the address space allows.
    HIBI_ERROR_SKIN_CAPACITY_PARAMS: SkinParamError::Capacity = 1290;
}
