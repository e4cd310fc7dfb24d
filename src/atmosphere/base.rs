//! The unedited atmosphere an [`super::Atmosphere`] starts from: temperature and pressure as
//! functions of geometric altitude.

use super::table_profile::TableProfile;
use super::usa76::{self, State};

/// The base atmosphere: T(z) and P(z) before any edit.
#[derive(Clone, Debug, PartialEq)]
pub enum BaseProfile {
    /// The U.S. Standard Atmosphere 1976 (0–86 km).
    Usa76,
    /// A tabulated T(z), P(z).
    Table(TableProfile),
}

impl BaseProfile {
    /// T, P and their height derivatives at geometric altitude `z_m`.
    pub fn state(&self, z_m: f64) -> State {
        match self {
            BaseProfile::Usa76 => usa76::at_geometric(z_m),
            BaseProfile::Table(t) => t.state(z_m),
        }
    }

    /// The highest altitude the profile is defined to, m.
    pub fn max_altitude_m(&self) -> f64 {
        match self {
            BaseProfile::Usa76 => usa76::TOP_GEOMETRIC_M,
            BaseProfile::Table(t) => t.altitude_range().1,
        }
    }

    /// Altitudes where dT/dz or dP/dz jumps (so ∇n is discontinuous), m: the USA76 layer bases
    /// and ends; a table's first and last rows (PCHIP is C¹ between them).
    pub fn kink_heights_m(&self) -> Vec<f64> {
        match self {
            BaseProfile::Usa76 => usa76::kink_heights_geometric_m().collect(),
            BaseProfile::Table(t) => {
                let (lo, hi) = t.altitude_range();
                vec![lo, hi]
            }
        }
    }

    /// Altitudes between which the profile is analytic, m: the kinks, and a table's every row
    /// (where the second derivatives of its cubics jump). A quadrature over height wants its
    /// pieces there; a ray integrator needs only the kinks.
    pub fn smooth_piece_ends_m(&self) -> Vec<f64> {
        match self {
            BaseProfile::Usa76 => self.kink_heights_m(),
            BaseProfile::Table(t) => t.knot_altitudes_m().to_vec(),
        }
    }

    /// A lower bound of the temperature below `top_m`, K.
    pub fn min_temperature_below(&self, top_m: f64) -> f64 {
        match self {
            BaseProfile::Usa76 => usa76::min_temperature_below(top_m),
            BaseProfile::Table(t) => t.min_temperature(),
        }
    }
}
