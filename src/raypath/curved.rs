//! Following light through a medium whose refractive index varies: Fermat's ray equation
//! d/ds(n dr/ds) = ∇n (Gutierrez et al. 2005, eq. 7), one integrator step at a time.
//!
//! A path alternates between two kinds of leg:
//! - *straight*, where it is outside the field's gradient region: one chord to the nearest of
//!   a surface, the region's boundary and the world sphere (no ODE runs there);
//! - *curved*, inside the region: each accepted step of the integrator (the scene's
//!   [`crate::ode::Method`]) is cut into chords within the arc tolerance
//!   (`arc`); every chord is intersected with the scene and handed to the visitor, so a
//!   surface crossing is found on the chord that crosses it and located on the arc to within the
//!   tolerance; the arriving direction is the arc's tangent there (dense output). A leg ends when
//!   a step ends outside the region.
//!
//! A surface the arc touches tangentially is hit when the arc goes deeper than the tolerance
//! and missed otherwise, never both: a hit ends the event, and the next event starts on the
//! side the path leaves to.

use super::arc::{ChordOnArc, chord_count};
use super::far::TrapWatch;
use super::{Chord, Event, Propagator, RayState};
use crate::field::GradientRegion;
use crate::geometry::{Hit, Ray};
use crate::media::refractive_index::IndexField;
use crate::ode::{Integrator, OdeState, Step};
use glam::DVec3;

/// The wavelength at which a path that carries several follows a non-dispersive field (any
/// wavelength gives the same path there).
pub const REFERENCE_WAVELENGTH_NM: f64 = 550.0;

/// Legs (straight or curved) after which a path is given up as lost: a bound no physical path
/// reaches, since each leg either ends the event or crosses the region's boundary.
const MAX_LEGS: usize = 10_000;

/// Where a path is within one event.
struct Walk {
    position: DVec3,
    dir: DVec3,
    /// The wavelength the path follows, nm.
    wavelength_nm: f64,
    /// Path length so far, m.
    travelled: f64,
    medium: u32,
    chords: u64,
    /// Whether the path is trapped in a duct past the geometry ([`super::far`]).
    trap: TrapWatch,
}

/// Kink crossings nearer than this are the one the path is on (it was cut there), m.
const KINK_MIN_M: f64 = 1e-6;

/// How a leg ended.
enum Leg {
    /// The event is found.
    Done(Event),
    /// The path goes on with a leg of the other kind.
    Switch,
    /// The path goes on from a new point (past the layered upper air), with a leg of the kind
    /// its region says.
    Restart,
}

/// The next event of a path starting at `state` in a medium with index field `field` that
/// bends light inside `region`.
pub(super) fn next_event(
    prop: &Propagator,
    state: &RayState,
    field: &IndexField,
    region: &GradientRegion,
    visit: &mut dyn FnMut(&Chord) -> Option<f64>,
) -> Event {
    let lambda = state.wavelength_nm.unwrap_or(REFERENCE_WAVELENGTH_NM);
    let medium = state.medium.unwrap_or_default();
    // The medium's tabulated index where it has one (an atmosphere of height alone), else the
    // field itself.
    let table = prop.aids[medium as usize].table.as_ref();
    let k = table.map_or(0.0, |t| t.k(lambda));
    let sample = |p: DVec3| match table {
        Some(t) => t.n_grad(k, lambda, p),
        None => field.n_grad(lambda, p),
    };
    let mut walk = Walk {
        position: state.position,
        dir: state.dir,
        wavelength_nm: lambda,
        travelled: 0.0,
        medium,
        chords: 0,
        trap: TrapWatch::default(),
    };
    let Some(Ok(mut ode)) = prop.curved.map(|c| Integrator::new(c.method)) else {
        prop.work.lose();
        return Event::Lost { position: state.position };
    };
    let mut curved = region.contains(walk.position);
    let mut event = Event::Lost { position: state.position };
    for _ in 0..MAX_LEGS {
        let leg = if curved {
            curved_leg(prop, &sample, region, &mut ode, &mut walk, visit)
        } else {
            straight_leg(prop, region, &mut walk, visit)
        };
        match leg {
            Leg::Done(e) => {
                event = e;
                break;
            }
            Leg::Switch => curved = !curved,
            Leg::Restart => curved = region.contains(walk.position),
        }
    }
    let c = ode.counters();
    prop.work.add(c.accepted, c.rejected, c.rhs_evals, walk.chords);
    if matches!(event, Event::Lost { .. }) {
        prop.work.lose();
    }
    event
}

