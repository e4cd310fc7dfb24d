//! Dense output: the state anywhere inside an accepted step, from coefficients built once per
//! step.
//!
//! All methods share Hairer's form (DOPRI5, routine CONTD5)
//!
//! ```text
//!     y(s0 + θh) = c1 + θ·(c2 + (1−θ)·(c3 + θ·(c4 + (1−θ)·c5))),     θ ∈ [0, 1],
//!     c1 = y0,  c2 = y1 − y0,  c3 = h·f0 − c2,  c4 = c2 − h·f1 − c3,
//! ```
//!
//! which with c5 = 0 is the cubic Hermite interpolant of (y0, f0, y1, f1) (used for Euler and
//! RK4), and with c5 = h·Σ dᵢkᵢ the 4th-order continuous extension of Dormand–Prince RK5(4)7M
//! (see [`super::dopri5`]). It matches y0, y1 and both end derivatives exactly.
//!
//! # References
//! E. Hairer, S. P. Nørsett, G. Wanner, *Solving Ordinary Differential Equations I*, 2nd ed.,
//! Springer 1993, §II.6 (dense output, Hermite interpolation, eq. 6.7), and the DOPRI5 Fortran
//! code (CONTD5).

use super::system::RayY;
use glam::DVec3;

/// The interpolant of one step: the end states, the end derivatives, the step and c5 (zero for
/// the cubic Hermite interpolant). c2…c4 are formed when evaluated, so building a step costs
/// nothing beyond what the step computed anyway.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Dense {
    /// State at the start of the step.
    pub y0: RayY,
    /// Derivative d/ds of the state at the start.
    pub f0: RayY,
    /// State at the end of the step.
    pub y1: RayY,
    /// Derivative d/ds of the state at the end.
    pub f1: RayY,
    /// Step length h, m of arc.
    pub h: f64,
    /// Dormand–Prince correction h·Σ dᵢkᵢ (zero: the cubic Hermite interpolant).
    pub c5: RayY,
}

impl Dense {
    /// The constant interpolant (a zero-length step).
    pub fn constant(y: RayY) -> Dense {
        Dense { y0: y, y1: y, ..Dense::default() }
    }

    /// The cubic Hermite interpolant of (y0, f0) and (y1, f1) over a step h.
    pub fn hermite(y0: RayY, f0: RayY, y1: RayY, f1: RayY, h: f64) -> Dense {
        Dense { y0, f0, y1, f1, h, c5: RayY::default() }
    }

    /// The state at fraction `theta` of the step (clamped to [0, 1]).
    #[inline]
    pub fn at(&self, theta: f64) -> RayY {
        let (t, u) = clamp(theta);
        let c2 = self.y1 - self.y0;
        let c3 = self.f0 * self.h - c2;
        let c4 = c2 - self.f1 * self.h - c3;
        self.y0 + (c2 + (c3 + (c4 + self.c5 * u) * t) * u) * t
    }

    /// The position at fraction `theta` (clamped to [0, 1]).
    #[inline]
    pub fn position_at(&self, theta: f64) -> DVec3 {
        let (t, u) = clamp(theta);
        let c2 = self.y1.r - self.y0.r;
        let c3 = self.f0.r * self.h - c2;
        let c4 = c2 - self.f1.r * self.h - c3;
        self.y0.r + (c2 + (c3 + (c4 + self.c5.r * u) * t) * u) * t
    }
}

/// θ clamped to [0, 1] (NaN to 0) and 1 − θ.
#[inline]
fn clamp(theta: f64) -> (f64, f64) {
    let t = if theta > 0.0 { theta.min(1.0) } else { 0.0 };
    (t, 1.0 - t)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    /// A cubic in s is reproduced exactly by the Hermite interpolant of its end values and
    /// slopes.
    #[test]
    fn hermite_reproduces_a_cubic() {
        let p = |s: f64| DVec3::new(1.0 + 2.0 * s - s * s + 0.5 * s * s * s, s * s, -s);
        let dp = |s: f64| DVec3::new(2.0 - 2.0 * s + 1.5 * s * s, 2.0 * s, -1.0);
        let (s0, h) = (0.3, 0.7);
        let y = |s: f64| RayY { r: p(s), v: dp(s) };
        let f = |s: f64| RayY { r: dp(s), v: DVec3::new(-2.0 + 3.0 * s, 2.0, 0.0) };
        let d = Dense::hermite(y(s0), f(s0), y(s0 + h), f(s0 + h), h);
        for k in 0..=10 {
            let t = k as f64 / 10.0;
            assert!((d.position_at(t) - p(s0 + t * h)).length() < 1e-14, "θ = {t}");
            assert!((d.at(t).r - p(s0 + t * h)).length() < 1e-14);
        }
        assert_eq!(d.at(0.0), y(s0));
    }
}
