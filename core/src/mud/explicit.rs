//! The paper's loop exactly (Hirota et al. Fig. 2): forces (Eq. 2), stability test (Eq. 3),
//! the exact motion of a damped mass under a constant force over one short step (Eq. 4),
//! breaking (Eq. 5), and a long step of shrinking (Eq. 1) whenever the lattice is stable.
//!
//! One short step visits every spring once: it tests the spring for breaking against the
//! positions of the previous move (Eq. 5, "go to 2"), then adds its force (Eq. 2).
//!
//! The pass runs direction by direction and row by row: a row's springs in one direction
//! join two contiguous runs of nodes, so the inner loop has no branches and no indirection
//! and vectorises. Breaks are found in that loop and applied in a scalar pass over the row.
//! The order of every sum is fixed, so the result is the same bit for bit on every build.

use super::lattice::Lattice;
use super::material::Material;
use super::{ABSENT, Boundary, Mud, SolverState, take};
use crate::scalar::Scalar;

/// Velocities, forces, spring liveness and the constants of the damped step.
pub(super) struct Dynamics<'a, S> {
    vx: &'a mut [S],
    vy: &'a mut [S],
    fx: &'a mut [S],
    fy: &'a mut [S],
    /// Per spring: 1 while intact, 0 once broken or absent (it multiplies the force).
    alive: &'a mut [S],
    /// One row's spring force vectors.
    gx: &'a mut [S],
    gy: &'a mut [S],
    /// exp(−c·τ/m) − 1.
    decay: S,
    /// −(m/c)·(exp(−c·τ/m) − 1).
    drift: S,
    /// 1/c.
    inverse_damping: S,
    /// τ/c.
    step_over_damping: S,
}

