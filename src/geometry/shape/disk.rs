//! Disk: centre, normal (need not be unit; the front normal is its normalisation) and radius.
//!
//! # Intersection
//! As for [`super::Quad`]: the plane through the centre is met at t = n·(c − o)/(n·d); the hit is
//! inside when |w|² ≤ r² with w = t d − (c − o), the hit point relative to the centre. A ray
//! whose origin is within rounding error of the plane (|n·(c − o)| ≤ γ₅ Σ|nᵢ (c − o)ᵢ|) has no
//! hit.

use super::ShapeSample;
use crate::geometry::rounding::{abs_dot, gamma, max_abs};
use crate::geometry::{Aabb, Frame, Ray};
use crate::sampling::concentric_disk;
use glam::DVec3;
use std::f64::consts::PI;

/// A flat disk (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Disk {
    /// Centre, m.
    pub center: DVec3,
    /// Normal of the front side (need not be unit).
    pub normal: DVec3,
    /// Radius, m.
    pub radius: f64,
}

impl Disk {
    /// Nearest t in (0, t_max) at which the ray meets the disk.
    pub fn distance(&self, ray: &Ray, t_max: f64) -> Option<f64> {
        let n = self.unit_normal();
        let f = self.center - ray.origin;
        let num = n.dot(f);
        let t = num / n.dot(ray.dir);
        if !(t > 0.0 && t < t_max) || num.abs() <= gamma(5) * abs_dot(n, f) {
            return None;
        }
        let w = t * ray.dir - f;
        (w.length_squared() <= self.radius * self.radius).then_some(t)
    }

    /// Front unit normal.
    pub fn unit_normal(&self) -> DVec3 {
        self.normal.normalize_or_zero()
    }

    /// The point at distance `t` along `ray`, projected onto the disk's plane.
    pub fn hit_point(&self, ray: &Ray, t: f64) -> DVec3 {
        let p = ray.at(t);
        let n = self.unit_normal();
        p - n * n.dot(p - self.center)
    }

    /// Along axis i the disk reaches c_i ± r √(1 − n_i²); padded by rounding error.
    pub fn bounds(&self) -> Aabb {
        let n = self.unit_normal();
        let half = self.radius * (DVec3::ONE - n * n).max(DVec3::ZERO).map(f64::sqrt);
        Aabb { min: self.center - half, max: self.center + half }.padded(gamma(4) * self.error_scale())
    }

    /// π r².
    pub fn area(&self) -> f64 {
        PI * self.radius * self.radius
    }

    /// How far a point `x` of the disk lies inside its rim: a disc of that radius about `x`
    /// lies on the disk.
    pub fn clearance(&self, x: DVec3) -> f64 {
        self.radius - (x - self.center).length()
    }

    /// Uniform by area: the concentric map of the square onto the unit disk (area-preserving,
    /// PBRT4 §A.5.1), scaled by r in the disk's plane.
    pub fn sample(&self, u: [f64; 2]) -> ShapeSample {
        let n = self.unit_normal();
        let frame = Frame::from_normal(n);
        let [x, y] = concentric_disk(u);
        ShapeSample { point: self.center + self.radius * (x * frame.s + y * frame.t), normal: n }
    }

    /// |c|∞ + r.
    pub fn error_scale(&self) -> f64 {
        max_abs(self.center) + self.radius
    }

    /// Finite centre, a non-zero finite normal and a positive finite radius.
    pub fn check(&self) -> Result<(), String> {
        if !(self.center.is_finite() && self.normal.is_finite()) {
            return Err(format!("disk centre {} or normal {} is not finite", self.center, self.normal));
        }
        if !self.unit_normal().is_normalized() {
            return Err(format!("disk normal {} has zero length", self.normal));
        }
        if !(self.radius > 0.0 && self.radius.is_finite()) {
            return Err(format!("disk radius {} must be positive and finite", self.radius));
        }
        Ok(())
    }
}
