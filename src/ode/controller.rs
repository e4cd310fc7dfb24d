//! Step-size control for the embedded Dormand–Prince pair: error norm, accept/reject, the next
//! step size (I or PI control), bounds, and the initial step guess.
//!
//! Error norm (Hairer I, eq. II.4.11), over the six components of y = (r, v):
//!
//! ```text
//!     err = sqrt( (1/6) Σᵢ ( eᵢ / (atol + rtol·max(|y0ᵢ|, |y1ᵢ|)) )² ),
//! ```
//!
//! a step is accepted when err ≤ 1. Next step (Hairer I, eq. II.4.13; with PI control,
//! Gustafsson 1991 in the form of Hairer's DOPRI5 and Hairer & Wanner II, §IV.2):
//!
//! ```text
//!     h_new = h · min(fac_max, max(fac_min, safety · err^(−α) · err_prev^β)),
//!     α = 1/5 − 0.75 β,  β = 0.04 (PI) or 0 (plain I control, α = 1/5),
//! ```
//!
//! with err_prev the error of the last accepted step (at least 10⁻⁴). After a rejection the
//! retry uses h·max(fac_min, safety·err^(−α)) and the step after it may not grow. Steps are kept
//! in [h_min, h_max].
//!
//! Where the error grows along the path faster than the step's size explains (a photon
//! descending into a hot road's layer, where ∇n ∝ e^(−height/6.7 m)), the proposal is shortened
//! by the trend of the error density ([`Controller::follow_trend`]).
//!
//! # References
//! - E. Hairer, S. P. Nørsett, G. Wanner, *Solving Ordinary Differential Equations I*, 2nd ed.,
//!   Springer 1993, §II.4 ("Automatic step size control", "Starting step size").
//! - E. Hairer, G. Wanner, *Solving Ordinary Differential Equations II*, 2nd ed., Springer
//!   1996, §IV.2 (PI step-size control); K. Gustafsson, "Control theoretic techniques for
//!   stepsize selection in explicit Runge–Kutta methods", ACM TOMS 17 (1991) 533–554.
//! - K. Gustafsson, "Control-theoretic techniques for stepsize selection in implicit Runge–Kutta
//!   methods", ACM TOMS 20 (1994) 496–517 (the predictive controller, which extrapolates the
//!   error's trend from one step to the next; [`Controller::follow_trend`] does so for a
//!   growing error density).

use super::error::OdeError;
use super::system::{IndexSample, RayY, eval};

/// Hairer's defaults (DOPRI5).
pub const SAFETY: f64 = 0.9;
/// Smallest factor a step may shrink by.
pub const FAC_MIN: f64 = 0.2;
/// Largest factor a step may grow by.
pub const FAC_MAX: f64 = 10.0;
/// β of PI step control (Gustafsson; Hairer's DOPRI5).
pub const PI_BETA: f64 = 0.04;
/// ln 10⁻⁴: the floor of err_prev (Hairer's DOPRI5).
const LN_ERR_FLOOR: f64 = -9.210340371976184;
/// (10⁻⁸)²: the floor of err² in the error density's trend (a step with err = 0, in a field of
/// zero gradient, would otherwise give an infinite rate). Errors this small make the step grow by
/// the largest factor whatever the trend.
const DENSITY_ERR_SQ_FLOOR: f64 = 1e-16;

/// The outcome of one error test.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Decision {
    /// The step passed the error test.
    Accept {
        /// The step proposed for the next step, m.
        h_next: f64,
    },
    /// The step failed the error test and is retried.
    Reject {
        /// The smaller step to retry with, m.
        h_retry: f64,
    },
}

/// The controller state between steps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Controller {
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance.
    pub atol: f64,
    /// Smallest step, m.
    pub h_min: f64,
    /// Largest step, m.
    pub h_max: f64,
    /// β of the PI controller (0: plain I control).
    pub beta: f64,
    alpha: f64,
    /// ln(err_prev) (err_prev ≥ 10⁻⁴), so a step costs one ln and one exp, not two powf.
    ln_err_prev: f64,
    rejected_last: bool,
    /// (err/h⁵)² of the last accepted step, unless it was cut by the caller or the path
    /// restarted since ([`Controller::follow_trend`]).
    density_sq_prev: Option<f64>,
    /// Whether proposals follow the error density's trend (off: plain PI control, for
    /// comparisons).
    pub trend: bool,
}