impl<'a, S: Scalar> Dynamics<'a, S> {
    pub(super) fn new(scalars: &mut &'a mut [S], lattice: &Lattice, other: &[u32], material: &Material<S>) -> Self {
        let nodes = lattice.node_count();
        let [vx, vy, fx, fy] = [(); 4].map(|_| take(scalars, nodes));
        let alive = take(scalars, lattice.spring_count());
        let [gx, gy] = [(); 2].map(|_| take(scalars, lattice.columns as usize));
        vx.fill(S::ZERO);
        vy.fill(S::ZERO);
        for (a, &o) in alive.iter_mut().zip(other.iter()) {
            *a = if o == ABSENT { S::ZERO } else { S::ONE };
        }
        let (m, c, tau) = (material.mass, material.damping, material.short_step);
        let decay = (-(c * tau / m)).exp() - S::ONE;
        Dynamics {
            vx,
            vy,
            fx,
            fy,
            alive,
            gx,
            gy,
            decay,
            drift: -(m / c) * decay,
            inverse_damping: S::ONE / c,
            step_over_damping: tau / c,
        }
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

/// One spring's state for the force pass: the rest length, the deep-layer vector e·deep and
/// the stiffness of its direction.
#[derive(Clone, Copy)]
struct SpringLaw<S> {
    rest: S,
    ex: S,
    ey: S,
    stiffness: S,
}

impl<S: Scalar> SpringLaw<S> {
    /// The force vector a spring from (ax, ay) to (bx, by) (displacements) exerts on its first
    /// node (Eq. 2), times `alive`, and whether it is stretched past `kappa` (Eq. 5).
    ///
    /// k·(l − l0)·d/l is computed as k·(1 − l0/l)·d with 1/l from `inverse_sqrt`, and the
    /// break test l > κ·l0 as l² > (κ·l0)²: no square root and no division, so that the row
    /// loop vectorises.
    #[inline(always)]
    fn force(&self, ax: S, ay: S, bx: S, by: S, alive: S, kappa: S) -> (S, S, bool) {
        let dx = self.ex + bx - ax;
        let dy = self.ey + by - ay;
        let squared = dx * dx + dy * dy;
        let over = (squared > self.limit_squared(kappa)) & (alive > S::ZERO);
        let inverse_length = squared.max(S::RESOLUTION).inverse_sqrt();
        let f = alive * self.stiffness * (S::ONE - self.rest * inverse_length);
        (f * dx, f * dy, over)
    }

    /// (κ·l0)²: the squared length past which a spring breaks.
    #[inline(always)]
    fn limit_squared(&self, kappa: S) -> S {
        let limit = kappa * self.rest;
        limit * limit
    }
}

/// The force vectors of a row's springs in one direction, from the displacements of their
/// first nodes `a` and second nodes `b`; whether any intact one is past its break stretch.
/// Equal-length slices and plain indexing let the loop vectorise.
#[inline(always)]
fn row_forces<S: Scalar>(
    law: &SpringLaw<S>,
    a: (&[S], &[S]),
    b: (&[S], &[S]),
    springs: (&[S], &[S]),
    out: (&mut [S], &mut [S]),
) -> bool {
    let n = out.0.len();
    let (ax, ay, bx, by) = (&a.0[..n], &a.1[..n], &b.0[..n], &b.1[..n]);
    let (alive, kappa) = (&springs.0[..n], &springs.1[..n]);
    let (gx, gy) = (&mut out.0[..n], &mut out.1[..n]);
    let mut over = false;
    for t in 0..n {
        let (x, y, o) = law.force(ax[t], ay[t], bx[t], by[t], alive[t], kappa[t]);
        gx[t] = x;
        gy[t] = y;
        over |= o;
    }
    over
}

/// f = −h·u for every node (the shear springs of Eq. 2).
#[inline(always)]
fn shear_forces<S: Scalar>(h: S, (ux, uy): (&[S], &[S]), (fx, fy): (&mut [S], &mut [S])) {
    let n = fx.len();
    let (ux, uy, fy) = (&ux[..n], &uy[..n], &mut fy[..n]);
    for i in 0..n {
        fx[i] = -(h * ux[i]);
        fy[i] = -(h * uy[i]);
    }
}

/// f += sign·g over a row (sign ±1: the force on a spring's first or second node).
#[inline(always)]
fn add_row<S: Scalar>(fx: &mut [S], fy: &mut [S], gx: &[S], gy: &[S], sign: S) {
    let n = fx.len();
    let (fy, gx, gy) = (&mut fy[..n], &gx[..n], &gy[..n]);
    if sign > S::ZERO {
        for i in 0..n {
            fx[i] += gx[i];
            fy[i] += gy[i];
        }
    } else {
        for i in 0..n {
            fx[i] -= gx[i];
            fy[i] -= gy[i];
        }
    }
}

/// The largest |component| of any node's force, over four independent lanes so that the
/// reduction vectorises (max is exact, so the lanes change nothing but speed).
#[inline(always)]
fn largest_component<S: Scalar>(fx: &[S], fy: &[S]) -> S {
    let n = fx.len();
    let fy = &fy[..n];
    let mut lanes = [S::ZERO; 4];
    let whole = n - n % 4;
    for i in (0..whole).step_by(4) {
        for (k, lane) in lanes.iter_mut().enumerate() {
            *lane = lane.max(fx[i + k].abs()).max(fy[i + k].abs());
        }
    }
    for i in whole..n {
        lanes[0] = lanes[0].max(fx[i].abs()).max(fy[i].abs());
    }
    lanes[0].max(lanes[1]).max(lanes[2].max(lanes[3]))
}

/// Eq. 4, every node: v = vᵖ + (vᵖ − F/c)(e^(−cτ/m) − 1),
/// x = xᵖ + (vᵖ − F/c)(−m/c)(e^(−cτ/m) − 1) + (F/c)·τ.
#[inline(always)]
fn move_nodes<S: Scalar>(d: &mut Dynamics<'_, S>, (ux, uy): (&mut [S], &mut [S])) {
    let (decay, drift, inverse_damping, step_over_damping) = (d.decay, d.drift, d.inverse_damping, d.step_over_damping);
    let n = ux.len();
    let (uy, vx, vy, fx, fy) = (&mut uy[..n], &mut d.vx[..n], &mut d.vy[..n], &d.fx[..n], &d.fy[..n]);
    for i in 0..n {
        let qx = vx[i] - fx[i] * inverse_damping;
        let qy = vy[i] - fy[i] * inverse_damping;
        vx[i] += qx * decay;
        vy[i] += qy * decay;
        ux[i] += qx * drift + fx[i] * step_over_damping;
        uy[i] += qy * drift + fy[i] * step_over_damping;
    }
}

impl<S: Scalar> Mud<'_, S> {
    /// One short step: forces and breaks, then either a long step (stable) or a move.
    /// Returns the work done (spring slots visited).
    pub(super) fn explicit_step(&mut self) -> u64 {
        let (rest, deep) = self.factors();
        let time = (self.long_steps as f32).to_bits();
        let SolverState::Explicit(d) = &mut self.solver else { unreachable!("explicit step on another solver") };
        let (ux, uy) = (&mut *self.ux, &mut *self.uy);
        let m = &self.material;
        let lattice = self.lattice;
        let (nodes, columns, rows) = (lattice.node_count(), lattice.columns as usize, lattice.rows as usize);
        let periodic = lattice.boundary == Boundary::Periodic;
        let (fx, fy, alive) = (&mut *d.fx, &mut *d.fy, &mut *d.alive);
        let (gx, gy) = (&mut *d.gx, &mut *d.gy);
        let (break_time, break_stretch) = (&mut *self.break_time, &*self.break_stretch);

        // Eq. 2, shear part: −h·(x_i − X_i).
        shear_forces(m.shear, (ux, uy), (fx, fy));
        // Eq. 5 then Eq. 2, spring part, direction by direction, row by row.
        let mut newly_broken = 0;
        for k in 0..lattice.directions() {
            let v = lattice.direction_vector(k);
            let law = SpringLaw {
                rest,
                ex: S::from_f32(v[0]) * deep,
                ey: S::from_f32(v[1]) * deep,
                stiffness: m.stiffness[k],
            };
            for row in 0..rows {
                let (di, dj) = lattice.step(k, row);
                let mut next_row = row + dj as usize;
                if next_row >= rows {
                    if !periodic {
                        continue;
                    }
                    next_row -= rows;
                }
                // The contiguous run: columns whose neighbour stays in the lattice.
                let (lo, hi) = (usize::from(di < 0), columns - usize::from(di > 0));
                let len = hi - lo;
                let a = row * columns + lo;
                let b = (next_row * columns + lo) as i64 + di;
                let b = b as usize;
                let s = k * nodes + a;
                let over = row_forces(
                    &law,
                    (&ux[a..a + len], &uy[a..a + len]),
                    (&ux[b..b + len], &uy[b..b + len]),
                    (&alive[s..s + len], &break_stretch[s..s + len]),
                    (&mut gx[..len], &mut gy[..len]),
                );
                if over {
                    for t in 0..len {
                        let (x, y) = (law.ex + ux[b + t] - ux[a + t], law.ey + uy[b + t] - uy[a + t]);
                        if alive[s + t] > S::ZERO && x * x + y * y > law.limit_squared(break_stretch[s + t]) {
                            alive[s + t] = S::ZERO;
                            break_time[s + t] = time;
                            newly_broken += 1;
                            gx[t] = S::ZERO;
                            gy[t] = S::ZERO;
                        }
                    }
                }
                add_row(&mut fx[a..a + len], &mut fy[a..a + len], &gx[..len], &gy[..len], S::ONE);
                add_row(&mut fx[b..b + len], &mut fy[b..b + len], &gx[..len], &gy[..len], -S::ONE);
                // The spring that wraps around the row's end.
                if periodic && di != 0 {
                    let (i, j) = if di > 0 {
                        (row * columns + columns - 1, next_row * columns)
                    } else {
                        (row * columns, next_row * columns + columns - 1)
                    };
                    let s = k * nodes + i;
                    let (x, y, o) = law.force(ux[i], uy[i], ux[j], uy[j], alive[s], break_stretch[s]);
                    if o {
                        alive[s] = S::ZERO;
                        break_time[s] = time;
                        newly_broken += 1;
                    } else {
                        fx[i] += x;
                        fy[i] += y;
                        fx[j] -= x;
                        fy[j] -= y;
                    }
                }
            }
        }
        // Eq. 3: stable when every |F_i| < δF. The largest force component decides at once
        // unless it is below δF; only then is each |F_i| checked exactly.
        let largest = largest_component(fx, fy);
        let stable =
            largest < m.force_tolerance && fx.iter().zip(fy.iter()).all(|(&x, &y)| below(x, y, m.force_tolerance));
        if !stable {
            move_nodes(d, (ux, uy));
        }
        self.broken += newly_broken;
        if newly_broken > 0 && self.density_reached() {
            self.finished = true;
        }
        if stable && !self.finished {
            if self.params.shrink_ratio == 1.0 || self.target_misfit().is_some_and(|target| self.misfit >= target) {
                // Stable at the target (or nothing drives the lattice any more).
                self.finished = true;
            } else {
                // Eq. 1: the next long step, r = γ^(t/T).
                self.long_steps += 1;
                self.misfit = self.misfit_at(self.long_steps);
            }
        }
        lattice.spring_count() as u64
    }
}
