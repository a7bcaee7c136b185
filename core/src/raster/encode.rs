//! Formats an engine uploads, and normals from a height field: what every model's render
//! turns its heights, normals and colours into.

use super::{Clip, Tile};

/// A height in [0, 1] (clamped) as 16 bits: round(h · 65535).
pub fn height16(h: f32) -> u16 {
    // (libm's roundf is trunc(v + copysign(HALF, v)); the conversion truncates and saturates
    // alike, and NaN converts to 0 either way.)
    let v = h.clamp(0.0, 1.0) * 65535.0;
    (v + HALF.copysign(v)) as u16
}

/// A unit normal as an 8-bit RGB texel: each component c as round((c · ½ + ½) · 255).
pub fn normal_rgb8(n: [f32; 3]) -> [u8; 3] {
    // round(v) clamped to [0, 255] and converted, bit for bit: libm's roundf is
    // trunc(v + copysign(HALF, v)), and truncating before or after the clamp gives the same
    // conversion (which truncates itself; NaN stays NaN and converts to 0).
    n.map(|c| {
        let v = (c * 0.5 + 0.5) * 255.0;
        (v + HALF.copysign(v)).clamp(0.0, 255.0) as u8
    })
}

/// The largest `f32` below ½: added with the value's sign before truncating, it rounds half
/// away from zero (libm's roundf), without the value's ties of ½ − ulp rounding up.
const HALF: f32 = 0.5 - 0.25 * f32::EPSILON;

/// Linear [0, 1] (clamped) to an 8-bit sRGB code (IEC 61966-2-1).
pub fn srgb8(v: f32) -> u8 {
    let v = v.clamp(0.0, 1.0);
    let s = if v <= 0.003_130_8 { 12.92 * v } else { 1.055 * libm::powf(v, 1.0 / 2.4) - 0.055 };
    libm::roundf(s * 255.0) as u8
}

/// Linear RGB as an opaque 8-bit sRGB RGBA texel.
pub fn srgb8_opaque(c: [f32; 3]) -> [u8; 4] {
    [srgb8(c[0]), srgb8(c[1]), srgb8(c[2]), 255]
}

/// [`srgb8`] for many values: the smallest value of each code, found once, so that a code is
/// eight comparisons instead of a power. The same code as [`srgb8`] for every `f32` (a value
/// whose code is k is at least the smallest value of code k, and below that of k + 1: `srgb8`
/// never falls as its value rises, which its test checks at every `f32` from 0 to 1).
pub struct Srgb8 {
    /// `lowest[k]`: the smallest value whose code is at least k (`lowest[0]` is −∞).
    lowest: [f32; 256],
}

impl Srgb8 {
    /// The table, from [`srgb8`] itself: each code's smallest value by bisection over the
    /// `f32`s from 0 to 1 (255 × 30 conversions).
    pub fn new() -> Srgb8 {
        let mut lowest = [f32::NEG_INFINITY; 256];
        for (k, lowest) in lowest.iter_mut().enumerate().skip(1) {
            // The smallest bits in (below, above] whose code is at least k.
            let (mut below, mut above) = (0u32, 1.0f32.to_bits());
            if srgb8(0.0) >= k as u8 {
                *lowest = 0.0;
                continue;
            }
            while above - below > 1 {
                let middle = below + (above - below) / 2;
                if srgb8(f32::from_bits(middle)) >= k as u8 {
                    above = middle;
                } else {
                    below = middle;
                }
            }
            *lowest = f32::from_bits(above);
        }
        Srgb8 { lowest }
    }

    /// [`srgb8`] of `v`.
    pub fn code(&self, v: f32) -> u8 {
        let mut code = 0usize;
        for step in [128, 64, 32, 16, 8, 4, 2, 1] {
            if v >= self.lowest[code + step] {
                code += step;
            }
        }
        code as u8
    }

    /// [`srgb8_opaque`] of `c`.
    pub fn opaque(&self, c: [f32; 3]) -> [u8; 4] {
        [self.code(c[0]), self.code(c[1]), self.code(c[2]), 255]
    }
}

impl Default for Srgb8 {
    fn default() -> Self {
        Srgb8::new()
    }
}

