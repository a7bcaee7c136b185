//! Rasters of a drying-mud run into caller buffers of any size: an anti-aliased,
//! width-aware crack mask, a break-time map (so a shader can make the cracks appear over
//! time), and a height map with the cracks as grooves. Periodic lattices give seamless
//! rasters: strokes wrap around the domain.

use super::Mud;
use crate::raster::{
    Clip, Derived, Frame, HeightWindow, Layer, Layers, RasterError, SRGB8, Srgb8, Stroke, StrokeHit, Tile,
    coverage_code, draw_mask, draw_time, for_each_hit, for_each_run, pixel_count,
};
use crate::scalar::Scalar;

/// The rasters one [`Mud::render`] call draws: every [`Layers`] field but `cell`.
pub type MudLayers<'o> = Layers<'o>;

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
    /// Depth of the widest groove in pixels, for the normals and the preview's shading.
    pub bump: f32,
    /// Draw the cracks as far as they had broken at this time (long steps): only the parts
    /// of the network whose break time is at most `until`, at the widths the run has now;
    /// +∞ draws them all.
    pub until: f32,
}

impl Default for MudRender {
    fn default() -> Self {
        MudRender {
            width: 512,
            height: 512,
            width_scale: 1.0,
            min_width: 1.0,
            groove_depth: 1.0,
            offset: [0.0; 2],
            bump: 2.0,
            until: f32::INFINITY,
        }
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
        if !(self.bump.is_finite() && self.bump >= 0.0) {
            return Err(RasterError::Bump);
        }
        if self.until.is_nan() {
            return Err(RasterError::Until);
        }
        pixel_count(self.width, self.height)
    }
}

