//! Links hibi-core into a binary that has no std and no allocator (see Cargo.toml).
#![no_std]

use hibi_core::mud::MudParams;
use hibi_core::scalar::Q16;
use hibi_core::{Rng, Scalar, Stream};

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    loop {}
}

/// Touches every module and backend so that all of them are compiled and linked.
#[unsafe(no_mangle)]
pub extern "C" fn hibi_no_std_probe(seed: u64) -> f32 {
    let mut rng = Rng::new(seed, Stream::BreakStretch);
    let u = rng.uniform_f32() + rng.normal_f32() + rng.poisson(12.0).unwrap_or(0) as f32;
    let spacing = MudParams::default().predicted_spacing(MudParams::default().target_shrink).map_or(0.0, |s| s.spacing);
    let m = micromath::F32(u).sin();
    spacing + Q16::from_f32(u).sqrt().to_f32() + m.to_f32() + Q16::from_f32(u).exp().to_f32()
}
