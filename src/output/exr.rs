//! Spectral OpenEXR in the layout of Fichet, Pacanowski & Wilkie 2021.

use super::SpectralImage;
use std::path::Path;

/// Writes `image` to `path` (not atomically: callers write to a staged temporary path).
pub fn write_spectral_exr(path: &Path, image: &SpectralImage) -> std::io::Result<()> {
    todo!("{}{}", path.display(), image.width)
}
