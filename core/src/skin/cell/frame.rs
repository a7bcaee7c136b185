//! A level's frame and the exact corners of the cells (Ishii et al. §3.1): where two or three
//! centre points' bisectors meet, computed in a frame and an order that depend on the sites'
//! ids alone, and rounded to the level's fixed point, so both cells sharing a corner get it
//! bit for bit (see the cell module's docs).

use super::super::params::{LevelParams, MAX_PERTURBATION_DEPTH};
use super::super::sites::Site;
use crate::geom::round_to_i64;

/// The level a cell is built in: frame (the plane before the level's stretch) and periods.
#[derive(Clone, Copy, Debug)]
pub(in crate::skin) struct Frame {
    pub(in crate::skin) level: u32,
    pub(in crate::skin) seed: u64,
    pub(in crate::skin) stretch: [f64; 2],
    /// The surface's period in the frame.
    pub(in crate::skin) period: [f64; 2],
    /// The surface's period in fixed point.
    pub(in crate::skin) world_period: [i64; 2],
    /// Fractional bits of the stored fixed point (the finest level's).
    pub(in crate::skin) shift: u32,
    /// Fractional bits this level rounds its own points to.
    pub(in crate::skin) bits: u32,
    /// 2^bits, and 1 / (2^shift · stretch) per axis.
    pub(super) own_unit: f64,
    pub(super) to_frame: [f64; 2],
    /// 2^shift · stretch per axis.
    pub(super) from_frame: [f64; 2],
    pub(in crate::skin) perturbation: f64,
    /// A·2^(−n·h) for subdivision n = 1..=depth (index n − 1), of the perturbation's V.
    pub(super) amplitude: [f64; MAX_PERTURBATION_DEPTH as usize],
    /// The farthest a perturbed point can move off its edge's line, per unit of the edge's
    /// length: 3·Σ A·2^(−n·h) over the subdivisions (parameter 2's V with Rnd within ±3), and a
    /// thousandth more for rounding.
    pub(super) reach: f64,
    pub(in crate::skin) depth: u32,
}

impl Frame {
    pub(in crate::skin) fn new(level: usize, l: &LevelParams, seed: u64, size: [u32; 2], levels: u32) -> Frame {
        let stretch = [f64::from(l.stretch[0]), f64::from(l.stretch[1])];
        let shift = fixed_point_bits(levels);
        let amplitude = core::array::from_fn(|n| {
            f64::from(l.perturbation) * libm::exp2(-((n + 1) as f64) * f64::from(l.perturbation_decay))
        });
        Frame {
            level: level as u32,
            seed,
            stretch,
            period: [f64::from(size[0]) / stretch[0], f64::from(size[1]) / stretch[1]],
            world_period: [i64::from(size[0]) << shift, i64::from(size[1]) << shift],
            shift,
            bits: BASE_BITS + EDGE_BITS * level as u32,
            own_unit: (1u64 << (BASE_BITS + EDGE_BITS * level as u32)) as f64,
            to_frame: [1.0 / ((1u64 << shift) as f64 * stretch[0]), 1.0 / ((1u64 << shift) as f64 * stretch[1])],
            from_frame: [(1u64 << shift) as f64 * stretch[0], (1u64 << shift) as f64 * stretch[1]],
            perturbation: f64::from(l.perturbation),
            amplitude,
            reach: 3.0 * amplitude[..l.perturbation_depth as usize].iter().sum::<f64>() * 1.001,
            depth: l.perturbation_depth,
        }
    }

    /// A site's position relative to the image of `reference` (the frame every shared
    /// computation is done in).
    pub(super) fn relative(&self, site: &Site, reference: &Site) -> [f64; 2] {
        // (In the same image, nearly always: its base, as adding 0·period leaves it, the period
        // being finite and no base −0.)
        if site.image == reference.image {
            return site.base;
        }
        let d = [site.image[0] - reference.image[0], site.image[1] - reference.image[1]];
        [site.base[0] + f64::from(d[0]) * self.period[0], site.base[1] + f64::from(d[1]) * self.period[1]]
    }

    /// A frame position relative to `reference`'s image, in fixed point (rounded to this
    /// level's resolution). A position past `i64`'s range (a Voronoi vertex of nearly
    /// collinear centres, far off a degenerately stretched surface) saturates there, image
    /// offset included (the skin fuzz target's finding 15).
    pub(super) fn fixed(&self, at: [f64; 2], reference: &Site) -> [i64; 2] {
        self.fixed_in(at, reference.image)
    }

    /// [`Frame::fixed`] relative to the periodic image `image`.
    #[inline(always)]
    pub(super) fn fixed_in(&self, at: [f64; 2], image: [i32; 2]) -> [i64; 2] {
        // (Below 64: `shift` is at most 44 and `bits` at least 8.)
        let s = self.shift - self.bits;
        let q = |k: usize| {
            let world = round_to_i64(at[k] * self.stretch[k] * self.own_unit);
            let w = world << s;
            if w >> s == world {
                // (Nearly every site is image 0: no offset to add.)
                match image[k] {
                    0 => w,
                    image => w.saturating_add(i64::from(image).saturating_mul(self.world_period[k])),
                }
            } else if world < 0 {
                i64::MIN
            } else {
                i64::MAX
            }
        };
        [q(0), q(1)]
    }

