//! The spectral image: what a render produces, per pixel and band.

use super::Bands;

/// A rendered image: per-pixel spectral radiance per band (W m⁻² sr⁻¹ nm⁻¹) and its linear-sRGB
/// rendering (Y in cd m⁻²).
#[derive(Clone, Debug)]
pub struct SpectralImage {
    /// Width, pixels.
    pub width: usize,
    /// Height, pixels.
    pub height: usize,
    /// The wavelength bands of the values.
    pub bands: Bands,
    /// Row-major pixels, `bands.count` values each: `data[(y * width + x) * bands.count + b]`.
    pub data: Vec<f32>,
    /// Row-major pixels, three linear-sRGB values each.
    pub rgb: Vec<f32>,
}
