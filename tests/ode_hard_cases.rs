//! Numerically hard rays, each with its expected result stated and derived beside it. Every
//! state along every path is checked finite; step counts are bounded.

mod ode_common;

use glam::DVec3;
use morgana::ode::{Integrator, Method, OdeError, OdeState, Step};
use ode_common::{catenary, launch_at, linear, run, tanh_layer};

/// Tolerances of these tests: rtol = atol = TOL; measured global errors stay near TOL per metre
/// of path (see ode_closed_form), so position checks use 10·TOL·L.
const TOL: f64 = 1e-10;

fn dp() -> Method {
    Method::dormand_prince(TOL, TOL)
}

/// The θ in `step` where v_y = 0 (v_y(0) > 0 ≥ v_y(1)), by bisection on dense output.
fn apex_in(step: &Step) -> f64 {
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if step.at(mid).v.y > 0.0 { lo = mid } else { hi = mid }
    }
    0.5 * (lo + hi)
}

/// The highest point of a path that goes up and comes back down.
fn apex(steps: &[Step]) -> DVec3 {
    let s = steps.iter().find(|s| s.y0().v.y > 0.0 && s.y1().v.y <= 0.0).expect("the ray turns");
    s.position_at(apex_in(s))
}

/// Launched at θ0 = 30° into n = 1 − 0.1·y (n falls upward), the ray turns where v_y = 0:
/// v_y = n0 sin θ0 + a s vanishes at s* = −n0 sin θ0 / a = 5 m, where by Bouguer's invariant
/// n(y_max) = n0 cos θ0, i.e. y_max = (n0/|a|)(1 − cos θ0) = 10(1 − cos 30°) m ≈ 1.3397 m.
/// v_y is odd about s* and n depends on v_y², so the path is mirror-symmetric about x(s*):
/// at 2s* it is back at y = 0 with x = 2x(s*) and v = (n0 cos θ0, −n0 sin θ0, 0).
#[test]
fn turning_point_apex_and_symmetry() {
    let (n0, a, theta0) = (1.0, -0.1, 30f64.to_radians());
    let field = linear(n0, a);
    let s_star = -n0 * theta0.sin() / a;
    let y_max = n0 / a.abs() * (1.0 - theta0.cos());
    let start = launch_at(&field, DVec3::ZERO, theta0);
    let (top, ..) = run(dp(), &field, start, s_star);
    let (end, steps, ode) = run(dp(), &field, start, 2.0 * s_star);
    let bound = 10.0 * TOL * 2.0 * s_star;
    eprintln!(
        "apex y {:.12} (expected {y_max:.12}), end y {:.3e}, end x − 2x* {:.3e}, {} steps",
        top.y.r.y,
        end.y.r.y,
        end.y.r.x - 2.0 * top.y.r.x,
        steps.len()
    );
    assert!((top.y.r.y - y_max).abs() < bound);
    assert!(top.y.v.y.abs() < bound, "v_y = 0 at the apex");
    assert!((apex(&steps).y - y_max).abs() < bound, "apex found by dense output");
    assert!(end.y.r.y.abs() < bound);
    assert!((end.y.r.x - 2.0 * top.y.r.x).abs() < bound);
    assert!((end.y.v - DVec3::new(theta0.cos(), -theta0.sin(), 0.0) * n0).length() < bound);
    for u in [1.0, 2.5, 4.0] {
        let (before, ..) = run(dp(), &field, start, s_star - u);
        let (after, ..) = run(dp(), &field, start, s_star + u);
        assert!((before.y.r.y - after.y.r.y).abs() < bound, "symmetric heights at s* ± {u}");
        assert!(((before.y.r.x + after.y.r.x) / 2.0 - top.y.r.x).abs() < bound);
    }
    assert!(ode.counters().accepted < 100);
}

