//! Spatial variation of a medium: a dimensionless density d(x) ≥ 0 that multiplies the
//! medium's σ_a(λ) and σ_s(λ). One file per kind, dispatched by a closed enum.
//!
//! Free-flight sampling and transmittance need majorants: each kind splits a segment into
//! intervals, each with an upper bound of d on it ("a majorant per region"), see
//! [`Density::majorant_intervals`].

mod air_profile;
mod column_table;
mod exponential;
mod fbm;
mod grid;
mod height_moments;
mod spherical_exponential;

pub use air_profile::{AirProfile, MAX_TABLES};
pub use column_table::{COLUMN_TOLERANCE, ColumnTable};
pub use exponential::ExponentialHeight;
pub use fbm::Fbm;
pub use grid::{GRID_MAGIC, Grid3D};
pub use height_moments::{Moments, ROUNDING};
pub use spherical_exponential::SphericalExponential;

use crate::atomic::Staged;
use crate::error::{Error, Result};
use glam::DVec3;

/// Samples `f` on an `n`-point lattice over [min, max] and writes it as an `.mgrid` file,
/// atomically. Bad sizes or values are input errors.
pub fn write_grid_atomically(
    path: &std::path::Path,
    n: [usize; 3],
    min: DVec3,
    max: DVec3,
    f: impl Fn(DVec3) -> f64,
) -> Result<()> {
    if !(2..=1024).contains(&n[0]) {
        return Err(Error::input(None, format!("--res {}: the grid needs 2 to 1024 points per axis", n[0])));
    }
    let grid = Grid3D::from_fn(n, min, max, f).map_err(|e| Error::input(None, e))?;
    let io = |e: std::io::Error| Error::internal(format!("cannot write {}: {e}", path.display()));
    let staged = Staged::new(path).map_err(io)?;
    grid.write(&staged.temp).map_err(io)?;
    staged.commit().map_err(io)
}

/// The density d(x) of a medium, dimensionless, ≥ 0; one variant per kind.
#[derive(Clone, Debug)]
pub enum Density {
    /// d = 1 everywhere: a homogeneous medium.
    Uniform,
    /// Exponential in height along a fixed `up` direction (flat Earth).
    ExponentialHeight(ExponentialHeight),
    /// Exponential in height above a spherical Earth.
    SphericalExponential(SphericalExponential),
    /// Trilinear lattice read from an `.mgrid` file.
    Grid(Grid3D),
    /// The molecular number density of an atmosphere, tabulated in height.
    AirProfile(AirProfile),
    /// Procedural fBm turbulence.
    Fbm(Box<Fbm>),
}

impl Density {
    /// d at `p`.
    pub fn at(&self, p: DVec3) -> f64 {
        match self {
            Density::Uniform => 1.0,
            Density::ExponentialHeight(e) => e.at(p),
            Density::SphericalExponential(e) => e.at(p),
            Density::Grid(g) => g.at(p),
            Density::AirProfile(a) => a.at(p),
            Density::Fbm(f) => f.at(p),
        }
    }

    /// ∫₀ᵗ d(o + s·dir) ds in closed form, where one exists (uniform, exponential), or by a
    /// quadrature accurate to 10⁻¹² (exponential above a sphere) or to the table's interpolation
    /// (an atmosphere's air, 10⁻⁷).
    pub fn integral_exact(&self, o: DVec3, dir: DVec3, t: f64) -> Option<f64> {
        match self {
            Density::Uniform => Some(t),
            Density::ExponentialHeight(e) => Some(e.integral(o, dir, t)),
            Density::SphericalExponential(e) => Some(e.integral(o, dir, t)),
            Density::AirProfile(a) => Some(a.integral(o, dir, t)),
            Density::Grid(_) | Density::Fbm(_) => None,
        }
    }

    /// [`Density::integral_exact`], but an atmosphere's air reads the column of a ray that
    /// leaves through its top from its table ([`ColumnTable`], to [`COLUMN_TOLERANCE`]): what a
    /// transmittance toward the sun needs.
    pub fn integral_tabulated(&self, o: DVec3, dir: DVec3, t: f64) -> Option<f64> {
        match self {
            Density::AirProfile(a) => Some(a.integral_to_top(o, dir, t)),
            _ => self.integral_exact(o, dir, t),
        }
    }

    /// Calls `visit(t0, t1, bound)` for consecutive intervals covering [0, t_max] of the ray
    /// `o + t·dir`, with `bound` ≥ d everywhere on the interval. `visit` returns false to stop.
    pub fn majorant_intervals(&self, o: DVec3, dir: DVec3, t_max: f64, visit: &mut dyn FnMut(f64, f64, f64) -> bool) {
        match self {
            Density::Uniform => {
                visit(0.0, t_max, 1.0);
            }
            Density::ExponentialHeight(e) => e.majorant_intervals(o, dir, t_max, visit),
            Density::SphericalExponential(e) => e.majorant_intervals(o, dir, t_max, visit),
            Density::Grid(g) => g.majorant_intervals(o, dir, t_max, visit),
            Density::AirProfile(a) => a.majorant_intervals(o, dir, t_max, visit),
            Density::Fbm(f) => {
                visit(0.0, t_max, f.bound());
            }
        }
    }

    /// The part [a, b] of [0, t_max] of the ray `o + t·dir` outside which d = 0 exactly (an
    /// atmosphere above its top), or `None` where d = 0 all along; [0, t_max] for densities that
    /// fill space.
    pub fn support(&self, o: DVec3, dir: DVec3, t_max: f64) -> Option<(f64, f64)> {
        match self {
            Density::AirProfile(a) => a.below_top(o, dir, t_max),
            _ => Some((0.0, t_max)),
        }
    }

    /// True for [`Density::Uniform`].
    pub fn is_uniform(&self) -> bool {
        matches!(self, Density::Uniform)
    }

    /// True when d depends on the distance from `centre` alone (within 1 mm of it): uniform, or
    /// exponential or an atmosphere's air above a spherical Earth centred there.
    pub fn is_radial_about(&self, centre: DVec3) -> bool {
        let near = |c: DVec3| (c - centre).length() <= 1e-3;
        match self {
            Density::Uniform => true,
            Density::SphericalExponential(e) => near(e.centre),
            Density::AirProfile(a) => match a.earth() {
                crate::atmosphere::Earth::Spherical(s) => near(s.centre),
                crate::atmosphere::Earth::Flat { .. } => false,
            },
            Density::ExponentialHeight(_) | Density::Grid(_) | Density::Fbm(_) => false,
        }
    }
}
