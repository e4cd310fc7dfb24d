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
//! by adaptive Gauss–Kronrod (7–15) quadrature to `tol_rad` ([`crate::quadrature`]): the
//! integrand is smooth in each layer, where the 15-point rule needs a fraction of the
//! evaluations of adaptive Simpson. At the top r_s the
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
use crate::quadrature::adaptive_gauss_kronrod;
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
    let integral_rad = adaptive_gauss_kronrod(&mut |z| tropo.at(z), z_t, zenith_rad, tol_rad)
        + adaptive_gauss_kronrod(&mut |z| strato.at(z), z_s, z_t, tol_rad);
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
    /// n at the last root: the next root is started at k/(n_last sin z).
    n_last: Cell<f64>,
    count: Cell<u64>,
    error: Cell<Option<&'static str>>,
}

impl<'a> Integrand<'a> {
    fn new(m: &'a ModelAtmosphere, layer: Layer, k: f64, r_start: f64) -> Integrand<'a> {
        let n_start = m.n_rdndr(layer, r_start).0;
        Integrand { m, layer, k, n_last: Cell::new(n_start), count: Cell::new(0), error: Cell::new(None) }
    }

    /// The integrand at z. Newton's iteration for n(r)·r = k/sin z starts at
    /// r = k/(n_last sin z): n varies by 3 × 10⁻⁴ over the whole atmosphere, so the start is
    /// within ~2 km of the root wherever the quadrature evaluated last, and n·r is nearly linear
    /// in r. It stops when the next correction is below 1 µm and returns the integrand where it
    /// stands (within that 1 µm of the root: a relative change of ~10⁻¹⁰ over a scale height of
    /// 8 km, far below the quadrature's tolerance).
    fn at(&self, z: f64) -> f64 {
        self.count.set(self.count.get() + 1);
        let target = self.k / z.sin();
        let mut r = target / self.n_last.get();
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
            if dr.abs() < 1e-6 {
                self.n_last.set(n);
                return -rd / slope;
            }
            r -= dr;
        }
        self.error.set(Some("the root r(z) of n(r)·r·sin z = k did not converge"));
        0.0
    }
}
