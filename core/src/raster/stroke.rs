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
    let reach = stroke.half_width[0].max(stroke.half_width[1]) + 1.0;
    let clip = frame.clip;
    // The clip's first and last column and row, within the raster when it does not wrap.
    let (mut left, mut right) = (clip.x, clip.x + i64::from(clip.width) - 1);
    let (mut top, mut bottom) = (clip.y, clip.y + i64::from(clip.height) - 1);
    if frame.period.is_none() {
        (left, right) = (left.max(0), right.min(i64::from(frame.width) - 1));
        (top, bottom) = (top.max(0), bottom.min(i64::from(frame.height) - 1));
    }
    // Each axis on its own: the copies' ends in pixels at the periodic offsets −1, 0 and +1
    // periods (0 alone when the frame does not wrap), and the pixels they reach.
    let copies = if frame.period.is_some() { 3 } else { 1 };
    let period = frame.period.unwrap_or([0.0; 2]);
    let axis = |k: usize, first: i64, last: i64| -> [Extent; 3] {
        core::array::from_fn(|i| {
            if i >= copies {
                return Extent { ends: [0.0; 2], pixels: [0.0; 2], reached: false };
            }
            let offset = if copies == 3 { (i as f32 - 1.0) * period[k] } else { 0.0 };
            let a = (stroke.start[k] + offset) * frame.scale[k];
            let b = (stroke.end[k] + offset) * frame.scale[k];
            let lo = libm::floorf(a.min(b) - reach).max(first as f32);
            let hi = libm::floorf(a.max(b) + reach).min(last as f32);
            Extent { ends: [a, b], pixels: [lo, hi], reached: lo <= hi }
        })
    };
    let xs = axis(0, left, right);
    let ys = axis(1, top, bottom);
    for y in ys[..copies].iter().filter(|e| e.reached) {
        for x in xs[..copies].iter().filter(|e| e.reached) {
            let (a, b) = ([x.ends[0], y.ends[0]], [x.ends[1], y.ends[1]]);
            draw_capsule(clip, a, b, [x.pixels, y.pixels], stroke, &mut visit);
        }
    }
}

/// One axis of a copy of a stroke: its ends' coordinates in pixels, and the first and last
/// pixel within `reach` of them on the clip, if any (`reached`).
#[derive(Clone, Copy)]
struct Extent {
    ends: [f32; 2],
    pixels: [f32; 2],
    reached: bool,
}

/// Draws one copy of a stroke whose ends are `a` and `b` in pixels, within the pixels
/// `bounds` (first and last column, first and last row, the box within the widest half
/// width + 1 of its ends): each row only over the columns [`Span`] finds the stroke can
/// cover.
fn draw_capsule(
    clip: Clip,
    a: [f32; 2],
    b: [f32; 2],
    bounds: [[f32; 2]; 2],
    stroke: &Stroke,
    visit: &mut impl FnMut(StrokeHit),
) {
    let [[x0, x1], [y0, y1]] = bounds;
    let d = [b[0] - a[0], b[1] - a[1]];
    let dd = d[0] * d[0] + d[1] * d[1];
    let columns = clip.width as usize;
    // (Not on 32-bit targets, for the Cortex-M3's flash: the whole bounding box visits the
    // same hits.)
    let span = if cfg!(target_pointer_width = "64") {
        Span::new(a, d, dd, stroke.half_width[0].max(stroke.half_width[1]))
    } else {
        None
    };
    // One pixel: column `x`, whose centre is at `cx` (x + ½), on a row whose centre lies `py`
    // below a, `row` its first pixel's index.
    macro_rules! pixel {
        ($x:expr, $cx:expr, $py:expr, $row:expr) => {{
            let p = [$cx - a[0], $py];
            let t = if dd > 0.0 { ((p[0] * d[0] + p[1] * d[1]) / dd).clamp(0.0, 1.0) } else { 0.0 };
            let q = [p[0] - d[0] * t, p[1] - d[1] * t];
            let distance = libm::sqrtf(q[0] * q[0] + q[1] * q[1]);
            let half_width = stroke.half_width[0] + (stroke.half_width[1] - stroke.half_width[0]) * t;
            let coverage = (half_width - distance + 0.5).min(1.0);
            if coverage > 0.0 {
                visit(StrokeHit {
                    pixel: $row + ($x - clip.x) as usize,
                    coverage,
                    depth: if half_width > 0.0 { distance / half_width } else { 1.0 },
                    half_width,
                    value: stroke.value[0] + (stroke.value[1] - stroke.value[0]) * t,
                });
            }
        }};
    }
    for y in y0 as i64..=y1 as i64 {
        let row = (y - clip.y) as usize * columns;
        let py = y as f32 + 0.5 - a[1];
        match &span {
            Some(span) => {
                let [from, to] = span.columns(y as f32 + 0.5);
                let (first, last) = ((x0 as i64).max(from), (x1 as i64).min(to));
                // Within a span's bounds x + ½ is exact, and so is counting it up by 1.
                let mut cx = first as f32 + 0.5;
                for x in first..last + 1 {
                    pixel!(x, cx, py, row);
                    cx += 1.0;
                }
            }
            None => {
                for x in x0 as i64..x1 as i64 + 1 {
                    pixel!(x, x as f32 + 0.5, py, row);
                }
            }
        }
    }
}

