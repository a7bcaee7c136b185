//! Fragments: the regions the crack network cuts the plate into, as polygons (for a physics
//! engine, say). The plate's border joins the cracks, dead ends are pruned (a crack that ends
//! inside a region does not cut it), and every face of what remains is walked.
//!
//! A fragment is one outer ring, counter-clockwise with y up (positive shoelace area), and
//! rarely holes: clockwise rings of a closed piece of network that touches neither the border
//! nor the cracks around it, each naming the fragment it lies in. A ring can touch itself
//! where one crack has the same fragment on both sides (a slit between two loops). The rings'
//! signed areas add up to the plate's area, and each point of the plate lies in exactly one
//! fragment.

use super::faces::{CrackGraph, HalfEdge, PlaneGraph, next_around_face, walk_face};
use super::grid::NONE;
use super::{Glass, GlassError, take};
use crate::geom::pseudo_angle;
use crate::geom::{crosses_ray, shoelace};
use crate::polygon::{NOT_A_HOLE, Ring};

/// Caller words the fragment walk works in, sized for the plate's vertex capacity.
pub(super) struct FragmentScratch<'a> {
    /// Per vertex (and the four corners): edges left after pruning, plus 2 on the border.
    pub(super) degree: &'a mut [u32],
    /// First the stack of dead ends to prune, then the border's vertices in perimeter order.
    pub(super) border: &'a mut [u32],
    /// Per vertex: its index in `border`, NONE off the border.
    pub(super) border_index: &'a mut [u32],
    /// One bit per crack edge: not pruned.
    pub(super) alive: &'a mut [u32],
    /// One bit per half-edge: walked.
    pub(super) visited: &'a mut [u32],
}

pub(super) fn bit(bits: &[u32], i: usize) -> bool {
    bits[i / 32] & (1 << (i % 32)) != 0
}

pub(super) fn set_bit(bits: &mut [u32], i: usize, on: bool) {
    if on {
        bits[i / 32] |= 1 << (i % 32);
    } else {
        bits[i / 32] &= !(1 << (i % 32));
    }
}

impl<'a> FragmentScratch<'a> {
    /// Words for a plate of `vertices` vertices (as many edges, as many border vertices, and
    /// four corners).
    pub(super) fn words(vertices: usize) -> Option<usize> {
        let nodes = vertices.checked_add(4)?;
        let half_edges = vertices.checked_add(nodes)?.checked_mul(2)?;
        nodes.checked_mul(3)?.checked_add(vertices.div_ceil(32))?.checked_add(half_edges.div_ceil(32))
    }

    /// The scratch in the caller's `words` for a plate of `vertices` vertices, or how many
    /// words it needs if `words` is shorter.
    pub(super) fn new(mut words: &'a mut [u32], vertices: usize) -> Result<Self, GlassError> {
        let needed = Self::words(vertices).unwrap_or(usize::MAX);
        if words.len() < needed {
            return Err(GlassError::BufferTooSmall { needed });
        }
        let nodes = vertices + 4;
        let words = &mut words;
        Ok(FragmentScratch {
            degree: take(words, nodes),
            border: take(words, nodes),
            border_index: take(words, nodes),
            alive: take(words, vertices.div_ceil(32)),
            visited: take(words, (2 * (vertices + nodes)).div_ceil(32)),
        })
    }
}

/// The place of border point `p` along the perimeter of a `w` × `h` plate, counter-clockwise
/// from (0, 0) with y up: the side (0 bottom, 1 right, 2 top, 3 left; (0, 0) begins the bottom,
/// each other corner ends the side that reaches it) and the coordinate along it, negated where
/// the walk runs towards 0.
///
/// Compared exactly: one f64 distance along the whole perimeter, such as 2·W + H − x on the top
/// side, rounds away differences below 2·W·2⁻⁵³ (or below the spacing of f64 near 2·W + H, for
/// points near a corner), and a border out of order joins the wrong ends, losing fragments.
pub(super) fn perimeter(p: [f32; 2], w: f32, h: f32) -> (u8, f32) {
    if p[1] == 0.0 {
        (0, p[0])
    } else if p[0] == w {
        (1, p[1])
    } else if p[1] == h {
        (2, -p[0])
    } else {
        (3, -p[1])
    }
}

