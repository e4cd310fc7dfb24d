//! Integrators for the ray equation d/ds (n dr/ds) = ∇n: adaptive Dormand–Prince RK5(4)7M with
//! dense output (what the paper uses, Gutierrez et al. 2005 §2.3), and fixed-step classical RK4
//! and explicit Euler for comparison.
//!
//! The pieces are kept apart: [`system`] (state, right-hand side, the |v| = n projection),
//! [`dopri5`] (the tableau), [`controller`] (error norm and step size), [`dense`] (the
//! interpolant inside a step), [`rk4`], [`euler`]. An [`Integrator`] advances one *accepted*
//! step at a time and hands back a [`Step`] that can be evaluated anywhere inside (to land on a
//! surface or a free-flight distance); `h_limit` caps the step so a caller can stop exactly at
//! a known arc length.
//!
//! ```
//! use morgana::ode::{Integrator, Method, OdeState};
//! use glam::DVec3;
//! // n = 1 + 0.01·y: a ray launched along +x bends upward (toward larger n).
//! let field = |p: DVec3| (1.0 + 0.01 * p.y, DVec3::new(0.0, 0.01, 0.0));
//! let mut state = OdeState::launch(&field, DVec3::ZERO, DVec3::X).unwrap();
//! let mut ode = Integrator::new(Method::dormand_prince(1e-9, 1e-12)).unwrap();
//! ode.integrate_to(&field, &mut state, 10.0).unwrap();
//! assert!(state.y.r.y > 0.0 && (state.s - 10.0).abs() < 1e-12);
//! ```
//!
//! # References
//! See the submodules; the method is J. R. Dormand, P. J. Prince, J. Comput. Appl. Math. 6
//! (1980) 19–26, implemented after E. Hairer, S. P. Nørsett, G. Wanner, *Solving Ordinary
//! Differential Equations I*, §II.4–6 and their DOPRI5 code.

pub mod accuracy;
pub mod controller;
pub mod dense;
pub mod dopri5;
pub mod error;
pub mod euler;
pub mod kink;
pub mod rk4;
mod settings;
pub mod system;

pub use controller::Controller;
pub use dense::Dense;
pub use error::OdeError;
pub use settings::CurvedSettings;
pub use system::{IndexSample, RayY};

use glam::DVec3;

/// Which integrator, with its parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Method {
    /// Adaptive Dormand–Prince RK5(4)7M. `rtol`, `atol`: the tolerances of the error norm
    /// ([`controller`]); `pi`: PI step control (Hairer's β = 0.04) instead of plain I control;
    /// `h0`: the first step (m), or Hairer's guess when `None`; `h_min`, `h_max`: bounds on the
    /// step (m).
    DormandPrince {
        /// Relative tolerance.
        rtol: f64,
        /// Absolute tolerance (m for r, units of n for v).
        atol: f64,
        /// PI step control (β = 0.04) instead of plain I control.
        pi: bool,
        /// First step, m; `None`: Hairer's starting-step guess.
        h0: Option<f64>,
        /// Smallest step allowed, m.
        h_min: f64,
        /// Largest step allowed, m.
        h_max: f64,
    },
    /// Classical RK4 with fixed step `h_m` (m).
    Rk4 {
        /// Step length, m of arc.
        h_m: f64,
    },
    /// Explicit Euler with fixed step `h_m` (m).
    Euler {
        /// Step length, m of arc.
        h_m: f64,
    },
}

impl Method {
    /// Dormand–Prince with PI control, Hairer's starting step, no step bounds.
    pub fn dormand_prince(rtol: f64, atol: f64) -> Method {
        Method::DormandPrince { rtol, atol, pi: true, h0: None, h_min: 0.0, h_max: f64::INFINITY }
    }

    /// A short name: "dopri5", "rk4" or "euler".
    pub fn name(&self) -> &'static str {
        match self {
            Method::DormandPrince { .. } => "dopri5",
            Method::Rk4 { .. } => "rk4",
            Method::Euler { .. } => "euler",
        }
    }

    /// The error Dormand–Prince allows per step where |v| = `n`, as kink cuts
    /// ([`kink::KinkSpheres::next_cut`]) judge a step by ([`kink::Tolerance`]); `None` for the
    /// fixed-step methods, which reject nothing.
    pub fn kink_tolerance(&self, n: f64) -> Option<kink::Tolerance> {
        match *self {
            Method::DormandPrince { rtol, atol, .. } => Some(kink::Tolerance { rtol, atol, n }),
            Method::Rk4 { .. } | Method::Euler { .. } => None,
        }
    }

    /// Checks the parameters, naming the one out of range.
    pub fn validate(&self) -> Result<(), OdeError> {
        match *self {
            Method::DormandPrince { rtol, atol, pi, h0, h_min, h_max } => {
                if let Some(h) = h0.filter(|h| !(*h > 0.0 && h.is_finite())) {
                    return Err(OdeError::InvalidSettings {
                        parameter: "h0 (m)",
                        value: h,
                        expected: "a finite step > 0",
                    });
                }
                Controller::new(rtol, atol, pi, h_min, h_max).validate()
            }
            Method::Rk4 { h_m } | Method::Euler { h_m } if !(h_m > 0.0 && h_m.is_finite()) => {
                Err(OdeError::InvalidSettings { parameter: "h_m (m)", value: h_m, expected: "a finite step > 0" })
            }
            Method::Rk4 { .. } | Method::Euler { .. } => Ok(()),
        }
    }
}

