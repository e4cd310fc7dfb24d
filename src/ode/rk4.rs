//! The classical fourth-order Runge–Kutta step with a fixed step size (the reference method of
//! the accuracy figure; Kutta 1901).
//!
//! ```text
//!     k1 = f(y0), k2 = f(y0 + h/2·k1), k3 = f(y0 + h/2·k2), k4 = f(y0 + h·k3),
//!     y1 = y0 + h/6·(k1 + 2k2 + 2k3 + k4).
//! ```
//!
//! Global error O(h⁴).
//!
//! # References
//! E. Hairer, S. P. Nørsett, G. Wanner, *Solving Ordinary Differential Equations I*, 2nd ed.,
//! Springer 1993, §II.1, Table 1.2 (left).

use super::error::OdeError;
use super::system::{IndexSample, RayY, eval};

/// One RK4 step of size `h` from `y0` with `f0` = f(y0); three field samples (counted in
/// `evals`).
#[inline]
pub fn step<F: IndexSample>(field: &F, y0: &RayY, f0: &RayY, h: f64, evals: &mut u64) -> Result<RayY, OdeError> {
    let mut stage = |y: RayY| {
        *evals += 1;
        eval(field, &y).map(|(f, _)| f)
    };
    let k1 = *f0;
    let k2 = stage(*y0 + k1 * (0.5 * h))?;
    let k3 = stage(*y0 + k2 * (0.5 * h))?;
    let k4 = stage(*y0 + k3 * h)?;
    Ok(*y0 + (k1 + (k2 + k3) * 2.0 + k4) * (h / 6.0))
}
