//! The paper's loop exactly (Hirota et al. Fig. 2): forces (Eq. 2), stability test (Eq. 3),
//! the exact motion of a damped mass under a constant force over one short step (Eq. 4),
//! breaking (Eq. 5), and a long step of shrinking (Eq. 1) whenever the lattice is stable.
//!
//! One short step visits every spring once: it tests the spring for breaking against the
//! positions of the previous move (Eq. 5, "go to 2"), then adds its force (Eq. 2).

use super::material::Material;
use super::{ABSENT, INTACT, Mud, SolverState, take};
use crate::scalar::Scalar;

/// Velocities, forces and the constants of the damped step.
pub(super) struct Dynamics<'a, S> {
    vx: &'a mut [S],
    vy: &'a mut [S],
    fx: &'a mut [S],
    fy: &'a mut [S],
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
    pub(super) fn new(scalars: &mut &'a mut [S], nodes: usize, material: &Material<S>) -> Self {
        let [vx, vy, fx, fy] = [(); 4].map(|_| take(scalars, nodes));
        vx.fill(S::ZERO);
        vy.fill(S::ZERO);
        let (m, c, tau) = (material.mass, material.damping, material.short_step);
        let decay = (-(c * tau / m)).exp() - S::ONE;
        Dynamics {
            vx,
            vy,
            fx,
            fy,
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

impl<S: Scalar> Mud<'_, S> {
    /// One short step: forces and breaks, then either a long step (stable) or a move.
    /// Returns the work done (springs visited).
    pub(super) fn explicit_step(&mut self) -> u64 {
        let (rest, deep) = self.factors();
        let time = (self.long_steps as f32).to_bits();
        let SolverState::Explicit(d) = &mut self.solver else {
            unreachable!("explicit step on another solver")
        };
        let (ux, uy) = (&mut *self.ux, &mut *self.uy);
        let m = &self.material;
        let lattice = &self.lattice;
        let dirs = lattice.directions();
        let nodes = lattice.node_count();
        let vectors: [[S; 2]; 3] =
            core::array::from_fn(|k| lattice.direction_vector(k).map(S::from_f32));

        // Eq. 2, shear part: −h·(x_i − X_i).
        for i in 0..nodes {
            d.fx[i] = -(m.shear * ux[i]);
            d.fy[i] = -(m.shear * uy[i]);
        }
        // Eq. 5 then Eq. 2, spring part.
        let mut newly_broken = 0;
        for i in 0..nodes {
            for (k, vector) in vectors.iter().enumerate().take(dirs) {
                let spring = i * dirs + k;
                let j = self.other[spring];
                if j == ABSENT || self.break_time[spring] != INTACT {
                    continue;
                }
                let j = j as usize;
                let dx = vector[0] * deep + ux[j] - ux[i];
                let dy = vector[1] * deep + uy[j] - uy[i];
                let length = (dx * dx + dy * dy).sqrt();
                if length > self.break_stretch[spring] * rest {
                    self.break_time[spring] = time;
                    newly_broken += 1;
                    continue;
                }
                if length == S::ZERO {
                    continue;
                }
                let f = m.stiffness[k] * (length - rest) / length;
                let (gx, gy) = (f * dx, f * dy);
                d.fx[i] += gx;
                d.fy[i] += gy;
                d.fx[j] -= gx;
                d.fy[j] -= gy;
            }
        }
        // Eq. 3: stable when every |F_i| < δF.
        let stable = (0..nodes).all(|i| below(d.fx[i], d.fy[i], m.force_tolerance));
        if !stable {
            // Eq. 4: v = vᵖ + (vᵖ − F/c)(e^(−cτ/m) − 1),
            //        x = xᵖ + (vᵖ − F/c)(−m/c)(e^(−cτ/m) − 1) + (F/c)·τ.
            for i in 0..nodes {
                let qx = d.vx[i] - d.fx[i] * d.inverse_damping;
                let qy = d.vy[i] - d.fy[i] * d.inverse_damping;
                d.vx[i] += qx * d.decay;
                d.vy[i] += qy * d.decay;
                ux[i] += qx * d.drift + d.fx[i] * d.step_over_damping;
                uy[i] += qy * d.drift + d.fy[i] * d.step_over_damping;
            }
        }
        self.broken += newly_broken;
        if newly_broken > 0 && self.density_reached() {
            self.finished = true;
        }
        if stable && !self.finished {
            if self.params.shrink_ratio == 1.0
                || self
                    .target_misfit()
                    .is_some_and(|target| self.misfit >= target)
            {
                // Stable at the target (or nothing drives the lattice any more).
                self.finished = true;
            } else {
                // Eq. 1: the next long step, r = γ^(t/T).
                self.long_steps += 1;
                self.misfit = self.misfit_at(self.long_steps);
            }
        }
        (nodes * dirs) as u64
    }
}
