//! Rasters of a drying-mud run into caller buffers of any size: an anti-aliased,
//! width-aware crack mask, a break-time map (so a shader can make the cracks appear over
//! time), and a height map with the cracks as grooves. Periodic lattices give seamless
//! rasters: strokes wrap around the domain.

use super::Mud;
use crate::raster::{
    Frame, RasterError, Stroke, StrokeHit, check_lengths, draw_mask, draw_time, for_each_hit, pixel_count,
};
use crate::scalar::Scalar;

/// The rasters one [`Mud::render`] call draws: any of them, each `width × height` values,
/// row-major.
#[derive(Default)]
pub struct MudLayers<'o> {
    /// Crack coverage, 0 (none) to 255 (full).
    pub mask: Option<&'o mut [u8]>,
    /// Height: 1 on a cell's surface, down to 1 − `groove_depth` in the widest crack.
    pub height: Option<&'o mut [f32]>,
    /// Break time in long steps of the crack covering the pixel; +∞ where there is none.
    pub time: Option<&'o mut [f32]>,
}

/// How to draw: raster size and stroke widths.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MudRender {
    /// Raster width in pixels; the lattice's domain is stretched over it.
    pub width: u32,
    /// Raster height in pixels.
    pub height: u32,
    /// Crack widths are multiplied by this before drawing (1 = true width).
    pub width_scale: f32,
    /// The narrowest stroke, in pixels, so that hairline cracks stay visible.
    pub min_width: f32,
    /// Depth of the widest groove in the height map.
    pub groove_depth: f32,
    /// Where the raster's top-left corner sits in the domain, in lattice units (pans a
    /// periodic tile; on open lattices it shifts the view).
    pub offset: [f32; 2],
}

impl Default for MudRender {
    fn default() -> Self {
        MudRender { width: 512, height: 512, width_scale: 1.0, min_width: 1.0, groove_depth: 1.0, offset: [0.0; 2] }
    }
}

/// The narrowest crack [`MudRender::fit`] draws, in lattice spacings: the traced network is
/// connected, so the stroke only has to keep the youngest cracks visible.
pub const HAIRLINE: f32 = 0.2;

impl MudRender {
    /// The default drawing `width` pixels wide over a domain of `extent` (lattice units, from
    /// [`Mud::extent`] or [`super::MudParams::extent`]): its height at the domain's aspect
    /// (rounded, at least 1 pixel), so that nothing is stretched, and its narrowest stroke
    /// [`HAIRLINE`] of a spacing (at least 1 pixel, rounded to 1/100 px); the rest as
    /// [`MudRender::default`].
    pub fn fit(extent: [f32; 2], width: u32) -> MudRender {
        let [w, h] = extent;
        let height = (libm::roundf(width as f32 * h / w) as u32).max(1);
        let pixels_per_spacing = width as f32 / w;
        let min_width = libm::roundf((HAIRLINE * pixels_per_spacing).max(1.0) * 100.0) / 100.0;
        MudRender { width, height, min_width, ..MudRender::default() }
    }

    fn validate(&self) -> Result<usize, RasterError> {
        if !(self.width_scale.is_finite() && self.width_scale >= 0.0) {
            return Err(RasterError::WidthScale);
        }
        if !(self.min_width.is_finite() && self.min_width >= 0.0) {
            return Err(RasterError::MinWidth);
        }
        if !(self.groove_depth.is_finite() && self.groove_depth >= 0.0) {
            return Err(RasterError::GrooveDepth);
        }
        if !(self.offset[0].is_finite() && self.offset[1].is_finite()) {
            return Err(RasterError::Offset);
        }
        pixel_count(self.width, self.height)
    }
}

