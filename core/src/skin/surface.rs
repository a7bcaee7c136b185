//! Height, normal and cell maps (Ishii et al. §3.2.1–3.2.2, Fig. 5–7 and 10), written once over
//! the [`Scalar`] trait.
//!
//! For a pixel p in a cell with centre p0, x' runs from p0 through p to the outline: the
//! fraction u = |p − p0| / |b − p0| of the way to the boundary point b. Inside the fan
//! triangle (p0, v_i, v_i+1) that is u = (p − p0)·g_i, with g_i the edge's normal divided by
//! its distance from p0. The height is the profile z'(x'_end·u'), where the roundness ratio
//! ρ blends u with the circular u_c = min(1, |p − p0| / apothem): u' = (1 − ρ)·u + ρ·u_c. At
//! ρ = 0 the contours are scaled copies of the polygon, at ρ = 1 circles inscribed in each
//! edge (our reading of Fig. 12, which moves the control points along an arc towards the
//! middle of each edge; the paper gives no formula). The level's normal
//! is the profile's normal in the x'z' plane, turned to the ray's direction, with z = 1; the
//! surface's normal sums the levels' x and y (Fig. 10).
//!
//! Pixels go through in batches, a plain loop per step, so that the processor overlaps many
//! pixels and most steps handle several at once: a cell's pixels find their fan triangles
//! (by pseudo-angle, the same ones as a binary search over the corners' angles), then the
//! pixels of cells of one level get their profile coordinate and normal factor, then their
//! profile samples.

use core::cmp::Ordering;

use super::cell::MAX_OUTLINE;
use super::profile::ProfileTable;
use super::{MAX_LEVELS, Skin, SkinCell, SkinError};
use crate::geom::pseudo_angle;
use crate::scalar::Scalar;

/// The maps to write; each is optional and `width × height` long, row-major.
#[derive(Default)]
pub struct SkinLayers<'o> {
    /// Height, the sum over levels of the profile heights (profile units).
    pub height: Option<&'o mut [f32]>,
    /// Unit tangent-space normal (x right, y up, z out of the surface), as in OpenGL normal
    /// maps.
    pub normal: Option<&'o mut [[f32; 3]]>,
    /// For each pixel, the index in [`Skin::cells`] of its cell at `cell_level`.
    pub cell: Option<&'o mut [u32]>,
    /// The level `cell` is taken from.
    pub cell_level: u32,
}

/// Per outline edge of the cell being drawn: g (so that u = (p − p0)·g), 1 / apothem, and
/// the pseudo-angle of the edge's first vertex seen from the centre.
#[derive(Clone, Copy, Default)]
struct Wedge {
    g: [f32; 2],
    inverse_apothem: f32,
    angle: f32,
}

/// Wedges a render keeps: one per outline edge and one at the front (see [`Fan`]).
const SLOTS: usize = MAX_OUTLINE + 1;

/// A cell's wedges: `slots[1..=n]` from the corner of smallest angle on, and `slots[0]` the
/// last one again. A pixel in direction `a` (a pseudo-angle) lies in the wedge its ray leaves
/// by, the last one whose first corner's angle is at most `a`, cyclically: `slots[k]` with k
/// the number of wedges whose angle is at most `a`. (For a cell star-shaped around its
/// centre, as Voronoi cells and their perturbations mostly are, the angles ascend and k is a
/// binary search's answer.)
struct Fan<'w> {
    slots: &'w [Wedge],
    /// Whether the angles ascend: then k is also the count of angles at most `a`.
    sorted: bool,
}

/// Fans of up to this many wedges count their angles below a pixel's (in steps that handle
/// several pixels at once) instead of searching them.
const COUNTED: usize = 48;

/// A cell's pixels whose wedges are looked up together.
const BATCH: usize = 64;

/// Outline edges whose wedges are made together.
const EDGES: usize = 8;

/// Pixels (of cells of one level) whose heights and normals are evaluated together.
const QUEUE: usize = 128;

