//! Terrestrial refraction: where a ray launched near the horizon is once it has crossed a
//! given central angle (ground distance over the Earth's radius), in air whose index depends on
//! height alone — by quadrature of Bouguer's invariant, not by integrating the ray equation.
//!
//! # Method
//! In n(r) a path lies in a plane through the Earth's centre and keeps c = n r cos e (e the
//! elevation above the local horizontal; Born & Wolf, *Principles of Optics*, §3.2.1). With
//! g(r) = n r − c and D = √(n²r² − c²) = √(g (g + 2c)), the central angle grows as
//!
//! ```text
//!     dφ = c dr / (r D)
//! ```
//!
//! while r changes monotonically, that is while g > 0. A ray launched down (e₀ < 0) falls to
//! its perigee r_p, where g(r_p) = 0, then climbs; one launched up climbs from the start. Where
//! n·r falls with height somewhere (a duct) g can return to zero above the perigee and the ray
//! turn back down: a node of the quadrature with g ≤ 0, or a g′ ≤ 0 where the perigee is
//! sought, is reported as an error (the ray trace follows such rays). Where g → 0 the integrand
//! has a 1/√(r − r_p) singularity; the substitution r = r_t + t² makes it finite,
//!
//! ```text
//!     dφ = 2 t c / (r D) dt,        → √(2c/g′(r_p)) / r_p at t = 0 when r_t = r_p,
//! ```
//!
//! with r_t the perigee for a ray that reaches it, and otherwise (a climbing ray, or one that
//! meets the ground first) the root of g linearised at the start, r_t = r₀ − g₀/g′₀
//! (g′ = n + r dn/dr): near where the integrand's singularity lies, so that the substituted
//! integrand is smooth along the whole path. The angle Φ(T) = ∫ 2tc/(rD) dt from the start to T
//! is split where the index is not analytic ([`RadialAir::kink_heights_m`]: layer boundaries, a
//! table's rows) and integrated by adaptive Gauss–Kronrod (7–15,
//! [`crate::quadrature::adaptive_gauss_kronrod_to_depth`]) to `tol_rad`. The end T with Φ(T) = φ is
//! found by Newton's method (dΦ/dT is the integrand) from a guess by the trapezoid rule, each
//! correction's short stretch integrated by Simpson's rule (over a fiftieth of the path or
//! less its error is far below the tolerance) or, when longer, adaptively again.
//!
//! g is formed as (N − N₀)·r + n₀ x + g₀ from the refractivity N = n − 1 (taken at the height
//! above the ground, never at a radius, which is rounded to 10⁻⁹ m), the height above the start
//! x = r − r₀ and g₀ = 2 n₀ r₀ sin²(e₀/2), and the substitution is made in x, so that no
//! 6 371 km quantities cancel. Within 10 m of a perigee, or of a start within that of
//! level, g is its cubic Taylor polynomial from differences of g′ instead: there g is the small
//! difference of rounded values that 1/√g would amplify. Only N is sampled at the quadrature's
//! nodes; dn/dh only at the start, the perigee and the Taylor polynomial's three points.
//! Above the top of the air n = 1 and the path is straight: the invariant becomes r cos e = c
//! (Snell's law at the top keeps it), and φ = arccos(c/r) − arccos(c/r_top) beyond the top; a
//! ray whose straight line never gets to the angle asked is [`Reach::Away`].
//!
//! [`follow`] answers where a ray is at an angle; [`perigee`] where a descending ray turns up;
//! [`true_altitude`] carries the quadrature to the top for astronomical refraction.
//!
//! Checks (`tests/terrestrial.rs`): the closed form for n ∝ r^(−k) (e = e₀ + (1 − k)φ exactly),
//! the ray equation ([`crate::ode`], Dormand–Prince at rtol 10⁻¹⁵) through USA76 and the hot
//! road, and atm-refraction 0.6.1 (fixed-step RK4 in the ground distance) as an independent
//! peer.
//!
//! # References
//! - M. Born & E. Wolf, *Principles of Optics*, 7th ed., Cambridge 1999, §3.2.1.
//! - W. M. Smart, *Textbook on Spherical Astronomy*, 6th ed., Cambridge 1977, ch. III.
//! - R. Piessens et al., *QUADPACK*, Springer 1983 (the Gauss–Kronrod pair).