    /// A fixed-point point in the frame, relative to `reference`'s image.
    pub(super) fn unfixed(&self, p: [i64; 2], reference: &Site) -> [f64; 2] {
        // (Nearly every site is image 0: no offset to take off.)
        if reference.image == [0, 0] {
            return self.in_frame(p);
        }
        let u = |k: usize| {
            let local = match reference.image[k] {
                0 => p[k],
                image => p[k].saturating_sub(i64::from(image).saturating_mul(self.world_period[k])),
            };
            local as f64 * self.to_frame[k]
        };
        [u(0), u(1)]
    }

    /// The site's position in fixed point.
    pub(in crate::skin) fn site_fixed(&self, site: &Site) -> [i64; 2] {
        self.fixed(site.base, site)
    }

    /// How far (1/256 px, in fixed point) the test that keeps a perturbed edge inside its
    /// parent looks beyond the edge's box.
    pub(super) fn inside_slack(&self) -> i64 {
        1 << (self.shift - BASE_BITS)
    }

    /// A fixed-point point in this frame, absolute.
    pub(in crate::skin) fn in_frame(&self, p: [i64; 2]) -> [f64; 2] {
        [p[0] as f64 * self.to_frame[0], p[1] as f64 * self.to_frame[1]]
    }
}

/// Fractional bits of level 0's own points.
pub(super) const BASE_BITS: u32 = 8;
/// Bits of the parameter a corner on a parent's edge is rounded to.
pub(super) const EDGE_BITS: u32 = 12;

/// Fractional bits of the fixed point a skin of `levels` levels is stored in.
pub(in crate::skin) const fn fixed_point_bits(levels: u32) -> u32 {
    BASE_BITS + EDGE_BITS * (levels - 1)
}

/// A corner computed the same way by every cell that has it: its frame position relative to
/// the periodic image `image` (of the site it was computed from), and its fixed-point
/// position.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Corner {
    pub(super) at: [f64; 2],
    pub(super) image: [i32; 2],
    pub(super) fixed: [i64; 2],
}

/// The two sites ordered by (id, image): the first is the one whose frame and direction an
/// edge between them is computed in.
pub(super) fn sorted2<'s>(a: &'s Site, b: &'s Site) -> (&'s Site, &'s Site) {
    // (Ids first; the images, in order, only between images of one site.)
    let first = if a.id == b.id { (a.image[0], a.image[1]) <= (b.image[0], b.image[1]) } else { a.id < b.id };
    if first { (a, b) } else { (b, a) }
}

/// The circumcentre of three sites (a Voronoi vertex), in the frame of the lowest id.
pub(super) fn circumcentre(f: &Frame, a: &Site, b: &Site, c: &Site) -> Corner {
    // Ordered by (id, image), in three exchanges.
    let (a, b) = sorted2(a, b);
    let (b, c) = sorted2(b, c);
    let (a, b) = sorted2(a, b);
    let r = a;
    let (p, q) = (f.relative(b, r), f.relative(c, r));
    let o = r.base;
    let (bx, by, cx, cy) = (p[0] - o[0], p[1] - o[1], q[0] - o[0], q[1] - o[1]);
    let d = 2.0 * (bx * cy - by * cx);
    let (b2, c2) = (bx * bx + by * by, cx * cx + cy * cy);
    let at = [o[0] + (cy * b2 - by * c2) / d, o[1] + (bx * c2 - cx * b2) / d];
    Corner { at, image: r.image, fixed: f.fixed(at, r) }
}

/// Where the bisector of `a` and `b` meets the parent's edge from `p` to `q`: at a parameter
/// rounded to 1/2^12 of the edge, so that the corner lies exactly on it.
pub(super) fn bisector_meets_edge(f: &Frame, a: &Site, b: &Site, p: [i64; 2], q: [i64; 2]) -> Corner {
    let (lo, hi) = sorted2(a, b);
    let (x, y) = (lo.base, f.relative(hi, lo));
    let (pf, qf) = (f.unfixed(p, lo), f.unfixed(q, lo));
    let d = [y[0] - x[0], y[1] - x[1]];
    let m = [0.5 * (x[0] + y[0]), 0.5 * (x[1] + y[1])];
    let e = [qf[0] - pf[0], qf[1] - pf[1]];
    let t = ((m[0] - pf[0]) * d[0] + (m[1] - pf[1]) * d[1]) / (e[0] * d[0] + e[1] * d[1]);
    let t = if t.is_finite() { t.clamp(0.0, 1.0) } else { 0.0 };
    let fixed = if f.level == 0 {
        // The parent is the surface (or a box around a periodic centre): axis-aligned edges,
        // so the corner is on the edge when its constant coordinate is copied.
        let mut x = f.fixed([pf[0] + t * e[0], pf[1] + t * e[1]], lo);
        for k in 0..2 {
            if p[k] == q[k] {
                x[k] = p[k];
            }
        }
        x
    } else {
        // The parent's points are multiples of 2^(shift − bits + EDGE_BITS): exact division.
        let steps = 1i64 << EDGE_BITS;
        let k = round_to_i64(t * steps as f64).clamp(0, steps);
        [p[0] + k * ((q[0] - p[0]) >> EDGE_BITS), p[1] + k * ((q[1] - p[1]) >> EDGE_BITS)]
    };
    Corner { at: f.unfixed(fixed, lo), image: lo.image, fixed }
}
