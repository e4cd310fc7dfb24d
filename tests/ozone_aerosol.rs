//! Ozone and aerosols in the scattering atmosphere (`ozone_du`, `aerosol` of a
//! `[[medium]] type = "atmosphere"`): the ozone column's optical depth at the Chappuis peak
//! against σ·N, the aerosols' against Ångström's law, the whole atmosphere's transmittance —
//! computed and path-traced — against Beer–Lambert on the summed profiles, energy conservation
//! over a black Earth, a constituent of zero amount changing nothing, the mixture's phase
//! sampling against its density, and the scene errors.

mod common;

use common::sky::{ZENITH_BEAM, black_earth, directional_beam};
use common::{scene, scene_error};
use glam::DVec3;
use morgana::media::Medium;
use morgana::media::rayleigh_air::cross_section_m2;
use morgana::media::tracking::transmittance;
use morgana::photon::{MapKind, PassSettings, PhotonSink, PhotonStats, shoot};
use morgana::photon_map::PhotonPath;
use morgana::rng::{Rng, Stream};

/// Bogumil et al. (2003), SCIAMACHY, 293 K, as published: σ(603.0779 nm) = 5.30671 × 10⁻²¹ cm².
const CHAPPUIS_NM: f64 = 603.0779;
const CHAPPUIS_SIGMA_M2: f64 = 5.30671e-25;
/// 1 DU = 2.6867 × 10¹⁶ molecules cm⁻² (WMO-No. 8): 300 DU = 8.0601 × 10²² m⁻².
const MOLECULES_PER_M2_PER_DU: f64 = 2.6867e20;

fn air(s: &morgana::scene::Scene) -> &Medium {
    s.world.media.iter().find(|m| m.name == "air").expect("the air medium")
}

/// Vertical optical depth of the whole atmosphere at `nm`, from the transmittance up a vertical
/// chord from the ground.
fn vertical_tau(m: &Medium, nm: f64) -> f64 {
    let mut rng = Rng::for_task(1, Stream::Test, 0);
    -transmittance(m, nm, DVec3::ZERO, DVec3::Y, 1e7, &mut rng).ln()
}

/// USA76 number density N = P N_A/(R* T) at geometric height `h` (the standard's constants).
fn usa76_n(h: f64) -> f64 {
    let s = morgana::atmosphere::usa76::at_geometric(h);
    s.pressure_pa * 6.022_169e23 / (8.314_32 * s.temperature_k)
}

/// ∫ N dh from the ground to the 86 km top by Simpson's rule on 1 m steps.
fn air_column_per_m2() -> f64 {
    let n = 86_000usize;
    let f = |i: usize| usa76_n(i as f64);
    let inner: f64 = (1..n).map(|i| if i % 2 == 1 { 4.0 * f(i) } else { 2.0 * f(i) }).sum();
    (f(0) + inner + f(n)) / 3.0
}

/// 300 DU of ozone alone (no Rayleigh): the vertical optical depth at the Chappuis peak is
/// σ·N = 5.30671e-25 m² × 300 × 2.6867e20 m⁻² = 0.042773 (the column is the scene's by
/// construction, so this checks the profile's scaling, its tabulation and quadrature, and the
/// cross-section table against the published value). To 10⁻⁵: the profile is log-linear between
/// AFGL's levels, so its slope breaks at each level, and the 16-point rule on 1 km pieces of the
/// 5 m table integrates across those breaks with a relative error of 2 × 10⁻⁶ (the Simpson
/// normalisation on 1 m steps agrees with the exact layer integrals to 10⁻⁹).
#[test]
fn ozone_column_optical_depth_at_the_chappuis_peak_is_sigma_n() {
    let s = scene(&black_earth(550.0, 650.0, "rayleigh = false\nozone_du = 300", ZENITH_BEAM));
    let got = vertical_tau(air(&s), CHAPPUIS_NM);
    let want = CHAPPUIS_SIGMA_M2 * 300.0 * MOLECULES_PER_M2_PER_DU;
    println!("τ_O3({CHAPPUIS_NM} nm, 300 DU) = {got:.6}, σN = {want:.6}");
    assert!((got / want - 1.0).abs() < 1e-5, "τ = {got}, σN = {want}");
    // Twice the column, twice the depth; none, none.
    let s2 = scene(&black_earth(550.0, 650.0, "rayleigh = false\nozone_du = 600", ZENITH_BEAM));
    assert!((vertical_tau(air(&s2), CHAPPUIS_NM) / (2.0 * want) - 1.0).abs() < 1e-5);
}

