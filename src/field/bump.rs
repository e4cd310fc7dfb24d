//! A local perturbation of n: a smooth bump δn·(1 − r²/R²)³ inside a ball of radius R, zero
//! outside. The kernel is C² at r = R, so n and ∇n are continuous where the bump ends; its shape
//! is close to a Gaussian of σ ≈ R/2.8 but with compact support, so its gradient region is finite.

use glam::DVec3;

/// A smooth local bump of n (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bump {
    /// Centre, m.
    pub centre: DVec3,
    /// Radius R, m (zero beyond it).
    pub radius_m: f64,
    /// δn at the centre.
    pub delta_n: f64,
}

impl Bump {
    /// A bump; values finite and `radius_m` positive.
    pub fn new(centre: DVec3, radius_m: f64, delta_n: f64) -> Result<Bump, String> {
        if !(centre.is_finite() && delta_n.is_finite()) {
            return Err(format!("bump: centre {centre} and delta_n {delta_n} must be finite"));
        }
        if !(radius_m.is_finite() && radius_m > 0.0) {
            return Err(format!("bump: radius {radius_m} m must be finite and positive"));
        }
        Ok(Bump { centre, radius_m, delta_n })
    }

    /// δn·w(r) and its gradient, w = (1 − s)³ with s = r²/R²; ∇w = −6(1 − s)²·(p − c)/R².
    pub fn value_grad(&self, p: DVec3) -> (f64, DVec3) {
        let q = p - self.centre;
        let r2 = self.radius_m * self.radius_m;
        let s = q.length_squared() / r2;
        if s >= 1.0 {
            return (0.0, DVec3::ZERO);
        }
        let one = 1.0 - s;
        (self.delta_n * one * one * one, (-6.0 * self.delta_n * one * one / r2) * q)
    }
}
