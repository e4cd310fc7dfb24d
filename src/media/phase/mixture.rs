//! A mixture of phase functions weighted by each component's scattering coefficient:
//!
//! p(λ, μ) = Σᵢ σ_s,i(λ) pᵢ(λ, μ) / Σᵢ σ_s,i(λ),
//!
//! the phase function of a medium whose scatterers (say pure water and particles) scatter
//! independently: the volume scattering functions add, β = Σ σ_s,i pᵢ, and p = β / σ_s. Because
//! the σ_s,i depend on wavelength differently (water ∝ λ^−4.32, particles nearly flat), so does
//! the mixture: blue light sees more of the water's broad lobe.
//!
//! Mean cosine: Σ σ_s,i gᵢ / Σ σ_s,i.
//!
//! Sampling: pick component i with probability σ_s,i(λ)/Σ σ_s,i(λ) (reusing the uniform number,
//! rescaled), sample it exactly; the density of the result is the full mixture p (one-sample
//! model), so `pdf` of a sample is the mixture's, never the component's.
//!
//! If every σ_s,i(λ) is zero the medium does not scatter at λ and no caller needs p; the
//! components are then weighted equally so the result is still a normalised density.
//!
//! # References
//! - Mobley, *Light and Water* (1994), §3.8: β = β_w + β_p for water plus particles.
//! - Pharr, Jakob & Humphreys, *Physically Based Rendering*, 4th ed. (2023), §11.1 (scattering
//!   from several kinds of particles adds).

use super::{PhaseFunction, is_nonnegative};
use crate::spectrum::Spectrum;

/// One scatterer of a mixture: its scattering coefficient σ_s(λ) (m⁻¹) and phase function.
#[derive(Clone, Debug)]
pub struct MixtureComponent {
    /// Scattering coefficient σ_s,i(λ), m⁻¹ at density 1.
    pub sigma_s: Spectrum,
    /// Phase function of this scatterer.
    pub phase: PhaseFunction,
}

impl MixtureComponent {
    /// A scatterer with coefficient `sigma_s` (m⁻¹) and phase function `phase`.
    pub fn new(sigma_s: Spectrum, phase: PhaseFunction) -> MixtureComponent {
        MixtureComponent { sigma_s, phase }
    }
}

/// Phase functions weighted by σ_s,i(λ).
#[derive(Clone, Debug)]
pub struct Mixture {
    components: Vec<MixtureComponent>,
}

impl Mixture {
    /// At least one component; every σ_s,i must be non-negative.
    pub fn new(components: Vec<MixtureComponent>) -> Result<Mixture, String> {
        if components.is_empty() {
            return Err("phase function mixture has no components: give at least one (σ_s, phase) pair".into());
        }
        if let Some(i) = components.iter().position(|c| !is_nonnegative(&c.sigma_s)) {
            return Err(format!(
                "phase function mixture component #{i}: its scattering coefficient σ_s is negative or not a \
                 number somewhere; it must be ≥ 0 at every wavelength"
            ));
        }
        Ok(Mixture { components })
    }

    /// The scatterers, in the order given.
    pub fn components(&self) -> &[MixtureComponent] {
        &self.components
    }

    /// The weight σ_s,i(λ) of component `i` (negative or NaN values count as zero), or one for
    /// every component if all are zero.
    fn weights(&self, wavelength_nm: f64) -> impl Iterator<Item = f64> + '_ {
        let total = self.total_sigma_s(wavelength_nm);
        let equal = !(total > 0.0 && total.is_finite());
        self.components.iter().map(move |c| if equal { 1.0 } else { c.sigma_s.eval(wavelength_nm).max(0.0) })
    }

    /// Σ σ_s,i(λ): the scattering coefficient of the mixture.
    pub fn total_sigma_s(&self, wavelength_nm: f64) -> f64 {
        self.components.iter().map(|c| c.sigma_s.eval(wavelength_nm).max(0.0)).sum()
    }

    /// p(λ, cos θ): the σ_s,i(λ)-weighted mean of the components' densities, sr⁻¹.
    pub fn eval(&self, wavelength_nm: f64, cos_theta: f64) -> f64 {
        self.weighted_mean(wavelength_nm, |c| c.phase.eval(wavelength_nm, cos_theta))
    }

    /// Mean cosine Σ σ_s,i gᵢ / Σ σ_s,i at λ.
    pub fn mean_cosine(&self, wavelength_nm: f64) -> f64 {
        self.weighted_mean(wavelength_nm, |c| c.phase.mean_cosine(wavelength_nm))
    }

    /// Writes the weights of [`Mixture::eval`] at λ into `out` (one per component), so that
    /// [`Mixture::eval_weighted`] can give the same densities without evaluating σ_s,i again.
    pub fn weights_into(&self, wavelength_nm: f64, out: &mut [f64]) {
        for (o, w) in out.iter_mut().zip(self.weights(wavelength_nm)) {
            *o = w;
        }
    }

    /// [`Mixture::eval`] with the weights `w` that [`Mixture::weights_into`] wrote for this
    /// wavelength: the same sums in the same order, so the same number to the last bit.
    pub fn eval_weighted(&self, w: &[f64], wavelength_nm: f64, cos_theta: f64) -> f64 {
        let (mut num, mut den) = (0.0, 0.0);
        for (c, &w) in self.components.iter().zip(w) {
            if w > 0.0 {
                num += w * c.phase.eval(wavelength_nm, cos_theta);
                den += w;
            }
        }
        num / den
    }

    /// Σ wᵢ f(componentᵢ) / Σ wᵢ.
    fn weighted_mean(&self, wavelength_nm: f64, f: impl Fn(&MixtureComponent) -> f64) -> f64 {
        let (mut num, mut den) = (0.0, 0.0);
        for (c, w) in self.components.iter().zip(self.weights(wavelength_nm)) {
            if w > 0.0 {
                num += w * f(c);
                den += w;
            }
        }
        num / den
    }

    /// Component choice by `u0`, then the rescaled `u0` samples that component.
    pub fn sample_cos_theta(&self, wavelength_nm: f64, u0: f64) -> f64 {
        let total: f64 = self.weights(wavelength_nm).sum();
        let target = u0 * total;
        let mut acc = 0.0;
        let mut last = 0;
        for (i, w) in self.weights(wavelength_nm).enumerate() {
            if w <= 0.0 {
                continue;
            }
            if target < acc + w {
                return self.sample_component(i, wavelength_nm, (target - acc) / w);
            }
            last = i;
            acc += w;
        }
        // u0 rounded up to the end: the last component with positive weight.
        self.sample_component(last, wavelength_nm, 1.0)
    }

    fn sample_component(&self, i: usize, wavelength_nm: f64, u: f64) -> f64 {
        self.components[i].phase.sample_cos_theta(wavelength_nm, u.clamp(0.0, 1.0 - f64::EPSILON / 2.0))
    }

    /// True unless the weights are fixed (one component, or constant σ_s,i) and no component
    /// depends on wavelength itself.
    pub fn depends_on_wavelength(&self) -> bool {
        let weights_vary = self.components.len() > 1 && self.components.iter().any(|c| !c.sigma_s.is_constant());
        weights_vary || self.components.iter().any(|c| c.phase.depends_on_wavelength())
    }
}
