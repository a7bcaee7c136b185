//! The deterministic random source.
//!
//! Every random decision in hibi comes from a [`Rng`]: Xoshiro128++ (from `rand_xoshiro`)
//! seeded from one `u64` run seed through SplitMix64. Each *purpose* (break strengths, speeds,
//! jitter, ...) draws from its own [`Stream`], so adding a feature that draws more numbers
//! for one purpose never reshuffles the decisions of another.
//!
//! The distributions are written here, from bits, so that they are the same on every
//! platform: uniform `f32`/`f64` from the top bits of the generator, the standard normal by
//! Marsaglia's polar method over `libm`, Poisson by Knuth's product method applied to
//! small-mean pieces up to a mean of [`POISSON_PIECES_MAX_MEAN`] and by Hörmann's transformed
//! rejection (PTRS) above it, up to [`POISSON_MAX_MEAN`], and the papers' `Rand(x)`.

use crate::enumeration::enumeration;
use rand_core::{Rng as _, SeedableRng};
use rand_xoshiro::Xoshiro128PlusPlus;

enumeration! {
    /// The purposes that draw random numbers, each with its own independent stream.
    ///
    /// The discriminants are part of the determinism contract: never renumber a variant.
    pub enum Stream {
        /// Model A: per-spring break stretch κ_i = κ̄ + σ/√A_i·N(0,1).
        BreakStretch = 1,
        /// Model A: node jitter of the irregular lattice.
        LatticeJitter = 2,
        /// Model B: the number of radial cracks, M = Poisson_Rand(M_ave).
        RadialCount = 16,
        /// Model B: crack speeds V1, V2, V3 (`Rand`).
        CrackSpeed = 17,
        /// Model B: ring radii d_i = Rand(d_ave).
        RingRadius = 18,
        /// Model B: the direction of the random force F3.
        RandomForce = 19,
        /// Model B: the rotation of the star of radial cracks and of the ring start points.
        ImpactRotation = 20,
        /// Model C: site positions (uniform random layout).
        SiteLayout = 32,
        /// Model C: site jitter on lattice layouts.
        SiteJitter = 33,
        /// Model C: midpoint displacement of cell edges (keyed further by the edge).
        EdgePerturbation = 34,
    }
}

impl Stream {
    /// The stream's key, as [`Rng::from_key`] takes it.
    pub const fn key(self) -> u64 {
        self as u64
    }
}

enumeration! {
    /// The shape of the papers' `Rand(x)`.
    pub enum Spread {
        /// Uniform over [(1 − z)·x, (1 + z)·x].
        Uniform,
        /// Normal with mean x and standard deviation z·x/3, redrawn until it falls within
        /// [(1 − z)·x, (1 + z)·x] (so ±3σ spans the paper's range).
        Normal,
    }
}

/// Largest mean [`Rng::poisson`] accepts.
pub const POISSON_MAX_MEAN: f64 = 1.0e6;

/// Up to this mean [`Rng::poisson`] sums Knuth draws of small-mean pieces (a cost in
/// proportion to the mean: about 1.1 uniform draws per unit of mean); above it, one
/// transformed rejection (a few uniform draws, whatever the mean). Glass's radial counts
/// (`radial_mean` ≤ 10 000) always take the first way.
pub const POISSON_PIECES_MAX_MEAN: f64 = 1.0e4;

/// The transformed rejection's tries before it gives up and returns the mean rounded down:
/// each try is accepted with probability above 0.9, so that happens with probability below
/// 10⁻²⁵⁶ (never, in practice), and a call's time stays bounded.
const PTRS_TRIES: u32 = 256;

/// Knuth's product method stays exact in `f64` for means up to about 700 (exp(−λ) must not
/// underflow); pieces of this mean keep every product far from the bottom of `f64`'s range.
const POISSON_PIECE: f64 = 8.0;

/// What a random draw can refuse.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum RngError {
    /// The Poisson mean is negative, not finite, or above [`POISSON_MAX_MEAN`].
    PoissonMean,
    /// `Rand(x)`: `z` is outside [0, 1) or `x` is not finite.
    RandArgument,
}

