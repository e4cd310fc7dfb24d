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
//! # Approaching a layer
//!
//! Some kinks bound a thin layer: a hot road's, where ∇n grows as e^(−height/6.7 m) towards the
//! road. A step aimed at such a kink from far above dives into the layer in one go, its last
//! stages see a gradient thousands of times that of its first, and it is rejected; the retries
//! (0.2× each) and the no-growth rule after a rejection then cost a dozen steps before the layer
//! is reached (measured: 45 attempts for a sun photon in `mirage_hot_road`, 22 of them in the
//! last kilometre). Where |∇n| on the path's side grows towards the kink with e-folding depth L
//! (probed next to it: the side's gradient G and L) and the layer is thin — 4L shorter than the
//! way to the next kink on that side, which leaves out a standard atmosphere's layer boundaries,
//! as far apart as its scale height — the step ends where the layer's field would make it fail:
//! along a path that meets the kink t ahead from depth Δr, the layer grows e-fold every
//! ℓ = L·t/Δr, a step of length xℓ ends where ∇n = G·e^(x − Δr/L), and the step's error
//! estimate through a field growing as e^(s/ℓ) is, in v, xℓ·∇n(end)·K(x) and, in r,
//! (xℓ)²·∇n(end)·K_r(x)/n, with K and K_r sums over the tableau (bounded by the constants
//! `KV_MAX`, `KV4`, `KR_MAX`, `KR3` below). The longest x whose bounds stay within the
//! controller's tolerance for an error along the radial direction (one component's share, so
//! the step passes with room) solves x + m·ln x = b for m = 1, 2, 5 (Newton). The result: one
//! step to where the layer begins to matter, then steps that shrink with it, none rejected
//! (that sun photon: 31 attempts; 26 with the first step at the top of the atmosphere that
//! `raypath::curved` now takes).
//!
//! # Thin layers
//!
//! A temperature inversion's gradient is a smooth bump (Fermi, ∝ σ(1 − σ), 4w thick) with no
//! jump, and plain step control dives into it from the calm air above and fails, several
//! times over (a third of `mirage_superior`'s photon-pass attempts). Its peak is a step end
//! ([`Kink::layer`]) whose two sides are approached as above, the layer modelled as growing
//! e-fold every w up to twice |∇n| at the peak; a step that crosses the peak is flagged
//! ([`Cut::into_layer`]) so that its caller leaves the peak with the step it came in with
//! (the field falls away as it grew), not the controller's proposal kept from before the layer.
//! Where the integrator's own proposal already passes a layer's test
//! ([`KinkSpheres::next_cut_within`]), the longest step that would is not solved for.
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
    /// The field just inside (index 0) and just outside (1) the sphere, for paths that approach
    /// it from that side.
    pub sides: [Side; 2],
}

/// The field on one side of a kink.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Side {
    /// |∇n| next to the kink, m⁻¹.
    pub gradient: f64,
    /// |∇n|/|∂∇n/∂r| next to the kink, m (∞ where ∇n does not change): the depth over which the
    /// field grows e-fold towards it.
    pub scale_m: f64,
}

impl Side {
    /// No field: nothing to approach.
    pub const FLAT: Side = Side { gradient: 0.0, scale_m: f64::INFINITY };
}

/// The error a Dormand–Prince step may make, as kink cuts judge a step by: the controller's
/// tolerances and |v| = n where the step starts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerance {
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance.
    pub atol: f64,
    /// |v| = n at the step's start.
    pub n: f64,
}

impl Tolerance {
    /// The error allowed in one component of v: atol + rtol·n/√3 (a component's share of |v|),
    /// what a straddle is judged by.
    pub fn v(&self) -> f64 {
        self.atol + self.rtol * self.n / 3f64.sqrt()
    }

