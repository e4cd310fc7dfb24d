//! Dispersion bundles: the wavelengths of a camera path through a medium that bends each
//! differently, from four traced guides instead of one path per wavelength.
//!
//! In air, n − 1 = K(λ)·q(x) (Gladstone–Dale; [`crate::atmosphere::RadialTable`]), so a path's
//! end — its direction on escape, or the point, normal and direction where it meets a surface —
//! and the transmittance along it are smooth functions of κ = n(λ, x₀) − 1 at the path's start
//! x₀, as long as the paths of the wavelengths all end the same way (on the same surface, or all
//! escaping). A bundle of N ≥ [`MIN_LANES`] lanes traces the guide lanes 0, ⌊N/4⌉, ⌊N/2⌉ and
//! N − 1 in full and gives every other lane i the cubic Lagrange interpolant in κ of the guides'
//! ends and of their transmittances at λᵢ (each guide's path carries every lane's absorption,
//! which costs one density integral per chord: [`crate::media::tracking::transmittances`]).
//!
//! **The check.** The quadratic through guides 0, ⌊N/2⌉ and N − 1, evaluated at the quarter
//! guide, must reproduce its traced end: the point to within `arc_tolerance_m` (what the
//! integrator locates surface crossings to), the direction to within the larger of
//! `arc_tolerance_m / s` radians (s the quarter guide's path length: the angle that moves the
//! path's far end by the arc tolerance) and [`DIRECTION_STEPS`] times the direction error
//! Dormand–Prince allows in one step (atol + rtol/√3 where |v| = n ≈ 1; a traced path of tens
//! of steps carries more than that), and every lane's transmittance to within
//! [`TRANSMITTANCE_TOLERANCE`] of it. (The second bound matters where a path runs on, straight,
//! for thousands of kilometres to the end of the world, which would make the first one far
//! tighter than the integrator's own accuracy.)
//! The quadratic's error is the cubic's error estimate, as a lower-order solution is the error
//! estimate of an embedded Runge–Kutta pair; the cubic is used. Where the check fails — near a
//! fold of a mirage, at a duct's edge, where the guides end on different surfaces — every lane
//! is traced on its own, as without bundles, reusing the guides.
//!
//! An interpolated surface point is put back on the surface by a short probe along the
//! interpolated normal (it must meet the guides' surface within 4 × `arc_tolerance_m`, else
//! that lane is traced on its own), so what follows the hit (shading, photon look-ups,
//! continuation rays) starts exactly on the surface.
//!
//! Where the medium's transmittance has no closed form it is ratio-tracked, each guide's
//! estimate is noisy, and the check refuses the bundle: such paths are traced per lane.
//!
//! Bundles are used only where the medium does not scatter (it only absorbs: no light is
//! gathered along the way, whose position would matter per lane) and for camera paths (a
//! gather path already follows one lane). `[integrator] dispersion_bundles = false` traces
//! every lane, the oracle the tests compare with.

use super::{Along, At, EyeTracer, Mode, Scratch};
use crate::geometry::{Hit, Ray};
use crate::media::tracking::PathDepth;
use crate::raypath::{Event, RayState};
use crate::rng::Rng;
use crate::spectrum::MAX_BANDS;
use glam::DVec3;

pub use crate::scene::BUNDLE_MIN_LANES as MIN_LANES;

/// How far an interpolated transmittance may be from the traced one at the check guide,
/// relative to the larger of the two plus 10⁻⁹ (a transmittance below that is not resolved).
pub const TRANSMITTANCE_TOLERANCE: f64 = 1e-4;

/// The direction of an interpolated end may miss by this many times the error Dormand–Prince
/// allows in the direction in one step (see the module notes).
pub const DIRECTION_STEPS: f64 = 10.0;

/// What the check holds the quarter guide's predicted end to.
#[derive(Clone, Copy, Debug)]
struct Tolerance {
    /// Points, m: `arc_tolerance_m`.
    position_m: f64,
    /// The least direction tolerance, rad: [`DIRECTION_STEPS`] times Dormand–Prince's per step
    /// (0 for the fixed-step integrators).
    direction_floor: f64,
}

/// A probe back onto the surface runs this many arc tolerances each side of the interpolated
/// point.
const PROBE_TOLERANCES: f64 = 4.0;