/// A scene's own ozone: `ozone = { column_du }` is `ozone_du` (the AFGL shape, to the bit); a
/// profile file's levels give the column σ ∫ n dh, read log-linearly or linearly between them,
/// scaled to `column_du` when it is given; a cross-section table replaces Bogumil's.
#[test]
fn an_ozone_profile_file_and_cross_section_give_their_column() {
    let tau = |extra: &str| vertical_tau(air(&scene(&black_earth(550.0, 650.0, extra, ZENITH_BEAM))), CHAPPUIS_NM);
    assert_eq!(tau("rayleigh = false\nozone = { column_du = 300 }"), tau("rayleigh = false\nozone_du = 300"));
    // Two levels, 1e12 cm⁻³ at the ground and 1e10 at the top (86 km): log-linear, the column
    // is (n₀ − n₁) H_top / ln(n₀/n₁); linear, (n₀ + n₁) H_top / 2.
    let file = std::env::temp_dir().join(format!("morgana_ozone_{}.csv", std::process::id()));
    std::fs::write(&file, "altitude_m,number_density_per_cm3\n0,1e12\n86000,1e10\n").unwrap();
    let f = file.display();
    let (n0, n1, top): (f64, f64, f64) = (1e18, 1e16, 86_000.0);
    let log_column = (n0 - n1) * top / (n0 / n1).ln();
    let linear_column = 0.5 * (n0 + n1) * top;
    for (extra, column) in [
        (format!("ozone = {{ profile = \"{f}\" }}"), log_column),
        (format!("ozone = {{ profile = \"{f}\", interpolation = \"linear\" }}"), linear_column),
        (format!("ozone = {{ profile = \"{f}\", column_du = 250 }}"), 250.0 * MOLECULES_PER_M2_PER_DU),
    ] {
        let got = tau(&format!("rayleigh = false\n{extra}"));
        let want = CHAPPUIS_SIGMA_M2 * column;
        assert!((got / want - 1.0).abs() < 1e-5, "{extra}: τ = {got}, σ ∫n dh = {want}");
    }
    let sigma = "cross_section_cm2 = { nm = [500, 700], values = [2e-21, 4e-21] }";
    let got = tau(&format!("rayleigh = false\nozone = {{ profile = \"{f}\", {sigma} }}"));
    let want = (2e-25 + 2e-25 * (CHAPPUIS_NM - 500.0) / 200.0) * log_column;
    assert!((got / want - 1.0).abs() < 1e-5, "given σ: τ = {got}, σ ∫n dh = {want}");
    let _ = std::fs::remove_file(&file);
}

/// Aerosols alone: the vertical optical depth is β (λ/1 µm)^−α (Ångström 1929) at every
/// wavelength, whatever the scale height (the profile integrates to one over the column).
#[test]
fn aerosol_optical_depth_follows_angstrom() {
    for (alpha, beta, h) in [(1.3, 0.05, 1200.0), (0.4, 0.2, 3000.0)] {
        let extra = format!(
            "rayleigh = false\naerosol = {{ angstrom_alpha = {alpha:?}, angstrom_beta = {beta:?}, scale_height_m = {h:?}, albedo = 0.9, g = 0.7 }}"
        );
        let s = scene(&black_earth(400.0, 800.0, &extra, ZENITH_BEAM));
        for nm in [400.0, 550.0, 700.0, 800.0] {
            let got = vertical_tau(air(&s), nm);
            let want = beta * (nm / 1000.0f64).powf(-alpha);
            assert!((got / want - 1.0).abs() < 1e-5, "α {alpha}, β {beta}, {nm} nm: τ = {got}, βλ^−α = {want}");
        }
    }
}

const HAZE: &str =
    "aerosol = { angstrom_alpha = 1.3, angstrom_beta = 0.1, scale_height_m = 1500, albedo = 1.0, g = 0.7 }";

/// Air + 300 DU ozone + aerosols: the computed transmittance of the whole atmosphere straight up
/// equals exp(−τ_R − τ_O3 − τ_a), each optical depth from its own closed form (Rayleigh:
/// σ_R ∫N dh by Simpson's rule on the USA76 standard; ozone σN; aerosols βλ^−α), to 10⁻⁵ (the
/// ozone quadrature above). Along the 60° chord of a round Earth the mixture's optical depth is
/// the sum of each constituent's alone, to 10⁻¹².
#[test]
fn whole_atmosphere_transmittance_is_beer_lambert_on_the_summed_profile() {
    let all = format!("ozone_du = 300\n{HAZE}");
    let s = scene(&black_earth(550.0, 650.0, &all, ZENITH_BEAM));
    let m = air(&s);
    let nm = CHAPPUIS_NM;
    let tau_r = cross_section_m2(nm, 360.0) * air_column_per_m2();
    let tau_o3 = CHAPPUIS_SIGMA_M2 * 300.0 * MOLECULES_PER_M2_PER_DU;
    let tau_a = 0.1 * (nm / 1000.0f64).powf(-1.3);
    let got = vertical_tau(m, nm);
    println!("τ = {got:.6}: Rayleigh {tau_r:.6} + ozone {tau_o3:.6} + aerosol {tau_a:.6}");
    assert!((got / (tau_r + tau_o3 + tau_a) - 1.0).abs() < 1e-5, "{got} vs {}", tau_r + tau_o3 + tau_a);
    // Slant: the mixture's depth is the sum of its constituents' alone, chord by chord.
    let dir = DVec3::new(60f64.to_radians().sin(), 60f64.to_radians().cos(), 0.0);
    let slant = |extra: &str| {
        let s = scene(&black_earth(550.0, 650.0, extra, ZENITH_BEAM));
        let mut rng = Rng::for_task(2, Stream::Test, 0);
        -transmittance(air(&s), nm, DVec3::ZERO, dir, 1e7, &mut rng).ln()
    };
    let sum = slant("") + slant("rayleigh = false\nozone_du = 300") + slant(&format!("rayleigh = false\n{HAZE}"));
    let mut rng = Rng::for_task(2, Stream::Test, 0);
    let mixed = -transmittance(m, nm, DVec3::ZERO, dir, 1e7, &mut rng).ln();
    assert!((mixed / sum - 1.0).abs() < 1e-12, "{mixed} vs {sum}");
}

