//! The paper's loop exactly (Hirota et al. Fig. 2): forces (Eq. 2), stability test (Eq. 3),
//! the exact motion of a damped mass under a constant force over one short step (Eq. 4),
//! breaking (Eq. 5), and a long step of shrinking (Eq. 1) whenever the lattice is stable.
//!
//! One short step visits every spring once: it tests the spring for breaking against the
//! positions of the previous move (Eq. 5, "go to 2"), then adds its force (Eq. 2).
//!
//! The pass runs direction by direction and row by row: a row's springs in one direction
//! join two contiguous runs of nodes, so the inner loops have no branches and no indirection
//! and vectorise. A row goes through short loops, chunk by chunk (difference vectors, 1/l,
//! forces) rather than one long loop: a spring's chain of dependent operations is long, and
//! in one loop the processor runs out of registers before it overlaps enough springs. The
//! springs past the run's last whole vector share one more vector with the spring that wraps
//! around the row's end. Each intact spring keeps its squared break length (κ·l0)², set once
//! per long step, so the break test needs neither κ nor a square root.
//!
//! The sums keep the paper's order: every node starts from its shear spring, then takes the
//! springs of direction 0 (its own, then its left neighbour's, then the wrapping one at the
//! row's ends), computed and summed in one loop; then each direction that joins a row to the
//! next adds, row by row, each spring's force to both its nodes as it is found (a node takes
//! one term per row processed, so the order of its terms is the rows' order). A spring past
//! its break stretch adds +0 (or, wrapping, nothing), as the paper's loop skips it; the breaks
//! are recorded afterwards in a scalar pass over the row. So every value is the same bit for
//! bit on every build, and the same as with one pass per direction and a row of scratch.
//!
//! A long step follows a short step whose forces pass Eq. 3, and also one that changed no
//! displacement and no velocity and broke nothing: every short step after it would repeat it
//! exactly, so a backend that cannot move a node by the force left (Q16.16: F·τ/c below half a
//! unit) would otherwise never pass Eq. 3. And at most [`settle_bound`] short steps follow a
//! long step or a break (a lattice whose rounding keeps it moving without passing Eq. 3), so a
//! run takes at most that many short steps per long step and per spring.
//!
//! A short step can stop between rows and go on at the next call of [`Mud::step`] (frame
//! budgets): its [`Phase`] is kept in [`Dynamics`] and each phase runs in the same order
//! whatever the cuts, so a budgeted run is the same bit for bit as one call.

use super::irregular::Mesh;
use super::lattice::Lattice;
use super::material::Material;
use super::{Boundary, Mud, SolverState, Topology, take};
use crate::scalar::Scalar;

/// Velocities, forces, spring limits and the constants of the damped step.
pub(super) struct Dynamics<'a, S> {
    vx: &'a mut [S],
    vy: &'a mut [S],
    fx: &'a mut [S],
    fy: &'a mut [S],
    /// Per spring: (κ·l0)², the squared length past which it breaks, while intact; −1 once
    /// broken or absent.
    limit: &'a mut [S],
    /// The rest length `limit` was computed for (it changes with each long step).
    limit_rest: Option<S>,
    /// exp(−c·τ/m) − 1.
    decay: S,
    /// −(m/c)·(exp(−c·τ/m) − 1).
    drift: S,
    /// 1/c.
    inverse_damping: S,
    /// τ/c.
    step_over_damping: S,
    /// The irregular lattice's nodes each have their own mass, damping and force tolerance:
    /// per node, the four constants above in that order, then δF = k_min·δx.
    node_constants: &'a mut [S],
    /// Where the short step under way stands: its next piece.
    phase: Phase,
    /// Springs the short step under way has broken so far (counted in `Mud::broken` as they
    /// break; the crack density is tested once the short step is done).
    newly_broken: u32,
    /// Whether the short step under way has changed a displacement or a velocity (Eq. 4).
    moved: bool,
    /// Short steps since the last long step or break.
    unsettled: u64,
    /// The most short steps that follow a long step or a break before the lattice is taken
    /// as settled ([`settle_bound`]).
    settle_bound: u64,
}

/// Where a short step stands between calls of [`Mud::step`]: it is done phase by phase, and
/// each phase item by item in the paper's order, so stopping between items changes nothing.
/// Nothing a phase reads is changed between its pieces: the displacements change only in
/// [`Phase::Move`], the misfit, the rest and deep factors and the time only after the short
/// step, and the limits only by the breaks of the rows, in order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Phase {
    /// The short step has not begun.
    Start,
    /// Setting the intact springs' limits (κ·l0)² for the long step's rest length, from
    /// this spring on (once per long step).
    Limits(usize),
    /// Forces (Eq. 2) and breaks (Eq. 5) of the regular lattices, from row `row` of direction
    /// `k` on.
    Rows { k: usize, row: usize },
    /// The irregular lattice's shear forces, from this node on.
    Shear(usize),
    /// The irregular lattice's springs, from this one on.
    Springs(usize),
    /// The quick half of the stability test (Eq. 3) of the regular lattices, from this node on.
    Reaches(usize),
    /// The exact stability test (Eq. 3), from this node on.
    Below(usize),
    /// The damped move (Eq. 4), from this node on.
    Move(usize),
}

/// Constants per node of the irregular lattice's explicit run.
pub(super) const NODE_CONSTANTS: usize = 5;

/// Whether the damped step (Eq. 4) is stable for a node of mass `m` and damping `c` under a
/// stiffness of at most `lambda`, for a short step `tau` (all in lattice units, as f64).
///
/// Under a force F = −λ·u, Eq. 4 maps (u, v) to (u', v') by [[1 − λa, b], [−(1 − e)λ/c, e]],
/// with e = exp(−cτ/m), a = τ/c − (m/c²)(1 − e) and b = (m/c)(1 − e). With x = cτ/m and
/// μ = λ·m/c², the determinant is e + μ(1 − (1 + x)e) ≥ e > 0 and 1 − trace + det =
/// λ(1 − e)τ/c > 0, so both eigenvalues lie inside the unit circle (Jury's conditions) when
/// μ·(x(1 + e) − 2(1 − e)) < 2(1 + e) and μ·(1 − (1 + x)e) < 1 − e. Both left sides grow with
/// λ, so an upper bound on λ gives a sufficient test.
pub(super) fn stable(m: f64, c: f64, lambda: f64, tau: f64) -> bool {
    let x = c * tau / m;
    let e = libm::exp(-x);
    let mu = lambda * m / (c * c);
    mu * (x * (1.0 + e) - 2.0 * (1.0 - e)) < 2.0 * (1.0 + e) && mu * (1.0 - (1.0 + x) * e) < 1.0 - e
}

