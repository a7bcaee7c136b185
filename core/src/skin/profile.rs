//! The cross-section of a ridge (Ishii et al. §3.2.1, Fig. 6–7): a chain of cubic Bézier
//! segments in the body plane, sampled once into a table of height and slope over x'.

use super::params::Profile;

/// Table intervals over x' ∈ [0, x'_end].
pub(super) const SAMPLES: usize = 256;

/// A profile sampled at `SAMPLES + 1` evenly spaced x': height z'(x') and slope dz'/dx'.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct ProfileTable {
    /// x' at the polygon's edge (the last control point's x').
    pub(super) end: f32,
    /// SAMPLES / end.
    scale: f32,
    /// Height and slope at each sample, side by side so that a lookup reads one stretch of
    /// memory.
    samples: [[f32; 2]; SAMPLES + 1],
}

impl Default for ProfileTable {
    /// A flat table (every sample 0), until one is sampled.
    fn default() -> Self {
        ProfileTable { end: 0.0, scale: 0.0, samples: [[0.0; 2]; SAMPLES + 1] }
    }
}

/// A cubic Bézier coordinate at t: B(t) = (1−t)³p0 + 3(1−t)²t p1 + 3(1−t)t² p2 + t³p3.
fn bezier(p: [f64; 4], t: f64) -> f64 {
    let s = 1.0 - t;
    s * s * s * p[0] + 3.0 * s * s * t * p[1] + 3.0 * s * t * t * p[2] + t * t * t * p[3]
}

/// dB/dt.
fn bezier_derivative(p: [f64; 4], t: f64) -> f64 {
    let s = 1.0 - t;
    3.0 * s * s * (p[1] - p[0]) + 6.0 * s * t * (p[2] - p[1]) + 3.0 * t * t * (p[3] - p[2])
}

/// The coordinates `axis` (0 for x', 1 for z') of segment `s`'s four control points.
fn controls(points: &[[f32; 2]], s: usize, axis: usize) -> [f64; 4] {
    let c = &points[3 * s..3 * s + 4];
    [c[0][axis], c[1][axis], c[2][axis], c[3][axis]].map(f64::from)
}

impl ProfileTable {
    /// Samples `profile` (validated: x' starts at 0 and never decreases).
    #[cfg(test)]
    pub(super) fn new(profile: &Profile) -> ProfileTable {
        let mut table = ProfileTable::default();
        for k in 0..=SAMPLES {
            let (s, t) = ProfileTable::place(profile, k);
            table.sample_at(profile, k, s, t);
        }
        table.finish(profile);
        table
    }

    /// Where sample `k` lies on `profile`'s curve: its segment and its Bézier parameter t.
    /// Found from the control points' x' alone, so profiles that differ only in height (as a
    /// hierarchy's levels often do, see [`ProfileTable::shares_places`]) place their samples
    /// alike. One sample at a time, so that no array of them is on the stack.
    pub(super) fn place(profile: &Profile, k: usize) -> (usize, f64) {
        let points = profile.used();
        let end = points[points.len() - 1][0];
        let segments = points.len() / 3;
        // The sample's x and segment (the last one that starts at or before it).
        let x = f64::from(end) * k as f64 / SAMPLES as f64;
        let mut s = 0;
        while s + 1 < segments && f64::from(points[3 * (s + 1)][0]) <= x {
            s += 1;
        }
        // x'(t) is monotone (control x' never decrease): bisection finds t.
        let c = controls(points, s, 0);
        let (mut lo, mut hi) = (0.0f64, 1.0f64);
        for _ in 0..48 {
            let mid = 0.5 * (lo + hi);
            let below = bezier(c, mid) < x;
            lo = if below { mid } else { lo };
            hi = if below { hi } else { mid };
        }
        (s, 0.5 * (lo + hi))
    }

