//! Quad: the parallelogram origin + a u + b v, a, b ∈ [0, 1]; front normal n = (u × v)/|u × v|.
//!
//! # Intersection
//! The plane n·(x − origin) = 0 is met at t = n·(origin − o) / (n·d). The hit point relative to
//! the origin, w = t d − (origin − o), is then expressed as w = a u + b v by
//! a = (u × v)·(w × v)/|u × v|² and b = (u × v)·(u × w)/|u × v|² (Cramer's rule in the plane).
//!
//! The numerator n·(origin − o) is the signed distance of the ray origin from the plane; when it
//! is within its rounding bound γ₅ Σ|nᵢ (origin − o)ᵢ| of zero, the origin is on the plane as far
//! as f64 can tell and there is no hit (pbrt-v4 §6.8.4 argues the same for triangles). The plane is
//! the one through `origin` with the computed unit normal, the same normal that hits report and
//! that [`crate::geometry::spawn_origin`] offsets along.

use super::ShapeSample;
use crate::geometry::rounding::{abs_dot, gamma, max_abs};
use crate::geometry::{Aabb, Ray};
use glam::DVec3;

/// The parallelogram origin + a u + b v, a, b ∈ [0, 1] (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Quad {
    /// A corner, m.
    pub origin: DVec3,
    /// First edge, m.
    pub u: DVec3,
    /// Second edge, m; the front normal is u × v.
    pub v: DVec3,
}

impl Quad {
    /// Nearest t in (0, t_max) at which the ray meets the quad.
    pub fn distance(&self, ray: &Ray, t_max: f64) -> Option<f64> {
        let n = self.normal();
        let f = self.origin - ray.origin;
        let num = n.dot(f);
        let t = num / n.dot(ray.dir);
        if !(t > 0.0 && t < t_max) || num.abs() <= gamma(5) * abs_dot(n, f) {
            return None;
        }
        let w = t * ray.dir - f;
        let uv = self.u.cross(self.v);
        let inv = 1.0 / uv.length_squared();
        let a = uv.dot(w.cross(self.v)) * inv;
        let b = uv.dot(self.u.cross(w)) * inv;
        ((0.0..=1.0).contains(&a) && (0.0..=1.0).contains(&b)).then_some(t)
    }

    /// Front unit normal (u × v)/|u × v|.
    pub fn normal(&self) -> DVec3 {
        self.u.cross(self.v).normalize_or_zero()
    }

    /// The point at distance `t` along `ray`, projected onto the quad's plane.
    pub fn hit_point(&self, ray: &Ray, t: f64) -> DVec3 {
        let p = ray.at(t);
        let n = self.normal();
        p - n * n.dot(p - self.origin)
    }

    /// The four corners, padded by their rounding error.
    pub fn bounds(&self) -> Aabb {
        let o = self.origin;
        let corners = [o, o + self.u, o + self.v, o + self.u + self.v];
        let b = corners.into_iter().fold(Aabb::EMPTY, Aabb::include);
        b.padded(gamma(2) * self.error_scale())
    }

    /// |u × v|.
    pub fn area(&self) -> f64 {
        self.u.cross(self.v).length()
    }

    /// The in-plane distance from a point `x` of the quad to its nearest edge line: a disc of
    /// that radius about `x` lies on the quad.
    pub fn clearance(&self, x: DVec3) -> f64 {
        let d = x - self.origin;
        let from_line = |p: DVec3, e: DVec3| p.cross(e).length() / e.length();
        from_line(d, self.u)
            .min(from_line(d - self.v, self.u))
            .min(from_line(d, self.v))
            .min(from_line(d - self.u, self.v))
    }

    /// Uniform by area: origin + u₀ u + u₁ v (an affine map of the unit square).
    pub fn sample(&self, u: [f64; 2]) -> ShapeSample {
        ShapeSample { point: self.origin + u[0] * self.u + u[1] * self.v, normal: self.normal() }
    }

    /// |origin|∞ + |u|∞ + |v|∞.
    pub fn error_scale(&self) -> f64 {
        max_abs(self.origin) + max_abs(self.u) + max_abs(self.v)
    }

    /// Finite corner and edges spanning a parallelogram of non-zero area.
    pub fn check(&self) -> Result<(), String> {
        if !(self.origin.is_finite() && self.u.is_finite() && self.v.is_finite()) {
            return Err(format!("quad origin {} u {} v {} is not finite", self.origin, self.u, self.v));
        }
        if !(self.area() > 0.0 && self.normal().is_normalized()) {
            return Err(format!("quad u {} and v {} are parallel: zero area", self.u, self.v));
        }
        Ok(())
    }
}