impl<S: Scalar> Mud<'_, S> {
    /// The frame that maps the (deformed-frame) domain onto the raster, visiting `clip`.
    fn frame(&self, render: &MudRender, clip: Clip) -> Frame {
        let (_, deep) = self.factors();
        let [w, h] = self.lattice.extent().map(|e| e * deep.to_f32());
        Frame {
            width: render.width,
            height: render.height,
            scale: [render.width as f32 / w, render.height as f32 / h],
            period: (self.params.boundary == super::Boundary::Periodic).then_some([w, h]),
            clip,
        }
    }

    /// Pixels per lattice unit (the mean of the two axes').
    fn pixels_per_unit(&self, render: &MudRender) -> f32 {
        let frame = self.frame(render, Clip::whole(1, 1));
        0.5 * (frame.scale[0] + frame.scale[1])
    }

    /// A crack's half stroke width in pixels, from its width in lattice units, at
    /// `pixels_per_unit` ([`Mud::pixels_per_unit`]).
    fn half_width(render: &MudRender, pixels_per_unit: f32, width: f32) -> f32 {
        0.5 * (width.max(0.0) * render.width_scale * pixels_per_unit).max(render.min_width)
    }

    /// Calls `visit` for every pixel of `clip` that a crack stroke covers (broken by
    /// `render.until`), each stroke widened on either side by `margin` pixels.
    fn draw(&self, render: &MudRender, clip: Clip, margin: f32, mut visit: impl FnMut(StrokeHit)) {
        let (cut, until) = (render.until < f32::INFINITY, render.until);
        self.strokes(render, clip, margin, |frame, stroke| {
            for_each_hit(frame, stroke, |hit| {
                if !cut || hit.value <= until {
                    visit(hit);
                }
            });
        });
    }

    /// Calls `each` with the frame visiting `clip` and every crack stroke (every piece of the
    /// network, whatever its break time), each widened on either side by `margin` pixels.
    fn strokes(&self, render: &MudRender, clip: Clip, margin: f32, mut each: impl FnMut(&Frame, &Stroke)) {
        let frame = self.frame(render, clip);
        // On a periodic lattice the view wraps: reduce the offset to one period.
        let [ox, oy] = match frame.period {
            Some([w, h]) => [
                render.offset[0] - w * libm::floorf(render.offset[0] / w),
                render.offset[1] - h * libm::floorf(render.offset[1] / h),
            ],
            None => render.offset,
        };
        let ppu = self.pixels_per_unit(render);
        let half = |w: f32| Self::half_width(render, ppu, w) + margin;
        self.for_each_network_piece(|a, b| {
            let stroke = Stroke {
                start: [a.at[0] - ox, a.at[1] - oy],
                end: [b.at[0] - ox, b.at[1] - oy],
                half_width: [half(a.width), half(b.width)],
                value: [a.time, b.time],
            };
            each(&frame, &stroke);
        });
    }

    /// Draws the requested layers of the whole image (see [`Mud::render_tile`]).
    #[inline(always)]
    pub fn render(&self, render: &MudRender, layers: MudLayers<'_>) -> Result<(), RasterError> {
        self.render_tile(render, &Tile::whole(render.width, render.height), layers)
    }

    /// Draws the requested layers (every [`Layers`] field but `cell`) of `tile` of the image
    /// `render` describes, each pixel bit for bit as the whole image has it, in one pass:
    ///
    /// - mask: an anti-aliased, width-aware coverage;
    /// - time: for each pixel the earliest break time of the cracks covering at least half of
    ///   it;
    /// - height: raised cells between grooves (older, wider cracks deeper; see [`BEVEL`]);
    /// - normal: the height's, by central differences, with the widest groove `bump` pixels
    ///   deep;
    /// - preview: dry clay lit from the upper left, dark in the cracks.
    ///
    /// `height16`, `normal`, `normal_rgb8` and `preview` need the scratch. Every buffer is
    /// checked first: nothing is written on failure. The run is only read.
    #[inline(always)]
    pub fn render_tile(&self, render: &MudRender, tile: &Tile, layers: MudLayers<'_>) -> Result<(), RasterError> {
        if layers.derived() { self.render_derived(render, tile, layers) } else { self.render_own(render, tile, layers) }
    }

    /// [`Mud::render_tile`] of the mask, time and height maps only (none needs the scratch).
    #[inline(never)]
    fn render_own(&self, render: &MudRender, tile: &Tile, layers: MudLayers<'_>) -> Result<(), RasterError> {
        render.validate()?;
        tile.check_inside(render.width, render.height)?;
        let pixels = layers.check(tile, |l| l != Layer::Cell, |_| false)?;
        let Layers { mask, height, time, .. } = layers;
        self.draw_own(render, tile, pixels, mask, time);
        if let Some(out) = height {
            let out = &mut out[..pixels];
            out.fill(1.0);
            self.draw_grooves(render, tile.clip(0), out);
        }
        Ok(())
    }

    /// The mask and the time map of `tile` (`pixels` pixels).
    fn draw_own(
        &self,
        render: &MudRender,
        tile: &Tile,
        pixels: usize,
        mask: Option<&mut [u8]>,
        time: Option<&mut [f32]>,
    ) {
        let clip = tile.clip(0);
        if let Some(out) = mask {
            draw_mask(&mut out[..pixels], |visit| self.draw(render, clip, 0.0, visit));
        }
        if let Some(out) = time {
            draw_time(&mut out[..pixels], |visit| self.draw(render, clip, 0.0, visit));
        }
    }

    /// [`Mud::render_tile`] with a layer derived from the height (`height16`, the normals, the
    /// preview): the heights of the tile and its margin in the scratch first.
    #[inline(never)]
    fn render_derived(&self, render: &MudRender, tile: &Tile, layers: MudLayers<'_>) -> Result<(), RasterError> {
        render.validate()?;
        tile.check_inside(render.width, render.height)?;
        let pixels = layers.check(tile, |l| l != Layer::Cell, |_| true)?;
        let clip = tile.clip(0);
        let Layers { mut mask, height, height16: h16, normal, normal_rgb8: n8, time, preview, scratch, .. } = layers;
        self.draw_own(render, tile, pixels, mask.as_deref_mut(), time);
        // (Checked: the derived layers need the scratch.)
        let Some(scratch) = scratch else {
            return Err(RasterError::BufferTooSmall { layer: Layer::Scratch, needed: 0 });
        };
        let periodic = self.params.boundary == super::Boundary::Periodic;
        let mut window = HeightWindow::new(scratch, *tile, [render.width, render.height], periodic, 1.0);
        let window_clip = window.clip();
        self.draw_grooves(render, window_clip, window.bits());
        // The preview's coverage is the mask's, read from it when it is drawn.
        let mut preview = preview.map(|p| &mut p[..pixels]);
        if let Some(p) = preview.as_deref_mut() {
            match mask.as_deref() {
                Some(m) => p.iter_mut().zip(m).for_each(|(p, &m)| *p = [0, 0, 0, m]),
                None => {
                    p.fill([0; 4]);
                    let code = |hit: StrokeHit| coverage_code(hit.coverage);
                    self.draw(render, clip, 0.0, |hit| p[hit.pixel][3] = p[hit.pixel][3].max(code(hit)));
                }
            }
        }
        let light = preview_light();
        let mut shade =
            preview.map(|p| move |i: usize, n: [f32; 3]| p[i] = clay(n, light, f32::from(p[i][3]) / 255.0, &SRGB8));
        let shade = shade.as_mut().map(|s| s as &mut dyn FnMut(usize, [f32; 3]));
        window.write(render.bump, Derived { height, height16: h16, normal, normal_rgb8: n8 }, shade);
        Ok(())
    }

    /// Lowers every pixel of `clip` in a groove (`heights` holds the clip's pixels, row by
    /// row): the height map is 1 on a cell's surface, and each cell's edge rounds off over
    /// [`BEVEL`] spacings into its crack, whose floor lies `groove_depth` times (½ + ½ · its
    /// width over the widest crack's) below the surface: raised cells between grooves, older
    /// (wider) cracks deeper. A pixel's height is the lowest it is given.
    fn draw_grooves<H: HeightCell>(&self, render: &MudRender, clip: Clip, heights: &mut [H]) {
        self.draw_grooves_fringe(render, clip, heights, fringe_lowers);
    }

    /// [`Mud::draw_grooves`], drawing the strokes' anti-aliased fringes (on 64-bit targets)
    /// where `fringe(bevel, widest stroke, groove depth)` says they can lower a height.
    #[inline(always)]
    fn draw_grooves_fringe<H: HeightCell>(
        &self,
        render: &MudRender,
        clip: Clip,
        heights: &mut [H],
        fringe: fn(f32, f32, f32) -> bool,
    ) {
        let ppu = self.pixels_per_unit(render);
        let widest = self.widest(render, ppu);
        if widest <= 0.0 {
            return;
        }
        let (bevel, groove_depth) = (BEVEL * ppu, render.groove_depth);
        // The height a stroke gives a pixel it covers (coverage > 0), `from_axis` pixels from
        // its axis. Written without branches, so that a run's lanes are worked on together;
        // the comparisons give what `max(0.0)` would (the edge's sign does not reach the
        // height: it is squared). The render's constants divide once, as reciprocals.
        let (per_bevel, per_widest) = (1.0 / bevel, 1.0 / widest);
        let height = move |coverage: f32, from_axis: f32, half_width: f32| {
            let crack = half_width - bevel;
            // 1 on the crack's floor, falling to 0 at the bevel's outer edge.
            let fall = 1.0 - (from_axis - crack) * per_bevel;
            // (On 64-bit targets the fall's floor at 0 first: a maximum in the lanes.)
            let edge = if cfg!(target_pointer_width = "64") {
                let fall = if fall > 0.0 { fall } else { 0.0 };
                if from_axis <= crack { 1.0 } else { fall }
            } else if from_axis <= crack {
                1.0
            } else if fall > 0.0 {
                fall
            } else {
                0.0
            };
            let floor = groove_depth * (0.5 + 0.5 * crack * per_widest);
            let groove = floor * edge * edge * coverage;
            1.0 - groove
        };
        // (Not on 32-bit targets, for the Cortex-M3's flash and stack: pixel by pixel there,
        // the same heights.)
        if cfg!(target_pointer_width = "64") {
            let (cut, until) = (render.until < f32::INFINITY, render.until);
            let fringe = fringe(bevel, widest + bevel, groove_depth);
            // (Drawn apart without a cut, so that the lanes do not work out the break times.)
            if cut {
                self.strokes(render, clip, bevel, |frame, stroke| {
                    for_each_run(frame, stroke, heights, fringe, move |cell, hit| {
                        let h = height(hit.coverage, hit.distance, hit.half_width);
                        let hit = (hit.coverage > 0.0) & (hit.value <= until);
                        cell.lower(if hit { h } else { f32::INFINITY });
                    });
                });
            } else {
                self.strokes(render, clip, bevel, |frame, stroke| {
                    // A pixel the stroke does not cover (coverage ≤ 0) is given a height of
                    // at least 1 (the floor and the edge squared are not negative), which
                    // lowers none: the heights start at 1.
                    for_each_run(frame, stroke, heights, fringe, move |cell, hit| {
                        cell.lower(height(hit.coverage, hit.distance, hit.half_width));
                    });
                });
            }
        } else {
            self.draw(render, clip, bevel, |hit| {
                if let Some(cell) = heights.get_mut(hit.pixel) {
                    cell.lower(height(hit.coverage, hit.distance, hit.half_width));
                }
            });
        }
    }

    /// The widest half stroke width ([`Mud::half_width`]) among the ends of the pieces
    /// [`Mud::for_each_network_piece`] gives, 0 if none: each cut side's point has its
    /// spring's separation, and a cell's centroid (where 1 or at least 3 sides are cut) the
    /// mean of its cut sides' (0 at a dead end). Found from the widths alone, without the
    /// points' positions: the half width of the widest end, the half width never falling as
    /// the width rises (what the widest of the ends' half widths is, bit for bit).
    fn widest(&self, render: &MudRender, pixels_per_unit: f32) -> f32 {
        if !self.shows_network() {
            return 0.0;
        }
        let (mut widest, mut any) = (0.0f32, false);
        let mut widths = super::network::Widths::new();
        self.for_each_touched_cell(|cell| {
            let Some((c, cut)) = self.cut_sides(cell) else { return };
            any = true;
            let (mut sum, mut n) = (0.0f32, 0);
            for k in (0..c.corners).filter(|&k| cut[k]) {
                let width = widths.separation(self, c.sides[k] as usize);
                widest = if width > widest { width } else { widest };
                sum += width;
                n += 1;
            }
            if n >= 3 {
                let centroid = sum / n as f32;
                widest = if centroid > widest { centroid } else { widest };
            }
        });
        if any { Self::half_width(render, pixels_per_unit, widest) } else { 0.0 }
    }
}