/// Whether the explicit run of a regular `lattice` with `material` (computed in `f32`
/// whatever the backend, so that every backend accepts the same parameters) passes [`stable`]
/// with Gershgorin's bound on the stiffness a node sees: its shear spring h plus twice its
/// surface springs (two per direction). The bound is sufficient, not tight: the stiffest mode
/// is about h + 4k (square) or h + 6k (hexagonal) against the bound's h + 8k and h + 12k, so
/// steps up to about twice the accepted ones may still converge. The irregular lattice's
/// nodes each have their own mass and damping and are tested one by one as the run's setup
/// builds them ([`NodeConstants::is_stable`]).
pub(super) fn stable_lattice(lattice: &Lattice, material: &Material<f32>) -> bool {
    let tau = f64::from(material.short_step);
    let springs: f32 = material.stiffness[..lattice.directions()].iter().map(|&k| 2.0 * k).sum();
    let lambda = f64::from(material.shear) + 2.0 * f64::from(springs);
    stable(f64::from(material.mass), f64::from(material.damping), lambda, tau)
}

/// E-folds of the slowest decay of Eq. 4's map that a short-step streak may take
/// ([`settle_bound`]).
pub(super) const SETTLE_EFOLDS: f64 = 64.0;

/// The modulus of the larger eigenvalue of Eq. 4's map under a stiffness `lambda` (the matrix
/// of [`stable`]): how much one short step shrinks that mode of the motion at least.
fn contraction(m: f64, c: f64, lambda: f64, tau: f64) -> f64 {
    let e = libm::exp(-(c * tau / m));
    let a = tau / c - (m / (c * c)) * (1.0 - e);
    let b = (m / c) * (1.0 - e);
    let (p, q, r) = (1.0 - lambda * a, b, -(1.0 - e) * lambda / c);
    let (trace, det) = (p + e, p * e - q * r);
    let discriminant = trace * trace - 4.0 * det;
    if discriminant >= 0.0 {
        0.5 * (libm::fabs(trace) + crate::scalar::sqrt(discriminant))
    } else {
        crate::scalar::sqrt(det)
    }
}

/// The slowest [`contraction`] over the stiffnesses a node may see, from its shear spring
/// `shear` (the lattice's slowest mode: every node moving together stretches no surface
/// spring) to the stability test's bound `bound`, on 17 stiffnesses spaced evenly in ratio.
fn slowest_contraction(m: f64, c: f64, (shear, bound): (f64, f64), tau: f64) -> f64 {
    (0..=16).fold(0.0f64, |worst, i| {
        let lambda = shear * libm::pow(bound / shear, f64::from(i) / 16.0);
        let rho = contraction(m, c, lambda, tau);
        // NaN (no contraction known) counts as the worst.
        if rho.is_nan() { f64::INFINITY } else { worst.max(rho) }
    })
}

/// The most short steps that follow a long step or a break before the explicit run takes the
/// lattice as settled and takes a long step: [`SETTLE_EFOLDS`] e-folds of the slowest mode of
/// Eq. 4's map, ⌈64 / −ln ρ⌉ with ρ from [`slowest_contraction`] (the worst node's on the
/// irregular lattice: [`NodeConstants::slowest_contraction`], folded over the nodes by the
/// run's setup), at least 1, saturating at `u64::MAX`. In exact arithmetic a force falls
/// e⁶⁴ ≈ 6·10²⁷-fold in that many steps; at the paper's values it is about 14,000 short steps
/// (hexagonal; a break settles within about 1,000), 22 % more on the square lattice. It bounds
/// a run whose arithmetic cannot bring every force below δF (Eq. 3) but keeps moving: a run
/// takes at most this many short steps per long step and per break. Computed in `f32`
/// constants and `f64`, as [`stable_lattice`], so that it does not depend on the backend.
pub(super) fn settle_bound(lattice: &Lattice, material: &Material<f32>) -> u64 {
    let tau = f64::from(material.short_step);
    let springs: f32 = material.stiffness[..lattice.directions()].iter().map(|&k| 2.0 * k).sum();
    let shear = f64::from(material.shear);
    let stiffness = (shear, shear + 2.0 * f64::from(springs));
    settle_bound_of(slowest_contraction(f64::from(material.mass), f64::from(material.damping), stiffness, tau))
}

/// [`settle_bound`] of the slowest contraction `rho`.
pub(super) fn settle_bound_of(rho: f64) -> u64 {
    // ρ < 1 for a lattice that passes the stability test; ρ ≥ 1 (or NaN) bounds nothing.
    if rho < 1.0 { (libm::ceil(SETTLE_EFOLDS / -libm::log(rho)) as u64).max(1) } else { u64::MAX }
}

/// The constants of one node of the irregular lattice (paper §2): m = ρ·B·H and
/// c = 2·√(k_max·m)·α, with B the node's Voronoi area and k_max over its springs and its shear
/// spring h; in lattice units m = B. δF = k_min·δx with k_min over the same springs.
pub(super) struct NodeConstants {
    mass: f32,
    damping: f32,
    shear: f32,
    /// The weakest of its springs and its shear spring, k_min.
    weakest: f32,
    /// Σk over its surface springs.
    springs: f32,
}

impl NodeConstants {
    pub(super) fn of(mesh: &Mesh, node: usize, shear_per_area: f32, alpha: f32) -> Self {
        let mass = mesh.area(node);
        let shear = mass * shear_per_area;
        let (mut k_max, mut weakest, mut springs) = (shear, shear, 0.0f32);
        mesh.for_each_spring_at(node, |spring, _, _| {
            k_max = k_max.max(mesh.stiffness(spring));
            weakest = weakest.min(mesh.stiffness(spring));
            springs += mesh.stiffness(spring);
        });
        NodeConstants { mass, damping: 2.0 * crate::scalar::sqrtf(k_max * mass) * alpha, shear, weakest, springs }
    }

    /// Whether the node alone passes [`stable`] with its Gershgorin bound h + 2·Σk, for the
    /// short step of `reference` (a heuristic on the irregular lattice rather than a proof:
    /// the coupled update does not split into one mode per node).
    pub(super) fn is_stable(&self, reference: &Material<f32>) -> bool {
        let lambda = f64::from(self.shear + 2.0 * self.springs);
        stable(f64::from(self.mass), f64::from(self.damping), lambda, f64::from(reference.short_step))
    }

