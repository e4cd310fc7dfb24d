//! The refractive index of air through the Gladstone–Dale relation n − 1 = K(λ)·ρ: refractivity
//! is proportional to density, with K(λ) = (n_ref(λ) − 1)/ρ_ref fixed by a reference law at a
//! reference state. Gutierrez et al. 2005 (Eqs. 17–18) use Cauchy's law; Ciddor 1996 is the
//! modern alternative (it is itself Gladstone–Dale scaling of standard air, Ciddor Eq. 5).
//!
//! K and ρ must be the same kind of density. Ciddor's ρ_ref is the real-gas density
//! pM_a/(ZRT) of standard air, so air given by its pressure and temperature (atmospheres,
//! temperature grids) gets n − 1 from [`AirDispersion::refractivity_grad`], which scales by the
//! real-gas density at (p, T) — Ciddor's own formula. (Scaling the ideal-gas density by Ciddor's K
//! put n − 1 0.04 % low at every height: the compressibility Z ≈ 0.9996.) Cauchy's K refers to
//! the ideal-gas density of its reference state, and is scaled by the ideal-gas density.
//!
//! # References
//! - J. H. Gladstone & T. P. Dale 1858, "On the influence of temperature on the refraction of
//!   light", Phil. Trans. R. Soc. 148:887–894.

mod cauchy;
mod ciddor;

pub use cauchy::CauchyBornWolf;
pub use ciddor::Ciddor;

/// A law for K(λ) of air.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum AirDispersion {
    /// Cauchy's formula for air at 0 °C, 1 atm (Born & Wolf).
    CauchyBornWolf,
    /// Ciddor 1996 standard dry air with a CO₂ mole fraction.
    Ciddor(Ciddor),
}

/// Wavelengths (nm) over which the air laws are evaluated; outside, they are extrapolations (and
/// Ciddor's poles at 65 and 132 nm make them meaningless).
pub const AIR_LAW_RANGE_NM: (f64, f64) = (200.0, 2000.0);

impl AirDispersion {
    /// Ciddor's law for `co2_ppm` (0–2000 µmol/mol, the range Ciddor 1996 covers).
    pub fn ciddor(co2_ppm: f64) -> Result<AirDispersion, String> {
        Ciddor::new(co2_ppm).map(AirDispersion::Ciddor)
    }

    /// K(λ) = (n_ref(λ) − 1)/ρ_ref, m³ kg⁻¹.
    pub fn gladstone_dale_m3_per_kg(&self, wavelength_nm: f64) -> f64 {
        match self {
            AirDispersion::CauchyBornWolf => CauchyBornWolf::gladstone_dale_m3_per_kg(wavelength_nm),
            AirDispersion::Ciddor(c) => c.gladstone_dale_m3_per_kg(wavelength_nm),
        }
    }

    /// n = 1 + K(λ)·ρ, ρ the density K refers to (see the module notes).
    pub fn n(&self, wavelength_nm: f64, density_kg_m3: f64) -> f64 {
        1.0 + self.gladstone_dale_m3_per_kg(wavelength_nm) * density_kg_m3
    }

    /// n − 1 of air at `pressure_pa` and `temperature_k`, N = K(λ)·ρ(p, T) with the density
    /// each law's K refers to, and its partial derivatives: (N, ∂N/∂p in Pa⁻¹, ∂N/∂T in K⁻¹).
    /// Ciddor: Ciddor's Eq. 5 with his real-gas density (compressibility Z); Cauchy: the ideal
    /// gas with the USA76 constants ([`super::gas::density_kg_m3`]).
    pub fn refractivity_grad(&self, wavelength_nm: f64, pressure_pa: f64, temperature_k: f64) -> (f64, f64, f64) {
        match self {
            AirDispersion::CauchyBornWolf => {
                let n = CauchyBornWolf::gladstone_dale_m3_per_kg(wavelength_nm)
                    * super::gas::density_kg_m3(pressure_pa, temperature_k);
                (n, n / pressure_pa, -n / temperature_k)
            }
            AirDispersion::Ciddor(c) => c.refractivity_grad(wavelength_nm, temperature_k, pressure_pa),
        }
    }

    /// The density D that K refers to at `pressure_pa` and `temperature_k`, so that
    /// n − 1 = K(λ)·D (the factor of [`AirDispersion::refractivity_grad`] that does not depend on
    /// wavelength), and its partial derivatives: (D in kg m⁻³, ∂D/∂p, ∂D/∂T).
    pub fn density_grad(&self, pressure_pa: f64, temperature_k: f64) -> (f64, f64, f64) {
        match self {
            AirDispersion::CauchyBornWolf => {
                let d = super::gas::density_kg_m3(pressure_pa, temperature_k);
                (d, d / pressure_pa, -d / temperature_k)
            }
            AirDispersion::Ciddor(c) => c.density_grad(temperature_k, pressure_pa),
        }
    }

    /// The scene's wavelength range must lie where the law is defined.
    pub fn check_range(&self, (min_nm, max_nm): (f64, f64)) -> Result<(), String> {
        let (lo, hi) = AIR_LAW_RANGE_NM;
        if min_nm < lo || max_nm > hi {
            return Err(format!(
                "the refractive index of air is defined here for {lo}–{hi} nm; the scene asks for {min_nm}–{max_nm} nm"
            ));
        }
        Ok(())
    }

    /// The name used in atmosphere files.
    pub fn name(&self) -> &'static str {
        match self {
            AirDispersion::CauchyBornWolf => "cauchy_born_wolf",
            AirDispersion::Ciddor(_) => "ciddor",
        }
    }
}
