//! The ray equation as a first-order system in arc length, and its state.
//!
//! Fermat's principle gives the ray equation d/ds (n dr/ds) = ∇n (Born & Wolf, *Principles of
//! Optics*, §3.2.1, eq. 3.2(2); Gutierrez et al. 2005, eq. 7) with s the arc length. With the
//! *ray vector* v = n dr/ds (so |v| = n along an exact solution) it becomes the autonomous system
//!
//! ```text
//!     dr/ds = v / n(r),        dv/ds = ∇n(r),
//! ```
//!
//! which is smooth wherever n is, needs n and ∇n once per evaluation, and keeps the Bouguer
//! invariants of layered media exact: where ∂n/∂x = 0 the component v_x does not change at all,
//! in any Runge–Kutta method. (Gutierrez et al. write it for the unit tangent, eq. 9–11, which
//! needs dn/ds as well.)
//!
//! The magnitude |v| = n(r) is a first integral that a numerical step keeps only to its local
//! error; [`project`] restores it after a step (optional: see [`super::Integrator::with_projection`]).
//!
//! # References
//! - M. Born, E. Wolf, *Principles of Optics*, 7th ed., Cambridge 1999, §3.2.
//! - D. Gutierrez, A. Muñoz, O. Anson, F. J. Serón, "Non-linear volume photon mapping",
//!   Eurographics Symposium on Rendering 2005, §2.3, eq. 7–11.

use super::error::OdeError;
use glam::DVec3;
use std::ops::{Add, Mul, Sub};

/// n and ∇n at a point, for one wavelength.
pub trait IndexSample {
    /// The refractive index n (dimensionless) and its gradient ∇n (m⁻¹) at `p` (m).
    fn n_grad(&self, p: DVec3) -> (f64, DVec3);
}

impl<F: Fn(DVec3) -> (f64, DVec3)> IndexSample for F {
    #[inline]
    fn n_grad(&self, p: DVec3) -> (f64, DVec3) {
        self(p)
    }
}

/// The state of the ray system: position `r` (m) and ray vector `v` = n·dr/ds. The same type
/// holds a derivative d/ds (`r` = dr/ds, `v` = dv/ds = ∇n) and the dense-output coefficients.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RayY {
    /// Position r, m (or dr/ds, the unit tangent, in a derivative).
    pub r: DVec3,
    /// Ray vector v = n dr/ds (or dv/ds = ∇n, m⁻¹, in a derivative).
    pub v: DVec3,
}

impl RayY {
    /// The state at `p` travelling along `dir` (any length, not zero) where the index is `n`:
    /// v = n·dir/|dir|.
    pub fn new(p: DVec3, dir: DVec3, n: f64) -> RayY {
        RayY { r: p, v: dir.normalize_or_zero() * n }
    }

    /// The state at `p` travelling along `dir`, with n sampled from `field`.
    pub fn launch<F: IndexSample>(field: &F, p: DVec3, dir: DVec3) -> Result<RayY, OdeError> {
        if !(p.is_finite() && dir.is_finite() && dir.length_squared() > 0.0) {
            return Err(OdeError::BadState { r: p, v: dir });
        }
        let (n, _) = sample(field, p)?;
        Ok(RayY::new(p, dir, n))
    }

    /// The unit direction of travel v/|v| (zero if v is).
    #[inline]
    pub fn direction(&self) -> DVec3 {
        self.v.normalize_or_zero()
    }

    /// The curvature vector of the path here where the gradient is `grad`:
    /// a = (∇n − (∇n·d)d)/n, d = v/|v| and n = |v| (what kink cuts predict a crossing with).
    pub fn curvature(&self, grad: DVec3) -> DVec3 {
        let n = self.v.length();
        let d = self.v / n;
        (grad - grad.dot(d) * d) / n
    }

    /// All six components finite.
    #[inline]
    pub fn is_finite(&self) -> bool {
        self.r.is_finite() && self.v.is_finite()
    }

    /// The components in a fixed order (x, y, z, v_x, v_y, v_z).
    #[inline]
    pub fn to_array(&self) -> [f64; 6] {
        [self.r.x, self.r.y, self.r.z, self.v.x, self.v.y, self.v.z]
    }
}

