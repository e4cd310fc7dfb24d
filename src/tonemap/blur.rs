//! Gaussian-like blur at fixed widths, by three passes of a box filter per axis.
//!
//! Three box passes of radius r (width 2r + 1) have the variance of a Gaussian with
//! σ² = 3 ((2r + 1)² − 1)/12 = r (r + 1), and approach its shape (central limit theorem; Wells
//! 1986). Level k ≥ 1 uses r = 2^(k−1), so σ_k = √(r (r + 1)) = 1.41, 2.45, 4.47, 8.49, …
//! pixels; level 0 is the image itself. Edges are clamped (the border pixel repeats), and each
//! pass keeps the sum of the values of a row or column constant away from the borders.
//!
//! # References
//! - W. M. Wells (1986), "Efficient Synthesis of Gaussian Filters by Cascaded Uniform Filters",
//!   IEEE PAMI 8(2), 234–239.

/// Number of blur levels, including level 0 (no blur).
pub const BLUR_LEVELS: usize = 9;

/// The box radius of level `level` (0 for level 0).
fn radius(level: usize) -> usize {
    if level == 0 { 0 } else { 1 << (level - 1) }
}

/// The Gaussian σ (pixels) that level `level` approximates.
pub fn level_sigma_px(level: usize) -> f64 {
    let r = radius(level) as f64;
    (r * (r + 1.0)).sqrt()
}

/// `values` (row-major, `w` × `h`) blurred at `level`.
pub fn blur_level(values: &[f64], w: usize, h: usize, level: usize) -> Vec<f64> {
    let r = radius(level);
    let mut out = values.to_vec();
    if r == 0 {
        return out;
    }
    for _ in 0..3 {
        for y in 0..h {
            box_pass(&mut out[y * w..(y + 1) * w], r);
        }
        let mut column = vec![0.0; h];
        for x in 0..w {
            for y in 0..h {
                column[y] = out[y * w + x];
            }
            box_pass(&mut column, r);
            for y in 0..h {
                out[y * w + x] = column[y];
            }
        }
    }
    out
}

/// One box filter of radius `r` over `line`, clamping at the ends, by a running sum.
fn box_pass(line: &mut [f64], r: usize) {
    let n = line.len();
    if n == 0 {
        return;
    }
    let src = line.to_vec();
    let at = |i: isize| src[i.clamp(0, n as isize - 1) as usize];
    let r = r as isize;
    let mut sum: f64 = (-r..=r).map(at).sum();
    let width = (2 * r + 1) as f64;
    for (i, v) in line.iter_mut().enumerate() {
        *v = sum / width;
        let i = i as isize;
        sum += at(i + r + 1) - at(i - r);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_impulse_spreads_with_the_stated_variance() {
        // A single bright pixel in a large image: the blurred image's second moment along x is σ².
        let (w, h) = (201, 1);
        for level in 1..5 {
            let mut v = vec![0.0; w];
            v[100] = 1.0;
            let b = blur_level(&v, w, h, level);
            let sum: f64 = b.iter().sum();
            let var: f64 = b.iter().enumerate().map(|(i, p)| p * (i as f64 - 100.0).powi(2)).sum::<f64>() / sum;
            assert!((sum - 1.0).abs() < 1e-12);
            assert!((var - level_sigma_px(level).powi(2)).abs() < 1e-9, "level {level}: {var}");
        }
        assert_eq!(blur_level(&[1.0, 2.0], 2, 1, 0), vec![1.0, 2.0]);
        // A constant image stays constant (clamped edges).
        assert!(blur_level(&[3.0; 12], 4, 3, 3).iter().all(|&x| (x - 3.0).abs() < 1e-12));
    }
}
