//! Closed-form phase functions: normalisation over the sphere, values against the published
//! formulas, mean cosines, and parameter validation. Expected values come from the formulas
//! and the literature cited beside them.

mod phase_common;

use morgana::media::phase::PhaseFunction;
use phase_common::{sampled_mean_cosine, sphere_integral};
use std::f64::consts::PI;

const NM: f64 = 550.0;

fn hg(g: f64) -> PhaseFunction {
    PhaseFunction::henyey_greenstein(g).unwrap()
}

/// Closed-form Henyey–Greenstein (Henyey & Greenstein 1941).
fn hg_formula(g: f64, mu: f64) -> f64 {
    (1.0 - g * g) / (4.0 * PI * (1.0 + g * g - 2.0 * g * mu).powf(1.5))
}

fn analytic_variants() -> Vec<(&'static str, PhaseFunction)> {
    vec![
        ("isotropic", PhaseFunction::isotropic()),
        ("rayleigh", PhaseFunction::rayleigh()),
        ("rayleigh, air's ρ = 0.0283", PhaseFunction::rayleigh_depolarised(0.0283).unwrap()),
        ("rayleigh, ρ = 0.5", PhaseFunction::rayleigh_depolarised(0.5).unwrap()),
        ("pure water", PhaseFunction::pure_water()),
        ("raman", PhaseFunction::raman()),
        ("hg 0", hg(0.0)),
        ("hg 0.5", hg(0.5)),
        ("hg -0.7", hg(-0.7)),
        ("hg 0.924", hg(0.924)),
        ("hg 0.99", hg(0.99)),
        ("schlick 0.6", PhaseFunction::schlick(0.6).unwrap()),
        ("schlick -0.9", PhaseFunction::schlick(-0.9).unwrap()),
        ("schlick from g 0.924", PhaseFunction::schlick_from_g(0.924).unwrap()),
        ("two-term hg", PhaseFunction::two_term_hg(0.95, 0.93, -0.4).unwrap()),
    ]
}

#[test]
fn every_closed_form_phase_function_integrates_to_one_over_the_sphere() {
    for (name, p) in analytic_variants() {
        let integral = sphere_integral(&|mu| p.eval(NM, mu), &[]);
        assert!((integral - 1.0).abs() < 1e-9, "{name}: ∫ p dω = {integral}");
    }
}

#[test]
fn the_published_pure_water_formula_integrates_to_one() {
    // Morel (1974) via Mobley (1994): 0.06225 (1 + 0.835 cos²θ); 4π · 0.06225 · (1 + 0.835/3)
    // = 0.99997, one to the four digits printed.
    let published = |mu: f64| 0.06225 * (1.0 + 0.835 * mu * mu);
    let integral = sphere_integral(&published, &[]);
    assert!((integral - 1.0).abs() < 1e-4, "∫ = {integral}");
    let water = PhaseFunction::pure_water();
    for mu in [-1.0, -0.3, 0.0, 0.5, 1.0] {
        let rel = water.eval(NM, mu) / published(mu) - 1.0;
        assert!(rel.abs() < 3e-5, "pure water at μ = {mu}: relative difference {rel}");
    }
}

#[test]
fn rayleigh_and_raman_match_their_published_formulas() {
    let rayleigh = PhaseFunction::rayleigh();
    for mu in [-1.0f64, -0.4, 0.0, 0.7, 1.0] {
        let want = 3.0 / (16.0 * PI) * (1.0 + mu * mu);
        assert!((rayleigh.eval(NM, mu) - want).abs() < 1e-15, "Rayleigh at μ = {mu}");
    }
    // Mobley (1994): 0.067 (1 + 0.55 cos²ψ); the normalised constant is 1/(4π(1 + 0.55/3)) =
    // 0.067249, which rounds to the published two digits.
    let raman = PhaseFunction::raman();
    assert!((raman.eval(NM, 0.0) - 0.067).abs() < 0.0005, "Raman K = {}", raman.eval(NM, 0.0));
    assert!((raman.eval(NM, 1.0) / raman.eval(NM, 0.0) - 1.55).abs() < 1e-12);
}

