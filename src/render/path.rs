//! The reference estimator: an unbiased spectral volumetric path tracer (`[integrator] method =
//! "path"`), the independent check the photon-map integrator is tested against.
//!
//! Each camera sample follows one of its lanes' wavelengths, chosen uniformly and weighted by the
//! lane count (so wavelength-dependent free flights and refractions need no spectral MIS).
//! Free-flight distances come from the same delta tracking as photons; at a medium interaction
//! the throughput is multiplied by the albedo and the phase function is sampled; at a diffuse
//! surface by ρ(λ) with cosine sampling; at specular surfaces by their weight. Direct light
//! combines two strategies by multiple importance sampling with the power heuristic (Veach &
//! Guibas 1995): next-event estimation (one shadow ray per light, transmittance by ratio
//! tracking) and emission hit by the phase- or BSDF-sampled direction, each weighted by
//! p²/(p_light² + p_scatter²) with the solid-angle densities of the two strategies. (Light
//! sampling alone has infinite variance for points near an emitting surface.) Delta lights are
//! reached only by next-event estimation; emission seen from the camera or through specular
//! surfaces counts fully. A path refracted from a medium of index n into one of index n′ has its
//! throughput multiplied by (n/n′)², because radiance, unlike power, is not conserved across a
//! refracting boundary — L/n² is (Veach 1997, §5.2): a camera under water sees the sky n² times
//! brighter (less the Fresnel loss) within Snell's window. The same holds at index-mismatched
//! boundaries between media without a material, and for the photon-map eye pass
//! ([`super::eye`]).
//! Russian roulette on the throughput after [`ROULETTE_DEPTH`] events (Veach 1997, §10;
//! Novák et al. 2018 for the volumetric parts).
//!
//! Inelastic media: the light a component re-emits at λ is a volume source J(x, ω, λ) =
//! Σ_i ∫ σ_i(λ') Φ f̂ E p_i L(x, ω', λ') dω' dλ', which need not be proportional to σ_t(λ) (a
//! fluorescent dye is clear at its emission wavelength), so it is estimated by the track-length
//! estimator: after each straight segment of length d that a path crosses in an inelastic
//! medium, with probability [`INELASTIC_BRANCH`] the path leaves for a point x uniform on the
//! segment (E[d J(x)] over free flights is ∫ T J dt), an excitation λ' drawn by
//! [`crate::media::inelastic::Inelastic::sample_excitation`], the throughput multiplied by
//! d d(x) σ_i(λ') Φ f̂ E / (pdf q), then next-event estimation and a new direction with the
//! component's emission phase function at λ'; otherwise it goes on as before, its throughput
//! divided by 1 − q. Segments are straight (the path tracer assumes no index field).

use super::direct::{ShadowOrigin, sample_lights};
use super::lanes::Lanes;
use super::stats::RayCounts;
use crate::geometry::Hit;
use crate::light::{Incident, Light};
use crate::material::{Lambertian, Material};
use crate::media::phase::PhaseFunction;
use crate::media::tracking;
use crate::raypath::{Event, Propagator, RayState};
use crate::rng::Rng;
use crate::scene::Scene;
use crate::spectrum::{BandValues, MAX_BANDS};
use glam::DVec3;
use std::f64::consts::PI;

/// Events after which Russian roulette may end a path.
pub const ROULETTE_DEPTH: usize = 4;
/// Hard limit on events per path (reached only by pathological scenes).
pub const MAX_EVENTS: usize = 4096;
/// Probability of leaving a segment through an inelastic component, in a medium that has any.
pub const INELASTIC_BRANCH: f64 = 0.5;

pub struct PathTracer<'a> {
    scene: &'a Scene,
    prop: Propagator<'a>,
}

/// The state of one path.
struct Walk {
    lambda: f64,
    beta: f64,
    /// How emission hit next counts: fully (from the camera, after specular events) or with the
    /// MIS weight of a direction sampled with density `pdf` from `from`.
    emission: Emission,
    /// The point the first next-event estimation samples on the lights, stratified over the
    /// pixel's samples by the caller; taken by that estimation, `None` after it.
    light_u: Option<[f64; 2]>,
}

