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
    /// Distance from the stroke's axis, in pixels (`depth` times `half_width`, without the
    /// division's rounding).
    pub distance: f32,
    /// The carried value there.
    pub value: f32,
}

/// Calls `visit` for every pixel the stroke covers, row by row, once per copy of the stroke
/// (a wrapped stroke near an edge is drawn at each periodic offset that reaches the raster).
pub fn for_each_hit(frame: &Frame, stroke: &Stroke, mut visit: impl FnMut(StrokeHit)) {
    for_each_copy::<false>(frame, stroke, |a, b, bounds| draw_capsule(frame.clip, a, b, bounds, stroke, &mut visit));
}

/// [`for_each_run`] hands over a multiple of this many pixels at a time.
const LANES: usize = 4;

/// Calls `lane(cell, hit)` for the pixels [`for_each_hit`] visits, in the same order, each
/// with its cell of `cells` (which holds the clip's pixels, row by row); and for some
/// neighbours of theirs on the same row, whose `hit.coverage` is not > 0 (0, −0 or NaN):
/// `lane` must leave those cells as they are. A hit's `pixel` is 0 (the cell is the pixel).
/// Each row's pixels that the stroke can cover are handed over together, in a loop without a
/// branch per pixel, which LLVM vectorises where `lane` has none either.
///
/// Without `fringe`, the pixels whose centre lies farther than the half width from the axis
/// (the anti-aliased fringe, coverage < ½, up to ½ pixel wide) may be left out: every pixel
/// with coverage ≥ ½ is still visited, and the rest in the same order.
pub(crate) fn for_each_run<C>(
    frame: &Frame,
    stroke: &Stroke,
    cells: &mut [C],
    fringe: bool,
    lane: impl Fn(&mut C, StrokeHit),
) {
    for_each_copy::<true>(frame, stroke, |a, b, bounds| {
        draw_runs(frame.clip, a, b, bounds, (stroke, fringe), cells, &lane)
    });
}

