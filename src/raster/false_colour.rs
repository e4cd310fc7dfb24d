//! The one false-colour renderer: values on a grid drawn as blocks of colour, with a colour bar,
//! labelled ticks, the unit and, optionally, a title and a line of statistics.
//!
//! It serves two users with two settings:
//! - sensor readings (`sensor::Reading::write_png`): the viridis map on a linear scale from 0 to
//!   a rounded-up maximum ([`Scale::linear_to`]), five ticks, a title and the statistics
//!   (mean, min, max, uniformity U₀ = min/mean), dark text on white; grid cell (i, j) is drawn
//!   with i to the right and j upward, so a plane is seen from the side its normal points to
//!   when u, v, n are right-handed;
//! - luminance images (`morgana tonemap --false-colour`): the luminance ramp on a logarithmic
//!   scale of whole decades ([`Scale::log_decades_for`]), a tick at every decade, "cd/m2",
//!   white text on black; pixel rows run downward as in the image.
//!
//! A value gets the colour of t = its position on the scale, clamped to [0, 1]; non-finite
//! values (and non-positive ones on a log scale) are black.
//!
//! # References
//! - S. van der Walt, N. Smith (2015), "mpl colormaps" — viridis, approximated here by linear
//!   interpolation between nine of its samples.

use super::font::{HEIGHT, text_width};
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

/// (t, sRGB-encoded colour) stops of the luminance ramp: dark violet through blue, cyan,
/// green, yellow and orange to red.
const RAMP: [(f64, [f64; 3]); 7] = [
    (0.0, [0.10, 0.00, 0.35]),
    (0.15, [0.15, 0.15, 0.85]),
    (0.35, [0.00, 0.70, 0.95]),
    (0.50, [0.10, 0.80, 0.25]),
    (0.65, [0.95, 0.90, 0.10]),
    (0.82, [1.00, 0.45, 0.00]),
    (1.0, [0.85, 0.00, 0.00]),
];

/// The colour of t ∈ [0, 1] on viridis (clamped; non-finite values are black).
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

/// The luminance ramp's colour at t ∈ [0, 1], interpolated linearly between its stops in
/// sRGB-encoded values.
pub fn ramp(t: f64) -> Rgb {
    let t = t.clamp(0.0, 1.0);
    let i = RAMP.iter().position(|(s, _)| *s >= t).unwrap_or(RAMP.len() - 1).max(1);
    let ((t0, c0), (t1, c1)) = (RAMP[i - 1], RAMP[i]);
    let u = (t - t0) / (t1 - t0);
    [0, 1, 2].map(|k| (255.0 * (c0[k] + u * (c1[k] - c0[k]))).round() as u8)
}

/// A colour map.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ColourMap {
    /// Viridis (perceptually uniform, for sensor readings).
    Viridis,
    /// The luminance ramp ([`ramp`]).
    Ramp,
}

impl ColourMap {
    /// The colour at t ∈ [0, 1].
    pub fn at(self, t: f64) -> Rgb {
        match self {
            ColourMap::Viridis => viridis(t),
            ColourMap::Ramp => ramp(t),
        }
    }
}

/// Where values fall on the colour bar.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Scale {
    /// 0 to `top`, linear.
    Linear {
        /// Value at the top of the scale.
        top: f64,
    },
    /// 10^lo to 10^hi, logarithmic, in whole decades.
    LogDecades {
        /// Lowest decade: the scale starts at 10^lo.
        lo: i32,
        /// Highest decade: the scale ends at 10^hi.
        hi: i32,
    },
}

impl Scale {
    /// A linear scale from 0 to [`scale_top`] of `max`.
    pub fn linear_to(max: f64) -> Scale {
        Scale::Linear { top: scale_top(max) }
    }

