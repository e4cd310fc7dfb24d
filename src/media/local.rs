//! A medium at one point x: what a collision or an in-scattering estimate there needs — σ_t,
//! σ_s, the albedo and the phase function, which for an atmosphere of constituents
//! ([`super::constituents`]) all change with height.
//!
//! A medium with a density field is its coefficients at density 1 scaled by d(x): here
//! [`MediumAt::density`] is d(x) and σ_t, σ_s are per unit density, exactly as the medium gives
//! them, and the phase function is the medium's. An atmosphere of constituents has density 1
//! (0 above its top) and σ_t, σ_s, albedo and phase those of the constituents' mixture at x.

use super::constituents::{Constituents, PerConstituent};
use super::medium::{Coefficients, Medium};
use super::phase::{PhaseFunction, direction_about};
use crate::rng::Rng;
use glam::DVec3;

/// The medium at a point (see the module docs).
#[derive(Clone, Copy, Debug)]
pub struct MediumAt<'a> {
    medium: &'a Medium,
    local: Local<'a>,
}

#[derive(Clone, Copy, Debug)]
enum Local<'a> {
    /// Coefficients at density 1 scaled by d(x).
    Scaled { density: f64 },
    /// The constituents' profiles d_c(x).
    Constituents { c: &'a Constituents, d: PerConstituent },
}

impl Medium {
    /// This medium at `p`.
    pub fn at(&self, p: DVec3) -> MediumAt<'_> {
        let local = match &self.coefficients {
            Coefficients::Constituents(c) => Local::Constituents { c, d: c.densities(p) },
            _ => Local::Scaled { density: self.density.at(p) },
        };
        MediumAt { medium: self, local }
    }

    /// Values in a photon's scattering row in this medium ([`MediumAt::write_scatter_row`]).
    pub fn scatter_row_len(&self) -> usize {
        1 + match &self.coefficients {
            Coefficients::Constituents(c) => 1 + c.list().len(),
            _ => self.phase.weight_count(),
        }
    }

    /// σ_s/σ_t × p(λ, cos θ) at the place and wavelength `row` was written for
    /// ([`MediumAt::write_scatter_row`]): bit for bit `albedo(λ) · phase_eval(λ, cos θ)` there,
    /// without evaluating a spectrum or a density.
    pub fn scattered_from_row(&self, row: &[f64], wavelength_nm: f64, cos_theta: f64) -> f64 {
        let phase = match &self.coefficients {
            Coefficients::Constituents(c) => constituent_phase(c, &row[2..], row[1], wavelength_nm, cos_theta),
            _ => self.phase.eval_with_weights(&row[1..], wavelength_nm, cos_theta),
        };
        row[0] * phase
    }
}

/// The constituents' mixture p = Σ w_c p_c / Σ w_c for weights `w` with sum `total` (the first
/// constituent's phase function where nothing scatters).
fn constituent_phase(c: &Constituents, w: &[f64], total: f64, wavelength_nm: f64, cos_theta: f64) -> f64 {
    if total <= 0.0 {
        return c.list()[0].phase.eval(wavelength_nm, cos_theta);
    }
    let mut sum = 0.0;
    for (wi, k) in w.iter().zip(c.list()) {
        if *wi > 0.0 {
            sum += wi * k.phase.eval(wavelength_nm, cos_theta);
        }
    }
    sum / total
}

impl<'a> MediumAt<'a> {
    /// Writes into `row` ([`Medium::scatter_row_len`] values) what an in-scattering estimate
    /// needs at this place for light of wavelength λ, apart from the angle: the albedo, then the
    /// phase function's weights (a mixture's σ_s,i(λ); the constituents' total and their
    /// scattering w_c). [`Medium::scattered_from_row`] reads it.
    pub fn write_scatter_row(&self, wavelength_nm: f64, row: &mut [f64]) {
        row[0] = self.albedo(wavelength_nm);
        match &self.local {
            Local::Scaled { .. } => self.medium.phase.write_weights(wavelength_nm, &mut row[1..]),
            Local::Constituents { c, d } => {
                let w = c.scattering(wavelength_nm, d);
                row[1] = w.iter().sum();
                for (r, v) in row[2..].iter_mut().zip(&w) {
                    *r = *v;
                }
            }
        }
    }