/// Chandrasekhar (1950, §I.18; Hansen & Travis 1974, Eq. 2.15), written as published:
/// P(Θ) = 3/(4(1 + 2γ)) [(1 + 3γ) + (1 − γ) cos²Θ], γ = ρ/(2 − ρ), normalised to 4π; the phase
/// function per steradian is P/(4π). ρ = 0 is the classical Rayleigh 3/(16π)(1 + μ²).
#[test]
fn depolarised_rayleigh_matches_chandrasekhars_form() {
    for rho in [0.0, 0.0279, 0.0283, 0.1, 0.6] {
        let p = PhaseFunction::rayleigh_depolarised(rho).unwrap();
        let gamma = rho / (2.0 - rho);
        for mu in [-1.0f64, -0.6, 0.0, 0.35, 1.0] {
            let want = 3.0 / (4.0 * (1.0 + 2.0 * gamma)) * ((1.0 + 3.0 * gamma) + (1.0 - gamma) * mu * mu) / (4.0 * PI);
            assert!((p.eval(NM, mu) / want - 1.0).abs() < 1e-13, "ρ = {rho}, μ = {mu}: {} vs {want}", p.eval(NM, mu));
        }
    }
    // Air (ρ ≈ 0.028): forward over sideways scattering P(0)/P(90°) = 1 + c with
    // c = (1 − ρ)/(1 + ρ) = 0.9455, instead of the classical 2.
    let air = PhaseFunction::rayleigh_depolarised(0.028).unwrap();
    assert!((air.eval(NM, 1.0) / air.eval(NM, 0.0) - (1.0 + 0.972 / 1.028)).abs() < 1e-12);
    for bad in [-0.01, 1.0, f64::NAN] {
        let e = error_of(PhaseFunction::rayleigh_depolarised(bad));
        assert!(e.contains("depolarisation ratio") && e.contains("[0, 1)"), "{e}");
    }
}

#[test]
fn henyey_greenstein_matches_the_closed_form_and_its_backscatter_fraction() {
    for g in [-0.7, 0.0, 0.3, 0.924] {
        let p = hg(g);
        for mu in [-1.0, -0.2, 0.0, 0.6, 0.99, 1.0] {
            let (got, want) = (p.eval(NM, mu), hg_formula(g, mu));
            assert!((got / want - 1.0).abs() < 1e-12, "HG g = {g}, μ = {mu}: {got} vs {want}");
        }
    }
    // Backscatter fraction B = (1 − g)/(2g) [(1 + g)/√(1 + g²) − 1] (Mobley, Ocean Optics Web Book).
    let g: f64 = 0.924;
    let want = (1.0 - g) / (2.0 * g) * ((1.0 + g) / (1.0 + g * g).sqrt() - 1.0);
    let p = hg(g);
    let back = sphere_integral(&|mu| if mu < 0.0 { p.eval(NM, mu) } else { 0.0 }, &[90.0]);
    assert!((back - want).abs() < 1e-10, "B = {back} vs {want}");
}

