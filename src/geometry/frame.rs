//! Orthonormal frames about a normal.

use glam::DVec3;

/// An orthonormal basis (s, t, n).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// First tangent (local x).
    pub s: DVec3,
    /// Second tangent (local y).
    pub t: DVec3,
    /// Normal (local z).
    pub n: DVec3,
}

impl Frame {
    /// A frame whose z axis is the unit vector `n` (Duff et al. 2017, "Building an Orthonormal
    /// Basis, Revisited").
    pub fn from_normal(n: DVec3) -> Frame {
        let sign = 1.0f64.copysign(n.z);
        let a = -1.0 / (sign + n.z);
        let b = n.x * n.y * a;
        let s = DVec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
        let t = DVec3::new(b, sign + n.y * n.y * a, -n.y);
        Frame { s, t, n }
    }

    /// Local (x, y, z) to world coordinates.
    pub fn to_world(&self, v: DVec3) -> DVec3 {
        v.x * self.s + v.y * self.t + v.z * self.n
    }

    /// World to local (x, y, z) coordinates.
    pub fn to_local(&self, v: DVec3) -> DVec3 {
        DVec3::new(v.dot(self.s), v.dot(self.t), v.dot(self.n))
    }
}
