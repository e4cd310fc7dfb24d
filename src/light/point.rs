//! An isotropic point light of spectral intensity I(λ): Φ = 4π ∫ I(λ) dλ.

use crate::sampling::uniform_sphere;
use glam::DVec3;

use super::{Incident, LightSpectrum};

/// An isotropic point light (see the module docs).
#[derive(Clone, Debug)]
pub struct PointLight {
    /// Position, m.
    pub position: DVec3,
    /// Spectral intensity I(λ), W sr⁻¹ nm⁻¹.
    pub emission: LightSpectrum,
}

impl PointLight {
    /// Φ = 4π ∫ I dλ within the scene's wavelength range, W.
    pub fn power_w(&self) -> f64 {
        4.0 * std::f64::consts::PI * self.emission.integral()
    }

    /// A uniformly distributed unit direction of travel.
    pub fn emit_dir(&self, u: [f64; 2]) -> DVec3 {
        uniform_sphere(u)
    }

    /// Irradiance at distance d is I/d², so weight = 1/d².
    pub fn incident(&self, p: DVec3) -> Option<Incident> {
        let d = self.position - p;
        let dist2 = d.length_squared();
        (dist2 > 0.0).then(|| {
            let dist = dist2.sqrt();
            Incident { wi: d / dist, dist, weight: 1.0 / dist2 }
        })
    }
}