#[test]
fn schlick_and_two_term_hg_match_their_closed_forms() {
    // Schlick: (1 − k²)/(4π (1 − kμ)²) with k > 0 forward.
    let k: f64 = 0.6;
    let s = PhaseFunction::schlick(k).unwrap();
    for mu in [-1.0f64, 0.0, 0.5, 1.0] {
        let want = (1.0 - k * k) / (4.0 * PI * (1.0 - k * mu).powi(2));
        assert!((s.eval(NM, mu) / want - 1.0).abs() < 1e-12, "Schlick μ = {mu}");
    }
    // k = 1.55 g − 0.55 g³ (Pharr & Humphreys 2004): for g = 0.5, k = 0.70625.
    let from_g = PhaseFunction::schlick_from_g(0.5).unwrap();
    let k = 0.70625f64;
    let want = (1.0 - k * k) / (4.0 * PI * (1.0 - k * 0.3f64).powi(2));
    assert!((from_g.eval(NM, 0.3) / want - 1.0).abs() < 1e-12);
    let t = PhaseFunction::two_term_hg(0.8, 0.9, -0.5).unwrap();
    for mu in [-1.0, 0.0, 0.9] {
        let want = 0.8 * hg_formula(0.9, mu) + 0.2 * hg_formula(-0.5, mu);
        assert!((t.eval(NM, mu) / want - 1.0).abs() < 1e-12, "two-term μ = {mu}");
    }
}

#[test]
fn mean_cosines_match_closed_forms_quadrature_and_samples() {
    // (phase, closed-form mean cosine)
    let schlick_mean = |k: f64| 1.0 / k - (1.0 - k * k) * k.atanh() / (k * k);
    let cases = [
        ("isotropic", PhaseFunction::isotropic(), 0.0),
        ("rayleigh", PhaseFunction::rayleigh(), 0.0),
        ("pure water", PhaseFunction::pure_water(), 0.0),
        ("raman", PhaseFunction::raman(), 0.0),
        ("hg 0.924 (Lucifer's ocean)", hg(0.924), 0.924),
        ("hg -0.7", hg(-0.7), -0.7),
        ("schlick 0.6", PhaseFunction::schlick(0.6).unwrap(), schlick_mean(0.6)),
        ("schlick 0.05", PhaseFunction::schlick(0.05).unwrap(), schlick_mean(0.05)),
        ("two-term hg", PhaseFunction::two_term_hg(0.95, 0.93, -0.4).unwrap(), 0.95 * 0.93 - 0.05 * 0.4),
    ];
    for (i, (name, p, want)) in cases.iter().enumerate() {
        let reported = p.mean_cosine(NM);
        let quadrature = sphere_integral(&|mu| mu * p.eval(NM, mu), &[]);
        assert!((reported - want).abs() < 1e-9, "{name}: mean_cosine() = {reported}, closed form {want}");
        assert!((quadrature - want).abs() < 1e-9, "{name}: ∫ μ p dω = {quadrature}, closed form {want}");
        let (mean, sem) = sampled_mean_cosine(p, NM, 200_000, 100 + i as u64);
        assert!((mean - want).abs() < 5.0 * sem + 1e-12, "{name}: sampled mean {mean} ± {sem} vs {want}");
        println!("{name}: mean cosine {reported:.6} (closed form {want:.6}, sampled {mean:.5} ± {sem:.5})");
    }
}

#[test]
fn schlick_from_g_overestimates_the_mean_cosine_of_forward_lobes() {
    // The k(g) fit matches the shape of HG(g), not its mean cosine: the closed form
    // ⟨μ⟩ = 1/k − (1 − k²) artanh(k)/k² exceeds g by 0.032 at g = 0.5 and 0.066 at g = 0.924
    // (Lucifer's ocean), so ocean scenes that need the right g should use HG or a table.
    let k_of = |g: f64| 1.55 * g - 0.55 * g * g * g;
    for (g, excess) in [(0.5, 0.031_996), (0.924, 0.065_710), (-0.5, -0.031_996)] {
        let k = k_of(g);
        let closed = 1.0 / k - (1.0 - k * k) * k.atanh() / (k * k);
        let m = PhaseFunction::schlick_from_g(g).unwrap().mean_cosine(NM);
        assert!((m - closed).abs() < 1e-12 && (m - g - excess).abs() < 1e-5, "g = {g}: mean cosine {m}");
        println!("Schlick from g = {g}: k = {k:.5}, mean cosine {m:.5}");
    }
}

