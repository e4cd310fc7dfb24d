//! A 5×7 pixel font for the false-colour legend: digits, `.`, `-`, `e` and the letters of
//! "cd/m2". Each glyph is seven rows of five bits, most significant bit on the left.

/// Glyph advance in font pixels (5 columns and 1 of spacing).
pub const ADVANCE: usize = 6;
/// Glyph height in font pixels.
pub const HEIGHT: usize = 7;

/// The rows of `c`, or `None` for a character the font lacks.
fn glyph(c: char) -> Option<[u8; 7]> {
    Some(match c {
        '0' => [0b01110, 0b10001, 0b10011, 0b10101, 0b11001, 0b10001, 0b01110],
        '1' => [0b00100, 0b01100, 0b00100, 0b00100, 0b00100, 0b00100, 0b01110],
        '2' => [0b01110, 0b10001, 0b00001, 0b00010, 0b00100, 0b01000, 0b11111],
        '3' => [0b11110, 0b00001, 0b00001, 0b01110, 0b00001, 0b00001, 0b11110],
        '4' => [0b00010, 0b00110, 0b01010, 0b10010, 0b11111, 0b00010, 0b00010],
        '5' => [0b11111, 0b10000, 0b11110, 0b00001, 0b00001, 0b10001, 0b01110],
        '6' => [0b00110, 0b01000, 0b10000, 0b11110, 0b10001, 0b10001, 0b01110],
        '7' => [0b11111, 0b00001, 0b00010, 0b00100, 0b01000, 0b01000, 0b01000],
        '8' => [0b01110, 0b10001, 0b10001, 0b01110, 0b10001, 0b10001, 0b01110],
        '9' => [0b01110, 0b10001, 0b10001, 0b01111, 0b00001, 0b00010, 0b01100],
        '.' => [0, 0, 0, 0, 0, 0b01100, 0b01100],
        '-' => [0, 0, 0, 0b11111, 0, 0, 0],
        'e' => [0, 0, 0b01110, 0b10001, 0b11111, 0b10000, 0b01110],
        'c' => [0, 0, 0b01110, 0b10000, 0b10000, 0b10001, 0b01110],
        'd' => [0b00001, 0b00001, 0b01101, 0b10011, 0b10001, 0b10001, 0b01111],
        '/' => [0, 0b00001, 0b00010, 0b00100, 0b01000, 0b10000, 0],
        'm' => [0, 0, 0b11010, 0b10101, 0b10101, 0b10001, 0b10001],
        ' ' => [0; 7],
        _ => return None,
    })
}

/// Width of `text` in image pixels at `scale` image pixels per font pixel.
pub fn text_width(text: &str, scale: usize) -> usize {
    text.chars().count() * ADVANCE * scale
}

/// Draws `text` into an RGB8 image (`width` pixels per row) with its top-left corner at
/// (x, y); pixels outside the image and characters the font lacks are skipped.
pub fn draw_text(rgb: &mut [u8], width: usize, x: usize, y: usize, text: &str, scale: usize, colour: [u8; 3]) {
    let height = rgb.len() / (3 * width.max(1));
    for (n, c) in text.chars().enumerate() {
        let Some(rows) = glyph(c) else { continue };
        for (r, bits) in rows.iter().enumerate() {
            for col in 0..5 {
                if bits & (0b10000 >> col) == 0 {
                    continue;
                }
                for dy in 0..scale {
                    for dx in 0..scale {
                        let px = x + (n * ADVANCE + col) * scale + dx;
                        let py = y + r * scale + dy;
                        if px < width && py < height {
                            rgb[3 * (py * width + px)..][..3].copy_from_slice(&colour);
                        }
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn draws_the_glyph_bits() {
        let mut rgb = vec![0u8; 3 * 12 * 7];
        draw_text(&mut rgb, 12, 0, 0, "1-", 1, [255, 255, 255]);
        let on = |x: usize, y: usize| rgb[3 * (y * 12 + x)] == 255;
        // '1': the stem at column 2, the foot at row 6 from column 1 to 3; '-' on row 3.
        assert!((0..7).all(|y| on(2, y)));
        assert!(on(1, 6) && on(3, 6) && !on(0, 6) && !on(4, 0));
        assert!((6..11).all(|x| on(x, 3)) && !on(6, 2));
        assert_eq!(text_width("cd/m2", 2), 60);
        assert!(glyph('x').is_none());
    }
}