/// A straight leg outside the gradient region: to a surface, into the region, or out of the
/// world.
fn straight_leg(
    prop: &Propagator,
    region: &GradientRegion,
    w: &mut Walk,
    visit: &mut dyn FnMut(&Chord) -> Option<f64>,
) -> Leg {
    let hit = prop.world.bvh.intersect(&prop.world.shapes, &Ray::new(w.position, w.dir), f64::INFINITY);
    let end = hit.map_or_else(|| prop.world_exit(w.position, w.dir), |h| h.t);
    let entry = region.entry_distance(w.position, w.dir, end).filter(|t| *t < end);
    let length = entry.unwrap_or(end);
    w.chords += 1;
    let end_normal = if entry.is_none() { hit.map(|h| h.normal) } else { None };
    let chord = Chord { origin: w.position, dir: w.dir, length, medium: Some(w.medium), column_m: None, end_normal };
    if let Some(t) = visit(&chord).filter(|t| *t < length) {
        return Leg::Done(Event::Medium {
            position: w.position + t * w.dir,
            dir: w.dir,
            path_length: w.travelled + t,
            medium: w.medium,
        });
    }
    if let Some(t) = entry {
        w.position += t * w.dir;
        w.travelled += t;
        return Leg::Switch;
    }
    Leg::Done(match hit {
        Some(mut h) => {
            h.t += w.travelled;
            Event::Surface { hit: h, dir: w.dir, path_length: h.t, medium: Some(w.medium) }
        }
        None => Event::Escape { dir: w.dir },
    })
}

/// A curved leg inside the gradient region, step by step, until an event or until a step ends
/// outside the region.
fn curved_leg<F: Fn(DVec3) -> (f64, DVec3)>(
    prop: &Propagator,
    sample: &F,
    region: &GradientRegion,
    ode: &mut Integrator,
    w: &mut Walk,
    visit: &mut dyn FnMut(&Chord) -> Option<f64>,
) -> Leg {
    let Ok(mut state) = OdeState::launch(sample, w.position, w.dir) else {
        return Leg::Done(Event::Lost { position: w.position });
    };
    // A new leg goes on with the step size the last one reached (issue 18, item 2).
    ode.resume();
    let Some(settings) = prop.curved else { return Leg::Done(Event::Lost { position: w.position }) };
    let h_cap = settings.max_step_m.min(prop.world_radius);
    let kinks = prop.aids[w.medium as usize].kinks.as_ref();
    // A path that starts just above the layered upper air's bottom going up (a camera in it)
    // leaves it in one move.
    if let Some((shell, a)) = ascent_from(prop.upward_shell(w.medium), w) {
        return climb(prop, shell, w, w.position, a, visit);
    }
    // ∇n where the next step starts (the first step's slope, sampled once): the path's curvature.
    let Ok(f0) = ode.prime(sample, &state.y) else { return Leg::Done(Event::Lost { position: w.position }) };
    let mut grad = f0.v;
    // The length of the last step, the size to leave a thin layer's peak with.
    let mut last_h = f64::INFINITY;
    loop {
        let tol = settings.kink_tolerance(state.y.v.length());
        let h_want = ode.proposal().unwrap_or(f64::INFINITY);
        let next =
            kinks.and_then(|k| k.next_cut_within(w.position, w.dir, state.y.curvature(grad), KINK_MIN_M, tol, h_want));
        let cut = next.map(|c| c.length_m);
        let h_limit = cut.map_or(h_cap, |t| t.min(h_cap));
        if cut.is_some() && grad.length() * h_limit <= tol.map_or(0.0, |t| t.v()) {
            // Entering where ∇n is 0 or nearly (the top of an atmosphere, where n − 1 tapers to
            // 0 with zero slope: 10⁻²³ m⁻¹ by rounding) the starting-step guess has no scale to
            // go by and comes out at centimetres, then grows ×10 a step; ∇n changes v by less
            // than the tolerance all the way to the next kink, up to which the field is smooth,
            // so that is the first step.
            ode.propose_first_step(h_limit);
        }
        let Ok(step) = ode.step(sample, &mut state, h_limit) else {
            return Leg::Done(Event::Lost { position: w.position });
        };
        if step.reached_limit && next.is_some_and(|c| c.into_layer && c.length_m <= h_cap) {
            ode.limit_proposal(last_h.max(step.h()));
        }
        last_h = step.h();
        grad = step.dense.f1.v;
        // Where the step climbs through the layered upper air's bottom, the path is handed out
        // up to there and leaves the air in one move from there.
        let climbing = prop.upward_shell(w.medium).and_then(|sh| {
            let theta = sh.bottom_crossing(step.y0().r, step.y1().r, |t| step.position_at(t))?;
            let at = step.position_at(theta);
            Some((sh, theta, at, sh.ascend(at, step.direction_at(theta), w.wavelength_nm)?))
        });
        let theta_end = climbing.map_or(1.0, |c| c.1);
        if let Some(e) = chords_of(prop, &step, settings.arc_tolerance_m, w, visit, theta_end) {
            return Leg::Done(e);
        }
        if let Some((sh, _, at, a)) = climbing {
            return climb(prop, sh, w, at, a, visit);
        }
        w.position = state.y.r;
        w.dir = state.y.direction();
        if prop.outside_world(w.position) {
            return Leg::Done(Event::Escape { dir: w.dir });
        }
        if !region.contains(w.position) {
            return Leg::Switch;
        }
        if let Some(cone) = &prop.far[w.medium as usize]
            && w.trap.observe(cone, w.position, w.dir)
        {
            prop.work.trap();
            return Leg::Done(Event::Escape { dir: w.dir });
        }
    }
}

