//! Raster graphics: a small RGB canvas for plots (lines, rectangles, text in the one 5×7 font,
//! [`font`]), the one PNG encoder ([`png`]), colour maps and false-colour grids
//! ([`false_colour`]) and spectrum line plots ([`spectrum_plot`]). Enough for polar intensity
//! diagrams, sensor maps with a colour bar and legends, without a plotting dependency.

pub mod false_colour;
pub mod font;
pub mod log_axes;
pub mod png;
pub mod spectrum_plot;

use std::io;
use std::path::Path;

/// An sRGB-encoded colour, 8 bits per channel.
pub type Rgb = [u8; 3];

/// White.
pub const WHITE: Rgb = [255, 255, 255];
/// Black.
pub const BLACK: Rgb = [0, 0, 0];
/// Light grey (grid lines).
pub const GREY: Rgb = [190, 190, 190];
/// Lighter grey (the decade grid of log-log plots).
pub const LIGHT_GREY: Rgb = [225, 225, 225];

/// An RGB image, row-major from the top left.
#[derive(Clone, Debug, PartialEq)]
pub struct Canvas {
    /// Width, pixels.
    pub width: usize,
    /// Height, pixels.
    pub height: usize,
    /// Pixels, row-major from the top left.
    pub pixels: Vec<Rgb>,
}

impl Canvas {
    /// A `width × height` canvas filled with `background`.
    pub fn new(width: usize, height: usize, background: Rgb) -> Canvas {
        Canvas { width, height, pixels: vec![background; width * height] }
    }

    /// Sets pixel (x, y) when it lies on the canvas.
    pub fn set(&mut self, x: i64, y: i64, c: Rgb) {
        if x >= 0 && y >= 0 && (x as usize) < self.width && (y as usize) < self.height {
            self.pixels[y as usize * self.width + x as usize] = c;
        }
    }

    /// Pixel (x, y), which must lie on the canvas.
    pub fn get(&self, x: usize, y: usize) -> Rgb {
        self.pixels[y * self.width + x]
    }

    /// Fills the rectangle [x0, x0 + w) × [y0, y0 + h).
    pub fn fill_rect(&mut self, x0: i64, y0: i64, w: i64, h: i64, c: Rgb) {
        for y in y0..y0 + h {
            for x in x0..x0 + w {
                self.set(x, y, c);
            }
        }
    }

    /// A line of the given thickness (pixels) from (x0, y0) to (x1, y1), by stepping along its
    /// longer extent.
    pub fn line(&mut self, (x0, y0): (f64, f64), (x1, y1): (f64, f64), thickness: i64, c: Rgb) {
        if !(x0.is_finite() && y0.is_finite() && x1.is_finite() && y1.is_finite()) {
            return;
        }
        let steps = ((x1 - x0).abs().max((y1 - y0).abs()).ceil() as i64).clamp(1, 1 << 16);
        let r = thickness / 2;
        for i in 0..=steps {
            let t = i as f64 / steps as f64;
            let (x, y) = ((x0 + t * (x1 - x0)).round() as i64, (y0 + t * (y1 - y0)).round() as i64);
            self.fill_rect(x - r, y - r, thickness.max(1), thickness.max(1), c);
        }
    }

    /// A polyline through `points`.
    pub fn polyline(&mut self, points: &[(f64, f64)], thickness: i64, c: Rgb) {
        for w in points.windows(2) {
            self.line(w[0], w[1], thickness, c);
        }
    }

    /// `text` with its top-left corner at (x, y), each font pixel `scale` pixels wide.
    pub fn text(&mut self, x: i64, y: i64, text: &str, scale: i64, c: Rgb) {
        for (k, ch) in text.chars().enumerate() {
            let rows = font::glyph(ch);
            let gx = x + (k * font::ADVANCE) as i64 * scale;
            for (r, bits) in rows.iter().enumerate() {
                for col in 0..5 {
                    if bits & (0x10 >> col) != 0 {
                        self.fill_rect(gx + col * scale, y + r as i64 * scale, scale, scale, c);
                    }
                }
            }
        }
    }

    /// Width in pixels of `text` drawn at `scale`.
    pub fn text_width(text: &str, scale: i64) -> i64 {
        (text.chars().count() * font::ADVANCE) as i64 * scale
    }

    /// Height in pixels of a line of text at `scale`.
    pub fn text_height(scale: i64) -> i64 {
        font::HEIGHT as i64 * scale
    }

    /// Writes an 8-bit RGB PNG (not atomically; callers stage the path).
    pub fn write_png(&self, path: &Path) -> io::Result<()> {
        let bytes: Vec<u8> = self.pixels.iter().flatten().copied().collect();
        png::write_rgb8(path, self.width, self.height, &bytes)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_text_and_clipping() {
        let mut c = Canvas::new(40, 20, WHITE);
        c.line((0.0, 0.0), (39.0, 19.0), 1, BLACK);
        assert_eq!(c.get(0, 0), BLACK);
        assert_eq!(c.get(39, 19), BLACK);
        c.line((-100.0, 5.0), (100.0, 5.0), 3, GREY);
        assert_eq!(c.get(20, 4), GREY);
        c.text(1, 10, "1", 1, BLACK);
        // The "1" glyph's top row has one dot in the middle column.
        assert_eq!(c.get(3, 10), BLACK);
        assert_eq!(c.get(1, 10), WHITE);
        assert_eq!(Canvas::text_width("LUX", 2), 36);
    }

    #[test]
    fn writes_a_png_that_decodes_to_the_same_pixels() {
        let mut c = Canvas::new(7, 5, WHITE);
        c.fill_rect(2, 1, 3, 2, [10, 200, 30]);
        let path = std::env::temp_dir().join(format!("morgana-raster-{}.png", std::process::id()));
        c.write_png(&path).unwrap();
        let decoder = ::png::Decoder::new(std::io::BufReader::new(std::fs::File::open(&path).unwrap()));
        let mut reader = decoder.read_info().unwrap();
        let mut buf = vec![0; reader.output_buffer_size().unwrap()];
        let info = reader.next_frame(&mut buf).unwrap();
        assert_eq!((info.width, info.height), (7, 5));
        assert_eq!(&buf[(7 + 2) * 3..][..3], &[10, 200, 30], "pixel (2, 1)");
        assert_eq!(&buf[..3], &[255, 255, 255]);
        std::fs::remove_file(&path).ok();
    }
}
