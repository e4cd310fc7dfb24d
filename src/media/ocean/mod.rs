//! Sea water configured by its constituents' concentrations, built from published tables that
//! morgana carries (see [`builtin`] for each table's source), or a scene's own folder of them.
//!
//! The medium, at wavelength λ (nm):
//! - elastic absorption σ_a = a_w + max(0, a_p − a_φ) (water, non-algal particles);
//! - elastic scattering: a mixture of water (b_w, pure-water phase function) and particles (b_p,
//!   Petzold's average-particle phase function or Henyey–Greenstein g = 0.924) — see
//!   [`water`] and [`phytoplankton`];
//! - inelastic components, each adding its coefficient to the extinction:
//!   - chlorophyll fluorescence, σ = a_φ (Bricaud 1998), Gaussian 685 nm / 10.6 nm, Φ_C;
//!   - CDOM fluorescence, σ = a_y(λ) = a_y(440) exp(−S (λ − 440)), S = 0.014 nm⁻¹ (Bricaud,
//!     Morel & Prieur 1981; Mobley 1994 Eq. 3.27 — exponential: the linear form printed by
//!     Gutierrez et al. 2005 is a typo), FA7 redistribution (Hawes 1992) with its own yield
//!     Γ(λ') ≈ 0.01–0.02, or a constant Φ_Y;
//!   - Raman scattering by water, b_R(λ') = 2.7·10⁻⁴ (488/λ')^5.3 m⁻¹: Bartlett et al. (1998)
//!     measured b_R(488) = (2.7 ± 0.2)·10⁻⁴ m⁻¹ and λ'^(−5.3 ± 0.3) *normalised to photons*
//!     (λ'^−5.5 normalised to energy), so this component counts photons (photon-number
//!     accounting: energy × λ'/λ); Walrafen's band; the Raman phase function. (Mobley 1994,
//!     §5.13, uses 2.6·10⁻⁴ m⁻¹ and an energy-normalised redistribution; a generic `raman`
//!     component defaults to that energy accounting.)
//!
//! Spectra are tabulated every 1 nm over the scene's wavelength range.
//!
//! # References
//! - Mobley, *Light and Water* (1994), ch. 3 and §5.12–5.13.
//! - Bartlett, Voss, Sathyendranath & Vodacek, Appl. Opt. 37 (1998), 3324–3332.
//! - Bricaud, Morel & Prieur, "Absorption by dissolved organic matter of the sea (yellow
//!   substance) in the UV and visible domains", Limnol. Oceanogr. 26 (1981), 43–53.

pub mod builtin;
pub mod phytoplankton;
pub mod tables;
pub mod water;

use super::inelastic::{Accounting, Component, GaussianEmission, Process, RamanShift, Redistribution, Yield};
use super::phase::{MixtureComponent, PhaseFunction};
use super::{Coefficients, Medium, density::Density, inelastic::Inelastic};
use crate::spectrum::{Spectrum, Tabulated};
pub use builtin::OceanData;

/// The particles' phase function.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ParticlePhase {
    /// Petzold's average particle phase function (Mobley et al. 1993, Table 2).
    Petzold,
    /// Henyey–Greenstein with the given mean cosine g (0.924 matches Petzold).
    HenyeyGreenstein(f64),
}

/// What a scene says about its sea water.
#[derive(Clone, Debug, PartialEq)]
pub struct OceanParams {
    /// Chlorophyll-a concentration Chl, mg m⁻³.
    pub chl_mg_m3: f64,
    /// CDOM absorption a_y(440), m⁻¹.
    pub cdom_a440_per_m: f64,
    /// Spectral slope S of CDOM absorption, a_y(λ) = a_y(440) exp(−S (λ − 440)), nm⁻¹.
    pub cdom_slope_per_nm: f64,
    /// Φ_C; 0 turns chlorophyll fluorescence off.
    pub chl_yield: f64,
    /// Φ_Y; `None`: FA7's own Γ(λ'); `Some(0)` turns CDOM fluorescence off.
    pub cdom_yield: Option<f64>,
    /// Whether water Raman scattering is a component.
    pub raman: bool,
    /// Phase function of the particles' elastic scattering.
    pub particle_phase: ParticlePhase,
    /// Where the tables come from (built in unless the scene names a `data_dir`).
    pub data: OceanData,
}

impl OceanParams {
    /// Defaults: clear water (Chl 0.1 mg m⁻³, no CDOM), Φ_C = 0.02, FA7 yield, Raman on,
    /// Petzold particles.
    pub fn new(data: OceanData) -> OceanParams {
        OceanParams {
            chl_mg_m3: 0.1,
            cdom_a440_per_m: 0.0,
            cdom_slope_per_nm: 0.014,
            chl_yield: 0.02,
            cdom_yield: None,
            raman: true,
            particle_phase: ParticlePhase::Petzold,
            data,
        }
    }
}

/// a_y(λ) = a_y(440) exp(−S (λ − 440)), m⁻¹.
pub fn cdom_absorption(a440: f64, slope: f64, wavelength_nm: f64) -> f64 {
    a440 * (-slope * (wavelength_nm - 440.0)).exp()
}

