//! RGB albedo to a smooth reflectance spectrum (Jakob & Hanika 2019).

/// A sigmoid-polynomial reflectance s(λ) = S(c0 λ² + c1 λ + c2) in [0, 1].
#[derive(Clone, Debug, PartialEq)]
pub struct RgbSigmoid {
    pub coefficients: [f64; 3],
}

impl RgbSigmoid {
    /// Fits the spectrum whose linear-sRGB albedo under D65 is `rgb` (each in [0, 1]).
    pub fn fit(rgb: [f64; 3]) -> Result<RgbSigmoid, String> {
        todo!("{rgb:?}")
    }
    pub fn eval(&self, wavelength_nm: f64) -> f64 {
        todo!("{wavelength_nm}")
    }
}
