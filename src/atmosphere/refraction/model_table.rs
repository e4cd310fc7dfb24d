//! The table of `morgana refraction` without `--atmosphere`: refraction per zenith distance in
//! the model atmosphere of the observer's conditions ([`super::model`]), by quadrature
//! ([`super::quadrature`]) or by the ray trace ([`super::model_trace`]), as text and as CSV
//! (`zenith_distance_deg,apparent_altitude_deg,refraction_arcsec`).

use super::ARCSEC_PER_RAD;
use super::model::{ModelAtmosphere, Refractivity};
use super::model_trace::traced_refraction;
use super::quadrature::refraction;
use crate::error::{Error, Result};
use std::fmt::Write as _;
use std::path::Path;

/// The quadrature's tolerance per layer, rad (10⁻¹⁰ rad = 2 × 10⁻⁵″, far below the 0.01″
/// the quadrature and the trace agree to).
pub const QUADRATURE_TOL_RAD: f64 = 1e-10;

/// How the refraction is computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ModelMethod {
    /// The refraction integral by adaptive quadrature.
    Quadrature,
    /// The ray trace (the quadrature's oracle).
    Trace,
}

/// One zenith distance: the refraction (rad) and the work (integrand evaluations or steps).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ModelRow {
    /// Apparent zenith distance, degrees.
    pub zenith_deg: f64,
    /// True minus apparent zenith distance, rad.
    pub refraction_rad: f64,
    /// Integrand evaluations (quadrature) or accepted steps (trace).
    pub work: u64,
}

/// The refraction table of one model atmosphere.
#[derive(Clone, Debug, PartialEq)]
pub struct ModelTable {
    /// The model.
    pub model: ModelAtmosphere,
    /// The method used.
    pub method: ModelMethod,
    /// One row per zenith distance, in the order asked.
    pub rows: Vec<ModelRow>,
}

/// The refraction at each apparent zenith distance (degrees, 0–90) of `zeniths_deg`; the rows
/// are computed in parallel (each is independent of the others, so the table does not depend on
/// the thread count).
pub fn model_table(model: &ModelAtmosphere, zeniths_deg: &[f64], method: ModelMethod) -> Result<ModelTable> {
    use rayon::prelude::*;
    let rows = zeniths_deg.par_iter().map(|&z| model_row(model, z, method)).collect::<Result<Vec<_>>>()?;
    Ok(ModelTable { model: *model, method, rows })
}

/// One row of [`model_table`].
fn model_row(model: &ModelAtmosphere, zenith_deg: f64, method: ModelMethod) -> Result<ModelRow> {
    let (refraction_rad, work) = match method {
        ModelMethod::Quadrature => {
            let q =
                refraction(model, zenith_deg.to_radians(), QUADRATURE_TOL_RAD).map_err(|e| Error::input(None, e))?;
            (q.total_rad(), q.evaluations)
        }
        ModelMethod::Trace => traced_refraction(model, zenith_deg.to_radians()).map_err(|e| Error::input(None, e))?,
    };
    Ok(ModelRow { zenith_deg, refraction_rad, work })
}

impl ModelTable {
    /// The table as text: a header with the conditions, one line per zenith distance.
    pub fn to_text(&self) -> String {
        let o = &self.model.observer;
        let law = match self.model.law {
            Refractivity::Ciddor(c) => format!("Ciddor 1996 moist air, {} µmol/mol CO₂", c.co2_ppm),
            Refractivity::HohenkerkSinclair => "slaRefro's refractivity (IAG 1999 dry air)".to_string(),
        };
        let (method, work) = match self.method {
            ModelMethod::Quadrature => ("quadrature of the refraction integral", "evaluations"),
            ModelMethod::Trace => ("ray trace", "ode_steps"),
        };
        let mut s = format!(
            "astronomical refraction ({method}): model atmosphere of Hohenkerk & Sinclair, {law}\n\
             {} nm, observer at {} m, {} hPa, {:.2} °C, relative humidity {}, latitude {}°, lapse rate {} K/m\n\
             zenith_deg  apparent_alt_deg  refraction_arcsec  refraction_arcmin  {work}\n",
            o.wavelength_nm,
            o.height_m,
            o.pressure_hpa,
            o.temperature_k - 273.15,
            o.humidity,
            o.latitude_deg,
            o.lapse_k_per_m
        );
        for r in &self.rows {
            let a = r.refraction_rad * ARCSEC_PER_RAD;
            let _ = writeln!(
                s,
                "{:>10}  {:>16}  {a:>17.4}  {:>17.4}  {:>11}",
                r.zenith_deg,
                round9(90.0 - r.zenith_deg),
                a / 60.0,
                r.work
            );
        }
        s
    }

    /// Writes the CSV atomically to `path`.
    pub fn write_csv(&self, path: &Path) -> Result<()> {
        let mut text = String::from("zenith_distance_deg,apparent_altitude_deg,refraction_arcsec\n");
        for r in &self.rows {
            let _ = writeln!(
                text,
                "{},{},{:.6}",
                r.zenith_deg,
                round9(90.0 - r.zenith_deg),
                r.refraction_rad * ARCSEC_PER_RAD
            );
        }
        super::write_csv(path, &text)
    }
}

/// `x` rounded to 10⁻⁹ (so 90 − 89.9 prints as 0.1).
fn round9(x: f64) -> f64 {
    (x * 1e9).round() / 1e9
}