    /// The node's [`slowest_contraction`] for the short step of `reference`.
    pub(super) fn slowest_contraction(&self, reference: &Material<f32>) -> f64 {
        let stiffness = (f64::from(self.shear), f64::from(self.shear + 2.0 * self.springs));
        let tau = f64::from(reference.short_step);
        slowest_contraction(f64::from(self.mass), f64::from(self.damping), stiffness, tau)
    }
}

/// The `limit` of a broken or absent spring.
fn broken<S: Scalar>() -> S {
    -S::ONE
}

impl<'a, S: Scalar> Dynamics<'a, S> {
    /// The arrays, carved from `scalars` for a lattice of `shape`, and the constants of the
    /// damped step; the run's setup writes the arrays ([`Dynamics::clear_nodes`],
    /// [`Dynamics::set_up_spring`], [`Dynamics::set_node_constants`]) and, on the irregular
    /// lattice, the settle bound.
    pub(super) fn new(scalars: &mut &'a mut [S], shape: &Lattice, material: &Material<S>, settle_bound: u64) -> Self {
        let nodes = shape.node_count();
        let [vx, vy, fx, fy] = [(); 4].map(|_| take(scalars, nodes));
        let limit = take(scalars, shape.spring_count());
        let irregular = shape.topology == Topology::Irregular;
        let node_constants = take(scalars, if irregular { NODE_CONSTANTS * nodes } else { 0 });
        let (m, c, tau) = (material.mass, material.damping, material.short_step);
        let decay = (-(c * tau / m)).exp() - S::ONE;
        Dynamics {
            vx,
            vy,
            fx,
            fy,
            limit,
            limit_rest: None,
            decay,
            drift: -(m / c) * decay,
            inverse_damping: S::ONE / c,
            step_over_damping: tau / c,
            node_constants,
            phase: Phase::Start,
            newly_broken: 0,
            moved: false,
            unsettled: 0,
            settle_bound,
        }
    }

    /// Nodes `from..end` at rest (the forces are written by each short step before they are
    /// read).
    pub(super) fn clear_nodes(&mut self, from: usize, end: usize) {
        self.vx[from..end].fill(S::ZERO);
        self.vy[from..end].fill(S::ZERO);
    }

    /// Spring `spring`'s limit: broken if absent; an intact spring gets its limit at the
    /// first short step.
    pub(super) fn set_up_spring(&mut self, spring: usize, absent: bool) {
        self.limit[spring] = if absent { broken() } else { S::ZERO };
    }

    /// The irregular node `node`'s constants of the damped step (Eq. 4) and its δF, from its
    /// mass, damping and weakest spring `n`.
    pub(super) fn set_node_constants(
        &mut self,
        node: usize,
        n: &NodeConstants,
        material: &Material<S>,
        tolerance_length: f32,
    ) {
        let tau = material.short_step;
        let (m, c) = (S::from_f32(n.mass), S::from_f32(n.damping));
        let decay = (-(c * tau / m)).exp() - S::ONE;
        let tolerance = S::from_f32(n.weakest * tolerance_length);
        self.node_constants[NODE_CONSTANTS * node..NODE_CONSTANTS * (node + 1)].copy_from_slice(&[
            decay,
            -(m / c) * decay,
            S::ONE / c,
            tau / c,
            tolerance,
        ]);
    }

    /// The irregular lattice's settle bound, once the setup has seen every node.
    pub(super) fn set_settle_bound(&mut self, settle_bound: u64) {
        self.settle_bound = settle_bound;
    }
}

/// |(fx, fy)| < tolerance, exactly as the paper's test, computed so that fixed point does not
/// lose the squares of small forces: compare the larger component first, then the squares of
/// the components divided by the tolerance.
fn below<S: Scalar>(fx: S, fy: S, tolerance: S) -> bool {
    let (ax, ay) = (fx.abs(), fy.abs());
    let largest = ax.max(ay);
    if largest >= tolerance {
        return false;
    }
    let (rx, ry) = (ax / tolerance, ay / tolerance);
    rx * rx + ry * ry < S::ONE
}

/// A direction's springs for the force pass: the rest length, the deep-layer vector e·deep
/// and the stiffness.
#[derive(Clone, Copy)]
struct SpringLaw<S> {
    rest: S,
    ex: S,
    ey: S,
    stiffness: S,
}

impl<S: Scalar> SpringLaw<S> {
    /// The difference vector d = e·deep + b − a of a spring from (ax, ay) to (bx, by)
    /// (displacements) and its squared length.
    #[inline(always)]
    fn difference(&self, ax: S, ay: S, bx: S, by: S) -> (S, S, S) {
        let dx = self.ex + bx - ax;
        let dy = self.ey + by - ay;
        (dx, dy, dx * dx + dy * dy)
    }

    /// Whether a spring of squared length `squared` and limit `limit` is intact and past its
    /// break stretch (Eq. 5): l > κ·l0 as l² > (κ·l0)², with no square root.
    #[inline(always)]
    #[allow(clippy::neg_cmp_op_on_partial_ord, reason = "a NaN limit is an intact spring's")]
    fn past_limit(squared: S, limit: S) -> bool {
        (squared > limit) & !(limit < S::ZERO)
    }

    /// The break test alone, computed as the force pass computes it.
    #[inline(always)]
    fn breaks(&self, ax: S, ay: S, bx: S, by: S, limit: S) -> bool {
        Self::past_limit(self.difference(ax, ay, bx, by).2, limit)
    }
}

/// Springs per chunk of a row in the force pass (a multiple of 4).
const CHUNK: usize = 256;

/// A chunk of a row's springs in the force pass: difference vectors, squared and inverse
/// lengths. The last chunk of a row takes up to four more: the springs of the run past its
/// last whole vector and the spring that wraps around the row's end.
struct Chunk<S> {
    dx: [S; CHUNK + 4],
    dy: [S; CHUNK + 4],
    squared: [S; CHUNK + 4],
    inverse: [S; CHUNK + 4],
}

impl<S: Scalar> Chunk<S> {
    fn new() -> Self {
        let zero = [S::ZERO; CHUNK + 4];
        Chunk { dx: zero, dy: zero, squared: zero, inverse: zero }
    }

