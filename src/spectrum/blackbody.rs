//! Planck's law.

/// Spectral radiance of a black body, W m⁻² sr⁻¹ nm⁻¹ (CODATA 2018 constants).
pub fn planck_radiance(temperature_k: f64, wavelength_nm: f64) -> f64 {
    todo!("{temperature_k}{wavelength_nm}")
}
