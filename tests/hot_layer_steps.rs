//! Issue 18, item 2: photons descending into a hot road's layer, where ∇n grows like
//! e^(−height/6.667 m), no longer spend their work on rejected steps. Plain PI control grows a
//! step from the error of the last one, which the next, steeper, stretch of the layer then fails;
//! two things predict the growth: the road's kink knows the layer above it (its gradient and
//! e-folding depth), so a step aimed at it ends where the layer would fail the error test
//! (`morgana::ode::kink`, "Approaching a layer"), and following the error density's trend
//! (`morgana::ode::Controller::follow_trend`) extrapolates the growth the last steps saw. Over
//! rays from 1 km and 20 km at 10–60° down to half a metre above the road (the directions of
//! `mirage_hot_road`'s sun and steeper), with the steps cut at the kinks as the propagator cuts
//! them:
//! - with both (the propagator), at most 10 % of the step attempts that start inside the layer
//!   (below 10 z₀ = 66.7 m, where the layer's e^(−h/z₀) outweighs USA76 in every derivative of
//!   ∇n past the first) are rejected (the goal for the photon pass), and fewer attempts
//!   are made in all (accepted + rejected, six field samples each) than with the trend alone;
//! - with the trend alone (a layer the kinks do not describe), fewer steps are rejected and
//!   fewer attempts made than with plain PI control, which rejects more than 10 % of those in
//!   the layer (so the checks can fail);
//! - each ray ends within the integrator's tolerance, summed over its steps, of a reference at
//!   tolerance 10⁻¹³.
//!
//!   cargo test --release --test hot_layer_steps

mod ode_common;

use glam::DVec3;
use morgana::atmosphere::edit::{Edit, HotSurface};
use morgana::atmosphere::{Atmosphere, EARTH_RADIUS_M, RadialTable};
use morgana::media::refractive_index::IndexField;
use morgana::ode::{CurvedSettings, Integrator, Method, OdeState};
use morgana::raypath::kink::{Kink, KinkSpheres, Side};
use ode_common::{arc_length_to_height, height_above};

/// The scenes' default tolerances (relative and absolute).
const TOL: f64 = 1e-9;

/// `atmospheres/hot_road.toml`: USA76 with 30 K at the road decaying over 6.667 m.
fn hot_road() -> Atmosphere {
    let usa76 = Atmosphere::usa76();
    let hot = HotSurface::new(30.0, 6.667).expect("valid edit");
    Atmosphere::new(
        "hot road",
        usa76.earth,
        usa76.base.clone(),
        vec![Edit::HotSurface(hot)],
        usa76.dispersion,
        usa76.top_m(),
    )
    .expect("valid atmosphere")
}

/// The hot layer's e-folding height, m.
const Z0_M: f64 = 6.667;

/// Work and end of one ray.
struct Run {
    end: OdeState,
    accepted: u64,
    rejected: u64,
    /// Accepted and rejected attempts of the steps that start below 10 z₀.
    in_layer: (u64, u64),
}

/// Follows the ray to arc length `s_end` through `sample` at tolerance `tol`, cutting steps at
/// `kinks` as the propagator does, with or without the trend.
fn follow(
    sample: &dyn Fn(DVec3) -> (f64, DVec3),
    kinks: &KinkSpheres,
    (p, dir): (DVec3, DVec3),
    s_end: f64,
    tol: f64,
    trend: bool,
) -> Run {
    let method = Method::dormand_prince(tol, tol);
    let settings = CurvedSettings { method, ..CurvedSettings::default() };
    let mut ode = Integrator::new(method).expect("valid method").with_trend(trend);
    let mut state = OdeState::launch(&sample, p, dir).expect("the field is finite here");
    let mut grad = ode.prime(&sample, &state.y).expect("the field is finite here").v;
    let mut in_layer = (0, 0);
    while state.s < s_end {
        let left = s_end - state.s;
        let (n, d) = (state.y.v.length(), state.y.direction());
        let bend = (grad - grad.dot(d) * d) / n;
        let cut = kinks.next_cut(state.y.r, d, bend, 1e-6, settings.kink_tolerance(n));
        let h = cut.map_or(left, |t| t.min(left));
        let (before, inside) = (ode.counters(), height(state.y.r) < 10.0 * Z0_M);
        let step = ode.step(&sample, &mut state, h).expect("the step succeeds");
        if inside {
            in_layer.0 += 1;
            in_layer.1 += ode.counters().rejected - before.rejected;
        }
        grad = step.dense.f1.v;
        if step.reached_limit && h == left {
            state.s = s_end;
        }
    }
    let c = ode.counters();
    Run { end: state, accepted: c.accepted, rejected: c.rejected, in_layer }
}

