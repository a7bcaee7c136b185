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

/// [`srgb8`]'s table, made once: [`Srgb8::new`]'s bisection written out as the bits of each
/// code's smallest value (a test compares it with the bisection), so that a render reads it
/// in place instead of making its kilobyte on the stack.
pub static SRGB8: Srgb8 = Srgb8 { lowest: LOWEST };

/// [`SRGB8`]'s values: the bits of each code's smallest value.
const LOWEST: [f32; 256] = {
    const BITS: [u32; 256] = [
        0xff800000, 0x391f22b4, 0x39eeb40e, 0x3a46eb61, 0x3a8b3e5d, 0x3ab3070b, 0x3adacfb7, 0x3b014c32, 0x3b153089,
        0x3b2914df, 0x3b3cf936, 0x3b50f2d1, 0x3b65fb9a, 0x3b7c3404, 0x3b89d05f, 0x3b962333, 0x3ba314be, 0x3bb0a731,
        0x3bbedcb7, 0x3bcdb76c, 0x3bdd3966, 0x3bed64ae, 0x3bfe3b44, 0x3c07df90, 0x3c10f919, 0x3c1a6b32, 0x3c2436c7,
        0x3c2e5cc7, 0x3c38de19, 0x3c43bba3, 0x3c4ef646, 0x3c5a8ee2, 0x3c668654, 0x3c72dd74, 0x3c7f9512, 0x3c865703,
        0x3c8d1490, 0x3c940396, 0x3c9b247c, 0x3ca277a8, 0x3ca9fd79, 0x3cb1b654, 0x3cb9a299, 0x3cc1c2a9, 0x3cca16e3,
        0x3cd29fa4, 0x3cdb5d4d, 0x3ce45034, 0x3ced78b7, 0x3cf6d72f, 0x3d0035fc, 0x3d051bb6, 0x3d0a1cee, 0x3d0f39d1,
        0x3d14728a, 0x3d19c745, 0x3d1f382c, 0x3d24c56a, 0x3d2a6f24, 0x3d303586, 0x3d3618b9, 0x3d3c18e6, 0x3d423633,
        0x3d4870cb, 0x3d4ec8d3, 0x3d553e73, 0x3d5bd1d3, 0x3d628319, 0x3d69526a, 0x3d703fee, 0x3d774bce, 0x3d7e7627,
        0x3d82df92, 0x3d869374, 0x3d8a56cc, 0x3d8e29ad, 0x3d920c28, 0x3d95fe50, 0x3d9a0036, 0x3d9e11ed, 0x3da23385,
        0x3da66510, 0x3daaa6a1, 0x3daef847, 0x3db35a16, 0x3db7cc1c, 0x3dbc4e6c, 0x3dc0e115, 0x3dc5842a, 0x3dca37ba,
        0x3dcefbd6, 0x3dd3d08f, 0x3dd8b5f5, 0x3dddac19, 0x3de2b30a, 0x3de7cad9, 0x3decf395, 0x3df22d4f, 0x3df7781a,
        0x3dfcd3ff, 0x3e012088, 0x3e03dfaf, 0x3e06a77c, 0x3e0977f7, 0x3e0c5127, 0x3e0f3314, 0x3e121dc6, 0x3e151144,
        0x3e180d95, 0x3e1b12c2, 0x3e1e20d1, 0x3e2137cb, 0x3e2457b7, 0x3e27809a, 0x3e2ab27c, 0x3e2ded67, 0x3e313160,
        0x3e347e6f, 0x3e37d49d, 0x3e3b33ed, 0x3e3e9c68, 0x3e420e14, 0x3e4588fa, 0x3e490d21, 0x3e4c9a8f, 0x3e50314b,
        0x3e53d15c, 0x3e577ac9, 0x3e5b2d99, 0x3e5ee9d2, 0x3e62af7c, 0x3e667e9d, 0x3e6a5740, 0x3e6e3964, 0x3e722512,
        0x3e761a54, 0x3e7a192d, 0x3e7e21a6, 0x3e8119e2, 0x3e8327c8, 0x3e853a86, 0x3e875222, 0x3e896e9d, 0x3e8b8ffc,
        0x3e8db641, 0x3e8fe170, 0x3e92118b, 0x3e944696, 0x3e968094, 0x3e98bf89, 0x3e9b0376, 0x3e9d4c61, 0x3e9f9a4b,
        0x3ea1ed38, 0x3ea4452a, 0x3ea6a226, 0x3ea9042c, 0x3eab6b43, 0x3eadd76b, 0x3eb048a9, 0x3eb2bf02, 0x3eb53a72,
        0x3eb7bb02, 0x3eba40b1, 0x3ebccb86, 0x3ebf5b81, 0x3ec1f0a8, 0x3ec48afa, 0x3ec72a7d, 0x3ec9cf32, 0x3ecc791e,
        0x3ecf2842, 0x3ed1dca3, 0x3ed49640, 0x3ed75521, 0x3eda1945, 0x3edce2b1, 0x3edfb166, 0x3ee2856a, 0x3ee55ebc,
        0x3ee83d62, 0x3eeb215c, 0x3eee0ab0, 0x3ef0f95d, 0x3ef3ed6a, 0x3ef6e6d6, 0x3ef9e5a7, 0x3efce9e1, 0x3efff37e,
        0x3f018146, 0x3f030b82, 0x3f049878, 0x3f062827, 0x3f07ba92, 0x3f094fb9, 0x3f0ae7a0, 0x3f0c8244, 0x3f0e1fab,
        0x3f0fbfd2, 0x3f1162be, 0x3f13086e, 0x3f14b0e5, 0x3f165c22, 0x3f180a29, 0x3f19baf9, 0x3f1b6e96, 0x3f1d24fe,
        0x3f1ede35, 0x3f209a3b, 0x3f225913, 0x3f241abb, 0x3f25df37, 0x3f27a687, 0x3f2970ae, 0x3f2b3dab, 0x3f2d0d83,
        0x3f2ee033, 0x3f30b5be, 0x3f328e25, 0x3f346969, 0x3f36478c, 0x3f38288f, 0x3f3a0c74, 0x3f3bf33a, 0x3f3ddce5,
        0x3f3fc975, 0x3f41b8eb, 0x3f43ab48, 0x3f45a08f, 0x3f4798bf, 0x3f4993db, 0x3f4b91e2, 0x3f4d92d8, 0x3f4f96bd,
        0x3f519d92, 0x3f53a757, 0x3f55b410, 0x3f57c3bd, 0x3f59d65e, 0x3f5bebf6, 0x3f5e0485, 0x3f60200d, 0x3f623e91,
        0x3f64600b, 0x3f668486, 0x3f68abfa, 0x3f6ad671, 0x3f6d03e3, 0x3f6f345b, 0x3f7167d0, 0x3f739e4d, 0x3f75d7ca,
        0x3f781452, 0x3f7a53db, 0x3f7c9671, 0x3f7edc0e,
    ];
    let mut lowest = [0.0; 256];
    let mut k = 0;
    while k < 256 {
        lowest[k] = f32::from_bits(BITS[k]);
        k += 1;
    }
    lowest
};

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
        let length = crate::scalar::sqrtf(gx * gx + gy * gy + 1.0);
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
    fn the_static_table_is_the_bisections_bit_for_bit() {
        let made = Srgb8::new();
        for k in 0..256 {
            assert_eq!(SRGB8.lowest[k].to_bits(), made.lowest[k].to_bits(), "code {k}");
        }
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
