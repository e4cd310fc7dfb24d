//! Phase functions: the angular distribution of scattered light, one file per model, dispatched
//! by the closed enum [`PhaseFunction`].
//!
//! # Convention
//! - Directions are directions of **travel**. `wi` is the direction the light travelled before
//!   scattering and `wo` the direction it travels after; the scattering angle θ is the angle
//!   between them, `cos θ = wi · wo`. Forward scattering (no deflection) is `cos θ = 1`.
//! - Values are densities **per steradian** in `wo` that integrate to one over the sphere:
//!   `∫ p(wi · wo) dω(wo) = 2π ∫₋₁¹ p(μ) dμ = 1`. A volume scattering function is
//!   `β(θ) = σ_s p(θ)`.
//! - Every model depends on θ only (rotational symmetry about `wi`), so `eval` and `pdf` take
//!   `cos θ`, and the azimuth of a sample is uniform.
//! - Every sampler is exact: `sample` draws `wo` from `p` itself, so the returned pdf equals
//!   [`PhaseFunction::pdf`] (and [`PhaseFunction::eval`]) at the sampled direction, and the Monte
//!   Carlo weight `p / pdf` of a sampled scattering is exactly one.
//! - Methods take the wavelength in nm; only [`Mixture`] depends on it (through σ_s,i(λ)).
//!   `u` is a point of the unit square; `u[0]` chooses θ (and a mixture component), `u[1]` the
//!   azimuth.
//!
//! # Models
//! | constructor | density p(μ), μ = cos θ | file |
//! |---|---|---|
//! | [`PhaseFunction::isotropic`] | 1/(4π) | `isotropic.rs` |
//! | [`PhaseFunction::rayleigh`] | 3/(16π) (1 + μ²) | `cos_squared.rs` |
//! | [`PhaseFunction::rayleigh_depolarised`] | K (1 + (1 − ρ)/(1 + ρ) μ²) (Chandrasekhar 1950) | `cos_squared.rs` |
//! | [`PhaseFunction::pure_water`] | 0.06225 (1 + 0.835 μ²) (Morel 1974) | `cos_squared.rs` |
//! | [`PhaseFunction::raman`] | 0.067 (1 + 0.55 μ²) (Raman scattering by water) | `cos_squared.rs` |
//! | [`PhaseFunction::henyey_greenstein`] | (1 − g²) / (4π (1 + g² − 2gμ)^{3/2}) | `henyey_greenstein.rs` |
//! | [`PhaseFunction::schlick`] | (1 − k²) / (4π (1 − kμ)²) | `schlick.rs` |
//! | [`PhaseFunction::two_term_hg`] | w HG(g₁) + (1 − w) HG(g₂) | `two_term_hg.rs` |
//! | [`PhaseFunction::tabulated_csv`] | measured table, e.g. Petzold's average particle | `tabulated.rs` |
//! | [`PhaseFunction::mixture`] | Σ σ_s,i(λ) p_i / Σ σ_s,i(λ) | `mixture.rs` |
//!
//! # References
//! - Pharr, Jakob & Humphreys, *Physically Based Rendering*, 4th ed. (2023), §11.3 (phase
//!   functions and their sampling).
//! - Mobley, *Light and Water* (1994), §3.8 (oceanic phase functions); Mobley, *Ocean Optics Web
//!   Book*, "The Henyey–Greenstein phase function".

mod cos_squared;
mod henyey_greenstein;
mod isotropic;
mod mixture;
mod schlick;
mod tabulated;
mod two_term_hg;

pub use cos_squared::CosSquared;
pub use henyey_greenstein::HenyeyGreenstein;
pub use isotropic::Isotropic;
pub use mixture::{Mixture, MixtureComponent};
pub use schlick::Schlick;
pub use tabulated::TabulatedPhase;
pub use two_term_hg::TwoTermHg;

use crate::geometry::Frame;
use crate::spectrum::Spectrum;
use glam::DVec3;
use std::f64::consts::PI;
use std::path::Path;

/// A phase function (see the module documentation for the conventions).
#[derive(Clone, Debug)]
pub enum PhaseFunction {
    /// p = 1/(4π).
    Isotropic(Isotropic),
    /// Rayleigh, pure water and Raman: `k (1 + c cos²θ)`.
    CosSquared(CosSquared),
    /// Henyey–Greenstein with mean cosine g.
    HenyeyGreenstein(HenyeyGreenstein),
    /// Schlick's approximation to Henyey–Greenstein.
    Schlick(Schlick),
    /// Two Henyey–Greenstein lobes, weights w and 1 − w.
    TwoTermHg(TwoTermHg),
    /// Tabulated at scattering angles (e.g. Petzold).
    Tabulated(TabulatedPhase),
    /// Scatterers weighted by their σ_s,i(λ); depends on wavelength.
    Mixture(Mixture),
}

