//! Chromatic adaptation: von Kries scaling in a cone-like space, with three choices of space.
//!
//! A colour XYZ seen under a scene white XYZ_w is mapped to the colour that looks the same
//! under the display white XYZ_wr:
//!
//! XYZ_a = M⁻¹ · diag(D ρ_wr/ρ_w + 1 − D) · M · XYZ, with ρ_w = M · XYZ_w, ρ_wr = M · XYZ_wr,
//!
//! both whites scaled to Y = 1 (so the luminance of the scene white is kept) and D ∈ [0, 1] the
//! degree of adaptation (D = 1: complete, the eye fully discounts the illuminant; D = 0: none).
//! With D = 1 this is `colour.adaptation.chromatic_adaptation_VonKries` of colour-science, which
//! `scripts/colour_check.py` compares against (ΔE₀₀ ≤ 0.1); the D-blend is CAT16's one-step form
//! (Li et al. 2017, Eq. 7) with Y_w = Y_wr. M is
//! - [`Cat::VonKries`]: the Hunt–Pointer–Estévez cone fundamentals (equal-energy normalised),
//!   i.e. von Kries's hypothesis in LMS (Fairchild 2013, §9.1–9.2);
//! - [`Cat::Bradford`]: the linearised Bradford matrix (Lam 1985; Fairchild 2013, §9.5);
//! - [`Cat::Cat16`]: the CAT16 matrix of Li et al. (2017).
//!
//! Gutierrez et al. (2005, §6) add chromatic adaptation to display underwater images, where the
//! eye adapts to blue-green light; a von Kries transform with the scene white estimated from the
//! image ([`super::white`]) is that operator's core.
//!
//! # References
//! - M. D. Fairchild (2013), *Color Appearance Models*, 3rd ed., Wiley, ch. 9.
//! - K. M. Lam (1985), *Metamerism and Colour Constancy*, PhD thesis, University of Bradford.
//! - C. Li, Z. Li, Z. Wang, Y. Xu, M. R. Luo, G. Cui, M. Melgosa, M. H. Brill, M. Pointer
//!   (2017), "Comprehensive color solutions: CAM16, CAT16, and CAM16-UCS", Color Research &
//!   Application 42(6), 703–718.
//! - D. Gutierrez, A. Muñoz, O. Anson, F. J. Serón (2005), "Non-linear Volume Photon Mapping",
//!   Eurographics Symposium on Rendering, §6 (`../shared/papers/`); the operator itself is
//!   described in their reference \[GSMA04\] (Gutierrez, Serón, Muñoz, Anson 2004), which is not
//!   available here, so this module implements the standard von Kries form it builds on.

use super::matrix::{Mat3, diagonal, invert, mul, mul_vec};

/// The cone-like space of the von Kries scaling.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Cat {
    /// Hunt–Pointer–Estévez LMS cone fundamentals (von Kries's own hypothesis).
    VonKries,
    /// The linearised Bradford matrix.
    Bradford,
    /// The CAT16 matrix of Li et al. (2017).
    Cat16,
}

impl Cat {
    /// Every transform, in the order above.
    pub const ALL: [Cat; 3] = [Cat::VonKries, Cat::Bradford, Cat::Cat16];

    /// The matrix M from XYZ to the cone-like space.
    pub fn matrix(self) -> Mat3 {
        match self {
            Cat::VonKries => [[0.40024, 0.70760, -0.08081], [-0.22630, 1.16532, 0.04570], [0.0, 0.0, 0.91822]],
            Cat::Bradford => [[0.8951, 0.2664, -0.1614], [-0.7502, 1.7135, 0.0367], [0.0389, -0.0685, 1.0296]],
            Cat::Cat16 => {
                [[0.401288, 0.650173, -0.051461], [-0.250268, 1.204414, 0.045854], [-0.002079, 0.048952, 0.953127]]
            }
        }
    }

    /// The name used in scene files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Cat::VonKries => "von_kries",
            Cat::Bradford => "bradford",
            Cat::Cat16 => "cat16",
        }
    }

    /// Parses `von_kries`, `bradford` or `cat16` (dashes work as underscores; case-insensitive).
    pub fn parse(s: &str) -> Option<Cat> {
        let s = s.to_ascii_lowercase().replace('-', "_");
        Cat::ALL.into_iter().find(|c| c.name() == s)
    }
}