/// One guide's traced path: its end, the transmittance of every lane along it, its length.
#[derive(Clone, Copy)]
struct Traced {
    event: Event,
    tr: [f64; MAX_BANDS],
    length: f64,
}

/// The guide lanes of a bundle of `n` lanes, in order: the ends, the quarter and the middle.
pub fn guides(n: usize) -> [usize; 4] {
    let last = n - 1;
    [0, (last + 2) / 4, last.div_ceil(2), last]
}

/// The Lagrange basis at `x` on `nodes` (distinct): weights w with Σ w_g f(node_g) the
/// interpolant of f at x.
pub fn lagrange<const N: usize>(nodes: &[f64; N], x: f64) -> [f64; N] {
    std::array::from_fn(|g| (0..N).filter(|h| *h != g).map(|h| (x - nodes[h]) / (nodes[g] - nodes[h])).product())
}

/// Where a path ends, reduced to what interpolates: direction, and on a surface its point,
/// normal and path length.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct End {
    /// Unit direction of travel at the end.
    pub dir: DVec3,
    /// On a surface: the point, the unit normal, the path length.
    pub surface: Option<(DVec3, DVec3, f64)>,
}

/// The surface (primitive, and the medium the path arrives through) a bundle's guides meet.
type OnSurface = (u32, Option<u32>);

/// The guides' ends when they end the same way — all escaping, or all on one surface arriving
/// from the same side through the same medium — with that surface.
fn common_ends(traced: &[Traced; 4]) -> Option<([End; 4], Option<OnSurface>)> {
    let mut ends = [End { dir: DVec3::ZERO, surface: None }; 4];
    let mut on: Option<(u32, Option<u32>, bool)> = None;
    for (g, t) in traced.iter().enumerate() {
        ends[g] = match t.event {
            Event::Escape { dir } if on.is_none() => End { dir, surface: None },
            Event::Surface { hit, dir, path_length, medium } => {
                let side = dir.dot(hit.normal) < 0.0;
                match on {
                    None if g == 0 => on = Some((hit.prim, medium, side)),
                    Some(s) if s == (hit.prim, medium, side) => {}
                    _ => return None,
                }
                End { dir, surface: Some((hit.point, hit.normal, path_length)) }
            }
            _ => return None,
        };
    }
    Some((ends, on.map(|(p, m, _)| (p, m))))
}

/// Σ w_g v_g.
fn combine<const N: usize>(w: &[f64; N], v: [DVec3; N]) -> DVec3 {
    w.iter().zip(v).map(|(w, v)| *w * v).sum()
}

/// The end interpolated at κ = `x` from the guides' ends at `nodes` (the weights of
/// [`lagrange`]): directions and normals renormalised.
pub fn interpolate<const N: usize>(ends: &[End; N], nodes: &[f64; N], x: f64) -> End {
    let w = lagrange(nodes, x);
    let dir = combine(&w, ends.map(|e| e.dir)).normalize();
    let surface = ends[0].surface.map(|_| {
        let s = ends.map(|e| e.surface.unwrap_or((DVec3::ZERO, DVec3::ZERO, 0.0)));
        let length = w.iter().zip(&s).map(|(w, s)| w * s.2).sum();
        (combine(&w, s.map(|s| s.0)), combine(&w, s.map(|s| s.1)).normalize(), length)
    });
    End { dir, surface }
}

/// Whether `guess` is `truth` to within `pos_tol` (points) and `dir_tol` (radians).
pub fn close(guess: &End, truth: &End, pos_tol: f64, dir_tol: f64) -> bool {
    let angle = guess.dir.cross(truth.dir).length().atan2(guess.dir.dot(truth.dir));
    let points = match (guess.surface, truth.surface) {
        (Some(a), Some(b)) => (a.0 - b.0).length() <= pos_tol,
        (None, None) => true,
        _ => false,
    };
    angle <= dir_tol && points
}

/// The fit of a bundle that passed its check: the guides' ends and transmittances, at their κ.
struct Fit {
    nodes: [f64; 4],
    ends: [End; 4],
    surface: Option<OnSurface>,
    tr: [[f64; MAX_BANDS]; 4],
}

