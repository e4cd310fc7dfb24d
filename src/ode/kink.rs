//! Kinks as step ends: where a radial field's gradient jumps (a standard atmosphere's layer
//! boundaries, where dT/dh changes; a hot road's edit, held constant below the ground) an
//! integrator step that straddles the kink sees a discontinuous right-hand side. The error
//! estimate of a Dormand–Prince step whose last stages (c = 1) lie past a jump Δg of ∇n is
//! (e₆ + e₇)·h·Δg = 0.0169·h·Δg in the ray vector v, however little it straddles (e₆, e₇ the
//! error weights of the two stages at the step's end, [`crate::ode::dopri5`]) — so a step of
//! kilometres that ends just past the 11 km tropopause (Δg ≈ 3·10⁻⁹ m⁻¹) fails a 10⁻⁹ tolerance,
//! and so does any step that ends past a hot road's surface. Each step is therefore cut where the
//! path meets the next kink sphere |p − C| = R_k:
//!
//! - the crossing is predicted from the path's curvature, not a straight line: with
//!   q = p − C, d the unit direction and a = (∇n − (∇n·d)d)/n the curvature vector, the path
//!   p + td + ½t²a + O(t³) has |q + td + ½t²a|² = |q|² + 2(q·d)t + (1 + q·a)t² + O(t³) (d ⊥ a),
//!   so the crossing is the smallest positive root of (1 + q·a)t² + 2(q·d)t + |q|² − R_k² = 0.
//!   (The straight line, the same without q·a, was ~100 m off over a 10 km grazing step: q·a ≈
//!   −0.17 at sea level, the refraction that makes the effective Earth radius 4/3 R.) The cubic
//!   term left out, from the change of a along the step over the field's scale length L, moves
//!   the crossing by δt ≈ |a|·|ṙ|·t³/(6L·|ṙ_c|), ṙ and ṙ_c the path's rate of climb now and at
//!   the crossing;
//! - when 0.0169·t·Δg is within half the tolerance of v, one step goes to just past the kink
//!   (relatively 10⁻⁷ and 0.1 mm beyond the predicted crossing), so the next starts on the far
//!   side and sees a smooth field;
//! - otherwise the kink is crossed in two steps: the first ends short of it, by the larger of
//!   4 δt and half the longest step whose straddle would pass (at most 1 m, at most half the
//!   way), with all its stages on the near side; the second, short, goes across.
//!
//! A hot road's kink is its ground: there the step across ends a little below the road, where
//! the chords find it, and the part of the step past it is never used. A cut step keeps the
//! controller's proposal for the next one ([`crate::ode::Integrator::step`]), so the step size is
//! not lost at the cut.
//!
//! Spheres of the scene that are not kinks (a sea under a smooth profile) are not step ends: a
//! step aimed at a surface ends within the prediction's error of it, and one that ends a few
//! nanometres short of an Earth-sized sphere starts the next where the sphere's intersection
//! cannot tell the surface from the ray's origin (a ray in a 1000 km surface duct went through
//! the sea after 19 bounces when the sea was a step end).
//!
//! # References
//! - E. Hairer, S. P. Nørsett, G. Wanner, *Solving Ordinary Differential Equations I*, 2nd ed.,
//!   Springer 1993, §II.6 (discontinuities: "the step size control is then unable to cope … it
//!   is better to stop the integration at the discontinuity and to restart").

use super::dopri5::{E6, E7};
use glam::DVec3;

/// A sphere |p − C| = R where the field's gradient may jump.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Kink {
    /// Radius R, m.
    pub radius_m: f64,
    /// |Δ∇n| across it, m⁻¹ (0 where the field is smooth there, as over a sea).
    pub jump: f64,
    /// The shorter of the lengths |∇n|/|∂∇n/∂r| on its two sides, m: how fast the path's
    /// curvature changes near it.
    pub scale_m: f64,
}

