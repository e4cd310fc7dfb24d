//! The one propagation interface for photons and eye rays.
//!
//! From a ray state (position, direction, wavelength, current medium)
//! [`Propagator::next_event_with`] follows light to what it meets next — a surface, an
//! interaction in a medium, or escape — handing every straight chord of the path to a visitor on
//! the way. The visitor is how media act: a photon's free-flight sampler stops the path at an
//! interaction; an eye ray's marcher accumulates transmittance and in-scattered light. No tracer
//! may assume a path is `o + t·d`: today every path is one straight chord per event; the
//! curved-paths issue plugs Dormand–Prince arcs in here, handing their chords to the same
//! visitors and intersecting them with the same segment queries
//! ([`crate::geometry::Bvh::intersect`]).
//!
//! Media extend to the *world sphere* (twice the radius of the sphere bounding the scene and the
//! camera); a path leaving it escapes.

pub mod accuracy;
pub mod ode;

use crate::geometry::{Hit, Ray};
use crate::media::tracking;
use crate::rng::Rng;
use crate::scene::Scene;
use crate::spectrum::MAX_BANDS;
use glam::DVec3;

/// A ray state: where light is, where it goes, at which wavelength (`None` while nothing on the
/// path depends on wavelength: an eye path carrying all bands), and in which medium.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayState {
    pub position: DVec3,
    pub dir: DVec3,
    pub wavelength_nm: Option<f64>,
    pub medium: Option<u32>,
}

/// A straight piece of a path inside one medium (or vacuum).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Chord {
    pub origin: DVec3,
    pub dir: DVec3,
    pub length: f64,
    pub medium: Option<u32>,
}

/// What light meets next.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Event {
    /// A surface; `dir` is the unit direction of travel on arrival, `path_length` the distance
    /// travelled along the path (arc length once paths curve), `medium` the medium it came
    /// through.
    Surface { hit: Hit, dir: DVec3, path_length: f64, medium: Option<u32> },
    /// The visitor stopped the path inside `medium` (a photon's interaction).
    Medium { position: DVec3, dir: DVec3, path_length: f64, medium: u32 },
    /// Nothing more is hit; `dir` is the final direction of travel.
    Escape { dir: DVec3 },
}

/// Moves light through a scene.
pub struct Propagator<'a> {
    scene: &'a Scene,
    world_centre: DVec3,
    world_radius: f64,
}

