//! The paper's 1-D crack spacing prediction (Hirota et al. §4.1, Fig. 8).
//!
//! 2N springs of constant k in a row over the deep layer, tied to it by shear springs h,
//! deep-node spacing L, rest length l0:
//!
//! F_n = k(L − l0 − d_n + d_{n−1}),  F_n − F_{n+1} = h·d_n,  d_0 = 0,  F_{N+1} = 0,
//!
//! α, β = (1 + h/2k) ± √((1 + h/2k)² − 1),
//! d_1 = k(L − l0) / [(k + h)(αᴺ − βᴺ)/(α − β) − k(αᴺ⁻¹ − βᴺ⁻¹)/(α − β)],
//! d_N = (αᴺ − βᴺ)/(α − β)·d_1.
//!
//! The centre spring is the most stretched; the row stays whole while (L − d_1)/l0 < κ.
//! Solving (L − d_1)/l0 = κ for N (here by bisection over real N) gives the crack spacing
//! D = 2N·L and the opening width w = 2·d_N. The paper found simulated spacings somewhat
//! smaller than D.

use super::lattice::Lattice;
use super::material::Material;
use super::params::MudParams;

/// The 1-D model's prediction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpacingPrediction {
    /// N: springs on each side of the centre when the centre spring reaches κ.
    pub half_springs: f32,
    /// D = 2N·L: the crack spacing, in units of L.
    pub spacing: f32,
    /// w = 2·d_N: the opening width, in units of L.
    pub opening: f32,
}

/// d_1 and d_N for real N (units of L = 1).
fn displacements(k: f64, h: f64, rest: f64, n: f64) -> (f64, f64) {
    let c = 1.0 + h / (2.0 * k);
    let root = crate::scalar::sqrt(c * c - 1.0);
    let (alpha, beta) = (c + root, c - root);
    let chain = |m: f64| (libm::pow(alpha, m) - libm::pow(beta, m)) / (alpha - beta);
    let d1 = k * (1.0 - rest) / ((k + h) * chain(n) - k * chain(n - 1.0));
    (d1, chain(n) * d1)
}

/// The crack spacing the 1-D model predicts for spring constant `k`, shear spring `h`
/// (any consistent unit), break stretch `kappa`, and rest length `rest` = l0/L. `None` when
/// the row never breaks (L/l0 ≤ κ: even an endless row is not stretched enough) or the inputs
/// are not positive and finite.
pub fn predict_spacing(k: f32, h: f32, kappa: f32, rest: f32) -> Option<SpacingPrediction> {
    let (k, h, kappa, rest) = (f64::from(k), f64::from(h), f64::from(kappa), f64::from(rest));
    if [k, h, kappa, rest].iter().any(|x| !x.is_finite() || *x <= 0.0) || 1.0 / rest <= kappa {
        return None;
    }
    let centre_stretch = |n: f64| (1.0 - displacements(k, h, rest, n).0) / rest;
    // The centre stretch grows with N towards 1/rest > κ: bracket the crossing, then bisect.
    let (mut low, mut high) = (1.0, 1.0);
    while centre_stretch(high) < kappa {
        low = high;
        high *= 2.0;
        if high > 1e7 {
            return None;
        }
    }
    if low == high {
        low = 0.5;
    }
    for _ in 0..100 {
        let mid = 0.5 * (low + high);
        if centre_stretch(mid) < kappa { low = mid } else { high = mid }
    }
    let n = 0.5 * (low + high);
    let (_, dn) = displacements(k, h, rest, n);
    Some(SpacingPrediction { half_springs: n as f32, spacing: (2.0 * n) as f32, opening: (2.0 * dn) as f32 })
}

impl MudParams {
    /// The 1-D prediction for these parameters at shrink `shrink` (rest = 1 − shrink), with
    /// the lattice's spring and shear constants and the mean break stretch; spacing and opening
    /// in cm.
    pub fn predicted_spacing(&self, shrink: f32) -> Option<SpacingPrediction> {
        self.validate().ok()?;
        let lattice: Lattice = self.lattice();
        let material = Material::<f32>::new(self, &lattice).ok()?;
        let p = predict_spacing(material.stiffness[0], material.shear, self.break_stretch_mean, 1.0 - shrink)?;
        let w = self.element_size;
        Some(SpacingPrediction { half_springs: p.half_springs, spacing: p.spacing * w, opening: p.opening * w })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_prediction_satisfies_the_papers_equations() {
        let (k, h, kappa, rest) = (1.0, 0.2, 1.02, 0.975);
        let p = predict_spacing(k, h, kappa, rest).unwrap();
        let n = f64::from(p.half_springs);
        let (d1, _) = displacements(1.0, 0.2, 0.975, n);
        // (L − d_1)/l0 = κ at the predicted N.
        assert!(((1.0 - d1) / 0.975 - 1.02).abs() < 1e-6);
        assert_eq!(p.spacing, 2.0 * p.half_springs);
        // Check the closed form against the recurrence for an integer N.
        let n = 7;
        let (d1, dn) = displacements(1.0, 0.2, 0.975, f64::from(n));
        let mut d = [0.0f64; 9];
        d[1] = d1;
        // F_n − F_{n+1} = h·d_n with F_n = k(L − l0 − d_n + d_{n−1}) gives d_{n+1}.
        for m in 1..n as usize {
            let f_n = 1.0 * (1.0 - 0.975 - d[m] + d[m - 1]);
            let f_next = f_n - 0.2 * d[m];
            d[m + 1] = d[m] + (1.0 - 0.975) - f_next / 1.0;
        }
        assert!((d[n as usize] - dn).abs() < 1e-9, "{} vs {dn}", d[n as usize]);
        // The free end carries no force: F_{N+1} = F_N − h·d_N = 0.
        let f_last = 1.0 - 0.975 - d[n as usize] + d[n as usize - 1];
        assert!((f_last - 0.2 * dn).abs() < 1e-9, "F_(N+1) = {}", f_last - 0.2 * dn);
    }

    #[test]
    fn stiffer_surfaces_crack_wider_apart() {
        // A larger E/G (stiffer surface springs against the same shear) spaces cracks further.
        let soft = predict_spacing(1.0, 0.2, 1.02, 0.97).unwrap();
        let stiff = predict_spacing(1.0, 0.05, 1.02, 0.97).unwrap();
        assert!(stiff.spacing > soft.spacing);
        // More shrink, closer cracks.
        let later = predict_spacing(1.0, 0.2, 1.02, 0.95).unwrap();
        assert!(later.spacing < soft.spacing);
    }

    #[test]
    fn no_prediction_without_enough_shrink() {
        assert_eq!(predict_spacing(1.0, 0.2, 1.02, 0.99), None);
        assert_eq!(predict_spacing(f32::NAN, 0.2, 1.02, 0.9), None);
    }
}
