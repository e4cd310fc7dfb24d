//! Issue 18, items 1–2: paths into a temperature inversion (a superior mirage's layer) no longer
//! spend their work on rejected steps. The inversion's gradient is a smooth bump 4w thick at
//! its height h (Fermi: ∝ σ(1 − σ), u = (z − h)/w); plain control sizes a step from the calm
//! air above, dives into the bump and fails, several times on the way in. Its peak is now a
//! step end that paths approach from either side as a layer growing towards it
//! (`morgana::ode::kink::Kink::layer`), and a path that crosses the peak leaves it with the
//! steps it came in with (`morgana::ode::kink::Cut::into_layer`), as the propagator does
//! (`morgana::raypath::curved`).
//!
//! Rays from 1 km at 1–60° and 20 km at 5–60° down to half a metre above the sea through
//! `atmospheres/inversion.toml` (2 °C air, a 10 K inversion at 30 m with w = 3 m), and rays
//! from 10 m climbing out through it at 0.25–5°, with the steps cut at the kinks as the
//! propagator cuts them:
//! - with the layer's peak as a step end, at most 10 % of the attempts are rejected (the
//!   issue's goal for the photon pass), at most a fifth as many as without it (the kinks of
//!   USA76 alone: 10.7 %), and fewer attempts are made in all;
//! - each ray ends within the integrator's tolerance, summed over its steps, of a reference at
//!   tolerance 10⁻¹³.
//!
//!   cargo test --release --test inversion_steps -- --nocapture

mod ode_common;

use glam::DVec3;
use morgana::atmosphere::edit::{Edit, Inversion, Offset};
use morgana::atmosphere::{Atmosphere, EARTH_RADIUS_M, RadialTable};
use morgana::media::refractive_index::IndexField;
use morgana::ode::{CurvedSettings, Integrator, Method, OdeState};
use morgana::raypath::kink::KinkSpheres;
use ode_common::arc_length_to_height;

/// The scenes' default tolerances (relative and absolute).
const TOL: f64 = 1e-9;
/// The inversion: height of its midpoint and thickness parameter w, m.
const H_M: f64 = 30.0;
const W_M: f64 = 3.0;

/// `atmospheres/inversion.toml`: USA76 13 K colder, with a 10 K inversion at 30 m.
fn inversion() -> Atmosphere {
    let usa76 = Atmosphere::usa76();
    let edits = vec![
        Edit::Offset(Offset { dt_k: -13.0 }),
        Edit::Inversion(Inversion::new(10.0, H_M, W_M).expect("valid edit")),
    ];
    Atmosphere::new("inversion", usa76.earth, usa76.base.clone(), edits, usa76.dispersion, usa76.top_m())
        .expect("valid atmosphere")
}

/// Work and end of one ray.
struct Run {
    end: OdeState,
    accepted: u64,
    rejected: u64,
}

/// Follows the ray to arc length `s_end` through `sample` at tolerance `tol`, cutting steps at
/// `kinks` and leaving a layer's peak as the propagator does.
fn follow(
    sample: &dyn Fn(DVec3) -> (f64, DVec3),
    kinks: &KinkSpheres,
    (p, dir): (DVec3, DVec3),
    s_end: f64,
    tol: f64,
) -> Run {
    let method = Method::dormand_prince(tol, tol);
    let settings = CurvedSettings { method, ..CurvedSettings::default() };
    let mut ode = Integrator::new(method).expect("valid method");
    let mut state = OdeState::launch(&sample, p, dir).expect("the field is finite here");
    let mut grad = ode.prime(&sample, &state.y).expect("the field is finite here").v;
    let mut last_h = f64::INFINITY;
    while state.s < s_end {
        let left = s_end - state.s;
        let (n, d) = (state.y.v.length(), state.y.direction());
        let bend = (grad - grad.dot(d) * d) / n;
        let want = ode.proposal().unwrap_or(f64::INFINITY);
        let cut = kinks.next_cut_within(state.y.r, d, bend, 1e-6, settings.kink_tolerance(n), want);
        let h = cut.map_or(left, |c| c.length_m.min(left));
        let step = ode.step(&sample, &mut state, h).expect("the step succeeds");
        if step.reached_limit && cut.is_some_and(|c| c.into_layer && c.length_m <= left) {
            ode.limit_proposal(last_h.max(step.h()));
        }
        last_h = step.h();
        grad = step.dense.f1.v;
        if step.reached_limit && h == left {
            state.s = s_end;
        }
    }
    let c = ode.counters();
    Run { end: state, accepted: c.accepted, rejected: c.rejected }
}

