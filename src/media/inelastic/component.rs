//! One inelastic process of a medium: what absorbs (or Raman-scatters) at λ', with what yield,
//! into which spectrum and directions, and how energy is counted.
//!
//! # Energy accounting (explicit, per component)
//! - [`Accounting::PhotonNumber`]: Φ counts photons (a quantum yield). A re-emitted photon
//!   carries the energy it was absorbed with times λ'/λ (each photon's energy is hc/λ), so the
//!   energy redistribution is f(λ' → λ) = Φ f̂(λ' → λ) λ'/λ — Mobley (1994) Eq. 5.104 for
//!   chlorophyll, Gutierrez et al. (2005) Eq. 12. Default for fluorescence.
//! - [`Accounting::Energy`]: Φ is an energy yield and the re-emitted photon keeps its energy,
//!   f = Φ f̂. Default for a generic Raman component, whose redistribution as published
//!   (Mobley 1994, §5.13) integrates to one over λ, i.e. b_R counts energy (the form of the
//!   Mobley et al. 1993 comparisons). The ocean model's Raman component counts photons instead,
//!   because its b_R(λ') (Bartlett et al. 1998, λ'^−5.3) is normalised to photons.
//!
//! Raman scattering is a scattering, not an absorption: its coefficient b_R(λ') adds to the
//! extinction and every Raman event inside the component's excitation window re-emits (Φ = 1);
//! outside the window Φ = 0, as for fluorescence.

use super::redistribution::Redistribution;
use crate::media::phase::PhaseFunction;
use crate::spectrum::Spectrum;
use serde::Serialize;

/// Which kind of inelastic event a component stands for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Process {
    /// Absorption, then re-emission with probability Φ (the second Russian roulette).
    Fluorescence,
    /// Inelastic scattering: every event re-emits.
    Raman,
}

/// How the yield Φ counts (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Accounting {
    /// Φ counts photons; a re-emitted photon's energy is scaled by λ'/λ.
    PhotonNumber,
    /// Φ counts energy; a re-emitted photon keeps its energy.
    Energy,
}

/// The quantum (or energy) yield Φ(λ').
#[derive(Clone, Debug)]
pub enum Yield {
    /// The same Φ at every excitation wavelength.
    Constant(f64),
    /// Φ(λ') as a spectrum over the excitation wavelength.
    Spectral(Spectrum),
    /// The redistribution's own yield (FA7's Γ(λ')).
    FromRedistribution,
}

/// One inelastic process of a medium (fluorescence or Raman) and how it re-emits.
#[derive(Clone, Debug)]
pub struct Component {
    /// Label in `report.json` and messages.
    pub name: String,
    /// Fluorescence or Raman.
    pub process: Process,
    /// σ_a,i(λ') for fluorescence, b_R(λ') for Raman; m⁻¹ at density 1.
    pub coefficient: Spectrum,
    /// Quantum (or energy) yield Φ(λ'); ignored for Raman, which always re-emits.
    pub quantum_yield: Yield,
    /// Excitations outside this window (nm) are absorbed without re-emission (Φ = 0 there).
    pub excitation_nm: (f64, f64),
    /// Normalised emission spectrum f̂(λ' → λ), nm⁻¹.
    pub redistribution: Redistribution,
    /// Angular distribution of the re-emitted light about the absorbed photon's direction.
    pub phase: PhaseFunction,
    /// Whether Φ counts photons or energy.
    pub accounting: Accounting,
}

impl Component {
    /// σ_a,i(λ') or b_R(λ'), m⁻¹ at density 1.
    pub fn coefficient(&self, excitation_nm: f64) -> f64 {
        self.coefficient.eval(excitation_nm).max(0.0)
    }

    /// Φ(λ') in [0, 1]: the probability that an absorption by this component re-emits (1 for
    /// Raman inside its window).
    pub fn yield_at(&self, excitation_nm: f64) -> f64 {
        let (lo, hi) = self.excitation_nm;
        if !(lo..=hi).contains(&excitation_nm) {
            return 0.0;
        }
        let phi = match (&self.quantum_yield, self.process) {
            (_, Process::Raman) => 1.0,
            (Yield::Constant(c), _) => *c,
            (Yield::Spectral(s), _) => s.eval(excitation_nm),
            (Yield::FromRedistribution, _) => self.redistribution.intrinsic_yield(excitation_nm).unwrap_or(0.0),
        };
        phi.clamp(0.0, 1.0)
    }

    /// The factor a re-emitted photon's energy is multiplied by.
    pub fn energy_factor(&self, excitation_nm: f64, emission_nm: f64) -> f64 {
        match self.accounting {
            Accounting::PhotonNumber => excitation_nm / emission_nm,
            Accounting::Energy => 1.0,
        }
    }

    /// The energy redistribution per unit absorbed (or Raman-scattered) energy:
    /// Φ(λ') f̂(λ' → λ) times the energy factor, per nm.
    pub fn energy_redistribution(&self, excitation_nm: f64, emission_nm: f64) -> f64 {
        self.yield_at(excitation_nm)
            * self.redistribution.density(excitation_nm, emission_nm)
            * self.energy_factor(excitation_nm, emission_nm)
    }
}
