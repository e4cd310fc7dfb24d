//! Dual numbers v + d·ε (ε² = 0): a value and its derivative carried through arithmetic, so that
//! the model atmosphere's n(r) gives dn/dr exactly (to rounding) from the same expressions
//! (forward-mode automatic differentiation).
//!
//! # References
//! - A. Griewank & A. Walther, *Evaluating Derivatives*, 2nd ed., SIAM 2008, ch. 3 (forward mode).

use std::ops::{Add, Div, Mul, Sub};

/// A value `v` and its derivative `d` with respect to the one independent variable.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dual {
    /// The value.
    pub v: f64,
    /// Its derivative.
    pub d: f64,
}

impl Dual {
    /// A constant (derivative 0).
    pub fn constant(v: f64) -> Dual {
        Dual { v, d: 0.0 }
    }

    /// The independent variable itself (derivative 1).
    pub fn variable(v: f64) -> Dual {
        Dual { v, d: 1.0 }
    }

    /// xᵖ for a constant p: (xᵖ)' = p·xᵖ⁻¹·x'.
    pub fn powf(self, p: f64) -> Dual {
        let y = self.v.powf(p);
        Dual { v: y, d: if self.v == 0.0 { 0.0 } else { p * y / self.v * self.d } }
    }

    /// eˣ: (eˣ)' = eˣ·x'.
    pub fn exp(self) -> Dual {
        let y = self.v.exp();
        Dual { v: y, d: y * self.d }
    }
}

impl Add for Dual {
    type Output = Dual;
    fn add(self, o: Dual) -> Dual {
        Dual { v: self.v + o.v, d: self.d + o.d }
    }
}

impl Sub for Dual {
    type Output = Dual;
    fn sub(self, o: Dual) -> Dual {
        Dual { v: self.v - o.v, d: self.d - o.d }
    }
}

impl Mul for Dual {
    type Output = Dual;
    fn mul(self, o: Dual) -> Dual {
        Dual { v: self.v * o.v, d: self.d * o.v + self.v * o.d }
    }
}

impl Div for Dual {
    type Output = Dual;
    fn div(self, o: Dual) -> Dual {
        Dual { v: self.v / o.v, d: (self.d * o.v - self.v * o.d) / (o.v * o.v) }
    }
}

impl Add<f64> for Dual {
    type Output = Dual;
    fn add(self, c: f64) -> Dual {
        Dual { v: self.v + c, d: self.d }
    }
}

impl Mul<f64> for Dual {
    type Output = Dual;
    fn mul(self, c: f64) -> Dual {
        Dual { v: self.v * c, d: self.d * c }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn derivatives_match_central_differences() {
        // f(x) = (3x^2.5 + 1)·e^(−x/2) / (x + 4) − x; central differences with h = 10⁻⁵ are
        // accurate to ~h² f''' ≈ 10⁻¹⁰.
        let f = |x: Dual| (x.powf(2.5) * 3.0 + 1.0) * (x * -0.5).exp() / (x + 4.0) - x;
        for x in [0.3, 1.0, 2.7, 9.0] {
            let h = 1e-5;
            let fd = (f(Dual::constant(x + h)).v - f(Dual::constant(x - h)).v) / (2.0 * h);
            let ad = f(Dual::variable(x)).d;
            assert!((ad - fd).abs() < 1e-8 * (1.0 + fd.abs()), "x = {x}: {ad} vs {fd}");
        }
    }
}