/// The pruned cracks plus the plate's border: border edge `k` runs from `border[k]` to
/// `border[k + 1]` (counter-clockwise), with edge index `edge_count + k`.
pub(super) struct PlateGraph<'g> {
    pub(super) cracks: CrackGraph<'g>,
    pub(super) alive: &'g [u32],
    pub(super) border: &'g [u32],
    pub(super) border_index: &'g [u32],
    pub(super) corners: [[f32; 2]; 4],
}

impl PlateGraph<'_> {
    pub(super) fn edge_count(&self) -> u32 {
        self.cracks.edges.len() as u32
    }
}

impl PlaneGraph for PlateGraph<'_> {
    fn point(&self, v: u32) -> [f32; 2] {
        match (v as usize).checked_sub(self.cracks.vertices.len()) {
            Some(corner) => self.corners[corner],
            None => self.cracks.point(v),
        }
    }

    fn ends(&self, h: HalfEdge) -> (u32, u32) {
        match (h >> 1).checked_sub(self.edge_count()) {
            Some(k) => {
                let n = self.border.len();
                let (a, b) = (self.border[k as usize], self.border[(k as usize + 1) % n]);
                if h & 1 == 0 { (a, b) } else { (b, a) }
            }
            None => self.cracks.ends(h),
        }
    }

    fn for_each_out(&self, v: u32, mut visit: impl FnMut(HalfEdge, f32)) {
        if (v as usize) < self.cracks.vertices.len() {
            self.cracks.for_each_out(v, |h, angle| {
                if bit(self.alive, (h >> 1) as usize) {
                    visit(h, angle);
                }
            });
        }
        let k = self.border_index[v as usize];
        if k != NONE {
            let n = self.border.len() as u32;
            for h in [2 * (self.edge_count() + k), 2 * (self.edge_count() + (k + n - 1) % n) + 1] {
                visit(h, self.angle(h));
            }
        }
    }

    fn angle(&self, h: HalfEdge) -> f32 {
        if h >> 1 < self.edge_count() {
            return self.cracks.angle(h);
        }
        let (u, w) = self.ends(h);
        let (a, b) = (self.point(u), self.point(w));
        if a != b {
            return pseudo_angle([b[0] - a[0], b[1] - a[1]]);
        }
        // Two crack ends at one point of the border (cracks from an impact a hair from the
        // edge all reach it there): the edge between them has no length, and the zero
        // vector's angle (0) would put it among the cracks, so that the outside's walk left
        // the border and took fragments with it. It runs along its side instead, as a border
        // edge of any length does: right, up, left or down (0, 1, 2, 3), reversed on the way
        // back.
        let [width, height] = self.corners[2];
        let side = perimeter(a, width, height).0;
        f32::from((side + if h & 1 == 0 { 0 } else { 2 }) % 4)
    }

    fn half_edge_bound(&self) -> usize {
        2 * (self.cracks.edges.len() + self.border.len())
    }
}

/// A ring found by the walk: where it starts, its signed area and its number of points.
#[derive(Clone, Copy)]
struct FoundRing {
    start: HalfEdge,
    area: f64,
    points: usize,
}