    /// The run's springs `start..end` (at most `CHUNK`, a multiple of 4), and when `end` is
    /// the end of the run's whole vectors, the run's last springs and the wrapping one after
    /// them: difference vectors and squared and inverse lengths. Returns how many of the
    /// run's last springs there are.
    #[inline(always)]
    fn load(&mut self, law: &SpringLaw<S>, row: &Row, (ux, uy): (&[S], &[S]), start: usize, end: usize) -> usize {
        let (a, b, m) = (row.a + start, row.b + start, end - start);
        self.differences(law, (&ux[a..a + m], &uy[a..a + m]), (&ux[b..b + m], &uy[b..b + m]));
        if end < row.body() {
            self.inverse_lengths(m);
            return 0;
        }
        let count = row.len - end;
        for t in 0..count {
            let (a, b) = (a + m + t, b + m + t);
            self.set(m + t, law, (ux[a], uy[a]), (ux[b], uy[b]));
        }
        if let Some((i, j, _)) = row.wrap {
            self.set(m + count, law, (ux[i], uy[i]), (ux[j], uy[j]));
        }
        let more = count > 0 || row.wrap.is_some();
        self.inverse_lengths(if more { m + 4 } else { m });
        count
    }

    /// The springs from `a` to `b`: difference vectors and squared lengths.
    #[inline(never)]
    fn differences(&mut self, law: &SpringLaw<S>, (ax, ay): (&[S], &[S]), (bx, by): (&[S], &[S])) {
        let m = ax.len();
        let (ay, bx, by) = (&ay[..m], &bx[..m], &by[..m]);
        let (dx, dy, squared) = (&mut self.dx[..m], &mut self.dy[..m], &mut self.squared[..m]);
        for t in 0..m {
            (dx[t], dy[t], squared[t]) = law.difference(ax[t], ay[t], bx[t], by[t]);
        }
    }

    /// Spring `t` of the chunk, from (ax, ay) to (bx, by), without its inverse length.
    #[inline(always)]
    fn set(&mut self, t: usize, law: &SpringLaw<S>, (ax, ay): (S, S), (bx, by): (S, S)) {
        (self.dx[t], self.dy[t], self.squared[t]) = law.difference(ax, ay, bx, by);
    }

    /// 1/l of the first `m` springs, from l² (at least the backend's resolution).
    #[inline(never)]
    fn inverse_lengths(&mut self, m: usize) {
        let (squared, inverse) = (&self.squared[..m], &mut self.inverse[..m]);
        for t in 0..m {
            inverse[t] = squared[t].max(S::RESOLUTION).inverse_sqrt();
        }
    }

    /// The first `m` springs, for the force loop.
    #[inline(always)]
    fn view(&self, m: usize) -> ChunkView<'_, S> {
        ChunkView { dx: &self.dx[..m], dy: &self.dy[..m], squared: &self.squared[..m], inverse: &self.inverse[..m] }
    }
}

/// The first springs of a chunk, all slices of one length.
struct ChunkView<'c, S> {
    dx: &'c [S],
    dy: &'c [S],
    squared: &'c [S],
    inverse: &'c [S],
}

impl<S: Scalar> ChunkView<'_, S> {
    /// Spring `t`'s force on its first node (Eq. 2), k·(l − l0)·d/l computed as
    /// k·(1 − l0/l)·d, and whether it is past its break stretch; a spring past it, or broken,
    /// exerts none (the paper's loop skips it: the force is exactly +0 then).
    #[inline(always)]
    fn force(&self, law: &SpringLaw<S>, t: usize, limit: S) -> (S, S, bool) {
        let squared = self.squared[t];
        let over = SpringLaw::past_limit(squared, limit);
        // The stiffness times the spring's liveness (1 or 0): k > 0, so 0·k is +0.
        let k = if limit < S::ZERO { S::ZERO } else { law.stiffness };
        let f = k * (S::ONE - law.rest * self.inverse[t]);
        let (x, y) = (f * self.dx[t], f * self.dy[t]);
        if over { (S::ZERO, S::ZERO, true) } else { (x, y, false) }
    }
}

/// A chunk of a row's springs in its own direction, each from node t to node t + 1: each
/// node's force (Eq. 2) in the paper's order, its shear spring −h·u, its own spring's force
/// (zero past the break stretch) and minus its left neighbour's (`left` for the chunk's first
/// node); whether a spring is past, and the last spring's force. (The output and the springs'
/// arrays come in as separate arguments, so that the compiler knows they do not overlap.)
#[inline(never)]
fn chunk_forces_summed<S: Scalar>(
    law: &SpringLaw<S>,
    (chunk, limits): (&Chunk<S>, &[S]),
    (h, ux, uy): (S, &[S], &[S]),
    fx: &mut [S],
    fy: &mut [S],
    left: (S, S),
) -> (bool, (S, S)) {
    let m = fx.len();
    let view = chunk.view(m);
    let (limits, ux, uy, fy) = (&limits[..m], &ux[..m], &uy[..m], &mut fy[..m]);
    let (mut over, (mut left_x, mut left_y)) = (false, left);
    for t in 0..m {
        let (x, y, o) = view.force(law, t, limits[t]);
        fx[t] = (-(h * ux[t]) + x) - left_x;
        fy[t] = (-(h * uy[t]) + y) - left_y;
        (left_x, left_y) = (x, y);
        over |= o;
    }
    (over, (left_x, left_y))
}

/// A chunk's force vectors added to the first nodes `fa` and subtracted from the second `fb`;
/// whether one is past its break stretch (it adds zero).
#[inline(never)]
fn chunk_forces_applied<S: Scalar>(
    law: &SpringLaw<S>,
    chunk: &Chunk<S>,
    limits: &[S],
    fax: &mut [S],
    fay: &mut [S],
    fbx: &mut [S],
    fby: &mut [S],
) -> bool {
    let m = fax.len();
    let view = chunk.view(m);
    let (limits, fax, fay, fbx, fby) = (&limits[..m], &mut fax[..m], &mut fay[..m], &mut fbx[..m], &mut fby[..m]);
    let mut over = false;
    for t in 0..m {
        let (x, y, o) = view.force(law, t, limits[t]);
        fax[t] += x;
        fay[t] += y;
        fbx[t] -= x;
        fby[t] -= y;
        over |= o;
    }
    over
}