/// Shoots `n` photons of the global pass with `seed`, and checks that every emitted watt is
/// accounted for: absorbed by the ground, escaped to space or absorbed in the air (to 10⁻⁹), none
/// truncated. Returns the sink, the statistics and the emitted power.
fn shoot_balanced(s: &morgana::scene::Scene, n: u64, seed: u64) -> (PhotonSink, PhotonStats, f64) {
    let (sink, st) = shoot(&s.world, &PassSettings::of(s), MapKind::Global, n, seed, &|_| {});
    let emitted = n as f64 * st.power_per_photon_w;
    assert_eq!(st.truncated_w, 0.0);
    let out = st.absorbed_surface_w + st.escaped_w + st.absorbed_medium_w;
    assert!((out / emitted - 1.0).abs() < 1e-9, "ground + space + air = {out} of {emitted} W");
    (sink, st, emitted)
}

/// Photons path-traced down through air + ozone + aerosols (delta tracking over the summed
/// majorants): the fraction reaching the ground unscattered is exp(−τ_slant) of the summed
/// optical depths along the 60° chord, within 4 standard errors; with ω = 1 aerosols, all that
/// is lost in the air is ozone's absorption, and every watt is accounted for.
#[test]
fn path_traced_transmittance_and_energy_balance() {
    let light = directional_beam([-0.8660254037844386, -0.5, 0.0]);
    // A 1 nm band at the Chappuis peak: σ_O3 varies by < 0.1 % across it (5.302–5.311e-21 cm²).
    let all = format!("ozone_du = 300\n{HAZE}");
    let s = scene(&black_earth(602.58, 603.58, &all, &light));
    let n = 100_000u64;
    let (sink, st, emitted) = shoot_balanced(&s, n, 21);
    assert!(st.absorbed_medium_w > 0.0, "ozone absorbs");
    // The slant depth from the computed transmittance (checked against closed forms above).
    let dir = DVec3::new(0.8660254037844386, 0.5, 0.0);
    let mut rng = Rng::for_task(3, Stream::Test, 0);
    let want = transmittance(air(&s), CHAPPUIS_NM, DVec3::ZERO, dir, 1e7, &mut rng);
    let direct: f64 = sink.surface.iter().filter(|p| p.path == PhotonPath::Direct).map(|p| p.power_w).sum();
    let got = direct / emitted;
    let se = (want * (1.0 - want) / n as f64).sqrt();
    println!(
        "direct {got:.5} vs exp(−τ) {want:.5} (s.e. {se:.5}); absorbed in air {:.5}",
        st.absorbed_medium_w / emitted
    );
    assert!((got - want).abs() < 4.0 * se, "direct {got} vs {want}");
}

/// Without ozone, ω = 1 aerosols over a black Earth: reflected + transmitted = incident, none
/// absorbed in the air; with ω = 0.8 the air absorbs and the balance still closes.
#[test]
fn unit_albedo_aerosols_conserve_energy_over_a_black_earth() {
    let light = directional_beam([-0.5, -0.8660254037844386, 0.0]);
    for (albedo, absorbs) in [(1.0, false), (0.8, true)] {
        let extra = format!(
            "aerosol = {{ angstrom_alpha = 1.3, angstrom_beta = 0.3, scale_height_m = 1500, albedo = {albedo:?}, g = 0.7 }}"
        );
        let s = scene(&black_earth(500.0, 600.0, &extra, &light));
        let n = 50_000u64;
        let (_, st, _) = shoot_balanced(&s, n, 31);
        assert_eq!(st.absorbed_medium_w > 0.0, absorbs, "ω = {albedo}: absorbed {}", st.absorbed_medium_w);
        assert!(st.escaped_w > 0.0 && st.absorbed_surface_w > 0.0);
    }
}

