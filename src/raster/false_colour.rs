//! False-colour maps of values on a grid (a sensor's reading): each grid cell a block of colour,
//! the viridis scale from 0 to a rounded-up maximum, a colour bar with five labelled ticks, a
//! title and a line of statistics (mean, min, max, uniformity U₀ = min/mean).
//!
//! Cell (i, j) is drawn with i to the right and j upward, so the plane is seen from the side its
//! normal points to when u, v, n are right-handed.
//!
//! # References
//! - S. van der Walt, N. Smith (2015), "mpl colormaps" — viridis, approximated here by linear
//!   interpolation between nine of its samples.

use super::{BLACK, Canvas, GREY, Rgb, WHITE};
use std::io;
use std::path::Path;

/// Viridis at 0, 1/8, …, 1.
const VIRIDIS: [Rgb; 9] = [
    [68, 1, 84],
    [71, 44, 122],
    [59, 81, 139],
    [44, 113, 142],
    [33, 144, 141],
    [39, 173, 129],
    [92, 200, 99],
    [170, 220, 50],
    [253, 231, 37],
];

/// The colour of t ∈ [0, 1] (clamped; non-finite values are black).
pub fn viridis(t: f64) -> Rgb {
    if !t.is_finite() {
        return BLACK;
    }
    let x = t.clamp(0.0, 1.0) * 8.0;
    let i = (x.floor() as usize).min(7);
    let f = x - i as f64;
    let (a, b) = (VIRIDIS[i], VIRIDIS[i + 1]);
    [0, 1, 2].map(|k| (a[k] as f64 + f * (b[k] as f64 - a[k] as f64)).round() as u8)
}

const MARGIN: i64 = 16;
const TITLE: i64 = 40;
const BAR: i64 = 110;

/// A grid of values to draw: nx × ny, row-major with i fastest.
pub struct GridMap<'a> {
    /// Title, e.g. the sensor's name and quantity.
    pub title: &'a str,
    /// Unit of the values, e.g. "lx".
    pub unit: &'a str,
    pub nx: usize,
    pub ny: usize,
    pub values: &'a [f64],
}

/// Mean, minimum, maximum and uniformity U₀ = min/mean of values.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stats {
    pub mean: f64,
    pub min: f64,
    pub max: f64,
    pub uniformity: f64,
}

impl Stats {
    /// The statistics of `v` (mean 0 and U₀ = 0 for no values or a zero mean).
    pub fn of(v: &[f64]) -> Stats {
        let mean = v.iter().sum::<f64>() / v.len().max(1) as f64;
        let min = v.iter().copied().fold(f64::INFINITY, f64::min);
        let max = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        Stats { mean, min, max, uniformity: if mean > 0.0 { min / mean } else { 0.0 } }
    }
}

/// Writes the false-colour map of `m` as a PNG (not atomically; callers stage the path).
pub fn write_png(m: &GridMap, path: &Path) -> io::Result<()> {
    let cell = ((560 / m.nx.max(1)).min(440 / m.ny.max(1)).max(1)) as i64;
    let (map_w, map_h) = (cell * m.nx as i64, cell * m.ny as i64);
    let width = (2 * MARGIN + map_w + BAR) as usize;
    let height = (TITLE + map_h + 2 * MARGIN).max(TITLE + 220) as usize;
    let mut c = Canvas::new(width, height, WHITE);
    let stats = Stats::of(m.values);
    let top = scale_top(stats.max);
    for (k, v) in m.values.iter().enumerate() {
        let (i, j) = ((k % m.nx) as i64, (k / m.nx) as i64);
        let y = TITLE + map_h - (j + 1) * cell;
        c.fill_rect(MARGIN + i * cell, y, cell, cell, viridis(v / top));
    }
    title(&mut c, m, stats);
    colour_bar(&mut c, MARGIN * 2 + map_w, TITLE, map_h.max(200), top, m.unit);
    c.write_png(path)
}

