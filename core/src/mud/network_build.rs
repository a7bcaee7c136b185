//! The crack network built in steps, each within a budget of work, into caller memory; once
//! built it is read in ranges. The same vertices, edges and points, in the same order and bit
//! for bit, as [`Mud::network`] writes ([`super::network`] describes them): the same passes
//! over the mesh cells (the vertices, then the edges leaving each cell) and the springs (the
//! closed cracks), cut into pieces that a [`NetworkBuild::step`] call stops between.

use super::network::{EdgePoints, NetworkCounts, NetworkEdge, NetworkPoint, NetworkVertex};
use super::{Mud, MudError};
use crate::scalar::Scalar;

use core::cell::Cell;

/// How much caller memory a network build of a run needs ([`Mud::network_build_memory`]):
/// the most vertices, edges and points its lattice's network can have.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NetworkBuildMemory {
    /// Vertices: a mesh cell's centroid, or a cut spring on the open border.
    pub vertices: usize,
    /// Edges: each passes at least one cut spring, and a spring lies on one edge.
    pub edges: usize,
    /// Points: a cut spring's on the edge it lies on, and each edge's two ends.
    pub points: usize,
}

impl NetworkBuildMemory {
    /// The memory for a lattice of `cells` mesh cells and `springs` springs.
    pub(super) fn of(cells: usize, springs: usize) -> Option<NetworkBuildMemory> {
        Some(NetworkBuildMemory {
            vertices: cells.checked_add(springs)?,
            edges: springs,
            points: springs.checked_mul(3)?,
        })
    }
}

/// Owned memory for a network build (the `alloc` feature), from
/// [`NetworkBuildMemory::allocate`].
#[cfg(feature = "alloc")]
pub struct NetworkBuildStore {
    vertices: alloc::vec::Vec<NetworkVertex>,
    edges: alloc::vec::Vec<NetworkEdge>,
    points: alloc::vec::Vec<NetworkPoint>,
}

#[cfg(feature = "alloc")]
impl NetworkBuildMemory {
    /// Owned buffers of this size.
    pub fn allocate(&self) -> NetworkBuildStore {
        NetworkBuildStore {
            vertices: alloc::vec![NetworkVertex::default(); self.vertices],
            edges: alloc::vec![NetworkEdge::default(); self.edges],
            points: alloc::vec![NetworkPoint::default(); self.points],
        }
    }
}

#[cfg(feature = "alloc")]
impl NetworkBuildStore {
    /// The buffers, for [`NetworkBuild::new`].
    pub fn buffers(&mut self) -> NetworkBuildBuffers<'_> {
        NetworkBuildBuffers { vertices: &mut self.vertices, edges: &mut self.edges, points: &mut self.points }
    }
}

/// Caller memory for a network build: each at least its [`NetworkBuildMemory`] field. The
/// build reads no element it has not written (the buffers may hold any bytes).
pub struct NetworkBuildBuffers<'a> {
    /// Vertices.
    pub vertices: &'a mut [NetworkVertex],
    /// Edges.
    pub edges: &'a mut [NetworkEdge],
    /// Edge points.
    pub points: &'a mut [NetworkPoint],
}

/// Where a network build stands, as [`NetworkBuild::step`] reports it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct NetworkBuildProgress {
    /// Vertices, edges and points written so far (all of them once finished).
    pub counts: NetworkCounts,
    /// Every vertex, edge and point is written: [`NetworkBuild::vertices`],
    /// [`NetworkBuild::edges`] and [`NetworkBuild::points`] hold the network.
    pub finished: bool,
    /// Work done since the build (re)started, in the units of [`NetworkBuild::step`]'s budget.
    pub work: u64,
}

/// The passes of a build, in order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Pass {
    /// Per mesh cell: its vertices.
    Vertices,
    /// Per mesh cell: the edges that start from it.
    Edges,
    /// Per spring (of those the trace found closed cracks from): the closed crack it is the
    /// lowest spring of.
    Closed,
    /// Done.
    Done,
}

/// A network built in steps: see the module docs.
pub struct NetworkBuild<'a> {
    buffers: NetworkBuildBuffers<'a>,
    pass: Pass,
    /// The next mesh cell or spring of the pass.
    next: usize,
    counts: NetworkCounts,
    work: u64,
    /// The network the build reads: the run's traces shown so far, and its lattice's size.
    stamp: (u32, usize, usize),
}

impl<S: Scalar> Mud<'_, S> {
    /// The caller memory a network build of this run needs (see [`NetworkBuild`]); it
    /// follows the lattice, so one block serves the run at any point.
    pub fn network_build_memory(&self) -> NetworkBuildMemory {
        let (cells, springs) = (self.lattice.cell_count(), self.lattice.spring_count());
        // The lattice's arrays fit in memory already, so three times its springs fit a usize.
        NetworkBuildMemory::of(cells, springs).unwrap_or(NetworkBuildMemory { vertices: 0, edges: 0, points: 0 })
    }

    /// What identifies the network shown.
    fn network_stamp(&self) -> (u32, usize, usize) {
        (self.shown_traces, self.lattice.cell_count(), self.lattice.spring_count())
    }
}

impl<'a> NetworkBuild<'a> {
    /// A build of `mud`'s network in `buffers` (each at least [`Mud::network_build_memory`]);
    /// nothing is written until [`NetworkBuild::step`]. A buffer shorter than that is
    /// refused, naming the elements it needs.
    pub fn new<S: Scalar>(mud: &Mud<'_, S>, buffers: NetworkBuildBuffers<'a>) -> Result<Self, MudError> {
        Self::check(mud, &buffers)?;
        Ok(NetworkBuild {
            buffers,
            pass: Pass::Vertices,
            next: 0,
            counts: NetworkCounts::default(),
            work: 0,
            stamp: mud.network_stamp(),
        })
    }

