//! Shapes: one file each, dispatched by a closed enum.
//!
//! Every shape answers the same questions: where a segment first meets it ([`Shape::intersect`]),
//! which point and normal that is ([`Shape::hit_point`], [`Shape::normal_at`]), its box, area and
//! uniform area samples, and where a ray leaving it should start ([`Shape::spawn_origin`]).
//!
//! # Rays leaving a surface
//! Every intersection routine refuses roots within its own rounding error of t = 0, so a ray
//! whose origin lies on a surface (as far as f64 can tell) does not hit that surface there. On top
//! of that, rays leaving a hit should start at [`Shape::spawn_origin`], which offsets the point
//! along the normal by an error bound scaled by the shape's coordinates (see
//! `geometry/spawn.rs`), and query t in (0, t_max).

mod disk;
mod quad;
mod sphere;
mod triangle;

pub use disk::Disk;
pub use quad::Quad;
pub use sphere::Sphere;
pub use triangle::{Shear, Triangle};

use super::spawn::offset_origin;
use super::{Aabb, Ray};
use glam::DVec3;

/// A point sampled uniformly by area on a shape.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShapeSample {
    /// The sampled point, m.
    pub point: DVec3,
    /// Unit normal on the front side.
    pub normal: DVec3,
}

/// A surface, one variant per kind (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// A sphere.
    Sphere(Sphere),
    /// A parallelogram.
    Quad(Quad),
    /// A flat disk.
    Disk(Disk),
    /// A triangle.
    Triangle(Triangle),
}

impl Shape {
    /// Nearest intersection with t in (0, t_max): distance and unit front-side normal.
    pub fn intersect(&self, ray: &Ray, t_max: f64) -> Option<(f64, DVec3)> {
        let t = self.distance(ray, t_max)?;
        Some((t, self.normal_at(self.hit_point(ray, t))))
    }

    /// Nearest t in (0, t_max) at which the ray meets the shape, without the normal.
    pub fn distance(&self, ray: &Ray, t_max: f64) -> Option<f64> {
        match self {
            Shape::Sphere(s) => s.distance(ray, t_max),
            Shape::Quad(s) => s.distance(ray, t_max),
            Shape::Disk(s) => s.distance(ray, t_max),
            Shape::Triangle(s) => s.distance(ray, t_max),
        }
    }

    /// [`Shape::distance`] for a ray whose triangle shear (see [`Shear`]) is already known:
    /// the form to use when one ray meets many shapes.
    #[inline]
    pub fn distance_sheared(&self, ray: &Ray, shear: &Shear, t_max: f64) -> Option<f64> {
        match self {
            Shape::Triangle(s) => s.distance_sheared(ray, shear, t_max),
            _ => self.distance(ray, t_max),
        }
    }

    /// The point at distance `t` along `ray` (a hit found by [`Shape::intersect`]), moved onto
    /// the surface: radially for spheres, along the normal for disks and quads, through
    /// barycentric coordinates for triangles. Its distance from the surface is a few ε times
    /// [`Shape::error_scale`], however far the ray came.
    pub fn hit_point(&self, ray: &Ray, t: f64) -> DVec3 {
        match self {
            Shape::Sphere(s) => s.hit_point(ray, t),
            Shape::Quad(s) => s.hit_point(ray, t),
            Shape::Disk(s) => s.hit_point(ray, t),
            Shape::Triangle(s) => s.hit_point(ray, t),
        }
    }

    /// Unit front-side geometric normal at a point `p` on the surface.
    pub fn normal_at(&self, p: DVec3) -> DVec3 {
        match self {
            Shape::Sphere(s) => s.normal_at(p),
            Shape::Quad(s) => s.normal(),
            Shape::Disk(s) => s.unit_normal(),
            Shape::Triangle(s) => s.normal(),
        }
    }

