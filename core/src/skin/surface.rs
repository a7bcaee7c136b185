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
//! Only the finest cells are drawn: a coarser cell is the union of its descendants, pixel for
//! pixel, so each pixel's coarser cells are its finest cell's ancestors, whose fans are kept
//! one per level. Pixels go through in batches, a plain loop per step, so that the processor
//! overlaps many pixels and most steps handle several at once: a finest cell's pixels find
//! their fan triangles (by pseudo-angle, the same ones as a binary search over the corners'
//! angles), then, with those of its siblings, their ancestors' triangles; then every level's
//! profile coordinate and normal factor, its profile samples, and the sums over the levels,
//! which are written once.

use core::cmp::Ordering;
use core::ops::Range;

use super::profile::{ProfileTable, blend};
use super::scan::{Held, held};
use super::shade::{Light, ShadeParams};
use super::{MAX_LEVELS, Skin, SkinCell, SkinError};
use crate::geom::pseudo_angle;
use crate::raster::{Layer, Layers, Tile, height16, normal_rgb8};
use crate::scalar::Scalar;

/// The maps one [`Skin::render`] call writes: every [`Layers`] field but `time`.
pub type SkinLayers<'o> = Layers<'o>;

/// How to draw: the rasters are the surface's `width × height` pixels (or a tile of them);
/// this picks what the cell map shows and how the preview is lit.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SkinRender {
    /// The level the cell map is taken from (below `levels`; default 0, the coarsest).
    pub cell_level: u32,
    /// Light and palette of the preview.
    pub shade: ShadeParams,
}

/// The furrow mask's value for an outline of each level, coarsest first.
pub const FURROWS: [u8; MAX_LEVELS] = [255, 160, 100, 64];

/// Per outline edge of a cell: g (so that u = (p − p0)·g), 1 / apothem, and the pseudo-angle
/// of the edge's first vertex seen from the centre; made once, as the cell is built.
/// (Opaque; caller memory for [`super::SkinBuffers`].)
#[derive(Clone, Copy, Debug, Default)]
pub struct Wedge {
    g: [f32; 2],
    inverse_apothem: f32,
    angle: f32,
}

/// A cell's wedges: `slots[1..=n]` from the corner of smallest angle on, and `slots[0]` the
/// last one again, its angle [`ASCENDING`] if the others' angles ascend (0 if not). A pixel in direction `a` (a pseudo-angle) lies in the wedge its ray leaves
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
const COUNTED: usize = 256;

/// Counting a fan longer than this, eight pixels start past the wedges at or below all of
/// them, found by a binary search, and count on to the last wedge at or below the largest of
/// them (the angles ascend); on a 64-bit build ([`WINDOWED`]) the search's steps depend on the
/// fan's length alone, and [`WINDOW`] wedges are counted whatever their angles unless more lie
/// below the largest. Eight pixels of a coarse cell's long fan mostly span a few of its
/// wedges. A shorter fan (the finest cells' own and, in Table 1's presets, most of the next
/// level's) is counted whole: no search, and no loop exit that depends on the pixels' angles,
/// which a processor mispredicts. (A 32-bit part, whose branches cost a cycle or two, counts
/// fewer fans whole.)
#[cfg(target_pointer_width = "64")]
const LONG_FAN: usize = 32;
#[cfg(not(target_pointer_width = "64"))]
const LONG_FAN: usize = 12;

/// Whether a long fan's pixels count a window of wedges after a search without branches (see
/// [`LONG_FAN`]); a 32-bit part takes fewer steps with branches.
const WINDOWED: bool = cfg!(target_pointer_width = "64");

/// Wedges of a long fan counted for eight pixels (see [`LONG_FAN`]).
const WINDOW: usize = 4;

/// Pixels whose wedges are looked up together: of one finest-level cell for its own level,
/// of the cells that share their coarser cells for the coarser levels.
const BATCH: usize = 64;

/// Lanes of a batch: steps that handle eight pixels at once may run past its end.
const LANES: usize = BATCH + 8;

/// Pixels whose heights and normals are evaluated together (a batch's worth: the queue's
/// arrays are on the stack, and each pixel's sums are its own, whatever the queue's length).
const QUEUE: usize = BATCH;

/// A level's fan while its cell's descendants are drawn: where it starts in the skin's
/// wedges and its length (with the front slot), whether its angles ascend, its centre
/// (pixels) and its cell.
#[derive(Clone, Copy, Default)]
struct FanAt {
    start: usize,
    len: usize,
    sorted: bool,
    centre: [f32; 2],
    cell: u32,
}

/// The fans of the cell being drawn and of its ancestors, one per level.
struct Fans<'w> {
    /// The skin's wedges: per cell, one per outline edge and one at the front (see [`Fan`]).
    wedges: &'w [Wedge],
    at: &'w [FanAt; MAX_LEVELS],
    /// The level of the cells being drawn (the finest).
    finest: usize,
}

impl Fans<'_> {
    fn fan(&self, level: usize) -> Fan<'_> {
        let at = &self.at[level];
        Fan { slots: &self.wedges[at.start..][..at.len], sorted: at.sorted }
    }
}

/// Pixels on their way to the maps, a field per array so that each step is a plain loop:
/// first the pixels queued from finest-level cells that share their coarser cells (`len`),
/// then, with their wedges at every level found, those ready to evaluate (`ready`). Steps
/// that handle several pixels at once run over whole groups; the lanes past the pixels hold
/// stale but finite values.
struct Batch<S> {
    len: usize,
    /// The first lane of the finest cell being drawn.
    cell: usize,
    /// Index in the maps, and the pixel's centre as the outline places it (pixels).
    index: [u32; LANES],
    x: [f32; LANES],
    y: [f32; LANES],
    /// Offset from the centre of the level being looked up, its pseudo-angle, and k in
    /// [`Fan`].
    dx: [f32; LANES],
    dy: [f32; LANES],
    angle: [f32; LANES],
    wedge: [u32; LANES],
    ready: usize,
    /// Index in the maps.
    ready_index: [u32; QUEUE],
    /// Per level, u in the pixel's wedge, and the offset in apothems (eight lanes at a time,
    /// the last ones past the queue stale).
    u: [[f32; LANES]; MAX_LEVELS],
    qx: [[f32; LANES]; MAX_LEVELS],
    qy: [[f32; LANES]; MAX_LEVELS],
    /// The profile's sample interval and the weight of its far end at the pixel's x', and the
    /// factor that turns the profile's slope into the normal's x and y (of the level being
    /// evaluated).
    interval: [u32; QUEUE],
    weight: [f32; QUEUE],
    lean: [S; QUEUE],
    /// The profile's samples at the interval's ends (on x86-64 apart, as the height and slope
    /// at its near end, then at its far end, for plain loops).
    #[cfg(not(target_arch = "x86_64"))]
    ends: [[[f32; 2]; 2]; QUEUE],
    #[cfg(target_arch = "x86_64")]
    ends: [[f32; QUEUE]; 4],
    /// The sums over the levels evaluated: height, and the normal's x and y; and the unit
    /// normal they make.
    height: [f32; QUEUE],
    slope: [[f32; QUEUE]; 2],
    normal: [[f32; QUEUE]; 3],
}

