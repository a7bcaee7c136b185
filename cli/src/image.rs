//! Pictures in memory, and the core's layers encoded as pictures: a still or the frames of a
//! crack model's growth.

use std::num::NonZeroUsize;

use hibi_core::raster::{Layers, Tile};

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

/// How many threads draw a picture: `asked` (`--threads`), else the machine's cores.
pub fn threads(asked: Option<NonZeroUsize>) -> usize {
    asked.or_else(|| std::thread::available_parallelism().ok()).map_or(1, NonZeroUsize::get)
}

/// The layers of a core render to ask for to draw `layer` over `pixels` pixels, and the picture
/// they make; the core draws every layer, the command line only encodes it.
pub struct Buffers {
    layer: Layer,
    width: u32,
    height: u32,
    mask: Vec<u8>,
    height16: Vec<u16>,
    normal: Vec<[u8; 3]>,
    time: Vec<f32>,
    preview: Vec<[u8; 4]>,
}

/// A layer's buffer if it was asked for (not empty).
fn wanted<T>(buffer: &mut [T]) -> Option<&mut [T]> {
    (!buffer.is_empty()).then_some(buffer)
}

impl Buffers {
    /// Buffers for `layer` of a `width × height` picture.
    pub fn new(layer: Layer, width: u32, height: u32) -> Buffers {
        let pixels = width as usize * height as usize;
        let n = |wanted: bool| if wanted { pixels } else { 0 };
        Buffers {
            layer,
            width,
            height,
            mask: vec![0; n(layer == Layer::Mask)],
            height16: vec![0; n(layer == Layer::Height)],
            normal: vec![[0; 3]; n(layer == Layer::Normal)],
            time: vec![0.0; n(layer == Layer::Time)],
            preview: vec![[0; 4]; n(layer == Layer::Shaded)],
        }
    }

    /// Draws the picture with `draw(tile, layers)`, which renders one tile of the model's
    /// picture: in full-width bands of rows, one band per thread on up to `threads` threads.
    /// The core draws each pixel of a tile bit for bit as the whole picture has it, so the
    /// picture is the same whatever the number of threads; the core itself stays on one thread.
    pub fn draw(&mut self, threads: usize, draw: impl Fn(&Tile, Layers) + Sync) {
        let (width, height) = (self.width, self.height);
        let rows = height.div_ceil(threads.clamp(1, height.max(1) as usize) as u32).max(1);
        let scratch = self.layer != Layer::Time;
        let whole = Layers {
            mask: wanted(&mut self.mask),
            height16: wanted(&mut self.height16),
            normal_rgb8: wanted(&mut self.normal),
            time: wanted(&mut self.time),
            preview: wanted(&mut self.preview),
            ..Layers::default()
        };
        let bands: Vec<(Tile, Layers)> = whole.bands(&Tile::whole(width, height), rows).collect();
        let band = |(tile, layers): (Tile, Layers)| {
            let len = hibi_core::raster::scratch_len(tile.width, tile.height).expect("a picture that fits in memory");
            let mut own = vec![0u32; if scratch { len } else { 0 }];
            let scratch = if scratch { Some(&mut own[..]) } else { None };
            draw(&tile, Layers { scratch, ..layers });
        };
        if bands.len() == 1 {
            bands.into_iter().for_each(band);
        } else {
            std::thread::scope(|scope| {
                for job in bands {
                    scope.spawn(|| band(job));
                }
            });
        }
    }

    /// The drawn layer as a picture: mask 8-bit grey, height 16-bit grey, normal and preview
    /// 8-bit RGB, time 16-bit grey from the earliest break (0) to the latest (65534), 65535
    /// where nothing broke.
    pub fn picture(self) -> Image {
        let (width, height) = (self.width, self.height);
        let pixels = if !self.mask.is_empty() {
            Pixels::Gray8(self.mask)
        } else if !self.height16.is_empty() {
            Pixels::Gray16(self.height16)
        } else if !self.normal.is_empty() {
            Pixels::Rgb8(self.normal.into_iter().flatten().collect())
        } else if !self.preview.is_empty() {
            Pixels::Rgb8(self.preview.into_iter().flat_map(|[r, g, b, _]| [r, g, b]).collect())
        } else {
            let (first, last) = time_range(&self.time).unwrap_or((0.0, 0.0));
            let span = if last > first { last - first } else { 1.0 };
            let code = |t: f32| if t.is_finite() { ((t - first) / span * 65534.0).round() as u16 } else { 65535 };
            Pixels::Gray16(self.time.iter().map(|&t| code(t)).collect())
        };
        Image { width, height, pixels }
    }
}

