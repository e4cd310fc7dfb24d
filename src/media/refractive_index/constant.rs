//! A homogeneous medium: the same n(λ) everywhere, from a dispersion law.

use crate::atmosphere::AirDispersion;
use crate::material::Ior;

/// n(λ) independent of position.
#[derive(Clone, Debug, PartialEq)]
pub enum Constant {
    /// A constant, Cauchy or Sellmeier law (see [`Ior`]).
    Ior(Ior),
    /// Air of a given density: n = 1 + K(λ)·ρ (Gladstone–Dale, see [`AirDispersion`]).
    Air {
        /// Gladstone–Dale law K(λ) of the air.
        dispersion: AirDispersion,
        /// Air density ρ, kg m⁻³.
        density_kg_m3: f64,
    },
}

impl Constant {
    /// n(λ).
    pub fn n(&self, wavelength_nm: f64) -> f64 {
        match self {
            Constant::Ior(ior) => ior.eval(wavelength_nm),
            Constant::Air { dispersion, density_kg_m3 } => dispersion.n(wavelength_nm, *density_kg_m3),
        }
    }

    /// True when n depends on wavelength.
    pub fn is_dispersive(&self) -> bool {
        match self {
            Constant::Ior(ior) => ior.is_dispersive(),
            Constant::Air { density_kg_m3, .. } => *density_kg_m3 != 0.0,
        }
    }

    /// The air law's wavelength range, for air.
    pub fn check_range(&self, range_nm: (f64, f64)) -> Result<(), String> {
        match self {
            Constant::Ior(_) => Ok(()),
            Constant::Air { dispersion, .. } => dispersion.check_range(range_nm),
        }
    }

    /// The smallest n over [min_nm, max_nm], sampled every nanometre and at the ends (NaN if any
    /// sample is NaN).
    pub fn min_n(&self, (min_nm, max_nm): (f64, f64)) -> f64 {
        let steps = ((max_nm - min_nm).abs().ceil() as usize).clamp(1, 100_000);
        (0..=steps)
            .map(|i| self.n(min_nm + (max_nm - min_nm) * i as f64 / steps as f64))
            .fold(f64::INFINITY, |a, v| if a.is_nan() || v.is_nan() { f64::NAN } else { a.min(v) })
    }
}
