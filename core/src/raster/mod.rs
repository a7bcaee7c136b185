//! Drawing into caller buffers: anti-aliased, width-aware strokes (crack masks, height
//! grooves, break-time maps), shared by the models.
//!
//! Rasters are computed in `f32` whatever backend the model ran on: the inputs are the
//! models' `f32` outputs, and IEEE `f32` arithmetic gives the same pixels everywhere.

mod regions;
mod stroke;

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
    /// A drawing parameter is not finite or out of range (the message names it).
    Param(&'static str),
}

/// The number of pixels of a `width` × `height` raster, checked.
pub fn pixel_count(width: u32, height: u32) -> Result<usize, RasterError> {
    if width == 0 || height == 0 {
        return Err(RasterError::Size);
    }
    (width as usize)
        .checked_mul(height as usize)
        .ok_or(RasterError::Size)
}
