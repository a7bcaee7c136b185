//! The fast solver: linear quasi-static equilibrium with event-driven breaking.
//!
//! Linearised about the deep layer, the equilibrium of Eq. 2 at misfit s (shrink 1 − r,
//! growth 1/r − 1) is linear in s: the displacements are s·u, where u solves, at every node,
//!
//! (h·I + Σ_j k_ij e_ij e_ijᵀ)·u_i = Σ_j k_ij (l0 + e_ij·u_j) e_ij
//!
//! (e_ij the unit vector from i to j, intact springs only). Spring i–j is then stretched to
//! l = l0·deep + s·e_ij·(u_j − u_i) and breaks (Eq. 5) when l > κ·l0·rest, i.e. at the misfit
//!
//! s_break = (κ − 1) / (e·(u_j − u_i) + a + κ·b)   (l0 = 1; shrink a = 0, b = 1; growth a = 1, b = 0).
//!
//! So instead of creeping up the shrink by long steps, the solver jumps the misfit straight
//! to the smallest s_break, breaks that spring, re-relaxes the nodes around it (Gauss–Seidel
//! on a FIFO work queue, so relaxation spreads outwards from the break: a node whose u
//! changes by more than the tolerance queues its neighbours), and repeats. A spring found
//! past its limit while the relaxation spreads breaks at once, as the paper's explicit loop
//! breaks springs that are overloaded on the way to equilibrium (without this rule the
//! quasi-static cells came out a third larger). The node updates are not over-relaxed: an
//! over-relaxed update (1.2 was used) overshoots equilibrium, and the overshoot breaks springs
//! the equilibrium would not; on the traced network the two solvers' mean cell areas were
//! then 19 % apart over 8 seeds (48²), and without it they agree within 15 %. When the queue is empty, springs whose
//! s_break is below the misfit break first, smallest s_break first (the most overstrained).
//! A tournament tree over blocks of springs keeps the smallest s_break in O(log n).
//!
//! Every relaxation ends within a bound that follows from the parameters: the tolerance is at
//! least [`SOLVE_ROUNDING`] units of the backend's resolution, and after a break (or the
//! setup) at most [`relax_bound`] nodes are relaxed before the rest of the queue is dropped.

use super::{ABSENT, Drive, INTACT, Mud, SolverState, take};
use crate::scalar::Scalar;

/// `body` for each `k` in `0..n` (`n` at most 6), written out: a loop over a node's springs
/// whose indices into its arrays are then constants.
macro_rules! unrolled {
    ($n:expr, |$k:ident| $body:block) => {
        unrolled!(@each $n, $k, $body, 0 1 2 3 4 5)
    };
    (@each $n:expr, $k:ident, $body:block, $($i:literal)*) => {{
        $({
            let $k: usize = $i;
            if $k < $n $body
        })*
    }};
}

/// No index (empty tree slot, empty queue flag).
const NONE: u32 = u32::MAX;

/// Springs per leaf of the tournament tree: a leaf holds its block's winner, so most updates
/// (a spring that neither wins nor held the win) end at the leaf, and the tree stays small
/// enough to stay in cache.
pub(super) const BLOCK: usize = 32;

/// The smallest misfit the relaxation tolerance is scaled by (see [`Mud::relax`]).
const TOLERANCE_MISFIT_FLOOR: f32 = 0.005;

/// The least relaxation tolerance, in units of the backend's resolution ([`Scalar::RESOLUTION`]):
/// a node's solve sums rounded products over its springs, so its u moves by a few units from
/// rounding alone, and a smaller tolerance passes that back and forth between neighbours.
/// Measured on Q16.16 (the smallest δx, 100² open hexagonal plate, shrink to the end): 1 or 2
/// units relax for over 2·10⁹ units of work without reaching the end, 4 end in 6·10⁷ and 8 in
/// 5·10⁷ (f32: 4·10⁷); the irregular lattice's nodes have more springs (64², 8 units: half the
/// work of 4). In f32 it applies only where δx/(W·s) < 8·ε ≈ 9.5·10⁻⁷: never at the paper's δx
/// (s ≤ 100), and at smaller δx only at growths past (δx/W)/(9.5·10⁻⁷).
const SOLVE_ROUNDING: i32 = 8;

/// Arrays of the quasi-static solver.
pub(super) struct Relaxation<'a, S> {
    /// Per spring: the misfit at which it breaks (S::MAX: never, broken or absent).
    break_misfit: &'a mut [S],
    /// Tournament tree over blocks of springs: `tree[leaves + b]` holds the winner (smallest
    /// break misfit, then lowest index) of springs `BLOCK·b..BLOCK·(b + 1)`; each inner slot
    /// the winner of its two children; `tree[1]` wins.
    tree: &'a mut [u32],
    leaves: usize,
    /// FIFO ring of nodes to relax.
    queue: &'a mut [u32],
    /// Per node: QUEUED and TOUCHED bits, and on a regular lattice (64-bit targets) which of
    /// its springs are broken (from [`BROKEN_SHIFT`] up) and whether it lies away from the
    /// edges ([`INTERIOR`], [`ODD_ROW_SHIFT`]).
    flags: &'a mut [u32],
    head: usize,
    len: usize,
    /// Nodes relaxed since the tree was last brought up to date.
    touched: &'a mut [u32],
    touched_len: usize,
    /// How far the refresh under way has come: touched nodes whose springs are up to date,
    /// then (past `touched_len`) touched marks cleared.
    refreshed: usize,
    /// Node relaxations since the last break (or the setup).
    relaxed: u64,
    /// The most node relaxations that follow a break before the rest of the queue is dropped
    /// ([`relax_bound`]).
    relax_bound: u64,
    /// The relaxation tolerance at the misfit now ([`relax_tolerance`]).
    tolerance: S,
    /// A regular lattice's spring laws in [`Lattice::star_in_row`]'s order: e towards the
    /// other node, and k ([`interior_laws`]).
    ///
    /// [`Lattice::star_in_row`]: super::Lattice::star_in_row
    laws: [[S; 3]; 6],
    /// The lattice's [`Lattice::column_reciprocal`].
    ///
    /// [`Lattice::column_reciprocal`]: super::Lattice::column_reciprocal
    reciprocal: u64,
}

