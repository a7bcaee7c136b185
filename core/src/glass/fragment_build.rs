//! The fragments built in steps, each within a budget of work, into caller memory; once built
//! they are read in ranges. The same rings and points, in the same order and bit for bit, as
//! [`Glass::fragments`] writes ([`super::fragments`] describes them): the same passes (dead
//! ends pruned, the border laid out and sorted, every face walked, each hole given its outer
//! ring), cut into pieces of bounded work that a [`FragmentBuild::step`] call stops between.

use super::faces::{CrackGraph, HalfEdge, PlaneGraph, next_around_face};
use super::fragments::{FragmentScratch, PlateGraph, bit, perimeter, set_bit};
use super::grid::NONE;
use super::{Glass, GlassError};
use crate::geom::{crosses_ray, shoelace};
use crate::polygon::{NOT_A_HOLE, Ring};

use core::cell::Cell;

/// Array elements a pass clears or fills in one unit of work.
const CHUNK: usize = 16;

/// How much caller memory a fragment build of a plate needs ([`Glass::fragment_build_memory`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FragmentBuildMemory {
    /// `u32` words of scratch (as many as [`GlassMemory::scratch`](super::GlassMemory::scratch)).
    pub words: usize,
    /// [`Ring`] records: the most fragment rings the plate's capacity allows.
    pub rings: usize,
    /// Ring points (`[f32; 2]`): the most the plate's capacity allows.
    pub points: usize,
}

impl FragmentBuildMemory {
    /// The memory for a plate of `vertices` vertices at most. Every half-edge of the pruned
    /// cracks and the border (at most `vertices` edges and as many border edges and four more:
    /// [`FragmentScratch::words`]) lies on at most one ring, as one point; a ring of non-zero
    /// area has at least three points (two half-edges between the same two points enclose no
    /// area: the shoelace terms of a segment and its reverse cancel exactly).
    fn of(vertices: usize) -> Option<FragmentBuildMemory> {
        let words = FragmentScratch::words(vertices)?;
        let points = vertices.checked_mul(2)?.checked_add(4)?.checked_mul(2)?;
        Some(FragmentBuildMemory { words, rings: points / 3, points })
    }
}

/// Owned memory for a fragment build (the `alloc` feature), from
/// [`FragmentBuildMemory::allocate`].
#[cfg(feature = "alloc")]
pub struct FragmentBuildStore {
    words: alloc::vec::Vec<u32>,
    rings: alloc::vec::Vec<Ring>,
    points: alloc::vec::Vec<[f32; 2]>,
}

#[cfg(feature = "alloc")]
impl FragmentBuildMemory {
    /// Owned buffers of this size.
    pub fn allocate(&self) -> FragmentBuildStore {
        FragmentBuildStore {
            words: alloc::vec![0; self.words],
            rings: alloc::vec![Ring::default(); self.rings],
            points: alloc::vec![[0.0; 2]; self.points],
        }
    }
}

#[cfg(feature = "alloc")]
impl FragmentBuildStore {
    /// The buffers, for [`FragmentBuild::new`].
    pub fn buffers(&mut self) -> FragmentBuildBuffers<'_> {
        FragmentBuildBuffers { words: &mut self.words, rings: &mut self.rings, points: &mut self.points }
    }
}

/// Caller memory for a fragment build: each at least its [`FragmentBuildMemory`] field. The
/// build reads no element it has not written (the buffers may hold any bytes).
pub struct FragmentBuildBuffers<'a> {
    /// Scratch words.
    pub words: &'a mut [u32],
    /// Ring records.
    pub rings: &'a mut [Ring],
    /// Ring points.
    pub points: &'a mut [[f32; 2]],
}

