//! Random streams that make output independent of the thread count.
//!
//! Every unit of work (a batch of photons, a pixel) gets its own generator derived from
//! `(seed, stream, task)`, so results depend only on which work was done, never on which thread
//! did it or in what order. The derivation hashes the triple with SplitMix64 (Steele, Lea & Flood
//! 2014, "Fast splittable pseudorandom number generators") into the 128-bit state of a PCG64 MCG
//! (O'Neill 2014).

use rand::{Rng as _, SeedableRng};
use rand_pcg::Pcg64Mcg;

/// Named streams, so that two phases never share random numbers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u64)]
pub enum Stream {
    /// Global-map photon batches (the volume map's photons come from this pass too).
    GlobalPhotons = 1,
    /// Caustic-map photon batches.
    CausticPhotons = 2,
    /// Eye samples, one task per pixel (gather rays draw from it as well).
    Eye = 3,
    /// Reserved for gather rays (not drawn from today: they use [`Stream::Eye`]).
    Gather = 4,
    /// Reserved for a volume photon pass (not drawn from today: volume photons come from the global
    /// pass).
    VolumePhotons = 5,
    /// Sensor evaluation.
    Sensor = 7,
    /// Sensor evaluation, a direction's chunks of samples after its first
    /// (`render::sensors::sky_radiance`).
    SensorChunk = 8,
    /// Tests, and seeded procedural content (the fBm permutation).
    Test = 99,
}

/// SplitMix64 finaliser: a bijective 64-bit mixer.
pub fn splitmix64(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// The seed of progressive pass `pass` (0-based) of a run seeded with `seed`: `seed` itself for
/// the first pass (so a one-pass run is the run it always was), and a SplitMix64 hash of
/// (seed, pass) for the others, so every pass draws from streams independent of the others'.
pub fn pass_seed(seed: u64, pass: u32) -> u64 {
    if pass == 0 {
        return seed;
    }
    splitmix64(seed ^ splitmix64(0x5EED_0000_0000_0000 ^ u64::from(pass)))
}

/// A per-task random generator.
#[derive(Clone, Debug)]
pub struct Rng(Pcg64Mcg);

impl Rng {
    /// The generator for `task` of `stream` under `seed`.
    pub fn for_task(seed: u64, stream: Stream, task: u64) -> Self {
        let a = splitmix64(seed ^ splitmix64(stream as u64));
        let b = splitmix64(a ^ splitmix64(task.wrapping_add(0x632B_E59B_D9B4_E019)));
        let c = splitmix64(b ^ 0xD1B5_4A32_D192_ED03);
        let state = ((b as u128) << 64) | (c as u128) | 1;
        Rng(Pcg64Mcg::from_seed(state.to_le_bytes()))
    }

    /// Uniform in [0, 1).
    #[inline]
    pub fn uniform(&mut self) -> f64 {
        self.0.random::<f64>()
    }

    /// Two independent uniforms in [0, 1).
    #[inline]
    pub fn uniform2(&mut self) -> [f64; 2] {
        [self.uniform(), self.uniform()]
    }

    /// Uniform integer in [0, n); `n` must be positive.
    #[inline]
    pub fn below(&mut self, n: u64) -> u64 {
        self.0.random_range(0..n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pass_seeds_keep_the_first_and_differ_after() {
        assert_eq!(pass_seed(7, 0), 7);
        let seeds: std::collections::BTreeSet<u64> = (0..1000).map(|p| pass_seed(7, p)).collect();
        assert_eq!(seeds.len(), 1000);
        assert_ne!(pass_seed(7, 1), pass_seed(8, 1));
    }

    #[test]
    fn streams_and_tasks_differ_and_repeat() {
        let a: Vec<f64> = (0..4).map(|_| Rng::for_task(7, Stream::Eye, 3).uniform()).collect();
        assert!(a.windows(2).all(|w| w[0] == w[1]), "same triple must repeat");
        let mut x = Rng::for_task(7, Stream::Eye, 3);
        let mut y = Rng::for_task(7, Stream::Eye, 4);
        let mut z = Rng::for_task(7, Stream::GlobalPhotons, 3);
        let (x0, y0, z0) = (x.uniform(), y.uniform(), z.uniform());
        assert!(x0 != y0 && x0 != z0 && y0 != z0);
    }

    #[test]
    fn uniform_mean_and_range() {
        let mut r = Rng::for_task(1, Stream::Test, 0);
        let n = 100_000;
        let mut sum = 0.0;
        for _ in 0..n {
            let u = r.uniform();
            assert!((0.0..1.0).contains(&u));
            sum += u;
        }
        // Mean of U(0,1) is 1/2 with standard error 1/sqrt(12 n) = 9.1e-4; allow 5 sigma.
        assert!((sum / n as f64 - 0.5).abs() < 5.0 * (1.0 / (12.0 * n as f64)).sqrt());
    }
}
