//! The irregular lattice (a third topology, beyond the paper): the triangular lattice's nodes
//! jittered by up to [`JITTER`] of the element size and connected by their Delaunay
//! triangulation, so that cracks are not held to three directions.
//!
//! Construction (deterministic, no allocation, in the run's memory, resumable item by item
//! within [`Mud::step`](super::Mud::step)'s budgets: [`Construction`]): the nodes start on the
//! triangular lattice, whose triangles are Delaunay. Node by node, in index order, each is
//! moved to its jittered place (uniform in a disk, drawn from [`Stream::LatticeJitter`]); a
//! move that would fold a triangle over is halved until it does not, and the node moves on
//! from there. After each move Lawson's flips make every edge around the node locally
//! Delaunay again (the fourth node outside the circle through the other three), which makes
//! the whole triangulation Delaunay. Positions are integers in 1/[`UNIT`] of the element
//! size, so the in-circle and orientation tests are exact and every platform flips the same
//! edges. On a torus the triangulation wraps; at open edges the lattice's border is kept
//! (its edges never flip), so the mesh is Delaunay inside the plate.
//!
//! The slots stay the triangular lattice's: three springs and two triangles per node (a flip
//! re-assigns a spring's nodes and a triangle's corners; it makes no edge and removes none),
//! so the open lattice's missing springs and cells are missing here too.
//!
//! Each spring then takes the paper's constants from its own geometry: its rest length l0
//! (the distance of its nodes), its face (the dual Voronoi edge: the distance between the
//! circumcentres of its two triangles; at an open edge, from the one circumcentre to the
//! spring's midpoint), so k = A·E/l0 with A = face·H, κ_i = κ̄ + σ/√A_i·N(0, 1), and each node's
//! area B (its Voronoi cell, Σ l0·face/4 over its springs) gives its shear spring h = B·G/H.

use super::lattice::Lattice;
use super::material::anisotropy;
use super::params::{Boundary, MudParams, Topology};
use super::take;
use crate::rng::Rng;

/// Positions are integer multiples of 1/UNIT of the element size.
pub const UNIT: i64 = 1024;
/// The row pitch in 1/UNIT: √3/2 rounded (887/1024 = 0.8662).
pub const PITCH: i64 = 887;
/// The jitter radius, element sizes: each node moves uniformly within a disk of this radius
/// around its triangular-lattice site. 0.4: the spring directions spread evenly over 180°
/// (see `tests/mud.rs`, crack orientations), while no two nodes come closer than 0.2.
pub const JITTER: f32 = 0.4;
/// The smallest face a spring is given, element sizes. Four nearly cocircular nodes make a
/// Voronoi edge of almost no length; its spring would be nearly massless in stiffness and,
/// with σ/√A, in strength. The floor keeps both finite.
pub const FACE_FLOOR: f32 = 0.05;
/// No cell, no node.
const NONE: u32 = u32::MAX;
/// Words per spring in [`Mesh::shape`]: e (x, y), l0, face, k.
const SHAPE: usize = 5;
/// The most triangles around a node the construction follows.
const MAX_STAR: usize = 32;
/// The most springs at a node: a flip that would give a node more is not made (a
/// Delaunay triangulation of nodes jittered by 0.4 has at most about 11).
pub const MAX_DEGREE: usize = 16;

/// The irregular lattice's tables, in the run's word memory (f32 and i32 stored as bits).
#[derive(Clone, Copy, PartialEq, Eq)]
pub struct Mesh<'a> {
    /// Per node: x, y in 1/UNIT.
    position: &'a [u32],
    /// Per node: its Voronoi area B (f32).
    area: &'a [u32],
    /// Per spring: origin and other node (NONE, NONE where the slot is empty).
    ends: &'a [u32],
    /// Per spring: unit vector e from origin to other, rest length l0, face, stiffness k.
    shape: &'a [u32],
    /// Per spring: the cell to its left and to its right (cell·4 + side) or NONE.
    sides_of: &'a [u32],
    /// Per cell: three corners (counter-clockwise) then three sides (side k joins corner k
    /// to k + 1); NONE where the slot is empty.
    cells: &'a [u32],
    /// Per node n: its springs are `star[offsets[n]..offsets[n + 1]]`, bit 31 set where the
    /// spring arrives at n.
    offsets: &'a [u32],
    star: &'a [u32],
}

impl core::fmt::Debug for Mesh<'_> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("Mesh").field("nodes", &self.area.len()).field("springs", &(self.ends.len() / 2)).finish()
    }
}

/// Words the tables of an irregular lattice of `nodes` nodes take.
pub const fn words_for(nodes: u128) -> u128 {
    let (springs, cells) = (3 * nodes, 2 * nodes);
    nodes * 4 + 1 + springs * (2 + SHAPE as u128 + 2 + 2) + cells * 6
}

