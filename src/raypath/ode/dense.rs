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

/// The five coefficient states of a step's interpolant.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Dense {
    pub c: [RayY; 5],
}

impl Dense {
    /// The constant interpolant (a zero-length step).
    pub fn constant(y: RayY) -> Dense {
        Dense { c: [y, RayY::default(), RayY::default(), RayY::default(), RayY::default()] }
    }

    /// Hermite form with the extra coefficient `c5` (zero for the cubic Hermite interpolant).
    /// `f0`, `f1` are dy/ds at the two ends, `h` the step.
    pub fn with_c5(y0: RayY, f0: RayY, y1: RayY, f1: RayY, h: f64, c5: RayY) -> Dense {
        let c2 = y1 - y0;
        let c3 = f0 * h - c2;
        let c4 = c2 - f1 * h - c3;
        Dense { c: [y0, c2, c3, c4, c5] }
    }

    /// The cubic Hermite interpolant.
    pub fn hermite(y0: RayY, f0: RayY, y1: RayY, f1: RayY, h: f64) -> Dense {
        Dense::with_c5(y0, f0, y1, f1, h, RayY::default())
    }

    /// The state at fraction `theta` of the step (clamped to [0, 1]).
    #[inline]
    pub fn at(&self, theta: f64) -> RayY {
        let t = theta.clamp(0.0, 1.0);
        let u = 1.0 - t;
        let [c1, c2, c3, c4, c5] = self.c;
        c1 + (c2 + (c3 + (c4 + c5 * u) * t) * u) * t
    }

    /// The position at fraction `theta` (clamped to [0, 1]).
    #[inline]
    pub fn position_at(&self, theta: f64) -> glam::DVec3 {
        let t = theta.clamp(0.0, 1.0);
        let u = 1.0 - t;
        let [c1, c2, c3, c4, c5] = self.c.map(|c| c.r);
        c1 + (c2 + (c3 + (c4 + c5 * u) * t) * u) * t
    }
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
