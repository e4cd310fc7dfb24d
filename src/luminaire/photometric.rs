//! Photometric → radiometric: lumens and candela to watts, spectrally.
//!
//! A luminaire's spectrum s(λ) (any scale) fixes the watts per lumen: the luminous quantity of a
//! spectral radiant quantity X_e(λ) is X_v = K_m ∫ X_e(λ) V(λ) dλ with K_m = 683.002 lm/W and
//! V = ȳ, the CIE 1931 photopic luminous efficiency. So one candela of a source with spectrum s
//! is the spectral intensity
//!
//! I_e(λ) per cd = s(λ) / (K_m ∫ s(λ) ȳ(λ) dλ)     [W sr⁻¹ nm⁻¹ cd⁻¹],
//!
//! the integral taken over the whole visible range, 360–830 nm, as the 1 nm sum of
//! [`crate::spectrum::colour`]. A scene simulates only [min_nm, max_nm]: its watts are
//! Φ_v ∫_{min}^{max} I_e per cd dλ, and the luminous flux it carries is the fraction
//! [`luminous_fraction_in`] of the file's lumens (1 when the range covers 360–830 nm).
//!
//! # References
//! - CIE 018:2019, *The Basis of Physical Photometry*, 3rd ed. (K_m, V(λ) = ȳ(λ)).
//! - BIPM, *The International System of Units*, 9th ed. (2019): K_cd = 683 lm/W at 540 THz.

use crate::spectrum::Spectrum;
use crate::spectrum::cie::cmf_1931_at_nm;
use crate::spectrum::colour::{K_M, SUM_END_NM, SUM_START_NM, cmf_sums};

/// ∫ s(λ) ȳ(λ) dλ over 360–830 nm (1 nm sum), nm × unit of s.
pub fn luminous_integral(s: &Spectrum) -> f64 {
    cmf_sums(|l| s.eval(l))[1]
}

/// The spectral intensity of one candela of light with spectrum shape `s` (module docs);
/// `None` when `s` has no luminous content.
pub fn per_candela(s: &Spectrum) -> Option<Spectrum> {
    let y = luminous_integral(s);
    (y > 0.0 && y.is_finite()).then(|| s.clone().scaled(1.0 / (K_M * y)))
}

/// The fraction of the luminous content of `s` within [min_nm, max_nm] (1 nm sums).
pub fn luminous_fraction_in(s: &Spectrum, min_nm: f64, max_nm: f64) -> f64 {
    let total = luminous_integral(s);
    if total <= 0.0 {
        return 0.0;
    }
    let inside: f64 = (SUM_START_NM..=SUM_END_NM)
        .filter(|nm| (min_nm..=max_nm).contains(&f64::from(*nm)))
        .map(|nm| s.eval(f64::from(nm)) * cmf_1931_at_nm(nm)[1])
        .sum();
    inside / total
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectrum::Tabulated;

    #[test]
    fn one_candela_at_555_nm_is_one_683rd_watt_per_steradian() {
        // A line at 555 nm, where ȳ = 1: 1 cd = 1/683.002 W/sr.
        let line = Spectrum::Tabulated(Tabulated::new(vec![554.0, 555.0, 556.0], vec![0.0, 1.0, 0.0]).unwrap());
        let per_cd = per_candela(&line).unwrap();
        assert!((per_cd.integral(500.0, 600.0) - 1.0 / 683.002).abs() < 1e-15);
        assert_eq!(luminous_fraction_in(&line, 380.0, 780.0), 1.0);
        assert_eq!(luminous_fraction_in(&line, 560.0, 780.0), 0.0);
    }

    #[test]
    fn the_flux_scale_does_not_depend_on_the_spectrum_scale() {
        let a = per_candela(&Spectrum::Blackbody { temperature_k: 3000.0 }).unwrap();
        let b = per_candela(&Spectrum::Blackbody { temperature_k: 3000.0 }.scaled(1e6)).unwrap();
        assert!((a.eval(600.0) / b.eval(600.0) - 1.0).abs() < 1e-12);
        // Back to lumens: K_m Σ I_e ȳ = 1 cd.
        assert!((K_M * luminous_integral(&a) - 1.0).abs() < 1e-12);
        assert!(per_candela(&Spectrum::Constant(0.0)).is_none());
    }

    #[test]
    fn a_narrow_range_carries_part_of_the_lumens() {
        // Equal energy: the luminous fraction in 500–600 nm is Σȳ(500..600)/Σȳ(360..830).
        let e = Spectrum::Constant(1.0);
        let part: f64 = (500..=600).map(|nm| cmf_1931_at_nm(nm)[1]).sum();
        let all: f64 = (360..=830).map(|nm| cmf_1931_at_nm(nm)[1]).sum();
        assert!((luminous_fraction_in(&e, 500.0, 600.0) - part / all).abs() < 1e-15);
        assert!(luminous_fraction_in(&e, 380.0, 780.0) > 0.9999);
    }
}
