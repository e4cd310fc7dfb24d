//! Radiance estimates from photon maps.
//!
//! Surfaces (Jensen 2001, §7.2; course notes §3.2): reflected radiance at x from the k nearest
//! photons within radius r (r = distance to the farthest one found),
//!
//! L_r(x, b) ≈ Σ_p f_r(λ_p) w_p ΔΦ_p / (c · s · π r² · Δλ_b),
//!
//! summed over photons whose wavelength λ_p falls in band b (so L is per nm), that arrived on
//! the side of the surface being viewed and lie on a surface of similar orientation; w_p and c
//! are the [`Filter`]'s weight and normalisation: box (w = 1, c = 1), cone (w = 1 − d/(k r),
//! c = 1 − 2/(3k)) or Epanechnikov (w = 2(1 − d²/r²), c = 1). s is the share of the disc that
//! lies on surfaces able to hold photons, measured by the estimator's [`DiscShare`] (the
//! world's, `World::gather_share`); without one s = 1, Jensen's form, which reads edges dark.
//!
//! Media (Jensen & Christensen 1998, Eq. 6 with the albedo factor of §4.3): photons are stored at
//! every interaction, so their density is σ_t times the fluence, and the radiance scattered
//! toward ω per unit length is
//!
//! σ_s L_i(x, ω, b) ≈ Σ_p α(λ_p) f(λ_p; ω_p·ω) ΔΦ_p / (V Δλ_b),
//!
//! with α = σ_s/σ_t the single-scattering albedo at the photon's own wavelength and f the phase
//! function (ω_p the photon's direction of travel, ω the scattered light's), and V the sphere's
//! volume (4/3)π r³ — or, in air stratified in height, its volume weighted by the air's density
//! relative to that at x ([`super::stratified`]), which keeps the ground and the air's steep
//! profile from biasing a sphere far larger than the scale height. A medium with
//! inelastic components adds the light they re-emit into band b from photons of every
//! wavelength, Σ_p Σ_i p_i(ω_p·ω) T_i(λ_p, b) ΔΦ_p over the same volume (see
//! [`crate::media::inelastic::BandTransfer`]); that term counts every photon, direct ones
//! included, because shadow rays compute elastic single scattering only.
//!
//! Walls (`edge_correction`): where the chord being marched starts or ends on a surface within
//! r of x, the ball reaches past it, where no photon of this medium lies, and V overstates the
//! volume the photons found stand for: by a cap of height h = r − d (d the distance from x to
//! the surface's tangent plane), the fraction h²(3r − h)/(4r³) of the ball — half when x lies on
//! the wall. [`Estimator::volume_scattered_within`] counts only the photons on x's side of such
//! [`Wall`]s (none leaks through a thin wall) and divides by V times the share of the ball left,
//! 1 − Σ caps (caps of two walls can overlap only where a chord is shorter than the ball is wide
//! and both its ends are oblique; the share is held at ≥ [`MIN_WALL_SHARE`] there).
//!
//! Folded photons: where the scene is symmetric about the sun's axis through the Earth's centre
//! ([`crate::scene::symmetry`]) the volume map's photons are turned about it into one
//! half-plane ([`crate::geometry::AxialFold`]) and so is each query; the k nearest then lie in
//! a disc of the half-plane, which stands for the ring it sweeps about the axis, and V is that
//! ring's density-weighted volume ([`super::stratified::ring_volume`]).
//!
//! The radius: when k photons are found, the k-th sets r and is left out of the sum — for
//! photons from a Poisson process, (k − 1)/V(r_k) is unbiased where k/V(r_k) is too high by
//! k/(k − 1) (Loftsgaarden & Quesenberry 1965; Silverman 1986, §5.2); when fewer are found
//! within the maximum radius, that radius is r and every photon counts.

use super::filter::{Filter, filter_norm, filter_weight};
use super::scatter_rows::{self, ScatterRows};
use super::stratified::{Region, region_volume};
use super::{Neighbours, PhotonMap, PhotonPath, PhotonRecord};
use crate::media::density::Density;
use crate::media::{Coefficients, Medium};
use crate::spectrum::{BandValues, Bands, MAX_BANDS};
use glam::DVec3;
use std::f64::consts::PI;
use std::sync::Arc;

/// Photons on surfaces tilted more than this (cosine) from the query normal are ignored.
const MIN_NORMAL_COS: f64 = 0.5;

/// Which photons an estimate counts, by what they met on the way.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Paths {
    /// Every photon.
    All,
    /// Leave out direct photons (direct light comes from shadow rays).
    NotDirect,
    /// Only photons after a diffuse bounce or a scattering (direct light and caustics come
    /// from elsewhere).
    DiffuseOnly,
}

