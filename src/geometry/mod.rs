//! Rays, frames, shapes and the bounding-volume hierarchy. All f64: scenes span from centimetres
//! above a road to the Earth's radius.
//!
//! Intersection is always asked of a segment (origin, unit direction, t_max), so the same queries
//! serve straight rays and the chords of curved arcs.

mod aabb;
pub mod axial;
mod bvh;
mod camera;
pub mod convex_polygon;
mod frame;
pub mod mesh;
pub mod min_rect;
pub mod rounding;
pub mod shape;
mod spawn;

pub use aabb::Aabb;
pub use axial::AxialFold;
pub use bvh::Bvh;
pub use camera::{Camera, Projection};
pub use frame::Frame;
pub use glam::DVec3;
pub use shape::{Disk, Quad, Shape, ShapeSample, Sphere, Triangle};
pub use spawn::{SPAWN_ERROR_FACTOR, offset_origin};

/// A ray: origin and unit direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    /// Origin, m.
    pub origin: DVec3,
    /// Unit direction of travel.
    pub dir: DVec3,
}

impl Ray {
    /// A ray from `origin` along `dir` (which the caller keeps unit).
    pub fn new(origin: DVec3, dir: DVec3) -> Ray {
        Ray { origin, dir }
    }

    /// The point at distance `t` (m) along the ray.
    pub fn at(&self, t: f64) -> DVec3 {
        self.origin + t * self.dir
    }
}

/// The first intersection along a segment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Distance along the segment from its origin.
    pub t: f64,
    /// The hit point, m.
    pub point: DVec3,
    /// Unit geometric normal on the shape's front side (outward for spheres; u×v for quads).
    pub normal: DVec3,
    /// Index of the shape hit in the slice the BVH was built over.
    pub prim: u32,
}

/// A new ray origin at surface point `p` (normal `n`) leaving in direction `dir`, offset off the
/// surface far enough that the new ray does not hit the same surface again.
///
/// The offset is 128 ε |p|∞ along ±n (pbrt-v4 §6.8.6; see `geometry/spawn.rs`). That suffices
/// when the surface's own coordinates are no larger than |p|. A shape defined far from where it
/// is hit (the Earth's centre is 6.4e6 m below a road at the origin) needs the offset of
/// [`Shape::spawn_origin`], which also scales with the shape's coordinates; prefer that one, or
/// [`Hit::spawn_origin`], whenever the shape is known.
pub fn spawn_origin(p: DVec3, n: DVec3, dir: DVec3) -> DVec3 {
    offset_origin(p, n, dir, 0.0)
}

impl Hit {
    /// The origin for a ray leaving this hit in direction `dir`; `shapes` is the slice the hit
    /// was found in. See [`Shape::spawn_origin`].
    pub fn spawn_origin(&self, shapes: &[Shape], dir: DVec3) -> DVec3 {
        match shapes.get(self.prim as usize) {
            Some(shape) => shape.spawn_origin(self.point, self.normal, dir),
            None => spawn_origin(self.point, self.normal, dir),
        }
    }
}