    /// The size of an error along the unit vector `u` in a state component whose value is `y`
    /// that weighs in the controller's norm as one component at its tolerance: 1/‖u ⊘ sc‖ with
    /// scᵢ = atol + rtol·|yᵢ| (the norm of [`crate::ode::Controller`]).
    fn along(&self, u: DVec3, y: DVec3) -> f64 {
        let sc = DVec3::splat(self.atol) + self.rtol * y.abs();
        1.0 / (u / sc).length()
    }
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
        // The scale |∇n|/|∂∇n/∂r| on one side from ∇n next to the kink (g0) and 1 m away (g1),
        // and that side as a layer to approach where |∇n| grows towards the kink.
        let side = |g0: DVec3, g1: DVec3| {
            let d = (g1 - g0).length() / (SCALE_PROBE_M - PROBE_M);
            let scale_m = if d > 0.0 { (g0.length().max(g1.length()) / d).max(PROBE_M) } else { f64::INFINITY };
            let gradient = g0.length();
            let layer = gradient > g1.length() && gradient.is_finite() && scale_m.is_finite();
            (scale_m, if layer { Side { gradient, scale_m } } else { Side::FLAT })
        };
        let (below_scale, below) = side(below, at(-SCALE_PROBE_M));
        let (above_scale, above) = side(above, at(SCALE_PROBE_M));
        let scale_m = below_scale.min(above_scale);
        Kink { radius_m, jump: if jump.is_finite() { jump } else { f64::INFINITY }, scale_m, sides: [below, above] }
    }

    /// The peak of a thin layer at `radius_m` about `centre` (a smooth bump of |∇n|, an
    /// inversion's), whose gradient falls off e-fold every `scale_m` on either side far from
    /// it: a step end (there is no jump to straddle, but past it the field no longer grows),
    /// approached from both sides as a layer whose |∇n| grows towards it with that depth up to
    /// `LAYER_ENVELOPE` = 2 times |∇n| at the peak. For a Fermi step (peak gradient P,
    /// 4P·σ(1 − σ) = 4P·e^{−|u|}/(1 + e^{−|u|})²) that model, 2P·e^{−|u|}, is the larger
    /// wherever |u| ≥ 0.88 (2/(1 + e^{−|u|})² ≤ 1): everywhere a step approaching the peak is
    /// judged but its last. The air's own gradient is counted in P, which makes it larger still.
    /// Measured on `mirage_superior`'s photon pass (300 000 photons, the book's curved-paths
    /// page): rejected steps 32 % → 1.1 %, field samples −43 %; the bound 4P (everywhere above
    /// the layer's) rejects 0.1 % but takes 6 % more samples, P alone 10.7 % and 8 % more.
    pub fn layer(sample: &dyn Fn(DVec3) -> (f64, DVec3), centre: DVec3, radius_m: f64, scale_m: f64) -> Kink {
        let mut k = Kink::probe(sample, centre, radius_m);
        let gradient = LAYER_ENVELOPE * sample(centre + DVec3::Y * radius_m).1.length();
        if gradient.is_finite() && gradient > 0.0 && scale_m > 0.0 {
            k.sides = [Side { gradient, scale_m }; 2];
        }
        k
    }
}

/// |∇n| of a thin layer's envelope at its peak, in units of |∇n| there ([`Kink::layer`]).
const LAYER_ENVELOPE: f64 = 2.0;

impl KinkSpheres {
    /// The kinks at `radii_m` about `centre` of the field `sample`, sorted, duplicates (within
    /// 1 µm) merged.
    pub fn new(sample: &dyn Fn(DVec3) -> (f64, DVec3), centre: DVec3, radii_m: &[f64]) -> KinkSpheres {
        let kinks = radii_m.iter().filter(|r| r.is_finite() && **r > 0.0).map(|&r| Kink::probe(sample, centre, r));
        KinkSpheres { centre, kinks: kinks.collect() }.sorted()
    }

    /// These kinks and the peaks of thin layers, (radius, e-folding depth of the envelope) in
    /// m ([`Kink::layer`]), as step ends.
    pub fn with_layers(mut self, sample: &dyn Fn(DVec3) -> (f64, DVec3), layers: &[(f64, f64)]) -> KinkSpheres {
        let ok = |r: f64, l: f64| r.is_finite() && r > 0.0 && l.is_finite() && l > 0.0;
        let centre = self.centre;
        self.kinks.extend(layers.iter().filter(|(r, l)| ok(*r, *l)).map(|&(r, l)| Kink::layer(sample, centre, r, l)));
        self.sorted()
    }

