//! Monotone piecewise-cubic Hermite interpolation (PCHIP): C¹, and monotone wherever the data
//! are, so a tabulated profile neither overshoots nor has a kink in its derivative.
//!
//! On [x_k, x_{k+1}] with h_k = x_{k+1} − x_k, secant δ_k = (y_{k+1} − y_k)/h_k and t = (x − x_k)/h_k,
//! f(x) = H₀₀(t) y_k + H₁₀(t) h_k m_k + H₀₁(t) y_{k+1} + H₁₁(t) h_k m_{k+1}
//! with the cubic Hermite basis H₀₀ = 2t³ − 3t² + 1, H₁₀ = t³ − 2t² + t, H₀₁ = −2t³ + 3t²,
//! H₁₁ = t³ − t². Interior slopes are the weighted harmonic mean of the neighbouring secants,
//! 1/m_k = (w₁/δ_{k−1} + w₂/δ_k)/(w₁ + w₂), w₁ = 2h_k + h_{k−1}, w₂ = h_k + 2h_{k−1}, and zero
//! where the secants change sign or vanish; end slopes use the shape-preserving three-point
//! formula. Outside [x_0, x_last] the value is held at the end value (slope zero).
//!
//! # References
//! - F. N. Fritsch & R. E. Carlson 1980, "Monotone piecewise cubic interpolation", SIAM J. Numer.
//!   Anal. 17:238–246 (the monotonicity conditions).
//! - F. N. Fritsch & J. Butland 1984, "A method for constructing local monotone piecewise cubic
//!   interpolants", SIAM J. Sci. Stat. Comput. 5:300–304 (the harmonic-mean slopes).
//! - C. Moler 2004, *Numerical Computing with MATLAB*, §3.4 `pchip` (the end-slope formula).

/// A C¹ monotone cubic through `(x[i], y[i])`.
#[derive(Clone, Debug, PartialEq)]
pub struct MonotoneCubic {
    x: Vec<f64>,
    y: Vec<f64>,
    m: Vec<f64>,
}

impl MonotoneCubic {
    /// At least two knots with strictly increasing finite `x` and finite `y`.
    pub fn new(x: Vec<f64>, y: Vec<f64>) -> Result<MonotoneCubic, String> {
        check_knots(&x, &y)?;
        let m = slopes(&x, &y);
        Ok(MonotoneCubic { x, y, m })
    }

    /// The knot abscissae and values.
    pub fn knots(&self) -> (&[f64], &[f64]) {
        (&self.x, &self.y)
    }

    /// [x_0, x_last].
    pub fn domain(&self) -> (f64, f64) {
        (self.x[0], self.x[self.x.len() - 1])
    }

    /// The smallest and largest knot value: bounds of the interpolant (it does not overshoot).
    pub fn value_range(&self) -> (f64, f64) {
        self.y.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| (lo.min(v), hi.max(v)))
    }

    /// f(x).
    pub fn eval(&self, x: f64) -> f64 {
        self.eval_deriv(x).0
    }

    /// f(x) and f′(x); held constant (f′ = 0) outside the knots. NaN in, NaN out.
    pub fn eval_deriv(&self, x: f64) -> (f64, f64) {
        let (lo, hi) = self.domain();
        if x.is_nan() {
            return (f64::NAN, f64::NAN);
        }
        if x <= lo {
            return (self.y[0], 0.0);
        }
        if x >= hi {
            return (self.y[self.y.len() - 1], 0.0);
        }
        let k = self.x.partition_point(|&v| v <= x).saturating_sub(1).min(self.x.len() - 2);
        let h = self.x[k + 1] - self.x[k];
        let t = (x - self.x[k]) / h;
        let (y0, y1, m0, m1) = (self.y[k], self.y[k + 1], self.m[k], self.m[k + 1]);
        let t2 = t * t;
        let t3 = t2 * t;
        let f = (2.0 * t3 - 3.0 * t2 + 1.0) * y0
            + (t3 - 2.0 * t2 + t) * h * m0
            + (-2.0 * t3 + 3.0 * t2) * y1
            + (t3 - t2) * h * m1;
        let df = ((6.0 * t2 - 6.0 * t) * (y0 - y1)) / h + (3.0 * t2 - 4.0 * t + 1.0) * m0 + (3.0 * t2 - 2.0 * t) * m1;
        (f, df)
    }
}

fn check_knots(x: &[f64], y: &[f64]) -> Result<(), String> {
    if x.len() != y.len() {
        return Err(format!("{} abscissae but {} values: need one value per knot", x.len(), y.len()));
    }
    if x.len() < 2 {
        return Err(format!("{} knot(s): need at least 2", x.len()));
    }
    if let Some(i) = x.iter().chain(y).position(|v| !v.is_finite()) {
        let (what, j) = if i < x.len() { ("abscissa", i) } else { ("value", i - x.len()) };
        return Err(format!("{what} #{j} is not a finite number"));
    }
    if let Some(i) = x.windows(2).position(|w| w[1] <= w[0]) {
        return Err(format!("abscissae are not strictly increasing: #{} is {} after {}", i + 1, x[i + 1], x[i]));
    }
    Ok(())
}