impl Add for RayY {
    type Output = RayY;
    #[inline]
    fn add(self, o: RayY) -> RayY {
        RayY { r: self.r + o.r, v: self.v + o.v }
    }
}

impl Sub for RayY {
    type Output = RayY;
    #[inline]
    fn sub(self, o: RayY) -> RayY {
        RayY { r: self.r - o.r, v: self.v - o.v }
    }
}

impl Mul<f64> for RayY {
    type Output = RayY;
    #[inline]
    fn mul(self, k: f64) -> RayY {
        RayY { r: self.r * k, v: self.v * k }
    }
}

/// n and ∇n at `p`, checked: n must be finite and positive, ∇n finite. (One test for all
/// four: t = n + Σ∂n is finite only if each term is; components so large that their sum
/// overflows are refused too.)
#[inline]
pub fn sample<F: IndexSample>(field: &F, p: DVec3) -> Result<(f64, DVec3), OdeError> {
    let (n, grad_n) = field.n_grad(p);
    let t = n + grad_n.x + grad_n.y + grad_n.z;
    if n > 0.0 && t.is_finite() { Ok((n, grad_n)) } else { Err(OdeError::BadIndex { at: p, n, grad_n }) }
}

/// The right-hand side f(y) = (v/n, ∇n) given n and ∇n at y.r.
#[inline]
pub fn rhs(y: &RayY, n: f64, grad_n: DVec3) -> RayY {
    RayY { r: y.v * (1.0 / n), v: grad_n }
}

/// f(y), sampling the field at y.r; returns f and n(y.r).
#[inline]
pub fn eval<F: IndexSample>(field: &F, y: &RayY) -> Result<(RayY, f64), OdeError> {
    let (n, g) = sample(field, y.r)?;
    Ok((rhs(y, n, g), n))
}

/// Projection onto the invariant |v| = n(r): v ← n·v/|v|, and the derivative's dr/ds = v/n
/// recomputed for the projected v (∇n does not depend on v), so the pair stays consistent for
/// FSAL and dense output. `n` is n(y.r).
#[inline]
pub fn project(y: &mut RayY, f: &mut RayY, n: f64) {
    let len = y.v.length();
    if len > 0.0 && len.is_finite() {
        y.v *= n / len;
        f.r = y.v / n;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rhs_of_a_linear_field_and_projection() {
        let field = |p: DVec3| (1.0 + 0.1 * p.y, DVec3::new(0.0, 0.1, 0.0));
        let y = RayY::launch(&field, DVec3::new(0.0, 2.0, 0.0), DVec3::new(3.0, 0.0, 4.0)).unwrap();
        assert!((y.v.length() - 1.2).abs() < 1e-15);
        let (f, n) = eval(&field, &y).unwrap();
        assert_eq!(n, 1.2);
        assert!((f.r - DVec3::new(0.6, 0.0, 0.8)).length() < 1e-15, "dr/ds is the unit tangent");
        assert_eq!(f.v, DVec3::new(0.0, 0.1, 0.0));
        let mut y2 = RayY { r: y.r, v: y.v * 1.01 };
        let mut f2 = rhs(&y2, n, f.v);
        project(&mut y2, &mut f2, n);
        assert!((y2.v.length() - n).abs() < 1e-15);
        assert!((f2.r.length() - 1.0).abs() < 1e-15);
    }

    #[test]
    fn bad_samples_are_errors() {
        let zero = |_: DVec3| (0.0, DVec3::ZERO);
        assert!(matches!(sample(&zero, DVec3::ZERO), Err(OdeError::BadIndex { .. })));
        let nan_grad = |_: DVec3| (1.0, DVec3::new(f64::NAN, 0.0, 0.0));
        assert!(sample(&nan_grad, DVec3::ZERO).is_err());
        let inf = |_: DVec3| (f64::INFINITY, DVec3::ZERO);
        assert!(sample(&inf, DVec3::ZERO).is_err());
        let ok = |_: DVec3| (1.0, DVec3::ZERO);
        assert!(RayY::launch(&ok, DVec3::ZERO, DVec3::ZERO).is_err(), "zero direction");
    }
}