impl RngError {
    /// A message naming what is wrong, NUL-terminated for C.
    pub const fn message(self) -> &'static core::ffi::CStr {
        match self {
            RngError::PoissonMean => c"poisson mean must be finite and within [0, 1e6]",
            RngError::RandArgument => c"Rand(x): x must be finite, z within [0, 1), and (1 + z) * |x| at most FLT_MAX",
        }
    }
}

impl core::fmt::Display for RngError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(self.message().to_str().unwrap_or("rng error"))
    }
}

impl core::error::Error for RngError {}

/// A deterministic random stream: Xoshiro128++ seeded through SplitMix64.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Rng {
    generator: Xoshiro128PlusPlus,
}

/// SplitMix64's increment of its state per output.
const SPLITMIX64_GAMMA: u64 = 0x9E37_79B9_7F4A_7C15;

/// The SplitMix64 finaliser: a bijective mix of a 64-bit key.
const fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// log k! for a whole k ≥ 0: exact sums below 10, Stirling's series above,
/// log k! = (k + ½)·log(k + 1) − (k + 1) + ½·log 2π + 1/(12(k + 1)) − 1/(360(k + 1)³) + 1/(1260(k + 1)⁵),
/// whose next term is below 10⁻¹⁰ there (our own series: libm's `lgamma` would add kilobytes of
/// tables to a 256 KiB part).
fn log_factorial(k: f64) -> f64 {
    if k < 10.0 {
        let mut sum = 0.0;
        let mut i = 2.0;
        while i <= k {
            sum += libm::log(i);
            i += 1.0;
        }
        return sum;
    }
    let n = k + 1.0;
    let inv = 1.0 / n;
    let inv2 = inv * inv;
    (n - 0.5) * libm::log(n) - n + 0.918_938_533_204_672_8 + inv * (1.0 / 12.0 - inv2 * (1.0 / 360.0 - inv2 / 1260.0))
}

impl Rng {
    /// The stream for `purpose` of the run seeded with `seed`.
    pub fn new(seed: u64, purpose: Stream) -> Self {
        Self::from_key(seed, purpose.key())
    }

    /// The stream with an arbitrary 64-bit key, for keys derived from data (an edge's
    /// identity, a cell's index) or chosen by a C caller. Xoshiro128++ is seeded by SplitMix64
    /// from `seed ^ mix64(key)`.
    pub fn from_key(seed: u64, key: u64) -> Self {
        // `Xoshiro128PlusPlus::seed_from_u64`, written out: the first two outputs of SplitMix64
        // from that state (whose output function is `mix64`), little-endian, as the seed.
        let state = seed ^ mix64(key);
        let mut bytes = [0u8; 16];
        for (k, chunk) in bytes.chunks_exact_mut(8).enumerate() {
            let x = state.wrapping_add(SPLITMIX64_GAMMA.wrapping_mul(k as u64 + 1));
            chunk.copy_from_slice(&mix64(x).to_le_bytes());
        }
        Rng { generator: Xoshiro128PlusPlus::from_seed(bytes) }
    }

    /// The next 32 raw bits.
    pub fn next_u32(&mut self) -> u32 {
        self.generator.next_u32()
    }

    /// Uniform in [0, 1) with 24 random bits (every representable multiple of 2⁻²⁴).
    pub fn uniform_f32(&mut self) -> f32 {
        (self.next_u32() >> 8) as f32 * (1.0 / 16_777_216.0)
    }

    /// Uniform in [0, 1) with 53 random bits, from two 32-bit outputs (high word first).
    pub fn uniform_f64(&mut self) -> f64 {
        let high = u64::from(self.next_u32());
        let low = u64::from(self.next_u32());
        (((high << 32) | low) >> 11) as f64 * (1.0 / 9_007_199_254_740_992.0)
    }

    /// Uniform in [`low`, `high`).
    pub fn uniform_range(&mut self, low: f32, high: f32) -> f32 {
        low + (high - low) * self.uniform_f32()
    }

