//! 8-bit sRGB PNG preview.
//!
//! Each pixel's linear sRGB c (absolute: Y in cd m⁻²) is scaled by an exposure factor s, clipped
//! to [0, 1], passed through the sRGB transfer function and quantised to 8 bits:
//! v = round(255 · encode(clamp(s · c, 0, 1))). The factor is
//! - [`Exposure::Ev`]: s = 2^ev;
//! - [`Exposure::Auto`]: s = 1 / Y₉₉, where Y₉₉ is the 99th percentile (nearest rank over all
//!   pixels) of the luminance Y = 0.2126 R + 0.7152 G + 0.0722 B, so 1 % of the pixels clip.
//!   When Y₉₉ is not positive (a black image), s = 1.
//!
//! Non-finite values are written as 0. The file carries an sRGB chunk (perceptual intent).
//!
//! # References
//! - IEC 61966-2-1:1999, *sRGB* (transfer function and luminance row).
//! - W3C (2003), *PNG Specification*, 2nd ed., §11.3.3.5 (sRGB chunk).

use crate::spectrum::SpectralImage;
use crate::spectrum::colour::{linear_srgb_luminance, srgb_encode};
use std::io;
use std::path::Path;

/// The luminance percentile that [`Exposure::Auto`] maps to display white.
pub const AUTO_PERCENTILE: f64 = 0.99;

/// How the preview maps linear sRGB to display values.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Exposure {
    /// Scale so that a high percentile of luminance maps to display white.
    Auto,
    /// Multiply by 2^ev.
    Ev(f64),
}

/// Writes the 8-bit sRGB preview of `image.rgb` to `path` (not atomically: callers write to a
/// staged temporary path).
pub fn write_png_preview(path: &Path, image: &SpectralImage, exposure: Exposure) -> io::Result<()> {
    let pixels = image.width.saturating_mul(image.height);
    if image.width == 0 || image.height == 0 || Some(image.rgb.len()) != pixels.checked_mul(3) {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!(
                "a {}×{} preview needs {} RGB values and a non-empty size, got {}",
                image.width,
                image.height,
                pixels.saturating_mul(3),
                image.rgb.len()
            ),
        ));
    }
    let bytes = encode_pixels(&image.rgb, exposure_scale(&image.rgb, exposure));
    crate::raster::png::write_rgb8(path, image.width, image.height, &bytes)
}

/// The factor s that multiplies linear sRGB before encoding.
pub fn exposure_scale(rgb: &[f32], exposure: Exposure) -> f64 {
    match exposure {
        Exposure::Ev(ev) => {
            let s = ev.exp2();
            if s.is_finite() { s } else { 1.0 }
        }
        Exposure::Auto => {
            let mut y: Vec<f64> = rgb
                .chunks_exact(3)
                .map(|c| linear_srgb_luminance([c[0], c[1], c[2]].map(f64::from)))
                .map(|y| if y.is_finite() { y } else { 0.0 })
                .collect();
            if y.is_empty() {
                return 1.0;
            }
            // Nearest rank: the smallest value with at least 99 % of the pixels at or below it.
            let rank = ((AUTO_PERCENTILE * y.len() as f64).ceil() as usize).clamp(1, y.len());
            let (_, p, _) = y.select_nth_unstable_by(rank - 1, f64::total_cmp);
            let p = *p;
            if p > 0.0 { 1.0 / p } else { 1.0 }
        }
    }
}

/// 8-bit sRGB bytes of linear values times `scale`.
fn encode_pixels(rgb: &[f32], scale: f64) -> Vec<u8> {
    rgb.iter()
        .map(|&c| {
            let v = f64::from(c) * scale;
            let v = if v.is_finite() { v.clamp(0.0, 1.0) } else { 0.0 };
            (255.0 * srgb_encode(v)).round() as u8
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectrum::Bands;

    fn image(rgb: Vec<f32>, width: usize, height: usize) -> SpectralImage {
        SpectralImage {
            width,
            height,
            bands: Bands::new(400.0, 700.0, 1).unwrap(),
            data: vec![0.0; width * height],
            rgb,
        }
    }

    #[test]
    fn auto_exposure_maps_the_99th_percentile_to_white() {
        // 200 grey pixels with luminance 1, 2, …, 200: nearest-rank p99 is the 198th value.
        let rgb: Vec<f32> = (1..=200).flat_map(|i| [i as f32; 3]).collect();
        let s = exposure_scale(&rgb, Exposure::Auto);
        assert!((s - 1.0 / 198.0).abs() < 1e-9, "{s}");
        assert_eq!(exposure_scale(&[0.0; 6], Exposure::Auto), 1.0);
        assert_eq!(exposure_scale(&rgb, Exposure::Ev(-1.0)), 0.5);
    }

    #[test]
    fn encodes_with_the_srgb_curve_and_clips() {
        let bytes = encode_pixels(&[0.0, 0.18, 1.0, 2.0, -1.0, f32::NAN], 1.0);
        // 0.18 ↦ 0.4614 ↦ 118 (IEC 61966-2-1).
        assert_eq!(bytes, vec![0, 118, 255, 255, 0, 0]);
    }

    #[test]
    fn writes_a_png_that_decodes_to_the_expected_bytes() {
        let img = image(vec![0.18, 0.18, 0.18, 1.0, 0.0, 0.5], 2, 1);
        let path = std::env::temp_dir().join(format!("morgana-png-{}.png", std::process::id()));
        write_png_preview(&path, &img, Exposure::Ev(0.0)).unwrap();
        let decoder = png::Decoder::new(io::BufReader::new(std::fs::File::open(&path).unwrap()));
        let mut reader = decoder.read_info().unwrap();
        let mut buf = vec![0; reader.output_buffer_size().unwrap()];
        let info = reader.next_frame(&mut buf).unwrap();
        std::fs::remove_file(&path).unwrap();
        assert_eq!((info.width, info.height), (2, 1));
        // 0.5 ↦ 0.7354 ↦ 188.
        assert_eq!(&buf[..6], &[118, 118, 118, 255, 0, 188]);
        let err = write_png_preview(&path, &image(vec![0.0; 5], 2, 1), Exposure::Auto);
        assert_eq!(err.unwrap_err().kind(), io::ErrorKind::InvalidInput);
    }
}
