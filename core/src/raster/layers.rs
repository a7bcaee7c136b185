//! The layers every model draws from its strokes: a coverage mask and a time map. A model
//! hands in its pixel count and a function that feeds every stroke hit to a visitor.

use super::{RasterError, StrokeHit};

/// Checks that `out` holds `pixels` values.
fn fits<T>(pixels: usize, out: &[T]) -> Result<(), RasterError> {
    if out.len() < pixels { Err(RasterError::BufferTooSmall { needed: pixels }) } else { Ok(()) }
}

/// The anti-aliased mask: each pixel's largest coverage, 0 to 255. Nothing is written if `out`
/// is shorter than `pixels`.
pub fn draw_mask(
    pixels: usize,
    out: &mut [u8],
    strokes: impl FnOnce(&mut dyn FnMut(StrokeHit)),
) -> Result<(), RasterError> {
    fits(pixels, out)?;
    out[..pixels].fill(0);
    strokes(&mut |hit| {
        let v = libm::roundf(hit.coverage * 255.0) as u8;
        out[hit.pixel] = out[hit.pixel].max(v);
    });
    Ok(())
}

/// The time map: each pixel's earliest time among the strokes covering at least half of it;
/// +∞ where none does. Nothing is written if `out` is shorter than `pixels`.
pub fn draw_time(
    pixels: usize,
    out: &mut [f32],
    strokes: impl FnOnce(&mut dyn FnMut(StrokeHit)),
) -> Result<(), RasterError> {
    fits(pixels, out)?;
    out[..pixels].fill(f32::INFINITY);
    strokes(&mut |hit| {
        if hit.coverage >= 0.5 {
            out[hit.pixel] = out[hit.pixel].min(hit.value);
        }
    });
    Ok(())
}