/// Where the maps a render writes go.
trait Sink {
    /// Whether heights or normals are wanted (else only the cell map is drawn).
    const SHADES: bool;
    /// Whether normals are wanted.
    const NORMALS: bool;
    /// Sets pixel `i` to height `z` and unit normal `normal` (when normals are wanted).
    fn set(&mut self, i: usize, z: f32, normal: [f32; 3]);
}

/// No height or normal map.
struct NoMaps;

impl Sink for NoMaps {
    const SHADES: bool = false;
    const NORMALS: bool = false;
    fn set(&mut self, _: usize, _: f32, _: [f32; 3]) {}
}

/// Heights only.
struct Heights<'o>(&'o mut [f32]);

impl Sink for Heights<'_> {
    const SHADES: bool = true;
    const NORMALS: bool = false;
    #[inline]
    fn set(&mut self, i: usize, z: f32, _: [f32; 3]) {
        self.0[i] = z;
    }
}

/// Normals only.
struct Normals<'o>(&'o mut [[f32; 3]]);

impl Sink for Normals<'_> {
    const SHADES: bool = true;
    const NORMALS: bool = true;
    #[inline]
    fn set(&mut self, i: usize, _: f32, normal: [f32; 3]) {
        self.0[i] = normal;
    }
}

/// Heights and normals.
struct Both<'o>(&'o mut [f32], &'o mut [[f32; 3]]);

impl Sink for Both<'_> {
    const SHADES: bool = true;
    const NORMALS: bool = true;
    #[inline]
    fn set(&mut self, i: usize, z: f32, normal: [f32; 3]) {
        self.0[i] = z;
        self.1[i] = normal;
    }
}

/// Any set of maps, in the formats an engine uploads: heights (`f32`, 16-bit over
/// `range`), normals (`f32`, 8-bit RGB) and the shaded preview. `NORMALS`: whether any of them
/// needs the normals (when none does, they are not made; a 32-bit build makes them always, for
/// the flash of one drawing fewer).
struct Outputs<'o, const NORMALS: bool = true> {
    height: Option<&'o mut [f32]>,
    height16: Option<&'o mut [u16]>,
    normal: Option<&'o mut [[f32; 3]]>,
    normal_rgb8: Option<&'o mut [[u8; 3]]>,
    preview: Option<(&'o mut [[u8; 4]], Light, &'o ShadeParams)>,
    /// The lowest height and 1 / the height range.
    low: f32,
    per_span: f32,
}

impl<'o> Outputs<'o> {
    /// Whether any map the outputs hold needs the normals.
    #[cfg(target_pointer_width = "64")]
    fn normals(&self) -> bool {
        self.normal.is_some() || self.normal_rgb8.is_some() || self.preview.is_some()
    }

    /// The same outputs, with no normal made (none of them may need one).
    #[cfg(target_pointer_width = "64")]
    fn heights(self) -> Outputs<'o, false> {
        let Outputs { height, height16, normal, normal_rgb8, preview, low, per_span } = self;
        Outputs { height, height16, normal, normal_rgb8, preview, low, per_span }
    }

    /// Whether any map the outputs hold needs the heights and normals.
    fn shades(&self) -> bool {
        self.height.is_some()
            || self.height16.is_some()
            || self.normal.is_some()
            || self.normal_rgb8.is_some()
            || self.preview.is_some()
    }
}

impl Outputs<'_> {
    /// Sets every one of the first `pixels` pixels as [`Sink::set`] sets one to height `z` and
    /// unit normal `normal`: each format's value made once.
    fn fill(&mut self, pixels: usize, z: f32, normal: [f32; 3]) {
        let t = (z - self.low) * self.per_span;
        if let Some(out) = self.height.as_deref_mut() {
            out[..pixels].fill(z);
        }
        if let Some(out) = self.height16.as_deref_mut() {
            out[..pixels].fill(height16(t));
        }
        if let Some(out) = self.normal.as_deref_mut() {
            out[..pixels].fill(normal);
        }
        if let Some(out) = self.normal_rgb8.as_deref_mut() {
            out[..pixels].fill(normal_rgb8(normal));
        }
        if let Some((out, light, params)) = self.preview.as_mut() {
            out[..pixels].fill(light.shade(normal, t, params));
        }
    }
}

