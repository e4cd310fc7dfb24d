//! Adaptive sampling across progressive passes (`[integrator] adaptive = true`, `--adaptive`):
//! from the second pass on, each pass spends the eye samples of a uniform pass,
//! B = spp · width · height, where they take the most squared error out of the image.
//!
//! **The estimate stays the average of the passes.** Pass i's value of pixel p is the mean of
//! its n_{p,i} samples, x_{p,i}, and the image is x̄_p = (1/N) Σᵢ x_{p,i}, as without adaptive
//! sampling. The counts n_{p,i} are fixed before pass i from the passes before it, and pass i
//! traces fresh photon maps and fresh samples, so E[x_{p,i} | passes before i] is what a
//! uniform pass i gives: the average has the expectation of the uniform one (its only bias is
//! that of the gather radii, which the passes shrink), and the passes' deviations stay
//! uncorrelated, so the pass-to-pass estimate s²/N of [`super::progressive::Welford`] still
//! estimates the variance of the average, now that the passes' variances differ:
//! E[s²/N] = (1/N²) Σᵢ Var x_{p,i} + (spread of the passes' biases)/(N(N − 1)).
//! Weighting the passes by their sample counts instead — the mean over all of a pixel's
//! samples — would be biased: the later counts depend on the earlier values, so a pixel whose
//! first samples missed a glint draws few more and keeps its dark first value at full weight
//! (Kirk & Arvo 1991).
//!
//! **Where the samples go.** Within a pass the image's expected squared error is
//! Σ_p σ_p² / n_p + (what the photon maps add, which eye samples do not change), σ_p² the
//! variance of one sample of pixel p summed over the bands. For a budget Σ_p n_p = B it is
//! least at n_p ∝ σ_p (Neyman 1934); with a floor of one sample per pixel and a cap of
//! [`MAX_FACTOR`] · spp, n_p = clamp(λ σ̃_p, 1, cap) with λ such that Σ_p n_p = B, rounded so
//! that the running sum of the counts follows the running sum of those shares. σ_p² is the
//! pooled variance of the pixel's samples within each pass, over every pass so far
//! (Σ sums of squared deviations / Σ (n − 1)): the noise eye samples can reduce. (The
//! pass-to-pass spread also holds the photon maps' noise, which more eye samples would not
//! reduce.) σ̃_p is σ_p widened to the largest over the pixel and its eight neighbours (a
//! pixel whose samples missed a glint its neighbour saw gets samples too), plus
//! [`DEFENSIVE`] times the image's mean of that (no pixel's share rests on a spread of zero
//! measured from a few samples).
//!
//! The counts are a function of the sums rank 0 holds; it sends them to every rank before the
//! pass, so the image does not depend on the rank count, and the sums are in the checkpoint.
//!
//! # References
//! - B. P. Welford (1962), "Note on a method for calculating corrected sums of squares and
//!   products", Technometrics 4(3), 419–420.
//! - J. Neyman (1934), "On the two different aspects of the representative method", Journal of
//!   the Royal Statistical Society 97(4), 558–625 (optimum allocation).
//! - D. Kirk and J. Arvo (1991), "Unbiased sampling techniques for image synthesis",
//!   SIGGRAPH '91, 153–156.

use super::checkpoint::codec::{Reader, Result as ReadResult, Writer};
use crate::spectrum::MAX_BANDS;
use serde::Serialize;

pub use crate::scene::progressive::ADAPTIVE_MAX_FACTOR as MAX_FACTOR;

/// The share of the image's mean widened spread added to every pixel's.
pub const DEFENSIVE: f64 = 0.1;

/// Bisection steps for λ (each halves the bracket; 100 reach f64 resolution from any start).
const BISECTIONS: u32 = 100;

/// The pooled within-pass spread of every pixel's samples over the passes so far.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Spread {
    /// Σ over passes of the pixel's sum of squared deviations of its samples from their mean,
    /// summed over bands.
    ss: Vec<f64>,
    /// Σ over passes of (samples − 1).
    dof: Vec<u64>,
}

impl Spread {
    /// Adds one pass: each pixel's sum of squared deviations `ss` over its `counts` samples.
    pub fn add(&mut self, ss: &[f32], counts: &[u32]) {
        if self.ss.is_empty() {
            self.ss = vec![0.0; ss.len()];
            self.dof = vec![0; ss.len()];
        }
        for ((s, d), (x, n)) in self.ss.iter_mut().zip(&mut self.dof).zip(ss.iter().zip(counts)) {
            *s += f64::from(x.max(0.0));
            *d += u64::from(n.saturating_sub(1));
        }
    }

    /// Whether no pass was added.
    pub fn is_empty(&self) -> bool {
        self.ss.is_empty()
    }

    /// Each pixel's standard deviation of one sample, √(Σ ss / Σ (n − 1)) (0 without degrees
    /// of freedom).
    pub fn sigma(&self) -> Vec<f64> {
        self.ss.iter().zip(&self.dof).map(|(s, d)| if *d == 0 { 0.0 } else { (s / *d as f64).sqrt() }).collect()
    }