impl Fit {
    /// The fit of `traced` at `nodes`, if the quadratic without the quarter guide (index 1)
    /// predicts it (see the module notes).
    fn check(traced: &[Traced; 4], nodes: [f64; 4], lanes: usize, tol: Tolerance) -> Option<Fit> {
        let distinct = (0..4).all(|g| (g + 1..4).all(|h| nodes[g] != nodes[h]));
        if !distinct {
            return None;
        }
        let (ends, surface) = common_ends(traced)?;
        let outer = [nodes[0], nodes[2], nodes[3]];
        let guess = interpolate(&[ends[0], ends[2], ends[3]], &outer, nodes[1]);
        let arc = tol.position_m;
        let dir_tol = (arc / traced[1].length.max(arc)).max(tol.direction_floor);
        if !close(&guess, &ends[1], arc, dir_tol) {
            return None;
        }
        let w = lagrange(&outer, nodes[1]);
        let tr = traced.map(|t| t.tr);
        let tr_ok = (0..lanes).all(|i| {
            let guess = w[0] * tr[0][i] + w[1] * tr[2][i] + w[2] * tr[3][i];
            (guess - tr[1][i]).abs() <= TRANSMITTANCE_TOLERANCE * (guess.abs().max(tr[1][i]) + 1e-9)
        });
        tr_ok.then_some(Fit { nodes, ends, surface, tr })
    }

    /// Lane `i`'s transmittance and end at κ = `x`.
    fn at(&self, i: usize, x: f64) -> (f64, End) {
        let w = lagrange(&self.nodes, x);
        let tr = (0..4).map(|g| w[g] * self.tr[g][i]).sum();
        (tr, interpolate(&self.ends, &self.nodes, x))
    }
}

