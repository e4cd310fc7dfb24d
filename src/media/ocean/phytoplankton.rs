//! Chlorophyll-bearing particles: absorption after Bricaud et al. (1998), scattering after
//! Gordon & Morel (1983) / Loisel & Morel (1998), and chlorophyll fluorescence.
//!
//! - Absorption by all particles a_p(λ) = A_p(λ) Chl^{E_p(λ)} and by phytoplankton alone
//!   a_φ(λ) = A_φ(λ) Chl^{E_φ(λ)} (Chl in mg m⁻³, 400–700 nm; held at the end values outside).
//!   a_φ is the fluorescing component; a_p − a_φ (non-algal particles, ≥ 0) absorbs only.
//! - Scattering b_p(λ) = 0.30 Chl^0.62 (550/λ) m⁻¹ (Gordon & Morel 1983; the λ⁻¹ dependence as
//!   in Mobley 1994, Eq. 3.40; Loisel & Morel 1998 refine the coefficient for Case 1 waters).
//! - Fluorescence: Gaussian emission at 685 nm, σ = 10.6 nm, excited 370–690 nm, quantum yield
//!   Φ_C (default 0.02; 0.01–0.1 in the literature), isotropic, photon-number accounting
//!   (Mobley 1994, §5.12, Eq. 5.104).
//!
//! # References
//! - Bricaud, Morel, Babin, Allali & Claustre, "Variations of light absorption by suspended
//!   particles with chlorophyll a concentration in oceanic (case 1) waters", JGR 103 (1998),
//!   31033–31044.
//! - Gordon & Morel, *Remote Assessment of Ocean Color for Interpretation of Satellite Visible
//!   Imagery* (1983).
//! - Loisel & Morel, "Light scattering and chlorophyll concentration in case 1 waters: a
//!   reexamination", Limnol. Oceanogr. 43 (1998), 847–858.

use super::builtin::{BRICAUD_FILE, OceanData};
use super::tables::{clamped, column};
use crate::spectrum::Tabulated;

/// Bricaud's coefficient tables.
#[derive(Clone, Debug)]
pub struct Bricaud {
    ap: Tabulated,
    ep: Tabulated,
    aphi: Tabulated,
    ephi: Tabulated,
}

impl Bricaud {
    /// Reads A_p, E_p, A_φ, E_φ from the built-in table or the scene's `data_dir`.
    pub fn read(data: &OceanData) -> Result<Bricaud, String> {
        let (path, rows) = data.rows(BRICAUD_FILE, 5)?;
        Ok(Bricaud {
            ap: column(&path, &rows, 1)?,
            ep: column(&path, &rows, 2)?,
            aphi: column(&path, &rows, 3)?,
            ephi: column(&path, &rows, 4)?,
        })
    }

    /// a_p(λ) for `chl` mg m⁻³, m⁻¹.
    pub fn particles(&self, chl: f64, wavelength_nm: f64) -> f64 {
        power_law(clamped(&self.ap, wavelength_nm), chl, clamped(&self.ep, wavelength_nm))
    }

    /// a_φ(λ), m⁻¹.
    pub fn phytoplankton(&self, chl: f64, wavelength_nm: f64) -> f64 {
        power_law(clamped(&self.aphi, wavelength_nm), chl, clamped(&self.ephi, wavelength_nm))
    }
}

fn power_law(a: f64, chl: f64, e: f64) -> f64 {
    if chl > 0.0 { a * chl.powf(e) } else { 0.0 }
}

/// b_p(λ) = 0.30 Chl^0.62 (550/λ), m⁻¹.
pub fn scattering(chl: f64, wavelength_nm: f64) -> f64 {
    if chl > 0.0 { 0.30 * chl.powf(0.62) * 550.0 / wavelength_nm } else { 0.0 }
}
