//! Parameters of the drying-mud model (Hirota et al. §2–3), in the paper's physical units
//! (cm, g, s), with the paper's defaults and one validation that names the wrong field.

use crate::enumeration::enumeration;

/// The largest shrink the model follows: rest lengths a hundredth of the plate's. A spring
/// that breaks only beyond it never breaks.
pub(crate) const LARGEST_SHRINK: f32 = 0.99;

/// The largest growth the model follows (the deep layer 101 times the plate), and the most
/// one long step may grow ([`MudParamError::ShrinkRatio`]).
pub(crate) const LARGEST_GROWTH: f32 = 100.0;

enumeration! {
    /// Mesh topology (paper Fig. 4).
    pub enum Topology {
        /// Square elements: 4 neighbours, no in-plane shear; axis-aligned, short, fine cracks.
        Square,
        /// Hexagonal elements (a triangular lattice of nodes): 6 neighbours; isotropic cracks.
        Hexagonal,
        /// Beyond the paper: the triangular lattice's nodes jittered and joined by their Delaunay
        /// triangulation, each spring with its own length and face (its Voronoi edge), so cracks
        /// run in any direction (see `mud::irregular`). Periodic: columns ≥ 8, rows even and ≥ 8.
        /// Both solvers run on it (the explicit one spring by spring, without the regular
        /// lattices' vectorised rows).
        Irregular,
    }
}

enumeration! {
    /// What happens at the lattice's edges.
    pub enum Boundary {
        /// Free edges: the outermost nodes have fewer springs.
        Open,
        /// The lattice wraps around (a torus): tileable patterns. Hexagonal lattices need an even
        /// number of rows.
        Periodic,
    }
}

enumeration! {
    /// How the lattice is brought to equilibrium.
    pub enum Solver {
        /// The paper's loop exactly (Fig. 2): forces, stability test, exact damped short steps,
        /// breaking after every short step, shrinking by long steps.
        Explicit,
        /// Linear quasi-static equilibrium with event-driven breaking: the shrink jumps straight
        /// to the next break, local relaxation after each break. Same statistics, far faster.
        QuasiStatic,
    }
}

enumeration! {
    /// What drives the misfit between the two layers.
    pub enum Drive {
        /// The surface dries and shrinks: rest lengths l0·r(t), r(t) = γ^(t/T) (Eq. 1).
        Shrink,
        /// The deep layer grows (tree bark): its node spacing expands by 1/r(t), surface rest
        /// lengths stay; the pattern is drawn in the growing frame.
        Growth,
    }
}