/// The earliest and latest finite time on a time map, if anything broke.
pub fn time_range(time: &[f32]) -> Option<(f32, f32)> {
    let finite = time.iter().copied().filter(|t| t.is_finite());
    let (lo, hi) = finite.fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), t| (lo.min(t), hi.max(t)));
    (lo <= hi).then_some((lo, hi))
}

/// A crack model's `layer` as a picture, or (`frames`) its growth: that many pictures evenly
/// spaced in time from the first break to the last, each drawn by the core as the cracks stood
/// then. `draw(until, tile, layers)` renders a tile of the model's `width × height` image; the
/// tiles of a picture are drawn on up to `threads` threads.
pub fn crack_pictures(
    (width, height): (u32, u32),
    layer: Layer,
    frames: Option<u32>,
    threads: usize,
    draw: impl Fn(f32, &Tile, Layers) + Sync,
) -> Vec<Image> {
    let picture = |layer: Layer, until: f32| {
        let mut buffers = Buffers::new(layer, width, height);
        buffers.draw(threads, |tile, layers| draw(until, tile, layers));
        buffers
    };
    let Some(count) = frames else { return vec![picture(layer, f32::INFINITY).picture()] };
    let time = picture(Layer::Time, f32::INFINITY).time;
    let Some((first, last)) = time_range(&time) else {
        return vec![picture(layer, f32::INFINITY).picture(); count as usize];
    };
    (1..=count).map(|k| picture(layer, first + (last - first) * k as f32 / count as f32).picture()).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn layers_encode_as_documented() {
        let mut b = Buffers::new(Layer::Time, 4, 1);
        b.draw(1, |_, layers| layers.time.unwrap().copy_from_slice(&[f32::INFINITY, 2.0, 3.5, 5.0]));
        assert_eq!(b.picture().pixels, Pixels::Gray16(vec![65535, 0, 32767, 65534]));
        let mut b = Buffers::new(Layer::Shaded, 1, 1);
        b.draw(1, |_, layers| layers.preview.unwrap()[0] = [1, 2, 3, 255]);
        assert_eq!(b.picture().pixels, Pixels::Rgb8(vec![1, 2, 3]));
    }

    #[test]
    fn bands_cover_every_row_once_on_any_number_of_threads() {
        for threads in 1..=9 {
            let tiles = std::sync::Mutex::new(Vec::new());
            let mut b = Buffers::new(Layer::Mask, 3, 7);
            b.draw(threads, |tile, layers| {
                let scratch = layers.scratch.expect("a mask may need the scratch");
                assert_eq!(scratch.len(), hibi_core::raster::scratch_len(3, tile.height).unwrap());
                let mask = layers.mask.unwrap();
                assert_eq!(mask.len(), 3 * tile.height as usize);
                for (i, v) in mask.iter_mut().enumerate() {
                    *v = (tile.y as usize * 3 + i) as u8;
                }
                tiles.lock().unwrap().push(*tile);
            });
            assert_eq!(b.picture().pixels, Pixels::Gray8((0..21).collect()), "{threads} threads");
            let tiles = tiles.into_inner().unwrap();
            assert!(tiles.len() <= threads && (threads > 1 || tiles.len() == 1), "{threads} threads: {tiles:?}");
            assert_eq!(tiles.iter().map(|t| t.height).sum::<u32>(), 7);
            assert!(tiles.iter().all(|t| t.x == 0 && t.width == 3));
        }
    }

    #[test]
    fn growth_frames_cut_the_time_range_evenly() {
        let cut = std::sync::Mutex::new(Vec::new());
        let frames = crack_pictures((2, 1), Layer::Mask, Some(4), 2, |until, _, layers| {
            cut.lock().unwrap().push(until);
            if let Some(t) = layers.time {
                t.copy_from_slice(&[1.0, 5.0]);
            }
        });
        assert_eq!(frames.len(), 4);
        assert_eq!(*cut.lock().unwrap(), vec![f32::INFINITY, 2.0, 3.0, 4.0, 5.0]);
    }

    #[test]
    fn tiles_repeat() {
        let image = Image { width: 2, height: 1, pixels: Pixels::Gray8(vec![0, 255]) };
        let tiled = image.tiled(2, 2);
        assert_eq!((tiled.width, tiled.height), (4, 2));
        assert_eq!(tiled.to_rgb8()[..12], [0, 0, 0, 255, 255, 255, 0, 0, 0, 255, 255, 255]);
    }
}
