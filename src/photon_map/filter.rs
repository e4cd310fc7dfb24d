//! The kernels of photon-density estimates: box, cone (Jensen 1996) and Epanechnikov, with the
//! normalisation that makes each an unbiased density estimate over the disc of radius r.
//!
//! # References
//! - H. W. Jensen (1996), "Global illumination using photon maps", Rendering Techniques '96,
//!   §3.3 (the cone filter).
//! - B. W. Silverman (1986), *Density Estimation for Statistics and Data Analysis*, §4.2.

use serde::Serialize;

/// The kernel of a photon-density estimate.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Filter {
    /// Uniform weights over the disc.
    Box,
    /// Jensen's cone filter w = 1 − d/(k r), normalised by 1 − 2/(3k).
    Cone {
        /// The cone constant k ≥ 1.
        k: f64,
    },
    /// Epanechnikov kernel w = 2(1 − d²/r²), normalised over the disc.
    Epanechnikov,
}

/// The filter weight of a photon at distance `d` in a disc of radius `r`.
pub fn filter_weight(filter: Filter, d: f64, r: f64) -> f64 {
    match filter {
        Filter::Box => 1.0,
        Filter::Cone { k } => (1.0 - d / (k * r)).max(0.0),
        Filter::Epanechnikov => (2.0 * (1.0 - d * d / (r * r))).max(0.0),
    }
}

/// ∫_disc w dA / (π r²) for a filter.
pub fn filter_norm(filter: Filter) -> f64 {
    match filter {
        Filter::Box | Filter::Epanechnikov => 1.0,
        Filter::Cone { k } => 1.0 - 2.0 / (3.0 * k),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::quadrature::gauss_legendre;

    #[test]
    fn filter_normalisations_integrate_the_weights() {
        // (1/(π r²)) ∫₀ʳ w(d) 2π d dd, by quadrature, for r = 1.
        for f in [Filter::Box, Filter::Cone { k: 1.0 }, Filter::Cone { k: 1.1 }, Filter::Epanechnikov] {
            let integral = gauss_legendre(&|d| filter_weight(f, d, 1.0) * 2.0 * d, 0.0, 1.0, 8);
            assert!((integral - filter_norm(f)).abs() < 1e-12, "{f:?}: {integral}");
        }
    }
}
