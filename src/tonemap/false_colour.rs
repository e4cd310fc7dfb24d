//! False colour: luminance in cd m⁻² on a logarithmic colour scale, with a legend.
//!
//! The scale spans whole decades from 10^⌊log₁₀ L₁⌋ to 10^⌈log₁₀ L_max⌉, L₁ being the 1st
//! percentile (nearest rank) of the positive pixel luminances, at least one and at most ten
//! decades (the top ten when the image spans more). A pixel of luminance L gets the colour of
//! t = (log₁₀ L − lo)/(hi − lo), clamped to [0, 1], on a ramp from dark violet (t = 0) through
//! blue, cyan, green, yellow and orange to red (t = 1), interpolated linearly between stops in
//! sRGB-encoded values; black pixels stay black. The legend on the right shows the ramp with a
//! tick and a label at every decade and the unit, "cd/m2".
//!
//! The luminance shown is the photopic luminance of the input, before any adaptation or tone
//! mapping, as a luminance meter would read it.

use super::exposure::percentile;
use crate::raster::font::{HEIGHT, draw_text, text_width};

/// (t, sRGB-encoded colour) stops of the ramp.
const RAMP: [(f64, [f64; 3]); 7] = [
    (0.0, [0.10, 0.00, 0.35]),
    (0.15, [0.15, 0.15, 0.85]),
    (0.35, [0.00, 0.70, 0.95]),
    (0.50, [0.10, 0.80, 0.25]),
    (0.65, [0.95, 0.90, 0.10]),
    (0.82, [1.00, 0.45, 0.00]),
    (1.0, [0.85, 0.00, 0.00]),
];

/// The decades of the scale.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LogScale {
    pub lo_decade: i32,
    pub hi_decade: i32,
}

impl LogScale {
    /// The scale for these pixel luminances (cd m⁻²).
    pub fn for_luminance(luminance: &[f64]) -> LogScale {
        let positive: Vec<f64> = luminance.iter().copied().filter(|l| l.is_finite() && *l > 0.0).collect();
        if positive.is_empty() {
            return LogScale { lo_decade: 0, hi_decade: 1 };
        }
        let max = positive.iter().copied().fold(0.0, f64::max);
        let hi = max.log10().ceil() as i32;
        let lo = (percentile(&positive, 0.01).log10().floor() as i32).clamp(hi - 10, hi - 1);
        LogScale { lo_decade: lo, hi_decade: hi }
    }

    /// Position of `l` on the scale, in [0, 1].
    pub fn t(&self, l: f64) -> f64 {
        ((l.log10() - f64::from(self.lo_decade)) / f64::from(self.hi_decade - self.lo_decade)).clamp(0.0, 1.0)
    }
}

/// The ramp colour at t ∈ [0, 1].
pub fn ramp(t: f64) -> [u8; 3] {
    let t = t.clamp(0.0, 1.0);
    let i = RAMP.iter().position(|(s, _)| *s >= t).unwrap_or(RAMP.len() - 1).max(1);
    let ((t0, c0), (t1, c1)) = (RAMP[i - 1], RAMP[i]);
    let u = (t - t0) / (t1 - t0);
    [0, 1, 2].map(|k| (255.0 * (c0[k] + u * (c1[k] - c0[k]))).round() as u8)
}

/// The label of decade k: plain numbers from 0.001 to 1000, else "1ek".
pub fn decade_label(k: i32) -> String {
    if (-3..=3).contains(&k) { format!("{}", 10f64.powi(k)) } else { format!("1e{k}") }
}

/// A false-colour RGB8 image with its legend: (width, height, bytes).
pub fn false_colour(luminance: &[f64], width: usize, height: usize) -> (usize, usize, Vec<u8>) {
    let scale = LogScale::for_luminance(luminance);
    let s = if height >= 160 { 2 } else { 1 };
    let decades = (scale.hi_decade - scale.lo_decade) as usize;
    let label_w = (scale.lo_decade..=scale.hi_decade).map(|k| text_width(&decade_label(k), s)).max().unwrap_or(0);
    let panel_w = 4 * s + 12 * s + 3 * s + 2 * s + label_w.max(text_width("cd/m2", s)) + 4 * s;
    let bar_top = 4 * s + HEIGHT * s + 6 * s;
    let needed = bar_top + (decades + 1) * (HEIGHT + 3) * s + 4 * s;
    let (out_w, out_h) = (width + panel_w, height.max(needed));
    let mut rgb = vec![0u8; 3 * out_w * out_h];
    for y in 0..height {
        for x in 0..width {
            let l = luminance[y * width + x];
            let c = if l.is_finite() && l > 0.0 { ramp(scale.t(l)) } else { [0; 3] };
            rgb[3 * (y * out_w + x)..][..3].copy_from_slice(&c);
        }
    }
    draw_legend(&mut rgb, out_w, out_h, width, &scale, s, bar_top);
    (out_w, out_h, rgb)
}