/// The parameters of a drying-mud run. `Default` gives the paper's values and ours where the
/// paper gives none (see each field).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MudParams {
    /// Mesh topology.
    pub topology: Topology,
    /// Edges: open or periodic (tileable).
    pub boundary: Boundary,
    /// Equilibrium solver.
    pub solver: Solver,
    /// Shrinking surface or growing deep layer.
    pub drive: Drive,
    /// Nodes per row.
    pub columns: u32,
    /// Rows of nodes.
    pub rows: u32,
    /// Seed of every random draw of the run.
    pub seed: u64,

    /// H: thickness of the surface layer \[cm\]. Not given by the paper: 1 cm, with W = 1 cm,
    /// gives the closed polygonal cells of its figures (`docs/src/models/papers.md`, Model A, Defaults).
    pub layer_thickness: f32,
    /// W: element size, the lattice spacing \[cm\]. Not given by the paper: 1 cm (see H).
    pub element_size: f32,
    /// T: the long time step \[s\]; break times are reported in long steps.
    pub long_step: f32,
    /// τ: the short time step of the explicit solver \[s\]. Paper: 0.001. The explicit solver
    /// refuses a step that fails the stability test of its damped step (about ten times the
    /// paper's at the defaults: [`MudParamError::ShortStepStability`]). The short steps after
    /// a long step or a break end at the stability test (Eq. 3), at a short step that moves
    /// no node and breaks nothing (at rest as far as the backend resolves it), or after at
    /// most ⌈64/−ln ρ⌉ of them, ρ the slowest contraction of the damped step (Eq. 4) over the
    /// stiffnesses a node sees: 64 e-folds of the slowest mode, 13,988 short steps at the
    /// paper's values (hexagonal), where a break settles within about 1,000. A run so takes at
    /// most that many short steps per long step and per spring.
    pub short_step: f32,
    /// γ: shrink ratio per long step, in [`f32::MIN_POSITIVE`, 1): the rest lengths shrink to
    /// γⁿ after n long steps (γ = 1 would never shrink, so nothing would ever crack; it is
    /// rejected, as both solvers would otherwise disagree on what it means). With [`Drive::Growth`] the deep
    /// layer grows by 1/γ per long step, at most 101-fold: γ ≥ 1/101. Paper: 0.9999.
    pub shrink_ratio: f32,
    /// δx: allowed displacement error \[cm\]; the force tolerance is δF = k_min·δx. Paper: 1e-4.
    /// The quasi-static solver resolves displacements per unit misfit to δx/s at misfit s, and
    /// to no less than 8 units of the backend's resolution; after a break it relaxes at most
    /// ⌈64/ln(1 + h/Σk)⌉ sweeps' worth of nodes (1,312 sweeps at the paper's values).
    pub displacement_tolerance: f32,
    /// α: damping factor, c = 2·√(k_max·m)·α. Paper: 20 (empirically stable).
    pub damping_factor: f32,

    /// ρ: density [g/cm³]. Not given by the paper: 1.8, wet clayey mud.
    pub density: f32,
    /// E: Young's modulus [g/(cm·s²)]. Paper: 1.0e6.
    pub young_modulus: f32,
    /// G: shear modulus [g/(cm·s²)]. Paper: 2.0e5.
    pub shear_modulus: f32,
    /// κ̄: mean break stretch, > 1. Paper: 1.02.
    pub break_stretch_mean: f32,
    /// σ: spread of the break stretch per unit area [1/cm]; κ_i = κ̄ + σ/√A_i·N(0,1).
    /// Paper: 0.001.
    pub break_stretch_spread: f32,
    /// Beyond the paper, for mesh-scale independence (§4.2): the break margin κ̄ − 1 is
    /// scaled by (1 cm / W)^x, so finer meshes get stronger springs. 0 (the default) is the
    /// paper's rule, κ̄ at every W. The paper's rule breaks more springs on finer meshes
    /// (crack density 0.39 / 0.54 / 0.68 per cm at W = 2, 1, 0.5 cm); x = 0.25 keeps density
    /// and mean cell area within 15 % from step to step (`tests/mud.rs`). 0.5 would keep a
    /// crack tip's load (a strain ∝ √(a/W) one spring ahead) at the same far-field strain, but
    /// new cracks start under uniform strain, which does not depend on W (x = 0); the measured
    /// exponent lies between. Within [0, 1].
    pub break_stretch_size_exponent: f32,

    /// φ: the direction cracks prefer to run along [radians from the x axis] (paper Fig. 7).
    pub anisotropy_direction: f32,
    /// How much weaker springs across φ are than springs along φ: the break margin κ − 1 of a
    /// spring at angle θ is (κ − 1)·(cos²(θ − φ) + sin²(θ − φ)/ratio). 1 = isotropic; ≥ 1.
    pub anisotropy_ratio: f32,
    /// Optional stiffness anisotropy: k(θ) = k·(cos²(θ − φ) + sin²(θ − φ)/ratio). 1 = none;
    /// within [1, 1e6] (the model computes in units where the weakest spring is ≥ 1e-6).
    pub stiffness_anisotropy_ratio: f32,

    /// The run ends when the shrink 1 − r reaches this (growth: 1/r − 1). 0 = no target:
    /// the run then ends at the largest misfit the model follows (shrink 0.99, growth 100),
    /// as it does, in both solvers, when no spring is left that can break before the end (a
    /// large `break_stretch_mean`, say: the run ends at the target, uncracked).
    /// Default 0.023: closed polygonal cells whose tips have joined up, before they subdivide
    /// towards lattice scale.
    pub target_shrink: f32,
    /// The run also ends when the crack length per area reaches this [1/cm]. 0 = no limit.
    pub target_crack_density: f32,
}

