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

impl FaceShape {
    /// Nothing walked yet.
    const EMPTY: FaceShape = FaceShape { area: 0.0, min: [f32::INFINITY; 2], max: [f32::NEG_INFINITY; 2], edges: 0 };

    /// Adds the step of a walk from point `a` to point `b`.
    fn add(&mut self, a: [f32; 2], b: [f32; 2]) {
        self.edges += 1;
        self.area += 0.5 * shoelace(a, b);
        self.min = [self.min[0].min(a[0]), self.min[1].min(a[1])];
        self.max = [self.max[0].max(a[0]), self.max[1].max(a[1])];
    }

    /// Whether `p` lies in the box.
    fn holds(&self, p: [f32; 2]) -> bool {
        p[0] >= self.min[0] && p[0] <= self.max[0] && p[1] >= self.min[1] && p[1] <= self.max[1]
    }
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

    /// The key that orders the edges at vertex `v`: the pseudo-angle of the half-edge leaving
    /// `v` along edge `e`, and that half-edge (what [`next_around_face`] orders them by).
    fn key(&self, v: u32, e: u32) -> (f32, HalfEdge) {
        let edge = &self.edges[e as usize];
        let side = u32::from(edge.from != v);
        (edge.angles[side as usize], 2 * e + side)
    }

