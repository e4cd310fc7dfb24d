//! Curved-ray throughput: morgana's Dormand–Prince against two Rust peers, on identical fields
//! and at matched endpoint accuracy.
//!
//! `cargo bench --bench raypath` (add `-- --quick` for a short criterion run; a filter that
//! matches no group, e.g. `-- none`, prints only the tables). After the criterion groups it
//! prints tables of medians (own timing loop: 5–7 samples of at least 50 ms each; set
//! `RAYPATH_BENCH_MIN=1` to print the fastest sample instead, steadier on a busy machine) with
//! the endpoint errors and the ratios. For profiling, `RAYPATH_PROFILE=morgana` (or
//! `ode_solvers`) with `RAYPATH_PROFILE_N=300000` runs only that many catenary rays.
//!
//! 1. **ode_solvers 0.6.2 `Dopri5`** (the same method, Hairer's DOPRI5 transcribed): the ray in
//!    n = 1 + 10⁻³·y over 1 km launched along +x (the `morgana accuracy` problem), both at
//!    rtol = atol = 10⁻⁹ (the paper's tolerance) with PI control; endpoint errors against the
//!    closed-form catenary are printed for both. Goal (issue 18): morgana ≥ 3× faster.
//! 2. **atm-refraction 0.6.1** (fixed-step RK4 in the ground distance x, in polar coordinates
//!    h(x) on a sphere of radius 6371 km, with its own US-1976 atmosphere and Edlén index at
//!    530 nm): morgana integrates the 3-D ray equation with atm-refraction's own n(h) and dn/dh
//!    as the field (∇n = dn/dh·r̂), on the same sphere. Ray: from 10 m at +0.5° elevation to a
//!    ground distance of 100 km. Both stop at the same place (morgana finds the polar angle
//!    x/R on its last step by dense output); "same accuracy" means the same error in the end
//!    height h(100 km) against a reference solution (morgana at tolerance 10⁻¹³, cross-checked
//!    against atm-refraction with a 1 m step). atm-refraction is run with its default step
//!    (5 m, what its `h_at_dist` uses) and coarser ones; morgana over tolerances; the time
//!    ratio is read at equal error by log-log interpolation along each method's
//!    error-vs-time points. Goal (issue 18): morgana ≥ 10× atm-refraction over the range of errors
//!    both reach. morgana's end is located on the dense output (Newton's method, a few
//!    iterations) and its height taken without cancelling 6 371 km coordinates.
//!    In air whose index depends on height alone morgana has a second way to the same answer:
//!    Bouguer's invariant turns the path into one integral over height
//!    (`morgana::atmosphere::refraction::terrestrial`, what `morgana refraction
//!    --ground-distances-km` uses), given the same n(h) and dn/dh as a closure; its rows are
//!    timed over angle tolerances and compared the same way.

use atm_refraction::{EarthShape, Environment, air::us76_atmosphere};
use criterion::{BenchmarkId, Criterion};
use glam::DVec3;
use morgana::atmosphere::refraction::terrestrial::{RadialAir, RadialIndex, Reach, follow};
use morgana::ode::accuracy::{Point, pareto, time_at};
use morgana::ode::{Counters, Integrator, Method, OdeError, OdeState, Step};
use ode_solvers::{Dopri5, OutputType, System, Vector6};
use std::hint::black_box;
use std::time::Instant;

const K: f64 = 1e-3;
const LENGTH: f64 = 1000.0;
const TOL: f64 = 1e-9;
const RADIUS: f64 = 6_371_000.0;
const H0: f64 = 10.0;
const ELEVATION_DEG: f64 = 0.5;
const DISTANCE: f64 = 100_000.0;

fn linear(p: DVec3) -> (f64, DVec3) {
    (1.0 + K * p.y, DVec3::new(0.0, K, 0.0))
}

/// The catenary endpoint (see `morgana::raypath::accuracy`).
fn exact_end() -> DVec3 {
    let ks = K * LENGTH;
    DVec3::new(ks.asinh() / K, K * LENGTH * LENGTH / (1.0 + (1.0 + ks * ks).sqrt()), 0.0)
}

fn morgana_catenary(tol: f64) -> Result<(OdeState, Counters), OdeError> {
    let mut ode = Integrator::new(Method::dormand_prince(tol, tol))?;
    let mut state = OdeState::launch(&linear, DVec3::ZERO, DVec3::X)?;
    ode.integrate_to(&linear, &mut state, LENGTH)?;
    Ok((state, ode.counters()))
}

struct Ray<F>(F);

