//! Each volume photon's scattering row: what a volume estimate weighs the photon by, apart from
//! the angle, computed once per medium that reads the map instead of at every estimate that
//! gathers it.
//!
//! The point estimate of in-scattered radiance at x (Jensen & Christensen 1998, eq. 6, with the
//! albedo of a stored photon's collision),
//!
//! L_s(x, ω) ≈ Σ_p σ_s/σ_t(λ_p, x_p) · p(λ_p, x_p, ω_p·ω) ΔΦ_p / ((4/3)π r³ Δλ),
//!
//! weighs each of its k nearest photons by the medium's albedo and phase function at the
//! photon's own wavelength and place. Both are spectral look-ups (an ocean's water, chlorophyll,
//! CDOM and particle tables; a mixture's σ_s,i(λ) for its weights) that depend on the photon,
//! not on the query, except through the angle — and a ray march asks for the same photons at
//! step after step. Profiled on `examples/underwater_luminaire.toml` (`perf record`, 40 × 30
//! pixels, 2026-12-04), they were 63 % of the eye pass. Here the albedo and the phase
//! function's weights ([`crate::media::MediumAt::write_scatter_row`]) are computed for every
//! photon of the map the first time a medium reads it, and each estimate reads them back
//! ([`crate::media::Medium::scattered_from_row`]), bit for bit the numbers it computed itself.
//!
//! Memory: 8 bytes × [`Medium::scatter_row_len`] (1 + the phase function's weights) per photon
//! and medium read, beside the map's 32 bytes per photon; `crate::render::memory` counts it in
//! the eye pass. Rows are filled on one thread (a rayon worker waiting for the fill must not
//! pick up another estimate of the same medium): one albedo and one set of weights per photon,
//! what a single k-nearest estimate used to evaluate k times.

use super::{PhotonMap, PhotonRecord};
use crate::media::Medium;
use std::sync::OnceLock;

/// The rows of every photon of one map, per medium of the world, filled on first use.
#[derive(Debug, Default)]
pub struct ScatterRows {
    per_medium: Vec<OnceLock<Rows>>,
}

/// One medium's rows: `stride` values per photon, in the map's order.
#[derive(Debug)]
pub struct Rows {
    stride: usize,
    values: Vec<f64>,
}

impl Rows {
    /// The row of photon `i` (an index of the map the rows were filled from).
    pub fn of(&self, i: u32) -> &[f64] {
        let at = i as usize * self.stride;
        &self.values[at..at + self.stride]
    }
}

impl ScatterRows {
    /// Empty rows for a world of `media` media.
    pub fn new(media: usize) -> ScatterRows {
        ScatterRows { per_medium: (0..media).map(|_| OnceLock::new()).collect() }
    }

    /// The rows of `map`'s photons in medium `id` (`medium`), filled now if this is the first
    /// time; `None` for an id outside the world (the caller computes the weights itself).
    pub fn rows(&self, map: &PhotonMap, id: u32, medium: &Medium) -> Option<&Rows> {
        let cell = self.per_medium.get(id as usize)?;
        Some(cell.get_or_init(|| fill(map, medium)))
    }
}

/// α(λ_p) · p(λ_p; cos θ) of photon `i` (`p`, its record) in `medium`: read from `rows` when
/// there are some, computed at the photon's place otherwise (the same number either way).
pub fn scattered(rows: Option<&Rows>, medium: &Medium, i: u32, p: &PhotonRecord, cos: f64) -> f64 {
    let l = p.wavelength_nm;
    match rows {
        Some(rows) => medium.scattered_from_row(rows.of(i), l, cos),
        None => {
            let at = medium.at(p.position);
            at.albedo(l) * at.phase_eval(l, cos)
        }
    }
}

/// Every photon's row in `medium`.
fn fill(map: &PhotonMap, medium: &Medium) -> Rows {
    let stride = medium.scatter_row_len();
    let mut values = vec![0.0; stride * map.len()];
    for (i, row) in values.chunks_exact_mut(stride).enumerate() {
        let p = map.record(i as u32);
        medium.at(p.position).write_scatter_row(p.wavelength_nm, row);
    }
    Rows { stride, values }
}