/// The spring laws of a regular lattice's node, in [`super::Lattice::star_in_row`]'s order:
/// e towards the other node (the direction's vector, negated for an incoming spring) and k,
/// as [`Mud::relax`] finds them spring by spring. (Unused on the irregular lattice.)
pub(super) fn interior_laws<S: Scalar>(lattice: &super::Lattice, material: &super::Material<S>) -> [[S; 3]; 6] {
    let dirs = lattice.directions();
    core::array::from_fn(|k| {
        let (d, sign) = (k % dirs, if k < dirs { 1.0 } else { -1.0 });
        let v = lattice.direction_vector(d);
        [S::from_f32(v[0] * sign), S::from_f32(v[1] * sign), material.stiffness[d]]
    })
}

/// The entries of a table of [`interior_system`]s ([`Mud::quasi_static_step`]): one per set of a
/// node's six springs broken on the 64-bit targets, which relax a regular lattice's nodes away
/// from its edges by fixed offsets (none on the others, whose flash holds the general case
/// alone).
const SYSTEMS: usize = if cfg!(target_pointer_width = "64") { 64 } else { 0 };

/// The least budget for which [`Mud::quasi_static_step`] tabulates the [`interior_system`]s
/// (filling the table is a few thousand instructions; a unit of work about a hundred).
const TABULATE_FROM: u64 = 1 << 12;

/// A regular lattice's node's 2×2 system away from the edges ([`Mud::relax`]'s, in its order)
/// when the springs in `broken` (bit k: the star's kth, of the first `n`) are broken: the
/// matrix h·I + Σ k e eᵀ over the intact springs (`laws`: [`interior_laws`]), its determinant
/// ([`solve_node`]'s) and its diagonal's mean ([`Mud::settle`]'s).
fn interior_system<S: Scalar>(laws: &[[S; 3]], n: usize, shear: S, broken: usize) -> [S; 5] {
    let (mut a00, mut a01, mut a11) = (shear, S::ZERO, shear);
    for (k, &[ex, ey, kk]) in laws.iter().enumerate().take(n) {
        if broken & 1 << k == 0 {
            a00 += kk * ex * ex;
            a01 += kk * ex * ey;
            a11 += kk * ey * ey;
        }
    }
    [a00, a01, a11, determinant([a00, a01, a11]), diagonal_mean([a00, a01, a11])]
}

/// The spring laws [`Interior`] holds: a regular lattice's six on the 64-bit targets (none on
/// the others, which relax every node by the general case).
const LAWS: usize = if cfg!(target_pointer_width = "64") { 6 } else { 0 };

/// What [`Mud::quasi_static_step`] hands the relaxations of a regular lattice's nodes away
/// from its edges, for the length of the call.
struct Interior<'t, S> {
    /// The spring laws ([`interior_laws`]).
    laws: [[S; 3]; LAWS],
    /// The [`interior_system`]s by set of broken springs, if tabulated (if not, they are
    /// summed node by node).
    systems: Option<&'t [[S; 5]; SYSTEMS]>,
}

/// [`interior_system`] where no table holds it (a small budget), out of the relaxation's way.
#[inline(never)]
fn untabulated_system<S: Scalar>(laws: &[[S; 3]], n: usize, shear: S, broken: usize) -> [S; 5] {
    interior_system(laws, n, shear, broken)
}

/// The node is in the queue.
const QUEUED: u32 = 1;
/// The node is in the touched list.
const TOUCHED: u32 = 2;
/// The first of a regular lattice's node's flags that mark its springs broken, one bit per
/// spring in [`super::Lattice::star_in_row`]'s order (64-bit targets: what the relaxation away
/// from the edges reads instead of the springs' break times).
const BROKEN_SHIFT: u32 = 2;
/// A regular lattice's node away from its edges ([`super::Lattice::interior_row`]; 64-bit
/// targets), whose springs the relaxation finds by fixed offsets.
const INTERIOR: u32 = 1 << (BROKEN_SHIFT + 6);
/// The flag that says an [`INTERIOR`] node's row is odd.
const ODD_ROW_SHIFT: u32 = BROKEN_SHIFT + 7;

/// E-folds of the slowest convergence of the relaxation that the relaxations after a break may
/// take ([`relax_bound`]).
pub(super) const RELAX_EFOLDS: f64 = 64.0;