/// Total internal reflection in a 1 cm gradient from n1 = 1.33 (below) to n2 = 1.0 (above),
/// n(y) = n1 + (n2 − n1)(1 + tanh(y/L))/2. Bouguer: n(y) cos θ(y) = n1 cos θ1.
/// - θ1 = 30°: n1 cos θ1 = 1.1518 > n2, so the ray turns at n(y_t) = n1 cos θ1, i.e.
///   y_t = L atanh(2(n1 cos θ1 − n1)/(n2 − n1) − 1) ≈ 0.80 mm, and leaves downward at −30°.
/// - θ1 = 60°: n1 cos θ1 = 0.665 < n2: it crosses and leaves at cos θ2 = n1 cos θ1 / n2.
#[test]
fn total_internal_reflection_in_a_gradient() {
    let (n1, n2, l) = (1.33, 1.0, 0.01);
    let field = tanh_layer(n1, n2, l);
    let t1 = 30f64.to_radians();
    let start = launch_at(&field, DVec3::new(0.0, -0.2, 0.0), t1);
    let (end, steps, ode) = run(dp(), &field, start, 1.5);
    let y_t = l * (2.0 * (n1 * t1.cos() - n1) / (n2 - n1) - 1.0).atanh();
    let top = apex(&steps);
    eprintln!(
        "TIR: apex y {:.6e} m (expected {y_t:.6e}), exit direction {:?}, {} accepted, {} rejected",
        top.y,
        end.y.direction(),
        ode.counters().accepted,
        ode.counters().rejected
    );
    assert!((top.y - y_t).abs() < 10.0 * TOL * 1.5, "apex {} vs {y_t}", top.y);
    assert!(end.y.r.y < -0.3, "back in the lower medium");
    assert!((end.y.direction() - DVec3::new(t1.cos(), -t1.sin(), 0.0)).length() < 1e-8);
    assert!(ode.counters().accepted + ode.counters().rejected < 500);

    let t1 = 60f64.to_radians();
    let start = launch_at(&field, DVec3::new(0.0, -0.2, 0.0), t1);
    let (end, ..) = run(dp(), &field, start, 1.0);
    let cos2 = n1 * t1.cos() / n2;
    let expected = DVec3::new(cos2, (1.0 - cos2 * cos2).sqrt(), 0.0);
    eprintln!("transmitted: exit direction {:?}, expected {expected:?}", end.y.direction());
    assert!(end.y.r.y > 0.3, "in the upper medium");
    assert!((end.y.direction() - expected).length() < 1e-8);
}

/// A steep, weak gradient like the hot layer of an inferior mirage: n rises by 1e-4 over about
/// 1 cm (n = 1 + 1e-4 (1 + tanh(y/5 mm))/2). Grazing rays from 10 cm above, descending:
/// critical elevation θc = acos(1/1.0001) ≈ 0.01414 rad. At 0.010 rad the ray is reflected and
/// leaves upward at +0.010 rad; at 0.020 rad it passes with cos θ2 = 1.0001 cos(0.02).
#[test]
fn steep_gradient_mirage_layer() {
    let field = tanh_layer(1.0, 1.0001, 0.005);
    for (theta, reflected) in [(0.010f64, true), (0.020, false)] {
        let start = launch_at(&field, DVec3::new(0.0, 0.1, 0.0), -theta);
        let (end, steps, ode) = run(dp(), &field, start, 30.0);
        let expected = if reflected {
            DVec3::new(theta.cos(), theta.sin(), 0.0)
        } else {
            let c2 = 1.0001 * theta.cos();
            DVec3::new(c2, -(1.0 - c2 * c2).sqrt(), 0.0)
        };
        let c = ode.counters();
        eprintln!(
            "θ {theta}: exit {:?} vs {expected:?}, {} steps ({} rejected, {} evals)",
            end.y.direction(),
            steps.len(),
            c.rejected,
            c.rhs_evals
        );
        assert_eq!(end.y.r.y > 0.1, reflected);
        assert!((end.y.direction() - expected).length() < 1e-8, "{:?}", end.y.direction() - expected);
        assert!(c.accepted + c.rejected < 1000, "bounded work");
    }
}