impl<S: Scalar> Mud<'_, S> {
    /// The frame that maps the (deformed-frame) domain onto the raster.
    fn frame(&self, render: &MudRender) -> Frame {
        let (_, deep) = self.factors();
        let [w, h] = self.lattice.extent().map(|e| e * deep.to_f32());
        Frame {
            width: render.width,
            height: render.height,
            scale: [render.width as f32 / w, render.height as f32 / h],
            period: (self.params.boundary == super::Boundary::Periodic).then_some([w, h]),
        }
    }

    /// Pixels per lattice unit (the mean of the two axes').
    fn pixels_per_unit(&self, render: &MudRender) -> f32 {
        let frame = self.frame(render);
        0.5 * (frame.scale[0] + frame.scale[1])
    }

    /// Calls `visit` for every pixel of every crack stroke, each widened on either side by
    /// `margin` pixels.
    fn draw(&self, render: &MudRender, margin: f32, mut visit: impl FnMut(StrokeHit)) {
        let frame = self.frame(render);
        let pixels_per_unit = self.pixels_per_unit(render);
        let half = |w: f32| 0.5 * (w.max(0.0) * render.width_scale * pixels_per_unit).max(render.min_width) + margin;
        // On a periodic lattice the view wraps: reduce the offset to one period.
        let [ox, oy] = match frame.period {
            Some([w, h]) => [
                render.offset[0] - w * libm::floorf(render.offset[0] / w),
                render.offset[1] - h * libm::floorf(render.offset[1] / h),
            ],
            None => render.offset,
        };
        self.for_each_network_piece(|a, b| {
            let stroke = Stroke {
                start: [a.at[0] - ox, a.at[1] - oy],
                end: [b.at[0] - ox, b.at[1] - oy],
                half_width: [half(a.width), half(b.width)],
                value: [a.time, b.time],
            };
            for_each_hit(&frame, &stroke, &mut visit);
        });
    }

    /// Draws the requested layers (see [`MudLayers`]): the mask, an anti-aliased,
    /// width-aware coverage; the time map, for each pixel the earliest break time of the
    /// cracks covering at least half of it; the height map, raised cells between grooves (older, wider cracks deeper; see [`BEVEL`]).
    /// Every buffer is checked first: nothing is written on failure.
    pub fn render(&self, render: &MudRender, layers: MudLayers<'_>) -> Result<(), RasterError> {
        let pixels = render.validate()?;
        let MudLayers { mask, height, time } = layers;
        check_lengths(
            pixels,
            [mask.as_deref().map(<[u8]>::len), height.as_deref().map(<[f32]>::len), time.as_deref().map(<[f32]>::len)],
        )?;
        if let Some(out) = mask {
            draw_mask(pixels, out, |visit| self.draw(render, 0.0, visit))?;
        }
        if let Some(out) = time {
            draw_time(pixels, out, |visit| self.draw(render, 0.0, visit))?;
        }
        if let Some(out) = height {
            self.render_height(render, pixels, out);
        }
        Ok(())
    }

    /// The height map: 1 on a cell's surface. Each cell's edge rounds off over
    /// [`BEVEL`] spacings into its crack, whose floor lies `groove_depth` times
    /// (½ + ½ · its width over the widest crack's) below the surface: raised cells between
    /// grooves, older (wider) cracks deeper.
    fn render_height(&self, render: &MudRender, pixels: usize, out: &mut [f32]) {
        let mut widest = 0.0f32;
        self.draw(render, 0.0, |hit| widest = widest.max(hit.half_width));
        out[..pixels].fill(1.0);
        if widest <= 0.0 {
            return;
        }
        let bevel = BEVEL * self.pixels_per_unit(render);
        self.draw(render, bevel, |hit| {
            let crack = hit.half_width - bevel;
            let from_axis = hit.depth * hit.half_width;
            // 1 on the crack's floor, falling to 0 at the bevel's outer edge.
            let edge = if from_axis <= crack { 1.0 } else { (1.0 - (from_axis - crack) / bevel).max(0.0) };
            let floor = render.groove_depth * (0.5 + 0.5 * crack / widest);
            let groove = floor * edge * edge * hit.coverage;
            out[hit.pixel] = out[hit.pixel].min(1.0 - groove);
        });
    }
}

/// How far a cell's edge rounds off into its crack in the height map [lattice spacings].
pub const BEVEL: f32 = 0.6;
