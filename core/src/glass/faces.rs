//! The crack network as a plane graph: half-edges, the order of edges around each vertex, and
//! walks around faces. Growth uses it to find the region a stop has just closed (paper §4.2.3,
//! stop condition 2); [`super::fragments`] uses it, with the plate's border added, for the
//! fragments.
//!
//! A half-edge `h` runs along edge `h >> 1`: from its first vertex to its second when
//! `h & 1 == 0`, the other way when it is 1, so `h ^ 1` is its twin. Walking a face keeps the
//! face on the left: bounded faces come out counter-clockwise (positive shoelace area, with y
//! up), the outside of a connected piece clockwise.

use super::grid::NONE;
use super::{CrackEnd, Edge, Glass, Vertex};
use crate::geom::{crosses_ray, pseudo_angle, shoelace};

impl Edge {
    /// A segment of crack `crack` from vertex `from` to `to`, not yet chained or linked.
    pub(super) fn new(from: u32, to: u32, crack: u32, time: [f32; 2]) -> Edge {
        Edge { from, to, crack, next: NONE, time, links: [NONE; 2], angles: [0.0; 2], ends: [0.0; 4] }
    }

    /// Sets the pseudo-angles of the edge's two directions from its ends' positions.
    pub(super) fn orient(&mut self, from: [f32; 2], to: [f32; 2]) {
        let d = [to[0] - from[0], to[1] - from[1]];
        self.angles = [pseudo_angle(d), pseudo_angle([-d[0], -d[1]])];
    }
}

/// One direction along an edge.
pub(super) type HalfEdge = u32;

/// A plane graph that faces can be walked in.
pub(super) trait PlaneGraph {
    /// The position of vertex `v`.
    fn point(&self, v: u32) -> [f32; 2];
    /// The vertex half-edge `h` leaves from and the one it reaches.
    fn ends(&self, h: HalfEdge) -> (u32, u32);
    /// Calls `visit` with every half-edge leaving vertex `v` and its pseudo-angle (what
    /// [`Self::angle`] gives), read together.
    fn for_each_out(&self, v: u32, visit: impl FnMut(HalfEdge, f32));
    /// The pseudo-angle of half-edge `h`'s direction.
    fn angle(&self, h: HalfEdge) -> f32;
    /// An upper bound on the number of half-edges (a walk longer than this is broken).
    fn half_edge_bound(&self) -> usize;
}

/// The half-edge after `h` around the face on its left: at the vertex `h` reaches, the first
/// edge clockwise from the way back.
pub(super) fn next_around_face<G: PlaneGraph>(g: &G, h: HalfEdge) -> HalfEdge {
    let w = g.ends(h).1;
    let back = (g.angle(h ^ 1), h ^ 1);
    let before = |a: (f32, u32), b: (f32, u32)| a.0 < b.0 || (a.0 == b.0 && a.1 < b.1);
    // The predecessor of `back` in (angle, half-edge) order, cyclically.
    let (mut below, mut last) = (None::<(f32, u32)>, None::<(f32, u32)>);
    g.for_each_out(w, |o, angle| {
        let key = (angle, o);
        if before(key, back) && below.is_none_or(|b| before(b, key)) {
            below = Some(key);
        }
        if last.is_none_or(|l| before(l, key)) {
            last = Some(key);
        }
    });
    below.or(last).map_or(h ^ 1, |k| k.1)
}

/// Calls `visit` with every half-edge around the face left of `start`, from `start` on.
/// Returns false if the walk did not come back within the graph's half-edge bound.
pub(super) fn walk_face<G: PlaneGraph>(g: &G, start: HalfEdge, mut visit: impl FnMut(HalfEdge)) -> bool {
    let mut h = start;
    for _ in 0..=g.half_edge_bound() {
        visit(h);
        h = next_around_face(g, h);
        if h == start {
            return true;
        }
    }
    false
}

/// The area and bounding box of a face.
#[derive(Clone, Copy, Debug)]
pub(super) struct FaceShape {
    /// Signed area by the shoelace formula: positive for a bounded face.
    pub(super) area: f64,
    /// Smallest and largest x and y of its vertices.
    pub(super) min: [f32; 2],
    pub(super) max: [f32; 2],
    /// Its half-edges: the steps of a walk around it.
    pub(super) edges: usize,
}

