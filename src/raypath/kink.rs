//! Kinks as step ends: where a radial field's gradient jumps (a standard atmosphere's layer
//! boundaries, where dT/dh changes), an integrator step that straddles the kink sees a
//! discontinuous right-hand side; its error estimate is then of the order of the jump times the
//! step, and the controller rejects and shrinks until the step is tiny — five or six rejections
//! per kink crossed. Instead each step is cut where the straight line along the current
//! direction meets the next kink sphere |p − C| = R_k (a little beyond it): the path crosses
//! the kink at the end of a step (within the arc's sagitta of the step), and each step sees a
//! smooth problem. A cut step keeps the controller's proposal for the next one
//! ([`crate::ode::Integrator::step`]), so the step size is not lost at the cut.
//!
//! # References
//! - E. Hairer, S. P. Nørsett, G. Wanner, *Solving Ordinary Differential Equations I*, 2nd ed.,
//!   Springer 1993, §II.6 (discontinuities: "the step size control is then unable to cope … it
//!   is better to stop the integration at the discontinuity and to restart").

use glam::DVec3;

/// Spheres about a centre where a field's gradient is discontinuous.
#[derive(Clone, Debug, PartialEq)]
pub struct KinkSpheres {
    /// Centre, m.
    pub centre: DVec3,
    /// Radii, m.
    pub radii: Vec<f64>,
}

/// A step is cut this far beyond the straight-line crossing (relatively, and 0.1 mm), so that
/// it ends past the kink rather than just short of it (the path curves away from the line by
/// its sagitta): a step that started a hair short of the kink would begin with the slope of the
/// other side and see the whole jump as its error.
const BEYOND: f64 = 1e-7;
const BEYOND_M: f64 = 1e-4;

impl KinkSpheres {
    /// The distance along the straight line from `p` along unit `dir` to the next crossing of a
    /// kink sphere, a little beyond it; `None` when the line crosses none. Crossings nearer than
    /// `min_m` (the path is on the kink) are skipped.
    pub fn next_cut(&self, p: DVec3, dir: DVec3, min_m: f64) -> Option<f64> {
        let q = p - self.centre;
        let r = q.length();
        let b = q.dot(dir);
        let mut best = f64::INFINITY;
        for &rk in &self.radii {
            // |q + t·dir|² = rk²: t² + 2bt + c = 0 with c = (r − rk)(r + rk), roots in the stable
            // form (no cancellation when t is small against r).
            let c = (r - rk) * (r + rk);
            let disc = b * b - c;
            if disc < 0.0 {
                continue;
            }
            let sq = disc.sqrt();
            let (t1, t2) = if b > 0.0 { (-c / (b + sq), -b - sq) } else { (c / (-b + sq), -b + sq) };
            for t in [t1, t2] {
                if t > min_m && t < best {
                    best = t;
                }
            }
        }
        best.is_finite().then_some(best * (1.0 + BEYOND) + BEYOND_M)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_cut_is_just_past_the_nearest_crossing_ahead() {
        let k = KinkSpheres { centre: DVec3::ZERO, radii: vec![10.0, 20.0] };
        // From r = 15 outward along x: the sphere of 20 at t = 5.
        let t = k.next_cut(DVec3::new(15.0, 0.0, 0.0), DVec3::X, 1e-9).unwrap();
        assert!(t > 5.0 && t < 5.0 + 2e-4, "{t}");
        // Inward: the sphere of 10 at t = 5.
        let t = k.next_cut(DVec3::new(15.0, 0.0, 0.0), -DVec3::X, 1e-9).unwrap();
        assert!(t > 5.0 && t < 5.0 + 2e-4, "{t}");
        // Tangent-ish line above the inner sphere: meets only the outer one, at √(20² − 15²).
        let t = k.next_cut(DVec3::new(0.0, 15.0, 0.0), DVec3::X, 1e-9).unwrap();
        assert!((t - (400.0f64 - 225.0).sqrt()).abs() < 2e-4, "{t}");
        // On a kink, going out: the crossing at t = 0 is skipped; beyond the last sphere, none.
        let t = k.next_cut(DVec3::new(10.0, 0.0, 0.0), DVec3::X, 1e-9).unwrap();
        assert!(t > 10.0 && t < 10.0 + 2e-4, "{t}");
        assert_eq!(k.next_cut(DVec3::new(30.0, 0.0, 0.0), DVec3::X, 1e-9), None);
    }

    #[test]
    fn earth_scale_crossings_are_found_without_cancellation() {
        let r_earth = 6.371e6;
        let k = KinkSpheres { centre: DVec3::new(0.0, -r_earth, 0.0), radii: vec![r_earth + 11_000.0] };
        // From 10 999 m straight up: 1 m to the kink.
        let t = k.next_cut(DVec3::new(0.0, 10_999.0, 0.0), DVec3::Y, 1e-9).unwrap();
        assert!((t - 1.0).abs() < 2e-4, "{t}");
    }
}
