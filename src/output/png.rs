//! 8-bit sRGB PNG preview.

use super::SpectralImage;
use std::path::Path;

/// How the preview maps linear sRGB to display values.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Exposure {
    /// Scale so that a high percentile of luminance maps to display white.
    Auto,
    /// Multiply by 2^ev.
    Ev(f64),
}

pub fn write_png_preview(
    path: &Path,
    image: &SpectralImage,
    exposure: Exposure,
) -> std::io::Result<()> {
    todo!("{}{}{exposure:?}", path.display(), image.width)
}
