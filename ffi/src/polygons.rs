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
