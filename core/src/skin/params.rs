//! The six parameters of the skin model (Ishii et al. §4.2, Fig. 11) and their checks.

use crate::enumeration::enumeration;
use crate::rng::Spread;

/// Most hierarchy levels a skin can have.
pub const MAX_LEVELS: usize = 4;
/// Most cubic Bézier segments in one level's cross-section.
pub const MAX_SEGMENTS: usize = 4;
/// Most midpoint-displacement subdivisions of an edge (2^depth pieces).
pub const MAX_PERTURBATION_DEPTH: u32 = 5;

enumeration! {
    /// Parameter 1, the centre-point layout.
    pub enum SiteLayout {
        /// Triangular lattice: rows `spacing·√3/2` apart, every other row shifted by half.
        Triangular,
        /// Square lattice.
        Square,
        /// Uniform random: each centre uniformly placed in its own square of side `spacing` (a
        /// stratified uniform layout, so that every neighbourhood is bounded). The jitter fields
        /// are ignored.
        Random,
    }
    default Triangular
}

/// Parameter 5, a cross-section: cubic Bézier segments in the body plane (x' from the centre
/// point at 0 to the polygon's edge at the last point's x', z' the height). Segment `k` has
/// control points `points[3k..=3k+3]`; consecutive segments share an end point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Profile {
    /// Number of segments, 1..=[`MAX_SEGMENTS`].
    pub segments: u32,
    /// Control points (x', z'); the first `3·segments + 1` are used.
    pub points: [[f32; 2]; 3 * MAX_SEGMENTS + 1],
}

impl Profile {
    /// A profile of one segment.
    pub const fn cubic(p: [[f32; 2]; 4]) -> Profile {
        let mut points = [[0.0; 2]; 3 * MAX_SEGMENTS + 1];
        let mut i = 0;
        while i < 4 {
            points[i] = p[i];
            i += 1;
        }
        Profile { segments: 1, points }
    }

    /// A profile of two segments; `b[0]` must equal `a[3]`.
    pub const fn two(a: [[f32; 2]; 4], b: [[f32; 2]; 4]) -> Profile {
        let mut p = Profile::cubic(a);
        p.points[4] = b[1];
        p.points[5] = b[2];
        p.points[6] = b[3];
        p.segments = 2;
        p
    }

    /// The used control points.
    pub fn used(&self) -> &[[f32; 2]] {
        &self.points[..3 * (self.segments as usize).min(MAX_SEGMENTS) + 1]
    }
}

/// One hierarchy level: its polygons and its cross-section.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LevelParams {
    /// Lattice spacing of the centre points [px, before stretch].
    pub spacing: f32,
    /// Parameter 2, the perturbation ratio A in V = A·2^(−n·h)·Rnd·L (0: straight edges).
    pub perturbation: f32,
    /// h in V = A·2^(−n·h)·Rnd·L, the decay per subdivision.
    pub perturbation_decay: f32,
    /// Subdivisions n = 1..=depth of every edge (each doubles its points).
    pub perturbation_depth: u32,
    /// Parameter 3, the stretch (Sx, Sy): x' = Sx·x, y' = Sy·y on this level's polygons.
    pub stretch: [f32; 2],
    /// Parameter 5, the cross-section.
    pub profile: Profile,
    /// Parameter 6, the roundness ratio: 0 gives polygonal height contours, 1 nearly circular.
    pub roundness: f32,
}

/// Everything that defines a skin: size, seed, layout and the levels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SkinParams {
    /// Width of the surface and of its rasters \[px\].
    pub width: u32,
    /// Height \[px\].
    pub height: u32,
    /// Seed of every random draw.
    pub seed: u64,
    /// Parameter 1: centre-point layout.
    pub layout: SiteLayout,
    /// Parameter 1: jitter of lattice centres, uniform or normal.
    pub jitter: Spread,
    /// Parameter 1: jitter ratio, largest jitter per axis / lattice spacing, in [0, 1].
    pub jitter_ratio: f32,
    /// Tileable: the surface repeats with period (width, height). Each level's lattice then
    /// fits a whole number of spacings into the period, and at least two centre points
    /// across it on each axis (a spacing wider than half the surface shrinks to that).
    pub periodic: bool,
    /// Parameter 4: number of hierarchy levels, 1..=[`MAX_LEVELS`].
    pub levels: u32,
    /// The levels, coarsest first; the first `levels` are used.
    pub level: [LevelParams; MAX_LEVELS],
}

/// The paper's Fig. 13 b profile: steep but smooth.
pub const PROFILE_13B: Profile =
    Profile::two([[0.0, 3.0], [2.0, 3.0], [4.0, 3.0], [7.0, 3.0]], [[7.0, 3.0], [8.0, 3.0], [9.0, 2.5], [10.0, 0.0]]);

impl Default for LevelParams {
    /// A level of 40-pixel cells with the Fig. 13 b profile, straight edges, roundness 0.2.
    fn default() -> Self {
        LevelParams {
            spacing: 40.0,
            perturbation: 0.0,
            perturbation_decay: 1.0,
            perturbation_depth: 3,
            stretch: [1.0, 1.0],
            profile: PROFILE_13B,
            roundness: 0.2,
        }
    }
}

impl Default for SkinParams {
    /// 400 × 400 px (the paper's images), one level, triangular lattice, uniform jitter 0.5;
    /// finer levels (when `levels` is raised) at a third of the spacing each, with one
    /// perturbation subdivision fewer.
    fn default() -> Self {
        let level = LevelParams::default();
        let mut levels = [level; MAX_LEVELS];
        // Each finer level: a third of the spacing, and one subdivision fewer, so that the
        // perturbation's pieces stay about 2 px long at every level.
        for (k, l) in levels.iter_mut().enumerate().skip(1) {
            l.spacing = level.spacing / libm::powf(3.0, k as f32);
            l.perturbation_depth = level.perturbation_depth.saturating_sub(k as u32).max(1);
        }
        SkinParams {
            width: 400,
            height: 400,
            seed: 1,
            layout: SiteLayout::Triangular,
            jitter: Spread::Uniform,
            jitter_ratio: 0.5,
            periodic: false,
            levels: 1,
            level: levels,
        }
    }
}

