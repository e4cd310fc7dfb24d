//! Cauchy's dispersion formula for air, n − 1 = a(1 + b/λ²), λ in μm, for air at 0 °C and
//! 760 mm Hg: a = 28.79 × 10⁻⁵, b = 5.67 × 10⁻³ μm². Gutierrez et al. 2005 (Eq. 18) print
//! a = 29.79e-5 and b = 5.67e-5, both misprints.
//!
//! The Gladstone–Dale constant divides by the density of that reference air, ideal gas with the
//! USA76 constants: ρ_ref = 101325 · M₀/(R* · 273.15 K) = 1.2923 kg m⁻³.
//!
//! # References
//! - M. Born & E. Wolf, *Principles of Optics*, 7th ed. (Cambridge 1999), §2.3.4, Eq. (2.3.38)
//!   and the constants for air quoted there.

use crate::atmosphere::gas::density_kg_m3;

/// Cauchy's law for air (Born & Wolf).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CauchyBornWolf;

impl CauchyBornWolf {
    /// Cauchy constant a of the reference air (dimensionless).
    pub const A: f64 = 28.79e-5;
    /// Cauchy constant b of the reference air, μm².
    pub const B_UM2: f64 = 5.67e-3;
    /// The reference state: 0 °C, 1 atm.
    pub const REF_TEMPERATURE_K: f64 = 273.15;
    /// Pressure of the reference state, Pa.
    pub const REF_PRESSURE_PA: f64 = 101_325.0;

    /// n − 1 of the reference air.
    pub fn refractivity(wavelength_nm: f64) -> f64 {
        let l_um = wavelength_nm * 1e-3;
        Self::A * (1.0 + Self::B_UM2 / (l_um * l_um))
    }

    /// K(λ) = (n_ref − 1)/ρ_ref, m³ kg⁻¹.
    pub fn gladstone_dale_m3_per_kg(wavelength_nm: f64) -> f64 {
        Self::refractivity(wavelength_nm) / density_kg_m3(Self::REF_PRESSURE_PA, Self::REF_TEMPERATURE_K)
    }
}
