//! Ward Larson, Rushmeier & Piatko (1997): histogram adjustment with a visibility ceiling.
//!
//! World brightness is B_w = ln L_w. A histogram f(b_i) of B_w over the foveal samples (the
//! 1° local adaptation luminances, [`super::foveal`]) has N = 100 bins of width Δb between the
//! smallest and the largest pixel luminance (extended by half a bin each way; luminances below
//! 10⁻⁷ cd m⁻² count as 10⁻⁷). Its cumulative distribution P(b) = Σ_{b_i < b} f(b_i) / T,
//! T = Σ f(b_i), maps world brightness to display brightness (Eq. 4):
//!
//! B_d = ln L_dmin + (ln L_dmax − ln L_dmin) P(B_w).
//!
//! Plain histogram equalisation would exaggerate contrast where the histogram is dense. The
//! ceiling (Eq. 5 with the linear ceiling, Eq. 9 with the human one) limits the slope
//! dL_d/dL_w to what the eye would see: by the linear ceiling dL_d/dL_w ≤ L_d/L_w (no contrast
//! is enlarged), by the human ceiling dL_d/dL_w ≤ ΔL_t(L_d)/ΔL_t(L_w) (a difference just visible
//! in the world is at most just visible on the display; ΔL_t is [`super::threshold`]). As a
//! bound on the histogram this reads
//!
//! f(b_i) ≤ c(b_i) · T Δb / (ln L_dmax − ln L_dmin),
//! c = 1 (linear) or c = ΔL_t(L_d) L_w / (ΔL_t(L_w) L_d) (human),
//!
//! and is enforced by the paper's iteration: clip every bin to its ceiling, recompute T and the
//! ceilings, and repeat; if T drops below 2.5 % of the original count, no compression is needed
//! and the map is linear (below). The paper stops once a pass clips less than 2.5 % of the
//! *original* count, which can leave the final histogram far above its ceilings once T has
//! shrunk; here a pass must clip less than 2.5 % of the *current* T, and the cumulative
//! distribution is rebuilt from the final histogram, so each bin's slope is within 1/0.975 of its
//! ceiling (up to the small change of the ceilings with the last rebuild).
//!
//! When the scene's brightness range fits the display's (ln L_max − ln L_min ≤ ln L_dmax −
//! ln L_dmin) the paper maps linearly: L_d = s L_w with s = ΔL_t(L_dm)/ΔL_t(L_wa) (human; Ward
//! 1994's contrast-preserving scale) or s = L_dm/L_wa (linear), L_dm = √(L_dmin L_dmax) and
//! L_wa the log-average of the foveal samples. The displayed pixel is L_d / L_dmax for the linear
//! map and (L_d − L_dmin)/(L_dmax − L_dmin) for the adjusted histogram.
//!
//! The display has L_dmax = 100 cd m⁻² and a 32:1 range (L_dmin = 3.125 cd m⁻²), the defaults
//! of the first author's implementation (Radiance `pcond`). Veiling glare (§5.1) is not
//! simulated; acuity and colour sensitivity are applied before this operator ([`super::acuity`],
//! [`super::mesopic`]).
//!
//! With the linear ceiling the operator depends only on ratios of luminances, so it is
//! invariant under scaling the scene; the human ceiling is not (a dim scene looks dim).
//!
//! # References
//! - G. Ward Larson, H. Rushmeier, C. Piatko (1997), "A Visibility Matching Tone Reproduction
//!   Operator for High Dynamic Range Scenes", IEEE TVCG 3(4), 291–306, §3–4.
//! - G. Ward (1994), "A contrast-based scalefactor for luminance display", Graphics Gems IV,
//!   415–421.

use super::foveal::FovealImage;
use super::threshold::threshold_cd_m2;
use super::{Display, ToneCurve};

/// Number of histogram bins.
pub const BINS: usize = 100;
/// The fraction of the count that may be clipped in the last pass.
pub const TRIM_TOLERANCE: f64 = 0.025;
/// Luminances below this count as this, cd m⁻².
pub const MIN_LUMINANCE_CD_M2: f64 = 1e-7;

