//! A perfect mirror with spectral reflectance R(λ).

use super::{SpecularSample, reflect};
use crate::spectrum::Spectrum;
use glam::DVec3;

#[derive(Clone, Debug)]
pub struct Mirror {
    pub reflectance: Spectrum,
}

impl Mirror {
    pub fn sample(&self, dir: DVec3, n: DVec3, wavelength_nm: f64) -> SpecularSample {
        SpecularSample { dir: reflect(dir, n), weight: self.reflectance.eval(wavelength_nm), transmitted: false }
    }
}
