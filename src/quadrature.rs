//! Numerical quadrature: the composite 16-point Gauss–Legendre rule and Simpson's rule, used by
//! the renderer (optical depths through round-Earth air, inelastic band transfer) and by tests,
//! and adaptive Gauss–Kronrod (7–15) quadrature to a tolerance (the refraction integral).
//!
//! # References
//! - Press, Teukolsky, Vetterling & Flannery, *Numerical Recipes*, 3rd ed. (2007), §4.1 (Simpson)
//!   and §4.6 (Gauss–Legendre nodes by Newton iteration on P_n).
//! - R. Piessens, E. de Doncker-Kapenga, C. W. Überhuber & D. K. Kahaner, *QUADPACK* (Springer
//!   1983), §2.2 and routine QK15 (the 7-point Gauss and 15-point Kronrod nodes and weights).

use std::f64::consts::PI;

/// Composite 16-point Gauss–Legendre rule over `panels` equal panels of [a, b].
pub fn gauss_legendre(f: &dyn Fn(f64) -> f64, a: f64, b: f64, panels: usize) -> f64 {
    panel_sum(f, a, (b - a) / panels as f64, 0..panels)
}

/// The 16-point rule over the one panel [a, b] of several integrands at once, added into
/// `sums`: `f(x, values)` writes each integrand's value at x into `values`, and `sums[k]` gains
/// (b − a)/2 Σᵢ wᵢ fₖ(xᵢ). A composite rule on unequal panels is these calls in turn; the
/// integrands share every node. `sums` has at most 8 integrands.
pub fn gauss_legendre_panel_many(f: &mut dyn FnMut(f64, &mut [f64]), a: f64, b: f64, sums: &mut [f64]) {
    let (nodes, weights) = gauss_legendre_16();
    let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
    let k = sums.len().min(8);
    let (mut panel, mut values) = ([0.0f64; 8], [0.0f64; 8]);
    for (x, w) in nodes.iter().zip(weights.iter()) {
        f(mid + half * x, &mut values[..k]);
        for (s, v) in panel.iter_mut().zip(&values[..k]) {
            *s += w * v;
        }
    }
    for (s, p) in sums.iter_mut().zip(&panel[..k]) {
        *s += p * half;
    }
}

/// [`gauss_legendre`] of an `f` that is exactly zero outside `support`: the same panels and
/// the same sum, but only the panels that reach into the support are visited (the others add
/// exact zeros), so the work follows the support's width, not that of [a, b].
pub fn gauss_legendre_on_support(f: &dyn Fn(f64) -> f64, a: f64, b: f64, panels: usize, support: (f64, f64)) -> f64 {
    let h = (b - a) / panels as f64;
    // One panel of margin on either side against rounding of the panel edges.
    let first = ((support.0 - a) / h).floor() - 1.0;
    let last = ((support.1 - a) / h).ceil() + 1.0;
    let first = if first.is_nan() { 0 } else { first.clamp(0.0, panels as f64) as usize };
    let last = if last.is_nan() { panels } else { last.clamp(0.0, panels as f64) as usize };
    panel_sum(f, a, h, first..last)
}

/// The 16-point rule summed over the panels `[a + p·h, a + (p + 1)·h]`, p in `panels`.
fn panel_sum(f: &dyn Fn(f64) -> f64, a: f64, h: f64, panels: std::ops::Range<usize>) -> f64 {
    let (nodes, weights) = gauss_legendre_16();
    let mut sum = 0.0;
    for p in panels {
        let mid = a + (p as f64 + 0.5) * h;
        for (x, w) in nodes.iter().zip(weights.iter()) {
            sum += w * f(mid + 0.5 * h * x);
        }
    }
    sum * 0.5 * h
}

/// Nodes and weights of the 16-point Gauss–Legendre rule on [−1, 1], computed once (the
/// renderer's optical depths through round-Earth air call the rule millions of times).
/// The 16-point Gauss–Legendre nodes and weights on [−1, 1].
pub fn gauss_legendre_16() -> &'static ([f64; 16], [f64; 16]) {
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

/// Kronrod nodes on [0, 1] of the 15-point rule (QUADPACK QK15 `xgk`); the odd entries (1, 3,
/// 5, 7) are the 7-point Gauss nodes.
const KRONROD_15_X: [f64; 8] = [
    0.991_455_371_120_812_6,
    0.949_107_912_342_758_5,
    0.864_864_423_359_769_1,
    0.741_531_185_599_394_4,
    0.586_087_235_467_691_1,
    0.405_845_151_377_397_2,
    0.207_784_955_007_898_5,
    0.0,
];

/// Kronrod weights (QK15 `wgk`), for the nodes of [`KRONROD_15_X`] and their negatives.
const KRONROD_15_W: [f64; 8] = [
    0.022_935_322_010_529_22,
    0.063_092_092_629_978_55,
    0.104_790_010_322_250_18,
    0.140_653_259_715_525_92,
    0.169_004_726_639_267_9,
    0.190_350_578_064_785_4,
    0.204_432_940_075_298_9,
    0.209_482_141_084_727_83,
];