/// 10⁶ m through a weak gradient (n = 1 − 2.6e-8·y, about the standard atmosphere's dn/dh at
/// the ground), launched horizontally: the endpoint matches the catenary to 10·TOL·L, the work
/// stays small, and the drift of |v| − n stays within the budget the error control allows,
/// N·√6·(atol + rtol·n) plus |∇n|·(position error).
#[test]
fn very_long_path_in_a_weak_gradient() {
    let (a, length) = (-2.6e-8, 1e6);
    let field = linear(1.0, a);
    let start = launch_at(&field, DVec3::ZERO, 0.0);
    let (end, steps, ode) = run(dp(), &field, start, length);
    let (exact, _) = catenary(1.0, a, 0.0, length);
    let err = (end.y.r - exact).length();
    let n = field(end.y.r).0;
    let drift = steps.iter().map(|s| (s.y1().v.length() - field(s.y1().r).0).abs()).fold(0.0, f64::max);
    let budget = steps.len() as f64 * 6f64.sqrt() * (TOL + TOL * n) + a.abs() * err;
    eprintln!(
        "1e6 m: error {err:.3e} m, y = {:.3} m, {} steps, {} rejected, max ||v| − n| {drift:.3e} (budget {budget:.3e})",
        end.y.r.y,
        steps.len(),
        ode.counters().rejected
    );
    assert!(err < 10.0 * TOL * length, "{err}");
    assert!(steps.len() < 200);
    assert!(drift <= budget);

    // In a linear field v is integrated exactly; in an exponential profile it is not:
    // n = 1 + 2.9e-4·exp(−y/8 km) (a flat-Earth exponential atmosphere), same path. No closed
    // form: the endpoint is checked against the same ray at tolerance 1e-13.
    let field = |p: DVec3| {
        let e = 2.9e-4 * (-p.y / 8000.0).exp();
        (1.0 + e, DVec3::new(0.0, -e / 8000.0, 0.0))
    };
    let start = launch_at(&field, DVec3::ZERO, 0.0);
    let (end, steps, ode) = run(dp(), &field, start, length);
    let (fine, ..) = run(Method::dormand_prince(1e-13, 1e-13), &field, start, length);
    let err = (end.y.r - fine.y.r).length();
    let drift = steps.iter().map(|s| (s.y1().v.length() - field(s.y1().r).0).abs()).fold(0.0, f64::max);
    let grad_max = steps.iter().map(|s| field(s.y1().r).1.length()).fold(0.0, f64::max);
    let budget = steps.len() as f64 * 6f64.sqrt() * (TOL + TOL * field(end.y.r).0) + grad_max * err;
    eprintln!(
        "exponential, 1e6 m: y = {:.3} m, |Δ| vs tol 1e-13 {err:.3e} m, {} steps, {} rejected, \
         max ||v| − n| {drift:.3e} (budget {budget:.3e})",
        end.y.r.y,
        steps.len(),
        ode.counters().rejected
    );
    assert!(err < 10.0 * TOL * length, "{err}");
    assert!(steps.len() < 500);
    assert!(drift <= budget);
}

/// h_limit = 0 gives a zero step: no work, no motion, no NaN; negative or NaN limits are
/// errors; the next real step still works.
#[test]
fn zero_length_and_invalid_step_requests() {
    let field = linear(1.0, 0.1);
    let mut state = launch_at(&field, DVec3::ZERO, 0.3);
    let before = state;
    for method in [dp(), Method::Rk4 { h_m: 0.1 }, Method::Euler { h_m: 0.1 }] {
        let mut ode = Integrator::new(method).unwrap();
        let step = ode.step(&field, &mut state, 0.0).unwrap();
        assert_eq!((step.h(), step.y0(), step.y1(), state), (0.0, before.y, before.y, before));
        assert_eq!(step.at(0.5), before.y);
        assert_eq!(ode.counters().rhs_evals, 0);
        for bad in [-1.0, f64::NAN] {
            assert!(matches!(ode.step(&field, &mut state, bad), Err(OdeError::InvalidStepLimit { .. })));
        }
        assert_eq!(state, before);
        let step = ode.step(&field, &mut state, 0.05).unwrap();
        assert!(step.h() > 0.0 && step.h() <= 0.05 && state.y.is_finite());
        state = before;
    }
}

/// n ≤ 0 where the ray starts is an error naming the value, and so is n ≤ 0 met on the way
/// (a field with a sign error beyond x = 1 m: n = −1 there).
#[test]
fn nonpositive_index_is_an_error() {
    let bad = linear(-0.5, 0.0);
    let e = OdeState::launch(&bad, DVec3::ZERO, DVec3::X).unwrap_err();
    assert!(matches!(e, OdeError::BadIndex { n, .. } if n == -0.5));
    assert!(e.to_string().contains("n = -0.5") && e.to_string().contains("expected a finite n > 0"), "{e}");
    let broken = |p: DVec3| if p.x > 1.0 { (-1.0, DVec3::ZERO) } else { (1.0, DVec3::ZERO) };
    for method in [dp(), Method::Rk4 { h_m: 0.3 }, Method::Euler { h_m: 0.3 }] {
        let mut state = OdeState::launch(&broken, DVec3::ZERO, DVec3::X).unwrap();
        let mut ode = Integrator::new(method).unwrap();
        let err = ode.integrate_to(&broken, &mut state, 5.0).unwrap_err();
        assert!(matches!(err, OdeError::BadIndex { at, n, .. } if at.x > 1.0 && n == -1.0), "{err}");
        assert!(state.y.is_finite() && state.y.r.x <= 1.0);
    }
}