    /// Whether `a` and `b` place their samples alike: the same segments and control x'.
    pub(super) fn shares_places(a: &Profile, b: &Profile) -> bool {
        let (p, q) = (a.used(), b.used());
        p.len() == q.len() && p.iter().zip(q).all(|(p, q)| p[0].to_bits() == q[0].to_bits())
    }

    /// Sets sample `k` of `profile`, placed at parameter `t` of segment `s` (from
    /// [`ProfileTable::place`] of this profile or of one that shares its places).
    pub(super) fn sample_at(&mut self, profile: &Profile, k: usize, s: usize, t: f64) {
        let points = profile.used();
        let pz = controls(points, s, 1);
        let dx = bezier_derivative(controls(points, s, 0), t);
        let dz = bezier_derivative(pz, t);
        // Where the curve is vertical in x' (dx = 0) the slope is the limit of its neighbours;
        // clamp it to a steep but finite value.
        let slope = if dx.abs() > 1e-9 { (dz / dx).clamp(-1e3, 1e3) as f32 } else { 0.0 };
        self.samples[k] = [bezier(pz, t) as f32, slope];
    }

    /// Completes a table whose every sample `sample_at` has set.
    pub(super) fn finish(&mut self, profile: &Profile) {
        let points = profile.used();
        let end = points[points.len() - 1][0];
        // Fill vertical tangents with their neighbours' slope.
        let samples = &mut self.samples;
        for k in 0..=SAMPLES {
            if samples[k][1] == 0.0 {
                let neighbour = if k > 0 { samples[k - 1][1] } else { samples[(k + 1).min(SAMPLES)][1] };
                let dz = (samples[k.min(SAMPLES - 1) + 1][0] - samples[k.min(SAMPLES - 1)][0]) * SAMPLES as f32 / end;
                samples[k][1] = if dz != 0.0 { dz } else { neighbour };
            }
        }
        (self.end, self.scale) = (end, SAMPLES as f32 / end);
    }

    /// Height and slope at `x` ∈ [0, end], linearly interpolated: what `interval`, `ends` and
    /// `blend` give in parts.
    #[cfg(test)]
    pub(super) fn at(&self, x: f32) -> (f32, f32) {
        let f = (x * self.scale).clamp(0.0, SAMPLES as f32);
        // f rounded down, the last interval for f = SAMPLES.
        let k = (f as u32).min(SAMPLES as u32 - 1);
        blend(self.ends(k), f - k as f32)
    }

    /// The lookup of height and slope at `x`, part one (then `ends` and `blend`), split so that
    /// a batch of lookups does the arithmetic of each part together: the sample interval `x`
    /// falls in and the weight of its far end (the interval is f = x·SAMPLES/end, clamped to
    /// [0, SAMPLES], rounded down; the last one for f = SAMPLES). Only
    /// comparisons, basic arithmetic and bit casts, which vectorise: for 0 <= f < 2^23,
    /// f + 2^23 is 2^23 plus f rounded to an integer, exactly, and that integer is in the low
    /// bits of the sum.
    #[inline(always)]
    pub(super) fn interval(&self, x: f32) -> (u32, f32) {
        const ROUND: f32 = 8_388_608.0;
        let f = (x * self.scale).clamp(0.0, SAMPLES as f32);
        let near = (f + ROUND) - ROUND;
        let below = if near > f { near - 1.0 } else { near };
        let k = if below < SAMPLES as f32 { below } else { (SAMPLES - 1) as f32 };
        ((k + ROUND).to_bits().wrapping_sub(ROUND.to_bits()), f - k)
    }

    /// The lowest and highest sampled height.
    pub(super) fn range(&self) -> [f32; 2] {
        self.samples.iter().fold([f32::INFINITY, f32::NEG_INFINITY], |[lo, hi], s| [lo.min(s[0]), hi.max(s[0])])
    }