impl Controller {
    /// A controller with PI control when `pi` (β = 0.04) and plain I control otherwise.
    pub fn new(rtol: f64, atol: f64, pi: bool, h_min: f64, h_max: f64) -> Controller {
        let beta = if pi { PI_BETA } else { 0.0 };
        Controller {
            rtol,
            atol,
            h_min,
            h_max,
            beta,
            alpha: 0.2 - 0.75 * beta,
            ln_err_prev: LN_ERR_FLOOR,
            rejected_last: false,
            density_sq_prev: None,
            trend: true,
        }
    }

    /// Forgets the history (the previous error, a pending rejection and the error's trend).
    pub fn reset(&mut self) {
        self.ln_err_prev = LN_ERR_FLOOR;
        self.rejected_last = false;
        self.density_sq_prev = None;
    }

    /// Forgets the error's trend only (a new leg of a path, not continuous with the last step).
    pub fn forget_trend(&mut self) {
        self.density_sq_prev = None;
    }

    /// The proposal `h_next` for the step after an accepted one of size `h` with error norm²
    /// `err_sq`, shortened where the error density grows along the path; `cut`: the step ended
    /// where the caller cut it (at a kink it may straddle, so its error says nothing of the
    /// field's), which forgets the trend and keeps the proposal.
    ///
    /// A step's error estimate is err ≈ C·h⁵ (the embedded pair is of orders 5 and 4), and the
    /// proposal h_next = h·safety·err^(−1/5) holds C·h_next⁵ = safety⁵ if the error density C
    /// stays as it was. Where the field's variation grows along the path — a photon descending
    /// into a hot road's layer, where every derivative of ∇n grows like e^(λs), λ = |dh/ds|/z₀ —
    /// C grows too, and a step of size H from here has C·e^(λH) at its far end, where its error
    /// is made. With λ measured from the density of this step and the last,
    /// λ = (ln Cₙ − ln Cₙ₋₁)/h (the two steps end h apart), keeping the predicted error of the
    /// next step at safety⁵ gives
    ///
    /// ```text
    ///     H = h_next·e^(−λH/5),   i.e.  H = W(ab)/b,  a = h_next, b = λ/5
    /// ```
    ///
    /// (W the Lambert function), solved by Newton's method. Where the density does not grow the
    /// proposal stands; the step is only ever shortened, so the error bound is the controller's.
    /// Measured on `mirage_hot_road` (100 000 photons): rejected steps in the photon pass 18.0 %
    /// → 9.1 %, field samples −9.0 % (the book's curved-paths page).
    pub fn follow_trend(&mut self, h: f64, err_sq: f64, h_next: f64, cut: bool) -> f64 {
        let prev = self.density_sq_prev.take();
        if cut || !self.trend || h.is_nan() || h <= 0.0 {
            return h_next;
        }
        // (err/h⁵)², by multiplications: a logarithm only where the density grows.
        let (h2, err_sq) = (h * h, err_sq.max(DENSITY_ERR_SQ_FLOOR));
        let h4 = h2 * h2;
        let density_sq = err_sq / (h4 * h4 * h2);
        self.density_sq_prev = Some(density_sq);
        match prev.map(|p| density_sq / p) {
            // λ = Δln C / h with C = err/h⁵, i.e. ½·ln(ratio of the squares)/h; b = λ/5.
            Some(ratio) if ratio > 1.0 && ratio.is_finite() => shorten_for_growth(h_next, 0.1 * ratio.ln() / h),
            _ => h_next,
        }
    }

    /// The scaled RMS norm of the error estimate `e` of a step from `y0` to `y1`.
    #[inline]
    pub fn error_norm(&self, e: &RayY, y0: &RayY, y1: &RayY) -> f64 {
        self.error_norm_squared(e, y0, y1).sqrt()
    }

    /// The square of [`Controller::error_norm`] (what the step loop uses: no square root on
    /// its critical path).
    #[inline]
    pub fn error_norm_squared(&self, e: &RayY, y0: &RayY, y1: &RayY) -> f64 {
        let (e, a, b) = (e.to_array(), y0.to_array(), y1.to_array());
        // Weights 1/scᵢ need only y0 and y1, so they are ready before the estimate is.
        let q: [f64; 6] = std::array::from_fn(|i| e[i] * (1.0 / (self.atol + self.rtol * a[i].abs().max(b[i].abs()))));
        let sq = q.map(|x| x * x);
        ((sq[0] + sq[1]) + (sq[2] + sq[3]) + (sq[4] + sq[5])) * (1.0 / 6.0)
    }