impl<F: Fn(DVec3) -> (f64, DVec3)> System<f64, Vector6<f64>> for Ray<F> {
    fn system(&self, _s: f64, y: &Vector6<f64>, dy: &mut Vector6<f64>) {
        let (n, g) = (self.0)(DVec3::new(y[0], y[1], y[2]));
        dy[0] = y[3] / n;
        dy[1] = y[4] / n;
        dy[2] = y[5] / n;
        dy[3] = g.x;
        dy[4] = g.y;
        dy[5] = g.z;
    }
}

/// ode_solvers' endpoint and its (accepted, rejected, field samples).
fn ode_solvers_catenary(tol: f64) -> (DVec3, [u64; 3]) {
    let y = Vector6::new(0.0, 0.0, 0.0, 1.0, 0.0, 0.0);
    let mut solver = Dopri5::new(Ray(linear), 0.0, LENGTH, LENGTH, y, tol, tol);
    solver.set_output(OutputType::Sparse);
    let stats = solver.integrate().expect("ode_solvers integrates");
    let e = solver.y_out().last().expect("a final state");
    let work = [stats.accepted_steps, stats.rejected_steps, stats.num_eval].map(u64::from);
    (DVec3::new(e[0], e[1], e[2]), work)
}

fn environment() -> Environment {
    Environment { shape: EarthShape::Spherical { radius: RADIUS }, atmosphere: us76_atmosphere(), wavelength: 530e-9 }
}

/// atm-refraction's end height at DISTANCE with RK4 step `step` (m of ground distance).
fn atm_height(env: &Environment, step: f64) -> f64 {
    let mut stepper = env.cast_ray_stepper(H0, ELEVATION_DEG.to_radians(), false);
    stepper.set_step_size(step);
    let n = (DISTANCE / step).round() as usize;
    let mut last = None;
    for _ in 0..n {
        last = stepper.next();
    }
    last.map_or(f64::NAN, |s| s.h)
}

/// morgana's end height at DISTANCE through atm-refraction's n(h), at tolerance `tol`, and
/// the number of field samples. The frame is a scene's: origin at the launch point, y up, the
/// Earth's centre at (0, −(R + h0), 0).
fn morgana_height(env: &Environment, tol: f64) -> Result<(f64, u64), OdeError> {
    let centre = DVec3::new(0.0, -(RADIUS + H0), 0.0);
    let field = |p: DVec3| {
        let r = p - centre;
        let len = r.length();
        let h = len - RADIUS;
        (env.n(h), r * (env.dn(h) / len))
    };
    let e = ELEVATION_DEG.to_radians();
    let mut state = OdeState::launch(&field, DVec3::ZERO, DVec3::new(e.cos(), e.sin(), 0.0))?;
    let mut ode = Integrator::new(Method::dormand_prince(tol, tol))?;
    let phi_end = DISTANCE / RADIUS;
    loop {
        let step = ode.step(&field, &mut state, f64::INFINITY)?;
        if polar_angle(step.y1().r) >= phi_end {
            let p = step.position_at(crossing(&step, phi_end));
            return Ok((height(p), ode.counters().rhs_evals));
        }
    }
}

/// atm-refraction's n(h) as morgana's radial index: the quadrature's nodes ask for n alone
/// (`Environment::n`), the perigee and the start for dn/dh as well (`Environment::dn`).
struct AtmIndex<'a>(&'a Environment);

impl RadialIndex for AtmIndex<'_> {
    fn refractivity(&self, h_m: f64) -> f64 {
        self.0.n(h_m) - 1.0
    }
    fn refractivity_slope(&self, h_m: f64) -> (f64, f64) {
        (self.0.n(h_m) - 1.0, self.0.dn(h_m))
    }
}

/// The end height at DISTANCE by Bouguer's quadrature through atm-refraction's n(h), the angle
/// integrals to `tol` rad, and the number of field samples (its layer boundaries as kinks).
fn bouguer_height(env: &Environment, tol: f64) -> (f64, u64) {
    let air = RadialAir {
        refractivity: AtmIndex(env),
        kink_heights_m: vec![11e3, 20e3, 32e3, 47e3, 51e3, 71e3, 84.852e3],
        ground_radius_m: RADIUS,
        top_m: 86e3,
    };
    match follow(&air, H0, ELEVATION_DEG.to_radians(), DISTANCE / RADIUS, tol) {
        Ok(p) => match p.reach {
            Reach::Aloft { height_m, .. } => (height_m, p.evaluations),
            Reach::Ground { .. } | Reach::Away { .. } => (f64::NAN, p.evaluations),
        },
        Err(_) => (f64::NAN, 0),
    }
}

/// The polar angle x/R at the Earth's centre of a point in the launch frame.
fn polar_angle(p: DVec3) -> f64 {
    p.x.atan2(p.y + RADIUS + H0)
}

