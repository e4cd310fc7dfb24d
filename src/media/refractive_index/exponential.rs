//! An exponential profile in height, n = 1 + (n₀ − 1)·exp(−h/H): the refractivity of an
//! isothermal atmosphere, whose density falls with scale height H = RT/(Mg).
//!
//! Below the ground (h < 0) n is held at n₀, so the field stays bounded however deep a path goes.

use crate::atmosphere::Earth;
use glam::DVec3;

/// n = 1 + (n₀ − 1) exp(−h/H), h the height above the ground of [`Earth`] (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Exponential {
    /// n at the ground.
    pub n0: f64,
    /// Scale height H, m.
    pub scale_height_m: f64,
    /// How height is measured (flat or spherical Earth).
    pub earth: Earth,
}

impl Exponential {
    /// Checks that `n0` is finite and `scale_height_m` finite and positive.
    pub fn new(n0: f64, scale_height_m: f64, earth: Earth) -> Result<Exponential, String> {
        if !n0.is_finite() {
            return Err(format!("exponential field: n0 = {n0} must be finite"));
        }
        if !(scale_height_m.is_finite() && scale_height_m > 0.0) {
            return Err(format!("exponential field: scale height {scale_height_m} m must be finite and positive"));
        }
        Ok(Exponential { n0, scale_height_m, earth })
    }

    /// n and ∇n = −(n₀ − 1)/H · exp(−h/H) · ∇h (zero below the ground).
    pub fn n_grad(&self, p: DVec3) -> (f64, DVec3) {
        let (h, gh) = self.earth.height_grad(p);
        if h <= 0.0 {
            return (self.n0, DVec3::ZERO);
        }
        let e = (self.n0 - 1.0) * (-h / self.scale_height_m).exp();
        (1.0 + e, (-e / self.scale_height_m) * gh)
    }

    /// n lies between 1 and n₀.
    pub fn min_n(&self) -> f64 {
        self.n0.min(1.0)
    }
}