/// A path that leaves the layered upper air upward from `from` in one move, to where `a` says
/// it reaches the top ([`super::shell::LayeredShell::ascend`]): in absorbing air the visitor
/// gets the crossing as one chord with its density column ([`Chord::column_m`]); above an open
/// top the path then escapes in its direction there, and under a shape's top it goes on from
/// just inside it (to cross it as a surface). Nothing else lies in the shell (every shape is
/// below its bottom) and nothing scatters there.
fn climb(
    prop: &Propagator,
    shell: &super::shell::LayeredShell,
    w: &mut Walk,
    from: DVec3,
    a: super::shell::Ascent,
    visit: &mut dyn FnMut(&Chord) -> Option<f64>,
) -> Leg {
    prop.work.ascent();
    let span = a.position - from;
    let length = span.length();
    let dir = if length > 0.0 { span / length } else { a.dir };
    if !prop.is_clear(w.medium) {
        w.chords += 1;
        let chord =
            Chord { origin: from, dir, length, medium: Some(w.medium), column_m: Some(a.column_m), end_normal: None };
        if let Some(t) = visit(&chord).filter(|t| *t < length) {
            return Leg::Done(Event::Medium {
                position: from + t * dir,
                dir: a.dir,
                path_length: w.travelled + t,
                medium: w.medium,
            });
        }
    }
    w.travelled += length;
    if shell.open_top() {
        return Leg::Done(Event::Escape { dir: a.dir });
    }
    w.position = a.position - TOP_BACKOFF_M * a.dir;
    w.dir = a.dir;
    Leg::Restart
}

/// `shell`'s ascent for a path that starts where `w` is, if it leaves the air in one move.
fn ascent_from<'s>(
    shell: Option<&'s super::shell::LayeredShell>,
    w: &Walk,
) -> Option<(&'s super::shell::LayeredShell, super::shell::Ascent)> {
    let shell = shell?;
    Some((shell, shell.ascend(w.position, w.dir, w.wavelength_nm)?))
}

/// How far inside a shape's top sphere a path that climbed the layered upper air in one move
/// goes on from, m (it then meets the sphere as a surface).
const TOP_BACKOFF_M: f64 = 1e-4;

/// Hands the chords of the part θ ∈ [0, `theta_end`] of one step to the scene and the visitor;
/// the event, if one happens there.
fn chords_of(
    prop: &Propagator,
    step: &Step,
    tol_m: f64,
    w: &mut Walk,
    visit: &mut dyn FnMut(&Chord) -> Option<f64>,
    theta_end: f64,
) -> Option<Event> {
    let mut count = chord_count(step, tol_m);
    if count > 1 && prop.is_clear(w.medium) && !geometry_near(prop, step, tol_m) {
        // Clear air with nothing to hit near this step: no interaction can happen on it and no
        // surface can be crossed, so one chord serves (and the path length adds the step's arc
        // length, not the chord's).
        count = 1;
    }
    let surfaces = count == 1 || chords_may_hit(prop, step, count);
    for i in 0..count {
        let c = ChordOnArc::part(step, i, count, theta_end);
        let d = c.to - c.from;
        let len = d.length();
        if len.is_nan() || len <= 0.0 {
            continue;
        }
        let u = d / len;
        let hit = if surfaces { prop.world.bvh.intersect(&prop.world.shapes, &Ray::new(c.from, u), len) } else { None };
        let seg = hit.map_or(len, |h| h.t);
        w.chords += 1;
        let end_normal = hit.map(|h| h.normal);
        let chord = Chord { origin: c.from, dir: u, length: seg, medium: Some(w.medium), column_m: None, end_normal };
        if let Some(t) = visit(&chord).filter(|t| *t < seg) {
            return Some(Event::Medium {
                position: c.from + t * u,
                dir: step.direction_at(c.theta_at(t, len)),
                path_length: w.travelled + t,
                medium: w.medium,
            });
        }
        if let Some(h) = hit {
            let (h, theta, chord_dir) = refine(prop, step, &c, h, u);
            return Some(surface(step, theta, h, chord_dir, c.from, w));
        }
        w.travelled += if count == 1 { theta_end * step.h() } else { len };
        if prop.outside_world(c.to) {
            return Some(Event::Escape { dir: step.direction_at(c.theta1) });
        }
    }
    None
}

