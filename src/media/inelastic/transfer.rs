//! What the volume photon map needs to see inelastic light: for each component and each
//! excitation λ' (1-nm nodes over the scene's range, linear between), the energy it re-emits
//! into each output band per unit energy of photons *stored* at λ':
//!
//! T_i(λ', b) = σ_i(λ')/σ_t(λ') · ∫_b Φ_i(λ') f̂_i(λ' → λ) E_i(λ', λ) dλ,
//!
//! with σ_i the component's absorption (or Raman) coefficient, σ_t the medium's extinction (the
//! stored photons' density is σ_t times the fluence, so σ_i/σ_t turns a stored photon's power
//! into the power the component takes from the field), and E_i the energy factor (λ'/λ or 1).
//! The radiance the component emits toward ω per unit length, per band, is then
//!
//! J_i(x, ω, b) ≈ Σ_p p_i(ω_p · ω) T_i(λ_p, b) ΔΦ_p / ((4/3)π r³ Δλ_b)
//!
//! — the expected value of the second roulette and of the wavelength draw over every stored
//! photon, rather than a density estimate of the rare re-emission events themselves, so the
//! estimate has the variance of the in-scattering estimate. Band integrals are by composite
//! 16-point Gauss–Legendre quadrature on panels of at most 2 nm, visiting only the panels where
//! the redistribution is not exactly zero (so a scene over 400–70,000 nm builds its table in
//! seconds, not hours: the work grows with the range times the emission band's width, not with
//! the range squared).

use super::Inelastic;
use crate::quadrature::gauss_legendre_on_support;
use crate::spectrum::BandValues;
use crate::spectrum::Bands;

/// Spacing of the excitation nodes, nm.
pub const NODE_STEP_NM: f64 = 1.0;

/// The table T_i(λ', b) of the module docs: energy re-emitted into band b per unit energy of
/// photons stored at excitation λ', per component, at 1-nm excitation nodes.
#[derive(Clone, Debug)]
pub struct BandTransfer {
    bands: Bands,
    nodes: usize,
    /// [component][node][band], `bands.count` values per node.
    table: Vec<f64>,
}

impl BandTransfer {
    /// The table for `inelastic` in a medium of extinction `sigma_t(λ)` (density 1).
    pub fn new(inelastic: &Inelastic, sigma_t: &dyn Fn(f64) -> f64, bands: &Bands) -> BandTransfer {
        let nodes = ((bands.max_nm - bands.min_nm) / NODE_STEP_NM).ceil() as usize + 1;
        let mut table = Vec::with_capacity(inelastic.components.len() * nodes * bands.count);
        for c in &inelastic.components {
            for j in 0..nodes {
                let lex = (bands.min_nm + j as f64 * NODE_STEP_NM).min(bands.max_nm);
                let st = sigma_t(lex);
                let share = if st > 0.0 { c.coefficient(lex) / st } else { 0.0 };
                for b in 0..bands.count {
                    let (lo, hi) = bands.edges_nm(b);
                    let panels = ((hi - lo) / 2.0).ceil().max(1.0) as usize;
                    let v = if share > 0.0 && c.yield_at(lex) > 0.0 {
                        let support = c.redistribution.nonzero_nm(lex);
                        gauss_legendre_on_support(&|l| c.energy_redistribution(lex, l), lo, hi, panels, support)
                    } else {
                        0.0
                    };
                    table.push(share * v);
                }
            }
        }
        BandTransfer { bands: *bands, nodes, table }
    }

    /// T_i(λ', b) for component `i`, linear between nodes.
    pub fn at(&self, i: usize, excitation_nm: f64, b: usize) -> f64 {
        self.node(excitation_nm).map_or(0.0, |node| self.lerp(i, node, b))
    }

    /// The node j below λ' and the fraction t past it (`None` below the first node, where T
    /// is 0).
    fn node(&self, excitation_nm: f64) -> Option<(usize, f64)> {
        let x = (excitation_nm - self.bands.min_nm) / NODE_STEP_NM;
        if x.is_nan() || x < 0.0 || self.nodes < 2 {
            return None;
        }
        let j = (x.floor() as usize).min(self.nodes - 2);
        Some((j, (x - j as f64).clamp(0.0, 1.0)))
    }

    /// T_i between nodes j and j + 1 at fraction t, band b.
    fn lerp(&self, i: usize, (j, t): (usize, f64), b: usize) -> f64 {
        let row = |j: usize| self.table[(i * self.nodes + j) * self.bands.count + b];
        (1.0 - t) * row(j) + t * row(j + 1)
    }

    /// Adds Σ_i p_i(cos θ) T_i(λ_p, b) ΔΦ_p to every band of `out` for one stored photon (the
    /// node found once per photon, not per band).
    pub fn add_photon(&self, inelastic: &Inelastic, out: &mut BandValues, wavelength_nm: f64, cos: f64, power_w: f64) {
        let node = self.node(wavelength_nm);
        let count = self.bands.count;
        for (i, c) in inelastic.components.iter().enumerate() {
            let p = c.phase.eval(wavelength_nm, cos) * power_w;
            let Some((j, t)) = node else {
                out.iter_mut().take(count).for_each(|o| *o += p * 0.0);
                continue;
            };
            // The rows of nodes j and j + 1 side by side: the loop over bands vectorises.
            let at = (i * self.nodes + j) * count;
            let (lo, hi) = (&self.table[at..at + count], &self.table[at + count..at + 2 * count]);
            for ((o, a), b) in out.iter_mut().zip(lo).zip(hi) {
                *o += p * ((1.0 - t) * a + t * b);
            }
        }
    }
}
