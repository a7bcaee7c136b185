//! # hibi-core
//!
//! hibi (ひび, "crack") generates crack and cell patterns from three graphics papers: a
//! spring lattice of drying mud (Hirota et al.), a stochastic crack grower for a glass plate
//! hit by a ball (Agui et al.), and hierarchical Voronoi cells for skin (Ishii et al.).
//!
//! This crate is the core: `#![no_std]`, no `alloc` (the compiler proves it never
//! allocates; the `alloc` feature adds only `XMemory::allocate`, owned buffers for callers
//! with a heap), no `unsafe`. Every byte it writes is handed in by the caller, every run is
//! bounded and resumable, and the same seed, parameters and scalar backend give the same
//! bytes on every platform and in every build.
//!
//! - [`rng`]: the deterministic random source (Xoshiro128++, one stream per purpose).
//! - [`scalar`]: the number type the models compute in (`f32`, `micromath`, Q16.16).
//! - [`mud`]: model A, the drying-mud spring lattice.
//! - [`glass`]: model B, the crack grower for a glass plate hit by a ball.
//! - [`skin`]: model C, hierarchical Voronoi skin cells.
//! - [`polygon`]: the rings glass fragments and mud cells are written as.
//! - [`raster`]: drawing into caller buffers.
#![no_std]
#![forbid(unsafe_code)]
#![deny(missing_docs)]

#[cfg(feature = "alloc")]
extern crate alloc;

mod enumeration;
mod error;
mod geom;
pub mod glass;
pub mod mud;
pub mod polygon;
pub mod raster;
pub mod rng;
pub mod scalar;
pub mod skin;

pub use rng::{Rng, RngError, Spread, Stream};
pub use scalar::Scalar;
