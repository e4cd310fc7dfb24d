//! Fields with closed-form rays, written here independently of the integrators under test.
#![allow(dead_code)]

use glam::DVec3;
use morgana::ode::{Integrator, Method, OdeState, Step};

/// n = n0 + a·y.
pub fn linear(n0: f64, a: f64) -> impl Fn(DVec3) -> (f64, DVec3) + Copy {
    move |p: DVec3| (n0 + a * p.y, DVec3::new(0.0, a, 0.0))
}

/// The exact ray in n = n0 + a·y launched from the origin at elevation `theta0` (rad) in the
/// x–y plane: position and ray vector v = n dr/ds at arc length s.
///
/// Derivation: dv/ds = ∇n = (0, a, 0), so v_x = p = n0 cos θ0 is constant (Bouguer's invariant
/// n cos θ = const of a layered medium) and v_y = q0 + a s with q0 = n0 sin θ0. Since |v| = n,
/// n(s) = √(p² + v_y²), and y = (n − n0)/a = (2 q0 s + a s²)/(n + n0) (cancellation-free form).
/// dx/ds = p/n integrates to x = (p/a)(asinh(v_y/p) − asinh(q0/p)) = (p/a)·asinh(a(n0 s − q0 y)/p²)
/// (the identity asinh u − asinh w = asinh(u√(1+w²) − w√(1+u²))). For θ0 = 0 this is the
/// catenary y = (n0/a)(cosh(a x/n0) − 1), x(s) = (n0/a) asinh(a s/n0).
pub fn catenary(n0: f64, a: f64, theta0: f64, s: f64) -> (DVec3, DVec3) {
    let (p, q0) = (n0 * theta0.cos(), n0 * theta0.sin());
    let vy = q0 + a * s;
    let n = (p * p + vy * vy).sqrt();
    let y = (2.0 * q0 * s + a * s * s) / (n + n0);
    let x = p / a * (a * (n0 * s - q0 * y) / (p * p)).asinh();
    (DVec3::new(x, y, 0.0), DVec3::new(p, vy, 0.0))
}

/// A smooth step from n_below (y ≪ −L) to n_above (y ≫ L): n = n_b + (n_a − n_b)(1 + tanh(y/L))/2.
pub fn tanh_layer(n_below: f64, n_above: f64, l: f64) -> impl Fn(DVec3) -> (f64, DVec3) + Copy {
    move |p: DVec3| {
        let t = (p.y / l).tanh();
        let dn = n_above - n_below;
        (n_below + dn * 0.5 * (1.0 + t), DVec3::new(0.0, dn * 0.5 * (1.0 - t * t) / l, 0.0))
    }
}

/// Maxwell's fish-eye n = n0/(1 + r²/a²) (Born & Wolf, *Principles of Optics*, §4.2.2): every
/// ray is a circle, and all rays from p pass through the conjugate point −a² p/|p|².
pub fn fish_eye(n0: f64, a: f64) -> impl Fn(DVec3) -> (f64, DVec3) + Copy {
    move |p: DVec3| {
        let q = 1.0 + p.length_squared() / (a * a);
        (n0 / q, p * (-2.0 * n0 / (a * a * q * q)))
    }
}

/// The fish-eye ray from `p0` along unit `d0` at arc length s: the circle through p0 and the
/// conjugate point p* tangent to d0. With w = p0 − p* and w⊥ its part normal to d0, the centre
/// is c = p0 + ρ m, m = −w⊥/|w⊥|, ρ = |w|²/(2|w⊥|), and p(s) = c − ρ m cos(s/ρ) + ρ d0 sin(s/ρ).
pub fn fish_eye_ray(a: f64, p0: DVec3, d0: DVec3, s: f64) -> DVec3 {
    let conj = -a * a * p0 / p0.length_squared();
    let w = p0 - conj;
    let w_perp = w - w.dot(d0) * d0;
    let m = -w_perp.normalize();
    let rho = w.length_squared() / (2.0 * w_perp.length());
    let c = p0 + rho * m;
    c - rho * m * (s / rho).cos() + rho * d0 * (s / rho).sin()
}

