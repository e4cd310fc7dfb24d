//! Shapes: one file each, dispatched by a closed enum.

mod disk;
mod quad;
mod sphere;
mod triangle;

pub use disk::Disk;
pub use quad::Quad;
pub use sphere::Sphere;
pub use triangle::Triangle;

use super::{Aabb, Ray};
use glam::DVec3;

/// A point sampled uniformly by area on a shape.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShapeSample {
    pub point: DVec3,
    /// Unit normal on the front side.
    pub normal: DVec3,
}

#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    Sphere(Sphere),
    Quad(Quad),
    Disk(Disk),
    Triangle(Triangle),
}

impl Shape {
    /// Nearest intersection with t in (0, t_max): distance and unit front-side normal.
    pub fn intersect(&self, ray: &Ray, t_max: f64) -> Option<(f64, DVec3)> {
        todo!("{ray:?}{t_max}")
    }
    pub fn bounds(&self) -> Aabb {
        todo!()
    }
    pub fn area(&self) -> f64 {
        todo!()
    }
    /// Uniform-by-area sample (density 1/area).
    pub fn sample(&self, u: [f64; 2]) -> ShapeSample {
        todo!("{u:?}")
    }
}