impl Default for MudParams {
    fn default() -> Self {
        MudParams {
            topology: Topology::Hexagonal,
            boundary: Boundary::Periodic,
            solver: Solver::QuasiStatic,
            drive: Drive::Shrink,
            columns: 128,
            rows: 128,
            seed: 1,
            layer_thickness: 1.0,
            element_size: 1.0,
            long_step: 1.0,
            short_step: 0.001,
            shrink_ratio: 0.9999,
            displacement_tolerance: 1.0e-4,
            damping_factor: 20.0,
            density: 1.8,
            young_modulus: 1.0e6,
            shear_modulus: 2.0e5,
            break_stretch_mean: 1.02,
            break_stretch_spread: 0.001,
            break_stretch_size_exponent: 0.0,
            anisotropy_direction: 0.0,
            anisotropy_ratio: 1.0,
            stiffness_anisotropy_ratio: 1.0,
            target_shrink: 0.023,
            target_crack_density: 0.0,
        }
    }
}

crate::error::error_list! {
    /// A parameter that is out of its range; each names the field and its constraint.
    pub enum MudParamError {
        /// `columns` must be ≥ 2 (≥ 3 when periodic, ≥ 8 periodic irregular).
        Columns => c"mud: columns must be >= 2 (>= 3 when periodic, >= 8 periodic irregular)",
        /// `rows` must be ≥ 2 (periodic: ≥ 3 square, even and ≥ 4 hexagonal, even and ≥ 8 irregular).
        Rows => c"mud: rows must be >= 2 (periodic: >= 3 square, even and >= 4 hexagonal, even and >= 8 irregular)",
        /// `layer_thickness` (H) must be finite and > 0.
        LayerThickness => c"mud: layer_thickness (H) must be finite and > 0",
        /// `element_size` (W) must be finite and > 0.
        ElementSize => c"mud: element_size (W) must be finite and > 0",
        /// `long_step` (T) must be finite and > 0.
        LongStep => c"mud: long_step (T) must be finite and > 0",
        /// `short_step` (τ) must be finite and > 0.
        ShortStep => c"mud: short_step (tau) must be finite and > 0",
        /// `shrink_ratio` (γ) must be at least `f32::MIN_POSITIVE` and below 1 (1 would never shrink;
        /// a subnormal ratio would lose its precision); with [`Drive::Growth`], one long step may
        /// grow the deep layer at most by the largest misfit the model follows: 1/γ − 1 ≤ 100.
        ShrinkRatio => c"mud: shrink_ratio (gamma) must be >= FLT_MIN and < 1 (1 would never shrink); with the growth drive, 1/gamma - 1 <= 100",
        /// `displacement_tolerance` (δx) must be finite and > 0.
        DisplacementTolerance => c"mud: displacement_tolerance (delta x) must be finite and > 0",
        /// `damping_factor` (α) must be finite and > 0.
        DampingFactor => c"mud: damping_factor (alpha) must be finite and > 0",
        /// `density` (ρ) must be finite and > 0.
        Density => c"mud: density (rho) must be finite and > 0",
        /// `young_modulus` (E) must be finite and > 0.
        YoungModulus => c"mud: young_modulus (E) must be finite and > 0",
        /// `shear_modulus` (G) must be finite and > 0.
        ShearModulus => c"mud: shear_modulus (G) must be finite and > 0",
        /// `break_stretch_mean` (κ̄) must be finite and > 1.
        BreakStretchMean => c"mud: break_stretch_mean (kappa) must be finite and > 1",
        /// `break_stretch_spread` (σ) must be finite and ≥ 0.
        BreakStretchSpread => c"mud: break_stretch_spread (sigma) must be finite and >= 0",
        /// `anisotropy_direction` (φ) must be finite.
        AnisotropyDirection => c"mud: anisotropy_direction must be finite",
        /// `anisotropy_ratio` must be finite and ≥ 1.
        AnisotropyRatio => c"mud: anisotropy_ratio must be finite and >= 1",
        /// `stiffness_anisotropy_ratio` must be within [1, 1e6].
        StiffnessAnisotropyRatio => c"mud: stiffness_anisotropy_ratio must be within [1, 1e6]",
        /// `target_shrink` must be finite and within [0, 1).
        TargetShrink => c"mud: target_shrink must be finite and within [0, 1)",
        /// `target_crack_density` must be finite and ≥ 0.
        TargetCrackDensity => c"mud: target_crack_density must be finite and >= 0",
        /// The lattice is too large: `columns` × `rows` must be ≤ 2²⁸ (268 435 456 nodes;
        /// irregular: also `columns` ≤ 2²⁰ and `rows` ≤ 2²¹), and its memory must fit in the
        /// address space.
        SizeOverflow => c"mud: columns x rows must be <= 2^28 (irregular: columns <= 2^20, rows <= 2^21), within memory",
        /// The deep-layer spring constant h = (G/E)·(W/H)² (per unit element area) is outside
        /// [1e-6, 1e6]: the ratios of `shear_modulus`, `young_modulus`, `element_size` and
        /// `layer_thickness` are too far apart for the units the model computes in.
        ShearScale => c"mud: (shear_modulus / young_modulus) * (element_size / layer_thickness)^2 must be within [1e-6, 1e6]",
        /// `break_stretch_size_exponent` must be within [0, 1].
        BreakStretchSizeExponent => c"mud: break_stretch_size_exponent must be within [0, 1]",
        /// The damping constant 2·√(k_max·m)·α (lattice units) is outside [1e-6, 1e6]:
        /// `damping_factor` is too large or too small for the lattice.
        DampingScale => c"mud: damping_factor is out of scale: 2 * sqrt(k_max * m) * damping_factor must be within [1e-6, 1e6]",
        /// The short step in lattice time units τ / (W·√(ρ/E)) is outside [1e-6, 1e6].
        ShortStepScale => c"mud: short_step / (element_size * sqrt(density / young_modulus)) must be within [1e-6, 1e6]",
        /// The force tolerance k_min·δx/W (lattice units) is outside [1e-6, 1e6].
        ToleranceScale => c"mud: displacement_tolerance is out of scale: k_min * displacement_tolerance / element_size must be within [1e-6, 1e6]",
        /// The spread of the break stretch per element, σ/√(face·W·H), is not finite.
        SpreadScale => c"mud: break_stretch_spread / sqrt(face * element_size * layer_thickness) must be finite",
        /// The explicit solver's short step fails the stability test of its damped step
        /// (Eq. 4 under a bound on the stiffest mode; a sufficient test, so past it the run may
        /// diverge). Make `short_step` smaller or `damping_factor` larger, or use the
        /// quasi-static solver.
        ShortStepStability => c"mud: short_step fails the explicit solver's stability test (make short_step smaller or damping_factor larger, or use the quasi-static solver)",
    }
}

