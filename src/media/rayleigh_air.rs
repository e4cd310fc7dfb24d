//! Rayleigh scattering by dry air: the cross-section per molecule σ(λ), the King factor F(λ) and
//! the depolarisation ratio ρ(λ) of Bodhaine, Wood, Dutton & Slusser (1999), and the phase
//! function with depolarisation.
//!
//! # Refractive index of CO₂-adjusted standard air (288.15 K, 1013.25 hPa)
//! Peck & Reeder (1972) for 300 ppm CO₂ (Bodhaine Eq. 18), λ in µm:
//!
//! (n₃₀₀ − 1) × 10⁸ = 8060.51 + 2 480 990/(132.274 − λ⁻²) + 17 455.7/(39.329 57 − λ⁻²),
//!
//! scaled to a CO₂ volume fraction C (parts per volume; Bodhaine Eq. 19):
//! (n − 1) = (n₃₀₀ − 1) [1 + 0.54 (C − 0.0003)].
//!
//! # King factor (Bodhaine Eqs. 5, 6, 23; the gases' factors of Bates 1984)
//! F(N₂) = 1.034 + 3.17 × 10⁻⁴ λ⁻²,  F(O₂) = 1.096 + 1.385 × 10⁻³ λ⁻² + 1.448 × 10⁻⁴ λ⁻⁴,
//! F(Ar) = 1.00,  F(CO₂) = 1.15, weighted by volume percent (C in percent, 0.036 for 360 ppm):
//!
//! F(air) = [78.084 F(N₂) + 20.946 F(O₂) + 0.934 F(Ar) + C F(CO₂)] / (78.084 + 20.946 + 0.934 + C).
//!
//! # Cross-section (Bodhaine Eq. 22)
//! σ(λ) = 24π³ (n² − 1)² / (λ⁴ N_s² (n² + 2)²) · F(air),
//!
//! with N_s = 2.546 899 × 10¹⁹ cm⁻³ the molecular density of the standard air the index was
//! measured in (Bodhaine §2: Avogadro's 6.022 1367 × 10²³ mol⁻¹ over the molar volume
//! 22.4141 L mol⁻¹, at 288.15 K). σ is independent of the density the air is later given: n − 1
//! grows in proportion to N, so (n² − 1)²/N² does not change (to order (n − 1)).
//!
//! # Depolarisation and the phase function
//! The King factor is F = (6 + 3ρ)/(6 − 7ρ) for the depolarisation ratio ρ of unpolarised light,
//! so ρ = 6(F − 1)/(3 + 7F). With γ = ρ/(2 − ρ) the phase function of Chandrasekhar (1950,
//! §I.18; Hansen & Travis 1974, Eq. 2.15), normalised per steradian, is
//!
//! p(μ) = 3/(4(1 + 2γ)) [(1 + 3γ) + (1 − γ) μ²] / (4π),
//!
//! which is K (1 + c μ²) with c = (1 − γ)/(1 + 3γ) = (1 − ρ)/(1 + ρ) — the form of
//! [`super::phase::CosSquared`], so the phase function is that model with this c
//! ([`phase_c`]); ρ = 0 gives the classical 3/(16π)(1 + μ²).
//!
//! # References
//! - B. A. Bodhaine, N. B. Wood, E. G. Dutton, J. R. Slusser, "On Rayleigh optical depth
//!   calculations", J. Atmos. Oceanic Technol. 16 (1999), 1854–1861: Eqs. 5, 6, 18, 19, 22, 23,
//!   the fit Eq. 29 and the optical depth Eq. 30.
//! - E. R. Peck, K. Reeder, "Dispersion of air", J. Opt. Soc. Am. 62 (1972), 958–962.
//! - D. R. Bates, "Rayleigh scattering by air", Planet. Space Sci. 32 (1984), 785–790.
//! - S. Chandrasekhar, *Radiative Transfer* (1950), §I.18.
//! - J. E. Hansen, L. D. Travis, "Light scattering in planetary atmospheres", Space Sci. Rev. 16
//!   (1974), 527–610.

use std::f64::consts::PI;

/// Molecular density of the standard air of the refractive-index formula (288.15 K,
/// 1013.25 hPa), m⁻³ (Bodhaine: 2.546 899 × 10¹⁹ cm⁻³).
pub const N_STANDARD_PER_M3: f64 = 6.022_136_7e23 / 22.4141e-3 * 273.15 / 288.15;

