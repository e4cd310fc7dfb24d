//! The table of `morgana refraction`: the refraction per apparent altitude (by Bouguer's
//! quadrature or traced, [`super::refractor`]) beside the classical formulas carried to the observer's pressure and temperature, the CSV
//! (`apparent_altitude_deg,true_altitude_deg,refraction_arcsec`; both values empty for a ray that
//! does not escape), the dispersion between wavelengths and the flattened sun.

use super::formulas::{bennett_rad, conditions_factor, saemundsson_rad};
use super::refractor::{Answer, Refractor};
use super::sun::{Flattening, SUN_DIAMETER_RAD, flattened_disc};
use super::{ARCSEC_PER_RAD, Outcome, Trace};
use crate::error::Result;
use std::fmt::Write as _;
use std::path::Path;

/// One apparent altitude: the trace and the formulas' refraction there (rad; `None` where a
/// formula does not apply: below 0° apparent for Bennett, below −1° true or no escape for
/// Saemundsson, which is evaluated at the traced true altitude).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Row {
    /// Apparent altitude of the ray at the observer, degrees.
    pub apparent_altitude_deg: f64,
    /// The ray's outcome (traced, or the quadrature's: see `quadrature_evaluations`).
    pub trace: Trace,
    /// Bennett's refraction at the observer's conditions, rad.
    pub bennett_rad: Option<f64>,
    /// Saemundsson's refraction at the traced true altitude and the observer's conditions, rad.
    pub saemundsson_rad: Option<f64>,
    /// `Some(evaluations)` when the row came from Bouguer's quadrature
    /// ([`super::terrestrial::true_altitude`]; `trace` then holds its outcome, no path length
    /// and no steps), `None` when it was traced.
    pub quadrature_evaluations: Option<u64>,
}

/// The refraction table of one observer.
#[derive(Clone, Debug, PartialEq)]
pub struct Table {
    /// Name of the atmosphere.
    pub atmosphere: String,
    /// Wavelength traced, nm.
    pub wavelength_nm: f64,
    /// Observer's height above the ground, m.
    pub observer_height_m: f64,
    /// The air at the observer, and the factor (P/1010)(283/(273 + T)) applied to the formulas.
    pub pressure_hpa: f64,
    /// Air temperature at the observer, °C.
    pub temperature_c: f64,
    /// The conditions factor (P/1010)(283/(273 + T)) applied to both formulas.
    pub factor: f64,
    /// One row per apparent altitude, in the order asked.
    pub rows: Vec<Row>,
}

/// Every apparent altitude (degrees) of `altitudes_deg`, by the refractor's method.
pub fn table(refractor: &Refractor, altitudes_deg: &[f64]) -> Result<Table> {
    let tracer = refractor.tracer();
    let atm = tracer.atmosphere();
    let air = atm.air(tracer.observer());
    let (pressure_hpa, temperature_c) = (air.pressure_pa / 100.0, air.temperature_k - 273.15);
    let factor = conditions_factor(pressure_hpa, temperature_c);
    let mut rows = Vec::with_capacity(altitudes_deg.len());
    for &a in altitudes_deg {
        let Answer { trace, quadrature_evaluations } = refractor.answer(a.to_radians())?;
        let bennett_rad = (a >= 0.0).then(|| factor * bennett_rad(a));
        let saemundsson_rad =
            trace.true_altitude_rad().map(f64::to_degrees).filter(|t| *t >= -1.0).map(|t| factor * saemundsson_rad(t));
        rows.push(Row { apparent_altitude_deg: a, trace, bennett_rad, saemundsson_rad, quadrature_evaluations });
    }
    Ok(Table {
        atmosphere: atm.name.clone(),
        wavelength_nm: tracer.wavelength_nm(),
        observer_height_m: atm.earth.height(tracer.observer()),
        pressure_hpa,
        temperature_c,
        factor,
        rows,
    })
}

impl Table {
    /// The table as text, one line per apparent altitude.
    pub fn to_text(&self) -> String {
        let mut s = format!(
            "astronomical refraction: atmosphere \"{}\", {} nm, observer at {} m ({:.2} hPa, {:.2} °C)\n\
             formulas for 1010 hPa, 10 °C, scaled by (P/1010)(283/(273+T)) = {:.5}; Saemundsson at the traced true altitude\n",
            self.atmosphere,
            self.wavelength_nm,
            self.observer_height_m,
            self.pressure_hpa,
            self.temperature_c,
            self.factor
        );
        s.push_str("apparent_deg      true_deg  refraction_arcsec  refraction_arcmin  bennett_arcsec  saemundsson_arcsec  ode_steps\n");
        if self.rows.iter().any(|r| r.quadrature_evaluations.is_some()) {
            s.push_str("(by Bouguer's quadrature: the last column is its evaluations of n, marked q; rays it does not follow are traced)\n");
        }
        for r in &self.rows {
            s.push_str(&row_text(r));
            s.push('\n');
        }
        s
    }

