//! Sampling wavelengths in proportion to a spectrum.

use super::Spectrum;

/// Draws wavelengths in [min_nm, max_nm] with density proportional to a non-negative spectrum.
#[derive(Clone, Debug)]
pub struct SpectrumSampler {}

impl SpectrumSampler {
    /// `None` when the spectrum integrates to zero over the range (or is negative somewhere).
    pub fn new(spectrum: &Spectrum, min_nm: f64, max_nm: f64) -> Option<SpectrumSampler> {
        todo!("{spectrum:?}{min_nm}{max_nm}")
    }
    /// A wavelength for uniform `u` and its density (per nm).
    pub fn sample(&self, u: f64) -> (f64, f64) {
        todo!("{u}")
    }
    /// Density (per nm) of `wavelength_nm`.
    pub fn pdf(&self, wavelength_nm: f64) -> f64 {
        todo!("{wavelength_nm}")
    }
    /// ∫ s(λ) dλ over the range.
    pub fn integral(&self) -> f64 {
        todo!()
    }
}

/// Numerical integral of a smooth spectrum.
pub(super) fn integrate_smooth(spectrum: &Spectrum, min_nm: f64, max_nm: f64) -> f64 {
    todo!("{spectrum:?}{min_nm}{max_nm}")
}
