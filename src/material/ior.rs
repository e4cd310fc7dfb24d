//! Refractive index of transparent solids and liquids as a function of wavelength.
//!
//! # References
//! - Cauchy's formula n(λ) = A + B/λ² + C/λ⁴ (λ in μm): Born & Wolf, *Principles of Optics*,
//!   7th ed., §2.3.
//! - Sellmeier's formula n²(λ) = 1 + Σᵢ Bᵢλ²/(λ² − Cᵢ) (λ in μm, Cᵢ in μm²).
//! - N-BK7: SCHOTT optical glass data sheet N-BK7 (517642.251), Sellmeier coefficients
//!   B = (1.03961212, 0.231792344, 1.01046945), C = (0.00600069867, 0.0200179144, 103.560653) μm²;
//!   n_d (587.56 nm) = 1.51680.
//! - Fused silica: Malitson 1965, "Interspecimen comparison of the refractive index of fused
//!   silica", J. Opt. Soc. Am. 55:1205. B = (0.6961663, 0.4079426, 0.8974794),
//!   C = (0.0684043², 0.1162414², 9.896161²) μm²; n_d = 1.4585.
//! - Water and sea water: Quan & Fry 1995, "Empirical equation for the index of refraction of
//!   seawater", Appl. Opt. 34:3477–3480, for S = 0–35 ‰, T = 0–30 °C, λ = 400–700 nm (λ in nm):
//!   n = n₀ + (n₁ + n₂T + n₃T²)S + n₄T² + (n₅ + n₆S + n₇T)/λ + n₈/λ² + n₉/λ³, with
//!   n₀ = 1.31405, n₁ = 1.779·10⁻⁴, n₂ = −1.05·10⁻⁶, n₃ = 1.6·10⁻⁸, n₄ = −2.02·10⁻⁶,
//!   n₅ = 15.868, n₆ = 0.01155, n₇ = −0.00423, n₈ = −4382, n₉ = 1.1455·10⁶.
//!   Catalogue names: "water" (S = 0, T = 20 °C), "seawater" (S = 35 ‰, T = 20 °C).

use serde::Serialize;

/// The largest refractive index a material may have: 10, above every transparent material
/// (germanium's ≈ 4 in the infrared, silicon's ≈ 3.5, rutile's 2.9, diamond's 2.4); an index of
/// 9 × 10¹⁸ was accepted before and rendered NaN pixels.
pub const MAX_IOR: f64 = 10.0;

/// A refractive index as a function of wavelength: a constant or a dispersion law.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "model", rename_all = "snake_case")]
pub enum Ior {
    /// The same n at every wavelength.
    Constant {
        /// The index n.
        n: f64,
    },
    /// Cauchy: n = a + b/λ² + c/λ⁴, λ in μm.
    Cauchy {
        /// Constant term a.
        a: f64,
        /// b, μm².
        b_um2: f64,
        /// c, μm⁴.
        c_um4: f64,
    },
    /// Sellmeier: n² = 1 + Σᵢ Bᵢλ²/(λ² − Cᵢ), λ in μm.
    Sellmeier {
        /// Coefficients B₁..B₃ (dimensionless).
        b: [f64; 3],
        /// Coefficients C₁..C₃, μm².
        c_um2: [f64; 3],
    },
    /// Quan & Fry (1995) for water of salinity S (‰) at temperature T (°C).
    QuanFry {
        /// Salinity S, ‰ (PSU); the fit covers 0 to 35.
        salinity_psu: f64,
        /// Temperature T, °C; the fit covers 0 to 30.
        temperature_c: f64,
    },
}

impl Ior {
    /// n at `wavelength_nm`.
    pub fn eval(&self, wavelength_nm: f64) -> f64 {
        let l_um = wavelength_nm * 1e-3;
        let l2 = l_um * l_um;
        match self {
            Ior::Constant { n } => *n,
            Ior::Cauchy { a, b_um2, c_um4 } => a + b_um2 / l2 + c_um4 / (l2 * l2),
            Ior::Sellmeier { b, c_um2 } => {
                let s: f64 = b.iter().zip(c_um2).map(|(b, c)| b * l2 / (l2 - c)).sum();
                (1.0 + s).sqrt()
            }
            Ior::QuanFry { salinity_psu: s, temperature_c: t } => quan_fry(*s, *t, wavelength_nm),
        }
    }

    /// True unless the index is the same at every wavelength.
    pub fn is_dispersive(&self) -> bool {
        match self {
            Ior::Constant { .. } => false,
            Ior::Cauchy { b_um2, c_um4, .. } => *b_um2 != 0.0 || *c_um4 != 0.0,
            Ior::Sellmeier { .. } | Ior::QuanFry { .. } => true,
        }
    }

