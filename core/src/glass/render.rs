//! Rasters of the crack network into caller buffers of any size: an anti-aliased mask and a
//! time map (the step at which the crack front passed each pixel, for animating the break).

use super::Glass;
use crate::raster::{
    Clip, Derived, Frame, HeightWindow, Layer, Layers, RasterError, SRGB8, Srgb8, Stroke, StrokeHit, Tile,
    coverage_code, draw_mask, draw_time, for_each_hit, pixel_count,
};

/// The rasters one [`Glass::render`] call draws: every [`Layers`] field but `cell`.
pub type GlassLayers<'o> = Layers<'o>;

/// How to draw: raster size and line width.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GlassRender {
    /// Raster width in pixels; the plate is stretched over it.
    pub width: u32,
    /// Raster height in pixels.
    pub height: u32,
    /// Width of a crack line in raster pixels.
    pub line_width: f32,
    /// Depth of a fully covered crack in pixels, for the normals (the height is 1 − coverage).
    pub bump: f32,
    /// Draw the cracks as far as they had grown at this time step: only the parts the front
    /// passed by `until`; +∞ draws them all.
    pub until: f32,
}

impl Default for GlassRender {
    fn default() -> Self {
        GlassRender { width: 640, height: 640, line_width: 1.2, bump: 2.0, until: f32::INFINITY }
    }
}

impl GlassRender {
    fn validate(&self) -> Result<usize, RasterError> {
        if !(self.line_width.is_finite() && self.line_width > 0.0) {
            return Err(RasterError::LineWidth);
        }
        if !(self.bump.is_finite() && self.bump >= 0.0) {
            return Err(RasterError::Bump);
        }
        if self.until.is_nan() {
            return Err(RasterError::Until);
        }
        pixel_count(self.width, self.height)
    }
}