/// Pixels on their way to the maps, a field per array so that each step is a plain loop: first
/// the pixels of the cell being drawn (`len`), then, with their wedges found, those of any
/// cells of its level (`ready`). Steps that handle several pixels at once run over whole
/// groups; the lanes past the pixels hold stale but finite values.
struct Batch<S> {
    len: usize,
    /// Index in the maps (and four spare lanes for the groups of four that fill them).
    index: [u32; BATCH + 4],
    /// Offset from the centre in pixels, its pseudo-angle, and k in [`Fan`].
    dx: [f32; BATCH + 4],
    dy: [f32; BATCH + 4],
    angle: [f32; BATCH],
    wedge: [u32; BATCH],
    ready: usize,
    /// Index in the maps.
    ready_index: [u32; QUEUE],
    /// u in the pixel's wedge, and the offset in apothems.
    u: [f32; QUEUE],
    qx: [f32; QUEUE],
    qy: [f32; QUEUE],
    /// The profile's sample interval and the weight of its far end at the pixel's x', and the
    /// factor that turns the profile's slope into the normal's x and y.
    interval: [u32; QUEUE],
    weight: [f32; QUEUE],
    lean: [S; QUEUE],
}

/// Where the maps a render writes go.
trait Sink {
    /// Whether heights or normals are wanted (else only the cell map is drawn).
    const SHADES: bool;
    /// Whether normals are wanted.
    const NORMALS: bool;
    /// Adds one level's height `z` and normal x/y `slope` to pixel `i`.
    fn add(&mut self, i: usize, z: f32, slope: [f32; 2]);
}

/// No height or normal map.
struct NoMaps;

impl Sink for NoMaps {
    const SHADES: bool = false;
    const NORMALS: bool = false;
    fn add(&mut self, _: usize, _: f32, _: [f32; 2]) {}
}

/// Heights only.
struct Heights<'o>(&'o mut [f32]);

impl Sink for Heights<'_> {
    const SHADES: bool = true;
    const NORMALS: bool = false;
    #[inline]
    fn add(&mut self, i: usize, z: f32, _: [f32; 2]) {
        self.0[i] += z;
    }
}

/// Normals only.
struct Normals<'o>(&'o mut [[f32; 3]]);

impl Sink for Normals<'_> {
    const SHADES: bool = true;
    const NORMALS: bool = true;
    #[inline]
    fn add(&mut self, i: usize, _: f32, slope: [f32; 2]) {
        self.0[i][0] += slope[0];
        self.0[i][1] += slope[1];
    }
}

/// Heights and normals.
struct Both<'o>(&'o mut [f32], &'o mut [[f32; 3]]);

impl Sink for Both<'_> {
    const SHADES: bool = true;
    const NORMALS: bool = true;
    #[inline]
    fn add(&mut self, i: usize, z: f32, slope: [f32; 2]) {
        self.0[i] += z;
        self.1[i][0] += slope[0];
        self.1[i][1] += slope[1];
    }
}

/// What every pixel of one level shares.
struct Ridge<'t, S> {
    table: &'t ProfileTable,
    end: S,
    roundness: S,
    /// 1 − roundness.
    flat: S,
}

impl<S: Scalar> Batch<S> {
    fn new() -> Self {
        Batch {
            len: 0,
            index: [0; BATCH + 4],
            dx: [0.0; BATCH + 4],
            dy: [0.0; BATCH + 4],
            angle: [0.0; BATCH],
            wedge: [0; BATCH],
            ready: 0,
            ready_index: [0; QUEUE],
            u: [0.0; QUEUE],
            qx: [0.0; QUEUE],
            qy: [0.0; QUEUE],
            interval: [0; QUEUE],
            weight: [0.0; QUEUE],
            lean: [S::ZERO; QUEUE],
        }
    }