/// `ozone_du = 0` gives the same photon pass, to the bit, as no ozone: zero extinction adds
/// nothing to any majorant, rate or depth, and ozone does not scatter, so no choice is drawn.
/// An aerosol of zero optical depth leaves the transmittance unchanged to the bit.
#[test]
fn a_constituent_of_zero_amount_changes_nothing() {
    let light = directional_beam([-0.5, -0.8660254037844386, 0.0]);
    let plain = scene(&black_earth(400.0, 700.0, "", &light));
    let zero = scene(&black_earth(400.0, 700.0, "ozone_du = 0", &light));
    let n = 20_000u64;
    let (a_sink, a) = shoot(&plain.world, &PassSettings::of(&plain), MapKind::Global, n, 41, &|_| {});
    let (b_sink, b) = shoot(&zero.world, &PassSettings::of(&zero), MapKind::Global, n, 41, &|_| {});
    assert_eq!(a, b, "photon statistics");
    assert_eq!(a_sink.volume.len(), b_sink.volume.len());
    assert!(a_sink.volume.iter().zip(&b_sink.volume).all(|(p, q)| p.position == q.position && p.power_w == q.power_w));
    let no_haze = scene(&black_earth(
        400.0,
        700.0,
        "aerosol = { angstrom_beta = 0.0, scale_height_m = 1000, albedo = 0.9, g = 0.7 }",
        &light,
    ));
    let dir = DVec3::new(0.5, 0.8660254037844386, 0.0);
    for nm in [400.0, 550.0, 700.0] {
        let mut rng = Rng::for_task(4, Stream::Test, 0);
        let t0 = transmittance(air(&plain), nm, DVec3::ZERO, dir, 1e7, &mut rng);
        let t1 = transmittance(air(&zero), nm, DVec3::ZERO, dir, 1e7, &mut rng);
        let t2 = transmittance(air(&no_haze), nm, DVec3::ZERO, dir, 1e7, &mut rng);
        assert_eq!(t0.to_bits(), t1.to_bits(), "{nm} nm: {t0} vs {t1}");
        assert_eq!(t0.to_bits(), t2.to_bits(), "{nm} nm: {t0} vs {t2}");
    }
}

/// At a height where air and aerosols scatter comparably, directions drawn by the medium at
/// that point follow the density it reports (the scattering-weighted mixture of Rayleigh and
/// Henyey–Greenstein): a χ² test of cos θ.
#[test]
fn the_mixture_at_a_point_samples_its_own_phase_function() {
    let s = scene(&black_earth(540.0, 560.0, HAZE, ZENITH_BEAM));
    let m = air(&s);
    let x = DVec3::new(0.0, 1500.0, 0.0);
    let at = m.at(x);
    let wi = DVec3::new(0.3, -0.9, 0.1).normalize();
    let mut rng = Rng::for_task(5, Stream::Test, 0);
    let p = morgana::testing::chi2::chi2_1d(
        (-1.0, 1.0),
        40,
        200_000,
        || Some(at.phase_sample(550.0, wi, rng.uniform2()).0.dot(wi)),
        |mu| 2.0 * std::f64::consts::PI * at.phase_eval(550.0, mu),
    );
    assert!(p > 1e-3, "p = {p}");
    // Both constituents matter here: forward, the mixture lies well between Rayleigh's
    // 3/(8π) ≈ 0.12 (depolarisation changes it by < 3 %) and Henyey–Greenstein's
    // (1 − g²)/(4π (1 − g)³) = 1.503 sr⁻¹ for g = 0.7.
    let forward = at.phase_eval(550.0, 1.0);
    let hg = (1.0 - 0.49) / (4.0 * std::f64::consts::PI * 0.3f64.powi(3));
    assert!(forward > 0.2 && forward < 0.9 * hg, "p(0°) = {forward}");
}

/// Henyey–Greenstein's density (1 − g²)/(4π (1 + g² − 2gμ)^{3/2}) per steradian (Henyey &
/// Greenstein 1941).
fn hg(g: f64, mu: f64) -> f64 {
    (1.0 - g * g) / (4.0 * std::f64::consts::PI * (1.0 + g * g - 2.0 * g * mu).powf(1.5))
}

/// Plane-parallel single scattering of aerosols alone (Liou 2002, ch. 6; the profile's shape
/// does not matter) for a sun `sun_zenith` from the zenith, E = 1 W m⁻² nm⁻¹, at a view direction
/// `d` (unit, +y up) at wavelength `nm`: looking up from the ground,
/// E ω p(Θ) μ₀/(μ₀ − μ) [e^{−τ/μ₀} − e^{−τ/μ}]; looking down from above the top,
/// E ω p(Θ) μ₀/(μ₀ + μ) [1 − e^{−τ(1/μ₀ + 1/μ)}], with τ = β (λ/1 µm)^−α.
struct SingleScattering<'a> {
    alpha: f64,
    beta: f64,
    sun_zenith: f64,
    albedo: &'a dyn Fn(f64) -> f64,
    phase: &'a dyn Fn(f64) -> f64,
}

