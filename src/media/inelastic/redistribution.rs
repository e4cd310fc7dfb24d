//! Wavelength redistribution functions f̂(λ' → λ): the normalised spectrum (per nm of λ, with
//! ∫ f̂ dλ = 1) of the light an inelastic event at excitation λ' sends out, one file per model.
//!
//! The quantum yield and the energy accounting are the component's (see [`super::Component`]);
//! FA7 also carries its own yield Γ(λ'). Anti-Stokes emission (λ < λ') is whatever the model
//! gives: a Gaussian emission band is excitation-independent and so emits below λ' when λ'
//! exceeds its peak; Raman and FA7 emit almost only above λ'.

use super::fa7::Fa7;
use super::gaussian::GaussianEmission;
use super::raman::{NM_CM, RamanShift};
use crate::rng::Rng;

/// A wavelength redistribution f̂(λ' → λ), one variant per model.
#[derive(Clone, Debug)]
pub enum Redistribution {
    /// An excitation-independent Gaussian band (chlorophyll fluorescence).
    Gaussian(GaussianEmission),
    /// Hawes' FA7 excitation–emission matrix (CDOM fluorescence), with its own yield Γ(λ').
    Fa7(Box<Fa7>),
    /// A wavenumber shift by the water Raman band.
    Raman(RamanShift),
}

impl Redistribution {
    /// f̂(λ' → λ) per nm.
    pub fn density(&self, excitation_nm: f64, emission_nm: f64) -> f64 {
        match self {
            Redistribution::Gaussian(g) => g.density(emission_nm),
            Redistribution::Fa7(f) => f.density(excitation_nm, emission_nm),
            Redistribution::Raman(r) => r.density(excitation_nm, emission_nm),
        }
    }

    /// The emission wavelengths (nm) outside which f̂(λ' → λ) is exactly zero in f64, so that
    /// band integrals need not visit them.
    pub fn nonzero_nm(&self, excitation_nm: f64) -> (f64, f64) {
        match self {
            Redistribution::Gaussian(g) => g.nonzero_nm(),
            Redistribution::Fa7(_) => super::fa7::EMISSION_RANGE_NM,
            Redistribution::Raman(r) => r.nonzero_nm(excitation_nm),
        }
    }

    /// An emission wavelength drawn from f̂(λ' → ·), if the model emits at this excitation.
    pub fn sample(&self, excitation_nm: f64, rng: &mut Rng) -> Option<f64> {
        match self {
            Redistribution::Gaussian(g) => Some(g.sample(rng)),
            Redistribution::Fa7(f) => f.sample(excitation_nm, rng),
            Redistribution::Raman(r) => r.sample(excitation_nm, rng),
        }
    }

    /// The model's own quantum yield at λ', if it defines one (FA7's Γ).
    pub fn intrinsic_yield(&self, excitation_nm: f64) -> Option<f64> {
        match self {
            Redistribution::Fa7(f) => Some(f.quantum_yield(excitation_nm)),
            _ => None,
        }
    }

    /// An excitation λ' for light emitted at λ, within `window` (nm), and its density per nm:
    /// uniform over the window, except Raman, whose shift band is sampled (κ' = κ + Δκ, density
    /// g(Δκ) 10⁷/λ'²). The adjoint direction, for the path tracer.
    pub fn sample_excitation(&self, emission_nm: f64, window: (f64, f64), rng: &mut Rng) -> Option<(f64, f64)> {
        let (lo, hi) = window;
        if hi.partial_cmp(&lo) != Some(std::cmp::Ordering::Greater) {
            return None;
        }
        match self {
            Redistribution::Raman(r) => {
                let shift = r.sample_shift(rng);
                let l = NM_CM / (NM_CM / emission_nm + shift);
                let pdf = r.band(shift) * NM_CM / (l * l);
                ((lo..=hi).contains(&l) && pdf > 0.0).then_some((l, pdf))
            }
            _ => Some((lo + (hi - lo) * rng.uniform(), 1.0 / (hi - lo))),
        }
    }
}