crate::error::error_list! {
    /// A parameter out of range: the field is named.
    pub enum SkinParamError {
        /// `width` or `height` is 0 or above 32768.
        Size => c"skin: width and height must be in 1..=32768",
        /// `jitter_ratio` is not in [0, 1].
        JitterRatio => c"skin: jitter_ratio must be in [0, 1]",
        /// `levels` is 0 or above [`MAX_LEVELS`].
        Levels => c"skin: levels must be in 1..=4",
        /// A level's `spacing` is not finite and at least 1 px.
        Spacing => c"skin: a level's spacing must be finite and >= 1 px",
        /// A level's `perturbation` or `perturbation_decay` is negative or not finite.
        Perturbation => c"skin: a level's perturbation and perturbation_decay must be finite and >= 0",
        /// A level's `perturbation_depth` is above [`MAX_PERTURBATION_DEPTH`].
        PerturbationDepth => c"skin: a level's perturbation_depth must be <= 5",
        /// A level's `stretch` is not finite and positive, or so small that the level's centre
        /// points across the surface outnumber 2^31.
        Stretch => c"skin: a level's stretch must be finite and > 0, and not so small that its centre points across the surface outnumber 2^31",
        /// A level's profile has 0 or more than [`MAX_SEGMENTS`] segments.
        ProfileSegments => c"skin: a profile must have 1..=4 Bezier segments",
        /// A profile point is not finite, does not start at x' = 0, or its x' decreases (x'(t)
        /// must be monotone), or it ends at x' = 0.
        ProfilePoints => c"skin: profile points must be finite, start at x' = 0, never decrease in x' and end at x' > 0",
        /// A level's `roundness` is not in [0, 1].
        Roundness => c"skin: a level's roundness must be in [0, 1]",
        /// The surface needs more memory than the address space allows.
        Capacity => c"skin: the surface is too large for memory",
    }
}

impl SkinParams {
    /// Checks every field; the first bad one is named.
    pub fn validate(&self) -> Result<(), SkinParamError> {
        use SkinParamError::*;
        let positive = |v: f32| v.is_finite() && v > 0.0;
        if !(1..=32_768).contains(&self.width) || !(1..=32_768).contains(&self.height) {
            return Err(Size);
        }
        if !(0.0..=1.0).contains(&self.jitter_ratio) {
            return Err(JitterRatio);
        }
        if self.levels == 0 || self.levels as usize > MAX_LEVELS {
            return Err(Levels);
        }
        for l in &self.level[..self.levels as usize] {
            if !(l.spacing.is_finite() && l.spacing >= 1.0) {
                return Err(Spacing);
            }
            let non_negative = |v: f32| v.is_finite() && v >= 0.0;
            if !(non_negative(l.perturbation) && non_negative(l.perturbation_decay)) {
                return Err(Perturbation);
            }
            if l.perturbation_depth > MAX_PERTURBATION_DEPTH {
                return Err(PerturbationDepth);
            }
            if !(positive(l.stretch[0]) && positive(l.stretch[1])) {
                return Err(Stretch);
            }
            if l.profile.segments == 0 || l.profile.segments as usize > MAX_SEGMENTS {
                return Err(ProfileSegments);
            }
            let points = l.profile.used();
            let finite = points.iter().all(|p| p[0].is_finite() && p[1].is_finite());
            let monotone = points.windows(2).all(|w| w[1][0] >= w[0][0]);
            if !(finite && monotone && points[0][0] == 0.0 && points[points.len() - 1][0] > 0.0) {
                return Err(ProfilePoints);
            }
            if !(0.0..=1.0).contains(&l.roundness) {
                return Err(Roundness);
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_valid_and_every_bad_field_is_named() {
        assert_eq!(SkinParams::default().validate(), Ok(()));
        type Spoil = fn(&mut SkinParams);
        let cases: [(Spoil, SkinParamError); 11] = [
            (|p| p.width = 40_000, SkinParamError::Size),
            (|p| p.height = 0, SkinParamError::Size),
            (|p| p.jitter_ratio = 1.5, SkinParamError::JitterRatio),
            (|p| p.levels = 5, SkinParamError::Levels),
            (|p| p.level[0].spacing = 0.5, SkinParamError::Spacing),
            (|p| p.level[0].perturbation = -0.1, SkinParamError::Perturbation),
            (|p| p.level[0].perturbation_depth = 6, SkinParamError::PerturbationDepth),
            (|p| p.level[0].stretch = [1.0, f32::INFINITY], SkinParamError::Stretch),
            (|p| p.level[0].profile.segments = 5, SkinParamError::ProfileSegments),
            (|p| p.level[0].profile.points[2][0] = 1.0, SkinParamError::ProfilePoints),
            (|p| p.level[0].roundness = -0.5, SkinParamError::Roundness),
        ];
        for (spoil, expected) in cases {
            let mut p = SkinParams::default();
            spoil(&mut p);
            assert_eq!(p.validate(), Err(expected));
        }
        // Levels beyond `levels` are not checked.
        let mut p = SkinParams::default();
        p.level[1].spacing = f32::NAN;
        assert_eq!(p.validate(), Ok(()));
        p.levels = 2;
        assert_eq!(p.validate(), Err(SkinParamError::Spacing));
    }
}