/// The operator's parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WardHistogram {
    /// Display white L_dmax, cd m⁻².
    pub display_max_cd_m2: f64,
    /// L_dmax / L_dmin.
    pub display_range: f64,
    /// The human (true) or the linear (false) ceiling.
    pub human_ceiling: bool,
}

impl Default for WardHistogram {
    fn default() -> Self {
        WardHistogram { display_max_cd_m2: 100.0, display_range: 32.0, human_ceiling: true }
    }
}

/// How world luminance becomes display luminance.
#[derive(Clone, Debug)]
pub enum WardMapping {
    /// L_d = scale · L_w.
    Linear {
        /// Display luminance per world luminance.
        scale: f64,
    },
    /// The adjusted histogram: `counts` per bin from `b_min` in steps of `bin_width`, and its
    /// cumulative distribution at the bin edges.
    Adjusted {
        /// World brightness ln L_w at the lower edge of the first bin.
        b_min: f64,
        /// Bin width Δb in ln L_w.
        bin_width: f64,
        /// Count of each bin after clipping to the ceiling.
        counts: Vec<f64>,
        /// Cumulative distribution P(b) at the bin edges (one more than `counts`).
        cumulative: Vec<f64>,
    },
}

/// The prepared operator.
#[derive(Clone, Debug)]
pub struct WardCurve {
    /// Linear map or adjusted histogram.
    pub mapping: WardMapping,
    /// Display black L_dmin, cd m⁻².
    pub ld_min: f64,
    /// Display white L_dmax, cd m⁻².
    pub ld_max: f64,
    /// The human (true) or the linear (false) ceiling.
    pub human_ceiling: bool,
}

impl WardHistogram {
    /// Prepares the map from the foveal image and the pixel luminances (for the extremes).
    pub fn curve(&self, foveal: &FovealImage, luminance: &[f64]) -> WardCurve {
        let ld_max = self.display_max_cd_m2;
        let ld_min = ld_max / self.display_range;
        let mut curve = WardCurve {
            mapping: WardMapping::Linear { scale: 1.0 },
            ld_min,
            ld_max,
            human_ceiling: self.human_ceiling,
        };
        let samples: Vec<f64> = foveal.luminance.iter().map(|&l| clamp_low(l).ln()).collect();
        let b_avg = samples.iter().sum::<f64>() / samples.len().max(1) as f64;
        let (lo, hi) =
            luminance.iter().chain(&foveal.luminance).fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &l| {
                let l = clamp_low(l).ln();
                (a.min(l), b.max(l))
            });
        let display_span = (ld_max / ld_min).ln();
        if hi - lo <= display_span {
            curve.mapping = WardMapping::Linear { scale: curve.linear_scale(b_avg.exp()) };
            return curve;
        }
        let bin_width = (hi - lo) / (BINS - 1) as f64;
        let b_min = lo - 0.5 * bin_width;
        let mut counts = vec![0.0; BINS];
        for b in &samples {
            counts[(((b - b_min) / bin_width) as usize).min(BINS - 1)] += 1.0;
        }
        match curve.adjust(counts, b_min, bin_width, samples.len() as f64) {
            Some(m) => curve.mapping = m,
            None => curve.mapping = WardMapping::Linear { scale: curve.linear_scale(b_avg.exp()) },
        }
        curve
    }
}

impl WardCurve {
    /// The linear scale for world adaptation luminance `l_wa`.
    fn linear_scale(&self, l_wa: f64) -> f64 {
        let l_dm = (self.ld_min * self.ld_max).sqrt();
        if self.human_ceiling { threshold_cd_m2(l_dm) / threshold_cd_m2(l_wa) } else { l_dm / l_wa }
    }

    /// The ceiling factor c at world luminance `l_w` shown as `l_d`.
    pub fn ceiling_factor(&self, l_w: f64, l_d: f64) -> f64 {
        if self.human_ceiling { threshold_cd_m2(l_d) * l_w / (threshold_cd_m2(l_w) * l_d) } else { 1.0 }
    }

