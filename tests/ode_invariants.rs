//! Conservation laws of the ray equation, checked along numerical paths.
//!
//! - Layered medium n(y): Bouguer's (Snell's) invariant n(y)·(dx/ds) = n cos θ is constant
//!   (Born & Wolf, *Principles of Optics*, §3.2.1). With the unit direction d = v/|v| it reads
//!   I = n(r)·d_x; its drift measures how far |v| strays from n(r).
//! - Spherically symmetric n(|r|): Bouguer's formula |r|·n·sin ψ = const, ψ the angle between
//!   r and the ray (Born & Wolf §3.2.1, eq. (17)); in vector form L = r × v is constant,
//!   d/ds(r × v) = (v/n) × v + r × n'(r) r̂ = 0. Runge–Kutta methods keep the linear invariant
//!   v_x exactly but not this quadratic one, so its drift measures the integration error.
//!
//! Bound: the error control keeps each step's estimated local error per component below
//! √6·(atol + rtol·|yᵢ|), so after N steps an invariant with sensitivity G to the state drifts
//! by at most about N·√6·G·tol — the "C·tol" of each check, with N and G stated there.

mod ode_common;

use glam::DVec3;
use morgana::ode::{Integrator, Method, OdeState, Step};
use ode_common::{fish_eye, fish_eye_radius, fish_eye_ray, launch_at, tanh_layer};

fn path<F: Fn(DVec3) -> (f64, DVec3)>(
    method: Method,
    project: bool,
    field: &F,
    start: OdeState,
    s_end: f64,
) -> Vec<Step> {
    let mut ode = Integrator::new(method).unwrap().with_projection(project);
    let mut state = start;
    let mut steps = Vec::new();
    while state.s < s_end {
        let left = s_end - state.s;
        let step = ode.step(field, &mut state, left).unwrap_or_else(|e| panic!("{e}"));
        steps.push(step);
        if step.reached_limit {
            break;
        }
    }
    steps
}

/// Through the 1 cm water–air-like layer (n 1.33 → 1.0) at 30° (reflected) and 60°
/// (transmitted), and the 1e-4 mirage layer at grazing incidence: I = n(r)·d_x stays within
/// N·√6·G·tol of its start, with G = 1 + |∇n|max·(path length) (|v| errors enter I directly,
/// position errors through ∇n).
#[test]
fn bouguer_invariant_in_layered_media() {
    let cases = [
        (tanh_layer(1.33, 1.0, 0.01), DVec3::new(0.0, -0.2, 0.0), 30f64.to_radians(), 1.5, 16.5),
        (tanh_layer(1.33, 1.0, 0.01), DVec3::new(0.0, -0.2, 0.0), 60f64.to_radians(), 1.0, 16.5),
        (tanh_layer(1.0, 1.0001, 0.005), DVec3::new(0.0, 0.1, 0.0), -0.01, 30.0, 0.01),
    ];
    for (field, p0, theta, s_end, grad_max) in cases {
        let mut drifts = Vec::new();
        for tol in [1e-6, 1e-9, 1e-12] {
            for project in [false, true] {
                let start = launch_at(&field, p0, theta);
                let invariant = |y: &OdeState| field(y.y.r).0 * y.y.direction().x;
                let i0 = invariant(&start);
                let steps = path(Method::dormand_prince(tol, tol), project, &field, start, s_end);
                let drift = steps.iter().map(|s| (invariant(&s.state_at(1.0)) - i0).abs()).fold(0.0, f64::max);
                let bound = steps.len() as f64 * 6f64.sqrt() * (1.0 + grad_max * s_end) * tol;
                eprintln!(
                    "θ {theta:.3} tol {tol:e} projection {project}: {} steps, Bouguer drift {drift:.2e} (bound {bound:.2e})",
                    steps.len()
                );
                assert!(drift <= bound, "drift {drift} > {bound}");
                drifts.push((tol, project, drift));
            }
        }
        falls_with_tolerance(&drifts);
    }
}

/// Maxwell's fish-eye n = 1.5/(1 + r²), a full circle of the ray (from (0.5, 0, 0) at 53° to
/// the radius): |r × v| and |r|·n(r)·sin ψ stay within N·√6·G·tol, G = 2·(|r|max + n_max)
/// (the sensitivity of r × v to errors in r and v), and the path stays on its closed-form
/// circle.
#[test]
fn bouguer_formula_in_a_spherical_field() {
    let field = fish_eye(1.5, 1.0);
    let (p0, d0) = (DVec3::new(0.5, 0.0, 0.0), DVec3::new(0.6, 0.8, 0.0));
    let s_end = 2.0 * std::f64::consts::PI * fish_eye_radius(1.0, p0, d0);
    let mut drifts = Vec::new();
    for tol in [1e-6, 1e-9, 1e-12] {
        for project in [false, true] {
            let start = launch_at(&field, p0, 0.8f64.atan2(0.6));
            let l0 = start.y.r.cross(start.y.v);
            let bouguer =
                |y: &OdeState| y.y.r.length() * field(y.y.r).0 * y.y.r.normalize().cross(y.y.direction()).length();
            let b0 = bouguer(&start);
            let steps = path(Method::dormand_prince(tol, tol), project, &field, start, s_end);
            let ends: Vec<OdeState> = steps.iter().map(|s| s.state_at(1.0)).collect();
            let l_drift = ends.iter().map(|y| (y.y.r.cross(y.y.v) - l0).length()).fold(0.0, f64::max);
            let b_drift = ends.iter().map(|y| (bouguer(y) - b0).abs()).fold(0.0, f64::max);
            let r_max = ends.iter().map(|y| y.y.r.length()).fold(0.0, f64::max);
            let off_circle = ends.iter().map(|y| (y.y.r - fish_eye_ray(1.0, p0, d0, y.s)).length()).fold(0.0, f64::max);
            let bound = steps.len() as f64 * 6f64.sqrt() * 2.0 * (r_max + 1.5) * tol;
            eprintln!(
                "fish-eye tol {tol:e} projection {project}: {} steps, |Δ(r×v)| {l_drift:.2e}, Δ(r n sinψ) {b_drift:.2e} \
                 (bound {bound:.2e}), off the circle {off_circle:.2e} m",
                steps.len()
            );
            assert!(l_drift <= bound && b_drift <= bound);
            assert!(off_circle <= bound * (1.0 + s_end), "{off_circle}");
            drifts.push((tol, project, l_drift));
        }
    }
    falls_with_tolerance(&drifts);
}

/// Over six decades of tolerance the drift must fall by at least three: a controller that
/// ignored the tolerance would pass the worst-case bounds at loose tolerances but not this.
fn falls_with_tolerance(drifts: &[(f64, bool, f64)]) {
    for project in [false, true] {
        let at = |tol: f64| drifts.iter().find(|d| d.0 == tol && d.1 == project).map(|d| d.2).unwrap();
        assert!(at(1e-12) < at(1e-6) * 1e-3, "projection {project}: {} vs {}", at(1e-12), at(1e-6));
    }
}
