//! The accuracy study of `morgana accuracy`: the paper's Figure 1 (Gutierrez et al. 2005, §2.3), reproduced and
//! extended — the endpoint error of a ray against its closed form, and the wall time, for
//! Dormand–Prince RK5(4)7M over tolerances 10⁻¹…10⁻¹², and for explicit Euler and classical
//! RK4 over fixed step sizes; plus the speedup of Dormand–Prince over each at equal error.
//!
//! The test problem is the paper's: n = 1 + k·y (they use k ∈ [−0.1, 0.1] m⁻¹). A ray launched
//! at the origin along +x follows the catenary (v_x = 1 and v_y = k·s exactly, |v| = n):
//!
//! ```text
//!     x(s) = asinh(k s)/k,    y(s) = (√(1 + (k s)²) − 1)/k = k s²/(1 + √(1 + (k s)²)).
//! ```
//!
//! The default path, L = 1 km at k = 10⁻³ m⁻¹, bends the ray by 45° (v_y/v_x = kL = 1) over a
//! curvature length 1/k = L, so every method's error is well above round-off over the whole
//! range and the curve is neither nearly straight nor wound up. Fixed step sizes are fractions
//! of min(L, 1/|k|).
//!
//! Speedup at equal error: each method's (error, time) points are reduced to their Pareto
//! front (no faster point is also more accurate), log t is interpolated linearly in log error
//! along it, and the ratio t_other(e)/t_DP(e) is taken at every decade e inside both fronts.
//! Timings are medians of several samples, each repeating the integration until it lasts at
//! least `min_sample_s`, so they are well above the timer's resolution.
//!
//! # References
//! D. Gutierrez, A. Muñoz, O. Anson, F. J. Serón, "Non-linear volume photon mapping", EGSR 2005,
//! §2.3 and Fig. 1 (speedups over Euler "of up to 106.4").

pub mod plot;

use crate::atomic::Staged;
use crate::error::{Error, Result};
use crate::ode::{Integrator, Method, OdeError, OdeState};
use glam::DVec3;
use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

/// The largest bending |k|·L of the test ray (its slope at the end is k·L).
pub const MAX_BENDING: f64 = 100.0;

/// A test ray whose end is known independently of the integrators: the field it follows, where
/// it starts and where it is after its arc length. [`Problem`] is the paper's linear field with
/// its closed form; a ray through a standard atmosphere, with its end from Bouguer's invariant
/// by quadrature, lives beside the atmospheres (`crate::atmosphere::horizon_ray`).
pub trait TestRay {
    /// n and ∇n at `p`.
    fn n_grad(&self, p: DVec3) -> (f64, DVec3);
    /// The start point and unit direction.
    fn start(&self) -> (DVec3, DVec3);
    /// The arc length the ray is followed for, m.
    fn length_m(&self) -> f64;
    /// Where the ray is after [`TestRay::length_m`], m.
    fn end(&self) -> DVec3;
    /// The length fixed steps are fractions of, m.
    fn scale_m(&self) -> f64;
    /// One line saying what the ray is and where it ends, for the text report.
    fn describe(&self) -> String;
    /// The figure's title (its font has capitals, digits and a few signs).
    fn title(&self) -> String;
}

/// The test ray: n = 1 + k·y, launched at the origin along +x, followed for `length_m`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Problem {
    /// Gradient k of n = 1 + k·y, m⁻¹.
    pub k_per_m: f64,
    /// Arc length L the ray is followed for, m.
    pub length_m: f64,
}

impl Problem {
    /// Checks k (finite, nonzero), the length (finite, > 0, at most 10⁸ m) and the bending
    /// |k|·L ≤ [`MAX_BENDING`] (beyond it the ray is within a fraction of a degree of vertical and
    /// a fixed-step integrator's work grows without bound).
    pub fn new(k_per_m: f64, length_m: f64) -> Result<Problem> {
        if !(k_per_m.is_finite() && k_per_m != 0.0) {
            return Err(Error::input(
                None,
                format!("--k: found {k_per_m}; expected a finite nonzero gradient in m^-1 (n = 1 + k*y)"),
            ));
        }
        if !(length_m > 0.0 && length_m <= 1e8) {
            return Err(Error::input(
                None,
                format!("--length-m: found {length_m}; expected a path length in (0, 1e8] m"),
            ));
        }
        if k_per_m.abs() * length_m > MAX_BENDING {
            return Err(Error::input(
                None,
                format!(
                    "--k {k_per_m} with --length-m {length_m}: |k|·L = {:.3e} is more than {MAX_BENDING} (the ray would turn to within {:.2}° of vertical); use a smaller gradient or a shorter path",
                    k_per_m.abs() * length_m,
                    (1.0 / MAX_BENDING).atan().to_degrees()
                ),
            ));
        }
        Ok(Problem { k_per_m, length_m })
    }