/// Where an integration is: arc length `s` (m) and the state `y`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OdeState {
    /// Arc length travelled since launch, m.
    pub s: f64,
    /// Position r (m) and ray vector v = n dr/ds.
    pub y: RayY,
}

impl OdeState {
    /// The state at s = 0 at `p` travelling along `dir`, with |v| = n(p).
    pub fn launch<F: IndexSample>(field: &F, p: DVec3, dir: DVec3) -> Result<OdeState, OdeError> {
        Ok(OdeState { s: 0.0, y: RayY::launch(field, p, dir)? })
    }
}

/// One accepted step from arc length `s0` to `s0 + h`, with its interpolant: `dense` holds
/// the end states y0, y1 (m, and ray vectors), their derivatives f0, f1 (f.r is the unit
/// tangent dr/ds, f.v = ∇n) and the step h.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Step {
    /// Arc length at the start of the step, m.
    pub s0: f64,
    /// The step was cut to the caller's `h_limit` (it ends exactly there).
    pub reached_limit: bool,
    /// The step's interpolant (end states, end derivatives, step length).
    pub dense: Dense,
}

impl Step {
    /// The zero-length step at `state`.
    pub fn zero(state: &OdeState) -> Step {
        Step { s0: state.s, reached_limit: true, dense: Dense::constant(state.y) }
    }

    /// The step length h (m of arc).
    #[inline]
    pub fn h(&self) -> f64 {
        self.dense.h
    }

    /// The state at the start.
    #[inline]
    pub fn y0(&self) -> RayY {
        self.dense.y0
    }

    /// The state at the end.
    #[inline]
    pub fn y1(&self) -> RayY {
        self.dense.y1
    }

    /// The state at fraction θ ∈ [0, 1] of the step (clamped), by dense output.
    #[inline]
    pub fn at(&self, theta: f64) -> RayY {
        self.dense.at(theta)
    }

    /// The position at fraction θ ∈ [0, 1] (clamped).
    #[inline]
    pub fn position_at(&self, theta: f64) -> DVec3 {
        self.dense.position_at(theta)
    }

    /// The unit direction of travel at fraction θ.
    pub fn direction_at(&self, theta: f64) -> DVec3 {
        self.at(theta).direction()
    }

    /// Arc length and state at fraction θ, for restarting from inside the step.
    pub fn state_at(&self, theta: f64) -> OdeState {
        let t = theta.clamp(0.0, 1.0);
        OdeState { s: self.s0 + t * self.h(), y: self.at(t) }
    }
}

/// Work done: accepted and rejected steps, and field samples (n and ∇n at a point).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Counters {
    /// Accepted steps.
    pub accepted: u64,
    /// Rejected steps (Dormand–Prince only).
    pub rejected: u64,
    /// Field samples: evaluations of n and ∇n.
    pub rhs_evals: u64,
}

/// The default budget of steps between restarts.
pub const DEFAULT_MAX_STEPS: u64 = 1_000_000;
/// Consecutive rejections inside one step before giving up.
pub const MAX_REJECTIONS: u32 = 64;

/// f(y) at the end of the last step, reused as the next step's first stage while the state
/// handed in is that same end state (FSAL for Dormand–Prince; the Hermite end slope for the
/// fixed-step methods).
#[derive(Clone, Copy, Debug)]
struct EndSlope {
    y: RayY,
    f: RayY,
}

/// Advances a ray one accepted step at a time. Allocation-free; one per thread (or per path).
#[derive(Clone, Debug)]
pub struct Integrator {
    method: Method,
    controller: Controller,
    h_next: Option<f64>,
    project: bool,
    max_steps: u64,
    steps_since_restart: u64,
    end: Option<EndSlope>,
    counters: Counters,
}

impl Integrator {
    /// An integrator for `method` (checked), without projection.
    pub fn new(method: Method) -> Result<Integrator, OdeError> {
        method.validate()?;
        let controller = match method {
            Method::DormandPrince { rtol, atol, pi, h_min, h_max, .. } => Controller::new(rtol, atol, pi, h_min, h_max),
            _ => Controller::new(1.0, 0.0, false, 0.0, f64::INFINITY),
        };
        Ok(Integrator {
            method,
            controller,
            h_next: None,
            project: false,
            max_steps: DEFAULT_MAX_STEPS,
            steps_since_restart: 0,
            end: None,
            counters: Counters::default(),
        })
    }

