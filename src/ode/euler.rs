//! The explicit Euler step with a fixed step size, y1 = y0 + h·f(y0) (global error O(h)); the
//! method the paper's Dormand–Prince integrator replaced (Gutierrez et al. 2005, §2.3).
//!
//! # References
//! E. Hairer, S. P. Nørsett, G. Wanner, *Solving Ordinary Differential Equations I*, 2nd ed.,
//! Springer 1993, §I.7 and §II.1.

use super::system::RayY;

/// One Euler step of size `h` from `y0` with `f0` = f(y0); no field samples.
#[inline]
pub fn step(y0: &RayY, f0: &RayY, h: f64) -> RayY {
    *y0 + *f0 * h
}
