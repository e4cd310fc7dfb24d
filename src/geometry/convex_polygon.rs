//! A convex polygon of the plane that points are drawn from uniformly: the fan of triangles from
//! its first vertex, one chosen with probability proportional to its area, then a uniform point
//! in it (u₁ = √ξ₁ along the fan's radius: Pharr, Jakob & Humphreys, *Physically Based
//! Rendering*, 4th ed., §6.5.1, uniform triangle sampling).

use super::min_rect::{convex_hull, polygon_area};

/// A convex polygon, counter-clockwise, with the cumulative areas of its fan triangles.
#[derive(Clone, Debug, PartialEq)]
pub struct ConvexPolygon {
    /// Vertices, counter-clockwise.
    pub vertices: Vec<[f64; 2]>,
    /// Cumulative area of fan triangles 1..=i, m²; the last is the polygon's area.
    cumulative: Vec<f64>,
}

impl ConvexPolygon {
    /// The convex hull of `points`; `None` when it has no area.
    pub fn hull_of(points: &[[f64; 2]]) -> Option<ConvexPolygon> {
        let vertices = convex_hull(points);
        if vertices.len() < 3 || polygon_area(&vertices) <= 0.0 {
            return None;
        }
        let o = vertices[0];
        let mut sum = 0.0;
        let cumulative = (1..vertices.len() - 1)
            .map(|i| {
                sum += 0.5 * cross(o, vertices[i], vertices[i + 1]);
                sum
            })
            .collect();
        Some(ConvexPolygon { vertices, cumulative })
    }

    /// Area, m².
    pub fn area(&self) -> f64 {
        self.cumulative.last().copied().unwrap_or(0.0)
    }

    /// A uniform point of the polygon from `u` ∈ [0, 1)².
    pub fn sample(&self, u: [f64; 2]) -> [f64; 2] {
        let a = u[0] * self.area();
        let i = self.cumulative.partition_point(|c| *c <= a).min(self.cumulative.len() - 1);
        let lo = if i == 0 { 0.0 } else { self.cumulative[i - 1] };
        let xi = ((a - lo) / (self.cumulative[i] - lo)).clamp(0.0, 1.0);
        let (p0, p1, p2) = (self.vertices[0], self.vertices[i + 1], self.vertices[i + 2]);
        let r = xi.sqrt();
        let (b1, b2) = (r * (1.0 - u[1]), r * u[1]);
        [p0[0] + b1 * (p1[0] - p0[0]) + b2 * (p2[0] - p0[0]), p0[1] + b1 * (p1[1] - p0[1]) + b2 * (p2[1] - p0[1])]
    }

    /// Whether `p` is inside or on the edge (within `eps` of the edge lines, m).
    pub fn contains(&self, p: [f64; 2], eps: f64) -> bool {
        let n = self.vertices.len();
        (0..n).all(|i| {
            let (a, b) = (self.vertices[i], self.vertices[(i + 1) % n]);
            let len = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
            cross(a, b, p) >= -eps * len
        })
    }
}

fn cross(o: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::{Rng, Stream};

    #[test]
    fn samples_are_inside_and_uniform() {
        // A hexagon; 10⁵ samples. Inside: all. Uniform: the fraction in the left half (x < 0 of
        // a shape symmetric about x = 0) is ½ within 5σ, and in the disc of radius 0.5 about
        // the centre (inside the hexagon) π·0.25/area within 5σ.
        let pts: Vec<[f64; 2]> =
            (0..6).map(|k| (k as f64 * std::f64::consts::PI / 3.0).sin_cos()).map(|(s, c)| [c, s]).collect();
        let poly = ConvexPolygon::hull_of(&pts).expect("hexagon");
        let area = 1.5 * 3f64.sqrt();
        assert!((poly.area() - area).abs() < 1e-12);
        let mut rng = Rng::for_task(5, Stream::Test, 0);
        let n = 100_000;
        let (mut left, mut disc) = (0, 0);
        for _ in 0..n {
            let p = poly.sample(rng.uniform2());
            assert!(poly.contains(p, 1e-12), "{p:?}");
            left += (p[0] < 0.0) as usize;
            disc += (p[0] * p[0] + p[1] * p[1] < 0.25) as usize;
        }
        let check = |count: usize, want: f64| {
            let f = count as f64 / n as f64;
            assert!((f - want).abs() < 5.0 * (want * (1.0 - want) / n as f64).sqrt(), "{f} vs {want}");
        };
        check(left, 0.5);
        check(disc, std::f64::consts::PI * 0.25 / area);
        assert!(!poly.contains([1.01, 0.0], 1e-12));
    }
}
