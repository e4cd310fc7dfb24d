//! Schlick's phase function (Blasi, Le Saëc & Schlick 1993), a cheap stand-in for
//! Henyey–Greenstein:
//!
//! p(μ) = (1 − k²) / (4π (1 − kμ)²),  μ = cos θ,  −1 < k < 1.
//!
//! With this module's convention (μ = 1 is forward), k > 0 scatters forward. Sources that
//! measure θ between one direction and the reverse of the other write (1 + k cos θ)².
//!
//! k from g: k = 1.55 g − 0.55 g³ (Pharr & Humphreys 2004; Jensen 2001), which makes the shape
//! close to HG(g). It gives |k| < 1 only for |g| < 0.93812 (the root of 0.55g² + 0.55g = 1);
//! beyond that k ≥ 1 and the density is not normalisable, so [`Schlick::from_g`] refuses it.
//!
//! Mean cosine (integrating μ p over the sphere):
//! ⟨μ⟩ = 1/k − (1 − k²) artanh(k) / k², with the series Σₙ 2k^{2n+1}/((2n+1)(2n+3)) =
//! 2k/3 + 2k³/15 + … for small |k|. It is close to, but not exactly, the g that k came from.
//!
//! Sampling by inversion of F(μ) = (1 − k²)/(2k) [1/(1 − kμ) − 1/(1 + k)]:
//! μ = (ξ + k) / (1 + kξ) with ξ = 2u − 1 (exact, no division by k).
//!
//! # References
//! - Blasi, Le Saëc & Schlick, "A rendering algorithm for discrete volume density objects",
//!   Computer Graphics Forum 12(3) (Eurographics 1993), 201–210.
//! - Pharr & Humphreys, *Physically Based Rendering*, 1st ed. (2004), §15.2 (k = 1.55g − 0.55g³).
//! - Jensen, *Realistic Image Synthesis Using Photon Mapping* (2001), §10.1.

use super::check_open_unit;
use std::f64::consts::PI;

/// Schlick's phase function with shape parameter k.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Schlick {
    k: f64,
}

impl Schlick {
    /// `k` must lie strictly between −1 and 1.
    pub fn new(k: f64) -> Result<Schlick, String> {
        check_open_unit("Schlick k", k)?;
        Ok(Schlick { k })
    }

    /// The Schlick function approximating HG(g): k = 1.55 g − 0.55 g³, defined for
    /// |g| < 0.93812 (where |k| < 1).
    pub fn from_g(g: f64) -> Result<Schlick, String> {
        check_open_unit("Schlick g", g)?;
        let k = 1.55 * g - 0.55 * g * g * g;
        Schlick::new(k).map_err(|_| {
            format!(
                "Schlick g = {g} gives k = 1.55g − 0.55g³ = {k:.6}, outside (−1, 1): \
                 g must lie strictly between −0.93812 and 0.93812 (use Henyey–Greenstein, or give k directly)"
            )
        })
    }

    /// The shape parameter k, −1 < k < 1.
    pub fn k(&self) -> f64 {
        self.k
    }

    /// p(cos θ), sr⁻¹.
    pub fn eval(&self, cos_theta: f64) -> f64 {
        let k = self.k;
        let d = (1.0 - k) + k * (1.0 - cos_theta);
        (1.0 - k * k) / (4.0 * PI * d * d)
    }

    /// μ = (ξ + k)/(1 + kξ), ξ = 2u − 1.
    pub fn sample_cos_theta(&self, u0: f64) -> f64 {
        let xi = 2.0 * u0 - 1.0;
        ((xi + self.k) / (1.0 + self.k * xi)).clamp(-1.0, 1.0)
    }

    /// ⟨μ⟩ = 1/k − (1 − k²) artanh(k)/k² (series for |k| < 0.1).
    pub fn mean_cosine(&self) -> f64 {
        let k = self.k;
        if k.abs() < 0.1 {
            return (0..12)
                .map(|n| {
                    let m = (2 * n + 1) as f64;
                    2.0 * k.powi(2 * n + 1) / (m * (m + 2.0))
                })
                .sum();
        }
        1.0 / k - (1.0 - k * k) * k.atanh() / (k * k)
    }
}
