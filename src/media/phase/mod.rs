//! Phase functions: one file each, dispatched by a closed enum.
//!
//! (Interim: isotropic only, until the phase-function work lands.)

use crate::geometry::Frame;
use crate::sampling::uniform_sphere;
use glam::DVec3;

/// Directions are directions of travel; cos θ = wi·wo.
#[derive(Clone, Debug, PartialEq)]
pub enum PhaseFunction {
    Isotropic,
}

impl PhaseFunction {
    pub fn eval(&self, _wavelength_nm: f64, _cos_theta: f64) -> f64 {
        1.0 / (4.0 * std::f64::consts::PI)
    }
    pub fn pdf(&self, wavelength_nm: f64, cos_theta: f64) -> f64 {
        self.eval(wavelength_nm, cos_theta)
    }
    pub fn sample(&self, wavelength_nm: f64, wi: DVec3, u: [f64; 2]) -> (DVec3, f64) {
        let wo = Frame::from_normal(wi).to_world(uniform_sphere(u));
        (wo, self.pdf(wavelength_nm, 1.0))
    }
    pub fn mean_cosine(&self, _wavelength_nm: f64) -> f64 {
        0.0
    }
}
