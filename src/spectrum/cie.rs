//! CIE colour-matching functions and standard illuminants.

use super::Spectrum;

/// CIE 1931 2° colour-matching functions (x̄, ȳ, z̄) at `wavelength_nm`; zero outside 360–830 nm.
pub fn cmf_1931(wavelength_nm: f64) -> [f64; 3] {
    todo!("{wavelength_nm}")
}

/// A CIE standard illuminant by name.
pub fn illuminant(name: &str) -> Option<Spectrum> {
    todo!("{name}")
}
