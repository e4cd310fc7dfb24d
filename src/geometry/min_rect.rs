//! The smallest rectangle around points of a plane: their convex hull (Andrew's monotone
//! chain), then rotating calipers — the minimum-area enclosing rectangle has a side on an edge of
//! the hull (Freeman & Shapira 1975), so trying the direction of each hull edge finds it.
//!
//! # References
//! - A. M. Andrew 1979, "Another efficient algorithm for convex hulls in two dimensions",
//!   Inf. Process. Lett. 9:216–219.
//! - H. Freeman & R. Shapira 1975, "Determining the minimum-area encasing rectangle for an
//!   arbitrary closed curve", Commun. ACM 18:409–413.
//! - G. T. Toussaint 1983, "Solving geometric problems with the rotating calipers", Proc. IEEE
//!   MELECON '83.

/// A rectangle in the plane: its sides along the unit vector (cos θ, sin θ) and its normal,
/// with the extents of the points along each.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rect2 {
    /// Angle of the first side, rad.
    pub angle_rad: f64,
    /// [min, max] along (cos θ, sin θ), then along (−sin θ, cos θ).
    pub extent: [[f64; 2]; 2],
}

impl Rect2 {
    /// Area.
    pub fn area(&self) -> f64 {
        (self.extent[0][1] - self.extent[0][0]) * (self.extent[1][1] - self.extent[1][0])
    }

    /// Grows the extents to take in point `p` (plane coordinates).
    pub fn include(&mut self, p: [f64; 2]) {
        let c = self.coords(p);
        for (e, c) in self.extent.iter_mut().zip(c) {
            *e = [e[0].min(c), e[1].max(c)];
        }
    }

    /// Coordinates of `p` along the rectangle's sides.
    pub fn coords(&self, p: [f64; 2]) -> [f64; 2] {
        let (s, c) = self.angle_rad.sin_cos();
        [c * p[0] + s * p[1], -s * p[0] + c * p[1]]
    }
}

/// The convex hull of `points`, counter-clockwise, without collinear points.
pub fn convex_hull(points: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let mut p: Vec<[f64; 2]> = points.iter().copied().filter(|q| q[0].is_finite() && q[1].is_finite()).collect();
    p.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    p.dedup();
    if p.len() < 3 {
        return p;
    }
    let cross = |o: [f64; 2], a: [f64; 2], b: [f64; 2]| (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
    let mut hull: Vec<[f64; 2]> = Vec::with_capacity(2 * p.len());
    for pass in 0..2 {
        let start = hull.len();
        let pts: Box<dyn Iterator<Item = &[f64; 2]>> =
            if pass == 0 { Box::new(p.iter()) } else { Box::new(p.iter().rev()) };
        for &q in pts {
            while hull.len() >= start + 2 && cross(hull[hull.len() - 2], hull[hull.len() - 1], q) <= 0.0 {
                hull.pop();
            }
            hull.push(q);
        }
        hull.pop();
    }
    hull
}

/// Area of a simple polygon (shoelace formula; positive counter-clockwise).
pub fn polygon_area(poly: &[[f64; 2]]) -> f64 {
    let n = poly.len();
    0.5 * (0..n).map(|i| poly[i][0] * poly[(i + 1) % n][1] - poly[(i + 1) % n][0] * poly[i][1]).sum::<f64>()
}

/// The minimum-area rectangle around `points` (at angle 0 when they span no area: fewer than
/// three distinct points or all on a line).
pub fn min_area_rect(points: &[[f64; 2]]) -> Rect2 {
    let hull = convex_hull(points);
    let around = |angle_rad: f64| {
        let mut r = Rect2 { angle_rad, extent: [[f64::INFINITY, f64::NEG_INFINITY]; 2] };
        for &q in &hull {
            r.include(q);
        }
        r
    };
    let mut best = around(0.0);
    if hull.len() < 3 {
        return best;
    }
    for i in 0..hull.len() {
        let (a, b) = (hull[i], hull[(i + 1) % hull.len()]);
        let r = around((b[1] - a[1]).atan2(b[0] - a[0]));
        if r.area() < best.area() {
            best = r;
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_rotated_rectangle_is_found_exactly() {
        // The corners of a 3 × 1 rectangle turned by 30° and points inside it: the smallest
        // rectangle is that one, area 3 (the axis-aligned box is (3 cos 30° + sin 30°)(3 sin 30°
        // + cos 30°) = 7.03).
        let (s, c) = 30f64.to_radians().sin_cos();
        let turn = |x: f64, y: f64| [c * x - s * y, s * x + c * y];
        let mut pts = vec![turn(0.0, 0.0), turn(3.0, 0.0), turn(3.0, 1.0), turn(0.0, 1.0)];
        pts.extend((1..10).map(|i| turn(0.3 * i as f64, 0.1 * i as f64)));
        let r = min_area_rect(&pts);
        assert!((r.area() - 3.0).abs() < 1e-12, "{r:?}");
        assert!((polygon_area(&convex_hull(&pts)) - 3.0).abs() < 1e-12);
    }

    #[test]
    fn every_point_is_inside_and_no_edge_direction_does_better() {
        // Random point clouds: the rectangle contains them all, and a brute-force search over
        // 3600 angles finds no smaller one (within its angular resolution).
        let mut rng = crate::rng::Rng::for_task(7, crate::rng::Stream::GlobalPhotons, 0);
        for _ in 0..50 {
            let pts: Vec<[f64; 2]> =
                (0..12).map(|_| [rng.uniform() * 5.0, rng.uniform() * 2.0 + rng.uniform()]).collect();
            let r = min_area_rect(&pts);
            for &p in &pts {
                for (e, q) in r.extent.iter().zip(r.coords(p)) {
                    assert!(q >= e[0] - 1e-12 && q <= e[1] + 1e-12);
                }
            }
            let brute = (0..3600)
                .map(|i| {
                    let a = i as f64 * std::f64::consts::PI / 3600.0;
                    let mut x = Rect2 { angle_rad: a, extent: [[f64::INFINITY, f64::NEG_INFINITY]; 2] };
                    for &p in &pts {
                        x.include(p);
                    }
                    x.area()
                })
                .fold(f64::INFINITY, f64::min);
            assert!(r.area() <= brute + 1e-12, "{} vs brute {brute}", r.area());
        }
    }
}
