//! Rays in n = n0 + a·y against the closed-form catenary (derived in `ode_common::catenary`):
//! Dormand–Prince error falls in proportion to the tolerance, RK4 converges as h⁴, Euler as h.
//! The orders are the textbook ones (Hairer, Nørsett & Wanner, *Solving ODEs I*, §II.1–4:
//! "tolerance proportionality" of error-per-step control with local extrapolation, and the
//! orders 4 and 1).

mod ode_common;

use glam::DVec3;
use morgana::ode::{Method, OdeState};
use ode_common::{catenary, launch_at, linear, log_slope, run};

const N0: f64 = 1.0;
const S_END: f64 = 20.0;

/// Endpoint error |r(s_end) − r_exact| (m), the integrator's counters.
fn endpoint_error(method: Method, a: f64, theta0: f64, project: bool) -> (f64, u64, u64) {
    let field = linear(N0, a);
    let start = launch_at(&field, DVec3::ZERO, theta0);
    let (end, _, ode) = run_with(method, &field, start, project);
    let (r, _) = catenary(N0, a, theta0, S_END);
    ((end.y.r - r).length(), ode.counters().accepted, ode.counters().rhs_evals)
}

fn run_with<F: Fn(DVec3) -> (f64, DVec3)>(
    method: Method,
    field: &F,
    start: OdeState,
    project: bool,
) -> (OdeState, usize, morgana::ode::Integrator) {
    if !project {
        let (end, steps, ode) = run(method, field, start, S_END);
        return (end, steps.len(), ode);
    }
    let mut ode = morgana::ode::Integrator::new(method).unwrap().with_projection(true);
    let mut state = start;
    ode.integrate_to(field, &mut state, S_END).unwrap();
    (state, ode.counters().accepted as usize, ode)
}

#[test]
fn dormand_prince_error_is_proportional_to_tolerance() {
    for a in [0.1, -0.1] {
        let mut points = Vec::new();
        let mut last = f64::INFINITY;
        for tol in [1e-4, 1e-6, 1e-8, 1e-10] {
            let (err, steps, evals) = endpoint_error(Method::dormand_prince(tol, tol), a, 0.0, false);
            eprintln!("a = {a}: tol {tol:e}: error {err:.3e} m, {steps} steps, {evals} evals");
            assert!(err < last, "error must shrink with the tolerance");
            last = err;
            points.push((tol, err));
        }
        let slope = log_slope(&points);
        eprintln!("a = {a}: d log(err) / d log(tol) = {slope:.3}");
        assert!((slope - 1.0).abs() < 0.3, "slope {slope}");
    }
}

#[test]
fn rk4_converges_as_h_to_the_fourth() {
    let (e1, ..) = endpoint_error(Method::Rk4 { h_m: 0.2 }, 0.1, 0.0, false);
    let (e2, ..) = endpoint_error(Method::Rk4 { h_m: 0.1 }, 0.1, 0.0, false);
    let order = (e1 / e2).log2();
    eprintln!("rk4: h 0.2 → {e1:.3e} m, h 0.1 → {e2:.3e} m, order {order:.3}");
    assert!((order - 4.0).abs() < 0.3, "order {order}");
}

#[test]
fn euler_converges_as_h() {
    let (e1, ..) = endpoint_error(Method::Euler { h_m: 2e-3 }, 0.1, 0.0, false);
    let (e2, ..) = endpoint_error(Method::Euler { h_m: 1e-3 }, 0.1, 0.0, false);
    let order = (e1 / e2).log2();
    eprintln!("euler: h 2e-3 → {e1:.3e} m, h 1e-3 → {e2:.3e} m, order {order:.3}");
    assert!((order - 1.0).abs() < 0.3, "order {order}");
}

/// The general catenary, launched 30° up into increasing n and 20° down into decreasing n.
#[test]
fn launch_at_an_angle() {
    for (a, theta0) in [(0.1, 30f64.to_radians()), (-0.05, -20f64.to_radians())] {
        let mut points = Vec::new();
        for tol in [1e-6, 1e-8, 1e-10] {
            let (err, steps, _) = endpoint_error(Method::dormand_prince(tol, tol), a, theta0, false);
            eprintln!("a = {a}, θ0 = {:.0}°: tol {tol:e}: error {err:.3e} m, {steps} steps", theta0.to_degrees());
            points.push((tol, err));
        }
        let slope = log_slope(&points);
        assert!((slope - 1.0).abs() < 0.3, "slope {slope}");
        let (e1, ..) = endpoint_error(Method::Rk4 { h_m: 0.2 }, a, theta0, false);
        let (e2, ..) = endpoint_error(Method::Rk4 { h_m: 0.1 }, a, theta0, false);
        assert!(((e1 / e2).log2() - 4.0).abs() < 0.3, "rk4 order {}", (e1 / e2).log2());
    }
}

/// The projection |v| ← n(r) keeps the invariant exactly; its effect on the endpoint error is
/// printed (in a linear field v(s) is linear in s, so every Runge–Kutta method integrates v
/// exactly and the projection can only move v by the position error).
#[test]
fn projection_keeps_the_invariant() {
    let field = linear(N0, 0.1);
    let methods = [
        Method::dormand_prince(1e-6, 1e-6),
        Method::dormand_prince(1e-9, 1e-9),
        Method::Rk4 { h_m: 0.2 },
        Method::Euler { h_m: 1e-3 },
    ];
    for method in methods {
        for theta0 in [0.0, 30f64.to_radians()] {
            let start = launch_at(&field, DVec3::ZERO, theta0);
            let (plain, _, _) = run_with(method, &field, start, false);
            let (proj, _, _) = run_with(method, &field, start, true);
            let (r, _) = catenary(N0, 0.1, theta0, S_END);
            let drift = |y: &OdeState| (y.y.v.length() - field(y.y.r).0).abs();
            eprintln!(
                "{} θ0 {:.0}°: error {:.3e} m plain, {:.3e} m projected; ||v| − n| {:.1e} plain, {:.1e} projected",
                method.name(),
                theta0.to_degrees(),
                (plain.y.r - r).length(),
                (proj.y.r - r).length(),
                drift(&plain),
                drift(&proj)
            );
            assert!(drift(&proj) <= 4.0 * f64::EPSILON * field(proj.y.r).0, "{}", drift(&proj));
        }
    }
}
