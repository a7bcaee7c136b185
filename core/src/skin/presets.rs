//! The paper's Table 1 settings (Ishii et al. §5, Fig. 13–19) as named presets, in our best
//! reading of the table's scan, which lost its decimal points (`docs/src/models/papers.md`, Model C).
//! Every row uses a triangular lattice with uniform jitter, stretch (1, 1), no perturbation,
//! jitter 0.5 and roundness 0.2 unless it says otherwise. The spacing is ours (the paper does
//! not print it): 40 px at level 1 on the paper's 400 × 400 images, a third of that at each
//! finer level.

use super::params::{LevelParams, MAX_LEVELS, PROFILE_13B, Profile, SkinParams};

/// Every preset name, in figure order.
pub const PRESETS: [&str; 23] = [
    "fig13a", "fig13b", "fig13c", "fig14a", "fig14b", "fig14c", "fig15a", "fig15b", "fig15c", "fig16a", "fig16b",
    "fig17a", "fig17b", "fig17c", "fig18a", "fig18b", "fig18c", "fig19a", "fig19b", "fig19c", "fig19d", "fig19e",
    "fig19f",
];

/// Fig. 13 a: two segments with a kink.
const PROFILE_13A: Profile =
    Profile::two([[0.0, 3.0], [2.0, 3.0], [4.0, 3.0], [8.0, 3.0]], [[8.0, 3.0], [9.0, 1.5], [9.75, 1.0], [10.0, 0.0]]);
/// Fig. 13 c: one gentle segment.
const PROFILE_13C: Profile = Profile::cubic([[0.0, 3.0], [5.0, 3.0], [8.0, 2.5], [10.0, 0.0]]);
/// Fig. 18: the three levels' profiles.
const PROFILES_18: [Profile; 3] = [
    Profile::cubic([[0.0, 3.0], [5.0, 3.0], [7.0, 2.0], [10.0, 0.0]]),
    Profile::cubic([[0.0, 0.5], [5.0, 0.5], [7.0, 0.3], [10.0, 0.0]]),
    Profile::cubic([[0.0, 0.1], [5.0, 0.1], [7.0, 0.07], [10.0, 0.0]]),
];
/// Fig. 19 a–c: the three levels' profiles.
const PROFILES_19: [Profile; 3] = [
    Profile::cubic([[0.0, 4.0], [5.0, 4.0], [9.0, 3.0], [10.0, 0.0]]),
    Profile::cubic([[0.0, 2.0], [5.0, 2.0], [9.0, 1.5], [10.0, 0.0]]),
    Profile::cubic([[0.0, 0.8], [5.0, 0.8], [9.0, 0.4], [10.0, 0.0]]),
];
/// Fig. 19 d–f: the three levels' profiles.
const PROFILES_19_WRIST: [Profile; 3] = [
    Profile::cubic([[0.0, 8.0], [5.0, 8.0], [9.0, 4.0], [10.0, 0.0]]),
    Profile::cubic([[0.0, 4.0], [5.0, 4.0], [9.0, 3.0], [10.0, 0.0]]),
    Profile::cubic([[0.0, 1.0], [5.0, 1.0], [9.0, 0.7], [10.0, 0.0]]),
];

/// `levels` levels with these profiles, perturbation `a` and stretch `s` on every level.
fn hierarchy(profiles: [Profile; 3], levels: u32, a: f32, s: [f32; 2]) -> SkinParams {
    let mut p = SkinParams { levels, ..SkinParams::default() };
    for (l, profile) in profiles.iter().enumerate() {
        p.level[l] = LevelParams { profile: *profile, perturbation: a, stretch: s, ..p.level[l] };
    }
    p
}

/// The preset of that name (see [`PRESETS`]), or None.
pub fn preset(name: &str) -> Option<SkinParams> {
    let one = |profile: Profile| {
        let mut p = SkinParams::default();
        p.level[0].profile = profile;
        p
    };
    let with = |f: &dyn Fn(&mut SkinParams)| {
        let mut p = one(PROFILE_13B);
        f(&mut p);
        p
    };
    let wrist = |sx: f32| {
        let mut p = hierarchy(PROFILES_19_WRIST, 3, 0.1, [1.0, 1.0]);
        p.level[0].stretch = [sx, 1.0];
        p
    };
    let p = match name {
        "fig13a" => one(PROFILE_13A),
        "fig13b" => one(PROFILE_13B),
        "fig13c" => one(PROFILE_13C),
        "fig14a" => with(&|p| (p.jitter_ratio, p.level[0].roundness) = (0.0, 0.0)),
        "fig14b" => with(&|p| (p.jitter_ratio, p.level[0].roundness) = (0.0, 0.4)),
        "fig14c" => with(&|p| (p.jitter_ratio, p.level[0].roundness) = (0.0, 1.0)),
        "fig15a" => with(&|p| p.jitter_ratio = 0.0),
        "fig15b" => with(&|p| p.jitter_ratio = 0.4),
        "fig15c" => with(&|p| p.jitter_ratio = 1.0),
        "fig16a" => with(&|p| p.level[0].perturbation = 0.0),
        "fig16b" => with(&|p| p.level[0].perturbation = 0.1),
        "fig17a" => with(&|p| p.level[0].stretch = [1.0, 1.0]),
        "fig17b" => with(&|p| p.level[0].stretch = [1.0, 3.0]),
        "fig17c" => with(&|p| p.level[0].stretch = [3.0, 1.0]),
        "fig18a" => hierarchy(PROFILES_18, 1, 0.0, [1.0, 1.0]),
        "fig18b" => hierarchy(PROFILES_18, 2, 0.0, [1.0, 1.0]),
        "fig18c" => hierarchy(PROFILES_18, 3, 0.0, [1.0, 1.0]),
        "fig19a" => hierarchy(PROFILES_19, 3, 0.1, [1.0, 1.0]),
        "fig19b" => hierarchy(PROFILES_19, 3, 0.1, [1.0, 3.0]),
        "fig19c" => hierarchy(PROFILES_19, 3, 0.1, [3.0, 1.0]),
        "fig19d" => wrist(20.0),
        "fig19e" => wrist(15.0),
        "fig19f" => wrist(5.0),
        _ => return None,
    };
    debug_assert!(p.levels as usize <= MAX_LEVELS);
    Some(p)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_table_1_setting_is_valid_and_other_names_none() {
        for name in PRESETS {
            assert_eq!(preset(name).map(|p| p.validate()), Some(Ok(())), "{name}");
        }
        assert_eq!(preset("fig20"), None);
        assert_eq!(preset("fig19a").map(|p| p.levels), Some(3));
        assert_eq!(preset("fig19d").map(|p| (p.level[0].stretch, p.level[1].stretch)), Some(([20.0, 1.0], [1.0, 1.0])));
    }
}
