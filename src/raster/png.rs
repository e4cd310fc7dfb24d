//! 8-bit sRGB PNG output of display-ready pixels.

use std::fs::File;
use std::io::{self, BufWriter};
use std::path::Path;

/// Writes `rgb` (row-major, 3 bytes per pixel, sRGB-encoded) as a PNG with an sRGB chunk
/// (perceptual intent; W3C PNG 2nd ed. §11.3.3.5). Not atomic: callers write to a staged path.
pub fn write_rgb8(path: &Path, width: usize, height: usize, rgb: &[u8]) -> io::Result<()> {
    let (Ok(w), Ok(h)) = (u32::try_from(width), u32::try_from(height)) else {
        return Err(io::Error::new(io::ErrorKind::InvalidInput, format!("{width}×{height} is too large for PNG")));
    };
    if width == 0 || height == 0 || Some(rgb.len()) != width.checked_mul(height).and_then(|p| p.checked_mul(3)) {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!(
                "a {width}×{height} PNG needs {} bytes, got {}",
                width.saturating_mul(height).saturating_mul(3),
                rgb.len()
            ),
        ));
    }
    let mut encoder = png::Encoder::new(BufWriter::new(File::create(path)?), w, h);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
    let mut writer = encoder.write_header()?;
    writer.write_image_data(rgb)?;
    writer.finish()?;
    Ok(())
}
