//! Eye paths: the second pass of photon mapping (Jensen 2001, ch. 9; Jensen & Christensen 1998,
//! §4.4).
//!
//! Along every chord of a path inside a medium, an adaptive ray marcher accumulates
//! transmittance and the light scattered toward the eye: from the volume photon map, plus — with
//! `direct = "shadow_rays"` — single scattering by shadow rays (then the map's direct photons are
//! left out). At a diffuse surface seen from the camera (directly or through mirrors and glass)
//! radiance is the sum of
//! - direct light, by shadow rays to each light, attenuated by the media they cross;
//! - caustics, by a radiance estimate on the caustic map;
//! - indirect light, by final gathering — cosine-distributed rays whose diffuse hits read the
//!   precomputed irradiance of the global map — or by a direct estimate on the global map's
//!   diffusely scattered photons.
//!
//! With `direct = "photon_map"` the photon maps alone give all of it (Lucifer's choice, needed
//! where shadow rays cannot follow curved paths). Gather rays that reach an emitter — directly
//! or through specular surfaces — add nothing: that light is counted by the shadow rays and the
//! caustic map. Specular surfaces are followed; an eye path carrying several wavelengths splits
//! into one path per lane at a dispersive surface (a gather path instead follows one lane chosen
//! at random, weighted by the lane count).

use super::direct::{ShadowOrigin, sample_lights};
use super::lanes::Lanes;
use super::photon_pass::Maps;
use super::stats::RayCounts;
use crate::geometry::Hit;
use crate::light::{Incident, Light};
use crate::material::{Lambertian, Material};
use crate::photon_map::{
    BandValues, BeamEstimator, BeamHit, Estimator, Neighbours, Paths, ScatterRows, TubeEstimator, TubeHit,
};
use crate::raypath::{Event, Propagator, RayState};
use crate::rng::Rng;
use crate::sampling::ScrambledSobol2;
use crate::scene::{IntegratorSettings, Scene};
use crate::spectrum::MAX_BANDS;
use glam::DVec3;
use std::f64::consts::PI;
use std::sync::Arc;

mod bundle;
mod medium;

/// Whether a path is seen by the camera (through specular surfaces at most) or is a gather ray.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Mode {
    Camera,
    Gather,
}

/// Camera paths split at glass into both Fresnel branches for their first this-many specular
/// events (entering and leaving a glass object), then choose one branch by Fresnel.
const FRESNEL_SPLIT_DEPTH: usize = 2;

/// Per-thread scratch for photon queries and counters.
#[derive(Default)]
pub struct Scratch {
    nb: Neighbours,
    hits: Vec<BeamHit>,
    tubes: Vec<TubeHit>,
    /// Rays this thread traced, by kind.
    pub rays: RayCounts,
}

/// Light accumulated along a path up to its next surface: scattered radiance and transmittance.
struct Along {
    l: BandValues,
    tr: BandValues,
}

/// Where an eye path is: its wavelengths, its depth, whether it is a gather ray.
#[derive(Clone, Copy)]
struct At<'l> {
    lanes: &'l Lanes,
    depth: usize,
    mode: Mode,
    /// The point a camera sample's shadow rays sample on the lights at its diffuse hit, when
    /// the pixel stratifies it ([`EyeTracer::camera_radiance`]).
    light_u: Option<[f64; 2]>,
    /// The normal of the surface the path leaves (its first chord starts there), if it does.
    from_surface: Option<DVec3>,
}

impl At<'_> {
    fn wavelength(&self) -> Option<f64> {
        (self.lanes.len == 1).then_some(self.lanes.nm[0])
    }
}

/// The eye pass: follows camera paths through the scene and reads the photon maps.
pub struct EyeTracer<'a> {
    scene: &'a Scene,
    prop: Propagator<'a>,
    maps: &'a Maps,
    /// Global map as camera paths read it at diffuse surfaces (when they do).
    global: Option<Estimator<'a>>,
    /// Global map with every photon, for gather rays without precomputed irradiance.
    global_all: Option<Estimator<'a>>,
    caustic: Option<Estimator<'a>>,
    /// Volume map as camera paths read it (without direct photons under shadow rays).
    volume: Option<Estimator<'a>>,
    /// Volume map with every photon, for gather rays.
    volume_all: Option<Estimator<'a>>,
    /// The beam estimate on the volume map as camera paths read it (`volume_estimate = "beam"`).
    beam: Option<BeamEstimator<'a>>,
    /// The photon beams as camera paths read them (`volume_estimate = "photon_beams"`).
    tubes: Option<TubeEstimator<'a>>,
}