    /// The closed-form position at arc length s (module docs).
    pub fn exact(&self, s: f64) -> DVec3 {
        let k = self.k_per_m;
        let q = (1.0 + (k * s) * (k * s)).sqrt();
        DVec3::new((k * s).asinh() / k, k * s * s / (1.0 + q), 0.0)
    }

    /// The length fixed steps are fractions of: min(L, 1/|k|).
    pub fn scale_m(&self) -> f64 {
        self.length_m.min(1.0 / self.k_per_m.abs())
    }
}

impl TestRay for Problem {
    #[inline]
    fn n_grad(&self, p: DVec3) -> (f64, DVec3) {
        (1.0 + self.k_per_m * p.y, DVec3::new(0.0, self.k_per_m, 0.0))
    }
    fn start(&self) -> (DVec3, DVec3) {
        (DVec3::ZERO, DVec3::X)
    }
    fn length_m(&self) -> f64 {
        self.length_m
    }
    fn end(&self) -> DVec3 {
        self.exact(self.length_m)
    }
    fn scale_m(&self) -> f64 {
        Problem::scale_m(self)
    }
    fn describe(&self) -> String {
        let e = self.end();
        format!(
            "ray in n = 1 + {:e}*y from the origin along +x, arc length {} m; closed-form endpoint ({:.6}, {:.6}) m",
            self.k_per_m, self.length_m, e.x, e.y
        )
    }
    fn title(&self) -> String {
        format!("RAY IN N = 1 + {:.0E} Y, ARC LENGTH {} M: ERROR VS CLOSED-FORM CATENARY", self.k_per_m, self.length_m)
    }
}

/// What to measure.
#[derive(Clone, Debug, PartialEq)]
pub struct Plan {
    /// Dormand–Prince tolerances to run (rtol = atol).
    pub tolerances: Vec<f64>,
    /// Euler step sizes to run, m.
    pub euler_steps_m: Vec<f64>,
    /// RK4 step sizes to run, m.
    pub rk4_steps_m: Vec<f64>,
    /// Timing samples per configuration (the median is reported).
    pub samples: usize,
    /// Shortest duration of one timing sample, s (the integration is repeated until it lasts this
    /// long).
    pub min_sample_s: f64,
    /// Rescale v to |v| = n after each step (see [`crate::ode::Integrator::with_projection`]).
    pub project: bool,
}

impl Plan {
    /// The full figure: tolerances 10⁻¹…10⁻¹² (the paper's 10⁻³…10⁻¹² and two looser ones, where
    /// Dormand–Prince's error meets Euler's), 9 Euler and 8 RK4 step sizes, median of 5 samples
    /// of at least 20 ms each.
    pub fn standard(p: &impl TestRay) -> Plan {
        let h = p.scale_m();
        Plan {
            tolerances: (1..=12).map(|e| 10f64.powi(-e)).collect(),
            euler_steps_m: [1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5, 3e-6, 1e-6].iter().map(|f| f * h).collect(),
            rk4_steps_m: [1e-1, 5e-2, 2e-2, 1e-2, 5e-3, 2e-3, 1e-3, 5e-4].iter().map(|f| f * h).collect(),
            samples: 5,
            min_sample_s: 0.02,
            project: false,
        }
    }

    /// A smoke run: 4 tolerances, 3 step sizes each, 3 samples of at least 1 ms.
    pub fn quick(p: &impl TestRay) -> Plan {
        let h = p.scale_m();
        Plan {
            tolerances: vec![1e-2, 1e-4, 1e-6, 1e-8],
            euler_steps_m: [1e-2, 1e-3, 1e-4].iter().map(|f| f * h).collect(),
            rk4_steps_m: [1e-1, 1e-2, 1e-3].iter().map(|f| f * h).collect(),
            samples: 3,
            min_sample_s: 0.001,
            project: false,
        }
    }

    fn methods(&self) -> Vec<(Method, f64)> {
        let dp = self.tolerances.iter().map(|t| (Method::dormand_prince(*t, *t), *t));
        let euler = self.euler_steps_m.iter().map(|h| (Method::Euler { h_m: *h }, *h));
        let rk4 = self.rk4_steps_m.iter().map(|h| (Method::Rk4 { h_m: *h }, *h));
        dp.chain(rk4).chain(euler).collect()
    }
}

