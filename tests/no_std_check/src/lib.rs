//! Links hibi-core into a binary that has no std and no allocator (see Cargo.toml).
#![no_std]

use hibi_core::scalar::Q16;
use hibi_core::{Point, Rng, Scalar, Segment, Stream};

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    loop {}
}

/// Touches every module and backend so that all of them are compiled and linked.
#[unsafe(no_mangle)]
pub extern "C" fn hibi_no_std_probe(seed: u64) -> f32 {
    let mut rng = Rng::new(seed, Stream::BreakStretch);
    let u = rng.uniform_f32() + rng.normal_f32() + rng.poisson(12.0).unwrap_or(0) as f32;
    let a = Segment::new(Point::new(0.0f32, 0.0), Point::new(u, 1.0));
    let b = Segment::new(Point::new(Q16::ZERO, Q16::ONE), Point::new(Q16::ONE, Q16::ZERO));
    let m = micromath::F32(u).sin();
    a.length() + b.length().to_f32() + m.to_f32() + Q16::from_f32(u).exp().to_f32()
}