impl<'a> Mesh<'a> {
    /// Node `node`'s position, element sizes.
    pub fn position(&self, node: usize) -> [f32; 2] {
        let p = [self.position[2 * node] as i32, self.position[2 * node + 1] as i32];
        [p[0] as f32 / UNIT as f32, p[1] as f32 / UNIT as f32]
    }

    /// Node `node`'s Voronoi area B, element sizes squared.
    pub fn area(&self, node: usize) -> f32 {
        f32::from_bits(self.area[node])
    }

    /// The nodes of `spring`, if its slot is used.
    pub fn ends(&self, spring: usize) -> Option<(usize, usize)> {
        let (a, b) = (self.ends[2 * spring], self.ends[2 * spring + 1]);
        (a != NONE).then_some((a as usize, b as usize))
    }

    fn shape(&self, spring: usize, k: usize) -> f32 {
        f32::from_bits(self.shape[SHAPE * spring + k])
    }

    /// Unit vector from the spring's origin to its other node.
    pub fn direction(&self, spring: usize) -> [f32; 2] {
        [self.shape(spring, 0), self.shape(spring, 1)]
    }

    /// Rest length l0, element sizes.
    pub fn rest_length(&self, spring: usize) -> f32 {
        self.shape(spring, 2)
    }

    /// The face the spring crosses (its dual Voronoi edge), element sizes.
    pub fn face(&self, spring: usize) -> f32 {
        self.shape(spring, 3)
    }

    /// The spring's constant k = face/l0 (times the stiffness anisotropy), units of E·H.
    pub fn stiffness(&self, spring: usize) -> f32 {
        self.shape(spring, 4)
    }

    /// The cells on either side of a spring (left first), as [`Lattice::cells_of_spring`].
    pub fn cells_of_spring(&self, spring: usize) -> [Option<(usize, usize)>; 2] {
        [0, 1].map(|k| {
            let v = self.sides_of[2 * spring + k];
            (v != NONE).then_some(((v >> 2) as usize, (v & 3) as usize))
        })
    }

    /// Corners and sides of a cell, if its slot is used.
    pub fn cell(&self, cell: usize) -> Option<([u32; 3], [u32; 3])> {
        let c = &self.cells[6 * cell..6 * cell + 6];
        (c[0] != NONE).then_some(([c[0], c[1], c[2]], [c[3], c[4], c[5]]))
    }

    /// Calls `visit(spring, other, sign)` for each spring at `node` (sign −1 where it arrives).
    #[inline(always)]
    pub fn for_each_spring_at(&self, node: usize, mut visit: impl FnMut(usize, usize, f32)) {
        for &entry in &self.star[self.offsets[node] as usize..self.offsets[node + 1] as usize] {
            let spring = (entry & !(1 << 31)) as usize;
            let incoming = entry >> 31 == 1;
            let other = self.ends[2 * spring + usize::from(!incoming)] as usize;
            visit(spring, other, if incoming { -1.0 } else { 1.0 });
        }
    }
}

/// The construction's mutable state.
struct Builder<'w, 's> {
    columns: usize,
    periodic: bool,
    /// The period in 1/UNIT (x, y).
    period: [i64; 2],
    position: &'w mut [u32],
    ends: &'w mut [u32],
    sides_of: &'w mut [u32],
    cells: &'w mut [u32],
    scratch: Scratch<'s>,
    /// Springs waiting in `scratch.pending`.
    pending_len: usize,
}

/// Twice the signed area of a, b, c: > 0 when counter-clockwise.
fn orient(a: [i64; 2], b: [i64; 2], c: [i64; 2]) -> i128 {
    let (bx, by, cx, cy) = (b[0] - a[0], b[1] - a[1], c[0] - a[0], c[1] - a[1]);
    i128::from(bx) * i128::from(cy) - i128::from(by) * i128::from(cx)
}

/// > 0 when d lies inside the circle through the counter-clockwise a, b, c (exact).
fn in_circle(a: [i64; 2], b: [i64; 2], c: [i64; 2], d: [i64; 2]) -> i128 {
    let rel = |p: [i64; 2]| [i128::from(p[0] - d[0]), i128::from(p[1] - d[1])];
    let (a, b, c) = (rel(a), rel(b), rel(c));
    let lift = |p: [i128; 2]| p[0] * p[0] + p[1] * p[1];
    lift(a) * (b[0] * c[1] - c[0] * b[1])
        + lift(b) * (c[0] * a[1] - a[0] * c[1])
        + lift(c) * (a[0] * b[1] - b[0] * a[1])
}

