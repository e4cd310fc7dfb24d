//! The classical refraction formulas the traced values are compared with. Both are fits for
//! visual light at 1010 hPa and 10 °C; for other conditions they are multiplied by the
//! pressure–temperature factor.
//!
//! - Bennett 1982, from the apparent altitude h (degrees): R = cot(h + 7.31/(h + 4.4)) arcmin;
//!   fitted to Garfinkel's (1967) refraction theory, "accurate to within 0.07′ for 0°–90°"
//!   (Meeus 1991, p. 102).
//! - Saemundsson 1986, from the true altitude h₀ (degrees): R = 1.02 cot(h₀ + 10.3/(h₀ + 5.11))
//!   arcmin, "consistent with Bennett's to within 0.1′" (Meeus 1991, p. 103).
//! - Conditions: R × (P/1010)(283/(273 + T)), P in hPa, T in °C (Meeus 1991, p. 103). For the
//!   sea level of the U.S. Standard Atmosphere 1976 (1013.25 hPa, 15 °C) the factor is 0.98580.
//!
//! # References
//! - G. G. Bennett 1982, "The calculation of astronomical refraction in marine navigation",
//!   J. Navigation 35:255–259.
//! - Th. Saemundsson 1986, "Astronomical refraction", Sky & Telescope 72:70.
//! - J. Meeus, *Astronomical Algorithms*, Willmann-Bell 1991, pp. 102–103 (the accuracy
//!   statements and the factor as quoted in the Wikipedia article "Atmospheric refraction",
//!   section "Calculating refraction"; 2nd ed. 1998, ch. 16).

/// Radians per arcminute.
const RAD_PER_ARCMIN: f64 = std::f64::consts::PI / 10_800.0;

/// The pressure the formulas are fitted for, hPa.
pub const FORMULA_PRESSURE_HPA: f64 = 1010.0;
/// The temperature the formulas are fitted for, °C.
pub const FORMULA_TEMPERATURE_C: f64 = 10.0;

/// Bennett's refraction at apparent altitude `apparent_altitude_deg` (0–90°), rad, for
/// 1010 hPa and 10 °C.
pub fn bennett_rad(apparent_altitude_deg: f64) -> f64 {
    let h = apparent_altitude_deg;
    RAD_PER_ARCMIN / (h + 7.31 / (h + 4.4)).to_radians().tan()
}

/// Saemundsson's refraction for a star at true altitude `true_altitude_deg` (from about −1° to
/// 90°), rad, for 1010 hPa and 10 °C.
pub fn saemundsson_rad(true_altitude_deg: f64) -> f64 {
    let h = true_altitude_deg;
    1.02 * RAD_PER_ARCMIN / (h + 10.3 / (h + 5.11)).to_radians().tan()
}

/// The factor (P/1010)(283/(273 + T)) that carries the formulas to pressure `pressure_hpa` and
/// temperature `temperature_c`.
pub fn conditions_factor(pressure_hpa: f64, temperature_c: f64) -> f64 {
    (pressure_hpa / FORMULA_PRESSURE_HPA) * ((273.0 + FORMULA_TEMPERATURE_C) / (273.0 + temperature_c))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn published_values() {
        // Bennett at the horizon: cot(7.31/4.4 = 1.66136°) = 34.478′ (the 34.5′ commonly quoted).
        let r0 = bennett_rad(0.0) / RAD_PER_ARCMIN;
        assert!((r0 - 34.478).abs() < 1e-3, "{r0}");
        // 1013.25 hPa, 15 °C: (1013.25/1010)(283/288) = 0.985801.
        assert!((conditions_factor(1013.25, 15.0) - 0.985_801).abs() < 1e-6);
        assert_eq!(conditions_factor(1010.0, 10.0), 1.0);
        // Saemundsson is the inverse of Bennett to 0.1′: at apparent 10°, true = 10° − R.
        let rb = bennett_rad(10.0);
        let rs = saemundsson_rad(10.0 - rb.to_degrees());
        assert!((rb - rs).abs() < 0.1 * RAD_PER_ARCMIN, "{} vs {}", rb / RAD_PER_ARCMIN, rs / RAD_PER_ARCMIN);
    }
}