use crate::quadrature::adaptive_gauss_kronrod_to_depth;
use std::cell::Cell;

/// Deepest halving of the adaptive quadrature (intervals of 1/4096 of a piece: the substituted
/// integrand is smooth, so only rounding noise would ask for more).
const MAX_DEPTH: u32 = 12;
/// How far above its base g′ is sampled for the Taylor form, m (module notes).
const NUDGE_M: f64 = 1e-9;
/// What a ray that turns back in the air is told.
const DUCT: &str = "the ray turns back inside the air (a duct: n·r falls with height on its path), where Bouguer's quadrature does not follow it; trace the ray";
/// Longest reach of the Taylor form of g about a perigee or a level start, m; a thousandth of
/// the field's length scale |g″/g‴| where that is shorter (USA76 near the ground: 7 km, so 7 m,
/// where the truncation error g⁗u⁴/24 is ~10⁻¹⁰ m, 10⁻¹¹ of g).
const NEAR_M: f64 = 10.0;

/// An index of refraction that depends on the height h above a spherical ground alone (the
/// distance from the Earth's centre less its radius), smooth between the heights of
/// [`RadialAir::kink_heights_m`]. A closure h ↦ (n − 1, dn/dh) is one. It takes the height, not
/// the radius: a radius is rounded to 10⁻⁹ m, which a ray near its turning point would feel.
pub trait RadialIndex {
    /// n − 1 at height `h_m` (what the quadrature samples along the path).
    fn refractivity(&self, h_m: f64) -> f64 {
        self.refractivity_slope(h_m).0
    }
    /// n − 1 and dn/dh (m⁻¹) at height `h_m` (for the perigee and the ray's start).
    fn refractivity_slope(&self, h_m: f64) -> (f64, f64);
}

impl<F: Fn(f64) -> (f64, f64)> RadialIndex for F {
    fn refractivity_slope(&self, h_m: f64) -> (f64, f64) {
        self(h_m)
    }
}

/// Air over a spherical ground whose index depends on the height alone.
#[derive(Clone, Debug)]
pub struct RadialAir<F> {
    /// The index.
    pub refractivity: F,
    /// Heights where the index is not analytic — dn/dh jumps (layer boundaries) or a higher
    /// derivative does (a table's rows) — m, ascending: the quadrature's pieces end there.
    pub kink_heights_m: Vec<f64>,
    /// Radius of the ground, m: a ray that falls to it ends there.
    pub ground_radius_m: f64,
    /// Height of the top, m, above which n = 1.
    pub top_m: f64,
}

/// Where a ray is at the central angle asked for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Reach {
    /// Still in the air (or above it).
    Aloft {
        /// Height above the ground, m.
        height_m: f64,
        /// Elevation of the ray above the local horizontal there, rad (negative: descending).
        elevation_rad: f64,
    },
    /// It leaves the air upward on a straight line that never gets that far round the Earth.
    Away {
        /// The central angle its straight line tends to, rad.
        max_angle_rad: f64,
    },
    /// It met the ground first, at this central angle from the start, rad.
    Ground {
        /// Central angle from the start to where it met the ground, rad.
        angle_rad: f64,
    },
}

/// A followed ray: where it is, and the work it took.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Path {
    /// Where the ray is.
    pub reach: Reach,
    /// Where it passed its perigee, if it did before the angle asked for: the central angle
    /// from the start, rad.
    pub perigee_angle_rad: Option<f64>,
    /// Evaluations of the refractivity.
    pub evaluations: u64,
}

/// The ray leaving height `h0_m` at elevation `e0_rad` (|e0| < π/2), followed through central
/// angle `angle_rad` ≥ 0, the angle integrals to `tol_rad` (module notes). An error when the
/// ray turns back in the air (a duct: n·r falls with height somewhere on its path, so the
/// invariant allows a second turning point) or when a value is out of range.
pub fn follow<F: RadialIndex>(
    air: &RadialAir<F>,
    h0_m: f64,
    e0_rad: f64,
    angle_rad: f64,
    tol_rad: f64,
) -> Result<Path, String> {
    check(air, h0_m, e0_rad, angle_rad, tol_rad)?;
    let ray = Ray::new(air, h0_m, e0_rad);
    let reach = ray.reach(angle_rad, tol_rad);
    if let Some(e) = ray.error.get() {
        return Err(e.to_string());
    }
    Ok(Path { reach: reach?, perigee_angle_rad: ray.perigee_angle.get(), evaluations: ray.count.get() })
}