/// The most node relaxations that follow a break (or the setup) before the quasi-static run
/// takes the lattice as relaxed and drops the rest of its queue: [`RELAX_EFOLDS`] e-folds of
/// the slowest sweep over the nodes, ⌈64 / ln(1 + h/Σk)⌉ sweeps of every node. A node's update
/// shrinks the error of the mode in which every node moves together (the slowest: it stretches
/// no surface spring, so only the shear spring h restores it) by the factor Σk/(h + Σk) at
/// least, Σk over the node's surface springs (the worst node's on the irregular lattice). In
/// exact arithmetic a sweep-by-sweep relaxation is then e⁶⁴-fold closer to equilibrium. At the
/// paper's values it is 1,312 sweeps (hexagonal): 5.4 million relaxations on a 64² plate, where
/// a break took at most about 1,000 (periodic, seeds 1–4) and the setup of an open plate's
/// boundary layer about 11,000. It bounds a relaxation whose arithmetic cannot settle below
/// its tolerance (node updates that round back and forth by a few units of the backend): a
/// run relaxes at most this many nodes per break and after the setup. Computed in `f32`
/// constants and `f64`, so that it does not depend on the backend; saturates at `u64::MAX`.
pub(super) fn relax_bound(lattice: &super::Lattice, material: &super::Material<f32>) -> u64 {
    let springs: f32 = material.stiffness[..lattice.directions()].iter().map(|&k| 2.0 * k).sum();
    relax_bound_of(f64::from(material.shear) / f64::from(springs), lattice.node_count())
}

/// h/Σk of the irregular lattice's node `node` ([`relax_bound`] takes the smallest, which the
/// run's setup folds over the nodes).
pub(super) fn shear_over_springs(mesh: &super::irregular::Mesh, node: usize, material: &super::Material<f32>) -> f64 {
    let mut springs = 0.0f64;
    mesh.for_each_spring_at(node, |spring, _, _| springs += f64::from(mesh.stiffness(spring)));
    let shear = f64::from(mesh.area(node) * material.shear_per_area);
    shear / springs
}

/// [`relax_bound`] of a lattice of `nodes` nodes whose slowest node has h/Σk = `ratio`.
pub(super) fn relax_bound_of(ratio: f64, nodes: usize) -> u64 {
    let sweeps = libm::ceil(RELAX_EFOLDS / libm::log1p(ratio));
    let relaxations = sweeps * nodes as f64;
    // A NaN or infinite count (no shear, or no spring) gives the largest bound.
    if relaxations.is_nan() { u64::MAX } else { (relaxations as u64).max(1) }
}

/// How far a node's u may move in a relaxation without its neighbours being relaxed again, at
/// misfit `misfit`: the paper's δx over the element size W, per unit misfit (displacements are
/// s·u, so u needs resolving to δx/(W·s)), with s no smaller than [`TOLERANCE_MISFIT_FLOOR`]
/// (so early relaxations are not needlessly coarse), and no less than [`SOLVE_ROUNDING`] units
/// of the backend's resolution.
pub(super) fn relax_tolerance<S: Scalar>(params: &super::MudParams, misfit: S) -> S {
    let scale = misfit.max(S::from_f32(TOLERANCE_MISFIT_FLOOR));
    let tolerance = S::from_f32(params.displacement_tolerance / params.element_size) / scale;
    tolerance.max(S::RESOLUTION * S::from_i32(SOLVE_ROUNDING))
}

impl<'a, S: Scalar> Relaxation<'a, S> {
    /// The arrays, carved from `scalars` and `words`; the run's setup writes them
    /// ([`Relaxation::clear_nodes`], [`Mud::set_break_misfits`], the tree and the queue) and,
    /// on the irregular lattice, the relax bound.
    pub(super) fn new(
        scalars: &mut &'a mut [S],
        words: &mut &'a mut [u32],
        (nodes, springs): (usize, usize),
        relax_bound: u64,
        tolerance: S,
        (laws, reciprocal): ([[S; 3]; 6], u64),
    ) -> Self {
        let leaves = springs.div_ceil(BLOCK).next_power_of_two();
        let break_misfit = take(scalars, springs);
        let tree = take(words, 2 * leaves);
        let queue = take(words, nodes);
        let flags = take(words, nodes);
        let touched = take(words, nodes);
        Relaxation {
            break_misfit,
            tree,
            leaves,
            queue,
            flags,
            head: 0,
            len: 0,
            touched,
            touched_len: 0,
            refreshed: 0,
            relaxed: 0,
            relax_bound,
            tolerance,
            laws,
            reciprocal,
        }
    }

    /// Nodes `from..end` of `lattice`: neither queued nor touched, no spring broken, and
    /// (64-bit targets) marked [`INTERIOR`] and [`ODD_ROW_SHIFT`] where they are.
    pub(super) fn clear_nodes(&mut self, from: usize, end: usize, lattice: &super::Lattice) {
        let reciprocal = self.reciprocal;
        for (node, flags) in self.flags[from..end].iter_mut().enumerate().map(|(k, f)| (from + k, f)) {
            *flags = match lattice.interior_row(node, reciprocal) {
                Some(row) if cfg!(target_pointer_width = "64") => INTERIOR | (row as u32 & 1) << ODD_ROW_SHIFT,
                _ => 0,
            };
        }
    }

    /// The tree's slots: 2·leaves.
    pub(super) fn tree_len(&self) -> usize {
        self.tree.len()
    }