fn draw_legend(rgb: &mut [u8], out_w: usize, out_h: usize, x0: usize, scale: &LogScale, s: usize, bar_top: usize) {
    let white = [255, 255, 255];
    draw_text(rgb, out_w, x0 + 4 * s, 4 * s, "cd/m2", s, white);
    let (bar_x, bar_w) = (x0 + 4 * s, 12 * s);
    let bar_bottom = out_h - 4 * s - HEIGHT * s / 2;
    let bar_top = bar_top + HEIGHT * s / 2;
    let span = (bar_bottom - bar_top) as f64;
    for y in bar_top..=bar_bottom {
        let c = ramp((bar_bottom - y) as f64 / span);
        for x in bar_x..bar_x + bar_w {
            rgb[3 * (y * out_w + x)..][..3].copy_from_slice(&c);
        }
    }
    let decades = scale.hi_decade - scale.lo_decade;
    for (i, k) in (scale.lo_decade..=scale.hi_decade).enumerate() {
        let y = bar_bottom - ((i as f64 / f64::from(decades)) * span).round() as usize;
        for x in bar_x + bar_w..bar_x + bar_w + 3 * s {
            for dy in 0..s {
                rgb[3 * ((y + dy).min(out_h - 1) * out_w + x)..][..3].copy_from_slice(&white);
            }
        }
        let label_y = y.saturating_sub(HEIGHT * s / 2);
        draw_text(rgb, out_w, bar_x + bar_w + 5 * s, label_y, &decade_label(k), s, white);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_scale_spans_whole_decades_from_p1_to_the_maximum() {
        let lum: Vec<f64> = (0..1000).map(|i| 0.05 * 1.01f64.powi(i)).collect();
        let s = LogScale::for_luminance(&lum);
        // p1 ≈ 0.0552 → 10⁻²; max ≈ 0.05 · 1.01⁹⁹⁹ ≈ 1049 → 10⁴.
        assert_eq!(s, LogScale { lo_decade: -2, hi_decade: 4 });
        assert_eq!(s.t(0.01), 0.0);
        assert!((s.t(1.0) - 2.0 / 6.0).abs() < 1e-12);
        assert_eq!(LogScale::for_luminance(&[0.0, f64::NAN]), LogScale { lo_decade: 0, hi_decade: 1 });
        assert_eq!(LogScale::for_luminance(&[5.0, 5.0]), LogScale { lo_decade: 0, hi_decade: 1 });
        assert_eq!(LogScale::for_luminance(&[1e-9, 1e9]).lo_decade, -1);
    }

    #[test]
    fn ramp_and_labels() {
        assert_eq!(ramp(0.0), [26, 0, 89]);
        assert_eq!(ramp(1.0), [217, 0, 0]);
        assert_eq!(ramp(0.5), [26, 204, 64]);
        assert_eq!(decade_label(-3), "0.001");
        assert_eq!(decade_label(2), "100");
        assert_eq!(decade_label(5), "1e5");
        assert_eq!(decade_label(-4), "1e-4");
    }

    #[test]
    fn the_image_keeps_its_pixels_and_gains_a_legend() {
        let lum: Vec<f64> = (0..64 * 48).map(|i| if i == 0 { 0.0 } else { f64::from(i) }).collect();
        let (w, h, rgb) = false_colour(&lum, 64, 48);
        assert!(w > 64 && h >= 48 && rgb.len() == 3 * w * h);
        assert_eq!(&rgb[..3], &[0, 0, 0], "black stays black");
        let last = 47 * 64 + 63;
        assert_eq!(&rgb[3 * (47 * w + 63)..][..3], &ramp(LogScale::for_luminance(&lum).t(lum[last])));
        // The legend has the white unit text somewhere right of the image.
        assert!((0..h).any(|y| (64..w).any(|x| rgb[3 * (y * w + x)..][..3] == [255, 255, 255])));
    }
}