/// A row's springs in one direction: the run of `len` springs `s..s + len` from nodes
/// `a..a + len` to nodes `b..b + len`, and the spring `w` from node `i` to node `j` that wraps
/// around the row's end, if any (`(i, j, w)`).
#[derive(Clone, Copy)]
struct Row {
    a: usize,
    b: usize,
    s: usize,
    len: usize,
    wrap: Option<(usize, usize, usize)>,
}

impl Row {
    /// The run's springs that go through whole vectors (a multiple of 4).
    fn body(&self) -> usize {
        self.len - self.len % 4
    }
}

/// A row's springs in its own direction (from each node to the next, and from the last to the
/// first) with the shear springs: every node's force, in the paper's order (shear, its own
/// spring, its left neighbour's, and the wrapping spring at the row's ends). Returns whether
/// one of the run's springs is past its break stretch (it adds zero) and whether the wrapping
/// one is (it adds nothing).
#[inline(always)]
fn row_forces_summed<S: Scalar>(
    law: &SpringLaw<S>,
    row: &Row,
    (ux, uy): (&[S], &[S]),
    (limits, h): (&[S], S),
    (fx, fy): (&mut [S], &mut [S]),
    chunk: &mut Chunk<S>,
) -> (bool, bool) {
    let Row { a, s, len, .. } = *row;
    debug_assert_eq!(row.b, a + 1);
    let (mut over, mut left) = (false, (S::ZERO, S::ZERO));
    let (m, end, count) = row_chunks(law, row, (ux, uy), chunk, |chunk, start, end| {
        let (o, l) = chunk_forces_summed(
            law,
            (chunk, &limits[s + start..s + end]),
            (h, &ux[a + start..a + end], &uy[a + start..a + end]),
            &mut fx[a + start..a + end],
            &mut fy[a + start..a + end],
            left,
        );
        (over, left) = (over | o, l);
    });
    let view = chunk.view(m + 4);
    for t in 0..count {
        let (x, y, o) = view.force(law, m + t, limits[s + end + t]);
        let i = a + end + t;
        fx[i] = (-(h * ux[i]) + x) - left.0;
        fy[i] = (-(h * uy[i]) + y) - left.1;
        left = (x, y);
        over |= o;
    }
    // The last node has no spring of its own but the wrapping one.
    let last = a + len;
    fx[last] = -(h * ux[last]) - left.0;
    fy[last] = -(h * uy[last]) - left.1;
    let mut wrap_over = false;
    if let Some((i, j, w)) = row.wrap {
        debug_assert_eq!((i, j), (last, a));
        let (x, y, o) = view.force(law, m + count, limits[w]);
        if o {
            wrap_over = true;
        } else {
            fx[a] -= x;
            fy[a] -= y;
            fx[last] += x;
            fy[last] += y;
        }
    }
    (over, wrap_over)
}

/// Walks a row's body chunk by chunk: loads each chunk's springs and hands it to `forces`
/// with its range `start..end`. Returns the last chunk's length, where the body ends, and how
/// many springs past it the last load also took (the row's tail, not a whole vector).
#[inline(always)]
fn row_chunks<S: Scalar>(
    law: &SpringLaw<S>,
    row: &Row,
    u: (&[S], &[S]),
    chunk: &mut Chunk<S>,
    mut forces: impl FnMut(&Chunk<S>, usize, usize),
) -> (usize, usize, usize) {
    let body = row.body();
    let mut start = 0;
    loop {
        let end = body.min(start + CHUNK);
        let count = chunk.load(law, row, u, start, end);
        forces(chunk, start, end);
        if end == body {
            return (end - start, end, count);
        }
        start = end;
    }
}

/// Two disjoint runs `a..a + n` and `b..b + n` of one array, both writable.
#[inline(always)]
fn two_runs<S>(v: &mut [S], a: usize, b: usize, n: usize) -> (&mut [S], &mut [S]) {
    if a < b {
        let (low, high) = v.split_at_mut(b);
        (&mut low[a..a + n], &mut high[..n])
    } else {
        let (low, high) = v.split_at_mut(a);
        (&mut high[..n], &mut low[b..b + n])
    }
}

/// A row's springs in a direction that joins the row to the next: each spring's force is
/// added to its first node and subtracted from its second, with no scratch row. The runs lie
/// in different rows and each node takes one term, so every sum keeps its order. Returns
/// whether one of the run's springs is past its break stretch (it adds zero) and whether the
/// wrapping one is (it adds nothing).
#[inline(always)]
fn row_forces_applied<S: Scalar>(
    law: &SpringLaw<S>,
    row: &Row,
    u: (&[S], &[S]),
    limits: &[S],
    (fx, fy): (&mut [S], &mut [S]),
    chunk: &mut Chunk<S>,
) -> (bool, bool) {
    let Row { a, b, s, .. } = *row;
    let mut over = false;
    let (m, end, count) = row_chunks(law, row, u, chunk, |chunk, start, end| {
        let (fax, fbx) = two_runs(fx, a + start, b + start, end - start);
        let (fay, fby) = two_runs(fy, a + start, b + start, end - start);
        over |= chunk_forces_applied(law, chunk, &limits[s + start..s + end], fax, fay, fbx, fby);
    });
    let view = chunk.view(m + 4);
    for t in 0..count {
        let (x, y, o) = view.force(law, m + t, limits[s + end + t]);
        let (i, j) = (a + end + t, b + end + t);
        fx[i] += x;
        fy[i] += y;
        fx[j] -= x;
        fy[j] -= y;
        over |= o;
    }
    let mut wrap_over = false;
    if let Some((i, j, w)) = row.wrap {
        let (x, y, o) = view.force(law, m + count, limits[w]);
        if o {
            wrap_over = true;
        } else {
            fx[i] += x;
            fy[i] += y;
            fx[j] -= x;
            fy[j] -= y;
        }
    }
    (over, wrap_over)
}

/// Spring breaks: the limits (set to broken), the break times and the time now.
struct Breaks<'b, S> {
    limit: &'b mut [S],
    break_time: &'b mut [u32],
    /// One bit per spring: broken (for the tracing).
    broken_blocks: &'b mut [u32],
    time: u32,
    count: u32,
}