    /// Appends the sums to a checkpoint.
    pub fn save(&self, w: &mut Writer) {
        w.f64s(&self.ss);
        w.f64s(&self.dof.iter().map(|d| *d as f64).collect::<Vec<f64>>());
    }

    /// The sums [`Spread::save`] wrote.
    pub fn load(r: &mut Reader) -> ReadResult<Spread> {
        let ss = r.f64s()?;
        let dof: Vec<u64> = r.f64s()?.into_iter().map(|d| d as u64).collect();
        if dof.len() != ss.len() {
            return Err("the adaptive sampling sums have different lengths".into());
        }
        Ok(Spread { ss, dof })
    }
}

/// The spread of one pixel's samples within a pass, band by band (Welford 1962): each sample's
/// band values are the pixel's estimate from that sample alone.
#[derive(Clone, Debug)]
pub struct PixelSpread {
    bands: usize,
    n: f64,
    mean: [f64; MAX_BANDS],
    m2: [f64; MAX_BANDS],
}

impl PixelSpread {
    /// No samples yet, of `bands` band values each.
    pub fn new(bands: usize) -> PixelSpread {
        PixelSpread { bands: bands.min(MAX_BANDS), n: 0.0, mean: [0.0; MAX_BANDS], m2: [0.0; MAX_BANDS] }
    }

    /// Adds one sample's band values.
    pub fn add(&mut self, x: &[f64; MAX_BANDS]) {
        self.n += 1.0;
        for ((x, m), m2) in x.iter().zip(&mut self.mean).zip(&mut self.m2).take(self.bands) {
            let d = x - *m;
            *m += d / self.n;
            *m2 += d * (x - *m);
        }
    }

    /// The sum over bands of the squared deviations of the samples from their mean.
    pub fn sum_sq(&self) -> f64 {
        self.m2[..self.bands].iter().sum()
    }
}

/// The samples each pixel of a `width` × `height` image gets in the next pass: `spp` each
/// before any pass, else the allocation of the module documentation for the budget
/// spp · width · height.
pub fn counts(spread: &Spread, (width, height): (usize, usize), spp: usize) -> Vec<u32> {
    let n = width * height;
    let uniform = vec![u32::try_from(spp).unwrap_or(u32::MAX); n];
    if spread.is_empty() {
        return uniform;
    }
    let mut sigma = dilate(&spread.sigma(), width, height);
    let mean = sigma.iter().sum::<f64>() / n.max(1) as f64;
    if !(mean > 0.0 && mean.is_finite()) {
        return uniform;
    }
    sigma.iter_mut().for_each(|s| *s += DEFENSIVE * mean);
    allocate(&sigma, (spp * n) as f64, spp.saturating_mul(MAX_FACTOR) as f64)
}

/// Each value replaced by the largest over its 3 × 3 neighbourhood (clipped at the edges).
pub fn dilate(v: &[f64], width: usize, height: usize) -> Vec<f64> {
    let mut out = vec![0.0; v.len()];
    for y in 0..height {
        for x in 0..width {
            let mut m = 0.0f64;
            for yy in y.saturating_sub(1)..(y + 2).min(height) {
                for xx in x.saturating_sub(1)..(x + 2).min(width) {
                    m = m.max(v[yy * width + xx]);
                }
            }
            out[y * width + x] = m;
        }
    }
    out
}

