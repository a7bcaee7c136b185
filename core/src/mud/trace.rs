//! Crack tracing by the paper's Fig. 5 rule.
//!
//! A crack's width is the broken spring's current length minus its rest length, and its cut
//! sits at the spring's midpoint. For every mesh cell (a triangle of the hexagonal model, a
//! square of the square one): one broken side gives a crack from its midpoint to the cell's
//! node centroid (a dead end); two broken sides give a straight crack joining their
//! midpoints; three or more meet at the centroid.

use super::{Mud, MudError};
use crate::scalar::Scalar;

/// One straight piece of crack, in lattice units (multiply by `element_size` for cm), on
/// the deformed surface. Each end carries the width and break time of the spring it sits on
/// (an end at a cell centroid carries those of the spring the segment comes from). On
/// periodic lattices, segments of cells on the far edges reach past the domain by less than
/// one spacing: draw them wrapped. In C: `hibi_mud_segment`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C)]
pub struct CrackSegment {
    /// First end (x, y).
    pub start: [f32; 2],
    /// Second end (x, y).
    pub end: [f32; 2],
    /// Crack width at each end: current length − rest length of the broken spring.
    pub width: [f32; 2],
    /// Break time at each end, in long steps T.
    pub time: [f32; 2],
}

/// The cut of one broken side: midpoint, width, break time.
#[derive(Clone, Copy)]
struct Cut {
    at: [f32; 2],
    width: f32,
    time: f32,
}

impl<S: Scalar> Mud<'_, S> {
    /// Calls `emit` with every crack segment, cell by cell in index order (what
    /// [`Mud::segments`] writes, without a buffer).
    pub fn for_each_segment(&self, mut emit: impl FnMut(CrackSegment)) {
        // Nothing has cracked while the setup is under way.
        if !self.is_set_up() {
            return;
        }
        let lattice = self.lattice;
        let (rest, deep) = self.factors();
        let (rest, deep) = (rest.to_f32(), deep.to_f32());
        let cells = lattice.node_count() * lattice.cells_per_node();
        for c in 0..cells {
            let Some(cell) = lattice.cell(c) else {
                continue;
            };
            let n = cell.corners;
            if (0..n).all(|k| !self.is_broken(cell.sides[k] as usize)) {
                continue;
            }
            // Current corner positions: deep position (unwrapped) plus displacement.
            let mut corner = [[0.0f32; 2]; 4];
            for (k, position) in corner.iter_mut().enumerate().take(n) {
                let (dx, dy) = self.displacement(cell.nodes[k] as usize);
                *position = [cell.reference[k][0] * deep + dx.to_f32(), cell.reference[k][1] * deep + dy.to_f32()];
            }
            let centroid = {
                let sum = corner[..n].iter().fold([0.0f32; 2], |s, p| [s[0] + p[0], s[1] + p[1]]);
                [sum[0] / n as f32, sum[1] / n as f32]
            };
            let mut cuts = [Cut { at: [0.0; 2], width: 0.0, time: 0.0 }; 4];
            let mut count = 0;
            for k in 0..n {
                let Some(time) = self.spring_break_time(cell.sides[k] as usize) else {
                    continue;
                };
                let (p, q) = (corner[k], corner[(k + 1) % n]);
                let length = libm::hypotf(q[0] - p[0], q[1] - p[1]);
                cuts[count] = Cut { at: [(p[0] + q[0]) * 0.5, (p[1] + q[1]) * 0.5], width: length - rest, time };
                count += 1;
            }
            let segment = |a: Cut, b: Cut| CrackSegment {
                start: a.at,
                end: b.at,
                width: [a.width, b.width],
                time: [a.time, b.time],
            };
            if count == 2 {
                emit(segment(cuts[0], cuts[1]));
            } else {
                for cut in &cuts[..count] {
                    emit(segment(*cut, Cut { at: centroid, ..*cut }));
                }
            }
        }
    }

    /// The number of crack segments [`Mud::segments`] writes now.
    pub fn segment_count(&self) -> usize {
        let mut count = 0;
        self.for_each_segment(|_| count += 1);
        count
    }

    /// Writes the crack segments into `out` and returns how many; if `out` is shorter than
    /// [`Mud::segment_count`], nothing is written.
    pub fn segments(&self, out: &mut [CrackSegment]) -> Result<usize, MudError> {
        let needed = self.segment_count();
        if out.len() < needed {
            return Err(MudError::BufferTooSmall { needed });
        }
        let mut written = 0;
        self.for_each_segment(|s| {
            out[written] = s;
            written += 1;
        });
        Ok(written)
    }
}