impl<S: Scalar> Breaks<'_, S> {
    /// Breaks spring `s`.
    fn record(&mut self, s: usize) {
        self.limit[s] = broken();
        self.break_time[s] = self.time;
        super::network::set_bit(self.broken_blocks, s);
        self.count += 1;
    }

    /// Breaks the run's springs that are past their break stretch (those the force pass
    /// flagged; it changed no displacement).
    #[inline(never)]
    fn record_run(&mut self, law: &SpringLaw<S>, row: &Row, (ux, uy): (&[S], &[S])) {
        let Row { a, b, s, len, .. } = *row;
        for t in 0..len {
            if law.breaks(ux[a + t], uy[a + t], ux[b + t], uy[b + t], self.limit[s + t]) {
                self.record(s + t);
            }
        }
    }
}

/// Whether some node's force has a component v with ¬(|v| < tolerance), NaN aside: the quick
/// half of the stability test, exactly "largest |component| ≥ tolerance" (a NaN fails the
/// exact test that follows). Two comparisons per component and no branch within a block of
/// nodes, so it vectorises; an unstable lattice (the usual case) is known after a few blocks.
#[inline(always)]
#[allow(clippy::neg_cmp_op_on_partial_ord, reason = "a NaN tolerance is never met")]
fn some_component_reaches<S: Scalar>(fx: &[S], fy: &[S], tolerance: S) -> bool {
    // A tolerance ≤ 0 (or NaN) is never met: |v| ≥ 0.
    if !(S::ZERO < tolerance) {
        return true;
    }
    fx.chunks(64).zip(fy.chunks(64)).any(|(fx, fy)| {
        let fy = &fy[..fx.len()];
        let mut reaches = false;
        for i in 0..fx.len() {
            reaches |= component_reaches(fx[i], fy[i], tolerance);
        }
        reaches
    })
}

/// Whether a component of the force (x, y) is at least `tolerance` (> 0) in size.
#[inline(always)]
fn component_reaches<S: Scalar>(x: S, y: S, tolerance: S) -> bool {
    (x >= tolerance) | (-x >= tolerance) | (y >= tolerance) | (-y >= tolerance)
}

/// Eq. 4, every node: v = vᵖ + (vᵖ − F/c)(e^(−cτ/m) − 1),
/// x = xᵖ + (vᵖ − F/c)(−m/c)(e^(−cτ/m) − 1) + (F/c)·τ. Returns whether a displacement or a
/// velocity changed (a NaN counts as a change).
/// (The arrays come in as separate arguments, so that the compiler knows they do not overlap.)
#[inline(never)]
fn move_nodes<S: Scalar>(
    [decay, drift, inverse_damping, step_over_damping]: [S; 4],
    vx: &mut [S],
    vy: &mut [S],
    fx: &[S],
    fy: &[S],
    ux: &mut [S],
    uy: &mut [S],
) -> bool {
    let n = ux.len();
    let (uy, vx, vy, fx, fy) = (&mut uy[..n], &mut vx[..n], &mut vy[..n], &fx[..n], &fy[..n]);
    let mut moved = false;
    for i in 0..n {
        let qx = vx[i] - fx[i] * inverse_damping;
        let qy = vy[i] - fy[i] * inverse_damping;
        let (wx, wy) = (vx[i] + qx * decay, vy[i] + qy * decay);
        let (x, y) =
            (ux[i] + (qx * drift + fx[i] * step_over_damping), uy[i] + (qy * drift + fy[i] * step_over_damping));
        moved |= (wx != vx[i]) | (wy != vy[i]) | (x != ux[i]) | (y != uy[i]);
        (vx[i], vy[i], ux[i], uy[i]) = (wx, wy, x, y);
    }
    moved
}

/// The end of a piece of `budget` items from `from`, at most `end`.
fn piece_end(from: usize, budget: u64, end: usize) -> usize {
    from.saturating_add(usize::try_from(budget).unwrap_or(usize::MAX)).min(end)
}

impl<'a, S: Scalar> Mud<'a, S> {
    /// The short steps' work, from where the last call stopped, until it reaches `budget` (at
    /// least 1) or its phase ends. Returns the work done: springs visited (limits, forces, the
    /// rescan of a row for its breaks) and nodes visited (stability test, move). A piece
    /// overruns `budget` by less than one row's springs in one direction and their rescan:
    /// at most 2·columns − 1 (the phases over nodes or single springs do not overrun).
    pub(super) fn explicit_step(&mut self, budget: u64) -> u64 {
        let budget = budget.max(1);
        loop {
            let SolverState::Explicit(d) = &self.solver else { unreachable!("explicit step on another solver") };
            let work = match d.phase {
                Phase::Start => {
                    self.begin_short_step();
                    continue;
                }
                Phase::Limits(from) => self.set_limits(from, budget),
                Phase::Rows { k, row } => self.rows(k, row, budget),
                Phase::Shear(from) => self.irregular_shear(from, budget),
                Phase::Springs(from) => self.irregular_springs(from, budget),
                Phase::Reaches(from) => self.some_force_reaches(from, budget),
                Phase::Below(from) => self.forces_below(from, budget),
                Phase::Move(from) => self.move_from(from, budget),
            };
            // Only a row skipped (the last of an open lattice, in a direction to the next row)
            // does no work: go on to the next.
            if work > 0 || self.finished {
                return work;
            }
        }
    }

