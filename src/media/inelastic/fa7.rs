//! CDOM fluorescence: the excitation-dependent redistribution of Hawes (1992), sample FA7.
//!
//! The spectral quantum efficiency (photons emitted per nm of λ per photon absorbed at λ') is
//!
//! η_Y(λ' → λ) = A₀(λ') exp{ −[ (1/λ − A₁/λ' − B₁) / (0.6 (A₂/λ' + B₂)) ]² }  (nm⁻¹, λ in nm),
//!
//! A₁ = 0.470, A₂ = 0.407, B₁ = 8.077·10⁻⁴ nm⁻¹, B₂ = −4.57·10⁻⁴ nm⁻¹, with A₀(λ') read from the
//! built-in table (`src/media/ocean/data/hawes_1992_cdom_fluorescence_FA7.csv`, linear between its rows, zero outside
//! 310–550 nm). The quantum yield is Γ(λ') = ∫ η_Y dλ, the normalised emission spectrum
//! η_Y/Γ, and the energy redistribution f_Y = η_Y λ'/λ (photon-number accounting).
//!
//! # Representation
//! η_Y is tabulated at excitation nodes every [`EXCITATION_STEP_NM`] nm over 310–550 nm and
//! emission nodes every 1 nm over [`EMISSION_RANGE_NM`], piecewise linear in λ. Between two
//! excitation nodes the normalised spectrum is the linear blend (1 − t) ĥ_k + t ĥ_{k+1}, and it
//! is sampled exactly so: node k + 1 with probability t, then the node's spectrum by inverse CDF.
//! Γ(λ') is interpolated linearly likewise. At a node the representation reproduces the formula
//! to the 1-nm emission interpolation (relative error ≈ h² |η''| / 8 < 10⁻⁴).
//!
//! # References
//! - Hawes, *Factors influencing the variability in the fluorescence signatures of marine
//!   dissolved organic matter*, MS thesis, University of South Florida (1992), Table 3, FA7.
//! - Mobley, *Light and Water* (1994), §5.12, Eq. 5.103 and Fig. 5.11; HydroLight's
//!   `wrfuncs.f` (the constants and A₀; see the built-in CSV's header).

use crate::rng::Rng;
use crate::spectrum::{Spectrum, SpectrumSampler, Tabulated};
use std::path::Path;

pub const A1: f64 = 0.470;
pub const A2: f64 = 0.407;
pub const B1_PER_NM: f64 = 8.077e-4;
pub const B2_PER_NM: f64 = -4.57e-4;
/// Excitation nodes of the representation, nm apart.
pub const EXCITATION_STEP_NM: f64 = 2.0;
/// Emission wavelengths represented; η_Y outside is below 10⁻⁶ of its peak for every excitation.
pub const EMISSION_RANGE_NM: (f64, f64) = (250.0, 1200.0);

/// The FA7 redistribution, with its A₀ table.
#[derive(Clone, Debug)]
pub struct Fa7 {
    /// A₀ table rows (λ' nm, nm⁻¹).
    table: Tabulated,
    /// First excitation node, nm.
    first_nm: f64,
    /// Per excitation node: Γ and the sampler of η_Y/Γ (None where Γ = 0).
    nodes: Vec<(f64, Option<SpectrumSampler>)>,
}