#[derive(Clone, Copy)]
enum Emission {
    Full,
    Mis { from: DVec3, pdf: f64 },
}

/// The power heuristic w = a²/(a² + b²).
fn power_heuristic(a: f64, b: f64) -> f64 {
    if a <= 0.0 { 0.0 } else { a * a / (a * a + b * b) }
}

impl<'a> PathTracer<'a> {
    pub fn new(scene: &'a Scene) -> PathTracer<'a> {
        let range = (scene.bands.min_nm, scene.bands.max_nm);
        PathTracer { scene, prop: Propagator::new(&scene.world, scene.curved()).with_upward_shell(range, false) }
    }

    /// Integrator work along this tracer's curved paths so far.
    pub fn curved_work(&self) -> crate::raypath::CurvedWorkTotals {
        self.prop.work.totals()
    }

    /// Radiance per lane arriving along `state`: one lane, chosen by `rng`, gets the estimate
    /// times the lane count; the others zero. `light_u`: the point the path's first next-event
    /// estimation samples on the lights, stratified over a pixel's samples by the caller;
    /// `None`: drawn from `rng`.
    pub fn camera_radiance(
        &self,
        state: &RayState,
        lanes: &Lanes,
        light_u: Option<[f64; 2]>,
        rng: &mut Rng,
        rays: &mut RayCounts,
    ) -> [f64; MAX_BANDS] {
        let mut out = [0.0; MAX_BANDS];
        let j = rng.below(lanes.len as u64) as usize;
        out[j] = lanes.len as f64 * self.trace(*state, lanes.nm[j], light_u, rng, rays);
        out
    }

    fn trace(
        &self,
        mut state: RayState,
        lambda: f64,
        light_u: Option<[f64; 2]>,
        rng: &mut Rng,
        rays: &mut RayCounts,
    ) -> f64 {
        state.wavelength_nm = Some(lambda);
        let mut w = Walk { lambda, beta: 1.0, emission: Emission::Full, light_u };
        let mut l = 0.0;
        for events in 0..MAX_EVENTS {
            rays.eye += 1;
            let lam = w.lambda;
            let event = self.prop.next_event_with(&state, &mut |c| {
                let m = self.scene.world.medium(c.medium)?;
                tracking::sample_interaction(m, lam, c.origin, c.dir, c.length, rng)
            });
            if let Some(branch) = self.inelastic_track(&state, &event, &mut w, &mut l, rng, rays) {
                match branch {
                    Some(s) => state = s,
                    None => return l,
                }
                continue;
            }
            let next = match event {
                Event::Escape { dir } => return l + w.beta * self.escaped(dir, lambda, w.emission),
                Event::Lost { .. } => return l,
                Event::Medium { position, dir, medium, .. } => {
                    match self.medium_event(position, dir, medium, &mut w, &mut l, rng, rays) {
                        Some(s) => s,
                        None => return l,
                    }
                }
                Event::Surface { hit, dir, medium, .. } => {
                    match self.surface(&hit, dir, medium, &mut w, &mut l, rng, rays) {
                        Some(s) => s,
                        None => return l,
                    }
                }
            };
            state = next;
            if events >= ROULETTE_DEPTH {
                let q = w.beta.min(0.95);
                if rng.uniform() >= q {
                    return l;
                }
                w.beta /= q;
            }
            if w.beta == 0.0 {
                return l;
            }
        }
        l
    }

    /// A collision in medium `medium`: elastic scattering, or (in an inelastic medium, with
    /// probability [`INELASTIC_BRANCH`]) an inelastic step to an excitation wavelength.
    #[allow(clippy::too_many_arguments)]
    fn medium_event(
        &self,
        position: DVec3,
        dir: DVec3,
        medium: u32,
        w: &mut Walk,
        l: &mut f64,
        rng: &mut Rng,
        rays: &mut RayCounts,
    ) -> Option<RayState> {
        let m = &self.scene.world.media[medium as usize];
        rays.medium_steps += 1;
        let at = m.at(position);
        w.beta *= at.albedo(w.lambda);
        let phase = at.choose_phase(w.lambda, rng);
        Some(self.scatter(position, dir, medium, phase, w, l, rng, rays))
    }

    /// Next-event estimation and a direction drawn from `phase` at `position`.
    #[allow(clippy::too_many_arguments)]
    fn scatter(
        &self,
        position: DVec3,
        dir: DVec3,
        medium: u32,
        phase: &PhaseFunction,
        w: &mut Walk,
        l: &mut f64,
        rng: &mut Rng,
        rays: &mut RayCounts,
    ) -> RayState {
        let lambda = w.lambda;
        let at = (position, None, Some(medium), w.light_u.take());
        *l += w.beta * self.direct(at, DVec3::ZERO, Some(phase), dir, lambda, rng, rays);
        let (wo, pdf) = phase.sample(lambda, dir, rng.uniform2());
        w.emission = Emission::Mis { from: position, pdf };
        RayState { position, dir: wo, wavelength_nm: Some(lambda), medium: Some(medium) }
    }

    /// The track-length branch into an inelastic component (see the module documentation):
    /// `None` when the path goes on with `event` (throughput divided by 1 − q), else the state it
    /// continues from at the excitation wavelength (`Some(None)`: it ends).
    fn inelastic_track(
        &self,
        state: &RayState,
        event: &Event,
        w: &mut Walk,
        l: &mut f64,
        rng: &mut Rng,
        rays: &mut RayCounts,
    ) -> Option<Option<RayState>> {
        let id = state.medium?;
        let m = &self.scene.world.media[id as usize];
        if m.inelastic.is_empty() {
            return None;
        }
        let end = match event {
            Event::Medium { position, .. } => *position,
            Event::Surface { hit, .. } => hit.point,
            Event::Escape { .. } | Event::Lost { .. } => return None,
        };
        if rng.uniform() >= INELASTIC_BRANCH {
            w.beta /= 1.0 - INELASTIC_BRANCH;
            return None;
        }
        let d = (end - state.position).length();
        let x = state.position + rng.uniform() * (end - state.position);
        let range = (self.scene.bands.min_nm, self.scene.bands.max_nm);
        let Some(e) = m.inelastic.sample_excitation(w.lambda, range, rng) else { return Some(None) };
        w.beta *= d * m.density.at(x) * e.weight / INELASTIC_BRANCH;
        w.lambda = e.wavelength_nm;
        let phase = &m.inelastic.components[e.component].phase;
        Some(Some(self.scatter(x, state.dir, id, phase, w, l, rng, rays)))
    }

    /// Emission and scattering at a surface; the state to continue from, if the path goes on.
    #[allow(clippy::too_many_arguments)]
    fn surface(
        &self,
        hit: &Hit,
        dir: DVec3,
        medium: Option<u32>,
        w: &mut Walk,
        l: &mut f64,
        rng: &mut Rng,
        rays: &mut RayCounts,
    ) -> Option<RayState> {
        let lambda = Some(w.lambda);
        if let Some(light) = self.scene.world.area_light_of(hit.prim) {
            let cos = light.emitted_cos(hit.normal, -dir);
            if cos > 0.0 {
                let mis = match w.emission {
                    Emission::Full => 1.0,
                    Emission::Mis { from, pdf } => {
                        let p_light = (hit.point - from).length_squared() / (cos * light.shape.area());
                        power_heuristic(pdf, p_light)
                    }
                };
                *l += w.beta * mis * light.emission.spectrum.eval(w.lambda);
            }
        }
        let material = match self.scene.world.material_of(hit.prim) {
            None if self.scene.world.prims[hit.prim as usize].light.is_none() => {
                let (d, across) = self.prop.cross(hit, dir, medium, w.lambda, rng.uniform());
                w.beta *= self.prop.radiance_scale(medium, across, w.lambda, hit.point);
                return Some(self.prop.leave(hit, d, lambda, across));
            }
            None => return None,
            Some(m) => m,
        };
        match material {
            Material::Lambertian(_) => {
                let n = if dir.dot(hit.normal) < 0.0 { hit.normal } else { -hit.normal };
                let rho = material.diffuse_reflectance(w.lambda);
                let at = (hit.point, Some(hit), medium, w.light_u.take());
                *l += w.beta * rho / PI * self.direct(at, n, None, dir, w.lambda, rng, rays);
                w.beta *= rho;
                let wo = Lambertian::sample(dir, hit.normal, rng.uniform2());
                w.emission = Emission::Mis { from: hit.point, pdf: wo.dot(n).abs() / PI };
                Some(self.prop.leave(hit, wo, lambda, medium))
            }
            _ => {
                let n_out = self.prop.n_outside(hit.prim, w.lambda, hit.point);
                let s = material.sample_specular_in(dir, hit.normal, w.lambda, material.specular_u(rng), n_out)?;
                if s.weight == 0.0 {
                    return None;
                }
                // The sampled weight carries power; radiance seen across a refracting boundary
                // also scales by (n_here/n_there)² (L/n² is conserved).
                let eta = if s.transmitted {
                    material.transmitted_index_ratio(dir, hit.normal, w.lambda, n_out)
                } else {
                    1.0
                };
                w.beta *= s.weight / (eta * eta);
                w.emission = Emission::Full;
                let next =
                    if s.transmitted { self.scene.world.medium_across(hit.prim, dir, hit.normal) } else { medium };
                Some(self.prop.leave(hit, s.dir, lambda, next))
            }
        }
    }

    /// Radiance of the lights at infinity seen along `dir` as the path counts it: fully from
    /// the camera or after specular events; after a scattering, the sky with the power
    /// heuristic against its sampling density and the sun's disc not at all (next-event
    /// estimation samples it as a delta light).
    fn escaped(&self, dir: DVec3, lambda: f64, emission: Emission) -> f64 {
        self.scene
            .world
            .lights
            .iter()
            .map(|li| match (emission, li) {
                (Emission::Full, _) => li.escape_radiance(dir, lambda),
                (Emission::Mis { pdf, .. }, Light::Sky(sky)) => {
                    power_heuristic(pdf, sky.pdf(dir)) * li.escape_radiance(dir, lambda)
                }
                (Emission::Mis { .. }, _) => 0.0,
            })
            .sum()
    }

    /// Next-event estimation at `p`: Σ_lights S(λ) weight T(λ) times cos θ·(1/π on a surface,
    /// normal `n`, the caller multiplies by ρ) or the phase function f in a medium (`n` zero,
    /// `phase` given;
    /// `dir` is the direction the path arrived in, so the scattering cosine is ω_i·dir), each
    /// area light's share weighted by the power heuristic against the scattering density.
    #[allow(clippy::too_many_arguments)]
    fn direct(
        &self,
        (p, from, medium, light_u): (DVec3, Option<&Hit>, Option<u32>, Option<[f64; 2]>),
        n: DVec3,
        phase: Option<&PhaseFunction>,
        dir: DVec3,
        lambda: f64,
        rng: &mut Rng,
        rays: &mut RayCounts,
    ) -> f64 {
        let mut e = 0.0;
        // The scattering factor: cos θ on a surface, the phase function in a medium.
        let factor = |_: &Light, inc: &Incident| match (n == DVec3::ZERO, phase) {
            (true, Some(ph)) => ph.eval(lambda, inc.wi.dot(dir)),
            (true, None) => 0.0,
            (false, _) => inc.wi.dot(n),
        };
        // Its density as a sampling strategy, for the MIS weight: f itself, or cos θ/π.
        let p_scatter = |f: f64| if n == DVec3::ZERO { f } else { f / PI };
        let mut add = |light: &Light, inc: &Incident, factor: f64, tr: &BandValues| {
            let mis = if light.is_delta() { 1.0 } else { power_heuristic(1.0 / inc.weight, p_scatter(factor)) };
            e += mis
                * light.spectrum().spectrum.eval(lambda)
                * inc.weight
                * light.disc_factor(inc, lambda)
                * factor
                * tr[0];
        };
        let at = ShadowOrigin { p, from, medium, wavelengths_nm: &[lambda], light_u };
        sample_lights(&self.prop, &self.scene.world.lights, &at, rng, &mut rays.shadow, &factor, &mut add);
        e
    }
}
