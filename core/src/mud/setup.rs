//! The setup of a run, done by its first [`Mud::step`] calls within their budgets (so that
//! [`Mud::new`] does work independent of the lattice's size): the irregular lattice's mesh and
//! its nodes' constants, every spring's break stretch, the arrays cleared, and the
//! quasi-static solver's break misfits, tree and queue.
//!
//! It goes pass by pass, item by item (a spring, a node, a mesh cell, a block of the tree), in
//! the order one call would take, so stopping between items changes nothing: the run does not
//! depend on the budgets. Until it is done the outputs describe an uncracked plate at shrink
//! 0, and nothing reads an array element it has not written (the buffers may hold any bytes).

use super::irregular::{self, Construction, Mesh};
use super::material::Material;
use super::quasi_static::BLOCK;
use super::{ABSENT, INTACT, Mud, MudError, MudParamError, Solver, SolverState, Topology, explicit, quasi_static};
use crate::rng::{Rng, Stream};
use crate::scalar::Scalar;

/// Work units one irregular node's constants count (the most springs at a node: the node's
/// springs are summed, and its stability and decay are computed from them).
const NODE_PIECE: u64 = irregular::MAX_DEGREE as u64;

/// The most work one piece of the setup does, in [`Mud::step`]'s units: a block of the
/// quasi-static solver's tree (32 springs). The irregular lattice's jittered nodes and node
/// constants count 16 each; every other item (a spring, a node, a mesh cell, a slot) 1.
pub const SETUP_PIECE: u64 = BLOCK as u64;

const _: () = assert!(NODE_PIECE <= SETUP_PIECE && irregular::JITTER_PIECE <= SETUP_PIECE);

/// The setup's passes, in order (those a run needs: the mesh and node constants only on the
/// irregular lattice, the tree and queue only with the quasi-static solver).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Pass {
    /// The irregular lattice's mesh ([`Construction`]).
    Mesh,
    /// Per irregular node: the explicit run's stability test (Eq. 3's damped step) and its
    /// five constants, and the node's share of the settle or relax bound.
    NodeConstants,
    /// Per spring: the node it reaches, its break stretch κ_i, intact, not cut, and the
    /// explicit solver's limit; per word of their flags, no break, nothing touched in the
    /// network shown and everything in its other copy (which the first trace clears).
    Springs,
    /// Per node: no displacement (explicit: no velocity; quasi-static: no flags); per block of
    /// them, nothing touched.
    Nodes,
    /// Per mesh cell: the tracing's stack and ring starts cleared; per block of them, nothing
    /// touched.
    Cells,
    /// Quasi-static, per spring: the misfit at which it breaks.
    BreakMisfits,
    /// Quasi-static, per tree slot: empty.
    TreeSlots,
    /// Quasi-static, per block of springs: its winner.
    TreeLeaves,
    /// Quasi-static, per inner slot, from the leaves up: its winner.
    TreeInner,
    /// Quasi-static, per node of an open or irregular lattice: queued for relaxing.
    Queue,
}

/// Where the setup stands: its pass, the pass's next item, and what it carries between them.
pub(super) struct Setup {
    pass: Pass,
    item: usize,
    /// The irregular lattice's construction under way.
    construction: Construction,
    /// The stream of the pass under way: the jitter's, then the break stretches'.
    rng: Rng,
    /// The constants in `f32` whatever the backend, for the stability test and the bounds.
    reference: Material<f32>,
    /// Over the irregular nodes so far: the slowest contraction of the explicit damped step,
    /// or the smallest h/Σk of the quasi-static relaxation.
    slowest: f64,
}

impl Setup {
    /// The setup of a run of `topology` and `solver` with `seed`, before its first item.
    pub(super) fn new(seed: u64, topology: Topology, solver: Solver, reference: Material<f32>) -> Self {
        let irregular = topology == Topology::Irregular;
        Setup {
            pass: if irregular { Pass::Mesh } else { Pass::Springs },
            item: 0,
            construction: Construction::new(),
            rng: Rng::new(seed, if irregular { Stream::LatticeJitter } else { Stream::BreakStretch }),
            reference,
            slowest: match solver {
                Solver::Explicit => 0.0,
                Solver::QuasiStatic => f64::INFINITY,
            },
        }
    }
}

impl<'a, S: Scalar> Mud<'a, S> {
    /// Whether the setup is done (and the arrays hold the run).
    pub(super) fn is_set_up(&self) -> bool {
        self.setup.is_none()
    }