/// One measured configuration. `parameter` is the tolerance (rtol = atol) for "dopri5" and the
/// step h (m) for "rk4" and "euler".
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Point {
    /// `"dopri5"`, `"rk4"` or `"euler"`.
    pub method: &'static str,
    /// Tolerance (dopri5) or step size h in m (rk4, euler).
    pub parameter: f64,
    /// Distance of the computed endpoint from the closed form, m.
    pub endpoint_error_m: f64,
    /// Median wall time of one integration, s.
    pub time_s: f64,
    /// Accepted steps.
    pub steps: u64,
    /// Field samples (evaluations of n and ∇n).
    pub rhs_evals: u64,
}

/// Dormand–Prince's speedup over the fixed-step methods at one endpoint error: in wall time,
/// and in field samples (what dominates once n(r) is costly to evaluate).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Speedup {
    /// The endpoint error the ratios are taken at, m (a decade).
    pub error_m: f64,
    /// Wall-time ratio t_Euler / t_DP at that error; `None` outside either front.
    pub over_euler: Option<f64>,
    /// Wall-time ratio t_RK4 / t_DP.
    pub over_rk4: Option<f64>,
    /// Field-sample ratio Euler / DP.
    pub evals_over_euler: Option<f64>,
    /// Field-sample ratio RK4 / DP.
    pub evals_over_rk4: Option<f64>,
}

/// Everything `morgana accuracy` measured.
#[derive(Clone, Debug, PartialEq)]
pub struct Report {
    /// The test ray, in words ([`TestRay::describe`]).
    pub ray: String,
    /// The figure's title ([`TestRay::title`]).
    pub title: String,
    /// Whether steps were projected to |v| = n.
    pub project: bool,
    /// One point per configuration that succeeded.
    pub points: Vec<Point>,
    /// Configurations that failed, with the integrator's message.
    pub failures: Vec<String>,
    /// Speedups at every decade of error inside both fronts.
    pub speedups: Vec<Speedup>,
}

/// The goals of the issue: DP at least this many times faster than Euler and RK4.
pub const GOAL_OVER_EULER: f64 = 100.0;
/// Goal: DP at least this many times faster than RK4.
pub const GOAL_OVER_RK4: f64 = 3.0;

/// Runs every configuration of `plan` on `problem`.
pub fn measure(problem: &impl TestRay, plan: &Plan) -> Report {
    let mut points = Vec::new();
    let mut failures = Vec::new();
    for (method, parameter) in plan.methods() {
        match measure_one(problem, plan, method) {
            Ok((endpoint_error_m, time_s, c)) => points.push(Point {
                method: method.name(),
                parameter,
                endpoint_error_m,
                time_s,
                steps: c.accepted,
                rhs_evals: c.rhs_evals,
            }),
            Err(e) => failures.push(format!("{} {parameter:e}: {e}", method.name())),
        }
    }
    let speedups = speedups(&points);
    Report { ray: problem.describe(), title: problem.title(), project: plan.project, points, failures, speedups }
}

/// Endpoint error, median time and counters of one configuration.
fn measure_one(
    problem: &impl TestRay,
    plan: &Plan,
    method: Method,
) -> std::result::Result<(f64, f64, crate::ode::Counters), OdeError> {
    let field = |p: DVec3| problem.n_grad(p);
    let (p0, d0) = problem.start();
    let once = || -> std::result::Result<(OdeState, crate::ode::Counters), OdeError> {
        let mut ode = Integrator::new(method)?.with_projection(plan.project).with_max_steps(u64::MAX);
        let mut state = OdeState::launch(&field, p0, d0)?;
        ode.integrate_to(&field, &mut state, problem.length_m())?;
        Ok((std::hint::black_box(state), ode.counters()))
    };
    let (end, counters) = once()?;
    let error = (end.y.r - problem.end()).length();
    let t_once = time(1, || {
        let _ = once();
    });
    let reps = ((plan.min_sample_s / t_once.max(1e-9)).ceil() as usize).clamp(1, 10_000_000);
    let mut samples: Vec<f64> = (0..plan.samples.max(1))
        .map(|_| {
            time(reps, || {
                let _ = once();
            })
        })
        .collect();
    samples.sort_by(f64::total_cmp);
    Ok((error, samples[samples.len() / 2], counters))
}

/// Mean seconds per call of `f` over `reps` calls.
fn time(reps: usize, mut f: impl FnMut()) -> f64 {
    let start = Instant::now();
    for _ in 0..reps {
        f();
    }
    start.elapsed().as_secs_f64() / reps as f64
}

/// The (error, time) Pareto front of `method`'s points, by increasing time and strictly
/// decreasing error.
pub fn pareto(points: &[Point], method: &str) -> Vec<(f64, f64)> {
    pareto_by(points, method, |p| p.time_s)
}

