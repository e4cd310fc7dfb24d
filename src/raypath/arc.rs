//! Cutting one integrator step's arc into straight chords that stay within a tolerance of it.
//!
//! Geometry and media are queried along straight segments, so an arc is handed on as chords. A
//! chord of length ℓ on a path of curvature κ lies within its sagitta κℓ²/8 of the arc; cutting
//! a step into N equal parts divides the sagitta of the whole step by N². The sagitta of the
//! whole step is measured directly, as the distance of the arc's midpoint (dense output at
//! θ = ½) from the midpoint of the straight chord, so no curvature estimate is needed:
//! N = ⌈√(2 d_mid / tol)⌉ — the factor 2 covers a curvature that varies by up to 2× along the
//! step, since the sagitta of a chord grows with the local curvature. Every point of the arc is
//! then within `tol` (to the accuracy of the dense output) of the chord through it, so a
//! surface the arc crosses by more than `tol` is crossed by a chord.

use crate::ode::Step;
use glam::DVec3;

/// Most chords per step (a step that needs more is shortened by the caller's step cap).
pub const MAX_CHORDS: usize = 1024;

/// The number of chords that keeps every chord of `step` within `tol_m` of the arc.
pub fn chord_count(step: &Step, tol_m: f64) -> usize {
    let mid_arc = step.position_at(0.5);
    let mid_chord = 0.5 * (step.y0().r + step.y1().r);
    let d = (mid_arc - mid_chord).length();
    if d.is_nan() || d <= tol_m {
        return 1;
    }
    ((2.0 * d / tol_m).sqrt().ceil() as usize).clamp(1, MAX_CHORDS)
}

/// Chord `i` of `count` on `step`: its end points and the step fractions θ at its ends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ChordOnArc {
    pub from: DVec3,
    pub to: DVec3,
    pub theta0: f64,
    pub theta1: f64,
}

impl ChordOnArc {
    /// Chord `i` of `count` on the part θ ∈ [0, `theta_end`] of `step`.
    pub fn part(step: &Step, i: usize, count: usize, theta_end: f64) -> ChordOnArc {
        let theta0 = theta_end * i as f64 / count as f64;
        let theta1 = theta_end * (i + 1) as f64 / count as f64;
        let from = if i == 0 { step.y0().r } else { step.position_at(theta0) };
        let to = if i + 1 == count && theta_end == 1.0 { step.y1().r } else { step.position_at(theta1) };
        ChordOnArc { from, to, theta0, theta1 }
    }

    /// The step fraction at distance `t` along the chord of length `len`.
    pub fn theta_at(&self, t: f64, len: f64) -> f64 {
        if len > 0.0 { self.theta0 + (self.theta1 - self.theta0) * (t / len).clamp(0.0, 1.0) } else { self.theta0 }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ode::{Integrator, Method, OdeState};

    /// The largest distance from the arc (sampled finely by dense output) to the chords.
    fn worst_gap(step: &Step, count: usize) -> f64 {
        let mut worst = 0.0f64;
        for i in 0..count {
            let c = ChordOnArc::part(step, i, count, 1.0);
            let d = (c.to - c.from).normalize();
            for j in 0..=20 {
                let theta = c.theta0 + (c.theta1 - c.theta0) * j as f64 / 20.0;
                let p = step.position_at(theta) - c.from;
                worst = worst.max((p - p.dot(d) * d).length());
            }
        }
        worst
    }

    #[test]
    fn chords_stay_within_the_tolerance_of_a_strongly_curved_arc() {
        // n = 1 + 0.05·y bends a horizontal ray with curvature κ = 0.05 m⁻¹; a 10 m step has a
        // sagitta of κh²/8 ≈ 0.6 m.
        let field = |p: DVec3| (1.0 + 0.05 * p.y, DVec3::new(0.0, 0.05, 0.0));
        let mut ode = Integrator::new(Method::Rk4 { h_m: 10.0 }).expect("method");
        let mut s = OdeState::launch(&field, DVec3::ZERO, DVec3::X).expect("launch");
        let step = ode.step(&field, &mut s, 10.0).expect("step");
        for tol in [1e-2, 1e-4, 1e-6] {
            let n = chord_count(&step, tol);
            let gap = worst_gap(&step, n);
            assert!(gap <= tol, "tol {tol}: {n} chords leave a gap of {gap}");
            assert!(n > 1);
        }
    }

    #[test]
    fn a_straight_step_is_one_chord() {
        let field = |_: DVec3| (1.0, DVec3::ZERO);
        let mut ode = Integrator::new(Method::dormand_prince(1e-9, 1e-12)).expect("method");
        let mut s = OdeState::launch(&field, DVec3::ZERO, DVec3::new(1.0, 2.0, 3.0)).expect("launch");
        let step = ode.step(&field, &mut s, 5.0).expect("step");
        assert_eq!(chord_count(&step, 1e-9), 1);
    }
}
