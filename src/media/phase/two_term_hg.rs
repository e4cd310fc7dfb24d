//! The two-term Henyey–Greenstein phase function
//!
//! p(μ) = w HG(μ; g₁) + (1 − w) HG(μ; g₂),  0 ≤ w ≤ 1,  −1 < g₁, g₂ < 1,
//!
//! a forward lobe plus a (usually backward, g₂ < 0) lobe, used for ocean particles because one
//! HG term cannot match both the forward peak and the backscatter of measured phase functions
//! (Kattawar 1975; Haltrin 2002 ties w, g₁, g₂ to a single parameter for sea water).
//! Mean cosine: w g₁ + (1 − w) g₂.
//!
//! Sampling: choose the first lobe with probability w (reusing the uniform number, rescaled),
//! then sample that lobe exactly; the density of the result is the full mixture p.
//!
//! # References
//! - Kattawar, "A three-parameter analytic phase function for multiple scattering calculations",
//!   JQSRT 15 (1975), 839–849.
//! - Haltrin, "One-parameter two-term Henyey–Greenstein phase function for light scattering in
//!   seawater", Applied Optics 41(6) (2002), 1022–1028.

use super::HenyeyGreenstein;

/// w HG(g₁) + (1 − w) HG(g₂).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TwoTermHg {
    w: f64,
    first: HenyeyGreenstein,
    second: HenyeyGreenstein,
}

impl TwoTermHg {
    /// `w` in [0, 1]; `g1`, `g2` strictly between −1 and 1.
    pub fn new(w: f64, g1: f64, g2: f64) -> Result<TwoTermHg, String> {
        if !(0.0..=1.0).contains(&w) {
            return Err(format!("two-term HG weight w = {w} is out of range: it must lie in [0, 1]"));
        }
        let first = HenyeyGreenstein::new(g1).map_err(|e| format!("two-term HG first term: {e}"))?;
        let second = HenyeyGreenstein::new(g2).map_err(|e| format!("two-term HG second term: {e}"))?;
        Ok(TwoTermHg { w, first, second })
    }

    /// (w, g₁, g₂).
    pub fn parameters(&self) -> (f64, f64, f64) {
        (self.w, self.first.g(), self.second.g())
    }

    /// p(cos θ), sr⁻¹.
    pub fn eval(&self, cos_theta: f64) -> f64 {
        self.w * self.first.eval(cos_theta) + (1.0 - self.w) * self.second.eval(cos_theta)
    }

    /// Lobe choice by `u0 < w`, then the rescaled `u0` samples the chosen lobe.
    pub fn sample_cos_theta(&self, u0: f64) -> f64 {
        let w = self.w;
        if u0 < w {
            self.first.sample_cos_theta((u0 / w).min(1.0))
        } else {
            self.second.sample_cos_theta(((u0 - w) / (1.0 - w)).clamp(0.0, 1.0))
        }
    }

    /// Mean cosine w g₁ + (1 − w) g₂.
    pub fn mean_cosine(&self) -> f64 {
        self.w * self.first.g() + (1.0 - self.w) * self.second.g()
    }
}
