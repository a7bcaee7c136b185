//! Pieces a physics engine takes, cut from polygons given as [`Ring`]s over a point buffer
//! (glass fragments, mud cells): triangles, and convex pieces of at most
//! [`MAX_PIECE_POINTS`] points. Every outer ring with the holes whose `hole_of` names it is
//! one polygon; its pieces' areas add up to the outer ring's area minus its holes', or the
//! polygon is refused by name ([`RingError::Crosses`]: a ring of it crosses itself or another,
//! so that no set of pieces covers it).
//!
//! Counts first, then caller buffers: [`pieces_scratch`] checks the rings and gives the
//! scratch words, [`piece_counts`] how many triangles and convex pieces the rings make, and
//! [`triangulate`] and [`convex_pieces`] write them. Nothing is allocated.
//!
//! Work: for a polygon of `m` nodes (its outer ring's points, and each hole's points plus
//! 2 for its bridge) at most `3·m²` point tests (ear clipping) and `m` edge tests per hole
//! (its bridge), plus `O(h log h)` to order its `h` holes; the check of the rings and points
//! is linear in the rings and the points they name. [`triangulate`] and [`convex_pieces`]
//! triangulate twice: once to count and check the areas (nothing is written if a polygon is
//! refused), once to write.

use super::convex::{MAX_PIECE_POINTS, Merger};
use super::triangulation::{self, WORDS_PER_NODE};
use super::{NOT_A_HOLE, Ring};

/// One triangle: three point indices, counter-clockwise with y up (positive area), and the
/// outer ring of the polygon it belongs to. In C: `hibi_triangle`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[repr(C)]
pub struct Triangle {
    /// Index of the polygon's outer ring (the glass fragment, the mud cell).
    pub ring: u32,
    /// Indices into the point buffer, counter-clockwise with y up.
    pub points: [u32; 3],
}

/// One convex piece: 3 to 8 point indices, counter-clockwise with y up and strictly convex
/// (no three consecutive points on a line), and the outer ring of the polygon it belongs
/// to. In C: `hibi_convex_piece`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[repr(C)]
pub struct ConvexPiece {
    /// Index of the polygon's outer ring (the glass fragment, the mud cell).
    pub ring: u32,
    /// How many of `points` are used (3 to 8); the rest are 0.
    pub point_count: u32,
    /// Indices into the point buffer, counter-clockwise with y up ([`MAX_PIECE_POINTS`],
    /// `HIBI_PIECE_MAX_POINTS` in C).
    pub points: [u32; 8],
}

const _: () = assert!(MAX_PIECE_POINTS == 8);

/// How many pieces [`triangulate`] and [`convex_pieces`] write for a set of rings.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PieceCounts {
    /// Triangles.
    pub triangles: usize,
    /// Convex pieces (never more than the triangles).
    pub pieces: usize,
}

crate::error::error_list! {
    /// What is wrong with a ring given to the piece functions.
    pub enum RingError {
        /// `first_point + point_count` runs past the point buffer.
        Points => c"polygon: a ring's first_point + point_count runs past the points",
        /// `hole_of` names a ring of the buffer that is not an outer ring (a hole, or the
        /// ring itself).
        HoleOf => c"polygon: a ring's hole_of names a ring that is not an outer ring",
        /// A point of the ring is NaN or infinite.
        NotFinite => c"polygon: a ring's point is not finite",
        /// One polygon (an outer ring, its holes and their bridges) holds 2³⁰ or more
        /// points, or there are 2³² or more rings.
        Size => c"polygon: a polygon holds 2^30 or more points with its holes, or there are 2^32 or more rings",
        /// The polygon's triangles do not add up to its area (its outer ring's signed area
        /// and its holes', from their points): the ring, or a hole of it, crosses itself or
        /// another ring of the polygon, and has no interior for pieces to cover.
        Crosses => c"polygon: a ring crosses itself or another ring of its polygon (its triangles do not add up to its area)",
    }
}

/// Why a piece function refused: nothing was written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PiecesError {
    /// Ring `ring` is wrong as `error` says.
    Ring {
        /// Index of the ring.
        ring: usize,
        /// What is wrong.
        error: RingError,
    },
    /// The scratch holds fewer words than [`pieces_scratch`] gives.
    ScratchTooSmall {
        /// Words needed.
        needed: usize,
    },
    /// The output buffer holds fewer entries than the rings make ([`piece_counts`]).
    BufferTooSmall {
        /// Entries needed.
        needed: usize,
    },
}