    fn check<S: Scalar>(mud: &Mud<'_, S>, buffers: &NetworkBuildBuffers<'_>) -> Result<(), MudError> {
        let m = mud.network_build_memory();
        for (have, needed) in
            [(buffers.vertices.len(), m.vertices), (buffers.edges.len(), m.edges), (buffers.points.len(), m.points)]
        {
            if have < needed {
                return Err(MudError::BufferTooSmall { needed });
            }
        }
        Ok(())
    }

    /// Goes on with the build of `mud`'s network until the work of this call reaches
    /// `max(budget, 1)` units, or it is finished. A unit is a mesh cell or a spring looked at,
    /// a vertex written, or a point an edge's walk passes (each edge is walked twice: to find
    /// its far end, then for its points); a piece is one mesh cell's vertices or edges, or
    /// one spring's closed crack, so a call overruns its budget by less than one piece: the
    /// points of the cracks leaving one mesh cell (at most 3 edges), twice. The result does
    /// not depend on the budgets. A run whose network shown changed since the build began (a
    /// trace finished in a step, or [`Mud::trace`]) starts the build over (its work from 0).
    /// Refused, naming the elements it needs, for a run whose lattice needs more memory than
    /// the buffers hold.
    pub fn step<S: Scalar>(&mut self, mud: &Mud<'_, S>, budget: u64) -> Result<NetworkBuildProgress, MudError> {
        Self::check(mud, &self.buffers)?;
        if mud.network_stamp() != self.stamp {
            *self = NetworkBuild {
                buffers: core::mem::replace(
                    &mut self.buffers,
                    NetworkBuildBuffers { vertices: &mut [], edges: &mut [], points: &mut [] },
                ),
                pass: Pass::Vertices,
                next: 0,
                counts: NetworkCounts::default(),
                work: 0,
                stamp: mud.network_stamp(),
            };
        }
        if self.pass != Pass::Done && !mud.shows_network() {
            self.pass = Pass::Done;
        }
        let budget = budget.max(1);
        let mut work = 0u64;
        while self.pass != Pass::Done && work < budget {
            work += self.piece(mud);
        }
        self.work += work;
        Ok(self.progress())
    }

    /// Does the next piece; returns its work.
    fn piece<S: Scalar>(&mut self, mud: &Mud<'_, S>) -> u64 {
        // The closed cracks are found from springs the trace found them in.
        let (cells, closed) = (mud.lattice.cell_count(), mud.closed_range());
        let at = self.next;
        let walked = Cell::new(0u64);
        let NetworkBuild { buffers, counts, .. } = self;
        match self.pass {
            Pass::Vertices if at < cells => {
                mud.vertices_of_cells(at..at + 1, &mut |vertex| {
                    if let Some(slot) = buffers.vertices.get_mut(counts.vertices) {
                        *slot = vertex;
                    }
                    counts.vertices += 1;
                    walked.set(walked.get() + 1);
                });
            }
            Pass::Edges if at < cells => mud.edges_from_cells(at..at + 1, &walked, &mut |from, to, _, walk| {
                Self::write_edge(buffers, counts, from, to, walk)
            }),
            Pass::Closed if at < closed.end => mud.closed_cracks(at..at + 1, &walked, &mut |from, to, _, walk| {
                Self::write_edge(buffers, counts, from, to, walk)
            }),
            _ => {
                (self.pass, self.next) = match self.pass {
                    Pass::Vertices => (Pass::Edges, 0),
                    Pass::Edges => (Pass::Closed, closed.start),
                    _ => (Pass::Done, 0),
                };
                return 0;
            }
        }
        self.next += 1;
        1 + walked.get()
    }

    fn write_edge(
        buffers: &mut NetworkBuildBuffers<'_>,
        counts: &mut NetworkCounts,
        from: u32,
        to: u32,
        walk: &EdgePoints<'_>,
    ) {
        let first = counts.points;
        walk(&mut |point| {
            if let Some(slot) = buffers.points.get_mut(counts.points) {
                *slot = point;
            }
            counts.points += 1;
        });
        let edge = NetworkEdge { from, to, first_point: first as u32, point_count: (counts.points - first) as u32 };
        if let Some(slot) = buffers.edges.get_mut(counts.edges) {
            *slot = edge;
        }
        counts.edges += 1;
    }

    /// Where the build stands.
    pub fn progress(&self) -> NetworkBuildProgress {
        NetworkBuildProgress { counts: self.counts, finished: self.pass == Pass::Done, work: self.work }
    }

    /// The network's vertices once finished (none before).
    pub fn vertices(&self) -> &[NetworkVertex] {
        self.finished_part(&self.buffers.vertices[..], self.counts.vertices)
    }

    /// The network's edges once finished (none before); each edge's `first_point` indexes
    /// [`NetworkBuild::points`].
    pub fn edges(&self) -> &[NetworkEdge] {
        self.finished_part(&self.buffers.edges[..], self.counts.edges)
    }

    /// The network's edge points once finished (none before).
    pub fn points(&self) -> &[NetworkPoint] {
        self.finished_part(&self.buffers.points[..], self.counts.points)
    }

    fn finished_part<'s, T>(&self, all: &'s [T], n: usize) -> &'s [T] {
        if self.pass == Pass::Done { &all[..n.min(all.len())] } else { &[] }
    }
}
