//! Triangle with vertices p₀, p₁, p₂; front normal (p₁ − p₀) × (p₂ − p₀), normalised.
//!
//! # Intersection: watertight
//! Woop, Benthin & Wald 2013, "Watertight Ray/Triangle Intersection" (JCGT 2(1)), as in pbrt-v4
//! §6.5.3. The vertices are translated to the ray origin, the axes permuted so that the ray's
//! largest direction component is z (k_z), and sheared so that the ray becomes the +z axis:
//!
//! ```text
//! x' = x − (d_kx/d_kz) z,   y' = y − (d_ky/d_kz) z,   z' = z / d_kz
//! ```
//!
//! The ray hits the triangle when the 2-D edge functions of the origin,
//! e₀ = x₁'y₂' − y₁'x₂', e₁ = x₂'y₀' − y₂'x₀', e₂ = x₀'y₁' − y₀'x₁', do not have opposite signs;
//! then t = (e₀ z₀' + e₁ z₁' + e₂ z₂') / (e₀ + e₁ + e₂). The transformed coordinates of a
//! vertex depend only on the vertex and the ray, and the edge function of an edge shared by two
//! triangles is computed from the same two products in the opposite order, fl(a) − fl(b) against
//! fl(b) − fl(a), so its two values are exact negatives: a ray through a shared edge or vertex
//! finds at least one of the triangles (zero counts as inside). No hit is lost in a closed mesh.
//!
//! A hit with t below pbrt-v4's conservative bound δ_t on the error of t (§6.8.4) is refused: it
//! cannot be told from the ray origin lying on the triangle.

use super::ShapeSample;
use crate::geometry::rounding::{gamma, max_abs};
use crate::geometry::{Aabb, Ray};
use crate::sampling::uniform_triangle;
use glam::DVec3;

/// A triangle, watertight against its neighbours (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Triangle {
    /// Vertices p₀, p₁, p₂, m; counter-clockwise seen from the front.
    pub p: [DVec3; 3],
}

/// A vertex in the ray's sheared frame.
#[derive(Clone, Copy)]
struct Sheared {
    x: f64,
    y: f64,
    z: f64,
}

/// The ray's part of the watertight test, shared by all triangles: the axis permutation
/// (k_z is the largest |d| component) and the shear constants.
#[derive(Clone, Copy, Debug)]
pub struct Shear {
    k: [usize; 3],
    s: [f64; 3],
}

impl Shear {
    /// The permutation and shear of `ray`.
    pub fn new(ray: &Ray) -> Shear {
        let d = ray.dir;
        let kz = d.abs().max_position();
        let (kx, ky) = ((kz + 1) % 3, (kz + 2) % 3);
        Shear { k: [kx, ky, kz], s: [-d[kx] / d[kz], -d[ky] / d[kz], 1.0 / d[kz]] }
    }

    /// A vertex in the ray's frame, translated to its origin.
    #[inline]
    fn apply(&self, ray: &Ray, p: DVec3) -> Sheared {
        let q = p - ray.origin;
        let [kx, ky, kz] = self.k;
        Sheared { x: q[kx] + self.s[0] * q[kz], y: q[ky] + self.s[1] * q[kz], z: q[kz] * self.s[2] }
    }
}

impl Triangle {
    /// Nearest t in (0, t_max) at which the ray meets the triangle.
    pub fn distance(&self, ray: &Ray, t_max: f64) -> Option<f64> {
        self.distance_sheared(ray, &Shear::new(ray), t_max)
    }

    /// [`Triangle::distance`] with the ray's shear computed once for many triangles.
    pub fn distance_sheared(&self, ray: &Ray, shear: &Shear, t_max: f64) -> Option<f64> {
        let v = self.p.map(|p| shear.apply(ray, p));
        let e =
            [v[1].x * v[2].y - v[1].y * v[2].x, v[2].x * v[0].y - v[2].y * v[0].x, v[0].x * v[1].y - v[0].y * v[1].x];
        let negative = e.iter().any(|&x| x < 0.0);
        let positive = e.iter().any(|&x| x > 0.0);
        let det = e[0] + e[1] + e[2];
        if (negative && positive) || det == 0.0 {
            return None;
        }
        let t_scaled = e[0] * v[0].z + e[1] * v[1].z + e[2] * v[2].z;
        let t = t_scaled / det;
        if !(t > 0.0 && t < t_max) || t <= t_error_bound(&v, &e, det) {
            return None;
        }
        Some(t)
    }

