//! A temperature inversion: a Fermi step of ΔT at height h with thickness w,
//! T += ΔT·σ((z − h)/w), σ(u) = 1/(1 + e^{−u}), so ∂ΔT/∂z = (ΔT/w)·σ(1 − σ). Inversions over cold
//! sea bend rays down (superior mirage); two stacked ones make a Fata Morgana. Gutierrez et al.
//! 2005 §5 interpolate their altered profiles with Fermi's distribution (their reference
//! \[VDWGL00\]).
//!
//! σ and σ(1 − σ) = e^{−|u|}/(1 + e^{−|u|})² are evaluated with e^{−|u|}, which cannot overflow.

use super::ThinLayer;
use glam::DVec3;

/// The thinnest inversion accepted, m. The gradient peaks at ΔT/(4w): a subnormal w (5e-324)
/// made it infinite and the refractive index NaN; a millimetre step is already a
/// discontinuity to the ray equation.
pub const MIN_THICKNESS_M: f64 = 1e-3;

/// A temperature inversion: a Fermi step of ΔT (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Inversion {
    /// Temperature step, K.
    pub dt_k: f64,
    /// Height of the step's midpoint, m.
    pub height_m: f64,
    /// Thickness parameter w, m (the step rises from 12% to 88% over ±2w).
    pub thickness_m: f64,
}

impl Inversion {
    /// Checks that all values are finite and `thickness_m` at least `MIN_THICKNESS_M` (1 mm).
    pub fn new(dt_k: f64, height_m: f64, thickness_m: f64) -> Result<Inversion, String> {
        if !(dt_k.is_finite() && height_m.is_finite()) {
            return Err(format!("inversion: dT_k = {dt_k} and height_m = {height_m} must be finite"));
        }
        if !(thickness_m.is_finite() && thickness_m >= MIN_THICKNESS_M) {
            return Err(format!(
                "inversion: thickness_m = {thickness_m} must be finite and at least {MIN_THICKNESS_M} m"
            ));
        }
        Ok(Inversion { dt_k, height_m, thickness_m })
    }

    /// The inversion as a thin layer: its gradient (ΔT/w)·σ(1 − σ) peaks at the midpoint h,
    /// and σ(1 − σ) = e^{−|u|}/(1 + e^{−|u|})² ≤ e^{−|u|}, so it is at most 4 times its peak
    /// times e^{−|z − h|/w}: an envelope that falls e-fold every w (curved paths' steps model it
    /// with 2 times the peak, `crate::ode::kink`, "Thin layers").
    pub fn thin_layer(&self) -> ThinLayer {
        ThinLayer { height_m: self.height_m, scale_m: self.thickness_m }
    }

    /// ΔT (K) and ∇ΔT (K m⁻¹) at height `h` (m) whose gradient is `gh`.
    pub fn delta(&self, h: f64, gh: DVec3) -> (f64, DVec3) {
        let u = (h - self.height_m) / self.thickness_m;
        let e = (-u.abs()).exp();
        let sigma = if u >= 0.0 { 1.0 / (1.0 + e) } else { e / (1.0 + e) };
        let slope = e / ((1.0 + e) * (1.0 + e));
        (self.dt_k * sigma, (self.dt_k * slope / self.thickness_m) * gh)
    }
}