/// Integer counts n_p ≥ 1 summing to `budget` (to within one) with shares
/// clamp(λ σ_p, 1, `cap`), λ found by bisection; every σ_p must be positive and
/// `budget` between the count of values and `cap` times it. Rounded by running sums:
/// n_p = round(Σ_{q ≤ p} r_q) − round(Σ_{q < p} r_q), at least 1.
pub fn allocate(sigma: &[f64], budget: f64, cap: f64) -> Vec<u32> {
    let total = |lambda: f64| sigma.iter().map(|s| (lambda * s).clamp(1.0, cap)).sum::<f64>();
    let smallest = sigma.iter().copied().fold(f64::INFINITY, f64::min);
    let (mut lo, mut hi) = (0.0, cap / smallest);
    for _ in 0..BISECTIONS {
        let mid = 0.5 * (lo + hi);
        if total(mid) < budget {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let mut out = Vec::with_capacity(sigma.len());
    let (mut run, mut given) = (0.0f64, 0i64);
    for s in sigma {
        run += (hi * s).clamp(1.0, cap);
        let now = run.round() as i64;
        let n = (now - given).max(1);
        given += n;
        out.push(n as u32);
    }
    out
}

/// Adaptive sampling as `report.json` records it (`progressive.adaptive`).
#[derive(Clone, Debug, Default, Serialize)]
pub struct AdaptiveReport {
    /// Eye samples a pass spends: spp · width · height.
    pub samples_per_pass: u64,
    /// The most samples a pixel may get in one pass (`MAX_FACTOR` · spp).
    pub max_pixel_samples: u64,
    /// The samples of the last pass run.
    pub last_pass_samples: u64,
    /// The most samples one pixel got in the last pass.
    pub last_pass_most_pixel_samples: u32,
    /// The pixels that got one sample in the last pass.
    pub last_pass_pixels_at_one: u64,
}

impl AdaptiveReport {
    /// The report after a pass with these `counts`, budgeted at `spp` a pixel.
    pub fn of(counts: &[u32], spp: usize) -> AdaptiveReport {
        AdaptiveReport {
            samples_per_pass: (spp * counts.len()) as u64,
            max_pixel_samples: spp.saturating_mul(MAX_FACTOR) as u64,
            last_pass_samples: counts.iter().map(|n| u64::from(*n)).sum(),
            last_pass_most_pixel_samples: counts.iter().copied().max().unwrap_or(0),
            last_pass_pixels_at_one: counts.iter().filter(|n| **n == 1).count() as u64,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_spend_the_budget_in_proportion_to_the_spread_between_floor_and_cap() {
        // σ = 1, 2, 4, 0.01 ×  with budget 40 and cap 20: λ σ for the first three then 1 for the
        // last: λ (1 + 2 + 4) + 1 = 40 → λ = 39/7; shares 5.57, 11.14, 22.3 → capped at 20, so
        // λ (1 + 2) + 20 + 1 = 40 → λ = 19/3: 6.33, 12.67, 20, 1.
        let n = allocate(&[1.0, 2.0, 4.0, 0.01], 40.0, 20.0);
        assert_eq!(n.iter().sum::<u32>(), 40, "{n:?}");
        assert_eq!(n, vec![6, 13, 20, 1]);
        // Equal spreads: the budget evenly.
        assert_eq!(allocate(&[3.0; 5], 20.0, 100.0), vec![4; 5]);
    }

    #[test]
    fn a_uniform_first_pass_and_a_uniform_pass_for_no_spread() {
        let mut s = Spread::default();
        assert_eq!(counts(&s, (3, 2), 4), vec![4; 6]);
        s.add(&[0.0; 6], &[4; 6]);
        assert_eq!(counts(&s, (3, 2), 4), vec![4; 6]);
    }

    #[test]
    fn one_bright_pixel_draws_the_samples_to_itself_and_its_neighbours() {
        // 5 × 5 pixels, 4 samples each; pixel (2, 2) alone has spread.
        let mut ss = vec![0.0f32; 25];
        ss[12] = 3.0;
        let mut s = Spread::default();
        s.add(&ss, &[4; 25]);
        let n = counts(&s, (5, 5), 4);
        let total: u32 = n.iter().sum();
        assert!((99..=101).contains(&total), "{total}");
        // The 3 × 3 block around it shares λ(1 + 0.1 · 9/25) each; the 16 others λ · 0.036.
        let inner = [6, 7, 8, 11, 12, 13, 16, 17, 18];
        for i in 0..25 {
            if inner.contains(&i) { assert!(n[i] >= 9, "{n:?}") } else { assert!(n[i] <= 2 && n[i] >= 1, "{n:?}") }
        }
    }

    #[test]
    fn the_pooled_spread_is_the_sum_of_squares_over_the_degrees_of_freedom() {
        let mut s = Spread::default();
        s.add(&[2.0, 0.0], &[3, 1]);
        s.add(&[4.0, 5.0], &[5, 1]);
        // (2 + 4)/(2 + 4) = 1; no degrees of freedom in the second pixel.
        assert_eq!(s.sigma(), vec![1.0, 0.0]);
        let mut w = Writer::default();
        s.save(&mut w);
        let back = Spread::load(&mut Reader::new(&w.bytes)).expect("what it wrote");
        assert_eq!(back, s);
    }

    #[test]
    fn a_pixel_spread_is_the_sum_of_squared_deviations_over_bands() {
        let mut p = PixelSpread::new(2);
        for x in [[1.0, 10.0], [3.0, 10.0], [5.0, 13.0]] {
            let mut v = [0.0; MAX_BANDS];
            v[..2].copy_from_slice(&x);
            v[2] = 99.0 * x[0]; // beyond the bands: ignored
            p.add(&v);
        }
        // Band 0: mean 3, (4 + 0 + 4); band 1: mean 11, (1 + 1 + 4).
        assert!((p.sum_sq() - 14.0).abs() < 1e-12, "{}", p.sum_sq());
    }

    #[test]
    fn dilation_takes_the_neighbourhood_maximum() {
        let v = [0.0, 0.0, 0.0, 0.0, 5.0, 0.0];
        assert_eq!(dilate(&v, 3, 2), vec![5.0; 6]);
        let v = [1.0, 0.0, 0.0, 0.0];
        assert_eq!(dilate(&v, 4, 1), vec![1.0, 1.0, 0.0, 0.0]);
    }
}
