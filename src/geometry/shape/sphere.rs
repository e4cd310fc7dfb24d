//! Sphere: centre and radius; the normal points outward.
//!
//! # Intersection
//! With f = o − c, points o + t d on the sphere solve a t² + 2 b t + C = 0 where a = d·d,
//! b = f·d and C = f·f − r². Following Haines et al. 2019 (*Ray Tracing Gems*, ch. 7,
//! "Precision Improvements for Ray/Sphere Intersection") and pbrt-v4 §6.2.2:
//!
//! - the discriminant is b² − a C = a (r + ℓ)(r − ℓ), with ℓ = |f − (b/a) d| the distance from
//!   the centre to the line; this keeps its precision when ℓ ≈ r (grazing rays) and when the
//!   origin is far away (b² ≈ a C), where b² − a C cancels;
//! - the roots are t = q/a and t = C/q with q = −(b + sgn(b) √Δ), so that neither is obtained by
//!   subtracting nearly equal numbers (Press et al., *Numerical Recipes* 3rd ed., §5.6).
//!
//! Two conventions make the test robust at the scale of the Earth (r = 6.371e6 m):
//! - a line passing within the tangent tolerance τ = γ₁₆ r outside the sphere (ℓ ∈ (r, r + τ],
//!   about 1e-8 m for the Earth, the rounding error of ℓ itself) is a tangent hit, reported once
//!   at the point of closest approach: tangent rays are neither lost nor doubled;
//! - a root within rounding error of t = 0 is not a hit: when |C| ≤ γ₈ (f·f + r²) the origin is
//!   on the surface as far as f64 can tell, and the root C/q is that origin. A ray leaving the
//!   surface outward then finds nothing, and one leaving inward finds the far side.

use super::ShapeSample;
use crate::geometry::rounding::{gamma, max_abs};
use crate::geometry::{Aabb, Ray};
use crate::sampling::uniform_sphere;
use glam::DVec3;
use std::f64::consts::PI;

/// A sphere with outward normal (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Sphere {
    /// Centre, m.
    pub center: DVec3,
    /// Radius, m.
    pub radius: f64,
}

impl Sphere {
    /// τ: lines passing within r + τ of the centre are tangent hits.
    pub fn tangent_tolerance(&self) -> f64 {
        gamma(16) * self.radius
    }

    /// Nearest t in (0, t_max) at which the ray meets the sphere.
    pub fn distance(&self, ray: &Ray, t_max: f64) -> Option<f64> {
        let (f, d, r) = (ray.origin - self.center, ray.dir, self.radius);
        let a = d.length_squared();
        let b = f.dot(d);
        let ell = (f - (b / a) * d).length();
        let gap = r - ell;
        if gap.is_nan() || gap < -self.tangent_tolerance() {
            return None;
        }
        let root = (a * (r + ell) * gap.max(0.0)).sqrt();
        let q = -(b + root.copysign(b));
        let ff = f.length_squared();
        let c = ff - r * r;
        let t_q = if q.abs() > gamma(8) * (ff * a).sqrt() { q / a } else { f64::NAN };
        let t_c = if c.abs() > gamma(8) * (ff + r * r) { c / q } else { f64::NAN };
        let (near, far) = if t_q <= t_c { (t_q, t_c) } else { (t_c, t_q) };
        [near, far].into_iter().find(|&t| t > 0.0 && t < t_max)
    }

    /// The point at distance `t` along `ray`, projected radially onto the sphere; its distance
    /// from the sphere is a few ε (|c| + r).
    pub fn hit_point(&self, ray: &Ray, t: f64) -> DVec3 {
        let w = ray.at(t) - self.center;
        let len = w.length();
        if len > 0.0 { self.center + w * (self.radius / len) } else { ray.at(t) }
    }

    /// Outward unit normal at a point on the sphere.
    pub fn normal_at(&self, p: DVec3) -> DVec3 {
        (p - self.center).normalize_or_zero()
    }

    /// The box c ± (r + τ), rounded outward (a tangent hit may lie τ outside the sphere).
    pub fn bounds(&self) -> Aabb {
        let pad = self.radius + self.tangent_tolerance() + gamma(2) * max_abs(self.center);
        Aabb { min: self.center, max: self.center }.padded(pad)
    }

    /// 4π r².
    pub fn area(&self) -> f64 {
        4.0 * PI * self.radius * self.radius
    }

    /// Uniform by area: the centre plus r times a uniform direction (pdf 1/(4π r²)).
    pub fn sample(&self, u: [f64; 2]) -> ShapeSample {
        let n = uniform_sphere(u);
        ShapeSample { point: self.center + self.radius * n, normal: n }
    }

    /// |c|∞ + r: the coordinate scale at which the intersection arithmetic rounds.
    pub fn error_scale(&self) -> f64 {
        max_abs(self.center) + self.radius
    }

    /// A finite centre and a finite positive radius.
    pub fn check(&self) -> Result<(), String> {
        if !self.center.is_finite() {
            return Err(format!("sphere centre {} is not finite", self.center));
        }
        if !(self.radius > 0.0 && self.radius.is_finite()) {
            return Err(format!("sphere radius {} must be positive and finite", self.radius));
        }
        Ok(())
    }
}
