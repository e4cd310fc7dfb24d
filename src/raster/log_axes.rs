//! Log-log plot axes: the decade range that covers a set of values, and a frame with a decade
//! grid and tick labels ("1E-3"). Shared by `morgana accuracy`'s figure and the convergence plot.

use super::{BLACK, Canvas, LIGHT_GREY};

/// Decade range [lo, hi] (exponents) covering the positive finite values.
pub fn decades(values: impl Iterator<Item = f64>) -> (i32, i32) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.filter(|v| *v > 0.0 && v.is_finite()) {
        lo = lo.min(v.log10());
        hi = hi.max(v.log10());
    }
    if !lo.is_finite() {
        return (0, 1);
    }
    let (a, b) = (lo.floor() as i32, hi.ceil() as i32);
    if a == b { (a, a + 1) } else { (a, b) }
}

/// Frame (left, right, top, bottom), decade grid and tick labels for decades `xa..=xb` and
/// `ya..=yb`; `map` takes a data point to the canvas.
pub fn axes(
    c: &mut Canvas,
    (l, r, t, b): (i64, i64, i64, i64),
    (xa, xb): (i32, i32),
    (ya, yb): (i32, i32),
    map: &dyn Fn((f64, f64)) -> (f64, f64),
) {
    let every = |a: i32, z: i32| if z - a > 8 { 2 } else { 1 };
    for e in xa..=xb {
        let (x, _) = map((10f64.powi(e), 10f64.powi(ya)));
        c.line((x, t as f64), (x, b as f64), 1, LIGHT_GREY);
        if (e - xa) % every(xa, xb) == 0 {
            let label = format!("1E{e}");
            c.text(x as i64 - Canvas::text_width(&label, 1) / 2, b + 6, &label, 1, BLACK);
        }
    }
    for e in ya..=yb {
        let (_, y) = map((10f64.powi(xa), 10f64.powi(e)));
        c.line((l as f64, y), (r as f64, y), 1, LIGHT_GREY);
        if (e - ya) % every(ya, yb) == 0 {
            let label = format!("1E{e}");
            c.text(l - 6 - Canvas::text_width(&label, 1), y as i64 - 3, &label, 1, BLACK);
        }
    }
    for (p, q) in [((l, t), (r, t)), ((r, t), (r, b)), ((r, b), (l, b)), ((l, b), (l, t))] {
        c.line((p.0 as f64, p.1 as f64), (q.0 as f64, q.1 as f64), 1, BLACK);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decades_cover_the_positive_values() {
        assert_eq!(decades([0.02, 3.0, -1.0, 0.0, f64::NAN].into_iter()), (-2, 1));
        assert_eq!(decades([10.0].into_iter()), (1, 2));
        assert_eq!(decades(std::iter::empty()), (0, 1));
    }
}
