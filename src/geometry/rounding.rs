//! Floating-point error bounds for the intersection routines.
//!
//! With unit roundoff ε = 2⁻⁵³, a chain of n roundings in f64 has relative error at most
//! γₙ = nε/(1 − nε) (Higham, *Accuracy and Stability of Numerical Algorithms*, 2nd ed., §3.1;
//! pbrt-v4 §6.8.1). Shapes use these bounds to refuse hits that lie within rounding error of the
//! ray origin, and to size the offset of spawned rays.

use glam::DVec3;

/// Unit roundoff of f64: half the machine epsilon.
pub const UNIT_ROUNDOFF: f64 = f64::EPSILON * 0.5;

/// γₙ = nε/(1 − nε), the relative error bound of n chained roundings.
#[inline]
pub const fn gamma(n: u32) -> f64 {
    let ne = n as f64 * UNIT_ROUNDOFF;
    ne / (1.0 - ne)
}

/// The largest component magnitude of `v` (its ∞-norm).
#[inline]
pub fn max_abs(v: DVec3) -> f64 {
    v.abs().max_element()
}

/// Σ |aᵢ bᵢ|: bounds the rounding error of a dot product (pbrt-v4 §6.8.1).
#[inline]
pub fn abs_dot(a: DVec3, b: DVec3) -> f64 {
    (a * b).abs().element_sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gamma_matches_definition() {
        let e = f64::EPSILON / 2.0;
        assert_eq!(gamma(0), 0.0);
        assert!((gamma(3) - 3.0 * e / (1.0 - 3.0 * e)).abs() < 1e-30);
        assert!(gamma(5) > 5.0 * e);
    }
}