    /// Checks 1 ≤ n ≤ `MAX_IOR` over [min_nm, max_nm] (sampled every nm and at the ends);
    /// the error names the first offending wavelength.
    pub fn validate(&self, min_nm: f64, max_nm: f64) -> Result<(), String> {
        let steps = ((max_nm - min_nm).ceil() as usize).max(1);
        for i in 0..=steps {
            let l = min_nm + (max_nm - min_nm) * i as f64 / steps as f64;
            let n = self.eval(l);
            if !(1.0..=MAX_IOR).contains(&n) {
                return Err(format!(
                    "refractive index is {n} at {l:.1} nm; it must be between 1 and {MAX_IOR} over the \
                     scene's wavelength range {min_nm}–{max_nm} nm"
                ));
            }
        }
        Ok(())
    }
}

/// n of sea water by Quan & Fry (1995), λ in nm.
fn quan_fry(s: f64, t: f64, l: f64) -> f64 {
    1.31405 + (1.779e-4 - 1.05e-6 * t + 1.6e-8 * t * t) * s - 2.02e-6 * t * t + (15.868 + 0.01155 * s - 0.00423 * t) / l
        - 4382.0 / (l * l)
        + 1.1455e6 / (l * l * l)
}

/// A glass from the built-in catalogue: "N-BK7" (alias "BK7") or "fused_silica".
pub fn named_glass(name: &str) -> Option<Ior> {
    match name {
        "N-BK7" | "BK7" => Some(Ior::Sellmeier {
            b: [1.039_612_12, 0.231_792_344, 1.010_469_45],
            c_um2: [0.006_000_698_67, 0.020_017_914_4, 103.560_653],
        }),
        "fused_silica" => Some(Ior::Sellmeier {
            b: [0.696_166_3, 0.407_942_6, 0.897_479_4],
            c_um2: [0.068_404_3f64.powi(2), 0.116_241_4f64.powi(2), 9.896_161f64.powi(2)],
        }),
        "water" => Some(Ior::QuanFry { salinity_psu: 0.0, temperature_c: 20.0 }),
        "seawater" => Some(Ior::QuanFry { salinity_psu: 35.0, temperature_c: 20.0 }),
        _ => None,
    }
}

/// Names accepted by [`named_glass`], for error messages.
pub const GLASS_NAMES: &[&str] = &["N-BK7", "BK7", "fused_silica", "water", "seawater"];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn catalogue_glasses_match_their_published_nd() {
        // n_d at the helium d line, 587.5618 nm.
        let bk7 = named_glass("N-BK7").unwrap().eval(587.5618);
        assert!((bk7 - 1.51680).abs() < 2e-5, "N-BK7 n_d = {bk7}");
        let silica = named_glass("fused_silica").unwrap().eval(587.5618);
        assert!((silica - 1.4585).abs() < 1e-4, "fused silica n_d = {silica}");
        // Abbe number of N-BK7 is 64.17 (SCHOTT): (n_d − 1)/(n_F − n_C), F = 486.1327, C = 656.2725 nm.
        let g = named_glass("N-BK7").unwrap();
        let v = (g.eval(587.5618) - 1.0) / (g.eval(486.1327) - g.eval(656.2725));
        assert!((v - 64.17).abs() < 0.05, "Abbe number {v}");
    }

    #[test]
    fn quan_fry_matches_published_indices_of_water() {
        // Pure water at 20 °C, 589.3 nm: n_D = 1.33299 (CRC Handbook; Quan & Fry's fit is within
        // 1e-4 of the data it was fitted to, Austin & Halikas 1976).
        let w = named_glass("water").unwrap().eval(589.3);
        assert!((w - 1.33299).abs() < 1e-4, "water n_D = {w}");
        // Sea water of 35 ‰ at 20 °C: n_D ≈ 1.3394 (Austin & Halikas 1976, the data Quan & Fry
        // fitted).
        let sw = named_glass("seawater").unwrap().eval(589.3);
        assert!((sw - 1.3394).abs() < 5e-4, "sea water n_D = {sw}");
        assert!(named_glass("water").unwrap().eval(450.0) > w, "normal dispersion");
    }

    #[test]
    fn normal_dispersion_and_validation() {
        let g = named_glass("BK7").unwrap();
        assert!(g.eval(450.0) > g.eval(650.0), "blue bends more");
        assert!(g.is_dispersive() && !Ior::Constant { n: 1.5 }.is_dispersive());
        let cauchy = Ior::Cauchy { a: 1.5046, b_um2: 0.00420, c_um4: 0.0 };
        assert!((cauchy.eval(500.0) - (1.5046 + 0.0042 / 0.25)).abs() < 1e-12);
        assert!(Ior::Constant { n: 0.9 }.validate(380.0, 780.0).is_err());
        assert!(g.validate(380.0, 780.0).is_ok());
    }
}
