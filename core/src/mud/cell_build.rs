//! The cells built in steps, each within a budget of work, into caller memory; once built
//! they are read in ranges. The same rings and points, in the same order and bit for bit, as
//! [`Mud::cells`] writes ([`super::cells`] describes them): the same passes (the rings by the
//! mesh cell they start from, the open border's own ring when no crack reaches it, each hole
//! given the smallest outer ring around it), cut into pieces that a [`CellBuild::step`] call
//! stops between.

use super::cells::{At, CellCounts, IN_WRAPPING_CELL};
use super::params::Boundary;
use super::{Mud, MudError};
use crate::geom::{crosses_ray, shoelace};
use crate::polygon::{NOT_A_HOLE, Ring};
use crate::scalar::Scalar;

/// How much caller memory a cell build of a run needs ([`Mud::cell_build_memory`]): the
/// most rings and points its lattice's cells can have.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CellBuildMemory {
    /// Rings: each runs along at least one side of a separating spring, and a spring's two
    /// sides lie on one ring each; and the open border's own ring.
    pub rings: usize,
    /// Points: a separating spring's crack point on each of its sides, a junction's centroid
    /// once per ring around it (at most once per side of its mesh cell), and the border's
    /// corners (at most three per mesh cell).
    pub points: usize,
}

impl CellBuildMemory {
    /// The memory for a lattice of `cells` mesh cells and `springs` springs.
    fn of(cells: usize, springs: usize) -> Option<CellBuildMemory> {
        let sides = springs.checked_mul(2)?;
        Some(CellBuildMemory {
            rings: sides.checked_add(1)?,
            points: sides.checked_mul(2)?.checked_add(cells.checked_mul(3)?)?,
        })
    }
}

/// Owned memory for a cell build (the `alloc` feature), from [`CellBuildMemory::allocate`].
#[cfg(feature = "alloc")]
pub struct CellBuildStore {
    rings: alloc::vec::Vec<Ring>,
    points: alloc::vec::Vec<[f32; 2]>,
}

#[cfg(feature = "alloc")]
impl CellBuildMemory {
    /// Owned buffers of this size.
    pub fn allocate(&self) -> CellBuildStore {
        CellBuildStore { rings: alloc::vec![Ring::default(); self.rings], points: alloc::vec![[0.0; 2]; self.points] }
    }
}

#[cfg(feature = "alloc")]
impl CellBuildStore {
    /// The buffers, for [`CellBuild::new`].
    pub fn buffers(&mut self) -> CellBuildBuffers<'_> {
        CellBuildBuffers { rings: &mut self.rings, points: &mut self.points }
    }
}

/// Caller memory for a cell build: each at least its [`CellBuildMemory`] field. The build
/// reads no element it has not written (the buffers may hold any bytes).
pub struct CellBuildBuffers<'a> {
    /// Ring records.
    pub rings: &'a mut [Ring],
    /// Ring points (lattice units).
    pub points: &'a mut [[f32; 2]],
}

/// Where a cell build stands, as [`CellBuild::step`] reports it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CellBuildProgress {
    /// Rings and points written so far (all of them once finished), and the boundaries that
    /// wrap around a periodic lattice found so far.
    pub counts: CellCounts,
    /// Every ring is written and every hole knows its outer ring: [`CellBuild::rings`] and
    /// [`CellBuild::points`] hold the cells.
    pub finished: bool,
    /// Work done since the build (re)started, in the units of [`CellBuild::step`]'s budget.
    pub work: u64,
}

/// The passes of a build, in order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Pass {
    /// Per mesh cell: the rings that start from it.
    Rings,
    /// Per mesh cell, on an open plate whose border no crack reaches: the first with a side on
    /// the border starts the border's ring.
    Border,
    /// Per hole and outer ring: whether the ring holds the hole's first point at any periodic
    /// shift.
    Holes,
    /// Done.
    Done,
}

/// The cells built in steps: see the module docs.
pub struct CellBuild<'a> {
    buffers: CellBuildBuffers<'a>,
    pass: Pass,
    /// The next mesh cell of the ring passes, or the hole of the hole pass.
    next: usize,
    /// The next outer ring tried for the hole, and the smallest found around it so far.
    candidate: usize,
    best: (u32, f64),
    border_touched: bool,
    counts: CellCounts,
    work: u64,
    /// The network the build reads: the run's traces shown so far, and its lattice's size.
    stamp: (u32, usize, usize),
}

