//! Centre points (paper parameter 1): a triangular or square lattice with uniform or normal
//! jitter, or a uniform random layout, per hierarchy level, in the level's own frame (the
//! plane before the level's stretch).

use super::params::{SiteLayout, SkinParams};
use crate::geom::round_to_i64;
use crate::rng::{Rng, Spread, Stream};

/// Lattice indices reach this far outside the surface (non-periodic ids stay unique).
pub(super) const MARGIN: i64 = 64;

/// A centre point (opaque; caller memory for [`super::SkinBuffers`]): its position in the level's frame, its id (unique in the level, the same
/// for every periodic image) and which periodic image it is.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Site {
    /// Position of this image: `base + image · period`.
    pub(super) at: [f64; 2],
    /// Position of image (0, 0).
    pub(super) base: [f64; 2],
    pub(super) id: u32,
    pub(super) image: [i32; 2],
}

/// The centre-point lattice of one level.
#[derive(Clone, Copy, Debug)]
pub(super) struct Lattice {
    level: u32,
    seed: u64,
    layout: SiteLayout,
    spread: Spread,
    /// Largest jitter per axis as a fraction of the spacing.
    jitter: f64,
    /// Column and row spacing in the frame.
    pub(super) step: [f64; 2],
    /// Columns and rows over the surface (the period when periodic).
    pub(super) count: [i64; 2],
    /// The surface in the frame: (width / Sx, height / Sy).
    pub(super) period: [f64; 2],
    periodic: bool,
}

impl Lattice {
    /// The lattice of level `level` (validated parameters).
    pub(super) fn new(p: &SkinParams, level: usize) -> Lattice {
        let l = &p.level[level];
        let period = [f64::from(p.width) / f64::from(l.stretch[0]), f64::from(p.height) / f64::from(l.stretch[1])];
        let s = f64::from(l.spacing);
        let row = if p.layout == SiteLayout::Triangular { s * crate::scalar::sqrt(3.0) / 2.0 } else { s };
        let mut count = [round_to_i64(period[0] / s).max(1), round_to_i64(period[1] / row).max(1)];
        let mut step = [s, row];
        if p.periodic {
            // At least two centre points across each period: with one, a cell's only neighbours
            // along that axis are its own images, and the cells inside it no longer meet
            // exactly across the seam.
            count = [count[0].max(2), count[1].max(2)];
            if p.layout == SiteLayout::Triangular && count[1] % 2 == 1 {
                // Shifted rows alternate: an even number of rows tiles. (Saturating: a count
                // this large is refused by `SkinParams::memory`.)
                count[1] = count[1].saturating_add(1);
            }
            step = [period[0] / count[0] as f64, period[1] / count[1] as f64];
        } else {
            // Saturating: `as` saturates a huge period (a tiny stretch), and `memory` refuses it.
            count = [
                (libm::ceil(period[0] / step[0]) as i64).saturating_add(1),
                (libm::ceil(period[1] / step[1]) as i64).saturating_add(1),
            ];
        }
        let (spread, jitter) = match p.layout {
            SiteLayout::Random => (Spread::Uniform, 1.0),
            _ => (p.jitter, f64::from(p.jitter_ratio)),
        };
        Lattice {
            level: level as u32,
            seed: p.seed,
            layout: p.layout,
            spread,
            jitter,
            step,
            count,
            period,
            periodic: p.periodic,
        }
    }

    /// The site at lattice index (i, j), which may lie outside the surface (a periodic image,
    /// or beyond the edge of a non-periodic surface).
    // (Inlined on 64-bit targets: a division's test of each site in its box then reads the
    // position where it was worked out, and the whole site is stored only when kept.)
    #[cfg_attr(target_pointer_width = "64", inline(always))]
    pub(super) fn site(&self, i: i64, j: i64) -> Site {
        let (wi, wj, image) = if self.periodic {
            let (wi, wj) = (i.rem_euclid(self.count[0]), j.rem_euclid(self.count[1]));
            (wi, wj, [i.div_euclid(self.count[0]) as i32, j.div_euclid(self.count[1]) as i32])
        } else {
            (i, j, [0, 0])
        };
        let shift = if self.layout == SiteLayout::Triangular && wj.rem_euclid(2) == 1 { 0.5 } else { 0.0 };
        let columns = self.count[0] + 2 * MARGIN;
        let id = if self.periodic { wj * self.count[0] + wi } else { (wj + MARGIN) * columns + (wi + MARGIN) };
        let key = Stream::SiteJitter.key() ^ (u64::from(self.level) << 56) ^ (id as u64);
        let mut rng = Rng::from_key(self.seed, key);
        let mut jitter = || -> f64 {
            let half = 0.5 * self.jitter;
            match self.spread {
                Spread::Uniform => (2.0 * f64::from(rng.uniform_f32()) - 1.0) * half,
                // Normal with σ = half/3, redrawn until within ±half (as Rand does).
                Spread::Normal => loop {
                    let v = rng.normal() * half / 3.0;
                    if v.abs() <= half {
                        break v;
                    }
                },
            }
        };
        let (dx, dy) = (jitter(), jitter());
        let base = [(wi as f64 + 0.5 + shift + dx) * self.step[0], (wj as f64 + 0.5 + dy) * self.step[1]];
        let at = [base[0] + f64::from(image[0]) * self.period[0], base[1] + f64::from(image[1]) * self.period[1]];
        Site { at, base, id: id as u32, image }
    }