    /// [`next_around_face`] in one step: each vertex's incidence list runs by descending
    /// [`Self::key`] ([`Glass::link`] keeps it so), so the predecessor of the way back in that
    /// order is the edge after it in the list, or the list's first when it is the last. The
    /// same half-edge as the search over every edge at the vertex, without it (at the impact
    /// point, M edges).
    pub(super) fn next_sorted(&self, h: HalfEdge) -> HalfEdge {
        let back = h ^ 1;
        let w = self.ends(back).0;
        let after = self.edges[(back >> 1) as usize].links[(back & 1) as usize];
        let next = if after == NONE { self.vertices[w as usize].first_edge } else { after };
        self.key(w, next).1
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

    /// Links edge `e` into vertex `v`'s incidence list at its place: the list runs by
    /// descending [`CrackGraph::key`], so that a face walk finds the next edge around a vertex
    /// in one step ([`CrackGraph::next_sorted`]). Walks the edges with larger keys (at most the
    /// vertex's degree; none for the radial cracks of an impact, which start in ascending
    /// angle order but for one wrap).
    pub(super) fn link(&mut self, v: u32, e: u32) {
        let (previous, after) = {
            let g = self.crack_graph();
            let key = g.key(v, e);
            let before = |a: (f32, u32), b: (f32, u32)| a.0 < b.0 || (a.0 == b.0 && a.1 < b.1);
            let mut previous = NONE;
            let mut x = self.vertices[v as usize].first_edge;
            while x != NONE && before(key, g.key(v, x)) {
                previous = x;
                x = g.next_at(v, x);
            }
            (previous, x)
        };
        let edge = &mut self.edges[e as usize];
        edge.links[usize::from(edge.from != v)] = after;
        if previous == NONE {
            self.vertices[v as usize].first_edge = e;
        } else {
            let p = &mut self.edges[previous as usize];
            p.links[usize::from(p.from != v)] = e;
        }
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

    /// Goes on with stop condition 2 (paper §4.2.3) until it is over (true) or the work
    /// reaches `deadline` (false; the next call goes on from there), one unit per step of a
    /// walk or crack looked at. The new half-edge `h` closed a cycle, splitting a face in two.
    /// The region it closed is the smaller of the two (walked in step, the one that closes
    /// first) if that one is bounded, else the other; every crack growing inside it stops.
    ///
    /// When the split face was itself already enclosed, both halves are new regions; only the
    /// smaller one counts as closed, so that a later impact inside an enclosed fragment keeps
    /// growing after its first cycle.
    pub(super) fn go_on_enclosure(&mut self, e: &mut Enclosure, deadline: u64) -> bool {
        loop {
            if self.clock.work >= deadline {
                return false;
            }
            match e.walk {
                Walk::Lockstep => {
                    // The two faces in step, two units a step.
                    self.clock.work += 2;
                    let g = self.crack_graph();
                    e.a = g.next_sorted(e.a);
                    e.b = g.next_sorted(e.b);
                    e.steps += 1;
                    if e.a == e.h || e.steps > g.half_edge_bound() {
                        e.faces = [e.h, e.h ^ 1];
                    } else if e.b == e.h ^ 1 {
                        e.faces = [e.h ^ 1, e.h];
                    } else {
                        continue;
                    }
                    e.which = 0;
                    self.begin_measure(e);
                }
                Walk::Measure => {
                    // The first of the two faces that is bounded, its vertices marked by the
                    // walk that measures it (a fresh mark per walk, so only the chosen face's
                    // vertices carry it).
                    self.clock.work += 1;
                    let g = self.crack_graph();
                    let (u, w) = g.ends(e.at);
                    e.shape.add(g.point(u), g.point(w));
                    e.at = g.next_sorted(e.at);
                    let (closed, broken) = (e.at == e.faces[e.which], e.shape.edges > g.half_edge_bound());
                    self.walk.marks[u as usize] = self.walk.mark;
                    if closed && e.shape.area > 0.0 {
                        e.walk = Walk::Cracks;
                        e.crack = 0;
                        e.testing = false;
                        let v = self.crack_graph().ends(e.faces[e.which]).0;
                        e.piece = self.component(v);
                    } else if closed || broken {
                        if e.which == 1 {
                            return true;
                        }
                        e.which = 1;
                        self.begin_measure(e);
                    }
                }
                Walk::Cracks if e.crack == self.crack_count => return true,
                Walk::Cracks if !e.testing => {
                    self.clock.work += 1;
                    let i = e.crack;
                    e.crack += 1;
                    if !self.cracks[i].growing() {
                        continue;
                    }
                    let tip = self.tip_vertex(i);
                    // A tip of this piece is inside when the walk passed it (its dangling crack
                    // lies in the face); a tip of another piece (a ring crack not yet joined)
                    // by the crossing rule, tested when it lies in the face's box.
                    if self.walk.marks[tip as usize] == self.walk.mark {
                        self.enclosed(i);
                    } else if self.component(tip) != e.piece && e.shape.holds(self.vertices[tip as usize].at) {
                        e.crack = i;
                        e.testing = true;
                        e.at = e.faces[e.which];
                        e.steps = 0;
                        e.inside = false;
                    }
                }
                Walk::Cracks => {
                    // The crossing number of the tip of crack `e.crack`, a step a unit.
                    self.clock.work += 1;
                    let g = self.crack_graph();
                    let p = g.point(self.tip_vertex(e.crack));
                    let (u, w) = g.ends(e.at);
                    e.inside ^= crosses_ray(g.point(u), g.point(w), p);
                    e.at = g.next_sorted(e.at);
                    e.steps += 1;
                    if e.at == e.faces[e.which] || e.steps > g.half_edge_bound() {
                        if e.inside {
                            self.enclosed(e.crack);
                        }
                        e.testing = false;
                        e.crack += 1;
                    }
                }
            }
        }
    }

    /// Starts the walk that measures and marks face `e.which` of the two.
    fn begin_measure(&mut self, e: &mut Enclosure) {
        self.walk.mark = self.walk.mark.wrapping_add(1);
        if self.walk.mark == 0 {
            // The marks start over (every 2³² − 1 walks): those of the vertices so far are
            // reset; a vertex added later gets its own when it is added.
            self.walk.marks[..self.vertex_count].fill(0);
            self.walk.mark = 1;
        }
        e.walk = Walk::Measure;
        e.at = e.faces[e.which];
        e.shape = FaceShape::EMPTY;
    }

    /// Stops crack `i`: a region closed around its tip.
    fn enclosed(&mut self, i: usize) {
        self.stop(i, CrackEnd::Enclosed);
    }
}

/// Which walk of stop condition 2 is under way.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Walk {
    /// The two faces beside the new edge, walked in step until one closes.
    Lockstep,
    /// Measuring (and marking) one of them.
    Measure,
    /// Looking at each growing crack, and walking the face for a tip's crossing number.
    Cracks,
}

/// Where stop condition 2 stands, between the calls of [`Glass::step`] that carry it out.
#[derive(Clone, Copy, Debug)]
pub(super) struct Enclosure {
    walk: Walk,
    /// The new half-edge, and the two walks in step from it and its twin.
    h: HalfEdge,
    a: HalfEdge,
    b: HalfEdge,
    /// Steps of the walk under way (in step, or of a crossing-number walk).
    steps: usize,
    /// The two faces, the smaller first, and which of them is being measured or was chosen.
    faces: [HalfEdge; 2],
    which: usize,
    /// The half-edge the walk under way is at.
    at: HalfEdge,
    /// The measured face.
    shape: FaceShape,
    /// The connected piece of the network the face belongs to.
    piece: u32,
    /// The next crack to look at; a crossing-number walk is under way for it (`testing`), with
    /// the parity so far (`inside`).
    crack: usize,
    testing: bool,
    inside: bool,
}

impl Enclosure {
    /// Nothing under way.
    pub(super) const IDLE: Enclosure = Enclosure::new(NONE);