    /// Tree slots `from..end` empty.
    pub(super) fn clear_tree(&mut self, from: usize, end: usize) {
        self.tree[from..end].fill(NONE);
    }

    /// The leaves of blocks `from..end`: each block's winner.
    pub(super) fn tree_leaves(&mut self, from: usize, end: usize) {
        for b in from..end {
            self.tree[self.leaves + b] = self.block_winner(b);
        }
    }

    /// Inner slots, the `from..end`th from the last leaf up (slot leaves − 1 first, slot 1
    /// last): each its children's winner.
    pub(super) fn tree_inner(&mut self, from: usize, end: usize) {
        for k in from..end {
            let slot = self.leaves - 1 - k;
            self.tree[slot] = self.winner(self.tree[2 * slot], self.tree[2 * slot + 1]);
        }
    }

    /// Nodes `from..end` queued for relaxing.
    pub(super) fn queue_nodes(&mut self, from: usize, end: usize) {
        for node in from..end {
            self.push(node);
        }
    }

    /// The irregular lattice's relax bound, once the setup has seen every node.
    pub(super) fn set_relax_bound(&mut self, relax_bound: u64) {
        self.relax_bound = relax_bound;
    }

    /// The better of two tree entries.
    fn winner(&self, a: u32, b: u32) -> u32 {
        match (a, b) {
            (NONE, _) => b,
            (_, NONE) => a,
            _ if self.break_misfit[b as usize] < self.break_misfit[a as usize] => b,
            _ => a, // ties go to the lower index, which is always `a`
        }
    }

    /// The winner of block `b` (the lowest index among equal misfits).
    fn block_winner(&self, b: usize) -> u32 {
        let end = (BLOCK * (b + 1)).min(self.break_misfit.len());
        let mut best = BLOCK * b;
        for s in BLOCK * b + 1..end {
            if self.break_misfit[s] < self.break_misfit[best] {
                best = s;
            }
        }
        best as u32
    }

    /// Re-decides spring `s`'s leaf, and the path from it to the root, after its value
    /// changed (`fell`: to a smaller one). Stops early where a slot keeps a winner other than
    /// `s` and the leaf's former winner: nothing above it can change.
    fn update(&mut self, s: usize, fell: bool) {
        let leaf = self.leaves + s / BLOCK;
        let held = self.tree[leaf];
        let winner = if held == s as u32 {
            // A block's winner whose value falls stays its winner (it was the smallest, and the
            // lowest index among equals); otherwise the block is looked through again.
            if fell { s as u32 } else { self.block_winner(s / BLOCK) }
        } else if self.break_misfit[s] < self.break_misfit[held as usize]
            || self.break_misfit[s] == self.break_misfit[held as usize] && (s as u32) < held
        {
            s as u32
        } else {
            return; // the leaf keeps its winner, whose value did not change
        };
        self.tree[leaf] = winner;
        let mut slot = leaf / 2;
        while slot >= 1 {
            let before = self.tree[slot];
            let after = self.winner(self.tree[2 * slot], self.tree[2 * slot + 1]);
            if after == before && after != s as u32 && after != held {
                return;
            }
            self.tree[slot] = after;
            slot /= 2;
        }
    }

    fn push(&mut self, node: usize) {
        if cfg!(target_pointer_width = "64") {
            queue_node(self.flags, self.queue, self.head, &mut self.len, node);
        } else if self.flags[node] & QUEUED == 0 {
            self.flags[node] |= QUEUED;
            let tail = ring_slot(self.head + self.len, self.queue.len());
            self.queue[tail] = node as u32;
            self.len += 1;
        }
    }

    /// [`Relaxation::push`] of `others[k]` for each bit k of `moves`, lowest first.
    #[inline(always)]
    fn push_each<const N: usize>(&mut self, others: &[usize; N], mut moves: u32) {
        let mut len = self.len;
        while moves != 0 {
            queue_node(self.flags, self.queue, self.head, &mut len, others[moves.trailing_zeros() as usize % N]);
            moves &= moves - 1;
        }
        self.len = len;
    }

    /// The next queued node, marked touched, and its flags then.
    #[inline(always)]
    fn pop(&mut self) -> Option<(usize, u32)> {
        if self.len == 0 {
            return None;
        }
        let node = self.queue[self.head] as usize;
        self.head += 1;
        if self.head == self.queue.len() {
            self.head = 0;
        }
        self.len -= 1;
        let flags = self.flags[node] & !QUEUED;
        if cfg!(target_pointer_width = "64") {
            // Without a branch on whether the node is touched, as `push` queues.
            if self.touched_len < self.touched.len() {
                self.touched[self.touched_len] = node as u32;
            }
            self.touched_len += (flags & TOUCHED ^ TOUCHED) as usize / TOUCHED as usize;
        } else if flags & TOUCHED == 0 {
            self.touched[self.touched_len] = node as u32;
            self.touched_len += 1;
        }
        self.flags[node] = flags | TOUCHED;
        Some((node, flags | TOUCHED))
    }
}

/// Queues `node` ([`Relaxation::push`]) in the ring `queue` of `len` nodes from `head`, unless
/// its `flags` say it is queued, without a branch on whether it is: the tail slot is free
/// (unless every node is queued), so writing the node there does no harm if it is.
#[inline(always)]
fn queue_node(flags: &mut [u32], queue: &mut [u32], head: usize, len: &mut usize, node: usize) {
    let node_flags = flags[node];
    if *len < queue.len() {
        queue[ring_slot(head + *len, queue.len())] = node as u32;
    }
    flags[node] = node_flags | QUEUED;
    *len += (node_flags & QUEUED ^ QUEUED) as usize;
}