/// Integrates to `s_end` and returns the end state and the accepted steps.
pub fn run<F: Fn(DVec3) -> (f64, DVec3)>(
    method: Method,
    field: &F,
    start: OdeState,
    s_end: f64,
) -> (OdeState, Vec<Step>, Integrator) {
    let mut ode = Integrator::new(method).unwrap_or_else(|e| panic!("{e}"));
    let mut state = start;
    let mut steps = Vec::new();
    while state.s < s_end {
        let left = s_end - state.s;
        let step = ode.step(field, &mut state, left).unwrap_or_else(|e| panic!("{e}"));
        assert!(state.y.is_finite(), "non-finite state {state:?}");
        steps.push(step);
        if step.reached_limit {
            state.s = s_end;
        }
    }
    (state, steps, ode)
}

/// The launch state at the origin at elevation `theta0` in the x–y plane of `field`.
pub fn launch_at<F: Fn(DVec3) -> (f64, DVec3)>(field: &F, p: DVec3, theta0: f64) -> OdeState {
    OdeState::launch(field, p, DVec3::new(theta0.cos(), theta0.sin(), 0.0)).unwrap_or_else(|e| panic!("{e}"))
}

/// Least-squares slope of log(y) against log(x).
pub fn log_slope(points: &[(f64, f64)]) -> f64 {
    let n = points.len() as f64;
    let (lx, ly): (Vec<f64>, Vec<f64>) = points.iter().map(|(x, y)| (x.ln(), y.ln())).unzip();
    let (mx, my) = (lx.iter().sum::<f64>() / n, ly.iter().sum::<f64>() / n);
    let sxy: f64 = lx.iter().zip(&ly).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = lx.iter().map(|x| (x - mx) * (x - mx)).sum();
    sxy / sxx
}

/// The unit tangent of [`fish_eye_ray`] at arc length s.
pub fn fish_eye_tangent(a: f64, p0: DVec3, d0: DVec3, s: f64) -> DVec3 {
    let conj = -a * a * p0 / p0.length_squared();
    let w = p0 - conj;
    let w_perp = w - w.dot(d0) * d0;
    let m = -w_perp.normalize();
    let rho = w.length_squared() / (2.0 * w_perp.length());
    m * (s / rho).sin() + d0 * (s / rho).cos()
}

/// The radius of [`fish_eye_ray`]'s circle.
pub fn fish_eye_radius(a: f64, p0: DVec3, d0: DVec3) -> f64 {
    let w = p0 + a * a * p0 / p0.length_squared();
    let w_perp = w - w.dot(d0) * d0;
    w.length_squared() / (2.0 * w_perp.length())
}

/// Height above an Earth of radius `radius_m` centred at (0, −radius_m, 0), m.
pub fn height_above(r: DVec3, radius_m: f64) -> f64 {
    (r - DVec3::new(0.0, -radius_m, 0.0)).length() - radius_m
}

/// The arc length at which the ray (p, dir) through `sample`, followed at tolerance 10⁻¹³ in
/// steps of at most `max_step_m`, first passes `height_m` above an Earth of radius `radius_m`
/// (up or down), located on the dense output of the step that passes it by bisection.
pub fn arc_length_to_height(
    sample: &dyn Fn(DVec3) -> (f64, DVec3),
    (p, dir): (DVec3, DVec3),
    (height_m, radius_m): (f64, f64),
    max_step_m: f64,
) -> f64 {
    let mut ode = Integrator::new(Method::dormand_prince(1e-13, 1e-13)).expect("valid method");
    let mut state = OdeState::launch(&sample, p, dir).expect("the field is finite here");
    let below = |q: DVec3| height_above(q, radius_m) < height_m;
    let start = below(p);
    loop {
        let step = ode.step(&sample, &mut state, max_step_m).expect("the step succeeds");
        if below(state.y.r) != start {
            let (mut lo, mut hi) = (0.0, 1.0);
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if below(step.position_at(mid)) == start { lo = mid } else { hi = mid }
            }
            return step.s0 + 0.5 * (lo + hi) * step.h();
        }
    }
}
