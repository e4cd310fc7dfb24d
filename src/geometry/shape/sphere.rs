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
    ///
    /// A segment whose two ends lie inside the ball by more than 10⁻⁹ r meets nothing (the ball
    /// is convex: the whole segment is inside), so it is answered without the roots — a photon
    /// in an atmosphere tests every chord against the sphere of its top. The answer is the one
    /// the roots give: along such a segment the surface is at least 10⁻⁹ r away, where their
    /// rounding is below 10⁻¹¹ r.
    pub fn distance(&self, ray: &Ray, t_max: f64) -> Option<f64> {
        let (f, d, r) = (ray.origin - self.center, ray.dir, self.radius);
        let deep = -2e-9 * r * r;
        if f.length_squared() - r * r < deep && (f + t_max * d).length_squared() - r * r < deep {
            return None;
        }
        self.distance_by_roots(ray, t_max)
    }

    /// [`Sphere::distance`] from the quadratic's roots alone.
    fn distance_by_roots(&self, ray: &Ray, t_max: f64) -> Option<f64> {
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

    /// The sphere's radius R: the part of the sphere within r ≤ R of one of its points is a
    /// cap of area π r² (Archimedes: a cap of chord r has area π r²), with normals within 60°
    /// of the point's.
    pub fn clearance(&self, _x: DVec3) -> f64 {
        self.radius
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::{Rng, Stream};

    /// A direction (not uniformly distributed: any spread will do here).
    fn unit(uniform: &mut impl FnMut() -> f64) -> DVec3 {
        (DVec3::new(uniform(), uniform(), uniform()) * 2.0 - 1.0).normalize()
    }

    /// The inside shortcut gives what the roots give, on segments inside an Earth-sized sphere
    /// (an atmosphere's top) and a unit sphere, starting at every depth from 10⁻¹⁰ r to r: half
    /// of random lengths (most cross the surface), half ending just short of the exit the roots
    /// find (10⁻⁹ r to 10⁻¹⁷ r before it), where rounding decides.
    #[test]
    fn the_inside_shortcut_answers_as_the_roots_do() {
        let mut rng = Rng::for_task(11, Stream::Test, 0);
        let mut uniform = move || rng.uniform();
        let (mut shortcut, mut hits) = (0, 0);
        for sphere in [
            Sphere { center: DVec3::new(0.0, -6.371e6, 0.0), radius: 6.461e6 },
            Sphere { center: DVec3::ZERO, radius: 1.0 },
        ] {
            let r = sphere.radius;
            for _ in 0..200_000 {
                let depth = r * 10f64.powf(-10.0 * uniform());
                let from = sphere.center + unit(&mut uniform) * (r - depth);
                let dir = unit(&mut uniform);
                let ray = Ray::new(from, dir);
                let exit = sphere.distance_by_roots(&ray, f64::INFINITY).unwrap_or(r);
                let t_max = if uniform() < 0.5 {
                    r * 10f64.powf(-9.0 * uniform()) * 2.0
                } else {
                    exit - r * 10f64.powf(-9.0 - 8.0 * uniform())
                };
                let (fast, roots) = (sphere.distance(&ray, t_max), sphere.distance_by_roots(&ray, t_max));
                assert_eq!(fast, roots, "from {from} along {dir} for {t_max} m");
                let end = from + t_max * dir - sphere.center;
                shortcut += usize::from((end.length_squared() - r * r) < -2e-9 * r * r && depth > 1e-9 * r);
                hits += usize::from(roots.is_some());
            }
        }
        assert!(shortcut > 100_000 && hits > 50_000, "{shortcut} segments took the shortcut, {hits} hit");
    }
}