/// PCHIP slopes (Fritsch–Butland interior, three-point shape-preserving ends).
fn slopes(x: &[f64], y: &[f64]) -> Vec<f64> {
    let n = x.len();
    let h: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
    let d: Vec<f64> = (0..n - 1).map(|k| (y[k + 1] - y[k]) / h[k]).collect();
    if n == 2 {
        return vec![d[0], d[0]];
    }
    let mut m = vec![0.0; n];
    for k in 1..n - 1 {
        if d[k - 1] * d[k] > 0.0 {
            let w1 = 2.0 * h[k] + h[k - 1];
            let w2 = h[k] + 2.0 * h[k - 1];
            m[k] = (w1 + w2) / (w1 / d[k - 1] + w2 / d[k]);
        }
    }
    m[0] = end_slope(h[0], h[1], d[0], d[1]);
    m[n - 1] = end_slope(h[n - 2], h[n - 3], d[n - 2], d[n - 3]);
    m
}

/// The three-point end slope, limited so the end interval stays monotone.
fn end_slope(h0: f64, h1: f64, d0: f64, d1: f64) -> f64 {
    let m = ((2.0 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
    if m * d0 <= 0.0 {
        0.0
    } else if d0 * d1 < 0.0 && m.abs() > 3.0 * d0.abs() {
        3.0 * d0
    } else {
        m
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spline(x: &[f64], y: &[f64]) -> MonotoneCubic {
        MonotoneCubic::new(x.to_vec(), y.to_vec()).unwrap()
    }

    #[test]
    fn interpolates_the_knots_and_reproduces_straight_lines() {
        let x = [0.0, 1.0, 2.5, 4.0, 7.0];
        let s = spline(&x, &x.map(|v| 3.0 - 2.0 * v));
        for v in [0.0, 0.3, 1.0, 1.7, 3.2, 6.9, 7.0] {
            let (f, df) = s.eval_deriv(v);
            assert!((f - (3.0 - 2.0 * v)).abs() < 1e-14, "f({v}) = {f}");
            if v > 0.0 && v < 7.0 {
                assert!((df + 2.0).abs() < 1e-13, "f'({v}) = {df}");
            }
        }
        let y = [1.0, 4.0, -2.0, 0.5, 0.5];
        let s = spline(&x, &y);
        for (xi, yi) in x.iter().zip(y) {
            assert!((s.eval(*xi) - yi).abs() < 1e-15);
        }
    }

    #[test]
    fn is_monotone_on_monotone_data_and_does_not_overshoot() {
        // Step-like data make an ordinary cubic spline overshoot; PCHIP must not.
        let x = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0];
        let y = [0.0, 0.0, 0.1, 9.9, 10.0, 10.0];
        let s = spline(&x, &y);
        let mut prev = f64::NEG_INFINITY;
        for i in 0..=5000 {
            let v = s.eval(5.0 * i as f64 / 5000.0);
            assert!(v >= prev - 1e-12, "not monotone at {i}");
            assert!((-1e-12..=10.0 + 1e-12).contains(&v), "overshoot {v}");
            prev = v;
        }
        assert_eq!(s.value_range(), (0.0, 10.0));
    }

    #[test]
    fn derivative_is_continuous_at_knots_and_matches_differences() {
        let x = [0.0, 0.7, 1.9, 2.0, 3.5, 6.0];
        let y = [2.0, 1.2, 1.1, 1.3, 4.0, 3.0];
        let s = spline(&x, &y);
        for &k in &x[1..x.len() - 1] {
            let e = 1e-9;
            let (_, left) = s.eval_deriv(k - e);
            let (_, right) = s.eval_deriv(k + e);
            assert!((left - right).abs() < 1e-6, "slope jumps at {k}: {left} vs {right}");
        }
        for i in 1..600 {
            let v = 6.0 * i as f64 / 600.0 + 0.003;
            if x.iter().any(|k| (v - k).abs() < 1e-3) || v >= 6.0 {
                continue;
            }
            let h = 1e-5;
            let fd = (s.eval(v + h) - s.eval(v - h)) / (2.0 * h);
            let (_, df) = s.eval_deriv(v);
            assert!((fd - df).abs() < 1e-6 * (1.0 + df.abs()), "f'({v}) = {df}, FD {fd}");
        }
    }

    #[test]
    fn matches_scipy_pchip() {
        // Reference values from scipy 1.17.1 `PchipInterpolator(x, y)` (Fritsch–Butland slopes,
        // same end formula), an independent implementation of the same method.
        let s = spline(&[0.0, 1.0, 3.0, 4.0, 6.0], &[0.0, 2.0, 3.0, 7.0, 6.0]);
        let want = [
            (0.5, 1.2053571428571428, 2.1607142857142856),
            (2.0, 2.471042471042471, 0.2924710424710424),
            (3.5, 5.121621621621622, 5.756756756756758),
            (5.0, 6.875, -0.375),
        ];
        for (v, f, df) in want {
            let (got, dgot) = s.eval_deriv(v);
            assert!((got - f).abs() < 1e-12 && (dgot - df).abs() < 1e-12, "f({v}) = {got}, {dgot}");
        }
    }

    #[test]
    fn holds_end_values_outside_and_rejects_bad_knots() {
        let s = spline(&[1.0, 2.0, 4.0], &[5.0, 6.0, 8.0]);
        assert_eq!(s.eval_deriv(0.0), (5.0, 0.0));
        assert_eq!(s.eval_deriv(9.0), (8.0, 0.0));
        assert!(s.eval(f64::NAN).is_nan());
        assert!(MonotoneCubic::new(vec![1.0], vec![1.0]).unwrap_err().contains("at least 2"));
        assert!(MonotoneCubic::new(vec![1.0, 1.0], vec![1.0, 2.0]).unwrap_err().contains("strictly"));
        assert!(MonotoneCubic::new(vec![1.0, 2.0], vec![1.0, f64::NAN]).unwrap_err().contains("value #1"));
        assert!(MonotoneCubic::new(vec![1.0, 2.0], vec![1.0]).unwrap_err().contains("one value per knot"));
    }
}
