//! The tone mapper's input: per-pixel absolute XYZ and scotopic luminance.
//!
//! Built from a rendered [`SpectralImage`] or a spectral EXR (both through
//! [`BandWeights`]: X, Y, Z from the CIE 1931 functions and the scotopic luminance from the
//! CIE 1951 V′(λ), computed from the bands themselves), or from tristimulus values alone (an
//! RGB EXR), when the scotopic luminance is estimated from XYZ
//! ([`scotopic_from_xyz`]).

use super::scotopic::scotopic_from_xyz;
use super::spectral_weights::BandWeights;
use crate::spectrum::SpectralImage;

/// Where the scotopic luminance came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ScotopicSource {
    /// Integrated with V′(λ) over the spectral bands.
    Spectral,
    /// Estimated from XYZ (no spectral data).
    EstimatedFromXyz,
}

/// Row-major pixels with absolute colorimetry.
#[derive(Clone, Debug)]
pub struct SceneImage {
    /// Width, pixels.
    pub width: usize,
    /// Height, pixels.
    pub height: usize,
    /// CIE 1931 XYZ, Y in cd m⁻² (non-finite inputs become 0).
    pub xyz: Vec<[f64; 3]>,
    /// Scotopic luminance, scotopic cd m⁻².
    pub scotopic: Vec<f64>,
    /// Whether `scotopic` came from the spectrum or was estimated from XYZ.
    pub scotopic_source: ScotopicSource,
}

impl SceneImage {
    /// From a rendered image's spectral bands.
    pub fn from_spectral(image: &SpectralImage) -> SceneImage {
        let weights = BandWeights::uniform(&image.bands);
        // The image's buffers have the right size by construction (the renderer makes them).
        SceneImage::from_bands(image.width, image.height, &weights, image.bands.count, &image.data)
            .unwrap_or_else(|e| unreachable!("rendered image: {e}"))
    }

    /// From row-major band values, `bands` per pixel.
    pub fn from_bands(
        width: usize,
        height: usize,
        weights: &BandWeights,
        bands: usize,
        data: &[f32],
    ) -> Result<SceneImage, String> {
        check_size(width, height, data.len(), bands)?;
        let (xyz, scotopic) =
            data.chunks_exact(bands).map(|p| (clean(weights.xyz(p)), weights.scotopic(p).max(0.0))).unzip();
        Ok(SceneImage { width, height, xyz, scotopic, scotopic_source: ScotopicSource::Spectral })
    }

    /// From XYZ alone; the scotopic luminance is estimated.
    pub fn from_xyz(width: usize, height: usize, xyz: Vec<[f64; 3]>) -> Result<SceneImage, String> {
        check_size(width, height, xyz.len(), 1)?;
        let xyz: Vec<[f64; 3]> = xyz.into_iter().map(clean).collect();
        let scotopic = xyz.iter().map(|&c| scotopic_from_xyz(c)).collect();
        Ok(SceneImage { width, height, xyz, scotopic, scotopic_source: ScotopicSource::EstimatedFromXyz })
    }

    /// Photopic luminance of pixel `i`, cd m⁻², never negative.
    pub fn luminance(&self, i: usize) -> f64 {
        self.xyz[i][1].max(0.0)
    }

    /// All photopic luminances.
    pub fn luminances(&self) -> Vec<f64> {
        (0..self.xyz.len()).map(|i| self.luminance(i)).collect()
    }
}

fn clean(xyz: [f64; 3]) -> [f64; 3] {
    xyz.map(|c| if c.is_finite() { c } else { 0.0 })
}

fn check_size(width: usize, height: usize, values: usize, per_pixel: usize) -> Result<(), String> {
    let pixels = width.checked_mul(height).filter(|&p| p > 0);
    match pixels.and_then(|p| p.checked_mul(per_pixel)) {
        Some(n) if n == values => Ok(()),
        _ => Err(format!("a {width}×{height} image with {per_pixel} values per pixel cannot hold {values} values")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectrum::Bands;
    use crate::spectrum::colour::BandsToColour;

    #[test]
    fn spectral_pixels_get_the_documented_colour_and_rod_luminance() {
        let bands = Bands::new(400.0, 700.0, 3).unwrap();
        let image = SpectralImage {
            width: 2,
            height: 1,
            bands,
            data: vec![0.1, 0.2, 0.3, 0.0, f32::NAN, 1.0],
            rgb: vec![0.0; 6],
        };
        let s = SceneImage::from_spectral(&image);
        let want = BandsToColour::new(&bands).xyz(&[0.1f32, 0.2, 0.3].map(f64::from));
        assert!((0..3).all(|k| (s.xyz[0][k] - want[k]).abs() < 1e-9 * want[1]), "{:?} vs {want:?}", s.xyz[0]);
        assert!(s.scotopic[0] > 0.0 && s.xyz[1][1].is_finite());
        assert_eq!(s.scotopic_source, ScotopicSource::Spectral);
        assert!(SceneImage::from_xyz(2, 2, vec![[1.0; 3]; 3]).is_err());
        let e = SceneImage::from_xyz(1, 1, vec![[0.9505, 1.0, 1.089]]).unwrap();
        assert!(e.scotopic[0] > 2.0 && e.scotopic[0] < 2.8);
    }
}
