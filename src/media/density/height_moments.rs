//! The moments ∫ₐᵇ uʲ d(u) du (j = 0…3) of a height profile d tabulated piecewise linearly on
//! uniform cells, from cumulative sums at the nodes: a few lookups for any interval, exact for
//! the interpolant (each cell's integrand is a polynomial of degree ≤ 4, which 3-point
//! Gauss–Legendre integrates exactly).
//!
//! They turn an integral of a cubic in height times the density into four differences: the
//! density-weighted volume of a photon-gather sphere in stratified air
//! ([`crate::photon_map::stratified`]) is one, asked once per volume estimate.
//!
//! Precision: a moment over [a, b] is the difference of two cumulative sums (compensated, so
//! each is good to a few ulps of itself), so its absolute error is a few ulps of the larger
//! cumulative sum: relative to the interval's own moment that is large where the profile has
//! fallen by many orders (a 1.5 km haze at 75 km: 10⁻²² of the ground's density, all of it
//! lost). [`Moments::scale`] carries those sums so that a caller can bound the error of what it
//! computes from the moments and integrate otherwise where the bound is too large.

use std::sync::Arc;

/// Cumulative moments of a piecewise-linear profile (see the module docs).
#[derive(Debug)]
pub struct HeightMoments {
    step_m: f64,
    values: Arc<[f64]>,
    /// ∫₀^{uᵢ} uʲ d(u) du at node i.
    cumulative: Vec<[f64; 4]>,
}

/// Moments over an interval and the cumulative sums they are differences of.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Moments {
    /// ∫ₐᵇ uʲ d(u) du, j = 0…3.
    pub value: [f64; 4],
    /// The sum of the two cumulative moments whose difference `value` is: its absolute error
    /// is at most [`ROUNDING`] times this (module docs).
    pub scale: [f64; 4],
}

/// A bound on a moment's absolute error relative to its [`Moments::scale`]: the compensated
/// cumulative sums err by about 2 ulps, the partial cell and the difference by a few more.
pub const ROUNDING: f64 = 8.0 * f64::EPSILON;

/// 3-point Gauss–Legendre nodes on [−1, 1] and their weights.
const GL3: [(f64, f64); 3] =
    [(-0.774_596_669_241_483_4, 5.0 / 9.0), (0.0, 8.0 / 9.0), (0.774_596_669_241_483_4, 5.0 / 9.0)];

impl HeightMoments {
    /// The moments of the profile whose node `i` (at height i·`step_m`) holds `values[i]`.
    pub fn new(step_m: f64, values: Arc<[f64]>) -> HeightMoments {
        // Neumaier's compensated summation: each sum good to ~2 ulps whatever the cell count.
        let mut cumulative = Vec::with_capacity(values.len());
        let (mut sum, mut carry) = ([0.0f64; 4], [0.0f64; 4]);
        cumulative.push(sum);
        for i in 0..values.len().saturating_sub(1) {
            let m = cell(step_m, &values, i, (i + 1) as f64 * step_m);
            for j in 0..4 {
                let t = sum[j] + m[j];
                carry[j] += if sum[j].abs() >= m[j].abs() { (sum[j] - t) + m[j] } else { (m[j] - t) + sum[j] };
                sum[j] = t;
            }
            cumulative.push([sum[0] + carry[0], sum[1] + carry[1], sum[2] + carry[2], sum[3] + carry[3]]);
        }
        HeightMoments { step_m, values, cumulative }
    }

    /// ∫ₐᵇ uʲ d(u) du for j = 0…3, with [a, b] clipped to the table's heights (d is zero
    /// outside them); zero when b ≤ a.
    pub fn between(&self, a: f64, b: f64) -> Moments {
        if b <= a {
            return Moments { value: [0.0; 4], scale: [0.0; 4] };
        }
        let (hi, lo) = (self.up_to(b), self.up_to(a));
        Moments {
            value: [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], hi[3] - lo[3]],
            scale: [hi[0] + lo[0], hi[1] + lo[1], hi[2] + lo[2], hi[3] + lo[3]],
        }
    }

    /// ∫₀ˣ uʲ d(u) du.
    fn up_to(&self, x: f64) -> [f64; 4] {
        let last = self.cumulative.len() - 1;
        let top = last as f64 * self.step_m;
        if x <= 0.0 || last == 0 {
            return [0.0; 4];
        }
        if x >= top {
            return self.cumulative[last];
        }
        let i = ((x / self.step_m) as usize).min(last - 1);
        let part = cell(self.step_m, &self.values, i, x);
        let c = self.cumulative[i];
        [c[0] + part[0], c[1] + part[1], c[2] + part[2], c[3] + part[3]]
    }
}

/// ∫ uʲ d(u) du over [uᵢ, `end`] within cell i, d linear there: exact by 3-point Gauss–Legendre.
fn cell(step_m: f64, values: &[f64], i: usize, end: f64) -> [f64; 4] {
    let start = i as f64 * step_m;
    let (half, mid) = (0.5 * (end - start), 0.5 * (end + start));
    let mut out = [0.0; 4];
    for (x, w) in GL3 {
        let u = mid + half * x;
        let f = (u - start) / step_m;
        let d = values[i] + f * (values[i + 1] - values[i]);
        let mut p = w * half * d;
        for o in &mut out {
            *o += p;
            p *= u;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn moments_of_a_linear_profile_are_its_closed_forms() {
        // d(u) = 2 − u/100 on [0, 100] (10 cells of 10): ∫ₐᵇ uʲ (2 − u/100) du in closed form.
        let values: Arc<[f64]> = (0..=10).map(|i| 2.0 - i as f64 / 10.0).collect::<Vec<_>>().into();
        let m = HeightMoments::new(10.0, values);
        let exact = |j: i32, a: f64, b: f64| {
            let k = f64::from(j);
            2.0 * (b.powi(j + 1) - a.powi(j + 1)) / (k + 1.0) - (b.powi(j + 2) - a.powi(j + 2)) / (100.0 * (k + 2.0))
        };
        for (a, b) in [(0.0, 100.0), (3.7, 58.2), (41.0, 43.5), (-5.0, 12.0), (90.0, 140.0)] {
            let got = m.between(a, b).value;
            let (a, b) = (a.max(0.0), b.min(100.0));
            for (j, got) in got.iter().enumerate() {
                let want = exact(j as i32, a, b);
                assert!((got - want).abs() <= 1e-12 * want.abs().max(1.0), "j = {j} on [{a}, {b}]: {got} vs {want}");
            }
        }
        assert_eq!(m.between(50.0, 20.0).value, [0.0; 4]);
    }
}
