//! The node lattice (paper Fig. 4) in lattice units (the element size W is 1): which springs
//! join which nodes, where the deep-layer nodes sit, and the mesh cells whose broken sides
//! are traced into cracks (Fig. 5).
//!
//! Node (i, j) is index `j·columns + i`. Square lattices sit at (i, j) with springs to the
//! right and up. Hexagonal elements form a triangular lattice of nodes at
//! (i + ½·(j mod 2), j·√3/2) with springs to the right, up-right and up-left. Springs are
//! stored direction by direction: spring `d·nodes + node` leaves `node` in direction `d`
//! (so a row's springs of one direction are contiguous); at an open edge it is absent.

use super::irregular::{self, Mesh};
use super::params::{Boundary, Topology};

/// √3/2: the row pitch of the triangular lattice.
pub const ROW_PITCH_HEX: f32 = 0.866_025_4;

/// The shape of a lattice: topology, edges and size, and for the irregular topology the
/// tables of its mesh (built with the run: the irregular lattice).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Lattice<'a> {
    /// Square or hexagonal elements.
    pub topology: Topology,
    /// Open or periodic edges.
    pub boundary: Boundary,
    /// Nodes per row.
    pub columns: u32,
    /// Rows of nodes.
    pub rows: u32,
    /// The irregular lattice's mesh; `None` for the regular topologies (and for an irregular
    /// lattice's shape before its run builds it).
    pub(crate) mesh: Option<Mesh<'a>>,
}

/// A mesh cell (a square, or a triangle of the hexagonal model) for crack tracing: its
/// corners (node and the unwrapped lattice offset of the corner from the cell's base node)
/// and its sides (springs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cell {
    /// Corner nodes; only the first `corners` entries are used.
    pub nodes: [u32; 4],
    /// Number of corners and sides (3 or 4).
    pub corners: usize,
    /// The spring of each side; side k joins corner k and corner k + 1.
    pub sides: [u32; 4],
    /// Unwrapped reference position of each corner, in lattice units.
    pub reference: [[f32; 2]; 4],
}

impl<'a> Lattice<'a> {
    /// A square or hexagonal lattice, or an irregular one's shape (before its run builds its mesh).
    pub const fn new(topology: Topology, boundary: Boundary, columns: u32, rows: u32) -> Self {
        Lattice { topology, boundary, columns, rows, mesh: None }
    }

