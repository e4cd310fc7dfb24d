//! Where a field's gradient can be non-zero. Outside the region n is constant, light travels in
//! straight lines and no ODE needs to run; every field is continuous across its region's
//! boundary, so switching between straight and curved propagation there is seamless.

use crate::geometry::Aabb;
use glam::DVec3;

/// A region that contains every point where ∇n may be non-zero (a closed set).
#[derive(Clone, Debug, PartialEq)]
pub enum GradientRegion {
    /// ∇n may be non-zero anywhere.
    Everywhere,
    /// ∇n ≡ 0: straight lines everywhere.
    Nowhere,
    /// r_min ≤ |p − centre| ≤ r_max (r_min = 0 is a ball).
    Shell {
        /// Centre, m.
        centre: DVec3,
        /// Inner radius, m.
        r_min: f64,
        /// Outer radius, m.
        r_max: f64,
    },
    /// h_min ≤ p·up ≤ h_max (`up` a unit vector; either bound may be infinite).
    Slab {
        /// Unit normal of the slab.
        up: DVec3,
        /// Lower bound of p·up, m (may be −∞).
        h_min: f64,
        /// Upper bound of p·up, m (may be +∞).
        h_max: f64,
    },
    /// An axis-aligned box.
    Box(Aabb),
    /// Any of several regions.
    Union(Vec<GradientRegion>),
}

impl GradientRegion {
    /// Whether `p` lies in the (closed) region.
    pub fn contains(&self, p: DVec3) -> bool {
        match self {
            GradientRegion::Everywhere => true,
            GradientRegion::Nowhere => false,
            GradientRegion::Shell { centre, r_min, r_max } => {
                let r2 = (p - *centre).length_squared();
                r2 >= r_min * r_min && r2 <= r_max * r_max
            }
            GradientRegion::Slab { up, h_min, h_max } => (*h_min..=*h_max).contains(&p.dot(*up)),
            GradientRegion::Box(b) => b.contains(p),
            GradientRegion::Union(rs) => rs.iter().any(|r| r.contains(p)),
        }
    }

    /// The smallest t in [0, t_max] at which `o + t·dir` (dir a unit vector) is in the region:
    /// 0 when `o` is inside, `None` when the segment misses it.
    pub fn entry_distance(&self, o: DVec3, dir: DVec3, t_max: f64) -> Option<f64> {
        if self.contains(o) {
            return Some(0.0);
        }
        let t = match self {
            GradientRegion::Everywhere => Some(0.0),
            GradientRegion::Nowhere => None,
            GradientRegion::Shell { centre, r_min, r_max } => shell_entry(o - *centre, dir, *r_min, *r_max),
            GradientRegion::Slab { up, h_min, h_max } => slab_entry(o.dot(*up), dir.dot(*up), *h_min, *h_max),
            GradientRegion::Box(b) => box_entry(b, o, dir),
            GradientRegion::Union(rs) => {
                rs.iter().filter_map(|r| r.entry_distance(o, dir, t_max)).min_by(|a, b| a.total_cmp(b))
            }
        };
        t.filter(|&t| t <= t_max)
    }

    /// The union of two regions, simplified when either is `Everywhere` or `Nowhere`.
    pub fn union(self, other: GradientRegion) -> GradientRegion {
        match (self, other) {
            (GradientRegion::Everywhere, _) | (_, GradientRegion::Everywhere) => GradientRegion::Everywhere,
            (GradientRegion::Nowhere, r) | (r, GradientRegion::Nowhere) => r,
            (GradientRegion::Union(mut a), GradientRegion::Union(b)) => {
                a.extend(b);
                GradientRegion::Union(a)
            }
            (GradientRegion::Union(mut a), r) | (r, GradientRegion::Union(mut a)) => {
                a.push(r);
                GradientRegion::Union(a)
            }
            (a, b) => GradientRegion::Union(vec![a, b]),
        }
    }
}

/// Entry into r_min ≤ |q + t·d| ≤ r_max from a point q outside it: the first crossing of the
/// outer sphere (from outside) or of the inner sphere (from within the hole).
fn shell_entry(q: DVec3, d: DVec3, r_min: f64, r_max: f64) -> Option<f64> {
    let b = q.dot(d);
    let c_len2 = q.length_squared();
    if c_len2 < r_min * r_min {
        // Inside the hole: leave it through the inner sphere (far root).
        let disc = b * b - (c_len2 - r_min * r_min);
        return Some(-b + disc.max(0.0).sqrt());
    }
    let disc = b * b - (c_len2 - r_max * r_max);
    if disc < 0.0 || b > 0.0 {
        return None;
    }
    Some((-b - disc.sqrt()).max(0.0))
}

