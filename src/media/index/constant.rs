//! A homogeneous medium: the same n(λ) everywhere, from a dispersion law.

use crate::material::Ior;

/// n(λ) independent of position.
#[derive(Clone, Debug, PartialEq)]
pub enum Constant {
    /// A constant, Cauchy or Sellmeier law (see [`Ior`]).
    Ior(Ior),
}

impl Constant {
    pub fn n(&self, wavelength_nm: f64) -> f64 {
        match self {
            Constant::Ior(ior) => ior.eval(wavelength_nm),
        }
    }

    pub fn is_dispersive(&self) -> bool {
        match self {
            Constant::Ior(ior) => ior.is_dispersive(),
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