    /// The irregular lattice's mesh, if this is one and its run has built it.
    pub fn mesh(&self) -> Option<&Mesh<'a>> {
        self.mesh.as_ref()
    }

    /// Spring slots per node: 2 (square) or 3 (hexagonal, irregular).
    pub const fn directions(&self) -> usize {
        match self.topology {
            Topology::Square => 2,
            Topology::Hexagonal | Topology::Irregular => 3,
        }
    }

    /// Number of nodes.
    pub const fn node_count(&self) -> usize {
        self.columns as usize * self.rows as usize
    }

    /// Number of spring slots (absent springs at open edges included).
    pub const fn spring_count(&self) -> usize {
        self.node_count() * self.directions()
    }

    /// Mesh cells per node: 1 square or 2 triangles.
    pub const fn cells_per_node(&self) -> usize {
        match self.topology {
            Topology::Square => 1,
            Topology::Hexagonal | Topology::Irregular => 2,
        }
    }

    /// The spacing between rows (of the irregular lattice's sites: √3/2 to 1/1024).
    pub const fn row_pitch(&self) -> f32 {
        match self.topology {
            Topology::Square => 1.0,
            Topology::Hexagonal => ROW_PITCH_HEX,
            Topology::Irregular => irregular::PITCH as f32 / irregular::UNIT as f32,
        }
    }

    /// Width and height of the lattice's domain (one period when periodic), lattice units.
    pub fn extent(&self) -> [f32; 2] {
        [self.columns as f32, self.rows as f32 * self.row_pitch()]
    }

    /// The element's area in the plane (B/W²): 1 or √3/2 (the irregular lattice's mean).
    pub const fn element_area(&self) -> f32 {
        self.row_pitch()
    }

    /// Length of the element face a spring crosses (per W): 1 or 1/√3 (the irregular
    /// lattice's springs each have their own, [`Lattice::face`]).
    pub const fn face_length(&self) -> f32 {
        match self.topology {
            Topology::Square => 1.0,
            Topology::Hexagonal | Topology::Irregular => 0.577_350_26,
        }
    }

    /// Unit vector of direction `d` of a regular lattice (the irregular lattice's springs
    /// each have their own, [`Lattice::spring_vector`]).
    pub const fn direction_vector(&self, d: usize) -> [f32; 2] {
        match (self.topology, d) {
            (Topology::Square, 0) => [1.0, 0.0],
            (Topology::Square, _) => [0.0, 1.0],
            (_, 0) => [1.0, 0.0],
            (_, 1) => [0.5, ROW_PITCH_HEX],
            (_, _) => [-0.5, ROW_PITCH_HEX],
        }
    }

    /// Unit vector of `spring`, from its origin towards the node it reaches (deep layer).
    #[cfg_attr(target_pointer_width = "64", inline(always))]
    pub fn spring_vector(&self, spring: usize) -> [f32; 2] {
        match &self.mesh {
            Some(m) => m.direction(spring),
            None => self.direction_vector(self.spring_origin(spring).1),
        }
    }

    /// Rest length l0 of `spring`, element sizes (1 on the regular lattices).
    pub fn rest_length(&self, spring: usize) -> f32 {
        self.mesh.as_ref().map_or(1.0, |m| m.rest_length(spring))
    }

    /// The element face `spring` crosses, element sizes.
    pub fn face(&self, spring: usize) -> f32 {
        self.mesh.as_ref().map_or(self.face_length(), |m| m.face(spring))
    }

    /// The periodic image of `p` nearest `from` (`p` itself on an open lattice).
    pub fn nearest_image(&self, from: [f32; 2], p: [f32; 2]) -> [f32; 2] {
        if self.boundary == Boundary::Open {
            return p;
        }
        let [w, h] = self.extent();
        let wrap = |d: f32, period: f32| d - period * libm::roundf(d / period);
        [from[0] + wrap(p[0] - from[0], w), from[1] + wrap(p[1] - from[1], h)]
    }

    /// Reference (deep-layer) position of a node, lattice units.
    pub fn reference(&self, node: usize) -> [f32; 2] {
        if let Some(m) = &self.mesh {
            return m.position(node);
        }
        self.reference_at(node % self.columns as usize, node / self.columns as usize)
    }

    /// Reference position of the regular lattice's node in column `i`, row `j`.
    fn reference_at(&self, i: usize, j: usize) -> [f32; 2] {
        let shift = if self.topology != Topology::Square && j % 2 == 1 { 0.5 } else { 0.0 };
        [i as f32 + shift, j as f32 * self.row_pitch()]
    }

    /// The node at column `i`, row `j` (possibly outside), wrapped when periodic.
    fn node_at(&self, i: i64, j: i64) -> Option<usize> {
        let (c, r) = (i64::from(self.columns), i64::from(self.rows));
        let (i, j) = match self.boundary {
            Boundary::Periodic => (i.rem_euclid(c), j.rem_euclid(r)),
            Boundary::Open if (0..c).contains(&i) && (0..r).contains(&j) => (i, j),
            Boundary::Open => return None,
        };
        Some((j * c + i) as usize)
    }

    /// The spring leaving `node` in direction `d`.
    pub const fn spring(&self, node: usize, d: usize) -> usize {
        d * self.node_count() + node
    }

    /// The node a spring leaves and its direction.
    pub const fn spring_origin(&self, spring: usize) -> (usize, usize) {
        // The direction by comparisons rather than a division (springs are stored direction
        // by direction; past the last direction the division's answer).
        let n = self.node_count();
        if spring >= 3 * n {
            return (spring % n, spring / n);
        }
        let d = (spring >= n) as usize + (spring >= 2 * n) as usize;
        (spring - d * n, d)
    }

    /// Column and row offset of the neighbour in direction `d` of a node in row `j`.
    pub const fn step(&self, d: usize, j: usize) -> (i64, i64) {
        let odd = (j % 2) as i64;
        match (self.topology, d) {
            (Topology::Square, 0) => (1, 0),
            (Topology::Square, _) => (0, 1),
            (_, 0) => (1, 0),
            (_, 1) => (odd, 1),
            (_, _) => (odd - 1, 1),
        }
    }

    /// The node that spring `d` of `node` reaches, if the spring exists.
    pub fn neighbour(&self, node: usize, d: usize) -> Option<usize> {
        let c = self.columns as usize;
        let (i, j) = (node % c, node / c);
        let (di, dj) = self.step(d, j);
        self.node_at(i as i64 + di, j as i64 + dj)
    }

    /// The node whose spring `d` reaches `node`, if that spring exists.
    pub fn back_neighbour(&self, node: usize, d: usize) -> Option<usize> {
        let c = self.columns as usize;
        let (i, j) = (node % c, node / c);
        // The neighbour is in row j − dj, whose parity decides the column offset.
        let (_, dj) = self.step(d, 0);
        let row = (j as i64 - dj).rem_euclid(i64::from(self.rows)) as usize;
        let (di, _) = self.step(d, row);
        self.node_at(i as i64 - di, j as i64 - dj)
    }

    /// The two nodes of a spring, if it exists.
    pub fn spring_nodes(&self, spring: usize) -> Option<(usize, usize)> {
        if let Some(m) = &self.mesh {
            return m.ends(spring);
        }
        let (node, d) = self.spring_origin(spring);
        self.neighbour(node, d).map(|other| (node, other))
    }

    /// Calls `visit(spring, other_node, direction, sign)` for every existing spring at `node`,
    /// in a fixed order: outgoing springs (sign +1: the spring points away from `node`), then
    /// incoming ones (sign −1).
    /// The irregular lattice's springs come in spring order, each with direction 0.
    #[inline(always)]
    pub fn for_each_spring_at(&self, node: usize, mut visit: impl FnMut(usize, usize, usize, f32)) {
        if let Some(m) = &self.mesh {
            m.for_each_spring_at(node, |spring, other, sign| visit(spring, other, 0, sign));
            return;
        }
        let dirs = self.directions();
        let n = self.node_count();
        let c = self.columns as usize;
        let (i, j) = (node % c, node / c);
        // The springs are listed first and visited in one loop, so `visit` is inlined once.
        let mut list = [(0usize, 0usize, 0usize, 0.0f32); 6];
        let mut count = 0;
        if i >= 1 && i + 1 < c && j >= 1 && j + 1 < self.rows as usize {
            // Interior node: neighbours are fixed offsets (no wrapping, no edges).
            match self.topology {
                Topology::Square => {
                    list[..4].copy_from_slice(&[
                        (node, node + 1, 0, 1.0),
                        (n + node, node + c, 1, 1.0),
                        (node - 1, node - 1, 0, -1.0),
                        (n + node - c, node - c, 1, -1.0),
                    ]);
                    count = 4;
                }
                _ => {
                    let odd = j % 2;
                    let (up_right, up_left) = (node + c + odd, node + c + odd - 1);
                    let (down_left, down_right) = (node - c - (1 - odd), node - c + odd);
                    list = [
                        (node, node + 1, 0, 1.0),
                        (n + node, up_right, 1, 1.0),
                        (2 * n + node, up_left, 2, 1.0),
                        (node - 1, node - 1, 0, -1.0),
                        (n + down_left, down_left, 1, -1.0),
                        (2 * n + down_right, down_right, 2, -1.0),
                    ];
                    count = 6;
                }
            }
        } else {
            for d in 0..dirs {
                if let Some(other) = self.neighbour(node, d) {
                    list[count] = (self.spring(node, d), other, d, 1.0);
                    count += 1;
                }
            }
            for d in 0..dirs {
                if let Some(other) = self.back_neighbour(node, d) {
                    list[count] = (self.spring(other, d), other, d, -1.0);
                    count += 1;
                }
            }
        }
        for &(spring, other, d, sign) in &list[..count] {
            visit(spring, other, d, sign);
        }
    }

    /// The row of a square or hexagonal lattice's node away from its edges (`None` for any
    /// other node, size or topology), found with `reciprocal` ([`Lattice::column_reciprocal`]).
    #[inline(always)]
    pub(crate) fn interior_row(&self, node: usize, reciprocal: u64) -> Option<usize> {
        let c = self.columns as usize;
        if node > u32::MAX as usize || matches!(self.topology, Topology::Irregular) {
            return None;
        }
        // ⌊node/c⌋ = ⌊node·⌈2⁶⁴/c⌉/2⁶⁴⌋ for every 32-bit node (Lemire, Kaser & Kurz 2019,
        // "Faster remainder by direct computation", Theorem 1 with N = 32, F = 64).
        let j = ((u128::from(reciprocal) * node as u128) >> 64) as usize;
        let i = node - j * c;
        (i >= 1 && i + 1 < c && j >= 1 && j + 1 < self.rows as usize).then_some(j)
    }

    /// The `N` springs at a square (`N` = 4) or hexagonal (`N` = 6) lattice's node away from
    /// its edges ([`Lattice::interior_row`]), whose row's parity is `odd` (0 or 1), and the
    /// nodes they reach, in [`Lattice::for_each_spring_at`]'s order (the outgoing springs by
    /// direction, then the incoming ones), each spring's direction and sign given by its
    /// place: direction `k % directions`, outgoing for `k < directions`. `None` for any other
    /// `N` or topology.
    #[inline(always)]
    pub(crate) fn star_in_row<const N: usize>(&self, node: usize, odd: usize) -> Option<([usize; N], [usize; N])> {
        let (n, c) = (self.node_count(), self.columns as usize);
        let (springs, others) = match (self.topology, N) {
            (Topology::Square, 4) => {
                ([node, n + node, node - 1, n + node - c, 0, 0], [node + 1, node + c, node - 1, node - c, 0, 0])
            }
            (Topology::Hexagonal, 6) => {
                let (up_right, up_left) = (node + c + odd, node + c + odd - 1);
                let (down_left, down_right) = (node - c - (1 - odd), node - c + odd);
                (
                    [node, n + node, 2 * n + node, node - 1, n + down_left, 2 * n + down_right],
                    [node + 1, up_right, up_left, node - 1, down_left, down_right],
                )
            }
            _ => return None,
        };
        Some((core::array::from_fn(|k| springs[k]), core::array::from_fn(|k| others[k])))
    }

    /// ⌈2⁶⁴/columns⌉, which [`Lattice::interior_row`] finds a node's row with (0 for fewer
    /// than two columns: no node is then away from the edges).
    pub(crate) const fn column_reciprocal(&self) -> u64 {
        match u64::MAX.checked_div(self.columns as u64) {
            Some(q) if self.columns > 1 => q + 1,
            _ => 0,
        }
    }

    /// Number of mesh cells (squares, or two triangles per node), including those whose
    /// sides are missing at an open edge (for which [`Lattice::cell`] is `None`).
    pub const fn cell_count(&self) -> usize {
        self.node_count() * self.cells_per_node()
    }

    /// Sides per mesh cell: 4 (square) or 3 (triangle).
    pub const fn sides_per_cell(&self) -> usize {
        match self.topology {
            Topology::Square => 4,
            _ => 3,
        }
    }

    /// The mesh cells on either side of `spring`, each with the index of the side the spring
    /// is in it: the cell to the spring's left (walking from its origin to the node it
    /// reaches) first, then the one to its right. A cell is `None` where it does not exist
    /// (an open edge).
    pub fn cells_of_spring(&self, spring: usize) -> [Option<(usize, usize)>; 2] {
        self.cells_of_spring_framed(spring).0
    }

    /// [`Lattice::cells_of_spring`], and whether the two cells are known to lie in one frame:
    /// their reference positions ([`Cell::reference`]) place the spring at the same point, not
    /// a period apart. They do on an open regular lattice, and away from a periodic one's
    /// edges; elsewhere (and on 32-bit targets, for the Cortex-M3's flash) `false` says only
    /// that the positions must be compared.
    #[inline(always)]
    pub(crate) fn cells_of_spring_framed(&self, spring: usize) -> ([Option<(usize, usize)>; 2], bool) {
        if let Some(m) = &self.mesh {
            return (m.cells_of_spring(spring), false);
        }
        let (node, d) = self.spring_origin(spring);
        // On a periodic lattice every cell exists; at open edges a cell exists if its sides do.
        let periodic = self.boundary == Boundary::Periodic;
        // Away from the edges of a periodic lattice the cells are fixed offsets from the
        // spring's origin (what the general case below finds: the same cells). Not on 32-bit
        // targets, for the Cortex-M3's flash.
        let c = self.columns as usize;
        let (i, j) = (node % c, node / c);
        // (Their base nodes are the origin's neighbours, unwrapped: one frame.)
        if cfg!(target_pointer_width = "64") && periodic && i >= 1 && i + 1 < c && j >= 1 && j < self.rows as usize {
            let cells = match (self.topology, d) {
                (Topology::Square, 0) => [Some((node, 0)), Some((node - c, 2))],
                (Topology::Square, _) => [Some((node - 1, 1)), Some((node, 3))],
                (_, 0) => [Some((2 * node, 0)), Some((2 * (node - c + j % 2) + 1, 1))],
                (_, 1) => [Some((2 * node + 1, 0)), Some((2 * node, 2))],
                (_, _) => [Some((2 * (node - 1), 1)), Some((2 * node + 1, 2))],
            };
            return (cells, true);
        }
        let exists =
            |cell: Option<usize>, side: usize| cell.filter(|&c| periodic || self.cell(c).is_some()).map(|c| (c, side));
        let cells = match (self.topology, d) {
            // Square cell b has sides [b→right, right→up-right, up→up-right, b→up], the last
            // two running clockwise; the side index says which.
            (Topology::Square, 0) => [exists(Some(node), 0), exists(self.back_neighbour(node, 1), 2)],
            (Topology::Square, _) => [exists(self.back_neighbour(node, 0), 1), exists(Some(node), 3)],
            (_, 0) => [exists(Some(2 * node), 0), exists(self.back_neighbour(node, 2).map(|b| 2 * b + 1), 1)],
            (_, 1) => [exists(Some(2 * node + 1), 0), exists(Some(2 * node), 2)],
            (_, _) => [exists(self.back_neighbour(node, 0).map(|b| 2 * b), 1), exists(Some(2 * node + 1), 2)],
        };
        // An open lattice's reference positions are the plate's own: one frame everywhere.
        (cells, cfg!(target_pointer_width = "64") && !periodic)
    }

    /// Mesh cell `cell` (`node·cells_per_node + k`), if all its sides exist.
    #[cfg_attr(target_pointer_width = "64", inline(always))]
    pub fn cell(&self, cell: usize) -> Option<Cell> {
        if let Some(m) = &self.mesh {
            let (nodes, sides) = m.cell(cell)?;
            let at = m.position(nodes[0] as usize);
            let near = |n: u32| self.nearest_image(at, m.position(n as usize));
            return Some(Cell {
                nodes: [nodes[0], nodes[1], nodes[2], 0],
                corners: 3,
                sides: [sides[0], sides[1], sides[2], 0],
                reference: [at, near(nodes[1]), near(nodes[2]), [0.0; 2]],
            });
        }
        let per = self.cells_per_node();
        let (base, k) = (cell / per, cell % per);
        let c = self.columns as usize;
        let (i, j) = (base % c, base / c);
        let at = self.reference_at(i, j);
        let offset = |d: usize| {
            let v = self.direction_vector(d);
            [at[0] + v[0], at[1] + v[1]]
        };
        // Away from the edges the corners are fixed offsets from the base node (what the
        // general case below finds, without wrapping: the same cell). Not on 32-bit targets,
        // for the Cortex-M3's flash: the general case alone computes the same.
        if cfg!(target_pointer_width = "64") && i >= 1 && i + 1 < c && j + 1 < self.rows as usize {
            let up_right = base + c + j % 2;
            let (nodes, corners, sides, reference) = match (self.topology, k) {
                (Topology::Square, _) => (
                    [base, base + 1, base + c + 1, base + c],
                    4,
                    [self.spring(base, 0), self.spring(base + 1, 1), self.spring(base + c, 0), self.spring(base, 1)],
                    [at, offset(0), [at[0] + 1.0, at[1] + 1.0], offset(1)],
                ),
                (_, 0) => (
                    [base, base + 1, up_right, 0],
                    3,
                    [self.spring(base, 0), self.spring(base + 1, 2), self.spring(base, 1), 0],
                    [at, offset(0), offset(1), [0.0; 2]],
                ),
                (_, _) => (
                    [base, up_right, up_right - 1, 0],
                    3,
                    [self.spring(base, 1), self.spring(up_right - 1, 0), self.spring(base, 2), 0],
                    [at, offset(1), offset(2), [0.0; 2]],
                ),
            };
            return Some(Cell { nodes: nodes.map(|n| n as u32), corners, sides: sides.map(|s| s as u32), reference });
        }
        match (self.topology, k) {
            (Topology::Square, _) => {
                let right = self.neighbour(base, 0)?;
                let up = self.neighbour(base, 1)?;
                let diagonal = self.neighbour(right, 1)?;
                Some(Cell {
                    nodes: [base as u32, right as u32, diagonal as u32, up as u32],
                    corners: 4,
                    sides: [
                        self.spring(base, 0) as u32,
                        self.spring(right, 1) as u32,
                        self.spring(up, 0) as u32,
                        self.spring(base, 1) as u32,
                    ],
                    reference: [at, offset(0), [at[0] + 1.0, at[1] + 1.0], offset(1)],
                })
            }
            (_, k) => {
                // A triangle: upward (k = 0) base, right, up-right; downward (k = 1) base,
                // up-right, up-left. Its third side is stored at the node it leaves in a
                // forward direction: right's direction 2, or up-left's direction 0.
                let (p, q) = (self.neighbour(base, k)?, self.neighbour(base, k + 1)?);
                let (from, d) = if k == 0 { (p, 2) } else { (q, 0) };
                self.neighbour(from, d)?;
                Some(Cell {
                    nodes: [base as u32, p as u32, q as u32, 0],
                    corners: 3,
                    sides: [
                        self.spring(base, k) as u32,
                        self.spring(from, d) as u32,
                        self.spring(base, k + 1) as u32,
                        0,
                    ],
                    reference: [at, offset(k), offset(k + 1), [0.0; 2]],
                })
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lattice(topology: Topology, boundary: Boundary, columns: u32, rows: u32) -> Lattice<'static> {
        Lattice::new(topology, boundary, columns, rows)
    }

    #[test]
    fn every_node_of_a_periodic_lattice_has_all_neighbours() {
        for (topology, degree) in [(Topology::Square, 4), (Topology::Hexagonal, 6)] {
            let l = lattice(topology, Boundary::Periodic, 6, 4);
            for node in 0..l.node_count() {
                let mut seen = 0;
                l.for_each_spring_at(node, |spring, other, _, _| {
                    let (a, b) = l.spring_nodes(spring).unwrap();
                    assert!(a == node && b == other || b == node && a == other);
                    seen += 1;
                });
                assert_eq!(seen, degree);
            }
        }
    }

    #[test]
    fn interior_fast_path_matches_the_general_rule() {
        for topology in [Topology::Square, Topology::Hexagonal] {
            let l = lattice(topology, Boundary::Open, 7, 6);
            for node in 0..l.node_count() {
                let mut fast = [(0, 0, 0, 0.0); 6];
                let mut n = 0;
                l.for_each_spring_at(node, |s, o, d, sign| {
                    fast[n] = (s, o, d, sign);
                    n += 1;
                });
                let mut general = [(0, 0, 0, 0.0); 6];
                let mut m = 0;
                for d in 0..l.directions() {
                    if let Some(o) = l.neighbour(node, d) {
                        general[m] = (l.spring(node, d), o, d, 1.0);
                        m += 1;
                    }
                }
                for d in 0..l.directions() {
                    if let Some(o) = l.back_neighbour(node, d) {
                        general[m] = (l.spring(o, d), o, d, -1.0);
                        m += 1;
                    }
                }
                assert_eq!(fast[..n], general[..m], "{topology:?} node {node}");
            }
        }
    }

    #[test]
    fn the_column_reciprocal_gives_each_node_its_row() {
        for columns in [2, 3, 7, 64, 100, 512, 1000, 65535, u32::MAX / 3, u32::MAX] {
            let reciprocal = lattice(Topology::Square, Boundary::Open, columns, 1).column_reciprocal();
            let c = u64::from(columns);
            for node in [0, 1, c - 1, c, c + 1, 2 * c - 1, 12345, 1 << 31, u64::from(u32::MAX) - 1, u64::from(u32::MAX)]
            {
                // (Nodes are 32-bit: the run's node indices are.)
                let Some(node) = u32::try_from(node).ok().map(u64::from) else { continue };
                let row = ((u128::from(reciprocal) * u128::from(node)) >> 64) as u64;
                assert_eq!(row, node / c, "{node} / {columns}");
            }
        }
        assert_eq!(lattice(Topology::Square, Boundary::Open, 1, 5).column_reciprocal(), 0);
    }

    #[test]
    fn the_interior_star_is_the_springs_at_the_node() {
        for (topology, degree) in [(Topology::Square, 4), (Topology::Hexagonal, 6)] {
            for boundary in [Boundary::Open, Boundary::Periodic] {
                let l = lattice(topology, boundary, 7, 6);
                let mut found = 0;
                for node in 0..l.node_count() {
                    let mut listed = [(0, 0, 0, 0.0); 6];
                    let mut n = 0;
                    l.for_each_spring_at(node, |s, o, d, sign| {
                        listed[n] = (s, o, d, sign);
                        n += 1;
                    });
                    let pad = |a: &[usize]| core::array::from_fn::<usize, 6, _>(|k| a.get(k).copied().unwrap_or(0));
                    let Some(row) = l.interior_row(node, l.column_reciprocal()) else { continue };
                    let star = if degree == 4 {
                        l.star_in_row::<4>(node, row % 2).map(|(s, o)| (pad(&s), pad(&o)))
                    } else {
                        l.star_in_row::<6>(node, row % 2).map(|(s, o)| (pad(&s), pad(&o)))
                    };
                    let Some((springs, others)) = star else { continue };
                    found += 1;
                    let dirs = l.directions();
                    let expected: [(usize, usize, usize, f32); 6] =
                        core::array::from_fn(|k| (springs[k], others[k], k % dirs, if k < dirs { 1.0 } else { -1.0 }));
                    assert_eq!(listed[..n], expected[..degree], "{topology:?} {boundary:?} {node}");
                }
                assert_eq!(found, 5 * 4, "{topology:?} {boundary:?}");
                assert!(l.star_in_row::<5>(8, 0).is_none());
            }
        }
    }

    #[test]
    fn back_neighbour_inverts_neighbour() {
        for topology in [Topology::Square, Topology::Hexagonal] {
            for boundary in [Boundary::Open, Boundary::Periodic] {
                let l = lattice(topology, boundary, 5, 6);
                for node in 0..l.node_count() {
                    for d in 0..l.directions() {
                        if let Some(n) = l.neighbour(node, d) {
                            assert_eq!(l.back_neighbour(n, d), Some(node), "{topology:?} {boundary:?} {node} {d}");
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn springs_join_nodes_one_spacing_apart() {
        let l = lattice(Topology::Hexagonal, Boundary::Open, 7, 6);
        for spring in 0..l.spring_count() {
            if let Some((a, b)) = l.spring_nodes(spring) {
                let (pa, pb) = (l.reference(a), l.reference(b));
                let d = libm::hypotf(pb[0] - pa[0], pb[1] - pa[1]);
                assert!((d - 1.0).abs() < 1e-6, "{spring}: {d}");
                let v = l.direction_vector(l.spring_origin(spring).1);
                assert!((pb[0] - pa[0] - v[0]).abs() < 1e-6 && (pb[1] - pa[1] - v[1]).abs() < 1e-6);
            }
        }
    }

    #[test]
    fn cells_tile_the_periodic_domain() {
        for topology in [Topology::Square, Topology::Hexagonal] {
            let l = lattice(topology, Boundary::Periodic, 6, 4);
            let cells = l.node_count() * l.cells_per_node();
            let mut area = 0.0;
            let mut side_uses = [0u32; 72];
            for c in 0..cells {
                let cell = l.cell(c).unwrap();
                let r = &cell.reference[..cell.corners];
                // Shoelace area; corners are counter-clockwise.
                let mut twice = 0.0;
                for k in 0..cell.corners {
                    let (p, q) = (r[k], r[(k + 1) % cell.corners]);
                    twice += p[0] * q[1] - q[0] * p[1];
                    let (a, b) = l.spring_nodes(cell.sides[k] as usize).unwrap();
                    let ends = [cell.nodes[k] as usize, cell.nodes[(k + 1) % cell.corners] as usize];
                    assert!(ends == [a, b] || ends == [b, a], "side {k} of cell {c}");
                    side_uses[cell.sides[k] as usize] += 1;
                }
                assert!(twice > 0.0);
                area += twice / 2.0;
            }
            let [w, h] = l.extent();
            assert!((area - w * h).abs() < 1e-3, "{topology:?}: {area} vs {}", w * h);
            // Every spring separates exactly two cells.
            assert!(side_uses[..l.spring_count()].iter().all(|&n| n == 2), "{topology:?}");
        }
    }

    #[test]
    fn cells_of_a_spring_are_the_cells_it_is_a_side_of() {
        for topology in [Topology::Square, Topology::Hexagonal] {
            for boundary in [Boundary::Open, Boundary::Periodic] {
                let l = lattice(topology, boundary, 5, 6);
                let mut found = [0u32; 90];
                for (spring, found) in found.iter_mut().enumerate().take(l.spring_count()) {
                    let (origin, d) = l.spring_origin(spring);
                    for (k, found_cell) in l.cells_of_spring(spring).into_iter().enumerate() {
                        let Some((cell, side)) = found_cell else { continue };
                        let c = l.cell(cell).unwrap();
                        assert_eq!(c.sides[side] as usize, spring, "{topology:?} {spring}");
                        *found += 1;
                        // The first cell lies to the spring's left, the second to its right.
                        let n = c.corners;
                        let at = c.reference[side];
                        let centre = c.reference[..n].iter().fold([0.0; 2], |s, p| [s[0] + p[0], s[1] + p[1]]);
                        let v = l.direction_vector(d);
                        let towards = [centre[0] / n as f32 - at[0], centre[1] / n as f32 - at[1]];
                        let left = v[0] * towards[1] - v[1] * towards[0] > 0.0;
                        assert_eq!(left, k == 0, "{topology:?} {boundary:?} spring {spring} from {origin}");
                    }
                }
                // Each side of each cell is found once, and a periodic spring has two cells.
                let sides: usize = (0..l.cell_count()).filter(|&c| l.cell(c).is_some()).count() * l.sides_per_cell();
                assert_eq!(found.iter().sum::<u32>() as usize, sides, "{topology:?} {boundary:?}");
                if boundary == Boundary::Periodic {
                    assert!(found[..l.spring_count()].iter().all(|&n| n == 2));
                }
            }
        }
    }

    #[test]
    fn cells_said_to_share_a_frame_place_their_spring_at_one_point() {
        for topology in [Topology::Square, Topology::Hexagonal] {
            for boundary in [Boundary::Open, Boundary::Periodic] {
                let l = lattice(topology, boundary, 7, 6);
                let mut shared = 0;
                for spring in 0..l.spring_count() {
                    let ([a, b], one_frame) = l.cells_of_spring_framed(spring);
                    assert_eq!([a, b], l.cells_of_spring(spring));
                    let (Some((a, side_a)), Some((b, side_b)), true) = (a, b, one_frame) else { continue };
                    let mid = |c: Cell, k: usize| {
                        let (p, q) = (c.reference[k], c.reference[(k + 1) % c.corners]);
                        [(p[0] + q[0]) * 0.5, (p[1] + q[1]) * 0.5]
                    };
                    let (p, q) = (mid(l.cell(a).unwrap(), side_a), mid(l.cell(b).unwrap(), side_b));
                    assert!(
                        (p[0] - q[0]).abs() < 1e-4 && (p[1] - q[1]).abs() < 1e-4,
                        "{topology:?} {boundary:?} {spring}"
                    );
                    shared += 1;
                }
                // Most springs' cells are known to share a frame (on 64-bit targets).
                if cfg!(target_pointer_width = "64") {
                    assert!(shared > l.spring_count() / 3, "{topology:?} {boundary:?}: {shared}");
                }
            }
        }
    }

    #[test]
    fn open_edges_drop_springs_and_cells() {
        let l = lattice(Topology::Square, Boundary::Open, 3, 3);
        assert_eq!((0..l.spring_count()).filter(|&s| l.spring_nodes(s).is_some()).count(), 12);
        assert_eq!((0..l.node_count()).filter(|&c| l.cell(c).is_some()).count(), 4);
    }
}
