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
    pub(super) height: [f32; SAMPLES + 1],
    pub(super) slope: [f32; SAMPLES + 1],
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

impl ProfileTable {
    /// Samples `profile` (validated: x' starts at 0 and never decreases).
    pub(super) fn new(profile: &Profile) -> ProfileTable {
        let points = profile.used();
        let end = points[points.len() - 1][0];
        let mut table =
            ProfileTable { end, scale: SAMPLES as f32 / end, height: [0.0; SAMPLES + 1], slope: [0.0; SAMPLES + 1] };
        for k in 0..=SAMPLES {
            let x = f64::from(end) * k as f64 / SAMPLES as f64;
            // The segment whose x' range holds x (the last one that starts at or before it).
            let segments = points.len() / 3;
            let mut s = 0;
            while s + 1 < segments && f64::from(points[3 * (s + 1)][0]) <= x {
                s += 1;
            }
            let c = &points[3 * s..3 * s + 4];
            let px = [c[0][0], c[1][0], c[2][0], c[3][0]].map(f64::from);
            let pz = [c[0][1], c[1][1], c[2][1], c[3][1]].map(f64::from);
            // x'(t) is monotone (control x' never decrease): bisection finds t.
            let (mut lo, mut hi) = (0.0f64, 1.0f64);
            for _ in 0..48 {
                let mid = 0.5 * (lo + hi);
                if bezier(px, mid) < x {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            let t = 0.5 * (lo + hi);
            let dx = bezier_derivative(px, t);
            let dz = bezier_derivative(pz, t);
            table.height[k] = bezier(pz, t) as f32;
            // Where the curve is vertical in x' (dx = 0) the slope is the limit of its neighbours;
            // clamp it to a steep but finite value.
            table.slope[k] = if dx.abs() > 1e-9 { (dz / dx).clamp(-1e3, 1e3) as f32 } else { 0.0 };
        }
        // Fill vertical tangents with their neighbours' slope.
        for k in 0..=SAMPLES {
            if table.slope[k] == 0.0 {
                let neighbour = if k > 0 { table.slope[k - 1] } else { table.slope[(k + 1).min(SAMPLES)] };
                let dz =
                    (table.height[k.min(SAMPLES - 1) + 1] - table.height[k.min(SAMPLES - 1)]) * SAMPLES as f32 / end;
                table.slope[k] = if dz != 0.0 { dz } else { neighbour };
            }
        }
        table
    }

    /// Height and slope at `x` ∈ [0, end], linearly interpolated.
    #[inline]
    pub(super) fn at(&self, x: f32) -> (f32, f32) {
        let f = (x * self.scale).clamp(0.0, SAMPLES as f32);
        let k = (f as usize).min(SAMPLES - 1);
        let w = f - k as f32;
        let lerp = |v: &[f32; SAMPLES + 1]| v[k] + (v[k + 1] - v[k]) * w;
        (lerp(&self.height), lerp(&self.slope))
    }
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
}