impl Glass<'_> {
    /// Prunes dead ends and lays out the border; returns the number of border vertices.
    fn prepare_fragments(&self, s: &mut FragmentScratch) -> usize {
        let (vertices, edges) = (self.vertex_count, self.edge_count);
        let (w, h) = (self.params.width, self.params.height);
        let corners = [[0.0, 0.0], [w, 0.0], [w, h], [0.0, h]];
        let on_border = |p: [f32; 2]| p[0] == 0.0 || p[1] == 0.0 || p[0] == w || p[1] == h;
        s.degree[..vertices + 4].fill(0);
        s.alive.fill(0);
        for (e, edge) in self.edges[..edges].iter().enumerate() {
            set_bit(s.alive, e, true);
            s.degree[edge.from as usize] += 1;
            s.degree[edge.to as usize] += 1;
        }
        // Prune: a vertex left with one edge is a dead end; remove that edge, and repeat.
        let mut stack = 0;
        for v in 0..vertices {
            if s.degree[v] == 1 && !on_border(self.vertices[v].at) {
                s.border[stack] = v as u32;
                stack += 1;
            }
        }
        let graph = CrackGraph { vertices: &self.vertices[..vertices], edges: &self.edges[..edges] };
        while stack > 0 {
            stack -= 1;
            let v = s.border[stack];
            let mut last = None;
            graph.for_each_edge_at(v, |e, half| {
                if bit(s.alive, e as usize) {
                    last = Some((e, half));
                }
            });
            let Some((e, half)) = last else { continue };
            set_bit(s.alive, e as usize, false);
            s.degree[v as usize] -= 1;
            let other = graph.ends(half).1;
            s.degree[other as usize] -= 1;
            if s.degree[other as usize] == 1 && !on_border(graph.point(other)) {
                s.border[stack] = other;
                stack += 1;
            }
        }
        // The border: cracks' ends on it, and the corners no crack ends at, in perimeter order.
        let mut n = 0;
        for v in 0..vertices {
            if s.degree[v] > 0 && on_border(self.vertices[v].at) {
                s.border[n] = v as u32;
                n += 1;
            }
        }
        // (Only the crack vertices are compared: a corner added here is no crack vertex, and
        // its index lies past them.)
        let ends = n;
        for (k, corner) in corners.iter().enumerate() {
            if !s.border[..ends].iter().any(|&v| self.vertices[v as usize].at == *corner) {
                s.border[n] = (vertices + k) as u32;
                n += 1;
            }
        }
        let point = |v: u32| {
            if (v as usize) < vertices { self.vertices[v as usize].at } else { corners[v as usize - vertices] }
        };
        s.border[..n].sort_unstable_by(|&a, &b| {
            let (pa, pb) = (perimeter(point(a), w, h), perimeter(point(b), w, h));
            pa.0.cmp(&pb.0).then(pa.1.total_cmp(&pb.1)).then(a.cmp(&b))
        });
        s.border_index[..vertices + 4].fill(NONE);
        for k in 0..n {
            s.border_index[s.border[k] as usize] = k as u32;
        }
        n
    }

    /// Walks every face of the plate once; calls `visit` with each fragment ring (not the
    /// outside of the plate) in a fixed order, working in the caller's `scratch`.
    fn for_each_ring(
        &self,
        scratch: &mut [u32],
        mut visit: impl FnMut(&PlateGraph, FoundRing),
    ) -> Result<(), GlassError> {
        let mut s = FragmentScratch::new(scratch, self.params.max_vertices as usize)?;
        let n = self.prepare_fragments(&mut s);
        let (w, h) = (self.params.width, self.params.height);
        let FragmentScratch { alive, border, border_index, visited, .. } = s;
        let g = PlateGraph {
            cracks: CrackGraph { vertices: &self.vertices[..self.vertex_count], edges: &self.edges[..self.edge_count] },
            alive,
            border: &border[..n],
            border_index,
            corners: [[0.0, 0.0], [w, 0.0], [w, h], [0.0, h]],
        };
        let half_edges = 2 * (self.edge_count + n);
        visited[..half_edges.div_ceil(32)].fill(0);
        // The outside of the plate: the border walked clockwise.
        walk_face(&g, 2 * g.edge_count() + 1, |h| set_bit(visited, h as usize, true));
        for start in 0..half_edges as u32 {
            let edge = (start >> 1) as usize;
            if bit(visited, start as usize) || (edge < self.edge_count && !bit(g.alive, edge)) {
                continue;
            }
            // Every walk comes back to its start while each vertex's edges are in a total order
            // (`pseudo_angle`). Should one not (it did when a zero-length edge's angle was
            // NaN: fuzz finding 11), it stops at the first half-edge another walk took and is
            // dropped, so the query stays linear in the half-edges whatever the geometry.
            let (mut ring, mut h, mut closed) = (FoundRing { start, area: 0.0, points: 0 }, start, false);
            for _ in 0..=g.half_edge_bound() {
                if bit(visited, h as usize) {
                    break;
                }
                set_bit(visited, h as usize, true);
                let (u, w) = g.ends(h);
                ring.area += 0.5 * shoelace(g.point(u), g.point(w));
                ring.points += 1;
                h = next_around_face(&g, h);
                if h == start {
                    closed = true;
                    break;
                }
            }
            if closed && ring.area != 0.0 {
                visit(&g, ring);
            }
        }
        Ok(())
    }

    /// The number of fragment rings and of their points: the buffer lengths
    /// [`Glass::fragments`] needs. The walk works in `scratch`, at least
    /// [`GlassMemory::scratch`](super::GlassMemory::scratch) words (else
    /// [`GlassError::BufferTooSmall`] with that number); the plate is only read.
    pub fn fragment_counts(&self, scratch: &mut [u32]) -> Result<(usize, usize), GlassError> {
        let (mut rings, mut points) = (0, 0);
        self.for_each_ring(scratch, |_, ring| {
            rings += 1;
            points += ring.points;
        })?;
        Ok((rings, points))
    }

    /// Writes the fragments of the network as it stands: each ring's record into `rings` and
    /// its points into `points`, and returns how many of each. Nothing is written if either
    /// buffer is shorter than [`Glass::fragment_counts`] says, or `scratch` shorter than
    /// [`GlassMemory::scratch`](super::GlassMemory::scratch).
    pub fn fragments(
        &self,
        scratch: &mut [u32],
        rings: &mut [Ring],
        points: &mut [[f32; 2]],
    ) -> Result<(usize, usize), GlassError> {
        let (ring_count, point_count) = self.fragment_counts(scratch)?;
        for (have, needed) in [(rings.len(), ring_count), (points.len(), point_count)] {
            if have < needed {
                return Err(GlassError::BufferTooSmall { needed });
            }
        }
        let (mut r, mut p) = (0, 0);
        self.for_each_ring(scratch, |g, ring| {
            rings[r] = Ring {
                area: ring.area,
                first_point: p as u32,
                point_count: ring.points as u32,
                hole_of: NOT_A_HOLE,
                reserved: 0,
            };
            walk_face(g, ring.start, |h| {
                points[p] = g.point(g.ends(h).0);
                p += 1;
            });
            r += 1;
        })?;
        let (rings, points) = (&mut rings[..r], &points[..p]);
        let outline = |ring: &Ring| &points[ring.first_point as usize..][..ring.point_count as usize];
        // A hole lies in the smallest outer ring around its first point that it does not touch.
        for i in 0..r {
            if rings[i].area > 0.0 {
                continue;
            }
            let q = outline(&rings[i])[0];
            let mut parent = (NONE, f64::INFINITY);
            for (j, candidate) in rings.iter().enumerate() {
                let ring = outline(candidate);
                let around =
                    ring.iter().zip(ring.iter().cycle().skip(1)).filter(|(a, b)| crosses_ray(**a, **b, q)).count();
                if candidate.area > 0.0 && candidate.area < parent.1 && around % 2 == 1 && !ring.contains(&q) {
                    parent = (j as u32, candidate.area);
                }
            }
            rings[i].hole_of = parent.0;
        }
        Ok((r, p))
    }
}
