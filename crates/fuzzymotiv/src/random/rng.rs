//! The one named, portable random generator and the few samplers built on it.
//!
//! Every random draw in the library goes through [`Rng64`] (xoshiro256++) and the helpers
//! below, which use only `next_u64`, so results depend on nothing but this generator's stream
//! (pinned by value-stability tests). Randomness is always passed in as `&mut R`.

pub use rand_core::{Rng, SeedableRng};

/// The project's generator: xoshiro256++ (portable, fast, 256-bit state).
pub type Rng64 = rand_xoshiro::Xoshiro256PlusPlus;

/// A generator seeded from a 64-bit seed (expanded with SplitMix64).
pub fn rng_from_seed(seed: u64) -> Rng64 {
    Rng64::seed_from_u64(seed)
}

/// A uniform draw from [0, 1) with 53 random bits.
#[inline]
pub fn uniform01<R: Rng + ?Sized>(rng: &mut R) -> f64 {
    (rng.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// A uniform draw from [lo, hi).
#[inline]
pub fn uniform<R: Rng + ?Sized>(rng: &mut R, lo: f64, hi: f64) -> f64 {
    lo + (hi - lo) * uniform01(rng)
}

/// A uniform index in `0..n` (`n > 0`), by Lemire's widening multiply (bias < 2^-64 · n).
#[inline]
pub fn index<R: Rng + ?Sized>(rng: &mut R, n: usize) -> usize {
    debug_assert!(n > 0);
    ((rng.next_u64() as u128 * n as u128) >> 64) as usize
}

/// A standard normal draw N(0, 1) by the Box–Muller transform (one of the pair is used).
#[inline]
pub fn standard_normal<R: Rng + ?Sized>(rng: &mut R) -> f64 {
    // 1 - u is in (0, 1], so the logarithm is finite.
    let u1 = 1.0 - uniform01(rng);
    let u2 = uniform01(rng);
    (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
}

/// Shuffle a slice in place (Fisher–Yates, from the back).
pub fn shuffle<T, R: Rng + ?Sized>(rng: &mut R, items: &mut [T]) {
    for i in (1..items.len()).rev() {
        let j = index(rng, i + 1);
        items.swap(i, j);
    }
}