    /// Queues the pixels `x0..x1` of row `y` (as the outline places them), `i0..` in the maps,
    /// of the cell centred at `centre` (pixels), with fan `fan`.
    #[inline]
    fn span<K: Sink>(&mut self, ridge: &Ridge<S>, fan: &Fan, sink: &mut K, centre: [f32; 2], row: [i64; 3], i0: usize) {
        let [y, mut x0, x1] = row;
        let mut i0 = i0;
        let dy = (y as f32 + 0.5) - centre[1];
        while x0 < x1 {
            if self.len == BATCH {
                self.locate(ridge, fan, sink);
            }
            let len = self.len;
            let count = ((x1 - x0) as usize).min(BATCH - len);
            // Four at a time, past `count` into the spare lanes. (x0 + j) as f32 is x0 as f32 +
            // j as f32, exactly (pixel columns are far below 2^24).
            let (first, left) = ((i0 as u32), x0 as f32 + 0.5);
            for c in (0..count).step_by(4) {
                let at = len + c..len + c + 4;
                let (index, dx, y) = (&mut self.index[at.clone()], &mut self.dx[at.clone()], &mut self.dy[at]);
                for l in 0..4 {
                    let j = c + l;
                    (index[l], dx[l], y[l]) = (first + j as u32, (left + j as f32) - centre[0], dy);
                }
            }
            self.len = len + count;
            (x0, i0) = (x0 + count as i64, i0 + count);
        }
    }

    /// Finds the wedges of the cell's queued pixels (fan `fan`) and readies them, evaluating
    /// the ready ones first if they would not fit.
    fn locate<K: Sink>(&mut self, ridge: &Ridge<S>, fan: &Fan, sink: &mut K) {
        let n = self.len;
        if self.ready + n > QUEUE {
            self.evaluate(ridge, sink);
        }
        // The direction of each pixel from the centre, eight at a time (the lanes past `n` are
        // stale).
        let m = n.next_multiple_of(8);
        for ((a, x), y) in
            self.angle[..m].chunks_exact_mut(8).zip(self.dx[..m].chunks_exact(8)).zip(self.dy[..m].chunks_exact(8))
        {
            for l in 0..8 {
                a[l] = pseudo_angle([x[l], y[l]]);
            }
        }
        // The fan triangle its ray leaves by.
        let wedges = &fan.slots[1..];
        if fan.sorted && wedges.len() <= COUNTED {
            // Eight pixels at a time.
            for (ks, angles) in self.wedge[..m].chunks_exact_mut(8).zip(self.angle[..m].chunks_exact(8)) {
                let mut k = [0u32; 8];
                for w in wedges {
                    for (k, &a) in k.iter_mut().zip(angles) {
                        *k += u32::from(w.angle <= a);
                    }
                }
                ks.copy_from_slice(&k);
            }
        } else {
            for (k, &a) in self.wedge[..n].iter_mut().zip(&self.angle[..n]) {
                *k = wedges.partition_point(|w| w.angle <= a) as u32;
            }
        }
        // u and the offset in apothems there (in f32: the offsets are in pixels, which Q16.16
        // could not square).
        let r = self.ready..self.ready + n;
        let pixel = self.index[..n].iter().zip(&self.wedge[..n]).zip(self.dx[..n].iter().zip(&self.dy[..n]));
        let index = self.ready_index[r.clone()].iter_mut().zip(&mut self.u[r.clone()]);
        let ready = index.zip(self.qx[r.clone()].iter_mut().zip(&mut self.qy[r.clone()]));
        for (((&i, &k), (&dx, &dy)), ((index, u), (qx, qy))) in pixel.zip(ready) {
            let w = &fan.slots[k as usize];
            *index = i;
            *u = dx * w.g[0] + dy * w.g[1];
            (*qx, *qy) = (dx * w.inverse_apothem, dy * w.inverse_apothem);
        }
        (self.len, self.ready) = (0, r.end);
    }

    /// Adds the ready pixels' heights and normals (all of the level of `ridge`) to `sink`.
    fn evaluate<K: Sink>(&mut self, ridge: &Ridge<S>, sink: &mut K) {
        let n = self.ready;
        for j in 0..n {
            let (at, lean) = ridge.shape(self.u[j], [self.qx[j], self.qy[j]]);
            (self.interval[j], self.weight[j]) = ridge.table.interval(at);
            self.lean[j] = lean;
        }
        let pixel = self.ready_index[..n].iter().zip(&self.interval[..n]).zip(&self.weight[..n]);
        let normal = self.lean[..n].iter().zip(&self.qx[..n]).zip(&self.qy[..n]);
        for (((&i, &k), &w), ((&lean, &qx), &qy)) in pixel.zip(normal) {
            let (z, dz) = ridge.table.lerp(k, w);
            let slope = if K::NORMALS {
                // The profile's normal (−slope, 1) in the x'z' plane, turned to the ray.
                let lean = S::from_f32(-dz) * lean;
                [(lean * S::from_f32(qx)).to_f32(), (lean * S::from_f32(qy)).to_f32()]
            } else {
                [0.0; 2]
            };
            sink.add(i as usize, z, slope);
        }
        self.ready = 0;
    }
}