/// The CO₂ concentration of Bodhaine et al.'s tables, ppm by volume.
pub const BODHAINE_CO2_PPM: f64 = 360.0;

/// Wavelengths the cross-section is used over, nm: those of Peck & Reeder's refractive index
/// (0.23–1.69 µm).
pub const RANGE_NM: (f64, f64) = (230.0, 1690.0);

/// Refractivity n − 1 of standard air with `co2_ppm` (Eqs. 18, 19).
pub fn refractivity(wavelength_nm: f64, co2_ppm: f64) -> f64 {
    let x = inverse_um2(wavelength_nm);
    let n300 = (8060.51 + 2_480_990.0 / (132.274 - x) + 17_455.7 / (39.329_57 - x)) * 1e-8;
    n300 * (1.0 + 0.54 * (co2_ppm * 1e-6 - 0.0003))
}

/// King factor F(air) with `co2_ppm` (Eqs. 5, 6, 23).
pub fn king_factor(wavelength_nm: f64, co2_ppm: f64) -> f64 {
    let x = inverse_um2(wavelength_nm);
    let f_n2 = 1.034 + 3.17e-4 * x;
    let f_o2 = 1.096 + 1.385e-3 * x + 1.448e-4 * x * x;
    let c = co2_ppm * 1e-4;
    (78.084 * f_n2 + 20.946 * f_o2 + 0.934 + c * 1.15) / (78.084 + 20.946 + 0.934 + c)
}

/// Depolarisation ratio ρ = 6(F − 1)/(3 + 7F) of a King factor F.
pub fn depolarisation_from_king(f: f64) -> f64 {
    6.0 * (f - 1.0) / (3.0 + 7.0 * f)
}

/// Depolarisation ratio ρ(λ) of air with `co2_ppm`.
pub fn depolarisation(wavelength_nm: f64, co2_ppm: f64) -> f64 {
    depolarisation_from_king(king_factor(wavelength_nm, co2_ppm))
}

/// The coefficient c = (1 − ρ)/(1 + ρ) of μ² in the phase function K (1 + c μ²).
pub fn phase_c(rho: f64) -> f64 {
    (1.0 - rho) / (1.0 + rho)
}

/// Rayleigh cross-section per molecule σ(λ), m² (Eq. 22).
pub fn cross_section_m2(wavelength_nm: f64, co2_ppm: f64) -> f64 {
    let n = 1.0 + refractivity(wavelength_nm, co2_ppm);
    let n2 = n * n;
    let lambda_m = wavelength_nm * 1e-9;
    let ratio = (n2 - 1.0) / (n2 + 2.0);
    24.0 * PI.powi(3) * ratio * ratio / (lambda_m.powi(4) * N_STANDARD_PER_M3 * N_STANDARD_PER_M3)
        * king_factor(wavelength_nm, co2_ppm)
}

/// The cross-section per molecule σ(λ) a scene's air scatters with.
#[derive(Clone, Debug, PartialEq)]
pub enum CrossSection {
    /// Bodhaine et al.'s σ(λ) of dry air with this CO₂ volume fraction, ppm ([`cross_section_m2`]).
    Bodhaine {
        /// CO₂ volume fraction, ppm.
        co2_ppm: f64,
    },
    /// A table the scene gives (a benchmark's or a line-by-line code's cross-sections), m², read
    /// as a power law between its samples.
    Table(crate::spectrum::PowerLawTable),
}

impl CrossSection {
    /// σ(λ), m².
    pub fn m2(&self, wavelength_nm: f64) -> f64 {
        match self {
            CrossSection::Bodhaine { co2_ppm } => cross_section_m2(wavelength_nm, *co2_ppm),
            CrossSection::Table(t) => t.eval(wavelength_nm),
        }
    }

    /// σ(λ) N_s, m⁻¹: the scattering coefficient of air at the standard density
    /// [`N_STANDARD_PER_M3`], which the air's density field (N/N_s) scales.
    pub fn at_standard_density(&self, wavelength_nm: f64) -> f64 {
        self.m2(wavelength_nm) * N_STANDARD_PER_M3
    }
}