/// Strokes and reaches shorter than this many pixels have their rows cut to [`Span`]s (longer
/// ones are drawn over their whole bounding box).
const SPAN_LIMIT: f32 = 4096.0;

/// Strokes that start closer than this many pixels to the raster's origin have their rows cut
/// to [`Span`]s (pixel coordinates stay exact to 1/128 pixel there).
const SPAN_REACH: f32 = 262144.0;

/// How far a [`Span`] reaches past where a pixel's centre can have coverage, in pixels: far
/// more than the rounding of the pixels' and the span's arithmetic at the sizes
/// [`SPAN_LIMIT`] and [`SPAN_REACH`] allow (a few 1/1000 pixel).
const SPAN_SLACK: f32 = 0.125;

/// The capsule whose pixels a stroke can cover (from `a` to `a + d`, in pixels), row by row:
/// a row's centre line meets it in one interval (it is convex), bounded by where the line
/// meets the two end discs and the two long edges. A pixel covers nothing unless its centre
/// lies within its half width + ½ of the axis (coverage = half width − distance + ½): the
/// capsule's radius is the widest half width + ½ + [`SPAN_SLACK`], so that every pixel with
/// coverage lies in its row's span.
struct Span {
    a: [f32; 2],
    d: [f32; 2],
    /// The radius, squared.
    rr: f32,
    /// The long edges' offset from the axis: the radius along the unit normal (NaN when the
    /// ends meet: the discs alone are the capsule).
    edge: [f32; 2],
    /// 1 / `d[1]`.
    per_row: f32,
}

impl Span {
    /// The capsule of a stroke whose widest half width is `widest`, or `None` when its rows
    /// are drawn whole (a stroke or width past [`SPAN_LIMIT`], a start past [`SPAN_REACH`], no
    /// width, anything not finite).
    fn new(a: [f32; 2], d: [f32; 2], dd: f32, widest: f32) -> Option<Span> {
        let radius = widest + 0.5 + SPAN_SLACK;
        let small = |v: f32, limit: f32| v.abs() < limit;
        let fits = small(d[0], SPAN_LIMIT)
            && small(d[1], SPAN_LIMIT)
            && (0.0..SPAN_LIMIT).contains(&widest)
            && small(a[0], SPAN_REACH)
            && small(a[1], SPAN_REACH);
        if !fits {
            return None;
        }
        let length = libm::sqrtf(dd);
        let edge = [-d[1] / length * radius, d[0] / length * radius];
        Some(Span { a, d, rr: radius * radius, edge, per_row: 1.0 / d[1] })
    }

