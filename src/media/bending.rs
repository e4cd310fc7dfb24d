//! Where ray bending in an atmosphere medium is negligible: a bound on how much the radiance
//! along a line of sight changes when the medium's refraction is switched off.
//!
//! In a horizontally stratified atmosphere a ray keeps n(h) sin z(h) = n₀ sin z (Snell's law
//! for layers; the bending invariant). Against the straight line at the same apparent zenith
//! angle z, the bent ray turns by at most the total refraction R ≤ (n₀ − 1) tan z, and its
//! local slant sec z(h) grows by at most (n₀ − 1) tan² z sec z relative to the straight one's
//! (d sec z / d sin z = tan z sec² z, δ sin z ≤ (n₀ − 1) sin z). The radiance carried along the
//! line of sight — the sun's or a surface's, attenuated by the air — therefore changes by at most
//!
//! B(z, λ) = (n₀(λ) − 1) tan² z · τ(λ) sec z
//!
//! relative, τ the vertical optical depth of the whole atmosphere (to first order in n₀ − 1 and
//! in the curvature of the Earth, which changes sec z by less than 1 % for z ≤ 75°). For an
//! exponential atmosphere, where n − 1 is proportional to the density, the change is half the
//! bound: the weight of n₀ − (n(h) − 1) over the air's column is (n₀ − 1)/2. The bound is on the
//! attenuation; the turn R moves the point of a distant source that is seen (nothing, for a
//! uniformly bright disc seen well inside its rim; the whole effect, for a mirage in clear air,
//! which the bound does not judge). Light scattered into
//! the line of sight changes by the same amount for each of its legs, provided every leg is as
//! high above the horizon; the bound does not cover multiply scattered light that travels near
//! the horizon on its way.
//!
//! # References
//! - Smart, W. M. (1977), *Textbook on Spherical Astronomy*, 6th ed., ch. 3 (refraction in a
//!   plane-stratified atmosphere, R ≈ (n₀ − 1) tan z).

use super::Medium;
use super::refractive_index::IndexField;
use super::tracking::optical_depth_exact;
use glam::DVec3;

/// Above this relative change, bending matters for a scene's radiance.
pub const NEGLIGIBLE: f64 = 1e-3;

/// The longest vertical chord over which the whole atmosphere's optical depth is read, m.
const COLUMN_M: f64 = 1.0e6;

/// B(z, λ) for medium `m` at the ground point `ground` (see the module's documentation), or
/// `None` when `m` is not an atmosphere whose air bends light, or the zenith angle is 90° or more.
pub fn radiance_bound(m: &Medium, wavelength_nm: f64, ground: DVec3, zenith_rad: f64) -> Option<f64> {
    let refractivity = refractivity(m, wavelength_nm, ground, zenith_rad)?;
    let tau = optical_depth_exact(m, wavelength_nm, ground, DVec3::Y, COLUMN_M)?;
    Some(refractivity * zenith_rad.tan().powi(2) * tau / zenith_rad.cos())
}

/// The most a line of sight at zenith angle z turns through the whole atmosphere,
/// R ≤ (n₀ − 1) tan z, rad; `None` as for [`radiance_bound`].
pub fn refraction_bound_rad(m: &Medium, wavelength_nm: f64, ground: DVec3, zenith_rad: f64) -> Option<f64> {
    Some(refractivity(m, wavelength_nm, ground, zenith_rad)? * zenith_rad.tan())
}

/// n₀ − 1 at `ground` for an atmosphere index field and a zenith angle below 90°.
fn refractivity(m: &Medium, wavelength_nm: f64, ground: DVec3, zenith_rad: f64) -> Option<f64> {
    let field = m.index.as_ref()?;
    if !matches!(field, IndexField::Atmosphere(_)) || !(0.0..std::f64::consts::FRAC_PI_2).contains(&zenith_rad) {
        return None;
    }
    Some(field.n(wavelength_nm, ground) - 1.0)
}
