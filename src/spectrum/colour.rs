//! Spectral → XYZ → linear sRGB.
//!
//! All tristimulus integrals use the "Integration" convention of colour-science: a sum over the
//! integer wavelengths 360, 361, …, 830 nm of s(λ)·c̄(λ)·Δλ with Δλ = 1 nm and c̄ the CIE 1931 2°
//! table ([`cmf_1931_at_nm`]).
//!
//! - Absolute (light): X = K_m Σ L(λ) x̄(λ) Δλ, Y in cd m⁻² for L in W m⁻² sr⁻¹ nm⁻¹.
//! - Relative (surface colour under an illuminant S): X = 100 Σ R S x̄ Δλ / Σ S ȳ Δλ, so the
//!   perfect white has Y = 100.
//! - Linear sRGB from XYZ (Y = 1 for white) with the IEC 61966-2-1 matrix; the sRGB transfer
//!   function for display.
//!
//! # References
//! - CIE 015:2018, *Colorimetry*, 4th ed., §7 (tristimulus values, k = 100 / Σ S ȳ Δλ).
//! - CIE 018:2019 / BIPM SI brochure: K_m = 683.002 lm W⁻¹ (K_cd = 683 lm W⁻¹ at 540 THz,
//!   i.e. 555.016 nm in air, rescaled to the peak of ȳ at 555 nm).
//! - IEC 61966-2-1:1999, *sRGB*, §5.2 (transfer function) and §5.3 (matrices).

use super::cie::cmf_1931_at_nm;
use super::{Bands, Spectrum};

/// Maximum luminous efficacy for photopic vision, lm/W.
pub const K_M: f64 = 683.002;

/// First integer wavelength of the tristimulus sums, nm.
pub const SUM_START_NM: u32 = 360;
/// Last integer wavelength of the tristimulus sums, nm.
pub const SUM_END_NM: u32 = 830;

/// XYZ → linear sRGB, IEC 61966-2-1 §5.3 (D65 white, 4 decimals as published).
pub const XYZ_TO_SRGB: [[f64; 3]; 3] =
    [[3.2406, -1.5372, -0.4986], [-0.9689, 1.8758, 0.0415], [0.0557, -0.2040, 1.0570]];

/// Converts per-band spectral radiance (W m⁻² sr⁻¹ nm⁻¹) to absolute XYZ (Y in cd m⁻²) and
/// linear sRGB.
///
/// The band values v_0 … v_{N−1} stand for the spectrum reconstructed as the piecewise-linear
/// function through (min_nm, v_0), (centre_0, v_0), (centre_1, v_1), …, (centre_{N−1}, v_{N−1}),
/// (max_nm, v_{N−1}), zero outside [min_nm, max_nm] (constant over the outer half bands). Then
/// X = K_m Σ_{λ = 360}^{830} L(λ) x̄(λ) · 1 nm (and likewise Y, Z), with λ = min_nm and
/// λ = max_nm included when they are integers. L is linear in the v_i, so X = Σ_i v_i W_i with
/// W_i = K_m Σ_λ φ_i(λ) x̄(λ), φ_i being the hat function of band i in the reconstruction; the
/// weights W_i (and M·W_i for sRGB) are computed once and conversion is a dot product.
#[derive(Clone, Debug)]
pub struct BandsToColour {
    xyz_weights: Vec<[f64; 3]>,
    rgb_weights: Vec<[f64; 3]>,
}

impl BandsToColour {
    /// The band weights for `bands`.
    pub fn new(bands: &Bands) -> BandsToColour {
        let n = bands.count;
        let w = bands.width_nm();
        let (c_first, c_last) = (bands.centre_nm(0), bands.centre_nm(n - 1));
        let mut xyz_weights = vec![[0.0; 3]; n];
        for nm in SUM_START_NM..=SUM_END_NM {
            let l = f64::from(nm);
            if l < bands.min_nm || l > bands.max_nm {
                continue;
            }
            let cmf = cmf_1931_at_nm(nm).map(|c| K_M * c);
            let mut add = |i: usize, phi: f64| {
                for k in 0..3 {
                    xyz_weights[i][k] += phi * cmf[k];
                }
            };
            if l <= c_first {
                add(0, 1.0);
            } else if l >= c_last {
                add(n - 1, 1.0);
            } else {
                let j = (((l - c_first) / w).floor() as usize).min(n - 2);
                let t = (l - bands.centre_nm(j)) / w;
                add(j, 1.0 - t);
                add(j + 1, t);
            }
        }
        let rgb_weights = xyz_weights.iter().map(|&w| xyz_to_linear_srgb(w)).collect();
        BandsToColour { xyz_weights, rgb_weights }
    }

    /// Absolute XYZ (Y in cd m⁻²) of per-band spectral radiance; `values` has one entry per
    /// band (extra entries are ignored, missing ones count as zero).
    pub fn xyz(&self, values: &[f64]) -> [f64; 3] {
        dot(&self.xyz_weights, values)
    }