/// Where a fragment build stands, as [`FragmentBuild::step`] reports it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FragmentProgress {
    /// Rings found so far (all of them once finished).
    pub rings: usize,
    /// Their points.
    pub points: usize,
    /// Every ring is found and every hole knows its outer ring: [`FragmentBuild::rings`] and
    /// [`FragmentBuild::points`] hold the fragments.
    pub finished: bool,
    /// Work done since the build (re)started, in the units of [`FragmentBuild::step`]'s
    /// budget.
    pub work: u64,
}

/// The passes of a build, in order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Pass {
    /// Every vertex's (and corner's) degree set to 0, [`CHUNK`] a unit.
    ClearDegrees,
    /// Every edge's alive bit cleared, [`CHUNK`] words a unit.
    ClearAlive,
    /// Per edge: alive, counted at its two ends.
    Count,
    /// Per vertex: a dead end (one edge, off the border) goes on the stack.
    DeadEnds,
    /// Per dead end popped: its edge pruned (one unit, and one per edge at the vertex).
    Prune,
    /// Per vertex: on the border with an edge left, it is listed.
    Border,
    /// The corners no crack ends at are listed.
    Corners,
    /// The border sorted along the perimeter: a heap built, one sift a piece...
    Heapify,
    /// ... then emptied from the back, one sift a piece (a unit per level sifted).
    Extract,
    /// Every vertex's (and corner's) border index set to none, [`CHUNK`] a unit.
    ClearIndex,
    /// Each border vertex's index, [`CHUNK`] a unit.
    Index,
    /// Every half-edge's walked bit cleared, [`CHUNK`] words a unit.
    ClearVisited,
    /// The outside of the plate walked (the border, clockwise), a step a piece.
    Outside,
    /// Every other face walked, a step a piece (a unit, and one per edge at the vertex
    /// reached); the rings written as they close.
    Walk,
    /// Per hole: the smallest outer ring around its first point that it does not touch, a
    /// unit per ring looked at and per point of a ring tested.
    Holes,
    /// Done.
    Done,
}

/// What identifies the state of a plate's network: a build started on one state starts over
/// when the plate it is stepped with is in another.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Stamp {
    work: u64,
    impacts: u32,
    vertices: usize,
    edges: usize,
    max_vertices: u32,
}

impl Stamp {
    fn of(glass: &Glass) -> Stamp {
        Stamp {
            work: glass.clock.work,
            impacts: glass.impacts,
            vertices: glass.vertex_count,
            edges: glass.edge_count,
            max_vertices: glass.params.max_vertices,
        }
    }
}

/// The ring being walked.
#[derive(Clone, Copy, Debug)]
struct Walking {
    /// The half-edge it started from, and the one it reached.
    start: HalfEdge,
    at: HalfEdge,
    area: f64,
    /// Its points so far (written from `first_point` on).
    points: usize,
    /// Steps taken (a walk that has not closed within the half-edges is dropped).
    steps: usize,
}

/// The hole being placed, and the outer ring being tested.
#[derive(Clone, Copy, Debug)]
struct Placing {
    /// The candidate ring, and its next point to test.
    candidate: usize,
    point: usize,
    /// Crossings of the ray from the hole's first point so far, and whether the candidate
    /// holds that point as one of its own.
    crossings: usize,
    touches: bool,
    /// The best outer ring so far and its area.
    parent: u32,
    area: f64,
}

/// A budgeted fragment build over caller memory ([`Glass::fragment_build_memory`]): made in
/// constant work by [`FragmentBuild::new`], stepped with the plate by [`FragmentBuild::step`]
/// until finished, then read whole ([`FragmentBuild::rings`], [`FragmentBuild::points`]) or
/// in ranges. A build stepped with a plate whose network changed since it began (a step or an
/// impact) starts over.
pub struct FragmentBuild<'a> {
    words: &'a mut [u32],
    rings: &'a mut [Ring],
    points: &'a mut [[f32; 2]],
    /// The plate's vertex capacity the buffers were checked for.
    capacity: usize,
    stamp: Option<Stamp>,
    pass: Pass,
    /// The pass's next item.
    item: usize,
    /// Dead ends on the stack.
    stack: usize,
    /// Border vertices listed, and the corners a crack ends at (bit k for corner k).
    border: usize,
    corners: u8,
    /// The heap's size while it is emptied.
    heap: usize,
    walking: Option<Walking>,
    placing: Option<Placing>,
    ring_count: usize,
    point_count: usize,
    work: u64,
}