impl<const NORMALS: bool> Sink for Outputs<'_, NORMALS> {
    const SHADES: bool = true;
    const NORMALS: bool = NORMALS;
    #[inline]
    fn set(&mut self, i: usize, z: f32, normal: [f32; 3]) {
        let t = (z - self.low) * self.per_span;
        if let Some(out) = self.height.as_deref_mut() {
            out[i] = z;
        }
        if let Some(out) = self.height16.as_deref_mut() {
            out[i] = height16(t);
        }
        if let Some(out) = self.normal.as_deref_mut() {
            out[i] = normal;
        }
        if let Some(out) = self.normal_rgb8.as_deref_mut() {
            out[i] = normal_rgb8(normal);
        }
        if let Some((out, light, params)) = self.preview.as_mut() {
            out[i] = light.shade(normal, t, params);
        }
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
            cell: 0,
            index: [0; LANES],
            x: [0.0; LANES],
            y: [0.0; LANES],
            dx: [0.0; LANES],
            dy: [0.0; LANES],
            angle: [0.0; LANES],
            wedge: [0; LANES],
            ready: 0,
            ready_index: [0; QUEUE],
            u: [[0.0; LANES]; MAX_LEVELS],
            qx: [[0.0; LANES]; MAX_LEVELS],
            qy: [[0.0; LANES]; MAX_LEVELS],
            interval: [0; QUEUE],
            weight: [0.0; QUEUE],
            lean: [S::ZERO; QUEUE],
            #[cfg(not(target_arch = "x86_64"))]
            ends: [[[0.0; 2]; 2]; QUEUE],
            #[cfg(target_arch = "x86_64")]
            ends: [[0.0; QUEUE]; 4],
            height: [0.0; QUEUE],
            slope: [[0.0; QUEUE]; 2],
            normal: [[0.0; QUEUE]; 3],
        }
    }

    /// Queues the pixels `x0..x1` of row `y` (as the outline places them), `i0..` in the maps,
    /// of the finest-level cell being drawn.
    #[inline]
    fn span<K: Sink>(&mut self, fans: &Fans, ridges: &[Ridge<S>], sink: &mut K, row: [i64; 3], i0: usize) {
        let [y, mut x0, x1] = row;
        let mut i0 = i0;
        let centre_y = y as f32 + 0.5;
        while x0 < x1 {
            if self.len == BATCH {
                self.flush(fans, ridges, sink);
            }
            let len = self.len;
            let count = ((x1 - x0) as usize).min(BATCH - len);
            // Four at a time, past `count` into the spare lanes. Every sum is exact, (x0 + j)
            // as f32 is x0 as f32 + j as f32 however it is summed (pixel columns are far below
            // 2^23).
            let (mut first, mut left) = ((i0 as u32), x0 as f32 + 0.5);
            for c in (0..count).step_by(4) {
                let at = len + c..len + c + 4;
                let (index, x, y) = (&mut self.index[at.clone()], &mut self.x[at.clone()], &mut self.y[at]);
                for l in 0..4 {
                    (index[l], x[l], y[l]) = (first + l as u32, left + [0.0, 1.0, 2.0, 3.0][l], centre_y);
                }
                (first, left) = (first + 4, left + 4.0);
            }
            self.len = len + count;
            (x0, i0) = (x0 + count as i64, i0 + count);
        }
    }

    /// Finds the wedges of the finest-level cell's queued pixels in its own fan.
    fn close_cell(&mut self, fans: &Fans) {
        let level = fans.finest;
        self.locate(level, self.cell..self.len, &fans.fan(level), fans.at[level].centre);
        self.cell = self.len;
    }

    /// Readies the queued pixels: their wedges in the finest cell's fan (for those not found
    /// yet) and in the coarser cells' fans, which they all share. Evaluates the ready pixels
    /// if another batch might not fit after them.
    fn flush<K: Sink>(&mut self, fans: &Fans, ridges: &[Ridge<S>], sink: &mut K) {
        self.close_cell(fans);
        for level in 0..fans.finest {
            self.locate(level, 0..self.len, &fans.fan(level), fans.at[level].centre);
        }
        self.ready_index[self.ready..self.ready + self.len].copy_from_slice(&self.index[..self.len]);
        (self.ready, self.len, self.cell) = (self.ready + self.len, 0, 0);
        if self.ready + BATCH > QUEUE {
            self.evaluate(ridges, sink);
        }
    }

    /// Finds the wedges of the queued pixels in `lanes` in the fan `fan` of level `level`,
    /// centred at `centre`, and readies them at that level.
    fn locate(&mut self, level: usize, lanes: Range<usize>, fan: &Fan, centre: [f32; 2]) {
        let (a, n) = (lanes.start, lanes.len());
        if n == 0 {
            return;
        }
        // The offset and direction of each pixel from the centre, eight at a time (the lanes
        // past `n` are stale).
        let all = a..a + n.next_multiple_of(8);
        let offsets = self.dx[all.clone()].chunks_exact_mut(8).zip(self.dy[all.clone()].chunks_exact_mut(8));
        let at = self.x[all.clone()].chunks_exact(8).zip(self.y[all.clone()].chunks_exact(8));
        for (((dx, dy), (x, y)), angle) in offsets.zip(at).zip(self.angle[all.clone()].chunks_exact_mut(8)) {
            for l in 0..8 {
                (dx[l], dy[l]) = (x[l] - centre[0], y[l] - centre[1]);
            }
            let eight = |v: &[f32]| -> [f32; 8] { core::array::from_fn(|l| v[l]) };
            angle.copy_from_slice(&pseudo_angles(eight(dx), eight(dy)));
        }
        // The fan triangle its ray leaves by.
        let wedges = &fan.slots[1..];
        if fan.sorted && wedges.len() <= COUNTED {
            // Eight pixels at a time, a wedge at a time (the pixels held in registers).
            let long = wedges.len() > LONG_FAN;
            for (ks, angles) in self.wedge[all.clone()].chunks_exact_mut(8).zip(self.angle[all.clone()].chunks_exact(8))
            {
                let angles: [f32; 8] = core::array::from_fn(|l| angles[l]);
                // Past the largest of the eight (a NaN, the centre's own, counts nothing), no
                // wedge counts; up to the smallest (none with a NaN among them), every one
                // does, found by a binary search. Eight pixels near each other, far from a
                // coarse cell's centre, mostly lie in one or two of its wedges.
                let (skip, last) = if long {
                    let (low, high): ([f32; 4], [f32; 4]) = (
                        core::array::from_fn(|l| if angles[l + 4] < angles[l] { angles[l + 4] } else { angles[l] }),
                        core::array::from_fn(|l| if angles[l + 4] > angles[l] { angles[l + 4] } else { angles[l] }),
                    );
                    let first = low.iter().fold(f32::INFINITY, |m, &a| if a < m { a } else { m });
                    let nan = angles.iter().fold(false, |nan, a| nan | a.is_nan());
                    let skip = match (nan, WINDOWED) {
                        (true, _) => 0,
                        (false, true) => at_most(wedges, first),
                        (false, false) => wedges.partition_point(|w| w.angle <= first),
                    };
                    (
                        skip,
                        if nan {
                            f32::INFINITY
                        } else {
                            high.iter().fold(f32::NEG_INFINITY, |m, &a| if a > m { a } else { m })
                        },
                    )
                } else {
                    (0, f32::INFINITY)
                };
                if long && WINDOWED {
                    // WINDOW wedges from at most `skip` (a long fan has more), counted whatever
                    // their angles, when none past them is at most the largest of the eight.
                    let start = skip.min(wedges.len() - WINDOW);
                    let beyond = wedges.get(start + WINDOW).map_or(f32::INFINITY, |w| w.angle);
                    if beyond > last {
                        let mut k = [start as u32; 8];
                        for w in &wedges[start..][..WINDOW] {
                            let t = w.angle;
                            k = core::array::from_fn(|l| k[l] + u32::from(t <= angles[l]));
                        }
                        ks.copy_from_slice(&k);
                        continue;
                    }
                }
                let mut k = [skip as u32; 8];
                for w in &wedges[skip..] {
                    let t = w.angle;
                    if t > last {
                        break;
                    }
                    k = core::array::from_fn(|l| k[l] + u32::from(t <= angles[l]));
                }
                ks.copy_from_slice(&k);
            }
        } else {
            // (Every lane, so that each lane's k is a slot of this fan.)
            for (k, &a) in self.wedge[all.clone()].iter_mut().zip(&self.angle[all.clone()]) {
                *k = wedges.partition_point(|w| w.angle <= a) as u32;
            }
        }
        // u and the offset in apothems there (in f32: the offsets are in pixels, which Q16.16
        // could not square).
        // Each pixel's wedge read one by one (every lane's k, stale or not, is a slot of the
        // fan), then the arithmetic in a plain loop, several at once. Lanes past `n` write
        // past the pixels' own, into lanes not read (or written again before they are).
        let to = self.ready + a..self.ready + all.end;
        let (us, qxs, qys) = (&mut self.u[level][to.clone()], &mut self.qx[level][to.clone()], &mut self.qy[level][to]);
        // (The wedge's g and 1 / apothem first, where u and q go.)
        let picked = us.chunks_exact_mut(8).zip(qxs.chunks_exact_mut(8).zip(qys.chunks_exact_mut(8)));
        for (ks, (gx, (gy, inverse_apothem))) in self.wedge[all.clone()].chunks_exact(8).zip(picked) {
            // (On x86-64 four wedges at a time, each read whole and turned into lanes.)
            #[cfg(target_arch = "x86_64")]
            for h in [0, 4] {
                let [a, b, c, _] = four_lanes(|l| {
                    let w = &fan.slots[ks[h + l] as usize];
                    [w.g[0], w.g[1], w.inverse_apothem, w.angle]
                });
                gx[h..h + 4].copy_from_slice(&a);
                gy[h..h + 4].copy_from_slice(&b);
                inverse_apothem[h..h + 4].copy_from_slice(&c);
            }
            #[cfg(not(target_arch = "x86_64"))]
            for l in 0..8 {
                let w = &fan.slots[ks[l] as usize];
                (gx[l], gy[l], inverse_apothem[l]) = (w.g[0], w.g[1], w.inverse_apothem);
            }
        }
        let eight = |v: &[f32]| -> [f32; 8] { core::array::from_fn(|l| v[l]) };
        let offsets = self.dx[all.clone()].chunks_exact(8).zip(self.dy[all].chunks_exact(8));
        let ready = us.chunks_exact_mut(8).zip(qxs.chunks_exact_mut(8).zip(qys.chunks_exact_mut(8)));
        for ((dx, dy), (u, (qx, qy))) in offsets.zip(ready) {
            let (dx, dy, gx, gy, inverse_apothem) = (eight(dx), eight(dy), eight(u), eight(qx), eight(qy));
            u.copy_from_slice(&core::array::from_fn::<f32, 8, _>(|l| dx[l] * gx[l] + dy[l] * gy[l]));
            qx.copy_from_slice(&core::array::from_fn::<f32, 8, _>(|l| dx[l] * inverse_apothem[l]));
            qy.copy_from_slice(&core::array::from_fn::<f32, 8, _>(|l| dy[l] * inverse_apothem[l]));
        }
    }

    /// Sums the ready pixels' heights and normals over the levels of `ridges`, in the order of
    /// levels, and sets them in `sink`.
    fn evaluate<K: Sink>(&mut self, ridges: &[Ridge<S>], sink: &mut K) {
        let n = self.ready;
        self.height[..n].fill(0.0);
        for slope in &mut self.slope {
            slope[..n].fill(0.0);
        }
        for (level, ridge) in ridges.iter().enumerate() {
            let (u, qx, qy) = (&self.u[level][..n], &self.qx[level][..n], &self.qy[level][..n]);
            for j in 0..n {
                let (at, lean) = ridge.shape(u[j], [qx[j], qy[j]]);
                (self.interval[j], self.weight[j]) = ridge.table.interval(at);
                // (Heights alone need no normal's factor; a 64-bit build keeps it all the same,
                // which leaves this loop one LLVM vectorises in every crate that draws.)
                if K::NORMALS || cfg!(target_pointer_width = "64") {
                    self.lean[j] = lean;
                }
            }
            // The samples read in a loop of their own, the arithmetic several at once.
            if !K::NORMALS {
                // (Heights alone: the two ends' heights apart, for plain loops, where the
                // normals' sums would be.)
                let [h0, h1] = &mut self.slope;
                #[cfg(target_arch = "x86_64")]
                for j in (0..n).step_by(4) {
                    let [near, _, far, _] = four_ends(ridge.table, &self.interval[j..j + 4]);
                    h0[j..j + 4].copy_from_slice(&near);
                    h1[j..j + 4].copy_from_slice(&far);
                }
                #[cfg(not(target_arch = "x86_64"))]
                for (j, &k) in self.interval[..n].iter().enumerate() {
                    let [[a0, _], [a1, _]] = ridge.table.ends(k);
                    (h0[j], h1[j]) = (a0, a1);
                }
                let ends = h0[..n].iter().zip(&h1[..n]);
                for ((&h0, &h1), (&w, height)) in ends.zip(self.weight[..n].iter().zip(&mut self.height[..n])) {
                    *height += blend([[h0, 0.0], [h1, 0.0]], w).0;
                }
                continue;
            }
            // (On x86-64 four intervals at a time: `four_ends`.)
            #[cfg(target_arch = "x86_64")]
            let ends = {
                let [h0, s0, h1, s1] = &mut self.ends;
                for j in (0..n).step_by(4) {
                    let [a, b, c, d] = four_ends(ridge.table, &self.interval[j..j + 4]);
                    h0[j..j + 4].copy_from_slice(&a);
                    s0[j..j + 4].copy_from_slice(&b);
                    h1[j..j + 4].copy_from_slice(&c);
                    s1[j..j + 4].copy_from_slice(&d);
                }
                let [h0, s0, h1, s1] = &self.ends;
                h0[..n]
                    .iter()
                    .zip(&s0[..n])
                    .zip(h1[..n].iter().zip(&s1[..n]))
                    .map(|((&h0, &s0), (&h1, &s1))| [[h0, s0], [h1, s1]])
            };
            #[cfg(not(target_arch = "x86_64"))]
            let ends = {
                for (ends, &k) in self.ends[..n].iter_mut().zip(&self.interval[..n]) {
                    *ends = ridge.table.ends(k);
                }
                self.ends[..n].iter().copied()
            };
            let sample = ends.zip(&self.weight[..n]).zip(&mut self.height[..n]);
            let [sx, sy] = &mut self.slope;
            let normal = self.lean[..n].iter().zip(qx.iter().zip(qy)).zip(sx[..n].iter_mut().zip(&mut sy[..n]));
            for (((ends, &w), height), ((&lean, (&qx, &qy)), (sx, sy))) in sample.zip(normal) {
                let (z, dz) = blend(ends, w);
                *height += z;
                // The profile's normal (−slope, 1) in the x'z' plane, turned to the ray.
                let lean = S::from_f32(-dz) * lean;
                *sx += (lean * S::from_f32(qx)).to_f32();
                *sy += (lean * S::from_f32(qy)).to_f32();
            }
        }
        if K::NORMALS {
            // Normalised in a plain loop of their own, several at once.
            let [sx, sy] = &self.slope;
            let [nx, ny, nz] = &mut self.normal;
            for j in 0..n {
                [nx[j], ny[j], nz[j]] = unit_normal([sx[j], sy[j]]);
            }
        }
        let [nx, ny, nz] = &self.normal;
        for j in 0..n {
            sink.set(self.ready_index[j] as usize, self.height[j], [nx[j], ny[j], nz[j]]);
        }
        self.ready = 0;
    }
}