    /// The paper's clipping iteration; `None` when no compression is needed.
    fn adjust(&self, mut counts: Vec<f64>, b_min: f64, bin_width: f64, total: f64) -> Option<WardMapping> {
        let span = (self.ld_max / self.ld_min).ln();
        for _ in 0..1000 {
            let cumulative = cumulative(&counts);
            let t: f64 = counts.iter().sum();
            if t <= total * TRIM_TOLERANCE {
                return None;
            }
            let mut trimmed = 0.0;
            for (i, c) in counts.iter_mut().enumerate() {
                let l_w = (b_min + (i as f64 + 0.5) * bin_width).exp();
                let p = 0.5 * (cumulative[i] + cumulative[i + 1]);
                let l_d = self.ld_min * (span * p).exp();
                let ceiling = self.ceiling_factor(l_w, l_d) * t * bin_width / span;
                if *c > ceiling {
                    trimmed += *c - ceiling;
                    *c = ceiling;
                }
            }
            if trimmed <= t * TRIM_TOLERANCE {
                break;
            }
        }
        let cumulative = cumulative(&counts);
        Some(WardMapping::Adjusted { b_min, bin_width, counts, cumulative })
    }

    /// Display luminance L_d (cd m⁻²) of world luminance `l_w`.
    pub fn display_luminance(&self, l_w: f64) -> f64 {
        match &self.mapping {
            WardMapping::Linear { scale } => scale * l_w.max(0.0),
            WardMapping::Adjusted { b_min, bin_width, cumulative, .. } => {
                let x = (clamp_low(l_w).ln() - b_min) / bin_width;
                let p = if x <= 0.0 {
                    0.0
                } else if x >= BINS as f64 {
                    1.0
                } else {
                    let i = x as usize;
                    let t = x - i as f64;
                    (1.0 - t) * cumulative[i] + t * cumulative[i + 1]
                };
                self.ld_min * ((self.ld_max / self.ld_min).ln() * p).exp()
            }
        }
    }
}

impl ToneCurve for WardCurve {
    fn display(&self, luminance: f64, _rod: f64) -> Display {
        let l_d = self.display_luminance(luminance);
        let y = match self.mapping {
            WardMapping::Linear { .. } => l_d / self.ld_max,
            WardMapping::Adjusted { .. } => (l_d - self.ld_min) / (self.ld_max - self.ld_min),
        };
        Display { y, rod_fraction: 0.0 }
    }
}

fn clamp_low(l: f64) -> f64 {
    if l.is_finite() { l.max(MIN_LUMINANCE_CD_M2) } else { MIN_LUMINANCE_CD_M2 }
}