    /// A standard normal draw (mean 0, variance 1), Marsaglia's polar method in `f64`: the
    /// first of [`Rng::normal_pair`].
    pub fn normal(&mut self) -> f64 {
        self.normal_pair()[0]
    }

    /// Two independent standard normal draws: both values one step of Marsaglia's polar
    /// method makes (a point (u, v) uniform in the unit disc, s = u² + v², and (u, v) times
    /// √(−2 ln s / s)), in `f64`.
    pub fn normal_pair(&mut self) -> [f64; 2] {
        loop {
            let u = 2.0 * self.uniform_f64() - 1.0;
            let v = 2.0 * self.uniform_f64() - 1.0;
            let s = u * u + v * v;
            if s > 0.0 && s < 1.0 {
                let scale = crate::scalar::sqrt(-2.0 * libm::log(s) / s);
                return [u * scale, v * scale];
            }
        }
    }

    /// A standard normal draw as `f32`.
    pub fn normal_f32(&mut self) -> f32 {
        self.normal() as f32
    }

    /// A Poisson draw with the given mean (the paper's `Poisson_Rand`).
    ///
    /// Exact: up to [`POISSON_PIECES_MAX_MEAN`], a Poisson variable of mean λ is the sum of
    /// independent Poisson variables whose means add up to λ, so λ is cut into pieces of mean
    /// ≤ 8, each drawn by Knuth's product method (count the uniforms whose running product
    /// stays above e^(−piece)); above it, by transformed rejection (PTRS), a few uniform draws
    /// whatever the mean, so a call's time is bounded (at most 10 000 pieces' worth).
    pub fn poisson(&mut self, mean: f64) -> Result<u32, RngError> {
        if !mean.is_finite() || !(0.0..=POISSON_MAX_MEAN).contains(&mean) {
            return Err(RngError::PoissonMean);
        }
        if mean > POISSON_PIECES_MAX_MEAN {
            return Ok(self.poisson_ptrs(mean));
        }
        let full_pieces = libm::floor(mean / POISSON_PIECE) as u32;
        let rest = mean - f64::from(full_pieces) * POISSON_PIECE;
        let full_limit = libm::exp(-POISSON_PIECE);
        let mut count = 0u32;
        for _ in 0..full_pieces {
            count += self.poisson_knuth(full_limit);
        }
        if rest > 0.0 {
            count += self.poisson_knuth(libm::exp(-rest));
        }
        Ok(count)
    }

    /// Knuth's method for a small mean λ, given `limit` = e^(−λ).
    /// A Poisson draw by W. Hörmann's transformed rejection with squeeze, PTRS ("The
    /// transformed rejection method for generating Poisson random variables", Insurance:
    /// Mathematics and Economics 12, 1993), exact for a mean of 10 or more: a candidate
    /// k = ⌊(2a/u_s + b)·U + μ + 0.43⌋ from U uniform in [−½, ½), accepted outright in the
    /// squeeze (u_s ≥ 0.07, V ≤ v_r), else when log(V·α/(a/u_s² + b)) ≤ −μ + k·log μ − log k!.
    fn poisson_ptrs(&mut self, mean: f64) -> u32 {
        let smu = crate::scalar::sqrt(mean);
        let b = 0.931 + 2.53 * smu;
        let a = -0.059 + 0.02483 * b;
        let inv_alpha = 1.1239 + 1.1328 / (b - 3.4);
        let v_r = 0.9277 - 3.6224 / (b - 2.0);
        let log_mean = libm::log(mean);
        for _ in 0..PTRS_TRIES {
            let u = self.uniform_f64() - 0.5;
            // V in (0, 1]: its logarithm is finite.
            let v = 1.0 - self.uniform_f64();
            let us = 0.5 - libm::fabs(u);
            let k = libm::floor((2.0 * a / us + b) * u + mean + 0.43);
            if us >= 0.07 && v <= v_r {
                return k as u32;
            }
            if k < 0.0 || (us < 0.013 && v > us) {
                continue;
            }
            let accept = libm::log(v) + libm::log(inv_alpha) - libm::log(a / (us * us) + b);
            if accept <= -mean + k * log_mean - log_factorial(k) {
                return k as u32;
            }
        }
        libm::floor(mean) as u32
    }