fn title(c: &mut Canvas, m: &GridMap, s: Stats) {
    let title: String = m.title.chars().filter(|c| c.is_ascii()).take(42).collect();
    let unit = m.unit.to_ascii_uppercase();
    c.text(MARGIN, 8, &title, 2, BLACK);
    let line =
        format!("MEAN {} {unit}  MIN {}  MAX {}  U0 {:.2}", short(s.mean), short(s.min), short(s.max), s.uniformity);
    c.text(MARGIN, 26, &line, 1, BLACK);
}

fn colour_bar(c: &mut Canvas, x: i64, y: i64, h: i64, top: f64, unit: &str) {
    for row in 0..h {
        let t = 1.0 - row as f64 / (h - 1).max(1) as f64;
        c.fill_rect(x, y + row, 20, 1, viridis(t));
    }
    for k in 0..=4 {
        let ty = y + (h - 1) * (4 - k) / 4;
        c.fill_rect(x + 20, ty, 5, 1, GREY);
        let label = format!("{} {}", short(top * k as f64 / 4.0), unit.to_ascii_uppercase());
        c.text(x + 28, ty - 3, &label, 1, BLACK);
    }
}

/// A value with three or four significant digits.
fn short(x: f64) -> String {
    match x.abs() {
        a if !a.is_finite() => "-".into(),
        a if a >= 100.0 => format!("{x:.0}"),
        a if a >= 10.0 => format!("{x:.1}"),
        a if a >= 1.0 => format!("{x:.2}"),
        _ => format!("{}", format!("{x:.3}").parse::<f64>().unwrap_or(x)),
    }
}

/// The smallest of 1, 1.25, 1.5, 2, 2.5, 3, 4, 5, 6, 8 × 10ⁿ at or above `x`: the top of the
/// colour scale.
pub fn scale_top(x: f64) -> f64 {
    if !(x > 0.0 && x.is_finite()) {
        return 1.0;
    }
    let p = 10f64.powf(x.log10().floor());
    [1.0, 1.25, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0]
        .iter()
        .map(|m| m * p)
        .find(|v| *v >= x * (1.0 - 1e-12))
        .unwrap_or(10.0 * p)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scale_tops_and_short_numbers() {
        assert_eq!(scale_top(1060.0), 1250.0);
        assert_eq!(scale_top(500.0), 500.0);
        assert_eq!(scale_top(0.0), 1.0);
        assert_eq!(short(180.767), "181");
        assert_eq!(short(12.345), "12.3");
        assert_eq!(short(0.1234), "0.123");
    }

    #[test]
    fn viridis_runs_from_purple_to_yellow() {
        assert_eq!(viridis(0.0), [68, 1, 84]);
        assert_eq!(viridis(1.0), [253, 231, 37]);
        assert_eq!(viridis(2.0), [253, 231, 37]);
        assert_eq!(viridis(0.5), [33, 144, 141]);
        assert_eq!(viridis(f64::NAN), BLACK);
    }

    #[test]
    fn a_map_shows_the_grid_with_j_upward() {
        let values = [0.0, 0.0, 0.0, 500.0];
        let m = GridMap { title: "desk illuminance", unit: "lx", nx: 2, ny: 2, values: &values };
        let path = std::env::temp_dir().join(format!("morgana-fc-{}.png", std::process::id()));
        write_png(&m, &path).unwrap();
        let decoder = ::png::Decoder::new(std::io::BufReader::new(std::fs::File::open(&path).unwrap()));
        let mut reader = decoder.read_info().unwrap();
        let mut buf = vec![0; reader.output_buffer_size().unwrap()];
        let info = reader.next_frame(&mut buf).unwrap();
        let px = |x: usize, y: usize| &buf[(y * info.width as usize + x) * 3..][..3];
        // Cells are 220 px (440/2); cell (1, 1) is top right: 500 lx = the top of the scale.
        assert_eq!(px((MARGIN + 330) as usize, (TITLE + 110) as usize), &viridis(1.0));
        assert_eq!(px((MARGIN + 110) as usize, (TITLE + 330) as usize), &viridis(0.0));
        std::fs::remove_file(&path).ok();
        let s = Stats::of(&values);
        assert_eq!((s.mean, s.min, s.max, s.uniformity), (125.0, 0.0, 500.0, 0.0));
    }
}