/// Whether any surface may lie within reach of `step`'s arc: the box around its ends and
/// midpoint, grown by twice the midpoint's distance from the chord (which bounds how far the arc
/// strays from it under the curvature assumption of [`super::arc`]) and the tolerance.
fn geometry_near(prop: &Propagator, step: &Step, tol_m: f64) -> bool {
    let (a, b, m) = (step.y0().r, step.y1().r, step.position_at(0.5));
    let pad = 2.0 * (m - 0.5 * (a + b)).length() + tol_m;
    let min = a.min(b).min(m) - DVec3::splat(pad);
    let max = a.max(b).max(m) + DVec3::splat(pad);
    prop.world.bvh.may_touch_box(&prop.world.shapes, &crate::geometry::Aabb { min, max })
}

/// Whether any of the `count` chords of `step` may meet a surface: false when the box around
/// their end points touches none ([`crate::geometry::Bvh::may_touch_box`], exact for spheres).
/// A chord is the segment between two of those points, so it lies inside their box (which is
/// convex): one box test per step stands in for `count` intersections, and says "no" only where
/// each of them would have found nothing. (Unlike [`geometry_near`] it assumes nothing about
/// the arc between the points.) Steps of more than [`BOXED_CHORDS`] chords are tested chord by
/// chord.
fn chords_may_hit(prop: &Propagator, step: &Step, count: usize) -> bool {
    if count > BOXED_CHORDS {
        return true;
    }
    let (a, b) = (step.y0().r, step.y1().r);
    let (mut min, mut max) = (a.min(b), a.max(b));
    for i in 1..count {
        let p = step.position_at(i as f64 / count as f64);
        (min, max) = (min.min(p), max.max(p));
    }
    let finite = min.is_finite() && max.is_finite();
    !finite || prop.world.bvh.may_touch_box(&prop.world.shapes, &crate::geometry::Aabb { min, max })
}

/// Most chords of one step whose end points [`chords_may_hit`] boxes.
const BOXED_CHORDS: usize = 16;

/// Sub-chords per refinement round and rounds: each round shrinks the sagitta of the chord
/// that crosses the surface by 8² = 64.
const REFINE_PARTS: usize = 8;
const REFINE_ROUNDS: usize = 3;

/// Locates the crossing found on chord `c` more closely on the arc: the part of the arc that the
/// chord spans is cut into finer chords, and the first of them that crosses the surface is
/// searched again. When no finer chord crosses (the arc only grazes the surface, within the
/// tolerance), the chord's own hit stands. Returns the hit, its step fraction θ and the
/// direction of the chord that found it.
fn refine(prop: &Propagator, step: &Step, c: &ChordOnArc, hit: Hit, u: DVec3) -> (Hit, f64, DVec3) {
    let len = (c.to - c.from).length();
    let mut best = (hit, c.theta_at(hit.t, len), u);
    let (mut t0, mut t1) = (c.theta0, c.theta1);
    for _ in 0..REFINE_ROUNDS {
        let mut found = None;
        for j in 0..REFINE_PARTS {
            let a = t0 + (t1 - t0) * j as f64 / REFINE_PARTS as f64;
            let b = t0 + (t1 - t0) * (j + 1) as f64 / REFINE_PARTS as f64;
            let (pa, pb) = (if j == 0 { c.from } else { step.position_at(a) }, step.position_at(b));
            let d = pb - pa;
            let l = d.length();
            if l.is_nan() || l <= 0.0 {
                continue;
            }
            if let Some(h) = prop.world.bvh.intersect(&prop.world.shapes, &Ray::new(pa, d / l), l) {
                found = Some((h, a + (b - a) * (h.t / l).clamp(0.0, 1.0), d / l, a, b));
                break;
            }
        }
        let Some((h, theta, dir, a, b)) = found else { break };
        best = (h, theta, dir);
        (t0, t1) = (a, b);
    }
    best
}

/// The surface event at hit `h` (step fraction `theta`, found by a chord along `chord_dir`): the
/// point and normal of the hit, the arc's tangent as the arriving direction — unless at a
/// grazing hit the tangent and the chord disagree about which side the path arrives from, where
/// the chord (which did cross) decides.
fn surface(step: &Step, theta: f64, mut h: Hit, chord_dir: DVec3, chord_from: DVec3, w: &Walk) -> Event {
    let tangent = step.direction_at(theta);
    let dir = if tangent.dot(h.normal).signum() == chord_dir.dot(h.normal).signum() { tangent } else { chord_dir };
    h.t = w.travelled + (h.point - chord_from).length();
    Event::Surface { hit: h, dir, path_length: h.t, medium: Some(w.medium) }
}
