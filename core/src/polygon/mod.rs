//! Polygons the models write: glass fragments and mud cells are both sets of [`Ring`]s over a
//! point buffer. This module is shared below the models; neither owns it.
//!
//! The pieces a physics engine takes are cut here too, from any such rings: triangles
//! ([`triangulate`]) and convex pieces of at most [`MAX_PIECE_POINTS`] points
//! ([`convex_pieces`]), counted first ([`pieces_scratch`], [`piece_counts`]) and written into
//! caller buffers.

mod convex;
mod pieces;
mod ring;
mod triangulation;

pub use convex::MAX_PIECE_POINTS;
pub use pieces::{
    ConvexPiece, PieceCounts, PiecesError, RingError, Triangle, convex_pieces, piece_counts, pieces_scratch,
    triangulate,
};
pub use ring::{NOT_A_HOLE, Ring};
