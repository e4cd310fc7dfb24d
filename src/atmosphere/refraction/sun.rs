//! The refracted shape of a disc (the sun) near the horizon.
//!
//! Refraction falls with altitude, so the lower limb of a low sun is lifted more than the upper:
//! the disc is squashed vertically. With the lower limb seen at apparent altitude a_L, its true
//! altitude is t_L = a_L − R(a_L); the upper limb is one diameter D higher, t_U = t_L + D, and is
//! seen at the apparent altitude a_U that solves a_U − R(a_U) = t_U. The apparent vertical
//! diameter is a_U − a_L; the horizontal diameter is unchanged to first order (refraction acts
//! along the vertical circle, and the two ends of a horizontal diameter are at the same
//! altitude), so the vertical/horizontal ratio is (a_U − a_L)/D.
//!
//! Near the horizon this ratio is about 5/6: refraction is 34′ at the horizon and 29′ half a
//! degree up, so the sun "seems to be flattened by about 5′ (about 1/6 of its apparent
//! diameter)" (Wikipedia, "Atmospheric refraction", section "Values", after Allen 1976).
//!
//! # References
//! - A. T. Young 2004, "Sunset science. IV. Low-altitude refraction", Astron. J. 127:3622 (the
//!   flattened sun as a measure of the refraction gradient).

use super::refractor::Refractor;
use crate::error::Result;

/// The sun's mean angular diameter used here, 0.53°, rad.
pub const SUN_DIAMETER_RAD: f64 = 0.53 * std::f64::consts::PI / 180.0;

/// The limbs of a refracted disc.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Flattening {
    /// Apparent altitude a_L of the lower limb, rad.
    pub lower_apparent_rad: f64,
    /// True altitude t_L of the lower limb, rad.
    pub lower_true_rad: f64,
    /// Apparent altitude a_U of the upper limb, rad.
    pub upper_apparent_rad: f64,
    /// True altitude t_U = t_L + D of the upper limb, rad.
    pub upper_true_rad: f64,
    /// Apparent vertical over horizontal diameter, (a_U − a_L)/D.
    pub ratio: f64,
}

/// The refracted disc of angular diameter `diameter_rad` whose lower limb is seen at
/// `lower_apparent_rad`; `None` if a limb's ray does not escape the atmosphere.
pub fn flattened_disc(refractor: &Refractor, lower_apparent_rad: f64, diameter_rad: f64) -> Result<Option<Flattening>> {
    let Some(r_low) = refractor.refraction_rad(lower_apparent_rad)? else { return Ok(None) };
    let lower_true_rad = lower_apparent_rad - r_low;
    let upper_true_rad = lower_true_rad + diameter_rad;
    // Refraction falls with altitude, so a_U lies between a_L and a_L + D.
    let hi = (lower_apparent_rad + diameter_rad).min(std::f64::consts::FRAC_PI_2);
    let Some(upper_apparent_rad) = apparent_for_true(refractor, upper_true_rad, lower_apparent_rad, hi)? else {
        return Ok(None);
    };
    Ok(Some(Flattening {
        lower_apparent_rad,
        lower_true_rad,
        upper_apparent_rad,
        upper_true_rad,
        ratio: (upper_apparent_rad - lower_apparent_rad) / diameter_rad,
    }))
}

/// The apparent altitude in [`lo`, `hi`] (rad) at which a star of true altitude `true_rad` is
/// seen: the root of g(a) = a − R(a) − t, by the Illinois variant of regula falsi to 10⁻¹¹ rad.
/// `None` when g does not change sign over the bracket or a ray in it does not escape.
pub fn apparent_for_true(refractor: &Refractor, true_rad: f64, lo: f64, hi: f64) -> Result<Option<f64>> {
    let g = |a: f64| -> Result<Option<f64>> { Ok(refractor.true_altitude_rad(a)?.map(|t| t - true_rad)) };
    let (Some(mut ga), Some(mut gb)) = (g(lo)?, g(hi)?) else { return Ok(None) };
    let (mut a, mut b) = (lo, hi);
    if ga == 0.0 {
        return Ok(Some(a));
    }
    if ga.signum() == gb.signum() {
        return Ok(None);
    }
    let mut side = 0;
    for _ in 0..100 {
        let c = (a * gb - b * ga) / (gb - ga);
        let Some(gc) = g(c)? else { return Ok(None) };
        if gc == 0.0 || (b - a).abs() < 1e-11 {
            return Ok(Some(c));
        }
        if gc.signum() == gb.signum() {
            (b, gb) = (c, gc);
            if side == -1 {
                ga *= 0.5;
            }
            side = -1;
        } else {
            (a, ga) = (c, gc);
            if side == 1 {
                gb *= 0.5;
            }
            side = 1;
        }
        if gc.abs() < 1e-13 {
            return Ok(Some(c));
        }
    }
    Ok(Some(0.5 * (a + b)))
}
