//! The crack network as polylines with a time per vertex.

use super::grid::NONE;
use super::{Glass, GlassError};

/// A point of a crack's polyline: its position and the time (steps since its impact) the
/// crack front passed it. In C: `hibi_glass_point`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C)]
pub struct CrackPoint {
    /// Position (x, y), in px.
    pub at: [f32; 2],
    /// Time in steps.
    pub time: f32,
}

impl Glass<'_> {
    /// Calls `visit` with the points of crack `i` in growth order (nothing for a crack that
    /// never grew).
    pub fn for_each_point(&self, i: usize, mut visit: impl FnMut(CrackPoint)) {
        let Some(c) = self.cracks[..self.crack_count].get(i) else { return };
        let mut e = c.first_segment;
        if e == NONE {
            return;
        }
        let first = self.edges[e as usize];
        visit(CrackPoint { at: self.vertices[first.from as usize].at, time: first.time[0] });
        while e != NONE {
            let edge = self.edges[e as usize];
            visit(CrackPoint { at: self.vertices[edge.to as usize].at, time: edge.time[1] });
            e = edge.next;
        }
    }

    /// The number of points of crack `i`.
    pub fn point_count(&self, i: usize) -> usize {
        let mut n = 0;
        self.for_each_point(i, |_| n += 1);
        n
    }

    /// Writes the points of crack `i` into `out` and returns how many; nothing is written if
    /// `out` is shorter than [`Glass::point_count`].
    pub fn points(&self, i: usize, out: &mut [CrackPoint]) -> Result<usize, GlassError> {
        let needed = self.point_count(i);
        if out.len() < needed {
            return Err(GlassError::BufferTooSmall { needed });
        }
        let mut n = 0;
        self.for_each_point(i, |p| {
            out[n] = p;
            n += 1;
        });
        Ok(n)
    }
}
