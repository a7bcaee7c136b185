//! The crack network: one line per physical crack, as a plane graph.
//!
//! The paper's Fig. 5 tracing (see [`super::trace`]) draws a straight crack on the lattice as
//! dashes. A crack perpendicular to one spring family breaks that family only; the springs
//! that bridge it at 60° are stretched by about half the opening, stay below their break
//! stretch, and each mesh cell they cross holds one broken side: a dead end. On the default
//! run the broken springs alone leave every node in one piece and no cell closes.
//!
//! The network is traced from the physics instead, by three rules:
//!
//! 1. **A crack tip continues across a separated side.** A mesh cell with exactly one cut
//!    side holds a crack tip. Of its intact sides, the one whose nodes have moved apart most,
//!    relative to what that spring can bridge, is cut too if they have moved apart by more:
//!    if |x_j − x_i − l·e_ij| > (κ_ij − 1)·l, with l the rest length now and e_ij the spring's
//!    direction. This is the paper's break rule (Eq. 5, l > κ·l) applied to the separation
//!    vector rather than to its component along the spring: the material between the two
//!    nodes has opened by more than it can stretch, though the opening runs across the
//!    spring. The cell on the other side of a newly cut spring may now hold a tip, and the rule
//!    repeats until no tip can continue. A continued crack takes the break time of the tip it
//!    continues.
//!
//!    **A tip one node from another crack joins it.** On the triangle meshes (hexagonal and
//!    irregular), if the node opposite a tip's cut side already borders another crack (one of
//!    its springs is cut), the crack runs on around that node to it: its springs between the
//!    tip and the other crack are cut, the shorter way round (at a tie, the way whose first
//!    spring has separated more). Seen as elements (each node the Voronoi cell of material
//!    around it, each spring the face two of them share), the tip has reached a corner of
//!    that node's element and the other crack runs along another of its faces: the only
//!    material left between them is one element, the smallest piece the lattice resolves,
//!    whose stress the tip's concentrated load and the other crack's free face would share
//!    inside it. The lattice cannot arrest a crack in less than an element, so it does not
//!    end there; isolated breaks one node apart join the same way. (Without this rule and
//!    the next, dead ends were 12–15 % of the default run's vertices of degree ≠ 2 on the
//!    hexagonal lattice and 25–27 % on the irregular one; most tips stopped with their
//!    most separated side at 0.8–1 of what it can bridge, many one node short.)
//!
//!    **A dead-end crack that has not opened is closed.** The converse of the first rule: a
//!    crack from a tip to its junction (or to its other tip) across none of whose springs the
//!    surface has separated by more than (κ − 1)·l is no crack of the network: the material
//!    on either side lies as close as an intact spring could hold it (a branch unloaded by
//!    the crack it left, or a break the cracks around it have pressed shut). Only whole
//!    dead-end cracks are closed, so the network stays connected and no cell changes.
//! 2. **A single node is not a cell.** Where the cracks have cut every spring of one node (a
//!    crack that splits around a node and joins again, which the first rule makes at some
//!    junctions), the crack passes the node on one side: on the triangle meshes, if two or
//!    more cracks leave the ring of cut springs around the node, the arc of its springs
//!    between two of them whose most separated spring has separated least is no longer cut
//!    (the node stays with that side). A ring with fewer ways out (closed, or one crack in)
//!    stays in the network, and the node stays joined, for the cells, to the neighbour it is
//!    least separated from. The cells get no fragment one node wide (before this rule about
//!    a quarter of the default run's cells were such crumbs).
//! 3. **Cracks that end inside a region do not cut it.** For the cells (faces), branches are
//!    pruned: a mesh cell with exactly one separating side has a dead end in it, that side is
//!    marked a branch, and so on back to the junction. Branches stay in the network; they do
//!    not bound a cell.
//!
//! The network's points are the cut springs' midpoints, smoothed along their cracks (see
//! `Mud::smoothing_offset`: the lattice places a crack only to within an element, and the
//! zigzag between the midpoints of neighbouring triangle sides is the mesh's, not the
//! crack's), and the centroids of the mesh cells where cracks end (one cut side) or meet
//! (three or more); Fig. 5's rule draws the pieces between them. Its vertices are those centroids, and, on open lattices, the midpoints of
//! cut springs on the plate's border; its edges are the chains of points between vertices.
//! The opening (width) at a point is the separation |x_j − x_i − l·e_ij| of its spring.

use super::cells::RingCursor;
use super::lattice::Cell;
use super::{INTACT, Mud};
use crate::scalar::Scalar;

/// Marks a cut spring on a branch: its crack ends inside a region, so it does not separate
/// cells (bit 31 of the trace word, whose other bits hold an `f32` time ≥ 0).
pub(super) const BRANCH: u32 = 1 << 31;

/// Points along a crack each way that place one of its points (see `Mud::smoothing_offset`).
const SMOOTHING: usize = 4;

/// Binomial weights of the points 1 to [`SMOOTHING`] away along a crack, each way: row 8 of
/// Pascal's triangle over 256 (the point itself, 70/256, stays where it is).
const SMOOTHING_WEIGHTS: [f32; SMOOTHING + 1] = [70.0 / 256.0, 56.0 / 256.0, 28.0 / 256.0, 8.0 / 256.0, 1.0 / 256.0];

/// Crack offsets are stored in steps of 1/`OFFSET_UNITS` lattice units (±16 units fit).
pub(super) const OFFSET_UNITS: f32 = 2048.0;

/// How many times a crack point's smoothing offset is halved, at most, to keep the point in
/// its spring's region (see `Mud::packed_offset`) before it is dropped.
const OFFSET_HALVINGS: u32 = 6;

/// Twice the signed area of the triangle `a`, `b`, `p` (positive: `p` left of `a` → `b`),
/// computed in `f64`.
fn side_of(a: [f32; 2], b: [f32; 2], p: [f32; 2]) -> f64 {
    let f = |v: [f32; 2]| [f64::from(v[0]), f64::from(v[1])];
    let (a, b, p) = (f(a), f(b), f(p));
    (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])
}

/// Whether `p` lies strictly inside the triangle `a`, `b`, `c` (either orientation; never
/// inside a degenerate one).
fn strictly_inside(p: [f32; 2], a: [f32; 2], b: [f32; 2], c: [f32; 2]) -> bool {
    let (d1, d2, d3) = (side_of(a, b, p), side_of(b, c, p), side_of(c, a, p));
    (d1 > 0.0 && d2 > 0.0 && d3 > 0.0) || (d1 < 0.0 && d2 < 0.0 && d3 < 0.0)
}

/// No vertex: the ends of a closed crack with no junction on it.
pub const NO_VERTEX: u32 = u32::MAX;

/// A junction or an end of the crack network. In C: `hibi_mud_network_vertex`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C)]
pub struct NetworkVertex {
    /// Position (x, y) on the deformed surface, lattice units (multiply by `element_size`
    /// for cm).
    pub at: [f32; 2],
    /// Edges meeting here: 1 at a crack's end, 3 or more at a junction.
    pub degree: u32,
    /// 1 where a crack reaches the plate's open border (an end that is not a dead end), else 0.
    pub on_border: u32,
}

/// A point of a network edge's polyline. In C: `hibi_mud_network_point`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C)]
pub struct NetworkPoint {
    /// Position (x, y), lattice units (multiply by `element_size` for cm). On periodic
    /// lattices an edge is continuous and may reach past the domain: draw it wrapped.
    pub at: [f32; 2],
    /// Opening of the crack here, lattice units: the separation of the spring it crosses;
    /// 0 at a dead end.
    pub width: f32,
    /// Break time here, in long steps T.
    pub time: f32,
}

/// A crack between two vertices: the polyline of `point_count` points from `first_point` on
/// in the point buffer. In C: `hibi_mud_network_edge`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C)]
pub struct NetworkEdge {
    /// The vertex it starts at, or `NO_VERTEX` (C: `HIBI_MUD_NO_VERTEX`) for a closed crack
    /// with no junction.
    pub from: u32,
    /// The vertex it ends at, or `NO_VERTEX`.
    pub to: u32,
    /// Index of its first point in the point buffer.
    pub first_point: u32,
    /// Points in its polyline, both ends included (a closed crack repeats its first point).
    pub point_count: u32,
}

/// How many vertices, edges and points [`Mud::network`] writes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct NetworkCounts {
    /// Vertices (junctions and ends).
    pub vertices: usize,
    /// Edges (cracks between vertices, and closed cracks).
    pub edges: usize,
    /// Points of all edges' polylines.
    pub points: usize,
}

/// A mesh cell as the network sees it: where its corners are now (in one continuous frame)
/// and which of its sides are cut.
#[derive(Clone, Copy)]
pub(super) struct TracedCell {
    pub(super) index: usize,
    pub(super) cell: Cell,
    /// Corner positions, deformed, in the frame shifted by `wrap` periods.
    pub(super) corner: [[f32; 2]; 4],
    /// Cut sides (branches included).
    pub(super) cut: [bool; 4],
    /// Sides that separate cells (cut, not a branch).
    pub(super) separating: [bool; 4],
}

impl TracedCell {
    pub(super) fn sides(&self) -> usize {
        self.cell.corners
    }

    pub(super) fn cut_count(&self) -> usize {
        self.cut[..self.sides()].iter().filter(|&&c| c).count()
    }

    pub(super) fn separating_count(&self) -> usize {
        self.separating[..self.sides()].iter().filter(|&&c| c).count()
    }

    /// The midpoint of side `k`.
    pub(super) fn midpoint(&self, k: usize) -> [f32; 2] {
        let (p, q) = (self.corner[k], self.corner[(k + 1) % self.sides()]);
        [(p[0] + q[0]) * 0.5, (p[1] + q[1]) * 0.5]
    }

    /// The centroid of the corners.
    pub(super) fn centroid(&self) -> [f32; 2] {
        let n = self.sides();
        let sum = self.corner[..n].iter().fold([0.0f32; 2], |s, p| [s[0] + p[0], s[1] + p[1]]);
        [sum[0] / n as f32, sum[1] / n as f32]
    }
}

/// The most work one piece of the tracing does ([`Mud::step`]'s units): a node whose
/// springs are all cut, at most 16, counted four times (the arc of them left uncut is chosen
/// by turning about the node). A tip that joins a crack one node away does at most 3 + 3·16.
pub const TRACE_PIECE: u64 = 4 * super::irregular::MAX_DEGREE as u64;