impl Glass<'_> {
    /// The caller memory a [`FragmentBuild`] of this plate needs (sized by its vertex capacity,
    /// so that one build's memory serves every state of the plate).
    pub fn fragment_build_memory(&self) -> FragmentBuildMemory {
        // (Its scratch words are the plate's query scratch, which `GlassParams::memory`
        // checked to fit; the rings and points are fewer than twice as many elements.)
        FragmentBuildMemory::of(self.params.max_vertices as usize).unwrap_or(FragmentBuildMemory {
            words: usize::MAX,
            rings: usize::MAX,
            points: usize::MAX,
        })
    }
}

impl<'a> FragmentBuild<'a> {
    /// A build of `glass`'s fragments in `buffers` (each at least its
    /// [`Glass::fragment_build_memory`] field, else [`GlassError::BufferTooSmall`] naming that
    /// need, and nothing is written); the same work at any size. Nothing is written to the
    /// buffers here: [`FragmentBuild::step`] does the work.
    pub fn new(glass: &Glass, buffers: FragmentBuildBuffers<'a>) -> Result<Self, GlassError> {
        let m = glass.fragment_build_memory();
        for (have, needed) in
            [(buffers.words.len(), m.words), (buffers.rings.len(), m.rings), (buffers.points.len(), m.points)]
        {
            if have < needed {
                return Err(GlassError::BufferTooSmall { needed });
            }
        }
        Ok(FragmentBuild {
            words: buffers.words,
            rings: buffers.rings,
            points: buffers.points,
            capacity: glass.params.max_vertices as usize,
            stamp: None,
            pass: Pass::ClearDegrees,
            item: 0,
            stack: 0,
            border: 0,
            corners: 0,
            heap: 0,
            walking: None,
            placing: None,
            ring_count: 0,
            point_count: 0,
            work: 0,
        })
    }

    /// Goes on with the build of `glass`'s fragments until about `budget` units of work are
    /// done in this call, or it is finished. A unit is an array element counted or tested
    /// (16 of them where the pass only clears or fills), a step of a face walk (and one
    /// more per edge at the vertex it reaches), a sift of the border's sort by one level, or
    /// a point of a ring tested for a hole. The budget is checked between pieces, so a call
    /// does at least one piece and overruns the budget by less than one: at most one unit
    /// and one per edge at a vertex. The result does not depend on the budgets.
    ///
    /// Should the plate's network differ from the one the build began on (stepped, or hit
    /// again, since), the build starts over (its work from 0). A plate of more vertex
    /// capacity than the buffers were checked for gives [`GlassError::BufferTooSmall`] and
    /// nothing is done.
    pub fn step(&mut self, glass: &Glass, budget: u64) -> Result<FragmentProgress, GlassError> {
        let m = glass.fragment_build_memory();
        if glass.params.max_vertices as usize > self.capacity {
            let needed = [(self.words.len(), m.words), (self.rings.len(), m.rings), (self.points.len(), m.points)]
                .into_iter()
                .find(|(have, need)| have < need)
                .map_or(m.words, |(_, need)| need);
            return Err(GlassError::BufferTooSmall { needed });
        }
        let stamp = Stamp::of(glass);
        if self.stamp != Some(stamp) {
            self.restart(stamp);
        }
        let start = self.work;
        while self.pass != Pass::Done && (self.work == start || self.work - start < budget) {
            self.work += self.piece(glass);
        }
        Ok(self.progress())
    }