    /// Accepts or rejects a step of size `h` with error norm `err` and proposes the next size.
    /// A non-finite `err` is a rejection with the largest decrease.
    pub fn decide(&mut self, h: f64, err: f64) -> Decision {
        self.decide_squared(h, err * err)
    }

    /// [`Controller::decide`] given err².
    pub fn decide_squared(&mut self, h: f64, err_sq: f64) -> Decision {
        if !err_sq.is_finite() {
            self.rejected_last = true;
            return Decision::Reject { h_retry: h * FAC_MIN };
        }
        let ln_err = 0.5 * err_sq.ln();
        if err_sq <= 1.0 {
            // safety · err^(−α) · err_prev^β; err = 0 gives +∞, clamped to the largest increase.
            let fac = SAFETY * (self.beta * self.ln_err_prev - self.alpha * ln_err).exp();
            let mut h_next = h * fac.clamp(FAC_MIN, FAC_MAX);
            if self.rejected_last {
                h_next = h_next.min(h);
            }
            self.ln_err_prev = ln_err.max(LN_ERR_FLOOR);
            self.rejected_last = false;
            Decision::Accept { h_next: h_next.min(self.h_max) }
        } else {
            self.rejected_last = true;
            Decision::Reject { h_retry: h * FAC_MIN.max(SAFETY * (-self.alpha * ln_err).exp()) }
        }
    }

    /// The step the error norm² `err_sq` of a step of size `h` predicts for the next one, without
    /// the bounds on growth: h·safety·err^(−1/5).
    pub fn predicted_step(&self, h: f64, err_sq: f64) -> f64 {
        h * SAFETY * (-0.1 * err_sq.ln()).exp()
    }

    /// The next step after an accepted step `h_try` that was cut short of the proposal `h`
    /// (to reach a limit) and whose controller proposes `h_next`: a cut step says nothing
    /// against the uncut proposal beyond what its error predicts (an untested first guess may be
    /// far too large), and a step cut to less than a tenth of it (just across a kink) predicts
    /// nothing for it. The prediction costs a logarithm and an exponential, so callers ask only
    /// for cut steps.
    pub fn after_cut(&self, h: f64, h_try: f64, err_sq: f64, h_next: f64) -> f64 {
        let keep = if h_try * FAC_MAX <= h { h } else { h.min(self.predicted_step(h_try, err_sq)) };
        h_next.max(keep)
    }

    /// The starting step size: the larger of Hairer's estimate (Hairer I, §II.4, steps a–f, for
    /// a method of order 5, from y0 and f0 = f(y0)) and the step the ray's own scales allow.
    /// One extra field sample (counted in `evals`).
    ///
    /// Hairer's estimate makes h⁶·max(‖f0‖, ‖f′‖) = 0.01 in the scaled norm; for a ray the
    /// position's derivative (the direction) is large in that norm while it is integrated
    /// exactly, so the estimate comes out thousands of times too small (centimetres where the
    /// controller settles at kilometres in air), and the first steps then grow ×10 at a time.
    /// The ray's scales give a better guess: with curvature κ = |∇n|/n and the length
    /// L = |∇n|/|d∇n/ds| over which the gradient changes (measured on the same probe step as
    /// Hairer's f′), the local error of a fifth-order step is about κ·h⁶/L⁴, so
    ///
    /// ```text
    ///     h = (tol·L⁴/κ)^(1/6),  tol = atol + rtol·max|r₀ᵢ|.
    /// ```
    pub fn initial_step<F: IndexSample>(&self, field: &F, y0: &RayY, f0: &RayY, evals: &mut u64) -> f64 {
        let zero = RayY::default();
        let norm = |x: &RayY| self.error_norm(x, y0, &zero);
        let (d0, d1) = (norm(y0), norm(f0));
        let h0 = if d0 < 1e-5 || d1 < 1e-5 { 1e-6 } else { 0.01 * d0 / d1 }.min(self.h_max);
        *evals += 1;
        let Ok((f1, _)) = eval(field, &(*y0 + *f0 * h0)) else {
            return h0.max(self.h_min);
        };
        let d2 = norm(&(f1 - *f0)) / h0;
        let d = d1.max(d2);
        let h1 = if d <= 1e-15 { (h0 * 1e-3).max(1e-6) } else { (0.01 / d).powf(0.2) };
        let hairer = (100.0 * h0).min(h1);
        let (grad, dgrad) = (f0.v.length(), (f1.v - f0.v).length() / h0);
        let (kappa, scale) = (grad / y0.v.length(), grad / dgrad);
        let tol = self.atol + self.rtol * y0.r.abs().max_element();
        let ray = (tol * scale.powi(4) / kappa).powf(1.0 / 6.0);
        let h = if ray.is_finite() { hairer.max(ray) } else { hairer };
        h.min(self.h_max).max(self.h_min)
    }