    /// Height and slope at both ends of interval `k` (what [`blend`] weighs), apart so that a
    /// batch of lookups reads its samples in one loop and does its arithmetic in another.
    #[inline(always)]
    pub(super) fn ends(&self, k: u32) -> [[f32; 2]; 2] {
        // k < SAMPLES already; the mask shows it.
        const { assert!(SAMPLES.is_power_of_two()) };
        let k = k as usize & (SAMPLES - 1);
        [self.samples[k], self.samples[k + 1]]
    }
}

/// Height and slope at weight `w` between the ends of an interval ([`ProfileTable::ends`]).
#[inline(always)]
pub(super) fn blend([[h0, s0], [h1, s1]]: [[f32; 2]; 2], w: f32) -> (f32, f32) {
    (h0 + (h1 - h0) * w, s0 + (s1 - s0) * w)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::skin::params::PROFILE_13B;

    #[test]
    fn the_table_follows_the_curve() {
        // A straight line as a Bézier: z' = 3 − 0.3·x'.
        let line = Profile::cubic([[0.0, 3.0], [10.0 / 3.0, 2.0], [20.0 / 3.0, 1.0], [10.0, 0.0]]);
        let t = ProfileTable::new(&line);
        for x in [0.0, 1.3, 5.0, 9.99, 10.0] {
            let (z, s) = t.at(x);
            assert!((z - (3.0 - 0.3 * x)).abs() < 1e-4 && (s + 0.3).abs() < 1e-4, "{x}: {z} {s}");
        }
        // Fig. 13 b: flat top, falls to 0 at the edge.
        let t = ProfileTable::new(&PROFILE_13B);
        assert!((t.at(0.0).0 - 3.0).abs() < 1e-5 && t.at(3.0).1.abs() < 1e-4);
        assert!(t.at(10.0).0.abs() < 1e-5 && t.at(9.8).1 < -2.0);
    }

    #[test]
    fn profiles_with_the_same_abscissae_share_their_places() {
        // Fig. 19's levels differ only in height: each one's table from the first's places
        // is its table from its own.
        let fig19 = crate::skin::preset("fig19a").expect("a preset");
        let levels = fig19.level.map(|l| l.profile);
        let placed = |profile: &Profile, by: &Profile| {
            let mut table = ProfileTable::default();
            for k in 0..=SAMPLES {
                let (s, t) = ProfileTable::place(by, k);
                table.sample_at(profile, k, s, t);
            }
            table.finish(profile);
            table
        };
        for profile in &levels[..fig19.levels as usize] {
            assert!(ProfileTable::shares_places(&levels[0], profile));
            assert_eq!(placed(profile, &levels[0]), ProfileTable::new(profile));
        }
        // Moving one control point along x' (or adding a segment) places them elsewhere.
        let mut moved = levels[1];
        moved.points[2][0] = 8.0;
        assert!(!ProfileTable::shares_places(&levels[1], &moved));
        assert_ne!(placed(&moved, &levels[0]), ProfileTable::new(&moved));
        // (A second segment after the same first one: the x' agree as far as both go.)
        let two = Profile::two(
            [[0.0, 2.0], [5.0, 2.0], [9.0, 1.5], [10.0, 0.5]],
            [[10.0, 0.5], [11.0, 0.3], [12.0, 0.1], [13.0, 0.0]],
        );
        assert!(!ProfileTable::shares_places(&levels[1], &two));
    }

    #[test]
    fn the_lookup_in_two_parts_is_the_lookup() {
        let t = ProfileTable::new(&PROFILE_13B);
        let samples = (0..=SAMPLES).map(|k| k as f32 / t.scale);
        let near = samples.clone().flat_map(|x| [x, f32::from_bits(x.to_bits() + 1), x - 1e-6, x + 1e-6]);
        for x in near.chain((-1000..=11_000).map(|i| i as f32 * 1e-3)).chain([-1.0, 10.0, 11.0, 1e9]) {
            let (k, w) = t.interval(x);
            let (a, b) = (t.at(x), blend(t.ends(k), w));
            assert_eq!((a.0.to_bits(), a.1.to_bits()), (b.0.to_bits(), b.1.to_bits()), "{x}");
        }
    }
}
