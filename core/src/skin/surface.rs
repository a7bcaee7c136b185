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

use super::cell::MAX_OUTLINE;
use super::{Skin, SkinCell, SkinError};
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

impl Skin<'_> {
    /// Writes the requested maps. Every buffer is checked first: if one is too short, or the
    /// cell level is not below `levels`, nothing is written. Uses about 48 KiB of stack for
    /// one outline's wedges and crossings.
    pub fn render<S: Scalar>(&self, layers: SkinLayers) -> Result<(), SkinError> {
        let pixels = self.params.width as usize * self.params.height as usize;
        let SkinLayers { mut height, mut normal, mut cell, cell_level } = layers;
        let lengths =
            [height.as_ref().map(|b| b.len()), normal.as_ref().map(|b| b.len()), cell.as_ref().map(|b| b.len())];
        if lengths.iter().flatten().any(|&n| n < pixels) {
            return Err(SkinError::BufferTooSmall { needed: pixels });
        }
        if cell.is_some() && cell_level >= self.params.levels {
            return Err(SkinError::Level);
        }
        let width = self.params.width as usize;
        if let Some(h) = height.as_deref_mut() {
            h[..pixels].fill(0.0);
        }
        if let Some(n) = normal.as_deref_mut() {
            n[..pixels].fill([0.0; 3]);
        }
        if let Some(c) = cell.as_deref_mut() {
            c[..pixels].fill(u32::MAX);
        }
        let mut wedges = [Wedge::default(); MAX_OUTLINE];
        let mut crossings = [0u64; MAX_OUTLINE];
        for (index, c) in self.cells.iter().enumerate() {
            let level = c.level as usize;
            let table = &self.tables[level];
            let roundness = S::from_f32(self.params.level[level].roundness);
            let end = S::from_f32(table.end);
            // Wedges serve heights and normals; a cell map alone needs only the pixels.
            let n = if height.is_some() || normal.is_some() { self.prepare(c, &mut wedges) } else { 0 };
            let unit = (1u64 << self.fixed_point_bits()) as f64;
            let centre = [(c.centre[0] as f64 / unit) as f32, (c.centre[1] as f64 / unit) as f32];
            let writes_cell = c.level == cell_level;
            self.for_each_pixel_unwrapped(c, &mut crossings, |x, y, wx, wy| {
                let i = wy as usize * width + wx as usize;
                if writes_cell && let Some(map) = cell.as_deref_mut() {
                    map[i] = index as u32;
                }
                if height.is_none() && normal.is_none() {
                    return;
                }
                let d = [(x as f32 + 0.5) - centre[0], (y as f32 + 0.5) - centre[1]];
                let (z, slope_xy) = if d == [0.0, 0.0] {
                    (table.at(0.0).0, [0.0, 0.0])
                } else {
                    // The fan triangle the ray from the centre through p leaves by: wedges
                    // are sorted by the angle of their first corner.
                    let a = pseudo_angle(d);
                    let k = wedges[..n].partition_point(|w| w.angle <= a);
                    let current = if k == 0 { n - 1 } else { k - 1 };
                    let w = wedges[current];
                    evaluate::<S>(table, end, roundness, d, w)
                };
                if let Some(h) = height.as_deref_mut() {
                    h[i] += z;
                }
                if let Some(nm) = normal.as_deref_mut() {
                    nm[i][0] += slope_xy[0];
                    nm[i][1] += slope_xy[1];
                }
            });
        }
        if let Some(nm) = normal {
            for v in &mut nm[..pixels] {
                // Fig. 10: each level's normal has z = 1; x and y add up. Rows run down the
                // raster, so y flips for a y-up normal map.
                let (x, y) = (v[0], -v[1]);
                let length = libm::sqrtf(x * x + y * y + 1.0);
                *v = [x / length, y / length, 1.0 / length];
            }
        }
        Ok(())
    }

    /// Fills `wedges` for `cell`'s outline; returns the outline length.
    fn prepare(&self, cell: &SkinCell, wedges: &mut [Wedge]) -> usize {
        let outline = self.outline(cell);
        let n = outline.len();
        let unit = (1u64 << self.fixed_point_bits()) as f64;
        let c = cell.centre;
        for i in 0..n {
            let (a, b) = (outline[i], outline[(i + 1) % n]);
            let va = [((a[0] - c[0]) as f64 / unit) as f32, ((a[1] - c[1]) as f64 / unit) as f32];
            let e = [((b[0] - a[0]) as f64 / unit) as f32, ((b[1] - a[1]) as f64 / unit) as f32];
            // Outward normal of a counter-clockwise edge, unnormalised: (e_y, −e_x).
            let outward = [e[1], -e[0]];
            let reach = va[0] * outward[0] + va[1] * outward[1];
            let length = libm::sqrtf(e[0] * e[0] + e[1] * e[1]);
            // Stored from the corner of smallest angle on, so that (for a cell star-shaped
            // around its centre, as Voronoi cells and their perturbations are) the angles
            // ascend and a binary search finds a pixel's wedge.
            wedges[i] = if reach > 0.0 && length > 0.0 {
                Wedge {
                    g: [outward[0] / reach, outward[1] / reach],
                    inverse_apothem: length / reach,
                    angle: pseudo_angle(va),
                }
            } else {
                // The centre on or beyond this edge's line (a fold): this wedge reads as edge.
                Wedge { g: [0.0, 0.0], inverse_apothem: 1.0, angle: pseudo_angle(va) }
            };
        }
        let start = (0..n).fold(0, |best, i| if wedges[i].angle < wedges[best].angle { i } else { best });
        wedges[..n].rotate_left(start);
        n
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
        let (w, h) = (i64::from(self.params.width), i64::from(self.params.height));
        let periodic = self.params.periodic;
        super::scan::for_each_pixel(self.outline(cell), self.fixed_point_bits(), crossings, |x, y| {
            let (wx, wy) = if periodic { (x.rem_euclid(w), y.rem_euclid(h)) } else { (x, y) };
            if (0..w).contains(&wx) && (0..h).contains(&wy) {
                visit(x, y, wx as u32, wy as u32);
            }
        });
    }
}

