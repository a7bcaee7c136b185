//! Model A: drying mud (Hirota, Hoshino, Kaneko, "Generation of Crack Patterns Based on a
//! Physical Model"; `docs/src/models/papers.md`, Model A).
//!
//! A surface layer of nodes joined by springs sits on a deep layer that never cracks; each
//! surface node is tied to its deep node by a shear spring. The surface shrinks (or the deep
//! layer grows), springs stretch past their break stretch and break, and the broken springs,
//! traced through the mesh cells (Fig. 5), are the cracks.
//!
//! Every model has the same shape (this is the example of each, but for the names):
//!
//! ```
//! # #[cfg(feature = "alloc")] { // `allocate` needs the `alloc` feature
//! use hibi_core::mud::{Mud, MudLayers, MudParams, MudRender};
//!
//! let params = MudParams { columns: 32, rows: 32, ..MudParams::default() };
//! let mut memory = params.memory().unwrap().allocate(); // or MudStorage, or your own buffers
//! let mut mud: Mud = Mud::new(&params, memory.buffers()).unwrap(); // Mud<Q16> for fixed point
//! while !mud.step(100_000).unwrap().finished {} // the first steps set the run up
//! let mut mask = vec![0u8; 64 * 64];
//! let render = MudRender { width: 64, height: 64, ..MudRender::default() };
//! mud.render(&render, MudLayers { mask: Some(&mut mask), ..MudLayers::default() }).unwrap();
//! assert!(mask.iter().any(|&m| m > 0));
//! # }
//! ```
//!
//! Memory is the caller's: [`MudParams::memory`] tells how many scalars and words a run needs;
//! [`MudStorage`] holds them in fixed-size arrays for callers without a heap, and with the
//! `alloc` feature [`MudMemory::allocate`] gives owned ones. Outputs are counted, then written
//! into caller buffers: [`Mud::network_counts`] and [`Mud::network`], [`Mud::cell_counts`] and
//! [`Mud::cells`], [`Mud::segment_count`] and [`Mud::segments`].

mod cell_build;
mod cells;
mod explicit;
mod irregular;
mod lattice;
mod material;
mod network;
mod network_build;
mod params;
mod presets;
mod quasi_static;
mod render;
mod setup;
mod spacing;
mod statistics;
mod trace;

#[cfg(feature = "alloc")]
pub use cell_build::CellBuildStore;
pub use cell_build::{CellBuild, CellBuildBuffers, CellBuildMemory, CellBuildProgress};
pub use cells::{CellCounts, IN_WRAPPING_CELL};
pub use lattice::Lattice;
pub use material::Material;
pub use network::{NO_VERTEX, NetworkCounts, NetworkEdge, NetworkPoint, NetworkVertex, TRACE_PIECE};
#[cfg(feature = "alloc")]
pub use network_build::NetworkBuildStore;
pub use network_build::{NetworkBuild, NetworkBuildBuffers, NetworkBuildMemory, NetworkBuildProgress};
pub use params::{Boundary, Drive, MudParamError, MudParams, Solver, Topology};
pub use presets::{PRESETS, preset};
pub use render::{BEVEL, HAIRLINE, MudLayers, MudRender};
pub use setup::SETUP_PIECE;
pub use spacing::{SpacingPrediction, predict_spacing};
pub use statistics::{CrackStatistics, JUNCTION_REACH};
pub use trace::CrackSegment;

use crate::scalar::Scalar;

/// The live traces' share of a run's work: a trace during the physics gets one unit of work
/// for every `LIVE_SHARE` units of the physics (see [`Mud::step`]).
pub const LIVE_SHARE: u64 = 8;

/// Between live traces, the physics' work after which a run looks for new breaks to trace
/// (see [`Mud::step`]).
pub const LIVE_CHECK: u64 = 1024;

/// Marks an intact spring in the break-time table.
const INTACT: u32 = u32::MAX;
/// Marks a missing spring (beyond an open edge) in the neighbour table.
const ABSENT: u32 = u32::MAX;

/// How much caller memory a run needs: `scalars` elements of the scalar type and `words`
/// `u32`s.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MudMemory {
    /// Elements of the scalar type (`f32`, `Q16`, ...).
    pub scalars: usize,
    /// `u32` words.
    pub words: usize,
}

/// The most nodes a lattice may have (`columns · rows`): 2²⁸ = 268 435 456. Springs, cells
/// and the network's vertices are numbered in `u32` words, with room for the tables' markers
/// and the irregular mesh's two flag bits.
pub const MAX_NODES: u64 = 1 << 28;

/// The most columns of an irregular lattice (2²⁰): its nodes' positions are `i32` in
/// 1/1024 of an element.
pub const MAX_IRREGULAR_COLUMNS: u32 = 1 << 20;

/// The most rows of an irregular lattice (2²¹): `rows · PITCH` in `i32` positions.
pub const MAX_IRREGULAR_ROWS: u32 = 1 << 21;

