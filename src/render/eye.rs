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
use crate::media::{Coefficients, Medium, tracking};
use crate::photon_map::{
    BandValues, BeamEstimator, BeamHit, ChordEstimate, Estimator, Neighbours, Paths, ScatterRows, SegmentEnds,
    TubeEstimator, TubeHit, Walls,
};
use crate::raypath::{Chord, Event, Propagator, RayState};
use crate::rng::Rng;
use crate::sampling::ScrambledSobol2;
use crate::scene::{IntegratorSettings, Scene};
use crate::spectrum::MAX_BANDS;
use glam::DVec3;
use std::f64::consts::PI;
use std::sync::Arc;

mod bundle;

/// Whether a path is seen by the camera (through specular surfaces at most) or is a gather ray.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Mode {
    Camera,
    Gather,
}

/// A gather ray's chord is marched in this many jittered steps (at least `march_step` each):
/// its radiance is averaged over many gather rays, so a coarse quadrature suffices.
const GATHER_STEPS: f64 = 4.0;

/// Relative change of the in-scattered light between march samples above which the step is
/// halved (JC98 §4.4), below which it is doubled back, and the most halvings.
const ADAPT_REFINE: f64 = 0.5;
const ADAPT_RELAX: f64 = 0.1;
const MAX_REFINE: u32 = 4;

/// Camera paths split at glass into both Fresnel branches for their first this-many specular
/// events (entering and leaving a glass object), then choose one branch by Fresnel.
const FRESNEL_SPLIT_DEPTH: usize = 2;

/// The most steps the mean-free-path rule may add to a camera ray's march over one chord: a
/// step is shortened to a quarter of the mean free path only down to a this-many-th of the
/// chord (never below what `march_step` itself gives). A step's sample point is jittered
/// uniformly within it, so T(s)·h estimates ∫ T over the step without bias at any length; short
/// steps only lower the noise. Without this bound a dye whose σ_a reaches 2 × 10⁸ m⁻¹ at one
/// wavelength held a 4 × 4 render's rays to 5 nm steps: 65 million steps (the render fuzzer,
/// seed 2, case 22244).
const MAX_MARCH_STEPS: f64 = 1e4;