impl<S: Scalar> Mud<'_, S> {
    /// The caller memory a cell build of this run needs (see [`CellBuild`]); it follows the
    /// lattice, so one block serves the run at any point.
    pub fn cell_build_memory(&self) -> CellBuildMemory {
        let (cells, springs) = (self.lattice.cell_count(), self.lattice.spring_count());
        CellBuildMemory::of(cells, springs).unwrap_or(CellBuildMemory { rings: 0, points: 0 })
    }

    /// What identifies the cells shown.
    pub(super) fn cells_stamp(&self) -> (u32, usize, usize) {
        (self.shown_traces, self.lattice.cell_count(), self.lattice.spring_count())
    }
}

impl<'a> CellBuild<'a> {
    /// A build of `mud`'s cells in `buffers` (each at least [`Mud::cell_build_memory`]);
    /// nothing is written until [`CellBuild::step`]. A buffer shorter than that is refused,
    /// naming the elements it needs.
    pub fn new<S: Scalar>(mud: &Mud<'_, S>, buffers: CellBuildBuffers<'a>) -> Result<Self, MudError> {
        Self::check(mud, &buffers)?;
        Ok(CellBuild {
            buffers,
            pass: Pass::Rings,
            next: 0,
            candidate: 0,
            best: (IN_WRAPPING_CELL, f64::INFINITY),
            border_touched: false,
            counts: CellCounts::default(),
            work: 0,
            stamp: mud.cells_stamp(),
        })
    }

    fn check<S: Scalar>(mud: &Mud<'_, S>, buffers: &CellBuildBuffers<'_>) -> Result<(), MudError> {
        let m = mud.cell_build_memory();
        for (have, needed) in [(buffers.rings.len(), m.rings), (buffers.points.len(), m.points)] {
            if have < needed {
                return Err(MudError::BufferTooSmall { needed });
            }
        }
        Ok(())
    }

