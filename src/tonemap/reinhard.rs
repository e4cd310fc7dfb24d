//! Reinhard, Stark, Shirley & Ferwerda (2002): the global photographic operator with a white
//! point.
//!
//! The key of the scene is the log-average luminance L̄_w = exp(mean ln L_w) (Eq. 1); the scaled
//! luminance L = (a / L̄_w) L_w with key value a = 0.18 (Eq. 2, "middle grey"); the display
//! luminance (Eq. 4)
//!
//! L_d = L (1 + L / L_white²) / (1 + L),
//!
//! with L_white the smallest scaled luminance mapped to white, by default the largest in the
//! image (the paper's choice), so L_d(L_white) = 1. Low luminances are kept (L_d → L as L → 0),
//! high ones compressed by about 1/L.
//!
//! Black pixels are left out of the log-average (the paper adds a small δ to each L_w instead);
//! with them left out the operator is exactly invariant under scaling the scene: L depends only
//! on L_w / L̄_w.
//!
//! # References
//! - E. Reinhard, M. Stark, P. Shirley, J. Ferwerda (2002), "Photographic Tone Reproduction for
//!   Digital Images", ACM Transactions on Graphics 21(3) (SIGGRAPH 2002), 267–276, §3.1.

use super::{Display, ToneCurve};

/// The key value a: the scaled luminance of the log-average scene luminance.
pub const KEY: f64 = 0.18;

/// Eq. 4 with the scale a / L̄_w.
#[derive(Clone, Copy, Debug)]
pub struct ReinhardCurve {
    /// a / L̄_w, per cd m⁻².
    pub scale: f64,
    /// L_white² (scaled units).
    pub white_squared: f64,
}

impl ReinhardCurve {
    /// The curve for an image with pixel luminances `luminance` (cd m⁻²).
    pub fn new(luminance: &[f64]) -> ReinhardCurve {
        let scale = log_average(luminance).map_or(1.0, |avg| KEY / avg);
        let white = luminance.iter().copied().fold(0.0, f64::max) * scale;
        let white = if white > 0.0 && white.is_finite() { white } else { 1.0 };
        ReinhardCurve { scale, white_squared: white * white }
    }
}

impl ToneCurve for ReinhardCurve {
    fn display(&self, luminance: f64, _rod: f64) -> Display {
        let l = self.scale * luminance.max(0.0);
        Display { y: l * (1.0 + l / self.white_squared) / (1.0 + l), rod_fraction: 0.0 }
    }
}

/// exp(mean ln L) over the positive finite luminances, if there are any.
pub fn log_average(luminance: &[f64]) -> Option<f64> {
    let (sum, n) =
        luminance.iter().filter(|l| l.is_finite() && **l > 0.0).fold((0.0, 0usize), |(s, n), l| (s + l.ln(), n + 1));
    (n > 0).then(|| (sum / n as f64).exp())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ramp() -> Vec<f64> {
        (0..300).map(|i| 10f64.powf(-2.0 + f64::from(i) / 50.0)).collect()
    }

    #[test]
    fn monotone_white_at_the_maximum_and_identity_for_dim_values() {
        let lum = ramp();
        let c = ReinhardCurve::new(&lum);
        let y: Vec<f64> = lum.iter().map(|&l| c.display(l, 0.0).y).collect();
        assert!(y.windows(2).all(|p| p[1] > p[0]));
        assert!((y[y.len() - 1] - 1.0).abs() < 1e-12, "the maximum maps to white");
        // L_d / L → 1 as L → 0 (the paper: low luminances are scaled by 1).
        let tiny = 1e-6 / c.scale;
        assert!((c.display(tiny, 0.0).y / (c.scale * tiny) - 1.0).abs() < 1e-5);
        // The log-average maps to L_d = 0.18 (1 + 0.18/L_white²)/1.18.
        let avg = log_average(&lum).unwrap();
        let want = KEY * (1.0 + KEY / c.white_squared) / (1.0 + KEY);
        assert!((c.display(avg, 0.0).y - want).abs() < 1e-12);
    }

    #[test]
    fn invariant_under_scaling_the_scene() {
        let lum = ramp();
        let a = ReinhardCurve::new(&lum);
        let scaled: Vec<f64> = lum.iter().map(|l| 37.5 * l).collect();
        let b = ReinhardCurve::new(&scaled);
        for &l in &lum {
            assert!((a.display(l, 0.0).y - b.display(37.5 * l, 0.0).y).abs() < 1e-12);
        }
        // Black pixels do not change the key.
        let mut with_black = lum.clone();
        with_black.extend([0.0; 50]);
        assert!((ReinhardCurve::new(&with_black).scale - a.scale).abs() < 1e-15);
        assert_eq!(log_average(&[0.0, -1.0]), None);
    }
}