/// The heights of a tile and a one-pixel margin around it, kept as `f32` bits in a render's
/// scratch; the margin is what the tile's normals read across its edges.
pub struct HeightWindow<'s> {
    heights: &'s mut [u32],
    tile: Tile,
    /// The image's width and height.
    image: [u32; 2],
    periodic: bool,
}

impl<'s> HeightWindow<'s> {
    /// A window over `scratch` (at least [`super::scratch_len`] values) for `tile` of an image
    /// `image` pixels wide and high, every height `fill`.
    pub fn new(scratch: &'s mut [u32], tile: Tile, image: [u32; 2], periodic: bool, fill: f32) -> Self {
        let len = (tile.width as usize + 2) * (tile.height as usize + 2);
        let heights = &mut scratch[..len];
        heights.fill(fill.to_bits());
        HeightWindow { heights, tile, image, periodic }
    }

    /// The clip a drawing into the window visits.
    pub fn clip(&self) -> Clip {
        self.tile.clip(1)
    }

    /// The height at a clip index.
    pub fn at(&self, i: usize) -> f32 {
        f32::from_bits(self.heights[i])
    }

    /// Sets the height at a clip index.
    pub fn set(&mut self, i: usize, h: f32) {
        self.heights[i] = h.to_bits();
    }

    /// The heights' bits, row by row over [`HeightWindow::clip`].
    pub(crate) fn bits(&mut self) -> &mut [u32] {
        self.heights
    }

    /// The height of the tile's pixel (column, row within the tile).
    pub fn inside(&self, x: u32, y: u32) -> f32 {
        self.at((y as usize + 1) * (self.tile.width as usize + 2) + x as usize + 1)
    }

    /// The unit normal (x right, y up, z out) of the tile's pixel (column, row within the
    /// tile), by central differences of the heights scaled by `bump` (pixels per unit of
    /// height): across the edge of a periodic image (more than two pixels on that axis) from
    /// the margin, one-sided at an open image's edges.
    pub fn normal(&self, x: u32, y: u32, bump: f32) -> [f32; 3] {
        let columns = self.tile.width as usize + 2;
        // The neighbours of image coordinate i among n (as offsets from i) and their distance.
        let around = |i: u32, n: u32| -> (i64, i64, f32) {
            if self.periodic && n > 2 {
                (-1, 1, 2.0)
            } else {
                let (a, b) = (i.saturating_sub(1), (i + 1).min(n - 1));
                (i64::from(a) - i64::from(i), i64::from(b) - i64::from(i), (b - a).max(1) as f32)
            }
        };
        let (ix, iy) = (self.tile.x + x, self.tile.y + y);
        let (left, right, dx) = around(ix, self.image[0]);
        let (up, down, dy) = around(iy, self.image[1]);
        let at = |dx: i64, dy: i64| {
            let (cx, cy) = (i64::from(x) + 1 + dx, i64::from(y) + 1 + dy);
            self.at(cy as usize * columns + cx as usize)
        };
        let gx = (at(right, 0) - at(left, 0)) / dx * bump;
        // Rows run down the image; y runs up.
        let gy = (at(0, up) - at(0, down)) / dy * bump;
        let length = libm::sqrtf(gx * gx + gy * gy + 1.0);
        [-gx / length, -gy / length, 1.0 / length]
    }

    /// Writes the layers derived from the window's heights, pixel by pixel over its tile:
    /// the height (`f32` and 16-bit) and the unit normal (`f32` and RGB8, [`Self::normal`] at
    /// `bump`), each where asked; `shade(i, normal)` is called with every pixel's normal when
    /// given (a model's preview).
    pub fn write(&self, bump: f32, out: Derived<'_>, mut shade: Option<&mut dyn FnMut(usize, [f32; 3])>) {
        let Derived { mut height, height16: mut h16, mut normal, normal_rgb8: mut n8 } = out;
        let wants_normal = normal.is_some() || n8.is_some() || shade.is_some();
        for y in 0..self.tile.height {
            for x in 0..self.tile.width {
                let i = y as usize * self.tile.width as usize + x as usize;
                let h = self.inside(x, y);
                if let Some(out) = height.as_deref_mut() {
                    out[i] = h;
                }
                if let Some(out) = h16.as_deref_mut() {
                    out[i] = height16(h);
                }
                if !wants_normal {
                    continue;
                }
                let n = self.normal(x, y, bump);
                if let Some(out) = normal.as_deref_mut() {
                    out[i] = n;
                }
                if let Some(out) = n8.as_deref_mut() {
                    out[i] = normal_rgb8(n);
                }
                if let Some(shade) = shade.as_deref_mut() {
                    shade(i, n);
                }
            }
        }
    }
}

