//! One trial step of the Dormand–Prince RK5(4)7M pair: the 5th-order solution (local
//! extrapolation), the embedded error estimate and the coefficient of its 4th-order continuous
//! extension.
//!
//! Seven stages, the seventh at the new point (FSAL: it is the next step's first stage):
//!
//! ```text
//!     kᵢ = f(y0 + h Σⱼ aᵢⱼ kⱼ),  i = 1..7,    y1 = y0 + h Σ bᵢ kᵢ  (bᵢ = a₇ᵢ),
//!     err = h Σ eᵢ kᵢ,  eᵢ = bᵢ − b̂ᵢ  (b̂ the embedded 4th-order weights),
//!     c5 = h Σ dᵢ kᵢ   (dense output, see [`super::dense`]).
//! ```
//!
//! The coefficients are exact rationals; everything lives on the stack (no allocation).
//!
//! # References
//! - J. R. Dormand, P. J. Prince, "A family of embedded Runge–Kutta formulae", J. Comput. Appl.
//!   Math. 6 (1980) 19–26 (the RK5(4)7M tableau, Table 2).
//! - E. Hairer, S. P. Nørsett, G. Wanner, *Solving Ordinary Differential Equations I*, 2nd ed.,
//!   Springer 1993, §II.5 Table 5.2 (tableau), §II.6 (continuous extension), and the DOPRI5
//!   Fortran code (constants E1..E7 and D1..D7; dense output D1 = −12715105075/11282082432,
//!   D3 = 87487479700/32700410799, D4 = −10690763975/1880347072,
//!   D5 = 701980252875/199316789632, D6 = −1453857185/822651844, D7 = 69997945/29380423).

use super::error::OdeError;
use super::system::{IndexSample, RayY, eval};

/// Node c₂ of the tableau (stage 2 is evaluated at s0 + c₂h).
pub const C2: f64 = 1.0 / 5.0;
/// Node c₃ of the tableau (stage 3 is evaluated at s0 + c₃h).
pub const C3: f64 = 3.0 / 10.0;
/// Node c₄ of the tableau (stage 4 is evaluated at s0 + c₄h).
pub const C4: f64 = 4.0 / 5.0;
/// Node c₅ of the tableau (stage 5 is evaluated at s0 + c₅h).
pub const C5: f64 = 8.0 / 9.0;

/// Coefficient a₂₁ of the tableau (stage 2, from k₁).
pub const A21: f64 = 1.0 / 5.0;
/// Coefficient a₃₁ of the tableau (stage 3, from k₁).
pub const A31: f64 = 3.0 / 40.0;
/// Coefficient a₃₂ of the tableau (stage 3, from k₂).
pub const A32: f64 = 9.0 / 40.0;
/// Coefficient a₄₁ of the tableau (stage 4, from k₁).
pub const A41: f64 = 44.0 / 45.0;
/// Coefficient a₄₂ of the tableau (stage 4, from k₂).
pub const A42: f64 = -56.0 / 15.0;
/// Coefficient a₄₃ of the tableau (stage 4, from k₃).
pub const A43: f64 = 32.0 / 9.0;
/// Coefficient a₅₁ of the tableau (stage 5, from k₁).
pub const A51: f64 = 19372.0 / 6561.0;
/// Coefficient a₅₂ of the tableau (stage 5, from k₂).
pub const A52: f64 = -25360.0 / 2187.0;
/// Coefficient a₅₃ of the tableau (stage 5, from k₃).
pub const A53: f64 = 64448.0 / 6561.0;
/// Coefficient a₅₄ of the tableau (stage 5, from k₄).
pub const A54: f64 = -212.0 / 729.0;
/// Coefficient a₆₁ of the tableau (stage 6, from k₁).
pub const A61: f64 = 9017.0 / 3168.0;
/// Coefficient a₆₂ of the tableau (stage 6, from k₂).
pub const A62: f64 = -355.0 / 33.0;
/// Coefficient a₆₃ of the tableau (stage 6, from k₃).
pub const A63: f64 = 46732.0 / 5247.0;
/// Coefficient a₆₄ of the tableau (stage 6, from k₄).
pub const A64: f64 = 49.0 / 176.0;
/// Coefficient a₆₅ of the tableau (stage 6, from k₅).
pub const A65: f64 = -5103.0 / 18656.0;