    /// After each accepted step, rescale v to |v| = n(r) (the invariant of the exact flow; see
    /// [`system::project`]). Free: n(r1) is already sampled for the end slope.
    pub fn with_projection(mut self, on: bool) -> Integrator {
        self.project = on;
        self
    }

    /// Whether Dormand–Prince shortens its proposals where the error density grows along the
    /// path ([`Controller::follow_trend`]; on by default). Off: plain PI control, as before
    /// issue 18 — for comparisons.
    pub fn with_trend(mut self, on: bool) -> Integrator {
        self.controller.trend = on;
        self
    }

    /// The budget of steps (accepted + rejected) between [`Integrator::restart`]s.
    pub fn with_max_steps(mut self, max_steps: u64) -> Integrator {
        self.max_steps = max_steps;
        self
    }

    /// The method this integrator was built with.
    pub fn method(&self) -> &Method {
        &self.method
    }

    /// Work done since the last [`Integrator::reset_counters`].
    pub fn counters(&self) -> Counters {
        self.counters
    }

    /// Sets the work counters to zero.
    pub fn reset_counters(&mut self) {
        self.counters = Counters::default();
    }

    /// Forgets the step-size history and the cached end slope and restores the step budget
    /// (for a new path). Counters are kept.
    pub fn restart(&mut self) {
        self.h_next = None;
        self.end = None;
        self.controller.reset();
        self.steps_since_restart = 0;
    }

    /// Goes on from a new state (a new leg of the same path, not continuous with the last
    /// step): forgets the cached end slope and restores the step budget, but keeps the step size
    /// the controller last proposed, a better first step than a fresh guess where the field
    /// varies on the same scale.
    pub fn resume(&mut self) {
        self.controller.forget_trend();
        self.end = None;
        self.steps_since_restart = 0;
    }

    /// One accepted step from `state`, at most `h_limit` (m) long; `state` moves to its end.
    /// `h_limit = 0` gives the zero-length step; a negative or NaN `h_limit` is an error.
    pub fn step<F: IndexSample>(&mut self, field: &F, state: &mut OdeState, h_limit: f64) -> Result<Step, OdeError> {
        if h_limit.is_nan() || h_limit < 0.0 {
            return Err(OdeError::InvalidStepLimit { h_limit });
        }
        if !(state.y.is_finite() && state.s.is_finite()) {
            return Err(OdeError::BadState { r: state.y.r, v: state.y.v });
        }
        if h_limit == 0.0 {
            return Ok(Step::zero(state));
        }
        let y0 = state.y;
        let f0 = self.slope_at(field, &y0)?;
        let (mut y1, mut f1, n1, h, c5) = match self.method {
            Method::DormandPrince { h0, .. } => self.dormand_prince(field, state.s, &y0, &f0, h0, h_limit)?,
            Method::Rk4 { h_m } => {
                let h = h_m.min(h_limit);
                self.budget(state.s)?;
                let y1 = rk4::step(field, &y0, &f0, h, &mut self.counters.rhs_evals)?;
                self.finish_fixed(field, y1, h)?
            }
            Method::Euler { h_m } => {
                let h = h_m.min(h_limit);
                self.budget(state.s)?;
                self.finish_fixed(field, euler::step(&y0, &f0, h), h)?
            }
        };
        if self.project {
            system::project(&mut y1, &mut f1, n1);
        }
        self.end = Some(EndSlope { y: y1, f: f1 });
        let step = Step { s0: state.s, reached_limit: h == h_limit, dense: Dense { y0, f0, y1, f1, h, c5 } };
        *state = OdeState { s: state.s + h, y: y1 };
        Ok(step)
    }

    /// The step (m) the next [`Integrator::step`] will try first, unless cut to its limit;
    /// `None` before the first step of a path (its starting step is then estimated).
    pub fn proposal(&self) -> Option<f64> {
        self.h_next
    }

    /// Shortens the proposal for the next step to at most `h` (m): for a caller that knows the
    /// field ahead changes faster than the steps so far (leaving a thin layer's peak).
    pub fn limit_proposal(&mut self, h: f64) {
        if let Some(p) = self.h_next.as_mut().filter(|_| h > 0.0) {
            *p = p.min(h).max(self.controller.h_min);
        }
    }

    /// Proposes `h` (m) as the next step when the integrator has none yet (a new path), in place
    /// of the starting-step guess; a step size already reached is kept.
    pub fn propose_first_step(&mut self, h: f64) {
        if self.h_next.is_none() && h > 0.0 && h.is_finite() {
            self.h_next = Some(h.min(self.controller.h_max).max(self.controller.h_min));
        }
    }