    /// The first and last column whose pixel centre may lie in the capsule on the row whose
    /// centre is at `cy` (first > last when none does).
    fn columns(&self, cy: f32) -> [i64; 2] {
        let v = cy - self.a[1];
        let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
        // The end discs, centred at 0 and d (x relative to a).
        for (x, y) in [(0.0, v), (self.d[0], v - self.d[1])] {
            let w2 = self.rr - y * y;
            if w2 > 0.0 {
                let w = libm::sqrtf(w2);
                (lo, hi) = (lo.min(x - w), hi.max(x + w));
            }
        }
        // The long edges, from a ± edge to a + d ± edge.
        for side in [1.0f32, -1.0] {
            let t = (v - side * self.edge[1]) * self.per_row;
            if (0.0..=1.0).contains(&t) {
                let x = side * self.edge[0] + t * self.d[0];
                (lo, hi) = (lo.min(x), hi.max(x));
            }
        }
        // Pixel x's centre is x + ½; truncation moves neither end inwards past a centre.
        [(self.a[0] + lo - 0.5) as i64, (self.a[0] + hi - 0.5) as i64]
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

    /// Every pixel of every copy's bounding box tested, one after the other: what
    /// [`for_each_hit`] must visit, in the same order, with the same values.
    fn every_pixel_of_the_boxes(frame: &Frame, stroke: &Stroke, visit: &mut impl FnMut(StrokeHit)) {
        let reach = stroke.half_width[0].max(stroke.half_width[1]) + 1.0;
        let clip = frame.clip;
        let (mut left, mut right) = (clip.x, clip.x + i64::from(clip.width) - 1);
        let (mut top, mut bottom) = (clip.y, clip.y + i64::from(clip.height) - 1);
        if frame.period.is_none() {
            (left, right) = (left.max(0), right.min(i64::from(frame.width) - 1));
            (top, bottom) = (top.max(0), bottom.min(i64::from(frame.height) - 1));
        }
        let copies = if frame.period.is_some() { 9 } else { 1 };
        for k in 0..copies {
            let offset = match frame.period {
                Some([pw, ph]) => [((k % 3) as f32 - 1.0) * pw, ((k / 3) as f32 - 1.0) * ph],
                None => [0.0; 2],
            };
            let a = [(stroke.start[0] + offset[0]) * frame.scale[0], (stroke.start[1] + offset[1]) * frame.scale[1]];
            let b = [(stroke.end[0] + offset[0]) * frame.scale[0], (stroke.end[1] + offset[1]) * frame.scale[1]];
            let x0 = libm::floorf(a[0].min(b[0]) - reach).max(left as f32);
            let x1 = libm::floorf(a[0].max(b[0]) + reach).min(right as f32);
            let y0 = libm::floorf(a[1].min(b[1]) - reach).max(top as f32);
            let y1 = libm::floorf(a[1].max(b[1]) + reach).min(bottom as f32);
            if !(x0 <= x1 && y0 <= y1) {
                continue;
            }
            let d = [b[0] - a[0], b[1] - a[1]];
            let dd = d[0] * d[0] + d[1] * d[1];
            for y in y0 as i64..=y1 as i64 {
                for x in x0 as i64..=x1 as i64 {
                    let p = [x as f32 + 0.5 - a[0], y as f32 + 0.5 - a[1]];
                    let t = if dd > 0.0 { ((p[0] * d[0] + p[1] * d[1]) / dd).clamp(0.0, 1.0) } else { 0.0 };
                    let q = [p[0] - d[0] * t, p[1] - d[1] * t];
                    let distance = libm::sqrtf(q[0] * q[0] + q[1] * q[1]);
                    let half_width = stroke.half_width[0] + (stroke.half_width[1] - stroke.half_width[0]) * t;
                    let coverage = (half_width - distance + 0.5).min(1.0);
                    if coverage > 0.0 {
                        visit(StrokeHit {
                            pixel: (y - clip.y) as usize * clip.width as usize + (x - clip.x) as usize,
                            coverage,
                            depth: if half_width > 0.0 { distance / half_width } else { 1.0 },
                            half_width,
                            value: stroke.value[0] + (stroke.value[1] - stroke.value[0]) * t,
                        });
                    }
                }
            }
        }
    }

    #[test]
    fn rows_cut_to_the_capsule_visit_what_the_whole_boxes_do() {
        extern crate std;
        use std::vec::Vec;
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 40) as f32 / (1u64 << 24) as f32
        };
        let (mut strokes, mut hits) = (0, 0);
        for case in 0..4000 {
            let periodic = case % 2 == 0;
            let (width, height) = (8 + (next() * 120.0) as u32, 8 + (next() * 120.0) as u32);
            let scale = [0.25 + next() * 4.0, 0.25 + next() * 4.0];
            let period = [width as f32 / scale[0], height as f32 / scale[1]];
            let margin = (next() * 3.0) as u32;
            let clip = match case % 3 {
                0 => Clip::whole(width, height),
                1 => Clip {
                    x: -i64::from(margin),
                    y: -i64::from(margin),
                    width: width + 2 * margin,
                    height: height + 2 * margin,
                },
                _ => Clip {
                    x: (next() * 20.0) as i64 - 5,
                    y: (next() * 20.0) as i64 - 5,
                    width: 1 + (next() * 60.0) as u32,
                    height: 1 + (next() * 60.0) as u32,
                },
            };
            let frame = Frame { width, height, scale, period: periodic.then_some(period), clip };
            let start = [next() * period[0] * 1.4 - 0.2 * period[0], next() * period[1] * 1.4 - 0.2 * period[1]];
            let length = match case % 5 {
                0 => 0.0,
                1 => next() * 2.0,
                2 if case % 4 == 2 => next() * 400.0,
                _ => next() * 40.0,
            };
            let angle = match case % 7 {
                0 => 0.0,
                1 => core::f32::consts::FRAC_PI_2,
                2 => core::f32::consts::FRAC_PI_4,
                _ => next() * 6.3,
            };
            let end = [start[0] + length * libm::cosf(angle), start[1] + length * libm::sinf(angle)];
            let half_width = match case % 4 {
                0 => [next() * 0.8, next() * 0.8],
                1 => [next() * 6.0; 2],
                2 => [0.0, next() * 12.0],
                _ => [next() * 4.0, next() * 4.0],
            };
            let stroke = Stroke { start, end, half_width, value: [next() * 10.0, next() * 10.0] };
            let (mut fast, mut whole) = (Vec::new(), Vec::new());
            for_each_hit(&frame, &stroke, |h| fast.push(h));
            every_pixel_of_the_boxes(&frame, &stroke, &mut |h| whole.push(h));
            assert_eq!(fast.len(), whole.len(), "case {case}: {frame:?} {stroke:?}");
            for (f, w) in fast.iter().zip(&whole) {
                let bits = |h: &StrokeHit| (h.pixel, [h.coverage, h.depth, h.half_width, h.value].map(f32::to_bits));
                assert_eq!(bits(f), bits(w), "case {case}: {frame:?} {stroke:?}");
            }
            strokes += usize::from(!whole.is_empty());
            hits += whole.len();
        }
        assert!(strokes > 2000 && hits > 100_000, "the cases draw: {strokes} strokes, {hits} hits");
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