impl Builder<'_, '_> {
    fn position(&self, node: u32) -> [i64; 2] {
        let n = node as usize;
        [i64::from(self.position[2 * n] as i32), i64::from(self.position[2 * n + 1] as i32)]
    }

    /// The image of `p` nearest `from` (the torus's periods), or `p` on an open lattice.
    fn near(&self, from: [i64; 2], p: [i64; 2]) -> [i64; 2] {
        if !self.periodic {
            return p;
        }
        let wrap = |d: i64, period: i64| (d + period / 2).rem_euclid(period) - period / 2;
        [from[0] + wrap(p[0] - from[0], self.period[0]), from[1] + wrap(p[1] - from[1], self.period[1])]
    }

    fn corners(&self, cell: usize) -> [u32; 3] {
        [self.cells[6 * cell], self.cells[6 * cell + 1], self.cells[6 * cell + 2]]
    }

    fn side(&self, cell: usize, k: usize) -> u32 {
        self.cells[6 * cell + 3 + k]
    }

    /// The cell across side `k` of `cell`, or NONE.
    fn across(&self, cell: usize, k: usize) -> u32 {
        let s = self.side(cell, k) as usize;
        let [l, r] = [self.sides_of[2 * s], self.sides_of[2 * s + 1]];
        let here = (cell as u32) << 2 | k as u32;
        let other = if l == here { r } else { l };
        if other == NONE { NONE } else { other >> 2 }
    }

    /// The cells around `node`, in order; `None` if more than MAX_STAR.
    fn star(&self, node: u32, out: &mut [u32; MAX_STAR]) -> Option<usize> {
        let start = self.scratch.node_cell[node as usize];
        let corner_of = |cell: u32| self.corners(cell as usize).iter().position(|&c| c == node).unwrap_or(0);
        let mut n = 0;
        // Counter-clockwise: across the side that arrives at the node (k + 2).
        let mut cell = start;
        let mut closed = false;
        loop {
            if n == MAX_STAR {
                return None;
            }
            out[n] = cell;
            n += 1;
            let next = self.across(cell as usize, (corner_of(cell) + 2) % 3);
            if next == NONE {
                break;
            }
            if next == start {
                closed = true;
                break;
            }
            cell = next;
        }
        if !closed {
            // An open edge: the rest lies clockwise from the start (across side k).
            let mut cell = self.across(start as usize, corner_of(start));
            while cell != NONE {
                if n == MAX_STAR {
                    return None;
                }
                out[n] = cell;
                n += 1;
                cell = self.across(cell as usize, corner_of(cell));
            }
        }
        Some(n)
    }

    /// Whether every cell around `node` keeps its orientation with the node at `to`.
    fn can_move(&self, node: u32, to: [i64; 2], star: &[u32]) -> bool {
        star.iter().all(|&cell| {
            let c = self.corners(cell as usize);
            let k = c.iter().position(|&x| x == node).unwrap_or(0);
            let b = self.near(to, self.position(c[(k + 1) % 3]));
            let d = self.near(to, self.position(c[(k + 2) % 3]));
            orient(to, b, d) > 0
        })
    }

    fn push(&mut self, spring: u32) {
        if self.scratch.queued[spring as usize] == 0 {
            self.scratch.queued[spring as usize] = 1;
            self.scratch.pending[self.pending_len] = spring;
            self.pending_len += 1;
        }
    }

    /// Lawson's flips until no pending spring fails the in-circle test.
    fn flip_pending(&mut self) {
        while self.pending_len > 0 {
            self.pending_len -= 1;
            let s = self.scratch.pending[self.pending_len] as usize;
            self.scratch.queued[s] = 0;
            self.flip_if_not_delaunay(s);
        }
    }

