//! Global exposure: a camera, not an eye. Display luminance y = s · L (1 = display white).
//!
//! - [`Exposure::Ev`]: s = 2^ev / (1 cd m⁻²): an image whose luminances are already in display
//!   range (0–1 cd m⁻² in morgana's absolute units) is shown unchanged at ev = 0.
//! - [`Exposure::Auto`]: s = 1 / L₉₉, with L₉₉ the 99th percentile (nearest rank) of the pixel
//!   luminances, so 1 % of the pixels clip; s = 1 for a black image. Scaling the scene by k
//!   scales L₉₉ by k, so the displayed image does not change.
//!
//! The same rule as the PNG preview of [`super::preview`].

use super::preview::AUTO_PERCENTILE;
pub use super::preview::Exposure;
use super::{Display, ToneCurve};

/// y = scale · L.
#[derive(Clone, Copy, Debug)]
pub struct ExposureCurve {
    /// Display luminance per scene luminance, (cd m⁻²)⁻¹.
    pub scale: f64,
}

impl ExposureCurve {
    /// The curve for `exposure` over the pixel luminances `luminance` (cd m⁻²).
    pub fn new(exposure: Exposure, luminance: &[f64]) -> ExposureCurve {
        let scale = match exposure {
            Exposure::Ev(ev) => Some(ev.exp2()).filter(|s| s.is_finite() && *s > 0.0).unwrap_or(1.0),
            Exposure::Auto => {
                let p = percentile(luminance, AUTO_PERCENTILE);
                if p > 0.0 { 1.0 / p } else { 1.0 }
            }
        };
        ExposureCurve { scale }
    }
}

impl ToneCurve for ExposureCurve {
    fn display(&self, luminance: f64, _rod: f64) -> Display {
        Display { y: self.scale * luminance, rod_fraction: 0.0 }
    }
}

/// The nearest-rank `q` quantile of `values` (0 when empty).
pub fn percentile(values: &[f64], q: f64) -> f64 {
    if values.is_empty() {
        return 0.0;
    }
    let mut v = values.to_vec();
    let rank = ((q * v.len() as f64).ceil() as usize).clamp(1, v.len());
    let (_, p, _) = v.select_nth_unstable_by(rank - 1, f64::total_cmp);
    *p
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ev_zero_is_the_identity_and_auto_is_scale_invariant() {
        let lum: Vec<f64> = (1..=200).map(|i| f64::from(i) / 400.0).collect();
        let id = ExposureCurve::new(Exposure::Ev(0.0), &lum);
        assert!(lum.iter().all(|&l| id.display(l, 0.0).y == l));
        assert_eq!(ExposureCurve::new(Exposure::Ev(-1.0), &lum).scale, 0.5);
        let a = ExposureCurve::new(Exposure::Auto, &lum);
        let scaled: Vec<f64> = lum.iter().map(|l| 1e4 * l).collect();
        let b = ExposureCurve::new(Exposure::Auto, &scaled);
        for &l in &lum {
            assert!((a.display(l, 0.0).y - b.display(1e4 * l, 0.0).y).abs() < 1e-12);
        }
        // p99 of 1..200 (nearest rank) is the 198th value.
        assert!((a.scale - 400.0 / 198.0).abs() < 1e-9);
        assert_eq!(ExposureCurve::new(Exposure::Auto, &[0.0; 4]).scale, 1.0);
    }
}
