//! Pearson chi-square goodness-of-fit tests for samplers, in the manner of Mitsuba 3's
//! `chi2.py` and pbrt-v4's sampling tests: draw many samples into bins, integrate the density the
//! sampler claims over each bin, pool bins whose expected count is below 5, and return the
//! p-value of the chi-square statistic. A test passes when p exceeds a significance level that is
//! corrected for the number of tests (Šidák), typically 1e-3 to 1e-2.
//!
//! The p-value is Q(k/2, χ²/2), the regularised upper incomplete gamma function, evaluated by
//! series or continued fraction (Press et al., *Numerical Recipes*, 3rd ed., §6.2).

use crate::quadrature::gauss_legendre;
use glam::DVec3;
use std::f64::consts::PI;

/// p-value of Pearson's statistic for observed against expected counts (same length). Bins with
/// expected count below 5 are pooled into one bin; an observation where nothing was expected
/// gives p = 0.
pub fn chi2_test(observed: &[f64], expected: &[f64]) -> f64 {
    assert_eq!(observed.len(), expected.len(), "chi2_test: observed and expected lengths differ");
    let mut stat = 0.0;
    let mut dof: i64 = -1;
    let (mut pooled_obs, mut pooled_exp) = (0.0, 0.0);
    for (&o, &e) in observed.iter().zip(expected) {
        if e <= 0.0 {
            if o > 0.0 {
                return 0.0;
            }
            continue;
        }
        if e < 5.0 {
            pooled_obs += o;
            pooled_exp += e;
            continue;
        }
        stat += (o - e) * (o - e) / e;
        dof += 1;
    }
    if pooled_exp > 0.0 {
        stat += (pooled_obs - pooled_exp) * (pooled_obs - pooled_exp) / pooled_exp;
        dof += 1;
    }
    if dof < 1 {
        return 1.0;
    }
    gamma_q(dof as f64 / 2.0, stat / 2.0)
}

/// Chi-square test of a discrete sampler against weights (need not be normalised).
pub fn chi2_discrete(weights: &[f64], n: usize, mut sample: impl FnMut() -> usize) -> f64 {
    let total: f64 = weights.iter().sum();
    let mut observed = vec![0.0; weights.len()];
    for _ in 0..n {
        let i = sample();
        if i >= weights.len() {
            return 0.0;
        }
        observed[i] += 1.0;
    }
    let expected: Vec<f64> = weights.iter().map(|w| w / total * n as f64).collect();
    chi2_test(&observed, &expected)
}

/// Chi-square test of a sampler on `[min, max]` against its claimed density `pdf` (which must
/// integrate to one over the interval). `None` samples count as failures to sample, which the
/// density must account for by integrating to less than one.
pub fn chi2_1d(
    range: (f64, f64),
    bins: usize,
    n: usize,
    mut sample: impl FnMut() -> Option<f64>,
    pdf: impl Fn(f64) -> f64,
) -> f64 {
    let (min, max) = range;
    let width = (max - min) / bins as f64;
    let mut observed = vec![0.0; bins];
    for _ in 0..n {
        let Some(x) = sample() else { continue };
        if !(min..=max).contains(&x) || !x.is_finite() {
            return 0.0;
        }
        let i = (((x - min) / width) as usize).min(bins - 1);
        observed[i] += 1.0;
    }
    let expected: Vec<f64> = (0..bins)
        .map(|i| {
            let a = min + i as f64 * width;
            gauss_legendre(&pdf, a, a + width, 4) * n as f64
        })
        .collect();
    chi2_test(&observed, &expected)
}

/// Chi-square test of a direction sampler against its claimed solid-angle density. Bins are
/// uniform in z = cos θ and φ, hence of equal solid angle; the density is integrated over each
/// bin by composite Gauss–Legendre rules in (z, φ), where dω = dz dφ. The rules never evaluate
/// the density on a bin edge, so a density with a jump on a bin edge is integrated correctly.
pub fn chi2_sphere(
    z_bins: usize,
    phi_bins: usize,
    n: usize,
    mut sample: impl FnMut() -> Option<DVec3>,
    pdf: impl Fn(DVec3) -> f64,
) -> f64 {
    let dz = 2.0 / z_bins as f64;
    let dphi = 2.0 * PI / phi_bins as f64;
    let mut observed = vec![0.0; z_bins * phi_bins];
    for _ in 0..n {
        let Some(w) = sample() else { continue };
        if !w.is_finite() || (w.length() - 1.0).abs() > 1e-6 {
            return 0.0;
        }
        let iz = (((w.z.clamp(-1.0, 1.0) + 1.0) / dz) as usize).min(z_bins - 1);
        let phi = w.y.atan2(w.x).rem_euclid(2.0 * PI);
        let ip = ((phi / dphi) as usize).min(phi_bins - 1);
        observed[iz * phi_bins + ip] += 1.0;
    }
    let dir = |z: f64, phi: f64| {
        let r = (1.0 - z * z).max(0.0).sqrt();
        DVec3::new(r * phi.cos(), r * phi.sin(), z)
    };
    let mut expected = vec![0.0; z_bins * phi_bins];
    for iz in 0..z_bins {
        for ip in 0..phi_bins {
            let (z0, p0) = (-1.0 + iz as f64 * dz, ip as f64 * dphi);
            let integral = gauss_legendre(
                &|z: f64| gauss_legendre(&|phi: f64| pdf(dir(z, phi)), p0, p0 + dphi, 2),
                z0,
                z0 + dz,
                4,
            );
            expected[iz * phi_bins + ip] = integral * n as f64;
        }
    }
    chi2_test(&observed, &expected)
}