/// The memory a lattice of this shape needs with this solver; `None` if it has more than
/// [`MAX_NODES`] nodes (or, irregular, more than [`MAX_IRREGULAR_COLUMNS`] columns or
/// [`MAX_IRREGULAR_ROWS`] rows), or if its memory overflows the address space.
pub const fn memory_for(topology: Topology, solver: Solver, columns: u32, rows: u32) -> Option<MudMemory> {
    // In u128 nothing below can overflow; the result is checked against the address space.
    let dirs: u128 = match topology {
        Topology::Square => 2,
        Topology::Hexagonal | Topology::Irregular => 3,
    };
    let nodes = columns as u128 * rows as u128;
    if nodes > MAX_NODES as u128 {
        return None;
    }
    if let Topology::Irregular = topology
        && (columns > MAX_IRREGULAR_COLUMNS || rows > MAX_IRREGULAR_ROWS)
    {
        return None;
    }
    // The irregular lattice keeps its mesh's tables (see `irregular`).
    let mesh = match topology {
        Topology::Irregular => irregular::words_for(nodes),
        _ => 0,
    };
    let springs = nodes * dirs;
    // Per node: displacement (x, y); explicit adds velocity and force (x, y).
    // Per spring: break stretch, and the explicit solver's liveness or the quasi-static
    // solver's break misfit.
    // Words per spring: the other node, the break time, the traced network's cut and where
    // its crack point lies (`network::crack_offset`); per
    // mesh cell (1 square, 2 triangles per node) one word for tracing and one for the cells'
    // ring starts. The network's words (cut, crack point, tracing, ring starts) are kept
    // twice: the network shown, and the one a live trace is building (`network::TraceBuffers`),
    // each with one bit per spring, mesh cell and node that its trace touched; one more bit per
    // spring marks the broken ones.
    // Quasi-static adds a tournament tree over blocks of 32 springs (2·P, P the next power of
    // two of the blocks), a work queue, node flags and a list of relaxed nodes (3 per node).
    let cells = nodes * (dirs - 1);
    let block = network::BLOCK as u128;
    let flags = 3 * springs.div_ceil(block) + 2 * cells.div_ceil(block) + 2 * nodes.div_ceil(block);
    let (scalars, words) = match solver {
        // The irregular lattice's explicit run keeps five constants per node.
        Solver::Explicit => {
            let constants = if mesh > 0 { explicit::NODE_CONSTANTS as u128 * nodes } else { 0 };
            (6 * nodes + 2 * springs + constants, 6 * springs + 4 * cells + flags + mesh)
        }
        Solver::QuasiStatic => {
            let blocks = springs.div_ceil(quasi_static::BLOCK as u128);
            let leaves = if blocks <= 1 { 1 } else { 1u128 << (128 - (blocks - 1).leading_zeros()) };
            (2 * nodes + 2 * springs, 6 * springs + 4 * cells + flags + 2 * leaves + 3 * nodes + mesh)
        }
    };
    // Keep every element count addressable in bytes (the largest element is 8 bytes).
    let limit = (isize::MAX / 8) as u128;
    if scalars > limit || words > limit {
        return None;
    }
    Some(MudMemory { scalars: scalars as usize, words: words as usize })
}

impl MudParams {
    /// Validates the parameters (fields and the scale of the derived constants) and returns
    /// the memory a run needs.
    pub fn memory(&self) -> Result<MudMemory, MudParamError> {
        self.validate()?;
        let memory =
            memory_for(self.topology, self.solver, self.columns, self.rows).ok_or(MudParamError::SizeOverflow)?;
        let lattice = self.lattice();
        let material = Material::<f32>::new(self, &lattice)?;
        // The explicit solver's short step must pass the stability test of its damped step
        // (the irregular lattice's is checked on its mesh, by the first steps: `Mud::step`).
        if self.solver == Solver::Explicit
            && self.topology != Topology::Irregular
            && !explicit::stable_lattice(&lattice, &material)
        {
            return Err(MudParamError::ShortStepStability);
        }
        Ok(memory)
    }

    /// Width and height of the domain of a run of these parameters, lattice units (see
    /// [`Mud::extent`]).
    pub fn extent(&self) -> [f32; 2] {
        self.lattice().extent()
    }

    /// The shape of the lattice these parameters describe (an irregular lattice's mesh is
    /// built by its run: [`Mud::lattice`]).
    pub const fn lattice(&self) -> Lattice<'static> {
        Lattice::new(self.topology, self.boundary, self.columns, self.rows)
    }
}

/// Caller memory for a run: at least [`MudParams::memory`] elements of each.
pub struct MudBuffers<'a, S> {
    /// At least [`MudMemory::scalars`] elements of the scalar type.
    pub scalars: &'a mut [S],
    /// At least [`MudMemory::words`] words.
    pub words: &'a mut [u32],
}

/// Owned memory for a run (the `alloc` feature), from [`MudMemory::allocate`].
#[cfg(feature = "alloc")]
pub struct MudStore<S> {
    scalars: alloc::vec::Vec<S>,
    words: alloc::vec::Vec<u32>,
}

#[cfg(feature = "alloc")]
impl MudMemory {
    /// Owned, zeroed buffers of this size.
    pub fn allocate<S: Scalar>(&self) -> MudStore<S> {
        MudStore { scalars: alloc::vec![S::ZERO; self.scalars], words: alloc::vec![0; self.words] }
    }
}

#[cfg(feature = "alloc")]
impl<S> MudStore<S> {
    /// The buffers, for [`Mud::new`].
    pub fn buffers(&mut self) -> MudBuffers<'_, S> {
        MudBuffers { scalars: &mut self.scalars, words: &mut self.words }
    }
}

/// Fixed-size storage for callers without a heap: `SCALARS` and `WORDS` come from
/// [`memory_for`] (a `const fn`), e.g.
/// `MudStorage<f32, { memory_for(..).unwrap().scalars }, { ... .words }>`.
pub struct MudStorage<S, const SCALARS: usize, const WORDS: usize> {
    /// Scalar storage.
    pub scalars: [S; SCALARS],
    /// Word storage.
    pub words: [u32; WORDS],
}

impl<S: Scalar, const SCALARS: usize, const WORDS: usize> MudStorage<S, SCALARS, WORDS> {
    /// Zeroed storage.
    pub const fn new() -> Self {
        MudStorage { scalars: [S::ZERO; SCALARS], words: [0; WORDS] }
    }

    /// The buffers, for [`Mud::new`].
    pub fn buffers(&mut self) -> MudBuffers<'_, S> {
        MudBuffers { scalars: &mut self.scalars, words: &mut self.words }
    }
}

impl<S: Scalar, const SCALARS: usize, const WORDS: usize> Default for MudStorage<S, SCALARS, WORDS> {
    fn default() -> Self {
        Self::new()
    }
}

/// Why a run could not be created or an output written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MudError {
    /// A parameter is out of range.
    Param(MudParamError),
    /// A caller buffer is too small: `needed` elements are required.
    BufferTooSmall {
        /// Elements the buffer must hold.
        needed: usize,
    },
}

impl From<MudParamError> for MudError {
    fn from(e: MudParamError) -> Self {
        MudError::Param(e)
    }
}

impl core::fmt::Display for MudError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            MudError::Param(e) => e.fmt(f),
            MudError::BufferTooSmall { needed } => write!(f, "mud: a caller buffer is too small ({needed} needed)"),
        }
    }
}

