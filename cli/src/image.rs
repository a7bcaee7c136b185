//! Pictures in memory, and the maps every crack model (mud, glass) shares: a coverage mask,
//! a height map and a break-time map, turned into the layer asked for and cut into growth
//! frames.

use crate::args::Layer;

/// Pixel data, row-major.
#[derive(Clone, Debug, PartialEq)]
pub enum Pixels {
    /// 8-bit grey.
    Gray8(Vec<u8>),
    /// 16-bit grey.
    Gray16(Vec<u16>),
    /// 8-bit RGB, three bytes a pixel.
    Rgb8(Vec<u8>),
}

/// A picture.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// The pixels.
    pub pixels: Pixels,
}

impl Image {
    /// An RGB picture from linear colours, sRGB-encoded.
    pub fn from_linear(width: u32, height: u32, colours: impl Iterator<Item = [f32; 3]>) -> Image {
        let pixels = colours.flat_map(|c| c.map(encode_srgb)).collect();
        Image { width, height, pixels: Pixels::Rgb8(pixels) }
    }

    /// The same picture as 8-bit RGB (grey repeated; 16-bit grey keeps its high byte).
    pub fn to_rgb8(&self) -> Vec<u8> {
        match &self.pixels {
            Pixels::Rgb8(p) => p.clone(),
            Pixels::Gray8(p) => p.iter().flat_map(|&v| [v; 3]).collect(),
            Pixels::Gray16(p) => p.iter().flat_map(|&v| [(v >> 8) as u8; 3]).collect(),
        }
    }

    /// `columns` × `rows` copies of this picture side by side.
    pub fn tiled(&self, columns: u32, rows: u32) -> Image {
        let rgb = self.to_rgb8();
        let (w, h) = (self.width as usize, self.height as usize);
        let mut out = Vec::with_capacity(rgb.len() * (columns * rows) as usize);
        for _ in 0..rows {
            for y in 0..h {
                for _ in 0..columns {
                    out.extend_from_slice(&rgb[3 * y * w..3 * (y + 1) * w]);
                }
            }
        }
        Image { width: self.width * columns, height: self.height * rows, pixels: Pixels::Rgb8(out) }
    }

    /// Pictures side by side on one row, `gap` pixels of `background` apart, top-aligned.
    pub fn row(images: &[Image], gap: u32, background: [u8; 3]) -> Image {
        let width = images.iter().map(|i| i.width).sum::<u32>() + gap * images.len().saturating_sub(1) as u32;
        let height = images.iter().map(|i| i.height).max().unwrap_or(0);
        let mut out: Vec<u8> = background.iter().copied().cycle().take(3 * (width * height) as usize).collect();
        let mut left = 0usize;
        for image in images {
            let rgb = image.to_rgb8();
            let w = image.width as usize;
            for y in 0..image.height as usize {
                let at = 3 * (y * width as usize + left);
                out[at..at + 3 * w].copy_from_slice(&rgb[3 * y * w..3 * (y + 1) * w]);
            }
            left += w + gap as usize;
        }
        Image { width, height, pixels: Pixels::Rgb8(out) }
    }
}

/// Linear [0, 1] to an 8-bit sRGB code.
pub fn encode_srgb(v: f32) -> u8 {
    let v = v.clamp(0.0, 1.0);
    let s = if v <= 0.003_130_8 { 12.92 * v } else { 1.055 * v.powf(1.0 / 2.4) - 0.055 };
    (s * 255.0).round() as u8
}

/// A unit normal as an RGB normal-map texel.
pub fn encode_normal(n: [f32; 3]) -> [u8; 3] {
    n.map(|c| ((c * 0.5 + 0.5) * 255.0).round().clamp(0.0, 255.0) as u8)
}

/// Normals of a height field by central differences (wrapping when `periodic`, one-sided at
/// open edges), with heights scaled by `bump` pixels; x right, y up, z out.
pub fn normals_from_height(width: u32, height: u32, heights: &[f32], bump: f32, periodic: bool) -> Vec<[f32; 3]> {
    let (w, h) = (width as usize, height as usize);
    let at = |x: usize, y: usize| heights[y * w + x];
    // The neighbours of column (or row) i among n, and the distance between them.
    let around = |i: usize, n: usize| -> (usize, usize, f32) {
        if periodic && n > 2 {
            ((i + n - 1) % n, (i + 1) % n, 2.0)
        } else {
            let (a, b) = (i.saturating_sub(1), (i + 1).min(n - 1));
            (a, b, (b - a).max(1) as f32)
        }
    };
    let mut out = Vec::with_capacity(w * h);
    for y in 0..h {
        let (up, down, dy) = around(y, h);
        for x in 0..w {
            let (left, right, dx) = around(x, w);
            let gx = (at(right, y) - at(left, y)) / dx * bump;
            // Rows run down the picture; y runs up.
            let gy = (at(x, up) - at(x, down)) / dy * bump;
            let n = [-gx, -gy, 1.0];
            let length = (n[0] * n[0] + n[1] * n[1] + 1.0).sqrt();
            out.push(n.map(|c| c / length));
        }
    }
    out
}