    /// The kinks sorted, duplicates (within 1 µm) merged (the first kept), and only thin layers
    /// approached: a side whose e-folding depth fits [`APPROACH_DEPTHS`] times within the way to
    /// the next kink on that side (not a smooth atmosphere's layer, whose scale height is about
    /// as long as its layers are thick).
    fn sorted(mut self) -> KinkSpheres {
        self.kinks.sort_by(|a, b| a.radius_m.total_cmp(&b.radius_m));
        self.kinks.dedup_by(|b, a| (b.radius_m - a.radius_m).abs() < 1e-6);
        let radii: Vec<f64> = self.kinks.iter().map(|k| k.radius_m).collect();
        for (i, k) in self.kinks.iter_mut().enumerate() {
            let gaps = [
                if i > 0 { radii[i] - radii[i - 1] } else { f64::INFINITY },
                radii.get(i + 1).map_or(f64::INFINITY, |r| r - radii[i]),
            ];
            for (side, gap) in k.sides.iter_mut().zip(gaps) {
                if APPROACH_DEPTHS * side.scale_m >= gap {
                    *side = Side::FLAT;
                }
            }
        }
        self
    }

    /// How long the next step from `p` may be: up to the next kink crossing — just past it, or
    /// short of it when the jump would fail a long step across (see the module notes) — or
    /// `None` when the path meets none.
    ///
    /// `dir` is the unit direction, `bend` the curvature vector a = (∇n − (∇n·d)d)/n (m⁻¹),
    /// `min_m` the distance below which a crossing is the one the path is on, and `tol` the
    /// error the integrator allows per step (`None`: a fixed-step method, which rejects nothing;
    /// every kink is then crossed in one step).
    pub fn next_cut(&self, p: DVec3, dir: DVec3, bend: DVec3, min_m: f64, tol: Option<Tolerance>) -> Option<f64> {
        self.next_cut_within(p, dir, bend, min_m, tol, f64::INFINITY).map(|c| c.length_m)
    }

    /// [`KinkSpheres::next_cut`] for an integrator that will try a step of at most `h_want`
    /// (m; its controller's proposal, ∞ when it has none): where a step that long passes a
    /// layer's test, the longest one that would is not solved for (it is longer,
    /// and the step is no different), which saves a dozen exponentials on most steps of a path
    /// that runs beside a layer (a ray trapped under an inversion).
    pub fn next_cut_within(
        &self,
        p: DVec3,
        dir: DVec3,
        bend: DVec3,
        min_m: f64,
        tol: Option<Tolerance>,
        h_want: f64,
    ) -> Option<Cut> {
        let q = p - self.centre;
        let r = q.length();
        let b = q.dot(dir);
        let a2 = 1.0 + q.dot(bend);
        let (t, k) = first_crossing(self.candidates(r, a2), r, a2, b, min_m)?;
        let across = t * (1.0 + BEYOND) + BEYOND_M;
        let Some(tol) = tol else { return Some(Cut { length_m: across, into_layer: false }) };
        let approach = approach(k, r, t, &Approach { tol, p, v: dir * tol.n, radial: q / r, h_want });
        // The longest step across whose straddle error stays within half the tolerance.
        let reach = 0.5 * tol.v() / (E_END.abs() * k.jump);
        if t <= reach {
            // Across onto a side that is a layer growing towards the kink: a thin layer's peak,
            // from which the field falls away as it grew on the way in.
            let into_layer = approach >= across && k.sides[usize::from(r < k.radius_m)] != Side::FLAT;
            return Some(Cut { length_m: across.min(approach), into_layer });
        }
        let climb_now = b / r;
        let climb_there = ((b + a2 * t) / k.radius_m).abs().max(1e-9);
        let spread = bend.length() * climb_now.abs().max(climb_there) * t * t * t / (6.0 * k.scale_m * climb_there);
        let short = (4.0 * spread).max((0.5 * reach).min(SHORT_MAX_M)).min(0.5 * t);
        Some(Cut { length_m: (t - short).min(approach), into_layer: false })
    }
}

/// How long the next step may be ([`KinkSpheres::next_cut_within`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cut {
    /// The longest step, m.
    pub length_m: f64,
    /// A step that long ends just past a thin layer's peak, where the field falls away from the
    /// path as it grew on the way in: the steps that approached the peak are the sizes to leave
    /// it with (mirrored), where the controller's proposal, kept across the cut, is not.
    pub into_layer: bool,
}

/// Where a path stands as it approaches a kink: the state the error test scales by.
struct Approach {
    tol: Tolerance,
    /// Position and ray vector v = n·d, where the step starts.
    p: DVec3,
    v: DVec3,
    /// The unit vector from the kinks' centre: the direction of a radial layer's ∇n.
    radial: DVec3,
    /// The longest step the integrator will try, m (∞: unknown).
    h_want: f64,
}