impl<'a> Propagator<'a> {
    pub fn new(scene: &'a Scene) -> Propagator<'a> {
        let b = scene.bounds.include(scene.camera.position);
        let centre = b.centre();
        let radius = 2.0 * (0.5 * b.diagonal().length()).max(1e-3);
        Propagator { scene, world_centre: centre, world_radius: radius }
    }

    /// The next event from `state`, not stopping in media.
    pub fn next_event(&self, state: &RayState) -> Event {
        self.next_event_with(state, &mut |_| None)
    }

    /// The next event from `state`; each chord of the path inside a medium is handed to `visit`,
    /// which returns the distance along the chord at which the path stops, if it does.
    pub fn next_event_with(&self, state: &RayState, visit: &mut dyn FnMut(&Chord) -> Option<f64>) -> Event {
        let ray = Ray::new(state.position, state.dir);
        let hit = self.scene.bvh.intersect(&self.scene.shapes, &ray, f64::INFINITY);
        if let Some(m) = state.medium {
            let length = hit.map_or_else(|| self.world_exit(state.position, state.dir), |h| h.t);
            let chord = Chord { origin: state.position, dir: state.dir, length, medium: state.medium };
            if let Some(t) = visit(&chord).filter(|t| *t < length) {
                return Event::Medium { position: ray.at(t), dir: state.dir, path_length: t, medium: m };
            }
        }
        match hit {
            Some(hit) => Event::Surface { hit, dir: state.dir, path_length: hit.t, medium: state.medium },
            None => Event::Escape { dir: state.dir },
        }
    }

    /// Distance from `p` along `dir` to the world sphere (0 if `p` is outside it).
    fn world_exit(&self, p: DVec3, dir: DVec3) -> f64 {
        let oc = p - self.world_centre;
        let b = oc.dot(dir);
        let c = oc.length_squared() - self.world_radius * self.world_radius;
        if c > 0.0 {
            return 0.0;
        }
        -b + (b * b - c).max(0.0).sqrt()
    }

    /// The state leaving surface `hit` in direction `dir`, in `medium`, offset so it does not
    /// re-hit the surface it leaves.
    pub fn leave(&self, hit: &Hit, dir: DVec3, wavelength_nm: Option<f64>, medium: Option<u32>) -> RayState {
        RayState { position: hit.spawn_origin(&self.scene.shapes, dir), dir, wavelength_nm, medium }
    }

    /// The first surface other than an index-matched boundary along the straight ray from `start`
    /// (on surface `from`, if any) toward `dir`, with the transmittance per lane of the media
    /// crossed on the way; `None` if nothing is hit. Only valid while paths are straight.
    pub fn first_opaque_hit(
        &self,
        start: DVec3,
        from: Option<&Hit>,
        dir: DVec3,
        medium: Option<u32>,
        wavelengths_nm: &[f64],
        rng: &mut Rng,
    ) -> Option<(Hit, [f64; MAX_BANDS])> {
        let mut tr = [1.0; MAX_BANDS];
        let mut origin = from.map_or(start, |h| h.spawn_origin(&self.scene.shapes, dir));
        let mut medium = medium;
        let mut travelled = 0.0;
        for _ in 0..64 {
            let hit = self.scene.bvh.intersect(&self.scene.shapes, &Ray::new(origin, dir), f64::INFINITY);
            let seg = hit.map_or_else(|| self.world_exit(origin, dir), |h| h.t);
            if let Some(m) = self.scene.medium(medium) {
                for (t, l) in tr.iter_mut().zip(wavelengths_nm) {
                    *t *= tracking::transmittance(m, *l, origin, dir, seg, rng);
                }
            }
            let mut h = hit?;
            travelled += h.t;
            let p = &self.scene.prims[h.prim as usize];
            if p.material.is_some() || p.light.is_some() {
                h.t = travelled;
                return Some((h, tr));
            }
            medium = self.scene.medium_across(h.prim, dir, h.normal);
            origin = h.spawn_origin(&self.scene.shapes, dir);
        }
        None
    }

    /// Transmittance per lane (`wavelengths_nm`) along the straight segment from a point toward
    /// `wi` for `dist` (less a relative margin, so the target itself does not count), through
    /// media and index-matched boundaries; `None` if anything else blocks it. `from` is the
    /// surface the segment starts on, if any. Only valid while paths are straight: the effect
    /// plan turns shadow rays off when they curve.
    #[allow(clippy::too_many_arguments)]
    pub fn shadow(
        &self,
        start: DVec3,
        from: Option<&Hit>,
        wi: DVec3,
        dist: f64,
        medium: Option<u32>,
        wavelengths_nm: &[f64],
        rng: &mut Rng,
    ) -> Option<[f64; MAX_BANDS]> {
        let mut tr = [1.0; MAX_BANDS];
        let mut origin = from.map_or(start, |h| h.spawn_origin(&self.scene.shapes, wi));
        let mut left = if dist.is_finite() { (dist - (origin - start).length()) * (1.0 - 1e-7) } else { f64::INFINITY };
        let mut medium = medium;
        for _ in 0..64 {
            if left <= 0.0 {
                return Some(tr);
            }
            let hit = self.scene.bvh.intersect(&self.scene.shapes, &Ray::new(origin, wi), left);
            let seg = hit.map_or_else(|| left.min(self.world_exit(origin, wi)), |h| h.t);
            if let Some(m) = self.scene.medium(medium) {
                for (t, l) in tr.iter_mut().zip(wavelengths_nm) {
                    *t *= tracking::transmittance(m, *l, origin, wi, seg, rng);
                }
            }
            let Some(h) = hit else { return Some(tr) };
            let p = &self.scene.prims[h.prim as usize];
            if p.material.is_some() || p.light.is_some() {
                return None;
            }
            medium = self.scene.medium_across(h.prim, wi, h.normal);
            origin = h.spawn_origin(&self.scene.shapes, wi);
            left -= h.t;
        }
        None
    }
}