/// The (error, cost) Pareto front of `method`'s points for any positive cost.
pub fn pareto_by(points: &[Point], method: &str, cost: impl Fn(&Point) -> f64) -> Vec<(f64, f64)> {
    let mut p: Vec<(f64, f64)> = points
        .iter()
        .filter(|p| p.method == method && p.endpoint_error_m > 0.0 && p.endpoint_error_m.is_finite() && cost(p) > 0.0)
        .map(|p| (p.endpoint_error_m, cost(p)))
        .collect();
    p.sort_by(|a, b| a.1.total_cmp(&b.1));
    let mut front: Vec<(f64, f64)> = Vec::new();
    for q in p {
        if front.last().is_none_or(|l| q.0 < l.0) {
            front.push(q);
        }
    }
    front
}

/// Time at `error` on a Pareto front, interpolating log t linearly in log error; `None`
/// outside the front's error range.
pub fn time_at(front: &[(f64, f64)], error: f64) -> Option<f64> {
    front.windows(2).find_map(|w| {
        let ((e0, t0), (e1, t1)) = (w[0], w[1]);
        if error > e0 || error < e1 {
            return None;
        }
        let f = if e0 == e1 { 0.0 } else { (error.ln() - e0.ln()) / (e1.ln() - e0.ln()) };
        Some((t0.ln() + f * (t1.ln() - t0.ln())).exp())
    })
}

/// DP's speedup over Euler and RK4 at every decade of error inside DP's front and the other's.
pub fn speedups(points: &[Point]) -> Vec<Speedup> {
    let fronts = |cost: fn(&Point) -> f64| ["dopri5", "euler", "rk4"].map(|m| pareto_by(points, m, cost));
    let [dp, euler, rk4] = fronts(|p| p.time_s);
    let [dp_n, euler_n, rk4_n] = fronts(|p| p.rhs_evals as f64);
    let ratio = |other: &[(f64, f64)], ours: &[(f64, f64)], e: f64| Some(time_at(other, e)? / time_at(ours, e)?);
    let Some((loosest, finest)) = dp.first().zip(dp.last()) else {
        return Vec::new();
    };
    ((finest.0.log10().ceil() as i32)..=(loosest.0.log10().floor() as i32))
        .map(|d| 10f64.powi(d))
        .map(|e| Speedup {
            error_m: e,
            over_euler: ratio(&euler, &dp, e),
            over_rk4: ratio(&rk4, &dp, e),
            evals_over_euler: ratio(&euler_n, &dp_n, e),
            evals_over_rk4: ratio(&rk4_n, &dp_n, e),
        })
        .filter(|s| s.over_euler.is_some() || s.over_rk4.is_some())
        .collect()
}

/// Writes the points as CSV (atomically).
pub fn write_csv(report: &Report, path: &Path) -> Result<()> {
    let mut text = String::from("method,parameter,endpoint_error_m,time_s,steps,rhs_evals\n");
    for p in &report.points {
        let _ = writeln!(
            text,
            "{},{:e},{:e},{:e},{},{}",
            p.method, p.parameter, p.endpoint_error_m, p.time_s, p.steps, p.rhs_evals
        );
    }
    write_atomically(path, |tmp| std::fs::write(tmp, &text))
}

/// Writes through a staged temporary file, renamed into place when complete.
pub fn write_atomically(path: &Path, write: impl FnOnce(&Path) -> std::io::Result<()>) -> Result<()> {
    let fail = |e: std::io::Error| Error::internal(format!("cannot write {}: {e}", path.display()));
    let staged = Staged::new(path).map_err(fail)?;
    write(&staged.temp).map_err(fail)?;
    staged.commit().map_err(fail)
}

/// A text report: the table of points, the speedups and whether the goals are met.
pub fn summary(report: &Report) -> String {
    let mut s =
        format!("{}{}\n", report.ray, if report.project { "; |v| projected onto n after each step" } else { "" });
    let _ = writeln!(
        s,
        "{:<7} {:>10} {:>14} {:>12} {:>9} {:>10}",
        "method", "parameter", "error_m", "time_s", "steps", "rhs_evals"
    );
    for q in &report.points {
        let _ = writeln!(
            s,
            "{:<7} {:>10.1e} {:>14.3e} {:>12.3e} {:>9} {:>10}",
            q.method, q.parameter, q.endpoint_error_m, q.time_s, q.steps, q.rhs_evals
        );
    }
    for f in &report.failures {
        let _ = writeln!(s, "failed: {f}");
    }
    s.push_str(&speedup_summary(&report.speedups));
    s
}