    /// Whole decades from 10^⌊log₁₀ v₁⌋ to 10^⌈log₁₀ v_max⌉, v₁ being the 1st percentile
    /// (nearest rank) of the positive finite values: at least one and at most ten decades (the
    /// top ten when the values span more).
    pub fn log_decades_for(values: &[f64]) -> Scale {
        let mut positive: Vec<f64> = values.iter().copied().filter(|l| l.is_finite() && *l > 0.0).collect();
        if positive.is_empty() {
            return Scale::LogDecades { lo: 0, hi: 1 };
        }
        let max = positive.iter().copied().fold(0.0, f64::max);
        let hi = max.log10().ceil() as i32;
        let rank = ((0.01 * positive.len() as f64).ceil() as usize).clamp(1, positive.len());
        let (_, p1, _) = positive.select_nth_unstable_by(rank - 1, f64::total_cmp);
        let lo = (p1.log10().floor() as i32).clamp(hi - 10, hi - 1);
        Scale::LogDecades { lo, hi }
    }

    /// Position of `v` on the scale, in [0, 1]; `None` for values drawn black.
    pub fn t(&self, v: f64) -> Option<f64> {
        match *self {
            Scale::Linear { top } => v.is_finite().then(|| (v / top).clamp(0.0, 1.0)),
            Scale::LogDecades { lo, hi } => {
                (v.is_finite() && v > 0.0).then(|| ((v.log10() - f64::from(lo)) / f64::from(hi - lo)).clamp(0.0, 1.0))
            }
        }
    }

    /// The ticks of the colour bar: (t, label).
    pub fn ticks(&self) -> Vec<(f64, String)> {
        match *self {
            Scale::Linear { top } => (0..=4).map(|k| (k as f64 / 4.0, short(top * k as f64 / 4.0))).collect(),
            Scale::LogDecades { lo, hi } => {
                (lo..=hi).map(|k| (f64::from(k - lo) / f64::from(hi - lo), decade_label(k))).collect()
            }
        }
    }
}

/// The label of decade k: plain numbers from 0.001 to 1000, else "1ek".
pub fn decade_label(k: i32) -> String {
    if (-3..=3).contains(&k) { format!("{}", 10f64.powi(k)) } else { format!("1e{k}") }
}

/// Which way grid rows run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rows {
    /// Row 0 at the bottom (a plane's v axis).
    Upward,
    /// Row 0 at the top (an image).
    Downward,
}

/// A grid of values to draw: nx × ny, row-major with i fastest.
pub struct Grid<'a> {
    /// Columns.
    pub nx: usize,
    /// Rows.
    pub ny: usize,
    /// The values, `nx × ny`.
    pub values: &'a [f64],
    /// Which way rows run on the picture.
    pub rows: Rows,
}

/// How the map and its legend look.
pub struct Look<'a> {
    /// How values map to t ∈ [0, 1].
    pub scale: Scale,
    /// How t maps to colour.
    pub map: ColourMap,
    /// Unit of the values, written above the colour bar (and after each tick on a linear
    /// scale).
    pub unit: &'a str,
    /// Title and statistics lines above the map, if any.
    pub heading: Option<(String, String)>,
    /// Pixels per grid cell.
    pub cell: usize,
    /// Background and text colours.
    pub background: Rgb,
    /// Text colour.
    pub text: Rgb,
    /// Font pixel size of the legend.
    pub text_scale: usize,
}