impl SingleScattering<'_> {
    fn radiance(&self, d: DVec3, nm: f64) -> f64 {
        let tau = self.beta * (nm / 1000.0f64).powf(-self.alpha);
        let sun = -morgana::sensor::sky_radiance::view_direction(self.sun_zenith, 90.0);
        let (mu0, mu) = (self.sun_zenith.to_radians().cos(), d.y.abs());
        let k = (self.albedo)(nm) * (self.phase)(sun.dot(-d)) * mu0;
        if d.y > 0.0 {
            k / (mu0 - mu) * ((-tau / mu0).exp() - (-tau / mu).exp())
        } else {
            k / (mu0 + mu) * (1.0 - (-tau * (1.0 / mu0 + 1.0 / mu)).exp())
        }
    }

    /// The mean over `lo`–`hi` nm (101 points), as the sensor's band average.
    fn band(&self, d: DVec3, lo: f64, hi: f64) -> f64 {
        (0..=100).map(|i| self.radiance(d, lo + (hi - lo) * i as f64 / 100.0)).sum::<f64>() / 101.0
    }
}

/// Renders aerosols alone in a flat atmosphere over black ground (`aerosol` the TOML table),
/// single scattering (`photons = 0`), one band over `lo`–`hi` nm, with `sky_radiance` sensors on
/// the ground looking `up` and at 100 km looking `down` (32 estimates each), over 8 seeds; checks
/// each direction against `want` within 4 standard errors, the standard error below 2 × 10⁻³ of
/// the value, and returns the means ([up…, down…]).
fn single_scattered_aerosol_sky(
    aerosol: &str,
    (lo, hi): (f64, f64),
    want: &SingleScattering,
    up: &[[f64; 2]],
    down: &[[f64; 2]],
) -> Vec<f64> {
    let world = common::sky::flat_air_over_black_ground()
        .replace("type = \"atmosphere\"\n", &format!("type = \"atmosphere\"\nrayleigh = false\naerosol = {aerosol}\n"));
    let toml = format!(
        "{pixel}\n[integrator]\nphotons = 0\nmarch_step = 200.0\nspp = 1\n{world}\n{sun}\n{sensors}",
        pixel = common::sky::zenith_pixel(1, lo, hi),
        sun = common::sky::point_sun(90.0 - want.sun_zenith),
        sensors = common::sky::ground_and_space_sensors(up, down, 32),
    );
    let runs = common::sky::readings_over_seeds(&mut scene(&toml), 8);
    let mut means = Vec::new();
    for (r, dirs) in [up, down].into_iter().enumerate() {
        for (k, [z, a]) in dirs.iter().enumerate() {
            let d = morgana::sensor::sky_radiance::view_direction(*z, *a);
            let expected = want.band(d, lo, hi);
            let values: Vec<f64> = runs.iter().map(|run| run[r].columns[3].1[k]).collect();
            let (mean, se) = common::mean_and_sem(&values);
            println!(
                "{lo}–{hi} nm [{z}, {a}]: sensor {mean:.6e} ± {se:.1e}, closed form {expected:.6e} (ratio − 1 = {:+.1e})",
                mean / expected - 1.0,
            );
            assert!((mean - expected).abs() < 4.0 * se, "{lo}–{hi} nm [{z}, {a}]: {mean} ± {se} vs {expected}");
            assert!(se < 2e-3 * expected, "[{z}, {a}]: standard error {se} is too large to test");
            means.push(mean);
        }
    }
    means
}

/// Aerosols alone (no Rayleigh, no ozone) with a two-term Henyey–Greenstein phase function
/// p = w HG(g₁) + (1 − w) HG(g₂) (Kattawar 1975; w = 0.8, g₁ = 0.75, g₂ = −0.4), ω = 0.9,
/// Ångström α = 1.3, β = 0.05, in a flat atmosphere over black ground, a point sun 30° from the
/// zenith (E = 1 W m⁻² nm⁻¹), `photons = 0` (single scattering). `sky_radiance` sensors on the
/// ground looking up and at 100 km looking down read the plane-parallel single-scattering closed
/// forms ([`SingleScattering`]), averaged over 545–555 nm. The directions see scattering angles
/// Θ = 10°, 90°, 150° and 180°: within 4 standard errors over 8 seeds, each below 2 × 10⁻³ of
/// the value. One lobe of the same mean cosine (g = 0.52) differs from the two-term law by
/// 58–75 % at these angles (the backward lobe quadruples p at 180°), so the test sees which
/// phase function was used.
#[test]
fn aerosols_with_a_two_term_phase_function_scatter_as_its_closed_form() {
    let (w, g1, g2, albedo, alpha, beta) = (0.8, 0.75, -0.4, 0.9, 1.3, 0.05);
    let up = [[40.0, 90.0], [60.0, 270.0]];
    let down = [[150.0, 270.0], [180.0, 0.0]];
    let aerosol = format!(
        "{{ angstrom_alpha = {alpha:?}, angstrom_beta = {beta:?}, scale_height_m = 1500, albedo = {albedo:?}, phase = {{ type = \"two_term_hg\", w = {w:?}, g1 = {g1:?}, g2 = {g2:?} }} }}"
    );
    let p = |mu: f64| w * hg(g1, mu) + (1.0 - w) * hg(g2, mu);
    let want = SingleScattering { alpha, beta, sun_zenith: 30.0, albedo: &|_| albedo, phase: &p };
    single_scattered_aerosol_sky(&aerosol, (545.0, 555.0), &want, &up, &down);
    let sun = -morgana::sensor::sky_radiance::view_direction(want.sun_zenith, 90.0);
    for [z, a] in up.iter().chain(&down) {
        let cos_theta = sun.dot(-morgana::sensor::sky_radiance::view_direction(*z, *a));
        let one_lobe = hg(w * g1 + (1.0 - w) * g2, cos_theta);
        assert!((one_lobe / p(cos_theta) - 1.0).abs() > 0.1, "[{z}, {a}]: this direction cannot tell the lobes apart");
    }
}