impl core::error::Error for MudError {
    fn source(&self) -> Option<&(dyn core::error::Error + 'static)> {
        match self {
            MudError::Param(e) => Some(e),
            MudError::BufferTooSmall { .. } => None,
        }
    }
}

/// Where a run stands, as [`Mud::step`] reports it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MudProgress {
    /// The misfit between the layers: shrink 1 − r (growth: 1/r − 1).
    pub shrink: f32,
    /// Time in long steps T (fractional for the quasi-static solver).
    pub time: f32,
    /// Springs broken so far.
    pub broken_springs: u32,
    /// Crack length per area [1/cm].
    pub crack_density: f32,
    /// The run reached its end (target shrink or crack density, or nothing left to happen).
    pub finished: bool,
    /// Work done since the run began, in the units of [`Mud::step`]'s budget.
    pub work: u64,
}

/// A drying-mud run over caller memory.
pub struct Mud<'a, S: Scalar = f32> {
    params: MudParams,
    lattice: Lattice<'a>,
    material: Material<S>,
    /// Displacement of each surface node from its deep node (x, y). The quasi-static solver
    /// keeps the displacement per unit misfit here instead.
    ux: &'a mut [S],
    uy: &'a mut [S],
    /// Per spring: κ_i (margin scaled by anisotropy).
    break_stretch: &'a mut [S],
    /// Per spring: the node it reaches, or ABSENT.
    other: &'a mut [u32],
    /// Per spring: the time it broke (f32 bits, long steps), or INTACT.
    break_time: &'a mut [u32],
    /// Per spring, the traced network: the time its crack formed (f32 bits, with
    /// `network::BRANCH` on a branch), or INTACT where it is not cut.
    trace: &'a mut [u32],
    /// Per spring cut in the traced network: where its crack point lies from the spring's
    /// midpoint (two `i16` in 1/`network::OFFSET_UNITS` lattice units; see
    /// `Mud::crack_point`).
    crack_offset: &'a mut [u32],
    /// Per mesh cell: the tracing's stack, then the index of the cell's first network vertex.
    stack: &'a mut [u32],
    /// Per mesh cell: which of its sides start a ring of the cells (see `cells`).
    ring_starts: &'a mut [u32],
    /// What the trace of the network shown counted of it.
    totals: network::Totals,
    /// The blocks of springs, mesh cells and nodes the network shown touched.
    touched: network::Touched<'a>,
    /// One bit per spring: broken (for the tracing; see `network::Touched`).
    broken_blocks: &'a mut [u32],
    /// The other copy of the network's words: the one a trace under way builds (see
    /// `network::TraceBuffers`).
    back: network::TraceBuffers<'a>,
    /// Springs broken when the trace under way (or the last) began.
    traced_broken: u32,
    /// Springs broken when the network shown was traced.
    shown_broken: u32,
    /// Traces shown so far (wrapping): what identifies the network shown, for the builds.
    shown_traces: u32,
    /// The trace under way, if one is.
    tracing: Option<network::TracePass>,
    /// The physics ended and its final trace has begun (or nothing broke).
    final_traced: bool,
    /// Work of the physics (the setup's and the tracing's apart).
    physics_work: u64,
    /// Work of the live traces (those during the physics).
    live_work: u64,
    /// The physics work at which the run next looks for new breaks to trace.
    next_check: u64,
    /// The top of the tracing's stack (in `stack`), while a trace is under way.
    trace_top: usize,
    /// The faces of the broken springs, summed (the irregular lattice's crack length).
    broken_face: f32,
    solver: SolverState<'a, S>,
    /// Long steps taken (explicit) and the misfit now.
    long_steps: u32,
    misfit: S,
    broken: u32,
    finished: bool,
    work: u64,
    /// The setup under way (`None` once done): see [`Mud::step`].
    setup: Option<setup::Setup>,
    /// The irregular lattice's words until its mesh is built (then `lattice.mesh` reads them).
    mesh_words: &'a mut [u32],
    /// Why the run ended in error, if it did (returned by every later step).
    failure: Option<MudError>,
}

/// The arrays only one solver needs.
enum SolverState<'a, S> {
    Explicit(explicit::Dynamics<'a, S>),
    QuasiStatic(quasi_static::Relaxation<'a, S>),
}

/// Cuts the first `n` elements off a buffer.
fn take<'a, T>(buffer: &mut &'a mut [T], n: usize) -> &'a mut [T] {
    let (head, tail) = core::mem::take(buffer).split_at_mut(n);
    *buffer = tail;
    head
}

