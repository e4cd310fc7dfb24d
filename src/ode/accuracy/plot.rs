//! The figure of `morgana accuracy`, on the crate's raster canvas: three log-log panels —
//! (a) Dormand–Prince endpoint error against tolerance and (b) its time against tolerance
//! (the two curves of the paper's Fig. 1), and (c) error against time for all three methods
//! (a work–precision diagram, where equal-error speedups are horizontal distances).

use super::Report;
use crate::raster::log_axes::{axes, decades};
use crate::raster::{BLACK, Canvas, GREY, Rgb, WHITE};

const PANEL_W: i64 = 440;
const PANEL_H: i64 = 400;
const TOP: i64 = 28;
const RED: Rgb = [200, 30, 30];
const BLUE: Rgb = [30, 70, 200];
const GREEN: Rgb = [20, 140, 40];

/// One curve.
struct Series {
    name: &'static str,
    colour: Rgb,
    points: Vec<(f64, f64)>,
}

/// One log-log panel.
struct Panel {
    title: &'static str,
    x_label: &'static str,
    y_label: &'static str,
    series: Vec<Series>,
}

/// The three panels of `report`.
pub fn figure(report: &Report) -> Canvas {
    let of = |m: &str, f: &dyn Fn(&super::Point) -> (f64, f64)| -> Vec<(f64, f64)> {
        report.points.iter().filter(|p| p.method == m).map(f).collect()
    };
    let dp_err = of("dopri5", &|p| (p.parameter, p.endpoint_error_m));
    let tol_line: Vec<(f64, f64)> = dp_err.iter().map(|(t, _)| (*t, *t)).collect();
    let panels = [
        Panel {
            title: "(A) DOPRI5 ERROR VS TOLERANCE",
            x_label: "TOLERANCE",
            y_label: "ENDPOINT ERROR (M)",
            series: vec![
                Series { name: "DOPRI5", colour: RED, points: dp_err },
                Series { name: "ERROR = TOL", colour: GREY, points: tol_line },
            ],
        },
        Panel {
            title: "(B) DOPRI5 TIME VS TOLERANCE",
            x_label: "TOLERANCE",
            y_label: "TIME PER RAY (S)",
            series: vec![Series { name: "DOPRI5", colour: RED, points: of("dopri5", &|p| (p.parameter, p.time_s)) }],
        },
        Panel {
            title: "(C) TIME VS ERROR",
            x_label: "ENDPOINT ERROR (M)",
            y_label: "TIME PER RAY (S)",
            series: ["dopri5", "rk4", "euler"]
                .into_iter()
                .zip([("DOPRI5", RED), ("RK4", BLUE), ("EULER", GREEN)])
                .map(|(m, (name, colour))| Series { name, colour, points: of(m, &|p| (p.endpoint_error_m, p.time_s)) })
                .collect(),
        },
    ];
    let mut c = Canvas::new(3 * PANEL_W as usize, (PANEL_H + TOP) as usize, WHITE);
    c.text(10, 8, &report.title, 2, BLACK);
    for (i, panel) in panels.iter().enumerate() {
        draw(&mut c, i as i64 * PANEL_W, TOP, panel);
    }
    c
}

/// Draws `panel` with its top-left corner at (x0, y0).
fn draw(c: &mut Canvas, x0: i64, y0: i64, panel: &Panel) {
    let (left, right, top, bottom) = (x0 + 62, x0 + PANEL_W - 14, y0 + 44, y0 + PANEL_H - 44);
    let all = || panel.series.iter().flat_map(|s| s.points.iter());
    let (xa, xb) = decades(all().map(|p| p.0));
    let (ya, yb) = decades(all().map(|p| p.1));
    let map = |(x, y): (f64, f64)| {
        let fx = (x.log10() - xa as f64) / (xb - xa) as f64;
        let fy = (y.log10() - ya as f64) / (yb - ya) as f64;
        (left as f64 + fx * (right - left) as f64, bottom as f64 - fy * (bottom - top) as f64)
    };
    axes(c, (left, right, top, bottom), (xa, xb), (ya, yb), &map);
    c.text(x0 + 10, y0 + 8, panel.title, 1, BLACK);
    c.text(left - 40, top - 14, panel.y_label, 1, BLACK);
    let xl = Canvas::text_width(panel.x_label, 1);
    c.text((left + right - xl) / 2, bottom + 26, panel.x_label, 1, BLACK);
    for (k, s) in panel.series.iter().enumerate() {
        let mut pts: Vec<(f64, f64)> = s.points.iter().filter(|p| p.0 > 0.0 && p.1 > 0.0).copied().collect();
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
        let px: Vec<(f64, f64)> = pts.iter().map(|p| map(*p)).collect();
        c.polyline(&px, if s.colour == GREY { 1 } else { 2 }, s.colour);
        if s.colour != GREY {
            for (x, y) in &px {
                c.fill_rect(*x as i64 - 2, *y as i64 - 2, 5, 5, s.colour);
            }
        }
        let ly = top + 6 + 12 * k as i64;
        c.fill_rect(right - 110, ly + 2, 16, 3, s.colour);
        c.text(right - 88, ly, s.name, 1, BLACK);
    }
}
