//! A linear field n = n₀ + k·(x·d̂), the test case of Gutierrez et al. 2005 §2.3 (their Fig. 1
//! uses n = 1 + k·y with k from −0.1 to 0.1 m⁻¹), whose ray paths are known in closed form: a ray
//! launched perpendicular to d̂ follows the catenary y = (n₀/k)(cosh(k·x/n₀) − 1).

use glam::DVec3;

/// n = n₀ + k·(x·d̂); ∇n = k·d̂.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Linear {
    /// n at the origin (where x·d̂ = 0).
    pub n0: f64,
    /// Gradient magnitude k, m⁻¹.
    pub k_per_m: f64,
    /// Unit direction d̂ of increasing n (for k > 0).
    pub dir: DVec3,
}

impl Linear {
    /// `dir` is normalised; all inputs must be finite, `dir` non-zero.
    pub fn new(n0: f64, k_per_m: f64, dir: DVec3) -> Result<Linear, String> {
        if !(n0.is_finite() && k_per_m.is_finite()) {
            return Err(format!("linear field: n0 = {n0} and k = {k_per_m} must be finite"));
        }
        let dir = dir.try_normalize().ok_or_else(|| format!("linear field: direction {dir} must be non-zero"))?;
        Ok(Linear { n0, k_per_m, dir })
    }

    /// n and ∇n at `p` (m).
    pub fn n_grad(&self, p: DVec3) -> (f64, DVec3) {
        (self.n0 + self.k_per_m * p.dot(self.dir), self.k_per_m * self.dir)
    }

    /// The minimum over a box is at one of its corners.
    pub fn min_over(&self, b: &crate::geometry::Aabb) -> f64 {
        let corners = (0..8).map(|i| {
            DVec3::new(
                if i & 1 == 0 { b.min.x } else { b.max.x },
                if i & 2 == 0 { b.min.y } else { b.max.y },
                if i & 4 == 0 { b.min.z } else { b.max.z },
            )
        });
        corners.map(|c| self.n_grad(c).0).fold(f64::INFINITY, f64::min)
    }
}
