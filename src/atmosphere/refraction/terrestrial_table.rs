//! The table of `morgana refraction --ground-distances-km`: where rays leaving the observer at
//! given apparent altitudes are at given distances along the ground ([`super::terrestrial`]),
//! beside the straight line through the same start, as text and as CSV
//! (`apparent_altitude_deg,ground_distance_km,height_m,elevation_deg,straight_height_m,lift_m`).
//!
//! The straight line leaving radius r₀ at elevation e is r(φ) = r₀ cos e / cos(φ + e) at central
//! angle φ (its nearest point to the centre is at φ = −e); the *lift* is how much higher the
//! refracted ray is than that line at the same ground distance.

use super::terrestrial::{RadialAir, RadialIndex, Reach, follow};
use crate::error::{Error, Result};
use std::fmt::Write as _;
use std::path::Path;

/// The angle integrals' tolerance, rad (6 μm along the ground at the Earth's radius).
pub const TERRESTRIAL_TOL_RAD: f64 = 1e-12;

/// Where one ray is at one ground distance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Place {
    /// In the air (or above it).
    Aloft {
        /// Height above the ground, m.
        height_m: f64,
        /// Elevation above the local horizontal, degrees (negative: descending).
        elevation_deg: f64,
        /// Height of the straight line from the same start, m (`None`: it never gets there).
        straight_height_m: Option<f64>,
    },
    /// The ray met the ground first, this far from the observer's foot, km.
    Ground {
        /// Distance along the ground to where it met it, km.
        at_km: f64,
    },
}

/// One ray at one ground distance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TerrestrialRow {
    /// Apparent altitude at the observer (elevation of the ray there), degrees.
    pub apparent_altitude_deg: f64,
    /// Distance along the ground from the observer's foot, km.
    pub ground_distance_km: f64,
    /// Where the ray is.
    pub place: Place,
    /// Evaluations of the index.
    pub evaluations: u64,
}

/// The table for one observer in one air.
#[derive(Clone, Debug, PartialEq)]
pub struct TerrestrialTable {
    /// What air, what wavelength (the header's first line).
    pub title: String,
    /// Observer's height above the ground, m.
    pub observer_height_m: f64,
    /// One row per apparent altitude and distance, altitudes outermost.
    pub rows: Vec<TerrestrialRow>,
}

/// Every ray of `altitudes_deg` (each in (−90°, 90°)) from `observer_height_m` above the ground of
/// `air`, at every distance of `distances_km` (each ≥ 0): an error naming the option for a value
/// out of range, or the ray's own (a duct on its path, a straight ray above the air that never
/// gets that far).
pub fn terrestrial_table<F: RadialIndex>(
    air: &RadialAir<F>,
    title: String,
    observer_height_m: f64,
    altitudes_deg: &[f64],
    distances_km: &[f64],
) -> Result<TerrestrialTable> {
    let top_m = air.top_m;
    if !(observer_height_m.is_finite() && (0.0..top_m).contains(&observer_height_m)) {
        return Err(Error::input(
            None,
            format!(
                "--observer-height-m: {observer_height_m} is out of range; expected 0 ≤ h < {top_m} m (the top of the air)"
            ),
        ));
    }
    if let Some(a) = altitudes_deg.iter().find(|a| !(a.is_finite() && a.abs() < 90.0)) {
        return Err(Error::input(
            None,
            format!("--apparent-altitudes-deg: {a} is out of range; expected −90 < a < 90"),
        ));
    }
    if let Some(d) = distances_km.iter().find(|d| !(d.is_finite() && **d >= 0.0)) {
        return Err(Error::input(None, format!("--ground-distances-km: {d} is out of range; expected a distance ≥ 0")));
    }
    let mut rows = Vec::with_capacity(altitudes_deg.len() * distances_km.len());
    for &a in altitudes_deg {
        for &d in distances_km {
            rows.push(row(air, observer_height_m, a, d)?);
        }
    }
    Ok(TerrestrialTable { title, observer_height_m, rows })
}