/// `x` is finite and > 0.
fn positive(x: f32) -> bool {
    x.is_finite() && x > 0.0
}

impl MudParams {
    /// Checks every field; the first wrong one is named.
    pub fn validate(&self) -> Result<(), MudParamError> {
        use MudParamError::*;
        let periodic = self.boundary == Boundary::Periodic;
        let min_columns = match (periodic, self.topology) {
            (false, _) => 2,
            (true, Topology::Irregular) => 8,
            (true, _) => 3,
        };
        if self.columns < min_columns {
            return Err(Columns);
        }
        let rows_ok = match (self.boundary, self.topology) {
            (Boundary::Open, _) => self.rows >= 2,
            (Boundary::Periodic, Topology::Square) => self.rows >= 3,
            (Boundary::Periodic, Topology::Hexagonal) => self.rows >= 4 && self.rows.is_multiple_of(2),
            (Boundary::Periodic, Topology::Irregular) => self.rows >= 8 && self.rows.is_multiple_of(2),
        };
        if !rows_ok {
            return Err(Rows);
        }
        let checks = [
            (positive(self.layer_thickness), LayerThickness),
            (positive(self.element_size), ElementSize),
            (positive(self.long_step), LongStep),
            (positive(self.short_step), ShortStep),
            // Not subnormal, and with the growth drive one long step grows the deep layer at
            // most by the largest misfit the model follows (1/γ − 1 ≤ 100): the run's last step
            // then ends within 101² times the plate's size (fuzzing found γ = 1e-40 growing to
            // an infinite shrink, and γ = FLT_MIN to segments past f32).
            (self.shrink_ratio >= f32::MIN_POSITIVE && self.shrink_ratio < 1.0, ShrinkRatio),
            (self.drive == Drive::Shrink || 1.0 / self.shrink_ratio - 1.0 <= LARGEST_GROWTH, ShrinkRatio),
            (positive(self.displacement_tolerance), DisplacementTolerance),
            (positive(self.damping_factor), DampingFactor),
            (positive(self.density), Density),
            (positive(self.young_modulus), YoungModulus),
            (positive(self.shear_modulus), ShearModulus),
            (self.break_stretch_mean.is_finite() && self.break_stretch_mean > 1.0, BreakStretchMean),
            (self.break_stretch_spread.is_finite() && self.break_stretch_spread >= 0.0, BreakStretchSpread),
            ((0.0..=1.0).contains(&self.break_stretch_size_exponent), BreakStretchSizeExponent),
            (self.anisotropy_direction.is_finite(), AnisotropyDirection),
            (self.anisotropy_ratio.is_finite() && self.anisotropy_ratio >= 1.0, AnisotropyRatio),
            ((1.0..=1e6).contains(&self.stiffness_anisotropy_ratio), StiffnessAnisotropyRatio),
            (self.target_shrink.is_finite() && (0.0..1.0).contains(&self.target_shrink), TargetShrink),
            (self.target_crack_density.is_finite() && self.target_crack_density >= 0.0, TargetCrackDensity),
        ];
        if let Some(&(_, error)) = checks.iter().find(|(ok, _)| !ok) {
            return Err(error);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_valid_and_the_papers() {
        let p = MudParams::default();
        assert_eq!(p.validate(), Ok(()));
        assert_eq!((p.young_modulus, p.shear_modulus), (1.0e6, 2.0e5));
        assert_eq!((p.break_stretch_mean, p.break_stretch_spread), (1.02, 0.001));
        assert_eq!(
            (p.shrink_ratio, p.short_step, p.displacement_tolerance, p.damping_factor),
            (0.9999, 0.001, 1e-4, 20.0)
        );
    }

    #[test]
    fn every_bad_field_is_named() {
        let base = MudParams::default();
        type Spoil = fn(&mut MudParams);
        let cases: [(Spoil, MudParamError); 22] = [
            (|p| p.columns = 1, MudParamError::Columns),
            (|p| p.rows = 5, MudParamError::Rows),
            (|p| p.layer_thickness = 0.0, MudParamError::LayerThickness),
            (|p| p.element_size = f32::NAN, MudParamError::ElementSize),
            (|p| p.long_step = f32::INFINITY, MudParamError::LongStep),
            (|p| p.short_step = -1.0, MudParamError::ShortStep),
            (|p| p.shrink_ratio = 1.5, MudParamError::ShrinkRatio),
            (|p| p.shrink_ratio = 0.0, MudParamError::ShrinkRatio),
            (|p| p.shrink_ratio = 1.0, MudParamError::ShrinkRatio),
            (|p| p.displacement_tolerance = 0.0, MudParamError::DisplacementTolerance),
            (|p| p.damping_factor = f32::NEG_INFINITY, MudParamError::DampingFactor),
            (|p| p.density = -2.0, MudParamError::Density),
            (|p| p.young_modulus = 0.0, MudParamError::YoungModulus),
            (|p| p.shear_modulus = -1.0, MudParamError::ShearModulus),
            (|p| p.break_stretch_mean = 1.0, MudParamError::BreakStretchMean),
            (|p| p.break_stretch_spread = -0.001, MudParamError::BreakStretchSpread),
            (|p| p.break_stretch_size_exponent = f32::NAN, MudParamError::BreakStretchSizeExponent),
            (|p| p.anisotropy_direction = f32::NAN, MudParamError::AnisotropyDirection),
            (|p| p.anisotropy_ratio = 0.5, MudParamError::AnisotropyRatio),
            (|p| p.stiffness_anisotropy_ratio = f32::NAN, MudParamError::StiffnessAnisotropyRatio),
            (|p| p.target_shrink = 1.0, MudParamError::TargetShrink),
            (|p| p.target_crack_density = -1.0, MudParamError::TargetCrackDensity),
        ];
        for (spoil, error) in cases {
            let mut p = base;
            spoil(&mut p);
            assert_eq!(p.validate(), Err(error), "{p:?}");
        }
    }
}
