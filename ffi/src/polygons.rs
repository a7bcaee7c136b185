//! The polygons glass fragments and mud cells are written as: the ring record `hibi_ring`
//! (the core's `polygon::Ring`) and its outer-ring mark, and the polygon queries, mud's
//! `hibi_mud_cells` and glass's `hibi_glass_fragments`: one C shape (the object and its extra
//! arguments, then a ring buffer, a point buffer and the two counts written), so the function
//! is written once, by `polygon_query!`.

/// `hibi_ring.hole_of` of an outer ring (a hole's names the outer ring it lies in).
pub const HIBI_RING_NOT_A_HOLE: u32 = u32::MAX;

const _: () = assert!(HIBI_RING_NOT_A_HOLE == hibi_core::polygon::NOT_A_HOLE);

/// A polygon query `$name`: runs the statements in braces, which open the object, then checks
/// `rings_written` and `points_written` (required) and the ring and point buffers, in that
/// order (every function checks its object first; the first failing argument is the one
/// `hibi_error_argument` names), runs `$query` on the buffers (named `$rings` and `$points`
/// there; it checks anything else of its own, such as a scratch, before it writes, and gives
/// the ring and point counts it wrote) and writes the counts. The doc comment is the caller's,
/// ending in its Safety clause for the object; the buffers' clause, the signature and the
/// checks are here.
macro_rules! polygon_query {
    (
        $(#[$doc:meta])*
        $name:ident($arg:ident: $object:ty $(, $extra:ident: $extra_ty:ty)*);
        { $($open:tt)* }
        |$rings:ident, $points:ident| $query:expr
    ) => {
        $(#[$doc])*
        /// `rings` and `points` NULL (only with length 0) or writable for their lengths, not
        /// overlapping; `rings_written` and `points_written` NULL (refused) or writable.
        #[unsafe(no_mangle)]
        #[allow(clippy::too_many_arguments)]
        pub unsafe extern "C" fn $name(
            $arg: *const $object,
            $($extra: $extra_ty,)*
            rings: *mut hibi_core::polygon::Ring,
            rings_len: usize,
            points: *mut $crate::glass::hibi_vec2,
            points_len: usize,
            rings_written: *mut usize,
            points_written: *mut usize,
        ) -> $crate::status::hibi_status {
            $crate::guard::guard(|| {
                $($open)*
                let written = $crate::guard::Outs::check([
                    (rings_written, c"rings_written"),
                    (points_written, c"points_written"),
                ])?;
                // SAFETY: the caller's contract; the ring type is the core's, and hibi_vec2 is
                // laid out as [f32; 2] (asserted in glass.rs).
                let ($rings, $points) = unsafe {
                    (
                        $crate::guard::buffer(rings, rings_len, c"rings")?,
                        $crate::guard::buffer(points.cast::<[f32; 2]>(), points_len, c"points")?,
                    )
                };
                let (ring_count, point_count) = $query?;
                // SAFETY: checked; the caller's contract.
                unsafe { written.write([ring_count, point_count]) }
            })
        }
    };
}
pub(crate) use polygon_query;

// ---- Pieces for a physics engine ----------------------------------------------------------

use hibi_core::polygon::{ConvexPiece, MAX_PIECE_POINTS, PiecesError, Ring, RingError, Triangle};

use crate::glass::hibi_vec2;
use crate::guard::{Outs, buffer, guard, input};
use crate::status::{
    HIBI_ERROR_BUFFER_TOO_SMALL, HIBI_ERROR_RING_CROSSES, HIBI_ERROR_RING_HOLE_OF, HIBI_ERROR_RING_POINT_NOT_FINITE,
    HIBI_ERROR_RING_POINTS, HIBI_ERROR_RING_SIZE, hibi_status, refuse_argument,
};

/// The most points of a `hibi_convex_piece` (Box2D's `b2_maxPolygonVertices`).
pub const HIBI_PIECE_MAX_POINTS: u32 = 8;

const _: () = assert!(HIBI_PIECE_MAX_POINTS as usize == MAX_PIECE_POINTS);

/// The status of a piece error; a short scratch or output is put on record by its C name.
fn pieces_status(error: PiecesError, output: &'static core::ffi::CStr) -> hibi_status {
    match error {
        PiecesError::Ring { error, .. } => match error {
            RingError::Points => HIBI_ERROR_RING_POINTS,
            RingError::HoleOf => HIBI_ERROR_RING_HOLE_OF,
            RingError::NotFinite => HIBI_ERROR_RING_POINT_NOT_FINITE,
            RingError::Size => HIBI_ERROR_RING_SIZE,
            RingError::Crosses => HIBI_ERROR_RING_CROSSES,
        },
        PiecesError::ScratchTooSmall { .. } => refuse_argument(c"scratch", HIBI_ERROR_BUFFER_TOO_SMALL),
        PiecesError::BufferTooSmall { .. } => refuse_argument(output, HIBI_ERROR_BUFFER_TOO_SMALL),
    }
}

/// The rings and points of a piece call, checked as buffers.
///
/// # Safety
/// As the piece functions'.
unsafe fn polygons<'a>(
    rings: *const Ring,
    rings_len: usize,
    points: *const hibi_vec2,
    points_len: usize,
) -> Result<(&'a [Ring], &'a [[f32; 2]]), hibi_status> {
    // SAFETY: the caller's contract; hibi_vec2 is laid out as [f32; 2] (asserted in glass.rs).
    unsafe { Ok((input(rings, rings_len, c"rings")?, input(points.cast::<[f32; 2]>(), points_len, c"points")?)) }
}

/// Checks the rings `rings[0..rings_len]` over the points `points[0..points_len]` (glass
/// fragments or mud cells as `hibi_glass_fragments` and `hibi_mud_cells` write them, or any
/// polygons in that shape) and writes into `*scratch_len` how many `uint32_t` words of scratch
/// `hibi_pieces_counts`, `hibi_triangulate` and `hibi_convex_pieces` need: 3 per ring plus 1,
/// and 4 per point of the largest outer ring and of every hole (2 more per hole).
///
/// An outer ring (`hole_of` `HIBI_RING_NOT_A_HOLE`) and the holes whose `hole_of` is its index
/// make one polygon. A hole whose `hole_of` is past the rings (`HIBI_MUD_IN_WRAPPING_CELL`)
/// and a ring of fewer than 3 points make no pieces. The rings' orientation is taken from
/// their points: an outer ring given clockwise is walked the other way.
///
/// Refused, naming nothing: `HIBI_ERROR_RING_POINTS` (a ring's `first_point + point_count`
/// runs past `points_len`), `HIBI_ERROR_RING_HOLE_OF` (a `hole_of` below `rings_len` names a
/// hole or the ring itself), `HIBI_ERROR_RING_POINT_NOT_FINITE` (a ring's point is NaN or
/// infinite), `HIBI_ERROR_RING_SIZE` (a polygon holds 2^30 or more points with its holes).
///
/// # Safety
/// `rings` and `points` NULL (only with length 0) or readable for their lengths;
/// `scratch_len` NULL (refused) or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn hibi_pieces_scratch_size(
    rings: *const Ring,
    rings_len: usize,
    points: *const hibi_vec2,
    points_len: usize,
    scratch_len: *mut usize,
) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let (rings, points) = unsafe { polygons(rings, rings_len, points, points_len) }?;
        let out = Outs::check([(scratch_len, c"scratch_len")])?;
        let words = hibi_core::polygon::pieces_scratch(rings, points).map_err(|e| pieces_status(e, c""))?;
        // SAFETY: checked; the caller's contract.
        unsafe { out.write([words]) }
    })
}