/// Spheres about a centre where a field's gradient may jump.
#[derive(Clone, Debug, PartialEq)]
pub struct KinkSpheres {
    /// Centre, m.
    pub centre: DVec3,
    /// The spheres.
    pub kinks: Vec<Kink>,
}

/// A step across a kink is cut this far beyond the predicted crossing (relatively, and 0.1 mm),
/// so that it ends past the kink rather than just short of it: a step that started a hair short
/// of the kink would straddle it with all its stages but the first.
const BEYOND: f64 = 1e-7;
const BEYOND_M: f64 = 1e-4;

/// The error weight of a Dormand–Prince step on the stages at its end: a jump Δg of the
/// right-hand side past the end adds |E_END|·h·Δg to the error estimate of v.
const E_END: f64 = E6 + E7;

/// The longest first step of a crossing in two ends at most this far short of the kink, m.
const SHORT_MAX_M: f64 = 1.0;

/// Radial offsets at which a kink's jump and scale are sampled, m.
const PROBE_M: f64 = 1e-3;
const SCALE_PROBE_M: f64 = 1.0;

/// Jumps are measured at one wavelength; n − 1 varies by a few per cent over the visible (Ciddor:
/// 3 % from 400 to 700 nm), so they are taken this much larger.
const JUMP_MARGIN: f64 = 1.25;

impl Kink {
    /// The kink at `radius_m` about `centre` of a field sampled by `sample` (n and ∇n at a
    /// point): the jump and scale probed along the +y radius.
    pub fn probe(sample: &dyn Fn(DVec3) -> (f64, DVec3), centre: DVec3, radius_m: f64) -> Kink {
        let at = |dr: f64| sample(centre + DVec3::Y * (radius_m + dr)).1;
        let (below, above) = (at(-PROBE_M), at(PROBE_M));
        let jump = JUMP_MARGIN * (above - below).length();
        let side = |g0: DVec3, g1: DVec3| {
            let d = (g1 - g0).length() / (SCALE_PROBE_M - PROBE_M);
            if d > 0.0 { g0.length().max(g1.length()) / d } else { f64::INFINITY }
        };
        let scale_m = side(below, at(-SCALE_PROBE_M)).min(side(above, at(SCALE_PROBE_M)));
        Kink { radius_m, jump: if jump.is_finite() { jump } else { f64::INFINITY }, scale_m: scale_m.max(PROBE_M) }
    }
}

impl KinkSpheres {
    /// The kinks at `radii_m` about `centre` of the field `sample`, sorted, duplicates (within
    /// 1 µm) merged.
    pub fn new(sample: &dyn Fn(DVec3) -> (f64, DVec3), centre: DVec3, radii_m: &[f64]) -> KinkSpheres {
        let mut radii: Vec<f64> = radii_m.iter().copied().filter(|r| r.is_finite() && *r > 0.0).collect();
        radii.sort_by(f64::total_cmp);
        radii.dedup_by(|a, b| (*a - *b).abs() < 1e-6);
        KinkSpheres { centre, kinks: radii.into_iter().map(|r| Kink::probe(sample, centre, r)).collect() }
    }

    /// How long the next step from `p` may be: up to the next kink crossing — just past it, or
    /// short of it when the jump would fail a long step across (see the module notes) — or
    /// `None` when the path meets none.
    ///
    /// `dir` is the unit direction, `bend` the curvature vector a = (∇n − (∇n·d)d)/n (m⁻¹),
    /// `min_m` the distance below which a crossing is the one the path is on, and `tol_v` the
    /// error the integrator allows in the ray vector v per step (`None`: a fixed-step method,
    /// which rejects nothing; every kink is then crossed in one step).
    pub fn next_cut(&self, p: DVec3, dir: DVec3, bend: DVec3, min_m: f64, tol_v: Option<f64>) -> Option<f64> {
        let q = p - self.centre;
        let r = q.length();
        let b = q.dot(dir);
        let a2 = 1.0 + q.dot(bend);
        let (t, k) = first_crossing(self.candidates(r, a2), r, a2, b, min_m)?;
        let across = t * (1.0 + BEYOND) + BEYOND_M;
        let Some(tol) = tol_v else { return Some(across) };
        // The longest step across whose straddle error stays within half the tolerance.
        let reach = 0.5 * tol / (E_END.abs() * k.jump);
        if t <= reach {
            return Some(across);
        }
        let climb_now = b / r;
        let climb_there = ((b + a2 * t) / k.radius_m).abs().max(1e-9);
        let spread = bend.length() * climb_now.abs().max(climb_there) * t * t * t / (6.0 * k.scale_m * climb_there);
        let short = (4.0 * spread).max((0.5 * reach).min(SHORT_MAX_M)).min(0.5 * t);
        Some(t - short)
    }
}

