//! A discrete distribution over indices, sampled by inverse CDF with binary search.

/// Samples index i with probability w_i / Σw.
#[derive(Clone, Debug)]
pub struct Discrete1D {
    cdf: Vec<f64>,
    total: f64,
}

impl Discrete1D {
    /// Builds from non-negative finite weights; `None` if there are none or they sum to zero.
    pub fn new(weights: &[f64]) -> Option<Self> {
        if weights.iter().any(|w| !w.is_finite() || *w < 0.0) {
            return None;
        }
        let mut cdf = Vec::with_capacity(weights.len());
        let mut acc = 0.0;
        for w in weights {
            acc += w;
            cdf.push(acc);
        }
        (acc > 0.0).then_some(Discrete1D { cdf, total: acc })
    }

    /// Index for uniform `u` in [0,1), its probability, and `u` remapped to [0,1) within the bin.
    pub fn sample(&self, u: f64) -> (usize, f64, f64) {
        let target = u * self.total;
        let i = if target >= self.total {
            // u rounded up to 1: the last bin with positive weight.
            self.cdf.partition_point(|c| *c < self.total)
        } else {
            self.cdf.partition_point(|c| *c <= target)
        };
        // Skip zero-weight bins that share the same CDF value.
        let lo = if i == 0 { 0.0 } else { self.cdf[i - 1] };
        let w = self.cdf[i] - lo;
        let remapped = if w > 0.0 { ((target - lo) / w).clamp(0.0, 1.0 - f64::EPSILON) } else { 0.0 };
        (i, w / self.total, remapped)
    }

    /// Probability of index `i`.
    pub fn probability(&self, i: usize) -> f64 {
        let lo = if i == 0 { 0.0 } else { self.cdf[i - 1] };
        (self.cdf[i] - lo) / self.total
    }

    /// Sum of the weights.
    pub fn total(&self) -> f64 {
        self.total
    }

    /// Number of outcomes.
    pub fn len(&self) -> usize {
        self.cdf.len()
    }

    /// True when there is no outcome.
    pub fn is_empty(&self) -> bool {
        self.cdf.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::{Rng, Stream};
    use crate::testing::chi2::chi2_discrete;

    #[test]
    fn rejects_empty_negative_and_zero() {
        assert!(Discrete1D::new(&[]).is_none());
        assert!(Discrete1D::new(&[0.0, 0.0]).is_none());
        assert!(Discrete1D::new(&[1.0, -1.0]).is_none());
        assert!(Discrete1D::new(&[1.0, f64::NAN]).is_none());
    }

    #[test]
    fn never_samples_zero_weight_bins() {
        let d = Discrete1D::new(&[0.0, 1.0, 0.0, 3.0, 0.0]).unwrap();
        let mut rng = Rng::for_task(1, Stream::Test, 0);
        for _ in 0..10_000 {
            let (i, p, r) = d.sample(rng.uniform());
            assert!(i == 1 || i == 3, "sampled zero-weight bin {i}");
            assert!(p > 0.0 && (0.0..1.0).contains(&r));
        }
        assert_eq!(d.sample(0.0).0, 1);
        assert_eq!(d.sample(1.0).0, 3);
        assert_eq!(d.sample(1.0 - f64::EPSILON).0, 3);
    }

    #[test]
    fn chi_square_matches_weights() {
        let w = [0.5, 2.0, 0.1, 4.0, 1.4];
        let d = Discrete1D::new(&w).unwrap();
        let mut rng = Rng::for_task(2, Stream::Test, 0);
        let p = chi2_discrete(&w, 200_000, || d.sample(rng.uniform()).0);
        assert!(p > 1e-3, "chi-square p-value {p}");
    }
}