/// The shape of the face left of `start` (None if the walk is broken); `visit` is called
/// with each half-edge of the walk, as by [`walk_face`].
pub(super) fn face_shape<G: PlaneGraph>(g: &G, start: HalfEdge, mut visit: impl FnMut(HalfEdge)) -> Option<FaceShape> {
    let mut shape = FaceShape { area: 0.0, min: [f32::INFINITY; 2], max: [f32::NEG_INFINITY; 2], edges: 0 };
    let closed = walk_face(g, start, |h| {
        visit(h);
        shape.edges += 1;
        let (u, w) = g.ends(h);
        let (a, b) = (g.point(u), g.point(w));
        shape.area += 0.5 * shoelace(a, b);
        shape.min = [shape.min[0].min(a[0]), shape.min[1].min(a[1])];
        shape.max = [shape.max[0].max(a[0]), shape.max[1].max(a[1])];
    });
    closed.then_some(shape)
}

/// Whether `p` lies inside the face left of `start` (crossing number).
pub(super) fn face_contains<G: PlaneGraph>(g: &G, start: HalfEdge, p: [f32; 2]) -> bool {
    let mut inside = false;
    walk_face(g, start, |h| {
        let (u, w) = g.ends(h);
        inside ^= crosses_ray(g.point(u), g.point(w), p);
    });
    inside
}

/// The cracks alone, as grown so far.
pub(super) struct CrackGraph<'g> {
    pub(super) vertices: &'g [Vertex],
    pub(super) edges: &'g [Edge],
}

impl CrackGraph<'_> {
    /// The next edge after `e` in vertex `v`'s incidence list.
    pub(super) fn next_at(&self, v: u32, e: u32) -> u32 {
        let edge = &self.edges[e as usize];
        if edge.from == v { edge.links[0] } else { edge.links[1] }
    }

    /// Calls `visit` with every edge at vertex `v` and the half-edge leaving `v` along it.
    pub(super) fn for_each_edge_at(&self, v: u32, mut visit: impl FnMut(u32, HalfEdge)) {
        let mut e = self.vertices[v as usize].first_edge;
        while e != NONE {
            // Which end of the edge `v` is: 0 its first, 1 its second (as in `next_at`).
            let side = u32::from(self.edges[e as usize].from != v);
            visit(e, 2 * e + side);
            e = self.edges[e as usize].links[side as usize];
        }
    }
}

impl PlaneGraph for CrackGraph<'_> {
    fn point(&self, v: u32) -> [f32; 2] {
        self.vertices[v as usize].at
    }

    fn ends(&self, h: HalfEdge) -> (u32, u32) {
        let e = &self.edges[(h >> 1) as usize];
        if h & 1 == 0 { (e.from, e.to) } else { (e.to, e.from) }
    }

    fn for_each_out(&self, v: u32, mut visit: impl FnMut(HalfEdge, f32)) {
        self.for_each_edge_at(v, |e, h| visit(h, self.edges[e as usize].angles[(h & 1) as usize]));
    }

    fn angle(&self, h: HalfEdge) -> f32 {
        self.edges[(h >> 1) as usize].angles[(h & 1) as usize]
    }

    fn half_edge_bound(&self) -> usize {
        2 * self.edges.len()
    }
}