    /// Steps the build to its end.
    pub fn run(&mut self, glass: &Glass) -> Result<FragmentProgress, GlassError> {
        self.step(glass, u64::MAX)
    }

    /// Where the build stands.
    pub fn progress(&self) -> FragmentProgress {
        FragmentProgress {
            rings: self.ring_count,
            points: self.point_count,
            finished: self.pass == Pass::Done,
            work: self.work,
        }
    }

    /// The fragment rings, once finished (none before): [`Glass::fragments`]' rings.
    pub fn rings(&self) -> &[Ring] {
        if self.pass == Pass::Done { &self.rings[..self.ring_count] } else { &[] }
    }

    /// Their points, once finished (none before): [`Glass::fragments`]' points.
    pub fn points(&self) -> &[[f32; 2]] {
        if self.pass == Pass::Done { &self.points[..self.point_count] } else { &[] }
    }

    /// Copies rings `first..first + out.len()` (of [`FragmentBuild::rings`]) into `out`:
    /// [`GlassError::BufferTooSmall`] naming the rings there are if the range reaches past
    /// them (or the build is not finished), and nothing is written.
    pub fn copy_rings(&self, first: usize, out: &mut [Ring]) -> Result<(), GlassError> {
        copy_range(self.rings(), first, out)
    }

    /// Copies points `first..first + out.len()` (of [`FragmentBuild::points`]) into `out`, as
    /// [`FragmentBuild::copy_rings`] does.
    pub fn copy_points(&self, first: usize, out: &mut [[f32; 2]]) -> Result<(), GlassError> {
        copy_range(self.points(), first, out)
    }

    fn restart(&mut self, stamp: Stamp) {
        self.stamp = Some(stamp);
        (self.pass, self.item, self.stack, self.border, self.corners, self.heap) = (Pass::ClearDegrees, 0, 0, 0, 0, 0);
        (self.walking, self.placing) = (None, None);
        (self.ring_count, self.point_count, self.work) = (0, 0, 0);
    }

    /// Moves to `pass`, from its first item.
    fn enter(&mut self, pass: Pass) {
        self.pass = pass;
        self.item = 0;
    }

    /// Does the next piece of the pass under way; returns its units.
    fn piece(&mut self, glass: &Glass) -> u64 {
        let words = core::mem::take(&mut self.words);
        let units = self.piece_in(glass, &mut *words);
        self.words = words;
        units
    }

