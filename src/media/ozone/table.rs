//! An ozone profile a scene gives: number density at listed altitudes, read log-linearly between
//! them like the built-in AFGL profile (n decays exponentially between two levels; linearly
//! between a level of zero and its neighbour, which a logarithm cannot reach), or linearly
//! ([`Interpolation::Linear`]), as codes that take their profiles as layers often do: a
//! benchmark computed that way is matched by reading its levels the same way.
//!
//! # File format
//! CSV with two columns `altitude_m,number_density_per_cm3`: `#` comment lines and blank lines
//! are skipped, the first data row may be a header; altitudes strictly increasing, densities
//! finite and not negative, at least two rows.

use crate::spectrum::table::parse_numeric_columns;

/// How a [`NumberDensityTable`] is read between its levels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Interpolation {
    /// ln n linear in altitude (linear next to a level of zero).
    Log,
    /// n linear in altitude.
    Linear,
}

/// Ozone number density against altitude (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct NumberDensityTable {
    altitude_m: Vec<f64>,
    per_m3: Vec<f64>,
    interpolation: Interpolation,
}

impl NumberDensityTable {
    /// From rows (altitude m, number density m⁻³).
    pub fn new(altitude_m: Vec<f64>, per_m3: Vec<f64>) -> Result<NumberDensityTable, String> {
        if altitude_m.len() < 2 {
            return Err(format!("{} row(s): need at least 2", altitude_m.len()));
        }
        if let Some(i) = altitude_m.iter().position(|h| !h.is_finite()) {
            return Err(format!("data row {}: altitude {} is not a finite number (m)", i + 1, altitude_m[i]));
        }
        if let Some(i) = altitude_m.windows(2).position(|w| w[1] <= w[0]) {
            return Err(format!(
                "data row {}: altitude {} m after {} m; altitudes must increase strictly",
                i + 2,
                altitude_m[i + 1],
                altitude_m[i]
            ));
        }
        if let Some(i) = per_m3.iter().position(|n| !(n.is_finite() && *n >= 0.0)) {
            return Err(format!("data row {}: number density {} must be a finite number ≥ 0", i + 1, per_m3[i] * 1e-6));
        }
        Ok(NumberDensityTable { altitude_m, per_m3, interpolation: Interpolation::Log })
    }

    /// The same levels read the `interpolation` way.
    pub fn with_interpolation(self, interpolation: Interpolation) -> NumberDensityTable {
        NumberDensityTable { interpolation, ..self }
    }

    /// Parses the CSV of the module docs (densities per cm³); errors carry the 1-based line.
    pub fn from_csv(text: &str) -> Result<NumberDensityTable, (usize, String)> {
        let mut cols = parse_numeric_columns(text, &["altitude_m", "number_density_per_cm3"])?.into_iter();
        let (h, n) = (cols.next().unwrap_or_default(), cols.next().unwrap_or_default());
        NumberDensityTable::new(h, n.iter().map(|n| n * 1e6).collect()).map_err(|e| (1, e))
    }

    /// [first, last] altitude, m.
    pub fn altitude_range(&self) -> (f64, f64) {
        (self.altitude_m[0], self.altitude_m[self.altitude_m.len() - 1])
    }

    /// n(h), m⁻³: log-linear between two positive levels (linear where either is zero), or
    /// linear; the end levels' values beyond the ends.
    pub fn at(&self, h_m: f64) -> f64 {
        let (h, n) = (&self.altitude_m, &self.per_m3);
        let last = h.len() - 1;
        if h_m <= h[0] {
            return n[0];
        }
        if h_m >= h[last] {
            return n[last];
        }
        let i = h.partition_point(|&x| x <= h_m) - 1;
        let f = (h_m - h[i]) / (h[i + 1] - h[i]);
        if self.interpolation == Interpolation::Log && n[i] > 0.0 && n[i + 1] > 0.0 {
            (n[i].ln() * (1.0 - f) + n[i + 1].ln() * f).exp()
        } else {
            n[i] * (1.0 - f) + n[i + 1] * f
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_are_hit_and_read_log_linearly_between_them() {
        let t = NumberDensityTable::from_csv("altitude_m,number_density_per_cm3\n0,1e12\n1000,4e12\n2000,0\n").unwrap();
        assert_eq!(t.at(0.0), 1e18);
        assert!((t.at(1000.0) / 4e18 - 1.0).abs() < 1e-15);
        assert!((t.at(500.0) / 2e18 - 1.0).abs() < 1e-12, "geometric mean: {}", t.at(500.0));
        assert!((t.at(1500.0) / 2e18 - 1.0).abs() < 1e-12, "linear to zero: {}", t.at(1500.0));
        assert_eq!(t.at(-10.0), 1e18);
        assert_eq!(t.at(5000.0), 0.0);
        assert_eq!(t.altitude_range(), (0.0, 2000.0));
        let t = t.with_interpolation(Interpolation::Linear);
        assert!((t.at(500.0) / 2.5e18 - 1.0).abs() < 1e-15, "arithmetic mean: {}", t.at(500.0));
    }

    #[test]
    fn bad_rows_are_refused_with_their_line() {
        let e = NumberDensityTable::from_csv("0,1e12\n0,2e12\n").unwrap_err();
        assert!(e.1.contains("row 2") && e.1.contains("increase strictly"), "{e:?}");
        let e = NumberDensityTable::from_csv("0,1e12\n1000,-1\n").unwrap_err();
        assert!(e.1.contains("row 2") && e.1.contains("≥ 0"), "{e:?}");
        let e = NumberDensityTable::from_csv("0,1e12\n").unwrap_err();
        assert!(e.1.contains("at least 2"), "{e:?}");
        let e = NumberDensityTable::from_csv("0,1e12\n1000,x\n").unwrap_err();
        assert_eq!(e.0, 2, "{e:?}");
    }
}