/// Writes how many triangles (`*triangles`) and convex pieces (`*pieces`) `hibi_triangulate`
/// and `hibi_convex_pieces` write for the rings. Works in `scratch[0..scratch_len]` (at least
/// `hibi_pieces_scratch_size` words, else `HIBI_ERROR_BUFFER_TOO_SMALL` naming `scratch`); as
/// much work as writing them. Refuses bad rings as `hibi_pieces_scratch_size` does, and a
/// polygon whose triangles do not add up to its area (`HIBI_ERROR_RING_CROSSES`: a ring of it
/// crosses itself or another ring of the polygon, so no pieces cover it).
///
/// # Safety
/// `rings` and `points` as in `hibi_pieces_scratch_size`; `scratch` NULL (only with length
/// 0) or writable for `scratch_len` words, overlapping nothing else; `triangles` and `pieces`
/// NULL (refused) or writable.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn hibi_pieces_counts(
    rings: *const Ring,
    rings_len: usize,
    points: *const hibi_vec2,
    points_len: usize,
    scratch: *mut u32,
    scratch_len: usize,
    triangles: *mut usize,
    pieces: *mut usize,
) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let (rings, points) = unsafe { polygons(rings, rings_len, points, points_len) }?;
        let out = Outs::check([(triangles, c"triangles"), (pieces, c"pieces")])?;
        // SAFETY: the caller's contract.
        let scratch = unsafe { buffer(scratch, scratch_len, c"scratch") }?;
        let counts = hibi_core::polygon::piece_counts(rings, points, scratch).map_err(|e| pieces_status(e, c""))?;
        // SAFETY: checked; the caller's contract.
        unsafe { out.write([counts.triangles, counts.pieces]) }
    })
}