/// Calls `draw(a, b, bounds)` for each copy of the stroke that reaches the clip: its ends in
/// pixels and the pixels within the widest half width + 1 of them (first and last column,
/// first and last row). With `BOTH` on 64-bit targets, the two axes at once where only the
/// stroke itself can reach the clip (the same copies).
#[inline(always)]
fn for_each_copy<const BOTH: bool>(
    frame: &Frame,
    stroke: &Stroke,
    mut draw: impl FnMut([f32; 2], [f32; 2], [[f32; 2]; 2]),
) {
    let reach = stroke.half_width[0].max(stroke.half_width[1]) + 1.0;
    let clip = frame.clip;
    // The clip's first and last column and row.
    let (left, right) = (clip.x, clip.x + i64::from(clip.width) - 1);
    let (top, bottom) = (clip.y, clip.y + i64::from(clip.height) - 1);
    let Some(period) = frame.period else {
        // Not wrapped: the stroke itself, on the pixels of the clip within the raster.
        let (left, right) = (left.max(0) as f32, right.min(i64::from(frame.width) - 1) as f32);
        let (top, bottom) = (top.max(0) as f32, bottom.min(i64::from(frame.height) - 1) as f32);
        let x = Extent::of(stroke, 0, 0.0, frame.scale[0], reach, [left, right]);
        let y = Extent::of(stroke, 1, 0.0, frame.scale[1], reach, [top, bottom]);
        if x.reached && y.reached {
            draw([x.ends[0], y.ends[0]], [x.ends[1], y.ends[1]], [x.pixels, y.pixels]);
        }
        return;
    };
    // Both axes at once where only the stroke itself can reach the clip (most strokes): what
    // the copies below find then.
    if BOTH && cfg!(target_pointer_width = "64") {
        let pixels = [[left as f32, right as f32], [top as f32, bottom as f32]];
        if let Some(middle) = Extent::middle_only(stroke, period, frame.scale, reach, pixels) {
            if let Some((a, b, bounds)) = middle {
                draw(a, b, bounds);
            }
            return;
        }
    }
    // Each axis on its own: the copies' ends in pixels at the periodic offsets −1, 0 and +1
    // periods, and the pixels they reach.
    let axis = |k: usize, first: i64, last: i64| {
        Extent::copies(stroke, k, period[k], frame.scale[k], reach, [first as f32, last as f32])
    };
    let xs = axis(0, left, right);
    let ys = axis(1, top, bottom);
    for y in ys.iter().filter(|e| e.reached) {
        for x in xs.iter().filter(|e| e.reached) {
            let (a, b) = ([x.ends[0], y.ends[0]], [x.ends[1], y.ends[1]]);
            draw(a, b, [x.pixels, y.pixels]);
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

impl Extent {
    /// Axis `k` of the copy of `stroke` shifted by `offset` (domain units), at `scale` pixels
    /// a unit, on the clip's pixels `first` to `last` of that axis.
    #[inline(always)]
    fn of(stroke: &Stroke, k: usize, offset: f32, scale: f32, reach: f32, [first, last]: [f32; 2]) -> Extent {
        let a = (stroke.start[k] + offset) * scale;
        let b = (stroke.end[k] + offset) * scale;
        let lo = floor(a.min(b) - reach).max(first);
        let hi = floor(a.max(b) + reach).min(last);
        Extent { ends: [a, b], pixels: [lo, hi], reached: lo <= hi }
    }

    /// [`Extent::copies`] of both axes (`period`, `scale`, `pixels` each x then y) where on
    /// neither a copy before or after the stroke can reach the clip: `Some` with the stroke's
    /// ends and the pixels it reaches if it does on both axes, `None` if not; or `None` where
    /// a copy before or after may reach the clip, or a pixel coordinate is 2²³ or more in
    /// magnitude (or not finite).
    #[inline(always)]
    #[allow(clippy::type_complexity)]
    fn middle_only(
        stroke: &Stroke,
        period: [f32; 2],
        scale: [f32; 2],
        reach: f32,
        pixels: [[f32; 2]; 2],
    ) -> Option<Option<([f32; 2], [f32; 2], [[f32; 2]; 2])>> {
        // As [`Extent::copies`] works out the middle copy (`Extent::of` at 0 periods).
        let at = |p: [f32; 2]| -> [f32; 2] { core::array::from_fn(|k| (p[k] + 0.0 * period[k]) * scale[k]) };
        let (a, b) = (at(stroke.start), at(stroke.end));
        for k in 0..2 {
            let [before, after] = Extent::copies_miss(a[k], b[k], period[k] * scale[k], reach, pixels[k]);
            if !(before && after) {
                return None;
            }
        }
        let ends = [a[0].min(b[0]) - reach, a[1].min(b[1]) - reach, a[0].max(b[0]) + reach, a[1].max(b[1]) + reach];
        let [x0, y0, x1, y1] = floor4(ends)?;
        let (x, y) = ([x0.max(pixels[0][0]), x1.min(pixels[0][1])], [y0.max(pixels[1][0]), y1.min(pixels[1][1])]);
        Some((x[0] <= x[1] && y[0] <= y[1]).then_some((a, b, [x, y])))
    }

    /// [`Extent::of`] the copies a `period` before, at and after the stroke. The copies before
    /// and after are the middle one shifted by a period, up to their rounding: one that
    /// [`Extent::copies_miss`] finds surely ends short of the clip's first pixel, or starts
    /// past its last, is not worked out.
    #[inline(always)]
    fn copies(stroke: &Stroke, k: usize, period: f32, scale: f32, reach: f32, pixels: [f32; 2]) -> [Extent; 3] {
        const MISSED: Extent = Extent { ends: [0.0; 2], pixels: [0.0; 2], reached: false };
        let extent = |i: usize| Extent::of(stroke, k, (i as f32 - 1.0) * period, scale, reach, pixels);
        let middle = extent(1);
        let [a, b] = middle.ends;
        let [before, after] = Extent::copies_miss(a, b, period * scale, reach, pixels);
        [if before { MISSED } else { extent(0) }, middle, if after { MISSED } else { extent(2) }]
    }

    /// Whether the copies `shift` pixels before and after one whose ends on an axis are `a`
    /// and `b` surely end short of the first of `pixels` and start past the last, by a slack
    /// that covers their rounding many times over (anything not finite makes the slack NaN:
    /// then neither is sure).
    #[inline(always)]
    fn copies_miss(a: f32, b: f32, shift: f32, reach: f32, pixels: [f32; 2]) -> [bool; 2] {
        let slack = (a.abs() + b.abs() + shift.abs()) * (1.0 / 1_048_576.0) + 1.0;
        [a.max(b) - shift + reach + slack < pixels[0], a.min(b) + shift - reach - slack > pixels[1]]
    }
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
    let per_dd = 1.0 / dd;
    let columns = clip.width as usize;
    // (Not on 32-bit targets, for the Cortex-M3's flash: the whole bounding box visits the
    // same hits.)
    let span = if cfg!(target_pointer_width = "64") {
        Span::new(a, d, dd, stroke.half_width[0].max(stroke.half_width[1]), FRINGE)
    } else {
        None
    };
    // One pixel: column `x`, whose centre is at `cx` (x + ½), on a row whose centre lies `py`
    // below a, `row` its first pixel's index.
    macro_rules! pixel {
        ($x:expr, $cx:expr, $py:expr, $row:expr) => {{
            let near = near([$cx - a[0], $py], d, dd, per_dd, stroke);
            if near.coverage > 0.0 {
                visit(near.hit($row + ($x - clip.x) as usize, stroke));
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

/// Where a pixel lies from a stroke's axis: the nearest point of the axis, at `t` along it,
/// its `distance` from there, the `half_width` there and the pixel's `coverage`.
struct Near {
    t: f32,
    distance: f32,
    half_width: f32,
    coverage: f32,
}

/// Where the pixel whose centre lies at `p` from `a` lies from a stroke from `a` to `a + d`
/// (`dd` = |d|², `per_dd` = 1 / dd, divided once per stroke).
#[inline(always)]
fn near(p: [f32; 2], d: [f32; 2], dd: f32, per_dd: f32, stroke: &Stroke) -> Near {
    let t = if dd > 0.0 { ((p[0] * d[0] + p[1] * d[1]) * per_dd).clamp(0.0, 1.0) } else { 0.0 };
    let q = [p[0] - d[0] * t, p[1] - d[1] * t];
    let distance = crate::scalar::sqrtf(q[0] * q[0] + q[1] * q[1]);
    let half_width = stroke.half_width[0] + (stroke.half_width[1] - stroke.half_width[0]) * t;
    Near { t, distance, half_width, coverage: (half_width - distance + 0.5).min(1.0) }
}

impl Near {
    /// What the stroke leaves on the pixel `pixel`: the coverage, and the depth and value
    /// there (worked out only here, so that a pixel the stroke misses costs no division: a
    /// call on parts without an FPU).
    #[inline(always)]
    fn hit(&self, pixel: usize, stroke: &Stroke) -> StrokeHit {
        StrokeHit {
            pixel,
            coverage: self.coverage,
            depth: if self.half_width > 0.0 { self.distance / self.half_width } else { 1.0 },
            half_width: self.half_width,
            distance: self.distance,
            value: stroke.value[0] + (stroke.value[1] - stroke.value[0]) * self.t,
        }
    }
}

/// [`draw_capsule`] for [`for_each_run`]: each row's pixels within [`Span::columns`] (all of
/// the row's within `bounds` when there is no span), each row in one loop; the span
/// reaches the anti-aliased fringe only with `fringe`.
fn draw_runs<C>(
    clip: Clip,
    a: [f32; 2],
    b: [f32; 2],
    bounds: [[f32; 2]; 2],
    (stroke, fringe): (&Stroke, bool),
    cells: &mut [C],
    lane: &impl Fn(&mut C, StrokeHit),
) {
    let [[x0, x1], [y0, y1]] = bounds;
    let d = [b[0] - a[0], b[1] - a[1]];
    let dd = d[0] * d[0] + d[1] * d[1];
    let columns = clip.width as usize;
    let widest = stroke.half_width[0].max(stroke.half_width[1]);
    let span = Span::new(a, d, dd, widest, if fringe { FRINGE } else { 0.0 });
    let span = match span {
        Some(span) if dd > 0.0 => return span_rows(clip, a, d, dd, [[x0, x1], [y0, y1]], &span, stroke, cells, lane),
        span => span,
    };
    let per_dd = 1.0 / dd;
    // Pixel by pixel: a stroke without a span or without a length.
    let [top, bottom] = span.as_ref().map_or([y0 as i64, y1 as i64], |span| span.rows([y0, y1]));
    for y in top..=bottom {
        let row = (y - clip.y) as usize * columns;
        let py = y as f32 + 0.5 - a[1];
        let (first, last) = match &span {
            Some(span) => {
                let [from, to] = span.columns(y as f32 + 0.5);
                ((x0 as i64).max(from), (x1 as i64).min(to))
            }
            None => (x0 as i64, x1 as i64),
        };
        if first > last {
            continue;
        }
        let pixels = (last - first + 1) as usize;
        let start = row + (first - clip.x) as usize;
        for (k, cell) in cells.iter_mut().skip(start).take(pixels).enumerate() {
            let cx = (first + k as i64) as f32 + 0.5;
            lane(cell, near([cx - a[0], py], d, dd, per_dd, stroke).hit(0, stroke));
        }
    }
}

/// [`draw_runs`] of a stroke with a [`Span`] and a length (`dd` > 0), from `a` along `d`: the
/// rows in blocks of [`LANES`], each block's columns worked out together, and each row's
/// pixels by [`span_lanes`] (pixel by pixel where the cells end before its last lanes).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn span_rows<C>(
    clip: Clip,
    a: [f32; 2],
    d: [f32; 2],
    dd: f32,
    [[x0, x1], [y0, y1]]: [[f32; 2]; 2],
    span: &Span,
    stroke: &Stroke,
    cells: &mut [C],
    lane: &impl Fn(&mut C, StrokeHit),
) {
    let columns = clip.width as usize;
    let per_dd = 1.0 / dd;
    let [top, bottom] = span.row_ends([y0, y1]);
    let (mut y, bottom) = (top as i64, bottom as i64);
    // Row centres, exact (a span's rows lie well within 2²³), and so is counting them up.
    let mut cy: [f32; LANES] = core::array::from_fn(|j| top + (j as f32 + 0.5));
    let mut row = (y - clip.y) as usize * columns;
    while y <= bottom {
        // Each row's columns, pixels and coordinates.
        let [from, to] = span.block_columns(cy, [x0, x1]);
        let count: [i32; LANES] = core::array::from_fn(|j| to[j] - from[j] + 1);
        let (cx, py) = (from.map(|x| x as f32 + 0.5), cy.map(|c| c - a[1]));
        let pd1 = py.map(|p| p * d[1]);
        for j in 0..LANES.min((bottom - y + 1) as usize) {
            let (first, pixels) = (i64::from(from[j]), count[j]);
            if pixels > 0 {
                let start = row + (first - clip.x) as usize;
                // (At most a clip's width: this does not overflow.)
                let lanes = (pixels as usize + (LANES - 1)) & !(LANES - 1);
                if let Some(cells) = cells.get_mut(start..start + lanes) {
                    // Within a span's bounds x + ½ is exact, and so is counting it up by 1.
                    span_lanes([cx[j], a[0], py[j], pd1[j]], d, per_dd, stroke, pixels, cells, lane);
                } else {
                    for (k, cell) in cells.iter_mut().skip(start).take(pixels as usize).enumerate() {
                        let cx = (first + k as i64) as f32 + 0.5;
                        lane(cell, near([cx - a[0], py[j]], d, dd, per_dd, stroke).hit(0, stroke));
                    }
                }
            }
            row += columns;
        }
        y += LANES as i64;
        cy = cy.map(|c| c + LANES as f32);
    }
}

/// [`near`] and [`Near::hit`] of `pixels` pixels from column `cx` (x + ½) on the row `py` below the start of
/// a stroke with a [`Span`] and a length (`per_dd` = 1 / |d|², `d` ≠ 0), which lies at column `ax` (`at` = [cx,
/// ax, py, py · d₁]), each handed to `lane` with its cell, and of the pixels after them (`cells` holds
/// a multiple of [`LANES`], at least `pixels`) with coverage 0. Within a span every coordinate
/// is finite, and so is the position `t` along the axis, so that comparisons give what `clamp`
/// and `min` do. Loops over the pixels without a branch, which LLVM
/// vectorises (the square roots too, four in one instruction on x86-64: [`crate::scalar::sqrtf`]).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn span_lanes<C>(
    [cx, ax, py, pd1]: [f32; 4],
    d: [f32; 2],
    per_dd: f32,
    stroke: &Stroke,
    pixels: i32,
    cells: &mut [C],
    lane: &impl Fn(&mut C, StrokeHit),
) {
    let lanes = cells.len() & !(LANES - 1);
    let [w0, w1] = stroke.half_width;
    let [v0, v1] = stroke.value;
    for (cell, i) in cells[..lanes].iter_mut().zip(0i32..) {
        let p0 = (cx + i as f32) - ax;
        let s = (p0 * d[0] + pd1) * per_dd;
        let s = if s > 0.0 { s } else { 0.0 };
        let t = if s < 1.0 { s } else { 1.0 };
        let (q0, q1) = (p0 - d[0] * t, py - d[1] * t);
        let distance = crate::scalar::sqrtf(q0 * q0 + q1 * q1);
        let w = w0 + (w1 - w0) * t;
        let c = w - distance + 0.5;
        let coverage = if c < 1.0 { c } else { 1.0 };
        lane(
            cell,
            StrokeHit {
                pixel: 0,
                coverage: if i < pixels { coverage } else { 0.0 },
                depth: if w > 0.0 { distance / w } else { 1.0 },
                half_width: w,
                distance,
                value: v0 + (v1 - v0) * t,
            },
        );
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

/// How far past its half width a stroke's anti-aliasing reaches, in pixels.
const FRINGE: f32 = 0.5;

/// The capsule whose pixels a stroke can cover (from `a` to `a + d`, in pixels), row by row:
/// a row's centre line meets it in one interval (it is convex), bounded by where the line
/// meets the two end discs and the two long edges. A pixel covers nothing unless its centre
/// lies within its half width and ½ ([`FRINGE`]) of the axis (its coverage is the half width
/// less the distance, plus ½): the capsule's radius is the widest half width, ½ and
/// [`SPAN_SLACK`], so that every pixel with coverage lies in its row's span (without the
/// fringe, the widest half width and [`SPAN_SLACK`]: every pixel with coverage ≥ ½).
struct Span {
    a: [f32; 2],
    d: [f32; 2],
    /// The radius.
    radius: f32,
    /// The radius, squared.
    rr: f32,
    /// The long edges' offset from the axis: the radius along the unit normal (NaN when the
    /// ends meet: the discs alone are the capsule).
    edge: [f32; 2],
    /// 1 / `d[1]`.
    per_row: f32,
}

impl Span {
    /// The capsule of a stroke whose widest half width is `widest`, reaching `fringe` pixels
    /// past it, or `None` when its rows are drawn whole (a stroke or width past
    /// [`SPAN_LIMIT`], a start past [`SPAN_REACH`], no width, anything not finite).
    fn new(a: [f32; 2], d: [f32; 2], dd: f32, widest: f32, fringe: f32) -> Option<Span> {
        let radius = widest + fringe + SPAN_SLACK;
        let small = |v: f32, limit: f32| v.abs() < limit;
        let fits = small(d[0], SPAN_LIMIT)
            && small(d[1], SPAN_LIMIT)
            && (0.0..SPAN_LIMIT).contains(&widest)
            && small(a[0], SPAN_REACH)
            && small(a[1], SPAN_REACH);
        if !fits {
            return None;
        }
        let length = crate::scalar::sqrtf(dd);
        let edge = [-d[1] / length * radius, d[0] / length * radius];
        Some(Span { a, d, radius, rr: radius * radius, edge, per_row: 1.0 / d[1] })
    }

    /// The first and last row of `y0` to `y1` whose pixel centres may lie in the capsule: the
    /// rows whose centre lies within the radius of the axis's top and bottom (first > last when
    /// none does).
    #[inline(always)]
    fn rows(&self, bounds: [f32; 2]) -> [i64; 2] {
        self.row_ends(bounds).map(|y| y as i64)
    }

    /// [`Span::rows`], as whole numbers in `f32`.
    #[inline(always)]
    fn row_ends(&self, [y0, y1]: [f32; 2]) -> [f32; 2] {
        let (top, bottom) = (lower(0.0, self.d[1]), higher(0.0, self.d[1]));
        let ends = [self.a[1] + top - self.radius - 0.5, self.a[1] + bottom + self.radius - 0.5];
        // (Both at once on 64-bit targets.)
        let both = if cfg!(target_pointer_width = "64") { floor4([ends[0], ends[1], 0.0, 0.0]) } else { None };
        let [first, last] = both.map_or_else(|| ends.map(floor), |[first, last, _, _]| [first, last]);
        [first.max(y0), last.min(y1)]
    }

    /// [`Span::columns`] of the rows whose centres are at `cy`, at once (without a branch, which
    /// LLVM vectorises), limited to the columns `x0` to `x1` (each a whole number of at most
    /// 2²³ in magnitude): each row's first and last column (first > last when none is).
    #[inline(always)]
    fn block_columns(&self, cy: [f32; LANES], [x0, x1]: [f32; 2]) -> [[i32; LANES]; 2] {
        let (mut first, mut last) = ([0.0f32; LANES], [0.0f32; LANES]);
        for ((&cy, first), last) in cy.iter().zip(&mut first).zip(&mut last) {
            let v = cy - self.a[1];
            let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
            // A disc the row misses moves neither end (x ∓ −∞ = ±∞).
            for (x, y) in [(0.0, v), (self.d[0], v - self.d[1])] {
                let w2 = self.rr - y * y;
                let w = if w2 > 0.0 { crate::scalar::sqrtf(w2) } else { f32::NEG_INFINITY };
                (lo, hi) = (lower(lo, x - w), higher(hi, x + w));
            }
            // Nor does an edge the row misses (NaN compares false).
            for side in [1.0f32, -1.0] {
                let t = (v - side * self.edge[1]) * self.per_row;
                let x = side * self.edge[0] + t * self.d[0];
                let x = if (0.0..=1.0).contains(&t) { x } else { f32::NAN };
                (lo, hi) = (lower(lo, x), higher(hi, x));
            }
            // As `columns` has them, each end limited to the columns first (truncation and the
            // limits each move an end the same way, in either order).
            let from = self.a[0] + lo - 0.5;
            let to = self.a[0] + hi - 0.5;
            *first = lower(higher(from, x0), x1 + 1.0);
            *last = higher(lower(to, x1), x0 - 1.0);
        }
        [truncate(first), truncate(last)]
    }

    /// The first and last column whose pixel centre may lie in the capsule on the row whose
    /// centre is at `cy` (first > last when none does).
    #[inline(always)]
    fn columns(&self, cy: f32) -> [i64; 2] {
        let v = cy - self.a[1];
        let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
        // The end discs, centred at 0 and d (x relative to a).
        for (x, y) in [(0.0, v), (self.d[0], v - self.d[1])] {
            let w2 = self.rr - y * y;
            if w2 > 0.0 {
                let w = crate::scalar::sqrtf(w2);
                (lo, hi) = (lower(lo, x - w), higher(hi, x + w));
            }
        }
        // The long edges, from a ± edge to a + d ± edge.
        for side in [1.0f32, -1.0] {
            let t = (v - side * self.edge[1]) * self.per_row;
            if (0.0..=1.0).contains(&t) {
                let x = side * self.edge[0] + t * self.d[0];
                (lo, hi) = (lower(lo, x), higher(hi, x));
            }
        }
        // Pixel x's centre is x + ½; truncation moves neither end inwards past a centre.
        [(self.a[0] + lo - 0.5) as i64, (self.a[0] + hi - 0.5) as i64]
    }
}

/// The lower of `a` and `b`, for numbers (what `min` gives when neither is NaN, in fewer
/// instructions on 64-bit targets: the span's ends are finite where they are compared; on
/// 32-bit ones, soft-float on some, `min`).
#[inline(always)]
fn lower(a: f32, b: f32) -> f32 {
    if !cfg!(target_pointer_width = "64") {
        a.min(b)
    } else if b < a {
        b
    } else {
        a
    }
}

/// The higher of `a` and `b`, for numbers (see [`lower`]).
#[inline(always)]
fn higher(a: f32, b: f32) -> f32 {
    if !cfg!(target_pointer_width = "64") {
        a.max(b)
    } else if b > a {
        b
    } else {
        a
    }
}

/// Each of `x` truncated towards zero, for whole-number parts below 2³¹ in magnitude (what
/// `as i32` gives them): SSE2's `cvttps2dq` on x86-64, four in one instruction.
#[inline(always)]
fn truncate(x: [f32; LANES]) -> [i32; LANES] {
    #[cfg(target_arch = "x86_64")]
    {
        safe_arch::truncate_m128_to_m128i(safe_arch::m128::from_array(x)).into()
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        x.map(|x| x as i32)
    }
}

/// [`floor`] of each of `x`, four at once, or `None` if one is 2²³ or more in magnitude (or not
/// a number).
#[inline(always)]
fn floor4(x: [f32; LANES]) -> Option<[f32; LANES]> {
    if !x.iter().fold(true, |small, x| small & (x.abs() < 8_388_608.0)) {
        return None;
    }
    let t = truncate(x);
    Some(core::array::from_fn(|k| {
        let t = t[k] as f32;
        if t > x[k] { t - 1.0 } else { t }
    }))
}

/// `libm::floorf(x)` but for the sign of a zero (−0 may come out +0; each caller turns the
/// result into an integer or compares it, where the two are the same): on 64-bit targets by
/// truncation below 2²³ in magnitude, where every `f32` converts to an `i32` exactly (32-bit
/// ones, soft-float on some, keep libm's).
#[inline(always)]
fn floor(x: f32) -> f32 {
    if cfg!(target_pointer_width = "64") && x.abs() < 8_388_608.0 {
        let t = x as i32 as f32;
        if t > x { t - 1.0 } else { t }
    } else {
        libm::floorf(x)
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
                    let t = if dd > 0.0 { ((p[0] * d[0] + p[1] * d[1]) * (1.0 / dd)).clamp(0.0, 1.0) } else { 0.0 };
                    let q = [p[0] - d[0] * t, p[1] - d[1] * t];
                    let distance = crate::scalar::sqrtf(q[0] * q[0] + q[1] * q[1]);
                    let half_width = stroke.half_width[0] + (stroke.half_width[1] - stroke.half_width[0]) * t;
                    let coverage = (half_width - distance + 0.5).min(1.0);
                    if coverage > 0.0 {
                        visit(StrokeHit {
                            pixel: (y - clip.y) as usize * clip.width as usize + (x - clip.x) as usize,
                            coverage,
                            depth: if half_width > 0.0 { distance / half_width } else { 1.0 },
                            half_width,
                            distance,
                            value: stroke.value[0] + (stroke.value[1] - stroke.value[0]) * t,
                        });
                    }
                }
            }
        }
    }

    /// [`for_each_hit`] and [`for_each_run`] give the hits of testing every pixel of the
    /// bounding boxes, bit for bit, in the same order; [`for_each_run`] without the fringe
    /// those of coverage ≥ ½ among them, and leaves out some of the rest.
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
        let (mut strokes, mut hits, mut fringe_left) = (0, 0, 0);
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
            // The runs' hits, each pixel's cell holding its index.
            let mut cells: Vec<usize> = (0..clip.width as usize * clip.height as usize).collect();
            let runs = core::cell::RefCell::new(Vec::new());
            for_each_run(&frame, &stroke, &mut cells, true, |&mut pixel, hit| {
                if hit.coverage > 0.0 {
                    runs.borrow_mut().push(StrokeHit { pixel, ..hit });
                }
            });
            let runs = runs.into_inner();
            // Without the fringe: every hit of coverage ≥ ½ among them, in the same order.
            let (mut cells, inner) = ((0..cells.len()).collect::<Vec<usize>>(), core::cell::RefCell::new(Vec::new()));
            for_each_run(&frame, &stroke, &mut cells, false, |&mut pixel, hit| {
                if hit.coverage > 0.0 {
                    inner.borrow_mut().push(StrokeHit { pixel, ..hit });
                }
            });
            let inner = inner.into_inner();
            let wanted: Vec<&StrokeHit> = whole.iter().filter(|h| h.coverage >= 0.5).collect();
            let mut from = inner.iter().filter(|h| h.coverage >= 0.5);
            for w in &wanted {
                let r = from.next().expect("a hit of coverage >= 1/2 left out");
                assert_eq!(
                    (r.pixel, [r.coverage, r.depth, r.half_width, r.distance, r.value].map(f32::to_bits)),
                    (w.pixel, [w.coverage, w.depth, w.half_width, w.distance, w.value].map(f32::to_bits)),
                    "case {case}: {frame:?} {stroke:?}"
                );
            }
            assert!(inner.len() <= runs.len(), "case {case}: the fringe left out added hits");
            fringe_left += runs.len() - inner.len();
            assert_eq!(fast.len(), whole.len(), "case {case}: {frame:?} {stroke:?}");
            assert_eq!(runs.len(), whole.len(), "case {case}: {frame:?} {stroke:?}");
            for ((f, r), w) in fast.iter().zip(&runs).zip(&whole) {
                let bits = |h: &StrokeHit| {
                    (h.pixel, [h.coverage, h.depth, h.half_width, h.distance, h.value].map(f32::to_bits))
                };
                assert_eq!(bits(f), bits(w), "case {case}: {frame:?} {stroke:?}");
                assert_eq!(bits(r), bits(w), "case {case}: {frame:?} {stroke:?}");
            }
            strokes += usize::from(!whole.is_empty());
            hits += whole.len();
        }
        assert!(strokes > 2000 && hits > 100_000, "the cases draw: {strokes} strokes, {hits} hits");
        assert!(fringe_left > hits / 20, "without the fringe, {fringe_left} of {hits} hits left out");
    }

    /// The copies [`Extent::copies`] leaves out are the ones that reach no pixel, at any
    /// scale and position (near the clip's edges, far from the origin, not finite), and the
    /// ones it works out are [`Extent::of`]'s, bit for bit.
    #[test]
    fn copies_left_out_reach_no_pixel() {
        let mut rng = crate::rng::Rng::from_key(0x2545_f491_4f6c_dd1d, 0);
        let mut next = move || rng.uniform_f32();
        let mut left_out = 0;
        for case in 0..200_000 {
            let magnitude = [1.0f32, 64.0, 4096.0, 262_144.0, 1.0e7][case % 5];
            let period = magnitude * (0.1 + next());
            let scale = [0.01f32, 0.5, 1.0, 3.7, 100.0][(case / 5) % 5];
            let first = ((next() - 0.5) * 8.0 + if case % 3 == 0 { 0.0 } else { -4.0 }) as i64 as f32;
            let last = first + libm::floorf(period * scale) + ((next() - 0.5) * 8.0) as i64 as f32;
            let at = |u: f32| match case % 11 {
                0 => f32::NAN,
                1 => f32::INFINITY,
                _ => (u * 1.6 - 0.3) * period,
            };
            let (start, end) = (at(next()), at(next()) + (next() - 0.5) * 4.0);
            let stroke = Stroke { start: [start, 0.0], end: [end, 0.0], half_width: [0.5; 2], value: [0.0; 2] };
            let reach = [1.5f32, 6.0, 300.0][case % 3];
            let copies = Extent::copies(&stroke, 0, period, scale, reach, [first, last]);
            for (i, copy) in copies.iter().enumerate() {
                let every = Extent::of(&stroke, 0, (i as f32 - 1.0) * period, scale, reach, [first, last]);
                if copy.reached {
                    let bits = |e: &Extent| (e.ends.map(f32::to_bits), e.pixels.map(f32::to_bits));
                    assert_eq!(bits(copy), bits(&every), "case {case}");
                } else {
                    assert!(!every.reached, "case {case}: copy {i} left out, but it reaches {:?}", every.pixels);
                    left_out += usize::from(i != 1);
                }
            }
        }
        assert!(left_out > 100_000, "copies are left out: {left_out}");
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