impl<'a, S: Scalar> Mud<'a, S> {
    /// Sets up a run of `params` in caller memory of at least [`MudParams::memory`] elements:
    /// checks the parameters and carves the buffers, work independent of the lattice's size.
    /// The rest of the setup (the irregular lattice's mesh, every spring's break stretch, the
    /// boundary layer of open edges to relax) is done by the first [`Mud::step`] calls, within
    /// their budgets. The buffers may hold any bytes: the run reads no element before writing
    /// it. Nothing is written to them here.
    pub fn new(params: &MudParams, buffers: MudBuffers<'a, S>) -> Result<Self, MudError> {
        let MudBuffers { scalars, words } = buffers;
        let memory = params.memory()?;
        if scalars.len() < memory.scalars {
            return Err(MudError::BufferTooSmall { needed: memory.scalars });
        }
        if words.len() < memory.words {
            return Err(MudError::BufferTooSmall { needed: memory.words });
        }
        let shape = params.lattice();
        let material = Material::new(params, &shape)?;
        // The stability test and the bounds on a settling lattice's work come from the f32
        // constants, whatever the backend.
        let reference = Material::<f32>::new(params, &shape)?;
        let (nodes, springs) = (shape.node_count(), shape.spring_count());
        let mut scalars = scalars;
        let mut words = words;
        let irregular = params.topology == Topology::Irregular;
        let mesh_words =
            if irregular { take(&mut words, irregular::words_for(nodes as u128) as usize) } else { &mut [] };
        let ux = take(&mut scalars, nodes);
        let uy = take(&mut scalars, nodes);
        let break_stretch = take(&mut scalars, springs);
        let other = take(&mut words, springs);
        let break_time = take(&mut words, springs);
        let trace = take(&mut words, springs);
        let crack_offset = take(&mut words, springs);
        let stack = take(&mut words, shape.cell_count());
        let ring_starts = take(&mut words, shape.cell_count());
        let block = network::BLOCK;
        let blocks = [springs.div_ceil(block), shape.cell_count().div_ceil(block), nodes.div_ceil(block)];
        let touched = |words: &mut &'a mut [u32]| network::Touched {
            springs: take(words, blocks[0]),
            cells: take(words, blocks[1]),
            nodes: take(words, blocks[2]),
        };
        let front_touched = touched(&mut words);
        let back = network::TraceBuffers {
            trace: take(&mut words, springs),
            crack_offset: take(&mut words, springs),
            stack: take(&mut words, shape.cell_count()),
            ring_starts: take(&mut words, shape.cell_count()),
            totals: network::Totals::default(),
            touched: touched(&mut words),
        };
        let broken_blocks = take(&mut words, blocks[0]);
        // The irregular lattice's bounds come from its nodes, which the setup sees one by one.
        let solver = match params.solver {
            Solver::Explicit => {
                let settle = if irregular { u64::MAX } else { explicit::settle_bound(&shape, &reference) };
                SolverState::Explicit(explicit::Dynamics::new(&mut scalars, &shape, &material, settle))
            }
            Solver::QuasiStatic => {
                let bound = if irregular { u64::MAX } else { quasi_static::relax_bound(&shape, &reference) };
                SolverState::QuasiStatic(quasi_static::Relaxation::new(
                    &mut scalars,
                    &mut words,
                    (nodes, springs),
                    bound,
                    quasi_static::relax_tolerance(params, S::ZERO),
                    // (Read by the 64-bit targets' fast path only.)
                    if cfg!(target_pointer_width = "64") {
                        (quasi_static::interior_laws(&shape, &material), shape.column_reciprocal())
                    } else {
                        ([[S::ZERO; 3]; 6], 0)
                    },
                ))
            }
        };
        Ok(Mud {
            params: *params,
            lattice: shape,
            material,
            ux,
            uy,
            break_stretch,
            other,
            break_time,
            trace,
            crack_offset,
            stack,
            ring_starts,
            totals: network::Totals::default(),
            touched: front_touched,
            broken_blocks,
            back,
            traced_broken: 0,
            shown_broken: 0,
            shown_traces: 0,
            tracing: None,
            final_traced: false,
            physics_work: 0,
            live_work: 0,
            next_check: 0,
            trace_top: 0,
            broken_face: 0.0,
            solver,
            long_steps: 0,
            misfit: S::ZERO,
            broken: 0,
            finished: false,
            work: 0,
            setup: Some(setup::Setup::new(params.seed, params.topology, params.solver, reference)),
            mesh_words,
            failure: None,
        })
    }

    /// Advances the run by about `budget` units of work (one unit is one spring or one node
    /// visited): it does pieces until their work reaches the budget, so a call on an
    /// unfinished run does at least one piece and overruns `max(budget, 1)` by less than one
    /// piece. A piece is bounded by a row of the lattice or a node, not by its size:
    ///
    /// - the setup, first: item by item, a spring, a node or a mesh cell (1 unit), an
    ///   irregular node's jitter into the mesh or its constants (16), a block of the
    ///   quasi-static solver's tree (32; at most [`SETUP_PIECE`]). Until it is done the run
    ///   is an uncracked plate at shrink 0 and the outputs describe that. The irregular
    ///   lattice's explicit run is tested for stability node by node on its mesh here: a
    ///   node that fails ends the run with [`MudParamError::ShortStepStability`].
    /// - explicit solver: a short step is resumed where the last call stopped, in the paper's
    ///   order (the springs' limits once per long step, then the forces and breaks of Eq. 2
    ///   and 5 row by row, direction by direction, the stability test of Eq. 3 and the move
    ///   of Eq. 4 node by node). A piece is one row's springs in one direction and their
    ///   rescan for breaks, at most 2·columns; the irregular lattice goes spring by spring and
    ///   node by node and does not overrun. Stopped mid-step, the displacements are partly
    ///   moved; the springs broken so far count in [`MudProgress::broken_springs`].
    /// - quasi-static solver: a node's relaxation (its springs: 4 square, 6 hexagonal, at most
    ///   16 irregular), a break event (1), or the refresh of the nodes
    ///   a relaxation touched, node by node (each its springs).
    ///
    /// The crack network is traced live, in pieces of at most [`TRACE_PIECE`] units within the
    /// same budgets: once springs have broken since the last trace began
    /// (looked for every [`LIVE_CHECK`] units of the physics), a trace of the springs broken so
    /// far begins, and it gets one unit of work for every [`LIVE_SHARE`] of the physics (the
    /// physics' work before it included; the first trace all the work it needs, so the first
    /// cracks show as soon as it is done). A trace visits the
    /// springs, mesh cells and nodes its cracks touch, and reads the rest as words of 32 flags:
    /// its work grows with the cracks, not with the lattice. It writes a second copy of the
    /// network's words; when it is done, that copy is the network shown. So at every call the
    /// network, the cells, the statistics and the rasters show one whole trace, of
    /// [`Mud::shown_broken_springs`] springs (a number that never falls), drawn at the
    /// displacements of now. When the physics ends, a trace under way is dropped and the final
    /// trace, of the cracks as they end, is done in the same way ([`Mud::is_tracing`]); the run
    /// is finished when it is. The live traces add at most one part in [`LIVE_SHARE`] to the
    /// physics' work, and the first trace's (on the default runs, about 11 % to a quasi-static
    /// run's total and 3–6 % to an explicit one's: see the changelog).
    ///
    /// The run does not depend on the budgets: every budget gives the same physics, the same
    /// final network and the same work, bit for bit, and even the same live networks at the
    /// same work (the switches between the physics and a live trace are at fixed counts of
    /// their work). Which live network a call shows depends on where its budget ends.
    ///
    /// A budget of `u64::MAX` ([`Mud::run`]) runs to the end in this one call, so no live
    /// network could be seen before it returns: it makes none. It does the physics and the
    /// final trace only, and ends with the same outputs, bit for bit, as every other budget
    /// (the network, the cells, the statistics, the rasters, every break time), with less
    /// work.
    ///
    /// An error ends the run: the call that finds it and every later one return it, and the
    /// outputs stay those of the uncracked plate.
    pub fn step(&mut self, budget: u64) -> Result<MudProgress, MudError> {
        if let Some(error) = self.failure {
            return Err(error);
        }
        let mut work = 0u64;
        if !self.is_set_up() {
            work = self.setup_step(budget);
            self.work += work;
            if let Some(error) = self.failure {
                return Err(error);
            }
            if !self.is_set_up() {
                return Ok(self.progress());
            }
        }
        let setup_work = work;
        // A live trace's words stay in front between its pieces within this call (the physics
        // does not read the network); the shown network's are put back before it returns.
        let mut swapped = false;
        while work < budget.max(1) {
            let left = budget.saturating_sub(work);
            if self.finished {
                // The physics is over: the final trace, of the cracks as they end (a live
                // trace under way is dropped: it read the run at an earlier time).
                if !self.final_traced {
                    self.final_traced = true;
                    self.tracing = None;
                    if self.broken > 0 {
                        self.start_trace();
                    }
                }
                if self.tracing.is_none() {
                    break;
                }
                work += self.trace_step_swapped(left, &mut swapped);
                continue;
            }
            // Live tracing: a trace of the springs broken so far gets one part in
            // `LIVE_SHARE` of the physics' work (the first one all it needs, so that the first
            // cracks show at once); between traces, new breaks are looked for every
            // `LIVE_CHECK` units. Each switch is at a fixed count of the physics' and the
            // traces' work, so the order of the pieces does not depend on the budgets.
            let (physics, live) = (self.physics_work, self.live_work);
            let slice = if budget == u64::MAX {
                // A call that runs to the end: no live network it traced could be seen.
                left
            } else if self.tracing.is_some() {
                let first = self.shown_broken == 0;
                if first || live.saturating_mul(LIVE_SHARE) < physics {
                    let share = if first { u64::MAX } else { physics.div_ceil(LIVE_SHARE) - live };
                    let done = self.trace_step_swapped(left.min(share), &mut swapped);
                    // (The first trace's work is not counted against the share.)
                    if !first {
                        self.live_work += done;
                    }
                    work += done;
                    continue;
                }
                live.saturating_mul(LIVE_SHARE) + 1 - physics
            } else {
                if physics >= self.next_check {
                    self.next_check = physics.saturating_add(LIVE_CHECK);
                    if self.broken > self.traced_broken {
                        self.start_trace();
                        continue;
                    }
                }
                self.next_check - physics
            };
            let slice = left.min(slice);
            let done = match self.solver {
                SolverState::Explicit(_) => self.explicit_step(slice),
                SolverState::QuasiStatic(_) => self.quasi_static_step(slice),
            };
            self.physics_work += done;
            work += done;
        }
        self.unswap(&mut swapped);
        self.work += work - setup_work;
        Ok(self.progress())
    }

    /// Runs to the end (target shrink or crack density), or to an error: [`Mud::step`] with a
    /// budget of `u64::MAX`, which makes no live trace (nothing could show one).
    pub fn run(&mut self) -> Result<MudProgress, MudError> {
        self.step(u64::MAX)
    }

    /// Whether the setup (the first steps' work: see [`Mud::step`]) is still under way; until it
    /// is done the run is an uncracked plate at shrink 0.
    pub fn is_setting_up(&self) -> bool {
        self.setup.is_some()
    }

    /// Where the run stands.
    pub fn progress(&self) -> MudProgress {
        MudProgress {
            shrink: self.misfit.to_f32(),
            time: self.time_now(),
            broken_springs: self.broken,
            crack_density: self.crack_density(),
            finished: self.finished && self.final_traced && self.tracing.is_none(),
            work: self.work,
        }
    }

    /// The parameters of the run.
    pub fn params(&self) -> &MudParams {
        &self.params
    }

    /// Width and height of the run's domain (one period when periodic), lattice units (times
    /// `element_size` for cm): columns × rows on the square lattice, columns × rows·√3/2 on
    /// the hexagonal one, columns × rows·887/1024 on the irregular one. Points of the network
    /// and the cells lie in it, x along a row and y across the rows, as a raster's columns
    /// and rows (row 0 at y = 0); a raster stretches it over its width × height
    /// ([`MudRender::fit`] keeps its aspect).
    pub fn extent(&self) -> [f32; 2] {
        self.lattice.extent()
    }

    /// The lattice of the run (an irregular lattice's mesh once the first steps have built
    /// it: until then [`Lattice::mesh`] is `None`).
    pub fn lattice(&self) -> &Lattice<'a> {
        &self.lattice
    }

    /// Crack length per area [1/cm]: broken faces over the lattice's area.
    pub fn crack_density(&self) -> f32 {
        let l = &self.lattice;
        let area = l.node_count() as f32 * l.element_area();
        let length = if l.mesh().is_some() { self.broken_face } else { self.broken as f32 * l.face_length() };
        // Elements of extreme size can pass f32's range in cm: saturate (fuzz finding 12).
        if length == 0.0 { 0.0 } else { (length / (area * self.params.element_size)).min(f32::MAX) }
    }

    /// Whether spring `spring` exists and is broken (none is while the setup is under way).
    pub fn is_broken(&self, spring: usize) -> bool {
        self.spring_break_time(spring).is_some()
    }

    /// The long step at which `spring` broke, if it did.
    pub fn spring_break_time(&self, spring: usize) -> Option<f32> {
        if !self.is_set_up() {
            return None;
        }
        self.break_time.get(spring).filter(|&&t| t != INTACT).map(|&t| f32::from_bits(t))
    }

    /// The rest factor r and the deep factor of the current misfit: shrink (r, 1), growth
    /// (1, 1 + misfit).
    fn factors(&self) -> (S, S) {
        match self.params.drive {
            Drive::Shrink => (S::ONE - self.misfit, S::ONE),
            Drive::Growth => (S::ONE, S::ONE + self.misfit),
        }
    }

    /// The misfit after `n` long steps: r = γⁿ (Eq. 1).
    fn misfit_at(&self, n: u32) -> S {
        let r = libm::powf(self.params.shrink_ratio, n as f32);
        S::from_f32(match self.params.drive {
            Drive::Shrink => 1.0 - r,
            Drive::Growth => 1.0 / r - 1.0,
        })
    }

    /// The time, in long steps, at which the misfit is `misfit`: n = ln r / ln γ.
    fn time_at(&self, misfit: S) -> f32 {
        let m = misfit.to_f32();
        let r = match self.params.drive {
            Drive::Shrink => 1.0 - m,
            Drive::Growth => 1.0 / (1.0 + m),
        };
        // γ < 1 (validated), so ln γ < 0; r ≥ 1 (no misfit yet) is time 0, not −0.
        let ln_gamma = libm::logf(self.params.shrink_ratio);
        if r >= 1.0 || r <= 0.0 { 0.0 } else { libm::logf(r) / ln_gamma }
    }

    fn time_now(&self) -> f32 {
        match self.solver {
            SolverState::Explicit(_) => self.long_steps as f32,
            SolverState::QuasiStatic(_) => self.time_at(self.misfit),
        }
    }

    /// The target misfit, if any.
    fn target_misfit(&self) -> Option<S> {
        (self.params.target_shrink > 0.0).then(|| S::from_f32(self.params.target_shrink))
    }

    /// The largest misfit the model follows: shrink 0.99 (rest lengths a hundredth), growth
    /// 100. A spring that breaks only beyond it never breaks.
    fn misfit_limit(&self) -> S {
        S::from_f32(match self.params.drive {
            Drive::Shrink => params::LARGEST_SHRINK,
            Drive::Growth => params::LARGEST_GROWTH,
        })
    }

    /// The misfit at which the run ends, in both solvers: the target, or else the limit.
    fn end_misfit(&self) -> S {
        self.target_misfit().unwrap_or_else(|| self.misfit_limit())
    }

    /// Whether the crack density reached its target.
    fn density_reached(&self) -> bool {
        self.params.target_crack_density > 0.0 && self.crack_density() >= self.params.target_crack_density
    }

    /// Breaks `spring` now.
    fn break_spring(&mut self, spring: usize) {
        self.break_time[spring] = self.time_now().to_bits();
        network::set_bit(self.broken_blocks, spring);
        self.broken += 1;
        if self.lattice.mesh().is_some() {
            self.broken_face += self.lattice.face(spring);
        }
        if self.density_reached() {
            self.finished = true;
        }
    }

    /// The node `spring` leaves.
    fn origin(&self, spring: usize) -> usize {
        match self.lattice.mesh() {
            Some(m) => m.ends(spring).map_or(0, |(a, _)| a),
            None => self.lattice.spring_origin(spring).0,
        }
    }

    /// The nodes `spring` joins (the one it leaves first), if it exists: from the run's table
    /// of the nodes springs reach, without the lattice's arithmetic.
    #[cfg_attr(target_pointer_width = "64", inline(always))]
    fn spring_ends(&self, spring: usize) -> Option<(usize, usize)> {
        let other = self.other[spring];
        (other != ABSENT).then(|| (self.origin(spring), other as usize))
    }

    /// Current displacement of `node` from its deep node. (Inlined on 64-bit targets, where
    /// the traces call it for every corner; not on 32-bit ones, for the Cortex-M3's flash.)
    #[cfg_attr(target_pointer_width = "64", inline(always))]
    fn displacement(&self, node: usize) -> (S, S) {
        match self.solver {
            SolverState::Explicit(_) => (self.ux[node], self.uy[node]),
            SolverState::QuasiStatic(_) => (self.misfit * self.ux[node], self.misfit * self.uy[node]),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    extern crate std;
    use std::vec;

    #[test]
    fn memory_is_exact_and_checked() {
        let p = MudParams { columns: 10, rows: 8, ..MudParams::default() };
        let m = p.memory().unwrap();
        assert_eq!(m.scalars, 80 * 2 + 240 * 2);
        // Springs: other, break time, cut and crack offset twice; cells: stack and ring starts
        // twice; flags per block of 32 springs (3), cells and nodes (2 each); a tree over 8 blocks of 32 springs; queue, flags and touched list per node.
        assert_eq!(m.words, 240 * 6 + 4 * 160 + (3 * 8 + 2 * 5 + 2 * 3) + 2 * 8 + 240);
        let (mut s, mut w) = (vec![0.0f32; m.scalars], vec![0u32; m.words]);
        assert!(Mud::new(&p, MudBuffers { scalars: &mut s[..m.scalars - 1], words: &mut w }).is_err());
        assert_eq!(
            Mud::new(&p, MudBuffers { scalars: &mut s, words: &mut w[..m.words - 1] }).err(),
            Some(MudError::BufferTooSmall { needed: m.words })
        );
        // Nothing was written on failure.
        assert!(s.iter().all(|&x| x == 0.0) && w.iter().all(|&x| x == 0));
        assert!(Mud::new(&p, MudBuffers { scalars: &mut s, words: &mut w }).is_ok());
        let huge = MudParams { columns: u32::MAX, rows: u32::MAX - 1, ..MudParams::default() };
        assert_eq!(huge.memory(), Err(MudParamError::SizeOverflow));
    }

    #[test]
    fn cells_are_the_regions_the_cracks_enclose() {
        let p = MudParams { columns: 12, rows: 12, topology: Topology::Square, ..MudParams::default() };
        let m = p.memory().unwrap();
        let (mut s, mut w) = (vec![0.0f32; m.scalars], vec![0u32; m.words]);
        let mut mud = Mud::new(&p, MudBuffers { scalars: &mut s, words: &mut w }).unwrap();
        // The setup, item by item (the budget ends each call there, before any physics).
        while !mud.is_set_up() {
            assert_eq!(mud.step(1).unwrap().shrink, 0.0);
        }
        mud.trace();
        // Nothing is cut: one region, which wraps around the torus and has no outline.
        assert_eq!(mud.statistics().cells, 1);
        assert_eq!(mud.cell_counts(), CellCounts { rings: 0, points: 0, wrapping: 0 });
        // Cut the periodic square lattice along two columns: springs in direction 0 leaving
        // columns 2 and 8 in every row. Two bands remain, each half the area, each bounded
        // by two cracks that wrap around the torus.
        for row in 0..12 {
            for column in [2, 8] {
                mud.break_spring(row * 12 + column);
            }
        }
        mud.trace();
        let stats = mud.statistics();
        assert_eq!((stats.cells, stats.mean_cell_area), (2, 72.0));
        assert_eq!(mud.cell_counts().wrapping, 4);
        // Cut a row across too: each band becomes a closed 6 × 12 rectangle, a plane
        // polygon reaching one period past its start.
        for column in 0..12 {
            mud.break_spring(144 + 5 * 12 + column);
        }
        mud.trace();
        let counts = mud.cell_counts();
        assert_eq!((counts.rings, counts.wrapping), (2, 0));
        let mut rings = vec![crate::polygon::Ring::default(); counts.rings];
        let mut points = vec![[0.0f32; 2]; counts.points];
        assert_eq!(mud.cells(&mut rings[..1], &mut points), Err(MudError::BufferTooSmall { needed: 2 }));
        assert!(rings.iter().all(|r| *r == crate::polygon::Ring::default()), "nothing written on failure");
        assert_eq!(mud.cells(&mut rings, &mut points), Ok(counts));
        for ring in &rings {
            assert!((ring.area - 72.0).abs() < 1e-3, "{ring:?}");
        }
        let stats = mud.statistics();
        assert_eq!((stats.cells, stats.mean_cell_area, stats.cell_area_spread), (2, 72.0, 0.0));
    }

    #[test]
    fn fixed_storage_serves_small_lattices() {
        const M: MudMemory = match memory_for(Topology::Hexagonal, Solver::QuasiStatic, 16, 16) {
            Some(m) => m,
            None => panic!(),
        };
        let mut storage = MudStorage::<f32, { M.scalars }, { M.words }>::new();
        let p = MudParams { columns: 16, rows: 16, ..MudParams::default() };
        let mut mud = Mud::new(&p, storage.buffers()).unwrap();
        assert!(mud.run().unwrap().finished);
    }

    #[test]
    fn an_explicit_short_step_past_the_stability_bound_is_refused() {
        let explicit = MudParams { solver: Solver::Explicit, ..MudParams::default() };
        for topology in [Topology::Square, Topology::Hexagonal] {
            let at = |short_step| MudParams { short_step, topology, columns: 8, rows: 8, ..explicit }.memory();
            // The paper's step, and ten times it, pass the test; twenty times it is refused.
            assert!(at(0.001).is_ok() && at(0.01).is_ok(), "{topology:?}");
            assert_eq!(at(0.02), Err(MudParamError::ShortStepStability), "{topology:?}");
            // The quasi-static solver has no short step to be unstable.
            let quasi_static = MudParams { short_step: 0.02, topology, columns: 8, rows: 8, ..MudParams::default() };
            assert!(quasi_static.memory().is_ok());
            // Nor is the 1-D spacing prediction, which does not depend on τ.
            assert!(MudParams { short_step: 0.02, topology, ..explicit }.predicted_spacing(0.02).is_some());
        }
    }

    /// What a run leaves, to compare runs bit for bit: break times, displacements, the
    /// traced network and cells.
    #[derive(Debug, PartialEq)]
    struct Outcome {
        break_time: vec::Vec<u32>,
        displacement: vec::Vec<(u32, u32)>,
        network: std::string::String,
        cells: CellCounts,
        progress: (u32, u32, u32, bool, u64),
    }

    /// Asserts that the network shown is one whole trace: every edge joins vertices that
    /// exist, its points follow the last edge's, each vertex meets as many edge ends as its
    /// degree, and the cells can be written. Returns the edges.
    fn assert_consistent(mud: &Mud<'_, f32>, p: &MudParams) -> usize {
        let counts = mud.network_counts();
        // The counts the trace kept are those of walking the network and the rings.
        assert_eq!(counts, mud.walked_network_counts(), "{p:?}");
        assert_eq!(mud.cell_counts(), mud.walked_cell_counts(), "{p:?}");
        let mut v = vec![NetworkVertex::default(); counts.vertices];
        let mut e = vec![NetworkEdge::default(); counts.edges];
        let mut q = vec![NetworkPoint::default(); counts.points];
        assert_eq!(mud.network(&mut v, &mut e, &mut q), Ok(counts), "{p:?}");
        let mut ends = vec![0u32; counts.vertices];
        let mut next = 0;
        for edge in &e {
            assert_eq!(edge.first_point, next, "{p:?}");
            assert!(edge.point_count >= 2, "{p:?}: {edge:?}");
            next += edge.point_count;
            for end in [edge.from, edge.to] {
                if end != NO_VERTEX {
                    ends[end as usize] += 1;
                }
            }
        }
        assert_eq!(next as usize, counts.points, "{p:?}");
        for (vertex, n) in v.iter().zip(&ends) {
            assert_eq!(vertex.degree, *n, "{p:?}: {vertex:?}");
        }
        let cells = mud.cell_counts();
        let mut rings = vec![crate::polygon::Ring::default(); cells.rings];
        let mut points = vec![[0.0f32; 2]; cells.points];
        assert_eq!(mud.cells(&mut rings, &mut points), Ok(cells), "{p:?}");
        counts.edges
    }

    /// The counts the trace keeps equal what walking the network and the rings finds, on
    /// every topology and boundary, with cracks and without (an open plate's border is a ring).
    #[test]
    fn the_counts_a_trace_keeps_are_the_walks() {
        use Boundary::{Open, Periodic};
        use Topology::{Hexagonal, Irregular, Square};
        for topology in [Square, Hexagonal, Irregular] {
            for boundary in [Open, Periodic] {
                for (seed, target_shrink) in [(1, 0.0005), (2, 0.023), (3, 0.06)] {
                    let p = MudParams {
                        columns: 20,
                        rows: 20,
                        topology,
                        boundary,
                        seed,
                        target_shrink,
                        ..MudParams::default()
                    };
                    let m = p.memory().unwrap();
                    let (mut s, mut w) = (vec![0.0f32; m.scalars], vec![0u32; m.words]);
                    let mut mud = Mud::new(&p, MudBuffers { scalars: &mut s, words: &mut w }).unwrap();
                    mud.run().unwrap();
                    assert_consistent(&mud, &p);
                }
            }
        }
    }

    /// Runs `p` with `budget` per call (`None`: one `run()`), asserting each call's work is
    /// within the budget and one piece, and that the network shown is always a whole trace,
    /// of as many springs as the last or more.
    fn outcome(p: &MudParams, budget: Option<u64>) -> Outcome {
        let m = p.memory().unwrap();
        let (mut s, mut w) = (vec![0.0f32; m.scalars], vec![0u32; m.words]);
        let mut mud = Mud::new(p, MudBuffers { scalars: &mut s, words: &mut w }).unwrap();
        let piece = match (p.solver, p.topology) {
            // A row's springs in one direction and their rescan for breaks.
            (Solver::Explicit, Topology::Square | Topology::Hexagonal) => 2 * u64::from(p.columns),
            // Spring by spring, node by node: no overrun.
            (Solver::Explicit, Topology::Irregular) => 1,
            // One node's springs.
            (Solver::QuasiStatic, Topology::Square) => 4,
            (Solver::QuasiStatic, Topology::Hexagonal) => 6,
            (Solver::QuasiStatic, Topology::Irregular) => irregular::MAX_DEGREE as u64,
        };
        let piece = piece.max(TRACE_PIECE);
        let (mut traced_in, mut shown, mut networks) = (0, 0, 0);
        let progress = match budget {
            None => mud.run().unwrap(),
            Some(budget) => loop {
                let before = mud.progress().work;
                let progress = mud.step(budget).unwrap();
                let work = progress.work - before;
                let bound = budget.max(1) - 1 + piece;
                assert!(work <= bound, "{p:?}: budget {budget}: {work} > {bound}");
                if mud.is_tracing() {
                    traced_in += 1;
                    assert!(!progress.finished, "{p:?}");
                }
                // A new network shows: a whole trace, of more broken springs than the last.
                let now = mud.shown_broken_springs();
                assert!(now >= shown && now <= progress.broken_springs, "{p:?}");
                if now != shown {
                    // (A break that has not opened is no crack of the network yet.)
                    networks += usize::from(assert_consistent(&mud, p) > 0);
                    shown = now;
                }
                if progress.finished {
                    break progress;
                }
            },
        };
        // A small budget spreads the traces over calls, and the cracks show as they break.
        if budget == Some(1) {
            assert!(traced_in > 100, "{p:?}: traced in {traced_in} calls");
        }
        // The explicit runs break spring by spring over many long steps: networks show on
        // the way (the quasi-static ones here break in one avalanche, shorter than a trace).
        if budget.is_some() && p.solver == Solver::Explicit {
            assert!(networks >= 10, "{p:?}: budget {budget:?}: {networks} networks shown during the run");
        }
        assert_eq!(mud.shown_broken_springs(), progress.broken_springs, "{p:?}");
        let counts = mud.network_counts();
        let mut v = vec![NetworkVertex::default(); counts.vertices];
        let mut e = vec![NetworkEdge::default(); counts.edges];
        let mut q = vec![NetworkPoint::default(); counts.points];
        mud.network(&mut v, &mut e, &mut q).unwrap();
        Outcome {
            break_time: mud.break_time.to_vec(),
            displacement: (0..mud.lattice.node_count())
                .map(|n| {
                    let (x, y) = mud.displacement(n);
                    (x.to_bits(), y.to_bits())
                })
                .collect(),
            network: std::format!("{v:?} {e:?} {q:?}"),
            cells: mud.cell_counts(),
            progress: (
                progress.broken_springs,
                progress.shrink.to_bits(),
                progress.time.to_bits(),
                progress.finished,
                progress.work,
            ),
        }
    }

    /// Frame budgets: any budget gives the same run, bit for bit, and the same work in total,
    /// and each call does at most its budget and one piece bounded by a row (explicit), a
    /// node's springs (quasi-static) or [`TRACE_PIECE`] (the tracing, which shows nothing
    /// while under way); one unbounded call gives the same run in less work (no live trace).
    #[test]
    fn budgets_change_no_bit_and_bound_each_call() {
        use Boundary::{Open, Periodic};
        use Topology::{Hexagonal, Irregular, Square};
        let small = MudParams { columns: 10, rows: 8, target_shrink: 0.03, ..MudParams::default() };
        let cases = [
            (Hexagonal, Periodic, Solver::Explicit, Drive::Shrink),
            (Hexagonal, Open, Solver::Explicit, Drive::Growth),
            (Square, Open, Solver::Explicit, Drive::Shrink),
            (Square, Periodic, Solver::Explicit, Drive::Growth),
            (Irregular, Periodic, Solver::Explicit, Drive::Shrink),
            (Irregular, Open, Solver::Explicit, Drive::Growth),
            (Hexagonal, Open, Solver::QuasiStatic, Drive::Shrink),
            (Hexagonal, Periodic, Solver::QuasiStatic, Drive::Growth),
            (Square, Periodic, Solver::QuasiStatic, Drive::Shrink),
            (Irregular, Open, Solver::QuasiStatic, Drive::Shrink),
            (Irregular, Periodic, Solver::QuasiStatic, Drive::Growth),
        ];
        for (topology, boundary, solver, drive) in cases {
            let p = MudParams { topology, boundary, solver, drive, ..small };
            let stepped = outcome(&p, Some(1));
            assert!(stepped.progress.0 > 0, "{p:?}: nothing broke");
            for budget in [7, 1000] {
                assert!(outcome(&p, Some(budget)) == stepped, "{p:?}: budget {budget} changed the run");
            }
            let whole = outcome(&p, None);
            assert!(whole.progress.4 < stepped.progress.4, "{p:?}: one call did {:?}", whole.progress);
            let work =
                (stepped.progress.0, stepped.progress.1, stepped.progress.2, stepped.progress.3, whole.progress.4);
            assert!(whole == Outcome { progress: work, ..stepped }, "{p:?}: one call changed the run");
            // Tracing again in one call finds the network the budgeted trace found.
            let m = p.memory().unwrap();
            let (mut s, mut w) = (vec![0.0f32; m.scalars], vec![0u32; m.words]);
            let mut mud = Mud::new(&p, MudBuffers { scalars: &mut s, words: &mut w }).unwrap();
            while !mud.step(3).unwrap().finished {}
            let before = mud.network_counts();
            mud.trace();
            assert_eq!(mud.network_counts(), before, "{p:?}");
        }
    }
}
