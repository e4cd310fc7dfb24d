//! The polar intensity diagram: the C0–C180 (red) and C90–C270 (blue) curves of
//! [`super::beam`] on a polar grid, nadir down, C0 and C90 to the right, radius ∝ intensity with
//! the outer circle at the rounded-up peak; circles at quarters of it and spokes every 30°.

use super::Photometry;
use super::beam::plane_curve;
use crate::raster::{BLACK, Canvas, GREY, Rgb, WHITE};
use std::io;
use std::path::Path;

const SIZE: usize = 640;
const RED: Rgb = [200, 30, 30];
const BLUE: Rgb = [30, 70, 200];

/// Writes the diagram of `p` to `path` as PNG.
pub fn write_polar_png(p: &Photometry, path: &Path) -> io::Result<()> {
    let curves = [plane_curve(&p.web, 0.0, 0.5), plane_curve(&p.web, 90.0, 0.5)];
    let peak = curves.iter().flat_map(|c| c.cd.iter().copied()).fold(0.0, f64::max);
    let outer = nice_ceiling(peak);
    let mut canvas = Canvas::new(SIZE, SIZE, WHITE);
    let (cx, cy, radius) = (SIZE as f64 / 2.0, SIZE as f64 / 2.0 + 10.0, SIZE as f64 * 0.40);
    let at = |angle_deg: f64, r: f64| {
        let a = angle_deg.to_radians();
        (cx + r * a.sin(), cy + r * a.cos())
    };
    for k in 1..=4 {
        let r = radius * k as f64 / 4.0;
        let ring: Vec<(f64, f64)> = (0..=360).map(|d| at(d as f64, r)).collect();
        canvas.polyline(&ring, 1, GREY);
        let label = format_cd(outer * k as f64 / 4.0);
        let (x, y) = at(180.0, r);
        canvas.text(x as i64 + 3, y as i64 + 2, &label, 1, GREY);
    }
    for k in 0..12 {
        canvas.line((cx, cy), at(30.0 * k as f64, radius), 1, GREY);
    }
    for (curve, colour) in curves.iter().zip([RED, BLUE]) {
        let scale = if outer > 0.0 { radius / outer } else { 0.0 };
        let pts: Vec<(f64, f64)> = curve.angles_deg.iter().zip(&curve.cd).map(|(a, i)| at(*a, i * scale)).collect();
        canvas.polyline(&pts, 2, colour);
    }
    legend(&mut canvas, p, peak);
    canvas.write_png(path)
}

fn legend(canvas: &mut Canvas, p: &Photometry, peak: f64) {
    let title: String = p.luminaire.chars().filter(|c| c.is_ascii()).take(50).collect();
    canvas.text(10, 10, &title, 2, BLACK);
    canvas.fill_rect(10, 36, 24, 3, RED);
    canvas.text(40, 33, "C0-C180", 1, BLACK);
    canvas.fill_rect(110, 36, 24, 3, BLUE);
    canvas.text(140, 33, "C90-C270", 1, BLACK);
    canvas.text(230, 33, &format!("IMAX {} CD   FLUX {:.0} LM", format_cd(peak), p.flux_lm()), 1, BLACK);
    canvas.text(10, SIZE as i64 - 16, "NADIR DOWN; C0, C90 TO THE RIGHT", 1, GREY);
}

/// The smallest of 1, 2, 2.5, 5 × 10ⁿ at or above `x`.
pub fn nice_ceiling(x: f64) -> f64 {
    if !(x > 0.0 && x.is_finite()) {
        return 1.0;
    }
    let p = 10f64.powf(x.log10().floor());
    [1.0, 2.0, 2.5, 5.0, 10.0].iter().map(|m| m * p).find(|v| *v >= x * (1.0 - 1e-12)).unwrap_or(10.0 * p)
}

fn format_cd(x: f64) -> String {
    if x >= 100.0 {
        format!("{x:.0}")
    } else {
        format!("{x:.3}").trim_end_matches('0').trim_end_matches('.').to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nice_ceilings() {
        assert_eq!(nice_ceiling(3.0), 5.0);
        assert_eq!(nice_ceiling(1234.0), 2000.0);
        assert_eq!(nice_ceiling(2000.0), 2000.0);
        assert_eq!(nice_ceiling(0.021), 0.025);
        assert_eq!(nice_ceiling(0.0), 1.0);
    }
}