/// The matrix taking XYZ seen under `white` to XYZ seen under `target_white` (see the module
/// documentation); `None` when a white is not usable (non-positive Y or cone response).
pub fn adaptation_matrix(cat: Cat, white: [f64; 3], target_white: [f64; 3], degree: f64) -> Option<Mat3> {
    let m = cat.matrix();
    let m_inv = invert(&m)?;
    let unit = |w: [f64; 3]| (w[1].is_finite() && w[1] > 0.0).then(|| w.map(|c| c / w[1]));
    let rho_w = mul_vec(&m, unit(white)?);
    let rho_wr = mul_vec(&m, unit(target_white)?);
    if rho_w.iter().chain(&rho_wr).any(|r| !(r.is_finite() && *r > 0.0)) {
        return None;
    }
    let d = degree.clamp(0.0, 1.0);
    let gains = [0, 1, 2].map(|k| d * rho_wr[k] / rho_w[k] + 1.0 - d);
    Some(mul(&m_inv, &mul(&diagonal(gains), &m)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tonemap::delta_e::{delta_e_2000, xyz_to_lab};
    use crate::tonemap::matrix::xy_to_xyz;

    const D65: [f64; 3] = [0.95045593, 1.0, 1.08905775];
    const D50: [f64; 3] = [0.96429568, 1.0, 0.82510460];

    #[test]
    fn reproduces_colour_sciences_documented_examples() {
        // colour.adaptation.chromatic_adaptation_VonKries docstring (colour-science 0.4.7):
        // XYZ (0.20654008, 0.12197225, 0.05136952) from D65 to D50 with Bradford gives
        // (0.2166600, 0.1260477, 0.0385506).
        let m = adaptation_matrix(Cat::Bradford, D65, D50, 1.0).unwrap();
        let got = mul_vec(&m, [0.20654008, 0.12197225, 0.05136952]);
        for (g, w) in got.iter().zip([0.2166600, 0.1260477, 0.0385506]) {
            assert!((g - w).abs() < 1e-7, "{got:?}");
        }
        // Its matrix_chromatic_adaptation_VonKries example, Bradford row 0: 1.0479297, 0.0229468, −0.0501922.
        for (g, w) in m[0].iter().zip([1.0479297, 0.0229468, -0.0501922]) {
            assert!((g - w).abs() < 1e-7, "{m:?}");
        }
    }

    #[test]
    fn the_scene_white_becomes_the_target_white() {
        let water = xy_to_xyz([0.24, 0.36]);
        for cat in Cat::ALL {
            let m = adaptation_matrix(cat, water.map(|c| 3.0 * c), D65, 1.0).unwrap();
            let w = mul_vec(&m, water);
            assert!((0..3).all(|k| (w[k] - D65[k]).abs() < 1e-12), "{cat:?}: {w:?}");
            // D = 0 is the identity; D = 0.5 lands between.
            let id = adaptation_matrix(cat, water, D65, 0.0).unwrap();
            assert!((0..3).all(|k| (mul_vec(&id, water)[k] - water[k]).abs() < 1e-12));
            let half = mul_vec(&adaptation_matrix(cat, water, D65, 0.5).unwrap(), water);
            let de = |a: [f64; 3]| delta_e_2000(xyz_to_lab(a, D65), xyz_to_lab(D65, D65));
            assert!(de(half) > 1.0 && de(half) < de(water), "{cat:?}");
        }
        assert!(adaptation_matrix(Cat::Cat16, [1.0, 0.0, 1.0], D65, 1.0).is_none());
    }

    #[test]
    fn parses_the_documented_names() {
        assert_eq!(Cat::parse("von-kries"), Some(Cat::VonKries));
        assert_eq!(Cat::parse("Bradford"), Some(Cat::Bradford));
        assert_eq!(Cat::parse("cat16"), Some(Cat::Cat16));
        assert_eq!(Cat::parse("cat02"), None);
    }
}
