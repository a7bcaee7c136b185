//! Capsule strokes: a segment whose half width varies linearly along it, drawn with one
//! pixel of anti-aliasing, optionally wrapped around a periodic domain.

/// A segment to draw, in domain units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stroke {
    /// First end.
    pub start: [f32; 2],
    /// Second end.
    pub end: [f32; 2],
    /// Half width at each end, in pixels.
    pub half_width: [f32; 2],
    /// A value carried along the stroke (a time), at each end.
    pub value: [f32; 2],
}

/// How domain units map to a raster.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// Raster width in pixels.
    pub width: u32,
    /// Raster height in pixels.
    pub height: u32,
    /// Pixels per domain unit, x and y.
    pub scale: [f32; 2],
    /// The domain's period (width, height) in domain units when it wraps around.
    pub period: Option<[f32; 2]>,
    /// The pixels drawn, and how a hit's index counts them.
    pub clip: Clip,
}

/// The rectangle of pixels a drawing visits, in the raster's pixel coordinates: `width`
/// columns from `x` and `height` rows from `y`; a hit's index counts row-major within it. On
/// a periodic frame it may reach past the raster's edges (the strokes' wrapped copies land
/// there); on an open one only the pixels on the raster are visited.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Clip {
    /// First column.
    pub x: i64,
    /// First row.
    pub y: i64,
    /// Columns.
    pub width: u32,
    /// Rows.
    pub height: u32,
}

impl Clip {
    /// The whole `width` × `height` raster.
    pub const fn whole(width: u32, height: u32) -> Clip {
        Clip { x: 0, y: 0, width, height }
    }
}

/// What a stroke leaves on one pixel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StrokeHit {
    /// Row-major pixel index.
    pub pixel: usize,
    /// Anti-aliased coverage in (0, 1].
    pub coverage: f32,
    /// Distance from the stroke's axis over its half width (0 on the axis, 1 at the edge;
    /// the anti-aliased fringe goes up to 1 + 1/half width).
    pub depth: f32,
    /// Half width there, in pixels.
    pub half_width: f32,
    /// The carried value there.
    pub value: f32,
}

/// Calls `visit` for every pixel the stroke covers, row by row, once per copy of the stroke
/// (a wrapped stroke near an edge is drawn at each periodic offset that reaches the raster).
pub fn for_each_hit(frame: &Frame, stroke: &Stroke, mut visit: impl FnMut(StrokeHit)) {
    let offsets: [[f32; 2]; 9] = match frame.period {
        Some([pw, ph]) => core::array::from_fn(|k| [((k % 3) as f32 - 1.0) * pw, ((k / 3) as f32 - 1.0) * ph]),
        None => [[0.0; 2]; 9],
    };
    let copies = if frame.period.is_some() { 9 } else { 1 };
    for offset in &offsets[..copies] {
        let a = [(stroke.start[0] + offset[0]) * frame.scale[0], (stroke.start[1] + offset[1]) * frame.scale[1]];
        let b = [(stroke.end[0] + offset[0]) * frame.scale[0], (stroke.end[1] + offset[1]) * frame.scale[1]];
        draw_capsule(frame, a, b, stroke, &mut visit);
    }
}