impl KinkSpheres {
    /// The kinks the model path from radius `r` can meet first: all of them, or where
    /// 1 + q·a = `a2` > 0 only the [`WINDOW`] on either side of `r`. There the squared radius
    /// along the model path, ρ²(t) = r² + 2bt + a2·t², is convex in t, so before it reaches a
    /// kink's level it passes every level between that and ρ(min_m) (intermediate values): the
    /// first crossing is of a kink next to ρ(min_m), which is within min_m (1 µm) of `r`, and
    /// kinks closer than 1 µm are merged ([`KinkSpheres::new`]). Two on each side leave a
    /// margin; `tests::the_window_finds_the_crossing_all_kinks_find` checks it against all.
    fn candidates(&self, r: f64, a2: f64) -> &[Kink] {
        if !(a2 > 0.0 && r.is_finite()) {
            return &self.kinks;
        }
        let j = self.kinks.partition_point(|k| k.radius_m < r);
        &self.kinks[j.saturating_sub(WINDOW)..(j + WINDOW).min(self.kinks.len())]
    }
}

/// Kinks on each side of the path's radius that [`KinkSpheres::next_cut`] tries where the model
/// path is convex in ρ².
const WINDOW: usize = 2;

/// The nearest crossing beyond `min_m` of the model path from radius `r` (slope `b` = q·d,
/// curvature term `a2` = 1 + q·a) with one of `kinks`, and that kink.
fn first_crossing(kinks: &[Kink], r: f64, a2: f64, b: f64, min_m: f64) -> Option<(f64, &Kink)> {
    let mut best: Option<(f64, &Kink)> = None;
    for k in kinks {
        // (1 + q·a)t² + 2bt + c = 0 with c = (r − R)(r + R), roots in the stable form.
        let c = (r - k.radius_m) * (r + k.radius_m);
        if let Some(t) = first_root(a2, b, c, min_m)
            && best.is_none_or(|(tb, _)| t < tb)
        {
            best = Some((t, k));
        }
    }
    best
}

