//! The paper's result figures (Agui et al. §5, Fig. 14–16) as named presets.
//!
//! Every figure is a 640 × 640 plate hit at (320, 320) with M_ave = 100 and the paper's
//! Table 2 constants (the defaults). The captions print each plate's drawn M, N and R and the
//! mean speeds: Fig. 14 varies V1_ave (30, 40, 50, 60; V2_ave = 5, normal Rand), Fig. 15 and
//! Fig. 16 use V1_ave = 40, V2_ave = 10, V3_ave = 10 with normal and uniform Rand. Each
//! preset's seed is the first whose Poisson draw gives the caption's M, so R = ⌊0.05·M + 0.5⌋
//! matches the caption too. N = ⌊0.0606·M + 3.293⌋ (Eq. 6) comes out one below most
//! captions' N: the printed N are counts of the paper's plates, not of its formula.
//!
//! | preset | caption | seed |
//! |---|---|---|
//! | `fig14a` | M = 113, R = 6, N = 11, V1_ave = 30, V2_ave = 5 | 65 |
//! | `fig14b` | M = 104, R = 5, N = 10, V1_ave = 40, V2_ave = 5 | 73 |
//! | `fig14c` | M = 113, R = 6, N = 11, V1_ave = 50, V2_ave = 5 | 65 |
//! | `fig14d` | M = 95, R = 5, N = 10, V1_ave = 60, V2_ave = 5 | 81 |
//! | `fig15a` | M = 114, R = 6, N = 11, normal | 27 |
//! | `fig15b` | M = 98, R = 5, N = 10, normal | 32 |
//! | `fig15c` | M = 105, R = 5, N = 10, normal | 17 |
//! | `fig15d` | M = 92, R = 5, N = 9, normal | 24 |
//! | `fig16a` | M = 104, R = 5, N = 10, uniform | 73 |
//! | `fig16b` | M = 89, R = 4, N = 8, uniform | 2 |
//! | `fig16c` | M = 108, R = 5, N = 9, uniform | 21 |
//! | `fig16d` | M = 96, R = 5, N = 10, uniform | 117 |
//!
//! (`fig14a` and `fig14c` share a seed, as their captions share M, N and R: the two differ
//! only in V1_ave.)

use super::params::GlassParams;
use crate::rng::Spread;

/// Every preset name, in figure order.
pub const PRESETS: [&str; 12] = [
    "fig14a", "fig14b", "fig14c", "fig14d", "fig15a", "fig15b", "fig15c", "fig15d", "fig16a", "fig16b", "fig16c",
    "fig16d",
];

/// A plate with the paper's constants, these mean speeds, Rand spread and seed.
fn plate(large_speed: f32, radial_speed: f32, spread: Spread, seed: u64) -> GlassParams {
    GlassParams { seed, large_speed, radial_speed, ring_speed: 10.0, spread, ..GlassParams::default() }
}

/// The preset of that name (see [`PRESETS`]), or `None`.
pub fn preset(name: &str) -> Option<GlassParams> {
    use Spread::{Normal, Uniform};
    let p = match name {
        "fig14a" => plate(30.0, 5.0, Normal, 65),
        "fig14b" => plate(40.0, 5.0, Normal, 73),
        "fig14c" => plate(50.0, 5.0, Normal, 65),
        "fig14d" => plate(60.0, 5.0, Normal, 81),
        "fig15a" => plate(40.0, 10.0, Normal, 27),
        "fig15b" => plate(40.0, 10.0, Normal, 32),
        "fig15c" => plate(40.0, 10.0, Normal, 17),
        "fig15d" => plate(40.0, 10.0, Normal, 24),
        "fig16a" => plate(40.0, 10.0, Uniform, 73),
        "fig16b" => plate(40.0, 10.0, Uniform, 2),
        "fig16c" => plate(40.0, 10.0, Uniform, 21),
        "fig16d" => plate(40.0, 10.0, Uniform, 117),
        _ => return None,
    };
    Some(p)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::glass::{Glass, GlassBuffers, ImpactCounts};
    extern crate std;
    use std::vec;

    /// The counts the first impact of `p` draws.
    fn counts(p: &GlassParams) -> ImpactCounts {
        let m = p.memory().unwrap();
        let (mut cracks, mut vertices) = (vec![Default::default(); m.cracks], vec![Default::default(); m.vertices]);
        let (mut edges, mut words) = (vec![Default::default(); m.edges], vec![0u32; m.words]);
        let buffers =
            GlassBuffers { cracks: &mut cracks, vertices: &mut vertices, edges: &mut edges, words: &mut words };
        Glass::new(p, buffers).unwrap().impact_counts()
    }

    #[test]
    fn every_preset_is_valid_and_draws_its_captions_m_and_r() {
        let captions: [(u32, u32); 12] = [
            (113, 6),
            (104, 5),
            (113, 6),
            (95, 5),
            (114, 6),
            (98, 5),
            (105, 5),
            (92, 5),
            (104, 5),
            (89, 4),
            (108, 5),
            (96, 5),
        ];
        for (name, (m, r)) in PRESETS.iter().zip(captions) {
            let p = preset(name).unwrap_or_else(|| panic!("{name}"));
            assert_eq!(p.validate(), Ok(()), "{name}");
            let c = counts(&p);
            assert_eq!((c.radial, c.rings), (m, r), "{name}");
        }
        assert_eq!(preset("fig13"), None);
    }
}
