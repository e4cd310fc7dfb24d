//! Wavelength sampling: chi-square tests against the spectrum itself, normalisation, and the
//! accuracy of the piecewise-linear representation of smooth spectra.

use morgana::quadrature::gauss_legendre;
use morgana::rng::{Rng, Stream};
use morgana::spectrum::{RgbSigmoid, Spectrum, SpectrumSampler, Tabulated};
use morgana::testing::chi2::chi2_1d;

const SIGNIFICANCE: f64 = 1e-3;

fn tabulated() -> Spectrum {
    // Domain 420–680 nm inside a 400–700 nm range, so the density jumps at both domain edges.
    Spectrum::Tabulated(
        Tabulated::new(vec![420.0, 470.0, 500.0, 560.0, 600.0, 680.0], vec![0.2, 1.0, 0.1, 0.9, 0.9, 0.3]).unwrap(),
    )
}

fn spiky() -> Spectrum {
    // Narrow emission lines (2 nm wide) on a faint continuum, as in a gas-discharge lamp.
    let mut nm = vec![380.0];
    let mut values = vec![0.01];
    for (centre, height) in [(436.0, 40.0), (546.0, 100.0), (578.0, 25.0), (611.0, 60.0)] {
        nm.extend([centre - 1.0, centre, centre + 1.0]);
        values.extend([0.01, height, 0.01]);
    }
    nm.push(780.0);
    values.push(0.01);
    Spectrum::Tabulated(Tabulated::new(nm, values).unwrap())
}

/// Chi-square p-value of `sampler` against the exact normalised spectrum s / ∫s.
fn p_value(spectrum: &Spectrum, range: (f64, f64), bins: usize, seed: u64) -> f64 {
    let sampler = SpectrumSampler::new(spectrum, range.0, range.1).unwrap();
    let total = spectrum.integral(range.0, range.1);
    let mut rng = Rng::for_task(seed, Stream::Test, 0);
    chi2_1d(range, bins, 400_000, || Some(sampler.sample(rng.uniform()).0), |l| spectrum.eval(l) / total)
}

#[test]
fn tabulated_samples_follow_the_spectrum() {
    let p = p_value(&tabulated(), (400.0, 700.0), 150, 1);
    assert!(p > SIGNIFICANCE, "p = {p}");
}

#[test]
fn blackbody_samples_follow_planck() {
    // 0.5 nm bins, finer than the representation's grid, so the inversion inside each grid
    // segment is tested too.
    for (i, t) in [1500.0, 5800.0, 20_000.0].into_iter().enumerate() {
        let p = p_value(&Spectrum::Blackbody { temperature_k: t }, (360.0, 830.0), 940, 10 + i as u64);
        assert!(p > SIGNIFICANCE, "T = {t}: p = {p}");
    }
}

#[test]
fn spiky_samples_follow_the_lines() {
    // 0.5 nm bins resolve the 2 nm-wide lines.
    let p = p_value(&spiky(), (380.0, 780.0), 800, 2);
    assert!(p > SIGNIFICANCE, "p = {p}");
}

#[test]
fn a_wrong_claim_is_rejected() {
    // Sampling a 3000 K black body while claiming 3300 K must fail the test.
    let sampler = SpectrumSampler::new(&Spectrum::Blackbody { temperature_k: 3000.0 }, 360.0, 830.0).unwrap();
    let claimed = Spectrum::Blackbody { temperature_k: 3300.0 };
    let total = claimed.integral(360.0, 830.0);
    let mut rng = Rng::for_task(3, Stream::Test, 0);
    let p = chi2_1d((360.0, 830.0), 94, 400_000, || Some(sampler.sample(rng.uniform()).0), |l| claimed.eval(l) / total);
    assert!(p < 1e-6, "p = {p}");
}

