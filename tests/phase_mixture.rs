//! The σ_s(λ)-weighted mixture: sea water (Morel's b_w(λ) = 0.0029 (λ/500)^−4.32 m⁻¹ with the
//! pure-water phase function) plus particles (b_p = 0.005 m⁻¹, Henyey–Greenstein g = 0.924).

mod phase_common;

use glam::DVec3;
use morgana::media::phase::{MixtureComponent, PhaseFunction};
use morgana::rng::{Rng, Stream};
use morgana::spectrum::{Spectrum, Tabulated};
use morgana::testing::chi2::chi2_sphere;
use phase_common::sphere_integral;
use std::f64::consts::PI;

const B_P: f64 = 0.005;
const G_P: f64 = 0.924;

/// Morel's sea-water scattering coefficient (m⁻¹).
fn b_w(nm: f64) -> f64 {
    0.0029 * (nm / 500.0).powf(-4.32)
}

/// b_w tabulated every 10 nm over 350–800 nm (exact at the nodes used below).
fn water_sigma_s() -> Spectrum {
    let nm: Vec<f64> = (0..=45).map(|i| 350.0 + 10.0 * i as f64).collect();
    let values = nm.iter().map(|l| b_w(*l)).collect();
    Spectrum::Tabulated(Tabulated::new(nm, values).unwrap())
}

fn sea_water() -> PhaseFunction {
    PhaseFunction::mixture(vec![
        MixtureComponent::new(water_sigma_s(), PhaseFunction::pure_water()),
        MixtureComponent::new(Spectrum::Constant(B_P), PhaseFunction::henyey_greenstein(G_P).unwrap()),
    ])
    .unwrap()
}

/// The published pure-water and HG formulas, weighted by b_w(λ) and b_p.
fn expected(nm: f64, mu: f64) -> f64 {
    let water = 0.06225 * (1.0 + 0.835 * mu * mu);
    let particles = (1.0 - G_P * G_P) / (4.0 * PI * (1.0 + G_P * G_P - 2.0 * G_P * mu).powf(1.5));
    (b_w(nm) * water + B_P * particles) / (b_w(nm) + B_P)
}

#[test]
fn the_mixture_weights_each_phase_function_by_its_scattering_coefficient() {
    let p = sea_water();
    for nm in [400.0, 550.0, 700.0] {
        for mu in [-1.0, -0.5, 0.0, 0.5, 0.9, 1.0] {
            let (got, want) = (p.eval(nm, mu), expected(nm, mu));
            assert!((got / want - 1.0).abs() < 3e-5, "{nm} nm, μ = {mu}: {got} vs {want}");
        }
        let integral = sphere_integral(&|mu| p.eval(nm, mu), &[]);
        assert!((integral - 1.0).abs() < 1e-9, "{nm} nm: ∫ p dω = {integral}");
    }
    // At 400 nm water scatters 0.0076 m⁻¹, more than the particles: backscatter is 2.4× that at 700.
    let back = |nm: f64| p.eval(nm, -1.0);
    assert!(back(400.0) > 2.0 * back(700.0), "{} vs {}", back(400.0), back(700.0));
    assert!(p.depends_on_wavelength());
}

#[test]
fn the_mixture_mean_cosine_is_the_scattering_weighted_mean() {
    let p = sea_water();
    for nm in [400.0, 500.0, 700.0] {
        let want = B_P * G_P / (b_w(nm) + B_P);
        let got = p.mean_cosine(nm);
        assert!((got - want).abs() < 1e-12, "{nm} nm: {got} vs {want}");
        println!("sea water at {nm} nm: b_w = {:.5} m⁻¹, mean cosine {got:.4}", b_w(nm));
    }
}

#[test]
fn sampling_picks_components_in_proportion_to_their_scattering_at_that_wavelength() {
    let p = sea_water();
    let sample_at = |seed: u64, sample_nm: f64, claimed_nm: f64| {
        let mut rng = Rng::for_task(seed, Stream::Test, 0);
        let p = &p;
        chi2_sphere(
            400,
            8,
            1_000_000,
            || Some(p.sample(sample_nm, DVec3::Z, rng.uniform2()).0),
            |w| p.pdf(claimed_nm, w.z),
        )
    };
    let ok = sample_at(90, 400.0, 400.0);
    println!("sea water at 400 nm: chi-square p = {ok:.4}");
    assert!(ok > 1e-3, "p = {ok}");
    // Samples drawn with the weights of 400 nm do not follow the density at 700 nm.
    let wrong = sample_at(91, 400.0, 700.0);
    assert!(wrong < 1e-9, "400 nm samples accepted as 700 nm: p = {wrong}");
}

#[test]
fn where_nothing_scatters_the_components_count_equally() {
    // Outside 350–800 nm both tabulated σ_s are zero: the result is still a normalised density.
    let zero_outside = |v: f64| Spectrum::Tabulated(Tabulated::new(vec![350.0, 800.0], vec![v, v]).unwrap());
    let p = PhaseFunction::mixture(vec![
        MixtureComponent::new(zero_outside(0.01), PhaseFunction::rayleigh()),
        MixtureComponent::new(zero_outside(0.03), PhaseFunction::isotropic()),
    ])
    .unwrap();
    let want = 0.5 * 3.0 / (16.0 * PI) * 2.0 + 0.5 / (4.0 * PI);
    assert!((p.eval(300.0, 1.0) - want).abs() < 1e-15, "{}", p.eval(300.0, 1.0));
    let mut rng = Rng::for_task(92, Stream::Test, 0);
    let (wo, pdf) = p.sample(300.0, DVec3::X, rng.uniform2());
    assert!(wo.is_finite() && (pdf - p.pdf(300.0, wo.x)).abs() < 1e-12);
}

#[test]
fn invalid_mixtures_are_rejected() {
    let e = PhaseFunction::mixture(vec![]).unwrap_err();
    assert!(e.contains("no components: give at least one"), "{e}");
    let e = PhaseFunction::mixture(vec![
        MixtureComponent::new(Spectrum::Constant(0.1), PhaseFunction::isotropic()),
        MixtureComponent::new(Spectrum::Constant(-0.1), PhaseFunction::rayleigh()),
    ])
    .unwrap_err();
    assert!(e.contains("component #1") && e.contains("must be ≥ 0 at every wavelength"), "{e}");
    let bad = Spectrum::Tabulated(Tabulated::new(vec![400.0, 500.0], vec![0.1, -0.2]).unwrap());
    assert!(PhaseFunction::mixture(vec![MixtureComponent::new(bad, PhaseFunction::isotropic())]).is_err());
    let fixed = PhaseFunction::mixture(vec![
        MixtureComponent::new(Spectrum::Constant(0.1), PhaseFunction::isotropic()),
        MixtureComponent::new(Spectrum::Constant(0.2), PhaseFunction::rayleigh()),
    ])
    .unwrap();
    assert!(!fixed.depends_on_wavelength());
}
