//! Spectral → XYZ → linear sRGB.

use super::Bands;

/// Maximum luminous efficacy for photopic vision, lm/W.
pub const K_M: f64 = 683.002;

/// Converts per-band spectral radiance (W m⁻² sr⁻¹ nm⁻¹) to absolute XYZ (Y in cd m⁻²) and
/// linear sRGB.
#[derive(Clone, Debug)]
pub struct BandsToColour {}

impl BandsToColour {
    pub fn new(bands: &Bands) -> BandsToColour {
        todo!("{bands:?}")
    }
    pub fn xyz(&self, values: &[f64]) -> [f64; 3] {
        todo!("{values:?}")
    }
    pub fn linear_srgb(&self, values: &[f64]) -> [f64; 3] {
        todo!("{values:?}")
    }
}

/// XYZ to linear sRGB (IEC 61966-2-1, D65 white).
pub fn xyz_to_linear_srgb(xyz: [f64; 3]) -> [f64; 3] {
    todo!("{xyz:?}")
}

/// The sRGB transfer function (linear → encoded), IEC 61966-2-1.
pub fn srgb_encode(linear: f64) -> f64 {
    todo!("{linear}")
}
