//! morgana's Dormand–Prince against an independent implementation of the same method,
//! ode_solvers 0.6.2 `Dopri5` (Hairer's DOPRI5 transcribed, PI control β = 0.04, Hairer's
//! starting step), on the same ray system with the same tolerances. Its Sparse output is used:
//! its Dense output is wrong at the end point (see ../shared/NOTES.md).
//!
//! Expected: both meet the tolerance against the closed-form catenary to the same degree, they
//! agree with each other to the size of that error, and take about as many steps (the step
//! sequences differ only through the last, cut step and the starting-step arithmetic).

mod ode_common;

use glam::DVec3;
use morgana::ode::{Method, RayY};
use ode_common::{catenary, launch_at, linear, run, tanh_layer};
use ode_solvers::{Dopri5, OutputType, System, Vector6};

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

fn theirs<F: Fn(DVec3) -> (f64, DVec3)>(field: F, y0: RayY, s_end: f64, tol: f64) -> (RayY, u32, u32) {
    let y = Vector6::new(y0.r.x, y0.r.y, y0.r.z, y0.v.x, y0.v.y, y0.v.z);
    let mut solver = Dopri5::new(Ray(field), 0.0, s_end, s_end, y, tol, tol);
    solver.set_output(OutputType::Sparse);
    let stats = solver.integrate().expect("ode_solvers integrates");
    let e = solver.y_out().last().expect("a final state");
    (
        RayY { r: DVec3::new(e[0], e[1], e[2]), v: DVec3::new(e[3], e[4], e[5]) },
        stats.accepted_steps,
        stats.rejected_steps,
    )
}

#[test]
fn agrees_with_ode_solvers_on_the_catenary() {
    let (a, theta0, s_end) = (0.1, 20f64.to_radians(), 20.0);
    let field = linear(1.0, a);
    let (exact, _) = catenary(1.0, a, theta0, s_end);
    for tol in [1e-5, 1e-7, 1e-9, 1e-11] {
        let start = launch_at(&field, DVec3::ZERO, theta0);
        let (ours, steps, ode) = run(Method::dormand_prince(tol, tol), &field, start, s_end);
        let (ref_y, ref_acc, ref_rej) = theirs(field, start.y, s_end, tol);
        let (e_ours, e_ref) = ((ours.y.r - exact).length(), (ref_y.r - exact).length());
        let diff = (ours.y.r - ref_y.r).length();
        eprintln!(
            "tol {tol:e}: error ours {e_ours:.3e} m, ode_solvers {e_ref:.3e} m, |ours − theirs| {diff:.3e} m; \
             steps {}+{} vs {ref_acc}+{ref_rej}",
            steps.len(),
            ode.counters().rejected
        );
        assert!(e_ours <= 3.0 * e_ref.max(tol) && e_ref <= 3.0 * e_ours.max(tol), "errors of one size");
        assert!(diff <= 3.0 * e_ours.max(e_ref).max(tol), "agree to the error size");
        let (n_ours, n_ref) = (steps.len() as f64, ref_acc as f64);
        assert!((n_ours - n_ref).abs() <= 2.0 + 0.1 * n_ref, "similar step counts: {n_ours} vs {n_ref}");
    }
}

/// A nonlinear field (a 2 cm tanh layer, total internal reflection) where the steps must
/// shrink and grow again: the two codes still agree.
#[test]
fn agrees_with_ode_solvers_through_a_reflecting_layer() {
    let field = tanh_layer(1.33, 1.0, 0.01);
    let start = launch_at(&field, DVec3::new(0.0, -0.2, 0.0), 30f64.to_radians());
    for tol in [1e-6, 1e-9] {
        let (ours, steps, ode) = run(Method::dormand_prince(tol, tol), &field, start, 1.0);
        let (ref_y, ref_acc, ref_rej) = theirs(field, start.y, 1.0, tol);
        let diff = (ours.y.r - ref_y.r).length();
        eprintln!(
            "layer tol {tol:e}: |ours − theirs| {diff:.3e} m; steps {}+{} vs {ref_acc}+{ref_rej}",
            steps.len(),
            ode.counters().rejected
        );
        assert!(diff <= 100.0 * tol, "{diff}");
        let (n_ours, n_ref) = (steps.len() as f64, ref_acc as f64);
        assert!((n_ours - n_ref).abs() <= 2.0 + 0.1 * n_ref, "similar step counts: {n_ours} vs {n_ref}");
    }
}

/// PI control (Hairer's β = 0.04, the default) and plain I control reach the same accuracy;
/// the step counts of both are printed for the record, and h_max and a given h0 are obeyed.
#[test]
fn pi_and_i_control_and_step_bounds() {
    let field = linear(1.0, 0.1);
    let (exact, _) = catenary(1.0, 0.1, 0.0, 20.0);
    for tol in [1e-6, 1e-9, 1e-12] {
        let mut errors = Vec::new();
        for pi in [true, false] {
            let m = Method::DormandPrince { rtol: tol, atol: tol, pi, h0: None, h_min: 0.0, h_max: f64::INFINITY };
            let (end, steps, ode) = run(m, &field, launch_at(&field, DVec3::ZERO, 0.0), 20.0);
            let e = (end.y.r - exact).length();
            eprintln!(
                "tol {tol:e} pi {pi}: error {e:.3e} m, {} accepted, {} rejected",
                steps.len(),
                ode.counters().rejected
            );
            errors.push(e);
        }
        assert!(errors[0] <= 3.0 * errors[1] && errors[1] <= 3.0 * errors[0], "{errors:?}");
    }
    let m = Method::DormandPrince { rtol: 1e-9, atol: 1e-9, pi: true, h0: Some(5.0), h_min: 0.0, h_max: 0.5 };
    let (_, steps, _) = run(m, &field, launch_at(&field, DVec3::ZERO, 0.0), 20.0);
    assert!(steps.iter().all(|s| s.h() <= 0.5), "h_max");
    assert!(steps.len() >= 40);
    let m = Method::DormandPrince { rtol: 1e-3, atol: 1e-3, pi: true, h0: Some(1e-3), h_min: 0.0, h_max: 1.0 };
    let (_, steps, _) = run(m, &field, launch_at(&field, DVec3::ZERO, 0.0), 20.0);
    assert_eq!(steps[0].h(), 1e-3, "the given first step");
}
