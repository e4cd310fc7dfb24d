//! Isotropic scattering: every direction equally likely, p = 1/(4π).
//!
//! Sampling: μ = cos θ is uniform on [−1, 1], μ = 2u − 1 (an area-preserving map of the sphere,
//! Archimedes' hat-box theorem).
//!
//! # References
//! - Pharr, Jakob & Humphreys, *Physically Based Rendering*, 4th ed. (2023), §A.5.2.

use std::f64::consts::PI;

/// Isotropic scattering.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Isotropic;

impl Isotropic {
    /// p(μ) = 1/(4π) for every μ.
    pub fn eval(&self, _cos_theta: f64) -> f64 {
        1.0 / (4.0 * PI)
    }

    /// μ = 2u − 1 (increasing in u, like every sampler here).
    pub fn sample_cos_theta(&self, u0: f64) -> f64 {
        2.0 * u0 - 1.0
    }
}
