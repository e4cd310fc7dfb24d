//! Eye paths: the second pass of photon mapping (Jensen 2001, ch. 9).
//!
//! At a diffuse surface seen from the camera (directly or through mirrors and glass) radiance
//! is the sum of
//! - direct light, by shadow rays to each light (`direct = "shadow_rays"`);
//! - caustics, by a radiance estimate on the caustic map;
//! - indirect light, by final gathering: cosine-distributed rays whose diffuse hits read the
//!   precomputed irradiance of the global map; or by a direct estimate on the global map.
//!
//! With `direct = "photon_map"` the global map alone gives all of it. Gather rays that reach an
//! emitter — directly or through specular surfaces — add nothing: that light is already counted
//! by the shadow rays and the caustic map. Specular surfaces are followed; an eye path carrying
//! several wavelengths splits into one path per lane at a dispersive surface (a gather path
//! instead follows one lane chosen at random, weighted by the lane count).

use super::lanes::Lanes;
use super::maps::Maps;
use super::stats::RayCounts;
use crate::geometry::Hit;
use crate::material::{Lambertian, Material};
use crate::photon_map::{BandValues, Estimator, Neighbours};
use crate::raypath::{Event, Propagator, RayState};
use crate::rng::Rng;
use crate::scene::{DirectLighting, Scene};
use crate::spectrum::MAX_BANDS;
use glam::DVec3;
use std::f64::consts::PI;

/// Whether a path is seen by the camera (through specular surfaces at most) or is a gather ray.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Mode {
    Camera,
    Gather,
}

/// Per-thread scratch for photon queries and counters.
#[derive(Default)]
pub struct Scratch {
    nb: Neighbours,
    pub rays: RayCounts,
}

pub struct EyeTracer<'a> {
    scene: &'a Scene,
    prop: Propagator<'a>,
    maps: &'a Maps,
    global: Option<Estimator<'a>>,
    caustic: Option<Estimator<'a>>,
}