impl Fa7 {
    /// Reads A₀ from a CSV of `lex_nm,A0_per_nm` rows (comment lines start with `#`).
    pub fn from_csv(path: &Path) -> Result<Fa7, String> {
        let text = std::fs::read_to_string(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
        Fa7::from_csv_text(path, &text)
    }

    /// [`Fa7::from_csv`] of the file's text; `path` names it in errors.
    pub fn from_csv_text(path: &Path, text: &str) -> Result<Fa7, String> {
        let (nm, a0) = crate::spectrum::table::parse_two_column_csv(text)
            .map_err(|(line, e)| format!("{}:{line}: {e}", path.display()))?;
        if a0.iter().any(|a| !(a.is_finite() && *a >= 0.0)) {
            return Err(format!("{}: A0 values must be finite and non-negative", path.display()));
        }
        let table = Tabulated::new(nm, a0).map_err(|e| format!("{}: {e}", path.display()))?;
        Fa7::from_table(table).map_err(|e| format!("{}: {e}", path.display()))
    }

    /// From an A₀(λ') table.
    pub fn from_table(table: Tabulated) -> Result<Fa7, String> {
        let (lo, hi) = table.domain_nm();
        let count = ((hi - lo) / EXCITATION_STEP_NM).floor() as usize + 1;
        let nodes = (0..count)
            .map(|k| {
                let lex = lo + k as f64 * EXCITATION_STEP_NM;
                let tab = emission_table(&table, lex)?;
                let gamma = tab.integral(EMISSION_RANGE_NM.0, EMISSION_RANGE_NM.1);
                let sampler = SpectrumSampler::new(&Spectrum::Tabulated(tab), EMISSION_RANGE_NM.0, EMISSION_RANGE_NM.1);
                Ok((gamma, sampler))
            })
            .collect::<Result<Vec<_>, String>>()?;
        Ok(Fa7 { table, first_nm: lo, nodes })
    }

    /// η_Y(λ' → λ) by the formula (nm⁻¹).
    pub fn eta(&self, excitation_nm: f64, emission_nm: f64) -> f64 {
        eta(&self.table, excitation_nm, emission_nm)
    }

    /// The excitation range where A₀ is tabulated, nm.
    pub fn excitation_nm(&self) -> (f64, f64) {
        self.table.domain_nm()
    }

    /// Node index k and blend weight t of excitation `lex` (None outside the table).
    fn locate(&self, lex: f64) -> Option<(usize, f64)> {
        let x = (lex - self.first_nm) / EXCITATION_STEP_NM;
        if !(x >= 0.0 && x <= (self.nodes.len() - 1) as f64) {
            return None;
        }
        let k = (x.floor() as usize).min(self.nodes.len().saturating_sub(2));
        Some((k, (x - k as f64).clamp(0.0, 1.0)))
    }

    /// The quantum yield Γ(λ') = ∫ η_Y dλ (linear between excitation nodes).
    pub fn quantum_yield(&self, excitation_nm: f64) -> f64 {
        match self.locate(excitation_nm) {
            None => 0.0,
            Some((k, _)) if self.nodes.len() == 1 => self.nodes[k].0,
            Some((k, t)) => (1.0 - t) * self.nodes[k].0 + t * self.nodes[k + 1].0,
        }
    }

    /// The normalised emission spectrum at excitation λ' (per nm), as represented.
    pub fn density(&self, excitation_nm: f64, emission_nm: f64) -> f64 {
        let Some((k, t)) = self.locate(excitation_nm) else { return 0.0 };
        let node = |j: usize| match self.nodes.get(j) {
            Some((_, Some(s))) => s.pdf(emission_nm),
            _ => 0.0,
        };
        let (a, b) = (node(k), node(k + 1));
        match (self.has(k), self.has(k + 1)) {
            (true, true) => (1.0 - t) * a + t * b,
            (true, false) => a,
            (false, true) => b,
            (false, false) => 0.0,
        }
    }

    fn has(&self, k: usize) -> bool {
        matches!(self.nodes.get(k), Some((_, Some(_))))
    }

    /// An emission wavelength for excitation λ', drawn from [`Fa7::density`].
    pub fn sample(&self, excitation_nm: f64, rng: &mut Rng) -> Option<f64> {
        let (k, t) = self.locate(excitation_nm)?;
        let pick = if rng.uniform() < t && self.has(k + 1) || !self.has(k) { k + 1 } else { k };
        match self.nodes.get(pick) {
            Some((_, Some(s))) => Some(s.sample(rng.uniform()).0),
            _ => None,
        }
    }
}

/// η_Y by the formula with A₀ from `table`.
fn eta(table: &Tabulated, lex: f64, lem: f64) -> f64 {
    let a0 = table.eval(lex);
    if a0 <= 0.0 || lex <= 0.0 || lem <= 0.0 {
        return 0.0;
    }
    let width = 0.6 * (A2 / lex + B2_PER_NM);
    if width <= 0.0 {
        return 0.0;
    }
    let z = (1.0 / lem - A1 / lex - B1_PER_NM) / width;
    a0 * (-z * z).exp()
}

/// η_Y(lex → ·) on the 1-nm emission grid.
fn emission_table(table: &Tabulated, lex: f64) -> Result<Tabulated, String> {
    let (lo, hi) = EMISSION_RANGE_NM;
    let n = (hi - lo) as usize;
    let nm: Vec<f64> = (0..=n).map(|i| lo + i as f64).collect();
    let values: Vec<f64> = nm.iter().map(|&l| eta(table, lex, l)).collect();
    Tabulated::new(nm, values)
}
