//! A positive quantity tabulated against wavelength and read as a power law between samples:
//! ln y linear in ln λ, the form of cross-sections that fall as λ⁻⁴ (Rayleigh) or as another
//! power (Ångström).
//!
//! Between samples j and j + 1:
//!
//! y(λ) = y_j (λ/λ_j)^k_j,  k_j = ln(y_{j+1}/y_j) / ln(λ_{j+1}/λ_j),
//!
//! which reproduces a pure power law exactly whatever the spacing (linear interpolation of λ⁻⁴
//! between 351 and 435 nm is 5 % high in the middle). Beyond the ends the end segment's power law
//! continues; callers that must not extrapolate check [`PowerLawTable::domain_nm`] first.

/// Samples (λ_j, y_j), y_j > 0, read as a power law between them (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct PowerLawTable {
    ln_nm: Vec<f64>,
    ln_y: Vec<f64>,
    nm: (f64, f64),
}

impl PowerLawTable {
    /// At least two samples, wavelengths finite, positive and strictly increasing, values finite
    /// and positive (a power law cannot pass through zero).
    pub fn new(nm: &[f64], values: &[f64]) -> Result<PowerLawTable, String> {
        if nm.len() != values.len() {
            return Err(format!("{} wavelengths but {} values: need one value per wavelength", nm.len(), values.len()));
        }
        if nm.len() < 2 {
            return Err(format!("{} sample(s): need at least 2", nm.len()));
        }
        if let Some(i) = nm.iter().position(|x| !(x.is_finite() && *x > 0.0)) {
            return Err(format!("wavelength #{} is {}: wavelengths must be positive numbers (nm)", i + 1, nm[i]));
        }
        if let Some(i) = nm.windows(2).position(|w| w[1] <= w[0]) {
            return Err(format!(
                "wavelengths are not strictly increasing: #{} is {} nm after {} nm",
                i + 2,
                nm[i + 1],
                nm[i]
            ));
        }
        if let Some(i) = values.iter().position(|y| !(y.is_finite() && *y > 0.0)) {
            return Err(format!(
                "value #{} (at {} nm) is {}: values must be positive (they are read as a power law between samples)",
                i + 1,
                nm[i],
                values[i]
            ));
        }
        Ok(PowerLawTable {
            ln_nm: nm.iter().map(|x| x.ln()).collect(),
            ln_y: values.iter().map(|y| y.ln()).collect(),
            nm: (nm[0], nm[nm.len() - 1]),
        })
    }

    /// y(λ): the power law through the samples around λ (the end segment's beyond the ends).
    pub fn eval(&self, wavelength_nm: f64) -> f64 {
        let x = wavelength_nm.ln();
        let last = self.ln_nm.len() - 2;
        let j = self.ln_nm[1..=last].partition_point(|&l| l <= x);
        let k = (self.ln_y[j + 1] - self.ln_y[j]) / (self.ln_nm[j + 1] - self.ln_nm[j]);
        (self.ln_y[j] + k * (x - self.ln_nm[j])).exp()
    }

    /// [first, last] sampled wavelength, nm.
    pub fn domain_nm(&self) -> (f64, f64) {
        self.nm
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_power_law_is_reproduced_between_and_beyond_sparse_samples() {
        let law = |nm: f64| 3.0e-26 * (nm / 550.0).powf(-4.08);
        let nm = [300.0, 351.0, 435.0, 700.0, 1020.0];
        let t = PowerLawTable::new(&nm, &nm.map(law)).unwrap();
        for x in [250.0, 300.0, 320.5, 351.0, 393.0, 550.0, 1020.0, 1700.0] {
            assert!((t.eval(x) / law(x) - 1.0).abs() < 1e-12, "{x} nm: {} against {}", t.eval(x), law(x));
        }
    }

    #[test]
    fn each_segment_has_its_own_exponent_and_the_samples_are_hit() {
        let (nm, y) = ([400.0, 500.0, 600.0], [1.0, 0.5, 0.4]);
        let t = PowerLawTable::new(&nm, &y).unwrap();
        for (x, v) in nm.iter().zip(y) {
            assert!((t.eval(*x) - v).abs() < 1e-15, "{x}");
        }
        let k0 = (0.5f64).ln() / (500.0f64 / 400.0).ln();
        assert!((t.eval(450.0) - (450.0f64 / 400.0).powf(k0)).abs() < 1e-14);
        let k1 = (0.8f64).ln() / (600.0f64 / 500.0).ln();
        assert!((t.eval(550.0) - 0.5 * (550.0f64 / 500.0).powf(k1)).abs() < 1e-14);
    }

    #[test]
    fn bad_tables_are_refused_with_the_sample_named() {
        let cases: [(&[f64], &[f64], &str); 5] = [
            (&[400.0], &[1.0], "need at least 2"),
            (&[400.0, 500.0], &[1.0], "one value per wavelength"),
            (&[400.0, 400.0], &[1.0, 2.0], "#2 is 400 nm after 400 nm"),
            (&[400.0, 500.0], &[1.0, 0.0], "value #2 (at 500 nm) is 0"),
            (&[-1.0, 500.0], &[1.0, 2.0], "wavelength #1 is -1"),
        ];
        for (nm, y, expected) in cases {
            let e = PowerLawTable::new(nm, y).unwrap_err();
            assert!(e.contains(expected), "{e}");
        }
    }
}