/// The samples at the ends of four intervals `k` ([`ProfileTable::ends`]), each read whole and
/// turned into lanes: the heights at their near ends, the slopes there, the heights at their
/// far ends and the slopes there. (Lanes past a queue read stale intervals, each one of the
/// table's.)
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn four_ends(table: &ProfileTable, k: &[u32]) -> [[f32; 4]; 4] {
    four_lanes(|l| {
        let [[a, b], [c, d]] = table.ends(k[l]);
        [a, b, c, d]
    })
}

/// Four records of four values, `read(0)` to `read(3)`, each read whole and turned into lanes
/// (SSE's transpose): lane l of the k-th array is value k of record l.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn four_lanes(read: impl Fn(usize) -> [f32; 4]) -> [[f32; 4]; 4] {
    use safe_arch::{m128, transpose_four_m128};
    let (mut a, mut b, mut c, mut d) =
        (m128::from(read(0)), m128::from(read(1)), m128::from(read(2)), m128::from(read(3)));
    transpose_four_m128(&mut a, &mut b, &mut c, &mut d);
    [a, b, c, d].map(m128::to_array)
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

impl<S: Scalar> Skin<'_, S> {
    /// Writes the requested maps of the whole surface (see [`Skin::render_tile`]).
    #[inline(always)]
    pub fn render(&self, render: &SkinRender, layers: SkinLayers) -> Result<(), SkinError> {
        self.render_tile(render, &Tile::whole(self.params.width, self.params.height), layers)
    }

    /// The lowest and highest height the surface can have: the sums over the levels of their
    /// profiles' lowest and highest sampled points (what `height16` and the preview scale).
    pub fn height_range(&self) -> [f32; 2] {
        let levels = &self.build.levels[..self.params.levels as usize];
        levels.iter().fold([0.0, 0.0], |[lo, hi], l| {
            let [a, b] = l.table.range();
            [lo + a, hi + b]
        })
    }

    /// Writes the requested maps (every [`Layers`] field but `time`) of `tile` of the surface,
    /// each pixel bit for bit as the whole surface has it, in one pass: the height (the sum
    /// over levels of the profile heights; `height16` over [`Skin::height_range`]); the normal
    /// (the profiles' slopes, Fig. 10); the cell map (for each pixel the index in
    /// [`Skin::cells`] of its cell at `cell_level`); the furrow mask ([`FURROWS`]: a pixel on
    /// the outline of a cell of a level, where its right or lower neighbour lies in another
    /// cell of that level; it needs the scratch); the shaded preview ([`super::shade`]'s
    /// lighting, the height scaled over [`Skin::height_range`]).
    ///
    /// Every buffer is checked first: if one is too short, the cell level is not below
    /// `levels`, or the preview's shading is out of range, nothing is written. The skin is only
    /// read (renders of one skin may run at once), and its working memory is on the stack
    /// (about 12 KiB in all: `tests/stack.rs`).
    #[inline(always)]
    pub fn render_tile(&self, render: &SkinRender, tile: &Tile, layers: SkinLayers) -> Result<(), SkinError> {
        // (A skin's normal map is its own, not derived from its heights.)
        let derived = layers.height16.is_some() || layers.normal_rgb8.is_some() || layers.preview.is_some();
        if derived || layers.mask.is_some() {
            self.render_derived(render, tile, layers)
        } else {
            self.render_own(render, tile, layers)
        }
    }

    /// Checks a render's tile, layers and cell level; the tile's pixel count.
    fn check_render(&self, render: &SkinRender, tile: &Tile, layers: &SkinLayers) -> Result<usize, SkinError> {
        tile.check_inside(self.params.width, self.params.height).map_err(SkinError::Raster)?;
        let pixels = layers.check(tile, |l| l != Layer::Time, |l| l.mask.is_some()).map_err(SkinError::Raster)?;
        if layers.cell.is_some() && render.cell_level >= self.params.levels {
            return Err(SkinError::Level);
        }
        Ok(pixels)
    }

    /// [`Skin::render_tile`] of the height, normal and cell maps only.
    #[inline(never)]
    fn render_own(&self, render: &SkinRender, tile: &Tile, layers: SkinLayers) -> Result<(), SkinError> {
        let pixels = self.check_render(render, tile, &layers)?;
        let Layers { height, normal, cell, .. } = layers;
        let cell = cell.map(|c| {
            c[..pixels].fill(u32::MAX);
            (&mut c[..pixels], render.cell_level)
        });
        // (Every pixel lies in a cell and is set; the fill is what a pixel in none would read.)
        let flat = unit_normal([0.0; 2]);
        match (height.map(|h| &mut h[..pixels]), normal.map(|n| &mut n[..pixels])) {
            (None, None) => self.draw(&mut NoMaps, cell, tile),
            (Some(h), None) => {
                h.fill(0.0);
                self.draw(&mut Heights(h), cell, tile);
            }
            (None, Some(n)) => {
                n.fill(flat);
                self.draw(&mut Normals(n), cell, tile);
            }
            (Some(h), Some(n)) => {
                h.fill(0.0);
                n.fill(flat);
                self.draw(&mut Both(h, n), cell, tile);
            }
        }
        Ok(())
    }

    /// [`Skin::render_tile`] with a derived layer (`height16`, `normal_rgb8`, the preview, the
    /// furrow mask).
    #[inline(never)]
    fn render_derived(&self, render: &SkinRender, tile: &Tile, layers: SkinLayers) -> Result<(), SkinError> {
        let pixels = self.check_render(render, tile, &layers)?;
        let light = match layers.preview {
            Some(_) => {
                render.shade.validate().map_err(SkinError::Shade)?;
                Light::of(&render.shade)
            }
            None => None,
        };
        let Layers { mask, height, height16, normal, normal_rgb8, cell, preview, scratch, .. } = layers;
        let cell = cell.map(|c| {
            c[..pixels].fill(u32::MAX);
            (&mut c[..pixels], render.cell_level)
        });
        let [low, high] = self.height_range();
        let per_span = if high > low { 1.0 / (high - low) } else { 1.0 };
        let mut outputs = Outputs {
            height: height.map(|h| &mut h[..pixels]),
            height16: height16.map(|h| &mut h[..pixels]),
            normal: normal.map(|n| &mut n[..pixels]),
            normal_rgb8: normal_rgb8.map(|n| &mut n[..pixels]),
            preview: preview.zip(light).map(|(p, l)| (&mut p[..pixels], l, &render.shade)),
            low,
            per_span,
        };
        if outputs.shades() {
            // What a pixel in no cell reads (every pixel of a built skin lies in one): height 0,
            // the normal straight up.
            let flat = unit_normal([0.0; 2]);
            outputs.fill(pixels, 0.0, flat);
            #[cfg(target_pointer_width = "64")]
            if !outputs.normals() {
                self.draw(&mut outputs.heights(), cell, tile);
            } else {
                self.draw(&mut outputs, cell, tile);
            }
            #[cfg(not(target_pointer_width = "64"))]
            self.draw(&mut outputs, cell, tile);
        } else {
            self.draw(&mut NoMaps, cell, tile);
        }
        if let (Some(mask), Some(scratch)) = (mask, scratch) {
            self.draw_furrows(tile, &mut mask[..pixels], scratch);
        }
        Ok(())
    }

    /// The furrow mask of `tile` ([`FURROWS`]), working in `scratch`: per level, the cell map of
    /// the tile with one more column on the right and one more row below (wrapping on a
    /// periodic surface, absent past an open one's edge), then the outlines it shows.
    #[inline(never)]
    fn draw_furrows(&self, tile: &Tile, mask: &mut [u8], scratch: &mut [u32]) {
        let (w, h) = (self.params.width, self.params.height);
        let periodic = self.params.periodic;
        let (tw, th) = (tile.width as usize, tile.height as usize);
        let columns = tw + 1;
        let map = &mut scratch[..columns * (th + 1)];
        // The surface column (row) of the margin, if there is one.
        let beyond = |start: u32, length: u32, size: u32| match start + length {
            end if end < size => Some(end),
            _ if periodic => Some(0),
            _ => None,
        };
        let (margin_x, margin_y) = (beyond(tile.x, tile.width, w), beyond(tile.y, tile.height, h));
        mask.fill(0);
        let mut held = held();
        for level in 0..self.params.levels {
            map.fill(u32::MAX);
            for (index, c) in self.cells().iter().enumerate().filter(|(_, c)| c.level == level) {
                self.for_each_run(c, &mut held, |_, x0, x1, wx, wy| {
                    let n = (x1 - x0) as u32;
                    let mut put_row = |r: usize| {
                        let (s, e) = (wx.max(tile.x), (wx + n).min(tile.x + tile.width));
                        if s < e {
                            let at = r * columns + (s - tile.x) as usize;
                            map[at..at + (e - s) as usize].fill(index as u32);
                        }
                        if margin_x.is_some_and(|m| (wx..wx + n).contains(&m)) {
                            map[r * columns + tw] = index as u32;
                        }
                    };
                    if (tile.y..tile.y + tile.height).contains(&wy) {
                        put_row((wy - tile.y) as usize);
                    }
                    if margin_y == Some(wy) {
                        put_row(th);
                    }
                });
            }
            let value = FURROWS[level as usize];
            // A pixel's right neighbour is in its row for every pixel but the last (which has
            // one in the margin, if there is one), its lower one in the next row for every row
            // but the last (likewise): the others in plain loops, several pixels at once.
            let Some(last) = tw.checked_sub(1) else { continue };
            let mark = |m: &mut u8, on: bool| *m = if on { (*m).max(value) } else { *m };
            for y in 0..th {
                let (row, out) = (&map[y * columns..][..columns], &mut mask[y * tw..][..tw]);
                let pairs = out[..last].iter_mut().zip(row[..last].iter().zip(&row[1..tw]));
                match (y + 1 < th || margin_y.is_some()).then(|| &map[(y + 1) * columns..][..tw]) {
                    Some(next) => {
                        for ((m, (&here, &right)), &below) in pairs.zip(next) {
                            mark(m, (right != here) | (below != here));
                        }
                    }
                    None => pairs.for_each(|(m, (&here, &right))| mark(m, right != here)),
                }
                let (here, below) =
                    (row[last], (y + 1 < th || margin_y.is_some()).then(|| map[(y + 1) * columns + last]));
                mark(&mut out[last], (margin_x.is_some() && row[tw] != here) | below.is_some_and(|b| b != here));
            }
        }
    }

    /// Sets every pixel's height and normal in `sink`, summed over the levels, and writes the
    /// cells of one level into the cell map.
    ///
    /// The cells of the finest level are drawn: the cells of every coarser level are the
    /// unions of their descendants, pixel for pixel, so a pixel's coarser cells are its finest
    /// cell's ancestors, which come before it in [`Skin::cells`]. Each level's fan is kept
    /// while its descendants are drawn.
    #[inline(never)] // one Batch on the stack at a time, whichever maps are drawn
    fn draw<K: Sink>(&self, sink: &mut K, mut cell: Option<(&mut [u32], u32)>, tile: &Tile) {
        if !K::SHADES {
            // A cell map alone needs only the pixels of its level's cells.
            let Some((map, level)) = cell else { return };
            let mut held = held();
            for (index, c) in self.cells().iter().enumerate().filter(|(_, c)| c.level == level) {
                self.for_each_run(c, &mut held, |_, x0, x1, wx, wy| {
                    if let Some((x0, x1, i0)) = clip_run(tile, x0, x1, wx, wy) {
                        map[i0..i0 + (x1 - x0) as usize].fill(index as u32);
                    }
                });
            }
            return;
        }
        let mut fans = [FanAt::default(); MAX_LEVELS];
        let mut batch = Batch::<S>::new();
        let mut held = held();
        let to_pixels = 1.0 / (1u64 << self.fixed_point_bits()) as f64;
        let levels = self.params.levels as usize;
        let finest = levels - 1;
        let wedges = self.build.wedges();
        let ridges: [Ridge<S>; MAX_LEVELS] = core::array::from_fn(|level| {
            let table = &self.build.levels[level.min(levels - 1)].table;
            let roundness = S::from_f32(self.params.level[level].roundness);
            Ridge { table, end: S::from_f32(table.end), roundness, flat: S::ONE - roundness }
        });
        let ridges = &ridges[..levels];
        for (index, c) in self.cells().iter().enumerate() {
            let level = c.level as usize;
            if level < finest && batch.len > 0 {
                // The queued pixels lie in the cell this one follows.
                batch.flush(&Fans { wedges, at: &fans, finest }, ridges, sink);
            }
            let start = c.first_vertex as usize + index;
            let slots = &wedges[start..][..c.vertex_count as usize + 1];
            let centre = [(c.centre[0] as f64 * to_pixels) as f32, (c.centre[1] as f64 * to_pixels) as f32];
            fans[level] =
                FanAt { start, len: slots.len(), sorted: slots[0].angle == ASCENDING, centre, cell: index as u32 };
            if level < finest {
                continue;
            }
            let view = Fans { wedges, at: &fans, finest };
            let mut map = cell.as_mut().map(|(map, level)| (&mut **map, fans[*level as usize].cell));
            self.for_each_run(c, &mut held, |y, x0, x1, wx, wy| {
                let Some((x0, x1, i0)) = clip_run(tile, x0, x1, wx, wy) else { return };
                if let Some((map, owner)) = map.as_mut() {
                    map[i0..i0 + (x1 - x0) as usize].fill(*owner);
                }
                batch.span(&view, ridges, sink, [y, x0, x1], i0);
            });
            batch.close_cell(&view);
        }
        batch.flush(&Fans { wedges, at: &fans, finest }, ridges, sink);
        batch.evaluate(ridges, sink);
    }

    /// Calls `visit(row, x0, x1, wrapped x0, wrapped row)` for every run of pixels `x0..x1` of
    /// one row whose centres lie in `cell`: unwrapped as the outline places them, and on the
    /// surface, where the run is contiguous (a run across the periodic seam comes in two
    /// pieces).
    ///
    /// The rows and columns scanned are bounded by the surface's size, whatever the outline's
    /// reach: off a period, the surface's rows; on one, those within two periods of the cell's
    /// centre (a cell of the periodic tessellation lies within about half a period of its
    /// centre; only an edge perturbed past the period, which would overlap the cell's own
    /// images, reaches beyond, and it is cut there).
    fn for_each_run(&self, cell: &SkinCell, held: &mut Held, mut visit: impl FnMut(i64, i64, i64, u32, u32)) {
        let (w, h) = (i64::from(self.params.width), i64::from(self.params.height));
        let periodic = self.params.periodic;
        let bits = self.fixed_point_bits();
        let centre = [cell.centre[0] >> bits, cell.centre[1] >> bits];
        let (rows, columns) = if periodic {
            ([centre[1] - 2 * h, centre[1] + 2 * h], [centre[0] - 2 * w, centre[0] + 2 * w])
        } else {
            ([0, h - 1], [0, w])
        };
        super::scan::for_each_span(self.outline(cell), bits, rows, held, |y, x0, x1| {
            let (x0, x1) = (x0.max(columns[0]), x1.min(columns[1]));
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
    /// in `cell`: unwrapped as the outline places it, and on the surface.
    pub(super) fn for_each_pixel_unwrapped(&self, cell: &SkinCell, mut visit: impl FnMut(i64, i64, u32, u32)) {
        self.for_each_run(cell, &mut held(), |y, x0, x1, wx, wy| {
            for (x, wx) in (x0..x1).zip(wx..) {
                visit(x, y, wx, wy);
            }
        });
    }
}

/// The part of a run (`x0..x1` unwrapped, starting at surface column `wx` of row `wy`) in
/// `tile`: its unwrapped columns and the tile index of its first pixel.
fn clip_run(tile: &Tile, x0: i64, x1: i64, wx: u32, wy: u32) -> Option<(i64, i64, usize)> {
    if !(tile.y..tile.y + tile.height).contains(&wy) {
        return None;
    }
    let n = (x1 - x0) as u32;
    let (s, e) = (wx.max(tile.x), (wx + n).min(tile.x + tile.width));
    if s >= e {
        return None;
    }
    let start = x0 + i64::from(s - wx);
    let i0 = (wy - tile.y) as usize * tile.width as usize + (s - tile.x) as usize;
    Some((start, start + i64::from(e - s), i0))
}

/// Fills `slots` (one more than `outline`'s length) with the fan of the cell of this
/// outline and centre (fixed point of `bits` fractional bits), as [`Fan`] reads it.
pub(super) fn fan(outline: &[[i64; 2]], c: [i64; 2], bits: u32, slots: &mut [Wedge]) {
    let n = outline.len();
    // 2^−bits: scaling by it is exact, so that (x as f32)·to_pixels rounds x / unit once,
    // like an exact division (below 2^53 also like (x as f64 / unit) as f32).
    let to_pixels = 1.0 / (1u64 << bits) as f32;
    let pixels = |x: i64| x as f32 * to_pixels;
    // Corner i relative to the centre, and its edge (to the next corner; the last corner's
    // edge ends at the first), in pixels. Wrapping, as release builds always did: a stretch of
    // 1e21 puts an outline's fixed-point corners far enough apart that the differences
    // overflow i64 (found by fuzzing; a panic with overflow checks on).
    let corner = |i: usize, a: [i64; 2]| {
        let b = *outline.get(i + 1).unwrap_or(&outline[0]);
        let v = [pixels(a[0].wrapping_sub(c[0])), pixels(a[1].wrapping_sub(c[1]))];
        (v, [pixels(b[0].wrapping_sub(a[0])), pixels(b[1].wrapping_sub(a[1]))])
    };
    let wedges = &mut slots[1..=n];
    // The first corner of smallest angle: the fan starts there.
    let (mut start, mut smallest) = (0, f32::INFINITY);
    // Four corners at a time on x86-64 (a finest cell has about ten), their square roots and
    // divisions in SSE's lanes; the lanes past the last corner repeat it and are not written.
    #[cfg(target_arch = "x86_64")]
    {
        for (chunk, at) in wedges.chunks_mut(4).zip((0..n).step_by(4)) {
            let (mut v, mut e) = ([[0.0f32; 4]; 2], [[0.0f32; 4]; 2]);
            for l in 0..4 {
                let i = (at + l).min(n - 1);
                let (vl, el) = corner(i, outline[i]);
                [v[0][l], v[1][l], e[0][l], e[1][l]] = [vl[0], vl[1], el[0], el[1]];
            }
            // (Lane by lane: a copy of the chunk's length would be a call.)
            for (w, made) in chunk.iter_mut().zip(four_wedges(v, e)) {
                *w = made;
            }
        }
        for (i, w) in wedges.iter().enumerate() {
            if w.angle < smallest || i == 0 {
                (start, smallest) = (i, w.angle);
            }
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    for (i, (w, &a)) in wedges.iter_mut().zip(outline).enumerate() {
        let (v, e) = corner(i, a);
        *w = wedge(v, e);
        if w.angle < smallest || i == 0 {
            (start, smallest) = (i, w.angle);
        }
    }
    wedges.rotate_left(start);
    let ascending = ascends(wedges);
    slots[0] = Wedge { angle: if ascending { ASCENDING } else { 0.0 }, ..slots[n] };
}

/// The wedge of a corner `v` (relative to the centre) whose edge (to the next corner) is `e`,
/// in pixels.
#[cfg_attr(target_arch = "x86_64", allow(dead_code))]
#[inline(always)]
fn wedge(v: [f32; 2], e: [f32; 2]) -> Wedge {
    let ([vx, vy], [ex, ey]) = (v, e);
    let length = crate::scalar::sqrtf(ex * ex + ey * ey);
    // Outward normal of a counter-clockwise edge, unnormalised: (e_y, −e_x).
    let outward = [ey, -ex];
    let reach = vx * outward[0] + vy * outward[1];
    let per_reach = 1.0 / reach;
    // With the centre on or beyond this edge's line (a fold), the wedge reads as edge.
    let kept = (reach > 0.0) & (length > 0.0);
    let g = if kept { [outward[0] * per_reach, outward[1] * per_reach] } else { [0.0, 0.0] };
    let inverse_apothem = if kept { length * per_reach } else { 1.0 };
    Wedge { g, inverse_apothem, angle: pseudo_angle([vx, vy]) }
}

/// [`wedge`] of four corners (x and y of each in a lane) in SSE, bit for bit: each lane's
/// arithmetic is the same IEEE operations in the same order, each choice made with masks.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn four_wedges(v: [[f32; 4]; 2], e: [[f32; 4]; 2]) -> [Wedge; 4] {
    use safe_arch::*;
    let splat = set_splat_m128;
    let (vx, vy, ex, ey) = (m128::from(v[0]), m128::from(v[1]), m128::from(e[0]), m128::from(e[1]));
    let length = sqrt_m128(add_m128(mul_m128(ex, ex), mul_m128(ey, ey)));
    let across = bitxor_m128(ex, splat(-0.0));
    let reach = add_m128(mul_m128(vx, ey), mul_m128(vy, across));
    let per_reach = div_m128(splat(1.0), reach);
    let kept = bitand_m128(cmp_gt_mask_m128(reach, zeroed_m128()), cmp_gt_mask_m128(length, zeroed_m128()));
    let mut gx = bitand_m128(kept, mul_m128(ey, per_reach));
    let mut gy = bitand_m128(kept, mul_m128(across, per_reach));
    let mut inverse_apothem =
        bitor_m128(bitand_m128(kept, mul_m128(length, per_reach)), bitandnot_m128(kept, splat(1.0)));
    // The pseudo-angle of v, as [`pseudo_angles`] makes it.
    let (upper, right) = (cmp_ge_mask_m128(vy, zeroed_m128()), cmp_ge_mask_m128(vx, zeroed_m128()));
    let (ax, ay) = (bitandnot_m128(splat(-0.0), vx), bitandnot_m128(splat(-0.0), vy));
    let differ = bitxor_m128(upper, right);
    let num = bitor_m128(bitand_m128(differ, ax), bitandnot_m128(differ, ay));
    let base = add_m128(bitandnot_m128(upper, splat(2.0)), bitand_m128(differ, splat(1.0)));
    let sum = add_m128(ax, ay);
    let zero = cmp_eq_mask_m128(sum, zeroed_m128());
    let total = bitor_m128(bitand_m128(zero, splat(1.0)), bitandnot_m128(zero, sum));
    let mut angle = add_m128(div_m128(num, total), base);
    // (A lane per wedge.)
    transpose_four_m128(&mut gx, &mut gy, &mut inverse_apothem, &mut angle);
    [gx, gy, inverse_apothem, angle].map(|w| {
        let [x, y, inverse_apothem, angle] = w.to_array();
        Wedge { g: [x, y], inverse_apothem, angle }
    })
}

/// The front slot's angle (which no pixel compares with) in a fan whose angles ascend.
const ASCENDING: f32 = 1.0;

/// [`pseudo_angle`] of eight directions, bit for bit, each step a plain loop over the eight so
/// that the divisions go four at a time: a zero vector's fraction is 0 / 1 (it lies in
/// quadrant 0, so its angle is 0, as [`pseudo_angle`] gives it).
#[inline(always)]
fn pseudo_angles(x: [f32; 8], y: [f32; 8]) -> [f32; 8] {
    let (mut num, mut length, mut base) = ([0.0f32; 8], [0.0f32; 8], [0.0f32; 8]);
    for l in 0..8 {
        let (upper, right) = (y[l] >= 0.0, x[l] >= 0.0);
        let (ax, ay) = (x[l].abs(), y[l].abs());
        num[l] = if upper == right { ay } else { ax };
        base[l] = (i32::from(!upper) << 1 | i32::from(upper != right)) as f32;
        let sum = ax + ay;
        length[l] = if sum == 0.0 { 1.0 } else { sum };
    }
    let mut out = [0.0f32; 8];
    for l in 0..8 {
        out[l] = num[l] / length[l];
    }
    for l in 0..8 {
        out[l] += base[l];
    }
    out
}

/// How many of `wedges` (at least one, their angles ascending) have an angle at most `a`: a
/// binary search whose steps depend on the fan's length alone, not on `a` (each picks one of
/// two indices, with no branch).
#[inline(always)]
fn at_most(wedges: &[Wedge], a: f32) -> usize {
    let (mut base, mut size) = (0, wedges.len());
    while size > 1 {
        let half = size / 2;
        base = if wedges[base + half].angle <= a { base + half } else { base };
        size -= half;
    }
    base + usize::from(wedges[base].angle <= a)
}

/// Whether the angles of a fan's wedges ascend from the first to the last (the fan of a cell
/// star-shaped around its centre): then a pixel's wedge is found by counting.
fn ascends(wedges: &[Wedge]) -> bool {
    wedges.windows(2).all(|w| w[0].angle.partial_cmp(&w[1].angle).is_some_and(Ordering::is_le))
}

/// Fig. 10: each level's normal has z = 1; x and y add up to `slope`. Rows run down the
/// raster, so y flips for a y-up normal map.
fn unit_normal(slope: [f32; 2]) -> [f32; 3] {
    let (x, y) = (slope[0], -slope[1]);
    let s = Scalar::inverse_sqrt(x * x + y * y + 1.0);
    [x * s, y * s, s]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[cfg(target_arch = "x86_64")]
    #[test]
    fn four_wedges_are_the_wedges_bit_for_bit() {
        // Every sign and zero, folds (the centre on or beyond the edge's line), zero-length
        // edges, tiny and huge magnitudes; then a spread as cells' corners have.
        let values = [0.0, -0.0, f32::from_bits(1), -f32::MIN_POSITIVE, 1.0, -1.0, 0.5, -7.25, 123.5, 3.0e18, -1e-20];
        let special = values.iter().flat_map(|&x| values.iter().map(move |&y| [x, y]));
        let spread = (0..4096u32).map(|i| [libm::sinf(i as f32 * 0.37) * 9.0, libm::cosf(i as f32 * 0.11) * -11.0]);
        let mut all = [[0.0f32; 2]; 11 * 11 + 4096];
        for (slot, d) in all.iter_mut().zip(special.chain(spread)) {
            *slot = d;
        }
        let bits = |w: &Wedge| [w.g[0], w.g[1], w.inverse_apothem, w.angle].map(f32::to_bits);
        let mut checked = 0;
        for (k, chunk) in all.chunks_exact(4).enumerate() {
            let chunk: [[f32; 2]; 4] = core::array::from_fn(|l| chunk[l]);
            // Each corner with the edges of corners further on, so that every pairing comes up.
            let edges: [[f32; 2]; 4] = core::array::from_fn(|l| all[(k * 7 + l * 13 + 1) % all.len()]);
            let v = [chunk.map(|d| d[0]), chunk.map(|d| d[1])];
            let e = [edges.map(|d| d[0]), edges.map(|d| d[1])];
            for (l, got) in four_wedges(v, e).iter().enumerate() {
                let want = wedge(chunk[l], edges[l]);
                assert_eq!(bits(got), bits(&want), "{:?} {:?}", chunk[l], edges[l]);
                checked += 1;
            }
        }
        assert!(checked >= 4096, "{checked}");
    }

    #[test]
    fn eight_pseudo_angles_are_the_pseudo_angles_bit_for_bit() {
        // Every quadrant and axis, both zeros, the smallest and largest magnitudes, infinities
        // and NaN, paired every way; then a spread of offsets as a render's pixels have.
        let values = [
            0.0,
            -0.0,
            f32::from_bits(1),
            -f32::from_bits(1),
            f32::MIN_POSITIVE,
            1.0,
            -1.0,
            0.5,
            3.0e38,
            -3.0e38,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
            1e-30,
            -7.25,
            123.5,
        ];
        let special = values.iter().flat_map(|&x| values.iter().map(move |&y| [x, y]));
        let spread = (0..4096u32).map(|i| {
            let v = libm::sinf(i as f32 * 0.37) * 90.0 + (i % 7) as f32 * 0.5;
            [v, libm::cosf(i as f32 * 0.11) * -117.0 + 0.5]
        });
        let (mut chunk, mut filled, mut checked) = ([[0.0f32; 2]; 8], 0, 0);
        for d in special.chain(spread) {
            chunk[filled] = d;
            filled += 1;
            if filled == 8 {
                let got = pseudo_angles(chunk.map(|d| d[0]), chunk.map(|d| d[1]));
                for (d, a) in chunk.iter().zip(got) {
                    let want = pseudo_angle(*d);
                    assert!(a.to_bits() == want.to_bits() || (a.is_nan() && want.is_nan()), "{d:?}: {a} {want}");
                }
                (filled, checked) = (0, checked + 8);
            }
        }
        assert_eq!(checked, 256 + 4096);
    }
}
