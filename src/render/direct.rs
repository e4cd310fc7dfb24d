//! Direct light by shadow rays: the one next-event estimator of the renderer, used by the
//! photon-map eye pass (surfaces and single scattering in media), the path tracer and the
//! sensors.
//!
//! At a point p each light is sampled once ([`Light::incident`]: a direction ω_i toward it, its
//! distance, and a weight — the light's geometric factor over the sampling density — such that
//! S(λ) · weight estimates the irradiance it sends along ω_i). The caller's
//! `factor` gives the scattering factor f(ω_i) — cos θ on a surface, the phase function in a
//! medium, 1 when the caller folds it in itself; a light with f ≤ 0 is skipped without a ray.
//! Otherwise one straight shadow segment gives the transmittance T(λ) per lane through media
//! and index-matched boundaries (`None` when something opaque blocks it), and the caller's `add`
//! accumulates S(λ) · weight · f · T(λ) with whatever multiple-importance weight it uses. The
//! sum over lights estimates ∫ L_light(λ, ω_i) f(ω_i) T(λ) dω_i (Veach 1997, §9.2; pbrt-v4
//! §13.4). Only valid while paths are straight: the effect plan turns shadow rays off where
//! they curve.

use crate::geometry::Hit;
use crate::light::{Incident, Light};
use crate::raypath::Propagator;
use crate::rng::Rng;
use crate::sampling::digital_shift;
use crate::spectrum::BandValues;
use glam::DVec3;

/// What a caller adds for one light: (light, incident sample, scattering factor, transmittance
/// per lane).
pub type AddLight<'a> = dyn FnMut(&Light, &Incident, f64, &BandValues) + 'a;

/// Where direct light is estimated.
pub struct ShadowOrigin<'a> {
    /// The point.
    pub p: DVec3,
    /// The surface it lies on, if any (shadow rays leave it offset off that surface).
    pub from: Option<&'a Hit>,
    /// The medium it is in.
    pub medium: Option<u32>,
    /// The wavelengths (lanes) the transmittance is wanted at, nm.
    pub wavelengths_nm: &'a [f64],
    /// The point sampled on the lights, in [0, 1)², when the caller stratifies it (a pixel's
    /// eye samples at their first diffuse hit): light j takes it digitally shifted by j
    /// ([`digital_shift`]), so each light's points stay stratified and the lights' differ;
    /// `None`: drawn from the generator.
    pub light_u: Option<[f64; 2]>,
}

/// Samples every light once from `at` (see the module documentation); counts each shadow ray
/// traced in `shadow_rays`.
#[allow(clippy::too_many_arguments)]
pub fn sample_lights(
    prop: &Propagator,
    lights: &[Light],
    at: &ShadowOrigin,
    rng: &mut Rng,
    shadow_rays: &mut u64,
    factor: &dyn Fn(&Light, &Incident) -> f64,
    add: &mut AddLight,
) {
    for (j, light) in lights.iter().enumerate() {
        let u = at.light_u.map_or_else(|| rng.uniform2(), |u| digital_shift(u, j as u64));
        let Some(inc) = light.incident(at.p, u) else { continue };
        let f = factor(light, &inc);
        if f <= 0.0 {
            continue;
        }
        *shadow_rays += 1;
        let Some(tr) = prop.shadow(at.p, at.from, inc.wi, inc.dist, at.medium, at.wavelengths_nm, rng) else {
            continue;
        };
        add(light, &inc, f, &tr);
    }
}