#[test]
fn pdf_is_normalised_and_matches_sample() {
    let sigmoid = Spectrum::RgbReflectance(RgbSigmoid::fit([0.8, 0.2, 0.1]).unwrap());
    let cases = [
        (tabulated(), 400.0, 700.0),
        (spiky(), 380.0, 780.0),
        (Spectrum::Blackbody { temperature_k: 2700.0 }, 360.0, 830.0),
        (sigmoid, 380.0, 780.0),
        (Spectrum::Constant(3.0).scaled(2.0), 500.0, 510.0),
    ];
    for (s, lo, hi) in cases {
        let sampler = SpectrumSampler::new(&s, lo, hi).unwrap();
        // ∫ pdf over the range, piece by piece (the pdf is linear on each piece, so a
        // Gauss–Legendre rule per piece is exact).
        let nodes = sampler.nodes();
        let mass: f64 = nodes.windows(2).map(|w| gauss_legendre(&|l| sampler.pdf(l), w[0], w[1], 1)).sum();
        assert!((mass - 1.0).abs() < 1e-9, "{s:?}: ∫pdf = {mass}");
        assert_eq!(sampler.pdf(lo - 1.0), 0.0);
        assert_eq!(sampler.pdf(hi + 1.0), 0.0);
        let mut rng = Rng::for_task(4, Stream::Test, 0);
        for _ in 0..1000 {
            let (l, pdf) = sampler.sample(rng.uniform());
            assert!((lo..=hi).contains(&l));
            assert!((pdf - sampler.pdf(l)).abs() <= 1e-9 * pdf.max(1e-12), "{l}: {pdf}");
            assert!(pdf > 0.0);
        }
        // Endpoints of u map to the ends of the support.
        assert!(sampler.sample(0.0).0 >= lo && sampler.sample(1.0).0 <= hi);
    }
}

#[test]
fn integral_matches_the_spectrum() {
    // Exact for piecewise-linear spectra.
    for (s, lo, hi) in [(tabulated(), 400.0, 700.0), (spiky(), 380.0, 780.0), (tabulated(), 450.0, 650.0)] {
        let sampler = SpectrumSampler::new(&s, lo, hi).unwrap();
        let want = s.integral(lo, hi);
        assert!((sampler.integral() - want).abs() < 1e-12 * want, "{} vs {want}", sampler.integral());
    }
    // Tabulated by hand: the triangle (0, 1, 0) over 500–520 nm has area 10.
    let tri = Spectrum::Tabulated(Tabulated::new(vec![500.0, 510.0, 520.0], vec![0.0, 1.0, 0.0]).unwrap());
    let sampler = SpectrumSampler::new(&tri.scaled(3.0), 400.0, 700.0).unwrap();
    assert!((sampler.integral() - 30.0).abs() < 1e-12);
    // Within the representation tolerance for smooth spectra.
    for t in [1000.0, 3000.0, 6500.0, 20_000.0] {
        let s = Spectrum::Blackbody { temperature_k: t };
        let sampler = SpectrumSampler::new(&s, 360.0, 830.0).unwrap();
        let want = s.integral(360.0, 830.0);
        assert!(((sampler.integral() - want) / want).abs() < 1e-4, "T = {t}");
    }
}

#[test]
fn smooth_representation_error_is_bounded() {
    let sigmoid = Spectrum::RgbReflectance(RgbSigmoid::fit([0.05, 0.9, 0.1]).unwrap());
    let mut cases: Vec<Spectrum> = [800.0, 1000.0, 3000.0, 6500.0, 20_000.0]
        .into_iter()
        .map(|t| Spectrum::Blackbody { temperature_k: t })
        .collect();
    cases.push(sigmoid);
    for s in cases {
        let (lo, hi) = (360.0, 830.0);
        let sampler = SpectrumSampler::new(&s, lo, hi).unwrap();
        let total = sampler.integral();
        let max = sampler.nodes().iter().map(|&l| s.eval(l)).fold(0.0, f64::max);
        // Dense check, 16 points per segment, against the exact spectrum.
        let mut worst = 0.0f64;
        for w in sampler.nodes().windows(2) {
            for k in 0..=16 {
                let l = w[0] + (w[1] - w[0]) * k as f64 / 16.0;
                worst = worst.max((sampler.pdf(l) * total - s.eval(l)).abs());
            }
        }
        assert!(worst <= 1.05e-4 * max, "{s:?}: |s − f̃| = {worst} vs max {max}");
    }
}

#[test]
fn refuses_unsamplable_spectra() {
    assert!(SpectrumSampler::new(&Spectrum::Constant(0.0), 400.0, 700.0).is_none());
    assert!(SpectrumSampler::new(&Spectrum::Constant(-1.0), 400.0, 700.0).is_none());
    assert!(SpectrumSampler::new(&tabulated(), 700.0, 800.0).is_none());
    assert!(SpectrumSampler::new(&Spectrum::Constant(1.0), 700.0, 400.0).is_none());
    assert!(SpectrumSampler::new(&Spectrum::Constant(1.0), f64::NAN, 400.0).is_none());
    let negative = Spectrum::Tabulated(Tabulated::new(vec![400.0, 700.0], vec![1.0, -0.1]).unwrap());
    assert!(SpectrumSampler::new(&negative, 400.0, 700.0).is_none());
}