/// Ring position `at` (below twice the `capacity`) wrapped without a division.
#[inline(always)]
fn ring_slot(at: usize, capacity: usize) -> usize {
    if at >= capacity { at - capacity } else { at }
}

/// A node's u from its 2×2 equilibrium (the module docs' equation, Eq. 2 linearised):
/// (h·I + Σ k e eᵀ)·u = Σ k (l0 + e·u_j) e, the symmetric matrix [a00 a01; a01 a11] and the
/// right-hand side b solved by Cramer's rule.
#[inline(always)]
fn solve_node<S: Scalar>(a: [S; 3], b: [S; 2]) -> (S, S) {
    solve_with(a, determinant(a), b)
}

/// [`solve_node`] given the matrix's determinant `det` ([`determinant`]).
#[inline(always)]
fn solve_with<S: Scalar>([a00, a01, a11]: [S; 3], det: S, [b0, b1]: [S; 2]) -> (S, S) {
    ((a11 * b0 - a01 * b1) / det, (a00 * b1 - a01 * b0) / det)
}

/// The determinant of the symmetric matrix [a00 a01; a01 a11].
#[inline(always)]
fn determinant<S: Scalar>([a00, a01, a11]: [S; 3]) -> S {
    a00 * a11 - a01 * a01
}

/// The mean of the diagonal of [a00 a01; a01 a11].
#[inline(always)]
fn diagonal_mean<S: Scalar>([a00, _, a11]: [S; 3]) -> S {
    (a00 + a11) * S::from_f32(0.5)
}

impl<'a, S: Scalar> Mud<'a, S> {
    /// Moves `node` to its equilibrium, the 2×2 system `a`, `b` ([`solve_node`]): its new u,
    /// how far it moved (Δu), and the mean of the system's diagonal (a neighbour moves by
    /// about k·e·Δu over its own diagonal, about this node's).
    #[inline(always)]
    fn settle(&mut self, node: usize, a: [S; 3], b: [S; 2]) -> ([S; 2], [S; 2], S) {
        let (old_x, old_y) = (self.ux[node], self.uy[node]);
        let (x, y) = solve_node(a, b);
        (self.ux[node], self.uy[node]) = (x, y);
        ([x, y], [x - old_x, y - old_y], diagonal_mean(a))
    }

    /// The misfit at which `spring` breaks given the current u; S::MAX if never.
    fn break_misfit_of(&self, spring: usize) -> S {
        let j = self.other[spring];
        if j == ABSENT || self.break_time[spring] != INTACT {
            return S::MAX;
        }
        self.break_misfit_between(spring, self.origin(spring), j as usize, self.lattice.spring_vector(spring))
    }

    /// [`Mud::break_misfit_of`] of intact `spring`, which leaves node `i` for node `j` in
    /// direction `e` (what the caller knows already: no division finds them again).
    #[inline(always)]
    fn break_misfit_between(&self, spring: usize, i: usize, j: usize, e: [f32; 2]) -> S {
        let e = e.map(S::from_f32);
        let mut opening = e[0] * (self.ux[j] - self.ux[i]) + e[1] * (self.uy[j] - self.uy[i]);
        if self.lattice.mesh().is_some() {
            // The strain: e·(u_j − u_i)/l0 (l0 = 1 on the regular lattices).
            opening /= S::from_f32(self.lattice.rest_length(spring));
        }
        let kappa = self.break_stretch[spring];
        let denominator = match self.params.drive {
            Drive::Shrink => opening + kappa,
            Drive::Growth => opening + S::ONE,
        };
        let limit = self.misfit_limit();
        if denominator <= S::ZERO {
            return S::MAX;
        }
        let s = (kappa - S::ONE) / denominator;
        if s > limit { S::MAX } else { s.max(S::ZERO) }
    }

