//! Line plots of spectra (e.g. remote-sensing reflectance R_rs(λ) for a chlorophyll sweep) as a
//! PNG, drawn with [`crate::raster`]: one coloured line per series, axes with tick labels, a
//! legend, and optional marker lines at given wavelengths.

use super::false_colour::viridis;
use super::{BLACK, Canvas, GREY, WHITE};
use std::io;
use std::path::Path;

/// One named series of (x, y) points.
pub struct Series {
    /// Legend label.
    pub label: String,
    /// The (x, y) points, drawn joined in the order given.
    pub points: Vec<(f64, f64)>,
}

const W: usize = 820;
const H: usize = 480;
const LEFT: f64 = 90.0;
const RIGHT: f64 = 220.0;
const TOP: f64 = 40.0;
const BOTTOM: f64 = 60.0;

/// Writes the plot; `markers` are x values drawn as thin grey vertical lines.
pub fn write_png(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
    markers: &[f64],
) -> io::Result<()> {
    let all = series.iter().flat_map(|s| s.points.iter());
    let (x0, x1) = all.clone().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| (a.min(p.0), b.max(p.0)));
    let y1 = all.fold(0.0f64, |m, p| m.max(p.1)).max(f64::MIN_POSITIVE) * 1.05;
    let (x0, x1) = if x1 > x0 { (x0, x1) } else { (x0 - 1.0, x0 + 1.0) };
    let px = |x: f64| LEFT + (x - x0) / (x1 - x0) * (W as f64 - LEFT - RIGHT);
    let py = |y: f64| H as f64 - BOTTOM - y / y1 * (H as f64 - TOP - BOTTOM);
    let mut c = Canvas::new(W, H, WHITE);
    for &m in markers {
        c.line((px(m), py(0.0)), (px(m), py(y1)), 1, GREY);
    }
    c.line((px(x0), py(0.0)), (px(x1), py(0.0)), 1, BLACK);
    c.line((px(x0), py(0.0)), (px(x0), py(y1)), 1, BLACK);
    for i in 0..=5 {
        let x = x0 + (x1 - x0) * i as f64 / 5.0;
        c.text(px(x) as i64 - 12, (H as f64 - BOTTOM + 8.0) as i64, &format!("{x:.0}"), 2, BLACK);
        let y = y1 * i as f64 / 5.0;
        c.text(4, py(y) as i64 - 7, &format!("{y:.1e}"), 2, BLACK);
    }
    c.text(LEFT as i64, 10, title, 2, BLACK);
    c.text((W as f64 / 2.0 - 60.0) as i64, (H as f64 - 24.0) as i64, x_label, 2, BLACK);
    c.text(4, 24, y_label, 2, BLACK);
    for (k, s) in series.iter().enumerate() {
        let colour = viridis(if series.len() > 1 { k as f64 / (series.len() - 1) as f64 * 0.9 } else { 0.0 });
        let pts: Vec<(f64, f64)> = s.points.iter().map(|p| (px(p.0), py(p.1))).collect();
        c.polyline(&pts, 2, colour);
        let ly = TOP as i64 + 22 * k as i64;
        c.fill_rect(W as i64 - RIGHT as i64 + 12, ly + 4, 18, 6, colour);
        c.text(W as i64 - RIGHT as i64 + 36, ly, &s.label, 2, BLACK);
    }
    c.write_png(path)
}