impl core::fmt::Display for PiecesError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            PiecesError::Ring { ring, error } => write!(f, "{error} (ring {ring})"),
            PiecesError::ScratchTooSmall { needed } => {
                write!(f, "polygon: the scratch is too small ({needed} words needed)")
            }
            PiecesError::BufferTooSmall { needed } => {
                write!(f, "polygon: the output buffer is too small ({needed} entries needed)")
            }
        }
    }
}

impl core::error::Error for PiecesError {
    fn source(&self) -> Option<&(dyn core::error::Error + 'static)> {
        match self {
            PiecesError::Ring { error, .. } => Some(error),
            _ => None,
        }
    }
}

/// The largest polygon, in nodes, and the ring count (kept below u32 indices' reach).
const MAX_NODES: u64 = 1 << 30;

/// What the rings need, from one check of them.
struct Plan {
    /// Scratch words.
    scratch: usize,
}

/// Whether ring `r` is a hole with pieces: of a given outer ring of at least 3 points, with
/// at least 3 points itself.
fn hole_with_pieces(rings: &[Ring], r: &Ring) -> Option<usize> {
    let outer = rings.get(r.hole_of as usize).filter(|_| r.hole_of != NOT_A_HOLE)?;
    (outer.point_count >= 3 && r.point_count >= 3).then_some(r.hole_of as usize)
}

/// Checks the rings, then the points (linear in the rings and the points they name).
fn plan(rings: &[Ring], points: &[[f32; 2]]) -> Result<Plan, PiecesError> {
    let fail = |ring, error| PiecesError::Ring { ring, error };
    if rings.len() as u64 >= 1 << 32 {
        return Err(fail(rings.len() - 1, RingError::Size));
    }
    let (mut largest_outer, mut hole_nodes) = (0u64, 0u64);
    for (i, r) in rings.iter().enumerate() {
        let end = r.first_point as usize as u64 + u64::from(r.point_count);
        if end > points.len() as u64 {
            return Err(fail(i, RingError::Points));
        }
        let names_a_ring = r.hole_of != NOT_A_HOLE && (r.hole_of as usize) < rings.len();
        if names_a_ring && (r.hole_of as usize == i || rings[r.hole_of as usize].hole_of != NOT_A_HOLE) {
            return Err(fail(i, RingError::HoleOf));
        }
        let n = u64::from(r.point_count);
        if r.hole_of == NOT_A_HOLE && n >= 3 {
            largest_outer = largest_outer.max(n);
        } else if hole_with_pieces(rings, r).is_some() {
            hole_nodes += n + 2;
        }
        if largest_outer + hole_nodes >= MAX_NODES {
            return Err(fail(i, RingError::Size));
        }
    }
    // The points, once the sizes are known to be in reach (rings may share points).
    for (i, r) in rings.iter().enumerate() {
        let pts = &points[r.first_point as usize..][..r.point_count as usize];
        if pts.iter().any(|p| !(p[0].is_finite() && p[1].is_finite())) {
            return Err(fail(i, RingError::NotFinite));
        }
    }
    let nodes = (largest_outer + hole_nodes) as usize;
    Ok(Plan { scratch: 3 * rings.len() + 1 + WORDS_PER_NODE * nodes })
}

/// Checks `rings` over `points` and gives the scratch words (`u32`) the other piece
/// functions need: `3·rings + 1` plus 4 per point of the largest outer ring and per point of
/// every hole (and 2 more per hole).
///
/// A ring is an outer ring when its `hole_of` is [`NOT_A_HOLE`]; a hole of ring `k` when
/// `hole_of` is `k` (an outer ring of the buffer); a hole whose `hole_of` is past the buffer
/// (such as a mud hole in a cell that wraps around a periodic plate) belongs to no polygon
/// given and makes no pieces; so do rings of fewer than 3 points.
///
/// # Errors
/// [`PiecesError::Ring`] naming the first wrong ring (the rings' ranges, `hole_of` and
/// sizes are checked before their points): its points run past `points`
/// ([`RingError::Points`]), its `hole_of` names a hole or itself ([`RingError::HoleOf`]), a
/// point of it is not finite ([`RingError::NotFinite`]), or the input is too large
/// ([`RingError::Size`]).
pub fn pieces_scratch(rings: &[Ring], points: &[[f32; 2]]) -> Result<usize, PiecesError> {
    Ok(plan(rings, points)?.scratch)
}

