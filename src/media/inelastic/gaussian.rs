//! A Gaussian emission band independent of the excitation wavelength: chlorophyll fluorescence.
//!
//! h(λ) = exp(−(λ − λ₀)²/(2σ²)) / (σ √(2π)) per nm, so ∫ h dλ = 1 (the mass below λ = 0 is
//! below 10⁻³⁰⁰ for any band in the visible and is ignored). For chlorophyll a, λ₀ = 685 nm and
//! σ = 10.6 nm (FWHM 25 nm).
//!
//! Sampling is exact: Box–Muller normal deviates, redrawn in the (never observed) case λ ≤ 0.
//!
//! # References
//! - Mobley, *Light and Water* (1994), §5.12, Eq. 5.104 (chlorophyll fluorescence redistribution
//!   Φ_C h_C(λ) λ'/λ, λ₀ = 685 nm, σ_C = 10.6 nm).
//! - Box & Muller, "A note on the generation of random normal deviates", Ann. Math. Stat. 29
//!   (1958), 610–611.

use crate::rng::Rng;
use std::f64::consts::PI;

/// A Gaussian emission band h(λ), normalised per nm (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GaussianEmission {
    /// Centre λ₀ of the band, nm.
    pub peak_nm: f64,
    /// Standard deviation σ of the band, nm.
    pub sigma_nm: f64,
}

impl GaussianEmission {
    /// A band at `peak_nm` of width `sigma_nm`; both must be finite and positive.
    pub fn new(peak_nm: f64, sigma_nm: f64) -> Result<GaussianEmission, String> {
        if !(peak_nm.is_finite() && peak_nm > 0.0 && sigma_nm.is_finite() && sigma_nm > 0.0) {
            return Err(format!(
                "gaussian emission needs peak_nm > 0 and sigma_nm > 0, found peak_nm = {peak_nm}, sigma_nm = {sigma_nm}"
            ));
        }
        Ok(GaussianEmission { peak_nm, sigma_nm })
    }

    /// The emission wavelengths outside which [`GaussianEmission::density`] is exactly zero in
    /// f64, nm: beyond ±40σ the factor exp(−800) underflows to 0 (exp underflows below −745).
    pub fn nonzero_nm(&self) -> (f64, f64) {
        (self.peak_nm - 40.0 * self.sigma_nm, self.peak_nm + 40.0 * self.sigma_nm)
    }

    /// h(λ) per nm.
    pub fn density(&self, emission_nm: f64) -> f64 {
        let z = (emission_nm - self.peak_nm) / self.sigma_nm;
        (-0.5 * z * z).exp() / (self.sigma_nm * (2.0 * PI).sqrt())
    }

    /// A wavelength drawn from h.
    pub fn sample(&self, rng: &mut Rng) -> f64 {
        loop {
            let l = self.peak_nm + self.sigma_nm * normal(rng);
            if l > 0.0 {
                return l;
            }
        }
    }

    /// The interval outside which h is below 10⁻¹⁴ of its peak (±8σ).
    pub fn support_nm(&self) -> (f64, f64) {
        ((self.peak_nm - 8.0 * self.sigma_nm).max(1.0), self.peak_nm + 8.0 * self.sigma_nm)
    }
}

/// A standard normal deviate (Box–Muller, one of the pair).
pub fn normal(rng: &mut Rng) -> f64 {
    let u1 = 1.0 - rng.uniform();
    let u2 = rng.uniform();
    (-2.0 * u1.ln()).sqrt() * (2.0 * PI * u2).cos()
}
