//! Golden snapshots of the frame: the first outputs of every random stream, and hashes of
//! every distribution and every scalar backend's functions over fixed grids. The README's
//! test command runs these in debug and in release; both must give these exact bits.
//!
//! A change here is a deliberate, reviewed event: it changes every pattern hibi makes.

use hibi_core::scalar::Q16;
use hibi_core::{Rng, Scalar, Spread, Stream};
use hibi_tests::fnv1a64;

/// Seed of the golden runs.
const SEED: u64 = 2026;

/// The first four 32-bit outputs of each stream for seed 2026, in `Stream::ALL` order.
const FIRST_OUTPUTS: [(Stream, [u32; 4]); 10] = [
    (Stream::BreakStretch, [1427003102, 2937897310, 2427765056, 1693374040]),
    (Stream::LatticeJitter, [954381491, 385118382, 373506146, 1222866654]),
    (Stream::RadialCount, [4086243937, 3633856879, 768297860, 2570844062]),
    (Stream::CrackSpeed, [1383952818, 2442216126, 3090181330, 251949910]),
    (Stream::RingRadius, [3449750040, 3083511762, 616720071, 1265029083]),
    (Stream::RandomForce, [1380643572, 156739567, 4233051604, 1789837582]),
    (Stream::ImpactRotation, [3269840399, 1070210178, 3338609189, 728232604]),
    (Stream::SiteLayout, [1846600729, 1829838922, 869880936, 2068712773]),
    (Stream::SiteJitter, [260090408, 2914357267, 291705697, 3463590335]),
    (Stream::EdgePerturbation, [2428378447, 991469845, 2887340429, 1140106291]),
];

#[test]
fn first_outputs_of_every_stream() {
    for (stream, expected) in FIRST_OUTPUTS {
        let mut rng = Rng::new(SEED, stream);
        let got: [u32; 4] = core::array::from_fn(|_| rng.next_u32());
        assert_eq!(got, expected, "stream {stream:?} changed");
    }
    assert_eq!(Stream::ALL.map(|s| s), FIRST_OUTPUTS.map(|(s, _)| s), "a stream is missing here");
}

/// Hash of 10 000 draws of each distribution, as raw bits.
#[test]
fn distributions_are_bit_exact() {
    let mut bytes = Vec::new();
    let mut rng = Rng::new(SEED, Stream::BreakStretch);
    for _ in 0..10_000 {
        bytes.extend(rng.uniform_f32().to_bits().to_le_bytes());
        bytes.extend(rng.uniform_f64().to_bits().to_le_bytes());
        bytes.extend(rng.normal().to_bits().to_le_bytes());
        bytes.extend(rng.poisson(37.5).unwrap().to_le_bytes());
        bytes.extend(rng.rand(40.0, 0.3, Spread::Normal).unwrap().to_bits().to_le_bytes());
        bytes.extend(rng.rand(40.0, 0.3, Spread::Uniform).unwrap().to_bits().to_le_bytes());
    }
    assert_eq!(fnv1a64(&bytes), 4447176120813173559, "the distributions changed");
}

/// Every function of a backend over a fixed grid, as the bits of `to_f32`.
fn backend_table<S: Scalar>() -> Vec<u8> {
    let mut bytes = Vec::new();
    let mut push = |v: S| bytes.extend(v.to_f32().to_bits().to_le_bytes());
    for i in -400..=400 {
        let x = S::from_f32(i as f32 * 0.037);
        let y = S::from_f32(i as f32 * -0.021 + 0.5);
        push(x.sqrt());
        push(x.sin());
        push(x.cos());
        push(y.atan2(x));
        push((x * S::from_f32(0.25)).exp());
        push(x.floor());
        push(x * y + x / (y + S::from_f32(3.0)));
    }
    bytes
}

#[test]
fn scalar_backends_are_bit_exact() {
    assert_eq!(fnv1a64(&backend_table::<f32>()), 2369291559573998798, "the f32 (libm) backend changed");
    assert_eq!(fnv1a64(&backend_table::<micromath::F32>()), 6723904205137209666, "the micromath backend changed");
    assert_eq!(fnv1a64(&backend_table::<Q16>()), 18042995786501796456, "the Q16.16 backend changed");
}