    /// Goes on with the setup, item by item, until the work reaches `max(budget, 1)`, the
    /// setup is done, or the irregular explicit run fails its stability test (the failure is
    /// kept); returns the work. Overruns the budget by less than [`SETUP_PIECE`].
    pub(super) fn setup_step(&mut self, budget: u64) -> u64 {
        let budget = budget.max(1);
        let mut work = 0u64;
        while work < budget && self.failure.is_none() {
            let Some(setup) = &mut self.setup else { break };
            let (pass, from) = (setup.pass, setup.item);
            if pass == Pass::Mesh {
                let scratch = irregular::Scratch {
                    node_cell: &mut *self.stack,
                    pending: &mut *self.trace,
                    queued: &mut *self.break_time,
                    degree: &mut *self.other,
                };
                let (done, built) = setup.construction.advance(
                    &self.lattice,
                    &self.params,
                    &mut *self.mesh_words,
                    scratch,
                    &mut setup.rng,
                    budget - work,
                );
                work += done;
                if built {
                    let words = core::mem::take(&mut self.mesh_words);
                    self.lattice.mesh = Some(Mesh::of(words, self.lattice.node_count()));
                    (setup.pass, setup.item) = (Pass::NodeConstants, 0);
                }
                continue;
            }
            let (len, cost) = self.pass_extent(pass);
            // Items from..end: as many as the budget left takes (at least one).
            let items = usize::try_from((budget - work).div_ceil(cost)).unwrap_or(usize::MAX);
            let end = from.saturating_add(items).min(len);
            let end = match pass {
                Pass::Mesh => unreachable!("built above"),
                Pass::NodeConstants => self.node_constants(from, end),
                Pass::Springs => self.springs(from, end),
                Pass::Nodes => {
                    let blocks = super::network::blocks_from(from, end);
                    self.touched.nodes[blocks.clone()].fill(0);
                    self.back.touched.nodes[blocks].fill(0);
                    self.ux[from..end].fill(S::ZERO);
                    self.uy[from..end].fill(S::ZERO);
                    match &mut self.solver {
                        SolverState::Explicit(d) => d.clear_nodes(from, end),
                        SolverState::QuasiStatic(r) => r.clear_nodes(from, end, &self.lattice),
                    }
                    end
                }
                Pass::Cells => {
                    self.stack[from..end].fill(0);
                    self.ring_starts[from..end].fill(0);
                    let blocks = super::network::blocks_from(from, end);
                    self.touched.cells[blocks.clone()].fill(0);
                    self.back.touched.cells[blocks].fill(0);
                    end
                }
                Pass::BreakMisfits => {
                    self.set_break_misfits(from, end);
                    end
                }
                Pass::TreeSlots | Pass::TreeLeaves | Pass::TreeInner => {
                    let SolverState::QuasiStatic(r) = &mut self.solver else { unreachable!("quasi-static pass") };
                    match pass {
                        Pass::TreeSlots => r.clear_tree(from, end),
                        Pass::TreeLeaves => r.tree_leaves(from, end),
                        _ => r.tree_inner(from, end),
                    }
                    end
                }
                Pass::Queue => {
                    let SolverState::QuasiStatic(r) = &mut self.solver else { unreachable!("quasi-static pass") };
                    r.queue_nodes(from, end);
                    end
                }
            };
            work += (end - from) as u64 * cost;
            if self.failure.is_some() {
                break;
            }
            let Some(setup) = &mut self.setup else { break };
            setup.item = end;
            if end == len {
                self.next_pass(pass);
            }
        }
        work
    }

    /// A pass's items and the work each counts.
    fn pass_extent(&self, pass: Pass) -> (usize, u64) {
        let l = &self.lattice;
        let (nodes, springs) = (l.node_count(), l.spring_count());
        match (pass, &self.solver) {
            (Pass::Mesh, _) => (0, 1),
            (Pass::NodeConstants, _) => (nodes, NODE_PIECE),
            (Pass::Springs | Pass::BreakMisfits, _) => (springs, 1),
            (Pass::Nodes, _) => (nodes, 1),
            (Pass::Cells, _) => (l.cell_count(), 1),
            (Pass::TreeSlots, SolverState::QuasiStatic(r)) => (r.tree_len(), 1),
            (Pass::TreeLeaves, _) => (springs.div_ceil(BLOCK), BLOCK as u64),
            (Pass::TreeInner, SolverState::QuasiStatic(r)) => (r.tree_len() / 2 - 1, 1),
            // The irregular lattice is not in equilibrium at u = 0 either: its springs differ
            // (a periodic regular lattice is, by symmetry).
            (Pass::Queue, _) if self.params.boundary == super::Boundary::Open || l.mesh().is_some() => (nodes, 1),
            _ => (0, 1),
        }
    }