impl EyeTracer<'_> {
    /// Whether a camera path carrying `lanes` in `medium` is followed as a bundle.
    pub(super) fn bundles(&self, medium: Option<u32>, at: At) -> bool {
        let absorbs_only = medium.is_none_or(|m| !self.scene.world.media[m as usize].scatters());
        self.scene.integrator.dispersion_bundles
            && at.mode == Mode::Camera
            && at.lanes.len >= MIN_LANES
            && absorbs_only
            && self.prop.curved_settings().is_some()
    }

    /// Radiance per lane along `state` from a bundle (see the module notes).
    pub(super) fn bundle(&self, state: &RayState, at: At, rng: &mut Rng, sc: &mut Scratch) -> [f64; MAX_BANDS] {
        let lanes = at.lanes;
        let settings = self.prop.curved_settings();
        let arc = settings.map_or(0.0, |c| c.arc_tolerance_m);
        let floor = settings.and_then(|c| c.kink_tolerance(1.0)).map_or(0.0, |t| DIRECTION_STEPS * t.v());
        let tol = Tolerance { position_m: arc, direction_floor: floor };
        let kappa: [f64; MAX_BANDS] = std::array::from_fn(|i| {
            if i < lanes.len { self.prop.n_at(state.medium, lanes.nm[i], state.position) - 1.0 } else { 0.0 }
        });
        let g = guides(lanes.len);
        let traced = g.map(|j| self.guide(state, j, at, rng, sc));
        let fit = Fit::check(&traced, g.map(|j| kappa[j]), lanes.len, tol);
        let mut out = [0.0; MAX_BANDS];
        for (i, o) in out.iter_mut().enumerate().take(lanes.len) {
            let single = lanes.single(i);
            let one = At { lanes: &single, ..at };
            let end = match g.iter().position(|j| *j == i) {
                Some(k) => Some((traced[k].tr[i], traced[k].event)),
                None => fit.as_ref().and_then(|f| self.interpolated(f, i, kappa[i], arc)),
            };
            *o = match end {
                Some((tr, event)) => {
                    sc.rays.bundled += u64::from(!g.contains(&i));
                    tr * self.end(event, one, rng, sc)[0]
                }
                None => self.radiance(&RayState { wavelength_nm: Some(lanes.nm[i]), ..*state }, one, rng, sc)[0],
            };
        }
        out
    }

    /// Guide lane `j`'s path from `state` to its end, carrying the transmittance of every lane.
    fn guide(&self, state: &RayState, j: usize, at: At, rng: &mut Rng, sc: &mut Scratch) -> Traced {
        sc.rays.eye += 1;
        let s = RayState { wavelength_nm: Some(at.lanes.nm[j]), ..*state };
        let mut along = Along { l: [0.0; MAX_BANDS], tr: [1.0; MAX_BANDS] };
        let mut length = 0.0;
        let nm = &at.lanes.nm[..at.lanes.len];
        let absorbing = state.medium.filter(|m| !self.prop.is_clear(*m));
        let mut depth = absorbing.map(|m| PathDepth::new(&self.scene.world.media[m as usize]));
        let event = self.prop.next_event_with(&s, &mut |c| {
            // The medium only absorbs (see `bundles`): its chords add to the path's optical
            // depth, exponentiated once at the end; a chord elsewhere (none, as paths stop at
            // every surface) is marched.
            match (depth.as_mut().filter(|_| c.medium == absorbing), c.column_m) {
                (Some(d), Some(column)) => d.add_column(column),
                (Some(d), None) => d.add(nm, c.origin, c.dir, c.length, rng),
                (None, _) => self.march(c, at.from_surface.filter(|_| c.origin == s.position), at, &mut along, rng, sc),
            }
            length += c.length;
            None
        });
        if let Some(d) = &depth {
            d.transmittances(nm, &mut along.tr[..nm.len()]);
        }
        Traced { event, tr: along.tr, length }
    }

    /// Lane `i`'s transmittance and end event from the fit at κ = `x`; `None` if its surface
    /// point cannot be put back on the guides' surface.
    fn interpolated(&self, fit: &Fit, i: usize, x: f64, arc: f64) -> Option<(f64, Event)> {
        let (tr, end) = fit.at(i, x);
        let Some((point, normal, path_length)) = end.surface else {
            return Some((tr, Event::Escape { dir: end.dir }));
        };
        let (prim, medium) = fit.surface?;
        let reach = PROBE_TOLERANCES * arc;
        let probe = Ray::new(point + reach * normal, -normal);
        let world = self.prop.world();
        let hit = world.bvh.intersect(&world.shapes, &probe, 2.0 * reach).filter(|h| h.prim == prim)?;
        let hit = Hit { t: path_length, ..hit };
        Some((tr, Event::Surface { hit, dir: end.dir, path_length, medium }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn guides_are_distinct_and_ordered_for_every_bundle_size() {
        for n in MIN_LANES..=MAX_BANDS {
            let g = guides(n);
            assert!(g.windows(2).all(|w| w[0] < w[1]), "{n}: {g:?}");
            assert_eq!((g[0], g[3]), (0, n - 1));
        }
        assert_eq!(guides(16), [0, 4, 8, 15]);
    }

    #[test]
    fn lagrange_weights_reproduce_cubics_and_sum_to_one() {
        let nodes = [0.3, 0.9, 1.4, 2.0];
        let f = |x: f64| 2.0 - x + 0.5 * x * x - 0.25 * x * x * x;
        for x in [0.3, 0.5, 1.0, 1.7, 2.0] {
            let w = lagrange(&nodes, x);
            let fit: f64 = w.iter().zip(nodes).map(|(w, n)| w * f(n)).sum();
            assert!((fit - f(x)).abs() < 1e-13, "{x}: {fit} vs {}", f(x));
            assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-14);
        }
    }

    #[test]
    fn ends_interpolate_along_a_smooth_family_and_the_check_sees_a_kink() {
        // Ends on a circle of directions at the angle θ(κ) = 0.01 + 0.2κ + 0.05κ². The
        // interpolants' errors are those of interpolating sin θ(κ) and cos θ(κ): f‴/6·Π(κ − κ_g)
        // ≈ 1.0e-5 rad for the quadratic at the quarter guide, f⁗/24·Π(κ − κ_g) ≈ 1.2e-6 rad for
        // the cubic at κ = 0.7 (evaluated independently in double precision).
        let end = |k: f64| {
            let a: f64 = 0.01 + 0.2 * k + 0.05 * k * k;
            End { dir: DVec3::new(a.sin(), 0.0, a.cos()), surface: None }
        };
        let nodes = [1.0, 0.9, 0.8, 0.6];
        let ends = nodes.map(end);
        let outer = [nodes[0], nodes[2], nodes[3]];
        let guess = interpolate(&[ends[0], ends[2], ends[3]], &outer, nodes[1]);
        assert!(close(&guess, &ends[1], 0.0, 1.2e-5) && !close(&guess, &ends[1], 0.0, 0.9e-5));
        let mid = interpolate(&ends, &nodes, 0.7);
        assert!(close(&mid, &end(0.7), 0.0, 1.4e-6) && !close(&mid, &end(0.7), 0.0, 1.0e-6));
        // A kink between the guides (the family jumps by 1e-3 rad beyond κ = 0.85): the
        // prediction misses the quarter guide by (0.75 − 0.125)·1e-3 rad, the weights of the two
        // shifted guides.
        let kinked = |k: f64| {
            let e = end(k);
            if k > 0.85 { e } else { End { dir: (e.dir + DVec3::new(1e-3, 0.0, 0.0)).normalize(), ..e } }
        };
        let ends = nodes.map(kinked);
        let guess = interpolate(&[ends[0], ends[2], ends[3]], &outer, nodes[1]);
        assert!(!close(&guess, &ends[1], 0.0, 6e-4) && close(&guess, &ends[1], 0.0, 6.5e-4));
    }

    fn escaping(dir: DVec3, tr: f64, length: f64) -> Traced {
        Traced { event: Event::Escape { dir }, tr: [tr; MAX_BANDS], length }
    }

    fn landing(prim: u32, point: DVec3, dir: DVec3, tr: f64) -> Traced {
        let hit = Hit { t: 1e4, point, normal: DVec3::Y, prim };
        Traced {
            event: Event::Surface { hit, dir, path_length: 1e4, medium: Some(0) },
            tr: [tr; MAX_BANDS],
            length: 1e4,
        }
    }

    #[test]
    fn a_bundle_needs_its_guides_to_end_alike_and_on_the_curve() {
        let nodes = [3.0e-4, 2.95e-4, 2.9e-4, 2.8e-4];
        let tol = Tolerance { position_m: 0.5, direction_floor: 0.0 };
        // Directions and transmittances linear in κ: the check holds.
        let dir = |k: f64| DVec3::new(0.0, 10.0 * k, 1.0).normalize();
        let tr = |k: f64| 0.5 + 100.0 * k;
        let smooth = nodes.map(|k| escaping(dir(k), tr(k), 1e6));
        let fit = Fit::check(&smooth, nodes, 16, tol).expect("a smooth bundle passes");
        let (t, end) = fit.at(3, 2.85e-4);
        assert!((t - tr(2.85e-4)).abs() < 1e-12 && close(&end, &End { dir: dir(2.85e-4), surface: None }, 0.0, 1e-12));
        // The quarter guide's transmittance off the curve by 2e-4 of itself: refused.
        let mut off = smooth;
        off[1].tr[5] *= 1.0 + 2.0 * TRANSMITTANCE_TOLERANCE;
        assert!(Fit::check(&off, nodes, 16, tol).is_none());
        // ... its direction off by 1e-6 rad, twice the 0.5 m / 1e6 m allowed: refused.
        let mut off = smooth;
        off[1].event = Event::Escape { dir: (dir(nodes[1]) + DVec3::new(1e-6, 0.0, 0.0)).normalize() };
        assert!(Fit::check(&off, nodes, 16, tol).is_none());
        // ... unless the integrator's own per-step floor is larger (a path running on straight
        // for thousands of kilometres): 10 × 1.6e-7 rad admits it.
        assert!(Fit::check(&off, nodes, 16, Tolerance { direction_floor: 1.6e-6, ..tol }).is_some());
        // One guide lands while the others escape, or two land on different surfaces: refused.
        let p = DVec3::new(0.0, 0.0, 1e4);
        let mut mixed = smooth;
        mixed[2] = landing(1, p, dir(nodes[2]), tr(nodes[2]));
        assert!(Fit::check(&mixed, nodes, 16, tol).is_none());
        let on = |prim: [u32; 4]| std::array::from_fn(|g| landing(prim[g], p, dir(nodes[g]), tr(nodes[g])));
        assert!(Fit::check(&on([1, 1, 2, 1]), nodes, 16, tol).is_none());
        assert!(Fit::check(&on([1; 4]), nodes, 16, tol).is_some());
        // Two guides at the same κ (a medium whose n does not depend on λ at the start): refused.
        let same = [nodes[0], nodes[0], nodes[2], nodes[3]];
        assert!(Fit::check(&smooth, same, 16, tol).is_none());
    }
}