impl Paths {
    /// Whether a photon that arrived by path `p` counts.
    pub fn accepts(self, p: PhotonPath) -> bool {
        match self {
            Paths::All => true,
            Paths::NotDirect => p != PhotonPath::Direct,
            Paths::DiffuseOnly => p == PhotonPath::Diffuse,
        }
    }
}

/// What a surface estimate divides its disc's area by: the share of the disc that lies on
/// surfaces able to hold photons.
pub trait DiscShare: Sync {
    /// The share, in (0, 1], of the disc of radius `r` about `x` in the plane normal to `n`
    /// that lies on surfaces able to hold photons arriving from `n`'s side.
    fn disc_share(&self, x: DVec3, n: DVec3, r: f64) -> f64;
}

/// A plane bounding the medium a volume estimate reads (a surface the marched chord starts or
/// ends on): a point on it and its unit normal toward the estimate's side.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Wall {
    /// A point of the plane, m.
    pub point: DVec3,
    /// Unit normal pointing into the medium's side.
    pub normal: DVec3,
}

/// The walls of one chord (the surfaces it starts and ends on, when it does), held without
/// allocating.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Walls {
    /// At the chord's start and at its end.
    pub ends: [Option<Wall>; 2],
}

impl Walls {
    /// The walls there are.
    pub fn iter(&self) -> impl Iterator<Item = &Wall> {
        self.ends.iter().flatten()
    }
}

/// The least share of the ball a volume estimate divides by when walls cut it (see the module
/// docs).
pub const MIN_WALL_SHARE: f64 = 0.25;

impl Wall {
    /// Whether `p` lies on the medium's side of the wall (or on it).
    fn holds(&self, p: DVec3) -> bool {
        (p - self.point).dot(self.normal) >= 0.0
    }

    /// The fraction of the ball of radius `r` about `x` that lies behind the wall: the cap of
    /// height h = r − d, h²(3r − h)/(4r³), for x at distance d < r in front of it; 0 beyond r.
    pub fn cap_fraction(&self, x: DVec3, r: f64) -> f64 {
        let d = (x - self.point).dot(self.normal).max(0.0);
        if d >= r || r.is_nan() || r <= 0.0 {
            return 0.0;
        }
        let h = (r - d) / r;
        h * h * (3.0 - h) / 4.0
    }
}

/// Density estimation on one map with fixed parameters.
pub struct Estimator<'a> {
    /// The photon map read.
    pub map: &'a PhotonMap,
    /// Nearest photons per estimate.
    pub k: usize,
    /// Largest gather radius, m.
    pub max_radius: f64,
    /// Kernel of the estimate.
    pub filter: Filter,
    /// The bands estimates are binned into.
    pub bands: Bands,
    /// Which photons count.
    pub paths: Paths,
    /// The volume photons' albedo and phase weights, per medium, filled on first use
    /// ([`ScatterRows`]); `None`: each estimate computes them for its photons.
    pub scatter_rows: Option<Arc<ScatterRows>>,
    /// What surface estimates measure their disc's share on surfaces with (see the module
    /// docs); `None`: the whole disc.
    pub disc_share: Option<&'a dyn DiscShare>,
}

