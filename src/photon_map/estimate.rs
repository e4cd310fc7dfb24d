//! Radiance estimates from a surface photon map (Jensen 2001, §7.2; course notes §3.2).
//!
//! Reflected radiance at x from the k nearest photons within radius r (r = distance to the
//! farthest one found):
//!
//! L_r(x, ω, b) ≈ Σ_p f_r(λ_p) w_p ΔΦ_p / (c · π r² · Δλ_b)
//!
//! summed over photons whose wavelength λ_p falls in band b (so L is per nm), that arrived on
//! the side of the surface being viewed and lie on a surface of similar orientation. The filter
//! weight w_p and its normalisation c are those of the chosen [`Filter`]: box (w = 1, c = 1),
//! cone (w = 1 − d/(k r), c = 1 − 2/(3k)) or Epanechnikov (w = 2(1 − d²/r²), c = 1).

use super::{Neighbours, PhotonMap, PhotonRecord};
use crate::scene::Filter;
use crate::spectrum::{Bands, MAX_BANDS};
use glam::DVec3;
use std::f64::consts::PI;

/// Per-band values, `bands.count` of them used.
pub type BandValues = [f64; MAX_BANDS];

/// Photons on surfaces tilted more than this (cosine) from the query normal are ignored.
const MIN_NORMAL_COS: f64 = 0.5;

/// Density estimation on one map with fixed parameters.
pub struct Estimator<'a> {
    pub map: &'a PhotonMap,
    pub k: usize,
    pub max_radius: f64,
    pub filter: Filter,
    pub bands: Bands,
}

impl Estimator<'_> {
    /// Irradiance per band (W m⁻² nm⁻¹) on the side of normal `n` at `x`.
    pub fn irradiance(&self, x: DVec3, n: DVec3, nb: &mut Neighbours) -> BandValues {
        self.estimate(x, n, nb, |_| 1.0)
    }

    /// Radiance per band (W m⁻² sr⁻¹ nm⁻¹) reflected by a Lambertian surface of reflectance
    /// `rho(λ)` at `x` toward the side of normal `n` (f_r = ρ(λ_p)/π at each photon's λ).
    pub fn lambertian_radiance(&self, x: DVec3, n: DVec3, rho: &dyn Fn(f64) -> f64, nb: &mut Neighbours) -> BandValues {
        self.estimate(x, n, nb, |p| rho(p.wavelength_nm) / PI)
    }

    fn estimate(&self, x: DVec3, n: DVec3, nb: &mut Neighbours, f: impl Fn(&PhotonRecord) -> f64) -> BandValues {
        let mut out = [0.0; MAX_BANDS];
        self.map.knn(x, self.k, self.max_radius, nb);
        let r2 = nb.max_dist2() as f64;
        if nb.is_empty() || r2 <= 0.0 {
            return out;
        }
        let r = r2.sqrt();
        for &(i, d2) in &nb.items {
            let p = self.map.record(i);
            if p.dir.dot(n) >= 0.0 || p.normal.dot(n).abs() < MIN_NORMAL_COS {
                continue;
            }
            let Some(b) = self.bands.index_of(p.wavelength_nm) else {
                continue;
            };
            out[b] += filter_weight(self.filter, (d2 as f64).sqrt(), r) * f(&p) * p.power_w;
        }
        let scale = 1.0 / (filter_norm(self.filter) * PI * r2 * self.bands.width_nm());
        out.iter_mut().take(self.bands.count).for_each(|v| *v *= scale);
        out
    }
}

/// The filter weight of a photon at distance `d` in a disc of radius `r`.
pub fn filter_weight(filter: Filter, d: f64, r: f64) -> f64 {
    match filter {
        Filter::Box => 1.0,
        Filter::Cone { k } => (1.0 - d / (k * r)).max(0.0),
        Filter::Epanechnikov => (2.0 * (1.0 - d * d / (r * r))).max(0.0),
    }
}

/// ∫_disc w dA / (π r²) for a filter.
pub fn filter_norm(filter: Filter) -> f64 {
    match filter {
        Filter::Box | Filter::Epanechnikov => 1.0,
        Filter::Cone { k } => 1.0 - 2.0 / (3.0 * k),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::chi2::gauss_legendre;

    #[test]
    fn filter_normalisations_integrate_the_weights() {
        // (1/(π r²)) ∫₀ʳ w(d) 2π d dd, by quadrature, for r = 1.
        for f in [Filter::Box, Filter::Cone { k: 1.0 }, Filter::Cone { k: 1.1 }, Filter::Epanechnikov] {
            let integral = gauss_legendre(&|d| filter_weight(f, d, 1.0) * 2.0 * d, 0.0, 1.0, 8);
            assert!((integral - filter_norm(f)).abs() < 1e-12, "{f:?}: {integral}");
        }
    }
}
