//! Sensors: quantities measured at chosen points of a scene, written beside the image.
//!
//! A sensor is a closed set of types (one file each, dispatched by [`Sensor`]) that produces a
//! [`Reading`]: a grid of points and one or more named columns of values, written as CSV and as
//! a false-colour PNG of the first column with a colour bar. Today: [`IlluminancePlane`]
//! (illuminance in lux on a grid, as lighting engineers' calculation surfaces). Irradiance or
//! radiance sensors (the ocean issue) are new variants producing the same kind of reading.
//!
//! Sensors run after the photon pass, reading the same photon maps as the eye pass.

mod false_colour;
mod illuminance_plane;
mod ocean_profile;

pub use false_colour::{false_colour_png, viridis};
pub use illuminance_plane::IlluminancePlane;
pub use ocean_profile::{OceanProfile, ProfileReading, ProfileRow};

use crate::render::eye::EyeTracer;
use crate::render::maps::Maps;
use crate::scene::Scene;
use glam::DVec3;
use std::io::{self, Write};
use std::path::Path;

#[derive(Clone, Debug)]
pub enum Sensor {
    IlluminancePlane(IlluminancePlane),
    /// Ocean irradiances and radiance at depths (written as a profile, see [`ProfileReading`]).
    OceanProfile(OceanProfile),
}

/// A sensor as the scene names it.
#[derive(Clone, Debug)]
pub struct NamedSensor {
    pub name: String,
    pub sensor: Sensor,
}

/// What a sensor measured: values at the points of an nx × ny grid (row-major, i fastest).
#[derive(Clone, Debug, PartialEq)]
pub struct Reading {
    pub name: String,
    /// E.g. "illuminance".
    pub quantity: &'static str,
    /// E.g. "lx".
    pub unit: &'static str,
    pub nx: usize,
    pub ny: usize,
    pub points: Vec<DVec3>,
    /// Named columns of values, one per point; the first is the one the PNG shows.
    pub columns: Vec<(String, Vec<f64>)>,
}

/// Mean, minimum, maximum and uniformity U₀ = min/mean of a column.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stats {
    pub mean: f64,
    pub min: f64,
    pub max: f64,
    pub uniformity: f64,
}

impl Reading {
    /// Statistics of the first column.
    pub fn stats(&self) -> Stats {
        let v = &self.columns[0].1;
        let mean = v.iter().sum::<f64>() / v.len().max(1) as f64;
        let min = v.iter().copied().fold(f64::INFINITY, f64::min);
        let max = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        Stats { mean, min, max, uniformity: if mean > 0.0 { min / mean } else { 0.0 } }
    }

    /// One row per point: i, j, x, y, z (m), then each column.
    pub fn write_csv(&self, path: &Path) -> io::Result<()> {
        let mut f = io::BufWriter::new(std::fs::File::create(path)?);
        write!(f, "i,j,x_m,y_m,z_m")?;
        for (name, _) in &self.columns {
            write!(f, ",{name}")?;
        }
        writeln!(f)?;
        for (k, p) in self.points.iter().enumerate() {
            write!(f, "{},{},{},{},{}", k % self.nx, k / self.nx, p.x, p.y, p.z)?;
            for (_, v) in &self.columns {
                write!(f, ",{}", v[k])?;
            }
            writeln!(f)?;
        }
        f.flush()
    }

    /// The false-colour map of the first column with a colour bar and its statistics.
    pub fn write_png(&self, path: &Path) -> io::Result<()> {
        false_colour_png(self, path)
    }
}

/// Evaluates every sensor of the scene against the photon maps.
pub fn evaluate_all(scene: &Scene, maps: &Maps) -> Vec<Reading> {
    let tracer = EyeTracer::new(scene, maps);
    scene
        .sensors
        .iter()
        .enumerate()
        .filter_map(|(i, s)| match &s.sensor {
            Sensor::IlluminancePlane(p) => Some(p.evaluate(scene, &tracer, &s.name, i as u64)),
            Sensor::OceanProfile(_) => None,
        })
        .collect()
}

/// Evaluates every ocean profile sensor of the scene against the volume map.
pub fn evaluate_profiles(scene: &Scene, maps: &Maps) -> Vec<ProfileReading> {
    scene
        .sensors
        .iter()
        .enumerate()
        .filter_map(|(i, s)| match &s.sensor {
            Sensor::OceanProfile(p) => Some(p.evaluate(scene, maps, &s.name, i as u64)),
            Sensor::IlluminancePlane(_) => None,
        })
        .collect()
}

/// A file-name-safe version of a sensor name.
pub fn file_stem(name: &str) -> String {
    name.chars().map(|c| if c.is_ascii_alphanumeric() || c == '-' || c == '_' { c } else { '_' }).collect()
}