/// ln Γ(x) for x > 0 (Lanczos approximation, g = 7, n = 9; relative error < 1e-15).
pub fn ln_gamma(x: f64) -> f64 {
    const G: f64 = 7.0;
    const C: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    if x < 0.5 {
        return (PI / (PI * x).sin()).ln() - ln_gamma(1.0 - x);
    }
    let x = x - 1.0;
    let mut a = C[0];
    let t = x + G + 0.5;
    for (i, c) in C.iter().enumerate().skip(1) {
        a += c / (x + i as f64);
    }
    0.5 * (2.0 * PI).ln() + (x + 0.5) * t.ln() - t + a.ln()
}

/// Regularised upper incomplete gamma function Q(a, x) = Γ(a, x)/Γ(a).
pub fn gamma_q(a: f64, x: f64) -> f64 {
    if x <= 0.0 {
        return 1.0;
    }
    if x < a + 1.0 { 1.0 - gamma_p_series(a, x) } else { gamma_q_continued_fraction(a, x) }
}

fn gamma_p_series(a: f64, x: f64) -> f64 {
    let mut ap = a;
    let mut sum = 1.0 / a;
    let mut del = sum;
    for _ in 0..10_000 {
        ap += 1.0;
        del *= x / ap;
        sum += del;
        if del.abs() < sum.abs() * 1e-15 {
            break;
        }
    }
    sum * (-x + a * x.ln() - ln_gamma(a)).exp()
}

fn gamma_q_continued_fraction(a: f64, x: f64) -> f64 {
    const TINY: f64 = 1e-300;
    let mut b = x + 1.0 - a;
    let mut c = 1.0 / TINY;
    let mut d = 1.0 / b;
    let mut h = d;
    for i in 1..10_000 {
        let an = -(i as f64) * (i as f64 - a);
        b += 2.0;
        d = an * d + b;
        if d.abs() < TINY {
            d = TINY;
        }
        c = b + an / c;
        if c.abs() < TINY {
            c = TINY;
        }
        d = 1.0 / d;
        let del = d * c;
        h *= del;
        if (del - 1.0).abs() < 1e-15 {
            break;
        }
    }
    (-x + a * x.ln() - ln_gamma(a)).exp() * h
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::{Rng, Stream};
    use crate::sampling::{cosine_hemisphere, cosine_hemisphere_pdf, uniform_sphere, uniform_sphere_pdf};

    #[test]
    fn gamma_q_matches_known_values() {
        // Q(1, x) = e^{-x}; Q(1/2, x) = erfc(sqrt x); chi-square with 10 dof at 18.307 has p = 0.05.
        assert!((gamma_q(1.0, 2.0) - (-2.0f64).exp()).abs() < 1e-12);
        assert!((gamma_q(0.5, 1.0) - 0.157_299_207_050_285_1).abs() < 1e-10);
        assert!((gamma_q(5.0, 18.307 / 2.0) - 0.05).abs() < 1e-4);
        assert!((ln_gamma(10.0) - 362_880f64.ln()).abs() < 1e-12);
        // Gauss–Legendre integrates x^7 exactly and e^x to machine precision.
        assert!((gauss_legendre(&|x| x.powi(7), 0.0, 2.0, 1) - 32.0).abs() < 1e-12);
        assert!((gauss_legendre(&|x: f64| x.exp(), 0.0, 1.0, 1) - (1f64.exp() - 1.0)).abs() < 1e-14);
    }

    #[test]
    fn accepts_a_correct_sampler_and_rejects_a_wrong_one() {
        let mut rng = Rng::for_task(3, Stream::Test, 0);
        let p_ok =
            chi2_sphere(10, 20, 200_000, || Some(cosine_hemisphere(rng.uniform2())), |w| cosine_hemisphere_pdf(w.z));
        assert!(p_ok > 1e-3, "correct cosine sampler rejected: p = {p_ok}");
        let mut rng = Rng::for_task(4, Stream::Test, 0);
        // Uniform-sphere samples folded to the upper hemisphere, claimed to be cosine-distributed.
        let p_bad = chi2_sphere(
            10,
            20,
            200_000,
            || {
                let w = uniform_sphere(rng.uniform2());
                Some(DVec3::new(w.x, w.y, w.z.abs()))
            },
            |w| cosine_hemisphere_pdf(w.z),
        );
        assert!(p_bad < 1e-6, "wrong sampler accepted: p = {p_bad}");
        let mut rng = Rng::for_task(5, Stream::Test, 0);
        let p_sphere = chi2_sphere(10, 20, 200_000, || Some(uniform_sphere(rng.uniform2())), |_| uniform_sphere_pdf());
        assert!(p_sphere > 1e-3, "uniform sphere rejected: p = {p_sphere}");
    }

    #[test]
    fn one_dimensional_test_rejects_a_shifted_density() {
        let mut rng = Rng::for_task(6, Stream::Test, 0);
        // Samples of the density 2x on [0,1] by inversion.
        let p_ok = chi2_1d((0.0, 1.0), 50, 100_000, || Some(rng.uniform().sqrt()), |x| 2.0 * x);
        assert!(p_ok > 1e-3, "p = {p_ok}");
        let mut rng = Rng::for_task(7, Stream::Test, 0);
        let p_bad = chi2_1d((0.0, 1.0), 50, 100_000, || Some(rng.uniform()), |x| 2.0 * x);
        assert!(p_bad < 1e-6, "p = {p_bad}");
    }
}