    /// [`FragmentBuild::piece`] with the scratch words apart.
    fn piece_in(&mut self, glass: &Glass, words: &mut [u32]) -> u64 {
        let (vertices, edges) = (glass.vertex_count, glass.edge_count);
        let (w, h) = (glass.params.width, glass.params.height);
        let corners = [[0.0, 0.0], [w, 0.0], [w, h], [0.0, h]];
        let on_border = |p: [f32; 2]| p[0] == 0.0 || p[1] == 0.0 || p[0] == w || p[1] == h;
        // (Checked in `new` for this capacity: the split cannot fail.)
        let Ok(s) = FragmentScratch::new(words, self.capacity) else {
            self.pass = Pass::Done;
            return 1;
        };
        let graph = CrackGraph { vertices: &glass.vertices[..vertices], edges: &glass.edges[..edges] };
        let point = |v: u32| {
            if (v as usize) < vertices { glass.vertices[v as usize].at } else { corners[v as usize - vertices] }
        };
        let item = self.item;
        match self.pass {
            Pass::ClearDegrees | Pass::ClearAlive | Pass::ClearIndex | Pass::ClearVisited => {
                let (array, len, value, next) = match self.pass {
                    Pass::ClearDegrees => (&mut *s.degree, vertices + 4, 0, Pass::ClearAlive),
                    Pass::ClearAlive => {
                        let n = s.alive.len();
                        (&mut *s.alive, n, 0, Pass::Count)
                    }
                    Pass::ClearIndex => (&mut *s.border_index, vertices + 4, NONE, Pass::Index),
                    _ => (&mut *s.visited, (2 * (edges + self.border)).div_ceil(32), 0, Pass::Outside),
                };
                let end = (item + CHUNK).min(len);
                array[item..end].fill(value);
                if end == len {
                    self.enter(next);
                } else {
                    self.item = end;
                }
                1
            }
            Pass::Count => {
                if item == edges {
                    self.enter(Pass::DeadEnds);
                    return 1;
                }
                let edge = &glass.edges[item];
                set_bit(s.alive, item, true);
                s.degree[edge.from as usize] += 1;
                s.degree[edge.to as usize] += 1;
                self.item += 1;
                1
            }
            Pass::DeadEnds => {
                if item == vertices {
                    self.enter(Pass::Prune);
                    return 1;
                }
                if s.degree[item] == 1 && !on_border(glass.vertices[item].at) {
                    s.border[self.stack] = item as u32;
                    self.stack += 1;
                }
                self.item += 1;
                1
            }
            Pass::Prune => {
                if self.stack == 0 {
                    self.enter(Pass::Border);
                    return 1;
                }
                self.stack -= 1;
                let v = s.border[self.stack];
                let (mut last, mut seen) = (None, 0u64);
                graph.for_each_edge_at(v, |e, half| {
                    seen += 1;
                    if bit(s.alive, e as usize) {
                        last = Some((e, half));
                    }
                });
                if let Some((e, half)) = last {
                    set_bit(s.alive, e as usize, false);
                    s.degree[v as usize] -= 1;
                    let other = graph.ends(half).1;
                    s.degree[other as usize] -= 1;
                    if s.degree[other as usize] == 1 && !on_border(graph.point(other)) {
                        s.border[self.stack] = other;
                        self.stack += 1;
                    }
                }
                1 + seen
            }
            Pass::Border => {
                if item == vertices {
                    self.enter(Pass::Corners);
                    return 1;
                }
                let at = glass.vertices[item].at;
                if s.degree[item] > 0 && on_border(at) {
                    s.border[self.border] = item as u32;
                    self.border += 1;
                    for (k, corner) in corners.iter().enumerate() {
                        if at == *corner {
                            self.corners |= 1 << k;
                        }
                    }
                }
                self.item += 1;
                1
            }
            Pass::Corners => {
                for k in 0..4 {
                    if self.corners & (1 << k) == 0 {
                        s.border[self.border] = (vertices + k) as u32;
                        self.border += 1;
                    }
                }
                self.enter(Pass::Heapify);
                self.item = self.border / 2;
                1
            }
            Pass::Heapify => {
                if item == 0 {
                    self.enter(Pass::Extract);
                    self.heap = self.border;
                    return 1;
                }
                self.item -= 1;
                let n = self.border;
                1 + sift_down(&mut s.border[..n], self.item, |a, b| along(point, w, h, a, b))
            }
            Pass::Extract => {
                if self.heap <= 1 {
                    self.enter(Pass::ClearIndex);
                    return 1;
                }
                self.heap -= 1;
                let end = self.heap;
                s.border.swap(0, end);
                1 + sift_down(&mut s.border[..end], 0, |a, b| along(point, w, h, a, b))
            }
            Pass::Index => {
                let end = (item + CHUNK).min(self.border);
                for k in item..end {
                    s.border_index[s.border[k] as usize] = k as u32;
                }
                if end == self.border {
                    self.enter(Pass::ClearVisited);
                } else {
                    self.item = end;
                }
                1
            }
            Pass::Outside | Pass::Walk | Pass::Holes => {
                let FragmentScratch { alive, border, border_index, visited, .. } = s;
                let plate = PlateGraph { cracks: graph, alive, border: &border[..self.border], border_index, corners };
                let g = Counting { graph: &plate, outs: Cell::new(0) };
                match self.pass {
                    Pass::Outside => self.outside(&g, visited),
                    Pass::Walk => self.walk(&g, visited),
                    _ => self.hole(),
                }
            }
            Pass::Done => 0,
        }
    }

