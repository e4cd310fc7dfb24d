//! How curved light paths are integrated: the method and its tolerances, the largest step, and
//! how closely the chords handed to intersection follow the arc.

use serde::Serialize;

/// How curved paths are followed (used only where a medium's refractive index varies).
#[derive(Clone, Debug, Serialize)]
pub struct CurvedSettings {
    /// The integrator of the ray equation.
    #[serde(skip)]
    pub method: super::Method,
    /// "dopri5", "rk4" or "euler".
    pub ode: &'static str,
    /// Dormand–Prince tolerances (relative, and absolute in m and in units of n).
    pub rtol: f64,
    /// Dormand–Prince absolute tolerance.
    pub atol: f64,
    /// Fixed step of RK4 and Euler, m.
    pub step_m: f64,
    /// Largest step, m (infinite: the world's size bounds it).
    pub max_step_m: f64,
    /// Chords stay within this distance of the arc, m; surface crossings are located to it.
    pub arc_tolerance_m: f64,
}

impl CurvedSettings {
    /// The error Dormand–Prince allows per step where |v| = `n`, as the propagator's kink cuts
    /// judge a step by ([`super::kink::Tolerance`]); `None` for the fixed-step methods, which
    /// reject nothing.
    pub fn kink_tolerance(&self, n: f64) -> Option<super::kink::Tolerance> {
        self.method.kink_tolerance(n)
    }
}

impl Default for CurvedSettings {
    fn default() -> Self {
        let (rtol, atol) = (1e-9, 1e-9);
        CurvedSettings {
            method: super::Method::dormand_prince(rtol, atol),
            ode: "dopri5",
            rtol,
            atol,
            step_m: 1.0,
            max_step_m: f64::INFINITY,
            arc_tolerance_m: 1e-4,
        }
    }
}