    /// Flips spring `s` (the diagonal of its two cells) when the node across it lies inside
    /// the circle through the other three.
    fn flip_if_not_delaunay(&mut self, s: usize) {
        let (left, right) = (self.sides_of[2 * s], self.sides_of[2 * s + 1]);
        if left == NONE || right == NONE {
            return; // the plate's border
        }
        let (l, kl) = ((left >> 2) as usize, (left & 3) as usize);
        let (r, kr) = ((right >> 2) as usize, (right & 3) as usize);
        let lc = self.corners(l);
        let rc = self.corners(r);
        let (a, b, c, d) = (lc[kl], lc[(kl + 1) % 3], lc[(kl + 2) % 3], rc[(kr + 2) % 3]);
        if c == d
            || self.scratch.degree[c as usize] as usize >= MAX_DEGREE
            || self.scratch.degree[d as usize] as usize >= MAX_DEGREE
        {
            return;
        }
        let pa = self.position(a);
        let (pb, pc, pd) =
            (self.near(pa, self.position(b)), self.near(pa, self.position(c)), self.near(pa, self.position(d)));
        if in_circle(pa, pb, pc, pd) <= 0 {
            return;
        }
        let (s_bc, s_ca) = (self.side(l, (kl + 1) % 3), self.side(l, (kl + 2) % 3));
        let (s_ad, s_db) = (self.side(r, (kr + 1) % 3), self.side(r, (kr + 2) % 3));
        // l becomes (c, a, d), r becomes (d, b, c); the spring runs c → d.
        self.cells[6 * l..6 * l + 6].copy_from_slice(&[c, a, d, s_ca, s_ad, s as u32]);
        self.cells[6 * r..6 * r + 6].copy_from_slice(&[d, b, c, s_db, s_bc, s as u32]);
        self.ends[2 * s] = c;
        self.ends[2 * s + 1] = d;
        self.sides_of[2 * s] = (r as u32) << 2 | 2;
        self.sides_of[2 * s + 1] = (l as u32) << 2 | 2;
        for (spring, cell, k, from) in [(s_ca, l, 0, c), (s_ad, l, 1, a), (s_db, r, 0, d), (s_bc, r, 1, b)] {
            let entry = usize::from(self.ends[2 * spring as usize] != from);
            self.sides_of[2 * spring as usize + entry] = (cell as u32) << 2 | k;
            self.push(spring);
        }
        self.scratch.degree[a as usize] -= 1;
        self.scratch.degree[b as usize] -= 1;
        self.scratch.degree[c as usize] += 1;
        self.scratch.degree[d as usize] += 1;
        self.scratch.node_cell[a as usize] = l as u32;
        self.scratch.node_cell[c as usize] = l as u32;
        self.scratch.node_cell[b as usize] = r as u32;
        self.scratch.node_cell[d as usize] = r as u32;
    }

    /// Moves `node` towards `target`, keeping the triangulation valid and Delaunay.
    fn move_node(&mut self, node: u32, target: [i64; 2]) {
        let mut star = [0u32; MAX_STAR];
        for _ in 0..8 {
            let at = self.position(node);
            let delta = [target[0] - at[0], target[1] - at[1]];
            if delta == [0, 0] {
                return;
            }
            let Some(n) = self.star(node, &mut star) else { return };
            let mut step = delta;
            while step != [0, 0] && !self.can_move(node, [at[0] + step[0], at[1] + step[1]], &star[..n]) {
                step = [step[0] / 2, step[1] / 2];
            }
            if step == [0, 0] {
                return;
            }
            let to = [at[0] + step[0], at[1] + step[1]];
            let wrapped =
                if self.periodic { [to[0].rem_euclid(self.period[0]), to[1].rem_euclid(self.period[1])] } else { to };
            self.position[2 * node as usize] = wrapped[0] as i32 as u32;
            self.position[2 * node as usize + 1] = wrapped[1] as i32 as u32;
            for &cell in &star[..n] {
                for k in 0..3 {
                    let s = self.side(cell as usize, k);
                    self.push(s);
                }
            }
            self.flip_pending();
        }
    }
}

/// Scratch the construction borrows from the run's other arrays.
pub(super) struct Scratch<'s> {
    /// Per node: a cell it is a corner of.
    pub node_cell: &'s mut [u32],
    /// Springs waiting for the in-circle test, and a flag per spring.
    pub pending: &'s mut [u32],
    pub queued: &'s mut [u32],
    /// Springs per node.
    pub degree: &'s mut [u32],
}

/// The mesh's tables, carved from the run's word memory (at least [`words_for`] its nodes).
struct Tables<'w> {
    position: &'w mut [u32],
    area: &'w mut [u32],
    ends: &'w mut [u32],
    shape: &'w mut [u32],
    sides_of: &'w mut [u32],
    cells: &'w mut [u32],
    offsets: &'w mut [u32],
    star: &'w mut [u32],
}

impl<'w> Tables<'w> {
    fn carve(words: &'w mut [u32], nodes: usize) -> Self {
        let (springs, cells) = (3 * nodes, 2 * nodes);
        let mut words = words;
        Tables {
            position: take(&mut words, 2 * nodes),
            area: take(&mut words, nodes),
            ends: take(&mut words, 2 * springs),
            shape: take(&mut words, SHAPE * springs),
            sides_of: take(&mut words, 2 * springs),
            cells: take(&mut words, 6 * cells),
            offsets: take(&mut words, nodes + 1),
            star: take(&mut words, 2 * springs),
        }
    }
}

