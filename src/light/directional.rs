//! A directional light: parallel rays of spectral irradiance E(λ) (normal to the beam) from
//! infinitely far away.
//!
//! Photons start on a disk perpendicular to the beam that covers the scene's bounding sphere,
//! so the emitted flux is Φ = π R² ∫E dλ for the bounding radius R; a directional light's power
//! is only defined relative to the region it lights, and `report.json` states that region.

use crate::geometry::Frame;
use crate::sampling::concentric_disk;
use glam::DVec3;

use super::{Incident, LightSpectrum};

#[derive(Clone, Debug)]
pub struct DirectionalLight {
    /// Unit direction the light travels in.
    pub dir: DVec3,
    /// Centre and radius of the scene's bounding sphere.
    pub scene_centre: DVec3,
    pub scene_radius: f64,
    /// Spectral irradiance normal to the beam, W m⁻² nm⁻¹.
    pub emission: LightSpectrum,
}

impl DirectionalLight {
    pub fn power_w(&self) -> f64 {
        std::f64::consts::PI * self.scene_radius * self.scene_radius * self.emission.integral()
    }

    /// A uniform point on the emitting disk, one radius upstream of the scene's centre.
    pub fn emit_origin(&self, u: [f64; 2]) -> DVec3 {
        let [x, y] = concentric_disk(u);
        let frame = Frame::from_normal(self.dir);
        self.scene_centre - self.dir * (1.001 * self.scene_radius) + self.scene_radius * (x * frame.s + y * frame.t)
    }

    /// Irradiance normal to the beam is E, so weight = 1 toward −dir at infinite distance.
    pub fn incident(&self) -> Incident {
        Incident { wi: -self.dir, dist: f64::INFINITY, weight: 1.0 }
    }
}