/// 7-point Gauss weights (QK15 `wg`), for the Kronrod nodes 1, 3, 5 and 7 (the centre).
const GAUSS_7_W: [f64; 4] =
    [0.129_484_966_168_869_7, 0.279_705_391_489_276_7, 0.381_830_050_505_118_9, 0.417_959_183_673_469_4];

/// The 7-point Gauss–Legendre rule on the one panel [a, b] (the Gauss nodes and weights of
/// QUADPACK's QK15, `KRONROD_15_X` 1, 3, 5, 7 and `GAUSS_7_W`). For f = e^{αx} on [−1, 1] its
/// error is 2¹⁵(7!)⁴/(15·(14!)³)·f⁽¹⁴⁾(ξ) = 2.1·10⁻¹⁵·α¹⁴e^{αξ} (the Gauss–Legendre remainder; Abramowitz & Stegun §25.4),
/// relative 10⁻¹⁹ at α = 1/2. Generic in `f` so that the integrand inlines into the rule.
pub fn gauss_legendre_7(f: impl Fn(f64) -> f64, a: f64, b: f64) -> f64 {
    let (c, h) = (0.5 * (a + b), 0.5 * (b - a));
    let mut sum = GAUSS_7_W[3] * f(c);
    for i in 0..3 {
        let x = h * KRONROD_15_X[2 * i + 1];
        sum += GAUSS_7_W[i] * (f(c - x) + f(c + x));
    }
    sum * h
}

/// The 7 nodes and weights of [`gauss_legendre_7`] on [−1, 1], for callers that reuse
/// per-node work across panels of equal width.
pub fn gauss_legendre_7_rule() -> [(f64, f64); 7] {
    let x = |i: usize| KRONROD_15_X[2 * i + 1];
    [
        (-x(0), GAUSS_7_W[0]),
        (-x(1), GAUSS_7_W[1]),
        (-x(2), GAUSS_7_W[2]),
        (0.0, GAUSS_7_W[3]),
        (x(2), GAUSS_7_W[2]),
        (x(1), GAUSS_7_W[1]),
        (x(0), GAUSS_7_W[0]),
    ]
}

/// The 15-point Kronrod and the embedded 7-point Gauss estimates of ∫_a^b f.
fn gauss_kronrod_15(f: &mut dyn FnMut(f64) -> f64, a: f64, b: f64) -> (f64, f64) {
    let (c, h) = (0.5 * (a + b), 0.5 * (b - a));
    let centre = f(c);
    let (mut kronrod, mut gauss) = (KRONROD_15_W[7] * centre, GAUSS_7_W[3] * centre);
    for i in 0..7 {
        let pair = f(c - h * KRONROD_15_X[i]) + f(c + h * KRONROD_15_X[i]);
        kronrod += KRONROD_15_W[i] * pair;
        if i % 2 == 1 {
            gauss += GAUSS_7_W[i / 2] * pair;
        }
    }
    (kronrod * h, gauss * h)
}

/// Deepest bisection of [`adaptive_gauss_kronrod`].
const GK_MAX_DEPTH: u32 = 30;

/// ∫_a^b f by adaptive Gauss–Kronrod quadrature: an interval's 15-point Kronrod value is
/// accepted when it differs from the embedded 7-point Gauss value by at most `tol` (a
/// conservative error bound: for a smooth f the Kronrod value is far better than the Gauss
/// value it is compared with), else the interval is halved and each half gets `tol`/2. Halving
/// stops 30 levels down (an interval 10⁻⁹ of the whole), where the value is accepted as it is.
pub fn adaptive_gauss_kronrod(f: &mut dyn FnMut(f64) -> f64, a: f64, b: f64, tol: f64) -> f64 {
    adaptive_gauss_kronrod_to_depth(f, a, b, tol, GK_MAX_DEPTH)
}

/// [`adaptive_gauss_kronrod`] halving at most `max_depth` levels down: at most 2^`max_depth`
/// intervals, so the work stays bounded when rounding noise in f keeps the two estimates from
/// agreeing to `tol`.
pub fn adaptive_gauss_kronrod_to_depth(f: &mut dyn FnMut(f64) -> f64, a: f64, b: f64, tol: f64, max_depth: u32) -> f64 {
    if a == b {
        return 0.0; // f is not evaluated: an empty interval may lie where f is undefined
    }
    gk_part(f, a, b, tol, max_depth)
}