    fn relaxation<'s>(&'s mut self) -> &'s mut Relaxation<'a, S> {
        match &mut self.solver {
            SolverState::QuasiStatic(r) => r,
            SolverState::Explicit(_) => unreachable!("quasi-static step on another solver"),
        }
    }

    /// Springs `from..end`: the misfit at which each breaks (the setup's, at u = 0; the tree
    /// is built from them, and every node of an open or irregular lattice queued: its
    /// boundary layer, or its differing springs, need relaxing).
    pub(super) fn set_break_misfits(&mut self, from: usize, end: usize) {
        for s in from..end {
            let value = self.break_misfit_of(s);
            self.relaxation().break_misfit[s] = value;
        }
    }

    /// Solves node `node`'s 2×2 equilibrium for u, and queues its neighbours
    /// if u moved by more than the tolerance ([`relax_tolerance`]). Returns the springs visited.
    /// `flags` are the node's ([`Relaxation::flags`]); `interior` the regular lattice's spring
    /// laws and, if tabulated, [`interior_system`]s (if not, they are summed here).
    #[cfg_attr(target_pointer_width = "64", inline(always))]
    fn relax(&mut self, node: usize, flags: u32, interior: &Interior<'_, S>) -> u64 {
        // Away from a regular lattice's edges, its springs by fixed offsets (64-bit targets:
        // the Cortex-M3's flash holds the general case alone, which computes the same).
        if cfg!(target_pointer_width = "64") && flags & INTERIOR != 0 {
            let odd = (flags >> ODD_ROW_SHIFT & 1) as usize;
            let star = match self.lattice.topology {
                super::Topology::Square => {
                    self.lattice.star_in_row::<4>(node, odd).map(|s| self.relax_interior(node, flags, s, interior))
                }
                super::Topology::Hexagonal => {
                    self.lattice.star_in_row::<6>(node, odd).map(|s| self.relax_interior(node, flags, s, interior))
                }
                super::Topology::Irregular => None,
            };
            if let Some(visited) = star {
                return visited;
            }
        }
        match self.lattice.mesh().copied() {
            // At most six springs on the regular lattices: a smaller list to set up (and no
            // mesh to look up a spring's law in).
            None => self.relax_with::<6>(node, None),
            mesh => self.relax_with::<{ super::irregular::MAX_DEGREE }>(node, mesh),
        }
    }

    /// [`Mud::relax`] of a regular lattice's node away from its edges, whose `N` springs and
    /// the nodes they reach are `star` ([`super::Lattice::star_in_row`]): the same
    /// arithmetic in the same order, with the springs' laws from [`interior_laws`] and the
    /// broken ones from the node's `flags`.
    #[inline(always)]
    fn relax_interior<const N: usize>(
        &mut self,
        node: usize,
        flags: u32,
        star: ([usize; N], [usize; N]),
        interior: &Interior<'_, S>,
    ) -> u64 {
        // Most nodes have all their springs: their updates test none.
        match flags >> BROKEN_SHIFT & 63 {
            0 => self.relax_star(node, 0, star, interior),
            broken => self.relax_star(node, broken, star, interior),
        }
        N as u64
    }

    /// [`Mud::relax_interior`] of a node whose broken springs are `broken` (bit k: the star's
    /// kth).
    #[inline(always)]
    fn relax_star<const N: usize>(
        &mut self,
        node: usize,
        broken: u32,
        (springs, others): ([usize; N], [usize; N]),
        interior: &Interior<'_, S>,
    ) {
        let laws = &interior.laws[..];
        // The matrix, its determinant and diagonal depend on the broken springs alone.
        let set = broken as usize;
        let [a00, a01, a11, det, diagonal] = match interior.systems.and_then(|table| table.get(set)) {
            Some(&system) => system,
            None => untabulated_system(laws, N, self.material.shear, set),
        };
        let (mut b0, mut b1) = (S::ZERO, S::ZERO);
        // (Both arrays cut to one length: one bounds check per node.)
        let len = self.ux.len().min(self.uy.len());
        let (ux, uy) = (&self.ux[..len], &self.uy[..len]);
        let u: [(S, S); N] = core::array::from_fn(|k| (ux[others[k]], uy[others[k]]));
        unrolled!(N, |k| {
            if broken & 1 << k == 0 {
                let [ex, ey, kk] = laws[k];
                let pull = kk * (S::ONE + ex * u[k].0 + ey * u[k].1);
                b0 += pull * ex;
                b1 += pull * ey;
            }
        });
        let (old_x, old_y) = (self.ux[node], self.uy[node]);
        let (x, y) = solve_with([a00, a01, a11], det, [b0, b1]);
        (self.ux[node], self.uy[node]) = (x, y);
        let (dx, dy) = (x - old_x, y - old_y);
        let (misfit, threshold) = (self.misfit, self.relaxation().tolerance * diagonal);
        let shrink = self.params.drive == Drive::Shrink;
        // Which springs break (bit k: the star's kth) and which other nodes move by more than
        // the tolerance, as `Mud::relax` decides them; then its breaks and queueings, in its
        // order.
        let (mut breaks, mut moves) = (0u32, 0u32);
        unrolled!(N, |k| {
            if broken & 1 << k == 0 {
                let [ex, ey, kk] = laws[k];
                let opening = ex * (u[k].0 - x) + ey * (u[k].1 - y);
                let kappa = self.break_stretch[springs[k]];
                let denominator = opening + if shrink { kappa } else { S::ONE };
                let breaking = (denominator > S::ZERO) & (kappa - S::ONE <= misfit * denominator);
                breaks |= u32::from(breaking) << k;
                moves |= u32::from(kk * (ex * dx + ey * dy).abs() > threshold) << k;
            }
        });
        if breaks == 0 {
            self.relaxation().push_each(&others, moves);
        } else {
            for k in 0..N {
                if breaks & 1 << k != 0 {
                    self.break_and_relax(springs[k]);
                } else if moves & 1 << k != 0 {
                    self.relaxation().push(others[k]);
                }
            }
        }
    }

    /// [`Mud::relax`] with room for `DEGREE` springs at the node, on the irregular lattice's
    /// `mesh` if there is one.
    #[inline(always)]
    fn relax_with<const DEGREE: usize>(&mut self, node: usize, mesh: Option<super::irregular::Mesh<'_>>) -> u64 {
        let h = match &mesh {
            Some(m) => S::from_f32(m.area(node) * self.material.shear_per_area),
            None => self.material.shear,
        };
        let (mut a00, mut a01, mut a11) = (h, S::ZERO, h);
        let (mut b0, mut b1) = (S::ZERO, S::ZERO);
        let mut visited = 0u64;
        // The node's intact springs: (spring, other node, e towards the other node, k, the
        // other node's u).
        let mut intact = [(0u32, 0u32, S::ZERO, S::ZERO, S::ZERO, S::ZERO, S::ZERO); DEGREE];
        let mut count = 0;
        self.lattice.for_each_spring_at(node, |spring, other, d, sign| {
            visited += 1;
            if self.break_time[spring] != INTACT {
                return;
            }
            // The spring's law: e (towards the other node), k and l0 (Eq. 2, linearised).
            let (v, k, rest) = match &mesh {
                Some(m) => (m.direction(spring), S::from_f32(m.stiffness(spring)), S::from_f32(m.rest_length(spring))),
                None => (self.lattice.direction_vector(d), self.material.stiffness[d], S::ONE),
            };
            let (ex, ey) = (S::from_f32(v[0] * sign), S::from_f32(v[1] * sign));
            a00 += k * ex * ex;
            a01 += k * ex * ey;
            a11 += k * ey * ey;
            let (ux, uy) = (self.ux[other], self.uy[other]);
            let pull = k * (rest + ex * ux + ey * uy);
            b0 += pull * ex;
            b1 += pull * ey;
            intact[count] = (spring as u32, other as u32, ex, ey, k, ux, uy);
            count += 1;
        });
        let ([x, y], [dx, dy], diagonal) = self.settle(node, [a00, a01, a11], [b0, b1]);
        let tolerance = self.relaxation().tolerance;
        let misfit = self.misfit;
        for &(spring, other, ex, ey, k, ux, uy) in &intact[..count] {
            let (spring, other) = (spring as usize, other as usize);
            // A spring that is past its limit on the way to equilibrium breaks now:
            // s_break ≤ s, i.e. κ − 1 ≤ s·(e·(u_j − u_i)/l0 + a + κ·b), without the division.
            // (Breaking moves no node: the other node's u is the one read above.)
            let mut opening = ex * (ux - x) + ey * (uy - y);
            if let Some(m) = &mesh {
                opening /= S::from_f32(m.rest_length(spring));
            }
            let kappa = self.break_stretch[spring];
            let denominator = match self.params.drive {
                Drive::Shrink => opening + kappa,
                Drive::Growth => opening + S::ONE,
            };
            if denominator > S::ZERO && kappa - S::ONE <= misfit * denominator {
                self.break_and_relax(spring);
            } else if k * (ex * dx + ey * dy).abs() > tolerance * diagonal {
                self.relaxation().push(other);
            }
        }
        visited
    }

    /// Brings the break misfits of the springs at the touched nodes up to date in the tree,
    /// node by node in the order they were relaxed, then clears the nodes' touched marks,
    /// until the work reaches `budget` (the refresh goes on where it stopped at the next
    /// call). Returns the work: springs visited, and one per mark cleared.
    fn refresh_touched(&mut self, budget: u64) -> u64 {
        let lattice = self.lattice;
        let count = self.relaxation().touched_len;
        let mut t = self.relaxation().refreshed;
        let mut work = 0u64;
        while t < count && work < budget {
            let node = self.relaxation().touched[t] as usize;
            // Away from a regular lattice's edges, its springs by fixed offsets (as in
            // `Mud::relax`).
            let flags = if cfg!(target_pointer_width = "64") { self.relaxation().flags[node] } else { 0 };
            if flags & INTERIOR != 0 {
                let odd = (flags >> ODD_ROW_SHIFT & 1) as usize;
                let done = match lattice.topology {
                    super::Topology::Square => {
                        lattice.star_in_row::<4>(node, odd).map(|s| self.refresh_interior(node, s))
                    }
                    super::Topology::Hexagonal => {
                        lattice.star_in_row::<6>(node, odd).map(|s| self.refresh_interior(node, s))
                    }
                    super::Topology::Irregular => None,
                };
                if let Some(done) = done {
                    work += done;
                    t += 1;
                    continue;
                }
            }
            lattice.for_each_spring_at(node, |spring, other, d, sign| {
                work += 1;
                // A spring between two touched nodes is brought up to date once, from its
                // origin (the tree's result does not depend on the order of updates).
                let shared = sign < 0.0 && self.relaxation().flags[other] & TOUCHED != 0;
                if shared || self.break_time[spring] != INTACT {
                    return;
                }
                // The spring leaves `node` (sign +1) or reaches it.
                let (i, j) = if sign > 0.0 { (node, other) } else { (other, node) };
                let e = match lattice.mesh() {
                    Some(m) => m.direction(spring),
                    None => lattice.direction_vector(d),
                };
                let value = self.break_misfit_between(spring, i, j, e);
                let r = self.relaxation();
                let before = r.break_misfit[spring];
                if before != value {
                    r.break_misfit[spring] = value;
                    r.update(spring, value < before);
                }
            });
            t += 1;
        }
        let r = self.relaxation();
        while t >= count && t < 2 * count && work < budget {
            let node = r.touched[t - count] as usize;
            r.flags[node] &= !TOUCHED;
            work += 1;
            t += 1;
        }
        if t == 2 * count {
            (r.touched_len, r.refreshed) = (0, 0);
        } else {
            r.refreshed = t;
        }
        work
    }

    /// [`Mud::refresh_touched`]'s update of one node away from a regular lattice's edges,
    /// whose springs and the nodes they reach are `star` ([`super::Lattice::star_in_row`]).
    /// Returns the springs visited.
    #[inline(always)]
    fn refresh_interior<const N: usize>(&mut self, node: usize, (springs, others): ([usize; N], [usize; N])) -> u64 {
        // The star's first half leaves the node, in the lattice's directions.
        let dirs = N / 2;
        let broken = self.relaxation().flags[node] >> BROKEN_SHIFT;
        unrolled!(N, |k| {
            let (spring, other, outgoing) = (springs[k], others[k], k < dirs);
            // A spring between two touched nodes is brought up to date once, from its origin.
            if broken & 1 << k == 0 && (outgoing || self.relaxation().flags[other] & TOUCHED == 0) {
                let (i, j) = if outgoing { (node, other) } else { (other, node) };
                let value = self.break_misfit_between(spring, i, j, self.lattice.direction_vector(k % dirs));
                let r = self.relaxation();
                let before = r.break_misfit[spring];
                if before != value {
                    r.break_misfit[spring] = value;
                    r.update(spring, value < before);
                }
            }
        });
        N as u64
    }

    /// Pieces of quasi-static work ([`Mud::quasi_static_piece`]) until their work reaches
    /// `max(budget, 1)` or the physics ends: what as many calls of one piece would do, without
    /// the way back through [`Mud::step`] between them. Returns the work done: at most
    /// `max(budget, 1)` − 1 plus the springs at one node.
    pub(super) fn quasi_static_step(&mut self, budget: u64) -> u64 {
        // A regular lattice's nodes away from its edges: their 2×2 systems by set of broken
        // springs, for a budget that repays filling them in (the same values, in a table on
        // the stack for this call).
        let mut table = [[S::ZERO; 5]; SYSTEMS];
        let regular = !matches!(self.lattice.topology, super::Topology::Irregular);
        let tabulated = SYSTEMS > 0 && budget >= TABULATE_FROM && regular;
        let laws: [[S; 3]; LAWS] = core::array::from_fn(|k| self.relaxation().laws[k]);
        if tabulated {
            let springs = 2 * self.lattice.directions();
            for (set, system) in table.iter_mut().enumerate() {
                *system = interior_system(&laws, springs, self.material.shear, set);
            }
        }
        let interior = Interior { laws, systems: tabulated.then_some(&table) };
        let mut work = self.quasi_static_piece(budget, &interior);
        while work < budget && !self.finished {
            work += self.quasi_static_piece(budget - work, &interior);
        }
        work
    }

    /// One piece of quasi-static work: relax queued nodes (their springs), each dropped from
    /// the queue instead once [`relax_bound`] nodes have been relaxed since the last break (one
    /// unit), until the queue is empty or the work reaches `budget` (at least one node); or
    /// refresh the touched nodes' springs until the work reaches `budget` (at least one
    /// node's); or break the next spring (jumping the misfit to it; one unit). Returns the work
    /// done (springs visited): at most `max(budget, 1)` − 1 plus the springs at one node.
    fn quasi_static_piece(&mut self, budget: u64, interior: &Interior<'_, S>) -> u64 {
        if let Some(first) = self.relaxation().pop() {
            let ((mut node, mut flags), mut work) = (first, 0u64);
            loop {
                let r = self.relaxation();
                if r.relaxed >= r.relax_bound {
                    work += 1;
                } else {
                    r.relaxed += 1;
                    work += self.relax(node, flags, interior);
                }
                if work >= budget {
                    return work;
                }
                match self.relaxation().pop() {
                    Some(next) => (node, flags) = next,
                    None => return work,
                }
            }
        }
        if self.relaxation().touched_len > 0 {
            let work = self.refresh_touched(budget.max(1));
            if work > 0 {
                return work;
            }
        }
        let r = self.relaxation();
        let next = r.tree[1];
        let at = if next == NONE { S::MAX } else { r.break_misfit[next as usize] };
        if at > self.misfit {
            // The next break lies past the end (S::MAX: nothing left can break): the run ends
            // there, as the explicit solver's long steps do.
            let end = self.end_misfit();
            if at > end {
                self.misfit = self.misfit.max(end);
                self.finished = true;
                return 1;
            }
            self.misfit = at;
            self.relaxation().tolerance = relax_tolerance(&self.params, at);
        }
        self.break_and_relax(next as usize);
        1
    }

    /// Breaks `spring`, retires it from the tree, and queues its two nodes for relaxation.
    fn break_and_relax(&mut self, spring: usize) {
        self.break_spring(spring);
        let (a, b) = (self.origin(spring), self.other[spring] as usize);
        if cfg!(target_pointer_width = "64") && self.lattice.mesh().is_none() {
            // The spring leaves `a` in its direction d (the star's dth spring) and reaches `b`
            // in it (the star's (directions + d)th).
            let (d, dirs) = (self.lattice.spring_origin(spring).1, self.lattice.directions());
            let r = self.relaxation();
            r.flags[a] |= 1 << (BROKEN_SHIFT as usize + d);
            r.flags[b] |= 1 << (BROKEN_SHIFT as usize + dirs + d);
        }
        let r = self.relaxation();
        r.relaxed = 0;
        r.break_misfit[spring] = S::MAX;
        r.update(spring, false);
        r.push(a);
        r.push(b);
    }
}