    fn dynamics(&mut self) -> &mut Dynamics<'a, S> {
        match &mut self.solver {
            SolverState::Explicit(d) => d,
            SolverState::QuasiStatic(_) => unreachable!("explicit step on another solver"),
        }
    }

    /// Begins a short step: the irregular lattice's shear forces, or the regular lattices'
    /// limits (when the long step changed the rest length) and rows.
    fn begin_short_step(&mut self) {
        let (rest, _) = self.factors();
        let irregular = self.lattice.mesh().is_some();
        let d = self.dynamics();
        d.newly_broken = 0;
        d.moved = false;
        d.phase = match () {
            _ if irregular => Phase::Shear(0),
            _ if d.limit_rest == Some(rest) => Phase::Rows { k: 0, row: 0 },
            _ => Phase::Limits(0),
        };
    }

    /// Sets the intact springs' limits (κ·l0)² for the rest length now, from spring `from`.
    fn set_limits(&mut self, from: usize, budget: u64) -> u64 {
        let (rest, _) = self.factors();
        let SolverState::Explicit(d) = &mut self.solver else { unreachable!("explicit step on another solver") };
        let springs = d.limit.len();
        let end = piece_end(from, budget, springs);
        for (l, &kappa) in d.limit[from..end].iter_mut().zip(self.break_stretch[from..end].iter()) {
            let limit = kappa * rest;
            *l = if *l < S::ZERO { *l } else { limit * limit };
        }
        d.phase = if end == springs {
            d.limit_rest = Some(rest);
            Phase::Rows { k: 0, row: 0 }
        } else {
            Phase::Limits(end)
        };
        (end - from) as u64
    }

    /// Forces and breaks (Eq. 5 then Eq. 2) of the regular lattices, row by row from row `r`
    /// of direction `k`, until the work reaches `budget` or the rows are done.
    fn rows(&mut self, mut k: usize, mut r: usize, budget: u64) -> u64 {
        let (rest, deep) = self.factors();
        let time = (self.long_steps as f32).to_bits();
        let SolverState::Explicit(d) = &mut self.solver else { unreachable!("explicit step on another solver") };
        let (ux, uy) = (&*self.ux, &*self.uy);
        let m = &self.material;
        let lattice = self.lattice;
        let (nodes, columns, rows) = (lattice.node_count(), lattice.columns as usize, lattice.rows as usize);
        let periodic = lattice.boundary == Boundary::Periodic;
        let (fx, fy) = (&mut *d.fx, &mut *d.fy);
        let mut breaks = Breaks {
            limit: &mut *d.limit,
            break_time: &mut *self.break_time,
            broken_blocks: &mut *self.broken_blocks,
            time,
            count: 0,
        };
        let law = |k: usize| {
            let v = lattice.direction_vector(k);
            SpringLaw { rest, ex: S::from_f32(v[0]) * deep, ey: S::from_f32(v[1]) * deep, stiffness: m.stiffness[k] }
        };
        let mut chunk = Chunk::new();
        // One row of direction k; returns the springs visited.
        let mut row_of = |k: usize, law: &SpringLaw<S>, r: usize| -> u64 {
            if k == 0 {
                // Direction 0 (to the right, in the row) with the shear part of Eq. 2,
                // −h·(x_i − X_i).
                debug_assert_eq!(lattice.step(0, 0), (1, 0));
                let len = columns - 1;
                let a = r * columns;
                let row = Row { a, b: a + 1, s: a, len, wrap: periodic.then_some((a + len, a, a + len)) };
                let (over, wrap_over) =
                    row_forces_summed(law, &row, (ux, uy), (breaks.limit, m.shear), (fx, fy), &mut chunk);
                let mut work = (len + usize::from(periodic)) as u64;
                if over {
                    breaks.record_run(law, &row, (ux, uy));
                    work += len as u64;
                }
                if wrap_over {
                    breaks.record(a + len);
                }
                return work;
            }
            // The directions that join a row to the next.
            let (di, dj) = lattice.step(k, r);
            debug_assert_eq!(dj, 1);
            let mut next = r + 1;
            if next == rows {
                if !periodic {
                    return 0;
                }
                next = 0;
            }
            // The contiguous run: columns whose neighbour stays in the lattice; and the
            // spring that wraps around the row's end.
            let (lo, hi) = (usize::from(di < 0), columns - usize::from(di > 0));
            let a = r * columns + lo;
            let wrap = match di {
                _ if !periodic => None,
                1 => Some((r * columns + columns - 1, next * columns)),
                -1 => Some((r * columns, next * columns + columns - 1)),
                _ => None,
            };
            let row = Row {
                a,
                b: ((next * columns + lo) as i64 + di) as usize,
                s: k * nodes + a,
                len: hi - lo,
                wrap: wrap.map(|(i, j)| (i, j, k * nodes + i)),
            };
            let (over, wrap_over) = row_forces_applied(law, &row, (ux, uy), breaks.limit, (fx, fy), &mut chunk);
            let mut work = (row.len + usize::from(row.wrap.is_some())) as u64;
            if over {
                breaks.record_run(law, &row, (ux, uy));
                work += row.len as u64;
            }
            if let (true, Some((_, _, w))) = (wrap_over, row.wrap) {
                breaks.record(w);
            }
            work
        };
        let mut work = 0u64;
        while k < lattice.directions() && work < budget {
            let law = law(k);
            while r < rows && work < budget {
                work += row_of(k, &law, r);
                r += 1;
            }
            if r == rows {
                (k, r) = (k + 1, 0);
            }
        }
        let count = breaks.count;
        d.newly_broken += count;
        d.phase = if k < lattice.directions() { Phase::Rows { k, row: r } } else { Phase::Reaches(0) };
        self.broken += count;
        work
    }

    /// The quick half of Eq. 3 from node `from`, in blocks of 64 nodes: a component of at
    /// least δF decides at once that the lattice is not stable; only when there is none is
    /// each |F_i| checked exactly.
    fn some_force_reaches(&mut self, from: usize, budget: u64) -> u64 {
        let tolerance = self.material.force_tolerance;
        let d = self.dynamics();
        let nodes = d.fx.len();
        let end = piece_end(from, budget, nodes);
        let mut i = from;
        while i < end {
            let block = end.min(i + 64);
            if some_component_reaches(&d.fx[i..block], &d.fy[i..block], tolerance) {
                // The work ends at the first node that decides, wherever the pieces were cut.
                #[allow(clippy::neg_cmp_op_on_partial_ord, reason = "a NaN tolerance is never met")]
                let decides = |n: usize| !(S::ZERO < tolerance) || component_reaches(d.fx[n], d.fy[n], tolerance);
                let first = (i..block).find(|&n| decides(n)).unwrap_or(block - 1);
                d.phase = Phase::Move(0);
                return (first + 1 - from) as u64;
            }
            i = block;
        }
        d.phase = if end == nodes { Phase::Below(0) } else { Phase::Reaches(end) };
        (end - from) as u64
    }

    /// Eq. 3 exactly from node `from`: stable when every |F_i| < δF (each node's own δF on
    /// the irregular lattice). A stable lattice ends the short step with a long step.
    fn forces_below(&mut self, from: usize, budget: u64) -> u64 {
        let (tolerance, irregular) = (self.material.force_tolerance, self.lattice.mesh().is_some());
        let d = self.dynamics();
        let nodes = d.fx.len();
        let end = piece_end(from, budget, nodes);
        for n in from..end {
            let tolerance = if irregular { d.node_constants[NODE_CONSTANTS * n + 4] } else { tolerance };
            if !below(d.fx[n], d.fy[n], tolerance) {
                d.phase = Phase::Move(0);
                return (n + 1 - from) as u64;
            }
        }
        if end < nodes {
            d.phase = Phase::Below(end);
        } else {
            d.phase = Phase::Start;
            let newly_broken = d.newly_broken;
            self.after_short_step(newly_broken, true);
        }
        (end - from) as u64
    }

    /// Eq. 4 from node `from` (each node's own constants on the irregular lattice); the last
    /// node ends the short step.
    fn move_from(&mut self, from: usize, budget: u64) -> u64 {
        let irregular = self.lattice.mesh().is_some();
        let SolverState::Explicit(d) = &mut self.solver else { unreachable!("explicit step on another solver") };
        let (ux, uy) = (&mut *self.ux, &mut *self.uy);
        let nodes = ux.len();
        let end = piece_end(from, budget, nodes);
        if irregular {
            for node in from..end {
                let [decay, drift, inverse_damping, step_over_damping] =
                    [0, 1, 2, 3].map(|k| d.node_constants[NODE_CONSTANTS * node + k]);
                let qx = d.vx[node] - d.fx[node] * inverse_damping;
                let qy = d.vy[node] - d.fy[node] * inverse_damping;
                let v = (d.vx[node] + qx * decay, d.vy[node] + qy * decay);
                let u = (
                    ux[node] + (qx * drift + d.fx[node] * step_over_damping),
                    uy[node] + (qy * drift + d.fy[node] * step_over_damping),
                );
                d.moved |= (v.0 != d.vx[node]) | (v.1 != d.vy[node]) | (u.0 != ux[node]) | (u.1 != uy[node]);
                (d.vx[node], d.vy[node], ux[node], uy[node]) = (v.0, v.1, u.0, u.1);
            }
        } else {
            let constants = [d.decay, d.drift, d.inverse_damping, d.step_over_damping];
            let (vx, vy, fx, fy) = (&mut d.vx[from..end], &mut d.vy[from..end], &d.fx[from..end], &d.fy[from..end]);
            d.moved |= move_nodes(constants, vx, vy, fx, fy, &mut ux[from..end], &mut uy[from..end]);
        }
        if end < nodes {
            d.phase = Phase::Move(end);
        } else {
            d.phase = Phase::Start;
            let newly_broken = d.newly_broken;
            self.after_short_step(newly_broken, false);
        }
        (end - from) as u64
    }

    /// The irregular lattice's shear forces (Eq. 2's −h·u, h from each node's area) from
    /// node `from`.
    fn irregular_shear(&mut self, from: usize, budget: u64) -> u64 {
        let shear_per_area = S::from_f32(self.material.shear_per_area);
        let Some(mesh) = self.lattice.mesh().copied() else { unreachable!("a regular lattice") };
        let SolverState::Explicit(d) = &mut self.solver else { unreachable!("explicit step on another solver") };
        let (ux, uy) = (&*self.ux, &*self.uy);
        let nodes = ux.len();
        let end = piece_end(from, budget, nodes);
        for node in from..end {
            let h = S::from_f32(mesh.area(node)) * shear_per_area;
            d.fx[node] = -(h * ux[node]);
            d.fy[node] = -(h * uy[node]);
        }
        d.phase = if end == nodes { Phase::Springs(0) } else { Phase::Shear(end) };
        (end - from) as u64
    }

    /// The irregular lattice's springs from spring `from`, in spring order: Eq. 5, then
    /// Eq. 2 for each intact spring.
    fn irregular_springs(&mut self, from: usize, budget: u64) -> u64 {
        let (rest, deep) = self.factors();
        let time = (self.long_steps as f32).to_bits();
        let Some(mesh) = self.lattice.mesh().copied() else { unreachable!("a regular lattice") };
        let SolverState::Explicit(d) = &mut self.solver else { unreachable!("explicit step on another solver") };
        let (ux, uy) = (&*self.ux, &*self.uy);
        let springs = self.break_time.len();
        let end = piece_end(from, budget, springs);
        let mut newly_broken = 0;
        for spring in from..end {
            let Some((a, b)) = mesh.ends(spring) else { continue };
            if self.break_time[spring] != super::INTACT {
                continue;
            }
            let e = mesh.direction(spring);
            let l0 = S::from_f32(mesh.rest_length(spring));
            let dx = S::from_f32(e[0]) * l0 * deep + ux[b] - ux[a];
            let dy = S::from_f32(e[1]) * l0 * deep + uy[b] - uy[a];
            let squared = dx * dx + dy * dy;
            let limit = self.break_stretch[spring] * l0 * rest;
            if squared > limit * limit {
                self.break_time[spring] = time;
                super::network::set_bit(self.broken_blocks, spring);
                self.broken_face += mesh.face(spring);
                newly_broken += 1;
                continue;
            }
            // k·(l − l0·r)/l = k·(1 − l0·r/l).
            let pull = S::from_f32(mesh.stiffness(spring)) * (S::ONE - l0 * rest * squared.inverse_sqrt());
            d.fx[a] += pull * dx;
            d.fy[a] += pull * dy;
            d.fx[b] -= pull * dx;
            d.fy[b] -= pull * dy;
        }
        d.newly_broken += newly_broken;
        d.phase = if end == springs { Phase::Below(0) } else { Phase::Springs(end) };
        self.broken += newly_broken;
        (end - from) as u64
    }

    /// Ends a short step that broke `newly_broken` springs (already counted): tests the crack
    /// density, and takes a long step (Eq. 1) if the lattice is settled: stable (Eq. 3), or
    /// at rest as far as the backend resolves it (the short step broke nothing and changed no
    /// displacement and no velocity, so every short step after it would repeat it and the
    /// stability test would never pass), or [`settle_bound`] short steps after the last long
    /// step or break.
    fn after_short_step(&mut self, newly_broken: u32, stable: bool) {
        if newly_broken > 0 && self.density_reached() {
            self.finished = true;
        }
        let d = self.dynamics();
        d.unsettled = if newly_broken > 0 { 0 } else { d.unsettled.saturating_add(1) };
        let settled = stable || newly_broken == 0 && (!d.moved || d.unsettled >= d.settle_bound);
        if settled {
            d.unsettled = 0;
        }
        if settled && !self.finished {
            if self.misfit >= self.end_misfit() {
                // Stable at the target (or at the largest misfit the model follows).
                self.finished = true;
            } else {
                // Eq. 1: the next long step, r = γ^(t/T).
                self.long_steps += 1;
                self.misfit = self.misfit_at(self.long_steps);
            }
        }
    }
}