/// Runs the triangulation of every polygon, calling `triangle` with each triangle and its
/// outer ring, and `polygon_done` after each polygon.
fn each_triangle(
    rings: &[Ring],
    points: &[[f32; 2]],
    scratch: &mut [u32],
    mut triangle: impl FnMut(u32, [u32; 3]),
    mut polygon_done: impl FnMut(usize, &[u32]),
) {
    let r = rings.len();
    let (start, rest) = scratch.split_at_mut(r + 1);
    let (list, rest) = rest.split_at_mut(r);
    let (right, nodes) = rest.split_at_mut(r);
    // Holes grouped by their outer ring (a counting sort): ring k's are list[start[k]..start[k+1]].
    start.fill(0);
    for ring in rings {
        if let Some(outer) = hole_with_pieces(rings, ring) {
            start[outer + 1] += 1;
        }
    }
    for k in 0..r {
        start[k + 1] += start[k];
    }
    for (i, ring) in rings.iter().enumerate() {
        right[i] = 0;
        if let Some(outer) = hole_with_pieces(rings, ring) {
            list[start[outer] as usize] = i as u32;
            start[outer] += 1;
            right[i] = triangulation::rightmost(ring, points);
        }
    }
    // start[k] now ends ring k's holes; they begin where ring k − 1's end.
    for (i, ring) in rings.iter().enumerate() {
        if ring.hole_of != NOT_A_HOLE || ring.point_count < 3 {
            continue;
        }
        let begin = if i == 0 { 0 } else { start[i - 1] as usize };
        let holes = &mut list[begin..start[i] as usize];
        triangulation::polygon(rings, i, holes, right, points, nodes, &mut |t| triangle(i as u32, t));
        polygon_done(i, holes);
    }
}

/// The scratch, checked.
fn scratch_for<'a>(plan: &Plan, scratch: &'a mut [u32]) -> Result<&'a mut [u32], PiecesError> {
    scratch.get_mut(..plan.scratch).ok_or(PiecesError::ScratchTooSmall { needed: plan.scratch })
}

/// Counts the triangles and convex pieces the rings make, working in `scratch` (at least
/// [`pieces_scratch`] words). Same work as writing them.
///
/// # Errors
/// As [`pieces_scratch`]; [`PiecesError::ScratchTooSmall`]; and [`RingError::Crosses`]
/// naming the outer ring of the first polygon whose triangles do not add up to its area (a
/// ring of it crosses itself or another: its pieces would not cover it).
pub fn piece_counts(rings: &[Ring], points: &[[f32; 2]], scratch: &mut [u32]) -> Result<PieceCounts, PiecesError> {
    let plan = plan(rings, points)?;
    count(rings, points, scratch_for(&plan, scratch)?)
}

/// Counts the triangles and pieces, and checks that each polygon's triangles add up to its
/// area (outer ring and holes, from their points) to within 10⁻⁶ of their own: a ring that
/// crosses itself or another ring of its polygon is refused ([`RingError::Crosses`]).
fn count(rings: &[Ring], points: &[[f32; 2]], scratch: &mut [u32]) -> Result<PieceCounts, PiecesError> {
    let mut counts = PieceCounts::default();
    let merger = core::cell::RefCell::new(Merger::default());
    let pieces = core::cell::Cell::new(0usize);
    let covered = core::cell::Cell::new(0.0f64);
    let mut crossing = None;
    each_triangle(
        rings,
        points,
        scratch,
        |_, t| {
            counts.triangles += 1;
            let [a, b, c] = t.map(|i| points[i as usize]);
            covered.set(covered.get() + triangulation::cross(a, b, c));
            merger.borrow_mut().add(t, points, &mut |_| pieces.set(pieces.get() + 1));
        },
        |i, holes| {
            merger.borrow_mut().finish(&mut |_| pieces.set(pieces.get() + 1));
            // Each ring is walked in its own orientation: the outer ring counter-clockwise,
            // the holes clockwise, whichever way their points are given.
            let area = triangulation::ring_area2(&rings[i], points).abs()
                - holes.iter().map(|&h| triangulation::ring_area2(&rings[h as usize], points).abs()).sum::<f64>();
            let triangles = covered.replace(0.0);
            // Rounding: the shoelace terms' products of coordinates, n of them, in f64.
            let (mut nodes, mut largest) = (0usize, 0.0f32);
            for r in core::iter::once(i).chain(holes.iter().map(|&h| h as usize)) {
                let ring = &rings[r];
                nodes += ring.point_count as usize;
                for p in &points[ring.first_point as usize..][..ring.point_count as usize] {
                    largest = largest.max(p[0].abs()).max(p[1].abs());
                }
            }
            let rounding = 1e-10 * nodes as f64 * f64::from(largest) * f64::from(largest);
            let slack = 1e-6 * triangles.abs().max(area.abs()) + rounding;
            let adds_up = (triangles - area).abs() <= slack;
            if !adds_up && crossing.is_none() {
                crossing = Some(i);
            }
        },
    );
    if let Some(ring) = crossing {
        return Err(PiecesError::Ring { ring, error: RingError::Crosses });
    }
    counts.pieces = pieces.get();
    Ok(counts)
}