/// How far a cell's edge rounds off into its crack in the height map [lattice spacings].
pub const BEVEL: f32 = 0.6;

/// Whether a groove stroke's anti-aliased fringe (its pixels whose centre lies past the half
/// width `w` there, coverage < ½) can lower a height below 1, for strokes at most `widest`
/// pixels half wide (the margin `bevel` included) and floors at most `groove_depth` deep. In
/// the fringe the distance is above w, so depth and distance from the axis round to at least
/// w, while the crack's edge w − bevel rounds to within ulp(w)/2 of it (below w, the stroke
/// being at most 2²⁰ bevels half wide): the bevel's fall there is at most
/// w/bevel·2⁻²⁴ + 2⁻²³ (bounded here four times over), and the groove, the floor times the
/// fall squared times the coverage, at most ½·`groove_depth`·fall². Where that is below
/// 2⁻²⁶, 1 − groove rounds to 1 and the fringe lowers nothing. Anything not finite says it
/// can.
fn fringe_lowers(bevel: f32, widest: f32, groove_depth: f32) -> bool {
    let ratio = widest / bevel;
    let fall = ratio * (1.0 / 4_194_304.0) + 1.0 / 2_097_152.0;
    let quiet = ratio <= 1_048_576.0 && groove_depth * fall * fall <= 1.0 / 33_554_432.0;
    !quiet
}

