//! The refraction integral of a spherically symmetric atmosphere, by adaptive quadrature over
//! the ray's zenith distance (Hohenkerk & Sinclair 1985; Auer & Standish 2000).
//!
//! # Method
//! Along a ray in n(r), Bouguer's invariant n r sin z = k (z the zenith distance of the ray's
//! direction at radius r) holds, and the ray turns by dR = −tan z dn/n. Written over z instead of
//! r, with n + r dn/dr from differentiating the invariant,
//!
//! R = ∫_{z_top}^{z₀} −(r dn/dr)/(n + r dn/dr) dz,
//!
//! whose integrand stays finite at the horizon (z₀ = 90°), where the integral over height has
//! its tan z singularity. Each value of the integrand needs the r with n(r) r sin z = k, found
//! by Newton's iteration (d(nr)/dr = n + r dn/dr). The integral is split at the tropopause, where
//! dn/dr jumps (the layers' formulas are used on their own side), and each part is integrated
//! by adaptive Simpson quadrature with Richardson's correction to `tol_rad`. At the top r_s the
//! ray leaves n_s for vacuum and turns by asin(n_s sin z_s) − z_s (Snell); that term is reported
//! apart ([`Refraction::top_rad`]), since slaRefro omits it.
//!
//! The integral needs n + r dn/dr > 0 everywhere on the path (no ducting: r n(r) increasing);
//! otherwise the ray does not simply climb out, and [`refraction`] refuses (the ray trace,
//! [`super::model_trace`], follows any path).
//!
//! # References
//! - C. Y. Hohenkerk & A. T. Sinclair 1985, HM Nautical Almanac Office Technical Note 63.
//! - L. H. Auer & E. M. Standish 2000, "Astronomical refraction: computational method for all
//!   zenith angles", Astron. J. 119:2472–2474.
//! - W. M. Smart, *Textbook on Spherical Astronomy*, 6th ed., 1977, ch. III.

use super::model::{Layer, ModelAtmosphere};
use std::cell::Cell;

/// Refraction for one apparent zenith distance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Refraction {
    /// The integral from the observer to the top r_s, rad (slaRefro's quantity).
    pub integral_rad: f64,
    /// The turn at the top, from n_s to vacuum, rad.
    pub top_rad: f64,
    /// Evaluations of the integrand.
    pub evaluations: u64,
}

impl Refraction {
    /// The whole refraction: true minus apparent zenith distance, rad.
    pub fn total_rad(&self) -> f64 {
        self.integral_rad + self.top_rad
    }
}

/// Deepest bisection of the adaptive Simpson rule.
const MAX_DEPTH: u32 = 40;

/// The refraction at apparent zenith distance `zenith_rad` (0 … π/2) of model `m`, each layer's
/// integral to `tol_rad`.
pub fn refraction(m: &ModelAtmosphere, zenith_rad: f64, tol_rad: f64) -> Result<Refraction, String> {
    if !(0.0..=std::f64::consts::FRAC_PI_2).contains(&zenith_rad) {
        return Err(format!(
            "zenith distance {} deg is out of range for the quadrature; expected 0 … 90 deg (the ray trace follows rays below the horizon)",
            zenith_rad.to_degrees()
        ));
    }
    let (r0, rt, rs) = (m.r_obs_m, m.r_tropopause_m, m.r_top_m);
    let (n0, _) = m.n_rdndr(Layer::Troposphere, r0);
    let k = n0 * r0 * zenith_rad.sin();
    let z_at = |layer: Layer, r: f64| (k / (m.n_rdndr(layer, r).0 * r)).clamp(-1.0, 1.0).asin();
    let (z_t, z_s) = (z_at(Layer::Troposphere, rt), z_at(Layer::Stratosphere, rs));
    let tropo = Integrand::new(m, Layer::Troposphere, k, r0);
    let strato = Integrand::new(m, Layer::Stratosphere, k, rt);
    let integral_rad =
        simpson(&|z| tropo.at(z), z_t, zenith_rad, tol_rad)? + simpson(&|z| strato.at(z), z_s, z_t, tol_rad)?;
    if let Some(e) = tropo.error.get().or(strato.error.get()) {
        return Err(e.to_string());
    }
    let n_s = m.n_rdndr(Layer::Stratosphere, rs).0;
    let top_rad = (n_s * z_s.sin()).min(1.0).asin() - z_s;
    Ok(Refraction { integral_rad, top_rad, evaluations: tropo.count.get() + strato.count.get() })
}

/// −(r dn/dr)/(n + r dn/dr) as a function of z in one layer, with r(z) from the invariant.
struct Integrand<'a> {
    m: &'a ModelAtmosphere,
    layer: Layer,
    k: f64,
    /// The last root, the next iteration's start.
    r_last: Cell<f64>,
    count: Cell<u64>,
    error: Cell<Option<&'static str>>,
}

impl<'a> Integrand<'a> {
    fn new(m: &'a ModelAtmosphere, layer: Layer, k: f64, r_start: f64) -> Integrand<'a> {
        Integrand { m, layer, k, r_last: Cell::new(r_start), count: Cell::new(0), error: Cell::new(None) }
    }

    fn at(&self, z: f64) -> f64 {
        self.count.set(self.count.get() + 1);
        let target = self.k / z.sin();
        let mut r = self.r_last.get();
        for _ in 0..30 {
            let (n, rd) = self.m.n_rdndr(self.layer, r);
            let slope = n + rd;
            if slope <= 0.0 {
                self.error.set(Some(
                    "n + r·dn/dr ≤ 0 on the path (a duct): the refraction integral does not apply; use --method trace",
                ));
                return 0.0;
            }
            let dr = (n * r - target) / slope;
            r -= dr;
            if dr.abs() < 1e-6 {
                let (n, rd) = self.m.n_rdndr(self.layer, r);
                self.r_last.set(r);
                return -rd / (n + rd);
            }
        }
        self.error.set(Some("the root r(z) of n(r)·r·sin z = k did not converge"));
        0.0
    }
}

/// ∫_a^b f by adaptive Simpson quadrature with Richardson's correction, to `tol` absolute.
fn simpson(f: &dyn Fn(f64) -> f64, a: f64, b: f64, tol: f64) -> Result<f64, String> {
    if a == b {
        return Ok(0.0);
    }
    let (fa, fm, fb) = (f(a), f(0.5 * (a + b)), f(b));
    let whole = (b - a) / 6.0 * (fa + 4.0 * fm + fb);
    Ok(simpson_part(f, (a, fa), (b, fb), fm, whole, tol, MAX_DEPTH))
}

/// One interval [a, b] (with f at both ends and the middle, and its Simpson value): accepted
/// when its halves agree with it to 15 tol (the Richardson error estimate), else split.
fn simpson_part(
    f: &dyn Fn(f64) -> f64,
    (a, fa): (f64, f64),
    (b, fb): (f64, f64),
    fm: f64,
    whole: f64,
    tol: f64,
    depth: u32,
) -> f64 {
    let m = 0.5 * (a + b);
    let (fl, fr) = (f(0.5 * (a + m)), f(0.5 * (m + b)));
    let left = (m - a) / 6.0 * (fa + 4.0 * fl + fm);
    let right = (b - m) / 6.0 * (fm + 4.0 * fr + fb);
    let delta = left + right - whole;
    if depth == 0 || delta.abs() <= 15.0 * tol {
        return left + right + delta / 15.0;
    }
    simpson_part(f, (a, fa), (m, fm), fl, left, 0.5 * tol, depth - 1)
        + simpson_part(f, (m, fm), (b, fb), fr, right, 0.5 * tol, depth - 1)
}