impl<S: Scalar> Ridge<'_, S> {
    /// From u and the offset q in apothems: x' for the profile, and the factor that turns the
    /// profile's slope dz'/dx' into the normal's x and y (times q; 0 at the centre, q = 0).
    #[inline(always)]
    fn shape(&self, u: f32, q: [f32; 2]) -> (f32, S) {
        let u = S::from_f32(u).clamp(S::ZERO, S::ONE);
        let q = [S::from_f32(q[0]), S::from_f32(q[1])];
        let r2 = q[0] * q[0] + q[1] * q[1];
        // r = |p − p0| / apothem, and 1/r.
        let inverse_r = r2.inverse_sqrt();
        let r = r2 * inverse_r;
        // Polygonal x' (u) blended with circular x' (r, which is at least u, capped at the
        // edge): ρ = 1 gives circles inscribed in each edge, the corners beyond them at the
        // foot.
        let steep = u > S::RESOLUTION;
        let circular = if steep { r.max(u) } else { u };
        let bent = self.flat * u + self.roundness * circular.min(S::ONE);
        // The normal leans along the ray by the profile's slope times du'/du there: 1 − ρ +
        // ρ·r/u inside the circle (where u_c = u·r/u), 1 − ρ beyond it; over r, which makes q
        // the ray's unit vector. So the factor is (1 − ρ)/r + ρ·max(1/u, 1/r) inside (r/u is
        // at least 1, and taken as 1 where u is 0), (1 − ρ)/r beyond.
        let circle = if steep { (S::ONE / u).max(inverse_r) } else { inverse_r };
        let inside = if circular < S::ONE { self.roundness * circle } else { S::ZERO };
        let lean = if r > S::ZERO { self.flat * inverse_r + inside } else { S::ZERO };
        ((self.end * bent).to_f32(), lean)
    }
}