/// Transmittance below which a marched path is continued by Russian roulette.
const ROULETTE_TRANSMITTANCE: f64 = 1e-3;

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

    /// Single scattering toward travel direction `wo` at `x` in medium `id`, per unit length:
    /// σ_s(λ, x) ∫ f(λ; ω_l·ω_o) L_light(λ) T(λ) dω, estimated by one shadow ray per light and,
    /// for area lights, one phase-sampled ray, combined by the power heuristic (light sampling
    /// alone has infinite variance near an emitting surface). `unit_sigma_s`: σ_s of each lane
    /// at density 1 where it does not vary along the chord (every medium but an atmosphere of
    /// constituents), computed once per chord by the caller.
    #[allow(clippy::too_many_arguments)]
    fn single_scattering(
        &self,
        x: DVec3,
        wo: DVec3,
        (id, m): (u32, &Medium),
        unit_sigma_s: Option<&BandValues>,
        lanes: &Lanes,
        rng: &mut Rng,
        sc: &mut Scratch,
    ) -> BandValues {
        let mut out = [0.0; MAX_BANDS];
        let here = m.at(x);
        let d = here.density();
        if d <= 0.0 {
            return out;
        }
        let sigma_s: BandValues = match unit_sigma_s {
            Some(u) => *u,
            None => std::array::from_fn(|i| if i < lanes.len { here.sigma_s(lanes.nm[i]) } else { 0.0 }),
        };
        let nm = &lanes.nm[..lanes.len];
        let phase = |l: f64, light_travel: DVec3| here.phase_eval(l, light_travel.dot(wo));
        // The phase function differs per lane, so `add` applies it (and its MIS weight) itself.
        let at = ShadowOrigin { p: x, from: None, medium: Some(id), wavelengths_nm: nm, light_u: None };
        let mut add = |light: &Light, inc: &Incident, _: f64, tr: &BandValues| {
            let s = &light.spectrum().spectrum;
            for i in 0..lanes.len {
                let l = lanes.nm[i];
                let f = phase(l, -inc.wi);
                let mis = if light.is_delta() { 1.0 } else { power_heuristic(1.0 / inc.weight, f) };
                out[i] += mis * d * sigma_s[i] * f * s.eval(l) * inc.weight * light.disc_factor(inc, l) * tr[i];
            }
        };
        sample_lights(&self.prop, &self.scene.world.lights, &at, rng, &mut sc.rays.shadow, &|_, _| 1.0, &mut add);
        if self.scene.world.lights.iter().any(|l| !l.is_delta()) {
            // Phase sampling, for the lane-0 wavelength's phase function, toward area lights.
            let (wi, pdf) = here.phase_sample(lanes.nm[0], wo, rng.uniform2());
            let to_light = -wi;
            sc.rays.shadow += 1;
            match self.prop.first_opaque_hit(x, None, to_light, Some(id), nm, rng) {
                Some((Some(hit), tr)) => {
                    if let Some(light) = self.scene.world.area_light_of(hit.prim) {
                        let cos = light.emitted_cos(hit.normal, wi);
                        if cos > 0.0 && pdf > 0.0 {
                            let p_light = hit.t * hit.t / (cos * light.shape.area());
                            let mis = power_heuristic(pdf, p_light);
                            let le = |l: f64| light.emission.spectrum.eval(l);
                            for i in 0..lanes.len {
                                let l = lanes.nm[i];
                                out[i] += mis * d * sigma_s[i] * phase(l, wi) / pdf * le(l) * tr[i];
                            }
                        }
                    }
                }
                Some((None, tr)) if pdf > 0.0 => {
                    for sky in self
                        .scene
                        .world
                        .lights
                        .iter()
                        .filter_map(|l| if let Light::Sky(s) = l { Some(s) } else { None })
                    {
                        let mis = power_heuristic(pdf, sky.pdf(to_light));
                        if mis > 0.0 {
                            for i in 0..lanes.len {
                                let l = lanes.nm[i];
                                let le = sky.emission.spectrum.eval(l);
                                out[i] += mis * d * sigma_s[i] * phase(l, wi) / pdf * le * tr[i];
                            }
                        }
                    }
                }
                _ => {}
            }
        }
        out
    }

    /// Marches chord `c` (JC98 §4.4): one sample per step, jittered independently in each (one
    /// offset shared by every step, as JC98 has it, leaves the first-order error
    /// (ξ − ½)·h·[g(end) − g(start)] of the whole chord in each estimate: ±7 % per sample for
    /// a sky seen from the ground in 2 km steps, against ±2.6 % with independent offsets); the
    /// step halves after a large
    /// change of the in-scattered light and relaxes back after small ones (see
    /// [`EyeTracer::step_length`]); transmittance carried exactly where the medium allows, by
    /// ratio tracking otherwise; Russian roulette once it is negligible.
    ///
    /// `start`: the normal of the surface the chord starts on, if it does (with the chord's
    /// own end, where the volume estimates end: the beam estimate's tube of discs, the point
    /// estimate's ball; [`SegmentEnds`]).
    fn march(&self, c: &Chord, start: Option<DVec3>, at: At, along: &mut Along, rng: &mut Rng, sc: &mut Scratch) {
        let Some(id) = c.medium.filter(|m| !self.prop.is_clear(*m)) else { return };
        let m = &self.scene.world.media[id as usize];
        let lanes = at.lanes;
        if let Some(column) = c.column_m {
            // The layered upper air crossed in one move (it only absorbs, σ_t(λ)·d): its
            // transmittance from the path's density column.
            for (t, l) in along.tr.iter_mut().zip(&lanes.nm[..lanes.len]) {
                *t *= (-m.sigma_t(*l) * column).exp();
            }
            return;
        }
        if !m.scatters() {
            // A medium that only absorbs sends nothing toward the eye: its transmittance, in one
            // piece (no steps, no roulette on a deep optical depth).
            self.attenuate(m, c, 0.0, c.length, lanes, along, rng);
            return;
        }
        let shadow = at.mode == Mode::Camera && self.scene.plan.shadow_rays.on;
        // Estimates end on the surfaces the chord starts and ends on (edge_correction).
        let ends = match self.scene.integrator.edge_correction {
            true => SegmentEnds { start, end: c.end_normal },
            false => SegmentEnds::default(),
        };
        // Gather rays keep the point estimate at a few coarse steps: they are averaged by the
        // dozen at each shading point, and a whole chord's tube of discs costs more than that.
        let chord_estimate = match (&self.beam, &self.tubes, at.mode) {
            (Some(b), _, Mode::Camera) => {
                let mut hits = std::mem::take(&mut sc.hits);
                let tr = self.beam_chord(b, &mut hits, (c, ends), (id, m), lanes, along, rng, sc);
                sc.hits = hits;
                Some(tr)
            }
            (None, Some(b), Mode::Camera) => {
                let mut hits = std::mem::take(&mut sc.tubes);
                let tr = self.beam_chord(b, &mut hits, (c, ends), (id, m), lanes, along, rng, sc);
                sc.tubes = hits;
                Some(tr)
            }
            _ => None,
        };
        if let Some(tr) = chord_estimate {
            if shadow {
                // Single scattering by shadow rays keeps its own jittered steps along the chord.
                self.march_steps((c, &Walls::default()), (id, m), at, None, along, rng, sc);
            } else {
                along.tr.iter_mut().zip(&tr).take(lanes.len).for_each(|(a, t)| *a *= t);
            }
            return;
        }
        let est = match at.mode {
            Mode::Camera => self.volume.as_ref(),
            Mode::Gather => self.volume_all.as_ref(),
        };
        let walls = est.map_or_else(Walls::default, |_| ends.walls(c.origin, c.dir, c.length));
        self.march_steps((c, &walls), (id, m), at, est, along, rng, sc);
    }

    /// A whole-chord estimate `b` along chord `c` — the beam estimate's discs
    /// ([`crate::photon_map::beam`]) or photon beams' tubes ([`TubeEstimator`]), gathered into
    /// the scratch `hits`: adds Σ_p T(0→t_p) L_p to `along.l` (weighted by the transmittance
    /// carried so far) and returns the chord's transmittance per lane. Each lane's transmittance
    /// is carried from hit to hit in order along the chord, so a heterogeneous medium is tracked
    /// once per lane.
    #[allow(clippy::too_many_arguments)]
    fn beam_chord<E: ChordEstimate>(
        &self,
        b: &E,
        hits: &mut Vec<E::Hit>,
        (c, ends): (&Chord, SegmentEnds),
        (id, m): (u32, &Medium),
        lanes: &Lanes,
        along: &mut Along,
        rng: &mut Rng,
        sc: &mut Scratch,
    ) -> BandValues {
        let n = lanes.len;
        let (mut t_at, mut tr) = ([0.0f64; MAX_BANDS], [1.0f64; MAX_BANDS]);
        // Each lane's extinction once per chord (an ocean's σ_t(λ) is several table look-ups).
        let lane_attenuation: Vec<tracking::Attenuation> =
            lanes.nm[..n].iter().map(|l| tracking::Attenuation::of(m, *l)).collect();
        let mut advance = |i: usize, t: f64, rng: &mut Rng| {
            if t > t_at[i] {
                tr[i] *= lane_attenuation[i].transmittance(c.origin + t_at[i] * c.dir, c.dir, t - t_at[i], rng);
                t_at[i] = t;
            }
            tr[i]
        };
        b.gather(c.origin, c.dir, c.length, ends, hits);
        sc.rays.medium_steps += 1;
        let mut tmp = [0.0; MAX_BANDS];
        let wo = -c.dir;
        for h in hits.iter() {
            let t = E::t(h);
            b.radiance(h, c.origin + t * c.dir, wo, (id, m), &mut tmp, &mut |band, l| {
                for i in (0..n).filter(|i| lanes.band[*i] as usize == band) {
                    along.l[i] += along.tr[i] * advance(i, t, rng) * l;
                }
            });
        }
        for i in 0..n {
            advance(i, c.length, rng);
        }
        tr
    }

    /// The ray march of [`EyeTracer::march`] over chord `c` in medium `(id, m)`, reading the
    /// point estimate `est` (if any; in front of `walls`, the surfaces the chord starts and ends
    /// on) and shadow rays (if the plan has them) at every step.
    #[allow(clippy::too_many_arguments)]
    fn march_steps(
        &self,
        (c, walls): (&Chord, &Walls),
        (id, m): (u32, &Medium),
        at: At,
        est: Option<&Estimator>,
        along: &mut Along,
        rng: &mut Rng,
        sc: &mut Scratch,
    ) {
        let lanes = at.lanes;
        let shadow = at.mode == Mode::Camera && self.scene.plan.shadow_rays.on;
        let wo = -c.dir;
        let mut sigma_t = [0.0; MAX_BANDS];
        for (s, l) in sigma_t.iter_mut().zip(&lanes.nm[..lanes.len]) {
            *s = m.sigma_t(*l);
        }
        let unit_sigma_s = (shadow && !matches!(m.coefficients, Coefficients::Constituents(_)))
            .then(|| std::array::from_fn(|i| if i < lanes.len { m.sigma_s(lanes.nm[i]) } else { 0.0 }));
        // Only the part of the chord where the medium is not empty is marched (an atmosphere's
        // air ends at its top): elsewhere nothing scatters and the transmittance is 1.
        let Some((a, b)) = m.support(c.origin, c.dir, c.length) else { return };
        let (mut t0, mut t_prev) = (a, a);
        let mut level = 0u32;
        let mut last: Option<f64> = None;
        while t0 < b {
            // Steps resolve the lanes that still carry light: a lane the medium has made opaque
            // (σ_t = 10¹² m⁻¹ at the excitation of a dye) must not hold the others to its steps.
            let sigma_t_max = (0..lanes.len).filter(|i| along.tr[*i] > 0.0).map(|i| sigma_t[i]).fold(0.0, f64::max);
            let h = self.step_length(m, c, (t0, b - a), sigma_t_max, level, at.mode);
            let t1 = (t0 + h).min(b);
            let s = t0 + rng.uniform() * (t1 - t0);
            sc.rays.medium_steps += 1;
            self.attenuate(m, c, t_prev, s, lanes, along, rng);
            t_prev = s;
            if !self.roulette(along, lanes, rng) {
                return;
            }
            let x = c.origin + s * c.dir;
            let mut src = [0.0; MAX_BANDS];
            if let Some(e) = est {
                let (v, _) = e.volume_scattered_within(x, wo, (id, m), walls, &mut sc.nb);
                add_by_band(&mut src, &v, lanes, &|_| 1.0);
            }
            if shadow {
                let ss = self.single_scattering(x, wo, (id, m), unit_sigma_s.as_ref(), lanes, rng, sc);
                add_by_lane(&mut src, &ss, lanes, &|_| 1.0);
            }
            for ((l, tr), s) in along.l.iter_mut().zip(&along.tr).zip(&src).take(lanes.len) {
                *l += tr * s * (t1 - t0);
            }
            // Adapt to the light: refine after a large change of the source, relax after a small one.
            let total: f64 = src[..lanes.len].iter().sum();
            if let Some(prev) = last {
                let change = (total - prev).abs() / prev.abs().max(total.abs()).max(f64::MIN_POSITIVE);
                if change > ADAPT_REFINE && level < MAX_REFINE {
                    level += 1;
                } else if change < ADAPT_RELAX && level > 0 {
                    level -= 1;
                }
            }
            last = Some(total);
            t0 = t1;
        }
        self.attenuate(m, c, t_prev, b, lanes, along, rng);
    }

    /// The next step from `t0` on a marched span of length `span`: `march_step` halved `level`
    /// times, capped where an atmosphere's density changes ([`Medium::climb_step`]) and at a
    /// quarter of the local mean free path, but not by the latter rules below a
    /// [`MAX_MARCH_STEPS`]th of the span — or, for a gather ray, the span in [`GATHER_STEPS`]
    /// steps.
    fn step_length(
        &self,
        m: &Medium,
        c: &Chord,
        (t0, span): (f64, f64),
        sigma_t_max: f64,
        level: u32,
        mode: Mode,
    ) -> f64 {
        let h_max = self.scene.integrator.march_step_m;
        if mode == Mode::Gather {
            return h_max.max(span / GATHER_STEPS);
        }
        let mut h = h_max / f64::from(1u32 << level);
        let floor = h.min(span / MAX_MARCH_STEPS);
        h = h.min(m.climb_step(c.origin + t0 * c.dir, c.dir));
        let local = sigma_t_max * m.density.at(c.origin + t0 * c.dir);
        if local > 0.0 {
            h = h.min(0.25 / local);
        }
        h.max(1e-6 * h_max).max(floor)
    }

    /// Multiplies the carried transmittance by that of the chord between `a` and `b`.
    #[allow(clippy::too_many_arguments)]
    fn attenuate(&self, m: &Medium, c: &Chord, a: f64, b: f64, lanes: &Lanes, along: &mut Along, rng: &mut Rng) {
        let o = c.origin + a * c.dir;
        tracking::transmittances(m, &lanes.nm[..lanes.len], o, c.dir, b - a, rng, &mut along.tr[..lanes.len]);
    }

    /// Russian roulette on negligible transmittance: continue with probability 1/2 and double
    /// the weight, or stop (false), which is unbiased.
    fn roulette(&self, along: &mut Along, lanes: &Lanes, rng: &mut Rng) -> bool {
        if along.tr[..lanes.len].iter().any(|t| *t >= ROULETTE_TRANSMITTANCE) {
            return true;
        }
        if rng.uniform() < 0.5 {
            along.tr.iter_mut().for_each(|t| *t = 0.0);
            return false;
        }
        along.tr.iter_mut().for_each(|t| *t *= 2.0);
        true
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