/// The rays: from 1 km down at 1–60° and from 20 km at 5–60° (at 1° it would pass the sea), and from 10 m up at 0.25–5° (from 0.2° up they leave the duct), each with the
/// height it is followed to (half a metre above the sea going down, 200 m going up).
fn rays() -> Vec<((DVec3, DVec3), f64)> {
    let dir = |deg: f64| DVec3::new(0.0, deg.to_radians().sin(), -deg.to_radians().cos());
    let mut rays = Vec::new();
    for (start_m, degs) in [(1_000.0, [1.0, 5.0, 20.0, 60.0]), (20_000.0, [5.0, 10.0, 20.0, 60.0])] {
        for deg in degs {
            rays.push(((DVec3::new(0.0, start_m, 0.0), dir(-deg)), 0.5));
        }
    }
    for deg in [0.25, 0.5, 1.0, 5.0] {
        rays.push(((DVec3::new(0.0, 10.0, 0.0), dir(deg)), 200.0));
    }
    rays
}

#[test]
fn paths_through_an_inversion_reject_few_steps_and_end_alike() {
    let atmosphere = inversion();
    let table = RadialTable::new(&atmosphere, TOL).expect("tabulated");
    let k = table.k(550.0);
    let sample = |q: DVec3| table.n_grad(k, 550.0, q);
    let field = IndexField::Atmosphere(Box::new(atmosphere));
    let exact = |q: DVec3| field.n_grad(550.0, q);
    let centre = DVec3::new(0.0, -EARTH_RADIUS_M, 0.0);
    let blind = KinkSpheres::new(&exact, centre, &field.kink_radii_m());
    let layers = field.thin_layer_radii_m();
    assert_eq!(layers, vec![(EARTH_RADIUS_M + H_M, W_M)], "the inversion is the field's one thin layer");
    let kinks = blind.clone().with_layers(&exact, &layers);
    let add = |(a, r): (u64, u64), (b, q): (u64, u64)| (a + b, r + q);
    // Attempts (accepted, rejected): with the layer, without.
    let mut all = [(0u64, 0u64); 2];
    for (ray, to_m) in rays() {
        let s_end = arc_length_to_height(&sample, ray, (to_m, EARTH_RADIUS_M), 10.0);
        let runs = [follow(&sample, &kinks, ray, s_end, TOL), follow(&sample, &blind, ray, s_end, TOL)];
        let reference = follow(&sample, &kinks, ray, s_end, 1e-13);
        for (i, run) in runs.iter().enumerate() {
            // Each step keeps its local error within atol + rtol·|r| (|r| ≤ 1.2·10⁵ m here);
            // the global error is at most the sum over the steps.
            let bound = (TOL + TOL * 1.2e5) * run.accepted as f64;
            let d = (run.end.y.r - reference.end.y.r).length();
            assert!(d <= bound, "{ray:?}, run {i}: {d} m from the reference (bound {bound} m)");
            all[i] = add(all[i], (run.accepted, run.rejected));
        }
        eprintln!(
            "from {:.0} m along {:?}: accepted, rejected with the layer {:?}, without {:?}",
            ray.0.y,
            ray.1,
            (runs[0].accepted, runs[0].rejected),
            (runs[1].accepted, runs[1].rejected)
        );
    }
    let share = |(a, r): (u64, u64)| r as f64 / (a + r) as f64;
    let attempts = |(a, r): (u64, u64)| a + r;
    eprintln!("in all: with the layer {:?}, without {:?}", all[0], all[1]);
    assert!(share(all[0]) <= 0.10, "{:.1} % rejected with the layer", 100.0 * share(all[0]));
    assert!(5 * all[0].1 <= all[1].1, "rejections: {:?} with the layer against {:?}", all[0], all[1]);
    assert!(attempts(all[0]) < attempts(all[1]), "attempts: {:?} with the layer against {:?}", all[0], all[1]);
}