    /// Stop condition 2 for the new half-edge `h`, not yet started.
    pub(super) const fn new(h: HalfEdge) -> Enclosure {
        Enclosure {
            walk: Walk::Lockstep,
            h,
            a: h,
            b: h ^ 1,
            steps: 0,
            faces: [h, h ^ 1],
            which: 0,
            at: h,
            shape: FaceShape::EMPTY,
            piece: NONE,
            crack: 0,
            testing: false,
            inside: false,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::glass::{CrackSlot, GlassBuffers, GlassParams};
    extern crate std;
    use std::vec;

    /// The one-step walk around a face ([`CrackGraph::next_sorted`], over incidence lists kept
    /// in angle order) gives the very half-edge of the search over every edge at the vertex
    /// ([`next_around_face`]), for every half-edge of grown plates: the paper's M_ave of 100
    /// and a crowded 200 (hubs of about 200 edges), ring cracks met and split, a second impact
    /// on the cracks of the first; and their lists hold each edge once at each end.
    #[test]
    fn the_one_step_walk_is_the_search_over_every_edge() {
        for (seed, radial_mean) in [(1, 100.0), (2, 100.0), (3, 200.0), (4, 40.0)] {
            let p = GlassParams { seed, radial_mean, ..GlassParams::default() };
            let m = p.memory().unwrap();
            let (mut cracks, mut vertices) =
                (vec![CrackSlot::default(); m.cracks], vec![Vertex::default(); m.vertices]);
            let (mut edges, mut words) = (vec![Edge::default(); m.edges], vec![0u32; m.words]);
            let buffers =
                GlassBuffers { cracks: &mut cracks, vertices: &mut vertices, edges: &mut edges, words: &mut words };
            let mut glass = Glass::new(&p, buffers).unwrap();
            while !glass.step(u64::MAX).finished {}
            glass.impact([200.0, 410.0]).unwrap();
            while !glass.step(u64::MAX).finished {}
            let g = glass.crack_graph();
            let mut seen = vec![0u32; g.edges.len()];
            for v in 0..g.vertices.len() as u32 {
                g.for_each_edge_at(v, |e, _| seen[e as usize] += 1);
            }
            assert!(seen.iter().all(|&n| n == 2), "seed {seed}: an edge not listed once at each end");
            for h in 0..2 * g.edges.len() as u32 {
                assert_eq!(g.next_sorted(h), next_around_face(&g, h), "seed {seed}, half-edge {h}");
            }
        }
    }

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