impl<'a> Mesh<'a> {
    /// The built mesh of `nodes` nodes in `words` (as [`Construction`] left them).
    pub(super) fn of(words: &'a [u32], nodes: usize) -> Self {
        let (springs, cells) = (3 * nodes, 2 * nodes);
        let mut words = words;
        let mut cut = |n: usize| {
            let (head, tail) = words.split_at(n);
            words = tail;
            head
        };
        Mesh {
            position: cut(2 * nodes),
            area: cut(nodes),
            ends: cut(2 * springs),
            shape: cut(SHAPE * springs),
            sides_of: cut(2 * springs),
            cells: cut(6 * cells),
            offsets: cut(nodes + 1),
            star: cut(2 * springs),
        }
    }
}

/// The passes of the construction, in order; each goes item by item (a node, a spring, a
/// cell), so that it can stop between items and go on where it stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Pass {
    /// The triangular lattice's sites (per node).
    Sites,
    /// Its springs' nodes and cells (per spring).
    Springs,
    /// No node has a cell yet (per cell).
    Unmarked,
    /// Its cells, and a cell of each node (per cell).
    Cells,
    /// No spring queued, no node with a spring (per spring).
    Cleared,
    /// The springs at each node (per spring).
    Degrees,
    /// Each node moved to its jittered place, with Lawson's flips (per node).
    Jitter,
    /// The Voronoi areas cleared (per node).
    Areas,
    /// Each spring's geometry, and its share of its nodes' areas (per spring).
    Shapes,
    /// The star offsets cleared (per node, and one more).
    Offsets,
    /// The springs at each node counted (per spring).
    Counts,
    /// The counts summed into offsets (per node).
    Sums,
    /// Each spring entered in its nodes' stars (per spring).
    Stars,
    /// The offsets moved back to each star's start, last node first (per node).
    Starts,
}

/// Work units one jittered node counts: the most springs at a node. Its move looks at the
/// cells around it, up to eight times, and Lawson's flips around it.
pub(super) const JITTER_PIECE: u64 = MAX_DEGREE as u64;

/// The construction of the irregular lattice under way: the pass and its next item.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Construction {
    pass: Pass,
    item: usize,
}

impl Construction {
    /// The construction before its first item.
    pub(super) const fn new() -> Self {
        Construction { pass: Pass::Sites, item: 0 }
    }