/// Draws one copy of a stroke whose ends are `a` and `b` in pixels.
fn draw_capsule(frame: &Frame, a: [f32; 2], b: [f32; 2], stroke: &Stroke, visit: &mut impl FnMut(StrokeHit)) {
    let reach = stroke.half_width[0].max(stroke.half_width[1]) + 1.0;
    let clip = frame.clip;
    // The clip's first and last column and row, within the raster when it does not wrap.
    let (mut left, mut right) = (clip.x, clip.x + i64::from(clip.width) - 1);
    let (mut top, mut bottom) = (clip.y, clip.y + i64::from(clip.height) - 1);
    if frame.period.is_none() {
        (left, right) = (left.max(0), right.min(i64::from(frame.width) - 1));
        (top, bottom) = (top.max(0), bottom.min(i64::from(frame.height) - 1));
    }
    let x0 = libm::floorf(a[0].min(b[0]) - reach).max(left as f32);
    let x1 = libm::floorf(a[0].max(b[0]) + reach).min(right as f32);
    let y0 = libm::floorf(a[1].min(b[1]) - reach).max(top as f32);
    let y1 = libm::floorf(a[1].max(b[1]) + reach).min(bottom as f32);
    if !(x0 <= x1 && y0 <= y1) {
        return;
    }
    let d = [b[0] - a[0], b[1] - a[1]];
    let dd = d[0] * d[0] + d[1] * d[1];
    let columns = clip.width as usize;
    for y in y0 as i64..=y1 as i64 {
        let row = (y - clip.y) as usize * columns;
        for x in x0 as i64..=x1 as i64 {
            let p = [x as f32 + 0.5 - a[0], y as f32 + 0.5 - a[1]];
            let t = if dd > 0.0 { ((p[0] * d[0] + p[1] * d[1]) / dd).clamp(0.0, 1.0) } else { 0.0 };
            let q = [p[0] - d[0] * t, p[1] - d[1] * t];
            let distance = libm::sqrtf(q[0] * q[0] + q[1] * q[1]);
            let half_width = stroke.half_width[0] + (stroke.half_width[1] - stroke.half_width[0]) * t;
            let coverage = (half_width - distance + 0.5).min(1.0);
            if coverage <= 0.0 {
                continue;
            }
            visit(StrokeHit {
                pixel: row + (x - clip.x) as usize,
                coverage,
                depth: if half_width > 0.0 { distance / half_width } else { 1.0 },
                half_width,
                value: stroke.value[0] + (stroke.value[1] - stroke.value[0]) * t,
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame(period: Option<[f32; 2]>) -> Frame {
        Frame { width: 16, height: 8, scale: [1.0, 1.0], period, clip: Clip::whole(16, 8) }
    }

    #[test]
    fn a_horizontal_stroke_covers_its_width_with_soft_edges() {
        let stroke = Stroke { start: [2.0, 4.0], end: [12.0, 4.0], half_width: [1.0, 1.0], value: [0.0, 10.0] };
        let mut cover = [0.0f32; 128];
        let mut value = [f32::NAN; 128];
        for_each_hit(&frame(None), &stroke, |h| {
            cover[h.pixel] = cover[h.pixel].max(h.coverage);
            value[h.pixel] = h.value;
        });
        // Rows 3 and 4 (centres 0.5 from the axis) are fully covered, rows 2 and 5 (1.5 away)
        // are not touched; x = 7 is halfway along.
        assert_eq!(cover[3 * 16 + 7], 1.0);
        assert_eq!(cover[4 * 16 + 7], 1.0);
        assert_eq!(cover[2 * 16 + 7], 0.0);
        assert!((value[4 * 16 + 7] - 5.5).abs() < 1e-5);
        // Past the end cap the coverage fades.
        assert!(cover[4 * 16 + 13] < 1.0);
    }

    #[test]
    fn periodic_strokes_wrap_across_the_edges() {
        let stroke = Stroke { start: [14.0, 4.0], end: [18.0, 4.0], half_width: [1.0, 1.0], value: [0.0; 2] };
        let mut cover = [0.0f32; 128];
        for_each_hit(&frame(Some([16.0, 8.0])), &stroke, |h| cover[h.pixel] = cover[h.pixel].max(h.coverage));
        assert_eq!(cover[4 * 16 + 15], 1.0);
        assert_eq!(cover[4 * 16], 1.0, "the part past x = 16 reappears at x = 0");
        let mut open = [0.0f32; 128];
        for_each_hit(&frame(None), &stroke, |h| open[h.pixel] = open[h.pixel].max(h.coverage));
        assert_eq!(open[4 * 16], 0.0);
    }
}
