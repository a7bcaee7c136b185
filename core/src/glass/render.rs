//! Rasters of the crack network into caller buffers of any size: an anti-aliased mask and a
//! time map (the step at which the crack front passed each pixel, for animating the break).

use super::Glass;
use crate::raster::{
    Frame, RasterError, Stroke, StrokeHit, check_lengths, draw_mask, draw_time, for_each_hit, pixel_count,
};

/// The rasters one [`Glass::render`] call draws: any of them, each `width × height` values,
/// row-major.
#[derive(Default)]
pub struct GlassLayers<'o> {
    /// Crack coverage, anti-aliased, 0 (none) to 255 (full).
    pub mask: Option<&'o mut [u8]>,
    /// For each pixel the earliest step at which a crack covering at least half of it was
    /// there; +∞ where none is (for animating the break).
    pub time: Option<&'o mut [f32]>,
}

/// How to draw: raster size and line width.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GlassRender {
    /// Raster width in pixels; the plate is stretched over it.
    pub width: u32,
    /// Raster height in pixels.
    pub height: u32,
    /// Width of a crack line in raster pixels.
    pub line_width: f32,
}

impl Default for GlassRender {
    fn default() -> Self {
        GlassRender { width: 640, height: 640, line_width: 1.2 }
    }
}

impl GlassRender {
    fn validate(&self) -> Result<usize, RasterError> {
        if !(self.line_width.is_finite() && self.line_width > 0.0) {
            return Err(RasterError::LineWidth);
        }
        pixel_count(self.width, self.height)
    }
}

impl Glass<'_> {
    /// Calls `visit` for every pixel of every crack segment.
    fn draw(&self, render: &GlassRender, mut visit: impl FnMut(StrokeHit)) {
        let frame = Frame {
            width: render.width,
            height: render.height,
            scale: [render.width as f32 / self.params.width, render.height as f32 / self.params.height],
            period: None,
        };
        let half = 0.5 * render.line_width;
        for i in 0..self.crack_count() {
            let mut previous = None;
            self.for_each_point(i, |p| {
                if let Some(q) = previous.replace(p) {
                    let q: super::CrackPoint = q;
                    let stroke = Stroke { start: q.at, end: p.at, half_width: [half; 2], value: [q.time, p.time] };
                    for_each_hit(&frame, &stroke, &mut visit);
                }
            });
        }
    }

    /// Draws the requested layers (see [`GlassLayers`]). Every buffer is checked first:
    /// nothing is written on failure.
    pub fn render(&self, render: &GlassRender, layers: GlassLayers<'_>) -> Result<(), RasterError> {
        let pixels = render.validate()?;
        let GlassLayers { mask, time } = layers;
        check_lengths(pixels, [mask.as_deref().map(<[u8]>::len), time.as_deref().map(<[f32]>::len)])?;
        if let Some(out) = mask {
            draw_mask(pixels, out, |visit| self.draw(render, visit))?;
        }
        if let Some(out) = time {
            draw_time(pixels, out, |visit| self.draw(render, visit))?;
        }
        Ok(())
    }
}