    /// Goes on with the build of `mud`'s cells until the work of this call reaches
    /// `max(budget, 1)` units, or it is finished. A unit is a mesh cell looked at, a ring
    /// point written, or a point of an outer ring tested for a hole (at each periodic shift);
    /// a piece is one mesh cell's rings, or one outer ring tested for one hole, so a call
    /// overruns its budget by less than one piece: the points of the rings starting from one
    /// mesh cell, or nine times one ring's points. The result does not depend on the budgets.
    /// A run whose network shown changed since the build began (a trace finished in a step,
    /// or [`Mud::trace`]) starts the build over (its work from 0). Refused, naming the
    /// elements it needs, for a run whose lattice needs more memory than the buffers hold.
    pub fn step<S: Scalar>(&mut self, mud: &Mud<'_, S>, budget: u64) -> Result<CellBuildProgress, MudError> {
        Self::check(mud, &self.buffers)?;
        if mud.cells_stamp() != self.stamp {
            let buffers = core::mem::replace(&mut self.buffers, CellBuildBuffers { rings: &mut [], points: &mut [] });
            *self = CellBuild::new(mud, buffers)?;
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
        let cells = mud.lattice.cell_count();
        let at = self.next;
        match self.pass {
            Pass::Rings if at < cells => {
                let mut work = 1;
                let mut border_touched = self.border_touched;
                let wrapping = mud.ring_starts_in(at..at + 1, &mut border_touched, &mut |start| {
                    work += self.write_ring(mud, start);
                });
                self.border_touched = border_touched;
                self.counts.wrapping += wrapping;
                self.next += 1;
                work
            }
            Pass::Rings => {
                let open = mud.params.boundary == Boundary::Open;
                self.pass = if open && !self.border_touched { Pass::Border } else { Pass::Holes };
                self.next = 0;
                self.start_hole();
                0
            }
            Pass::Border if at < cells => {
                let mut work = 1;
                if let Some(start) = mud.border_start(at) {
                    work += self.write_ring(mud, start);
                    self.next = cells;
                } else {
                    self.next += 1;
                }
                work
            }
            Pass::Border => {
                self.pass = Pass::Holes;
                self.next = 0;
                self.start_hole();
                0
            }
            Pass::Holes => self.hole_piece(mud),
            Pass::Done => 0,
        }
    }

    /// Walks the ring from `start` into the buffers; returns its points.
    fn write_ring<S: Scalar>(&mut self, mud: &Mud<'_, S>, start: At) -> u64 {
        let CellBuild { buffers, counts, .. } = self;
        let first = counts.points;
        mud.walk_ring(start, |q, _| {
            if let Some(slot) = buffers.points.get_mut(counts.points) {
                *slot = q;
            }
            counts.points += 1;
            true
        });
        let end = counts.points.min(buffers.points.len());
        let ring = &buffers.points[first.min(end)..end];
        let twice: f64 = ring.iter().zip(ring.iter().cycle().skip(1)).map(|(a, b)| shoelace(*a, *b)).sum();
        let record = Ring {
            area: 0.5 * twice,
            first_point: first as u32,
            point_count: (counts.points - first) as u32,
            hole_of: NOT_A_HOLE,
            reserved: 0,
        };
        if let Some(slot) = buffers.rings.get_mut(counts.rings) {
            *slot = record;
        }
        counts.rings += 1;
        (counts.points - first) as u64
    }

    /// Moves the hole pass to the next hole from `self.next` on (past the last ring: done).
    fn start_hole(&mut self) {
        let rings = &self.buffers.rings[..self.counts.rings.min(self.buffers.rings.len())];
        while self.next < rings.len() && rings[self.next].area >= 0.0 {
            self.next += 1;
        }
        if self.next >= rings.len() {
            self.pass = Pass::Done;
        }
        self.candidate = 0;
        self.best = (IN_WRAPPING_CELL, f64::INFINITY);
    }

    /// Tests the next outer ring for the hole under way (as [`Mud::cells`] does: the smallest
    /// outer ring around the hole's first point, at any periodic shift, in ring order); once
    /// every ring is tried, the hole gets its outer ring.
    fn hole_piece<S: Scalar>(&mut self, mud: &Mud<'_, S>) -> u64 {
        let n = self.counts.rings.min(self.buffers.rings.len());
        let (hole, j) = (self.next, self.candidate);
        if j >= n {
            self.buffers.rings[hole].hole_of = self.best.0;
            self.next += 1;
            self.start_hole();
            return 1;
        }
        self.candidate += 1;
        let ring = self.buffers.rings[j];
        if !(ring.area > 0.0 && ring.area < self.best.1) {
            return 1;
        }
        let q = self.buffers.points[self.buffers.rings[hole].first_point as usize];
        let first = ring.first_point as usize;
        let points = &self.buffers.points[first..first + ring.point_count as usize];
        let ([w, h], shifts) = mud.hole_shifts();
        let mut work = 1;
        for s in shifts {
            let p = [q[0] + s[0] * w, q[1] + s[1] * h];
            work += points.len() as u64;
            let crossings =
                points.iter().zip(points.iter().cycle().skip(1)).filter(|(a, b)| crosses_ray(**a, **b, p)).count();
            let on = points.contains(&p);
            if crossings % 2 == 1 && !on {
                self.best = (j as u32, ring.area);
                break;
            }
        }
        work
    }

    /// Where the build stands.
    pub fn progress(&self) -> CellBuildProgress {
        CellBuildProgress { counts: self.counts, finished: self.pass == Pass::Done, work: self.work }
    }

    /// The cells' rings once finished (none before); each ring's `first_point` indexes
    /// [`CellBuild::points`].
    pub fn rings(&self) -> &[Ring] {
        if self.pass == Pass::Done {
            &self.buffers.rings[..self.counts.rings.min(self.buffers.rings.len())]
        } else {
            &[]
        }
    }

    /// The cells' ring points once finished (none before).
    pub fn points(&self) -> &[[f32; 2]] {
        if self.pass == Pass::Done {
            &self.buffers.points[..self.counts.points.min(self.buffers.points.len())]
        } else {
            &[]
        }
    }
}