    /// Linear sRGB (absolute: Y in cd m⁻², so white of luminance 1 cd m⁻² is ≈ (1, 1, 1)).
    pub fn linear_srgb(&self, values: &[f64]) -> [f64; 3] {
        dot(&self.rgb_weights, values)
    }

    /// The per-band XYZ weights W_i (cd m⁻² per W m⁻² sr⁻¹ nm⁻¹).
    pub fn xyz_weights(&self) -> &[[f64; 3]] {
        &self.xyz_weights
    }
}

fn dot(weights: &[[f64; 3]], values: &[f64]) -> [f64; 3] {
    let mut out = [0.0; 3];
    for (w, v) in weights.iter().zip(values) {
        for k in 0..3 {
            out[k] += w[k] * v;
        }
    }
    out
}

/// Σ_{λ=360}^{830} s(λ) (x̄, ȳ, z̄)(λ) · 1 nm, without any normalisation.
pub fn cmf_sums(s: impl Fn(f64) -> f64) -> [f64; 3] {
    let mut out = [0.0; 3];
    for nm in SUM_START_NM..=SUM_END_NM {
        let v = s(f64::from(nm));
        let c = cmf_1931_at_nm(nm);
        for k in 0..3 {
            out[k] += v * c[k];
        }
    }
    out
}

/// Absolute XYZ (Y in cd m⁻²) of a spectral radiance in W m⁻² sr⁻¹ nm⁻¹.
pub fn absolute_xyz(radiance: &Spectrum) -> [f64; 3] {
    cmf_sums(|l| radiance.eval(l)).map(|c| K_M * c)
}

/// Relative XYZ of a reflectance under an illuminant, scaled so the perfect reflector has
/// Y = 100 (CIE 015:2018 §7.1).
pub fn relative_xyz(reflectance: &Spectrum, illuminant: &Spectrum) -> [f64; 3] {
    let white = cmf_sums(|l| illuminant.eval(l));
    let k = 100.0 / white[1];
    cmf_sums(|l| reflectance.eval(l) * illuminant.eval(l)).map(|c| k * c)
}

/// XYZ to linear sRGB (IEC 61966-2-1, D65 white).
pub fn xyz_to_linear_srgb(xyz: [f64; 3]) -> [f64; 3] {
    mat_vec(&XYZ_TO_SRGB, xyz)
}

/// Linear sRGB to XYZ: the exact inverse of [`xyz_to_linear_srgb`] (so round trips are exact;
/// it agrees with the IEC's published RGB → XYZ matrix to its 4 decimals).
pub fn linear_srgb_to_xyz(rgb: [f64; 3]) -> [f64; 3] {
    mat_vec(&invert3(&XYZ_TO_SRGB), rgb)
}

/// Luminance of linear sRGB, Y = 0.2126 R + 0.7152 G + 0.0722 B (IEC 61966-2-1 §5.3).
pub fn linear_srgb_luminance(rgb: [f64; 3]) -> f64 {
    0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]
}

/// The sRGB transfer function (linear → encoded), IEC 61966-2-1.
///
/// V = 12.92 L for L ≤ 0.0031308, else 1.055 L^(1/2.4) − 0.055.
pub fn srgb_encode(linear: f64) -> f64 {
    if linear <= 0.003_130_8 { 12.92 * linear } else { 1.055 * linear.powf(1.0 / 2.4) - 0.055 }
}

fn mat_vec(m: &[[f64; 3]; 3], v: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|r| m[r][0] * v[0] + m[r][1] * v[1] + m[r][2] * v[2])
}

