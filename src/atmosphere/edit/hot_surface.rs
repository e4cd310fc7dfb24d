//! Air heated by a hot surface: T += ΔT·exp(−z/z₀), z the height above the ground (held at ΔT
//! below it). Over a sunlit road the surface layer is a few hundred kelvin per metre: Gutierrez et
//! al. 2005 §5 use 30 K over 20 m for their inferior mirage.

use glam::DVec3;

/// Air heated by the ground: T += ΔT exp(−z/z₀) (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HotSurface {
    /// Excess temperature at the ground, K.
    pub dt_k: f64,
    /// e-folding height, m.
    pub z0_m: f64,
}

impl HotSurface {
    /// Checks that `dt_k` is finite and `z0_m` finite and positive.
    pub fn new(dt_k: f64, z0_m: f64) -> Result<HotSurface, String> {
        if !dt_k.is_finite() {
            return Err(format!("hot surface: dT_k = {dt_k} must be finite"));
        }
        if !(z0_m.is_finite() && z0_m > 0.0) {
            return Err(format!("hot surface: z0_m = {z0_m} must be finite and positive"));
        }
        Ok(HotSurface { dt_k, z0_m })
    }

    /// ΔT and ∇ΔT = −(ΔT/z₀)exp(−z/z₀)∇z.
    pub fn delta(&self, h: f64, gh: DVec3) -> (f64, DVec3) {
        if h <= 0.0 {
            return (self.dt_k, DVec3::ZERO);
        }
        let d = self.dt_k * (-h / self.z0_m).exp();
        (d, (-d / self.z0_m) * gh)
    }
}