impl Estimator<'_> {
    /// Irradiance per band (W m⁻² nm⁻¹) on the side of normal `n` at `x`.
    pub fn irradiance(&self, x: DVec3, n: DVec3, nb: &mut Neighbours) -> BandValues {
        self.surface(x, n, nb, |_| 1.0)
    }

    /// Radiance per band (W m⁻² sr⁻¹ nm⁻¹) reflected by a Lambertian surface of reflectance
    /// `rho(λ)` at `x` toward the side of normal `n` (f_r = ρ(λ_p)/π at each photon's λ).
    pub fn lambertian_radiance(&self, x: DVec3, n: DVec3, rho: &dyn Fn(f64) -> f64, nb: &mut Neighbours) -> BandValues {
        self.surface(x, n, nb, |p| rho(p.wavelength_nm) / PI)
    }

    fn surface(&self, x: DVec3, n: DVec3, nb: &mut Neighbours, f: impl Fn(&PhotonRecord) -> f64) -> BandValues {
        let mut out = [0.0; MAX_BANDS];
        let Some((r2, skip)) = self.gather(x, nb) else { return out };
        let r = r2.sqrt();
        for &(i, d2) in &nb.items {
            // The path is read from the stored flags: a photon left out is never decoded.
            if Some(i) == skip || !self.paths.accepts(self.map.photons()[i as usize].path()) {
                continue;
            }
            let p = self.map.record(i);
            if p.dir.dot(n) >= 0.0 || p.normal.dot(n).abs() < MIN_NORMAL_COS {
                continue;
            }
            let Some(b) = self.bands.index_of(p.wavelength_nm) else { continue };
            out[b] += filter_weight(self.filter, (d2 as f64).sqrt(), r) * f(&p) * p.power_w;
        }
        if out.iter().all(|v| *v == 0.0) {
            return out;
        }
        let share = self.disc_share.map_or(1.0, |d| d.disc_share(x, n, r));
        let scale = 1.0 / (filter_norm(self.filter) * share * PI * r2 * self.bands.width_nm());
        out.iter_mut().take(self.bands.count).for_each(|v| *v *= scale);
        out
    }

    /// Finds the photons around `x` and returns the squared radius of the estimate and the
    /// photon that only sets it (the k-th, when k were found), or `None` if there are none.
    fn gather(&self, x: DVec3, nb: &mut Neighbours) -> Option<(f64, Option<u32>)> {
        self.map.knn(x, self.k, self.max_radius, nb);
        if nb.is_empty() {
            return None;
        }
        if nb.len() < self.k || self.k < 2 {
            return Some((self.max_radius * self.max_radius, None));
        }
        let &(far, d2) = nb.items.iter().max_by(|a, b| a.1.total_cmp(&b.1))?;
        (d2 > 0.0).then_some((d2 as f64, Some(far)))
    }

    /// Radiance scattered per unit length toward travel direction `wo` at `x` in `medium`, per
    /// band (W m⁻³ sr⁻¹ nm⁻¹), and the radius of the sphere used (0 if no photon was found).
    ///
    /// In a map of folded photons ([`PhotonMap::folded`]) `x` and `wo` are folded too, the
    /// nearest photons are those of the disc about the folded `x`, and the volume they stand for
    /// is the ring it sweeps about the axis ([`super::stratified::Region::Ring`]).
    ///
    /// `id` is `medium`'s index in the world, which selects its [`ScatterRows`].
    pub fn volume_scattered(
        &self,
        x: DVec3,
        wo: DVec3,
        (id, medium): (u32, &Medium),
        nb: &mut Neighbours,
    ) -> (BandValues, f64) {
        self.volume_scattered_within(x, wo, (id, medium), &Walls::default(), nb)
    }

    /// [`Estimator::volume_scattered`] in the part of the medium in front of `walls` (see the
    /// module docs): photons behind a wall are not counted, and the ball's volume is scaled by
    /// the share of it in front of them. Walls apply to the plain ball only: folded photons and
    /// air stratified in height keep their own volumes.
    pub fn volume_scattered_within(
        &self,
        x: DVec3,
        wo: DVec3,
        (id, medium): (u32, &Medium),
        walls: &Walls,
        nb: &mut Neighbours,
    ) -> (BandValues, f64) {
        let mut out = [0.0; MAX_BANDS];
        let fold = self.map.fold();
        let (xq, wq) = fold.map_or((x, wo), |f| (f.point(x), f.direction(x, wo)));
        let Some((r2, skip)) = self.gather(xq, nb) else { return (out, 0.0) };
        let walls = if fold.is_none() && !stratified(medium) { *walls } else { Walls::default() };
        let transfer = medium.inelastic.transfer.as_ref();
        let rows = self.scatter_rows.as_ref().and_then(|r| r.rows(self.map, id, medium));
        for &(i, _) in &nb.items {
            // Re-emission counts every photon; elastic scattering only those the paths accept,
            // read from the stored flags so that a photon left out is never decoded.
            let accepted = self.paths.accepts(self.map.photons()[i as usize].path());
            if Some(i) == skip || (!accepted && transfer.is_none()) {
                continue;
            }
            let p = self.map.record(i);
            if !walls.iter().all(|w| w.holds(p.position)) {
                continue;
            }
            let l = p.wavelength_nm;
            if let Some(t) = transfer {
                t.add_photon(&medium.inelastic, &mut out, l, p.dir.dot(wq), p.power_w);
            }
            if !accepted {
                continue;
            }
            let Some(b) = self.bands.index_of(l) else { continue };
            let cos = p.dir.dot(wq);
            out[b] += scatter_rows::scattered(rows, medium, i, &p, cos) * p.power_w;
        }
        let r = r2.sqrt();
        let mid_nm = 0.5 * (self.bands.min_nm + self.bands.max_nm);
        let region = fold.map_or(Region::Ball, Region::Ring);
        let share = (1.0 - walls.iter().map(|w| w.cap_fraction(x, r)).sum::<f64>()).max(MIN_WALL_SHARE);
        let scale = 1.0 / (share * region_volume(medium, x, r, mid_nm, region) * self.bands.width_nm());
        out.iter_mut().take(self.bands.count).for_each(|v| *v *= scale);
        (out, r)
    }
}

/// Whether `medium`'s density is a profile in height (its estimates weigh their ball by it,
/// [`region_volume`]).
fn stratified(medium: &Medium) -> bool {
    matches!(medium.coefficients, Coefficients::Constituents(_)) || matches!(medium.density, Density::AirProfile(_))
}