/// Height above the sphere of a point in the launch frame, written so that no 6 371 km
/// coordinates cancel: |q|² − R² = x² + z² + u(u + 2R) with u = y + h0, over |q| + R (the plain
/// |q| − R rounds at ulp(6.4·10⁶ m) ≈ 10⁻⁹ m, which floored the errors measured here before).
fn height(p: DVec3) -> f64 {
    let u = p.y + H0;
    let excess = p.x * p.x + p.z * p.z + u * (u + 2.0 * RADIUS);
    let q = DVec3::new(p.x, p.y + RADIUS + H0, p.z).length();
    excess / (q + RADIUS)
}

/// θ in `step` where the polar angle reaches `target` (increasing along the step): Newton's
/// method on the dense output, with dφ/dθ = h·(Y·dₓ − x·d_y)/(x² + Y²) (Y = y + R + h₀, d the
/// direction there), from the linear guess, until θ moves by less than 10⁻¹³ m of path.
fn crossing(step: &Step, target: f64) -> f64 {
    let (phi0, phi1) = (polar_angle(step.y0().r), polar_angle(step.y1().r));
    let mut theta = ((target - phi0) / (phi1 - phi0)).clamp(0.0, 1.0);
    for _ in 0..20 {
        let (p, d) = (step.position_at(theta), step.direction_at(theta));
        let y = p.y + RADIUS + H0;
        let slope = step.h() * (y * d.x - p.x * d.y) / (p.x * p.x + y * y);
        let next = (theta - (polar_angle(p) - target) / slope).clamp(0.0, 1.0);
        let moved = (next - theta).abs() * step.h();
        theta = next;
        if moved < 1e-13 {
            break;
        }
    }
    theta
}

/// Median seconds per call over `samples` samples of at least `min_s` each.
fn median_time(samples: usize, min_s: f64, mut f: impl FnMut()) -> f64 {
    let t0 = Instant::now();
    f();
    let once = t0.elapsed().as_secs_f64().max(1e-9);
    let reps = ((min_s / once).ceil() as usize).max(1);
    let mut t: Vec<f64> = (0..samples)
        .map(|_| {
            let s = Instant::now();
            for _ in 0..reps {
                f();
            }
            s.elapsed().as_secs_f64() / reps as f64
        })
        .collect();
    t.sort_by(f64::total_cmp);
    if std::env::var_os("RAYPATH_BENCH_MIN").is_some() { t[0] } else { t[samples / 2] }
}

fn criterion_groups(c: &mut Criterion) {
    let mut g = c.benchmark_group("curved_ray_catenary_1km");
    g.bench_function(BenchmarkId::new("morgana_dopri5", TOL), |b| b.iter(|| morgana_catenary(black_box(TOL))));
    g.bench_function(BenchmarkId::new("ode_solvers_dopri5", TOL), |b| b.iter(|| ode_solvers_catenary(black_box(TOL))));
    g.finish();
    let env = environment();
    let mut g = c.benchmark_group("atmosphere_ray_100km");
    g.sample_size(20);
    g.bench_function(BenchmarkId::new("morgana_dopri5", 1e-9), |b| b.iter(|| morgana_height(&env, black_box(1e-9))));
    g.bench_function(BenchmarkId::new("atm_refraction_rk4_step_m", 5), |b| b.iter(|| atm_height(&env, black_box(5.0))));
    g.finish();
}

fn point(method: &'static str, parameter: f64, error: f64, time_s: f64) -> Point {
    Point { method, parameter, endpoint_error_m: error, time_s, steps: 0, rhs_evals: 0 }
}

fn summary_catenary() {
    let exact = exact_end();
    let (ours, our_work) = match morgana_catenary(TOL) {
        Ok((s, c)) => (s.y.r, [c.accepted, c.rejected, c.rhs_evals]),
        Err(_) => (DVec3::NAN, [0; 3]),
    };
    let (theirs, their_work) = ode_solvers_catenary(TOL);
    let t_ours = median_time(7, 0.05, || {
        let _ = black_box(morgana_catenary(black_box(TOL)));
    });
    let t_theirs = median_time(7, 0.05, || {
        black_box(ode_solvers_catenary(black_box(TOL)));
    });
    println!("\ncatenary n = 1 + 1e-3 y, 1 km, rtol = atol = {TOL:e}:");
    println!("  {:<22} {:>12} {:>14}  accepted/rejected/samples", "", "median", "endpoint error");
    let [a, r, n] = our_work;
    println!("  {:<22} {:>9.3} µs {:>12.3e} m  {a}/{r}/{n}", "morgana dopri5", t_ours * 1e6, (ours - exact).length());
    let [a, r, n] = their_work;
    println!(
        "  {:<22} {:>9.3} µs {:>12.3e} m  {a}/{r}/{n}",
        "ode_solvers Dopri5",
        t_theirs * 1e6,
        (theirs - exact).length()
    );
    let ratio = t_theirs / t_ours;
    println!("  morgana is {ratio:.2}x faster (goal >= 3x: {})", if ratio >= 3.0 { "met" } else { "NOT met" });
}

