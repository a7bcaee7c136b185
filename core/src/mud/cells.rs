//! Cells: the regions the crack network cuts the plate into, as polygons (the faces of the
//! network, with the plate's border on an open lattice).
//!
//! A cell's boundary runs along the separating cracks of the traced network (branches, the
//! cracks that end inside a region, do not bound it; see [`super::network`]) and, on an open
//! lattice, along the border. Walking a boundary keeps the cell on the left: an outer ring is
//! counter-clockwise with y up (positive shoelace area), a hole (an island cut out of a cell)
//! clockwise. A boundary runs through the network's points: from one cut side's crack point
//! (its spring's midpoint, smoothed along the crack: `Mud::crack_point`) to the next, and
//! through the centroid where three or more separating cracks meet. Every boundary piece is
//! walked once each way, so the rings' signed areas add up to the plate's.
//!
//! On a periodic lattice a ring is continuous and may reach past the domain (draw it
//! wrapped). A region that no crack crosses in one direction wraps around the torus and has
//! no outline in the plane: it is counted ([`CellCounts::wrapping`]) and not written. Its
//! holes (the islands in it, such as the one closed crack of a plate that has no other) are
//! written, with [`IN_WRAPPING_CELL`] for the cell they are in.

use super::network::TracedCell;
use super::{Boundary, Mud, MudError};
use crate::geom::shoelace;
use crate::polygon::{NOT_A_HOLE, Ring};
use crate::scalar::Scalar;

/// `hole_of` of a hole in a cell that wraps around a periodic lattice: that cell has no
/// outline in the plane, so no ring to name (`HIBI_MUD_IN_WRAPPING_CELL` in C). An outer
/// ring's `hole_of` is [`NOT_A_HOLE`].
pub const IN_WRAPPING_CELL: u32 = u32::MAX - 1;

/// How many rings and points [`Mud::cells`] writes, and the regions it cannot.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CellCounts {
    /// Rings: each cell's outer ring, and the holes in cells.
    pub rings: usize,
    /// Points of all rings.
    pub points: usize,
    /// Boundaries that wrap around a periodic lattice (not written).
    pub wrapping: usize,
}

/// Where a boundary walk is.
#[derive(Clone, Copy)]
pub(super) enum At {
    /// Entered mesh cell `c` through its side `k`.
    Inside { c: TracedCell, k: usize, wrap: [i32; 2] },
    /// At corner `i` of mesh cell `c`, on the open border.
    Border { c: TracedCell, i: usize },
}

/// Where the search for ring starts stands, as the trace keeps it between calls.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct RingCursor {
    /// The mesh cell whose separating sides are next.
    cell: usize,
    /// Its side the walk under way started from, or the next side to look at.
    side: usize,
    /// The walk under way from that side.
    walk: Option<RingWalk>,
}

impl RingCursor {
    /// The search's start.
    pub(super) const START: RingCursor = RingCursor { cell: 0, side: 0, walk: None };
}

/// A ring walk under way: where it is, its steps, the lowest key it has entered and the
/// points it has passed; and whether every mesh cell it has been in has two cut sides (a ring
/// along a closed crack, which has no vertex), and the lowest spring it has crossed then.
#[derive(Clone, Copy, Debug, PartialEq)]
struct RingWalk {
    at: RingAt,
    step: usize,
    lowest: usize,
    points: u64,
    passing: bool,
    lowest_spring: u32,
}

/// [`At`] by mesh cell index (the cell as the network sees it is worked out again).
#[derive(Clone, Copy, Debug, PartialEq)]
enum RingAt {
    Inside { cell: usize, k: usize, wrap: [i32; 2] },
    Border { cell: usize, i: usize },
}

/// How a ring walk ended.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum RingEnd {
    /// Back at the start, having moved by this many periods.
    Closed([i32; 2]),
    /// `visit` asked to stop.
    Stopped,
    /// The walk did not come back within its bound (cannot happen on a consistent trace).
    Broken,
}

/// The key of the border side `side` of mesh cell `cell`, apart from every [`key`].
fn border_key(cell: usize, side: usize) -> usize {
    usize::MAX - key(cell, side)
}

/// The key of entering mesh cell `cell` by side `side` (or, for a border corner, after all
/// those): rings are written from their lowest key.
fn key(cell: usize, side: usize) -> usize {
    cell * 4 + side
}