impl Glass<'_> {
    /// The crack network grown so far.
    pub(super) fn crack_graph(&self) -> CrackGraph<'_> {
        CrackGraph { vertices: &self.vertices[..self.vertex_count], edges: &self.edges[..self.edge_count] }
    }

    /// The root of vertex `v`'s connected piece of the network (with path halving).
    pub(super) fn component(&mut self, mut v: u32) -> u32 {
        while self.walk.roots[v as usize] != v {
            let grandparent = self.walk.roots[self.walk.roots[v as usize] as usize];
            self.walk.roots[v as usize] = grandparent;
            v = grandparent;
        }
        v
    }

    /// Joins the pieces of vertices `a` and `b`; true if they already were one piece (an edge
    /// between them closes a cycle).
    pub(super) fn join(&mut self, a: u32, b: u32) -> bool {
        let (ra, rb) = (self.component(a), self.component(b));
        self.walk.roots[ra as usize] = rb;
        ra == rb
    }

    /// The vertex at crack `i`'s tip.
    pub(super) fn tip_vertex(&self, i: usize) -> u32 {
        let c = &self.cracks[i];
        if c.last_segment == NONE { c.start_vertex } else { self.edges[c.last_segment as usize].to }
    }

    /// Stop condition 2 (paper §4.2.3): the new half-edge `h` closed a cycle, splitting a face
    /// in two. The region it closed is the smaller of the two (walked in step, the one that
    /// closes first) if that one is bounded, else the other; every crack growing inside it
    /// stops.
    ///
    /// When the split face was itself already enclosed, both halves are new regions; only the
    /// smaller one counts as closed, so that a later impact inside an enclosed fragment keeps
    /// growing after its first cycle.
    pub(super) fn enclose(&mut self, h: HalfEdge) {
        let (first, second, steps) = {
            let g = self.crack_graph();
            let (mut a, mut b) = (h, h ^ 1);
            let mut steps = 0;
            loop {
                a = next_around_face(&g, a);
                b = next_around_face(&g, b);
                steps += 1;
                if a == h || steps > g.half_edge_bound() {
                    break (h, h ^ 1, steps);
                }
                if b == h ^ 1 {
                    break (h ^ 1, h, steps);
                }
            }
        };
        let g = CrackGraph { vertices: &self.vertices[..self.vertex_count], edges: &self.edges[..self.edge_count] };
        // Work (Glass::step's budget): the walks in lockstep, the faces measured, the marking
        // walk (done by the walk that measures the face, still counted as one, so that a
        // budget means what it did), the cracks looked at and the crossing-number walks.
        let mut work = 2 * steps;
        // The first of the two faces that is bounded, its vertices marked by the walk that
        // measures it (a fresh mark per walk, so only the chosen face's vertices carry it).
        let mut found = None;
        for s in [first, second] {
            self.walk.mark = self.walk.mark.wrapping_add(1);
            if self.walk.mark == 0 {
                self.walk.marks.fill(0);
                self.walk.mark = 1;
            }
            let (marks, mark) = (&mut *self.walk.marks, self.walk.mark);
            let f = face_shape(&g, s, |h| marks[g.ends(h).0 as usize] = mark);
            work += f.map_or(g.half_edge_bound(), |f| f.edges);
            if let Some(f) = f.filter(|f| f.area > 0.0) {
                found = Some((s, f));
                break;
            }
        }
        let Some((start, shape)) = found else {
            self.clock.work += work as u64;
            return;
        };
        work += shape.edges + self.crack_count;
        let mark = self.walk.mark;
        let v = g.ends(start).0;
        let piece = self.component(v);
        for i in 0..self.crack_count {
            if !self.cracks[i].growing {
                continue;
            }
            let tip = self.tip_vertex(i);
            // A tip of this piece is inside when the walk passed it (its dangling crack lies in
            // the face); a tip of another piece (a ring crack not yet joined) by the crossing rule.
            let inside = if self.walk.marks[tip as usize] == mark {
                true
            } else if self.component(tip) == piece {
                false
            } else {
                let p = self.vertices[tip as usize].at;
                let in_box =
                    p[0] >= shape.min[0] && p[0] <= shape.max[0] && p[1] >= shape.min[1] && p[1] <= shape.max[1];
                work += usize::from(in_box) * shape.edges;
                in_box && face_contains(&self.crack_graph(), start, p)
            };
            if inside {
                let c = &mut self.cracks[i];
                c.growing = false;
                c.end = CrackEnd::Enclosed;
            }
        }
        self.clock.work += work as u64;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_point_is_inside_a_square_by_crossings() {
        let square = [[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]];
        let count = |p: [f32; 2]| (0..4).filter(|&i| crosses_ray(square[i], square[(i + 1) % 4], p)).count();
        assert_eq!(count([1.0, 1.0]) % 2, 1);
        assert_eq!(count([3.0, 1.0]) % 2, 0);
        assert_eq!(count([-1.0, 0.0]) % 2, 0);
        // Through a vertex: counted once.
        assert_eq!(count([-1.0, 2.0]) % 2, 0);
        let area: f64 = (0..4).map(|i| 0.5 * shoelace(square[i], square[(i + 1) % 4])).sum();
        assert_eq!(area, 4.0);
    }
}