    /// Builds the irregular lattice of `params` (shape `shape`) in `words` (at least
    /// [`words_for`] of its nodes), item by item, until the work reaches `budget` (at least
    /// one item) or the mesh is done; `rng` is the jitter's stream ([`Stream::LatticeJitter`]),
    /// kept between calls. Returns the work (one unit per item, [`JITTER_PIECE`] per jittered
    /// node) and whether the mesh is done: [`Mesh::of`] then reads it. Every item is the same
    /// whatever the cuts, so the mesh does not depend on the budgets.
    pub(super) fn advance(
        &mut self,
        shape: &Lattice<'_>,
        params: &MudParams,
        words: &mut [u32],
        scratch: Scratch<'_>,
        rng: &mut Rng,
        budget: u64,
    ) -> (u64, bool) {
        let hex = Lattice { topology: Topology::Hexagonal, mesh: None, ..*shape };
        let (nodes, springs, cells) = (hex.node_count(), hex.spring_count(), hex.cell_count());
        let columns = hex.columns as usize;
        let t = Tables::carve(words, nodes);
        let periodic = hex.boundary == Boundary::Periodic;
        let mut builder = Builder {
            columns,
            periodic,
            period: [hex.columns as i64 * UNIT, hex.rows as i64 * PITCH],
            position: t.position,
            ends: t.ends,
            sides_of: t.sides_of,
            cells: t.cells,
            scratch,
            pending_len: 0,
        };
        let (area, shape_words, offsets, star) = (t.area, t.shape, t.offsets, t.star);
        let mut work = 0u64;
        loop {
            let (pass, from) = (self.pass, self.item);
            let len = match pass {
                Pass::Sites | Pass::Jitter | Pass::Areas | Pass::Sums | Pass::Starts => nodes,
                Pass::Offsets => nodes + 1,
                Pass::Unmarked | Pass::Cells => cells,
                _ => springs,
            };
            let cost = if pass == Pass::Jitter { JITTER_PIECE } else { 1 };
            // Items from..end: as many as the budget left takes (at least one).
            let items = usize::try_from(budget.saturating_sub(work).div_ceil(cost).max(1)).unwrap_or(usize::MAX);
            let end = from.saturating_add(items).min(len);
            let b = &mut builder;
            match pass {
                // The triangular lattice: sites, springs and cells as the hexagonal topology
                // has them.
                Pass::Sites => {
                    for node in from..end {
                        let (i, j) = ((node % columns) as i64, (node / columns) as i64);
                        b.position[2 * node] = (i * UNIT + (j % 2) * UNIT / 2) as i32 as u32;
                        b.position[2 * node + 1] = (j * PITCH) as i32 as u32;
                    }
                }
                Pass::Springs => {
                    for spring in from..end {
                        let (a, c) = hex.spring_nodes(spring).map_or((NONE, NONE), |(a, c)| (a as u32, c as u32));
                        b.ends[2 * spring] = a;
                        b.ends[2 * spring + 1] = c;
                        for (k, side) in hex.cells_of_spring(spring).into_iter().enumerate() {
                            b.sides_of[2 * spring + k] = side.map_or(NONE, |(c, side)| (c as u32) << 2 | side as u32);
                        }
                    }
                }
                Pass::Unmarked => b.scratch.node_cell[from..end].fill(NONE),
                Pass::Cells => {
                    for cell in from..end {
                        let words = &mut b.cells[6 * cell..6 * cell + 6];
                        match hex.cell(cell) {
                            Some(c) => {
                                words.copy_from_slice(&[
                                    c.nodes[0], c.nodes[1], c.nodes[2], c.sides[0], c.sides[1], c.sides[2],
                                ]);
                                for &n in &c.nodes[..3] {
                                    b.scratch.node_cell[n as usize] = cell as u32;
                                }
                            }
                            None => words.fill(NONE),
                        }
                    }
                }
                Pass::Cleared => {
                    b.scratch.queued[from..end].fill(0);
                    b.scratch.degree[from..end].fill(0);
                }
                Pass::Degrees => {
                    for spring in from..end {
                        if b.ends[2 * spring] != NONE {
                            b.scratch.degree[b.ends[2 * spring] as usize] += 1;
                            b.scratch.degree[b.ends[2 * spring + 1] as usize] += 1;
                        }
                    }
                }
                // Jitter node by node.
                Pass::Jitter => {
                    let radius = JITTER * UNIT as f32;
                    for node in from..end {
                        let r = radius * crate::scalar::sqrtf(rng.uniform_f32());
                        let angle = 2.0 * core::f32::consts::PI * rng.uniform_f32();
                        let (i, j) = ((node % b.columns) as i64, (node / b.columns) as i64);
                        let site = [i * UNIT + (j % 2) * UNIT / 2, j * PITCH];
                        let jitter =
                            [libm::roundf(r * libm::cosf(angle)) as i64, libm::roundf(r * libm::sinf(angle)) as i64];
                        b.move_node(node as u32, [site[0] + jitter[0], site[1] + jitter[1]]);
                    }
                }
                Pass::Areas => area[from..end].fill(0.0f32.to_bits()),
                // Geometry: e, l0, face, k per spring; the Voronoi area per node.
                Pass::Shapes => {
                    let mesh = Mesh {
                        position: &*b.position,
                        area: &[],
                        ends: &*b.ends,
                        shape: &[],
                        sides_of: &*b.sides_of,
                        cells: &*b.cells,
                        offsets: &[],
                        star: &[],
                    };
                    for spring in from..end {
                        let words = &mut shape_words[SHAPE * spring..SHAPE * spring + SHAPE];
                        spring_shape(&mesh, shape, params, spring, words, area);
                    }
                }
                // Each node's springs, in spring order.
                Pass::Offsets => offsets[from..end].fill(0),
                Pass::Counts => {
                    for spring in from..end {
                        if b.ends[2 * spring] != NONE {
                            offsets[b.ends[2 * spring] as usize + 1] += 1;
                            offsets[b.ends[2 * spring + 1] as usize + 1] += 1;
                        }
                    }
                }
                Pass::Sums => {
                    for n in from..end {
                        offsets[n + 1] += offsets[n];
                    }
                }
                // Fill with a running cursor per node kept in `offsets` (offsets[n] moves up,
                // then is moved back).
                Pass::Stars => {
                    for spring in from..end {
                        if b.ends[2 * spring] != NONE {
                            let ends = [b.ends[2 * spring] as usize, b.ends[2 * spring + 1] as usize];
                            for (n, incoming) in [(ends[0], 0u32), (ends[1], 1u32)] {
                                star[offsets[n] as usize] = spring as u32 | incoming << 31;
                                offsets[n] += 1;
                            }
                        }
                    }
                }
                Pass::Starts => {
                    for k in from..end {
                        let n = nodes - k;
                        offsets[n] = offsets[n - 1];
                    }
                    if end == len {
                        offsets[0] = 0;
                    }
                }
            }
            work += (end - from) as u64 * cost;
            self.item = end;
            if end == len {
                let next = match pass {
                    Pass::Sites => Pass::Springs,
                    Pass::Springs => Pass::Unmarked,
                    Pass::Unmarked => Pass::Cells,
                    Pass::Cells => Pass::Cleared,
                    Pass::Cleared => Pass::Degrees,
                    Pass::Degrees => Pass::Jitter,
                    Pass::Jitter => Pass::Areas,
                    Pass::Areas => Pass::Shapes,
                    Pass::Shapes => Pass::Offsets,
                    Pass::Offsets => Pass::Counts,
                    Pass::Counts => Pass::Sums,
                    Pass::Sums => Pass::Stars,
                    Pass::Stars => Pass::Starts,
                    Pass::Starts => return (work, true),
                };
                *self = Construction { pass: next, item: 0 };
            }
            if work >= budget {
                return (work, false);
            }
        }
    }
}