impl Skin<'_> {
    /// Writes the requested maps. Every buffer is checked first: if one is too short, or the
    /// cell level is not below `levels`, nothing is written. Uses about 53 KiB of stack for
    /// one outline's wedges and crossings and a batch of pixels.
    pub fn render<S: Scalar>(&self, layers: SkinLayers) -> Result<(), SkinError> {
        let pixels = self.params.width as usize * self.params.height as usize;
        let SkinLayers { height, normal, cell, cell_level } = layers;
        let lengths =
            [height.as_ref().map(|b| b.len()), normal.as_ref().map(|b| b.len()), cell.as_ref().map(|b| b.len())];
        if lengths.iter().flatten().any(|&n| n < pixels) {
            return Err(SkinError::BufferTooSmall { needed: pixels });
        }
        if cell.is_some() && cell_level >= self.params.levels {
            return Err(SkinError::Level);
        }
        let cell = cell.map(|c| {
            c[..pixels].fill(u32::MAX);
            (&mut c[..pixels], cell_level)
        });
        match (height.map(|h| &mut h[..pixels]), normal.map(|n| &mut n[..pixels])) {
            (None, None) => self.draw::<S, _>(&mut NoMaps, cell),
            (Some(h), None) => {
                h.fill(0.0);
                self.draw::<S, _>(&mut Heights(h), cell);
            }
            (None, Some(n)) => {
                n.fill([0.0; 3]);
                self.draw::<S, _>(&mut Normals(n), cell);
                normalise(n);
            }
            (Some(h), Some(n)) => {
                h.fill(0.0);
                n.fill([0.0; 3]);
                self.draw::<S, _>(&mut Both(h, n), cell);
                normalise(n);
            }
        }
        Ok(())
    }

    /// Adds every cell's height and normal to `sink` and writes the cells of one level into
    /// the cell map.
    fn draw<S: Scalar, K: Sink>(&self, sink: &mut K, mut cell: Option<(&mut [u32], u32)>) {
        let width = self.params.width as usize;
        let mut wedges = [Wedge::default(); SLOTS];
        let mut crossings = [0u64; MAX_OUTLINE];
        let mut batch = Batch::<S>::new();
        let to_pixels = 1.0 / (1u64 << self.fixed_point_bits()) as f64;
        let ridges: [Ridge<S>; MAX_LEVELS] = core::array::from_fn(|level| {
            let table = &self.tables[level];
            let roundness = S::from_f32(self.params.level[level].roundness);
            Ridge { table, end: S::from_f32(table.end), roundness, flat: S::ONE - roundness }
        });
        // The level of the ready pixels.
        let mut ready = 0;
        for (index, c) in self.cells.iter().enumerate() {
            let mut map = cell.as_mut().filter(|(_, level)| *level == c.level).map(|(map, _)| &mut **map);
            if map.is_none() && !K::SHADES {
                continue;
            }
            let level = c.level as usize;
            if level != ready {
                // Each pixel gets its levels' heights in the order of levels.
                batch.evaluate(&ridges[ready], sink);
                ready = level;
            }
            let ridge = &ridges[level];
            let centre = [(c.centre[0] as f64 * to_pixels) as f32, (c.centre[1] as f64 * to_pixels) as f32];
            // Wedges serve heights and normals; a cell map alone needs only the pixels.
            let fan = if K::SHADES { self.prepare(c, &mut wedges) } else { Fan { slots: &[], sorted: false } };
            self.for_each_run(c, &mut crossings, |y, x0, x1, wx, wy| {
                let i0 = wy as usize * width + wx as usize;
                if let Some(map) = map.as_deref_mut() {
                    map[i0..i0 + (x1 - x0) as usize].fill(index as u32);
                }
                if K::SHADES {
                    batch.span(ridge, &fan, sink, centre, [y, x0, x1], i0);
                }
            });
            if batch.len > 0 {
                batch.locate(ridge, &fan, sink);
            }
        }
        batch.evaluate(&ridges[ready], sink);
    }

    /// Fills `slots` with `cell`'s fan.
    fn prepare<'w>(&self, cell: &SkinCell, slots: &'w mut [Wedge]) -> Fan<'w> {
        let outline = self.outline(cell);
        let n = outline.len();
        // 2^−bits: scaling by it is exact, so that (x as f32)·to_pixels rounds x / unit once,
        // like an exact division (below 2^53 also like (x as f64 / unit) as f32).
        let to_pixels = 1.0 / (1u64 << self.fixed_point_bits()) as f32;
        let pixels = |x: i64| x as f32 * to_pixels;
        let c = cell.centre;
        let wedges = &mut slots[1..=n];
        // The first corner of smallest angle, and the last place where the angle does not
        // ascend (cyclically) and how many there are: the angles ascend from `start` on if that
        // is only just before `start`, or nowhere.
        let (mut start, mut smallest) = (0, f32::INFINITY);
        let (mut descents, mut descent, mut previous) = (0, 0, f32::NAN);
        // A few edges at a time, each step a plain loop over them, so that the divisions go
        // several at once (the lanes past the outline's end hold zeros, and are not kept).
        for (chunk, out) in wedges.chunks_mut(EDGES).enumerate() {
            let first = chunk * EDGES;
            // The first corner relative to the centre, and the edge, in pixels.
            let (mut va, mut e) = ([[0.0f32; EDGES]; 2], [[0.0f32; EDGES]; 2]);
            for l in 0..out.len() {
                let i = first + l;
                let (a, b) = (outline[i], outline[if i + 1 == n { 0 } else { i + 1 }]);
                (va[0][l], va[1][l]) = (pixels(a[0] - c[0]), pixels(a[1] - c[1]));
                (e[0][l], e[1][l]) = (pixels(b[0] - a[0]), pixels(b[1] - a[1]));
            }
            // (libm's square root is a scalar instruction, in a loop of its own.)
            let mut length = [0.0f32; EDGES];
            for l in 0..EDGES {
                length[l] = libm::sqrtf(e[0][l] * e[0][l] + e[1][l] * e[1][l]);
            }
            let (mut gx, mut gy) = ([0.0f32; EDGES], [0.0f32; EDGES]);
            let (mut inverse_apothem, mut angle) = ([0.0f32; EDGES], [0.0f32; EDGES]);
            let [vx, vy] = va;
            let [ex, ey] = e;
            for l in 0..EDGES {
                // Outward normal of a counter-clockwise edge, unnormalised: (e_y, −e_x).
                let outward = [ey[l], -ex[l]];
                let reach = vx[l] * outward[0] + vy[l] * outward[1];
                let per_reach = 1.0 / reach;
                // With the centre on or beyond this edge's line (a fold), the wedge reads as
                // edge.
                let kept = (reach > 0.0) & (length[l] > 0.0);
                gx[l] = if kept { outward[0] * per_reach } else { 0.0 };
                gy[l] = if kept { outward[1] * per_reach } else { 0.0 };
                inverse_apothem[l] = if kept { length[l] * per_reach } else { 1.0 };
                angle[l] = pseudo_angle([vx[l], vy[l]]);
            }
            for (l, w) in out.iter_mut().enumerate() {
                let (i, angle) = (first + l, angle[l]);
                *w = Wedge { g: [gx[l], gy[l]], inverse_apothem: inverse_apothem[l], angle };
                if angle < smallest || i == 0 {
                    (start, smallest) = (i, angle);
                }
                if i > 0 && previous.partial_cmp(&angle).is_none_or(Ordering::is_gt) {
                    (descents, descent) = (descents + 1, i);
                }
                previous = angle;
            }
        }
        if wedges[n - 1].angle.partial_cmp(&wedges[0].angle).is_none_or(Ordering::is_gt) {
            (descents, descent) = (descents + 1, 0);
        }
        let sorted = descents == 0 || (descents == 1 && descent == start);
        wedges.rotate_left(start);
        slots[0] = slots[n];
        Fan { slots: &slots[..=n], sorted }
    }

    /// Calls `visit(row, x0, x1, wrapped x0, wrapped row)` for every run of pixels `x0..x1` of
    /// one row whose centres lie in `cell`: unwrapped as the outline places them, and on the
    /// surface, where the run is contiguous (a run across the periodic seam comes in two
    /// pieces). `crossings` is scratch of at least the outline's length.
    fn for_each_run(&self, cell: &SkinCell, crossings: &mut [u64], mut visit: impl FnMut(i64, i64, i64, u32, u32)) {
        let (w, h) = (i64::from(self.params.width), i64::from(self.params.height));
        let periodic = self.params.periodic;
        super::scan::for_each_span(self.outline(cell), self.fixed_point_bits(), crossings, |y, x0, x1| {
            if periodic {
                let wy = y.rem_euclid(h) as u32;
                let mut x = x0;
                while x < x1 {
                    let wx = x.rem_euclid(w);
                    let next = x1.min(x + (w - wx));
                    visit(y, x, next, wx as u32, wy);
                    x = next;
                }
            } else if (0..h).contains(&y) {
                let (x0, x1) = (x0.max(0), x1.min(w));
                if x0 < x1 {
                    visit(y, x0, x1, x0 as u32, y as u32);
                }
            }
        });
    }

    /// Calls `visit(column, row, wrapped column, wrapped row)` for every pixel whose centre lies
    /// in `cell`: unwrapped as the outline places it, and on the surface. `crossings` is scratch
    /// of at least the outline's length.
    pub(super) fn for_each_pixel_unwrapped(
        &self,
        cell: &SkinCell,
        crossings: &mut [u64],
        mut visit: impl FnMut(i64, i64, u32, u32),
    ) {
        self.for_each_run(cell, crossings, |y, x0, x1, wx, wy| {
            for (x, wx) in (x0..x1).zip(wx..) {
                visit(x, y, wx, wy);
            }
        });
    }
}

/// Fig. 10: each level's normal has z = 1; x and y add up. Rows run down the raster, so y
/// flips for a y-up normal map.
fn normalise(normals: &mut [[f32; 3]]) {
    for v in normals {
        let (x, y) = (v[0], -v[1]);
        let s = Scalar::inverse_sqrt(x * x + y * y + 1.0);
        *v = [x * s, y * s, s];
    }
}
