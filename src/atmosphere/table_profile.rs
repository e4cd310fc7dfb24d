//! A tabulated atmosphere: temperature and pressure against geometric altitude, as published for
//! reference atmospheres (e.g. the AFGL tropical model of Anderson et al. 1986).
//!
//! T(z) and ln P(z) are interpolated by monotone cubics (PCHIP, see
//! [`crate::field::MonotoneCubic`]), so both are C¹ and neither overshoots the table; the
//! pressure derivative is dP/dz = P·d(ln P)/dz. Below the first row and above the last the state is
//! held at the end rows (derivatives zero).
//!
//! # File format
//! CSV with three columns `altitude_m,temperature_k,pressure_pa`: `#` comment lines and blank lines
//! are skipped, the first data row may be a header; altitudes strictly increasing, temperatures and
//! pressures positive.

use super::usa76::State;
use crate::field::MonotoneCubic;
use crate::spectrum::table::parse_numeric_columns;

/// T(z) and P(z) from a table (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct TableProfile {
    temperature: MonotoneCubic,
    ln_pressure: MonotoneCubic,
}

impl TableProfile {
    /// From rows (altitude m, temperature K, pressure Pa): altitudes strictly increasing, T and P
    /// positive.
    pub fn new(altitude_m: Vec<f64>, temperature_k: Vec<f64>, pressure_pa: Vec<f64>) -> Result<TableProfile, String> {
        if let Some(i) = temperature_k.iter().position(|t| t.is_nan() || *t <= 0.0) {
            return Err(format!("row {}: temperature {} K must be positive", i + 1, temperature_k[i]));
        }
        if let Some(i) = pressure_pa.iter().position(|p| p.is_nan() || *p <= 0.0) {
            return Err(format!("row {}: pressure {} Pa must be positive", i + 1, pressure_pa[i]));
        }
        let ln_p = pressure_pa.iter().map(|p| p.ln()).collect();
        let temperature =
            MonotoneCubic::new(altitude_m.clone(), temperature_k).map_err(|e| format!("temperature: {e}"))?;
        let ln_pressure = MonotoneCubic::new(altitude_m, ln_p).map_err(|e| format!("pressure: {e}"))?;
        Ok(TableProfile { temperature, ln_pressure })
    }

    /// Parses the CSV described in the module notes; errors carry the 1-based line.
    pub fn from_csv(text: &str) -> Result<TableProfile, (usize, String)> {
        let mut cols = parse_numeric_columns(text, &["altitude_m", "temperature_k", "pressure_pa"])?.into_iter();
        let (z, t, p) = (cols.next(), cols.next(), cols.next());
        TableProfile::new(z.unwrap_or_default(), t.unwrap_or_default(), p.unwrap_or_default()).map_err(|e| (1, e))
    }

    /// The state at geometric altitude `z_m`.
    pub fn state(&self, z_m: f64) -> State {
        let (t, dt) = self.temperature.eval_deriv(z_m);
        let (lp, dlp) = self.ln_pressure.eval_deriv(z_m);
        let p = lp.exp();
        State { temperature_k: t, pressure_pa: p, dt_dz: dt, dp_dz: p * dlp }
    }

    /// [first, last] altitude of the table, m.
    pub fn altitude_range(&self) -> (f64, f64) {
        self.temperature.domain()
    }

    /// The table's altitudes, m: between two the profile is smooth (T and ln P one cubic each).
    pub fn knot_altitudes_m(&self) -> &[f64] {
        self.temperature.knots().0
    }

    /// The lowest tabulated temperature (the interpolant does not go below it).
    pub fn min_temperature(&self) -> f64 {
        self.temperature.value_range().0
    }
}