/// Spring `spring`'s geometry into `words` (e, l0, face, k; zero where its slot is empty),
/// and its share l0·face/4 added to each of its nodes' areas.
fn spring_shape(
    mesh: &Mesh<'_>,
    shape: &Lattice<'_>,
    params: &MudParams,
    spring: usize,
    words: &mut [u32],
    area: &mut [u32],
) {
    let Some((a, b)) = mesh.ends(spring) else {
        words.fill(0);
        return;
    };
    let pa = mesh.position(a);
    let pb = shape.nearest_image(pa, mesh.position(b));
    let d = [pb[0] - pa[0], pb[1] - pa[1]];
    let l0 = crate::scalar::sqrtf(d[0] * d[0] + d[1] * d[1]);
    let e = [d[0] / l0, d[1] / l0];
    let middle = [(pa[0] + pb[0]) * 0.5, (pa[1] + pb[1]) * 0.5];
    // The circumcentre of each side's cell, measured along the spring's left normal.
    let normal = [-e[1], e[0]];
    let mut reach = [0.0f32; 2];
    for (k, side) in mesh.cells_of_spring(spring).into_iter().enumerate() {
        let Some((cell, _)) = side else { continue };
        let (corners, _) = mesh.cell(cell).unwrap_or(([a as u32; 3], [0; 3]));
        let third = corners.into_iter().find(|&n| n as usize != a && n as usize != b).unwrap_or(a as u32);
        let pc = shape.nearest_image(pa, mesh.position(third as usize));
        let centre = circumcentre(pa, pb, pc);
        let along = (centre[0] - middle[0]) * normal[0] + (centre[1] - middle[1]) * normal[1];
        reach[k] = if k == 0 { along } else { -along };
    }
    // Two cells: the whole Voronoi edge; at an open edge, the part inside the plate.
    let face = (reach[0] + reach[1]).max(FACE_FLOOR);
    let k = face / l0 * anisotropy(e, params.anisotropy_direction, params.stiffness_anisotropy_ratio);
    words.copy_from_slice(&[e[0].to_bits(), e[1].to_bits(), l0.to_bits(), face.to_bits(), k.to_bits()]);
    for n in [a, b] {
        area[n] = (f32::from_bits(area[n]) + l0 * face * 0.25).to_bits();
    }
}

