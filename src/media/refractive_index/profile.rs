//! A tabulated profile n(h) in height, interpolated by a monotone cubic (PCHIP), so n and ∇n are
//! continuous and n never leaves the range of the table. Outside the table n is held at the end
//! values.
//!
//! # File format
//! CSV with two columns `height_m,n`: `#` comment lines and blank lines are skipped and the first
//! data row may be a header; heights strictly increasing.

use crate::atmosphere::Earth;
use crate::field::MonotoneCubic;
use crate::spectrum::table::parse_numeric_columns;
use glam::DVec3;

/// n(h) from a table of heights, monotone-cubic (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Profile {
    spline: MonotoneCubic,
    /// How height is measured (flat or spherical Earth).
    pub earth: Earth,
}

impl Profile {
    /// From knots (height_m, n): at least two, heights strictly increasing, n finite and > 0.
    pub fn new(height_m: Vec<f64>, n: Vec<f64>, earth: Earth) -> Result<Profile, String> {
        if let Some(i) = n.iter().position(|v| *v <= 0.0) {
            return Err(format!("index profile: n = {} at row {} must be positive", n[i], i + 1));
        }
        let spline = MonotoneCubic::new(height_m, n).map_err(|e| format!("index profile: {e}"))?;
        Ok(Profile { spline, earth })
    }

    /// Parses the CSV text described in the module notes; errors carry the 1-based line.
    pub fn from_csv(text: &str, earth: Earth) -> Result<Profile, (usize, String)> {
        let cols = parse_numeric_columns(text, &["height_m", "n"])?;
        let mut it = cols.into_iter();
        let (h, n) = (it.next().unwrap_or_default(), it.next().unwrap_or_default());
        Profile::new(h, n, earth).map_err(|e| (1, e))
    }

    /// Reads the CSV file described in the module notes; errors name the file and line.
    pub fn load(path: &std::path::Path, earth: Earth) -> crate::error::Result<Profile> {
        use crate::error::{Error, Location};
        let text = std::fs::read_to_string(path)
            .map_err(|e| Error::input(Some(Location::file(path)), format!("cannot read index profile: {e}")))?;
        Profile::from_csv(&text, earth).map_err(|(line, msg)| {
            Error::input(Some(Location { file: path.to_path_buf(), line: Some(line), column: None }), msg)
        })
    }

    /// n and ∇n = n′(h)·∇h.
    pub fn n_grad(&self, p: DVec3) -> (f64, DVec3) {
        let (h, gh) = self.earth.height_grad(p);
        let (n, dn) = self.spline.eval_deriv(h);
        (n, dn * gh)
    }

    /// [h_first, h_last]: outside, ∇n = 0.
    pub fn height_range(&self) -> (f64, f64) {
        self.spline.domain()
    }

    /// The smallest n of the table (the spline never leaves the table's range).
    pub fn min_n(&self) -> f64 {
        self.spline.value_range().0
    }
}