    /// Checks the settings, naming the one out of range.
    pub fn validate(&self) -> Result<(), OdeError> {
        let bad = |parameter, value, expected| Err(OdeError::InvalidSettings { parameter, value, expected });
        if !(self.rtol > 0.0 && self.rtol.is_finite()) {
            return bad("rtol", self.rtol, "a finite number > 0 (e.g. 1e-9)");
        }
        if !(self.atol >= 0.0 && self.atol.is_finite()) {
            return bad("atol", self.atol, "a finite number >= 0");
        }
        if !(self.h_min >= 0.0 && self.h_min.is_finite()) {
            return bad("h_min (m)", self.h_min, "a finite number >= 0");
        }
        if self.h_max.is_nan() || self.h_max <= self.h_min {
            return bad("h_max (m)", self.h_max, "a number greater than h_min");
        }
        Ok(())
    }
}

/// The root H of H = a·e^(−bH) (a, b ≥ 0): H = W(ab)/b, at most a.
///
/// With w = bH and z = ab, w·e^w = z: Newton's method on that increasing convex function from
/// w = ln(1 + z) (≥ W(z)) descends to the root monotonically, quadratically once near it.
fn shorten_for_growth(a: f64, b: f64) -> f64 {
    if !(b > 0.0 && a > 0.0 && b.is_finite() && a.is_finite()) {
        return a;
    }
    let z = a * b;
    let mut w = z.ln_1p();
    for _ in 0..32 {
        let e = w.exp();
        let dw = (w * e - z) / (e * (1.0 + w));
        w -= dw;
        if dw.abs() <= 1e-14 * w {
            break;
        }
    }
    (w / b).clamp(0.0, a)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn norm_is_the_scaled_rms() {
        let c = Controller::new(1e-3, 1e-6, false, 0.0, f64::INFINITY);
        let y0 = RayY { r: DVec3::new(1000.0, 0.0, 0.0), v: DVec3::new(1.0, 0.0, 0.0) };
        let e = RayY { r: DVec3::new(1.000001, 0.0, 0.0), v: DVec3::ZERO };
        // sc_x = 1e-6 + 1e-3·1000 = 1.000001, so the x term is 1 and the RMS is 1/√6.
        assert!((c.error_norm(&e, &y0, &y0) - 1.0 / 6f64.sqrt()).abs() < 1e-12);
    }

    #[test]
    fn accept_grow_and_reject_shrink() {
        let mut c = Controller::new(1e-6, 1e-9, false, 0.0, f64::INFINITY);
        // err = 1/32: I control gives 0.9·32^(1/5) = 1.8.
        assert!(matches!(c.decide(1.0, 1.0 / 32.0), Decision::Accept { h_next } if (h_next - 1.8).abs() < 1e-14));
        assert_eq!(c.decide(1.0, 0.0), Decision::Accept { h_next: FAC_MAX });
        match c.decide(1.0, 32.0) {
            Decision::Reject { h_retry } => assert!((h_retry - 0.45).abs() < 1e-15),
            d => panic!("{d:?}"),
        }
        // After a rejection the accepted step does not grow.
        assert_eq!(c.decide(0.45, 1e-3), Decision::Accept { h_next: 0.45 });
        assert!(matches!(c.decide(1.0, f64::NAN), Decision::Reject { h_retry } if h_retry == FAC_MIN));
        assert!(matches!(c.decide(1.0, 1e300), Decision::Reject { h_retry } if h_retry == FAC_MIN));
    }

    /// A step cut to a limit keeps the uncut proposal unless its error predicts less; one cut
    /// to under a tenth of the proposal (across a kink) keeps it whatever its error.
    #[test]
    fn a_cut_step_keeps_the_proposal_its_error_allows() {
        let c = Controller::new(1e-6, 1e-9, false, 0.0, f64::INFINITY);
        assert_eq!(c.after_cut(1.0, 0.05, 1e6, 0.2), 1.0);
        // err² = 1e−10: 0.5·0.9·(1e−10)^(−1/10) = 4.5 > 1, so the proposal 1 is kept.
        assert_eq!(c.after_cut(1.0, 0.5, 1e-10, 0.6), 1.0);
        // err² = 0.5: 0.45·0.5^(−1/10) = 0.4823 < 1 is kept over the controller's 0.3.
        let predicted = 0.45 * 0.5f64.powf(-0.1);
        assert!((c.after_cut(1.0, 0.5, 0.5, 0.3) - predicted).abs() < 1e-15);
        assert_eq!(c.after_cut(1.0, 0.5, 0.5, 0.7), 0.7);
    }

    #[test]
    fn h_max_caps_and_pi_remembers() {
        let mut c = Controller::new(1e-6, 1e-9, true, 0.0, 2.0);
        assert_eq!(c.decide(1.0, 0.0), Decision::Accept { h_next: 2.0 });
        let mut i = Controller::new(1e-6, 1e-9, false, 0.0, 100.0);
        let mut p = Controller::new(1e-6, 1e-9, true, 0.0, 100.0);
        i.decide(1.0, 0.5);
        p.decide(1.0, 0.5);
        let (Decision::Accept { h_next: hi }, Decision::Accept { h_next: hp }) =
            (i.decide(1.0, 0.5), p.decide(1.0, 0.5))
        else {
            panic!("both accept")
        };
        // PI: 0.9·0.5^(−0.17)·0.5^(0.04) vs I: 0.9·0.5^(−0.2).
        // ln/exp instead of powf: equal to rounding.
        assert!((hi / (0.9 * 0.5f64.powf(-0.2)) - 1.0).abs() < 1e-7);
        assert!((hp / (0.9 * 0.5f64.powf(-0.17) * 0.5f64.powf(0.04)) - 1.0).abs() < 1e-7);
    }

    #[test]
    fn the_growth_shortening_solves_its_equation() {
        for (a, b) in [(1.0, 0.0), (10.0, 0.01), (40.0, 0.1), (1e3, 1.0), (1e6, 10.0)] {
            let h = shorten_for_growth(a, b);
            // H = a·e^(−bH) to rounding (the residual relative to H).
            assert!((h - a * (-b * h).exp()).abs() <= 1e-9 * h, "a {a} b {b}: {h}");
            assert!(h <= a);
        }
    }

    #[test]
    fn a_growing_error_density_shortens_the_proposal() {
        let mut c = Controller::new(1e-9, 1e-9, true, 0.0, f64::INFINITY);
        // First step: no trend yet. Second: err grew ×e² at equal h over 4 m, so λ = 0.5 m⁻¹
        // and H = 8·e^(−0.1·H) = W(0.8)/0.1 = 4.9007 m (W(0.8) = 0.490068, by Newton on
        // w·e^w = 0.8; check: 8·e^(−0.490068) = 4.9007).
        assert_eq!(c.follow_trend(4.0, 1e-2, 8.0, false), 8.0);
        let h = c.follow_trend(4.0, 1e-2 * (4.0f64).exp(), 8.0, false);
        assert!((h - 4.9007).abs() < 1e-3, "{h}");
        // A falling density leaves it; a cut step forgets the trend.
        assert_eq!(c.follow_trend(4.0, 1e-4, 8.0, false), 8.0);
        assert_eq!(c.follow_trend(4.0, 1.0, 8.0, true), 8.0);
        assert_eq!(c.follow_trend(4.0, 1.0, 8.0, false), 8.0);
    }

    #[test]
    fn settings_are_checked() {
        assert!(Controller::new(0.0, 1e-9, true, 0.0, 1.0).validate().is_err());
        assert!(Controller::new(1e-6, -1.0, true, 0.0, 1.0).validate().is_err());
        assert!(Controller::new(1e-6, 1e-9, true, 1.0, 1.0).validate().is_err());
        assert!(Controller::new(1e-6, 1e-9, true, 0.0, f64::INFINITY).validate().is_ok());
        let e = Controller::new(f64::NAN, 1e-9, true, 0.0, 1.0).validate().unwrap_err();
        assert!(e.to_string().contains("rtol = NaN"), "{e}");
    }
}