impl<'a> EyeTracer<'a> {
    /// An eye tracer over `scene` reading `maps` with the estimate settings `s` (the scene's
    /// own, or a progressive pass's: see [`IntegratorSettings::for_pass`]).
    pub fn new(scene: &'a Scene, s: &IntegratorSettings, maps: &'a Maps) -> EyeTracer<'a> {
        let est = |map, k, max_radius, paths| Estimator {
            map,
            k,
            max_radius,
            filter: s.filter,
            bands: scene.bands,
            paths,
            scatter_rows: None,
            disc_share: scene.disc_share(),
        };
        // Both readings of the volume map weigh its photons alike: one set of rows serves them.
        let rows = Arc::new(ScatterRows::new(scene.world.media.len()));
        let volume = |k, max_radius, paths| {
            let map = maps.volume.as_ref()?;
            Some(Estimator { scatter_rows: Some(Arc::clone(&rows)), ..est(map, k, max_radius, paths) })
        };
        // Under shadow rays the maps' direct photons are left out (the rays count that light).
        let shadow = scene.plan.shadow_rays.on;
        let global_paths = if shadow { Paths::DiffuseOnly } else { Paths::All };
        let volume_paths = if shadow { Paths::NotDirect } else { Paths::All };
        let beam = |paths| -> Option<BeamEstimator<'a>> {
            let (map, discs) = (maps.volume.as_ref()?, maps.beam.as_ref()?);
            Some(BeamEstimator { map, discs, bands: scene.bands, paths, scatter_rows: Some(Arc::clone(&rows)) })
        };
        EyeTracer {
            scene,
            // Eye paths that climb out of the layered upper air above every shape leave it in one
            // move; in absorbing air `march` and the bundles' guides take its density column.
            prop: Propagator::new(&scene.world, scene.curved())
                .with_upward_shell((scene.bands.min_nm, scene.bands.max_nm), true),
            maps,
            global: maps.global.as_ref().map(|m| est(m, s.k, s.max_radius_m, global_paths)),
            global_all: maps.global.as_ref().map(|m| est(m, s.k, s.max_radius_m, Paths::All)),
            caustic: maps.caustic.as_ref().map(|m| est(m, s.caustic_k, s.caustic_max_radius_m, Paths::All)),
            volume: volume(s.volume_k, s.volume_max_radius_m, volume_paths),
            volume_all: volume(s.volume_k, s.volume_max_radius_m, Paths::All),
            beam: beam(volume_paths),
            tubes: maps.photon_beams.as_ref().map(|beams| TubeEstimator {
                beams,
                bands: scene.bands,
                paths: volume_paths,
            }),
        }
    }

    /// Integrator work along this tracer's curved paths so far.
    pub fn curved_work(&self) -> crate::raypath::CurvedWorkTotals {
        self.prop.work.totals()
    }

    /// Radiance arriving at the camera along `state`, per lane (W m⁻² sr⁻¹ nm⁻¹).
    ///
    /// `light_u`: the point the shadow rays sample on each light where the path meets a diffuse
    /// surface, stratified over a pixel's samples by the caller; `None`: drawn from `rng`.
    pub fn camera_radiance(
        &self,
        state: &RayState,
        lanes: &Lanes,
        light_u: Option<[f64; 2]>,
        rng: &mut Rng,
        sc: &mut Scratch,
    ) -> BandValues {
        self.radiance(state, At { lanes, depth: 0, mode: Mode::Camera, light_u, from_surface: None }, rng, sc)
    }

    /// Radiance per lane arriving along `state` as a gather ray reads it (light reflected at
    /// least once, from the global map's irradiance; emitters add nothing): the indirect part
    /// that sensors measure.
    pub fn gather_radiance(&self, state: &RayState, lanes: &Lanes, rng: &mut Rng, sc: &mut Scratch) -> BandValues {
        self.radiance(state, At { lanes, depth: 1, mode: Mode::Gather, light_u: None, from_surface: None }, rng, sc)
    }

    fn radiance(&self, state: &RayState, at: At, rng: &mut Rng, sc: &mut Scratch) -> BandValues {
        let mut out = [0.0; MAX_BANDS];
        if at.depth > self.scene.integrator.max_depth {
            return out;
        }
        if at.lanes.len > 1 && self.prop.splits_wavelengths(state.medium) {
            return self.split(state, at, rng, sc);
        }
        match at.mode {
            Mode::Camera => sc.rays.eye += 1,
            Mode::Gather => sc.rays.gather += 1,
        }
        let mut along = Along { l: [0.0; MAX_BANDS], tr: [1.0; MAX_BANDS] };
        let event = self.prop.next_event_with(state, &mut |c| {
            // Only the path's first chord starts on the surface it leaves.
            let start = at.from_surface.filter(|_| c.origin == state.position);
            self.march(c, start, at, &mut along, rng, sc);
            None
        });
        let surface = self.end(event, at, rng, sc);
        for i in 0..at.lanes.len {
            out[i] = along.l[i] + along.tr[i] * surface[i];
        }
        out
    }

    /// Radiance per lane leaving the end of a path back along it: from the surface it meets, or
    /// for a camera path that escapes, from the lights at infinity.
    fn end(&self, event: Event, at: At, rng: &mut Rng, sc: &mut Scratch) -> BandValues {
        match event {
            Event::Surface { hit, dir, medium, .. } => self.surface(&hit, dir, medium, at, rng, sc),
            Event::Escape { dir } if at.mode == Mode::Camera => self.escape(dir, at.lanes),
            _ => [0.0; MAX_BANDS],
        }
    }

    /// Radiance per lane along `state` in a medium that bends each wavelength differently: one
    /// path per lane (a gather path follows one lane chosen uniformly, weighted by the count), or
    /// a bundle of them interpolated from four guides where the medium only absorbs
    /// ([`bundle`]).
    fn split(&self, state: &RayState, at: At, rng: &mut Rng, sc: &mut Scratch) -> BandValues {
        sc.rays.splits += 1;
        if self.bundles(state.medium, at) {
            return self.bundle(state, at, rng, sc);
        }
        let mut out = [0.0; MAX_BANDS];
        let lanes = at.lanes;
        let one = |i: usize, rng: &mut Rng, sc: &mut Scratch| {
            let single = lanes.single(i);
            let s = RayState { wavelength_nm: Some(lanes.nm[i]), ..*state };
            self.radiance(&s, At { lanes: &single, ..at }, rng, sc)[0]
        };
        if at.mode == Mode::Gather {
            let j = rng.below(lanes.len as u64) as usize;
            out[j] = lanes.len as f64 * one(j, rng, sc);
            return out;
        }
        for (i, o) in out.iter_mut().enumerate().take(lanes.len) {
            *o = one(i, rng, sc);
        }
        out
    }

    /// Radiance per lane of the lights at infinity (the sun's disc) seen by a camera path that
    /// leaves the scene along `dir`; gather rays leave it to the shadow rays and photon maps.
    fn escape(&self, dir: DVec3, lanes: &Lanes) -> BandValues {
        let mut out = [0.0; MAX_BANDS];
        for light in &self.scene.world.lights {
            for (o, l) in out.iter_mut().zip(&lanes.nm[..lanes.len]) {
                *o += light.escape_radiance(dir, *l);
            }
        }
        out
    }

    /// Radiance leaving the surface `hit` back along the path arriving in direction `dir`.
    fn surface(
        &self,
        hit: &Hit,
        dir: DVec3,
        medium: Option<u32>,
        at: At,
        rng: &mut Rng,
        sc: &mut Scratch,
    ) -> BandValues {
        let mut out = [0.0; MAX_BANDS];
        if at.mode == Mode::Camera
            && let Some(light) = self.scene.world.area_light_of(hit.prim)
            && light.emitted_cos(hit.normal, -dir) > 0.0
        {
            for (o, l) in out.iter_mut().zip(&at.lanes.nm[..at.lanes.len]) {
                *o += light.emission.spectrum.eval(*l);
            }
        }
        let add = match self.scene.world.material_of(hit.prim) {
            None if self.scene.world.prims[hit.prim as usize].light.is_none() => {
                self.boundary(hit, dir, medium, at, rng, sc)
            }
            None => return out,
            Some(m) if m.is_diffuse() => self.diffuse(hit, dir, m, medium, at, rng, sc),
            Some(m) => self.specular(hit, dir, m, medium, at, rng, sc),
        };
        for i in 0..at.lanes.len {
            out[i] += add[i];
        }
        out
    }

    /// A camera path at glass, followed both ways: L = F·L_reflected + (1 − F)·L_refracted with
    /// the Fresnel reflectance F of each lane (the lanes share one direction: a dispersive glass
    /// has split them already), instead of choosing one branch with probability F. Unbiased
    /// either way; splitting removes the variance of the choice where it is seen directly —
    /// the glints of lights in a glass sphere, which a 5% chance of reflection otherwise turns
    /// into fireflies.
    #[allow(clippy::too_many_arguments)]
    fn fresnel_split(
        &self,
        hit: &Hit,
        dir: DVec3,
        d: &crate::material::Dielectric,
        medium: Option<u32>,
        at: At,
        rng: &mut Rng,
        sc: &mut Scratch,
    ) -> BandValues {
        let lanes = at.lanes;
        let eta_of = |l: f64| {
            let rel = d.ior.eval(l) / self.prop.n_outside(hit.prim, l, hit.point);
            if dir.dot(hit.normal) < 0.0 { rel } else { 1.0 / rel }
        };
        let cos_i = dir.dot(hit.normal).abs();
        let next = At { depth: at.depth + 1, from_surface: Some(hit.normal), ..at };
        let r = self.prop.leave(hit, crate::material::reflect(dir, hit.normal), at.wavelength(), medium);
        let lr = self.radiance(&r, next, rng, sc);
        let mut out = [0.0; MAX_BANDS];
        let Some(t_dir) = crate::material::refract(dir, hit.normal, eta_of(lanes.nm[0])) else {
            out[..lanes.len].copy_from_slice(&lr[..lanes.len]);
            return out;
        };
        let across = self.scene.world.medium_across(hit.prim, dir, hit.normal);
        let lt = self.radiance(&self.prop.leave(hit, t_dir, at.wavelength(), across), next, rng, sc);
        for i in 0..lanes.len {
            let eta = eta_of(lanes.nm[i]);
            let f = crate::material::fresnel_dielectric(cos_i, eta);
            // Radiance across a refracting boundary scales by (n_here/n_there)² = 1/η².
            out[i] = f * lr[i] + (1.0 - f) * lt[i] / (eta * eta);
        }
        out
    }

    /// A boundary between two media: straight on where their n agree, else Fresnel reflection
    /// or refraction with the local n of both sides (per lane where that depends on wavelength).
    fn boundary(
        &self,
        hit: &Hit,
        dir: DVec3,
        medium: Option<u32>,
        at: At,
        rng: &mut Rng,
        sc: &mut Scratch,
    ) -> BandValues {
        let lanes = at.lanes;
        let refracts = self.prop.boundary_refracts(hit.prim, lanes.nm[0], hit.point);
        if refracts && lanes.len > 1 && self.prop.boundary_is_dispersive(hit.prim) {
            sc.rays.splits += 1;
            let mut out = [0.0; MAX_BANDS];
            let one = |i: usize, rng: &mut Rng, sc: &mut Scratch| {
                let single = lanes.single(i);
                self.boundary(hit, dir, medium, At { lanes: &single, ..at }, rng, sc)[0]
            };
            if at.mode == Mode::Gather {
                let j = rng.below(lanes.len as u64) as usize;
                out[j] = lanes.len as f64 * one(j, rng, sc);
            } else {
                for (i, o) in out.iter_mut().enumerate().take(lanes.len) {
                    *o = one(i, rng, sc);
                }
            }
            return out;
        }
        let (d, across) = self.prop.cross(hit, dir, medium, lanes.nm[0], rng.uniform());
        let from = At { from_surface: Some(hit.normal), ..at };
        let mut l = self.radiance(&self.prop.leave(hit, d, at.wavelength(), across), from, rng, sc);
        for (i, l) in l.iter_mut().enumerate().take(lanes.len) {
            *l *= self.prop.radiance_scale(medium, across, lanes.nm[i], hit.point);
        }
        l
    }

    #[allow(clippy::too_many_arguments)]
    fn specular(
        &self,
        hit: &Hit,
        dir: DVec3,
        m: &Material,
        medium: Option<u32>,
        at: At,
        rng: &mut Rng,
        sc: &mut Scratch,
    ) -> BandValues {
        let mut out = [0.0; MAX_BANDS];
        let lanes = at.lanes;
        if m.is_dispersive() && lanes.len > 1 {
            sc.rays.splits += 1;
        }
        if m.is_dispersive() && lanes.len > 1 && at.mode == Mode::Gather {
            // A gather path follows one lane chosen uniformly, weighted by the lane count: an
            // unbiased estimate of every lane at the cost of one.
            let j = rng.below(lanes.len as u64) as usize;
            let single = lanes.single(j);
            out[j] = lanes.len as f64 * self.specular(hit, dir, m, medium, At { lanes: &single, ..at }, rng, sc)[0];
            return out;
        }
        if m.is_dispersive() && lanes.len > 1 {
            for (i, o) in out.iter_mut().enumerate().take(lanes.len) {
                let single = lanes.single(i);
                *o = self.specular(hit, dir, m, medium, At { lanes: &single, ..at }, rng, sc)[0];
            }
            return out;
        }
        if let Material::Dielectric(d) = m
            && at.mode == Mode::Camera
            && at.depth < FRESNEL_SPLIT_DEPTH
        {
            return self.fresnel_split(hit, dir, d, medium, at, rng, sc);
        }
        let u = m.specular_u(rng);
        let n_out = |l: f64| self.prop.n_outside(hit.prim, l, hit.point);
        let Some(s) = m.sample_specular_in(dir, hit.normal, lanes.nm[0], u, n_out(lanes.nm[0])) else { return out };
        let mut w = [0.0; MAX_BANDS];
        for (i, w) in w.iter_mut().enumerate().take(lanes.len) {
            *w = m.sample_specular_in(dir, hit.normal, lanes.nm[i], u, n_out(lanes.nm[i])).map_or(0.0, |s| s.weight);
        }
        if w[..lanes.len].iter().all(|w| *w == 0.0) {
            return out;
        }
        let next_medium =
            if s.transmitted { self.scene.world.medium_across(hit.prim, dir, hit.normal) } else { medium };
        let next = self.prop.leave(hit, s.dir, at.wavelength(), next_medium);
        let l = self.radiance(&next, At { depth: at.depth + 1, from_surface: Some(hit.normal), ..at }, rng, sc);
        for i in 0..lanes.len {
            // The sampled weight carries power; radiance across a refracting boundary also
            // scales by (n_here/n_there)² (L/n² is conserved).
            let eta = if s.transmitted {
                m.transmitted_index_ratio(dir, hit.normal, lanes.nm[i], n_out(lanes.nm[i]))
            } else {
                1.0
            };
            out[i] = w[i] * l[i] / (eta * eta);
        }
        out
    }

    #[allow(clippy::too_many_arguments)]
    fn diffuse(
        &self,
        hit: &Hit,
        dir: DVec3,
        m: &Material,
        medium: Option<u32>,
        at: At,
        rng: &mut Rng,
        sc: &mut Scratch,
    ) -> BandValues {
        let n = if dir.dot(hit.normal) < 0.0 { hit.normal } else { -hit.normal };
        let rho = |l: f64| m.diffuse_reflectance(l);
        let lanes = at.lanes;
        let mut out = [0.0; MAX_BANDS];
        let estimate = |e: &Estimator, nb: &mut Neighbours| e.lambertian_radiance(hit.point, n, &rho, nb);
        if at.mode == Mode::Gather {
            let cached = self.maps.irradiance.as_ref().and_then(|c| c.lookup(hit.point, n, &mut sc.nb));
            match (cached, &self.global_all) {
                (Some(e), _) => add_by_band(&mut out, &e, lanes, &|i| rho(lanes.nm[i]) / PI),
                (None, Some(g)) => add_by_band(&mut out, &estimate(g, &mut sc.nb), lanes, &|_| 1.0),
                (None, None) => {}
            }
            return out;
        }
        if !self.scene.plan.shadow_rays.on {
            if let Some(g) = &self.global {
                add_by_band(&mut out, &estimate(g, &mut sc.nb), lanes, &|_| 1.0);
            }
            return out;
        }
        if let Some(c) = &self.caustic {
            add_by_band(&mut out, &estimate(c, &mut sc.nb), lanes, &|_| 1.0);
        }
        if self.scene.plan.final_gather.on {
            let g = self.final_gather(hit, dir, medium, at, rng, sc);
            add_by_lane(&mut out, &g, lanes, &|i| rho(lanes.nm[i]));
        } else if let Some(g) = &self.global {
            add_by_band(&mut out, &estimate(g, &mut sc.nb), lanes, &|_| 1.0);
        }
        let origin = ShadowOrigin {
            p: hit.point,
            from: Some(hit),
            medium,
            wavelengths_nm: &lanes.nm[..lanes.len],
            light_u: at.light_u,
        };
        let direct = self.direct(origin, n, lanes, rng, sc);
        add_by_lane(&mut out, &direct, lanes, &|i| rho(lanes.nm[i]) / PI);
        out
    }

    /// Mean radiance per lane arriving along cosine-distributed gather rays; multiplied by ρ
    /// this is the reflected indirect radiance (f_r cos θ / p = ρ). The rays' directions are
    /// the first points of a 2-D Sobol' sequence, Owen-scrambled afresh at every shading point
    /// ([`ScrambledSobol2`]), mapped onto the cosine lobe: each is cosine-distributed, and
    /// together they stratify the hemisphere, so that smooth incident light is gathered with
    /// less noise than by independent directions.
    fn final_gather(
        &self,
        hit: &Hit,
        dir: DVec3,
        medium: Option<u32>,
        at: At,
        rng: &mut Rng,
        sc: &mut Scratch,
    ) -> BandValues {
        let count = at.lanes.share_of(self.scene.integrator.gather_rays);
        let mut sum = [0.0; MAX_BANDS];
        let gather = At { depth: at.depth + 1, mode: Mode::Gather, from_surface: Some(hit.normal), ..at };
        let directions = ScrambledSobol2::new(rng);
        for i in 0..count {
            let d = Lambertian::sample(dir, hit.normal, directions.point(i as u32));
            let l = self.radiance(&self.prop.leave(hit, d, at.wavelength(), medium), gather, rng, sc);
            for i in 0..at.lanes.len {
                sum[i] += l[i];
            }
        }
        sum.iter_mut().take(at.lanes.len).for_each(|v| *v /= count as f64);
        sum
    }

    /// Incident irradiance per lane at `at` (on a surface with normal `n`, or in a medium when
    /// `n` is zero — then without the cosine) from every light by one shadow ray each:
    /// E(λ) = Σ_lights S(λ) · weight · cos θ · T(λ). `at.wavelengths_nm` are `lanes`'.
    fn direct(&self, at: ShadowOrigin, n: DVec3, lanes: &Lanes, rng: &mut Rng, sc: &mut Scratch) -> BandValues {
        let mut e = [0.0; MAX_BANDS];
        let cos = |_: &Light, inc: &Incident| if n == DVec3::ZERO { 1.0 } else { inc.wi.dot(n) };
        let mut add = |light: &Light, inc: &Incident, cos: f64, tr: &BandValues| {
            let s = &light.spectrum().spectrum;
            for i in 0..lanes.len {
                e[i] += s.eval(lanes.nm[i]) * inc.weight * light.disc_factor(inc, lanes.nm[i]) * cos * tr[i];
            }
        };
        sample_lights(&self.prop, &self.scene.world.lights, &at, rng, &mut sc.rays.shadow, &cos, &mut add);
        e
    }
}

/// The power heuristic a²/(a² + b²) (Veach & Guibas 1995).
fn power_heuristic(a: f64, b: f64) -> f64 {
    if a <= 0.0 { 0.0 } else { a * a / (a * a + b * b) }
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
