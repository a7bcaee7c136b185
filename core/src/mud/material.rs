//! The paper's derived constants (Hirota et al. §2), nondimensionalised to lattice units so
//! that every backend, Q16.16 included, computes with numbers near 1.
//!
//! Units: length W (the element size), stiffness E·H (the square lattice's surface spring),
//! mass ρ·W²·H (the square element's mass), time √(mass/stiffness). In these units:
//! - surface spring k = A·E/l0 = face·H·E/W → `face_length` (1 square, 1/√3 hexagonal),
//!   times the optional stiffness anisotropy;
//! - shear spring h = B·G/H → `element_area`·(G/E)·(W/H)²;
//! - node mass m = ρ·B·H → `element_area`;
//! - damping c = 2·√(k_max·m)·α and force tolerance δF = k_min·δx, with k_max and k_min over
//!   the node's springs, the shear spring included (so every node has the same c and δF:
//!   the shear spring never breaks, and the weakest spring never goes missing);
//! - break stretch κ_i = κ̄ + σ/√A_i·N(0, 1), A_i = face·H in cm², and with anisotropy the
//!   margin κ_i − 1 scaled by the spring's direction.

use super::lattice::Lattice;
use super::params::{MudParamError, MudParams};
use crate::scalar::Scalar;

/// The largest number of spring directions (hexagonal).
pub const MAX_DIRECTIONS: usize = 3;

/// Derived constants of a run, in lattice units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material<S> {
    /// Surface spring constant per direction.
    pub stiffness: [S; MAX_DIRECTIONS],
    /// Break margin factor per direction: κ_i − 1 is scaled by it (1 without anisotropy).
    pub margin_factor: [f32; MAX_DIRECTIONS],
    /// Shear spring constant h.
    pub shear: S,
    /// Node mass m.
    pub mass: S,
    /// Damping coefficient c.
    pub damping: S,
    /// Short step τ.
    pub short_step: S,
    /// Force tolerance δF.
    pub force_tolerance: S,
    /// Spread of κ_i: σ/√A_i (A_i in cm²).
    pub break_stretch_spread: f32,
    /// h per unit node area (G/E)·(W/H)²: the irregular lattice's h = B_i·this.
    pub shear_per_area: f32,
    /// σ/√(W·H): the irregular lattice's spread of κ_i is this over √face.
    pub spread_per_root_face: f32,
}

/// cos²(θ − φ) + sin²(θ − φ)/ratio: the anisotropy factor of a spring at angle θ.
pub(super) fn anisotropy(direction: [f32; 2], preferred: f32, ratio: f32) -> f32 {
    let (sin, cos) = (libm::sinf(preferred), libm::cosf(preferred));
    let along = direction[0] * cos + direction[1] * sin;
    let across = direction[1] * cos - direction[0] * sin;
    along * along + across * across / ratio
}

