//! The layers a render writes, in the formats an engine uploads: which a caller asks for
//! ([`Layers`]), the checks every model's render makes before writing anything, and the mask
//! and time maps every crack model draws from its strokes.

use super::{RasterError, StrokeHit, Tile};

/// One kind of output of a render (and the scratch it may work in).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Layer {
    /// [`Layers::mask`].
    Mask,
    /// [`Layers::height`].
    Height,
    /// [`Layers::height16`].
    Height16,
    /// [`Layers::normal`].
    Normal,
    /// [`Layers::normal_rgb8`].
    NormalRgb8,
    /// [`Layers::time`].
    Time,
    /// [`Layers::cell`].
    Cell,
    /// [`Layers::preview`].
    Preview,
    /// [`Layers::scratch`].
    Scratch,
}

impl Layer {
    /// The field's name, as Rust and C spell it.
    pub const fn name(self) -> &'static str {
        match self {
            Layer::Mask => "mask",
            Layer::Height => "height",
            Layer::Height16 => "height16",
            Layer::Normal => "normal",
            Layer::NormalRgb8 => "normal_rgb8",
            Layer::Time => "time",
            Layer::Cell => "cell",
            Layer::Preview => "preview",
            Layer::Scratch => "scratch",
        }
    }
}

/// The rasters one render call writes, each optional and each the tile's `width × height`
/// pixels long, row-major, row 0 at the top (y = 0 of the model's domain). One pass draws every
/// layer asked for; a model refuses a layer it does not have ([`RasterError::NoLayer`]).
///
/// | layer | mud | glass | skin |
/// |---|---|---|---|
/// | `mask` | crack coverage | crack coverage | furrow net (255 at level 0, 160, 100, 64 finer) |
/// | `height`, `height16` | 1 on the cells, down into the grooves | 1 − coverage | sum of the levels' profiles |
/// | `normal`, `normal_rgb8` | from the height | from the height | the profiles' slopes |
/// | `time` | break time | time the front passed | — |
/// | `cell` | — | — | cell index at [`cell_level`](crate::skin::SkinRender::cell_level) |
/// | `preview` | lit clay | dark glass, bright cracks | lit skin ([`ShadeParams`](crate::skin::ShadeParams)) |
#[derive(Default)]
pub struct Layers<'o> {
    /// Coverage, 0 (none) to 255 (full).
    pub mask: Option<&'o mut [u8]>,
    /// Height as `f32`.
    pub height: Option<&'o mut [f32]>,
    /// Height in 16 bits: 0 to 65535 over the model's height range (mud and glass 0 to 1; skin
    /// 0 to the sum of its levels' highest profile points).
    pub height16: Option<&'o mut [u16]>,
    /// Unit tangent-space normal (x right, y up, z out of the surface), as in OpenGL normal
    /// maps.
    pub normal: Option<&'o mut [[f32; 3]]>,
    /// The normal as 8-bit RGB, each component c stored as round((c + 1) / 2 · 255).
    pub normal_rgb8: Option<&'o mut [[u8; 3]]>,
    /// Time (mud: break time in long steps; glass: the step the crack front passed); +∞ where
    /// no crack covers at least half of the pixel.
    pub time: Option<&'o mut [f32]>,
    /// Cell index (skin).
    pub cell: Option<&'o mut [u32]>,
    /// A shaded preview, 8-bit sRGB with alpha 255.
    pub preview: Option<&'o mut [[u8; 4]]>,
    /// Working memory, [`scratch_len`] values for the tile: needed for `height16`,
    /// `normal`, `normal_rgb8` and `preview` of mud and glass, and for skin's `mask`.
    pub scratch: Option<&'o mut [u32]>,
}

/// The scratch a render of a `width × height` tile works in, in `u32` values: the tile and a
/// one-pixel margin around it. None if it overflows.
pub const fn scratch_len(width: u32, height: u32) -> Option<usize> {
    (width as usize + 2).checked_mul(height as usize + 2)
}

impl Layers<'_> {
    /// Whether any layer beyond a model's own maps (mask, height, time, cell) is asked for:
    /// `height16`, `normal`, `normal_rgb8` or `preview`. The renders test it first, inlined, so
    /// that a caller who only ever asks for the models' own maps links none of the code that
    /// derives the others (a 64 KiB part has room for the one, not both).
    #[inline(always)]
    pub fn derived(&self) -> bool {
        self.height16.is_some() || self.normal.is_some() || self.normal_rgb8.is_some() || self.preview.is_some()
    }

    /// Checks the layers against a tile of `pixels` pixels before anything is written: every
    /// layer present is one the model has (`has`) and is long enough, and the scratch is there
    /// and long enough when `needs_scratch` says the layers asked for need it.
    pub fn check(
        &self,
        tile: &Tile,
        has: impl Fn(Layer) -> bool,
        needs_scratch: impl Fn(&Layers) -> bool,
    ) -> Result<usize, RasterError> {
        let pixels = tile.pixels()?;
        let lengths = [
            (Layer::Mask, self.mask.as_deref().map(<[u8]>::len)),
            (Layer::Height, self.height.as_deref().map(<[f32]>::len)),
            (Layer::Height16, self.height16.as_deref().map(<[u16]>::len)),
            (Layer::Normal, self.normal.as_deref().map(<[[f32; 3]]>::len)),
            (Layer::NormalRgb8, self.normal_rgb8.as_deref().map(<[[u8; 3]]>::len)),
            (Layer::Time, self.time.as_deref().map(<[f32]>::len)),
            (Layer::Cell, self.cell.as_deref().map(<[u32]>::len)),
            (Layer::Preview, self.preview.as_deref().map(<[[u8; 4]]>::len)),
        ];
        for (layer, length) in lengths {
            let Some(length) = length else { continue };
            if !has(layer) {
                return Err(RasterError::NoLayer(layer));
            }
            if length < pixels {
                return Err(RasterError::BufferTooSmall { layer, needed: pixels });
            }
        }
        if needs_scratch(self) {
            let needed = scratch_len(tile.width, tile.height).ok_or(RasterError::Size)?;
            if self.scratch.as_deref().map_or(0, <[u32]>::len) < needed {
                return Err(RasterError::BufferTooSmall { layer: Layer::Scratch, needed });
            }
        }
        Ok(pixels)
    }
}

/// A coverage in (0, 1] as a mask value.
pub fn coverage_code(coverage: f32) -> u8 {
    libm::roundf(coverage * 255.0) as u8
}

/// The anti-aliased mask: each pixel's largest coverage, 0 to 255; `out` holds the pixels the
/// strokes' hits index.
pub fn draw_mask(out: &mut [u8], strokes: impl FnOnce(&mut dyn FnMut(StrokeHit))) {
    out.fill(0);
    strokes(&mut |hit| {
        let v = coverage_code(hit.coverage);
        out[hit.pixel] = out[hit.pixel].max(v);
    });
}

/// The time map: each pixel's earliest time among the strokes covering at least half of it;
/// +∞ where none does.
pub fn draw_time(out: &mut [f32], strokes: impl FnOnce(&mut dyn FnMut(StrokeHit))) {
    out.fill(f32::INFINITY);
    strokes(&mut |hit| {
        if hit.coverage >= 0.5 {
            out[hit.pixel] = out[hit.pixel].min(hit.value);
        }
    });
}