impl Glass<'_> {
    /// Calls `visit` for every pixel of `clip` a crack segment (grown by `render.until`)
    /// covers.
    fn draw(&self, render: &GlassRender, clip: Clip, mut visit: impl FnMut(StrokeHit)) {
        let frame = Frame {
            width: render.width,
            height: render.height,
            scale: [render.width as f32 / self.params.width, render.height as f32 / self.params.height],
            period: None,
            clip,
        };
        let half = 0.5 * render.line_width;
        let cut = render.until < f32::INFINITY;
        for i in 0..self.crack_count() {
            let mut previous = None;
            self.for_each_point(i, |p| {
                if let Some(q) = previous.replace(p) {
                    let q: super::CrackPoint = q;
                    let stroke = Stroke { start: q.at, end: p.at, half_width: [half; 2], value: [q.time, p.time] };
                    for_each_hit(&frame, &stroke, |hit| {
                        if !cut || hit.value <= render.until {
                            visit(hit);
                        }
                    });
                }
            });
        }
    }

    /// Draws the requested layers of the whole image (see [`Glass::render_tile`]).
    #[inline(always)]
    pub fn render(&self, render: &GlassRender, layers: GlassLayers<'_>) -> Result<(), RasterError> {
        self.render_tile(render, &Tile::whole(render.width, render.height), layers)
    }

    /// Draws the requested layers (every [`Layers`] field but `cell`) of `tile` of the image
    /// `render` describes, each pixel bit for bit as the whole image has it, in one pass: the
    /// anti-aliased mask; the time map (for each pixel the earliest step at which a crack
    /// covering at least half of it was there); the height, 1 − coverage; its normals by
    /// central differences, a full crack `bump` pixels deep; a preview of dark glass with
    /// bright cracks. `height16`, `normal` and `normal_rgb8` need the scratch. Every buffer is
    /// checked first: nothing is written on failure. The plate is only read.
    #[inline(always)]
    pub fn render_tile(&self, render: &GlassRender, tile: &Tile, layers: GlassLayers<'_>) -> Result<(), RasterError> {
        if layers.derived() { self.render_derived(render, tile, layers) } else { self.render_own(render, tile, layers) }
    }

    /// [`Glass::render_tile`] of the mask, time and height maps only.
    #[inline(never)]
    fn render_own(&self, render: &GlassRender, tile: &Tile, layers: GlassLayers<'_>) -> Result<(), RasterError> {
        render.validate()?;
        tile.check_inside(render.width, render.height)?;
        let pixels = layers.check(tile, |l| l != Layer::Cell, |_| false)?;
        let clip = tile.clip(0);
        let Layers { mask, height, time, .. } = layers;
        if let Some(out) = time {
            draw_time(&mut out[..pixels], |visit| self.draw(render, clip, visit));
        }
        let mut mask = mask.map(|m| &mut m[..pixels]);
        if let Some(out) = mask.as_deref_mut() {
            draw_mask(out, |visit| self.draw(render, clip, visit));
        }
        if let Some(out) = height {
            self.draw_height(render, clip, mask.as_deref(), &mut out[..pixels]);
        }
        Ok(())
    }

    /// The height, 1 − coverage: from the mask when it is drawn, else from the strokes.
    fn draw_height(&self, render: &GlassRender, clip: Clip, mask: Option<&[u8]>, out: &mut [f32]) {
        match mask {
            Some(m) => out.iter_mut().zip(m).for_each(|(h, &m)| *h = depth(m)),
            None => {
                out.fill(1.0);
                self.draw(render, clip, |hit| out[hit.pixel] = out[hit.pixel].min(depth(coverage_code(hit.coverage))));
            }
        }
    }

    /// [`Glass::render_tile`] with a derived layer (`height16`, the normals, the preview).
    #[inline(never)]
    fn render_derived(&self, render: &GlassRender, tile: &Tile, layers: GlassLayers<'_>) -> Result<(), RasterError> {
        render.validate()?;
        tile.check_inside(render.width, render.height)?;
        let windowed = |l: &Layers| l.height16.is_some() || l.normal.is_some() || l.normal_rgb8.is_some();
        let pixels = layers.check(tile, |l| l != Layer::Cell, windowed)?;
        let clip = tile.clip(0);
        let needs_window = windowed(&layers);
        let Layers { mask, height, height16: h16, normal, normal_rgb8: n8, time, preview, scratch, .. } = layers;
        if let Some(out) = time {
            draw_time(&mut out[..pixels], |visit| self.draw(render, clip, visit));
        }
        // The mask first: the preview and (without the scratch) the height read it.
        let mut mask = mask.map(|m| &mut m[..pixels]);
        if let Some(out) = mask.as_deref_mut() {
            draw_mask(out, |visit| self.draw(render, clip, visit));
        }
        if let Some(p) = preview.map(|p| &mut p[..pixels]) {
            match mask.as_deref() {
                Some(m) => p.iter_mut().zip(m).for_each(|(p, &m)| *p = [0, 0, 0, m]),
                None => {
                    p.fill([0; 4]);
                    self.draw(render, clip, |hit| p[hit.pixel][3] = p[hit.pixel][3].max(coverage_code(hit.coverage)));
                }
            }
            for (i, px) in p.iter_mut().enumerate() {
                let (x, y) = (tile.x + (i % tile.width as usize) as u32, tile.y + (i / tile.width as usize) as u32);
                let (x, y) = (x as f32 / render.width as f32, y as f32 / render.height as f32);
                *px = plate(x, y, f32::from(px[3]) / 255.0, &SRGB8);
            }
        }
        let Some(scratch) = scratch.filter(|_| needs_window) else {
            if let Some(out) = height {
                self.draw_height(render, clip, mask.as_deref(), &mut out[..pixels]);
            }
            return Ok(());
        };
        let mut window = HeightWindow::new(scratch, *tile, [render.width, render.height], false, 1.0);
        self.draw(render, window.clip(), |hit| {
            let lower = window.at(hit.pixel).min(depth(coverage_code(hit.coverage)));
            window.set(hit.pixel, lower);
        });
        window.write(render.bump, Derived { height, height16: h16, normal, normal_rgb8: n8 }, None);
        Ok(())
    }
}

/// The height of a pixel of mask value `code`: 1 − coverage.
fn depth(code: u8) -> f32 {
    1.0 - f32::from(code) / 255.0
}

/// The preview's colour at (`x`, `y`), fractions of the image's width and height, with crack
/// coverage `coverage`: dark glass (linear RGB 0.012, 0.022, 0.030) with a faint sheen,
/// brightest at the upper left, blending into bright cracks (0.80, 0.90, 0.95), in sRGB by
/// `srgb`.
fn plate(x: f32, y: f32, coverage: f32, srgb: &Srgb8) -> [u8; 4] {
    let sheen = 0.02 * (1.0 - 0.5 * (x + y));
    let plate = [0.012 + sheen, 0.022 + sheen, 0.030 + sheen];
    let crack = [0.80f32, 0.90, 0.95];
    srgb.opaque(core::array::from_fn(|k| plate[k] + (crack[k] - plate[k]) * coverage))
}