/// One level's height and normal x/y (z = 1) at offset `d` from the centre, in wedge `w`.
#[inline]
fn evaluate<S: Scalar>(
    table: &super::profile::ProfileTable,
    end: S,
    roundness: S,
    d: [f32; 2],
    w: Wedge,
) -> (f32, [f32; 2]) {
    // Offsets in apothems keep every quantity small (Q16.16 has range ±32768).
    let scale = S::from_f32(w.inverse_apothem);
    let q = [S::from_f32(d[0]) * scale, S::from_f32(d[1]) * scale];
    let u = (S::from_f32(d[0] * w.g[0] + d[1] * w.g[1])).clamp(S::ZERO, S::ONE);
    let r = (q[0] * q[0] + q[1] * q[1]).sqrt();
    // k = |b − p0| / apothem − 1, with |b − p0| = |p − p0| / u.
    let k = if u > S::RESOLUTION { (r / u - S::ONE).max(S::ZERO) } else { S::ZERO };
    // Polygonal x' (u) blended with circular x' (|p − p0| / apothem = u·(1 + k), capped at the
    // edge): ρ = 1 gives circles inscribed in each edge, the corners beyond them at the foot.
    let circular = u * (S::ONE + k);
    let (round, round_rate) = if circular < S::ONE { (circular, S::ONE + k) } else { (S::ONE, S::ZERO) };
    let flat = S::ONE - roundness;
    let bent = flat * u + roundness * round;
    let rate = flat + roundness * round_rate;
    let (z, dz) = table.at((end * bent).to_f32());
    if r <= S::ZERO {
        return (z, [0.0, 0.0]);
    }
    // The profile's normal (−slope, 1) in the x'z' plane, turned to the ray's direction.
    let lean = (S::ZERO - S::from_f32(dz) * rate) / r;
    (z, [(lean * q[0]).to_f32(), (lean * q[1]).to_f32()])
}