impl PhaseFunction {
    /// Isotropic scattering, p = 1/(4π).
    pub fn isotropic() -> Self {
        PhaseFunction::Isotropic(Isotropic)
    }

    /// Rayleigh scattering by particles much smaller than the wavelength (unpolarised light),
    /// p = 3/(16π) (1 + cos²θ).
    pub fn rayleigh() -> Self {
        PhaseFunction::CosSquared(CosSquared::RAYLEIGH)
    }

    /// Rayleigh scattering by anisotropic molecules of depolarisation ratio `rho` in [0, 1)
    /// (Chandrasekhar 1950, §I.18): p = K (1 + c μ²) with c = (1 − ρ)/(1 + ρ); see
    /// [`CosSquared::rayleigh_depolarised`]. ρ ≈ 0.028 for air ([`crate::media::rayleigh_air`]).
    pub fn rayleigh_depolarised(rho: f64) -> Result<Self, String> {
        CosSquared::rayleigh_depolarised(rho).map(PhaseFunction::CosSquared)
    }

    /// Scattering by pure water (and sea water), p = 0.06225 (1 + 0.835 cos²θ) (Morel 1974).
    pub fn pure_water() -> Self {
        PhaseFunction::CosSquared(CosSquared::PURE_WATER)
    }

    /// The angular distribution of Raman (inelastic) scattering by water,
    /// p = 0.067 (1 + 0.55 cos²ψ) (Mobley 1994).
    pub fn raman() -> Self {
        PhaseFunction::CosSquared(CosSquared::RAMAN)
    }

    /// Henyey–Greenstein with asymmetry `g` in (−1, 1).
    pub fn henyey_greenstein(g: f64) -> Result<Self, String> {
        HenyeyGreenstein::new(g).map(PhaseFunction::HenyeyGreenstein)
    }

    /// Schlick's phase function with shape parameter `k` in (−1, 1).
    pub fn schlick(k: f64) -> Result<Self, String> {
        Schlick::new(k).map(PhaseFunction::Schlick)
    }

    /// Schlick's phase function approximating Henyey–Greenstein of asymmetry `g`
    /// (k = 1.55 g − 0.55 g³; see [`Schlick::from_g`] for the range of g allowed).
    pub fn schlick_from_g(g: f64) -> Result<Self, String> {
        Schlick::from_g(g).map(PhaseFunction::Schlick)
    }

    /// Two-term Henyey–Greenstein w HG(g₁) + (1 − w) HG(g₂).
    pub fn two_term_hg(w: f64, g1: f64, g2: f64) -> Result<Self, String> {
        TwoTermHg::new(w, g1, g2).map(PhaseFunction::TwoTermHg)
    }

    /// A tabulated phase function read from a CSV file of `angle_deg,value_per_sr` rows.
    pub fn tabulated_csv(path: &Path) -> Result<Self, String> {
        TabulatedPhase::from_csv(path).map(PhaseFunction::Tabulated)
    }

    /// A mixture weighted by each component's scattering coefficient σ_s,i(λ).
    pub fn mixture(components: Vec<MixtureComponent>) -> Result<Self, String> {
        Mixture::new(components).map(PhaseFunction::Mixture)
    }

    /// The phase function p(cos θ) per steradian at `wavelength_nm`.
    pub fn eval(&self, wavelength_nm: f64, cos_theta: f64) -> f64 {
        let mu = cos_theta.clamp(-1.0, 1.0);
        match self {
            PhaseFunction::Isotropic(p) => p.eval(mu),
            PhaseFunction::CosSquared(p) => p.eval(mu),
            PhaseFunction::HenyeyGreenstein(p) => p.eval(mu),
            PhaseFunction::Schlick(p) => p.eval(mu),
            PhaseFunction::TwoTermHg(p) => p.eval(mu),
            PhaseFunction::Tabulated(p) => p.eval(mu),
            PhaseFunction::Mixture(p) => p.eval(wavelength_nm, mu),
        }
    }

    /// How many weights [`PhaseFunction::write_weights`] writes: a mixture's component count,
    /// 0 for a single phase function.
    pub fn weight_count(&self) -> usize {
        match self {
            PhaseFunction::Mixture(p) => p.components().len(),
            _ => 0,
        }
    }

    /// Writes what [`PhaseFunction::eval`] computes from λ alone (a mixture's weights σ_s,i(λ))
    /// into `out`, [`PhaseFunction::weight_count`] values.
    pub fn write_weights(&self, wavelength_nm: f64, out: &mut [f64]) {
        if let PhaseFunction::Mixture(p) = self {
            p.weights_into(wavelength_nm, out);
        }
    }