impl<S: Scalar> Material<S> {
    /// The constants of `params` on `lattice` (params already validated).
    pub fn new(params: &MudParams, lattice: &Lattice) -> Result<Self, MudParamError> {
        let p = params;
        let (w, h_layer) = (p.element_size, p.layer_thickness);
        let face = lattice.face_length();
        let area = lattice.element_area();
        let mut stiffness = [0.0f32; MAX_DIRECTIONS];
        let mut margin_factor = [1.0f32; MAX_DIRECTIONS];
        for d in 0..lattice.directions() {
            let v = lattice.direction_vector(d);
            stiffness[d] = face * anisotropy(v, p.anisotropy_direction, p.stiffness_anisotropy_ratio);
            margin_factor[d] = anisotropy(v, p.anisotropy_direction, p.anisotropy_ratio);
        }
        let shear = area * (p.shear_modulus / p.young_modulus) * (w / h_layer) * (w / h_layer);
        let mass = area;
        let springs = &stiffness[..lattice.directions()];
        let k_max = springs.iter().fold(shear, |m, &k| m.max(k));
        let k_min = springs.iter().fold(shear, |m, &k| m.min(k));
        let damping = 2.0 * crate::scalar::sqrtf(k_max * mass) * p.damping_factor;
        // Time unit √(ρ·W²·H / (E·H)) = W·√(ρ/E).
        let time_unit = w * crate::scalar::sqrtf(p.density / p.young_modulus);
        let short_step = p.short_step / time_unit;
        let force_tolerance = k_min * p.displacement_tolerance / w;
        let face_area_cm2 = face * w * h_layer;
        let spread = p.break_stretch_spread / crate::scalar::sqrtf(face_area_cm2);
        // Each derived constant names the fields it comes from (k_max and k_min lie between
        // the shear and the springs' face·anisotropy, within [1e-6, 1] once the shear and
        // `stiffness_anisotropy_ratio` are in range).
        let in_scale = |x: f32| (1e-6..=1e6).contains(&x);
        let derived = [
            (in_scale(shear), MudParamError::ShearScale),
            (in_scale(damping), MudParamError::DampingScale),
            (in_scale(short_step), MudParamError::ShortStepScale),
            (in_scale(force_tolerance), MudParamError::ToleranceScale),
            (spread.is_finite(), MudParamError::SpreadScale),
        ];
        if let Some(&(_, error)) = derived.iter().find(|(ok, _)| !ok) {
            return Err(error);
        }
        Ok(Material {
            stiffness: stiffness.map(S::from_f32),
            margin_factor,
            shear: S::from_f32(shear),
            mass: S::from_f32(mass),
            damping: S::from_f32(damping),
            short_step: S::from_f32(short_step),
            force_tolerance: S::from_f32(force_tolerance),
            break_stretch_spread: spread,
            shear_per_area: shear / area,
            spread_per_root_face: p.break_stretch_spread / crate::scalar::sqrtf(w * h_layer),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mud::params::{Boundary, Topology};

    fn lattice(topology: Topology) -> Lattice<'static> {
        Lattice::new(topology, Boundary::Periodic, 8, 8)
    }

    #[test]
    fn square_constants_follow_the_paper() {
        let p = MudParams { topology: Topology::Square, ..MudParams::default() };
        let m = Material::<f32>::new(&p, &lattice(Topology::Square)).unwrap();
        // k = A·E/l0 = (1 cm · 1 cm)·E / 1 cm = E·H: 1 in units of E·H.
        assert_eq!(m.stiffness[..2], [1.0, 1.0]);
        // h = B·G/H = G·W²/H: G/E = 0.2 in units of E·H.
        assert!((m.shear - 0.2).abs() < 1e-7);
        assert_eq!(m.mass, 1.0);
        // c = 2·√(k_max·m)·α = 40; δF = k_min·δx = 0.2·1e-4.
        assert!((m.damping - 40.0).abs() < 1e-5);
        assert!((m.force_tolerance - 2e-5).abs() < 1e-10);
        // τ = 0.001 s in units of W·√(ρ/E) = √1.8e-6 s.
        assert!((m.short_step - 0.001 / crate::scalar::sqrtf(1.8e-6)).abs() < 1e-5);
        assert!((m.break_stretch_spread - 0.001).abs() < 1e-9);
    }

    #[test]
    fn hexagonal_faces_are_narrower() {
        let m = Material::<f32>::new(&MudParams::default(), &lattice(Topology::Hexagonal)).unwrap();
        assert!((m.stiffness[0] - 0.577_350_26).abs() < 1e-6);
        // σ/√A with A = W·H/√3 cm².
        assert!((m.break_stretch_spread - 0.001 * crate::scalar::sqrtf(1.732_050_8)).abs() < 1e-8);
    }

    #[test]
    fn anisotropy_weakens_springs_across_the_preferred_direction() {
        let p = MudParams { topology: Topology::Square, anisotropy_ratio: 4.0, ..MudParams::default() };
        let m = Material::<f32>::new(&p, &lattice(Topology::Square)).unwrap();
        assert_eq!(m.margin_factor[0], 1.0);
        assert!((m.margin_factor[1] - 0.25).abs() < 1e-6);
    }

    #[test]
    fn absurd_ratios_are_refused() {
        let d = MudParams::default();
        let cases = [
            (MudParams { young_modulus: 1e20, ..d }, MudParamError::ShearScale),
            (MudParams { damping_factor: 1e9, ..d }, MudParamError::DampingScale),
            (MudParams { short_step: 1e9, ..d }, MudParamError::ShortStepScale),
            (MudParams { displacement_tolerance: 1e-12, ..d }, MudParamError::ToleranceScale),
            (
                MudParams {
                    break_stretch_spread: 3e38,
                    element_size: 1e-20,
                    layer_thickness: 1e-20,
                    short_step: 1e-26,
                    displacement_tolerance: 1e-24,
                    ..d
                },
                MudParamError::SpreadScale,
            ),
        ];
        for (p, error) in cases {
            assert_eq!(Material::<f32>::new(&p, &lattice(Topology::Hexagonal)), Err(error), "{p:?}");
        }
    }
}