fn summary_atmosphere() {
    let env = environment();
    let reference = atm_height(&env, 10.0);
    let check = morgana_height(&env, 1e-13).map(|r| r.0).unwrap_or(f64::NAN);
    println!("\natmosphere ray (US-1976 via atm-refraction, 530 nm) from {H0} m at +{ELEVATION_DEG}° to 100 km:");
    println!(
        "  reference end height {reference:.9} m (atm-refraction, 10 m steps); morgana at tol 1e-13: {check:.9} m \
         (differ by {:.1e} m)",
        (check - reference).abs()
    );
    let mut points = Vec::new();
    println!("  {:<30} {:>12} {:>12} {:>8}", "", "median", "|h − h_ref|", "samples");
    for step in [5.0, 100.0, 1000.0, 2000.0, 5000.0, 10000.0, 20000.0, 50000.0] {
        let err = (atm_height(&env, step) - reference).abs();
        let t = median_time(5, 0.05, || {
            black_box(atm_height(&env, black_box(step)));
        });
        let samples = 4 * (DISTANCE / step) as u64;
        println!(
            "  {:<30} {:>9.2} µs {:>10.2e} m {:>8}",
            format!("atm-refraction RK4 {step} m"),
            t * 1e6,
            err,
            samples
        );
        points.push(point("atm", step, err, t));
    }
    for tol in [1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13] {
        let (h, evals) = morgana_height(&env, tol).unwrap_or((f64::NAN, 0));
        let t = median_time(5, 0.05, || {
            let _ = black_box(morgana_height(&env, black_box(tol)));
        });
        let err = (h - reference).abs();
        println!("  {:<30} {:>9.2} µs {:>10.2e} m {:>8}", format!("morgana dopri5 tol {tol:e}"), t * 1e6, err, evals);
        points.push(point("dopri5", tol, err, t));
    }
    for tol in [1e-6, 1e-8, 1e-10, 1e-12, 1e-14] {
        let (h, evals) = bouguer_height(&env, tol);
        let t = median_time(5, 0.05, || {
            black_box(bouguer_height(&env, black_box(tol)));
        });
        let err = (h - reference).abs();
        println!("  {:<30} {:>9.2} µs {:>10.2e} m {:>8}", format!("morgana Bouguer tol {tol:e}"), t * 1e6, err, evals);
        points.push(point("bouguer", tol, err, t));
    }
    for (method, label) in [("dopri5", "morgana dopri5"), ("bouguer", "morgana Bouguer quadrature")] {
        println!("  {label} against atm-refraction at equal error:");
        let (ours, theirs) = (pareto(&points, method), pareto(&points, "atm"));
        for q in points.iter().filter(|p| p.method == "atm") {
            match (our_time_at(&ours, q.endpoint_error_m), time_at(&theirs, q.endpoint_error_m)) {
                (Some((a, bound)), Some(b)) => println!(
                    "    at its error with {} m steps ({:.2e} m): {}{:.2}x faster (goal >= 10x: {}){}",
                    q.parameter,
                    q.endpoint_error_m,
                    if bound { ">= " } else { "" },
                    b / a,
                    if b >= 10.0 * a { "met" } else { "NOT met" },
                    if bound { " — morgana's cheapest point is already more accurate" } else { "" }
                ),
                _ => println!(
                    "    at its error with {} m steps ({:.2e} m): outside the measured range",
                    q.parameter, q.endpoint_error_m
                ),
            }
        }
    }
}

/// morgana's time at `error` on its Pareto front `front`, and whether it is only a bound: where
/// even its cheapest point is more accurate than `error`, that point's time (an upper bound of
/// the time it needs, so the speed ratio is a lower bound).
fn our_time_at(front: &[(f64, f64)], error: f64) -> Option<(f64, bool)> {
    if let Some(t) = time_at(front, error) {
        return Some((t, false));
    }
    front.first().filter(|(e, _)| *e <= error).map(|&(_, t)| (t, true))
}

fn main() {
    if let Ok(which) = std::env::var("RAYPATH_PROFILE") {
        let n: usize = std::env::var("RAYPATH_PROFILE_N").ok().and_then(|v| v.parse().ok()).unwrap_or(300_000);
        for _ in 0..n {
            if which == "morgana" {
                let _ = black_box(morgana_catenary(black_box(TOL)));
            } else {
                black_box(ode_solvers_catenary(black_box(TOL)));
            }
        }
        return;
    }
    let mut c = Criterion::default().configure_from_args();
    criterion_groups(&mut c);
    c.final_summary();
    summary_catenary();
    summary_atmosphere();
}
