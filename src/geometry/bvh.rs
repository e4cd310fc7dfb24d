//! Bounding-volume hierarchy over shapes.

use super::{Hit, Ray, Shape};

#[derive(Clone, Debug, Default)]
pub struct Bvh {}

impl Bvh {
    pub fn build(shapes: &[Shape]) -> Bvh {
        todo!("{}", shapes.len())
    }
    /// Nearest hit with t in (0, t_max) among `shapes` (the slice it was built over).
    pub fn intersect(&self, shapes: &[Shape], ray: &Ray, t_max: f64) -> Option<Hit> {
        todo!("{}{ray:?}{t_max}", shapes.len())
    }
    /// Whether anything is hit with t in (0, t_max).
    pub fn occluded(&self, shapes: &[Shape], ray: &Ray, t_max: f64) -> bool {
        todo!("{}{ray:?}{t_max}", shapes.len())
    }
}
