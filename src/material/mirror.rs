//! A perfect mirror with spectral reflectance R(λ).

use super::{SpecularSample, reflect};
use crate::spectrum::Spectrum;
use glam::DVec3;

/// A perfect mirror (see the module docs).
#[derive(Clone, Debug)]
pub struct Mirror {
    /// Reflectance R(λ) in [0, 1].
    pub reflectance: Spectrum,
}

impl Mirror {
    /// Reflects `dir` (direction of travel) about `n`; the weight is R(λ).
    pub fn sample(&self, dir: DVec3, n: DVec3, wavelength_nm: f64) -> SpecularSample {
        SpecularSample { dir: reflect(dir, n), weight: self.reflectance.eval(wavelength_nm), transmitted: false }
    }
}