/// 5th-order weights (= the seventh row of A; b₂ = b₇ = 0).
pub const B1: f64 = 35.0 / 384.0;
/// 5th-order weight b₃.
pub const B3: f64 = 500.0 / 1113.0;
/// 5th-order weight b₄.
pub const B4: f64 = 125.0 / 192.0;
/// 5th-order weight b₅.
pub const B5: f64 = -2187.0 / 6784.0;
/// 5th-order weight b₆.
pub const B6: f64 = 11.0 / 84.0;

/// Error weights eᵢ = bᵢ − b̂ᵢ (e₂ = 0).
pub const E1: f64 = 71.0 / 57600.0;
/// Error weight e₃ = b₃ − b̂₃.
pub const E3: f64 = -71.0 / 16695.0;
/// Error weight e₄ = b₄ − b̂₄.
pub const E4: f64 = 71.0 / 1920.0;
/// Error weight e₅ = b₅ − b̂₅.
pub const E5: f64 = -17253.0 / 339200.0;
/// Error weight e₆ = b₆ − b̂₆.
pub const E6: f64 = 22.0 / 525.0;
/// Error weight e₇ = b₇ − b̂₇.
pub const E7: f64 = -1.0 / 40.0;

/// Dense-output weights of Hairer's DOPRI5 (d₂ = 0).
pub const D1: f64 = -12715105075.0 / 11282082432.0;
/// Dense-output weight d₃.
pub const D3: f64 = 87487479700.0 / 32700410799.0;
/// Dense-output weight d₄.
pub const D4: f64 = -10690763975.0 / 1880347072.0;
/// Dense-output weight d₅.
pub const D5: f64 = 701980252875.0 / 199316789632.0;
/// Dense-output weight d₆.
pub const D6: f64 = -1453857185.0 / 822651844.0;
/// Dense-output weight d₇.
pub const D7: f64 = 69997945.0 / 29380423.0;

/// The result of one trial step of size h from y0.
#[derive(Clone, Copy, Debug)]
pub struct Trial {
    /// The 5th-order solution at s0 + h.
    pub y1: RayY,
    /// f(y1) = k₇ (the next step's k₁).
    pub f1: RayY,
    /// n(y1.r), sampled for k₇.
    pub n1: f64,
    /// The error estimate h Σ eᵢ kᵢ.
    pub err: RayY,
    /// The dense-output coefficient h Σ dᵢ kᵢ.
    pub c5: RayY,
}

/// One trial step of size `h` from `y0` with `f0` = f(y0). `evals` counts field samples
/// (six per complete trial). Fails with the field's [`OdeError::BadIndex`] at the first stage
/// point where it is unusable.
#[inline]
pub fn trial<F: IndexSample>(field: &F, y0: &RayY, f0: &RayY, h: f64, evals: &mut u64) -> Result<Trial, OdeError> {
    let k1 = *f0;
    let mut stage = |y: RayY| {
        *evals += 1;
        eval(field, &y)
    };
    // Each sum adds the newest stage last, to a part formed while that stage was evaluated:
    // the chain from one field sample to the next is one multiply and one add.
    let (k2, _) = stage(*y0 + k1 * (h * A21))?;
    let (k3, _) = stage((*y0 + k1 * (h * A31)) + k2 * (h * A32))?;
    let (k4, _) = stage((*y0 + (k1 * A41 + k2 * A42) * h) + k3 * (h * A43))?;
    let (k5, _) = stage((*y0 + (k1 * A51 + k2 * A52 + k3 * A53) * h) + k4 * (h * A54))?;
    let (k6, _) = stage((*y0 + (k1 * A61 + k2 * A62 + k3 * A63 + k4 * A64) * h) + k5 * (h * A65))?;
    let y1 = (*y0 + (k1 * B1 + k3 * B3 + k4 * B4 + k5 * B5) * h) + k6 * (h * B6);
    let (k7, n1) = stage(y1)?;
    let err = (k1 * E1 + k3 * E3 + k4 * E4 + k5 * E5 + k6 * E6) * h + k7 * (h * E7);
    let c5 = (k1 * D1 + k3 * D3 + k4 * D4 + k5 * D5 + k6 * D6) * h + k7 * (h * D7);
    Ok(Trial { y1, f1: k7, n1, err, c5 })
}

