//! Inelastic scattering: fluorescence and Raman scattering, which move light from an excitation
//! wavelength λ' to an emission wavelength λ (Gutierrez, Muñoz, Anson & Serón 2005, §2.1–2.2
//! and §3, the full radiative transfer equation's inelastic term
//! ∫∫ σ_i(λ') f_i(λ' → λ) L(λ', ω') p_i(ω' · ω) dω' dλ').
//!
//! A medium's [`Inelastic`] holds its [`Component`]s. In photon tracing (`src/photon/`), once the
//! first roulette on the albedo σ_s/σ_t has found an interaction not to be an elastic scattering,
//! [`Inelastic::interact`] chooses what took the photon in proportion to its coefficient — each
//! component's σ_i(λ'), or the medium's remaining absorption — and for fluorescence plays the
//! second roulette on the quantum yield Φ_i(λ') (Gutierrez et al. Eq. 14); a re-emitted photon
//! gets a wavelength drawn from f̂_i(λ' → ·), a direction from the emission phase function, and
//! its energy times the component's energy factor ([`Accounting`]). Raman scattering always
//! re-emits inside the component's excitation window; outside it (Φ = 0) every component only
//! absorbs, in photon tracing as in the volume-map estimate and the path tracer. The volume map
//! sees the re-emitted light through [`BandTransfer`]; the path tracer through
//! [`Inelastic::sample_excitation`].
//!
//! Models: [`GaussianEmission`] (chlorophyll), [`Fa7`] (CDOM, Hawes 1992), [`RamanShift`]
//! (water).
//!
//! # References
//! - Gutierrez, Muñoz, Anson & Serón, "Non-linear volume photon mapping", EGSR 2005.
//! - Mobley, *Light and Water* (1994), §5.12–5.13.

mod component;
mod fa7;
mod gaussian;
mod raman;
mod redistribution;
mod transfer;

pub use component::{Accounting, Component, Process, Yield};
pub use fa7::Fa7;
pub use gaussian::GaussianEmission;
pub use raman::RamanShift;
pub use redistribution::Redistribution;
pub use transfer::BandTransfer;

use crate::rng::Rng;
use glam::DVec3;

/// The inelastic components of a medium (none for most media).
#[derive(Clone, Debug, Default)]
pub struct Inelastic {
    /// The components, in scene order; [`Outcome`] and [`Excitation`] index into this.
    pub components: Vec<Component>,
    /// The band table of the volume-map estimate, built for the scene's bands.
    pub transfer: Option<BandTransfer>,
}

/// What an interaction that was not an elastic scattering did to a photon.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Outcome {
    /// Absorbed for good, by component `component` (None: by the medium's other absorption).
    Absorbed {
        /// Index of the absorbing component, or `None` for the medium's other absorption.
        component: Option<usize>,
    },
    /// Re-emitted (or Raman-scattered) by `component` at `wavelength_nm` toward `dir`, its
    /// energy multiplied by `energy_factor`.
    Emitted {
        /// Index of the component in [`Inelastic::components`].
        component: usize,
        /// Emission wavelength λ, nm.
        wavelength_nm: f64,
        /// Unit direction of travel of the re-emitted photon.
        dir: DVec3,
        /// Factor on the photon's energy: λ'/λ (photon-number accounting) or 1.
        energy_factor: f64,
    },
}

/// An excitation chosen for light emitted at λ (the path tracer's adjoint step).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Excitation {
    /// Index of the chosen component in [`Inelastic::components`].
    pub component: usize,
    /// Excitation wavelength λ', nm.
    pub wavelength_nm: f64,
    /// σ_i(λ') Φ_i f̂_i(λ' → λ) E_i(λ', λ) / (P(i) pdf(λ')), m⁻¹ at density 1.
    pub weight: f64,
}

impl Inelastic {
    /// No inelastic component.
    pub fn none() -> Inelastic {
        Inelastic::default()
    }

    /// True when the medium has no inelastic component.
    pub fn is_empty(&self) -> bool {
        self.components.is_empty()
    }

    /// Σ_i σ_i(λ), the components' share of the extinction at density 1, m⁻¹.
    pub fn sigma(&self, wavelength_nm: f64) -> f64 {
        self.components.iter().map(|c| c.coefficient(wavelength_nm)).sum()
    }

    /// After the first roulette: `non_elastic` = σ_t − σ_s at λ (density 1) is shared between
    /// the components and the medium's other absorption; chooses one in proportion, then plays
    /// the second roulette and draws the emission.
    pub fn interact(&self, wavelength_nm: f64, non_elastic: f64, dir: DVec3, rng: &mut Rng) -> Outcome {
        let mut x = rng.uniform() * non_elastic;
        let Some(i) = self.components.iter().position(|c| {
            let s = c.coefficient(wavelength_nm);
            let hit = x < s;
            x -= s;
            hit
        }) else {
            return Outcome::Absorbed { component: None };
        };
        let c = &self.components[i];
        let absorbed = Outcome::Absorbed { component: Some(i) };
        // The second roulette on Φ(λ'), which is 0 outside the component's excitation window for
        // Raman as for fluorescence; Raman's Φ is 1 inside it, so it needs no random number.
        let reemits = match c.process {
            Process::Fluorescence => rng.uniform() < c.yield_at(wavelength_nm),
            Process::Raman => c.yield_at(wavelength_nm) > 0.0,
        };
        if !reemits {
            return absorbed;
        }
        let Some(l) = c.redistribution.sample(wavelength_nm, rng) else { return absorbed };
        let (wo, _) = c.phase.sample(l, dir, rng.uniform2());
        Outcome::Emitted { component: i, wavelength_nm: l, dir: wo, energy_factor: c.energy_factor(wavelength_nm, l) }
    }

    /// For light emitted at λ: a component (uniformly) and an excitation λ' within its window
    /// and `range` (the wavelengths light can have), weighted so that the expectation of
    /// weight · L(λ') is Σ_i ∫ σ_i(λ') Φ_i f̂_i E_i L(λ') dλ'.
    pub fn sample_excitation(&self, emission_nm: f64, range: (f64, f64), rng: &mut Rng) -> Option<Excitation> {
        if self.components.is_empty() {
            return None;
        }
        let n = self.components.len();
        let i = (rng.below(n as u64) as usize).min(n - 1);
        let c = &self.components[i];
        let window = (c.excitation_nm.0.max(range.0), c.excitation_nm.1.min(range.1));
        let (lex, pdf) = c.redistribution.sample_excitation(emission_nm, window, rng)?;
        let weight = c.coefficient(lex) * c.energy_redistribution(lex, emission_nm) * n as f64 / pdf;
        (weight > 0.0 && weight.is_finite()).then_some(Excitation { component: i, wavelength_nm: lex, weight })
    }
}