/// How long a step towards kink `k`, met `t` ahead along the path from radius `r`, may be
/// before its last stages reach where the layer on the path's side of the kink (a hot road's)
/// makes it fail the error test (module notes, "Approaching a layer"); infinite where the field
/// there does not grow towards the kink.
fn approach(k: &Kink, r: f64, t: f64, at: &Approach) -> f64 {
    let side = k.sides[usize::from(r > k.radius_m)];
    let (depth, l) = ((r - k.radius_m).abs(), side.scale_m);
    if !(depth > 0.0 && side.gradient > 0.0 && t > 0.0) {
        return f64::INFINITY;
    }
    // ℓ: the path length over which the layer grows e-fold on the way (climb Δr/t); a step
    // x·ℓ long ends where ∇n = G·e^(x − D), D = Δr/L. Error in v: ℓx·∇n(end)·K(x) ≤ tol_v;
    // in r: (ℓx)²·∇n(end)·K_r(x)/n ≤ tol_r.
    let (tol_v, tol_r) = (at.tol.along(at.radial, at.v), at.tol.along(at.radial, at.p));
    let d = depth / l;
    let (d2, gt) = (d * d, side.gradient * t);
    if gt * KV_MAX.min(KV4 * d2 * d2) <= tol_v && gt * t * KR_MAX.min(KR3 * d2 * d) <= tol_r * at.tol.n {
        // A step all the way to the kink passes: nothing to hold back (most steps; no
        // logarithm needed).
        return f64::INFINITY;
    }
    let ell = t / d;
    // The bounds grow with the step, so a step of h_want that passes is no longer than the
    // longest that would: the integrator's own step stands. Its end lies short of the kink,
    // where ∇n = G·e^(x − D) ≤ G, which is tried first (no exponential).
    let (h, x) = (at.h_want, at.h_want / ell);
    if h < t {
        let (kv, kr) = (h * KV_MAX.min(KV4 * x.powi(4)), h * h * KR_MAX.min(KR3 * x.powi(3)));
        let passes = |g_end: f64| g_end * kv <= tol_v && g_end * kr <= tol_r * at.tol.n;
        if passes(side.gradient) || passes(side.gradient * (x - d).exp()) {
            return f64::INFINITY;
        }
    }
    let g = side.gradient * (-d).exp();
    let (bv, br) = ((tol_v / (ell * g)).ln(), (tol_r * at.tol.n / (ell * ell * g)).ln());
    let xv = x_plus_m_ln_x(bv - KV_MAX.ln(), 1.0).max(x_plus_m_ln_x(bv - KV4.ln(), 5.0));
    let xr = x_plus_m_ln_x(br - KR_MAX.ln(), 2.0).max(x_plus_m_ln_x(br - KR3.ln(), 5.0));
    let h = xv.min(xr) * ell;
    if h.is_finite() { h } else { f64::INFINITY }
}

/// The x > 0 with x + m·ln x = `b` (m > 0), to about 10⁻³: Newton's method in u = ln x on the
/// convex, increasing e^u + m·u − b from a start right of the root (ln b for b > 1, else b/m),
/// so it converges monotonically from above; four iterations, as a step length needs no more.
fn x_plus_m_ln_x(b: f64, m: f64) -> f64 {
    if !b.is_finite() {
        return if b > 0.0 { b } else { 0.0 };
    }
    let mut u = if b > 1.0 { b.ln() } else { b / m };
    for _ in 0..4 {
        let e = u.exp();
        u -= (e + m * u - b) / (e + m);
    }
    u.exp()
}

/// A side of a kink is a layer to approach ([`approach`]) where this many of its e-folding
/// depths fit within the way to the next kink on that side.
const APPROACH_DEPTHS: f64 = 4.0;

