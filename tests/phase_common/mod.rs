//! Helpers shared by the phase-function tests: quadrature over the sphere that copes with
//! forward peaks, a chi-square test binned in log(1 − cos θ), and the built-in Petzold table.
#![allow(dead_code)]

use morgana::media::phase::PhaseFunction;
use morgana::quadrature::gauss_legendre;
use morgana::rng::{Rng, Stream};
use morgana::testing::chi2::chi2_test;
use std::f64::consts::PI;
use std::path::PathBuf;

/// morgana's built-in Petzold table (embedded in the binary; read here as a file).
pub fn petzold_path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("src/media/ocean/data/petzold_average_particle_phase_function.csv")
}

/// The Petzold table's (angle °, value sr⁻¹) rows, parsed here independently of the loader.
pub fn petzold_rows() -> Vec<(f64, f64)> {
    let text = std::fs::read_to_string(petzold_path()).expect("built-in Petzold table");
    let rows: Vec<&str> = text.lines().filter(|l| !l.trim().is_empty() && !l.starts_with('#')).collect();
    assert_eq!(rows[0], "angle_deg,phase_function_per_sr", "the table's header row");
    rows[1..]
        .iter()
        .map(|l| {
            let (a, v) = l.split_once(',').unwrap();
            (a.trim().parse().unwrap(), v.trim().parse().unwrap())
        })
        .collect()
}

/// The Petzold phase function scenes get by name ("petzold"): the embedded table.
pub fn petzold() -> PhaseFunction {
    morgana::media::ocean::builtin::petzold()
}

/// x = 1 − cos θ for θ in degrees, without cancellation.
pub fn one_minus_cos_deg(deg: f64) -> f64 {
    2.0 * (deg.to_radians() / 2.0).sin().powi(2)
}

/// 2π ∫ f(μ) dμ over [−1, 1], written as 2π ∫₀² f(1 − x) dx and integrated piecewise
/// between the angles `breaks_deg` (where f may have kinks) by Gauss–Legendre: in ln x below
/// x = 10⁻² (the forward peak), linearly above.
pub fn sphere_integral(f: &dyn Fn(f64) -> f64, breaks_deg: &[f64]) -> f64 {
    let mut xs: Vec<f64> = vec![1e-40, 1e-2, 0.1, 0.5, 1.0, 1.5, 2.0];
    xs.extend(breaks_deg.iter().map(|d| one_minus_cos_deg(*d)).filter(|x| *x > 1e-40 && *x < 2.0));
    xs.sort_by(f64::total_cmp);
    xs.dedup();
    let mut sum = 0.0;
    for w in xs.windows(2) {
        let (a, b) = (w[0], w[1]);
        sum += if b <= 1e-2 {
            gauss_legendre(&|y: f64| f(1.0 - y.exp()) * y.exp(), a.ln(), b.ln(), 40)
        } else {
            gauss_legendre(&|x: f64| f(1.0 - x), a, b, 40)
        };
    }
    2.0 * PI * sum
}

/// Chi-square test of `phase.sample` binned in y = ln(1 − cos θ) over [ln x_min, ln 2]
/// (`bins` equal bins) plus one bin for 1 − cos θ < x_min; the expected counts integrate
/// `claimed_pdf(μ)` over each bin. This resolves the forward peak that bins uniform in cos θ
/// lump together.
pub fn chi2_log_angle(
    phase: &PhaseFunction,
    wavelength_nm: f64,
    claimed_pdf: &dyn Fn(f64) -> f64,
    x_min: f64,
    bins: usize,
    n: usize,
    seed: u64,
) -> f64 {
    let wi = glam::DVec3::new(0.3, -0.8, 0.52).normalize();
    let mut rng = Rng::for_task(seed, Stream::Test, 0);
    let (y0, y1) = (x_min.ln(), 2f64.ln());
    let dy = (y1 - y0) / bins as f64;
    let mut observed = vec![0.0; bins + 1];
    for _ in 0..n {
        let (wo, _) = phase.sample(wavelength_nm, wi, rng.uniform2());
        let x = 1.0 - wi.dot(wo);
        let bin = if x < x_min { 0 } else { 1 + (((x.ln() - y0) / dy) as usize).min(bins - 1) };
        observed[bin] += 1.0;
    }
    let mass = |ya: f64, yb: f64, panels: usize| {
        2.0 * PI * gauss_legendre(&|y: f64| claimed_pdf(1.0 - y.exp()) * y.exp(), ya, yb, panels)
    };
    let mut expected = vec![mass(1e-40f64.ln(), y0, 50) * n as f64];
    expected.extend((0..bins).map(|i| mass(y0 + i as f64 * dy, y0 + (i + 1) as f64 * dy, 2) * n as f64));
    chi2_test(&observed, &expected)
}

/// Mean and standard error of cos θ over `n` samples of `phase`.
pub fn sampled_mean_cosine(phase: &PhaseFunction, wavelength_nm: f64, n: usize, seed: u64) -> (f64, f64) {
    let wi = glam::DVec3::new(-0.2, 0.1, 0.97).normalize();
    let mut rng = Rng::for_task(seed, Stream::Test, 0);
    let (mut s, mut s2) = (0.0, 0.0);
    for _ in 0..n {
        let mu = wi.dot(phase.sample(wavelength_nm, wi, rng.uniform2()).0);
        s += mu;
        s2 += mu * mu;
    }
    let mean = s / n as f64;
    let var = (s2 / n as f64 - mean * mean) * n as f64 / (n as f64 - 1.0);
    (mean, (var / n as f64).sqrt())
}