fn speedup_summary(speedups: &[Speedup]) -> String {
    let mut s = String::from("speedup of dopri5 at equal endpoint error: time ratio (field-sample ratio)\n");
    let show = |x: Option<f64>, n: Option<f64>| match (x, n) {
        (Some(x), Some(n)) => format!("{x:.1}x ({n:.1}x)"),
        (Some(x), None) => format!("{x:.1}x"),
        _ => "-".to_string(),
    };
    for q in speedups {
        let _ = writeln!(
            s,
            "  error {:>8.0e} m: over euler {:>20}, over rk4 {:>14}",
            q.error_m,
            show(q.over_euler, q.evals_over_euler),
            show(q.over_rk4, q.evals_over_rk4)
        );
    }
    let euler: Vec<(f64, f64)> = speedups.iter().filter_map(|q| Some((q.error_m, q.over_euler?))).collect();
    let rk4: Vec<(f64, f64)> = speedups.iter().filter_map(|q| Some((q.error_m, q.over_rk4?))).collect();
    let rk4_n: Vec<(f64, f64)> = speedups.iter().filter_map(|q| Some((q.error_m, q.evals_over_rk4?))).collect();
    s.push_str(&goal_line("euler", "in time", GOAL_OVER_EULER, &euler));
    s.push_str(&goal_line("rk4", "in time", GOAL_OVER_RK4, &rk4));
    s.push_str(&goal_line("rk4", "in field samples", GOAL_OVER_RK4, &rk4_n));
    s
}

/// "goal dopri5 >= G x over M: met/not met ..." with the range of errors where it holds.
fn goal_line(name: &str, unit: &str, goal: f64, ratios: &[(f64, f64)]) -> String {
    if ratios.is_empty() {
        return format!("goal dopri5 >= {goal}x faster than {name} {unit}: not measured (no common error range)\n");
    }
    let min = ratios.iter().map(|r| r.1).fold(f64::INFINITY, f64::min);
    let max = ratios.iter().map(|r| r.1).fold(0.0, f64::max);
    let met: Vec<f64> = ratios.iter().filter(|r| r.1 >= goal).map(|r| r.0).collect();
    let verdict = if met.len() == ratios.len() {
        "MET at every common error".to_string()
    } else if met.is_empty() {
        "NOT MET at any common error".to_string()
    } else {
        let lo = met.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = met.iter().copied().fold(0.0, f64::max);
        format!("met at {}/{} common errors ({lo:.0e}..{hi:.0e} m)", met.len(), ratios.len())
    };
    format!("goal dopri5 >= {goal}x faster than {name} {unit}: {verdict}; speedup {min:.1}x..{max:.1}x\n")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(method: &'static str, e: f64, t: f64) -> Point {
        Point { method, parameter: 0.0, endpoint_error_m: e, time_s: t, steps: 0, rhs_evals: 0 }
    }

    /// On power laws t = c·e^(−p), log-log interpolation is exact, so the speedup of
    /// t = 1e-6·e^(−0.2) over t = 1e-3·e^(−1) at e is 1e3·e^(−0.8).
    #[test]
    fn speedup_of_power_laws_is_exact() {
        let mut pts = Vec::new();
        for d in 1..=9 {
            let e = 10f64.powi(-d);
            pts.push(point("dopri5", e, 1e-6 * e.powf(-0.2)));
            pts.push(point("euler", e * 3.0, 1e-3 * (e * 3.0).powf(-1.0)));
        }
        // A dominated point (slower and less accurate) must not bend the front.
        pts.push(point("euler", 0.5, 10.0));
        let s = speedups(&pts);
        assert!(!s.is_empty());
        for q in &s {
            let expected = 1e3 * q.error_m.powf(-0.8);
            let got = q.over_euler.unwrap();
            assert!((got / expected - 1.0).abs() < 1e-9, "at {}: {got} vs {expected}", q.error_m);
            assert!(q.over_rk4.is_none());
        }
        assert_eq!(time_at(&pareto(&pts, "dopri5"), 1.0), None, "outside the front");
    }

    #[test]
    fn closed_form_matches_the_catenary_in_x() {
        // y = (cosh(k x) − 1)/k on the curve.
        let p = Problem::new(1e-3, 1000.0).unwrap();
        let r = p.exact(1000.0);
        assert!(((p.k_per_m * r.x).cosh() - 1.0 - p.k_per_m * r.y).abs() < 1e-12);
        assert!(Problem::new(0.0, 1.0).is_err() && Problem::new(1e-3, -1.0).is_err());
    }
}
