//! The radius schedule of progressive photon mapping: how the gather kernels of pass i shrink.
//!
//! Knaus & Zwicker (2011) show that averaging N independent photon-mapping passes converges —
//! bias and variance both → 0 — when the kernel of pass i+1 is that of pass i shrunk so that
//! the variance of one pass grows by (i + 1)/(i + α) while its bias falls by (i + α)/(i + 1):
//!
//! r²ᵢ₊₁ = r²ᵢ (i + α)/(i + 1)   for surface (2-D) estimates
//! r³ᵢ₊₁ = r³ᵢ (i + α)/(i + 1)   for volume (3-D) estimates, the same argument in three dimensions,
//!
//! with i counted from 1 and 0 < α < 1; the mean squared error of the average then falls as
//! O(N^(−α)) for variance and O(N^(2(α−1))) for squared bias;
//! α = 2/3 makes the two fall alike (−α = 2(α − 1)).
//! Both rules scale the kernel's measure (area or volume) by the same factor
//! sᵢ = Π_{j=1}^{i−1} (j + α)/(j + 1), which [`measure_ratio`] returns.
//!
//! morgana's estimates gather the k nearest photons within a maximum radius. Within the cap the
//! k-nearest kernel's measure is k over the local photon density, so the schedule scales k by
//! sᵢ as well as the cap's measure: the kernel shrinks by sᵢ wherever photons are dense or
//! sparse, which is the radius rule of the paper applied to an adaptive radius. k never falls
//! below [`MIN_K`] (the k-th photon only sets the radius), which a run reaches after some 10⁵
//! passes at k = 100.
//!
//! # References
//! - C. Knaus and M. Zwicker (2011), "Progressive photon mapping: a probabilistic approach",
//!   ACM Transactions on Graphics 30(3), 25.
//! - T. Hachisuka, S. Ogaki and H. W. Jensen (2008), "Progressive photon mapping", ACM
//!   Transactions on Graphics 27(5), 130.

/// The fewest nearest photons a shrunk estimate gathers.
pub const MIN_K: usize = 2;

/// The default α: the balance of variance and squared bias (Knaus & Zwicker 2011).
pub const DEFAULT_ALPHA: f64 = 2.0 / 3.0;

/// sᵢ = Π_{j=1}^{i−1} (j + α)/(j + 1) for 0-based `pass` = i − 1: the factor by which the kernel
/// measure (area on surfaces, volume in media) of that pass is smaller than the first pass's.
pub fn measure_ratio(pass: u32, alpha: f64) -> f64 {
    (1..=pass).map(|j| (f64::from(j) + alpha) / (f64::from(j) + 1.0)).product()
}

/// The largest gather radius of a surface estimate in `pass`: r₁ √sᵢ.
pub fn surface_radius(r1: f64, pass: u32, alpha: f64) -> f64 {
    if pass == 0 { r1 } else { r1 * measure_ratio(pass, alpha).sqrt() }
}

/// The largest gather radius of a volume estimate in `pass`: r₁ ∛sᵢ.
pub fn volume_radius(r1: f64, pass: u32, alpha: f64) -> f64 {
    if pass == 0 { r1 } else { r1 * measure_ratio(pass, alpha).cbrt() }
}

/// Nearest photons per estimate in `pass`: k₁ sᵢ rounded, at least [`MIN_K`] (or k₁ if smaller).
pub fn k(k1: usize, pass: u32, alpha: f64) -> usize {
    if pass == 0 {
        return k1;
    }
    ((k1 as f64 * measure_ratio(pass, alpha)).round() as usize).max(MIN_K.min(k1))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_measure_follows_the_recurrence() {
        // r²₂ = r²₁ (1 + α)/2, r²₃ = r²₂ (2 + α)/3 (the recurrence above).
        let a = 0.5;
        assert_eq!(measure_ratio(0, a), 1.0);
        assert!((measure_ratio(1, a) - 0.75).abs() < 1e-15);
        assert!((measure_ratio(2, a) - 0.75 * 2.5 / 3.0).abs() < 1e-15);
        assert!((surface_radius(2.0, 1, a) - 2.0 * 0.75f64.sqrt()).abs() < 1e-15);
        assert!((volume_radius(2.0, 1, a).powi(3) - 8.0 * 0.75).abs() < 1e-12);
    }

    #[test]
    fn the_measure_falls_as_a_power_of_the_pass() {
        // sᵢ = Γ(i + α) / (Γ(1 + α) Γ(i + 1)) ~ i^(α−1) / Γ(1 + α): the ratio of passes 4000 and
        // 1000 is 4^(α−1) to O(1/i).
        let a = DEFAULT_ALPHA;
        let ratio = measure_ratio(3999, a) / measure_ratio(999, a);
        assert!((ratio - 4f64.powf(a - 1.0)).abs() < 1e-3, "{ratio}");
    }

    #[test]
    fn k_shrinks_with_the_measure_and_keeps_a_floor() {
        assert_eq!(k(100, 0, 0.5), 100);
        assert_eq!(k(100, 1, 0.5), 75);
        assert_eq!(k(100, 1_000_000, 0.5), MIN_K);
        assert_eq!(k(1, 5, 0.5), 1);
    }
}
