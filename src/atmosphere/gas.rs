//! The ideal gas ρ = pM/(R*T) with the constants of the U.S. Standard Atmosphere 1976.
//!
//! # References
//! - U.S. Standard Atmosphere, 1976 (NOAA-S/T 76-1562), Table 2 and Eq. 42:
//!   R* = 8.31432 J mol⁻¹ K⁻¹ (the standard's value; CODATA 2018 gives 8.314462618),
//!   M₀ = 28.9644 × 10⁻³ kg mol⁻¹ (sea-level mean molar mass of dry air),
//!   N_A = 6.022169 × 10²³ mol⁻¹.
//!   Gutierrez et al. 2005 §5 use M = 28.93e-3 kg/mol and R = 8.3145 J/(mol K); the two pairs
//!   differ by 0.1% in density.

/// Universal gas constant of USA76, J mol⁻¹ K⁻¹.
pub const R_STAR: f64 = 8.314_32;

/// Molar mass of dry air at sea level (USA76), kg mol⁻¹.
pub const M0_KG_PER_MOL: f64 = 28.964_4e-3;

/// ρ = pM₀/(R*T), kg m⁻³.
pub fn density_kg_m3(pressure_pa: f64, temperature_k: f64) -> f64 {
    pressure_pa * M0_KG_PER_MOL / (R_STAR * temperature_k)
}

/// Avogadro's number of USA76 (Table 2), mol⁻¹.
pub const AVOGADRO_PER_MOL: f64 = 6.022_169e23;

/// Number density N = P N_A/(R* T) of the ideal gas, with USA76's constants, m⁻³.
pub fn number_density_per_m3(pressure_pa: f64, temperature_k: f64) -> f64 {
    pressure_pa * AVOGADRO_PER_MOL / (R_STAR * temperature_k)
}
