//! Pure (sea) water: absorption and scattering.
//!
//! - Absorption a_w(λ): Pope & Fry (1997) over 380–727.5 nm, Smith & Baker (1981) outside it
//!   (200–800 nm), each held at its last value beyond.
//! - Scattering b_w(λ) = 0.0029 (λ/500)^−4.32 m⁻¹ (sea water; Morel 1974 as used by Mobley 1994,
//!   Table 3.8 and Eq. 3.39), with the pure-water phase function 0.06225 (1 + 0.835 cos²ψ).
//!
//! # References
//! - Pope & Fry, "Absorption spectrum (380–700 nm) of pure water. II. Integrating cavity
//!   measurements", Appl. Opt. 36 (1997), 8710–8723.
//! - Smith & Baker, "Optical properties of the clearest natural waters (200–800 nm)", Appl. Opt.
//!   20 (1981), 177–184.
//! - Morel, "Optical properties of pure water and pure sea water" (1974); Mobley, *Light and
//!   Water* (1994), §3.6.

use super::builtin::{OceanData, POPE_FRY_FILE, SMITH_BAKER_FILE};
use super::tables::clamped;
use crate::spectrum::Tabulated;

/// The two absorption tables.
#[derive(Clone, Debug)]
pub struct WaterAbsorption {
    pope_fry: Tabulated,
    smith_baker: Tabulated,
}

impl WaterAbsorption {
    /// Reads both absorption tables from the built-in data or the scene's `data_dir`.
    pub fn read(data: &OceanData) -> Result<WaterAbsorption, String> {
        Ok(WaterAbsorption {
            pope_fry: data.column(POPE_FRY_FILE, 2, 1)?,
            smith_baker: data.column(SMITH_BAKER_FILE, 2, 1)?,
        })
    }

    /// The wavelengths the tables cover together, nm (Smith & Baker's 200–800 nm).
    pub fn domain_nm(&self) -> (f64, f64) {
        let (a, b) = self.pope_fry.domain_nm();
        let (c, d) = self.smith_baker.domain_nm();
        (a.min(c), b.max(d))
    }

    /// a_w(λ), m⁻¹.
    pub fn at(&self, wavelength_nm: f64) -> f64 {
        let (lo, hi) = self.pope_fry.domain_nm();
        if (lo..=hi).contains(&wavelength_nm) {
            self.pope_fry.eval(wavelength_nm)
        } else {
            clamped(&self.smith_baker, wavelength_nm)
        }
    }
}

/// b_w(λ) = 0.0029 (λ/500)^−4.32, m⁻¹.
pub fn scattering(wavelength_nm: f64) -> f64 {
    0.0029 * (wavelength_nm / 500.0).powf(-4.32)
}
