//! The Beckmann distribution of microfacet normals, and the Cox–Munk sea surface as one.
//!
//! Slopes (z_x, z_y) of the facets are Gaussian and isotropic with mean-square slope
//! ⟨z_x² + z_y²⟩ = α² (α is the rms slope):
//!
//! ```text
//!     P(z_x, z_y) = exp(−(z_x² + z_y²)/α²) / (π α²),
//!     D(m) = P(tan θ_m) / cos⁴θ_m = exp(−tan²θ_m/α²) / (π α² cos⁴θ_m),   ∫ D(m) cos θ_m dω_m = 1.
//! ```
//!
//! Cox & Munk measured the slope statistics of the sea from photographs of the sun's glitter;
//! their isotropic fit for a clean surface is σ² = 0.003 + 5.12·10⁻³ W (W the wind speed in
//! m s⁻¹ at 12.5 m, for 1–14 m s⁻¹, ±0.004), and the slope distribution is this Gaussian to first
//! order (its Gram–Charlier skewness and peakedness terms are left out), so α² = σ².
//!
//! Smith's shadowing–masking for this D (exact form, Walter et al. 2007 eq. 25):
//! G₁(v, m) = χ⁺((v·m)/(v·n)) · 2 / (1 + erf a + e^{−a²}/(a√π)), a = 1/(α tan θ_v).
//!
//! # References
//! C. Cox, W. Munk, "Measurement of the roughness of the sea surface from photographs of the
//! sun's glitter", J. Opt. Soc. Am. 44 (1954) 838–850, eq. (2) and §6.
//! B. Walter, S. R. Marschner, H. Li, K. E. Torrance, "Microfacet models for refraction through
//! rough surfaces", EGSR 2007, §5.1 (Beckmann D, its sampling, G₁).
//! B. G. Smith, "Geometrical shadowing of a random rough surface", IEEE Trans. Antennas Propag.
//! 15 (1967) 668–671 (G₁ = 1/(1 + Λ)).
//! M. Abramowitz, I. Stegun, *Handbook of Mathematical Functions*, 7.1.26 (erf).

use crate::geometry::Frame;
use glam::DVec3;
use std::f64::consts::PI;

/// Largest wind speed accepted for the Cox–Munk fit, m s⁻¹ (their data span 1–14 m s⁻¹; beyond
/// that the fit is an extrapolation, and beyond this the sea is foam and spray, not facets).
pub const COX_MUNK_MAX_WIND_M_S: f64 = 30.0;

/// Isotropic Beckmann facets of rms slope `alpha`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Beckmann {
    /// RMS slope α (the Cox–Munk σ for a sea surface).
    pub alpha: f64,
}

impl Beckmann {
    /// The clean sea surface under a wind of `wind_speed_m_s` (Cox & Munk 1954):
    /// α² = 0.003 + 5.12·10⁻³ W.
    pub fn cox_munk(wind_speed_m_s: f64) -> Beckmann {
        Beckmann { alpha: (0.003 + 5.12e-3 * wind_speed_m_s).sqrt() }
    }

    /// D(m) for a facet normal at cos θ_m = `cos_m` from the mean normal (0 below it).
    pub fn d(&self, cos_m: f64) -> f64 {
        if cos_m <= 0.0 {
            return 0.0;
        }
        let c2 = cos_m * cos_m;
        let tan2 = (1.0 - c2) / c2;
        let a2 = self.alpha * self.alpha;
        (-tan2 / a2).exp() / (PI * a2 * c2 * c2)
    }

    /// A facet normal about the mean normal `n` with density D(m)·cos θ_m (Walter et al. 2007
    /// eq. 28): tan²θ_m = −α² ln(1 − u₁), φ_m = 2π u₂.
    pub fn sample(&self, n: DVec3, u1: f64, u2: f64) -> DVec3 {
        let tan2 = -self.alpha * self.alpha * (1.0 - u1).max(f64::MIN_POSITIVE).ln();
        let cos = 1.0 / (1.0 + tan2).sqrt();
        let sin = (1.0 - cos * cos).max(0.0).sqrt();
        let phi = 2.0 * PI * u2;
        Frame::from_normal(n).to_world(DVec3::new(sin * phi.cos(), sin * phi.sin(), cos))
    }

    /// Smith's G₁ for direction `v` (either side) seen from facet `m` on a surface of mean
    /// normal `n`: zero where v sees the back of the facet relative to its side of the surface.
    pub fn g1(&self, v: DVec3, m: DVec3, n: DVec3) -> f64 {
        let vn = v.dot(n);
        if v.dot(m) * vn <= 0.0 {
            return 0.0;
        }
        let c = vn.abs().min(1.0);
        let tan = (1.0 - c * c).sqrt() / c;
        if tan == 0.0 {
            return 1.0;
        }
        let a = 1.0 / (self.alpha * tan);
        2.0 / (1.0 + erf(a) + (-a * a).exp() / (a * PI.sqrt()))
    }
}