/// Writes the triangles of every polygon into `triangles[0..triangles_len]`, polygon by
/// polygon in ring order, and their count into `*written`: three indices into `points`,
/// counter-clockwise with y up, and the index of the polygon's outer ring. Holes are left
/// out; each polygon's triangle areas add up to its outer ring's area minus its holes', or
/// nothing is written (`HIBI_ERROR_RING_CROSSES`, as `hibi_pieces_counts` refuses).
/// Works in `scratch` as `hibi_pieces_counts` does. If `triangles_len` is below the count
/// (`hibi_pieces_counts`), nothing is written and the status is
/// `HIBI_ERROR_BUFFER_TOO_SMALL` naming `triangles`.
///
/// Work: at most 2·3·m² point tests for a polygon of m points (its outer ring's, its holes'
/// and 2 per hole), whatever the points hold: the polygons are triangulated once to count and
/// check them, once to write.
///
/// # Safety
/// As `hibi_pieces_counts`; `triangles` NULL (only with length 0) or writable for
/// `triangles_len` entries; `written` NULL (refused) or writable.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn hibi_triangulate(
    rings: *const Ring,
    rings_len: usize,
    points: *const hibi_vec2,
    points_len: usize,
    scratch: *mut u32,
    scratch_len: usize,
    triangles: *mut Triangle,
    triangles_len: usize,
    written: *mut usize,
) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let (rings, points) = unsafe { polygons(rings, rings_len, points, points_len) }?;
        let out = Outs::check([(written, c"written")])?;
        // SAFETY: the caller's contract.
        let (scratch, triangles) =
            unsafe { (buffer(scratch, scratch_len, c"scratch")?, buffer(triangles, triangles_len, c"triangles")?) };
        let n = hibi_core::polygon::triangulate(rings, points, scratch, triangles)
            .map_err(|e| pieces_status(e, c"triangles"))?;
        // SAFETY: checked; the caller's contract.
        unsafe { out.write([n]) }
    })
}

/// Writes the convex pieces of every polygon into `pieces[0..pieces_len]`, polygon by polygon
/// in ring order, and their count into `*written`: 3 to `HIBI_PIECE_MAX_POINTS` (8) indices
/// into `points`, counter-clockwise with y up and strictly convex (what Box2D's
/// `b2PolygonShape::Set`, Jolt's and PhysX's convex shapes take), and the index of the
/// polygon's outer ring. They are the triangles of `hibi_triangulate` merged while the union
/// stays convex; each polygon's piece areas add up to its outer ring's area minus its holes',
/// or nothing is written (`HIBI_ERROR_RING_CROSSES`, as `hibi_pieces_counts` refuses).
/// Works in `scratch` as `hibi_pieces_counts` does. If `pieces_len` is below the count
/// (`hibi_pieces_counts`), nothing is written and the status is
/// `HIBI_ERROR_BUFFER_TOO_SMALL` naming `pieces`.
///
/// # Safety
/// As `hibi_pieces_counts`; `pieces` NULL (only with length 0) or writable for `pieces_len`
/// entries; `written` NULL (refused) or writable.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn hibi_convex_pieces(
    rings: *const Ring,
    rings_len: usize,
    points: *const hibi_vec2,
    points_len: usize,
    scratch: *mut u32,
    scratch_len: usize,
    pieces: *mut ConvexPiece,
    pieces_len: usize,
    written: *mut usize,
) -> hibi_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let (rings, points) = unsafe { polygons(rings, rings_len, points, points_len) }?;
        let out = Outs::check([(written, c"written")])?;
        // SAFETY: the caller's contract.
        let (scratch, pieces) =
            unsafe { (buffer(scratch, scratch_len, c"scratch")?, buffer(pieces, pieces_len, c"pieces")?) };
        let n = hibi_core::polygon::convex_pieces(rings, points, scratch, pieces)
            .map_err(|e| pieces_status(e, c"pieces"))?;
        // SAFETY: checked; the caller's contract.
        unsafe { out.write([n]) }
    })
}
