//! Sensors: quantities measured at chosen points of a scene, written beside the image.
//!
//! A sensor is a closed set of types (one file each, dispatched by [`Sensor`]) that produces a
//! [`Reading`]: a grid of points and one or more named columns of values, written as CSV and as
//! a false-colour PNG of the first column with a colour bar. Today: [`IlluminancePlane`]
//! (illuminance in lux on a grid, as lighting engineers' calculation surfaces). Irradiance or
//! radiance sensors (the ocean issue) are new variants producing the same kind of reading.
//!
//! Sensors run after the photon pass, reading the same photon maps as the eye pass; the renderer
//! evaluates them (`render::sensors`).

mod illuminance_plane;
pub mod ocean_profile;
pub mod sky_radiance;

pub use illuminance_plane::IlluminancePlane;
pub use ocean_profile::{OceanProfile, ProfileError, ProfileReading, ProfileRow};
pub use sky_radiance::SkyRadiance;

use glam::DVec3;
use std::io::{self, Write};
use std::path::Path;

/// A sensor, one variant per kind.
#[derive(Clone, Debug)]
pub enum Sensor {
    /// Illuminance in lux on a grid of points on a plane.
    IlluminancePlane(IlluminancePlane),
    /// Ocean irradiances and radiance at depths (written as a profile, see [`ProfileReading`]).
    OceanProfile(OceanProfile),
    /// Radiance per band from listed directions at a point (one reading point per direction).
    SkyRadiance(SkyRadiance),
}

/// A sensor as the scene names it.
#[derive(Clone, Debug)]
pub struct NamedSensor {
    /// The sensor's name; outputs are `NAME_<sensor>.*`.
    pub name: String,
    /// What it measures and where.
    pub sensor: Sensor,
}

/// What a sensor measured: values at the points of an nx × ny grid (row-major, i fastest).
#[derive(Clone, Debug, PartialEq)]
pub struct Reading {
    /// The sensor's name.
    pub name: String,
    /// E.g. "illuminance".
    pub quantity: String,
    /// E.g. "lx".
    pub unit: String,
    /// Points along the grid's first edge.
    pub nx: usize,
    /// Points along the grid's second edge.
    pub ny: usize,
    /// The measuring points, m, row-major.
    pub points: Vec<DVec3>,
    /// Named columns of values, one per point; the first is the one the PNG shows.
    pub columns: Vec<(String, Vec<f64>)>,
}

pub use crate::raster::false_colour::Stats;

impl Reading {
    /// Statistics of the first column.
    pub fn stats(&self) -> Stats {
        Stats::of(&self.columns[0].1)
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
        use crate::raster::false_colour::{ColourMap, Grid, Look, Rows, Scale, write_png};
        let values = &self.columns[0].1;
        let stats = self.stats();
        let grid = Grid { nx: self.nx, ny: self.ny, values, rows: Rows::Upward };
        let look = Look {
            scale: Scale::linear_to(stats.max),
            map: ColourMap::Viridis,
            unit: &self.unit,
            heading: Some((format!("{} {}", self.name, self.quantity), stats.line(&self.unit))),
            cell: (560 / self.nx.max(1)).min(440 / self.ny.max(1)).max(1),
            background: crate::raster::WHITE,
            text: crate::raster::BLACK,
            text_scale: 1,
        };
        write_png(&grid, &look, path)
    }
}

/// A file-name-safe version of a sensor name.
pub fn file_stem(name: &str) -> String {
    name.chars().map(|c| if c.is_ascii_alphanumeric() || c == '-' || c == '_' { c } else { '_' }).collect()
}
