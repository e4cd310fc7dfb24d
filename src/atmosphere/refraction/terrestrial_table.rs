//! The tables of terrestrial refraction, as text and as CSV:
//! - `morgana refraction --ground-distances-km`: where rays leaving the observer at given
//!   apparent altitudes are at given distances along the ground ([`super::terrestrial`]),
//!   beside the straight line through the same start
//!   (`apparent_altitude_deg,ground_distance_km,height_m,elevation_deg,straight_height_m,lift_m,ground_at_km`);
//! - `morgana refraction --targets`: at what apparent elevations points at given distances and
//!   heights are seen, and how much the horizon hides there ([`super::sight`];
//!   `distance_km,height_m,hidden_height_m,straight_elevation_deg,image,apparent_elevation_deg,refraction_arcsec`).
//!
//! The straight line leaving radius r₀ at elevation e is r(φ) = r₀ cos e / cos(φ + e) at central
//! angle φ (its nearest point to the centre is at φ = −e); the *lift* is how much higher the
//! refracted ray is than that line at the same ground distance.

use super::ARCSEC_PER_RAD;
use super::sight::{Horizon, hidden_height, horizon, images, straight_elevation};
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
    /// The ray leaves the air upward and never gets this far round; at most this far, km.
    Away {
        /// The ground distance its straight line above the air tends to, km.
        max_km: f64,
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
    let half_way_km = std::f64::consts::PI * air.ground_radius_m / 1e3;
    if let Some(d) = distances_km.iter().find(|d| !(d.is_finite() && (0.0..=half_way_km).contains(*d))) {
        return Err(Error::input(
            None,
            format!(
                "--ground-distances-km: {d} is out of range; expected 0 … {half_way_km:.0} km (half-way round the Earth)"
            ),
        ));
    }
    let mut rows = Vec::with_capacity(altitudes_deg.len() * distances_km.len());
    for &a in altitudes_deg {
        for &d in distances_km {
            rows.push(row(air, observer_height_m, a, d)?);
        }
    }
    Ok(TerrestrialTable { title, observer_height_m, rows })
}

/// The observer's height must lie in the air.
fn check_height<F>(air: &RadialAir<F>, h0: f64) -> Result<()> {
    let top_m = air.top_m;
    if !(h0.is_finite() && (0.0..top_m).contains(&h0)) {
        return Err(Error::input(
            None,
            format!("--observer-height-m: {h0} is out of range; expected 0 ≤ h < {top_m} m (the top of the air)"),
        ));
    }
    Ok(())
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
        Reach::Away { max_angle_rad } => Place::Away { max_km: max_angle_rad * r_e / 1e3 },
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
                Place::Away { max_km } => writeln!(
                    s,
                    "{:>16}  {:>11}  leaves the air upward and never gets that far (at most {max_km:.3} km){:>12}",
                    r.apparent_altitude_deg, r.ground_distance_km, r.evaluations
                ),
            };
        }
        s
    }

    /// Writes the CSV atomically to `path`; a ray that met the ground first has empty height,
    /// elevation and lift, and its `ground_at_km`; one that leaves the air and never gets that
    /// far round has every column after the distance empty.
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
                Place::Away { .. } => writeln!(text, "{a},{d},,,,,"),
            };
        }
        super::write_csv(path, &text)
    }
}

/// One target of `--targets`.
#[derive(Clone, Debug, PartialEq)]
pub struct SightRow {
    /// Distance along the ground, km.
    pub distance_km: f64,
    /// Height above the ground, m.
    pub height_m: f64,
    /// How high the horizon hides things at that distance, m.
    pub hidden_height_m: f64,
    /// Elevation of the straight line to it, degrees.
    pub straight_elevation_deg: f64,
    /// The apparent elevations it is seen at, degrees, ascending (empty: hidden).
    pub images_deg: Vec<f64>,
}

/// The lines of sight from one observer.
#[derive(Clone, Debug, PartialEq)]
pub struct SightTable {
    /// What air, what wavelength.
    pub title: String,
    /// Observer's height above the ground, m.
    pub observer_height_m: f64,
    /// Ground radius, m.
    pub ground_radius_m: f64,
    /// The horizon (`None`: the observer is on the ground).
    pub horizon: Option<Horizon>,
    /// One row per target.
    pub rows: Vec<SightRow>,
}

