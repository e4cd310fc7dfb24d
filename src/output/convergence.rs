//! The convergence plot (`morgana render --convergence conv.png`): the relative standard error
//! of the target's mean after each progressive pass against the elapsed time, on log-log axes,
//! with the least-squares line of [`crate::render::progressive::fit`] and its slope printed.
//! For consistent progressive photon mapping the error falls as a power of the time, slope
//! about −α/2 once the passes take equal time (the noise variance of the average falls as
//! N^(−α), Knaus & Zwicker 2011); a flatter slope means the error is not falling as it should.

use crate::raster::log_axes::{axes, decades};
use crate::raster::{BLACK, Canvas, GREY, Rgb, WHITE};
use crate::render::progressive::ProgressiveReport;

const WIDTH: i64 = 640;
const HEIGHT: i64 = 440;
const BLUE: Rgb = [30, 70, 200];
const RED: Rgb = [200, 30, 30];

/// The plot of `report`'s history.
pub fn figure(report: &ProgressiveReport) -> Canvas {
    let mut c = Canvas::new(WIDTH as usize, HEIGHT as usize, WHITE);
    let pts: Vec<(f64, f64)> = report
        .history
        .iter()
        .filter_map(|r| r.rel_error.map(|e| (r.elapsed_s, e)))
        .filter(|(t, e)| *t > 0.0 && *e > 0.0 && t.is_finite() && e.is_finite())
        .collect();
    let title = format!("RELATIVE STANDARD ERROR OF THE {} MEAN AFTER EACH PASS", report.target.to_uppercase());
    c.text(12, 10, &title, 1, BLACK);
    let (left, right, top, bottom) = (74, WIDTH - 20, 64, HEIGHT - 48);
    let (xa, xb) = decades(pts.iter().map(|p| p.0));
    let (ya, yb) = decades(pts.iter().map(|p| p.1));
    let map = |(x, y): (f64, f64)| {
        let fx = (x.log10() - f64::from(xa)) / f64::from(xb - xa);
        let fy = (y.log10() - f64::from(ya)) / f64::from(yb - ya);
        (left as f64 + fx * (right - left) as f64, bottom as f64 - fy * (bottom - top) as f64)
    };
    axes(&mut c, (left, right, top, bottom), (xa, xb), (ya, yb), &map);
    c.text(left - 60, top - 14, "RELATIVE STANDARD ERROR", 1, BLACK);
    let x_label = "ELAPSED TIME (S)";
    c.text((left + right - Canvas::text_width(x_label, 1)) / 2, bottom + 26, x_label, 1, BLACK);
    let fit_line = match report.convergence_fit {
        Some(f) => {
            let (t0, t1) = (pts.first().map_or(1.0, |p| p.0), pts.last().map_or(1.0, |p| p.0));
            let at = |t: f64| (t, (f.intercept + f.slope * t.ln()).exp());
            c.line(map(at(t0)), map(at(t1)), 2, RED);
            format!("SLOPE {:.3} (LEAST SQUARES, {} PASSES)", f.slope, f.points)
        }
        None => format!("{} POINTS: TOO FEW TO FIT A SLOPE", pts.len()),
    };
    c.text(12, 28, &fit_line, 2, if report.convergence_fit.is_some() { RED } else { GREY });
    for p in &pts {
        let (x, y) = map(*p);
        c.fill_rect(x as i64 - 2, y as i64 - 2, 5, 5, BLUE);
    }
    c
}