/// A pixel of a height map that [`Mud::draw_grooves`] lowers: an `f32`, or its bits (the
/// scratch's heights).
trait HeightCell: Copy {
    /// Sets the height to `h` where `h` is lower (heights are never NaN; a NaN `h` lowers
    /// nothing, as `min` has it).
    fn lower(&mut self, h: f32);
}

impl HeightCell for f32 {
    #[inline(always)]
    fn lower(&mut self, h: f32) {
        *self = if h < *self { h } else { *self };
    }
}

impl HeightCell for u32 {
    #[inline(always)]
    fn lower(&mut self, h: f32) {
        let now = f32::from_bits(*self);
        *self = (if h < now { h } else { now }).to_bits();
    }
}

/// The preview's light: from the upper left (x right, y up, z out), unit length.
fn preview_light() -> [f32; 3] {
    let l = [-0.5f32, 0.6, 0.62];
    let length = crate::scalar::sqrtf(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
    l.map(|c| c / length)
}

/// The preview's colour of a pixel with normal `n` and crack coverage `coverage`: dry clay
/// (linear RGB 0.40, 0.27, 0.16) blending into a dark crack floor (0.035, 0.025, 0.018), lit by
/// Lambert's law with ambient 0.35, in sRGB by `srgb`.
fn clay(n: [f32; 3], light: [f32; 3], coverage: f32, srgb: &Srgb8) -> [u8; 4] {
    let (clay, crack, ambient) = ([0.40f32, 0.27, 0.16], [0.035f32, 0.025, 0.018], 0.35f32);
    let diffuse = (n[0] * light[0] + n[1] * light[1] + n[2] * light[2]).max(0.0);
    let lit = ambient + (1.0 - ambient) * diffuse;
    srgb.opaque(core::array::from_fn(|k| (clay[k] + (crack[k] - clay[k]) * coverage) * lit / 0.75))
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::mud::{Boundary, MudBuffers, MudParams, Topology};
    use std::vec;

    /// [`Mud::widest`] finds from the widths alone what the pieces' ends give.
    #[test]
    fn the_widest_stroke_is_the_widest_piece_end() {
        let runs = [
            MudParams { columns: 24, rows: 24, ..MudParams::default() },
            MudParams { columns: 20, rows: 18, boundary: Boundary::Open, ..MudParams::default() },
            MudParams { columns: 20, rows: 20, topology: Topology::Irregular, ..MudParams::default() },
            MudParams { columns: 16, rows: 16, topology: Topology::Square, ..MudParams::default() },
        ];
        for params in runs {
            let memory = params.memory().expect("valid parameters");
            let (mut scalars, mut words) = (vec![0.0f32; memory.scalars], vec![0u32; memory.words]);
            let buffers = MudBuffers { scalars: &mut scalars, words: &mut words };
            let mut mud = Mud::new(&params, buffers).expect("memory suffices");
            mud.run().expect("a stable run");
            for render in [
                MudRender::fit(mud.extent(), 96),
                MudRender { width_scale: 3.0, min_width: 0.0, ..MudRender::default() },
            ] {
                let ppu = mud.pixels_per_unit(&render);
                let mut pieces = 0.0f32;
                mud.for_each_network_piece(|a, b| {
                    pieces = pieces
                        .max(Mud::<f32>::half_width(&render, ppu, a.width))
                        .max(Mud::<f32>::half_width(&render, ppu, b.width));
                });
                assert!(pieces > 0.0, "{params:?} cracks");
                assert_eq!(mud.widest(&render, ppu).to_bits(), pieces.to_bits(), "{params:?} {render:?}");
            }
        }
    }

    /// Height maps drawn without the strokes' fringes where [`fringe_lowers`] says they lower
    /// nothing are those drawn with them, bit for bit, over sizes, widths, groove depths and
    /// views; and the fringes are left out in most of them.
    #[test]
    fn a_fringe_left_out_lowers_nothing() {
        let params = MudParams { columns: 24, rows: 24, ..MudParams::default() };
        let memory = params.memory().expect("valid parameters");
        let (mut scalars, mut words) = (vec![0.0f32; memory.scalars], vec![0u32; memory.words]);
        let buffers = MudBuffers { scalars: &mut scalars, words: &mut words };
        let mut mud = Mud::new(&params, buffers).expect("memory suffices");
        mud.run().expect("a stable run");
        let mut rng = crate::rng::Rng::from_key(0x5eed_f12e, 0);
        let (mut left_out, cases) = (0, 300);
        for case in 0..cases {
            let width = 8 + (rng.uniform_f32() * 600.0) as u32;
            let render = MudRender {
                width_scale: [0.0, 0.3, 1.0, 4.0, 40.0][case % 5] * (0.5 + rng.uniform_f32()),
                min_width: [0.0, 1.0, 2.5][case % 3],
                groove_depth: [0.0, 0.01, 1.0, 30.0, 1.0e4, 1.0e9][case % 6] * (0.5 + rng.uniform_f32()),
                offset: [rng.uniform_f32() * 50.0, rng.uniform_f32() * 50.0],
                until: if case % 4 == 0 { 20.0 * rng.uniform_f32() } else { f32::INFINITY },
                ..MudRender::fit(mud.extent(), width)
            };
            let clip = Clip::whole(render.width, render.height);
            let pixels = (render.width * render.height) as usize;
            let (mut with, mut without) = (vec![1.0f32; pixels], vec![1.0f32; pixels]);
            mud.draw_grooves_fringe(&render, clip, &mut with, |_, _, _| true);
            mud.draw_grooves(&render, clip, &mut without);
            let same = with.iter().zip(&without).all(|(a, b)| a.to_bits() == b.to_bits());
            assert!(same, "case {case}: {render:?}");
            let ppu = mud.pixels_per_unit(&render);
            let widest = mud.widest(&render, ppu);
            left_out += usize::from(!fringe_lowers(BEVEL * ppu, widest + BEVEL * ppu, render.groove_depth));
        }
        assert!(left_out > cases / 2, "the fringe left out in {left_out} of {cases}");
    }
}