/// The lines of sight from `observer_height_m` to each (distance km, height m) of `targets`.
pub fn sight_table<F: RadialIndex>(
    air: &RadialAir<F>,
    title: String,
    observer_height_m: f64,
    targets: &[(f64, f64)],
) -> Result<SightTable> {
    check_height(air, observer_height_m)?;
    let r_e = air.ground_radius_m;
    let fail = |e: String| Error::input(None, format!("--targets: {e}"));
    let half_way_km = std::f64::consts::PI * r_e / 1e3;
    if let Some((d, _)) = targets.iter().find(|(d, _)| *d > half_way_km) {
        return Err(fail(format!("{d} km is beyond half-way round the Earth ({half_way_km:.0} km)")));
    }
    let horizon = horizon(air, observer_height_m).map_err(fail)?;
    let mut rows = Vec::with_capacity(targets.len());
    for &(d, h) in targets {
        let phi = d * 1e3 / r_e;
        let at = |e: String| fail(format!("{d}:{h}: {e}"));
        rows.push(SightRow {
            distance_km: d,
            height_m: h,
            hidden_height_m: hidden_height(air, observer_height_m, phi).map_err(at)?,
            straight_elevation_deg: straight_elevation(r_e, observer_height_m, phi, h).to_degrees(),
            images_deg: images(air, observer_height_m, phi, h).map_err(at)?.iter().map(|e| e.to_degrees()).collect(),
        });
    }
    Ok(SightTable { title, observer_height_m, ground_radius_m: r_e, horizon, rows })
}

impl SightTable {
    /// The table as text: the horizon, then one line per target and image.
    pub fn to_text(&self) -> String {
        let mut s = format!(
            "lines of sight (Bouguer's invariant by quadrature): {}, observer at {} m\n",
            self.title, self.observer_height_m
        );
        let _ = match self.horizon {
            Some(h) => writeln!(
                s,
                "horizon {:.6} km away, dip {:.6}° (without refraction {:.6} km, {:.6}°)",
                h.angle_rad * self.ground_radius_m / 1e3,
                -h.elevation_rad.to_degrees(),
                self.geometric_horizon_rad() * self.ground_radius_m / 1e3,
                self.geometric_horizon_rad().to_degrees()
            ),
            None => writeln!(s, "the observer is on the ground: the horizon is at the observer's feet"),
        };
        s.push_str(
            "distance_km      height_m  hidden_height_m  straight_elev_deg  apparent_elev_deg  refraction_arcsec\n",
        );
        for r in &self.rows {
            if r.images_deg.is_empty() {
                let _ = writeln!(
                    s,
                    "{:>11}  {:>12}  {:>15.6}  {:>17.6}  hidden below the horizon",
                    r.distance_km, r.height_m, r.hidden_height_m, r.straight_elevation_deg
                );
            }
            for e in &r.images_deg {
                let _ = writeln!(
                    s,
                    "{:>11}  {:>12}  {:>15.6}  {:>17.6}  {e:>17.6}  {:>17.3}",
                    r.distance_km,
                    r.height_m,
                    r.hidden_height_m,
                    r.straight_elevation_deg,
                    (e - r.straight_elevation_deg) * 3600.0
                );
            }
        }
        s
    }

    /// arccos(R/r₀): the horizon's central angle, and the dip, without refraction.
    fn geometric_horizon_rad(&self) -> f64 {
        let h0 = self.observer_height_m;
        2.0 * (0.5 * h0 / (self.ground_radius_m + h0)).sqrt().asin()
    }

    /// Writes the CSV atomically to `path`: one row per image, numbered from the lowest (a
    /// hidden target: one row with the image columns empty).
    pub fn write_csv(&self, path: &Path) -> Result<()> {
        let mut text = String::from(
            "distance_km,height_m,hidden_height_m,straight_elevation_deg,image,apparent_elevation_deg,refraction_arcsec\n",
        );
        for r in &self.rows {
            let lead =
                format!("{},{},{:.9},{:.12}", r.distance_km, r.height_m, r.hidden_height_m, r.straight_elevation_deg);
            if r.images_deg.is_empty() {
                let _ = writeln!(text, "{lead},,,");
            }
            for (i, e) in r.images_deg.iter().enumerate() {
                let refraction = (e - r.straight_elevation_deg).to_radians() * ARCSEC_PER_RAD;
                let _ = writeln!(text, "{lead},{},{e:.12},{refraction:.6}", i + 1);
            }
        }
        super::write_csv(path, &text)
    }
}