/// Writes the triangles of every polygon (outer ring and its holes) into `out`, polygon by
/// polygon in ring order, and returns how many ([`PieceCounts::triangles`]). Their areas add
/// up to each polygon's. Works in `scratch` (at least [`pieces_scratch`] words).
///
/// ```
/// use hibi_core::polygon::{NOT_A_HOLE, Ring, Triangle, pieces_scratch, triangulate};
/// // A 4 × 4 square with a 2 × 2 square hole.
/// let points = [[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [0.0, 4.0], [1.0, 1.0], [1.0, 3.0], [3.0, 3.0], [3.0, 1.0]];
/// let rings = [
///     Ring { area: 16.0, first_point: 0, point_count: 4, hole_of: NOT_A_HOLE, reserved: 0 },
///     Ring { area: -4.0, first_point: 4, point_count: 4, hole_of: 0, reserved: 0 },
/// ];
/// let mut scratch = vec![0; pieces_scratch(&rings, &points)?];
/// let mut triangles = [Triangle::default(); 16];
/// let n = triangulate(&rings, &points, &mut scratch, &mut triangles)?;
/// let area: f32 = triangles[..n].iter().map(|t| {
///     let [a, b, c] = t.points.map(|i| points[i as usize]);
///     0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
/// }).sum();
/// assert_eq!((n, area), (8, 12.0));
/// # Ok::<(), hibi_core::polygon::PiecesError>(())
/// ```
///
/// # Errors
/// As [`piece_counts`], and [`PiecesError::BufferTooSmall`] (with the count) when `out` is
/// shorter than the triangles: nothing is written then.
pub fn triangulate(
    rings: &[Ring],
    points: &[[f32; 2]],
    scratch: &mut [u32],
    out: &mut [Triangle],
) -> Result<usize, PiecesError> {
    let plan = plan(rings, points)?;
    let scratch = scratch_for(&plan, scratch)?;
    let needed = count(rings, points, scratch)?.triangles;
    if out.len() < needed {
        return Err(PiecesError::BufferTooSmall { needed });
    }
    let mut written = 0;
    each_triangle(
        rings,
        points,
        scratch,
        |ring, points| {
            out[written] = Triangle { ring, points };
            written += 1;
        },
        |_, _| {},
    );
    Ok(written)
}

/// Writes the convex pieces of every polygon (outer ring and its holes) into `out`, polygon
/// by polygon in ring order, and returns how many ([`PieceCounts::pieces`]): each at most
/// [`MAX_PIECE_POINTS`] points, strictly convex, counter-clockwise; their areas add up to
/// each polygon's. Works in `scratch` (at least [`pieces_scratch`] words).
///
/// # Errors
/// As [`piece_counts`], and [`PiecesError::BufferTooSmall`] (with the count) when `out` is
/// shorter than the pieces: nothing is written then.
pub fn convex_pieces(
    rings: &[Ring],
    points: &[[f32; 2]],
    scratch: &mut [u32],
    out: &mut [ConvexPiece],
) -> Result<usize, PiecesError> {
    let plan = plan(rings, points)?;
    let scratch = scratch_for(&plan, scratch)?;
    let needed = count(rings, points, scratch)?.pieces;
    if out.len() < needed {
        return Err(PiecesError::BufferTooSmall { needed });
    }
    let written = core::cell::Cell::new(0usize);
    let ring_now = core::cell::Cell::new(0u32);
    let out = core::cell::RefCell::new(out);
    let merger = core::cell::RefCell::new(Merger::default());
    let mut write = |piece: &[u32]| {
        let mut p = ConvexPiece { ring: ring_now.get(), point_count: piece.len() as u32, ..ConvexPiece::default() };
        p.points[..piece.len()].copy_from_slice(piece);
        out.borrow_mut()[written.get()] = p;
        written.set(written.get() + 1);
    };
    let write = core::cell::RefCell::new(&mut write);
    each_triangle(
        rings,
        points,
        scratch,
        |ring, t| {
            ring_now.set(ring);
            merger.borrow_mut().add(t, points, &mut *write.borrow_mut());
        },
        |_, _| merger.borrow_mut().finish(&mut *write.borrow_mut()),
    );
    Ok(written.get())
}