/// λ⁻² with λ in µm.
fn inverse_um2(wavelength_nm: f64) -> f64 {
    let um = wavelength_nm * 1e-3;
    1.0 / (um * um)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Bodhaine Eq. 29: their fit to σ(λ) for 360 ppm CO₂, 10⁻²⁸ cm² with λ in µm.
    fn eq29_cm2(um: f64) -> f64 {
        let (x, l2) = (1.0 / (um * um), um * um);
        (1.045_599_6 - 341.290_61 * x - 0.902_308_50 * l2) / (1.0 + 0.002_705_988_9 * x - 85.968_563 * l2) * 1e-28
    }

    #[test]
    fn the_standard_density_is_bodhaines() {
        // Bodhaine §2: N_s = 2.546899 × 10¹⁹ cm⁻³.
        assert!((N_STANDARD_PER_M3 / 2.546_899e25 - 1.0).abs() < 1e-6, "{N_STANDARD_PER_M3}");
    }

    #[test]
    fn the_cross_section_follows_bodhaines_fit() {
        // Eq. 29 is the paper's fit to its Eq. 22 for 360 ppm CO₂. Eq. 22 here agrees with it to
        // 1e-4 relative over 0.25–0.85 µm (the residual there oscillates, below 8e-5); beyond,
        // the five-parameter fit drifts from the formula it fits (−1.3e-4 at 0.9 µm, −4.8e-4 at
        // 1 µm, −2e-3 at 1.2 µm), so 1e-3 at 0.9 and 1 µm.
        for (um, tol) in
            [(0.25, 1e-4), (0.3, 1e-4), (0.4, 1e-4), (0.55, 1e-4), (0.7, 1e-4), (0.85, 1e-4), (0.9, 1e-3), (1.0, 1e-3)]
        {
            let got_cm2 = cross_section_m2(um * 1e3, BODHAINE_CO2_PPM) * 1e4;
            let want = eq29_cm2(um);
            assert!((got_cm2 / want - 1.0).abs() < tol, "{um} µm: {got_cm2} vs {want}");
        }
        // σ(550 nm) = 4.5104 × 10⁻²⁷ cm² (Eq. 29 at 0.55 µm).
        let s = cross_section_m2(550.0, BODHAINE_CO2_PPM) * 1e4;
        assert!((s / 4.5104e-27 - 1.0).abs() < 1e-4, "{s}");
    }

    #[test]
    fn king_factor_and_depolarisation_are_consistent() {
        // F at 550 nm from the gases' factors (independent arithmetic):
        // F(N₂) = 1.034 + 3.17e-4/0.3025, F(O₂) = 1.096 + 1.385e-3/0.3025 + 1.448e-4/0.3025².
        let x = 1.0 / 0.3025;
        let (n2, o2) = (1.034 + 3.17e-4 * x, 1.096 + 1.385e-3 * x + 1.448e-4 * x * x);
        let want = (78.084 * n2 + 20.946 * o2 + 0.934 + 0.036 * 1.15) / 100.0;
        assert!((king_factor(550.0, 360.0) - want).abs() < 1e-12);
        // ρ round-trips through F = (6 + 3ρ)/(6 − 7ρ); ρ ≈ 0.028 in the visible (Young 1980:
        // 0.0279 for dry air; Bodhaine's F gives 0.0283 at 550 nm).
        let rho = depolarisation(550.0, 360.0);
        let f = (6.0 + 3.0 * rho) / (6.0 - 7.0 * rho);
        assert!((f - king_factor(550.0, 360.0)).abs() < 1e-12);
        assert!((0.027..0.030).contains(&rho), "ρ = {rho}");
        // c = (1 − ρ)/(1 + ρ) equals Chandrasekhar's (1 − γ)/(1 + 3γ) with γ = ρ/(2 − ρ).
        let g = rho / (2.0 - rho);
        assert!((phase_c(rho) - (1.0 - g) / (1.0 + 3.0 * g)).abs() < 1e-14);
    }

    #[test]
    fn more_co2_scatters_more() {
        // (n − 1) grows by 0.54 × 10⁻⁴ per 100 ppm (Eq. 19), σ by about twice that.
        let r = cross_section_m2(550.0, 460.0) / cross_section_m2(550.0, 360.0) - 1.0;
        assert!((1.0e-4..1.3e-4).contains(&r), "{r}");
    }
}
