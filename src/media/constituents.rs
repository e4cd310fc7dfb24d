//! An atmosphere of constituents — the air's molecules (Rayleigh scattering), ozone (absorption)
//! and aerosols (extinction with an albedo) — each with its own profile in height, its own
//! spectral extinction and its own phase function.
//!
//! # Extinction, albedo and phase at a point
//! Constituent c has an extinction σ_c(λ) per unit of its profile d_c(h) (a table in height over
//! the atmosphere's Earth, [`AirProfile`]), a single-scattering albedo ω_c(λ) ([`Albedo`]: one
//! number, or a table in wavelength) and a phase function p_c. At a point x at height h:
//!
//! σ_t(λ, x) = Σ_c σ_c(λ) d_c(h),  σ_s(λ, x) = Σ_c ω_c(λ) σ_c(λ) d_c(h),
//!
//! so constituent c absorbs (1 − ω_c(λ)) σ_c(λ) d_c(h). The albedo is σ_s/σ_t and the phase
//! function is the mixture weighted by each constituent's scattering,
//! p(λ, x, μ) = Σ_c w_c p_c(μ) / Σ_c w_c with w_c = ω_c(λ) σ_c(λ) d_c(h) — as
//! [`super::phase::Mixture`] weights by σ_s,i(λ), but with weights that vary with height too, so
//! albedo and phase change from the ozone layer to the aerosol haze. A collision's scattering
//! constituent is chosen with probability w_c / Σ w; with one scatterer no choice is drawn.
//!
//! # Tracking
//! All tables share the atmosphere's heights and pieces ([`AirProfile::pieces`]), so the
//! majorant of a piece is Σ_c σ_c(λ) max_c (each table's bound above the piece's lowest height),
//! and the optical depth of a chord is Σ_c σ_c(λ) ∫ d_c ds with the integrals taken together
//! ([`AirProfile::integrals`]). A constituent with σ_c(λ) = 0 adds nothing to either sum (it is
//! skipped), so an atmosphere whose extra constituents vanish tracks exactly as its air alone.
//!
//! # References
//! - Pharr, Jakob & Humphreys, *Physically Based Rendering*, 4th ed. (2023), §11.1 (scattering
//!   by several kinds of particles adds); Novák et al., "Monte Carlo methods for physically
//!   based volume rendering", SIGGRAPH course (2018), §4 (majorants).

use super::albedo::Albedo;
use super::density::AirProfile;
use super::phase::PhaseFunction;
use crate::spectrum::Spectrum;
use glam::DVec3;

/// The most constituents an atmosphere holds (air, ozone, aerosols).
pub const MAX_CONSTITUENTS: usize = 3;
const _: () = assert!(MAX_CONSTITUENTS <= crate::media::density::MAX_TABLES);

/// One value per constituent, in the atmosphere's order (unused slots 0).
pub type PerConstituent = [f64; MAX_CONSTITUENTS];

/// The extinction σ_c(λ) of a constituent per unit of its profile.
#[derive(Clone, Debug)]
pub enum Extinction {
    /// Rayleigh scattering of dry air at the standard density N_s: σ(λ) N_s (σ of Bodhaine et al.
    /// 1999, [`super::rayleigh_air`], or the scene's table); the profile carries N/N_s.
    Rayleigh(super::rayleigh_air::CrossSection),
    /// A cross-section per molecule, m² (ozone); the profile carries the number density, m⁻³.
    CrossSection(Spectrum),
    /// Ångström's law τ(λ) = β (λ/1 µm)^−α ([`super::aerosol`]); the profile is normalised to a
    /// unit column, m⁻¹.
    Angstrom {
        /// Ångström exponent α.
        alpha: f64,
        /// Optical depth at 1 µm, β.
        beta: f64,
    },
}

impl Extinction {
    /// σ_c(λ).
    pub fn at(&self, wavelength_nm: f64) -> f64 {
        match self {
            Extinction::Rayleigh(sigma) => sigma.at_standard_density(wavelength_nm),
            Extinction::CrossSection(s) => s.eval(wavelength_nm),
            Extinction::Angstrom { alpha, beta } => super::aerosol::optical_depth(wavelength_nm, *alpha, *beta),
        }
    }
}

