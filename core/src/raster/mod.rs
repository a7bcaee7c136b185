//! Drawing into caller buffers: anti-aliased, width-aware strokes (crack masks, height
//! grooves, break-time maps), shared by the models.
//!
//! Rasters are computed in `f32` whatever backend the model ran on: the inputs are the
//! models' `f32` outputs, and IEEE `f32` arithmetic gives the same pixels everywhere.

mod layers;
mod regions;
mod stroke;

pub use layers::{draw_mask, draw_time};
pub use regions::label_regions;
pub use stroke::{Frame, Stroke, StrokeHit, for_each_hit};

/// Why a raster could not be drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RasterError {
    /// Width or height is zero, or their product overflows.
    Size,
    /// The pixel buffer holds fewer than width × height values.
    BufferTooSmall {
        /// Pixels the buffer must hold.
        needed: usize,
    },
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
            RasterError::BufferTooSmall { .. } => c"render: the pixel buffer is smaller than width x height",
            RasterError::WidthScale => c"render: width_scale must be finite and >= 0",
            RasterError::MinWidth => c"render: min_width must be finite and >= 0",
            RasterError::GrooveDepth => c"render: groove_depth must be finite and >= 0",
            RasterError::Offset => c"render: offset must be finite",
            RasterError::LineWidth => c"render: line_width must be finite and > 0",
        }
    }
}

impl core::fmt::Display for RasterError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            RasterError::BufferTooSmall { needed } => {
                write!(f, "render: the pixel buffer is smaller than width x height ({needed} needed)")
            }
            e => f.write_str(e.message().to_str().unwrap_or("render error")),
        }
    }
}

impl core::error::Error for RasterError {}

/// Checks that every present buffer of a render holds `pixels` values, before any is written.
pub fn check_lengths<const N: usize>(pixels: usize, lengths: [Option<usize>; N]) -> Result<(), RasterError> {
    if lengths.into_iter().flatten().any(|n| n < pixels) {
        return Err(RasterError::BufferTooSmall { needed: pixels });
    }
    Ok(())
}

/// The number of pixels of a `width` × `height` raster, checked.
pub fn pixel_count(width: u32, height: u32) -> Result<usize, RasterError> {
    if width == 0 || height == 0 {
        return Err(RasterError::Size);
    }
    (width as usize).checked_mul(height as usize).ok_or(RasterError::Size)
}