/// One ray at one distance.
fn row<F: RadialIndex>(air: &RadialAir<F>, h0: f64, altitude_deg: f64, distance_km: f64) -> Result<TerrestrialRow> {
    let (r_e, e0) = (air.ground_radius_m, altitude_deg.to_radians());
    let phi = distance_km * 1e3 / r_e;
    let path = follow(air, h0, e0, phi, TERRESTRIAL_TOL_RAD)
        .map_err(|e| Error::input(None, format!("the ray at {altitude_deg}° to {distance_km} km: {e}")))?;
    let place = match path.reach {
        Reach::Aloft { height_m, elevation_rad } => {
            let straight = (phi + e0 < std::f64::consts::FRAC_PI_2).then(|| straight_height(h0, r_e, e0, phi));
            Place::Aloft { height_m, elevation_deg: elevation_rad.to_degrees(), straight_height_m: straight }
        }
        Reach::Ground { angle_rad } => Place::Ground { at_km: angle_rad * r_e / 1e3 },
    };
    Ok(TerrestrialRow {
        apparent_altitude_deg: altitude_deg,
        ground_distance_km: distance_km,
        place,
        evaluations: path.evaluations,
    })
}

/// Height of the straight line from height `h0` (ground radius `r_e`) at elevation `e0` at
/// central angle `phi` (φ + e₀ < π/2): r₀ cos e₀ / cos(φ + e₀) − R, written as
/// (h₀ cos e₀ + 2R sin(φ/2 + e₀) sin(φ/2)) / cos(φ + e₀) so that no Earth-sized terms cancel.
fn straight_height(h0: f64, r_e: f64, e0: f64, phi: f64) -> f64 {
    (h0 * e0.cos() + 2.0 * r_e * (0.5 * phi + e0).sin() * (0.5 * phi).sin()) / (phi + e0).cos()
}

impl TerrestrialTable {
    /// The table as text: the header, one line per ray and distance.
    pub fn to_text(&self) -> String {
        let mut s = format!(
            "terrestrial refraction (Bouguer's invariant by quadrature): {}, observer at {} m\n\
             apparent_alt_deg  distance_km        height_m  elevation_deg  straight_height_m        lift_m  evaluations\n",
            self.title, self.observer_height_m
        );
        for r in &self.rows {
            let _ = match r.place {
                Place::Aloft { height_m, elevation_deg, straight_height_m } => writeln!(
                    s,
                    "{:>16}  {:>11}  {height_m:>14.6}  {elevation_deg:>13.6}  {:>17}  {:>12}  {:>11}",
                    r.apparent_altitude_deg,
                    r.ground_distance_km,
                    straight_height_m.map_or("never".into(), |v| format!("{v:.6}")),
                    straight_height_m.map_or("—".into(), |v| format!("{:.6}", height_m - v)),
                    r.evaluations
                ),
                Place::Ground { at_km } => writeln!(
                    s,
                    "{:>16}  {:>11}  meets the ground {at_km:.6} km from the observer{:>34}",
                    r.apparent_altitude_deg, r.ground_distance_km, r.evaluations
                ),
            };
        }
        s
    }

    /// Writes the CSV atomically to `path`; a ray that met the ground first has empty height,
    /// elevation and lift, and its `ground_at_km`.
    pub fn write_csv(&self, path: &Path) -> Result<()> {
        let mut text = String::from(
            "apparent_altitude_deg,ground_distance_km,height_m,elevation_deg,straight_height_m,lift_m,ground_at_km\n",
        );
        for r in &self.rows {
            let (a, d) = (r.apparent_altitude_deg, r.ground_distance_km);
            let _ = match r.place {
                Place::Aloft { height_m, elevation_deg, straight_height_m } => writeln!(
                    text,
                    "{a},{d},{height_m:.9},{elevation_deg:.12},{},{},",
                    straight_height_m.map_or(String::new(), |v| format!("{v:.9}")),
                    straight_height_m.map_or(String::new(), |v| format!("{:.9}", height_m - v)),
                ),
                Place::Ground { at_km } => writeln!(text, "{a},{d},,,,,{at_km:.9}"),
            };
        }
        super::write_csv(path, &text)
    }
}
