//! Lines of sight over the round Earth, from [`super::terrestrial`]: how far away the horizon
//! is, how much of a distant object it hides, and at what apparent elevations a point of the
//! object is seen.
//!
//! - The *grazing ray* leaves the observer (height h₀, radius r₀) just clear of the ground: its
//!   perigee is [`GRAZE_M`] above it, so its invariant is c = n(ε)(R + ε), and
//!   cos e_g = c/(n₀ r₀), written as 2 sin²(e_g/2) = ((h₀ − ε) n₀ + (N₀ − N_ε)(R + ε))/(n₀ r₀)
//!   so that nothing Earth-sized cancels (N = n − 1). Where it touches the ground is the
//!   *horizon*; its height at a farther distance is the *hidden height* there: anything lower
//!   is below the horizon. In air without refraction e_g is the dip arccos(R/r₀).
//! - A point at height H and central angle φ is seen along every ray that reaches it: every root
//!   of f(e) = h(e, φ) − H over the launch elevation e. In standard air f grows with e and there is
//!   one root; where rays cross — over a thin hot layer, in a superior mirage — there can be two
//!   or three, the mirage's images. The roots are bracketed on a grid of elevations
//!   [`GRID_DEG`] apart over ±[`SPAN_DEG`] about the straight line's elevation (a ray that meets
//!   the ground first counts as below the point, one that leaves the air upward short of it as
//!   above) and each is refined by bisection to 10⁻¹² rad; a sign change with a ray in the
//!   ground or away on one side (the horizon's edge) is no image, and images closer together
//!   than the grid are not told apart. Where the grazing ray itself leaves the air short of a distance, the
//!   hidden height there is ∞.

use super::terrestrial::{RadialAir, RadialIndex, Reach, follow, perigee};

/// Height of the grazing ray's perigee above the ground, m.
pub const GRAZE_M: f64 = 1e-6;
/// Spacing of the elevations on which images are bracketed, degrees.
pub const GRID_DEG: f64 = 1e-3;
/// Half-width of the bracketing grid about the straight line's elevation, degrees.
pub const SPAN_DEG: f64 = 2.0;
/// Tolerance of the angle integrals, rad.
const TOL_RAD: f64 = 1e-12;

/// The observer's horizon.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Horizon {
    /// Elevation of the grazing ray at the observer, rad (≤ 0).
    pub elevation_rad: f64,
    /// Central angle from the observer's foot to where it touches the ground, rad.
    pub angle_rad: f64,
}

/// The horizon of an observer `h0_m` above the ground (`None` on the ground, where the grazing
/// ray is level and the horizon at the observer's feet).
pub fn horizon<F: RadialIndex>(air: &RadialAir<F>, h0_m: f64) -> Result<Option<Horizon>, String> {
    if h0_m <= GRAZE_M {
        return Ok(None);
    }
    let r = |h: f64| air.ground_radius_m + h;
    let (n0, ne) = (air.refractivity.refractivity(h0_m), air.refractivity.refractivity(GRAZE_M));
    let above = (h0_m - GRAZE_M) * (1.0 + n0) + (n0 - ne) * r(GRAZE_M);
    if above <= 0.0 {
        return Err(format!(
            "no ray from {h0_m} m grazes the ground: n·r does not grow from the ground to the observer (a duct)"
        ));
    }
    let elevation_rad = -2.0 * (above / (2.0 * (1.0 + n0) * r(h0_m))).sqrt().asin();
    let (_, angle_rad) = perigee(air, h0_m, elevation_rad, TOL_RAD)?
        .ok_or_else(|| format!("the grazing ray from {h0_m} m meets the ground before its perigee"))?;
    Ok(Some(Horizon { elevation_rad, angle_rad }))
}

/// How high the horizon of an observer `h0_m` up hides things at central angle `angle_rad`: the
/// grazing ray's height there (0 before the horizon), m.
pub fn hidden_height<F: RadialIndex>(air: &RadialAir<F>, h0_m: f64, angle_rad: f64) -> Result<f64, String> {
    let (e, beyond) = match horizon(air, h0_m)? {
        Some(h) => (h.elevation_rad, angle_rad > h.angle_rad),
        None => (0.0, angle_rad > 0.0),
    };
    if !beyond {
        return Ok(0.0);
    }
    match follow(air, h0_m, e, angle_rad, TOL_RAD)?.reach {
        Reach::Aloft { height_m, .. } => Ok(height_m),
        Reach::Ground { .. } => Err("the grazing ray met the ground again (a duct beyond the horizon)".to_string()),
        Reach::Away { .. } => Ok(f64::INFINITY),
    }
}

