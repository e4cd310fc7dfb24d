//! The Henyey–Greenstein phase function
//!
//! p(μ) = (1 − g²) / (4π (1 + g² − 2gμ)^{3/2}),  μ = cos θ,  −1 < g < 1,
//!
//! whose mean cosine is exactly g (g > 0 scatters forward; g = 0.924 matches the mean cosine of
//! Petzold's average ocean particle phase function, as in Lucifer). The denominator is evaluated
//! as (1 − g)² + 2g(1 − μ), which keeps its relative accuracy in the forward peak.
//!
//! Sampling by inversion of the CDF F(μ) = (1 − g²)/(2g) [(1 + g² − 2gμ)^{−1/2} − (1 + g)^{−1}]:
//! the textbook solution μ = [1 + g² − ((1 − g²)/(1 + gξ))²] / (2g), ξ = 2u − 1, divides by g;
//! multiplying out gives the equivalent form used here, exact at g = 0 and without cancellation
//! for small |g|:
//!
//! μ = [ξ + (g/2)(3 + ξ² + 2gξ − g²(1 − ξ²))] / (1 + gξ)².
//!
//! # References
//! - Henyey & Greenstein, "Diffuse radiation in the galaxy", ApJ 93 (1941), 70–83.
//! - Pharr, Jakob & Humphreys, *Physically Based Rendering*, 4th ed. (2023), §11.3.1 (sampling).
//! - Mobley, *Ocean Optics Web Book*, "The Henyey–Greenstein phase function" (mean cosine g;
//!   Petzold's average particle phase function has mean cosine 0.924).

use super::check_open_unit;
use std::f64::consts::PI;

/// Henyey–Greenstein with asymmetry parameter g.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HenyeyGreenstein {
    g: f64,
}

impl HenyeyGreenstein {
    /// `g` must lie strictly between −1 and 1.
    pub fn new(g: f64) -> Result<HenyeyGreenstein, String> {
        check_open_unit("Henyey–Greenstein g", g)?;
        Ok(HenyeyGreenstein { g })
    }

    /// The asymmetry parameter, which is also the mean cosine.
    pub fn g(&self) -> f64 {
        self.g
    }

    /// p(cos θ), sr⁻¹.
    pub fn eval(&self, cos_theta: f64) -> f64 {
        let g = self.g;
        let denom = (1.0 - g) * (1.0 - g) + 2.0 * g * (1.0 - cos_theta);
        (1.0 - g * g) / (4.0 * PI * denom * denom.sqrt())
    }

    /// Exact inversion of the CDF (module documentation).
    pub fn sample_cos_theta(&self, u0: f64) -> f64 {
        let (g, xi) = (self.g, 2.0 * u0 - 1.0);
        let s = 1.0 + g * xi;
        let numer = xi + 0.5 * g * (3.0 + xi * xi + 2.0 * g * xi - g * g * (1.0 - xi * xi));
        (numer / (s * s)).clamp(-1.0, 1.0)
    }
}
