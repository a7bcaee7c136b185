//! Golden snapshots: every scene of `hibi-scenes` (the random streams and distributions, the
//! scalar backends, and a run of every model with each of its outputs) must hash to its
//! listed value. The README's test command runs this in debug and in release; `targets/run`
//! runs the same list on other architectures.
//!
//! A change here is a deliberate, reviewed event: it changes every pattern hibi makes.

use hibi_core::{Rng, Stream};
use hibi_scenes::{GOLDENS, Memory, SEED, check, fnv1a64};

/// The first four 32-bit outputs of each stream for seed 2026, in `Stream::ALL` order: the
/// numbers the `rng.stream.*` scenes hash.
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
    for (i, (stream, expected)) in FIRST_OUTPUTS.into_iter().enumerate() {
        let mut rng = Rng::new(SEED, stream);
        let got: [u32; 4] = core::array::from_fn(|_| rng.next_u32());
        assert_eq!(got, expected, "stream {stream:?} changed");
        let bytes: Vec<u8> = expected.iter().flat_map(|v| v.to_le_bytes()).collect();
        assert_eq!(fnv1a64(&bytes), GOLDENS[i].1, "the scene {} hashes other numbers", GOLDENS[i].0);
    }
    assert_eq!(Stream::ALL.map(|s| s), FIRST_OUTPUTS.map(|(s, _)| s), "a stream is missing here");
}

#[test]
fn every_scene_matches_its_golden() {
    let mut memory = Memory::take().expect("the only test that takes the scenes' memory");
    let mut report = String::new();
    // SAFETY: a test thread's stack is 2 MiB (Rust's default), of which the test harness's
    // frames above this one use far less than the 1.5 MiB left below the painted 512 KiB.
    let (differ, peak) =
        unsafe { hibi_scenes::stack::measured(512 * 1024, || check(&mut memory, "host", &mut report)) };
    let differ = differ.expect("a String takes every line");
    println!("{report}stack peak {peak} bytes (painted below the scenes' caller)");
    assert_eq!(differ, 0, "golden scenes differ:\n{report}");
}
