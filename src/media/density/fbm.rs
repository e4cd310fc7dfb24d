//! Procedural turbulence: fractional Brownian motion of Perlin's improved gradient noise.
//!
//! d(x) = max(0, base + amplitude · Σ_{o<octaves} gainᵒ · noise(frequency · lacunarityᵒ · x)),
//! with Perlin's 2002 noise ("Improving Noise", SIGGRAPH) on a permutation drawn from `seed`
//! (Musgrave's fBm, in Ebert et al., *Texturing and Modeling*, 3rd ed., ch. 16). |noise| ≤ 1, so
//! base + amplitude·Σ gainᵒ bounds d: the majorant.

use crate::rng::{Rng, Stream};
use glam::DVec3;

/// Fractional Brownian motion of Perlin noise (see the module docs for the formula).
#[derive(Clone, Debug)]
pub struct Fbm {
    /// Offset of the density before clamping at zero.
    pub base: f64,
    /// Amplitude of the noise sum.
    pub amplitude: f64,
    /// Cycles per metre of the first octave.
    pub frequency: f64,
    /// Number of octaves summed.
    pub octaves: u32,
    /// Frequency ratio between consecutive octaves (2).
    pub lacunarity: f64,
    /// Amplitude ratio between consecutive octaves (0.5).
    pub gain: f64,
    perm: [u8; 512],
}

impl Fbm {
    /// fBm with lacunarity 2 and gain 0.5; `frequency` in cycles per metre, `seed` draws the
    /// permutation.
    pub fn new(base: f64, amplitude: f64, frequency: f64, octaves: u32, seed: u64) -> Fbm {
        let mut p: Vec<u8> = (0..=255).collect();
        let mut rng = Rng::for_task(seed, Stream::Test, 0xF8B);
        for i in (1..256).rev() {
            let j = rng.below(i as u64 + 1) as usize;
            p.swap(i, j);
        }
        let mut perm = [0u8; 512];
        for i in 0..512 {
            perm[i] = p[i & 255];
        }
        Fbm { base, amplitude, frequency, octaves, lacunarity: 2.0, gain: 0.5, perm }
    }

    /// d at `x` (m), clamped at 0.
    pub fn at(&self, x: DVec3) -> f64 {
        let mut sum = 0.0;
        let (mut f, mut a) = (self.frequency, 1.0);
        for _ in 0..self.octaves {
            sum += a * self.noise(x * f);
            f *= self.lacunarity;
            a *= self.gain;
        }
        (self.base + self.amplitude * sum).max(0.0)
    }

    /// An upper bound of [`Fbm::at`].
    pub fn bound(&self) -> f64 {
        let amps: f64 = (0..self.octaves).map(|o| self.gain.powi(o as i32)).sum();
        (self.base + self.amplitude.abs() * amps).max(0.0)
    }

    /// Perlin's improved noise in [−1, 1].
    fn noise(&self, p: DVec3) -> f64 {
        let fl = p.floor();
        let (xi, yi, zi) = ((fl.x as i64 & 255) as usize, (fl.y as i64 & 255) as usize, (fl.z as i64 & 255) as usize);
        let f = p - fl;
        let fade = |t: f64| t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
        let (u, v, w) = (fade(f.x), fade(f.y), fade(f.z));
        let pm = &self.perm;
        let a = pm[xi] as usize + yi;
        let (aa, ab) = (pm[a] as usize + zi, pm[a + 1] as usize + zi);
        let b = pm[xi + 1] as usize + yi;
        let (ba, bb) = (pm[b] as usize + zi, pm[b + 1] as usize + zi);
        let g = |h: u8, x: f64, y: f64, z: f64| grad(h, x, y, z);
        let lerp = |t: f64, a: f64, b: f64| a + t * (b - a);
        let (x, y, z) = (f.x, f.y, f.z);
        lerp(
            w,
            lerp(
                v,
                lerp(u, g(pm[aa], x, y, z), g(pm[ba], x - 1.0, y, z)),
                lerp(u, g(pm[ab], x, y - 1.0, z), g(pm[bb], x - 1.0, y - 1.0, z)),
            ),
            lerp(
                v,
                lerp(u, g(pm[aa + 1], x, y, z - 1.0), g(pm[ba + 1], x - 1.0, y, z - 1.0)),
                lerp(u, g(pm[ab + 1], x, y - 1.0, z - 1.0), g(pm[bb + 1], x - 1.0, y - 1.0, z - 1.0)),
            ),
        )
    }
}

/// Dot product with one of Perlin's 12 edge gradients (16 with repeats).
fn grad(hash: u8, x: f64, y: f64, z: f64) -> f64 {
    let h = hash & 15;
    let u = if h < 8 { x } else { y };
    let v = if h < 4 {
        y
    } else if h == 12 || h == 14 {
        x
    } else {
        z
    };
    (if h & 1 == 0 { u } else { -u }) + (if h & 2 == 0 { v } else { -v })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn noise_vanishes_on_the_lattice_and_stays_bounded() {
        let f = Fbm::new(0.5, 0.5, 1.0, 5, 3);
        let mut rng = Rng::for_task(1, Stream::Test, 0);
        for _ in 0..20_000 {
            let p = DVec3::new(rng.uniform(), rng.uniform(), rng.uniform()) * 40.0 - 20.0;
            let n = f.noise(p);
            assert!((-1.0..=1.0).contains(&n), "noise {n} at {p}");
            let d = f.at(p);
            assert!(d >= 0.0 && d <= f.bound() + 1e-12);
        }
        // Gradient noise is zero at lattice points.
        assert_eq!(f.noise(DVec3::new(3.0, -7.0, 11.0)), 0.0);
        // Same seed, same field; another seed, another field.
        let (g, h) = (Fbm::new(0.5, 0.5, 1.0, 5, 3), Fbm::new(0.5, 0.5, 1.0, 5, 4));
        let p = DVec3::new(0.37, 1.91, -2.2);
        assert_eq!(f.at(p), g.at(p));
        assert!(f.at(p) != h.at(p));
    }
}
