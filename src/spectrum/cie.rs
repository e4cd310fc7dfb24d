//! CIE colour-matching functions and standard illuminants.
//!
//! - CIE 1931 2° observer x̄, ȳ, z̄: the CIE 1 nm table over 360–830 nm (see
//!   [`cie_data`](super::cie_data)), linearly interpolated between table entries, zero outside.
//! - D65: the CIE 5 nm table over 300–830 nm, linearly interpolated (which reproduces the CIE's
//!   1 nm table), zero outside.
//! - A: Planck's law as CIE 15:2018 defines it,
//!   S_A(λ) = 100 (560/λ)⁵ (exp(c₂/(2848·560)) − 1) / (exp(c₂/(2848·λ)) − 1), c₂ = 1.435 × 10⁷
//!   nm K. Only c₂/T enters, so this equals a CODATA black body at T = 2848 K × c₂(CODATA)/c₂(CIE)
//!   ≈ 2855.54 K scaled to 100 at 560 nm, which is how it is built here.
//! - E: equal energy, 100 everywhere.
//!
//! # References
//! - CIE 015:2018, *Colorimetry*, 4th ed., §3.1 and Table 5 (illuminant A formula and D65).
//! - CIE 018:2019, *The Basis of Physical Photometry*, 3rd ed. (CIE 1931 2° CMFs).

use super::blackbody::{BOLTZMANN_K, LIGHT_C, PLANCK_H};
use super::cie_data::{CMF_1931, CMF_1931_START_NM, D65_5NM, D65_START_NM};
use super::{Spectrum, Tabulated, planck_radiance};

/// Last wavelength of the CMF table, nm.
pub const CMF_1931_END_NM: f64 = 830.0;

/// c₂ in the CIE's definition of illuminant A, nm K (CIE 015:2018).
const CIE_A_C2_NM_K: f64 = 1.435e7;
/// The temperature in the CIE's definition of illuminant A, K.
const CIE_A_T_K: f64 = 2848.0;

/// CIE 1931 2° colour-matching functions (x̄, ȳ, z̄) at `wavelength_nm`; zero outside 360–830 nm.
pub fn cmf_1931(wavelength_nm: f64) -> [f64; 3] {
    if !(CMF_1931_START_NM..=CMF_1931_END_NM).contains(&wavelength_nm) {
        return [0.0; 3];
    }
    let x = wavelength_nm - CMF_1931_START_NM;
    let i = (x.floor() as usize).min(CMF_1931.len() - 2);
    let t = x - i as f64;
    let (a, b) = (CMF_1931[i], CMF_1931[i + 1]);
    [0, 1, 2].map(|k| a[k] + t * (b[k] - a[k]))
}

/// The CMF table entry at integer wavelength `nm` (360..=830), exactly as tabulated.
pub fn cmf_1931_at_nm(nm: u32) -> [f64; 3] {
    match (nm as usize).checked_sub(CMF_1931_START_NM as usize) {
        Some(i) if i < CMF_1931.len() => CMF_1931[i],
        _ => [0.0; 3],
    }
}

/// A CIE standard illuminant by name ("D65", "A", "E", case-insensitive), normalised to 100 at
/// 560 nm.
pub fn illuminant(name: &str) -> Option<Spectrum> {
    match name.to_ascii_uppercase().as_str() {
        "D65" => Some(Spectrum::Tabulated(d65())),
        "A" => Some(illuminant_a()),
        "E" => Some(Spectrum::Constant(100.0)),
        _ => None,
    }
}

/// The names [`illuminant`] knows.
pub const ILLUMINANT_NAMES: [&str; 3] = ["D65", "A", "E"];

/// CIE standard illuminant D65 (relative, 100 at 560 nm), 300–830 nm.
fn d65() -> Tabulated {
    let nm = (0..D65_5NM.len()).map(|i| D65_START_NM + 5.0 * i as f64).collect();
    // The table is valid by construction: increasing wavelengths, finite values.
    Tabulated::new(nm, D65_5NM.to_vec()).unwrap_or_else(|e| unreachable!("D65 table: {e}"))
}

/// CIE standard illuminant A as a scaled CODATA black body (see the module documentation).
fn illuminant_a() -> Spectrum {
    let c2_codata_nm_k = PLANCK_H * LIGHT_C / BOLTZMANN_K * 1e9;
    let t = CIE_A_T_K * c2_codata_nm_k / CIE_A_C2_NM_K;
    Spectrum::Blackbody { temperature_k: t }.scaled(100.0 / planck_radiance(t, 560.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cmf_table_values_and_sums_match_the_cie() {
        // CIE 1931 2° table entries (CIE 018:2019).
        assert_eq!(cmf_1931(555.0)[1], 1.0);
        assert_eq!(cmf_1931(560.0), [0.5945, 0.995, 0.0039]);
        assert_eq!(cmf_1931_at_nm(360), [0.0001299, 3.917e-6, 0.0006061]);
        // Interpolated halfway between 560 and 561 nm.
        let mid = cmf_1931(560.5);
        let (a, b) = (cmf_1931_at_nm(560), cmf_1931_at_nm(561));
        assert!((mid[0] - 0.5 * (a[0] + b[0])).abs() < 1e-15);
        assert_eq!(cmf_1931(359.9), [0.0; 3]);
        assert_eq!(cmf_1931(830.1), [0.0; 3]);
        assert_eq!(cmf_1931_at_nm(831), [0.0; 3]);
        // Σ ȳ Δλ over 360–830 nm at 1 nm is 106.857 (CIE 015:2018, k = 100/Σ ȳ for E).
        let sums = (360..=830).fold([0.0; 3], |s, nm| {
            let c = cmf_1931_at_nm(nm);
            [s[0] + c[0], s[1] + c[1], s[2] + c[2]]
        });
        assert!((sums[1] - 106.857).abs() < 1e-3, "Σȳ = {}", sums[1]);
        // Illuminant E is its own white: the three sums agree to 0.04 %.
        assert!((sums[0] / sums[1] - 1.0).abs() < 4e-4);
        assert!((sums[2] / sums[1] - 1.0).abs() < 4e-4);
    }

    #[test]
    fn d65_matches_the_cie_1nm_table() {
        let d65 = illuminant("D65").unwrap();
        // Values from the CIE's 1 nm D65 table (dataset DOI 10.25039/CIE.DS.hjfjmt59).
        for (nm, want) in
            [(300.0, 0.0341), (301.0, 0.36014), (459.0, 117.732), (560.0, 100.0), (777.0, 64.4096), (830.0, 60.3125)]
        {
            let got = d65.eval(nm);
            assert!((got - want).abs() < 1e-4 * want.max(1.0), "D65({nm}) = {got}, CIE {want}");
        }
        assert_eq!(d65.eval(299.0), 0.0);
    }

    #[test]
    fn illuminant_a_matches_the_cie_table() {
        let a = illuminant("a").unwrap();
        // CIE 015:2018 Table 5 (illuminant A), 6 significant figures.
        for (nm, want) in [(300.0, 0.930483), (380.0, 9.7951), (500.0, 59.8611), (560.0, 100.0), (780.0, 241.675)] {
            let got = a.eval(nm);
            assert!(((got - want) / want).abs() < 1e-5, "A({nm}) = {got}, CIE {want}");
        }
    }

    #[test]
    fn knows_exactly_the_documented_names() {
        for name in ILLUMINANT_NAMES {
            let s = illuminant(name).unwrap();
            assert!((s.eval(560.0) - 100.0).abs() < 1e-9, "{name}");
        }
        assert!(illuminant("D50").is_none());
        assert!(illuminant("").is_none());
    }
}
