//! Polygons the models write: glass fragments and mud cells are both sets of [`Ring`]s over a
//! point buffer. This module is shared below the models; neither owns it.

mod ring;

pub use ring::{NOT_A_HOLE, Ring};