    /// A box containing every hit the shape can report (padded by rounding error).
    /// Whether the shape's surface may pass through box `b`: exactly for a sphere (its surface
    /// meets the box unless the box lies wholly inside or wholly outside it), conservatively by
    /// the bounding box for the other shapes.
    pub fn may_touch_box(&self, b: &Aabb) -> bool {
        match self {
            Shape::Sphere(s) => {
                let nearest = s.center.clamp(b.min, b.max);
                let far = DVec3::new(
                    if (s.center.x - b.min.x).abs() > (s.center.x - b.max.x).abs() { b.min.x } else { b.max.x },
                    if (s.center.y - b.min.y).abs() > (s.center.y - b.max.y).abs() { b.min.y } else { b.max.y },
                    if (s.center.z - b.min.z).abs() > (s.center.z - b.max.z).abs() { b.min.z } else { b.max.z },
                );
                // A relative margin keeps rounding at Earth scale on the safe side.
                let margin = 1e-9 * (s.radius + s.center.abs().max_element());
                (nearest - s.center).length() <= s.radius + margin && (far - s.center).length() >= s.radius - margin
            }
            _ => {
                let o = self.bounds();
                (0..3).all(|k| o.min[k] <= b.max[k] && o.max[k] >= b.min[k])
            }
        }
    }

    /// Bounding box, m.
    pub fn bounds(&self) -> Aabb {
        match self {
            Shape::Sphere(s) => s.bounds(),
            Shape::Quad(s) => s.bounds(),
            Shape::Disk(s) => s.bounds(),
            Shape::Triangle(s) => s.bounds(),
        }
    }

    /// For a point `x` on the surface, the largest r for which the surface within distance r
    /// of `x` is one piece of area π r² whose normals lie within 60° of the normal at `x` (a
    /// flat disc, or a cap of a sphere): the in-plane distance to the nearest edge for the flat
    /// shapes, the radius for a sphere. A photon-map disc of radius up to this lies wholly on
    /// the shape ([`crate::world::World::gather_share`]).
    pub fn clearance(&self, x: DVec3) -> f64 {
        match self {
            Shape::Sphere(s) => s.clearance(x),
            Shape::Quad(s) => s.clearance(x),
            Shape::Disk(s) => s.clearance(x),
            Shape::Triangle(s) => s.clearance(x),
        }
    }

    /// Surface area, m².
    pub fn area(&self) -> f64 {
        match self {
            Shape::Sphere(s) => s.area(),
            Shape::Quad(s) => s.area(),
            Shape::Disk(s) => s.area(),
            Shape::Triangle(s) => s.area(),
        }
    }

    /// Uniform-by-area sample (density 1/area).
    pub fn sample(&self, u: [f64; 2]) -> ShapeSample {
        match self {
            Shape::Sphere(s) => s.sample(u),
            Shape::Quad(s) => s.sample(u),
            Shape::Disk(s) => s.sample(u),
            Shape::Triangle(s) => s.sample(u),
        }
    }

    /// The magnitude (∞-norm, metres) of the coordinates the shape's intersection arithmetic
    /// works with; its rounding errors are a few ε times this.
    pub fn error_scale(&self) -> f64 {
        match self {
            Shape::Sphere(s) => s.error_scale(),
            Shape::Quad(s) => s.error_scale(),
            Shape::Disk(s) => s.error_scale(),
            Shape::Triangle(s) => s.error_scale(),
        }
    }

    /// The origin for a ray leaving this shape at `p` (unit normal `n`, e.g. from a hit or a
    /// sample) in direction `dir`: `p` offset to the side of `dir` by 128 ε max(|p|∞,
    /// [`Shape::error_scale`]). A ray from there, queried with t > 0, does not hit this shape
    /// again near `p`.
    pub fn spawn_origin(&self, p: DVec3, n: DVec3, dir: DVec3) -> DVec3 {
        offset_origin(p, n, dir, self.error_scale())
    }

    /// Whether the parameters describe a proper shape (finite, non-degenerate); the message
    /// says what is wrong.
    pub fn check(&self) -> Result<(), String> {
        match self {
            Shape::Sphere(s) => s.check(),
            Shape::Quad(s) => s.check(),
            Shape::Disk(s) => s.check(),
            Shape::Triangle(s) => s.check(),
        }
    }
}
