//! Drawing directions in proportion to a photometric web's intensity.
//!
//! The web's interpolant is bilinear in (C, z = cos γ) on each cell, and dω = dC dz, so the
//! density p(ω) = I(ω)/Φ is sampled exactly in two steps:
//! 1. a cell, with probability (its flux)/Φ — a discrete CDF over all cells;
//! 2. a point in the cell. With corner values a = I(C₀, z₀), b = I(C₁, z₀), c = I(C₀, z₁),
//!    d = I(C₁, z₁) and s, t ∈ [0, 1] across C and down z, the density ∝ bilinear(a, b, c, d);
//!    its marginal in s is linear from (a + c) to (b + d), and the conditional in t given s is
//!    linear from (1 − s)a + s b to (1 − s)c + s d.
//!
//! A density on [0, 1] linear from v₀ to v₁ has the CDF F(x) = (v₀x + (v₁ − v₀)x²/2)/((v₀ + v₁)/2);
//! its inverse, written without cancellation, is
//! x = u (v₀ + v₁) / (v₀ + √((1 − u) v₀² + u v₁²)).
//!
//! # References
//! - M. Pharr, W. Jakob, G. Humphreys, *Physically Based Rendering*, 4th ed. (2023), §A.4.1
//!   (sampling a linear function), §A.5 (piecewise 2-D distributions).

use super::web::{Cell, PhotometricWeb};
use crate::sampling::Discrete1D;
use glam::DVec3;

/// Samples unit directions (in the luminaire frame) with density I(ω)/Φ.
#[derive(Clone, Debug)]
pub struct WebSampler {
    cells: Vec<Cell>,
    dist: Discrete1D,
}

impl WebSampler {
    /// `None` when the web emits nothing.
    pub fn new(web: &PhotometricWeb) -> Option<WebSampler> {
        let cells: Vec<Cell> = web.cells().collect();
        let weights: Vec<f64> = cells.iter().map(Cell::flux).collect();
        let dist = Discrete1D::new(&weights)?;
        Some(WebSampler { cells, dist })
    }

    /// Φ of the web, lm.
    pub fn flux_lm(&self) -> f64 {
        self.dist.total()
    }

    /// A direction from three uniforms in [0, 1).
    pub fn sample(&self, web: &PhotometricWeb, u: [f64; 3]) -> DVec3 {
        let (k, _, _) = self.dist.sample(u[0]);
        let cell = &self.cells[k];
        let [a, b, c, d] = cell.cd;
        let s = sample_linear(u[1], a + c, b + d);
        let t = sample_linear(u[2], (1.0 - s) * a + s * b, (1.0 - s) * c + s * d);
        let c_deg = cell.c0 + s * (cell.c1 - cell.c0);
        let z = cell.z0 + t * (cell.z1 - cell.z0);
        web.axes().direction_cos(c_deg, z)
    }

    /// The density of [`WebSampler::sample`] at unit direction `d`, sr⁻¹.
    pub fn pdf(&self, web: &PhotometricWeb, d: DVec3) -> f64 {
        web.intensity(d) / self.flux_lm()
    }
}

/// Inverts the CDF of the density on [0, 1] that is linear from `v0` to `v1` (both ≥ 0).
pub fn sample_linear(u: f64, v0: f64, v1: f64) -> f64 {
    if v0 + v1 <= 0.0 {
        return u;
    }
    let denominator = v0 + ((1.0 - u) * v0 * v0 + u * v1 * v1).sqrt();
    if denominator <= 0.0 {
        // u = 0 with v0 = 0: the start of the interval.
        return 0.0;
    }
    (u * (v0 + v1) / denominator).clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::luminaire::web::WebAxes;
    use crate::rng::{Rng, Stream};
    use crate::testing::chi2::{chi2_1d, chi2_sphere};

    #[test]
    fn linear_inversion_solves_the_cdf() {
        for (v0, v1) in [(1.0, 3.0), (3.0, 1.0), (0.0, 2.0), (2.0, 0.0), (1.0, 1.0), (1e-12, 1.0)] {
            for i in 0..=20 {
                let u = i as f64 / 20.0;
                let x = sample_linear(u, v0, v1);
                let cdf = (v0 * x + 0.5 * (v1 - v0) * x * x) / (0.5 * (v0 + v1));
                assert!((cdf - u).abs() < 1e-12, "v0 {v0} v1 {v1} u {u}: x {x}, F(x) {cdf}");
            }
        }
    }

    #[test]
    fn linear_samples_follow_the_linear_density() {
        let mut rng = Rng::for_task(3, Stream::Test, 0);
        let p = chi2_1d(
            (0.0, 1.0),
            50,
            200_000,
            || Some(sample_linear(rng.uniform(), 0.5, 2.0)),
            |x| (0.5 + 1.5 * x) / 1.25,
        );
        assert!(p > 1e-3, "p = {p}");
    }

    /// An asymmetric web: a tilted beam with a C-dependence and a hard edge at γ = 100°.
    fn lopsided() -> PhotometricWeb {
        let c: Vec<f64> = (0..12).map(|i| 30.0 * i as f64).collect();
        let g: Vec<f64> = (0..=20).map(|j| 5.0 * j as f64).collect();
        let cd = c
            .iter()
            .flat_map(|ci| {
                g.iter().map(move |gj| {
                    let beam = (-((gj - 30.0) / 20.0f64).powi(2)).exp();
                    100.0 * beam * (1.5 + ci.to_radians().cos()) + 5.0
                })
            })
            .collect();
        PhotometricWeb::new(WebAxes::TYPE_C, c, true, g, cd).unwrap()
    }

    #[test]
    fn sampled_directions_follow_the_web() {
        let web = lopsided();
        let s = WebSampler::new(&web).unwrap();
        let mut rng = Rng::for_task(7, Stream::Test, 0);
        let p = chi2_sphere(
            60,
            24,
            400_000,
            || Some(s.sample(&web, [rng.uniform(), rng.uniform(), rng.uniform()])),
            |w| s.pdf(&web, w),
        );
        assert!(p > 1e-3, "p = {p}");
    }

    #[test]
    fn a_wrong_density_is_rejected() {
        // The same samples tested against a web with the C-dependence reversed must fail.
        let web = lopsided();
        let s = WebSampler::new(&web).unwrap();
        let mut rng = Rng::for_task(7, Stream::Test, 1);
        let p = chi2_sphere(
            60,
            24,
            400_000,
            || Some(s.sample(&web, [rng.uniform(), rng.uniform(), rng.uniform()])),
            |w| s.pdf(&web, DVec3::new(-w.x, w.y, w.z)),
        );
        assert!(p < 1e-6, "p = {p}");
    }

    #[test]
    fn a_dark_web_has_no_sampler() {
        let web = PhotometricWeb::new(WebAxes::TYPE_C, vec![0.0], true, vec![0.0, 90.0], vec![0.0, 0.0]).unwrap();
        assert!(WebSampler::new(&web).is_none());
    }
}