/// The false-colour picture of `grid`: the map, the colour bar with its ticks and labels, and
/// the heading if any.
pub fn draw(grid: &Grid, look: &Look) -> Canvas {
    let s = look.text_scale.max(1) as i64;
    let cell = look.cell.max(1) as i64;
    let (map_w, map_h) = (cell * grid.nx as i64, cell * grid.ny as i64);
    let margin = if look.heading.is_some() { 16 } else { 0 };
    let top = if look.heading.is_some() { 40 } else { 0 };
    let ticks = look.scale.ticks();
    let label = |text: &str| match look.scale {
        Scale::Linear { .. } => format!("{text} {}", look.unit.to_ascii_uppercase()),
        Scale::LogDecades { .. } => text.to_string(),
    };
    let label_w = ticks.iter().map(|(_, l)| text_width(&label(l), s as usize)).max().unwrap_or(0) as i64;
    let unit_w = text_width(look.unit, s as usize) as i64;
    let bar_x = margin + map_w + 4 * s.max(margin / 4);
    let bar_w = 12 * s;
    let width = bar_x + bar_w + 5 * s + label_w.max(unit_w) + 4 * s;
    let unit_h = 4 * s + HEIGHT as i64 * s + 6 * s;
    let bar_h = (map_h - unit_h - 4 * s).max((ticks.len() as i64) * (HEIGHT as i64 + 3) * s).max(60 * s);
    let height = (top + map_h + 2 * margin).max(top + unit_h + bar_h + 4 * s + HEIGHT as i64 * s / 2);
    let mut c = Canvas::new(width as usize, height as usize, look.background);
    for (k, v) in grid.values.iter().enumerate() {
        let (i, j) = ((k % grid.nx) as i64, (k / grid.nx) as i64);
        let row = match grid.rows {
            Rows::Upward => grid.ny as i64 - 1 - j,
            Rows::Downward => j,
        };
        let colour = look.scale.t(*v).map_or(BLACK, |t| look.map.at(t));
        c.fill_rect(margin + i * cell, top + row * cell, cell, cell, colour);
    }
    if let Some((title, stats)) = &look.heading {
        let title: String = title.chars().filter(|c| c.is_ascii()).take(42).collect();
        c.text(margin, 8, &title, 2, look.text);
        c.text(margin, 26, stats, 1, look.text);
    }
    c.text(bar_x, top + 4 * s, look.unit, s, look.text);
    colour_bar(&mut c, look, &ticks, bar_x, top + unit_h + HEIGHT as i64 * s / 2, bar_h, &label);
    c
}

/// The bar from t = 1 at `y` down to t = 0 at `y + h`, with a tick and a label at each tick.
#[allow(clippy::too_many_arguments)]
fn colour_bar(
    c: &mut Canvas,
    look: &Look,
    ticks: &[(f64, String)],
    x: i64,
    y: i64,
    h: i64,
    label: &dyn Fn(&str) -> String,
) {
    let s = look.text_scale.max(1) as i64;
    let bar_w = 12 * s;
    for row in 0..=h {
        c.fill_rect(x, y + row, bar_w, 1, look.map.at(1.0 - row as f64 / h.max(1) as f64));
    }
    let tick = if look.background == WHITE { GREY } else { look.text };
    for (t, text) in ticks {
        let ty = y + ((1.0 - t) * h as f64).round() as i64;
        c.fill_rect(x + bar_w, ty, 3 * s, s, tick);
        c.text(x + bar_w + 5 * s, ty - HEIGHT as i64 * s / 2, &label(text), s, look.text);
    }
}

/// Writes the false-colour map of `grid` as a PNG (not atomically; callers stage the path).
pub fn write_png(grid: &Grid, look: &Look, path: &Path) -> io::Result<()> {
    draw(grid, look).write_png(path)
}

