//! The ring record: one closed outline of a polygon with holes, as glass fragments and mud
//! cells are written.

/// `hole_of` of an outer ring (`HIBI_RING_NOT_A_HOLE` in C).
pub const NOT_A_HOLE: u32 = u32::MAX;

/// One ring of a polygon's outline (a glass fragment's, a mud cell's): `point_count` points
/// from `first_point` on in the point buffer, counter-clockwise with y up for an outer ring
/// (positive `area`; `hole_of` is `NOT_A_HOLE`), clockwise for a hole (negative `area`, and
/// `hole_of` names the outer ring it lies in, or holds a model's own mark, such as mud's
/// `IN_WRAPPING_CELL`). In C: `hibi_ring`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C)]
pub struct Ring {
    /// Signed area: px² for glass, lattice units² for mud.
    pub area: f64,
    /// Index of the ring's first point.
    pub first_point: u32,
    /// Number of points (the first is not repeated).
    pub point_count: u32,
    /// For a hole, the index of the outer ring it lies in; `NOT_A_HOLE` for an outer ring
    /// (`HIBI_RING_NOT_A_HOLE` in C).
    pub hole_of: u32,
    /// Always 0: the struct has no padding, so every byte a call writes is defined (an
    /// output can be hashed or compared as bytes).
    pub reserved: u32,
}
