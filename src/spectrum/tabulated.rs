//! Piecewise-linear spectra from samples.

/// Piecewise linear through (nm[i], values[i]); zero outside [nm[0], nm[last]].
#[derive(Clone, Debug, PartialEq)]
pub struct Tabulated {
    nm: Vec<f64>,
    values: Vec<f64>,
}

impl Tabulated {
    /// At least two samples, strictly increasing finite wavelengths, finite values.
    pub fn new(nm: Vec<f64>, values: Vec<f64>) -> Result<Tabulated, String> {
        todo!(
            "spectrum helper: validate and build {} {}",
            nm.len(),
            values.len()
        )
    }
    pub fn eval(&self, wavelength_nm: f64) -> f64 {
        todo!("{wavelength_nm}")
    }
    /// Exact integral of the piecewise-linear function over [a, b].
    pub fn integral(&self, a: f64, b: f64) -> f64 {
        todo!("{a}{b}")
    }
    /// The sampled wavelength domain.
    pub fn domain_nm(&self) -> (f64, f64) {
        (self.nm[0], self.nm[self.nm.len() - 1])
    }
    pub fn samples(&self) -> (&[f64], &[f64]) {
        (&self.nm, &self.values)
    }
}