/// b_R(λ') = 2.7·10⁻⁴ (488/λ')^5.3, m⁻¹.
pub fn raman_coefficient(wavelength_nm: f64) -> f64 {
    2.7e-4 * (488.0 / wavelength_nm).powf(5.3)
}

/// The sea-water medium over wavelengths `range` (nm).
pub fn sea_water(name: &str, p: &OceanParams, range: (f64, f64)) -> Result<Medium, String> {
    let water = water::WaterAbsorption::read(&p.data)?;
    let (lo, hi) = water.domain_nm();
    if range.0 < lo || range.1 > hi {
        return Err(format!(
            "the scene simulates {}–{} nm but sea water's absorption tables (Pope & Fry 1997, Smith & Baker 1981) cover {lo}–{hi} nm; set [output] min_nm and max_nm within it",
            range.0, range.1
        ));
    }
    let bricaud = phytoplankton::Bricaud::read(&p.data)?;
    let chl = p.chl_mg_m3;
    let grid = |f: &dyn Fn(f64) -> f64| tabulate(range, f);
    let sigma_a = grid(&|l| water.at(l) + (bricaud.particles(chl, l) - bricaud.phytoplankton(chl, l)).max(0.0))?;
    let mut scatterers = vec![MixtureComponent::new(grid(&water::scattering)?, PhaseFunction::pure_water())];
    if chl > 0.0 {
        let phase = match p.particle_phase {
            ParticlePhase::Petzold => p.data.petzold()?,
            ParticlePhase::HenyeyGreenstein(g) => PhaseFunction::henyey_greenstein(g)?,
        };
        scatterers.push(MixtureComponent::new(grid(&|l| phytoplankton::scattering(chl, l))?, phase));
    }
    let mut components = Vec::new();
    if chl > 0.0 && p.chl_yield > 0.0 {
        components.push(Component {
            name: "chlorophyll fluorescence".into(),
            process: Process::Fluorescence,
            coefficient: grid(&|l| bricaud.phytoplankton(chl, l))?,
            quantum_yield: Yield::Constant(p.chl_yield),
            excitation_nm: (370.0, 690.0),
            redistribution: Redistribution::Gaussian(GaussianEmission::new(685.0, 10.6)?),
            phase: PhaseFunction::isotropic(),
            accounting: Accounting::PhotonNumber,
        });
    }
    // CDOM absorbs even with its fluorescence off; then it joins σ_a below.
    let cdom_on = p.cdom_a440_per_m > 0.0 && p.cdom_yield != Some(0.0);
    let a_y = |l: f64| cdom_absorption(p.cdom_a440_per_m, p.cdom_slope_per_nm, l);
    if cdom_on {
        let fa7 = p.data.fa7()?;
        components.push(Component {
            name: "CDOM fluorescence".into(),
            process: Process::Fluorescence,
            coefficient: grid(&a_y)?,
            quantum_yield: p.cdom_yield.map_or(Yield::FromRedistribution, Yield::Constant),
            excitation_nm: fa7.excitation_nm(),
            redistribution: Redistribution::Fa7(Box::new(fa7)),
            phase: PhaseFunction::isotropic(),
            accounting: Accounting::PhotonNumber,
        });
    }
    if p.raman {
        components.push(raman_component(grid(&raman_coefficient)?, RamanShift::walrafen(), Accounting::PhotonNumber));
    }
    let sigma_a = if p.cdom_a440_per_m > 0.0 && !cdom_on { grid(&|l| sigma_a.eval(l) + a_y(l))? } else { sigma_a };
    Ok(Medium {
        name: name.to_string(),
        coefficients: Coefficients::AbsorptionMixture { sigma_a },
        phase: PhaseFunction::mixture(scatterers)?,
        density: Density::Uniform,
        index: None,
        inelastic: Inelastic { components, transfer: None },
    })
}

/// Raman scattering by water with coefficient `b_r` (m⁻¹).
pub fn raman_component(b_r: Spectrum, band: RamanShift, accounting: Accounting) -> Component {
    Component {
        name: "Raman (water)".into(),
        process: Process::Raman,
        coefficient: b_r,
        quantum_yield: Yield::Constant(1.0),
        excitation_nm: (0.0, f64::INFINITY),
        redistribution: Redistribution::Raman(band),
        phase: PhaseFunction::raman(),
        accounting,
    }
}

/// `f` tabulated every 1 nm over `range` (and at its ends).
pub fn tabulate(range: (f64, f64), f: &dyn Fn(f64) -> f64) -> Result<Spectrum, String> {
    let (lo, hi) = range;
    let n = ((hi - lo).ceil() as usize).max(1);
    let nm: Vec<f64> = (0..=n).map(|i| (lo + i as f64).min(hi)).collect();
    let mut nm = nm;
    nm.dedup_by(|a, b| a <= b);
    let values = nm.iter().map(|&l| f(l)).collect();
    Tabulated::new(nm, values).map(Spectrum::Tabulated)
}