    /// Writes the CSV atomically to `path`.
    pub fn write_csv(&self, path: &Path) -> Result<()> {
        let mut text = String::from("apparent_altitude_deg,true_altitude_deg,refraction_arcsec\n");
        for r in &self.rows {
            let (t, rr) = match (r.trace.true_altitude_rad(), r.trace.refraction_rad()) {
                (Some(t), Some(rr)) => (format!("{:.9}", t.to_degrees()), format!("{:.4}", rr * ARCSEC_PER_RAD)),
                _ => (String::new(), String::new()),
            };
            let _ = writeln!(text, "{},{t},{rr}", r.apparent_altitude_deg);
        }
        super::write_csv(path, &text)
    }
}

/// One line of the text table.
fn row_text(r: &Row) -> String {
    let arcsec = |x: Option<f64>| x.map_or_else(|| "—".to_string(), |v| format!("{:.1}", v * ARCSEC_PER_RAD));
    let head = format!("{:>12}", r.apparent_altitude_deg);
    match r.trace.outcome {
        Outcome::Escaped { true_altitude_rad } => {
            let rr = r.trace.apparent_altitude_rad - true_altitude_rad;
            format!(
                "{head}  {:>12.6}  {:>17.2}  {:>17.3}  {:>14}  {:>18}  {:>9}",
                true_altitude_rad.to_degrees(),
                rr * ARCSEC_PER_RAD,
                rr * ARCSEC_PER_RAD / 60.0,
                arcsec(r.bennett_rad),
                arcsec(r.saemundsson_rad),
                r.quadrature_evaluations.map_or_else(|| r.trace.ode_steps.to_string(), |n| format!("{n}q"))
            )
        }
        Outcome::Ground { distance_m } => {
            format!("{head}  the ray hits the ground {:.3} km away: no refraction", distance_m / 1e3)
        }
        Outcome::Trapped { max_height_m, ground_distance_m } => format!(
            "{head}  the ray is trapped (ducting): it turns down at {:.2} m and {}",
            max_height_m,
            ground_distance_m.map_or_else(
                || format!("is still in the atmosphere after {:.0} km", r.trace.path_length_m / 1e3),
                |d| format!("meets the ground {:.3} km away", d / 1e3)
            )
        ),
    }
}

/// Refraction at several wavelengths for each apparent altitude.
#[derive(Clone, Debug, PartialEq)]
pub struct Dispersion {
    /// Wavelengths traced, nm.
    pub wavelengths_nm: Vec<f64>,
    /// (apparent altitude, degrees; refraction at each wavelength, rad).
    pub rows: Vec<(f64, Vec<Option<f64>>)>,
}

/// Each apparent altitude at each wavelength, by the refractor's method.
pub fn dispersion(refractor: &Refractor, altitudes_deg: &[f64], wavelengths_nm: &[f64]) -> Result<Dispersion> {
    let refractors = wavelengths_nm.iter().map(|&l| refractor.at_wavelength(l)).collect::<Result<Vec<_>>>()?;
    let mut rows = Vec::with_capacity(altitudes_deg.len());
    for &a in altitudes_deg {
        let rs = refractors.iter().map(|r| r.refraction_rad(a.to_radians())).collect::<Result<Vec<_>>>()?;
        rows.push((a, rs));
    }
    Ok(Dispersion { wavelengths_nm: wavelengths_nm.to_vec(), rows })
}

impl Dispersion {
    /// The refraction at each wavelength (arcsec) and the first minus the last.
    pub fn to_text(&self) -> String {
        let (first, last) = (self.wavelengths_nm.first(), self.wavelengths_nm.last());
        let mut s = String::from("dispersion: refraction_arcsec at each wavelength\napparent_deg");
        for l in &self.wavelengths_nm {
            let _ = write!(s, "  {:>10}", format!("{l} nm"));
        }
        if let (Some(f), Some(l)) = (first, last) {
            let _ = write!(s, "  {:>16}", format!("{f}−{l} nm"));
        }
        s.push('\n');
        for (a, rs) in &self.rows {
            let _ = write!(s, "{a:>12}");
            for r in rs {
                let _ =
                    write!(s, "  {:>10}", r.map_or_else(|| "—".to_string(), |v| format!("{:.2}", v * ARCSEC_PER_RAD)));
            }
            let diff = match (rs.first().copied().flatten(), rs.last().copied().flatten()) {
                (Some(x), Some(y)) => format!("{:.2}", (x - y) * ARCSEC_PER_RAD),
                _ => "—".to_string(),
            };
            let _ = writeln!(s, "  {diff:>16}");
        }
        s
    }
}

/// The sun (0.53°) with its lower limb at apparent altitude 0, as text.
pub fn sun_text(refractor: &Refractor) -> Result<String> {
    Ok(match flattened_disc(refractor, 0.0, SUN_DIAMETER_RAD)? {
        Some(f) => flattening_text(&f),
        None => "sun with its lower limb on the horizon: a limb's ray does not escape (no figure)\n".to_string(),
    })
}

fn flattening_text(f: &Flattening) -> String {
    format!(
        "sun (0.53°) with its lower limb at apparent 0°: limbs at true {:.4}° and {:.4}°, seen at {:.4}° and {:.4}°; \
         vertical/horizontal diameter = {:.4}\n",
        f.lower_true_rad.to_degrees(),
        f.upper_true_rad.to_degrees(),
        f.lower_apparent_rad.to_degrees(),
        f.upper_apparent_rad.to_degrees(),
        f.ratio
    )
}