    /// A step of the walk around the outside of the plate (the border clockwise, from the
    /// first border edge's reverse), marking its half-edges walked.
    fn outside(&mut self, g: &Counting, visited: &mut [u32]) -> u64 {
        let start = 2 * g.graph.edge_count() + 1;
        let w = self.walking.get_or_insert(Walking { start, at: start, area: 0.0, points: 0, steps: 0 });
        set_bit(visited, w.at as usize, true);
        w.at = next_around_face(g, w.at);
        w.steps += 1;
        if w.at == start || w.steps > g.half_edge_bound() {
            self.walking = None;
            self.enter(Pass::Walk);
        }
        1 + g.outs.get()
    }

    /// A piece of the walks around every other face: a half-edge passed over as a start (walked
    /// already, or on a pruned edge), or a step of the walk under way; a ring that closes with
    /// non-zero area is kept, its points written as it was walked.
    fn walk(&mut self, g: &Counting, visited: &mut [u32]) -> u64 {
        let half_edges = 2 * (g.graph.edge_count() as usize + self.border);
        let Some(mut w) = self.walking else {
            let start = self.item;
            if start == half_edges {
                self.enter(Pass::Holes);
                return 1;
            }
            let edge = start >> 1;
            if bit(visited, start) || (edge < g.graph.edge_count() as usize && !bit(g.graph.alive, edge)) {
                self.item += 1;
            } else {
                let h = start as HalfEdge;
                self.walking = Some(Walking { start: h, at: h, area: 0.0, points: 0, steps: 0 });
            }
            return 1;
        };
        // (Every walk comes back to its start while each vertex's edges are in a total order;
        // should one not, it stops at the first half-edge another walk took, or after as many
        // steps as there are half-edges, and is dropped: `Glass::fragments`' walk.)
        let mut ended = None;
        if bit(visited, w.at as usize) || w.steps > g.half_edge_bound() {
            ended = Some(false);
        } else {
            set_bit(visited, w.at as usize, true);
            let (u, v) = g.ends(w.at);
            let (a, b) = (g.point(u), g.point(v));
            w.area += 0.5 * shoelace(a, b);
            // (Within the buffer: a half-edge lies on one ring at most.)
            if let Some(slot) = self.points.get_mut(self.point_count + w.points) {
                *slot = a;
            }
            w.points += 1;
            w.steps += 1;
            w.at = next_around_face(g, w.at);
            if w.at == w.start {
                ended = Some(true);
            }
        }
        match ended {
            None => self.walking = Some(w),
            Some(closed) => {
                self.walking = None;
                self.item += 1;
                if closed && w.area != 0.0 && self.ring_count < self.rings.len() {
                    self.rings[self.ring_count] = Ring {
                        area: w.area,
                        first_point: self.point_count as u32,
                        point_count: w.points as u32,
                        hole_of: NOT_A_HOLE,
                        reserved: 0,
                    };
                    self.ring_count += 1;
                    self.point_count += w.points;
                }
            }
        }
        1 + g.outs.get()
    }