    /// d(x) of a medium with a density field; for constituents 1 (0 where every profile
    /// vanishes, above the top).
    pub fn density(&self) -> f64 {
        match &self.local {
            Local::Scaled { density } => *density,
            Local::Constituents { d, .. } => {
                if d.iter().any(|v| *v > 0.0) {
                    1.0
                } else {
                    0.0
                }
            }
        }
    }

    /// σ_t(λ) per unit [`MediumAt::density`], m⁻¹.
    pub fn sigma_t(&self, wavelength_nm: f64) -> f64 {
        match &self.local {
            Local::Scaled { .. } => self.medium.sigma_t(wavelength_nm),
            Local::Constituents { c, d } => Constituents::dot(&c.extinction(wavelength_nm), d),
        }
    }

    /// σ_s(λ) per unit [`MediumAt::density`], m⁻¹ (elastic scattering).
    pub fn sigma_s(&self, wavelength_nm: f64) -> f64 {
        match &self.local {
            Local::Scaled { .. } => self.medium.sigma_s(wavelength_nm),
            Local::Constituents { c, d } => c.scattering(wavelength_nm, d).iter().sum(),
        }
    }

    /// The single-scattering albedo σ_s/σ_t at x (0 where σ_t = 0).
    pub fn albedo(&self, wavelength_nm: f64) -> f64 {
        match &self.local {
            Local::Scaled { .. } => self.medium.albedo(wavelength_nm),
            Local::Constituents { c, d } => {
                let t = Constituents::dot(&c.extinction(wavelength_nm), d);
                let s: f64 = c.scattering(wavelength_nm, d).iter().sum();
                if t > 0.0 { s / t } else { 0.0 }
            }
        }
    }

    /// The phase function's density p(λ, x, cos θ), sr⁻¹: the constituents' mixture weighted by
    /// their scattering at x.
    pub fn phase_eval(&self, wavelength_nm: f64, cos_theta: f64) -> f64 {
        match &self.local {
            Local::Scaled { .. } => self.medium.phase.eval(wavelength_nm, cos_theta),
            Local::Constituents { c, d } => {
                let w = c.scattering(wavelength_nm, d);
                constituent_phase(c, &w, w.iter().sum(), wavelength_nm, cos_theta)
            }
        }
    }

    /// A direction after scattering of light travelling along `wi`, drawn from the mixture at
    /// x (one sample: `u[0]` chooses the constituent and, rescaled, its angle), and its density
    /// [`MediumAt::phase_eval`].
    pub fn phase_sample(&self, wavelength_nm: f64, wi: DVec3, u: [f64; 2]) -> (DVec3, f64) {
        match &self.local {
            Local::Scaled { .. } => self.medium.phase.sample(wavelength_nm, wi, u),
            Local::Constituents { c, d } => {
                let w = c.scattering(wavelength_nm, d);
                let (k, u0) = c.pick(&w, u[0]);
                let cos = c.list()[k].phase.sample_cos_theta(wavelength_nm, u0);
                (direction_about(wi, cos, u[1]), self.phase_eval(wavelength_nm, cos))
            }
        }
    }

    /// The phase function of the constituent that scatters at a collision here, chosen with
    /// probability w_c / Σ w (one draw of `rng`, only when more than one constituent scatters);
    /// the medium's own phase function otherwise.
    pub fn choose_phase(&self, wavelength_nm: f64, rng: &mut Rng) -> &'a PhaseFunction {
        match &self.local {
            Local::Scaled { .. } => &self.medium.phase,
            Local::Constituents { c, d } => {
                let list = c.list();
                if c.scatterers() <= 1 {
                    let k = list.iter().position(|k| k.albedo.scatters()).unwrap_or(0);
                    return &list[k].phase;
                }
                let w = c.scattering(wavelength_nm, d);
                if w.iter().sum::<f64>() <= 0.0 {
                    return &list[0].phase;
                }
                &list[c.pick(&w, rng.uniform()).0].phase
            }
        }
    }
}