/// Springs, mesh cells and nodes are flagged one bit each, this many to a word: a trace's pass
/// reads a word of flags as one unit of work and visits only the items flagged in it.
pub(super) const BLOCK: usize = 32;

/// The words of flags whose first item lies in `from..end`.
pub(super) fn blocks_from(from: usize, end: usize) -> core::ops::Range<usize> {
    from.div_ceil(BLOCK)..end.div_ceil(BLOCK)
}

/// Sets the flag of item `at`.
pub(super) fn set_bit(flags: &mut [u32], at: usize) {
    flags[at / BLOCK] |= 1 << (at % BLOCK);
}

/// The first flagged item from `at` on in `at`'s word of flags (`Ok`), or, if there is none
/// before `end`, where the next word begins (`Err`, at most `end`): a pass reads a word's
/// flags it finds nothing in as one unit of work, and goes to a flagged item for nothing more
/// than the item's own.
pub(super) fn next_flagged(flags: &[u32], at: usize, end: usize) -> Result<usize, usize> {
    let rest = flags[at / BLOCK] >> (at % BLOCK);
    let word_end = ((at / BLOCK + 1) * BLOCK).min(end);
    match at + rest.trailing_zeros() as usize {
        flagged if rest != 0 && flagged < end => Ok(flagged),
        _ => Err(word_end),
    }
}

/// One bit per spring, mesh cell and node: set if the trace that wrote a copy of the network
/// cut the spring, or a spring of the cell or node (clear elsewhere: nothing there is cut, and
/// the trace's passes, which would do nothing there, pass over it).
pub(super) struct Touched<'a> {
    pub(super) springs: &'a mut [u32],
    pub(super) cells: &'a mut [u32],
    pub(super) nodes: &'a mut [u32],
}

/// The network's words a trace writes, kept twice (see [`Mud::step`]): the run's own fields
/// hold the network shown, and these the one a trace under way builds. A trace swaps them in
/// for its pieces and out again, and keeps them in when it is done: the network shown is
/// always one whole trace, never part of one.
pub(super) struct TraceBuffers<'a> {
    /// Per spring: the cut (break time, `BRANCH`) or `INTACT`.
    pub(super) trace: &'a mut [u32],
    /// Per spring: where its crack point lies.
    pub(super) crack_offset: &'a mut [u32],
    /// Per mesh cell: the tracing's stack, then the cell's first vertex.
    pub(super) stack: &'a mut [u32],
    /// Per mesh cell: the cells' ring starts.
    pub(super) ring_starts: &'a mut [u32],
    /// What its trace counted of the network.
    pub(super) totals: Totals,
    /// The blocks its trace touched.
    pub(super) touched: Touched<'a>,
}

/// What a trace counts of the network it writes, so that the outputs' counts need no walk
/// along it ([`Mud::network_counts`], [`Mud::cell_counts`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(super) struct Totals {
    /// Vertices (numbered in mesh cell order: `stack` holds each cell's first).
    pub(super) vertices: u32,
    /// The degrees of the vertices at mesh cells' centroids, summed: the edges' ends there,
    /// each a point of its edge.
    pub(super) centroid_degrees: u64,
    /// Vertices on the open border: one edge end each, whose point is its spring's.
    pub(super) border_vertices: u64,
    /// Cut springs (branches included): each a point of one edge or closed crack.
    pub(super) cut_springs: u64,
    /// The rings of the cells that close in the plane, and their points.
    pub(super) rings: u64,
    pub(super) ring_points: u64,
    /// The rings that wrap around a periodic lattice.
    pub(super) wrapping: u64,
    /// Branches that rule 2 began (a ring of cut springs about one node that no crack leaves:
    /// the only way a closed crack of branches comes about).
    pub(super) node_branches: u32,
    /// Closed cracks (no vertex on them), counted twice (once from each side: a closed crack
    /// of separating springs bounds two rings, one of branches is walked both ways), and the
    /// lowest and the highest of their lowest springs (each is found from its lowest spring:
    /// [`Mud::closed_cracks`]).
    pub(super) closed_twice: u64,
    pub(super) closed_springs: [u32; 2],
}

/// Where a trace under way stands: the pass, and the item it goes on with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum TracePass {
    /// The last trace into these words undone, by block of springs (its cuts), mesh cells and
    /// nodes (their flags).
    Clean(usize),
    /// Break times into the trace, by spring.
    Breaks(usize),
    /// Rule 1: stacking the mesh cells with one cut side, by cell.
    StackTips(usize),
    /// Rule 1: continuing the stacked tips.
    Continue,
    /// Rule 1: closing dead ends that have not opened, by cell, and the walk along one.
    DeadEnds(usize, Option<DeadEndWalk>),
    /// Rule 2, by node.
    Nodes(usize),
    /// Rule 3: stacking the mesh cells with one separating side, by cell.
    StackBranches(usize),
    /// Rule 3: pruning the stacked branches.
    Prune,
    /// Vertex numbering, by cell.
    Number(usize),
    /// Crack points, by spring.
    Offsets(usize),
    /// The closed cracks of branches, by mesh cell, and the walk along one.
    Closed(ClosedCursor),
    /// The cells' ring starts.
    Rings(super::cells::RingCursor),
}

/// A walk along a dead-end crack, where it stands.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum DeadEndWalk {
    /// Checking whether the crack has opened: spring `spring` of mesh cell `at` is next,
    /// `steps` springs from the tip.
    Check { at: usize, spring: usize, steps: usize },
    /// Closing it: mesh cell `at`'s cut spring is next.
    Close { at: usize },
}

/// Where the count of the closed cracks stands: the mesh cell whose chain is next, and the
/// walk along it under way.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct ClosedCursor {
    cell: usize,
    walk: Option<ChainWalk>,
}

impl ClosedCursor {
    const START: ClosedCursor = ClosedCursor { cell: 0, walk: None };
}

/// A walk along a chain of mesh cells with two cut sides each, from the cursor's cell: the
/// cell it is in and the side it leaves by, its steps, the lowest spring it has crossed, and
/// whether it is the walk the other way from the start (the chain has an end).
#[derive(Clone, Copy, Debug, PartialEq)]
struct ChainWalk {
    at: usize,
    out: usize,
    steps: usize,
    lowest: u32,
    back: bool,
}

/// The ring-start word's bit (`cells` uses the bits below them) that marks a mesh cell a
/// branch passes through (two cut sides, neither separating), for the count of the closed
/// cracks ...
const CHAIN_CELL: u32 = 1 << 12;
/// ... and the one that marks such a cell whose chain it has walked.
const CHAIN_WALKED: u32 = 1 << 13;

/// Where a walk along the network ends: a vertex, and the side of its cell it arrived by.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
struct Arrival {
    vertex: u32,
    side: usize,
}