/// One constituent: its extinction, albedo, phase function and profile in height.
#[derive(Clone, Debug)]
pub struct Constituent {
    /// "air", "ozone" or "aerosol": for messages and reports.
    pub name: &'static str,
    /// σ_c(λ) per unit of the profile.
    pub extinction: Extinction,
    /// Single-scattering albedo ω_c(λ) in [0, 1].
    pub albedo: Albedo,
    /// Phase function of its scattering (unused when ω_c ≡ 0).
    pub phase: PhaseFunction,
    /// d_c(h), tabulated on the atmosphere's heights.
    pub profile: AirProfile,
}

/// The constituents of one atmosphere (see the module docs).
#[derive(Clone, Debug)]
pub struct Constituents {
    list: Vec<Constituent>,
    scatterers: usize,
}

impl Constituents {
    /// One to [`MAX_CONSTITUENTS`] constituents whose profiles share one top (built by
    /// [`AirProfile::from_heights`] over the same Earth).
    pub fn new(list: Vec<Constituent>) -> Result<Constituents, String> {
        if list.is_empty() || list.len() > MAX_CONSTITUENTS {
            return Err(format!("an atmosphere holds 1 to {MAX_CONSTITUENTS} constituents, not {}", list.len()));
        }
        let top = list[0].profile.top_m();
        if let Some(c) = list.iter().find(|c| c.profile.top_m() != top) {
            return Err(format!(
                "constituent \"{}\" ends at {} m, the air at {top} m: one top for all",
                c.name,
                c.profile.top_m()
            ));
        }
        if let Some(c) = list.iter().find(|c| !c.albedo.is_valid()) {
            return Err(format!("constituent \"{}\": albedo {} is outside [0, 1]", c.name, c.albedo));
        }
        let scatterers = list.iter().filter(|c| c.albedo.scatters()).count();
        Ok(Constituents { list, scatterers })
    }

    /// The constituents, in order.
    pub fn list(&self) -> &[Constituent] {
        &self.list
    }

    /// How many constituents scatter (ω_c > 0 at some wavelength).
    pub fn scatterers(&self) -> usize {
        self.scatterers
    }

    /// σ_c(λ) of each constituent.
    pub fn extinction(&self, wavelength_nm: f64) -> PerConstituent {
        let mut s = [0.0; MAX_CONSTITUENTS];
        for (v, c) in s.iter_mut().zip(&self.list) {
            *v = c.extinction.at(wavelength_nm);
        }
        s
    }

    /// d_c at `p` (the height found once).
    pub fn densities(&self, p: DVec3) -> PerConstituent {
        let h = self.list[0].profile.height(p);
        let mut d = [0.0; MAX_CONSTITUENTS];
        for (v, c) in d.iter_mut().zip(&self.list) {
            *v = c.profile.at_height(h);
        }
        d
    }

    /// Σ_c a_c b_c over the constituents with a_c ≠ 0, summed in order from 0.
    pub fn dot(a: &PerConstituent, b: &PerConstituent) -> f64 {
        let mut sum = 0.0;
        for (x, y) in a.iter().zip(b) {
            if *x != 0.0 {
                sum += x * y;
            }
        }
        sum
    }

    /// σ_t(λ, x) = Σ_c σ_c d_c(x) for `sigma` = [`Constituents::extinction`].
    pub fn sigma_t_at(&self, sigma: &PerConstituent, p: DVec3) -> f64 {
        Constituents::dot(sigma, &self.densities(p))
    }

    /// An upper bound of σ_t(λ, x) anywhere: Σ_c σ_c(λ) × the largest value of d_c.
    pub fn sigma_t_bound(&self, wavelength_nm: f64) -> f64 {
        let mut bound = [0.0; MAX_CONSTITUENTS];
        for (b, c) in bound.iter_mut().zip(&self.list) {
            *b = c.profile.bound_from(f64::NEG_INFINITY);
        }
        Constituents::dot(&self.extinction(wavelength_nm), &bound)
    }