/// Inverse of a 3×3 matrix by cofactors (the matrices here are well conditioned).
fn invert3(m: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let c = |r: usize, k: usize| {
        let (r1, r2) = ((r + 1) % 3, (r + 2) % 3);
        let (k1, k2) = ((k + 1) % 3, (k + 2) % 3);
        m[r1][k1] * m[r2][k2] - m[r1][k2] * m[r2][k1]
    };
    let det = m[0][0] * c(0, 0) + m[0][1] * c(0, 1) + m[0][2] * c(0, 2);
    [0, 1, 2].map(|r| [0, 1, 2].map(|k| c(k, r) / det))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectrum::named_illuminant;

    fn close(a: [f64; 3], b: [f64; 3], tol: f64) -> bool {
        (0..3).all(|k| (a[k] - b[k]).abs() <= tol)
    }

    #[test]
    fn srgb_matrix_maps_the_d65_white_to_one() {
        // IEC 61966-2-1 D65 white, XYZ = (0.9505, 1.0000, 1.0890).
        let rgb = xyz_to_linear_srgb([0.9505, 1.0, 1.089]);
        assert!(close(rgb, [1.0; 3], 2e-4), "{rgb:?}");
        // The inverse's rows sum to the white; its middle row is the published luminance row.
        let white = linear_srgb_to_xyz([1.0; 3]);
        assert!(close(white, [0.9505, 1.0, 1.089], 2e-4), "{white:?}");
        let y_row = linear_srgb_to_xyz([1.0, 0.0, 0.0])[1];
        assert!((y_row - 0.2126).abs() < 1e-4, "{y_row}");
        let round = xyz_to_linear_srgb(linear_srgb_to_xyz([0.2, 0.5, 0.9]));
        assert!(close(round, [0.2, 0.5, 0.9], 1e-14));
    }

    #[test]
    fn transfer_function_hits_published_points() {
        assert_eq!(srgb_encode(0.0), 0.0);
        assert!((srgb_encode(1.0) - 1.0).abs() < 1e-12);
        // The breakpoint: 0.0031308 ↦ 0.04045 from both sides.
        assert!((srgb_encode(0.003_130_8) - 0.040_45).abs() < 1e-5);
        assert!((srgb_encode(0.003_130_81) - 0.040_45).abs() < 1e-5);
        // 18 % grey encodes to 0.4614 (8-bit 118).
        assert!((srgb_encode(0.18) - 0.461_4).abs() < 1e-4);
    }

    #[test]
    fn d65_white_is_srgb_white() {
        let d65 = named_illuminant("D65").unwrap();
        let xyz = relative_xyz(&Spectrum::Constant(1.0), &d65);
        assert!((xyz[1] - 100.0).abs() < 1e-12);
        // CIE 015:2018 Table 5: D65 white (2°) X = 95.04, Z = 108.88 (1 nm sums: 95.047, 108.883).
        assert!((xyz[0] - 95.04).abs() < 0.01 && (xyz[2] - 108.88).abs() < 0.01, "{xyz:?}");
        let rgb = xyz_to_linear_srgb(xyz.map(|c| c / 100.0));
        assert!(close(rgb, [1.0; 3], 1e-3), "{rgb:?}");
    }

    #[test]
    fn a_flat_radiance_has_the_luminance_of_k_m_times_the_y_sum() {
        // L = 1 W m⁻² sr⁻¹ nm⁻¹ over 360–830 nm: Y = 683.002 × 106.857 cd m⁻² (Σȳ, CIE 1 nm).
        let bands = Bands::new(360.0, 830.0, 47).unwrap();
        let conv = BandsToColour::new(&bands);
        let xyz = conv.xyz(&[1.0; 47]);
        assert!((xyz[1] / (K_M * 106.857) - 1.0).abs() < 1e-5, "{xyz:?}");
        // The same through the spectrum route.
        let direct = absolute_xyz(&Spectrum::Constant(1.0));
        assert!(close(xyz, direct, 1e-9 * direct[1]));
    }

    #[test]
    fn band_weights_are_the_documented_hat_functions() {
        // Bands 500–530 nm, centres 505, 515, 525 (width 10): v = (0, 1, 0) is the hat
        // 1 − |λ − 515| / 10 on [505, 525].
        let bands = Bands::new(500.0, 530.0, 3).unwrap();
        let conv = BandsToColour::new(&bands);
        let got = conv.xyz(&[0.0, 1.0, 0.0]);
        let mut want = [0.0; 3];
        for nm in 505..=525u32 {
            let phi = 1.0 - (f64::from(nm) - 515.0).abs() / 10.0;
            let c = cmf_1931_at_nm(nm);
            for k in 0..3 {
                want[k] += K_M * phi * c[k];
            }
        }
        assert!(close(got, want, 1e-9), "{got:?} vs {want:?}");
        // v = (1, 0, 0): flat on [500, 505], falling to 0 at 515.
        let got = conv.xyz(&[1.0, 0.0, 0.0]);
        let mut want = [0.0; 3];
        for nm in 500..=515u32 {
            let phi = if nm <= 505 { 1.0 } else { (515.0 - f64::from(nm)) / 10.0 };
            let c = cmf_1931_at_nm(nm);
            for k in 0..3 {
                want[k] += K_M * phi * c[k];
            }
        }
        assert!(close(got, want, 1e-9), "{got:?} vs {want:?}");
        // A single band is a box over its range.
        let one = BandsToColour::new(&Bands::new(550.0, 560.0, 1).unwrap());
        let y: f64 = (550..=560u32).map(|nm| K_M * cmf_1931_at_nm(nm)[1]).sum();
        assert!((one.xyz(&[1.0])[1] - y).abs() < 1e-9);
        // sRGB is the matrix applied to XYZ.
        let v = [0.3, 1.2, 0.7];
        assert!(close(conv.linear_srgb(&v), xyz_to_linear_srgb(conv.xyz(&v)), 1e-9));
    }
}