fn error_of(r: Result<PhaseFunction, String>) -> String {
    match r {
        Ok(p) => panic!("accepted but should have been rejected: {p:?}"),
        Err(e) => e,
    }
}

#[test]
fn invalid_parameters_are_rejected_with_what_is_allowed() {
    let e = error_of(PhaseFunction::henyey_greenstein(1.2));
    assert!(e.contains("g = 1.2 is out of range: it must lie strictly between −1 and 1"), "{e}");
    for g in [1.0, -1.0, f64::NAN, f64::INFINITY] {
        let e = error_of(PhaseFunction::henyey_greenstein(g));
        assert!(e.contains("strictly between −1 and 1"), "{e}");
    }
    let e = error_of(PhaseFunction::schlick(-1.0));
    assert!(e.contains("k = -1 is out of range"), "{e}");
    // k = 1.55g − 0.55g³ reaches 1 at g = 0.93812: g = 0.95 would give k > 1.
    let e = error_of(PhaseFunction::schlick_from_g(0.95));
    assert!(e.contains("0.93812") && e.contains("= 1.000944"), "{e}");
    assert!(PhaseFunction::schlick_from_g(0.938).is_ok());
    let e = error_of(PhaseFunction::two_term_hg(1.5, 0.9, -0.3));
    assert!(e.contains("w = 1.5 is out of range: it must lie in [0, 1]"), "{e}");
    let e = error_of(PhaseFunction::two_term_hg(0.5, 0.9, -1.0));
    assert!(e.contains("second term") && e.contains("g = -1"), "{e}");
    let e = morgana::media::phase::CosSquared::new(-0.5).unwrap_err();
    assert!(e.contains("c = -0.5 is out of range") && e.contains("≥ 0"), "{e}");
}

#[test]
fn samplers_invert_the_closed_form_cdfs() {
    // F(sample(u)) = u for the CDFs F(μ) = 2π ∫₋₁^μ p, written out from each density.
    let cos2_cdf = |c: f64, mu: f64| ((mu + 1.0) + c * (mu.powi(3) + 1.0) / 3.0) / (2.0 * (1.0 + c / 3.0));
    let hg_cdf =
        |g: f64, mu: f64| (1.0 - g * g) / (2.0 * g) * (1.0 / (1.0 + g * g - 2.0 * g * mu).sqrt() - 1.0 / (1.0 + g));
    let schlick_cdf = |k: f64, mu: f64| (1.0 - k * k) / (2.0 * k) * (1.0 / (1.0 - k * mu) - 1.0 / (1.0 + k));
    type Cdf = Box<dyn Fn(f64) -> f64>;
    let cases: Vec<(PhaseFunction, Cdf)> = vec![
        (PhaseFunction::isotropic(), Box::new(|mu| (mu + 1.0) / 2.0)),
        (PhaseFunction::rayleigh(), Box::new(move |mu| cos2_cdf(1.0, mu))),
        (PhaseFunction::pure_water(), Box::new(move |mu| cos2_cdf(0.835, mu))),
        (PhaseFunction::raman(), Box::new(move |mu| cos2_cdf(0.55, mu))),
        (PhaseFunction::rayleigh_depolarised(0.0283).unwrap(), Box::new(move |mu| cos2_cdf(0.9717 / 1.0283, mu))),
        (hg(0.924), Box::new(move |mu| hg_cdf(0.924, mu))),
        (hg(-0.3), Box::new(move |mu| hg_cdf(-0.3, mu))),
        (PhaseFunction::schlick(0.9).unwrap(), Box::new(move |mu| schlick_cdf(0.9, mu))),
    ];
    for (p, cdf) in &cases {
        for i in 0..=100 {
            let u = i as f64 / 100.0;
            let got = cdf(p.sample_cos_theta(NM, u));
            assert!((got - u).abs() < 1e-12, "{p:?}: F(sample({u})) = {got}");
        }
    }
}