/// A spectral single-scattering albedo (a synthetic table: ω = 0.95 at 500 nm falling linearly
/// to 0.55 at 600 nm, constant beyond): the single-scattered sky of aerosols alone (HG g = 0.7,
/// α = 1.3, β = 0.1, sun 30° from the zenith) reads the plane-parallel closed form with ω(λ)
/// in a band inside the table (545–555 nm, ω from 0.77 to 0.75) and in one beyond its end
/// (645–655 nm, ω = 0.55), within 4 standard errors over 8 seeds. The two bands' ω differ by
/// 28 %, so a scene that took one ω for all wavelengths (either end's, or the table's mean)
/// fails one of them by far more than its noise (< 2 × 10⁻³).
#[test]
fn a_spectral_albedo_scatters_as_the_closed_form_at_each_wavelength() {
    let (alpha, beta, g) = (1.3, 0.1, 0.7);
    let omega = |nm: f64| 0.95 + (0.55 - 0.95) * ((nm - 500.0) / 100.0).clamp(0.0, 1.0);
    let aerosol = format!(
        "{{ angstrom_alpha = {alpha:?}, angstrom_beta = {beta:?}, scale_height_m = 1500, g = {g:?}, albedo = {{ wavelength_nm = [500, 600], value = [0.95, 0.55] }} }}"
    );
    let p = |mu: f64| hg(g, mu);
    let want = SingleScattering { alpha, beta, sun_zenith: 30.0, albedo: &omega, phase: &p };
    let (up, down) = ([[40.0, 90.0], [60.0, 270.0]], [[150.0, 270.0]]);
    for band in [(545.0, 555.0), (645.0, 655.0)] {
        single_scattered_aerosol_sky(&aerosol, band, &want, &up, &down);
    }
}

/// A spectral albedo in the photon pass, over a black Earth, sun 60° from the zenith, aerosols
/// alone (α = 1.3, β = 0.3) with ω = 1 up to 460 nm falling linearly to 0.3 at 660 nm and a
/// forward-peaked phase function (HG g = 0.9999: the mean of 1 − cos Θ is 1 − g = 10⁻⁴, so
/// scattering changes a photon's mean path to the ground by a relative O(10⁻⁴), and almost none
/// go back up). The light absorbed in the air is then Beer–Lambert on the absorbing part alone,
/// A(λ) = 1 − exp(−(1 − ω(λ)) τ_slant(λ)), τ_slant from the computed transmittance along the
/// chord (checked against the closed forms above): at 449.5–450.5 nm (below the table: ω = 1)
/// nothing is absorbed; at 549.5–550.5 nm (ω = 0.685) and 699.5–700.5 nm (beyond the table:
/// ω = 0.3) within 4 standard errors of the binomial count; every watt is accounted for.
#[test]
fn a_spectral_albedo_absorbs_beer_lambert_on_its_absorbing_part() {
    let light = directional_beam([-0.8660254037844386, -0.5, 0.0]);
    let aerosol = "rayleigh = false\naerosol = { angstrom_alpha = 1.3, angstrom_beta = 0.3, scale_height_m = 1500, g = 0.9999, albedo = { wavelength_nm = [460, 660], value = [1.0, 0.3] } }";
    let omega = |nm: f64| 1.0 + (0.3 - 1.0) * ((nm - 460.0) / 200.0).clamp(0.0, 1.0);
    let dir = DVec3::new(0.8660254037844386, 0.5, 0.0);
    for centre in [450.0, 550.0, 700.0] {
        let s = scene(&black_earth(centre - 0.5, centre + 0.5, aerosol, &light));
        let n = 100_000u64;
        let (_, st, emitted) = shoot_balanced(&s, n, 51);
        let want = (0..=10)
            .map(|i| {
                let nm = centre - 0.5 + 0.1 * i as f64;
                let mut rng = Rng::for_task(6, Stream::Test, 0);
                let tau = -transmittance(air(&s), nm, DVec3::ZERO, dir, 1e7, &mut rng).ln();
                1.0 - (-(1.0 - omega(nm)) * tau).exp()
            })
            .sum::<f64>()
            / 11.0;
        let got = st.absorbed_medium_w / emitted;
        let se = (want * (1.0 - want) / n as f64).sqrt();
        println!("{centre} nm: absorbed {got:.5}, Beer–Lambert on (1 − ω) τ {want:.5} (s.e. {se:.5})");
        if want == 0.0 {
            assert_eq!(got, 0.0, "{centre} nm: ω = 1 absorbs nothing");
        } else {
            assert!((got - want).abs() < 4.0 * se, "{centre} nm: absorbed {got} vs {want} ± {se}");
        }
    }
}

