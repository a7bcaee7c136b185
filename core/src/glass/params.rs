//! Parameters of the glass-impact crack grower (Agui et al. §4, Table 2), in lattice units
//! (the paper's pixels), with the paper's defaults and one validation that names the field.

use crate::rng::Spread;

/// The parameters of a glass plate hit by a ball. `Default` gives the paper's values (Table 2,
/// §4.3) and ours where it gives none (see each field).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GlassParams {
    /// Plate width \[px\], within [1, [`MAX_SIDE`]]. Paper: 640.
    pub width: f32,
    /// Plate height \[px\], within [1, [`MAX_SIDE`]]. Paper: 640.
    pub height: f32,
    /// The impact point L (x, y), inside the plate. Paper: (320, 320).
    pub impact: [f32; 2],
    /// Seed of every random draw.
    pub seed: u64,
    /// M_ave: mean number of radial cracks, M = Poisson_Rand(M_ave) (Eq. 5). Default 100
    /// (the paper's figures have M = 89–114).
    pub radial_mean: f32,
    /// A: ring cracks appear only when M > A (Eq. 3). Paper: 70.
    pub ring_threshold: f32,
    /// e in N = ⌊e·M + f⌋, the number of large cracks (Eq. 6). Paper: 0.0606.
    pub large_slope: f32,
    /// f in N = ⌊e·M + f⌋ (Eq. 6). Paper: 3.293.
    pub large_offset: f32,
    /// a in R = ⌊a·M + b⌋, the number of ring start points (Eq. 3). Not printed by the paper;
    /// 0.05 matches every figure caption (M 113 → R 6, 104 → 5, 89 → 4).
    pub ring_slope: f32,
    /// b in R = ⌊a·M + b⌋ (Eq. 3). 0.5, as for a.
    ///
    /// Whatever a and b hold, the work an impact does is bounded by the capacities: it looks
    /// at no more than `max_cracks` ring start points and stops once the cracks or vertices
    /// are full; a larger R (each start point grows two cracks) counts as running out of
    /// capacity, which ends generation with [`GlassProgress::capacity_reached`](super::GlassProgress).
    pub ring_offset: f32,
    /// g in d_ave = g·M + h, the mean ring radius \[px\] (Eq. 7). Paper: 0.470.
    pub ring_radius_slope: f32,
    /// h in d_ave = g·M + h \[px\] (Eq. 7). Paper: 13.90.
    pub ring_radius_offset: f32,
    /// V1_ave: mean speed of the large cracks [px per step] (Eq. 9). Paper: 30–60, ≤ 40
    /// looks natural; default 40. A ring crack wakes at step ⌈d_i / V1_ave⌉, once the large
    /// cracks have passed its radius.
    pub large_speed: f32,
    /// V2_ave: mean speed of the other radial cracks (Eq. 10). Paper: 5–10; default 10.
    pub radial_speed: f32,
    /// V3_ave: mean speed of the ring cracks (Eq. 11). Paper: 10.
    ///
    /// Any finite speed > 0 is valid, and every run ends: generation of an impact stops after
    /// at most [`MAX_TIME_STEPS`] (32 768) time steps, and sooner, after ⌈2·(W + H) / v⌉ + 16,
    /// when v, the slowest speed Rand can draw ((1 − z)·min(V1_ave, V2_ave, V3_ave)), crosses
    /// the plate twice in fewer. So a run's work is at most that many time steps' whatever the
    /// speeds (time steps in which no crack is awake to grow are skipped, not done). Cracks
    /// too slow to stop on their own by then end where they are
    /// ([`CrackEnd::Generation`](super::CrackEnd)), and ring cracks whose waking step lies
    /// past it never grow: with z = 0.3 on the 640 × 640 plate, that takes a mean speed below
    /// about 0.11 px per step. The most work measured there (tests/glass.rs): every speed
    /// 1e-30, its 135 cracks growing in place at the impact for all 32 768 steps, 7.1·10⁸ units.
    pub ring_speed: f32,
    /// z of Rand(x): values within [(1 − z)x, (1 + z)x]. Paper: 0.3.
    pub spread_ratio: f32,
    /// Normal or uniform Rand(x). Paper: both (Fig. 15 normal, Fig. 16 uniform).
    pub spread: Spread,
    /// θ_th: the largest turn per update \[radians\] (Eq. 14, range()). Paper: 30°. A time
    /// step (dt = 1) is cut into updates of at most 10 px (and shorter ones while a crack or
    /// edge is close ahead, see below); each update turns once.
    pub turn_limit: f32,
    /// T in weight(t) = 1 − exp(−t/T) (Eq. 19) \[steps\]; t is the crack's age in steps.
    /// Paper: 10.
    pub turn_delay: f32,
    /// φ: angle of the sector S ahead of a tip \[radians\]. Paper: 100°.
    pub sector_angle: f32,
    /// B: radius of the sector S \[px\]. Paper: 50.
    pub sector_radius: f32,
    /// k1 in |F1| = k1/r² (§4.2.2 (1)): the push on a tip away from another tip in S at
    /// distance r, from a tip growing towards it (two tips closing in turn apart; the radial
    /// cracks of an impact run away from each other and do not push). The paper gives only
    /// the 1/r² law; ours: 400 px², so that a tip 20 px away pushes as hard as the unit F3.
    pub tip_repulsion: f32,
    /// k2 in |F2| = k2/d² (§4.2.2 (2)): for each crack or plate edge in S that the tip is
    /// closing in on, a pull along that crack's normal (to cross it at a right angle), d the
    /// shortest distance from the tip to the part of it inside S. While such a crack is near,
    /// an update covers only a quarter of that distance (at least 0.5 px times the cosine
    /// between the tip's heading and the nearest crack's normal, and at least 0.125 px), so
    /// that F2 turns the tip several times before it meets it (rule 8), the more the shallower
    /// it comes in; a radial crack already heading within 20° of square at it is not slowed.
    /// The paper gives only the 1/d² law; ours: 400 px². Measured over seeds 0–99
    /// (tests/glass.rs): median meeting angle 79.0°, 81.6 % of meetings within 60°–90°.
    pub crack_attraction: f32,
    /// Standard deviation of the direction of F3, a unit force, per 10 px of growth
    /// \[radians\] (per update it is scaled by √(update length / 10 px)), for a crack of
    /// weight(t) = 1: it is scaled by weight(t) as well, so that young cracks wander little
    /// (rule 3) and the radial cracks run straight out of the impact instead of drifting into
    /// their neighbours 3.6° away. F3's direction is drawn around the direction a radial crack
    /// started in (so radial cracks turn both ways but keep their course on the whole) and
    /// around a ring crack's course (ring cracks are not scaled by weight(t)). The paper gives
    /// none; ours: 45°, a whole multiple of 5° whose turns between successive 10 px pieces of
    /// radial cracks spread like its Fig. 5 (seeds 0–99: 1st and 99th percentiles −19.6° and
    /// 21.5°, mean 0.06°; the paper: −22.5° to 27.5°).
    pub wander: f32,
    /// How hard a ring crack keeps to its circle (rule 5): a force of this size along its
    /// course, the chord of its circle one update long, turned towards radius d_i by up to a
    /// quarter of the chord's angle (so it never turns outwards from the circle's tangent).
    /// Ours: 2 (F3, a unit force, then turns the course by at most 30°). No update turns a
    /// ring crack outwards of the chord of its circle that the update spans, so each ring
    /// crack turns at least as much as the arc it spans. Measured (seeds 0–99): every ring
    /// vertex within 4.0 % of d_i, and each of 990 ring cracks turns at least its arc.
    pub ring_adherence: f32,
    /// Most cracks the plate can hold (radial, ring and from every impact).
    pub max_cracks: u32,
    /// Most crack vertices the plate can hold.
    pub max_vertices: u32,
}