/// The layers [`HeightWindow::write`] derives from heights, each for the window's tile.
pub struct Derived<'o> {
    /// Heights.
    pub height: Option<&'o mut [f32]>,
    /// Heights as 16 bits ([`height16`]).
    pub height16: Option<&'o mut [u16]>,
    /// Unit normals.
    pub normal: Option<&'o mut [[f32; 3]]>,
    /// Unit normals as RGB8 ([`normal_rgb8`]).
    pub normal_rgb8: Option<&'o mut [[u8; 3]]>,
}

#[cfg(test)]
mod tests {
    use super::*;

    fn same(table: &Srgb8, bits: u32) {
        let v = f32::from_bits(bits);
        assert_eq!(table.code(v), srgb8(v), "at {v} ({bits:#x})");
    }

    #[test]
    fn the_table_gives_srgb8s_codes() {
        let table = Srgb8::new();
        // Around each code's smallest value, where a wrong entry would show.
        for k in 1..256 {
            let at = table.lowest[k].to_bits();
            (at.saturating_sub(3)..=at + 3).for_each(|bits| same(&table, bits));
            assert!(srgb8(table.lowest[k]) >= k as u8 && table.lowest[k] > table.lowest[k - 1]);
        }
        // A stride through [0, 1], and what lies outside it.
        (0..=1.0f32.to_bits()).step_by(4099).for_each(|bits| same(&table, bits));
        for v in [f32::NAN, -f32::NAN, f32::INFINITY, f32::NEG_INFINITY, -0.0, -1.0, 1.5, f32::MAX, f32::MIN_POSITIVE] {
            same(&table, v.to_bits());
        }
        assert_eq!(table.opaque([0.0, 0.5, 1.0]), srgb8_opaque([0.0, 0.5, 1.0]));
    }

    #[test]
    fn the_encodings_round_as_libm_does() {
        // libm's rounding, as the encodings are defined.
        let height = |h: f32| libm::roundf(h.clamp(0.0, 1.0) * 65535.0) as u16;
        let normal = |c: f32| libm::roundf((c * 0.5 + 0.5) * 255.0).clamp(0.0, 255.0) as u8;
        let check = |c: f32| {
            assert_eq!(height16(c), height(c), "height16 at {c} ({:#x})", c.to_bits());
            assert_eq!(normal_rgb8([c, -c, c])[0], normal(c), "normal_rgb8 at {c} ({:#x})", c.to_bits());
            assert_eq!(normal_rgb8([c, -c, c])[1], normal(-c), "normal_rgb8 at {} ({:#x})", -c, c.to_bits());
        };
        // Ties and the values an ulp or two beside them, both encodings' codes.
        for k in 0..=65535u32 {
            for v in [k as f32 / 65535.0, (k as f32 + 0.5) / 65535.0, (k as f32 + 0.5) / 127.5 - 1.0] {
                let bits = v.to_bits();
                (bits.saturating_sub(3)..=bits.saturating_add(3)).for_each(|b| check(f32::from_bits(b)));
            }
        }
        // A stride through every f32 (both signs), and the special values.
        (0..=u32::MAX).step_by(65_537).for_each(|b| check(f32::from_bits(b)));
        for v in [f32::NAN, -f32::NAN, f32::INFINITY, f32::NEG_INFINITY, 0.0, -0.0, f32::MAX, f32::MIN_POSITIVE] {
            check(v);
        }
    }

    /// The table's premise: [`srgb8`] never falls as its value rises, so that it equals the
    /// table at every `f32` from 0 to 1 (about 10⁹ of them: 20 s in release).
    #[test]
    #[ignore = "every f32 from 0 to 1: cargo test --release -p hibi-core -- --ignored every_f32"]
    fn the_table_gives_srgb8s_code_at_every_f32_from_0_to_1() {
        let table = Srgb8::new();
        (0..=1.0f32.to_bits()).for_each(|bits| same(&table, bits));
    }
}
