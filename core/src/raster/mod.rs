//! Drawing into caller buffers: anti-aliased, width-aware strokes (crack masks, height
//! grooves, break-time maps), shared by the models.
//!
//! Rasters are computed in `f32` whatever backend the model ran on: the inputs are the
//! models' `f32` outputs, and IEEE `f32` arithmetic gives the same pixels everywhere.

mod bands;
mod encode;
mod layers;
mod regions;
mod stroke;
mod tile;

pub use bands::Bands;
pub use encode::{Derived, HeightWindow, SRGB8, Srgb8, height16, normal_rgb8, srgb8, srgb8_opaque};
pub use layers::{Layer, Layers, coverage_code, draw_mask, draw_time, scratch_len};
pub use regions::label_regions;
pub(crate) use stroke::for_each_run;
pub use stroke::{Clip, Frame, Stroke, StrokeHit, for_each_hit};
pub use tile::Tile;

/// Why a raster could not be drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RasterError {
    /// Width or height is zero, or their product overflows.
    Size,
    /// A layer (or the scratch) holds fewer values than the tile has pixels (the scratch:
    /// than [`scratch_len`]).
    BufferTooSmall {
        /// The layer that is short.
        layer: Layer,
        /// Values it must hold.
        needed: usize,
    },
    /// A layer this model does not draw was asked for.
    NoLayer(Layer),
    /// The tile is empty or reaches past the image.
    Tile,
    /// `bump` is not finite or negative.
    Bump,
    /// `until` is NaN.
    Until,
    /// `width_scale` is not finite or negative.
    WidthScale,
    /// `min_width` is not finite or negative.
    MinWidth,
    /// `groove_depth` is not finite or negative.
    GrooveDepth,
    /// `offset` is not finite.
    Offset,
    /// `line_width` is not finite or not positive.
    LineWidth,
}

impl RasterError {
    /// A message naming what is wrong, NUL-terminated for C.
    pub const fn message(self) -> &'static core::ffi::CStr {
        match self {
            RasterError::Size => c"render: width and height must be > 0 and their product must fit in memory",
            RasterError::BufferTooSmall { .. } => c"render: a layer or the scratch is smaller than the tile needs",
            RasterError::WidthScale => c"render: width_scale must be finite and >= 0",
            RasterError::MinWidth => c"render: min_width must be finite and >= 0",
            RasterError::GrooveDepth => c"render: groove_depth must be finite and >= 0",
            RasterError::Offset => c"render: offset must be finite",
            RasterError::LineWidth => c"render: line_width must be finite and > 0",
            RasterError::NoLayer(_) => c"render: this model does not draw a layer that was asked for",
            RasterError::Tile => c"render: the tile must be non-empty and lie inside the image",
            RasterError::Bump => c"render: bump must be finite and >= 0",
            RasterError::Until => c"render: until must be a number (+infinity draws every crack)",
        }
    }
}

impl core::fmt::Display for RasterError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            RasterError::BufferTooSmall { layer, needed } => {
                write!(f, "render: layer {} is too small ({needed} values needed)", layer.name())
            }
            RasterError::NoLayer(layer) => write!(f, "render: this model has no {} layer", layer.name()),
            e => f.write_str(e.message().to_str().unwrap_or("render error")),
        }
    }
}

impl core::error::Error for RasterError {}

/// The number of pixels of a `width` × `height` raster, checked.
pub fn pixel_count(width: u32, height: u32) -> Result<usize, RasterError> {
    if width == 0 || height == 0 {
        return Err(RasterError::Size);
    }
    (width as usize).checked_mul(height as usize).ok_or(RasterError::Size)
}