impl<'a> EyeTracer<'a> {
    pub fn new(scene: &'a Scene, maps: &'a Maps) -> EyeTracer<'a> {
        let s = &scene.integrator;
        let est = |map, k, max_radius| Estimator { map, k, max_radius, filter: s.filter, bands: scene.bands };
        EyeTracer {
            scene,
            prop: Propagator::new(&scene.shapes, &scene.bvh),
            maps,
            global: maps.global.as_ref().map(|m| est(m, s.k, s.max_radius_m)),
            caustic: maps.caustic.as_ref().map(|m| est(m, s.caustic_k, s.caustic_max_radius_m)),
        }
    }

    /// Radiance arriving at a camera along `state`, per lane (W m⁻² sr⁻¹ nm⁻¹).
    pub fn camera_radiance(&self, state: &RayState, lanes: &Lanes, rng: &mut Rng, sc: &mut Scratch) -> BandValues {
        self.radiance(state, lanes, 0, Mode::Camera, rng, sc)
    }

    /// Radiance per lane arriving along `state` as a gather ray reads it (light reflected at
    /// least once, from the global map's irradiance; emitters add nothing): the indirect part
    /// that sensors measure.
    pub fn gather_radiance(&self, state: &RayState, lanes: &Lanes, rng: &mut Rng, sc: &mut Scratch) -> BandValues {
        self.radiance(state, lanes, 1, Mode::Gather, rng, sc)
    }

    fn radiance(
        &self,
        state: &RayState,
        lanes: &Lanes,
        depth: usize,
        mode: Mode,
        rng: &mut Rng,
        sc: &mut Scratch,
    ) -> BandValues {
        let mut out = [0.0; MAX_BANDS];
        if depth > self.scene.integrator.max_depth {
            return out;
        }
        match mode {
            Mode::Camera => sc.rays.eye += 1,
            Mode::Gather => sc.rays.gather += 1,
        }
        let Event::Surface { hit, dir, .. } = self.prop.next_event(state) else {
            return out;
        };
        if mode == Mode::Camera
            && let Some(light) = self.scene.area_light_of(hit.prim)
            && light.emitted_cos(hit.normal, -dir) > 0.0
        {
            for (o, l) in out.iter_mut().zip(&lanes.nm[..lanes.len]) {
                *o += light.emission.spectrum.eval(*l);
            }
        }
        let Some(material) = self.scene.material_of(hit.prim) else {
            return out;
        };
        let add = if material.is_diffuse() {
            self.diffuse(&hit, dir, material, lanes, depth, mode, rng, sc)
        } else {
            self.specular(&hit, dir, material, lanes, depth, mode, rng, sc)
        };
        for i in 0..lanes.len {
            out[i] += add[i];
        }
        out
    }

    #[allow(clippy::too_many_arguments)]
    fn specular(
        &self,
        hit: &Hit,
        dir: DVec3,
        m: &Material,
        lanes: &Lanes,
        depth: usize,
        mode: Mode,
        rng: &mut Rng,
        sc: &mut Scratch,
    ) -> BandValues {
        let mut out = [0.0; MAX_BANDS];
        if m.is_dispersive() && lanes.len > 1 && mode == Mode::Gather {
            // A gather path follows one lane chosen uniformly, weighted by the lane count: an
            // unbiased estimate of every lane at the cost of one.
            let j = rng.below(lanes.len as u64) as usize;
            out[j] = lanes.len as f64 * self.specular(hit, dir, m, &lanes.single(j), depth, mode, rng, sc)[0];
            return out;
        }
        if m.is_dispersive() && lanes.len > 1 {
            for (i, o) in out.iter_mut().enumerate().take(lanes.len) {
                *o = self.specular(hit, dir, m, &lanes.single(i), depth, mode, rng, sc)[0];
            }
            return out;
        }
        let u = rng.uniform();
        let Some(s) = m.sample_specular(dir, hit.normal, lanes.nm[0], u) else {
            return out;
        };
        let next = self.prop.leave(hit, s.dir, (lanes.len == 1).then_some(lanes.nm[0]));
        let l = self.radiance(&next, lanes, depth + 1, mode, rng, sc);
        for i in 0..lanes.len {
            let w = m.sample_specular(dir, hit.normal, lanes.nm[i], u).map_or(0.0, |s| s.weight);
            out[i] = w * l[i];
        }
        out
    }

    #[allow(clippy::too_many_arguments)]
    fn diffuse(
        &self,
        hit: &Hit,
        dir: DVec3,
        m: &Material,
        lanes: &Lanes,
        depth: usize,
        mode: Mode,
        rng: &mut Rng,
        sc: &mut Scratch,
    ) -> BandValues {
        let n = if dir.dot(hit.normal) < 0.0 { hit.normal } else { -hit.normal };
        let rho = |l: f64| m.diffuse_reflectance(l);
        let mut out = [0.0; MAX_BANDS];
        let estimate = |e: &Estimator, nb: &mut Neighbours| e.lambertian_radiance(hit.point, n, &rho, nb);
        if mode == Mode::Gather {
            let cached = self.maps.irradiance.as_ref().and_then(|c| c.lookup(hit.point, n, &mut sc.nb));
            match (cached, &self.global) {
                (Some(e), _) => add_by_band(&mut out, &e, lanes, &|i| rho(lanes.nm[i]) / PI),
                (None, Some(g)) => add_by_band(&mut out, &estimate(g, &mut sc.nb), lanes, &|_| 1.0),
                (None, None) => {}
            }
            return out;
        }
        if self.scene.integrator.direct == DirectLighting::PhotonMap {
            if let Some(g) = &self.global {
                add_by_band(&mut out, &estimate(g, &mut sc.nb), lanes, &|_| 1.0);
            }
            return out;
        }
        if let Some(c) = &self.caustic {
            add_by_band(&mut out, &estimate(c, &mut sc.nb), lanes, &|_| 1.0);
        }
        if self.scene.plan.final_gather.on {
            let g = self.final_gather(hit, dir, lanes, depth, rng, sc);
            add_by_lane(&mut out, &g, lanes, &|i| rho(lanes.nm[i]));
        } else if let Some(g) = &self.global {
            add_by_band(&mut out, &estimate(g, &mut sc.nb), lanes, &|_| 1.0);
        }
        let direct = self.direct(hit, n, lanes, rng, sc);
        add_by_lane(&mut out, &direct, lanes, &|i| rho(lanes.nm[i]) / PI);
        out
    }

    /// Mean radiance per lane arriving along cosine-distributed gather rays; multiplied by ρ
    /// this is the reflected indirect radiance (f_r cos θ / p = ρ).
    fn final_gather(
        &self,
        hit: &Hit,
        dir: DVec3,
        lanes: &Lanes,
        depth: usize,
        rng: &mut Rng,
        sc: &mut Scratch,
    ) -> BandValues {
        let count = lanes.share_of(self.scene.integrator.gather_rays);
        let mut sum = [0.0; MAX_BANDS];
        for _ in 0..count {
            let d = Lambertian::sample(dir, hit.normal, rng.uniform2());
            let next = self.prop.leave(hit, d, None);
            let l = self.radiance(&next, lanes, depth + 1, Mode::Gather, rng, sc);
            for i in 0..lanes.len {
                sum[i] += l[i];
            }
        }
        sum.iter_mut().take(lanes.len).for_each(|v| *v /= count as f64);
        sum
    }

    /// Incident irradiance per lane from every light by one shadow ray each:
    /// E(λ) = Σ_lights S(λ) · weight · cos θ, weight being the light's sampling factor.
    fn direct(&self, hit: &Hit, n: DVec3, lanes: &Lanes, rng: &mut Rng, sc: &mut Scratch) -> BandValues {
        let mut e = [0.0; MAX_BANDS];
        for light in &self.scene.lights {
            let u = rng.uniform2();
            let Some(inc) = light.incident(hit.point, u) else {
                continue;
            };
            let cos = inc.wi.dot(n);
            if cos <= 0.0 {
                continue;
            }
            sc.rays.shadow += 1;
            if !self.prop.unoccluded(hit, inc.wi, inc.dist) {
                continue;
            }
            let s = &light.spectrum().spectrum;
            for (e, l) in e.iter_mut().zip(&lanes.nm[..lanes.len]) {
                *e += s.eval(*l) * inc.weight * cos;
            }
        }
        e
    }
}

/// Adds `scale(i) · v[band of lane i]` to each lane of `out` (`v` holds per-band estimates).
fn add_by_band(out: &mut BandValues, v: &BandValues, lanes: &Lanes, scale: &dyn Fn(usize) -> f64) {
    for i in 0..lanes.len {
        out[i] += scale(i) * v[lanes.band[i] as usize];
    }
}

/// Adds `scale(i) · v[i]` to each lane of `out` (`v` holds per-lane values).
fn add_by_lane(out: &mut BandValues, v: &BandValues, lanes: &Lanes, scale: &dyn Fn(usize) -> f64) {
    for i in 0..lanes.len {
        out[i] += scale(i) * v[i];
    }
}