/// Height above the Earth of the atmosphere, m.
fn height(r: DVec3) -> f64 {
    height_above(r, EARTH_RADIUS_M)
}

#[test]
fn descending_into_a_hot_layer_rejects_few_steps_and_ends_alike() {
    let atmosphere = hot_road();
    let table = RadialTable::new(&atmosphere, TOL).expect("tabulated");
    let k = table.k(550.0);
    let sample = |q: DVec3| table.n_grad(k, 550.0, q);
    let field = IndexField::Atmosphere(Box::new(atmosphere));
    let exact = |q: DVec3| field.n_grad(550.0, q);
    let kinks = KinkSpheres::new(&exact, DVec3::new(0.0, -EARTH_RADIUS_M, 0.0), &field.kink_radii_m());
    // The same kinks without the layer: only the trend (or nothing) predicts it.
    let blind = KinkSpheres {
        centre: kinks.centre,
        kinks: kinks.kinks.iter().map(|k| Kink { sides: [Side::FLAT; 2], ..*k }).collect(),
    };
    let add = |(a, r): (u64, u64), (b, q): (u64, u64)| (a + b, r + q);
    // Attempts (accepted, rejected) in all and below 10 z0: propagator, trend alone, plain PI.
    let mut all = [(0u64, 0u64); 3];
    let mut layer = [(0u64, 0u64); 3];
    for start_m in [1_000.0, 20_000.0] {
        for elevation_deg in [10.0_f64, 20.0, 40.0, 60.0] {
            let e = elevation_deg.to_radians();
            let ray = (DVec3::new(0.0, start_m, 0.0), DVec3::new(0.0, -e.sin(), -e.cos()));
            // Down to half a metre above the road (steps of at most 100 m, so the field's kinks
            // cost the reference nothing it does not see).
            let s_end = arc_length_to_height(&sample, ray, (0.5, EARTH_RADIUS_M), 100.0);
            let runs = [
                follow(&sample, &kinks, ray, s_end, TOL, true),
                follow(&sample, &blind, ray, s_end, TOL, true),
                follow(&sample, &blind, ray, s_end, TOL, false),
            ];
            let reference = follow(&sample, &kinks, ray, s_end, 1e-13, true);
            for (i, run) in runs.iter().enumerate() {
                // Each step keeps its local error within atol + rtol·|r| (|r| ≤ 1.2·10⁵ m
                // here); the global error is at most the sum over the steps.
                let bound = (TOL + TOL * 1.2e5) * run.accepted as f64;
                let d = (run.end.y.r - reference.end.y.r).length();
                assert!(
                    d <= bound,
                    "{start_m} m, {elevation_deg}°, run {i}: {d} m from the reference (bound {bound} m)"
                );
                all[i] = add(all[i], (run.accepted, run.rejected));
                layer[i] = add(layer[i], run.in_layer);
            }
            eprintln!(
                "{start_m} m {elevation_deg}°: accepted, rejected: propagator {:?}, trend alone {:?}, plain PI {:?}",
                (runs[0].accepted, runs[0].rejected),
                (runs[1].accepted, runs[1].rejected),
                (runs[2].accepted, runs[2].rejected)
            );
        }
    }
    // Shares of the attempts (accepted steps plus rejections).
    let share = |(a, r): (u64, u64)| r as f64 / (a + r) as f64;
    let attempts = |(a, r): (u64, u64)| a + r;
    eprintln!("in all: propagator {:?}, trend alone {:?}, plain PI {:?}", all[0], all[1], all[2]);
    eprintln!("below 10 z0: propagator {:?}, trend alone {:?}, plain PI {:?}", layer[0], layer[1], layer[2]);
    assert!(share(layer[0]) <= 0.10, "in the layer {:.1} % rejected by the propagator", 100.0 * share(layer[0]));
    assert!(attempts(all[0]) < attempts(all[1]), "attempts: {:?} against the trend alone {:?}", all[0], all[1]);
    assert!(share(layer[2]) > 0.10, "in the layer plain PI control rejects {:.1} %", 100.0 * share(layer[2]));
    assert!(all[1].1 < all[2].1, "rejections: trend alone {:?} against plain PI {:?}", all[1], all[2]);
    assert!(attempts(all[1]) < attempts(all[2]), "attempts: trend alone {:?} against plain PI {:?}", all[1], all[2]);
}
