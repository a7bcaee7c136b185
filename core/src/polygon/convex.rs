//! Convex pieces of at most [`MAX_PIECE_POINTS`] points merged from a polygon's triangles,
//! as physics engines take them (Box2D's `b2_maxPolygonVertices`; Jolt's and PhysX's convex
//! shapes). A greedy form of Hertel and Mehlhorn's merge (a diagonal is dropped when the two
//! pieces it separates make a convex one): each triangle, in the order ear clipping writes
//! them (neighbours one after another), joins the piece under way when it shares an edge
//! with it and the union stays strictly convex with at most 8 points; otherwise the piece is
//! finished and the triangle starts the next. Constant work per triangle (at most 8 edges
//! compared and three corners tested); the pieces' areas add up to the triangles'.

use super::triangulation::cross;

/// The most points a convex piece has (Box2D's `b2_maxPolygonVertices`).
pub const MAX_PIECE_POINTS: usize = 8;

/// The piece under way.
#[derive(Default)]
pub(crate) struct Merger {
    piece: [u32; MAX_PIECE_POINTS],
    len: usize,
}

impl Merger {
    /// Adds counter-clockwise triangle `t`, calling `done` with the piece it finishes.
    pub(crate) fn add(&mut self, t: [u32; 3], points: &[[f32; 2]], done: &mut impl FnMut(&[u32])) {
        if self.len > 0 && self.len < MAX_PIECE_POINTS && self.join(t, points) {
            return;
        }
        self.finish(done);
        self.piece[..3].copy_from_slice(&t);
        self.len = 3;
    }

    /// Calls `done` with the piece under way, if any, and starts afresh.
    pub(crate) fn finish(&mut self, done: &mut impl FnMut(&[u32])) {
        if self.len > 0 {
            done(&self.piece[..self.len]);
        }
        self.len = 0;
    }

    /// Joins `t` if it shares an edge (v, u) with the piece's edge (u, v) and the union stays
    /// strictly convex: its third point goes between u and v.
    fn join(&mut self, t: [u32; 3], points: &[[f32; 2]]) -> bool {
        let at = |i: u32| points[i as usize];
        let len = self.len;
        for i in 0..len {
            let (u, v) = (self.piece[i], self.piece[(i + 1) % len]);
            for k in 0..3 {
                if t[k] == v && t[(k + 1) % 3] == u {
                    let w = t[(k + 2) % 3];
                    let before = self.piece[(i + len - 1) % len];
                    let after = self.piece[(i + 2) % len];
                    if cross(at(before), at(u), at(w)) > 0.0
                        && cross(at(u), at(w), at(v)) > 0.0
                        && cross(at(w), at(v), at(after)) > 0.0
                    {
                        self.piece.copy_within(i + 1..len, i + 2);
                        self.piece[i + 1] = w;
                        self.len += 1;
                        return true;
                    }
                    return false;
                }
            }
        }
        false
    }
}