impl Default for GlassParams {
    fn default() -> Self {
        GlassParams {
            width: 640.0,
            height: 640.0,
            impact: [320.0, 320.0],
            seed: 1,
            radial_mean: 100.0,
            ring_threshold: 70.0,
            large_slope: 0.0606,
            large_offset: 3.293,
            ring_slope: 0.05,
            ring_offset: 0.5,
            ring_radius_slope: 0.470,
            ring_radius_offset: 13.90,
            large_speed: 40.0,
            radial_speed: 10.0,
            ring_speed: 10.0,
            spread_ratio: 0.3,
            spread: Spread::Normal,
            turn_limit: 30.0 * core::f32::consts::PI / 180.0,
            turn_delay: 10.0,
            sector_angle: 100.0 * core::f32::consts::PI / 180.0,
            sector_radius: 50.0,
            tip_repulsion: 400.0,
            crack_attraction: 400.0,
            wander: 45.0 * core::f32::consts::PI / 180.0,
            ring_adherence: 2.0,
            max_cracks: 512,
            max_vertices: 16_384,
        }
    }
}

crate::error::error_list! {
    /// A parameter out of its range; each names the field and its constraint.
    pub enum GlassParamError {
        /// `width` and `height` must be finite and within [1, [`MAX_SIDE`]] (65536).
        Size => c"glass: width and height must be finite and within [1, 65536]",
        /// `impact` must lie inside the plate (strictly).
        Impact => c"glass: impact must lie inside the plate",
        /// `radial_mean` must be finite and within [0, 10000].
        RadialMean => c"glass: radial_mean must be finite and within [0, 10000]",
        /// `ring_threshold` must be finite.
        RingThreshold => c"glass: ring_threshold must be finite",
        /// `large_slope`, `large_offset`, `ring_slope`, `ring_offset` must be finite and >= 0.
        CountFormula => c"glass: large_slope, large_offset, ring_slope, ring_offset must be finite and >= 0",
        /// `ring_radius_slope`, `ring_radius_offset` must be finite and >= 0.
        RingRadius => c"glass: ring_radius_slope and ring_radius_offset must be finite and >= 0",
        /// `large_speed`, `radial_speed`, `ring_speed` must be finite and > 0.
        Speed => c"glass: large_speed, radial_speed, ring_speed must be finite and > 0",
        /// `spread_ratio` (z) must be within [0, 1).
        SpreadRatio => c"glass: spread_ratio (z) must be within [0, 1)",
        /// `turn_limit` must be within [0, π].
        TurnLimit => c"glass: turn_limit must be within [0, pi]",
        /// `turn_delay` (T) must be finite and > 0.
        TurnDelay => c"glass: turn_delay (T) must be finite and > 0",
        /// `sector_angle` must be within (0, 2π] and `sector_radius` finite and > 0.
        Sector => c"glass: sector_angle must be within (0, 2 pi] and sector_radius finite and > 0",
        /// `tip_repulsion`, `crack_attraction`, `ring_adherence` must be finite and >= 0, `wander`
        /// finite and >= 0.
        Forces => c"glass: tip_repulsion, crack_attraction, ring_adherence, wander must be finite and >= 0",
        /// `max_cracks` must be within [1, 2²⁸] and `max_vertices` within [2, 2²⁸]; their
        /// memory must fit in the address space.
        Capacity => c"glass: max_cracks must be within [1, 2^28] and max_vertices within [2, 2^28], within memory",
    }
}

