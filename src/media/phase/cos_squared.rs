//! Phase functions of the form p(μ) = K (1 + c μ²), μ = cos θ: Rayleigh, pure water, Raman.
//!
//! Normalisation: 2π ∫₋₁¹ K (1 + c μ²) dμ = 4π K (1 + c/3) = 1, so K = 1 / (4π (1 + c/3)).
//! - Rayleigh (unpolarised light): c = 1, K = 3/(16π).
//! - Rayleigh with depolarisation ratio ρ (anisotropic molecules, e.g. air with ρ ≈ 0.028):
//!   Chandrasekhar's p = 3/(4(1 + 2γ)) [(1 + 3γ) + (1 − γ) μ²]/(4π), γ = ρ/(2 − ρ), is this form
//!   with c = (1 − γ)/(1 + 3γ) = (1 − ρ)/(1 + ρ) (Chandrasekhar 1950, §I.18).
//! - Pure water and sea water (Morel 1974): c = 0.835 = (1 − δ)/(1 + δ) for the depolarisation
//!   ratio δ = 0.09, K = 0.062251 (published rounded as 0.06225).
//! - Raman scattering by water (Mobley 1994): c = 0.55, K = 0.067249 (published rounded as 0.067).
//!
//! K is computed from c rather than copied from the rounded published values, so that the
//! density integrates to one exactly.
//!
//! Mean cosine: zero (p is even in μ).
//!
//! Sampling by inversion of the CDF F(μ) = [(μ + 1) + c (μ³ + 1)/3] / [2 (1 + c/3)]:
//! F(μ) = u is the depressed cubic μ³ + (3/c) μ − (3/c + 1) ξ = 0 with ξ = 2u − 1, whose
//! discriminant is positive, so it has one real root; in hyperbolic form (stable for every
//! c > 0, and → ξ as c → 0)
//!
//! μ = (2/√c) sinh( (1/3) asinh( (3 + c) ξ √c / 2 ) ).
//!
//! For c = 1 this is Frisvad's exact Rayleigh sampler, μ = 2 sinh(asinh(2ξ)/3).
//!
//! # References
//! - Morel, "Optical properties of pure water and pure sea water", in Jerlov & Steemann Nielsen
//!   (eds.), *Optical Aspects of Oceanography* (1974), 1–24.
//! - Mobley, *Light and Water: Radiative Transfer in Natural Waters* (1994): the pure-water phase
//!   function 0.06225 (1 + 0.835 cos²ψ) and the Raman phase function 0.067 (1 + 0.55 cos²ψ).
//! - Chandrasekhar, *Radiative Transfer* (1950), §I.18 (Rayleigh scattering with depolarisation).
//! - Frisvad, "Importance sampling the Rayleigh phase function", JOSA A 28(12) (2011), 2436–2441.
//! - Press et al., *Numerical Recipes*, 3rd ed. (2007), §5.6 (roots of cubics).

use std::f64::consts::PI;

/// p(μ) = K (1 + c μ²) with c ≥ 0 and K normalising it over the sphere.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CosSquared {
    c: f64,
    k: f64,
}

impl CosSquared {
    /// Rayleigh scattering, 3/(16π) (1 + μ²).
    pub const RAYLEIGH: CosSquared = CosSquared::with_c(1.0);
    /// Pure (sea) water, 0.06225 (1 + 0.835 μ²) (Morel 1974).
    pub const PURE_WATER: CosSquared = CosSquared::with_c(0.835);
    /// Raman scattering by water, 0.067 (1 + 0.55 μ²) (Mobley 1994).
    pub const RAMAN: CosSquared = CosSquared::with_c(0.55);

    const fn with_c(c: f64) -> CosSquared {
        CosSquared { c, k: 1.0 / (4.0 * PI * (1.0 + c / 3.0)) }
    }

    /// K (1 + c μ²) for a finite c ≥ 0 (c = 0 is isotropic).
    pub fn new(c: f64) -> Result<CosSquared, String> {
        if c.is_finite() && c >= 0.0 {
            Ok(CosSquared::with_c(c))
        } else {
            Err(format!(
                "cos² coefficient c = {c} is out of range: it must be finite and ≥ 0 \
                 (1 for Rayleigh, 0.835 for pure water, 0.55 for Raman)"
            ))
        }
    }

    /// Rayleigh scattering with depolarisation ratio ρ in [0, 1): c = (1 − ρ)/(1 + ρ).
    pub fn rayleigh_depolarised(rho: f64) -> Result<CosSquared, String> {
        if rho.is_finite() && (0.0..1.0).contains(&rho) {
            Ok(CosSquared::with_c((1.0 - rho) / (1.0 + rho)))
        } else {
            Err(format!("depolarisation ratio ρ = {rho} is out of range: it must lie in [0, 1) (air: about 0.028)"))
        }
    }

    /// The coefficient c of μ².
    pub fn c(&self) -> f64 {
        self.c
    }

    /// The normalising factor K = 1/(4π (1 + c/3)).
    pub fn k(&self) -> f64 {
        self.k
    }

    /// p(cos θ) = K (1 + c cos²θ), sr⁻¹.
    pub fn eval(&self, cos_theta: f64) -> f64 {
        self.k * (1.0 + self.c * cos_theta * cos_theta)
    }

    /// The real root of the CDF cubic, in hyperbolic form (module documentation).
    pub fn sample_cos_theta(&self, u0: f64) -> f64 {
        let xi = 2.0 * u0 - 1.0;
        if self.c == 0.0 {
            return xi;
        }
        let sqrt_c = self.c.sqrt();
        (2.0 / sqrt_c) * (((3.0 + self.c) * xi * sqrt_c / 2.0).asinh() / 3.0).sinh()
    }
}