/// An exact ray never enters n ≤ 0 (|v| = n), but it can touch n = 0: in n = 1 − y launched
/// straight up, y = s and |v| = n = 1 − s until s = 1 m, where dr/ds = v/n is 0/0; the exact
/// continuation is the reflection y = 1 − |1 − s|. Expected: each method either stops with an
/// error (a stage sampled n ≤ 0) or carries on; every state stays finite with n > 0, within
/// 0.1 m (ten fixed steps) of the exact continuation — the order is lost at the 0/0 point, so
/// only closeness is asked — and the work is bounded.
#[test]
fn touching_n_equal_zero_stays_finite() {
    let field = linear(1.0, -1.0);
    for method in [dp(), Method::Rk4 { h_m: 0.01 }, Method::Euler { h_m: 0.01 }] {
        let mut state = OdeState::launch(&field, DVec3::ZERO, DVec3::Y).unwrap();
        let mut ode = Integrator::new(method).unwrap();
        let outcome = loop {
            let left = 2.0 - state.s;
            match ode.step(&field, &mut state, left) {
                Ok(step) => {
                    let y = state.y.r.y;
                    let exact = 1.0 - (1.0 - state.s).abs();
                    assert!(state.y.is_finite() && field(state.y.r).0 > 0.0 && (y - exact).abs() < 0.1, "{state:?}");
                    if step.reached_limit {
                        break format!("reached s = 2 m at y = {y:.4} m (exact 0)");
                    }
                }
                Err(e) => {
                    assert!(matches!(e, OdeError::BadIndex { .. } | OdeError::StepSizeUnderflow { .. }), "{e}");
                    break format!("stopped at s = {:.6} m: {e}", state.s);
                }
            }
        };
        eprintln!("{}: {outcome}", method.name());
        assert!(ode.counters().accepted + ode.counters().rejected < 10_000, "bounded");
    }
}

/// A field that is NaN everywhere cannot launch; one that is NaN beyond x = 1 m (a hole in a
/// data grid) stops the ray with an error naming a point beyond x = 1 m, and no state on the
/// way is NaN.
#[test]
fn nan_field_is_an_error() {
    let nan = |_: DVec3| (f64::NAN, DVec3::ZERO);
    assert!(matches!(OdeState::launch(&nan, DVec3::ZERO, DVec3::X), Err(OdeError::BadIndex { .. })));
    let holed = |p: DVec3| if p.x > 1.0 { (f64::NAN, DVec3::ZERO) } else { (1.0, DVec3::new(0.0, 1e-3, 0.0)) };
    for method in [dp(), Method::Rk4 { h_m: 0.3 }, Method::Euler { h_m: 0.3 }] {
        let mut state = OdeState::launch(&holed, DVec3::ZERO, DVec3::X).unwrap();
        let mut ode = Integrator::new(method).unwrap();
        let err = ode.integrate_to(&holed, &mut state, 5.0).unwrap_err();
        eprintln!("{}: stopped at x = {:.6} m with: {err}", method.name(), state.y.r.x);
        assert!(matches!(err, OdeError::BadIndex { at, .. } if at.x > 1.0), "{err}");
        assert!(state.y.is_finite() && state.y.r.x <= 1.0);
        assert!(err.to_string().contains("n = NaN"), "{err}");
    }
}

/// A non-finite state handed in is refused, and a tiny budget stops a long integration with
/// MaxSteps instead of running on.
#[test]
fn bad_states_and_step_budget() {
    let field = linear(1.0, 0.1);
    let mut ode = Integrator::new(dp()).unwrap();
    let mut state = OdeState { s: 0.0, y: morgana::ode::RayY { r: DVec3::NAN, v: DVec3::X } };
    assert!(matches!(ode.step(&field, &mut state, 1.0), Err(OdeError::BadState { .. })));
    let mut ode = Integrator::new(Method::Euler { h_m: 1e-3 }).unwrap().with_max_steps(100);
    let mut state = launch_at(&field, DVec3::ZERO, 0.0);
    let e = ode.integrate_to(&field, &mut state, 10.0).unwrap_err();
    assert!(matches!(e, OdeError::MaxSteps { max_steps: 100, .. }), "{e}");
    assert!((state.s - 0.1).abs() < 1e-12);
    for m in [
        Method::dormand_prince(0.0, 1e-9),
        Method::dormand_prince(1e-9, f64::NAN),
        Method::Rk4 { h_m: 0.0 },
        Method::Euler { h_m: f64::INFINITY },
        Method::DormandPrince { rtol: 1e-9, atol: 1e-9, pi: true, h0: Some(-1.0), h_min: 0.0, h_max: 1.0 },
    ] {
        let e = Integrator::new(m).unwrap_err();
        assert!(matches!(e, OdeError::InvalidSettings { .. }), "{m:?}: {e}");
    }
}
