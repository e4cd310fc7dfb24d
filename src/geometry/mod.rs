//! Rays, frames, shapes and the bounding-volume hierarchy. All f64: scenes span from centimetres
//! above a road to the Earth's radius.
//!
//! Intersection is always asked of a segment (origin, unit direction, t_max), so the same queries
//! serve straight rays and the chords of curved arcs.

mod aabb;
mod bvh;
mod frame;
pub mod mesh;
pub mod shape;

pub use aabb::Aabb;
pub use bvh::Bvh;
pub use frame::Frame;
pub use glam::DVec3;
pub use shape::{Disk, Quad, Shape, ShapeSample, Sphere, Triangle};

/// A ray: origin and unit direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    pub origin: DVec3,
    pub dir: DVec3,
}

impl Ray {
    pub fn new(origin: DVec3, dir: DVec3) -> Ray {
        Ray { origin, dir }
    }

    pub fn at(&self, t: f64) -> DVec3 {
        self.origin + t * self.dir
    }
}

/// The first intersection along a segment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Distance along the segment from its origin.
    pub t: f64,
    pub point: DVec3,
    /// Unit geometric normal on the shape's front side (outward for spheres; u×v for quads).
    pub normal: DVec3,
    /// Index of the shape hit in the slice the BVH was built over.
    pub prim: u32,
}

/// A new ray origin at surface point `p` (normal `n`) leaving in direction `dir`, offset off the
/// surface far enough that the new ray does not hit the same surface again.
pub fn spawn_origin(p: DVec3, n: DVec3, dir: DVec3) -> DVec3 {
    todo!("{p}{n}{dir}")
}