    /// A piece of the holes' placing: a ring looked at (an outer ring passed over, or a hole
    /// begun or ended, or a candidate outer ring passed over or begun), or a point of a
    /// candidate tested. A hole lies in the smallest outer ring around its first point that it
    /// does not touch.
    fn hole(&mut self) -> u64 {
        let i = self.item;
        if i == self.ring_count {
            self.enter(Pass::Done);
            return 1;
        }
        if self.rings[i].area > 0.0 {
            self.item += 1;
            return 1;
        }
        let q = self.points[self.rings[i].first_point as usize];
        let Some(mut p) = self.placing else {
            self.placing = Some(Placing {
                candidate: 0,
                point: 0,
                crossings: 0,
                touches: false,
                parent: NONE,
                area: f64::INFINITY,
            });
            return 1;
        };
        if p.candidate == self.ring_count {
            self.rings[i].hole_of = p.parent;
            self.placing = None;
            self.item += 1;
            return 1;
        }
        let candidate = self.rings[p.candidate];
        if !(candidate.area > 0.0 && candidate.area < p.area) {
            p.candidate += 1;
            self.placing = Some(p);
            return 1;
        }
        let outline = &self.points[candidate.first_point as usize..][..candidate.point_count as usize];
        if p.point < outline.len() {
            let (a, b) = (outline[p.point], outline[(p.point + 1) % outline.len()]);
            p.crossings += usize::from(crosses_ray(a, b, q));
            p.touches |= a == q;
            p.point += 1;
        } else {
            if p.crossings % 2 == 1 && !p.touches {
                (p.parent, p.area) = (p.candidate as u32, candidate.area);
            }
            (p.candidate, p.point, p.crossings, p.touches) = (p.candidate + 1, 0, 0, false);
        }
        self.placing = Some(p);
        1
    }
}

/// Copies `out.len()` elements of `all` from `first` into `out`, or refuses with the elements
/// there are, writing nothing.
fn copy_range<T: Copy>(all: &[T], first: usize, out: &mut [T]) -> Result<(), GlassError> {
    match first.checked_add(out.len()).and_then(|end| all.get(first..end)) {
        Some(range) => {
            out.copy_from_slice(range);
            Ok(())
        }
        None => Err(GlassError::BufferTooSmall { needed: all.len() }),
    }
}

/// Whether border vertex `a` comes before `b` along the perimeter (counter-clockwise from
/// (0, 0); ties, which only the same point gives, by index): the order of
/// [`Glass::fragments`]' sort, a total order on distinct vertices, so any sort gives the same
/// list.
fn along(point: impl Fn(u32) -> [f32; 2], w: f32, h: f32, a: u32, b: u32) -> bool {
    let (pa, pb) = (perimeter(point(a), w, h), perimeter(point(b), w, h));
    pa.0.cmp(&pb.0).then(pa.1.total_cmp(&pb.1)).then(a.cmp(&b)).is_lt()
}

/// Sifts `heap[i]` down a max-heap ordered by `less`; returns the levels it moved.
fn sift_down(heap: &mut [u32], mut i: usize, less: impl Fn(u32, u32) -> bool) -> u64 {
    let mut levels = 0;
    loop {
        let (l, r) = (2 * i + 1, 2 * i + 2);
        let mut top = i;
        if l < heap.len() && less(heap[top], heap[l]) {
            top = l;
        }
        if r < heap.len() && less(heap[top], heap[r]) {
            top = r;
        }
        if top == i {
            return levels;
        }
        heap.swap(i, top);
        i = top;
        levels += 1;
    }
}

/// A plate graph that counts the half-edges its walks look at around each vertex (the part of
/// a walk's step that grows with the vertex's edges).
struct Counting<'g, 'p> {
    graph: &'g PlateGraph<'p>,
    outs: Cell<u64>,
}

impl PlaneGraph for Counting<'_, '_> {
    fn point(&self, v: u32) -> [f32; 2] {
        self.graph.point(v)
    }

    fn ends(&self, h: HalfEdge) -> (u32, u32) {
        self.graph.ends(h)
    }

    fn for_each_out(&self, v: u32, mut visit: impl FnMut(HalfEdge, f32)) {
        self.graph.for_each_out(v, |h, angle| {
            self.outs.set(self.outs.get() + 1);
            visit(h, angle);
        });
    }

    fn angle(&self, h: HalfEdge) -> f32 {
        self.graph.angle(h)
    }

    fn half_edge_bound(&self) -> usize {
        self.graph.half_edge_bound()
    }
}