    /// [`PhaseFunction::eval`] from the weights [`PhaseFunction::write_weights`] wrote for
    /// this λ: bit for bit the same density.
    pub fn eval_with_weights(&self, weights: &[f64], wavelength_nm: f64, cos_theta: f64) -> f64 {
        match self {
            PhaseFunction::Mixture(p) => p.eval_weighted(weights, wavelength_nm, cos_theta.clamp(-1.0, 1.0)),
            _ => self.eval(wavelength_nm, cos_theta),
        }
    }

    /// Solid-angle density of [`PhaseFunction::sample`]; equal to [`PhaseFunction::eval`]
    /// because every sampler is exact.
    pub fn pdf(&self, wavelength_nm: f64, cos_theta: f64) -> f64 {
        self.eval(wavelength_nm, cos_theta)
    }

    /// Samples cos θ from the density 2π p(μ) on [−1, 1] with one uniform number `u0` in [0, 1).
    pub fn sample_cos_theta(&self, wavelength_nm: f64, u0: f64) -> f64 {
        let mu = match self {
            PhaseFunction::Isotropic(p) => p.sample_cos_theta(u0),
            PhaseFunction::CosSquared(p) => p.sample_cos_theta(u0),
            PhaseFunction::HenyeyGreenstein(p) => p.sample_cos_theta(u0),
            PhaseFunction::Schlick(p) => p.sample_cos_theta(u0),
            PhaseFunction::TwoTermHg(p) => p.sample_cos_theta(u0),
            PhaseFunction::Tabulated(p) => p.sample_cos_theta(u0),
            PhaseFunction::Mixture(p) => p.sample_cos_theta(wavelength_nm, u0),
        };
        mu.clamp(-1.0, 1.0)
    }

    /// Samples the outgoing travel direction `wo` for light travelling along the unit vector
    /// `wi`; returns `wo` and its solid-angle density, which equals `pdf(wavelength_nm, μ)` at the
    /// sampled μ = cos θ.
    pub fn sample(&self, wavelength_nm: f64, wi: DVec3, u: [f64; 2]) -> (DVec3, f64) {
        let mu = self.sample_cos_theta(wavelength_nm, u[0]);
        (direction_about(wi, mu, u[1]), self.pdf(wavelength_nm, mu))
    }

    /// The mean cosine (asymmetry parameter) g = ∫ cos θ p dω at `wavelength_nm`.
    pub fn mean_cosine(&self, wavelength_nm: f64) -> f64 {
        match self {
            PhaseFunction::Isotropic(_) => 0.0,
            PhaseFunction::CosSquared(_) => 0.0,
            PhaseFunction::HenyeyGreenstein(p) => p.g(),
            PhaseFunction::Schlick(p) => p.mean_cosine(),
            PhaseFunction::TwoTermHg(p) => p.mean_cosine(),
            PhaseFunction::Tabulated(p) => p.mean_cosine(),
            PhaseFunction::Mixture(p) => p.mean_cosine(wavelength_nm),
        }
    }

    /// True when the phase function changes with wavelength (a mixture whose σ_s,i(λ) are not
    /// all constant), so a path carrying many wavelengths must split at a scattering.
    pub fn depends_on_wavelength(&self) -> bool {
        match self {
            PhaseFunction::Mixture(p) => p.depends_on_wavelength(),
            _ => false,
        }
    }
}

/// The unit vector at angle acos(`cos_theta`) from the unit vector `axis`, at azimuth 2π `u1`.
pub fn direction_about(axis: DVec3, cos_theta: f64, u1: f64) -> DVec3 {
    let sin_theta = ((1.0 - cos_theta) * (1.0 + cos_theta)).max(0.0).sqrt();
    let phi = 2.0 * PI * u1;
    let local = DVec3::new(sin_theta * phi.cos(), sin_theta * phi.sin(), cos_theta);
    Frame::from_normal(axis).to_world(local)
}

/// `Ok(())` for a finite parameter strictly inside (−1, 1), else a message naming it.
fn check_open_unit(name: &str, value: f64) -> Result<(), String> {
    if value.is_finite() && value.abs() < 1.0 {
        Ok(())
    } else {
        Err(format!("{name} = {value} is out of range: it must lie strictly between −1 and 1"))
    }
}

/// A spectrum that can never be negative (checked where the variant allows it).
fn is_nonnegative(s: &Spectrum) -> bool {
    match s {
        Spectrum::Constant(c) => *c >= 0.0,
        Spectrum::Tabulated(t) => t.samples().1.iter().all(|v| *v >= 0.0),
        Spectrum::Scaled(k, s) => *k >= 0.0 && is_nonnegative(s),
        Spectrum::Blackbody { .. } | Spectrum::RgbReflectance(_) => true,
    }
}