/// The work of one step of a ring walk: the mesh cell across a side and its sides looked at
/// (and, for the points written, its nodes' displacements), as much as visiting three springs.
pub(super) const RING_STEP: u64 = 3;

/// Whether the trace's search for ring starts works out positions, which it does not read:
/// only on 32-bit targets, where the run calls the walks with positions alone, so that the
/// Cortex-M3's flash holds one form of them.
const SEARCH_POSITIONS: bool = cfg!(not(target_pointer_width = "64"));

/// Ring-start word bits of a mesh cell: side k starts a ring that closes in the plane.
const STARTS: u32 = 0;
/// Side k starts a ring that wraps around the torus.
const WRAPS: u32 = 4;
/// Side k lies on a ring already walked (while the starts are found).
const WALKED: u32 = 8;

impl<S: Scalar> Mud<'_, S> {
    /// The key a ring walk from `start` ends at.
    fn start_key(start: &At) -> usize {
        match *start {
            At::Inside { c, k, .. } => key(c.index, k),
            At::Border { c, i } => border_key(c.index, i),
        }
    }

    /// The most steps a ring walk takes (more cannot happen on a consistent trace).
    fn ring_step_bound(&self) -> usize {
        8 * self.lattice.cell_count() + 16
    }

    /// Walks the ring from `start`, calling `visit(point, key)` with every point and the key
    /// of each mesh cell it enters (`usize::MAX` for other points); stops if `visit` returns
    /// false.
    pub(super) fn walk_ring(&self, start: At, visit: impl FnMut([f32; 2], usize) -> bool) -> RingEnd {
        self.walk_ring_as(start, true, visit)
    }

    /// [`Self::walk_ring`], the points' positions worked out only if `positions` (a walk that
    /// counts points or follows keys needs none; `visit` gets 0 for them then).
    fn walk_ring_as(&self, start: At, positions: bool, mut visit: impl FnMut([f32; 2], usize) -> bool) -> RingEnd {
        let start_key = Self::start_key(&start);
        let mut at = start;
        for step in 0..self.ring_step_bound() {
            match self.ring_step(at, start_key, step > 0, positions, &mut visit) {
                Ok(next) => at = next,
                Err(end) => return end,
            }
        }
        RingEnd::Broken
    }

    /// One step of a ring walk from `at` (`moved`: not the walk's first): to the next mesh
    /// cell the ring enters or the next border corner, visiting the points on the way (at
    /// most one of them with a mesh cell's key). `Err` when the walk ends. The mesh cells'
    /// positions are worked out only if `positions`.
    fn ring_step(
        &self,
        at: At,
        start_key: usize,
        moved: bool,
        positions: bool,
        visit: &mut impl FnMut([f32; 2], usize) -> bool,
    ) -> Result<At, RingEnd> {
        let crack_point = |c: &TracedCell, j: usize| if positions { self.crack_point(c, j) } else { [0.0; 2] };
        Ok(match at {
            At::Inside { c, k, wrap } => {
                // The first separating side clockwise from k bounds this corner's region.
                let n = c.sides();
                let j = (1..n).map(|d| (k + n - d) % n).find(|&j| c.separating[j]).unwrap_or(k);
                if c.separating_count() >= 3 && !visit(c.centroid(), usize::MAX) {
                    return Err(RingEnd::Stopped);
                }
                match self.across_as(&c, j, wrap, positions) {
                    Some((next, side, wrap)) => {
                        if !visit(crack_point(&c, j), key(next.index, side)) {
                            return Err(RingEnd::Stopped);
                        }
                        if key(next.index, side) == start_key {
                            return Err(RingEnd::Closed(wrap));
                        }
                        At::Inside { c: next, k: side, wrap }
                    }
                    None => {
                        let i = (j + 1) % n;
                        if !visit(crack_point(&c, j), usize::MAX) || !visit(c.corner[i], usize::MAX) {
                            return Err(RingEnd::Stopped);
                        }
                        At::Border { c, i }
                    }
                }
            }
            At::Border { c, i } => {
                // The side leaving corner i counter-clockwise: on the border, or turn about
                // the corner into the next mesh cell.
                match self.across_as(&c, i, [0, 0], positions) {
                    Some((next, side, _)) => At::Border { c: next, i: (side + 1) % next.sides() },
                    None => {
                        if moved && border_key(c.index, i) == start_key {
                            return Err(RingEnd::Closed([0, 0]));
                        }
                        if c.separating[i] {
                            if !visit(crack_point(&c, i), key(c.index, i)) {
                                return Err(RingEnd::Stopped);
                            }
                            if key(c.index, i) == start_key {
                                return Err(RingEnd::Closed([0, 0]));
                            }
                            At::Inside { c, k: i, wrap: [0, 0] }
                        } else {
                            let i = (i + 1) % c.sides();
                            if !visit(c.corner[i], usize::MAX) {
                                return Err(RingEnd::Stopped);
                            }
                            At::Border { c, i }
                        }
                    }
                }
            }
        })
    }

    /// Finds where each ring starts (its lowest key) and whether it wraps, walking each ring
    /// once, from `cursor` until the work reaches `budget` (at least one item): part of the
    /// trace ([`Mud::trace`]). An item is a mesh cell (its sides) or one step of a ring walk
    /// ([`RING_STEP`]); a walk stopped by the budget goes on from its step in the next call. Returns the
    /// work and the cursor to go on from (`None`: done). The ring-start words were cleared
    /// when the vertices were numbered.
    pub(super) fn find_ring_starts(&mut self, mut cursor: RingCursor, budget: u64) -> (u64, Option<RingCursor>) {
        let cells = self.lattice.cell_count();
        let corners = self.lattice.sides_per_cell() as u64;
        let mut work = 0u64;
        while work < budget {
            let Some(walk) = cursor.walk else {
                // The next separating side of this cell, from `side` on, not walked yet.
                if cursor.cell >= cells {
                    return (work, None);
                }
                // Cells no crack touches are passed over (see `network::next_flagged`).
                if cursor.side == 0 {
                    match super::network::next_flagged(self.touched.cells, cursor.cell, cells) {
                        Ok(flagged) => cursor.cell = flagged,
                        Err(word_end) => {
                            work += 1;
                            cursor.cell = word_end;
                            continue;
                        }
                    }
                }
                if cursor.side == 0 {
                    work += corners;
                }
                let next_cell = RingCursor { cell: cursor.cell + 1, side: 0, walk: None };
                let Some(c) = self.cut_cell_as(cursor.cell, SEARCH_POSITIONS) else {
                    cursor = next_cell;
                    continue;
                };
                let walked = self.ring_starts[cursor.cell];
                let unwalked = |k: usize| c.separating[k] && walked & 1 << (WALKED + k as u32) == 0;
                cursor = match (cursor.side..c.sides()).find(|&k| unwalked(k)) {
                    Some(k) => {
                        let at = RingAt::Inside { cell: cursor.cell, k, wrap: [0, 0] };
                        let (lowest, lowest_spring) = (key(cursor.cell, k), c.cell.sides[k]);
                        let walk = RingWalk { at, step: 0, lowest, points: 0, passing: true, lowest_spring };
                        RingCursor { side: k, walk: Some(walk), ..cursor }
                    }
                    None => next_cell,
                };
                continue;
            };
            // Go on with the walk from side `cursor.side` of `cursor.cell`.
            let start_key = key(cursor.cell, cursor.side);
            let after = RingCursor { side: cursor.side + 1, walk: None, ..cursor };
            let Some(mut at) = self.ring_at(walk.at) else {
                cursor = after;
                continue;
            };
            let (mut step, mut lowest, mut points) = (walk.step, walk.lowest, walk.points);
            let (mut passing, mut lowest_spring) = (walk.passing, walk.lowest_spring);
            let end = loop {
                if step >= self.ring_step_bound() {
                    break Some(RingEnd::Broken);
                }
                if work >= budget {
                    break None;
                }
                let mut entered = usize::MAX;
                passing = passing && matches!(at, At::Inside { c, .. } if c.cut_count() == 2);
                let next = self.ring_step(at, start_key, step > 0, SEARCH_POSITIONS, &mut |_, k| {
                    points += 1;
                    if k != usize::MAX {
                        entered = k;
                    }
                    true
                });
                step += 1;
                work += RING_STEP;
                if entered != usize::MAX {
                    self.ring_starts[entered / 4] |= 1 << (WALKED + (entered % 4) as u32);
                    lowest = lowest.min(entered);
                }
                match next {
                    Ok(next) => at = next,
                    Err(end) => break Some(end),
                }
                if let (true, At::Inside { c, k, .. }) = (passing, at) {
                    lowest_spring = lowest_spring.min(c.cell.sides[k]);
                }
            };
            let Some(end) = end else {
                let at = Self::ring_at_of(&at);
                cursor.walk = Some(RingWalk { at, step, lowest, points, passing, lowest_spring });
                break;
            };
            let bit = match end {
                RingEnd::Closed([0, 0]) => Some(STARTS),
                RingEnd::Closed(_) => Some(WRAPS),
                RingEnd::Stopped | RingEnd::Broken => None,
            };
            if let Some(bit) = bit {
                self.ring_starts[lowest / 4] |= 1 << (bit + (lowest % 4) as u32);
            }
            // Each side of a closed crack (the cracks of separating springs: those of branches
            // the trace has counted) is a ring through mesh cells with two cut sides alone.
            if bit.is_some() && passing {
                self.note_closed_crack(lowest_spring, 1);
            }
            // A ring has as many points from any start (`cell_counts` reads the sums).
            match bit {
                Some(STARTS) => {
                    self.totals.rings += 1;
                    self.totals.ring_points += points;
                }
                Some(_) => self.totals.wrapping += 1,
                None => {}
            }
            cursor = after;
        }
        (work, Some(cursor))
    }

    /// A ring walk's place as the trace keeps it.
    fn ring_at_of(at: &At) -> RingAt {
        match *at {
            At::Inside { c, k, wrap } => RingAt::Inside { cell: c.index, k, wrap },
            At::Border { c, i } => RingAt::Border { cell: c.index, i },
        }
    }

    /// The ring walk's place `at`, with its mesh cell as the network sees it (its sides; the
    /// search for ring starts needs no positions).
    fn ring_at(&self, at: RingAt) -> Option<At> {
        let traced =
            |cell: usize, wrap: [i32; 2]| Some(self.traced_as(cell, self.lattice.cell(cell)?, wrap, SEARCH_POSITIONS));
        Some(match at {
            RingAt::Inside { cell, k, wrap } => At::Inside { c: traced(cell, wrap)?, k, wrap },
            RingAt::Border { cell, i } => At::Border { c: traced(cell, [0, 0])?, i },
        })
    }

    /// Calls `ring(start)` with the start of every ring that closes in the plane, in a fixed
    /// order (by the lowest mesh cell and side it enters), and returns the number of rings
    /// that wrap around a periodic lattice.
    fn for_each_ring(&self, mut ring: impl FnMut(At)) -> usize {
        // The setup or a trace under way has no cells to show yet.
        if !self.shows_network() {
            return 0;
        }
        let mut border_touched = false;
        let wrapping = self.ring_starts_in(0..self.lattice.cell_count(), &mut border_touched, &mut ring);
        if let Some(start) = self.border_ring(border_touched) {
            ring(start);
        }
        wrapping
    }

    /// An open plate whose border no crack reaches (`border_touched` false): the border is a
    /// ring of its own, which starts here.
    fn border_ring(&self, border_touched: bool) -> Option<At> {
        if self.params.boundary != Boundary::Open || border_touched {
            return None;
        }
        (0..self.lattice.cell_count()).find_map(|cell| self.border_start(cell))
    }

    /// [`Mud::for_each_ring`]'s rings whose start is in the mesh cells `cells`, in its order;
    /// returns how many rings that wrap start there, and sets `border_touched` if a separating
    /// side there is on the border.
    pub(super) fn ring_starts_in(
        &self,
        cells: core::ops::Range<usize>,
        border_touched: &mut bool,
        ring: &mut impl FnMut(At),
    ) -> usize {
        let mut wrapping = 0;
        for cell in cells {
            // The cell's positions are worked out for the rings that start in it only.
            let Some(t) = self.cut_cell_as(cell, false) else { continue };
            for k in (0..t.sides()).filter(|&k| t.separating[k]) {
                *border_touched |= self.is_border_side(&t, k);
                let flags = self.ring_starts[cell] >> k;
                if flags & 1 << STARTS != 0 {
                    ring(At::Inside { c: self.traced(cell, t.cell, [0, 0]), k, wrap: [0, 0] });
                } else if flags & 1 << WRAPS != 0 {
                    wrapping += 1;
                }
            }
        }
        wrapping
    }

    /// Where the ring of an open plate's border starts, if mesh cell `cell` has a side on the
    /// border (the first such cell starts it, when no crack reaches the border).
    pub(super) fn border_start(&self, cell: usize) -> Option<At> {
        let c = self.traced_cell(cell, [0, 0])?;
        (0..c.sides()).find(|&k| self.is_border_side(&c, k)).map(|k| At::Border { c, i: k })
    }

    /// The signed area and point count of the ring from `start` (lattice units²).
    fn ring_shape(&self, start: At) -> (f64, usize) {
        let (mut twice, mut count, mut previous, mut first) = (0.0f64, 0usize, [0.0f32; 2], None);
        self.walk_ring(start, |p, _| {
            if first.is_some() {
                twice += shoelace(previous, p);
            } else {
                first = Some(p);
            }
            previous = p;
            count += 1;
            true
        });
        if let Some(p) = first {
            twice += shoelace(previous, p);
        }
        (twice * 0.5, count)
    }

    /// How many rings and points [`Mud::cells`] writes: those the trace counted as it found
    /// where the rings start, and an open plate's border if no crack reaches it (walked).
    pub fn cell_counts(&self) -> CellCounts {
        // The setup or a trace under way has no cells to show yet.
        if !self.shows_network() {
            return CellCounts::default();
        }
        let t = &self.totals;
        let size = |n: u64| usize::try_from(n).unwrap_or(usize::MAX);
        let mut counts = CellCounts { rings: size(t.rings), points: size(t.ring_points), wrapping: size(t.wrapping) };
        // Whether a crack reaches an open plate's border.
        let border_touched = self.params.boundary == Boundary::Open
            && (0..self.lattice.cell_count()).any(|cell| {
                self.cut_cell_as(cell, false)
                    .is_some_and(|c| (0..c.sides()).any(|k| c.separating[k] && self.is_border_side(&c, k)))
            });
        if let Some(start) = self.border_ring(border_touched) {
            counts.rings += 1;
            self.walk_ring_as(start, false, |_, _| {
                counts.points += 1;
                true
            });
        }
        counts
    }

    /// [`Mud::cell_counts`] by walking every ring (what the counts must equal).
    #[cfg(test)]
    pub(super) fn walked_cell_counts(&self) -> CellCounts {
        let mut counts = CellCounts::default();
        counts.wrapping = self.for_each_ring(|start| {
            counts.rings += 1;
            self.walk_ring_as(start, false, |_, _| {
                counts.points += 1;
                true
            });
        });
        counts
    }

    /// Writes the cells of the traced network: one record per ring into `rings` (outer rings
    /// with positive area, holes with negative area naming the ring of the cell they are in,
    /// or [`IN_WRAPPING_CELL`]), their points (lattice units) into `points`, and returns the
    /// counts. Nothing is written if a buffer is shorter than [`Mud::cell_counts`] says.
    pub fn cells(&self, rings: &mut [Ring], points: &mut [[f32; 2]]) -> Result<CellCounts, MudError> {
        let counts = self.cell_counts();
        for (have, needed) in [(rings.len(), counts.rings), (points.len(), counts.points)] {
            if have < needed {
                return Err(MudError::BufferTooSmall { needed });
            }
        }
        // (The counts hold on every trace; were one to differ, what does not fit is left out
        // rather than written past a buffer.)
        let (mut r, mut p) = (0, 0);
        self.for_each_ring(|start| {
            let first = p;
            self.walk_ring(start, |q, _| {
                if let Some(slot) = points.get_mut(p) {
                    *slot = q;
                }
                p += 1;
                true
            });
            let ring = &points[first.min(points.len())..p.min(points.len())];
            let twice: f64 = ring.iter().zip(ring.iter().cycle().skip(1)).map(|(a, b)| shoelace(*a, *b)).sum();
            let area = 0.5 * twice;
            if let Some(slot) = rings.get_mut(r) {
                *slot = Ring {
                    area,
                    first_point: first as u32,
                    point_count: (p - first) as u32,
                    hole_of: NOT_A_HOLE,
                    reserved: 0,
                };
            }
            r += 1;
        });
        let written = r.min(rings.len());
        for ring in rings[..written].iter_mut().filter(|ring| (ring.first_point as usize) < points.len()) {
            if ring.area < 0.0 {
                ring.hole_of = self.ring_around(points[ring.first_point as usize]).unwrap_or(IN_WRAPPING_CELL);
            }
        }
        Ok(counts)
    }

    /// The index (in [`Mud::for_each_ring`]'s order) of the smallest outer ring around the
    /// point `q` of a hole, tried at every periodic shift; `None` when no ring closes around
    /// it: the hole lies in a cell that wraps around a periodic lattice. The rings are walked
    /// again, not read from a buffer, so that the statistics can ask too (holes are rare).
    fn ring_around(&self, q: [f32; 2]) -> Option<u32> {
        let ([w, h], shifts) = self.hole_shifts();
        let mut best = (None, f64::INFINITY);
        let mut j = 0;
        self.for_each_ring(|start| {
            let (area, _) = self.ring_shape(start);
            if area > 0.0 && area < best.1 {
                for s in shifts {
                    let p = [q[0] + s[0] * w, q[1] + s[1] * h];
                    let (mut crossings, mut on, mut previous, mut first) = (0usize, false, [0.0f32; 2], None);
                    self.walk_ring(start, |a, _| {
                        match first {
                            Some(_) => crossings += usize::from(crate::geom::crosses_ray(previous, a, p)),
                            None => first = Some(a),
                        }
                        on |= a == p;
                        previous = a;
                        true
                    });
                    if let Some(a) = first {
                        crossings += usize::from(crate::geom::crosses_ray(previous, a, p));
                    }
                    if crossings % 2 == 1 && !on {
                        best = (Some(j), area);
                        break;
                    }
                }
            }
            j += 1;
        });
        best.0
    }

    /// The plate's size (lattice units) and the shifts by it at which a hole's point is tried
    /// inside the outer rings: none on an open plate, the eight neighbouring copies too on a
    /// periodic one.
    pub(super) fn hole_shifts(&self) -> ([f32; 2], &'static [[f32; 2]]) {
        let (_, deep) = self.factors();
        let size = self.lattice.extent().map(|e| e * deep.to_f32());
        let shifts: &[[f32; 2]] = match self.params.boundary {
            Boundary::Open => &[[0.0, 0.0]],
            Boundary::Periodic => &[
                [0.0, 0.0],
                [-1.0, -1.0],
                [0.0, -1.0],
                [1.0, -1.0],
                [-1.0, 0.0],
                [1.0, 0.0],
                [-1.0, 1.0],
                [0.0, 1.0],
                [1.0, 1.0],
            ],
        };
        (size, shifts)
    }

    /// Sums over the net areas of the cells that close in the plane (outer ring less its
    /// holes), and the number of cells, wrapping ones included.
    pub(super) fn cell_areas(&self) -> (super::statistics::AreaSums, u32) {
        let (mut count, mut sum, mut sum_squares, mut holes) = (0usize, 0.0f64, 0.0f64, 0.0f64);
        let (mut wrapping_regions, mut in_wrapping) = (0, false);
        let wrapping = self.for_each_ring(|start| {
            let (area, _) = self.ring_shape(start);
            if area > 0.0 {
                count += 1;
                sum += area;
                sum_squares += area * area;
            } else {
                // A hole in no outer ring is in a cell that wraps (which has no area here).
                let mut q = None;
                self.walk_ring(start, |p, _| {
                    q = Some(p);
                    false
                });
                match q.and_then(|q| self.ring_around(q)) {
                    Some(_) => holes += area,
                    None => in_wrapping = true,
                }
            }
        });
        // Holes are rare (an island inside a cell): their cells' areas are corrected by
        // spreading the holes' area evenly, so only the spread is approximate then.
        if count > 0 && holes != 0.0 {
            let per = holes / count as f64;
            sum_squares += 2.0 * per * sum + count as f64 * per * per;
            sum += holes;
        }
        // A region that wraps is bounded by wrapping boundaries (and the holes in it) only;
        // with none at all the whole plate, less its islands, is one region.
        if wrapping > 0 || count == 0 || in_wrapping {
            wrapping_regions = if wrapping > 0 { (wrapping / 2).max(1) } else { 1 };
        }
        let sums = super::statistics::AreaSums { count, sum, sum_squares };
        (sums, (count + wrapping_regions) as u32)
    }
}