/// Astronomical refraction by the same quadrature: the true altitude (rad) of the star seen at
/// apparent altitude `e0_rad` from height `h0_m`, and the evaluations it took; `None` when the
/// ray meets the ground. The ray climbs (through its perigee if launched down) to the top,
/// sweeping the central angle Φ; there it leaves n_top for vacuum keeping n r cos e = c, so it
/// goes on at e_v = arccos(c/r_top) above the local horizontal, which Φ has turned from the
/// observer's: true = e_v − Φ, the refraction R = e₀ − true. sin e_v comes from
/// (r_top − c)(r_top + c)/r_top², with r_top − c = (top − h₀) − N₀ r₀ + 2 n₀ r₀ sin²(e₀/2)
/// free of cancellation.
pub fn true_altitude<F: RadialIndex>(
    air: &RadialAir<F>,
    h0_m: f64,
    e0_rad: f64,
    tol_rad: f64,
) -> Result<Option<(f64, u64)>, String> {
    check(air, h0_m, e0_rad, 0.0, tol_rad)?;
    let ray = Ray::new(air, h0_m, e0_rad);
    let t_top = |r: &Ray<F>| r.t_of(air.top_m - h0_m);
    let swept = if e0_rad < 0.0 {
        match ray.descend() {
            Descent::Ground { .. } => None,
            Descent::Perigee(_) => {
                Some(ray.integral(ray.t_of(0.0), 0.0, tol_rad) + ray.integral(0.0, t_top(&ray), tol_rad))
            }
        }
    } else {
        Some(ray.integral(ray.t_of(0.0), t_top(&ray), tol_rad))
    };
    if let Some(e) = ray.error.get() {
        return Err(e.to_string());
    }
    Ok(swept.map(|phi| {
        let r_top = air.ground_radius_m + air.top_m;
        let gap = (air.top_m - h0_m) - ray.big_n0 * ray.r0 + ray.g0;
        let e_v = ((gap * (2.0 * r_top - gap)).sqrt() / r_top).min(1.0).asin();
        (e_v - phi, ray.count.get())
    }))
}

/// Where a ray launched down from height `h0_m` at elevation `e0_rad` < 0 turns up: its
/// perigee's height (m) and central angle from the start (rad), the descent integrated to
/// `tol_rad`; `None` when it meets the ground first.
pub fn perigee<F: RadialIndex>(
    air: &RadialAir<F>,
    h0_m: f64,
    e0_rad: f64,
    tol_rad: f64,
) -> Result<Option<(f64, f64)>, String> {
    check(air, h0_m, e0_rad, 0.0, tol_rad)?;
    if e0_rad >= 0.0 {
        return Err(format!("elevation {e0_rad} rad: a perigee needs a ray launched down (< 0)"));
    }
    let ray = Ray::new(air, h0_m, e0_rad);
    let found = match ray.descend() {
        Descent::Ground { .. } => None,
        Descent::Perigee(x_p) => Some((h0_m + x_p, ray.integral(ray.t_of(0.0), 0.0, tol_rad))),
    };
    match ray.error.get() {
        Some(e) => Err(e.to_string()),
        None => Ok(found),
    }
}

fn check<F>(air: &RadialAir<F>, h0: f64, e0: f64, angle: f64, tol: f64) -> Result<(), String> {
    let (radius, top) = (air.ground_radius_m, air.top_m);
    if !(radius > 0.0 && radius.is_finite() && top > 0.0 && top.is_finite()) {
        return Err(format!("ground radius {radius} m and top {top} m: expected both positive and finite"));
    }
    if !(h0.is_finite() && (0.0..top).contains(&h0)) {
        return Err(format!("start height {h0} m: expected 0 ≤ h < {top} m (the top of the air)"));
    }
    if !(e0.is_finite() && e0.abs() < std::f64::consts::FRAC_PI_2) {
        return Err(format!("elevation {e0} rad: expected strictly between −π/2 and π/2"));
    }
    if !(angle.is_finite() && angle >= 0.0) {
        return Err(format!("central angle {angle} rad: expected a finite angle ≥ 0"));
    }
    if !(tol.is_finite() && tol > 0.0) {
        return Err(format!("tolerance {tol} rad: expected > 0"));
    }
    Ok(())
}