/// The largest `max_cracks` and `max_vertices` (2²⁸ = 268 435 456): vertices, edges and the
/// grids' entries (ten per vertex) are numbered in `u32` words.
pub const MAX_CAPACITY: u32 = 1 << 28;

/// The longest side a plate may have \[px\]: 2¹⁶. Positions are f32, so on a plate this size
/// they are 2⁻⁸ px apart or closer: finer than the shortest update of a crack tip (1/8 px) and
/// than the margin the sector queries allow for rounding (1/64 px), so every move lands where it
/// was planned. Much wider plates lose fragments: with the impact 320 px from the far end of a
/// 2²² × 640 px plate (positions 1/4 px apart), the fragments of 2 of seeds 1–3 missed
/// 3·10⁴ and 4·10⁴ px² (measured; 2²¹ px lost none over 24 plates).
pub const MAX_SIDE: f32 = 65_536.0;

/// The most time steps generation of one impact takes, whatever the speeds: 2¹⁵ (see
/// [`GlassParams::ring_speed`]). A crack of the paper's slowest speed, 5 px per step (3.5 with
/// Rand's z = 0.3), crosses even a plate of the largest side, 2¹⁶ px, within it.
pub const MAX_TIME_STEPS: u32 = 1 << 15;

/// Finite and ≥ 0.
fn non_negative(x: f32) -> bool {
    x.is_finite() && x >= 0.0
}

/// Finite and > 0.
fn positive(x: f32) -> bool {
    x.is_finite() && x > 0.0
}