    /// The part [a, b] of [0, t_max] of the ray `o + t·dir` outside which every constituent's
    /// profile is 0 (the hull of their parts below the top), or `None` where all are 0.
    pub fn support(&self, o: DVec3, dir: DVec3, t_max: f64) -> Option<(f64, f64)> {
        self.list.iter().filter_map(|c| c.profile.below_top(o, dir, t_max)).reduce(|p, q| (p.0.min(q.0), p.1.max(q.1)))
    }

    /// The shared pieces of the ray `o + t·dir` over [0, t_max], each with the majorant
    /// Σ_c σ_c max_c; see [`super::density::Density::majorant_intervals`].
    pub fn majorant_intervals(
        &self,
        sigma: &PerConstituent,
        o: DVec3,
        dir: DVec3,
        t_max: f64,
        visit: &mut dyn FnMut(f64, f64, f64) -> bool,
    ) {
        self.list[0].profile.pieces(o, dir, t_max, &mut |t0, t1, h| {
            let mut bound = [0.0; MAX_CONSTITUENTS];
            for ((b, c), s) in bound.iter_mut().zip(&self.list).zip(sigma) {
                if *s != 0.0 {
                    *b = c.profile.bound_from(h);
                }
            }
            visit(t0, t1, Constituents::dot(sigma, &bound))
        });
    }

    /// The optical depth Σ_c σ_c ∫₀ᵗ d_c ds along `o + s·dir` (`tabulated`: see
    /// [`Constituents::columns`]).
    pub fn optical_depth(&self, sigma: &PerConstituent, o: DVec3, dir: DVec3, t: f64, tabulated: bool) -> f64 {
        Constituents::dot(sigma, &self.columns(o, dir, t, tabulated))
    }

    /// The columns ∫₀ᵗ d_c ds of every constituent along `o + s·dir`, which do not depend on
    /// the wavelength: the optical depth at any λ is their dot product with σ_c(λ). With
    /// `tabulated`, a ray that leaves through the top reads them from the profiles' tables of
    /// columns to the top ([`AirProfile::columns_to_top`], to
    /// [`crate::media::density::COLUMN_TOLERANCE`]) instead of integrating.
    pub fn columns(&self, o: DVec3, dir: DVec3, t: f64, tabulated: bool) -> PerConstituent {
        let first = &self.list[0].profile;
        let mut tables = [first; MAX_CONSTITUENTS];
        for (slot, c) in tables.iter_mut().zip(&self.list) {
            *slot = &c.profile;
        }
        let n = self.list.len();
        let mut integrals = [0.0; MAX_CONSTITUENTS];
        if !(tabulated && AirProfile::columns_to_top(&tables[..n], o, dir, t, &mut integrals[..n])) {
            AirProfile::integrals(&tables[..n], o, dir, t, &mut integrals[..n]);
        }
        integrals
    }

    /// The scattering weights w_c = ω_c(λ) σ_c(λ) d_c at densities `d`.
    pub fn scattering(&self, wavelength_nm: f64, d: &PerConstituent) -> PerConstituent {
        let mut w = [0.0; MAX_CONSTITUENTS];
        for ((v, c), dc) in w.iter_mut().zip(&self.list).zip(d) {
            let albedo = c.albedo.at(wavelength_nm);
            if albedo > 0.0 && *dc != 0.0 {
                *v = albedo * c.extinction.at(wavelength_nm) * dc;
            }
        }
        w
    }

    /// The constituent whose weight in `w` holds `u` × Σ w (u in [0, 1)), and `u` rescaled to
    /// [0, 1) within it; the last with a positive weight if rounding runs past the end.
    pub fn pick(&self, w: &PerConstituent, u: f64) -> (usize, f64) {
        let total: f64 = w.iter().sum();
        let target = u * total;
        let (mut acc, mut last) = (0.0, 0);
        for (i, wi) in w.iter().enumerate().take(self.list.len()) {
            if *wi <= 0.0 {
                continue;
            }
            if target < acc + wi {
                return (i, ((target - acc) / wi).clamp(0.0, 1.0 - f64::EPSILON / 2.0));
            }
            acc += wi;
            last = i;
        }
        (last, 1.0 - f64::EPSILON / 2.0)
    }
}