/// The apparent elevations (rad, ascending) at which an observer `h0_m` up sees the point
/// `height_m` above the ground at central angle `angle_rad` > 0 (module notes): none when it is
/// hidden, several in a mirage.
pub fn images<F: RadialIndex>(
    air: &RadialAir<F>,
    h0_m: f64,
    angle_rad: f64,
    height_m: f64,
) -> Result<Vec<f64>, String> {
    if !(angle_rad.is_finite() && angle_rad > 0.0 && height_m.is_finite() && height_m >= 0.0) {
        return Err(format!("target at {angle_rad} rad, {height_m} m: expected an angle > 0 and a height ≥ 0"));
    }
    // How far above the point the ray from e passes, and whether it is in the air there.
    let miss = |e: f64| -> Result<(f64, bool), String> {
        Ok(match follow(air, h0_m, e, angle_rad, TOL_RAD)?.reach {
            Reach::Aloft { height_m: h, .. } => (h - height_m, true),
            Reach::Ground { .. } => (-1.0 - height_m, false),
            // Up and away, above every point at that angle.
            Reach::Away { .. } => (1.0, false),
        })
    };
    let geometric = straight_elevation(air.ground_radius_m, h0_m, angle_rad, height_m);
    let half = std::f64::consts::FRAC_PI_2 - 1e-6;
    let (lo, hi) = ((geometric - SPAN_DEG.to_radians()).max(-half), (geometric + SPAN_DEG.to_radians()).min(half));
    let steps = ((hi - lo) / GRID_DEG.to_radians()).ceil() as usize;
    let grid: Vec<f64> = (0..=steps).map(|i| lo + (hi - lo) * i as f64 / steps as f64).collect();
    let values = grid.iter().map(|&e| miss(e)).collect::<Result<Vec<_>, _>>()?;
    let mut roots = Vec::new();
    for i in 0..steps {
        let ((va, fa), (vb, fb)) = (values[i], values[i + 1]);
        if (va < 0.0) != (vb < 0.0) {
            // A sign change between rays that end in the ground or away and rays in the air is
            // an edge, not a ray to the point: a root needs rays in the air on both sides.
            let (e, in_air) = bisect(&miss, (grid[i], fa), (grid[i + 1], fb), va < 0.0)?;
            if in_air {
                roots.push(e);
            }
        }
    }
    Ok(roots)
}

/// The elevation of the straight line from height `h0` to the point `height` up at central
/// angle `phi` (ground radius `r_e`), rad.
pub fn straight_elevation(r_e: f64, h0: f64, phi: f64, height: f64) -> f64 {
    // The target in the observer's frame: forward (r_t sin φ), up (r_t cos φ − r₀), with
    // r_t cos φ − r₀ = (height − h₀) − 2 r_t sin²(φ/2).
    let r_t = r_e + height;
    let half = (0.5 * phi).sin();
    ((height - h0) - 2.0 * r_t * half * half).atan2(r_t * phi.sin())
}

/// The sign change of `miss` between `a` and `b` (each with whether its ray is in the air;
/// `rising`: negative at `a`), to 10⁻¹² rad, and whether the rays on both sides of it are in the
/// air.
fn bisect(
    miss: &dyn Fn(f64) -> Result<(f64, bool), String>,
    (mut a, mut in_a): (f64, bool),
    (mut b, mut in_b): (f64, bool),
    rising: bool,
) -> Result<(f64, bool), String> {
    while b - a > 1e-12 {
        let m = 0.5 * (a + b);
        let (v, in_m) = miss(m)?;
        if (v < 0.0) == rising {
            (a, in_a) = (m, in_m);
        } else {
            (b, in_b) = (m, in_m);
        }
    }
    Ok((0.5 * (a + b), in_a && in_b))
}