fn gk_part(f: &mut dyn FnMut(f64) -> f64, a: f64, b: f64, tol: f64, depth: u32) -> f64 {
    let (kronrod, gauss) = gauss_kronrod_15(f, a, b);
    if depth == 0 || (kronrod - gauss).abs() <= tol {
        return kronrod;
    }
    let m = 0.5 * (a + b);
    gk_part(f, a, m, 0.5 * tol, depth - 1) + gk_part(f, m, b, 0.5 * tol, depth - 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The rules' defining property (Piessens et al. 1983, §2.2): 7-point Gauss integrates
    /// polynomials of degree ≤ 13 exactly, 15-point Kronrod those of degree ≤ 22; neither is
    /// exact one degree higher (so a wrong digit in a node or weight shows).
    #[test]
    fn gauss_and_kronrod_are_exact_to_their_degrees() {
        for k in 0..=24u32 {
            let exact = (1.0 - (-1.0f64).powi(k as i32 + 1)) / f64::from(k + 1);
            let (kronrod, gauss) = gauss_kronrod_15(&mut |x| x.powi(k as i32), -1.0, 1.0);
            if k <= 13 {
                assert!((gauss - exact).abs() < 1e-15, "Gauss 7, x^{k}: {gauss} vs {exact}");
            }
            if k <= 22 {
                assert!((kronrod - exact).abs() < 1e-15, "Kronrod 15, x^{k}: {kronrod} vs {exact}");
            }
        }
        let (k24, g14) =
            (gauss_kronrod_15(&mut |x| x.powi(24), -1.0, 1.0).0, gauss_kronrod_15(&mut |x| x.powi(14), -1.0, 1.0).1);
        // Their errors one degree up are ~6e-9 (Kronrod, x²⁴) and ~2e-4 (Gauss, x¹⁴): far above rounding.
        assert!((k24 - 2.0 / 25.0).abs() > 1e-10 && (g14 - 2.0 / 15.0).abs() > 1e-6);
    }

    /// The one-panel 7-point rule is exact to degree 13 and not 14, on a shifted panel, and
    /// agrees with the 7-point Gauss value of the Kronrod pair.
    #[test]
    fn the_7_point_rule_is_exact_to_degree_13() {
        let (a, b) = (0.5f64, 2.0f64);
        for k in 0..=14i32 {
            let exact = (b.powi(k + 1) - a.powi(k + 1)) / f64::from(k + 1);
            let got = gauss_legendre_7(|x| x.powi(k), a, b);
            if k <= 13 {
                assert!((got / exact - 1.0).abs() < 1e-14, "x^{k}: {got} vs {exact}");
            } else {
                assert!((got / exact - 1.0).abs() > 1e-9, "x^{k} is not integrated exactly");
            }
        }
        let f = |x: f64| (3.0 * x).sin() + x.exp();
        let pair = gauss_kronrod_15(&mut |x| f(x), a, b).1;
        assert!((gauss_legendre_7(f, a, b) - pair).abs() < 1e-15);
    }

    /// Visiting only the panels that reach into the support gives the full rule's sum bit for
    /// bit when f is zero outside it (a Gaussian cut at ±40σ, where exp underflows), and a
    /// support that leaves out part of f changes the sum (so the panels really are skipped).
    #[test]
    fn the_rule_on_a_support_is_the_full_rule() {
        let (mu, sigma) = (685.0, 10.6);
        let f = |l: f64| (-0.5 * ((l - mu) / sigma).powi(2)).exp();
        let cut = |l: f64| if (l - mu).abs() <= 40.0 * sigma { f(l) } else { 0.0 };
        for (a, b) in [(400.0, 700.0), (650.0, 651.7), (400.0, 70000.0), (100.0, 300.0), (900.0, 5000.0)] {
            let panels = ((b - a) / 2.0f64).ceil() as usize;
            let full = gauss_legendre(&cut, a, b, panels);
            let on = gauss_legendre_on_support(&cut, a, b, panels, (mu - 40.0 * sigma, mu + 40.0 * sigma));
            assert_eq!(full.to_bits(), on.to_bits(), "[{a}, {b}]: {full} vs {on}");
            assert_eq!(gauss_legendre(&f, a, b, panels).to_bits(), full.to_bits(), "f is zero beyond 40σ");
        }
        let panels = 150;
        let short = gauss_legendre_on_support(&f, 400.0, 700.0, panels, (mu - 1.0, mu + 1.0));
        assert!(short < 0.5 * gauss_legendre(&f, 400.0, 700.0, panels), "{short}");
    }

    /// Closed forms: ∫₀^π sin = 2; ∫₀¹ √x = 2/3 (a singular derivative at 0, where the rule
    /// must subdivide); ∫₀^{10} e^{−x} = 1 − e^{−10}; each within its tolerance.
    #[test]
    fn adaptive_gauss_kronrod_meets_its_tolerance() {
        type Case<'a> = (&'a dyn Fn(f64) -> f64, f64, f64, f64);
        let cases: [Case; 3] = [
            (&f64::sin, 0.0, PI, 2.0),
            (&f64::sqrt, 0.0, 1.0, 2.0 / 3.0),
            (&|x: f64| (-x).exp(), 0.0, 10.0, 1.0 - (-10.0f64).exp()),
        ];
        for (f, a, b, exact) in cases {
            for tol in [1e-6, 1e-10] {
                let got = adaptive_gauss_kronrod(&mut |x| f(x), a, b, tol);
                assert!((got - exact).abs() <= tol, "∫ = {got} vs {exact}, tol {tol}");
            }
        }
    }
}
