//! Piecewise-linear spectra from samples.
//!
//! `s(λ) = y_j + (y_{j+1} − y_j)(λ − λ_j)/(λ_{j+1} − λ_j)` on `[λ_j, λ_{j+1}]`, and zero outside
//! `[λ_0, λ_last]`. Its integral over [a, b] is the sum of exact trapezoids of the segments
//! clipped to [a, b] (the function is linear on each piece, so the trapezoid rule is exact).

/// Piecewise linear through `(nm[i], values[i])`; zero outside `[nm[0], nm[last]]`.
#[derive(Clone, Debug, PartialEq)]
pub struct Tabulated {
    nm: Vec<f64>,
    values: Vec<f64>,
}

impl Tabulated {
    /// At least two samples, strictly increasing finite wavelengths, finite values.
    pub fn new(nm: Vec<f64>, values: Vec<f64>) -> Result<Tabulated, String> {
        if nm.len() != values.len() {
            return Err(format!(
                "tabulated spectrum has {} wavelengths but {} values: need one value per wavelength",
                nm.len(),
                values.len()
            ));
        }
        if nm.len() < 2 {
            return Err(format!("tabulated spectrum has {} sample(s): need at least 2", nm.len()));
        }
        if let Some(i) = nm.iter().position(|x| !x.is_finite()) {
            return Err(format!(
                "tabulated spectrum wavelength #{i} is {}: wavelengths must be finite numbers (nm)",
                nm[i]
            ));
        }
        if let Some(i) = values.iter().position(|x| !x.is_finite()) {
            return Err(format!(
                "tabulated spectrum value #{i} (at {} nm) is {}: values must be finite numbers",
                nm[i], values[i]
            ));
        }
        if let Some(i) = nm.windows(2).position(|w| w[1] <= w[0]) {
            return Err(format!(
                "tabulated spectrum wavelengths are not strictly increasing: #{} is {} nm after {} nm",
                i + 1,
                nm[i + 1],
                nm[i]
            ));
        }
        Ok(Tabulated { nm, values })
    }

    /// s(λ), linear between samples, zero outside.
    pub fn eval(&self, wavelength_nm: f64) -> f64 {
        let (lo, hi) = self.domain_nm();
        if !(lo..=hi).contains(&wavelength_nm) {
            return 0.0;
        }
        let j = self.segment(wavelength_nm);
        self.lerp(j, wavelength_nm)
    }

    /// Exact integral of the piecewise-linear function over [a, b].
    pub fn integral(&self, a: f64, b: f64) -> f64 {
        if a.is_nan() || b.is_nan() {
            return f64::NAN;
        }
        if b < a {
            return -self.integral(b, a);
        }
        let (lo, hi) = self.domain_nm();
        let (a, b) = (a.max(lo), b.min(hi));
        if b <= a {
            return 0.0;
        }
        let (ja, jb) = (self.segment(a), self.segment(b));
        let mut sum = 0.0;
        for j in ja..=jb {
            let x0 = self.nm[j].max(a);
            let x1 = self.nm[j + 1].min(b);
            if x1 > x0 {
                sum += 0.5 * (x1 - x0) * (self.lerp(j, x0) + self.lerp(j, x1));
            }
        }
        sum
    }

    /// The sampled wavelength domain.
    pub fn domain_nm(&self) -> (f64, f64) {
        (self.nm[0], self.nm[self.nm.len() - 1])
    }

    /// The sample wavelengths (nm) and values.
    pub fn samples(&self) -> (&[f64], &[f64]) {
        (&self.nm, &self.values)
    }

    /// Index j of the segment [nm[j], nm[j+1]] holding `x` (clamped to the first/last segment).
    fn segment(&self, x: f64) -> usize {
        let k = self.nm.partition_point(|&w| w <= x);
        k.saturating_sub(1).min(self.nm.len() - 2)
    }

    fn lerp(&self, j: usize, x: f64) -> f64 {
        let (x0, x1) = (self.nm[j], self.nm[j + 1]);
        let (y0, y1) = (self.values[j], self.values[j + 1]);
        let t = (x - x0) / (x1 - x0);
        y0 + t * (y1 - y0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri() -> Tabulated {
        // A triangle of height 2 on [400, 500] peaking at 450, then flat 1 to 600.
        Tabulated::new(vec![400.0, 450.0, 500.0, 600.0], vec![0.0, 2.0, 1.0, 1.0]).unwrap()
    }

    #[test]
    fn evaluates_linearly_and_is_zero_outside() {
        let t = tri();
        assert_eq!(t.eval(425.0), 1.0);
        assert_eq!(t.eval(450.0), 2.0);
        assert_eq!(t.eval(475.0), 1.5);
        assert_eq!(t.eval(600.0), 1.0);
        assert_eq!(t.eval(399.999), 0.0);
        assert_eq!(t.eval(600.001), 0.0);
        assert_eq!(t.eval(f64::NAN), 0.0);
    }

    #[test]
    fn integral_is_exact() {
        let t = tri();
        // Triangle area 50·2/2 = 50 on [400,450]; trapezoid (2+1)/2·50 = 75; rectangle 100.
        assert!((t.integral(0.0, 1000.0) - 225.0).abs() < 1e-12);
        assert!((t.integral(400.0, 450.0) - 50.0).abs() < 1e-12);
        // Partial segment: ∫_{425}^{475} = ∫_{425}^{450} (1..2) + ∫_{450}^{475} (2..1.5)
        //   = 25·1.5 + 25·1.75 = 81.25.
        assert!((t.integral(425.0, 475.0) - 81.25).abs() < 1e-12);
        assert!((t.integral(475.0, 425.0) + 81.25).abs() < 1e-12);
        assert_eq!(t.integral(700.0, 800.0), 0.0);
        assert!((t.integral(550.0, 550.0)).abs() < 1e-15);
    }

    #[test]
    fn rejects_bad_samples_with_a_reason() {
        let e = Tabulated::new(vec![400.0], vec![1.0]).unwrap_err();
        assert!(e.contains("at least 2"), "{e}");
        let e = Tabulated::new(vec![400.0, 500.0], vec![1.0]).unwrap_err();
        assert!(e.contains("one value per wavelength"), "{e}");
        let e = Tabulated::new(vec![400.0, 400.0], vec![1.0, 2.0]).unwrap_err();
        assert!(e.contains("strictly increasing"), "{e}");
        let e = Tabulated::new(vec![400.0, f64::NAN], vec![1.0, 2.0]).unwrap_err();
        assert!(e.contains("finite"), "{e}");
        let e = Tabulated::new(vec![400.0, 500.0], vec![1.0, f64::INFINITY]).unwrap_err();
        assert!(e.contains("finite"), "{e}");
    }
}