/// P at the bin edges: P_0 = 0, P_i = Σ_{j<i} f_j / T, P_N = 1.
fn cumulative(counts: &[f64]) -> Vec<f64> {
    let t: f64 = counts.iter().sum();
    let mut out = Vec::with_capacity(counts.len() + 1);
    let mut s = 0.0;
    out.push(0.0);
    for c in counts {
        s += c;
        out.push(if t > 0.0 { s / t } else { 0.0 });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tonemap::scene_image::SceneImage;

    /// A 120×90 image, seen with a 40° field of view: a room whose luminance grows smoothly from
    /// 0.01 to 10⁴ cd m⁻² across the diagonal, a window at 2000 cd m⁻² and a small lamp at
    /// 5·10⁴ cd m⁻².
    fn room(scale: f64) -> (FovealImage, Vec<f64>) {
        let (w, h) = (120, 90);
        let xyz = (0..w * h)
            .map(|i| {
                let (x, y) = (i % w, i / w);
                let l = if x > 90 && y < 40 {
                    2000.0
                } else if (10..13).contains(&x) && (5..8).contains(&y) {
                    5e4
                } else {
                    0.01 * 10f64.powf(6.0 * (x + y) as f64 / 210.0)
                };
                [0.0, l * scale, 0.0]
            })
            .collect();
        let img = SceneImage::from_xyz(w, h, xyz).unwrap();
        (FovealImage::new(&img, 40.0), img.luminances())
    }

    #[test]
    fn monotone_in_luminance() {
        let (fov, lum) = room(1.0);
        for human in [true, false] {
            let c = WardHistogram { human_ceiling: human, ..Default::default() }.curve(&fov, &lum);
            assert!(matches!(c.mapping, WardMapping::Adjusted { .. }));
            let mut last = -1.0;
            for i in 0..=800 {
                let y = c.display(10f64.powf(-3.0 + f64::from(i) / 100.0), 0.0).y;
                assert!(y >= last - 1e-12 && (0.0..=1.0).contains(&y), "at step {i}: {y} after {last}");
                last = y;
            }
        }
    }

    #[test]
    fn the_adjusted_histogram_is_within_its_ceiling() {
        let (fov, lum) = room(1.0);
        for human in [true, false] {
            let c = WardHistogram { human_ceiling: human, ..Default::default() }.curve(&fov, &lum);
            let WardMapping::Adjusted { b_min, bin_width, counts, cumulative } = &c.mapping else {
                panic!("expected histogram adjustment");
            };
            let span = (c.ld_max / c.ld_min).ln();
            let t: f64 = counts.iter().sum();
            for (i, f) in counts.iter().enumerate() {
                // The slope of the final map over bin i, dB_d/dB_w, against its ceiling c.
                let slope = span * (cumulative[i + 1] - cumulative[i]) / bin_width;
                assert!((slope - span * f / (t * bin_width)).abs() < 1e-9);
                let l_w = (b_min + (i as f64 + 0.5) * bin_width).exp();
                let l_d = c.display_luminance(l_w);
                let ceiling = c.ceiling_factor(l_w, l_d);
                assert!(
                    slope <= ceiling / (1.0 - TRIM_TOLERANCE) + 1e-9,
                    "human {human}, bin {i}: {slope} > {ceiling}"
                );
            }
        }
    }

    #[test]
    fn linear_ceiling_is_scale_invariant_and_human_one_is_not() {
        let (fov, lum) = room(1.0);
        let (fov_dim, lum_dim) = room(1e-3);
        let linear = WardHistogram { human_ceiling: false, ..Default::default() };
        let (a, b) = (linear.curve(&fov, &lum), linear.curve(&fov_dim, &lum_dim));
        for &l in lum.iter().step_by(37) {
            assert!((a.display(l, 0.0).y - b.display(1e-3 * l, 0.0).y).abs() < 1e-9, "at {l}");
        }
        let human = WardHistogram::default();
        let (a, b) = (human.curve(&fov, &lum), human.curve(&fov_dim, &lum_dim));
        // The median pixel of the dim scene is shown darker.
        let median = |c: &WardCurve, s: f64| {
            let y: Vec<f64> = lum.iter().map(|l| c.display(s * l, 0.0).y).collect();
            crate::tonemap::exposure::percentile(&y, 0.5)
        };
        let (bright, dim) = (median(&a, 1.0), median(&b, 1e-3));
        assert!(dim < 0.5 * bright, "a scene 1000× dimmer must look darker: {dim} vs {bright}");
    }

    #[test]
    fn a_scene_within_display_range_maps_linearly() {
        // 2 to 20 cd m⁻²: a 10:1 range fits the 32:1 display, so the map is a pure scale.
        let xyz: Vec<[f64; 3]> = (0..400).map(|i| [0.0, 2.0 + 18.0 * f64::from(i % 20) / 19.0, 0.0]).collect();
        let img = SceneImage::from_xyz(20, 20, xyz).unwrap();
        let fov = FovealImage::new(&img, 40.0);
        for human in [true, false] {
            let c = WardHistogram { human_ceiling: human, ..Default::default() }.curve(&fov, &img.luminances());
            let WardMapping::Linear { scale } = c.mapping else { panic!("expected a linear map") };
            for l in [2.0, 7.0, 20.0] {
                assert!((c.display(l, 0.0).y - scale * l / 100.0).abs() < 1e-12);
            }
        }
    }
}