    fn poisson_knuth(&mut self, limit: f64) -> u32 {
        let mut product = 1.0;
        let mut count = 0u32;
        loop {
            product *= self.uniform_f64();
            if product <= limit {
                return count;
            }
            count += 1;
        }
    }

    /// The papers' `Rand(x)`: a value within [(1 − z)·x, (1 + z)·x], uniform or normal
    /// (Agui et al. §4.1; see [`Spread`]).
    pub fn rand(&mut self, x: f32, z: f32, spread: Spread) -> Result<f32, RngError> {
        if !x.is_finite() || !(0.0..1.0).contains(&z) {
            return Err(RngError::RandArgument);
        }
        let (x, z) = (f64::from(x), f64::from(z));
        // The range's far end must be an `f32`: (1 + z)·x past `f32::MAX` would draw infinity.
        if (1.0 + z) * x.abs() > f64::from(f32::MAX) {
            return Err(RngError::RandArgument);
        }
        let value = match spread {
            Spread::Uniform => x * (1.0 - z + 2.0 * z * self.uniform_f64()),
            Spread::Normal => loop {
                let offset = self.normal() / 3.0;
                if (-1.0..=1.0).contains(&offset) {
                    break x * (1.0 + z * offset);
                }
            },
        };
        Ok(value as f32)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_keyed_stream_is_seeded_as_seed_from_u64_seeds_it() {
        // `from_key` writes out SplitMix64's seeding: the same generator for any seed and key.
        let mut x = 0x0123_4567_89AB_CDEFu64;
        for k in 0..20_000u64 {
            x = mix64(x ^ k);
            let (seed, key) = (x, x.rotate_left(29) ^ k);
            let expected = Xoshiro128PlusPlus::seed_from_u64(seed ^ mix64(key));
            assert_eq!(Rng::from_key(seed, key).generator, expected, "seed {seed:#x}, key {key:#x}");
        }
        // (State 0 included: `from_seed` takes the all-zero seed's fallback either way.)
        assert_eq!(Rng::from_key(mix64(0), 0).generator, Xoshiro128PlusPlus::seed_from_u64(0));
    }

    /// Mean and variance of `n` draws, by Welford's method.
    fn moments(n: u32, mut draw: impl FnMut() -> f64) -> (f64, f64) {
        let (mut mean, mut m2) = (0.0, 0.0);
        for i in 1..=n {
            let x = draw();
            let delta = x - mean;
            mean += delta / f64::from(i);
            m2 += delta * (x - mean);
        }
        (mean, m2 / f64::from(n - 1))
    }

    /// The sample mean is within 4 standard errors of `mean`, and the sample variance within
    /// 4 standard errors of `variance` (its standard error from the fourth central moment
    /// `mu4`: Var(s²) ≈ (μ4 − σ⁴)/n).
    fn assert_moments(n: u32, sample: (f64, f64), mean: f64, variance: f64, mu4: f64) {
        let n = f64::from(n);
        let mean_se = crate::scalar::sqrt(variance / n);
        let var_se = crate::scalar::sqrt((mu4 - variance * variance) / n);
        assert!((sample.0 - mean).abs() < 4.0 * mean_se, "mean {} vs {mean} (se {mean_se})", sample.0);
        assert!((sample.1 - variance).abs() < 4.0 * var_se, "variance {} vs {variance} (se {var_se})", sample.1);
    }

    const DRAWS: u32 = 100_000;

    #[test]
    fn streams_are_distinct_and_repeatable() {
        let first: [u32; 10] = Stream::ALL.map(|s| Rng::new(7, s).next_u32());
        for (i, a) in first.iter().enumerate() {
            for b in &first[i + 1..] {
                assert_ne!(a, b);
            }
        }
        assert_eq!(first, Stream::ALL.map(|s| Rng::new(7, s).next_u32()));
        assert_ne!(Rng::new(7, Stream::CrackSpeed), Rng::new(8, Stream::CrackSpeed));
    }

    #[test]
    fn uniform_f32_is_in_unit_interval_with_right_moments() {
        let mut rng = Rng::new(1, Stream::SiteLayout);
        let sample = moments(DRAWS, || {
            let u = rng.uniform_f32();
            assert!((0.0..1.0).contains(&u));
            f64::from(u)
        });
        assert_moments(DRAWS, sample, 0.5, 1.0 / 12.0, 1.0 / 80.0);
    }

    #[test]
    fn uniform_f64_has_right_moments() {
        let mut rng = Rng::new(2, Stream::SiteLayout);
        let sample = moments(DRAWS, || rng.uniform_f64());
        assert_moments(DRAWS, sample, 0.5, 1.0 / 12.0, 1.0 / 80.0);
    }

    #[test]
    fn normal_has_mean_zero_variance_one() {
        let mut rng = Rng::new(3, Stream::BreakStretch);
        let sample = moments(DRAWS, || rng.normal());
        assert_moments(DRAWS, sample, 0.0, 1.0, 3.0);
    }

    #[test]
    fn both_values_of_a_normal_pair_are_standard_and_uncorrelated() {
        let mut rng = Rng::new(3, Stream::EdgePerturbation);
        let second = moments(DRAWS, || rng.normal_pair()[1]);
        assert_moments(DRAWS, second, 0.0, 1.0, 3.0);
        // The product of independent standard normals has mean 0, variance 1 and fourth
        // moment 9.
        let product = moments(DRAWS, || {
            let [x, y] = rng.normal_pair();
            x * y
        });
        assert_moments(DRAWS, product, 0.0, 1.0, 9.0);
        // `normal` is the first value of the pair the same stream would make.
        let (mut a, mut b) = (Rng::new(9, Stream::BreakStretch), Rng::new(9, Stream::BreakStretch));
        for _ in 0..100 {
            assert_eq!(a.normal().to_bits(), b.normal_pair()[0].to_bits());
        }
    }

    #[test]
    fn poisson_variance_matches_mean() {
        for mean in [5.0, 100.0, 2000.0] {
            let mut rng = Rng::new(4, Stream::RadialCount);
            let sample = moments(DRAWS, || f64::from(rng.poisson(mean).unwrap()));
            // Poisson: variance λ, fourth central moment λ(1 + 3λ).
            assert_moments(DRAWS, sample, mean, mean, mean * (1.0 + 3.0 * mean));
        }
    }

    #[test]
    fn poisson_at_ten_thousand_is_exact_in_mean_and_variance() {
        let mean = 10_000.0;
        let n = 4_000;
        let mut rng = Rng::new(5, Stream::RadialCount);
        let sample = moments(n, || f64::from(rng.poisson(mean).unwrap()));
        assert_moments(n, sample, mean, mean, mean * (1.0 + 3.0 * mean));
    }

    #[test]
    fn poisson_above_ten_thousand_is_exact_in_mean_and_variance() {
        for mean in [10_000.5, 1e5, POISSON_MAX_MEAN] {
            let n = 20_000;
            let mut rng = Rng::new(5, Stream::RadialCount);
            let sample = moments(n, || f64::from(rng.poisson(mean).unwrap()));
            assert_moments(n, sample, mean, mean, mean * (1.0 + 3.0 * mean));
        }
    }

    /// The transformed rejection against the exact distribution: at a mean of 30 (it is exact
    /// from 10 up), a chi-square test over the values with an expected count of at least 50.
    #[test]
    fn transformed_rejection_matches_the_poisson_probabilities() {
        let (mean, n) = (30.0f64, 200_000u32);
        let mut rng = Rng::new(7, Stream::RadialCount);
        let mut counts = [0u32; 80];
        for _ in 0..n {
            counts[(rng.poisson_ptrs(mean) as usize).min(79)] += 1;
        }
        let (mut chi2, mut bins, mut p) = (0.0, 0, libm::exp(-mean));
        for (k, &seen) in counts.iter().enumerate().take(79) {
            if k > 0 {
                p *= mean / k as f64;
            }
            let expected = p * f64::from(n);
            if expected >= 50.0 {
                chi2 += (f64::from(seen) - expected).powi(2) / expected;
                bins += 1;
            }
        }
        // About 37 bins: the 0.999 quantile of chi-square with 36 degrees of freedom is 67.98.
        assert!(bins > 30, "{bins} bins");
        assert!(chi2 < 68.0, "chi-square {chi2:.1} over {bins} bins");
    }

    /// A draw's work does not grow with the mean: a Poisson draw of mean 1e6 takes the stream
    /// a few words on, where the pieces would take over a million.
    #[test]
    fn a_large_poisson_draw_takes_a_bounded_number_of_words() {
        for seed in 0..50 {
            let mut drawn = Rng::new(seed, Stream::RadialCount);
            drawn.poisson(POISSON_MAX_MEAN).unwrap();
            let next = drawn.next_u32();
            let mut walker = Rng::new(seed, Stream::RadialCount);
            let words = (0..=4 * PTRS_TRIES).find(|_| walker.next_u32() == next);
            // Each try reads four words (two f64); the first tries almost always accept.
            assert!(words.is_some_and(|w| w <= 4 * PTRS_TRIES), "seed {seed}: {words:?}");
        }
    }

    #[test]
    fn log_factorial_matches_the_sum_of_logarithms() {
        let mut sum = 0.0f64;
        for k in 0..2000u32 {
            if k > 1 {
                sum += libm::log(f64::from(k));
            }
            let got = log_factorial(f64::from(k));
            assert!((got - sum).abs() <= 1e-9 * sum.max(1.0), "log {k}! = {sum}, series {got}");
        }
    }

    #[test]
    fn poisson_edges() {
        let mut rng = Rng::new(6, Stream::RadialCount);
        assert_eq!(rng.poisson(0.0), Ok(0));
        for bad in [-1.0, f64::NAN, f64::INFINITY, POISSON_MAX_MEAN * 2.0] {
            assert_eq!(rng.poisson(bad), Err(RngError::PoissonMean));
        }
    }

    #[test]
    fn rand_stays_within_its_range_with_the_stated_moments() {
        let (x, z) = (40.0f32, 0.3f32);
        for spread in [Spread::Uniform, Spread::Normal] {
            let mut rng = Rng::new(9, Stream::CrackSpeed);
            let sample = moments(DRAWS, || {
                let v = rng.rand(x, z, spread).unwrap();
                assert!((28.0..=52.0).contains(&v), "{v}");
                f64::from(v)
            });
            let half = f64::from(x * z);
            let (variance, mu4) = match spread {
                Spread::Uniform => (half * half / 3.0, half.powi(4) / 5.0),
                // Normal with σ = half/3, truncated at ±3σ: variance factor 0.97333,
                // fourth moment factor 2.6800 (of σ², σ⁴).
                Spread::Normal => {
                    let s2 = (half / 3.0) * (half / 3.0);
                    (0.973_33 * s2, 2.680_0 * s2 * s2)
                }
            };
            assert_moments(DRAWS, sample, f64::from(x), variance, mu4);
        }
        let mut rng = Rng::new(9, Stream::CrackSpeed);
        assert_eq!(rng.rand(1.0, 1.0, Spread::Uniform), Err(RngError::RandArgument));
        assert_eq!(rng.rand(1.0, -0.1, Spread::Normal), Err(RngError::RandArgument));
        assert_eq!(rng.rand(f32::NAN, 0.3, Spread::Normal), Err(RngError::RandArgument));
        // Finite arguments whose range reaches past f32::MAX: refused, not drawn as infinity.
        assert_eq!(rng.rand(f32::MAX, 0.9, Spread::Uniform), Err(RngError::RandArgument));
        assert_eq!(rng.rand(-f32::MAX, 0.5, Spread::Normal), Err(RngError::RandArgument));
        assert!(rng.rand(f32::MAX, 0.0, Spread::Uniform).is_ok_and(f32::is_finite));
        assert!(rng.rand(f32::MAX / 2.0, 0.9, Spread::Uniform).is_ok_and(f32::is_finite));
    }
}