/// The smallest root t > `min_m` of a·t² + 2b·t + c = 0, if any.
fn first_root(a: f64, b: f64, c: f64, min_m: f64) -> Option<f64> {
    let disc = b * b - a * c;
    if disc < 0.0 {
        return None;
    }
    // q = −(b + sign(b)√disc): the roots are q/a and c/q, neither by cancellation.
    let q = -(b + b.signum() * disc.sqrt());
    let roots = [if a != 0.0 { q / a } else { f64::NAN }, if q != 0.0 { c / q } else { f64::NAN }];
    roots.into_iter().filter(|t| *t > min_m).min_by(f64::total_cmp)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Spheres without jumps (a fixed-step integrator's view: every cut goes across).
    fn smooth(centre: DVec3, radii: &[f64]) -> KinkSpheres {
        KinkSpheres {
            centre,
            kinks: radii.iter().map(|&radius_m| Kink { radius_m, jump: 0.0, scale_m: f64::INFINITY }).collect(),
        }
    }

    #[test]
    fn the_cut_is_just_past_the_nearest_crossing_ahead() {
        let k = smooth(DVec3::ZERO, &[10.0, 20.0]);
        let cut = |p: DVec3, d: DVec3| k.next_cut(p, d, DVec3::ZERO, 1e-9, None);
        // From r = 15 outward along x: the sphere of 20 at t = 5.
        let t = cut(DVec3::new(15.0, 0.0, 0.0), DVec3::X).unwrap();
        assert!(t > 5.0 && t < 5.0 + 2e-4, "{t}");
        // Inward: the sphere of 10 at t = 5.
        let t = cut(DVec3::new(15.0, 0.0, 0.0), -DVec3::X).unwrap();
        assert!(t > 5.0 && t < 5.0 + 2e-4, "{t}");
        // Tangent-ish line above the inner sphere: meets only the outer one, at √(20² − 15²).
        let t = cut(DVec3::new(0.0, 15.0, 0.0), DVec3::X).unwrap();
        assert!((t - (400.0f64 - 225.0).sqrt()).abs() < 2e-4, "{t}");
        // On a kink, going out: the crossing at t = 0 is skipped; beyond the last sphere, none.
        let t = cut(DVec3::new(10.0, 0.0, 0.0), DVec3::X).unwrap();
        assert!(t > 10.0 && t < 10.0 + 2e-4, "{t}");
        assert_eq!(cut(DVec3::new(30.0, 0.0, 0.0), DVec3::X), None);
    }

    #[test]
    fn earth_scale_crossings_are_found_without_cancellation() {
        let r_earth = 6.371e6;
        let k = smooth(DVec3::new(0.0, -r_earth, 0.0), &[r_earth + 11_000.0]);
        // From 10 999 m straight up: 1 m to the kink.
        let t = k.next_cut(DVec3::new(0.0, 10_999.0, 0.0), DVec3::Y, DVec3::ZERO, 1e-9, None).unwrap();
        assert!((t - 1.0).abs() < 2e-4, "{t}");
    }

    #[test]
    fn a_circular_path_meets_the_sphere_where_the_circle_does() {
        // A path of curvature 1/ρ, level at r0 and bending away from the centre (q·a = r0/ρ > 0),
        // is the circle x = ρ sin(t/ρ), y = r0 + ρ(1 − cos(t/ρ)); it climbs to the sphere of
        // radius r0 + 1 where x² + y² = (r0 + 1)² (solved by bisection below). The quadratic
        // model is good to O(t³/ρ²) there; the straight line is 8 m off.
        let (r0, rho) = (1000.0, 2000.0);
        let k = smooth(DVec3::ZERO, &[r0 + 1.0]);
        let bend = DVec3::Y / rho;
        let t = k.next_cut(DVec3::new(0.0, r0, 0.0), DVec3::X, bend, 1e-9, None).unwrap() - BEYOND_M;
        // Exact: solve |(ρ sin u, r0 + ρ(1 − cos u))|² = (r0 + 1)² for u = t/ρ by bisection.
        let f = |u: f64| (rho * u.sin()).powi(2) + (r0 + rho * (1.0 - u.cos())).powi(2) - (r0 + 1.0f64).powi(2);
        let (mut lo, mut hi) = (0.0, 1.0);
        for _ in 0..100 {
            let m = 0.5 * (lo + hi);
            if f(m) > 0.0 { hi = m } else { lo = m }
        }
        let exact = rho * 0.5 * (lo + hi);
        // The straight line meets the sphere at √((r0 + 1)² − r0²) = 44.7 m; the circle at 36.5 m.
        let line = ((r0 + 1.0f64).powi(2) - r0 * r0).sqrt();
        assert!((t - exact).abs() < 0.02 * (line - exact).abs(), "model {t}, circle {exact}, line {line}");
    }

    #[test]
    fn a_large_jump_far_ahead_is_crossed_in_two_steps() {
        // Δg = 10⁻⁶ m⁻¹ at tolerance 10⁻⁹: a step across may be at most 0.5e-9/(0.0169·1e-6) ≈
        // 3 cm long, so from 100 m below the first step ends short of the kink, within 1.5 cm of
        // it; from there the step goes across.
        let k = KinkSpheres { centre: DVec3::ZERO, kinks: vec![Kink { radius_m: 1000.0, jump: 1e-6, scale_m: 10.0 }] };
        let first = k.next_cut(DVec3::new(0.0, 900.0, 0.0), DVec3::Y, DVec3::ZERO, 1e-9, Some(1e-9)).unwrap();
        assert!(first < 100.0 && first > 100.0 - 0.015, "{first}");
        let second = k.next_cut(DVec3::new(0.0, 900.0 + first, 0.0), DVec3::Y, DVec3::ZERO, 1e-9, Some(1e-9)).unwrap();
        assert!(second > 100.0 - first && second < 100.0 - first + 2e-4, "{second}");
        // A small jump is crossed at once.
        let k = KinkSpheres { centre: DVec3::ZERO, kinks: vec![Kink { radius_m: 1000.0, jump: 1e-15, scale_m: 10.0 }] };
        let t = k.next_cut(DVec3::new(0.0, 900.0, 0.0), DVec3::Y, DVec3::ZERO, 1e-9, Some(1e-9)).unwrap();
        assert!(t > 100.0 && t < 100.0 + 2e-4, "{t}");
    }
    /// Where 1 + q·a > 0 the kinks next to the path's radius give the crossing all of them give
    /// (the same t, the same kink), at random points — on a kink, within a micrometre of one, and
    /// anywhere — going any way, with curvatures up to twice the spheres' (so 1 + q·a takes both
    /// signs; where it is ≤ 0 all are tried). Twelve kinks, two of them 2 µm apart.
    #[test]
    fn the_window_finds_the_crossing_all_kinks_find() {
        let mut rng = crate::rng::Rng::for_task(18, crate::rng::Stream::Eye, 6);
        let mut radii: Vec<f64> = (0..10).map(|i| 1000.0 + 10.0 * i as f64 + 3.0 * (i % 3) as f64).collect();
        radii.extend([1_040.000_002, 1_040.000_004]);
        let k = KinkSpheres::new(&|_| (1.0, DVec3::ZERO), DVec3::ZERO, &radii);
        assert_eq!(k.kinks.len(), 12, "kinks 2 µm apart are kept");
        let (mut found, mut windowed) = (0, 0);
        for i in 0..20_000 {
            let [u, v] = rng.uniform2();
            let [w, z] = rng.uniform2();
            let on = k.kinks[(u * 12.0) as usize % 12].radius_m;
            let r = match i % 3 {
                0 => on,
                1 => on + (2.0 * v - 1.0) * 1e-6,
                _ => 990.0 + 120.0 * v,
            };
            let up = DVec3::new((2.0 * w - 1.0) * 0.3, 1.0, 0.0).normalize();
            let p = up * r;
            let (y, phi) = (2.0 * z - 1.0, std::f64::consts::TAU * w);
            let dir = DVec3::new((1.0 - y * y).sqrt() * phi.cos(), y, (1.0 - y * y).sqrt() * phi.sin());
            let side = dir.cross(up).normalize_or_zero();
            let bend = (side * (2.0 * v - 1.0) + up * (2.0 * u - 1.0)) * (0.25 / 1000.0) * z * 8.0;
            let (b, a2) = (p.dot(dir), 1.0 + p.dot(bend));
            let all = first_crossing(&k.kinks, r, a2, b, 1e-6).map(|(t, k)| (t, k.radius_m));
            let window = k.candidates(r, a2);
            windowed += usize::from(window.len() < k.kinks.len());
            let got = first_crossing(window, r, a2, b, 1e-6).map(|(t, k)| (t, k.radius_m));
            assert_eq!(got, all, "r {r}, dir {dir}, bend {bend}, a2 {a2}");
            found += usize::from(all.is_some());
        }
        assert!(windowed > 10_000 && found > 10_000, "windowed {windowed}, found {found}");
    }
}