/// The centre of the circle through a, b, c.
fn circumcentre(a: [f32; 2], b: [f32; 2], c: [f32; 2]) -> [f32; 2] {
    let (bx, by, cx, cy) = (b[0] - a[0], b[1] - a[1], c[0] - a[0], c[1] - a[1]);
    let d = 2.0 * (bx * cy - by * cx);
    let (b2, c2) = (bx * bx + by * by, cx * cx + cy * cy);
    [a[0] + (cy * b2 - by * c2) / d, a[1] + (bx * c2 - cx * b2) / d]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mud::{Mud, MudBuffers, MudParams};
    extern crate std;
    use std::vec;
    use std::vec::Vec;

    fn with_mesh(boundary: Boundary, columns: u32, rows: u32, seed: u64, check: impl FnOnce(&Lattice<'_>)) {
        let p = MudParams { topology: Topology::Irregular, boundary, columns, rows, seed, ..MudParams::default() };
        let m = p.memory().unwrap();
        let (mut s, mut w) = (vec![0.0f32; m.scalars], vec![0u32; m.words]);
        let mut mud = Mud::new(&p, MudBuffers { scalars: &mut s, words: &mut w }).unwrap();
        // The first step builds the mesh.
        assert!(mud.lattice().mesh().is_none());
        mud.run().unwrap();
        check(mud.lattice());
    }

    fn twice_area(r: &[[f32; 2]]) -> f32 {
        (0..r.len()).map(|k| r[k][0] * r[(k + 1) % r.len()][1] - r[(k + 1) % r.len()][0] * r[k][1]).sum()
    }

    #[test]
    fn the_mesh_is_a_delaunay_triangulation_of_the_jittered_nodes() {
        for (boundary, columns, rows) in
            [(Boundary::Periodic, 16, 16), (Boundary::Open, 13, 10), (Boundary::Periodic, 9, 8)]
        {
            for seed in 1..4 {
                with_mesh(boundary, columns, rows, seed, |l| {
                    let m = l.mesh().unwrap();
                    let mut flipped_from_lattice = 0;
                    let mut area = 0.0f64;
                    for cell in 0..l.cell_count() {
                        let Some(c) = l.cell(cell) else { continue };
                        let t = twice_area(&c.reference[..3]);
                        assert!(t > 0.0, "cell {cell} folded over: {t}");
                        area += f64::from(t) / 2.0;
                        for k in 0..3 {
                            let s = c.sides[k] as usize;
                            let (a, b) = m.ends(s).unwrap();
                            let side = [c.nodes[k] as usize, c.nodes[(k + 1) % 3] as usize];
                            assert!(side == [a, b] || side == [b, a]);
                            let expected = if side == [a, b] { 0 } else { 1 };
                            assert_eq!(m.cells_of_spring(s)[expected], Some((cell, k)), "spring {s} of cell {cell}");
                        }
                    }
                    // No node lies inside the circumcircle of a cell it does not belong to:
                    // exact, against the integer positions, for the nodes near each cell.
                    let int = |n: usize| {
                        let p = m.position(n);
                        [(p[0] * UNIT as f32) as i64, (p[1] * UNIT as f32) as i64]
                    };
                    let [w, h] = l.extent();
                    for cell in 0..l.cell_count() {
                        let Some(c) = l.cell(cell) else { continue };
                        let corner = |k: usize| {
                            [(c.reference[k][0] * UNIT as f32) as i64, (c.reference[k][1] * UNIT as f32) as i64]
                        };
                        for n in 0..l.node_count() {
                            if c.nodes[..3].contains(&(n as u32)) {
                                continue;
                            }
                            let mut q = int(n);
                            if boundary == Boundary::Periodic {
                                let at = corner(0);
                                let wrap = |d: i64, period: f32| {
                                    let period = (period * UNIT as f32) as i64;
                                    (d + period / 2).rem_euclid(period) - period / 2
                                };
                                q = [at[0] + wrap(q[0] - at[0], w), at[1] + wrap(q[1] - at[1], h)];
                            } else if m.cells_of_spring(c.sides[0] as usize).contains(&None)
                                || m.cells_of_spring(c.sides[1] as usize).contains(&None)
                                || m.cells_of_spring(c.sides[2] as usize).contains(&None)
                            {
                                continue; // the open border is kept as it is
                            }
                            assert!(in_circle(corner(0), corner(1), corner(2), q) <= 0, "node {n} in cell {cell}");
                        }
                        let sites = c.nodes[..3].iter().map(|&n| n as usize).collect::<Vec<_>>();
                        let hex = Lattice::new(Topology::Hexagonal, boundary, l.columns, l.rows).cell(cell);
                        if hex.map(|h| h.nodes[..3].iter().map(|&n| n as usize).collect::<Vec<_>>()) != Some(sites) {
                            flipped_from_lattice += 1;
                        }
                    }
                    let mut moved = 0.0f32;
                    for n in 0..l.node_count() {
                        let p = m.position(n);
                        let site = Lattice::new(Topology::Hexagonal, boundary, l.columns, l.rows).reference(n);
                        moved += libm::hypotf(p[0] - site[0], p[1] - site[1]);
                    }
                    if boundary == Boundary::Open {
                        // Uniform in a disk of radius 0.4: a mean distance of 0.27.
                        let mean = moved / l.node_count() as f32;
                        assert!((mean - 2.0 / 3.0 * JITTER).abs() < 0.04, "{mean}");
                    }
                    // The jitter changes the triangulation (it is not the lattice's).
                    assert!(flipped_from_lattice > l.cell_count() / 20, "{flipped_from_lattice}");
                    let voronoi: f64 = (0..l.node_count()).map(|n| f64::from(m.area(n))).sum();
                    if boundary == Boundary::Periodic {
                        assert!((area - f64::from(w * h)).abs() < 1e-2, "cells {area} vs {}", w * h);
                        assert!((voronoi - f64::from(w * h)).abs() < 0.01 * f64::from(w * h), "{voronoi}");
                    }
                    for s in 0..l.spring_count() {
                        let Some((a, b)) = m.ends(s) else { continue };
                        assert!(m.rest_length(s) > 0.15 && m.rest_length(s) < 2.5, "{s}: {}", m.rest_length(s));
                        assert!(m.face(s) >= FACE_FLOOR && m.stiffness(s) > 0.0);
                        let mut seen = 0;
                        l.for_each_spring_at(a, |t, other, _, sign| {
                            if t == s {
                                assert_eq!((other, sign), (b, 1.0));
                                seen += 1;
                            }
                        });
                        assert_eq!(seen, 1);
                    }
                });
            }
        }
    }
}
