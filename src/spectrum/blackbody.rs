//! Planck's law.
//!
//! B_λ(T) = 2 h c² / λ⁵ · 1 / (exp(h c / (λ k T)) − 1)   [W m⁻² sr⁻¹ m⁻¹],
//! returned per nanometre (× 10⁻⁹), with λ in metres inside the formula.
//!
//! # References
//! - M. Planck (1901), "Über das Gesetz der Energieverteilung im Normalspectrum",
//!   Annalen der Physik 309(3).
//! - CODATA 2018 (Tiesinga et al. 2021, Rev. Mod. Phys. 93, 025010): h, c and k are exact
//!   in the 2019 SI.

/// Planck constant h, J s (exact).
pub const PLANCK_H: f64 = 6.626_070_15e-34;
/// Speed of light in vacuum c, m s⁻¹ (exact).
pub const LIGHT_C: f64 = 299_792_458.0;
/// Boltzmann constant k, J K⁻¹ (exact).
pub const BOLTZMANN_K: f64 = 1.380_649e-23;

/// Spectral radiance of a black body, W m⁻² sr⁻¹ nm⁻¹ (CODATA 2018 constants).
///
/// Zero for non-positive (or non-finite) temperatures and wavelengths.
pub fn planck_radiance(temperature_k: f64, wavelength_nm: f64) -> f64 {
    let valid = |x: f64| x > 0.0 && x.is_finite();
    if !(valid(temperature_k) && valid(wavelength_nm)) {
        return 0.0;
    }
    let lambda_m = wavelength_nm * 1e-9;
    let x = PLANCK_H * LIGHT_C / (lambda_m * BOLTZMANN_K * temperature_k);
    // exp_m1 keeps precision in the Rayleigh–Jeans limit (x → 0); for x > ~709 the exponential
    // overflows to ∞ and the radiance correctly underflows to 0.
    let per_m = 2.0 * PLANCK_H * LIGHT_C * LIGHT_C / lambda_m.powi(5) / x.exp_m1();
    per_m * 1e-9
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectrum::Spectrum;

    #[test]
    fn matches_independent_evaluations() {
        // Evaluated with scipy.constants (CODATA, exact h, c, k) in an independent script.
        let cases = [
            (5000.0, 500.0, 12_107.190_590_398_124),
            (6000.0, 555.0, 30_467.618_840_209_685),
            (300.0, 10_000.0, 0.009_924_033_330_070_694),
            (2856.0, 560.0, 268.008_142_838_493_7),
        ];
        for (t, l, want) in cases {
            let got = planck_radiance(t, l);
            assert!(((got - want) / want).abs() < 1e-12, "B({t} K, {l} nm) = {got}, want {want}");
        }
    }

    #[test]
    fn peak_obeys_wiens_displacement_law() {
        // λ_max = b / T with b = 2.897 771 955 × 10⁻³ m K (CODATA 2018).
        for t in [1000.0, 3000.0, 5772.0, 10_000.0] {
            let want_nm = 2.897_771_955e-3 / t * 1e9;
            // Golden-section search for the maximum around the expected peak.
            let (mut a, mut b) = (0.5 * want_nm, 2.0 * want_nm);
            let g = 0.5 * (5f64.sqrt() - 1.0);
            for _ in 0..200 {
                let c = b - g * (b - a);
                let d = a + g * (b - a);
                if planck_radiance(t, c) > planck_radiance(t, d) {
                    b = d;
                } else {
                    a = c;
                }
            }
            let peak = 0.5 * (a + b);
            assert!(((peak - want_nm) / want_nm).abs() < 1e-6, "T = {t}: peak {peak} nm, Wien {want_nm} nm");
        }
    }

    #[test]
    fn integrates_to_stefan_boltzmann() {
        // ∫ B_λ dλ over all λ = σ T⁴ / π, σ = 5.670 374 419 × 10⁻⁸ W m⁻² K⁻⁴ (CODATA 2018).
        // Integrate over [50 nm, L] and add the Rayleigh–Jeans tail beyond L,
        // ∫_L^∞ 2 c k T / λ⁴ dλ = 2 c k T / (3 L³) (relative size ~1e-7 here).
        let t = 5000.0;
        let l_m = 1e-3;
        let body = Spectrum::Blackbody { temperature_k: t }.integral(50.0, l_m * 1e9);
        let tail = 2.0 * LIGHT_C * BOLTZMANN_K * t / (3.0 * l_m.powi(3));
        let total = body + tail;
        let want = 5.670_374_419e-8 * t.powi(4) / std::f64::consts::PI;
        assert!(((total - want) / want).abs() < 1e-6, "∫B = {total}, σT⁴/π = {want}");
    }

    #[test]
    fn is_zero_for_invalid_arguments() {
        assert_eq!(planck_radiance(0.0, 500.0), 0.0);
        assert_eq!(planck_radiance(-5.0, 500.0), 0.0);
        assert_eq!(planck_radiance(5000.0, 0.0), 0.0);
        assert_eq!(planck_radiance(f64::NAN, 500.0), 0.0);
        assert_eq!(planck_radiance(f64::INFINITY, 500.0), 0.0);
        // Deep Wien tail underflows to zero rather than NaN.
        assert_eq!(planck_radiance(10.0, 100.0), 0.0);
    }
}