impl GlassParams {
    /// Checks every field; the first wrong one is named.
    pub fn validate(&self) -> Result<(), GlassParamError> {
        use GlassParamError::*;
        let tau = 2.0 * core::f32::consts::PI;
        let [x, y] = self.impact;
        let checks = [
            ([self.width, self.height].iter().all(|v| (1.0..=MAX_SIDE).contains(v)), Size),
            (x.is_finite() && y.is_finite() && x > 0.0 && x < self.width && y > 0.0 && y < self.height, Impact),
            (self.radial_mean.is_finite() && (0.0..=10_000.0).contains(&self.radial_mean), RadialMean),
            (self.ring_threshold.is_finite(), RingThreshold),
            (
                [self.large_slope, self.large_offset, self.ring_slope, self.ring_offset]
                    .iter()
                    .all(|&v| non_negative(v)),
                CountFormula,
            ),
            (non_negative(self.ring_radius_slope) && non_negative(self.ring_radius_offset), RingRadius),
            ([self.large_speed, self.radial_speed, self.ring_speed].iter().all(|&v| positive(v)), Speed),
            (self.spread_ratio.is_finite() && (0.0..1.0).contains(&self.spread_ratio), SpreadRatio),
            (self.turn_limit.is_finite() && (0.0..=core::f32::consts::PI).contains(&self.turn_limit), TurnLimit),
            (positive(self.turn_delay), TurnDelay),
            (
                self.sector_angle.is_finite()
                    && self.sector_angle > 0.0
                    && self.sector_angle <= tau
                    && positive(self.sector_radius),
                Sector,
            ),
            (
                [self.tip_repulsion, self.crack_attraction, self.ring_adherence, self.wander]
                    .iter()
                    .all(|&v| non_negative(v)),
                Forces,
            ),
            (
                (1..=MAX_CAPACITY).contains(&self.max_cracks) && (2..=MAX_CAPACITY).contains(&self.max_vertices),
                Capacity,
            ),
        ];
        match checks.iter().find(|(ok, _)| !ok) {
            Some(&(_, error)) => Err(error),
            None => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_the_papers_and_valid() {
        let p = GlassParams::default();
        assert_eq!(p.validate(), Ok(()));
        assert_eq!((p.ring_threshold, p.large_slope, p.large_offset), (70.0, 0.0606, 3.293));
        assert_eq!(
            (p.ring_radius_slope, p.ring_radius_offset, p.turn_delay, p.spread_ratio),
            (0.470, 13.90, 10.0, 0.3)
        );
        assert_eq!((p.sector_radius, p.width, p.impact), (50.0, 640.0, [320.0, 320.0]));
    }

    #[test]
    fn every_bad_field_is_named() {
        type Spoil = fn(&mut GlassParams);
        let cases: [(Spoil, GlassParamError); 18] = [
            (|p| p.width = 0.0, GlassParamError::Size),
            (|p| p.width = 65_537.0, GlassParamError::Size),
            (|p| p.height = 1e20, GlassParamError::Size),
            (|p| p.height = f32::NAN, GlassParamError::Size),
            (|p| p.impact = [700.0, 10.0], GlassParamError::Impact),
            (|p| p.impact = [0.0, 10.0], GlassParamError::Impact),
            (|p| p.radial_mean = -1.0, GlassParamError::RadialMean),
            (|p| p.large_slope = f32::INFINITY, GlassParamError::CountFormula),
            (|p| p.ring_radius_offset = -1.0, GlassParamError::RingRadius),
            (|p| p.large_speed = 0.0, GlassParamError::Speed),
            (|p| p.spread_ratio = 1.0, GlassParamError::SpreadRatio),
            (|p| p.turn_limit = -0.1, GlassParamError::TurnLimit),
            (|p| p.turn_delay = 0.0, GlassParamError::TurnDelay),
            (|p| p.sector_radius = -5.0, GlassParamError::Sector),
            (|p| p.wander = f32::NAN, GlassParamError::Forces),
            (|p| p.max_vertices = 1, GlassParamError::Capacity),
            (|p| p.max_vertices = MAX_CAPACITY + 1, GlassParamError::Capacity),
            (|p| p.max_cracks = MAX_CAPACITY + 1, GlassParamError::Capacity),
        ];
        for (spoil, error) in cases {
            let mut p = GlassParams::default();
            spoil(&mut p);
            assert_eq!(p.validate(), Err(error), "{p:?}");
        }
    }
}