    /// How far a point of the plane can be from its nearest centre point, at most (the
    /// frame's units): `(1 + J)/2 · √(step₀² + step₁²)`, J the jitter ratio, plus a hundredth
    /// of a step for rounding.
    ///
    /// Proof: the strata `[i + s, i + s + 1] × [j, j + 1]` steps (s the row's shift, ½ on odd
    /// triangular rows, else 0) tile the plane, row by row. A point at `(i + s + u, j + v)`
    /// steps, u and v in [0, 1], lies in stratum (i, j), whose centre point lies at
    /// `(i + s + ½ + x, j + ½ + y)` with |x|, |y| ≤ J/2 (uniform jitter by construction,
    /// normal jitter redrawn until within it, random layout J = 1): per axis they are at most
    /// `(½ + J/2)` steps apart.
    pub(super) fn reach(&self) -> f64 {
        let diagonal = crate::scalar::sqrt(self.step[0] * self.step[0] + self.step[1] * self.step[1]);
        (0.5 + 0.5 * self.jitter + 0.01) * diagonal
    }

    /// The most columns on either side of a centre point's own whose centre points, in the
    /// row `dj` rows away, can lie within `radius` of it (the frame's units); None when none
    /// of that row can.
    ///
    /// Proof: centre points (i, j) and (i + di, j + dj) lie `dj + y' − y` row steps apart
    /// vertically and `di + s' − s + x' − x` column steps horizontally, each jitter |x|, |y| at
    /// most J/2 ([`Lattice::reach`]'s strata) and the row shifts s, s' differing by at most σ
    /// (½ between rows of unlike parity on a triangular lattice, whose period holds an even
    /// number of rows; else 0). So they are at least `dy = (|dj| − J)⁺` row steps and
    /// `(|di| − σ − J)⁺` column steps apart, and within `radius` only if dy·step₁ ≤ radius and
    /// |di| ≤ σ + J + √(radius² − (dy·step₁)²) / step₀.
    pub(super) fn columns_within(&self, dj: i64, radius: f64) -> Option<i64> {
        let dy = (dj.unsigned_abs() as f64 - self.jitter).max(0.0) * self.step[1];
        if dy > radius {
            return None;
        }
        let sigma = if self.layout == SiteLayout::Triangular && dj % 2 != 0 { 0.5 } else { 0.0 };
        // (`as` saturates a huge count: the caller caps it.)
        Some(libm::floor(sigma + self.jitter + crate::scalar::sqrt(radius * radius - dy * dy) / self.step[0]) as i64)
    }

    /// How many lattice indices (i, j) within `range` (inclusive: i0, j0, i1, j1) have a centre
    /// point that can lie in the frame box [min, max] (jitter included, each row's shift
    /// counted; a hundredth of a step covers rounding). Not periodic images: the lattice's own
    /// indices.
    pub(super) fn count_over(&self, min: [f64; 2], max: [f64; 2], range: [i64; 4]) -> i64 {
        // Site (i, j) lies in [i + s + ½ − J/2, i + s + ½ + J/2] × [j + ½ − J/2, j + ½ + J/2]
        // steps. (`as` saturates far-off boxes; the range then bounds them.)
        let half = 0.5 * self.jitter + 0.01;
        let span = |lo: f64, hi: f64, step: f64, shift: f64, from: i64, to: i64| {
            let first = (libm::ceil(lo / step - 0.5 - shift - half) as i64).max(from);
            let last = (libm::floor(hi / step - 0.5 - shift + half) as i64).min(to);
            last.saturating_sub(first).saturating_add(1).max(0)
        };
        let rows = self.indices_over(min, max);
        let (j0, j1) = (rows[1].max(range[1]), rows[3].min(range[3]));
        if j1 < j0 {
            return 0;
        }
        // Rows j0..=j1: the odd ones shifted by half a step on a triangular lattice.
        let odd = (j1 + 1).div_euclid(2) - j0.div_euclid(2);
        let even = j1 - j0 + 1 - odd;
        let shifted = if self.layout == SiteLayout::Triangular { 0.5 } else { 0.0 };
        let columns = |shift: f64| span(min[0], max[0], self.step[0], shift, range[0], range[2]);
        even.saturating_mul(columns(0.0)).saturating_add(odd.saturating_mul(columns(shifted)))
    }

    /// The lattice indices (i0, j0, i1, j1) of every site that can lie in the frame box
    /// [min, max] (jitter included).
    pub(super) fn indices_over(&self, min: [f64; 2], max: [f64; 2]) -> [i64; 4] {
        // Site (i, j) lies in [i + 1/2 − J, i + 1 + J] × [j + 1/2 − J, j + 1/2 + J] steps, J
        // half the jitter ratio (odd triangular rows are shifted by half a step); a hundredth
        // of a step covers rounding.
        let half = 0.5 * self.jitter + 0.01;
        let lo = |v: f64, step: f64, reach: f64| libm::ceil(v / step - reach) as i64;
        let hi = |v: f64, step: f64| libm::floor(v / step - 0.5 + half) as i64;
        let mut r = [
            lo(min[0], self.step[0], 1.0 + half),
            lo(min[1], self.step[1], 0.5 + half),
            hi(max[0], self.step[0]),
            hi(max[1], self.step[1]),
        ];
        if !self.periodic {
            r[0] = r[0].max(-MARGIN);
            r[1] = r[1].max(-MARGIN);
            r[2] = r[2].min(self.count[0] + MARGIN - 1);
            r[3] = r[3].min(self.count[1] + MARGIN - 1);
        }
        r
    }
}