/// Bounds of the error a Dormand–Prince step of length h = x·ℓ makes through a field whose
/// ∇n grows as e^(s/ℓ) along it, ∇n(end) at its end (Eᵢ, cᵢ, aᵢⱼ of [`super::dopri5`]): in v,
/// h·∇n(end)·K(x), K(x) = |Σᵢ Eᵢ e^(−(1−cᵢ)x)| ≤ min(KV_MAX, KV4·x⁴); in r,
/// h²·∇n(end)·K_r(x)/n, K_r(x) = |Σᵢ Eᵢ Σⱼ aᵢⱼ e^(−(1−cⱼ)x)| ≤ min(KR_MAX, KR3·x³). KV4 and KR3
/// are the leading Taylor coefficients (71/6 480 000 and 37/360 000, the largest ratios over
/// x > 0); KV_MAX = |E₆ + E₇| is K's limit, approached from below; KR_MAX bounds K_r, which
/// peaks near x = 13 above its limit |E₇·b₆| = 0.00327. `tests::error_bounds_hold` checks them.
const KV_MAX: f64 = 22.0 / 525.0 - 1.0 / 40.0;
const KV4: f64 = 71.0 / 6_480_000.0;
const KR_MAX: f64 = 0.003_46;
const KR3: f64 = 37.0 / 360_000.0;

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
    use crate::ode::dopri5::*;

    /// atol = 10⁻⁹ alone: v() = 10⁻⁹.
    const TOL_1E9: Tolerance = Tolerance { rtol: 0.0, atol: 1e-9, n: 1.0 };

    /// K(x) and K_r(x) from the tableau (see [`KV_MAX`]).
    fn error_weights(x: f64) -> (f64, f64) {
        let c = [0.0, C2, C3, C4, C5, 1.0, 1.0];
        let e = [E1, 0.0, E3, E4, E5, E6, E7];
        let a: [&[f64]; 7] = [
            &[],
            &[A21],
            &[A31, A32],
            &[A41, A42, A43],
            &[A51, A52, A53, A54],
            &[A61, A62, A63, A64, A65],
            &[B1, 0.0, B3, B4, B5, B6],
        ];
        let g = |j: usize| (-(1.0 - c[j]) * x).exp();
        let kv: f64 = (0..7).map(|i| e[i] * g(i)).sum();
        let kr: f64 = (0..7).map(|i| e[i] * a[i].iter().enumerate().map(|(j, aij)| aij * g(j)).sum::<f64>()).sum();
        (kv.abs(), kr.abs())
    }

    #[test]
    fn error_bounds_hold() {
        let (mut kv_max, mut kr_max) = (0.0f64, 0.0f64);
        for i in 1..=200_000 {
            let x = i as f64 * 1e-3;
            let (kv, kr) = error_weights(x);
            assert!(kv <= KV_MAX.min(KV4 * x.powi(4)) * (1.0 + 1e-9) + 1e-15, "K({x}) = {kv}");
            assert!(kr <= KR_MAX.min(KR3 * x.powi(3)) * (1.0 + 1e-9) + 1e-15, "K_r({x}) = {kr}");
            (kv_max, kr_max) = (kv_max.max(kv), kr_max.max(kr));
        }
        // The bounds are close: each is reached within a few per cent.
        assert!(kv_max > 0.98 * KV_MAX && kr_max > 0.99 * KR_MAX, "{kv_max} {kr_max}");
        let (kv, kr) = error_weights(0.05);
        assert!(
            (kv / (KV4 * 0.05f64.powi(4)) - 1.0).abs() < 0.03 && (kr / (KR3 * 0.05f64.powi(3)) - 1.0).abs() < 0.03,
            "{kv} {kr}"
        );
    }

    /// A step of length h along a path that meets a layer ∇n = G·e^(−z/L) (pure exponential,
    /// the approach's model) `t` ahead from height z0, so that the layer grows e-fold every
    /// ℓ = L·t/z0 along it, integrated with the tableau: its v and r error estimates.
    fn layer_step_errors(g: f64, l: f64, (z0, t): (f64, f64), h: f64) -> (f64, f64) {
        let ell = l * t / z0;
        let x = h / ell;
        let g_end = g * (x - z0 / l).exp();
        let (kv, kr) = error_weights(x);
        (h * g_end * kv, h * h * g_end * kr)
    }

    #[test]
    fn a_step_towards_a_thin_layer_stops_where_its_error_passes() {
        // A hot road's layer (G = 4.2·10⁻⁶ m⁻¹, L = 6.667 m) under a path descending at 40°
        // from 1 000 m; tolerances 10⁻⁹ near the origin of the frame.
        let (g, l) = (4.2e-6, 6.667);
        let side = Side { gradient: g, scale_m: l };
        let kink = Kink { radius_m: 6.371e6, jump: g, scale_m: l, sides: [Side::FLAT, side] };
        let k = KinkSpheres { centre: DVec3::new(0.0, -6.371e6, 0.0), kinks: vec![kink] };
        let tol = Tolerance { rtol: 1e-9, atol: 1e-9, n: 1.0 };
        let e = 40f64.to_radians();
        let d = DVec3::new(e.cos(), -e.sin(), 0.0);
        for z0 in [1_000.0, 200.0, 60.0, 30.0] {
            let p = DVec3::new(0.0, z0, 0.0);
            let h = k.next_cut(p, d, DVec3::ZERO, 1e-9, Some(tol)).unwrap();
            // The crossing with the sphere, t ahead.
            let q = p - k.centre;
            let (b, c) = (q.dot(d), (q.length() - 6.371e6) * (q.length() + 6.371e6));
            let t = c / (-b + (b * b - c).sqrt());
            assert!(h < t, "{z0}: {h} of {t}");
            // The model's errors at the cut pass the test in v and r; a step 1.5 times longer
            // fails in one of them by a quarter (the bounds are within a few times the errors).
            let (tol_v, tol_r) = (tol.along(DVec3::Y, d), tol.along(DVec3::Y, p));
            let (ev, er) = layer_step_errors(g, l, (z0, t), h);
            assert!(ev <= tol_v && er <= tol_r, "{z0}: {ev} {er}");
            let (ev, er) = layer_step_errors(g, l, (z0, t), 1.5 * h);
            assert!(ev > tol_v / 4.0 || er > tol_r / 4.0, "{z0}: {ev} {er}");
        }
        // From 1 000 m the step ends where the layer starts to matter: 50–150 m above it.
        let h = k.next_cut(DVec3::new(0.0, 1_000.0, 0.0), d, DVec3::ZERO, 1e-9, Some(tol)).unwrap();
        let end = 1_000.0 - h * e.sin();
        assert!(end > 50.0 && end < 150.0, "{end}");
        // A flat field beyond the kink, or a path below it, is not held back.
        let flat = KinkSpheres { centre: k.centre, kinks: vec![Kink { sides: [Side::FLAT; 2], ..kink }] };
        let h = flat.next_cut(DVec3::new(0.0, 1_000.0, 0.0), d, DVec3::ZERO, 1e-9, Some(tol)).unwrap();
        assert!(h > 1_000.0 / e.sin() - 2.0, "{h}");
    }

    /// A Fermi bump of ∇n (w = 3 m) 30 m above a sphere of the Earth's radius about `centre`:
    /// n − 1 = 10⁻⁵·σ((z − 30)/3) − 3·10⁻⁸·z, z the height above the sphere.
    fn fermi(centre: DVec3) -> impl Fn(DVec3) -> (f64, DVec3) {
        move |p: DVec3| {
            let q = p - centre;
            let r = q.length();
            let u = (r - 6.371e6 - 30.0) / 3.0;
            let sigma = 1.0 / (1.0 + (-u).exp());
            let slope = 1e-5 / 3.0 * sigma * (1.0 - sigma) - 3e-8;
            (1.0 + 1e-5 * sigma - 3e-8 * (r - 6.371e6), q / r * slope)
        }
    }

    #[test]
    fn a_thin_layer_is_approached_from_both_sides_and_left_with_a_flag() {
        let centre = DVec3::new(0.0, -6.371e6, 0.0);
        let field = fermi(centre);
        let peak = 6.371e6 + 30.0;
        let k = KinkSpheres::new(&field, centre, &[6.371e6 + 11_000.0]).with_layers(&field, &[(peak, 3.0)]);
        assert_eq!(k.kinks.len(), 2, "the layer's peak joins the kinks, in order");
        let layer = k.kinks[0];
        assert_eq!(layer.radius_m, peak);
        let g = field(centre + DVec3::Y * peak).1.length();
        assert_eq!(layer.sides, [Side { gradient: LAYER_ENVELOPE * g, scale_m: 3.0 }; 2]);
        assert!(layer.jump < 1e-9 * g, "a smooth peak has no jump: {}", layer.jump);
        let tol = Tolerance { rtol: 1e-9, atol: 1e-9, n: 1.0 };
        let down = DVec3::new(20f64.to_radians().cos(), -20f64.to_radians().sin(), 0.0);
        let up = DVec3::new(down.x, -down.y, 0.0);
        for (z0, d) in [(300.0, down), (0.0, up)] {
            // From 270 m above the peak going down and 30 m below it going up the first step
            // ends where the layer starts to matter, outside its flanks (2w from the peak) but
            // within 15w, and the cut is not a crossing.
            let p = DVec3::new(0.0, z0, 0.0);
            let c = k.next_cut_within(p, d, DVec3::ZERO, 1e-9, Some(tol), f64::INFINITY).unwrap();
            let from_peak = (z0 + c.length_m * d.y - 30.0).abs();
            assert!((6.0..45.0).contains(&from_peak) && !c.into_layer, "from {z0} m: {c:?}, {from_peak} m");
        }
        // Half a metre short of the peak the step goes across, into the far side's layer.
        let p = DVec3::new(0.0, 30.0 + 0.5 * 20f64.to_radians().sin(), 0.0);
        let c = k.next_cut_within(p, down, DVec3::ZERO, 1e-9, Some(tol), f64::INFINITY).unwrap();
        assert!((c.length_m - 0.5).abs() < 1e-3 && c.into_layer, "{c:?}");
        // The same cut of a kink without layer sides is no crossing into one.
        let plain = KinkSpheres { centre, kinks: vec![Kink { sides: [Side::FLAT; 2], ..layer }] };
        let c = plain.next_cut_within(p, down, DVec3::ZERO, 1e-9, Some(tol), f64::INFINITY).unwrap();
        assert!(!c.into_layer, "{c:?}");
    }

    #[test]
    fn a_proposal_that_passes_the_layer_is_left_alone() {
        let centre = DVec3::new(0.0, -6.371e6, 0.0);
        let field = fermi(centre);
        let k = KinkSpheres::new(&field, centre, &[]).with_layers(&field, &[(6.371e6 + 30.0, 3.0)]);
        let tol = Tolerance { rtol: 1e-9, atol: 1e-9, n: 1.0 };
        let d = DVec3::new(20f64.to_radians().cos(), -20f64.to_radians().sin(), 0.0);
        let p = DVec3::new(0.0, 100.0, 0.0);
        let longest = k.next_cut_within(p, d, DVec3::ZERO, 1e-9, Some(tol), f64::INFINITY).unwrap().length_m;
        // A proposal shorter than the longest step that passes: no limit beyond the crossing
        // (the step taken is the proposal either way); a longer one: the same limit as without.
        let t = 70.0 / 20f64.to_radians().sin();
        let short = k.next_cut_within(p, d, DVec3::ZERO, 1e-9, Some(tol), 0.5 * longest).unwrap().length_m;
        assert!(short > t, "{short} against the crossing {t}");
        let long = k.next_cut_within(p, d, DVec3::ZERO, 1e-9, Some(tol), 2.0 * longest).unwrap().length_m;
        assert_eq!(long, longest);
    }

    /// Spheres without jumps (a fixed-step integrator's view: every cut goes across).
    fn smooth(centre: DVec3, radii: &[f64]) -> KinkSpheres {
        KinkSpheres {
            centre,
            kinks: radii
                .iter()
                .map(|&radius_m| Kink { radius_m, jump: 0.0, scale_m: f64::INFINITY, sides: [Side::FLAT; 2] })
                .collect(),
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
        let k = KinkSpheres {
            centre: DVec3::ZERO,
            kinks: vec![Kink { radius_m: 1000.0, jump: 1e-6, scale_m: 10.0, sides: [Side::FLAT; 2] }],
        };
        let first = k.next_cut(DVec3::new(0.0, 900.0, 0.0), DVec3::Y, DVec3::ZERO, 1e-9, Some(TOL_1E9)).unwrap();
        assert!(first < 100.0 && first > 100.0 - 0.015, "{first}");
        let second =
            k.next_cut(DVec3::new(0.0, 900.0 + first, 0.0), DVec3::Y, DVec3::ZERO, 1e-9, Some(TOL_1E9)).unwrap();
        assert!(second > 100.0 - first && second < 100.0 - first + 2e-4, "{second}");
        // A small jump is crossed at once.
        let k = KinkSpheres {
            centre: DVec3::ZERO,
            kinks: vec![Kink { radius_m: 1000.0, jump: 1e-15, scale_m: 10.0, sides: [Side::FLAT; 2] }],
        };
        let t = k.next_cut(DVec3::new(0.0, 900.0, 0.0), DVec3::Y, DVec3::ZERO, 1e-9, Some(TOL_1E9)).unwrap();
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