    /// Unnormalised front normal (p₁ − p₀) × (p₂ − p₀): twice the area.
    fn cross(&self) -> DVec3 {
        (self.p[1] - self.p[0]).cross(self.p[2] - self.p[0])
    }

    /// Front unit normal.
    pub fn normal(&self) -> DVec3 {
        self.cross().normalize_or_zero()
    }

    /// The point at distance `t` along `ray`, re-expressed as p₀ + b₁ e₁ + b₂ e₂ with
    /// e_i = p_i − p₀: the result lies in the triangle's plane up to rounding of that sum.
    pub fn hit_point(&self, ray: &Ray, t: f64) -> DVec3 {
        let (e1, e2) = (self.p[1] - self.p[0], self.p[2] - self.p[0]);
        let n = e1.cross(e2);
        let inv = 1.0 / n.length_squared();
        if !inv.is_finite() {
            return ray.at(t);
        }
        let w = ray.at(t) - self.p[0];
        let b1 = n.dot(w.cross(e2)) * inv;
        let b2 = n.dot(e1.cross(w)) * inv;
        self.p[0] + b1 * e1 + b2 * e2
    }

    /// The vertices' box, padded by rounding error.
    pub fn bounds(&self) -> Aabb {
        let b = self.p.into_iter().fold(Aabb::EMPTY, Aabb::include);
        b.padded(gamma(2) * self.error_scale())
    }

    /// |e₁ × e₂| / 2.
    pub fn area(&self) -> f64 {
        0.5 * self.cross().length()
    }

    /// The in-plane distance from a point `x` of the triangle to its nearest edge line: a disc
    /// of that radius about `x` lies on the triangle.
    pub fn clearance(&self, x: DVec3) -> f64 {
        let from_line = |a: DVec3, b: DVec3| (x - a).cross(b - a).length() / (b - a).length();
        let [p0, p1, p2] = self.p;
        from_line(p0, p1).min(from_line(p1, p2)).min(from_line(p2, p0))
    }

    /// Uniform by area: uniform barycentrics (Heitz 2019) applied to the vertices.
    pub fn sample(&self, u: [f64; 2]) -> ShapeSample {
        let b = uniform_triangle(u);
        ShapeSample { point: b[0] * self.p[0] + b[1] * self.p[1] + b[2] * self.p[2], normal: self.normal() }
    }

    /// max_i |p_i|∞.
    pub fn error_scale(&self) -> f64 {
        self.p.into_iter().map(max_abs).fold(0.0, f64::max)
    }

    /// Finite vertices spanning a non-zero area.
    pub fn check(&self) -> Result<(), String> {
        if !self.p.iter().all(|p| p.is_finite()) {
            return Err(format!("triangle vertex is not finite: {} {} {}", self.p[0], self.p[1], self.p[2]));
        }
        if !(self.area() > 0.0 && self.normal().is_normalized()) {
            return Err(format!("degenerate triangle (zero area): {} {} {}", self.p[0], self.p[1], self.p[2]));
        }
        Ok(())
    }
}

/// pbrt-v4's bound δ_t on the rounding error of t = Σ eᵢ zᵢ' / det (§6.8.4, eqs. 6.26–6.31).
fn t_error_bound(v: &[Sheared; 3], e: &[f64; 3], det: f64) -> f64 {
    let max = |f: fn(&Sheared) -> f64| v.iter().map(|s| f(s).abs()).fold(0.0, f64::max);
    let (max_x, max_y, max_z) = (max(|s| s.x), max(|s| s.y), max(|s| s.z));
    let delta_z = gamma(3) * max_z;
    let delta_x = gamma(5) * (max_x + max_z);
    let delta_y = gamma(5) * (max_y + max_z);
    let delta_e = 2.0 * (gamma(2) * max_x * max_y + delta_y * max_x + delta_x * max_y);
    let max_e = e.iter().map(|x| x.abs()).fold(0.0, f64::max);
    3.0 * (gamma(3) * max_e * max_z + delta_e * max_z + delta_z * max_e) / det.abs()
}