/// Mean, minimum, maximum and uniformity U₀ = min/mean of values.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stats {
    /// Mean of the values.
    pub mean: f64,
    /// Smallest value.
    pub min: f64,
    /// Largest value.
    pub max: f64,
    /// Uniformity U₀ = min/mean (0 when the mean is not positive).
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

    /// "MEAN m UNIT  MIN a  MAX b  U0 u", numbers to three or four significant digits.
    pub fn line(&self, unit: &str) -> String {
        format!(
            "MEAN {} {}  MIN {}  MAX {}  U0 {:.2}",
            short(self.mean),
            unit.to_ascii_uppercase(),
            short(self.min),
            short(self.max),
            self.uniformity
        )
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

/// The smallest of 1, 1.25, 1.5, 2, 2.5, 3, 4, 5, 6, 8 × 10ⁿ at or above `x`: the top of a
/// linear colour scale.
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
    fn colour_maps_run_from_end_to_end() {
        assert_eq!(viridis(0.0), [68, 1, 84]);
        assert_eq!(viridis(1.0), [253, 231, 37]);
        assert_eq!(viridis(2.0), [253, 231, 37]);
        assert_eq!(viridis(0.5), [33, 144, 141]);
        assert_eq!(viridis(f64::NAN), BLACK);
        assert_eq!(ramp(0.0), [26, 0, 89]);
        assert_eq!(ramp(1.0), [217, 0, 0]);
        assert_eq!(ramp(0.5), [26, 204, 64]);
    }

    #[test]
    fn the_log_scale_spans_whole_decades_from_p1_to_the_maximum() {
        let lum: Vec<f64> = (0..1000).map(|i| 0.05 * 1.01f64.powi(i)).collect();
        let s = Scale::log_decades_for(&lum);
        // p1 ≈ 0.0552 → 10⁻²; max ≈ 0.05 · 1.01⁹⁹⁹ ≈ 1049 → 10⁴.
        assert_eq!(s, Scale::LogDecades { lo: -2, hi: 4 });
        assert_eq!(s.t(0.01), Some(0.0));
        assert!((s.t(1.0).unwrap() - 2.0 / 6.0).abs() < 1e-12);
        assert_eq!(s.t(0.0), None);
        assert_eq!(Scale::log_decades_for(&[0.0, f64::NAN]), Scale::LogDecades { lo: 0, hi: 1 });
        assert_eq!(Scale::log_decades_for(&[5.0, 5.0]), Scale::LogDecades { lo: 0, hi: 1 });
        assert_eq!(Scale::log_decades_for(&[1e-9, 1e9]), Scale::LogDecades { lo: -1, hi: 9 });
        assert_eq!(decade_label(-3), "0.001");
        assert_eq!(decade_label(2), "100");
        assert_eq!(decade_label(5), "1e5");
        assert_eq!(decade_label(-4), "1e-4");
        let labels: Vec<String> = Scale::Linear { top: 500.0 }.ticks().into_iter().map(|t| t.1).collect();
        assert_eq!(labels, ["0", "125", "250", "375", "500"]);
    }

    #[test]
    fn a_sensor_map_shows_the_grid_with_j_upward() {
        let values = [0.0, 0.0, 0.0, 500.0];
        let grid = Grid { nx: 2, ny: 2, values: &values, rows: Rows::Upward };
        let stats = Stats::of(&values);
        let look = Look {
            scale: Scale::linear_to(stats.max),
            map: ColourMap::Viridis,
            unit: "lx",
            heading: Some(("desk illuminance".into(), stats.line("lx"))),
            cell: 220,
            background: WHITE,
            text: BLACK,
            text_scale: 1,
        };
        let c = draw(&grid, &look);
        // Cell (1, 1) is top right: 500 lx = the top of the scale; (0, 0) bottom left is 0.
        assert_eq!(c.get(16 + 330, 40 + 110), viridis(1.0));
        assert_eq!(c.get(16 + 110, 40 + 330), viridis(0.0));
        assert_eq!((stats.mean, stats.min, stats.max, stats.uniformity), (125.0, 0.0, 500.0, 0.0));
        assert_eq!(stats.line("lx"), "MEAN 125 LX  MIN 0  MAX 500  U0 0.00");
    }

    #[test]
    fn a_luminance_image_keeps_its_pixels_and_gains_a_legend() {
        let lum: Vec<f64> = (0..64 * 48).map(|i| if i == 0 { 0.0 } else { f64::from(i) }).collect();
        let scale = Scale::log_decades_for(&lum);
        let grid = Grid { nx: 64, ny: 48, values: &lum, rows: Rows::Downward };
        let look = Look {
            scale,
            map: ColourMap::Ramp,
            unit: "cd/m2",
            heading: None,
            cell: 1,
            background: BLACK,
            text: WHITE,
            text_scale: 1,
        };
        let c = draw(&grid, &look);
        assert!(c.width > 64 && c.height >= 48);
        assert_eq!(c.get(0, 0), BLACK, "black stays black");
        assert_eq!(c.get(63, 47), ramp(scale.t(lum[47 * 64 + 63]).unwrap()));
        // The legend has the white unit text somewhere right of the image.
        assert!((0..c.height).any(|y| (64..c.width).any(|x| c.get(x, y) == WHITE)));
    }
}