/// `albedo = { wavelength_nm = [...], value = [x, x] }` gives the photons of `albedo = x`, to the
/// bit: linear interpolation between equal values is that value exactly.
#[test]
fn a_flat_albedo_table_gives_the_number_forms_photons() {
    let light = directional_beam([-0.5, -0.8660254037844386, 0.0]);
    let haze = |albedo: &str| {
        scene(&black_earth(
            400.0,
            700.0,
            &format!("aerosol = {{ angstrom_beta = 0.2, scale_height_m = 1500, g = 0.7, albedo = {albedo} }}"),
            &light,
        ))
    };
    let number = haze("0.85");
    let table = haze("{ wavelength_nm = [300, 500, 900], value = [0.85, 0.85, 0.85] }");
    let n = 20_000u64;
    let (a_sink, a) = shoot(&number.world, &PassSettings::of(&number), MapKind::Global, n, 61, &|_| {});
    let (b_sink, b) = shoot(&table.world, &PassSettings::of(&table), MapKind::Global, n, 61, &|_| {});
    assert!(a.absorbed_medium_w > 0.0);
    assert_eq!(a, b, "photon statistics");
    assert_eq!(a_sink.volume.len(), b_sink.volume.len());
    assert!(a_sink.volume.iter().zip(&b_sink.volume).all(|(p, q)| p.position == q.position && p.power_w == q.power_w));
}

