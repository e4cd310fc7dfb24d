//! The one propagation interface for photons and eye rays.
//!
//! From a ray state (position, direction, wavelength) [`Propagator::next_event`] returns what
//! light meets next — a surface, or escape — with the direction of travel on arrival. No tracer
//! may assume a path is `o + t·d`: today every path is a straight segment; the curved-paths
//! issue plugs Dormand–Prince arcs in here, intersecting each arc's chords with the same segment
//! queries ([`crate::geometry::Bvh::intersect`]). Participating media add medium events here
//! (free-flight sampling for photons, marched transmittance for eye rays).

use crate::geometry::{Bvh, Hit, Ray, Shape};
use glam::DVec3;

/// A ray state: where light is, where it goes, and at which wavelength. `wavelength_nm` is
/// `None` when nothing on the path depends on wavelength (an eye path carrying all bands).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayState {
    pub position: DVec3,
    pub dir: DVec3,
    pub wavelength_nm: Option<f64>,
}

/// What light meets next.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Event {
    /// A surface; `dir` is the unit direction of travel on arrival, `path_length` the distance
    /// travelled along the path (arc length once paths curve).
    Surface { hit: Hit, dir: DVec3, path_length: f64 },
    /// Nothing more is hit; `dir` is the final direction of travel.
    Escape { dir: DVec3 },
}

/// Moves light through a scene's geometry.
pub struct Propagator<'a> {
    shapes: &'a [Shape],
    bvh: &'a Bvh,
}

impl<'a> Propagator<'a> {
    pub fn new(shapes: &'a [Shape], bvh: &'a Bvh) -> Propagator<'a> {
        Propagator { shapes, bvh }
    }

    /// The next event from `state`. In a scene without index fields or media the path is one
    /// straight segment to the first surface.
    pub fn next_event(&self, state: &RayState) -> Event {
        let ray = Ray::new(state.position, state.dir);
        match self.bvh.intersect(self.shapes, &ray, f64::INFINITY) {
            Some(hit) => Event::Surface { hit, dir: state.dir, path_length: hit.t },
            None => Event::Escape { dir: state.dir },
        }
    }

    /// The state leaving surface `hit` in direction `dir`, offset so it does not re-hit the
    /// surface it leaves.
    pub fn leave(&self, hit: &Hit, dir: DVec3, wavelength_nm: Option<f64>) -> RayState {
        RayState { position: hit.spawn_origin(self.shapes, dir), dir, wavelength_nm }
    }

    /// Whether the straight segment from surface point `hit` toward `wi` is free
    /// of geometry for `dist` (less a relative margin, so the target surface itself does not
    /// count). Only valid while paths are straight: the effect plan turns shadow rays off when
    /// they curve.
    pub fn unoccluded(&self, hit: &Hit, wi: DVec3, dist: f64) -> bool {
        let p = hit.point;
        let origin = hit.spawn_origin(self.shapes, wi);
        let t_max = if dist.is_finite() { (dist - (origin - p).length()) * (1.0 - 1e-7) } else { f64::INFINITY };
        t_max > 0.0 && !self.bvh.occluded(self.shapes, &Ray::new(origin, wi), t_max)
    }
}