fn slab_entry(h0: f64, rate: f64, h_min: f64, h_max: f64) -> Option<f64> {
    let target = if h0 < h_min { h_min } else { h_max };
    let t = (target - h0) / rate;
    (t.is_finite() && t >= 0.0).then_some(t)
}

fn box_entry(b: &Aabb, o: DVec3, d: DVec3) -> Option<f64> {
    let inv = d.recip();
    let t0 = (b.min - o) * inv;
    let t1 = (b.max - o) * inv;
    let near = t0.min(t1);
    let far = t0.max(t1);
    // NaN from 0·∞ on an axis the ray is parallel to: that axis does not constrain t.
    let t_in = [near.x, near.y, near.z].into_iter().filter(|v| !v.is_nan()).fold(0.0_f64, f64::max);
    let t_out = [far.x, far.y, far.z].into_iter().filter(|v| !v.is_nan()).fold(f64::INFINITY, f64::min);
    (t_in <= t_out).then_some(t_in)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shells_slabs_and_boxes_contain_and_are_entered_where_expected() {
        let shell = GradientRegion::Shell { centre: DVec3::ZERO, r_min: 1.0, r_max: 2.0 };
        assert!(shell.contains(DVec3::new(1.5, 0.0, 0.0)) && !shell.contains(DVec3::new(0.5, 0.0, 0.0)));
        assert_eq!(shell.entry_distance(DVec3::new(-5.0, 0.0, 0.0), DVec3::X, 10.0), Some(3.0));
        assert_eq!(shell.entry_distance(DVec3::new(-5.0, 0.0, 0.0), DVec3::X, 2.0), None);
        assert_eq!(shell.entry_distance(DVec3::new(5.0, 0.0, 0.0), DVec3::X, 10.0), None);
        assert_eq!(shell.entry_distance(DVec3::new(0.25, 0.0, 0.0), DVec3::X, 10.0), Some(0.75));
        assert_eq!(shell.entry_distance(DVec3::new(-5.0, 3.0, 0.0), DVec3::X, 10.0), None);

        let slab = GradientRegion::Slab { up: DVec3::Y, h_min: 0.0, h_max: 10.0 };
        assert_eq!(slab.entry_distance(DVec3::new(0.0, 20.0, 0.0), -DVec3::Y, 100.0), Some(10.0));
        assert_eq!(slab.entry_distance(DVec3::new(0.0, 20.0, 0.0), DVec3::X, 100.0), None);
        assert_eq!(slab.entry_distance(DVec3::new(0.0, 5.0, 0.0), DVec3::X, 100.0), Some(0.0));

        let b = GradientRegion::Box(Aabb { min: DVec3::splat(-1.0), max: DVec3::splat(1.0) });
        assert_eq!(b.entry_distance(DVec3::new(-3.0, 0.0, 0.0), DVec3::X, 10.0), Some(2.0));
        assert_eq!(b.entry_distance(DVec3::new(-3.0, 2.0, 0.0), DVec3::X, 10.0), None);
        let diag = DVec3::new(1.0, 1.0, 0.0).normalize();
        let t = b.entry_distance(DVec3::new(-3.0, -3.0, 0.0), diag, 10.0).unwrap();
        assert!((t - 2.0 * 2f64.sqrt()).abs() < 1e-12);
    }

    #[test]
    fn unions_simplify_and_take_the_nearest_entry() {
        let a = GradientRegion::Shell { centre: DVec3::new(5.0, 0.0, 0.0), r_min: 0.0, r_max: 1.0 };
        let b = GradientRegion::Shell { centre: DVec3::new(10.0, 0.0, 0.0), r_min: 0.0, r_max: 1.0 };
        let u = a.clone().union(GradientRegion::Nowhere).union(b);
        assert_eq!(u.entry_distance(DVec3::ZERO, DVec3::X, 100.0), Some(4.0));
        assert!(u.contains(DVec3::new(10.5, 0.0, 0.0)));
        assert_eq!(a.union(GradientRegion::Everywhere), GradientRegion::Everywhere);
        assert_eq!(GradientRegion::Nowhere.entry_distance(DVec3::ZERO, DVec3::X, 1.0), None);
    }
}
