//! Dense output inside a step against closed-form rays. Dormand–Prince's continuous extension
//! is of order 4 (Hairer, Nørsett & Wanner, *Solving ODEs I*, §II.6): from an exact start its
//! error inside one step falls as h⁵. The cubic Hermite interpolant of RK4's end points falls
//! as h⁴ (interpolation error y⁗·θ²(1−θ)²h⁴/4!, Hairer I eq. II.6.7).

mod ode_common;

use glam::DVec3;
use morgana::ode::dense::Dense;
use morgana::ode::system::{RayY, eval};
use morgana::ode::{Method, dopri5, rk4};
use ode_common::{fish_eye, fish_eye_radius, fish_eye_ray, fish_eye_tangent, launch_at, log_slope, run};

const A: f64 = 1.0;
const N0: f64 = 1.5;
/// Step sizes in the asymptotic range (the circle's radius is about 1.4 m; at h = 0.2 m RK4's
/// own O(h⁵) end-point error still dominates the Hermite term).
const STEPS: [f64; 3] = [0.05, 0.025, 0.0125];

/// The exact fish-eye state at arc length s from p0 along d0.
fn exact(p0: DVec3, d0: DVec3, s: f64) -> RayY {
    let r = fish_eye_ray(A, p0, d0, s);
    RayY { r, v: fish_eye_tangent(A, p0, d0, s) * fish_eye(N0, A)(r).0 }
}

/// Largest dense-output position error over θ ∈ {0.2, 0.4, 0.5, 0.6, 0.8} of one step of size
/// h from the exact state at s0, for DP (`dp = true`) or RK4 + Hermite.
fn one_step_dense_error(h: f64, dp: bool) -> f64 {
    let field = fish_eye(N0, A);
    let (p0, d0) = (DVec3::new(0.5, 0.0, 0.0), DVec3::new(0.6, 0.8, 0.0));
    let s0 = 0.7;
    let y0 = exact(p0, d0, s0);
    let (f0, _) = eval(&field, &y0).unwrap();
    let mut evals = 0;
    let dense = if dp {
        let t = dopri5::trial(&field, &y0, &f0, h, &mut evals).unwrap();
        Dense { y0, f0, y1: t.y1, f1: t.f1, h, c5: t.c5 }
    } else {
        let y1 = rk4::step(&field, &y0, &f0, h, &mut evals).unwrap();
        let (f1, _) = eval(&field, &y1).unwrap();
        Dense::hermite(y0, f0, y1, f1, h)
    };
    [0.2, 0.4, 0.5, 0.6, 0.8]
        .iter()
        .map(|t| (dense.position_at(*t) - exact(p0, d0, s0 + t * h).r).length())
        .fold(0.0, f64::max)
}

#[test]
fn dormand_prince_dense_output_is_fourth_order() {
    let points: Vec<(f64, f64)> = STEPS.iter().map(|h| (*h, one_step_dense_error(*h, true))).collect();
    let order = log_slope(&points);
    eprintln!("DP dense errors {points:?}: local order {order:.3}");
    assert!((order - 5.0).abs() < 0.3, "local order {order}, expected 5 (a 4th-order interpolant)");
}

#[test]
fn hermite_dense_output_of_rk4_is_fourth_order_locally() {
    let points: Vec<(f64, f64)> = STEPS.iter().map(|h| (*h, one_step_dense_error(*h, false))).collect();
    let order = log_slope(&points);
    eprintln!("RK4 Hermite dense errors {points:?}: local order {order:.3}");
    assert!((order - 4.0).abs() < 0.3, "local order {order}, expected 4");
}

/// Over a whole adaptive solve, dense output inside each step is as accurate as the step's two
/// end points (within a factor 10): the interpolant adds no error of its own size.
#[test]
fn dense_output_between_nodes_matches_the_closed_form() {
    let field = fish_eye(N0, A);
    let (p0, d0) = (DVec3::new(0.5, 0.0, 0.0), DVec3::new(0.6, 0.8, 0.0));
    let circumference = 2.0 * std::f64::consts::PI * fish_eye_radius(A, p0, d0);
    for tol in [1e-6, 1e-9] {
        let start = launch_at(&field, p0, 0.8f64.atan2(0.6));
        let (_, steps, _) = run(Method::dormand_prince(tol, tol), &field, start, circumference);
        let node_err = |s: f64, y: &RayY| (y.r - exact(p0, d0, s).r).length();
        let mut worst: f64 = 0.0;
        for s in &steps {
            let ends = node_err(s.s0, &s.y0()).max(node_err(s.s0 + s.h(), &s.y1()));
            for t in [0.25, 0.5, 0.75] {
                let e = (s.position_at(t) - exact(p0, d0, s.s0 + t * s.h()).r).length();
                worst = worst.max(e / ends.max(tol));
                assert!(e <= 10.0 * ends.max(tol), "θ {t} in step at s0 = {}: dense {e:e} vs ends {ends:e}", s.s0);
                assert!((s.state_at(t).s - (s.s0 + t * s.h())).abs() < 1e-15);
            }
        }
        eprintln!("tol {tol:e}: {} steps, worst dense / end-point error ratio {worst:.3}", steps.len());
        // The ends of the interpolant are the step's end points.
        for s in &steps {
            assert_eq!(s.at(0.0), s.y0());
            assert!((s.at(1.0).r - s.y1().r).length() <= 1e-15 * (1.0 + s.y1().r.length()));
        }
    }
}
