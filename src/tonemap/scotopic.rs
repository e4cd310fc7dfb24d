//! Scotopic (rod) luminance from spectral radiance, with the CIE 1951 V′(λ).
//!
//! L′ = K′_m Σ_{λ = 380}^{780} L(λ) V′(λ) · 1 nm, in scotopic cd m⁻² for L in W m⁻² sr⁻¹ nm⁻¹,
//! with K′_m = 1700.06 lm W⁻¹ (the scotopic efficacy at the 555.016 nm definition of the candela:
//! 683 / V′(555.016 nm)). Summing at the table's 1 nm points is the same convention as the
//! photopic sums of [`crate::spectrum::colour`].
//!
//! A spectral image gives L′ from its bands directly ([`super::spectral_weights`]); where only
//! XYZ is known (an RGB EXR), L′ is estimated with the fit of Ward Larson et al. (1997, Eq. 8):
//! L′ ≈ Y (1.33 (1 + (Y + Z)/X) − 1.68).
//!
//! Rod signals are compared with photopic ones through the scotopic/photopic ratio of a white,
//! [`SCOTOPIC_PER_PHOTOPIC_WHITE`] = 2.26 (Hunt 1995's normalisation of the rod input, also used by
//! Ward Larson et al. 1997): L′/2.26 is the "photopic-equivalent" rod luminance.
//!
//! # References
//! - CIE 018:2019, *The Basis of Physical Photometry*, 3rd ed. (V′(λ); K′_m = 1700.06 lm W⁻¹).
//! - G. Ward Larson, H. Rushmeier, C. Piatko (1997), "A Visibility Matching Tone Reproduction
//!   Operator for High Dynamic Range Scenes", IEEE TVCG 3(4), 291–306, §5.
//! - R. W. G. Hunt (1995), *The Reproduction of Colour*, 5th ed., §31 (rod input of the model).

use super::cie_scotopic_data::{V_PRIME_1951, V_PRIME_START_NM};
use crate::spectrum::Spectrum;

/// Maximum luminous efficacy for scotopic vision, lm/W (CIE 018:2019).
pub const K_M_SCOTOPIC: f64 = 1700.06;

/// Scotopic luminance of a white per unit photopic luminance (Hunt 1995).
pub const SCOTOPIC_PER_PHOTOPIC_WHITE: f64 = 2.26;

/// V′ at integer wavelength `nm`, exactly as tabulated; zero outside 380–780 nm.
pub fn v_prime_at_nm(nm: u32) -> f64 {
    match nm.checked_sub(V_PRIME_START_NM) {
        Some(i) => V_PRIME_1951.get(i as usize).copied().unwrap_or(0.0),
        None => 0.0,
    }
}

/// Scotopic luminance (scotopic cd m⁻²) of a spectral radiance in W m⁻² sr⁻¹ nm⁻¹.
pub fn scotopic_luminance(radiance: &Spectrum) -> f64 {
    let sum: f64 = (380..=780u32).map(|nm| radiance.eval(f64::from(nm)) * v_prime_at_nm(nm)).sum();
    K_M_SCOTOPIC * sum
}

/// Scotopic luminance estimated from absolute XYZ (Ward Larson et al. 1997, Eq. 8); zero when
/// X is not positive.
pub fn scotopic_from_xyz(xyz: [f64; 3]) -> f64 {
    let [x, y, z] = xyz;
    if !(x > 0.0 && y > 0.0) {
        return 0.0;
    }
    (y * (1.33 * (1.0 + (y + z) / x) - 1.68)).max(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectrum::colour::absolute_xyz;
    use crate::spectrum::{Tabulated, named_illuminant};

    #[test]
    fn table_holds_the_cie_values() {
        // CIE 1951 V′ at 5 nm points (CIE 018:2019).
        for (nm, want) in [(380, 5.89e-4), (505, 0.998), (510, 0.997), (555, 0.402), (600, 0.03315), (780, 1.39e-7)] {
            assert_eq!(v_prime_at_nm(nm), want, "{nm} nm");
        }
        assert_eq!(v_prime_at_nm(379), 0.0);
        assert_eq!(v_prime_at_nm(781), 0.0);
        // The candela's definition: K′_m V′(555.016 nm) = 683 lm/W (V′ linear between 555 and 556).
        let v = v_prime_at_nm(555) + 0.016 * (v_prime_at_nm(556) - v_prime_at_nm(555));
        assert!((K_M_SCOTOPIC * v - 683.0).abs() < 0.1, "{}", K_M_SCOTOPIC * v);
    }

    #[test]
    fn scotopic_luminance_is_the_v_prime_integral() {
        // A box spectrum of 1 W m⁻² sr⁻¹ nm⁻¹ over 500–510 nm: K′_m Σ_{500}^{510} V′.
        let t = Tabulated::new(vec![499.999, 500.0, 510.0, 510.001], vec![0.0, 1.0, 1.0, 0.0]).unwrap();
        let want: f64 = K_M_SCOTOPIC * (500..=510).map(v_prime_at_nm).sum::<f64>();
        let got = scotopic_luminance(&Spectrum::Tabulated(t));
        assert!((got / want - 1.0).abs() < 1e-12, "{got} vs {want}");
        // Σ V′ over the table at 1 nm is 97.0713 (colour-science 0.4.7 gives the same sum).
        let sum: f64 = (380..=780).map(v_prime_at_nm).sum();
        assert!((sum - 97.071_316_574).abs() < 1e-6, "{sum}");
    }

    #[test]
    fn xyz_estimate_is_close_for_daylight_and_incandescent_light() {
        // The Ward Larson fit against the V′ integral: within 5 % for D65, 10 % for illuminant A.
        for (name, tol) in [("D65", 0.05), ("A", 0.1)] {
            let s = named_illuminant(name).unwrap().scaled(1e-3);
            let exact = scotopic_luminance(&s);
            let estimate = scotopic_from_xyz(absolute_xyz(&s));
            assert!((estimate / exact - 1.0).abs() < tol, "{name}: {estimate} vs {exact}");
        }
        assert_eq!(scotopic_from_xyz([0.0, 1.0, 1.0]), 0.0);
    }
}
