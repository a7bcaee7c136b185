//! A parent outline's edges binned on a grid over its bounding box. A child's build asks
//! which of its parent's edges lie near a box (around each edge it perturbs) or across a ray
//! (is a point inside the parent); most of a parent's edges are far from either, and the grid
//! names the few that may not be, as bits, in the order of the outline. The exact tests then
//! run on those alone, so every answer is the one a test of every edge gives.

/// Bins per axis.
const BINS: usize = 8;

/// Most edges an outline can have for a grid (one bit each); longer outlines are searched
/// through their chunk boxes.
const GRID_EDGES: usize = 64;

/// The bins of one outline of at most [`GRID_EDGES`] edges. An edge's box covers a range of
/// bins along each axis, and meets a box of bins exactly when its ranges meet the box's on
/// both axes: so per axis and bin, the edges whose range starts at or before it and those
/// whose range ends at or after it answer every question in a few words, without a loop
/// over bins.
#[derive(Clone, Copy)]
pub(super) struct EdgeGrid {
    /// The outline's lowest corner, and per axis the power of two a bin spans.
    origin: [i64; 2],
    shift: [u32; 2],
    /// Per axis and bin, the edges whose range starts at or before it (bit k for edge k,
    /// from vertex k to vertex k + 1).
    up_to: [[u64; BINS]; 2],
    /// Per axis and bin, the edges whose range ends at or after it.
    from: [[u64; BINS]; 2],
}

impl EdgeGrid {
    pub(super) const fn new() -> EdgeGrid {
        EdgeGrid { origin: [0; 2], shift: [0; 2], up_to: [[0; BINS]; 2], from: [[0; BINS]; 2] }
    }

    /// Bins the edges of `outline`, whose bounding box is [low, high], if it has at most
    /// [`GRID_EDGES`] of them (a longer one is left out: [`EdgeGrid::of`] gives no grid for
    /// it).
    pub(super) fn fill(&mut self, outline: &[[i64; 2]], (low, high): ([i64; 2], [i64; 2])) {
        if outline.len() > GRID_EDGES {
            return;
        }
        self.origin = low;
        // The least shift that puts the whole span in BINS bins.
        self.shift = [0, 1].map(|k| {
            let span = high[k].saturating_sub(low[k]) as u64;
            (u64::BITS - span.leading_zeros()).saturating_sub(BINS.trailing_zeros())
        });
        // Each edge marked at the bin its range starts at and the bin it ends at, per axis,
        // then spread: forwards from a start, backwards from an end.
        let (mut starts, mut ends) = ([[0u64; BINS]; 2], [[0u64; BINS]; 2]);
        // Each vertex's bins, found once for both its edges: a bin never decreases as its
        // coordinate grows, so an edge's lowest and highest bins are its ends' lower and higher.
        let (origin, shift) = (self.origin, self.shift);
        let bins = |v: [i64; 2]| [bin(origin[0], shift[0], v[0]), bin(origin[1], shift[1], v[1])];
        let mut a = outline.last().map_or([0; 2], |&v| bins(v));
        for (k, &b) in outline.iter().enumerate() {
            // (Edge k runs from vertex k to k + 1: the edge before vertex k, from the last
            // vertex to the first, is edge n − 1.)
            let (bin_b, edge) = (bins(b), if k == 0 { outline.len() - 1 } else { k - 1 });
            let bit = 1u64 << edge;
            for axis in 0..2 {
                starts[axis][a[axis].min(bin_b[axis])] |= bit;
                ends[axis][a[axis].max(bin_b[axis])] |= bit;
            }
            a = bin_b;
        }
        for axis in 0..2 {
            let (mut started, mut ended) = (0, 0);
            for b in 0..BINS {
                started |= starts[axis][b];
                self.up_to[axis][b] = started;
                ended |= ends[axis][BINS - 1 - b];
                self.from[axis][BINS - 1 - b] = ended;
            }
        }
    }

    /// The grid, for the outline of `edges` edges it was last filled with (None for an outline
    /// too long to bin).
    pub(super) fn of(&self, edges: usize) -> Option<&EdgeGrid> {
        (edges <= GRID_EDGES).then_some(self)
    }

    /// The bin of coordinate `v` along `axis`, the first or last for a coordinate outside the
    /// outline's box. (It never decreases as `v` grows, so a box that meets an edge's box
    /// meets it in a bin both are marked in.)
    #[inline]
    fn bin(&self, axis: usize, v: i64) -> usize {
        bin(self.origin[axis], self.shift[axis], v)
    }

    /// The edges whose boxes may meet the box [low, high] (a superset of those that do): those
    /// whose bins meet its bins on both axes.
    #[inline]
    pub(super) fn near(&self, (low, high): ([i64; 2], [i64; 2])) -> u64 {
        let on =
            |axis: usize| self.from[axis][self.bin(axis, low[axis])] & self.up_to[axis][self.bin(axis, high[axis])];
        on(0) & on(1)
    }

    /// The edges whose boxes may meet the ray from `p` towards +x (a superset of those that
    /// do): those whose bins take in `p`'s row and reach its bin or beyond.
    #[inline]
    pub(super) fn across(&self, p: [i64; 2]) -> u64 {
        let row = self.bin(1, p[1]);
        self.from[0][self.bin(0, p[0])] & self.from[1][row] & self.up_to[1][row]
    }
}

/// The bin of coordinate `v` on an axis whose bins start at `origin` and span 2^`shift` each
/// ([`EdgeGrid::bin`]).
#[inline]
fn bin(origin: i64, shift: u32, v: i64) -> usize {
    (v.saturating_sub(origin) >> shift).clamp(0, BINS as i64 - 1) as usize
}

/// Calls `visit` with each edge in `edges` (bit k for edge k), in ascending order, until it
/// returns true.
#[inline]
pub(super) fn each_edge(mut edges: u64, mut visit: impl FnMut(usize) -> bool) {
    while edges != 0 {
        let e = edges.trailing_zeros() as usize;
        edges &= edges - 1;
        if visit(e) {
            return;
        }
    }
}