    /// Ends pass `pass`: sets up the next one, or ends the setup.
    fn next_pass(&mut self, pass: Pass) {
        let quasi_static = matches!(self.solver, SolverState::QuasiStatic(_));
        let next = match pass {
            Pass::Mesh => Some(Pass::NodeConstants),
            Pass::NodeConstants => {
                let slowest = self.setup.as_ref().map_or(0.0, |s| s.slowest);
                let nodes = self.lattice.node_count();
                match &mut self.solver {
                    SolverState::Explicit(d) => d.set_settle_bound(explicit::settle_bound_of(slowest)),
                    SolverState::QuasiStatic(r) => r.set_relax_bound(quasi_static::relax_bound_of(slowest, nodes)),
                }
                Some(Pass::Springs)
            }
            Pass::Springs => Some(Pass::Nodes),
            Pass::Nodes => Some(Pass::Cells),
            Pass::Cells if quasi_static => Some(Pass::BreakMisfits),
            Pass::BreakMisfits => Some(Pass::TreeSlots),
            Pass::TreeSlots => Some(Pass::TreeLeaves),
            Pass::TreeLeaves => Some(Pass::TreeInner),
            Pass::TreeInner => Some(Pass::Queue),
            Pass::Cells | Pass::Queue => None,
        };
        let seed = self.params.seed;
        match (next, &mut self.setup) {
            (Some(next), Some(setup)) => {
                (setup.pass, setup.item) = (next, 0);
                if next == Pass::Springs {
                    setup.rng = Rng::new(seed, Stream::BreakStretch);
                }
                // A pass with no items (the queue of a periodic regular lattice) ends at once,
                // so the setup ends with its last item.
                if self.pass_extent(next).0 == 0 {
                    self.next_pass(next);
                }
            }
            _ => self.setup = None,
        }
    }

    /// The irregular nodes `from..end`: each passes the explicit run's stability test (or the
    /// run fails there, and this returns the node after it) and gets its constants, and joins
    /// the bound on the settling or relaxing work. Returns where it stopped.
    fn node_constants(&mut self, from: usize, end: usize) -> usize {
        let Some(mesh) = self.lattice.mesh().copied() else { return end };
        let Some(setup) = &mut self.setup else { return end };
        let reference = setup.reference;
        let alpha = self.params.damping_factor;
        let tolerance_length = self.params.displacement_tolerance / self.params.element_size;
        for node in from..end {
            match &mut self.solver {
                SolverState::Explicit(d) => {
                    let n = explicit::NodeConstants::of(&mesh, node, reference.shear_per_area, alpha);
                    if !n.is_stable(&reference) {
                        self.failure = Some(MudError::Param(MudParamError::ShortStepStability));
                        return node + 1;
                    }
                    setup.slowest = setup.slowest.max(n.slowest_contraction(&reference));
                    d.set_node_constants(node, &n, &self.material, tolerance_length);
                }
                SolverState::QuasiStatic(_) => {
                    setup.slowest = setup.slowest.min(quasi_static::shear_over_springs(&mesh, node, &reference));
                }
            }
        }
        end
    }

    /// Springs `from..end`, in order: the node each reaches, its break stretch κ_i (drawn
    /// for absent springs too, so that a spring's κ does not depend on edges), intact and not
    /// cut. Returns `end`.
    fn springs(&mut self, from: usize, end: usize) -> usize {
        let Some(setup) = &mut self.setup else { return end };
        let params = &self.params;
        let (lattice, material) = (&self.lattice, &self.material);
        // κ̄ − 1, scaled to the element size when asked (mesh-scale independence, §4.2).
        let x = params.break_stretch_size_exponent;
        let scale = if x == 0.0 { 1.0 } else { libm::powf(1.0 / params.element_size, x) };
        let margin = (params.break_stretch_mean - 1.0) * scale;
        for spring in from..end {
            let other = lattice.spring_nodes(spring).map_or(ABSENT, |(_, b)| b as u32);
            self.other[spring] = other;
            // κ_i = κ̄ + σ/√A_i·N(0,1); anisotropy scales the margin κ_i − 1 (Fig. 7). The
            // irregular lattice's springs each have their own face and direction.
            let (spread, factor) = match lattice.mesh() {
                Some(m) => (
                    material.spread_per_root_face / crate::scalar::sqrtf(m.face(spring)),
                    super::material::anisotropy(
                        m.direction(spring),
                        params.anisotropy_direction,
                        params.anisotropy_ratio,
                    ),
                ),
                None => (material.break_stretch_spread, material.margin_factor[lattice.spring_origin(spring).1]),
            };
            let kappa = 1.0 + margin + spread * setup.rng.normal_f32();
            self.break_stretch[spring] = S::from_f32(1.0 + (kappa - 1.0) * factor);
            self.break_time[spring] = INTACT;
            self.trace[spring] = INTACT;
            self.crack_offset[spring] = 0;
            if spring % super::network::BLOCK == 0 {
                let b = spring / super::network::BLOCK;
                self.broken_blocks[b] = 0;
                self.touched.springs[b] = 0;
                // The other copy's cuts are not set: every spring is flagged, so that the
                // first trace into it clears them (`TracePass::Clean`).
                let valid = (lattice.spring_count() - spring).min(super::network::BLOCK);
                self.back.touched.springs[b] = u32::MAX >> (super::network::BLOCK - valid);
            }
            if let SolverState::Explicit(d) = &mut self.solver {
                d.set_up_spring(spring, other == ABSENT);
            }
        }
        end
    }
}