impl<S: Scalar> Mud<'_, S> {
    /// Whether `spring` is cut in the traced network (branches included).
    pub(super) fn is_cut(&self, spring: usize) -> bool {
        cut(self.trace[spring])
    }

    /// Whether `spring` separates two cells (cut and not a branch).
    pub(super) fn separates(&self, spring: usize) -> bool {
        separating(self.trace[spring])
    }

    /// The break time of a cut spring, long steps.
    fn cut_time(&self, spring: usize) -> f32 {
        f32::from_bits(self.trace[spring] & !BRANCH)
    }

    /// The separation of `spring`'s nodes from their rest arrangement,
    /// |x_j − x_i − l·e_ij|, lattice units (see the module docs).
    pub(super) fn separation(&self, spring: usize) -> f32 {
        let Some((a, b)) = self.spring_ends(spring) else {
            return 0.0;
        };
        let e = self.lattice.spring_vector(spring);
        let (rest, deep) = self.factors();
        let l0 = self.lattice.rest_length(spring);
        let (rest, deep) = (rest.to_f32() * l0, deep.to_f32() * l0);
        let (ax, ay) = self.displacement(a);
        let (bx, by) = self.displacement(b);
        let dx = e[0] * (deep - rest) + (bx - ax).to_f32();
        let dy = e[1] * (deep - rest) + (by - ay).to_f32();
        libm::hypotf(dx, dy)
    }

    /// How far `spring` has separated relative to what it can bridge: separation over
    /// (κ − 1)·l.
    fn separation_ratio(&self, spring: usize) -> f32 {
        let (rest, _) = self.factors();
        let margin = (self.break_stretch[spring].to_f32() - 1.0) * rest.to_f32() * self.lattice.rest_length(spring);
        if margin <= 0.0 { f32::INFINITY } else { self.separation(spring) / margin }
    }

    /// Cut sides of mesh cell `cell` (0 if it does not exist).
    fn cuts_in(&self, cell: usize, separating_only: bool) -> usize {
        let Some(c) = self.lattice.cell(cell) else {
            return 0;
        };
        let counted = |s: u32| if separating_only { self.separates(s as usize) } else { self.is_cut(s as usize) };
        c.sides[..c.corners].iter().filter(|&&s| counted(s)).count()
    }

    /// Traces the network of the cracks as they stand (see the module docs), in one call, work
    /// no budget counts. [`Mud::step`] traces live, in pieces within its budgets; call this to
    /// see the network of the springs broken right now (a trace under way is dropped). The
    /// network, the cells, the statistics and the rasters describe the state last traced.
    /// While the setup is under way (the first steps: see [`Mud::step`]) nothing has cracked
    /// and this does nothing.
    pub fn trace(&mut self) {
        if !self.is_set_up() {
            return;
        }
        self.start_trace();
        self.trace_step(u64::MAX);
    }

    /// Whether the final trace is under way: the physics has ended and the run is finished
    /// when the network of its cracks is traced. (The live traces, while the physics goes on,
    /// run within the same calls as the physics: see [`Mud::step`].) The outputs that read the
    /// network (network, cells, statistics, rasters) show the last network traced meanwhile.
    pub fn is_tracing(&self) -> bool {
        self.finished && self.tracing.is_some()
    }

    /// Springs broken when the network the outputs show was traced (0 before the first
    /// trace): it never falls, and the run's last network shows all of
    /// [`MudProgress::broken_springs`](super::MudProgress::broken_springs).
    pub fn shown_broken_springs(&self) -> u32 {
        self.shown_broken
    }

    /// Whether the outputs that read the network show it: not while the setup is under way
    /// (nothing has cracked then).
    pub(super) fn shows_network(&self) -> bool {
        self.is_set_up()
    }

    /// Begins a trace of the springs broken now into the network's other words (a trace
    /// under way is dropped).
    pub(super) fn start_trace(&mut self) {
        self.tracing = Some(TracePass::Clean(0));
        self.trace_top = 0;
        self.traced_broken = self.broken;
    }

    /// Swaps the network's words with their other copy (see [`TraceBuffers`]).
    fn swap_buffers(&mut self) {
        core::mem::swap(&mut self.trace, &mut self.back.trace);
        core::mem::swap(&mut self.crack_offset, &mut self.back.crack_offset);
        core::mem::swap(&mut self.stack, &mut self.back.stack);
        core::mem::swap(&mut self.ring_starts, &mut self.back.ring_starts);
        core::mem::swap(&mut self.totals, &mut self.back.totals);
        core::mem::swap(&mut self.touched, &mut self.back.touched);
    }

    /// Goes on with the trace under way, piece by piece, until the pieces' work reaches
    /// `max(budget, 1)` or the trace is done; returns the work, in the units of
    /// [`Mud::step`]'s budget. A piece is one item of one of the passes below, each at most
    /// [`TRACE_PIECE`] units: a spring (1; broken, 3 with the flags it sets; its crack point,
    /// 1 + 3·2·4 for the mesh cells along the crack), a mesh
    /// cell (its sides), a cell taken off a stack (its sides; twice more if a crack goes on
    /// from it; the springs turned about if it joins a crack one node away), a node (its
    /// springs; four times if all are cut), or one step of a walk along a dead-end crack (1), a
    /// cell's boundary or a chain of mesh cells with two cut sides (3: the next mesh cell's
    /// corners); a pass visits only the items the cracks touch, and a word of 32
    /// flags with none of them flagged is one piece (1); undoing the last trace in the copy
    /// of the network's words the trace writes is a word of flags and the springs cut in it
    /// (at most 33). The walks are resumed where they stopped, so no piece depends on a
    /// crack's length. The trace does not depend on the budgets.
    pub(super) fn trace_step(&mut self, budget: u64) -> u64 {
        let mut swapped = false;
        let work = self.trace_step_swapped(budget, &mut swapped);
        self.unswap(&mut swapped);
        work
    }

    /// [`Mud::trace_step`], leaving the words of a trace under way in front (`swapped`: the
    /// trace's copy is in front, as [`Mud::unswap`] puts back). Calls between which nothing
    /// reads the network (a run's physics does not) swap the two copies once, not every time.
    pub(super) fn trace_step_swapped(&mut self, budget: u64, swapped: &mut bool) -> u64 {
        let budget = budget.max(1);
        let mut work = 0u64;
        if self.tracing.is_none() {
            return 0;
        }
        // The trace works in the other copy of the network's words, the shown network stays.
        if !*swapped {
            self.swap_buffers();
            *swapped = true;
        }
        while let Some(pass) = self.tracing {
            if work >= budget {
                break;
            }
            let (done, next) = self.trace_pass(pass, budget - work);
            work += done;
            self.tracing = next;
        }
        if self.tracing.is_none() {
            // Done: its words are the network shown now.
            self.shown_broken = self.traced_broken;
            self.shown_traces = self.shown_traces.wrapping_add(1);
            *swapped = false;
        }
        work
    }

    /// Puts the shown network's words back in front after [`Mud::trace_step_swapped`].
    pub(super) fn unswap(&mut self, swapped: &mut bool) {
        if *swapped {
            self.swap_buffers();
            *swapped = false;
        }
    }

    /// Does items of `pass` until their work reaches `budget` or the pass ends; returns the
    /// work and where the trace stands then (`None`: done).
    fn trace_pass(&mut self, pass: TracePass, budget: u64) -> (u64, Option<TracePass>) {
        let cells = self.lattice.cell_count();
        let springs = self.lattice.spring_count();
        let corners = self.lattice.sides_per_cell() as u64;
        let mut work = 0u64;
        // Items `from..end` one by one, each costing what `item` returns, until the budget; a
        // block whose flag in `flags` is 0 is passed over as one unit (nothing in it is cut,
        // so `item` would do nothing there).
        macro_rules! items {
            ($from:expr, $end:expr, $flags:expr, $item:expr) => {{
                let mut at = $from;
                while at < $end && work < budget {
                    at = match next_flagged($flags, at, $end) {
                        Ok(flagged) => flagged,
                        Err(word_end) => {
                            work += 1;
                            word_end
                        }
                    };
                    if at < $end {
                        work += $item(&mut *self, at);
                        at += 1;
                    }
                }
                at
            }};
        }
        let next = match pass {
            TracePass::Clean(from) => {
                let blocks =
                    [springs.div_ceil(BLOCK), cells.div_ceil(BLOCK), self.lattice.node_count().div_ceil(BLOCK)];
                let end: usize = blocks.iter().sum();
                let mut at = from;
                while at < end && work < budget {
                    work += 1;
                    if at < blocks[0] {
                        let mut flags = self.touched.springs[at];
                        while flags != 0 {
                            self.trace[at * BLOCK + flags.trailing_zeros() as usize] = INTACT;
                            flags &= flags - 1;
                            work += 1;
                        }
                        self.touched.springs[at] = 0;
                    } else if at < blocks[0] + blocks[1] {
                        self.touched.cells[at - blocks[0]] = 0;
                    } else {
                        self.touched.nodes[at - blocks[0] - blocks[1]] = 0;
                    }
                    at += 1;
                }
                if at < end { TracePass::Clean(at) } else { TracePass::Breaks(0) }
            }
            TracePass::Breaks(from) => {
                // Break times are ≥ 0 (−0 at the very start, whose sign bit is cleared here).
                let at = items!(from, springs, self.broken_blocks, |m: &mut Self, s: usize| {
                    let time = m.break_time[s];
                    m.trace[s] = if time == INTACT { INTACT } else { time & !BRANCH };
                    if time != INTACT {
                        // Its flags, and those of its two mesh cells and two nodes.
                        m.touch(s);
                        return 3;
                    }
                    1
                });
                if at < springs { TracePass::Breaks(at) } else { TracePass::StackTips(0) }
            }
            // 1. Tips continue across separated sides. Counts only grow, so a mesh cell
            //    reaches one cut side at most once and the stack holds each cell at most once.
            TracePass::StackTips(from) => {
                let at = items!(from, cells, self.touched.cells, |m: &mut Self, cell: usize| {
                    m.trace_top = m.stack_single_cuts(cell..cell + 1, usize::MAX, m.trace_top, false);
                    corners
                });
                if at < cells { TracePass::StackTips(at) } else { TracePass::Continue }
            }
            TracePass::Continue => {
                while self.trace_top > 0 && work < budget {
                    work += corners + self.continue_tip();
                }
                if self.trace_top > 0 { TracePass::Continue } else { TracePass::DeadEnds(0, None) }
            }
            //    Dead-end cracks that have not opened are closed (the tips left after the rules
            //    above; closing one leaves its junction with two or more cut sides: no new tip).
            TracePass::DeadEnds(mut cell, mut walk) => {
                while cell < cells && work < budget {
                    if walk.is_none() {
                        match next_flagged(self.touched.cells, cell, cells) {
                            Ok(flagged) => cell = flagged,
                            Err(word_end) => {
                                work += 1;
                                cell = word_end;
                                continue;
                            }
                        }
                    }
                    match walk {
                        None => {
                            work += corners;
                            walk = self.dead_end_start(cell);
                        }
                        Some(w) => {
                            work += 1;
                            walk = self.dead_end_walk(cell, w);
                        }
                    }
                    if walk.is_none() {
                        cell += 1;
                    }
                }
                if cell < cells { TracePass::DeadEnds(cell, walk) } else { TracePass::Nodes(0) }
            }
            // 2. A node whose springs are all cut is not a cell of its own (see the module
            //    docs).
            TracePass::Nodes(from) => {
                if from == 0 {
                    self.totals = Totals::default();
                }
                let nodes = self.lattice.node_count();
                let at = items!(from, nodes, self.touched.nodes, |m: &mut Self, node: usize| m.separate_node(node));
                if at < nodes { TracePass::Nodes(at) } else { TracePass::StackBranches(0) }
            }
            // 3. Branches: counts only fall, so again each cell is stacked at most once.
            TracePass::StackBranches(from) => {
                let at = items!(from, cells, self.touched.cells, |m: &mut Self, cell: usize| {
                    m.trace_top = m.stack_single_cuts(cell..cell + 1, usize::MAX, m.trace_top, true);
                    corners
                });
                if at < cells { TracePass::StackBranches(at) } else { TracePass::Prune }
            }
            TracePass::Prune => {
                while self.trace_top > 0 && work < budget {
                    work += corners + self.prune_branch();
                }
                if self.trace_top > 0 { TracePass::Prune } else { TracePass::Number(0) }
            }
            // 4. Vertex numbering: each cell's first vertex index (its centroid if cracks end
            //    or meet there, then the cut sides of it on the border), so vertices are
            //    numbered in cell order. The cells' ring starts are cleared on the way, and the
            //    cells a branch passes through marked for the closed cracks.
            TracePass::Number(from) => {
                // A block no crack touches holds no vertex (and its words are not read).
                let at = items!(from, cells, self.touched.cells, |m: &mut Self, cell: usize| {
                    m.stack[cell] = m.totals.vertices;
                    let (degree, border, branch) = m.vertices_in(cell);
                    m.totals.vertices += u32::from(degree > 0) + border as u32;
                    m.totals.centroid_degrees += degree as u64;
                    m.totals.border_vertices += border as u64;
                    m.ring_starts[cell] = if branch { CHAIN_CELL } else { 0 };
                    corners
                });
                if at < cells { TracePass::Number(at) } else { TracePass::Offsets(0) }
            }
            // 5. Where each crack point lies (the vertices are numbered: walks can end).
            TracePass::Offsets(from) => {
                let at = items!(from, springs, self.touched.springs, |m: &mut Self, spring: usize| {
                    m.crack_offset[spring] = 0;
                    if !m.is_cut(spring) {
                        return 1;
                    }
                    m.totals.cut_springs += 1;
                    m.crack_offset[spring] = m.packed_offset(spring);
                    1 + 2 * SMOOTHING as u64 * super::cells::RING_STEP
                });
                match at {
                    _ if at < springs => TracePass::Offsets(at),
                    // Without a branch from rule 2 no closed crack is one of branches.
                    _ if self.totals.node_branches == 0 => TracePass::Rings(RingCursor::START),
                    _ => TracePass::Closed(ClosedCursor::START),
                }
            }
            // 6. The closed cracks of branches (those of separating springs are counted with
            //    the rings below): how many, and where the lowest springs they are found from
            //    lie (the outputs' counts and the edges' pass need no search for them).
            TracePass::Closed(cursor) => {
                let (done, cursor) = self.count_closed(cursor, budget);
                work += done;
                match cursor {
                    Some(c) => TracePass::Closed(c),
                    None => TracePass::Rings(RingCursor::START),
                }
            }
            // 7. The cells' rings: where each one starts (see `cells`).
            TracePass::Rings(cursor) => {
                let (done, cursor) = self.find_ring_starts(cursor, budget);
                work += done;
                match cursor {
                    Some(c) => TracePass::Rings(c),
                    None => return (work, None),
                }
            }
        };
        (work, Some(next))
    }

    /// Rule 1 for the cell on top of the stack: if it still holds a tip, the tip continues
    /// across its most separated intact side if that has separated by more than it can
    /// bridge, or else joins a crack one node away. Returns the work beyond the cell's sides.
    fn continue_tip(&mut self) -> u64 {
        self.trace_top -= 1;
        let cell = self.stack[self.trace_top] as usize;
        let Some(c) = self.lattice.cell(cell) else { return 0 };
        let sides = &c.sides[..c.corners];
        if sides.iter().filter(|&&s| self.is_cut(s as usize)).count() != 1 {
            return 0;
        }
        let Some(tip) = sides.iter().map(|&s| s as usize).find(|&s| self.is_cut(s)) else { return 0 };
        let mut best: Option<(f32, usize)> = None;
        for &s in sides {
            let s = s as usize;
            if !self.is_cut(s) {
                let ratio = self.separation_ratio(s);
                if best.is_none_or(|(b, _)| ratio > b) {
                    best = Some((ratio, s));
                }
            }
        }
        let Some((ratio, spring)) = best else { return 0 };
        if ratio <= 1.0 {
            // The tip stops here, unless it is one node from another crack. Cutting around
            // that node gives every mesh cell on the way two or more cut sides: no new tip.
            return self.join_across_node(cell, tip);
        }
        self.trace[spring] = self.trace[tip];
        self.touch(spring);
        self.trace_top = self.stack_single_cuts(self.neighbours_across(spring), cell, self.trace_top, false);
        2 * c.corners as u64
    }

    /// Flags the blocks of cut `spring`, its mesh cells and its nodes as touched by the trace.
    fn touch(&mut self, spring: usize) {
        set_bit(self.touched.springs, spring);
        for (cell, _) in self.lattice.cells_of_spring(spring).into_iter().flatten() {
            set_bit(self.touched.cells, cell);
        }
        if let Some((a, b)) = self.spring_ends(spring) {
            set_bit(self.touched.nodes, a);
            set_bit(self.touched.nodes, b);
        }
    }

    /// Rule 3 for the cell on top of the stack: if one side of it still separates, that side
    /// is a branch, and the cells across it are stacked. Returns the work beyond its sides.
    fn prune_branch(&mut self) -> u64 {
        self.trace_top -= 1;
        let cell = self.stack[self.trace_top] as usize;
        let Some(c) = self.lattice.cell(cell) else { return 0 };
        let mut separating = c.sides[..c.corners].iter().map(|&s| s as usize).filter(|&s| self.separates(s));
        let (Some(spring), None) = (separating.next(), separating.next()) else { return 0 };
        self.trace[spring] |= BRANCH;
        self.trace_top = self.stack_single_cuts(self.neighbours_across(spring), cell, self.trace_top, true);
        2 * c.corners as u64
    }

    /// Rule 2 for `node`: if all its springs are cut, on the triangle meshes where two or
    /// more cracks leave the ring around it, the crack passes it on one side: the arc of its
    /// springs between two cracks that has separated least is no longer cut (the node stays
    /// with that side). Otherwise (a closed ring, or one crack in) it stays joined, for the
    /// cells, to the neighbour it is least separated from (that spring no longer separates,
    /// and the pruning of rule 3 takes back what then ends inside a cell). Returns the work:
    /// its springs, four times if all are cut.
    fn separate_node(&mut self, node: usize) -> u64 {
        let mut least: Option<(f32, usize)> = None;
        let (mut all_cut, mut count) = (true, 0u64);
        self.lattice.for_each_spring_at(node, |spring, _, _, _| {
            all_cut &= self.is_cut(spring);
            count += 1;
            let ratio = self.separation_ratio(spring);
            if least.is_none_or(|(r, _)| ratio < r) {
                least = Some((ratio, spring));
            }
        });
        let (true, Some((_, spring))) = (all_cut, least) else { return count.max(1) };
        if !self.close_least_separated_arc(node, spring) {
            self.trace[spring] |= BRANCH;
            self.totals.node_branches += 1;
        }
        4 * count
    }

    /// The spring of triangle `cell` other than `spring` that has node `node`, if `cell` is
    /// a triangle with that node.
    fn other_side_at(&self, cell: usize, spring: usize, node: usize) -> Option<usize> {
        let c = self.lattice.cell(cell)?;
        if c.corners != 3 {
            return None;
        }
        (0..3)
            .find(|&k| {
                c.sides[k] as usize != spring && (c.nodes[k] as usize == node || c.nodes[(k + 1) % 3] as usize == node)
            })
            .map(|k| c.sides[k] as usize)
    }

    /// How many springs at `node` must be cut, starting with `first` (a side of tip cell
    /// `cell`) and turning around the node, to reach a spring at it that is cut; `None` if
    /// the turn comes back to `cell` or reaches the border first. Adds the turns to `work`.
    fn turns_to_crack(&self, cell: usize, first: usize, node: usize, work: &mut u64) -> Option<usize> {
        let (mut at, mut spring) = (cell, first);
        for turns in 1..=super::irregular::MAX_DEGREE {
            *work += 1;
            let next = self.neighbours_across(spring).find(|&n| n != at)?;
            if next == cell {
                return None;
            }
            let side = self.other_side_at(next, spring, node)?;
            if self.is_cut(side) {
                return Some(turns);
            }
            (at, spring) = (next, side);
        }
        None
    }

    /// Rule 2 on the triangle meshes, for a node whose springs are all cut (one of them
    /// `first`): turns around the node, and if two or more cracks leave the ring of cut
    /// springs around it, un-cuts the arc of springs between two of them whose most separated
    /// spring has separated least (the first such arc at a tie). Returns whether it did.
    fn close_least_separated_arc(&mut self, node: usize, first: usize) -> bool {
        const N: usize = super::irregular::MAX_DEGREE;
        // ring[i] = (spring, the triangle after it turning around the node, whether a crack
        // leaves that triangle across its side away from the node).
        let mut ring = [(0usize, 0usize, false); N];
        let Some((mut at, _)) = self.lattice.cells_of_spring(first)[0] else { return false };
        let mut spring = first;
        let mut n = 0;
        loop {
            let Some(c) = self.lattice.cell(at).filter(|c| c.corners == 3) else { return false };
            let away = (0..3).find(|&k| c.nodes[k] as usize != node && c.nodes[(k + 1) % 3] as usize != node);
            let Some(away) = away else { return false };
            if n == N {
                return false;
            }
            ring[n] = (spring, at, self.is_cut(c.sides[away] as usize));
            n += 1;
            let Some(next_spring) = self.other_side_at(at, spring, node) else { return false };
            let Some(next) = self.neighbours_across(next_spring).find(|&x| x != at) else { return false };
            if next_spring == first {
                break;
            }
            (at, spring) = (next, next_spring);
        }
        let ring = &ring[..n];
        let exits = ring.iter().filter(|r| r.2).count();
        if exits < 2 {
            return false;
        }
        // An arc runs from an exit triangle to the next: the springs after the first up to
        // and including the one before the second.
        let mut best: Option<(f32, usize, usize)> = None;
        for start in (0..n).filter(|&i| ring[i].2) {
            let len = (1..=n).find(|&d| ring[(start + d) % n].2).unwrap_or(n);
            let widest =
                (1..=len).map(|d| self.separation_ratio(ring[(start + d) % n].0)).fold(f32::NEG_INFINITY, f32::max);
            if best.is_none_or(|(w, _, _)| widest < w) {
                best = Some((widest, start, len));
            }
        }
        let Some((_, start, len)) = best else { return false };
        for d in 1..=len {
            self.trace[ring[(start + d) % n].0] = INTACT;
        }
        true
    }

    /// Rule 1, a tip one node from another crack: if the node of triangle `cell` opposite
    /// its cut side `tip` has a cut spring, cuts the springs at that node from the tip to it,
    /// the shorter way round (see the module docs). Returns the work: the springs turned
    /// about, both ways, and those cut.
    fn join_across_node(&mut self, cell: usize, tip: usize) -> u64 {
        let Some(c) = self.lattice.cell(cell) else { return 0 };
        if c.corners != 3 {
            return 0;
        }
        let Some(k) = c.sides[..3].iter().position(|&s| s as usize == tip) else { return 0 };
        let node = c.nodes[(k + 2) % 3] as usize;
        // The two sides at the node, each the first spring of one way round.
        let ways = [c.sides[(k + 1) % 3] as usize, c.sides[(k + 2) % 3] as usize];
        let mut work = 0u64;
        let turns = ways.map(|first| self.turns_to_crack(cell, first, node, &mut work));
        let first = match turns {
            [Some(a), Some(b)] if a == b => {
                if self.separation_ratio(ways[1]) > self.separation_ratio(ways[0]) {
                    ways[1]
                } else {
                    ways[0]
                }
            }
            [Some(a), Some(b)] => ways[usize::from(b < a)],
            [Some(_), None] => ways[0],
            [None, Some(_)] => ways[1],
            [None, None] => return work,
        };
        let time = self.trace[tip];
        let (mut at, mut spring) = (cell, first);
        for _ in 0..super::irregular::MAX_DEGREE {
            self.trace[spring] = time;
            self.touch(spring);
            work += 1;
            let Some(next) = self.neighbours_across(spring).find(|&n| n != at) else { break };
            let Some(side) = self.other_side_at(next, spring, node) else { break };
            if self.is_cut(side) {
                break;
            }
            (at, spring) = (next, side);
        }
        work
    }

    /// The dead-end pass at mesh cell `cell`: if it holds a tip, the walk along its crack
    /// that decides whether the crack has opened begins there.
    fn dead_end_start(&self, cell: usize) -> Option<DeadEndWalk> {
        if self.cuts_in(cell, false) != 1 {
            return None;
        }
        let c = self.lattice.cell(cell)?;
        let spring = c.sides[..c.corners].iter().map(|&s| s as usize).find(|&s| self.is_cut(s))?;
        Some(DeadEndWalk::Check { at: cell, spring, steps: 0 })
    }

    /// One step of the walk along the dead-end crack from tip cell `tip` (one spring):
    ///
    /// - checking: the crack from the tip to its junction (or its other tip) has not opened
    ///   if no spring on it has separated by more than it can bridge; a spring that has, the
    ///   border, or a walk longer than the mesh ends the check with the crack kept;
    /// - closing: each spring from the tip on is no longer cut, which leaves the rest a
    ///   dead-end crack from the cell beyond, up to the junction or the other tip.
    ///
    /// Returns the walk's next step, `None` when it is over.
    fn dead_end_walk(&mut self, tip: usize, walk: DeadEndWalk) -> Option<DeadEndWalk> {
        match walk {
            DeadEndWalk::Check { at, spring, steps } => {
                if steps > self.lattice.cell_count() || self.separation_ratio(spring) > 1.0 {
                    return None;
                }
                let next = self.neighbours_across(spring).find(|&n| n != at)?;
                let n = self.lattice.cell(next)?;
                let mut cut =
                    n.sides[..n.corners].iter().map(|&s| s as usize).filter(|&s| s != spring && self.is_cut(s));
                match (cut.next(), cut.next()) {
                    (Some(other), None) => Some(DeadEndWalk::Check { at: next, spring: other, steps: steps + 1 }),
                    // A junction or the other tip: the crack has not opened.
                    _ => Some(DeadEndWalk::Close { at: tip }),
                }
            }
            DeadEndWalk::Close { at } => {
                let c = self.lattice.cell(at)?;
                let spring = c.sides[..c.corners].iter().map(|&s| s as usize).find(|&s| self.is_cut(s))?;
                let next = self.neighbours_across(spring).find(|&n| n != at);
                self.trace[spring] = INTACT;
                let next = next?;
                (self.cuts_in(next, false) == 1).then_some(DeadEndWalk::Close { at: next })
            }
        }
    }

    /// Pushes onto the tracing stack (whose top is `top`) each of `cells` other than `except`
    /// with exactly one cut side (separating sides only, if asked); returns the new top.
    fn stack_single_cuts(
        &mut self,
        cells: impl Iterator<Item = usize>,
        except: usize,
        mut top: usize,
        separating_only: bool,
    ) -> usize {
        for cell in cells {
            if cell != except && self.cuts_in(cell, separating_only) == 1 {
                self.stack[top] = cell as u32;
                top += 1;
            }
        }
        top
    }

    /// The mesh cells on either side of `spring`.
    fn neighbours_across(&self, spring: usize) -> impl Iterator<Item = usize> + use<S> {
        self.lattice.cells_of_spring(spring).into_iter().flatten().map(|(cell, _)| cell)
    }

    /// Vertices mesh cell `cell` holds: its centroid if 1 or ≥ 3 sides are cut (its degree,
    /// the cut sides, or 0 if it is none), and each cut side on the border (how many); and
    /// whether a branch passes through it (exactly two sides cut, neither separating).
    fn vertices_in(&self, cell: usize) -> (usize, usize, bool) {
        let Some(c) = self.cut_cell_as(cell, false) else {
            return (0, 0, false);
        };
        let degree = if Self::centroid_is_vertex(&c) { c.cut_count() } else { 0 };
        let branch = c.cut_count() == 2 && c.separating_count() == 0;
        (degree, (0..c.sides()).filter(|&k| c.cut[k] && self.is_border_side(&c, k)).count(), branch)
    }

    /// Whether side `k` of a cell is on the open border (no cell on its other side).
    pub(super) fn is_border_side(&self, c: &TracedCell, k: usize) -> bool {
        // A periodic regular lattice has no border (not looked at on 32-bit targets, for the
        // Cortex-M3's flash: the cells across tell the same).
        if cfg!(target_pointer_width = "64")
            && self.params.boundary == super::Boundary::Periodic
            && self.lattice.mesh().is_none()
        {
            return false;
        }
        self.lattice.cells_of_spring(c.cell.sides[k] as usize).into_iter().flatten().count() < 2
    }

    /// Mesh cell `cell` as the network sees it, if a side of it is cut (most cells have none,
    /// and are passed over without working out their positions).
    pub(super) fn cut_cell(&self, cell: usize) -> Option<TracedCell> {
        self.cut_cell_as(cell, true)
    }

    /// [`Self::cut_cell`], with its corners' positions worked out only if `positions` (the
    /// walks that only follow the network's topology leave them at 0).
    pub(super) fn cut_cell_as(&self, cell: usize, positions: bool) -> Option<TracedCell> {
        // A mesh cell the trace did not touch has no cut side (see `Touched`). Not on 32-bit
        // targets, for the Cortex-M3's flash: the sides alone tell the same.
        if cfg!(target_pointer_width = "64")
            && self.touched.cells.get(cell / BLOCK).is_none_or(|&w| w & 1 << (cell % BLOCK) == 0)
        {
            return None;
        }
        let c = self.lattice.cell(cell)?;
        c.sides[..c.corners]
            .iter()
            .any(|&s| self.is_cut(s as usize))
            .then(|| self.traced_as(cell, c, [0, 0], positions))
    }

    /// Calls `visit` with every mesh cell the network may cut a side of, in order: on 64-bit
    /// targets the cells its trace touched (see `Touched`), on 32-bit ones, for the Cortex-M3's
    /// flash, every cell.
    pub(super) fn for_each_touched_cell(&self, mut visit: impl FnMut(usize)) {
        let cells = self.lattice.cell_count();
        if !cfg!(target_pointer_width = "64") {
            (0..cells).for_each(visit);
            return;
        }
        for (w, &word) in self.touched.cells.iter().enumerate() {
            let mut bits = word;
            while bits != 0 {
                let cell = w * BLOCK + bits.trailing_zeros() as usize;
                if cell >= cells {
                    return;
                }
                visit(cell);
                bits &= bits - 1;
            }
        }
    }

    /// Mesh cell `cell` and which of its sides the network cuts, if any is, for a cell
    /// [`Self::for_each_touched_cell`] gives: what [`Self::cut_cell_as`] tells without the
    /// positions, inlined on 64-bit targets into the passes that read only the cuts.
    #[inline(always)]
    pub(super) fn cut_sides(&self, cell: usize) -> Option<(Cell, [bool; 4])> {
        if !cfg!(target_pointer_width = "64") {
            return self.cut_cell_as(cell, false).map(|t| (t.cell, t.cut));
        }
        let c = self.lattice.cell(cell)?;
        let cut: [bool; 4] = core::array::from_fn(|k| k < c.corners && self.is_cut(c.sides[k] as usize));
        cut.contains(&true).then_some((c, cut))
    }

    /// Mesh cell `cell` as the network sees it, its positions shifted by `wrap` periods.
    pub(super) fn traced_cell(&self, cell: usize, wrap: [i32; 2]) -> Option<TracedCell> {
        self.lattice.cell(cell).map(|c| self.traced(cell, c, wrap))
    }

    /// Mesh cell `c` (index `cell`) as the network sees it, shifted by `wrap` periods.
    pub(super) fn traced(&self, cell: usize, c: Cell, wrap: [i32; 2]) -> TracedCell {
        self.traced_as(cell, c, wrap, true)
    }

    /// [`Self::traced`], its corners' positions left at 0 unless `positions`.
    pub(super) fn traced_as(&self, cell: usize, c: Cell, wrap: [i32; 2], positions: bool) -> TracedCell {
        let mut t = TracedCell { index: cell, cell: c, corner: [[0.0; 2]; 4], cut: [false; 4], separating: [false; 4] };
        for k in 0..c.corners {
            // (One read of the spring's word: `is_cut` and `separates` of it.)
            let word = self.trace[c.sides[k] as usize];
            (t.cut[k], t.separating[k]) = (cut(word), separating(word));
        }
        if !positions {
            return t;
        }
        let (_, deep) = self.factors();
        let deep = deep.to_f32();
        let [w, h] = self.lattice.extent();
        let shift = [wrap[0] as f32 * w, wrap[1] as f32 * h];
        for k in 0..c.corners {
            let (dx, dy) = self.displacement(c.nodes[k] as usize);
            t.corner[k] = [
                (c.reference[k][0] + shift[0]) * deep + dx.to_f32(),
                (c.reference[k][1] + shift[1]) * deep + dy.to_f32(),
            ];
        }
        t
    }

    /// The mesh cell across side `k` of `from`, the side the spring is in it, and the wrap
    /// that keeps the two cells' positions continuous; `None` at an open border.
    pub(super) fn across(&self, from: &TracedCell, k: usize, wrap: [i32; 2]) -> Option<(TracedCell, usize, [i32; 2])> {
        self.across_as(from, k, wrap, true)
    }

    /// [`Self::across`], the cell's positions worked out only if `positions` (the wrap always:
    /// a ring that wraps around a periodic lattice is told by it).
    pub(super) fn across_as(
        &self,
        from: &TracedCell,
        k: usize,
        wrap: [i32; 2],
        positions: bool,
    ) -> Option<(TracedCell, usize, [i32; 2])> {
        let spring = from.cell.sides[k] as usize;
        let ([a, b], one_frame) = self.lattice.cells_of_spring_framed(spring);
        let (cell, side) = [a, b].into_iter().flatten().find(|&(c, _)| c != from.index)?;
        let to = self.lattice.cell(cell)?;
        // The spring's midpoint in the two cells' reference frames differs by whole periods
        // (none where the lattice knows they share a frame).
        let wrap = if one_frame {
            wrap
        } else {
            let n = (from.cell.corners, to.corners);
            let mid = |r: &[[f32; 2]; 4], k: usize, n: usize| {
                [(r[k][0] + r[(k + 1) % n][0]) * 0.5, (r[k][1] + r[(k + 1) % n][1]) * 0.5]
            };
            let (p, q) = (mid(&from.cell.reference, k, n.0), mid(&to.reference, side, n.1));
            let [w, h] = self.lattice.extent();
            let periods = [libm::roundf((p[0] - q[0]) / w) as i32, libm::roundf((p[1] - q[1]) / h) as i32];
            [wrap[0] + periods[0], wrap[1] + periods[1]]
        };
        Some((self.traced_as(cell, to, wrap, positions), side, wrap))
    }

    /// The network point at the midpoint of side `k`.
    fn side_point(&self, c: &TracedCell, k: usize) -> NetworkPoint {
        let spring = c.cell.sides[k] as usize;
        NetworkPoint { at: self.crack_point(c, k), width: self.separation(spring), time: self.cut_time(spring) }
    }

    /// [`Self::side_point`], its spring's separation from `widths` when it holds it.
    fn side_point_in(&self, c: &TracedCell, k: usize, widths: &mut Widths) -> NetworkPoint {
        let spring = c.cell.sides[k] as usize;
        NetworkPoint { at: self.crack_point(c, k), width: widths.separation(self, spring), time: self.cut_time(spring) }
    }

    /// The network point at a cell's centroid: a dead end (width 0) or a junction (the mean
    /// width and the earliest time of the cracks meeting there).
    fn centroid_point(&self, c: &TracedCell) -> NetworkPoint {
        let (mut points, mut n) = ([NetworkPoint::default(); 4], 0);
        for k in (0..c.sides()).filter(|&k| c.cut[k]) {
            points[n] = self.side_point(c, k);
            n += 1;
        }
        Self::centroid_of(c, &points[..n])
    }

    /// [`Self::centroid_point`] from the points on the cell's cut sides, in order.
    fn centroid_of(c: &TracedCell, sides: &[NetworkPoint]) -> NetworkPoint {
        let (mut width, mut time) = (0.0f32, f32::INFINITY);
        for p in sides {
            width += p.width;
            time = time.min(p.time);
        }
        let n = sides.len();
        let width = if n >= 2 { width / n as f32 } else { 0.0 };
        NetworkPoint { at: c.centroid(), width, time }
    }

    /// Whether a cell's centroid is a vertex (a crack ends or cracks meet there).
    fn centroid_is_vertex(c: &TracedCell) -> bool {
        c.cut_count() == 1 || c.cut_count() >= 3
    }

    /// The vertex index of the border point on side `k` of `c`.
    fn border_vertex(&self, c: &TracedCell, k: usize) -> u32 {
        let before = (0..k).filter(|&j| c.cut[j] && self.is_border_side(c, j)).count();
        self.stack[c.index] + u32::from(Self::centroid_is_vertex(c)) + before as u32
    }

    /// Walks the network from the point on side `k` of `c` (already visited) into `c`,
    /// calling `visit` with each further point and the spring it sits on (`usize::MAX` at a
    /// centroid), to the vertex where it ends. `None` if it comes back to `start` without
    /// meeting one (a closed crack: the last point visited is the first again), or if `visit`
    /// returns false.
    fn walk(
        &self,
        start: (usize, usize),
        c: TracedCell,
        k: usize,
        wrap: [i32; 2],
        mut visit: impl FnMut(NetworkPoint, usize) -> bool,
    ) -> Option<Arrival> {
        self.walk_sides(start, c, k, wrap, true, |c, side| match side {
            Some(j) => visit(self.side_point(c, j), c.cell.sides[j] as usize),
            None => visit(self.centroid_point(c), usize::MAX),
        })
    }

    /// [`Self::walk`] by mesh cells: `visit(c, Some(j))` at the midpoint of side `j` of `c`,
    /// `visit(c, None)` at its centroid (the vertex the walk ends at).
    fn walk_sides(
        &self,
        start: (usize, usize),
        mut c: TracedCell,
        mut k: usize,
        mut wrap: [i32; 2],
        positions: bool,
        mut visit: impl FnMut(&TracedCell, Option<usize>) -> bool,
    ) -> Option<Arrival> {
        for _ in 0..=self.lattice.cell_count() {
            if Self::centroid_is_vertex(&c) {
                visit(&c, None);
                return Some(Arrival { vertex: self.stack[c.index], side: k });
            }
            // Two cut sides: leave by the other one.
            let out = (0..c.sides()).find(|&j| j != k && c.cut[j]).unwrap_or(k);
            if !visit(&c, Some(out)) {
                return None;
            }
            let Some((next, side, next_wrap)) = self.across_as(&c, out, wrap, positions) else {
                return Some(Arrival { vertex: self.border_vertex(&c, out), side: out });
            };
            if (next.index, side) == start {
                return None;
            }
            wrap = next_wrap;
            c = next;
            k = side;
        }
        None
    }

    /// Where the network point on cut side `k` of `c` lies: the spring's midpoint, moved as
    /// [`Self::smoothing_offset`] found when the network was traced.
    pub(super) fn crack_point(&self, c: &TracedCell, k: usize) -> [f32; 2] {
        let own = c.midpoint(k);
        let packed = self.crack_offset[c.cell.sides[k] as usize];
        let unit = |half: u32| f32::from(half as u16 as i16) / OFFSET_UNITS;
        [own[0] + unit(packed & 0xffff), own[1] + unit(packed >> 16)]
    }

    /// [`Self::smoothing_offset`] of cut `spring` as stored (two `i16` in 1/[`OFFSET_UNITS`]
    /// lattice units), shortened where the crack point would leave its spring's region: the
    /// two triangles the spring's ends make with its mesh cells' centroids. A smoothed point
    /// beyond (a sharp turn of the crack, a distorted irregular mesh, the open border) could
    /// pass a neighbouring piece of its ring, which then crossed itself; it is moved back
    /// towards its spring's midpoint, by halves, at most [`OFFSET_HALVINGS`] times, and then to
    /// the midpoint. Where the mesh is folded over at the spring (both centroids on one side
    /// of it) there is no such region, and the offset stays.
    fn packed_offset(&self, spring: usize) -> u32 {
        let pack = |v: f32| libm::roundf(v * OFFSET_UNITS).clamp(-32767.0, 32767.0);
        let Some((offset, home, side, other)) = self.smoothing_offset(spring) else { return 0 };
        let [x, y] = offset.map(pack);
        let word = |x: f32, y: f32| (x as i16 as u16) as u32 | ((y as i16 as u16) as u32) << 16;
        if x == 0.0 && y == 0.0 {
            return 0;
        }
        let (a, b) = (home.corner[side], home.corner[(side + 1) % home.sides()]);
        let centre = home.midpoint(side);
        let (near, far) = (home.centroid(), other.centroid());
        // A mesh folded over at the spring (both centroids on one side of it: a strongly
        // deformed lattice) has no region to keep the point in; the offset stays.
        if side_of(a, b, near) * side_of(a, b, far) >= 0.0 {
            return word(x, y);
        }
        for halvings in 0..=OFFSET_HALVINGS {
            let (x, y) = (libm::roundf(x / (1 << halvings) as f32), libm::roundf(y / (1 << halvings) as f32));
            let p = [centre[0] + x / OFFSET_UNITS, centre[1] + y / OFFSET_UNITS];
            if strictly_inside(p, a, b, near) || strictly_inside(p, a, b, far) {
                return word(x, y);
            }
        }
        0
    }

    /// How far the crack point of cut `spring` lies from the spring's midpoint: the binomial
    /// mean of its neighbours' offsets along the crack, [`SMOOTHING`] points each way (the
    /// paper's Fig. 5 places a crack at the midpoint of its broken spring). The lattice
    /// places a crack only to within one element: the zigzag between the midpoints of
    /// neighbouring triangle sides is the mesh's, not the crack's, and this takes it out.
    /// Vertices (ends, junctions, border points) stay where they are; a walk that reaches
    /// one before [`SMOOTHING`] points counts it for the rest. The triangle meshes only; the
    /// raw segments ([`Mud::segments`]) keep the midpoints.
    ///
    /// Returns the offset with the spring's first mesh cell, its side there and the mesh cell
    /// across it (in one frame), or `None` where the point stays at the midpoint.
    fn smoothing_offset(&self, spring: usize) -> Option<([f32; 2], TracedCell, usize, TracedCell)> {
        let [Some((first, side)), Some(_)] = self.lattice.cells_of_spring(spring) else { return None };
        // The square lattice keeps its midpoints: its axis-aligned steps are the paper's
        // Fig. 6 b, the lattice's artefact the figure shows.
        let home = self.traced_cell(first, [0, 0]).filter(|c| c.sides() == 3)?;
        let (other, other_side, wrap) = self.across(&home, side, [0, 0])?;
        let centre = home.midpoint(side);
        let mut offset = [0.0f32; 2];
        for (cell, entry, wrap) in [(home, side, [0, 0]), (other, other_side, wrap)] {
            let (mut n, mut last) = (0, centre);
            self.walk_sides((cell.index, entry), cell, entry, wrap, true, |c, side| {
                last = side.map_or_else(|| c.centroid(), |j| c.midpoint(j));
                n += 1;
                offset[0] += SMOOTHING_WEIGHTS[n] * (last[0] - centre[0]);
                offset[1] += SMOOTHING_WEIGHTS[n] * (last[1] - centre[1]);
                n < SMOOTHING
            });
            for w in &SMOOTHING_WEIGHTS[n + 1..] {
                offset[0] += w * (last[0] - centre[0]);
                offset[1] += w * (last[1] - centre[1]);
            }
        }
        Some((offset, home, side, other))
    }

    /// Calls `edge(from, to, count, points)` for every edge of the network, in a fixed order:
    /// by the vertex and side it starts from, then the closed cracks by their lowest spring.
    /// `count` is the number of the edge's points; `points` calls its argument with them in
    /// order.
    /// The closed cracks are looked for from the springs `closed` (all of them lie in
    /// [`Mud::closed_range`]).
    fn for_each_edge(&self, closed: core::ops::Range<usize>, mut edge: impl FnMut(u32, u32, usize, &EdgePoints<'_>)) {
        // The setup or a trace under way has no network to show yet.
        if !self.shows_network() {
            return;
        }
        let ignore = core::cell::Cell::new(0);
        self.edges_from_cells(0..self.lattice.cell_count(), &ignore, &mut edge);
        self.closed_cracks(closed, &ignore, &mut edge);
    }

    /// The walk along an edge from side `k` of mesh cell `c` (see
    /// [`Mud::edges_from_cells`]), from its centroid or from the border point on that side:
    /// calls `visit(cell, Some(j))` at the point on side `j` of a mesh cell, `visit(cell,
    /// None)` at its centroid, and returns where the edge ends. The mesh cells' positions are
    /// worked out only if `positions` (finding the end and counting the points needs none).
    fn edge_walk(
        &self,
        c: &TracedCell,
        k: usize,
        start: Start,
        positions: bool,
        visit: &mut dyn FnMut(&TracedCell, Option<usize>),
    ) -> Option<Arrival> {
        if start == Start::Centroid {
            visit(c, None);
        }
        visit(c, Some(k));
        let mut go_on = |t: &TracedCell, j: Option<usize>| {
            visit(t, j);
            true
        };
        match start {
            Start::Centroid => {
                let Some((n, side, wrap)) = self.across_as(c, k, [0, 0], positions) else {
                    return Some(Arrival { vertex: self.border_vertex(c, k), side: k });
                };
                self.walk_sides((c.index, k), n, side, wrap, positions, go_on)
            }
            Start::Border if Self::centroid_is_vertex(c) => {
                go_on(c, None);
                Some(Arrival { vertex: self.stack[c.index], side: k })
            }
            Start::Border => self.walk_sides((c.index, k), *c, k, [0, 0], positions, go_on),
        }
    }

    /// The network point `visit(cell, side)` of a walk stands for (see [`Self::walk_sides`]).
    fn walk_point(&self, c: &TracedCell, side: Option<usize>) -> NetworkPoint {
        match side {
            Some(j) => self.side_point(c, j),
            None => self.centroid_point(c),
        }
    }

    /// [`Mud::for_each_edge`]'s edges that start from the mesh cells `cells` (a vertex in
    /// them, or a border point of theirs), in its order; `walked` counts the points its walks
    /// pass (each edge is walked once to find its end and count its points, again for its
    /// points, if `edge` asks for them).
    pub(super) fn edges_from_cells(
        &self,
        cells: core::ops::Range<usize>,
        walked: &core::cell::Cell<u64>,
        edge: &mut impl FnMut(u32, u32, usize, &EdgePoints<'_>),
    ) {
        for cell in cells {
            // The walks that find the edges follow the mesh alone; the points of an edge
            // found are worked out from the cell's positions.
            let Some(t) = self.cut_cell_as(cell, false) else { continue };
            let centroid = Self::centroid_is_vertex(&t);
            for k in (0..t.sides()).filter(|&k| t.cut[k]) {
                for start in [Start::Centroid, Start::Border] {
                    let from = match start {
                        Start::Centroid if centroid => self.stack[cell],
                        Start::Border if self.is_border_side(&t, k) => self.border_vertex(&t, k),
                        _ => continue,
                    };
                    // Each edge is found from both ends: keep the walk from the lower end (an
                    // edge from a vertex back to itself by the same side is a border point's
                    // stub into its own cell, found once).
                    let mut count = 0;
                    let Some(end) = self.edge_walk(&t, k, start, false, &mut |_, _| {
                        walked.set(walked.get() + 1);
                        count += 1;
                    }) else {
                        continue;
                    };
                    if end < (Arrival { vertex: from, side: k }) {
                        continue;
                    }
                    edge(from, end.vertex, count, &|visit| {
                        let c = self.traced(cell, t.cell, [0, 0]);
                        self.edge_walk(&c, k, start, true, &mut |c, j| {
                            walked.set(walked.get() + 1);
                            visit(self.walk_point(c, j));
                        });
                    });
                }
            }
        }
    }

    /// [`Mud::for_each_edge`]'s closed cracks (with no vertex) whose lowest spring is in
    /// `springs`, in its order; `walked` counts the points its walks pass.
    pub(super) fn closed_cracks(
        &self,
        springs: core::ops::Range<usize>,
        walked: &core::cell::Cell<u64>,
        edge: &mut impl FnMut(u32, u32, usize, &EdgePoints<'_>),
    ) {
        // Closed cracks: every cell on them has two cut sides; each is found from its lowest
        // spring, in the cell on that spring's left.
        for spring in springs.filter(|&s| self.is_cut(s)) {
            let [Some((cell, side)), Some((right, _))] = self.lattice.cells_of_spring(spring) else { continue };
            // The mesh cell on the spring's right is the crack's last before it comes back, the
            // one on its left the first after: if the crack ends or meets others in either, or
            // goes on across a lower spring, the walk below would find that; they are looked at
            // first (each walk would run to the crack's end or its first lower spring).
            if right != cell {
                let Some(r) = self.lattice.cell(right) else { continue };
                let mut cut = r.sides[..r.corners].iter().map(|&s| s as usize).filter(|&s| self.is_cut(s));
                let (Some(a), Some(b), None) = (cut.next(), cut.next(), cut.next()) else { continue };
                if a.min(b) != spring {
                    continue;
                }
            }
            let Some(t) = self.lattice.cell(cell).map(|c| self.traced_as(cell, c, [0, 0], false)) else { continue };
            if Self::centroid_is_vertex(&t) || (0..t.sides()).any(|j| t.cut[j] && (t.cell.sides[j] as usize) < spring) {
                continue;
            }
            // Closed if the walk comes back without a vertex; found here if no spring on it
            // is lower (the walk stops at the first lower one). It follows the mesh alone.
            let (mut lowest, mut count) = (true, 1);
            let end = self.walk_sides((cell, side), t, side, [0, 0], false, |c, j| {
                walked.set(walked.get() + 1);
                count += 1;
                lowest = j.is_none_or(|j| c.cell.sides[j] as usize >= spring);
                lowest
            });
            if end.is_some() || !lowest {
                continue;
            }
            edge(NO_VERTEX, NO_VERTEX, count, &|visit| {
                let c = self.traced(cell, t.cell, [0, 0]);
                walked.set(walked.get() + 1);
                visit(self.side_point(&c, side));
                self.walk((cell, side), c, side, [0, 0], |p, _| {
                    walked.set(walked.get() + 1);
                    visit(p);
                    true
                });
            });
        }
    }

    /// The springs that the closed cracks are found from (each from its lowest spring, in
    /// [`Mud::closed_cracks`]) lie in, as the trace found them: none, if no crack is closed.
    pub(super) fn closed_range(&self) -> core::ops::Range<usize> {
        let [lowest, highest] = self.totals.closed_springs;
        if self.totals.closed_twice == 0 { 0..0 } else { lowest as usize..highest as usize + 1 }
    }

    /// Counts a closed crack whose lowest spring is `spring`, `sides` times of the two.
    pub(super) fn note_closed_crack(&mut self, spring: u32, sides: u64) {
        let [lowest, highest] = self.totals.closed_springs;
        self.totals.closed_springs =
            if self.totals.closed_twice == 0 { [spring, spring] } else { [lowest.min(spring), highest.max(spring)] };
        self.totals.closed_twice += sides;
    }

    /// Counts the closed cracks of branches for the trace ([`Totals::closed_twice`]), from
    /// `cursor` until the work reaches `budget`: each chain of mesh cells a branch passes
    /// through (marked when the vertices were numbered) is walked once, from its first cell,
    /// all the way round (a closed crack: a walk of [`Mud::closed_cracks`] that comes back
    /// without meeting a vertex) or to both its ends. A mesh cell with two cut sides has both
    /// or neither separating (the pruning of branches leaves no cell with one), so a closed
    /// crack is all branches or all separating springs; the rings count the latter
    /// ([`Mud::find_ring_starts`]). An item is a mesh cell looked at (1) or one step of a walk
    /// ([`super::cells::RING_STEP`]). Returns the work and the cursor to go on from (`None`:
    /// done).
    fn count_closed(&mut self, mut cursor: ClosedCursor, budget: u64) -> (u64, Option<ClosedCursor>) {
        let cells = self.lattice.cell_count();
        // The two cut sides of a marked mesh cell.
        let cut_sides = |m: &Self, cell: usize| {
            let c = m.lattice.cell(cell)?;
            let mut cut = (0..c.corners).filter(|&k| m.is_cut(c.sides[k] as usize));
            Some((c, [cut.next()?, cut.next()?]))
        };
        let mut work = 0u64;
        while work < budget {
            let start = cursor.cell;
            let Some(mut walk) = cursor.walk else {
                if start >= cells {
                    return (work, None);
                }
                // Cells no crack touches are passed over (see `next_flagged`).
                match next_flagged(self.touched.cells, start, cells) {
                    Ok(flagged) => cursor.cell = flagged,
                    Err(word_end) => {
                        work += 1;
                        cursor.cell = word_end;
                        continue;
                    }
                }
                work += 1;
                let cell = cursor.cell;
                cursor.cell += 1;
                if self.ring_starts[cell] & (CHAIN_CELL | CHAIN_WALKED) == CHAIN_CELL
                    && let Some((_, [out, _])) = cut_sides(self, cell)
                {
                    self.ring_starts[cell] |= CHAIN_WALKED;
                    cursor = ClosedCursor {
                        cell,
                        walk: Some(ChainWalk { at: cell, out, steps: 0, lowest: u32::MAX, back: false }),
                    };
                }
                continue;
            };
            // One step: across the side the walk leaves its cell by.
            work += super::cells::RING_STEP;
            let Some(c) = self.lattice.cell(walk.at) else {
                cursor = ClosedCursor { cell: start + 1, walk: None };
                continue;
            };
            let spring = c.sides[walk.out];
            walk.lowest = walk.lowest.min(spring);
            walk.steps += 1;
            let across =
                self.lattice.cells_of_spring(spring as usize).into_iter().flatten().find(|&(n, _)| n != walk.at);
            let next = match across {
                // Back at the start: a closed crack (the other way round is the same crack).
                Some((n, _)) if n == start => {
                    if !walk.back {
                        self.note_closed_crack(walk.lowest, 2);
                    }
                    None
                }
                // On through a cell with two cut sides (the walks are as long as those of
                // `walk_sides`, at most).
                Some((n, side)) if walk.steps <= cells && self.ring_starts[n] & CHAIN_CELL != 0 => {
                    self.ring_starts[n] |= CHAIN_WALKED;
                    cut_sides(self, n).map(|(_, [a, b])| ChainWalk {
                        at: n,
                        out: if a == side { b } else { a },
                        ..walk
                    })
                }
                // An end: the border, or a vertex.
                _ => None,
            };
            cursor.walk = match next {
                Some(next) => Some(next),
                // The other way from the start, to the chain's other end.
                None if !walk.back && across.is_none_or(|(n, _)| n != start) => cut_sides(self, start)
                    .map(|(_, [_, out])| ChainWalk { at: start, out, steps: 0, lowest: u32::MAX, back: true }),
                None => None,
            };
            if cursor.walk.is_none() {
                cursor.cell = start + 1;
            }
        }
        (work, Some(cursor))
    }

    /// Calls `arms(directions)` for every junction (a mesh cell where three or more cracks
    /// meet) with the direction of each crack leaving it, taken from the junction to the
    /// crack's point `reach` lattice units further along it (or its far end, if nearer): the
    /// crack's course, not the mesh cell's own geometry.
    pub(super) fn for_each_junction(&self, reach: f32, mut arms: impl FnMut(&[[f32; 2]])) {
        // The setup or a trace under way has no network to show yet.
        if !self.shows_network() {
            return;
        }
        for cell in 0..self.lattice.cell_count() {
            let Some(c) = self.cut_cell(cell) else { continue };
            if c.cut_count() < 3 {
                continue;
            }
            let centre = c.centroid();
            let (mut directions, mut n) = ([[0.0f32; 2]; 4], 0);
            for k in (0..c.sides()).filter(|&k| c.cut[k]) {
                let mut last = c.midpoint(k);
                let mut length = libm::hypotf(last[0] - centre[0], last[1] - centre[1]);
                if let Some((t, side, wrap)) = self.across(&c, k, [0, 0]) {
                    self.walk((cell, k), t, side, wrap, |p, _| {
                        length += libm::hypotf(p.at[0] - last[0], p.at[1] - last[1]);
                        last = p.at;
                        length < reach
                    });
                }
                directions[n] = [last[0] - centre[0], last[1] - centre[1]];
                n += 1;
            }
            arms(&directions[..n]);
        }
    }

    /// Calls `visit` with every vertex, in index order.
    pub(super) fn for_each_vertex(&self, mut visit: impl FnMut(NetworkVertex)) {
        // The setup or a trace under way has no network to show yet.
        if !self.shows_network() {
            return;
        }
        self.vertices_of_cells(0..self.lattice.cell_count(), &mut visit);
    }

    /// [`Mud::for_each_vertex`]'s vertices in the mesh cells `cells`, in its order.
    pub(super) fn vertices_of_cells(&self, cells: core::ops::Range<usize>, visit: &mut impl FnMut(NetworkVertex)) {
        for cell in cells {
            // Positions only for the mesh cells that hold a vertex (few of those cut).
            let Some(t) = self.cut_cell_as(cell, false) else { continue };
            if !Self::centroid_is_vertex(&t) && !(0..t.sides()).any(|k| t.cut[k] && self.is_border_side(&t, k)) {
                continue;
            }
            let c = self.traced(cell, t.cell, [0, 0]);
            if Self::centroid_is_vertex(&c) {
                visit(NetworkVertex { at: c.centroid(), degree: c.cut_count() as u32, on_border: 0 });
            }
            for k in (0..c.sides()).filter(|&k| c.cut[k] && self.is_border_side(&c, k)) {
                visit(NetworkVertex { at: c.midpoint(k), degree: 1, on_border: 1 });
            }
        }
    }

    /// How many vertices, edges and points [`Mud::network`] writes.
    ///
    /// From what the trace counted, without walking the edges: an edge has two ends, each at
    /// a vertex (a vertex of degree d is the end of d edges), and its points are its ends at
    /// mesh cells' centroids and one for each cut spring along it; a closed crack (no vertex,
    /// counted by the trace) repeats its first point.
    pub fn network_counts(&self) -> NetworkCounts {
        if !self.shows_network() {
            return NetworkCounts::default();
        }
        let t = &self.totals;
        let size = |n: u64| usize::try_from(n).unwrap_or(usize::MAX);
        NetworkCounts {
            vertices: t.vertices as usize,
            edges: size((t.centroid_degrees + t.border_vertices) / 2 + t.closed_twice / 2),
            points: size(t.cut_springs + t.centroid_degrees + t.closed_twice / 2),
        }
    }

    /// [`Mud::network_counts`] by walking every edge, the closed cracks looked for from every
    /// spring (what the counts must equal).
    #[cfg(test)]
    pub(super) fn walked_network_counts(&self) -> NetworkCounts {
        let mut counts = NetworkCounts::default();
        self.for_each_vertex(|_| counts.vertices += 1);
        self.for_each_edge(0..self.lattice.spring_count(), |_, _, points, _| {
            counts.edges += 1;
            counts.points += points;
        });
        counts
    }

    /// Writes the traced network: its vertices, its edges and their points, and returns the
    /// counts. Nothing is written if a buffer is shorter than [`Mud::network_counts`] says.
    pub fn network(
        &self,
        vertices: &mut [NetworkVertex],
        edges: &mut [NetworkEdge],
        points: &mut [NetworkPoint],
    ) -> Result<NetworkCounts, super::MudError> {
        let counts = self.network_counts();
        for (have, needed) in
            [(vertices.len(), counts.vertices), (edges.len(), counts.edges), (points.len(), counts.points)]
        {
            if have < needed {
                return Err(super::MudError::BufferTooSmall { needed });
            }
        }
        // (The counts hold on every trace; were one to differ, what does not fit is left out
        // rather than written past a buffer.)
        let mut v = 0;
        self.for_each_vertex(|vertex| {
            if let Some(slot) = vertices.get_mut(v) {
                *slot = vertex;
            }
            v += 1;
        });
        let (mut e, mut p) = (0, 0);
        self.for_each_edge(self.closed_range(), |from, to, _, walk| {
            let first = p;
            walk(&mut |point| {
                if let Some(slot) = points.get_mut(p) {
                    *slot = point;
                }
                p += 1;
            });
            if let Some(slot) = edges.get_mut(e) {
                *slot = NetworkEdge { from, to, first_point: first as u32, point_count: (p - first) as u32 };
            }
            e += 1;
        });
        Ok(counts)
    }

    /// Calls `emit(start, end)` for every straight piece of the traced network (Fig. 5's rule
    /// on the cut springs), cell by cell: what the rasters draw.
    pub(super) fn for_each_network_piece(&self, mut emit: impl FnMut(NetworkPoint, NetworkPoint)) {
        // The setup or a trace under way has no network to show yet.
        if !self.shows_network() {
            return;
        }
        // Each cut spring is a side of two cells: its separation is worked out once.
        let mut widths = Widths::new();
        self.for_each_touched_cell(|cell| {
            let Some(c) = self.cut_cell(cell) else { return };
            let (mut cut, mut n) = ([0usize; 4], 0);
            for k in (0..c.sides()).filter(|&k| c.cut[k]) {
                cut[n] = k;
                n += 1;
            }
            match cut[..n] {
                [] => {}
                [a, b] => emit(self.side_point_in(&c, a, &mut widths), self.side_point_in(&c, b, &mut widths)),
                ref sides => {
                    let points: [NetworkPoint; 4] = core::array::from_fn(|j| {
                        if j < n { self.side_point_in(&c, sides[j], &mut widths) } else { NetworkPoint::default() }
                    });
                    let centre = Self::centroid_of(&c, &points[..n]);
                    for &point in &points[..n] {
                        emit(point, centre);
                    }
                }
            }
        });
    }
}

/// Whether a spring's trace word says it is cut ([`Mud::is_cut`]).
#[inline(always)]
fn cut(word: u32) -> bool {
    word != INTACT
}

/// Whether a spring's trace word says it separates two cells: cut and not a branch
/// ([`Mud::separates`]).
#[inline(always)]
fn separating(word: u32) -> bool {
    cut(word) && word & BRANCH == 0
}

/// The separations of the cut springs a pass over the mesh cells has worked out, by spring
/// (each spring is a side of two cells, met one after the other in a pass): a direct-mapped
/// table, a spring's slot holding the last spring worked out there. On 32-bit targets, for the
/// Cortex-M3's stack, one slot.
pub(super) struct Widths {
    springs: [u32; WIDTHS],
    widths: [f32; WIDTHS],
}

/// Slots of [`Widths`]: a power of two.
const WIDTHS: usize = if cfg!(target_pointer_width = "64") { 512 } else { 1 };

impl Widths {
    pub(super) fn new() -> Widths {
        Widths { springs: [u32::MAX; WIDTHS], widths: [0.0; WIDTHS] }
    }

    /// [`Mud::separation`] of `spring`.
    #[inline(always)]
    pub(super) fn separation<S: Scalar>(&mut self, mud: &Mud<'_, S>, spring: usize) -> f32 {
        // Fibonacci hashing: springs close in number land in slots far apart.
        let slot =
            (spring as u32).wrapping_mul(0x9e37_79b9).rotate_left(WIDTHS.trailing_zeros()) as usize & (WIDTHS - 1);
        if self.springs[slot] == spring as u32 {
            return self.widths[slot];
        }
        let width = mud.separation(spring);
        (self.springs[slot], self.widths[slot]) = (spring as u32, width);
        width
    }
}

/// An edge's points: calls its argument with each, in order.
pub(super) type EdgePoints<'w> = dyn Fn(&mut dyn FnMut(NetworkPoint)) + 'w;

/// Where an edge walk starts.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Start {
    /// At a cell's centroid, out through a side.
    Centroid,
    /// At a border point, into its cell.
    Border,
}