    /// f(y) = (v/n, ∇n) at `y`, kept as the slope the next step from `y` starts with, so it
    /// costs no second field sample: for a caller that looks ahead before stepping (the path's
    /// curvature (∇n − (∇n·d)d)/n, which predicts where it meets a kink).
    pub fn prime<F: IndexSample>(&mut self, field: &F, y: &RayY) -> Result<RayY, OdeError> {
        let f = self.slope_at(field, y)?;
        self.end = Some(EndSlope { y: *y, f });
        Ok(f)
    }

    /// Steps from `state` until its arc length is exactly `s_end` (m).
    pub fn integrate_to<F: IndexSample>(
        &mut self,
        field: &F,
        state: &mut OdeState,
        s_end: f64,
    ) -> Result<(), OdeError> {
        if !s_end.is_finite() {
            return Err(OdeError::InvalidStepLimit { h_limit: s_end - state.s });
        }
        while state.s < s_end {
            if self.step(field, state, s_end - state.s)?.reached_limit {
                state.s = s_end;
            }
        }
        Ok(())
    }

    /// f(y0): the cached end slope of the previous step when `y0` is its end state.
    fn slope_at<F: IndexSample>(&mut self, field: &F, y0: &RayY) -> Result<RayY, OdeError> {
        if let Some(e) = self.end.filter(|e| e.y == *y0) {
            return Ok(e.f);
        }
        self.counters.rhs_evals += 1;
        system::eval(field, y0).map(|(f, _)| f)
    }

    /// Counts one step attempt against the budget.
    fn budget(&mut self, s: f64) -> Result<(), OdeError> {
        if self.steps_since_restart >= self.max_steps {
            return Err(OdeError::MaxSteps { s, max_steps: self.max_steps });
        }
        self.steps_since_restart += 1;
        Ok(())
    }

    /// The end slope of a fixed step (one field sample) and the accepted count.
    fn finish_fixed<F: IndexSample>(
        &mut self,
        field: &F,
        y1: RayY,
        h: f64,
    ) -> Result<(RayY, RayY, f64, f64, RayY), OdeError> {
        self.counters.rhs_evals += 1;
        let (f1, n1) = system::eval(field, &y1)?;
        self.counters.accepted += 1;
        Ok((y1, f1, n1, h, RayY::default()))
    }

    /// Trial steps until one passes the error test. A stage point where the field is unusable
    /// counts as a rejection with the largest decrease; if the step then underflows, that
    /// field error is what is reported.
    fn dormand_prince<F: IndexSample>(
        &mut self,
        field: &F,
        s0: f64,
        y0: &RayY,
        f0: &RayY,
        h0: Option<f64>,
        h_limit: f64,
    ) -> Result<(RayY, RayY, f64, f64, RayY), OdeError> {
        let mut h = match (self.h_next, h0) {
            (Some(h), _) => h,
            (None, Some(h)) => h.min(self.controller.h_max),
            (None, None) => self.controller.initial_step(field, y0, f0, &mut self.counters.rhs_evals),
        };
        let mut last_bad = None;
        for _ in 0..=MAX_REJECTIONS {
            let capped = h >= h_limit;
            let h_try = if capped { h_limit } else { h };
            if !capped && (h_try < self.controller.h_min || h_try <= 4.0 * f64::EPSILON * s0.abs()) {
                let h_min = self.controller.h_min.max(4.0 * f64::EPSILON * s0.abs());
                return Err(last_bad.unwrap_or(OdeError::StepSizeUnderflow { s: s0, h: h_try, h_min }));
            }
            self.budget(s0)?;
            let decision = match dopri5::trial(field, y0, f0, h_try, &mut self.counters.rhs_evals) {
                Ok(t) => {
                    let err_sq = self.controller.error_norm_squared(&t.err, y0, &t.y1);
                    match self.controller.decide_squared(h_try, err_sq) {
                        controller::Decision::Accept { h_next } => {
                            let h_next = self.controller.follow_trend(h_try, err_sq, h_next, capped);
                            let cut = capped && h_next >= h_try;
                            self.h_next =
                                Some(if cut { self.controller.after_cut(h, h_try, err_sq, h_next) } else { h_next });
                            self.counters.accepted += 1;
                            return Ok((t.y1, t.f1, t.n1, h_try, t.c5));
                        }
                        d => d,
                    }
                }
                Err(e) => {
                    last_bad = Some(e);
                    self.controller.decide(h_try, f64::NAN)
                }
            };
            self.counters.rejected += 1;
            if let controller::Decision::Reject { h_retry } = decision {
                h = h_retry;
            }
        }
        Err(last_bad.unwrap_or(OdeError::TooManyRejections { s: s0, rejections: MAX_REJECTIONS + 1 }))
    }
}
