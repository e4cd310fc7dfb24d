//! Illuminance on a grid of points on a plane (a lighting engineer's calculation surface: the
//! desk plane, a road, a wall).
//!
//! The grid spans origin + s u + t v for s, t ∈ [0, 1] with points at the centres of nx × ny
//! cells; it measures on the side of the unit normal n (default (u × v)/|u × v|). The plane is
//! virtual — it blocks no light — and need not lie on a surface. At each point
//!
//! E_v = K_m ∫ E_e(λ) ȳ(λ) dλ,  E_e(λ) = E_direct(λ) + E_indirect(λ)
//!
//! - E_direct = Σ_lights S(λ) · weight · cos θ, by one shadow ray per light and sample (exact for
//!   point-like lights; a luminaire emitting from its opening is averaged over its samples);
//! - E_indirect = π · mean L(λ) over cosine-distributed gather rays, L being what a gather ray of
//!   the eye pass reads from the global photon map where it meets a diffuse surface (so light
//!   reflected at least once; caustics through glass reach it along those rays).
//!
//! The lux integral runs over the scene's wavelength range only, by stratified sampling: each
//! sample takes one wavelength per band (jittered within it, as eye paths do), so
//! E_v ≈ K_m Σ_b E_e(λ_b) ȳ(λ_b) Δλ_b, an unbiased estimate. Columns: `E_lx`, `E_direct_lx`,
//! `E_indirect_lx`.

use glam::DVec3;

/// Illuminance on a grid of points on a plane (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct IlluminancePlane {
    /// A corner of the grid, m.
    pub origin: DVec3,
    /// First edge, m (points along it: `nx`).
    pub u: DVec3,
    /// Second edge, m (points along it: `ny`).
    pub v: DVec3,
    /// Unit normal of the measuring side.
    pub normal: DVec3,
    /// Points along `u`.
    pub nx: usize,
    /// Points along `v`.
    pub ny: usize,
    /// Estimates averaged per point.
    pub samples: usize,
    /// Gather rays per sample for indirect light (0: direct light only).
    pub gather_rays: usize,
}

impl IlluminancePlane {
    /// The centre of cell (i, j).
    pub fn point(&self, i: usize, j: usize) -> DVec3 {
        self.origin + (i as f64 + 0.5) / self.nx as f64 * self.u + (j as f64 + 0.5) / self.ny as f64 * self.v
    }
}