/// The direction the previews are lit from: the upper left, as the skin model's preview.
const LIGHT: [f32; 3] = [-0.5, 0.6, 0.62];

/// How a crack model looks in the shaded preview.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Look {
    /// Dried clay, lit from the upper left, dark in the cracks.
    Mud,
    /// Dark glass with bright cracks.
    Glass,
}

/// The maps a crack model (mud or glass) is drawn into.
#[derive(Clone, Debug)]
pub struct CrackMaps {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Crack coverage, 0 to 255.
    pub mask: Vec<u8>,
    /// Height: 1 on the surface, down to 0 in the deepest crack.
    pub heights: Vec<f32>,
    /// Break time of the crack covering each pixel; +∞ where none does.
    pub time: Vec<f32>,
    /// The maps tile (periodic lattice).
    pub periodic: bool,
    /// The preview's look.
    pub look: Look,
}

impl CrackMaps {
    /// The earliest and latest break time on the maps, if anything broke.
    pub fn time_range(&self) -> Option<(f32, f32)> {
        let finite = self.time.iter().copied().filter(|t| t.is_finite());
        let (lo, hi) = finite.fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), t| (lo.min(t), hi.max(t)));
        (lo <= hi).then_some((lo, hi))
    }

    /// The break time of every covered pixel: the time map marks pixels a crack covers at
    /// least half of; the anti-aliased rim around them takes its neighbours' earliest time.
    fn rim_times(&self) -> Vec<f32> {
        let (w, h) = (self.width as usize, self.height as usize);
        let mut out = self.time.clone();
        for y in 0..h {
            for x in 0..w {
                let i = y * w + x;
                if self.mask[i] == 0 || self.time[i].is_finite() {
                    continue;
                }
                let mut earliest = f32::INFINITY;
                for (dx, dy) in [(-1i64, -1i64), (0, -1), (1, -1), (-1, 0), (1, 0), (-1, 1), (0, 1), (1, 1)] {
                    let (nx, ny) = (x as i64 + dx, y as i64 + dy);
                    let (nx, ny) = if self.periodic {
                        (nx.rem_euclid(w as i64), ny.rem_euclid(h as i64))
                    } else if (0..w as i64).contains(&nx) && (0..h as i64).contains(&ny) {
                        (nx, ny)
                    } else {
                        continue;
                    };
                    earliest = earliest.min(self.time[ny as usize * w + nx as usize]);
                }
                out[i] = earliest;
            }
        }
        out
    }

    /// The maps as they stood at time `t`: only cracks broken by then (`times` from
    /// [`CrackMaps::rim_times`]).
    fn at_time(&self, times: &[f32], t: f32) -> CrackMaps {
        let mut frame = self.clone();
        for (i, &broke) in times.iter().enumerate() {
            // +∞ (never broke) is never shown.
            if broke > t || broke.is_nan() {
                frame.mask[i] = 0;
                frame.heights[i] = 1.0;
                frame.time[i] = f32::INFINITY;
            }
        }
        frame
    }

    /// `count` frames of the growth, evenly spaced in time from the first break to the last.
    pub fn growth(&self, count: u32) -> Vec<CrackMaps> {
        let Some((first, last)) = self.time_range() else {
            return vec![self.clone(); count as usize];
        };
        let times = self.rim_times();
        (1..=count).map(|k| self.at_time(&times, first + (last - first) * k as f32 / count as f32)).collect()
    }

    /// The layer as a picture; `bump` is the depth of the deepest crack in pixels.
    pub fn layer(&self, layer: Layer, bump: f32) -> Image {
        let (width, height) = (self.width, self.height);
        let pixels = match layer {
            Layer::Mask => Pixels::Gray8(self.mask.clone()),
            Layer::Height => {
                Pixels::Gray16(self.heights.iter().map(|&h| (h.clamp(0.0, 1.0) * 65535.0).round() as u16).collect())
            }
            Layer::Time => {
                let (first, last) = self.time_range().unwrap_or((0.0, 0.0));
                let span = if last > first { last - first } else { 1.0 };
                let code = |t: f32| if t.is_finite() { ((t - first) / span * 65534.0).round() as u16 } else { 65535 };
                Pixels::Gray16(self.time.iter().map(|&t| code(t)).collect())
            }
            Layer::Normal => {
                let n = normals_from_height(width, height, &self.heights, bump, self.periodic);
                Pixels::Rgb8(n.into_iter().flat_map(encode_normal).collect())
            }
            Layer::Shaded => return self.shaded(bump),
        };
        Image { width, height, pixels }
    }

    /// The lit preview.
    fn shaded(&self, bump: f32) -> Image {
        let coverage = self.mask.iter().map(|&m| f32::from(m) / 255.0);
        match self.look {
            Look::Mud => {
                let normals = normals_from_height(self.width, self.height, &self.heights, bump, self.periodic);
                let length = LIGHT.iter().map(|c| c * c).sum::<f32>().sqrt();
                let light = LIGHT.map(|c| c / length);
                let (clay, crack, ambient) = ([0.40, 0.27, 0.16], [0.035, 0.025, 0.018], 0.35);
                let colours = normals.iter().zip(coverage).map(|(n, c)| {
                    let diffuse = (n[0] * light[0] + n[1] * light[1] + n[2] * light[2]).max(0.0);
                    let lit = ambient + (1.0 - ambient) * diffuse;
                    std::array::from_fn(|k| (clay[k] + (crack[k] - clay[k]) * c) * lit / 0.75)
                });
                Image::from_linear(self.width, self.height, colours)
            }
            Look::Glass => {
                let (w, h) = (self.width as f32, self.height as f32);
                let colours = coverage.enumerate().map(|(i, c)| {
                    // A faint sheen across the plate, brightest at the upper left.
                    let (x, y) = ((i as u32 % self.width) as f32 / w, (i as u32 / self.width) as f32 / h);
                    let sheen = 0.02 * (1.0 - 0.5 * (x + y));
                    let plate = [0.012 + sheen, 0.022 + sheen, 0.030 + sheen];
                    let crack = [0.80, 0.90, 0.95];
                    std::array::from_fn(|k| plate[k] + (crack[k] - plate[k]) * c)
                });
                Image::from_linear(self.width, self.height, colours)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn maps() -> CrackMaps {
        // A 4 × 1 strip: a crack at x = 1 (t = 2) with a rim at x = 2, another at x = 3 (t = 5).
        CrackMaps {
            width: 4,
            height: 1,
            mask: vec![0, 255, 100, 255],
            heights: vec![1.0, 0.0, 0.6, 0.0],
            time: vec![f32::INFINITY, 2.0, f32::INFINITY, 5.0],
            periodic: false,
            look: Look::Mud,
        }
    }

    #[test]
    fn frames_show_only_what_broke_by_then_rims_included() {
        let m = maps();
        assert_eq!(m.time_range(), Some((2.0, 5.0)));
        let early = m.at_time(&m.rim_times(), 3.0);
        assert_eq!(early.mask, vec![0, 255, 100, 0]);
        assert_eq!(early.heights, vec![1.0, 0.0, 0.6, 1.0]);
        let frames = m.growth(2);
        assert_eq!(frames.len(), 2);
        assert_eq!(frames[1].mask, m.mask);
    }

    #[test]
    fn layers_encode_as_documented() {
        let m = maps();
        let time = m.layer(Layer::Time, 1.0);
        assert_eq!(time.pixels, Pixels::Gray16(vec![65535, 0, 65535, 65534]));
        let height = m.layer(Layer::Height, 1.0);
        assert_eq!(height.pixels, Pixels::Gray16(vec![65535, 0, 39321, 0]));
        let Pixels::Rgb8(normal) = m.layer(Layer::Normal, 1.0).pixels else { panic!() };
        // At x = 0 the surface falls to the right: the normal leans right (x > 0).
        assert!(normal[0] > 128);
    }

    #[test]
    fn flat_height_gives_straight_up_normals_and_tiles_repeat() {
        let n = normals_from_height(3, 3, &[1.0; 9], 2.0, true);
        assert!(n.iter().all(|&v| v == [0.0, 0.0, 1.0]));
        let image = Image { width: 2, height: 1, pixels: Pixels::Gray8(vec![0, 255]) };
        let tiled = image.tiled(2, 2);
        assert_eq!((tiled.width, tiled.height), (4, 2));
        assert_eq!(tiled.to_rgb8()[..12], [0, 0, 0, 255, 255, 255, 0, 0, 0, 255, 255, 255]);
    }
}
