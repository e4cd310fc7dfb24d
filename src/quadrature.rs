//! Numerical quadrature: the composite 16-point Gauss–Legendre rule and Simpson's rule, used by
//! the renderer (optical depths through round-Earth air, inelastic band transfer) and by tests.
//!
//! # References
//! - Press, Teukolsky, Vetterling & Flannery, *Numerical Recipes*, 3rd ed. (2007), §4.1 (Simpson)
//!   and §4.6 (Gauss–Legendre nodes by Newton iteration on P_n).

use std::f64::consts::PI;

/// Composite 16-point Gauss–Legendre rule over `panels` equal panels of [a, b].
pub fn gauss_legendre(f: &dyn Fn(f64) -> f64, a: f64, b: f64, panels: usize) -> f64 {
    let (nodes, weights) = gauss_legendre_16();
    let h = (b - a) / panels as f64;
    let mut sum = 0.0;
    for p in 0..panels {
        let mid = a + (p as f64 + 0.5) * h;
        for (x, w) in nodes.iter().zip(weights.iter()) {
            sum += w * f(mid + 0.5 * h * x);
        }
    }
    sum * 0.5 * h
}

/// Nodes and weights of the 16-point Gauss–Legendre rule on [−1, 1], computed once (the
/// renderer's optical depths through round-Earth air call the rule millions of times).
fn gauss_legendre_16() -> &'static ([f64; 16], [f64; 16]) {
    static RULE: std::sync::OnceLock<([f64; 16], [f64; 16])> = std::sync::OnceLock::new();
    RULE.get_or_init(gauss_legendre_16_newton)
}

/// Nodes and weights of the 16-point Gauss–Legendre rule on [−1, 1], by Newton iteration on
/// P16 (Press et al., *Numerical Recipes*, §4.6).
fn gauss_legendre_16_newton() -> ([f64; 16], [f64; 16]) {
    const N: usize = 16;
    let (mut x, mut w) = ([0.0; N], [0.0; N]);
    for i in 0..N / 2 {
        let mut z = (PI * (i as f64 + 0.75) / (N as f64 + 0.5)).cos();
        let mut dp = 0.0;
        for _ in 0..100 {
            let (mut p1, mut p2) = (1.0, 0.0);
            for j in 0..N {
                let p3 = p2;
                p2 = p1;
                p1 = ((2 * j + 1) as f64 * z * p2 - j as f64 * p3) / (j + 1) as f64;
            }
            dp = N as f64 * (z * p1 - p2) / (z * z - 1.0);
            let dz = p1 / dp;
            z -= dz;
            if dz.abs() < 1e-15 {
                break;
            }
        }
        x[i] = -z;
        x[N - 1 - i] = z;
        w[i] = 2.0 / ((1.0 - z * z) * dp * dp);
        w[N - 1 - i] = w[i];
    }
    (x, w)
}

/// Composite Simpson rule with `intervals` (even) sub-intervals.
pub fn simpson(f: &dyn Fn(f64) -> f64, a: f64, b: f64, intervals: usize) -> f64 {
    let m = intervals + intervals % 2;
    let h = (b - a) / m as f64;
    let mut s = f(a) + f(b);
    for i in 1..m {
        let w = if i % 2 == 1 { 4.0 } else { 2.0 };
        s += w * f(a + i as f64 * h);
    }
    s * h / 3.0
}