/// How a ray launched down descends ([`Ray::descend`]).
enum Descent {
    /// It turns up at this height above the start, m.
    Perigee(f64),
    /// It meets the ground first, where g and g′ are these.
    Ground { g: f64, slope: f64 },
}

/// Where a solve ended.
enum Solved {
    /// The angle is reached at this t.
    At(f64),
    /// The limit comes first, with this angle.
    Beyond(f64),
}

/// One ray's invariant and substitution (module notes).
struct Ray<'a, F> {
    air: &'a RadialAir<F>,
    /// The start's height and radius, m.
    h0: f64,
    r0: f64,
    big_n0: f64,
    n0: f64,
    /// The invariant n r cos e, m.
    c: f64,
    /// g at the start, 2 n₀ r₀ sin²(e₀/2), m.
    g0: f64,
    /// The ray starts down.
    down: bool,
    /// Height above the start of the substitution's centre r_t, m.
    x_t: Cell<f64>,
    /// g near the base of the integration as its Taylor polynomial.
    near: Cell<Option<Near>>,
    /// The central angle of the perigee, once passed.
    perigee_angle: Cell<Option<f64>>,
    count: Cell<u64>,
    error: Cell<Option<&'static str>>,
}

impl<'a, F: RadialIndex> Ray<'a, F> {
    fn new(air: &'a RadialAir<F>, h0: f64, e0: f64) -> Ray<'a, F> {
        let r0 = air.ground_radius_m + h0;
        let (big_n0, dn0) = air.refractivity.refractivity_slope(h0);
        let n0 = 1.0 + big_n0;
        let half = (0.5 * e0).sin();
        let ray = Ray {
            air,
            h0,
            r0,
            big_n0,
            n0,
            c: n0 * r0 * e0.cos(),
            g0: 2.0 * n0 * r0 * half * half,
            down: e0 < 0.0,
            x_t: Cell::new(0.0),
            near: Cell::new(None),
            perigee_angle: Cell::new(None),
            count: Cell::new(1),
            error: Cell::new(None),
        };
        let (g0, slope0) = (ray.g0, n0 + r0 * dn0);
        if slope0.is_nan() || slope0 <= 0.0 {
            ray.error.set(Some(DUCT));
        }
        ray.x_t.set(-g0 / slope0);
        // A start within reach of the root of g (a ray launched nearly level) needs g's Taylor
        // form there; one launched steeper never comes near it.
        if g0 < NEAR_M * slope0 {
            ray.near.set(Some(ray.taylor(0.0, g0)));
        }
        ray
    }

    /// g′ = n + r dn/dr at height x above the start, and g there.
    fn slope(&self, x: f64) -> (f64, f64) {
        self.count.set(self.count.get() + 1);
        let r = self.r0 + x;
        let (big_n, dn) = self.air.refractivity.refractivity_slope(self.h0 + x);
        let slope = 1.0 + big_n + r * dn;
        if slope.is_nan() || slope <= 0.0 {
            self.error.set(Some(DUCT));
        }
        (slope, self.g_from(x, r, big_n))
    }

    /// g about `x_b` (where it is `g_b`, known without cancellation) as its cubic Taylor
    /// polynomial, g″ and g‴ from one-sided differences of g′ over steps δ; used within δ of
    /// `x_b`, δ = [`NEAR_M`] or a thousandth of the field's length scale |g″/g‴| if that is
    /// shorter (not at all below a micrometre: a field that steep is left to the direct form).
    fn taylor(&self, x_b: f64, g_b: f64) -> Near {
        let mut delta = NEAR_M;
        let mut near = Near { x_b, g_b, d1: 0.0, d2: 0.0, d3: 0.0, reach: 0.0 };
        for _ in 0..2 {
            // g′ just above x_b, on the side the ray travels: where x_b is a kink (a profile's
            // lowest knot at the ground) the derivative at it may be the one below.
            let a = self.slope(x_b + NUDGE_M).0;
            let (b, c) = (self.slope(x_b + delta).0, self.slope(x_b + 2.0 * delta).0);
            let (d2, d3) = ((-3.0 * a + 4.0 * b - c) / (2.0 * delta), (a - 2.0 * b + c) / (delta * delta));
            near = Near { x_b, g_b, d1: a, d2, d3, reach: delta };
            let scale = if d3 == 0.0 { f64::INFINITY } else { (d2 / d3).abs() };
            if 1e-3 * scale >= delta {
                break;
            }
            delta = 1e-3 * scale;
            if delta.is_nan() || delta <= 1e-6 {
                return Near { reach: 0.0, ..near };
            }
        }
        near
    }

    /// g and n at height x above the start (module notes).
    fn g(&self, x: f64) -> (f64, f64) {
        self.count.set(self.count.get() + 1);
        let r = self.r0 + x;
        let big_n = self.air.refractivity.refractivity(self.h0 + x);
        (self.g_from(x, r, big_n), 1.0 + big_n)
    }

    /// g at height x (radius r, refractivity `big_n`): the Taylor form near its base, else
    /// (N − N₀)·r + n₀ x + g₀.
    fn g_from(&self, x: f64, r: f64, big_n: f64) -> f64 {
        match self.near.get() {
            Some(t) if (x - t.x_b).abs() <= t.reach => t.at(x),
            _ => (big_n - self.big_n0) * r + self.n0 * x + self.g0,
        }
    }

    /// The integrand dφ/dt at t (module notes); at t = 0, a root of g, its limit
    /// √(2c/g′)/r. A node where g ≤ 0 is past a turning point: the ray turns back there.
    fn h(&self, t: f64) -> f64 {
        let x = self.x_t.get() + t * t;
        let r = self.r0 + x;
        if t == 0.0 {
            let slope = match self.near.get() {
                Some(n) if n.x_b == x => n.d1,
                _ => self.slope(x).0,
            };
            return (2.0 * self.c / slope.max(f64::MIN_POSITIVE)).sqrt() / r;
        }
        let (g, _) = self.g(x);
        if g.is_nan() || g <= 0.0 {
            self.error.set(Some(DUCT));
            return 0.0;
        }
        2.0 * t * self.c / (r * (g * (g + 2.0 * self.c)).sqrt())
    }

    fn t_of(&self, x: f64) -> f64 {
        (x - self.x_t.get()).max(0.0).sqrt()
    }

    /// The t of the kink heights strictly between `a` and `b`, in the order from `a` to `b`.
    fn kinks_between(&self, a: f64, b: f64) -> Vec<f64> {
        let (lo, hi) = (a.min(b), a.max(b));
        let x_t = self.x_t.get();
        let mut ts: Vec<f64> = (self.air.kink_heights_m.iter())
            .filter(|&&k| k - self.h0 > x_t)
            .map(|&k| self.t_of(k - self.h0))
            .filter(|&t| t > lo && t < hi)
            .collect();
        if a > b {
            ts.reverse();
        }
        ts
    }

    /// |∫ h dt| between `a` and `b`, split at kinks.
    fn integral(&self, a: f64, b: f64, tol: f64) -> f64 {
        let mut ends = vec![a];
        ends.extend(self.kinks_between(a, b));
        ends.push(b);
        let pieces = (ends.len() - 1) as f64;
        let mut sum = 0.0;
        for w in ends.windows(2) {
            let (lo, hi) = (w[0].min(w[1]), w[0].max(w[1]));
            sum += adaptive_gauss_kronrod_to_depth(&mut |t| self.h(t), lo, hi, tol / pieces, MAX_DEPTH);
        }
        sum
    }

    /// From `t_start` towards `t_limit`, the t where the angle covered is `target`.
    fn solve(&self, t_start: f64, t_limit: f64, target: f64, tol: f64) -> Solved {
        let dir = if t_limit >= t_start { 1.0 } else { -1.0 };
        let (lo, hi) = (t_start.min(t_limit), t_start.max(t_limit));
        // The first guess from the slope at the start, then from the mean of the slopes at the
        // start and at that guess (the trapezoid rule), so that Newton's corrections are short.
        let h_start = self.h(t_start);
        let mut t = (t_start + dir * target / h_start).clamp(lo, hi);
        if t != t_limit {
            t = (t_start + dir * target / (0.5 * (h_start + self.h(t)))).clamp(lo, hi);
        }
        let mut phi = self.integral(t_start, t, tol);
        if t == t_limit && phi < target {
            return Solved::Beyond(phi);
        }
        let mut h_t = self.h(t);
        for _ in 0..60 {
            let residual = target - phi;
            let next = (t + dir * residual / h_t).clamp(lo, hi);
            if residual.abs() <= 1e-3 * tol || self.error.get().is_some() {
                return Solved::At(next);
            }
            let (piece, h_next) = self.step_integral(t, next, h_t, (t - t_start).abs(), tol);
            phi += if (next > t) == (dir > 0.0) { piece } else { -piece };
            (t, h_t) = (next, h_next);
        }
        Solved::At(t)
    }

    /// |∫ h dt| over a Newton correction from `t` (where h is `h_t`) to `next`, and h(next): by
    /// Simpson's rule when the correction is at most a fiftieth of the way `covered` so far and
    /// crosses no kink (its error, (δ/2)⁵h⁗/90, is then ~10⁻¹⁴ of the angle for a smooth h), else
    /// adaptively.
    fn step_integral(&self, t: f64, next: f64, h_t: f64, covered: f64, tol: f64) -> (f64, f64) {
        let h_next = self.h(next);
        let delta = (next - t).abs();
        if delta <= covered / 50.0 && self.kinks_between(t, next).is_empty() {
            let h_mid = self.h(0.5 * (t + next));
            return (delta / 6.0 * (h_t + 4.0 * h_mid + h_next), h_next);
        }
        (self.integral(t, next, 0.1 * tol), h_next)
    }

    /// For a ray launched down: where it turns up, with the substitution centred on its perigee
    /// and g's Taylor form about it; or, when it meets the ground first, g and g′ there.
    fn descend(&self) -> Descent {
        let x_ground = -self.h0;
        let (slope, g) = self.slope(x_ground);
        if g > 0.0 {
            return Descent::Ground { g, slope };
        }
        let x_p = self.perigee(x_ground);
        self.x_t.set(x_p);
        self.near.set(Some(self.taylor(x_p, 0.0)));
        Descent::Perigee(x_p)
    }

    /// Where the ray is at central angle `angle`.
    fn reach(&self, angle: f64, tol: f64) -> Result<Reach, String> {
        if !self.down {
            return self.climb(self.t_of(0.0), angle, tol);
        }
        if let Descent::Ground { g, slope } = self.descend() {
            // It meets the ground before its perigee: centre the substitution on the root of g
            // linearised there.
            let x_ground = -self.h0;
            self.x_t.set(x_ground - g / slope);
            return Ok(match self.solve(self.t_of(0.0), self.t_of(x_ground), angle, tol) {
                Solved::At(t) => self.aloft(t, -1.0),
                Solved::Beyond(phi) => Reach::Ground { angle_rad: phi },
            });
        }
        match self.solve(self.t_of(0.0), 0.0, angle, tol) {
            Solved::At(t) => Ok(self.aloft(t, -1.0)),
            Solved::Beyond(phi) => {
                self.perigee_angle.set(Some(phi));
                self.climb(0.0, angle - phi, tol)
            }
        }
    }

    /// The perigee's height above the start: the root of g in [`lo`, 0] (g(lo) ≤ 0 < g(0)), by
    /// Newton's method kept inside the bracket (bisection when it would leave it).
    fn perigee(&self, mut lo: f64) -> f64 {
        self.near.set(None);
        let mut hi = 0.0;
        let mut x = self.x_t.get().clamp(lo, hi);
        for _ in 0..200 {
            let (slope, g) = self.slope(x);
            if g > 0.0 {
                hi = x;
            } else {
                lo = x;
            }
            let mut next = x - g / slope;
            if !(next > lo && next < hi) {
                next = 0.5 * (lo + hi);
            }
            if (next - x).abs() <= 1e-13 * x.abs().max(1.0) || hi - lo <= 1e-13 * x.abs().max(1.0) {
                return next;
            }
            x = next;
        }
        x
    }

    /// Climbing from `t_start` through `angle`; above the top on a straight line.
    fn climb(&self, t_start: f64, angle: f64, tol: f64) -> Result<Reach, String> {
        let t_top = self.t_of(self.air.top_m - self.h0);
        match self.solve(t_start, t_top, angle, tol) {
            Solved::At(t) => Ok(self.aloft(t, 1.0)),
            Solved::Beyond(phi) => {
                // Above the top r cos e = c (n = 1): φ grows by arccos(c/r) − arccos(c/r_top).
                let r_top = self.air.ground_radius_m + self.air.top_m;
                let a0 = (self.c / r_top).clamp(-1.0, 1.0).acos();
                let e = angle - phi + a0;
                if e >= std::f64::consts::FRAC_PI_2 {
                    return Ok(Reach::Away { max_angle_rad: phi + std::f64::consts::FRAC_PI_2 - a0 });
                }
                Ok(Reach::Aloft { height_m: self.c / e.cos() - self.air.ground_radius_m, elevation_rad: e })
            }
        }
    }

    /// The point at t, its elevation's sign `sign`.
    fn aloft(&self, t: f64, sign: f64) -> Reach {
        let x = self.x_t.get() + t * t;
        let r = self.r0 + x;
        let (g, n) = self.g(x);
        let sin_e = ((g.max(0.0) * (g.max(0.0) + 2.0 * self.c)).sqrt() / (n * r)).min(1.0);
        Reach::Aloft { height_m: self.h0 + x, elevation_rad: sign * sin_e.asin() }
    }
}

/// g within `reach` of `x_b` as its Taylor polynomial: near a root of g (a perigee, or the
/// start of a ray launched nearly level) the direct form (N(r) − N₀)·r + … is the difference of
/// values each rounded to ~10⁻¹⁶ of n, relative noise that 1/√g amplifies without bound; the
/// polynomial takes g from the derivative of n instead, which has no such cancellation.
#[derive(Clone, Copy, Debug)]
struct Near {
    x_b: f64,
    g_b: f64,
    d1: f64,
    d2: f64,
    d3: f64,
    reach: f64,
}

impl Near {
    fn at(&self, x: f64) -> f64 {
        let u = x - self.x_b;
        self.g_b + u * (self.d1 + u * (0.5 * self.d2 + u * self.d3 / 6.0))
    }
}

/// The air of `atmosphere` at `wavelength_nm` as a [`RadialAir`]: n − 1 = K(λ)·q(h); an error unless the atmosphere is spherically symmetric (a round Earth, edits that
/// depend on height alone) or the wavelength is outside its dispersion law's range.
pub fn radial_air(
    atmosphere: &crate::atmosphere::Atmosphere,
    wavelength_nm: f64,
) -> Result<RadialAir<AtmosphereIndex<'_>>, String> {
    let crate::atmosphere::Earth::Spherical(s) = &atmosphere.earth else {
        return Err(format!(
            "atmosphere \"{}\" has a flat Earth: terrestrial refraction needs a round one",
            atmosphere.name
        ));
    };
    if atmosphere.radial_centre().is_none() {
        return Err(format!(
            "atmosphere \"{}\" has edits that vary along the ground: Bouguer's invariant needs n to depend on height alone",
            atmosphere.name
        ));
    }
    atmosphere.dispersion.check_range((wavelength_nm, wavelength_nm))?;
    let k = atmosphere.dispersion.gladstone_dale_m3_per_kg(wavelength_nm);
    Ok(RadialAir {
        refractivity: AtmosphereIndex { atmosphere, k },
        kink_heights_m: atmosphere.smooth_piece_ends_m(),
        ground_radius_m: s.radius_m,
        top_m: atmosphere.top_m(),
    })
}

/// The index of an atmosphere's air at one wavelength as a function of height:
/// n − 1 = K(λ)·q(h), q its reduced refractivity (density over the reference density) and K the
/// dispersion law's Gladstone–Dale factor ([`radial_air`]).
#[derive(Clone, Copy, Debug)]
pub struct AtmosphereIndex<'a> {
    atmosphere: &'a crate::atmosphere::Atmosphere,
    k: f64,
}

impl RadialIndex for AtmosphereIndex<'_> {
    fn refractivity_slope(&self, h_m: f64) -> (f64, f64) {
        let (q, dq) = self.atmosphere.reduced_refractivity(h_m);
        (self.k * q, self.k * dq)
    }
}