/// erf(x) for x ≥ 0 to 1.5·10⁻⁷ (Abramowitz & Stegun 7.1.26); erf(−x) = −erf(x).
pub fn erf(x: f64) -> f64 {
    let (s, x) = if x < 0.0 { (-1.0, -x) } else { (1.0, x) };
    let t = 1.0 / (1.0 + 0.327_591_1 * x);
    let poly =
        t * (0.254_829_592 + t * (-0.284_496_736 + t * (1.421_413_741 + t * (-1.453_152_027 + t * 1.061_405_429))));
    s * (1.0 - poly * (-x * x).exp())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::quadrature::gauss_legendre;
    use crate::rng::{Rng, Stream};

    #[test]
    fn erf_matches_published_values() {
        // Abramowitz & Stegun Table 7.1: erf(0.5) = 0.5204998778, erf(1) = 0.8427007929,
        // erf(2) = 0.9953222650.
        for (x, e) in [(0.5, 0.520_499_877_8), (1.0, 0.842_700_792_9), (2.0, 0.995_322_265_0)] {
            assert!((erf(x) - e).abs() < 2e-7, "erf({x}) = {}", erf(x));
            assert!((erf(-x) + e).abs() < 2e-7);
        }
    }

    #[test]
    fn d_is_normalised_in_projected_area() {
        // ∫ D(m) cos θ_m dω_m = 2π ∫₀¹ D(μ) μ dμ = 1 for every α.
        for alpha in [0.05, 0.2, 0.6] {
            let b = Beckmann { alpha };
            let i = 2.0 * PI * gauss_legendre(&|mu| b.d(mu) * mu, 0.0, 1.0, 400);
            assert!((i - 1.0).abs() < 1e-6, "α = {alpha}: {i}");
        }
    }

    #[test]
    fn sampled_slopes_have_the_cox_munk_mean_square() {
        // Cox & Munk (1954) eq. (2): σ² = 0.003 + 5.12e-3 W; at 10 m/s, 0.0542.
        let b = Beckmann::cox_munk(10.0);
        assert!((b.alpha * b.alpha - 0.0542).abs() < 1e-12);
        let mut rng = Rng::for_task(5, Stream::Test, 0);
        let n = 400_000;
        let (mut s, mut s2) = (0.0, 0.0);
        for _ in 0..n {
            let [u1, u2] = rng.uniform2();
            let m = b.sample(DVec3::Z, u1, u2);
            let t2 = (m.x * m.x + m.y * m.y) / (m.z * m.z);
            s += t2;
            s2 += t2 * t2;
        }
        let mean = s / n as f64;
        let se = ((s2 / n as f64 - mean * mean) / n as f64).sqrt();
        assert!((mean - 0.0542).abs() < 4.0 * se, "⟨tan²θ⟩ = {mean} ± {se}");
    }

    #[test]
    fn smith_g1_is_smiths_integral_over_the_slope_distribution() {
        // Smith (1967): G₁ = 1/(1 + Λ), Λ = (1/μ) ∫_μ^∞ (q − μ) P(q) dq with μ = cot θ_v and P the
        // slope density along v's azimuth, Gaussian with ⟨q²⟩ = α²/2 — evaluated here by
        // quadrature, independently of the closed form and its erf.
        let b = Beckmann { alpha: 0.3 };
        let p = |q: f64| (-q * q / (b.alpha * b.alpha)).exp() / (b.alpha * PI.sqrt());
        for deg in [10.0f64, 40.0, 60.0, 70.0, 80.0, 85.0, 88.0] {
            let t = deg.to_radians();
            let mu = 1.0 / t.tan();
            let lambda = gauss_legendre(&|q| (q - mu) * p(q), mu, mu + 12.0 * b.alpha, 200) / mu;
            let v = DVec3::new(t.sin(), 0.0, t.cos());
            let g = b.g1(v, DVec3::Z, DVec3::Z);
            assert!((g - 1.0 / (1.0 + lambda)).abs() < 1e-6, "θ = {deg}°: {g} vs {}", 1.0 / (1.0 + lambda));
        }
        assert_eq!(b.g1(DVec3::Z, DVec3::Z, DVec3::Z), 1.0);
        assert_eq!(b.g1(-DVec3::Z, DVec3::Z, DVec3::Z), 1.0, "straight through, from below");
        let (v, m) = (DVec3::new(0.985, 0.0, 0.174), DVec3::new(-0.5, 0.0, 0.866));
        assert_eq!(b.g1(v, m, DVec3::Z), 0.0, "the back of a facet tilted away from a grazing view");
    }
}
