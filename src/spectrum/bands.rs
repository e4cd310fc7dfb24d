//! The scene's output wavelength bands: `count` equal bands over [min_nm, max_nm].

use serde::Serialize;

/// The most bands a scene may ask for; per-band arrays on the stack are this long.
pub const MAX_BANDS: usize = 64;

/// Per-band values, `bands.count` of them used.
pub type BandValues = [f64; MAX_BANDS];

/// `count` equal-width bands covering [min_nm, max_nm].
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Bands {
    /// Short end of the range, nm.
    pub min_nm: f64,
    /// Long end of the range, nm.
    pub max_nm: f64,
    /// Number of bands (1 to [`MAX_BANDS`]).
    pub count: usize,
}

impl Bands {
    /// Validates the range (0 < min < max) and count (1..=MAX_BANDS).
    pub fn new(min_nm: f64, max_nm: f64, count: usize) -> Result<Bands, String> {
        if !(min_nm.is_finite() && max_nm.is_finite() && min_nm > 0.0 && max_nm > min_nm) {
            return Err(format!("wavelength range [{min_nm}, {max_nm}] nm is not valid: need 0 < min_nm < max_nm"));
        }
        if count == 0 || count > MAX_BANDS {
            return Err(format!("bands = {count} is out of range: allowed 1 to {MAX_BANDS}"));
        }
        Ok(Bands { min_nm, max_nm, count })
    }

    /// Width of every band in nm.
    pub fn width_nm(&self) -> f64 {
        (self.max_nm - self.min_nm) / self.count as f64
    }

    /// Lower and upper edge of band `i`.
    pub fn edges_nm(&self, i: usize) -> (f64, f64) {
        let w = self.width_nm();
        (self.min_nm + i as f64 * w, self.min_nm + (i + 1) as f64 * w)
    }

    /// Centre of band `i`.
    pub fn centre_nm(&self, i: usize) -> f64 {
        self.min_nm + (i as f64 + 0.5) * self.width_nm()
    }

    /// The band holding `wavelength_nm` (the upper edge belongs to the last band), if any.
    pub fn index_of(&self, wavelength_nm: f64) -> Option<usize> {
        if !(self.min_nm..=self.max_nm).contains(&wavelength_nm) {
            return None;
        }
        let i = ((wavelength_nm - self.min_nm) / self.width_nm()) as usize;
        Some(i.min(self.count - 1))
    }
}