#[test]
fn ozone_and_aerosol_keys_report_bad_input() {
    let bad = |extra: &str| scene_error(&black_earth(400.0, 700.0, extra, ZENITH_BEAM));
    let e = bad("ozone_du = -3.0");
    assert!(e.contains("ozone_du") && e.contains("out of range"), "{e}");
    let e = bad("aerosol = { scale_height_m = 1000, albedo = 0.9, g = 0.7 }");
    assert!(e.contains("angstrom_beta") && e.contains("visibility_km"), "{e}");
    let e = bad("aerosol = { angstrom_beta = 0.1, visibility_km = 20, scale_height_m = 1000, albedo = 0.9, g = 0.7 }");
    assert!(e.contains("not both"), "{e}");
    let e = bad("aerosol = { angstrom_beta = 0.1, scale_height_m = 1000, albedo = 1.5, g = 0.7 }");
    assert!(e.contains("albedo") && e.contains("out of range"), "{e}");
    let e = bad("aerosol = { angstrom_beta = 0.1, scale_height_m = 1000, albedo = 0.9, g = 1.0 }");
    assert!(e.contains("g = 1") && e.contains("out of range"), "{e}");
    let e = bad("aerosol = { angstrom_beta = 0.1, albedo = 0.9, g = 0.7 }");
    assert!(e.contains("scale_height_m"), "{e}");
    let e = bad("aerosol = { angstrom_beta = 0.1, scale_height_m = 1000, albedo = 0.9, g = 0.7, size = 3 }");
    assert!(e.contains("unknown key `size`"), "{e}");
    let e = bad("aerosol = { visibility_km = 900, scale_height_m = 1000, albedo = 0.9, g = 0.7 }");
    assert!(e.contains("visibility_km") && e.contains("air alone"), "{e}");
    let e = bad("aerosol = { angstrom_beta = 0.1, scale_height_m = 1000, albedo = 0.9 }");
    assert!(e.contains("give either g") && e.contains("two_term_hg"), "{e}");
    let both = "aerosol = { angstrom_beta = 0.1, scale_height_m = 1000, albedo = 0.9, g = 0.7, phase = { type = \"hg\", g = 0.7 } }";
    assert!(bad(both).contains("not both"), "{}", bad(both));
    let e = bad(
        "aerosol = { angstrom_beta = 0.1, scale_height_m = 1000, albedo = 0.9, phase = { type = \"two_term_hg\", w = 1.5, g1 = 0.8, g2 = -0.3 } }",
    );
    assert!(e.contains("aerosol: phase") && e.contains("w = 1.5") && e.contains("[0, 1]"), "{e}");
    let e = bad(
        "aerosol = { angstrom_beta = 0.1, scale_height_m = 1000, albedo = 0.9, phase = { type = \"two_term_hg\", w = 0.5, g1 = 0.8 } }",
    );
    assert!(e.contains("missing `g2`"), "{e}");
    let e = bad("aerosol = { angstrom_beta = 0.1, scale_height_m = 1000, albedo = 0.9, phase = { type = \"mie\" } }");
    assert!(e.contains("\"hg\"") && e.contains("\"two_term_hg\""), "{e}");
    let e = bad(
        "aerosol = { angstrom_beta = 0.1, scale_height_m = 1000, albedo = 0.9, phase = { type = \"hg\", g = 0.7, k = 2 } }",
    );
    assert!(e.contains("unknown key `k`"), "{e}");
    let table =
        |t: &str| bad(&format!("aerosol = {{ angstrom_beta = 0.1, scale_height_m = 1000, g = 0.7, albedo = {t} }}"));
    let e = table("{ wavelength_nm = [400, 700], value = [0.9, 1.2] }");
    assert!(e.contains("aerosol: albedo") && e.contains("value #1 is 1.2") && e.contains("[0, 1]"), "{e}");
    let e = table("{ wavelength_nm = [700, 400], value = [0.9, 0.8] }");
    assert!(e.contains("aerosol: albedo") && e.contains("strictly increasing"), "{e}");
    let e = table("{ wavelength_nm = [400], value = [0.9] }");
    assert!(e.contains("aerosol: albedo") && e.contains("at least 2"), "{e}");
    let e = table("{ wavelength_nm = [400, 500, 600], value = [0.9, 0.8] }");
    assert!(e.contains("aerosol: albedo") && e.contains("one value per wavelength"), "{e}");
    let e = table("{ wavelength_nm = [400, 700] }");
    assert!(e.contains("aerosol: albedo") && e.contains("missing `value`"), "{e}");
    let e = table("{ wavelength_nm = [400, \"red\"], value = [0.9, 0.8] }");
    assert!(e.contains("aerosol: albedo") && e.contains("`wavelength_nm` must be an array of numbers"), "{e}");
    let e = table("{ nm = [400, 700], value = [0.9, 0.8] }");
    assert!(e.contains("aerosol: albedo") && e.contains("unknown key `nm`"), "{e}");
    let e = table("{ wavelength_nm = [-5, 700], value = [0.9, 0.8] }");
    assert!(e.contains("aerosol: albedo") && e.contains("wavelength_nm #0"), "{e}");
    let e = table("\"high\"");
    assert!(e.contains("albedo must be a number in [0, 1] or a table"), "{e}");
    let e = bad("ozone_du = 300\nozone = { column_du = 300 }");
    assert!(e.contains("give ozone_du") && e.contains("not both"), "{e}");
    let e = bad("ozone = { }");
    assert!(e.contains("ozone") && e.contains("give a profile file, a column_du"), "{e}");
    let e = bad("ozone = { column_du = 2000 }");
    assert!(e.contains("column_du = 2000") && e.contains("out of range"), "{e}");
    let e = bad("ozone = { column_du = 300, interpolation = \"linear\" }");
    assert!(e.contains("interpolation reads a profile file"), "{e}");
    let e = bad("ozone = { profile = \"no_such_ozone.csv\" }");
    assert!(e.contains("no_such_ozone.csv") && e.contains("cannot read the ozone profile"), "{e}");
    let e = bad("ozone = { column_du = 300, cross_section_cm2 = { nm = [500, 600], values = [1e-21, 2e-21] } }");
    assert!(e.contains("ozone: cross_section_cm2") && e.contains("500–600 nm"), "{e}");
    let e = bad("ozone = { column_du = 300, size = 3 }");
    assert!(e.contains("unknown key `size`"), "{e}");
    let short = std::env::temp_dir().join(format!("morgana_ozone_short_{}.csv", std::process::id()));
    std::fs::write(&short, "# ozone\naltitude_m,number_density_per_cm3\n0,1e12\n50000,1e10\n").unwrap();
    let e = bad(&format!("ozone = {{ profile = \"{}\" }}", short.display()));
    assert!(e.contains("covers 0 to 50000 m") && e.contains("0 to 86000 m") && e.contains("extend it"), "{e}");
    std::fs::write(&short, "altitude_m,number_density_per_cm3\n0,1e12\n50000,-3\n90000,1e9\n").unwrap();
    let e = bad(&format!("ozone = {{ profile = \"{}\", interpolation = \"cubic\" }}", short.display()));
    assert!(e.contains("interpolation must be \"log\"") && e.contains("\"linear\""), "{e}");
    let e = bad(&format!("ozone = {{ profile = \"{}\" }}", short.display()));
    assert!(e.contains(&short.display().to_string()) && e.contains("data row 2") && e.contains("≥ 0"), "{e}");
    let _ = std::fs::remove_file(&short);
    let e = bad("aerosol = 0.3");
    assert!(e.contains("aerosol") && e.contains("table"), "{e}");
    // Every message names the file and line.
    assert!(e.contains("test.toml:"), "{e}");
    // Only an atmosphere takes them.
    let plain = black_earth(400.0, 700.0, "", ZENITH_BEAM)
        .replace("type = \"atmosphere\"\natmosphere = \"usa76\"\n", "sigma_a = 0\nsigma_s = 0.1\nozone_du = 300\n");
    let e = scene_error(&plain);
    assert!(e.contains("ozone_du") && e.contains("only with type = \"atmosphere\""), "{e}");
}