#[cfg(test)]
mod tests {
    use super::*;

    const C: [f64; 7] = [0.0, C2, C3, C4, C5, 1.0, 1.0];
    const B: [f64; 7] = [B1, 0.0, B3, B4, B5, B6, 0.0];
    const E: [f64; 7] = [E1, 0.0, E3, E4, E5, E6, E7];

    fn a() -> [[f64; 7]; 7] {
        let mut a = [[0.0; 7]; 7];
        a[1][0] = A21;
        a[2][..2].copy_from_slice(&[A31, A32]);
        a[3][..3].copy_from_slice(&[A41, A42, A43]);
        a[4][..4].copy_from_slice(&[A51, A52, A53, A54]);
        a[5][..5].copy_from_slice(&[A61, A62, A63, A64, A65]);
        a[6][..6].copy_from_slice(&B[..6]);
        a
    }

    /// Row sums equal the nodes (Hairer I, eq. II.1.9).
    #[test]
    fn rows_sum_to_nodes() {
        for (row, c) in a().iter().zip(C) {
            assert!((row.iter().sum::<f64>() - c).abs() < 1e-14, "{row:?} vs {c}");
        }
    }

    /// Quadrature conditions Σ bᵢ cᵢ^(q−1) = 1/q for q ≤ 5 and two tree conditions,
    /// Σ bᵢ aᵢⱼ cⱼ = 1/6 (order 3) and Σ bᵢ cᵢ² aᵢⱼ cⱼ = 1/10 (order 5) (Hairer I, Table II.2.2,
    /// 1/γ(t)). The embedded weights b̂ = b − e have order 4 but not 5, and Σ eᵢ = 0.
    #[test]
    fn order_conditions() {
        let a = a();
        let bhat: Vec<f64> = B.iter().zip(E).map(|(b, e)| b - e).collect();
        for q in 1..=5 {
            let s: f64 = B.iter().zip(C).map(|(b, c)| b * c.powi(q - 1)).sum();
            assert!((s - 1.0 / q as f64).abs() < 1e-14, "b order {q}: {s}");
        }
        for q in 1..=4 {
            let s: f64 = bhat.iter().zip(C).map(|(b, c)| b * c.powi(q - 1)).sum();
            assert!((s - 1.0 / q as f64).abs() < 1e-14, "b̂ order {q}: {s}");
        }
        let s5: f64 = bhat.iter().zip(C).map(|(b, c)| b * c.powi(4)).sum();
        assert!((s5 - 0.2).abs() > 1e-6, "b̂ must not have order 5");
        let ac: Vec<f64> = a.iter().map(|row| row.iter().zip(C).map(|(x, c)| x * c).sum()).collect();
        let s: f64 = B.iter().zip(&ac).map(|(b, x)| b * x).sum();
        assert!((s - 1.0 / 6.0).abs() < 1e-14);
        let s: f64 = B.iter().zip(&ac).zip(C).map(|((b, x), c)| b * c * c * x).sum();
        assert!((s - 0.1).abs() < 1e-14);
        assert!(E.iter().sum::<f64>().abs() < 1e-16);
    }

    /// The continuous extension is consistent: Σ dᵢ = 0 (so c5 vanishes for constant f), which
    /// makes the interpolant exact for linear solutions.
    #[test]
    fn dense_weights_sum_to_zero() {
        let s = D1 + D3 + D4 + D5 + D6 + D7;
        assert!(s.abs() < 1e-14, "{s}");
    }
}
