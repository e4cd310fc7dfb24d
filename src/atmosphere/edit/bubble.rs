//! A warm or cold bubble: T += ΔT·(1 − r²/R²)³ for r < R, zero outside; C² at r = R (see
//! [`crate::field::Bump`] for the same kernel on n).

use crate::field::Bump;
use glam::DVec3;

/// A warm or cold bubble of air (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bubble {
    /// Centre of the bubble, m.
    pub centre: DVec3,
    /// Radius R, m (ΔT is zero beyond it).
    pub radius_m: f64,
    /// Temperature excess ΔT at the centre, K (negative: a cold bubble).
    pub dt_k: f64,
    kernel: Bump,
}

impl Bubble {
    /// A bubble; `radius_m` must be positive and all values finite.
    pub fn new(centre: DVec3, radius_m: f64, dt_k: f64) -> Result<Bubble, String> {
        let kernel =
            Bump::new(centre, radius_m, dt_k).map_err(|e| e.replace("bump", "bubble").replace("delta_n", "dT_k"))?;
        Ok(Bubble { centre, radius_m, dt_k, kernel })
    }

    /// ΔT (K) and ∇ΔT (K m⁻¹) at `p`.
    pub fn delta(&self, p: DVec3) -> (f64, DVec3) {
        self.kernel.value_grad(p)
    }
}
