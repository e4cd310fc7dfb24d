//! The scattering atmosphere (`[[medium]] type = "atmosphere"`): transmittance against
//! Beer–Lambert on the USA76 profile, the Rayleigh optical depth against Bodhaine et al. (1999),
//! energy conservation of the photon pass over a black Earth, and its scene errors.

mod common;

use common::sky::{R_EARTH_M, ZENITH_BEAM, usa76_n};
use common::{scene, scene_error};
use glam::DVec3;
use morgana::media::Medium;
use morgana::media::density::COLUMN_TOLERANCE;
use morgana::media::rayleigh_air::cross_section_m2;
use morgana::media::tracking::{optical_depth_exact, transmittance};
use morgana::photon::{MapKind, PassSettings, shoot};
use morgana::photon_map::PhotonPath;
use morgana::rng::{Rng, Stream};
use std::f64::consts::PI;

const TOP_M: f64 = 86_000.0;

/// A black Earth (a sphere of radius 6371 km centred at (0, −R, 0)) in a USA76 Rayleigh
/// atmosphere over `min_nm`–`max_nm`, with `light` (TOML) added.
fn black_earth(min_nm: f64, max_nm: f64, light: &str) -> String {
    common::sky::black_earth(min_nm, max_nm, "rayleigh = true\nco2_ppm = 360", light)
}

fn air(s: &morgana::scene::Scene) -> &Medium {
    s.world.media.iter().find(|m| m.name == "air").expect("the air medium")
}

/// ∫ N ds along the chord from the ground at the origin toward zenith angle `zenith_deg`, up to
/// the 86 km top: composite Simpson's rule with 1 m steps on the exact standard, heights
/// h(s) = √(R² + s² + 2Rs cos z) − R above the sphere.
fn column_per_m2(zenith_deg: f64) -> f64 {
    let mu = zenith_deg.to_radians().cos();
    let r = R_EARTH_M;
    let length = -r * mu + (r * r * mu * mu + (r + TOP_M).powi(2) - r * r).sqrt();
    let height = |s: f64| (r * r + s * s + 2.0 * r * s * mu).sqrt() - r;
    let n = (length.ceil() as usize).div_ceil(2) * 2;
    let ds = length / n as f64;
    let f = |i: usize| usa76_n(height(i as f64 * ds).min(TOP_M));
    let inner: f64 = (1..n).map(|i| if i % 2 == 1 { 4.0 * f(i) } else { 2.0 * f(i) }).sum();
    (f(0) + inner + f(n)) * ds / 3.0
}

fn direction_at_zenith(zenith_deg: f64) -> DVec3 {
    let z = zenith_deg.to_radians();
    DVec3::new(z.sin(), z.cos(), 0.0)
}

/// The whole atmosphere's optical depth, vertical and at 60°, 300–800 nm, equals σ(λ) ∫N ds on
/// the USA76 profile to 10⁻⁶ relative by the exact quadrature (`optical_depth_exact`); the
/// transmittance a shadow ray gets (`transmittance`, which reads the column from the table of
/// columns to the top) equals exp(−σ ∫N ds) within that table's bound, |Δτ| ≤ 5 × 10⁻⁴ τ +
/// 10⁻⁵ τ_vertical (`COLUMN_TOLERANCE`).
#[test]
fn transmittance_of_the_whole_atmosphere_is_beer_lambert_on_the_profile() {
    let s = scene(&black_earth(300.0, 800.0, ZENITH_BEAM));
    let m = air(&s);
    let mut rng = Rng::for_task(1, Stream::Test, 0);
    let (relative, absolute) = COLUMN_TOLERANCE;
    let vertical = column_per_m2(0.0);
    for zenith in [0.0, 60.0] {
        let column = column_per_m2(zenith);
        let dir = direction_at_zenith(zenith);
        for k in 0..=10 {
            let nm = 300.0 + 50.0 * k as f64;
            let tau = cross_section_m2(nm, 360.0) * column;
            let exact = optical_depth_exact(m, nm, DVec3::ZERO, dir, 1e7).expect("the air's depth is exact");
            assert!((exact / tau - 1.0).abs() < 1e-6, "zenith {zenith}°, {nm} nm: τ = {exact}, Beer–Lambert {tau}");
            let got = transmittance(m, nm, DVec3::ZERO, dir, 1e7, &mut rng);
            let bound = relative * tau + absolute * cross_section_m2(nm, 360.0) * vertical;
            assert!(
                (got.ln() + tau).abs() <= bound,
                "zenith {zenith}°, {nm} nm: T = {got}, Beer–Lambert {}",
                (-tau).exp()
            );
        }
    }
}

/// Bodhaine et al. (1999) Eq. 30: τ_R(λ) = 0.0021520 (1.0455996 − 341.29061 λ⁻² − 0.90230850 λ²)
/// / (1 + 0.0027059889 λ⁻² − 85.968563 λ²) (λ in µm) for 1013.25 hPa at sea level, 45° latitude,
/// 360 ppm CO₂: 0.09707 at 550 nm. The USA76 column differs from Bodhaine's P₀N_A/(m_a g) by its
/// gravity (g₀(r₀/(r₀ + z))² weighted by mass, against Bodhaine's g at 5.5 km over 45°) and molar
/// mass (28.9644 against 28.9649 g/mol): a few 10⁻⁴; asserted to 10⁻³.
#[test]
fn vertical_rayleigh_optical_depth_matches_bodhaine() {
    let s = scene(&black_earth(300.0, 800.0, ZENITH_BEAM));
    let m = air(&s);
    for um in [0.3, 0.4, 0.55, 0.7, 0.8] {
        let (x, l2) = (1.0 / (um * um), um * um);
        let bodhaine = 0.002_152_0 * (1.045_599_6 - 341.290_61 * x - 0.902_308_50 * l2)
            / (1.0 + 0.002_705_988_9 * x - 85.968_563 * l2);
        let nm = um * 1e3;
        let tau = m.sigma_t(nm) * m.density.integral_exact(DVec3::ZERO, DVec3::Y, 1e7).unwrap();
        println!("{nm} nm: τ = {tau:.6}, Bodhaine Eq. 30 {bodhaine:.6}");
        assert!((tau / bodhaine - 1.0).abs() < 1e-3, "{nm} nm: τ = {tau}, Bodhaine {bodhaine}");
        if um == 0.55 {
            assert!((bodhaine - 0.09707).abs() < 5e-6);
        }
    }
}

/// A non-absorbing Rayleigh atmosphere over a black Earth, lit by a collimated beam at 60° from
/// the zenith aimed at a 2 km square: every emitted watt is absorbed by the ground or leaves to
/// space (reflected + transmitted = incident), none is absorbed by the air; and the photons
/// reaching the ground unscattered carry exp(−τ_slant) of the power, τ_slant = σ ∫N ds along the
/// 60° chord (Beer–Lambert through the free-flight sampling), within 4 standard errors.
#[test]
fn a_rayleigh_atmosphere_over_a_black_earth_conserves_energy() {
    let light = common::sky::directional_beam([-0.8660254037844386, -0.5, 0.0]);
    let s = scene(&black_earth(545.0, 555.0, &light));
    let n = 100_000u64;
    let (sink, st) = shoot(&s.world, &PassSettings::of(&s), MapKind::Global, n, 11, &|_| {});
    let emitted = n as f64 * st.power_per_photon_w;
    assert_eq!(st.absorbed_medium_w, 0.0, "the air absorbs nothing");
    assert_eq!(st.truncated_w, 0.0);
    let out = st.absorbed_surface_w + st.escaped_w;
    assert!(
        (out / emitted - 1.0).abs() < 1e-9,
        "ground {} + space {} of {emitted} W",
        st.absorbed_surface_w,
        st.escaped_w
    );
    // Direct transmission, averaged over the band's wavelengths (the spectrum is flat).
    let column = column_per_m2(60.0);
    let want =
        (0..=100).map(|i| (-cross_section_m2(545.0 + 0.1 * i as f64, 360.0) * column).exp()).sum::<f64>() / 101.0;
    let direct: f64 = sink.surface.iter().filter(|p| p.path == PhotonPath::Direct).map(|p| p.power_w).sum();
    let got = direct / emitted;
    let se = (want * (1.0 - want) / n as f64).sqrt();
    println!("direct transmittance {got:.5} vs {want:.5} (s.e. {se:.5}); reflected {:.5}", st.escaped_w / emitted);
    assert!((got - want).abs() < 4.0 * se, "direct {got} vs exp(−τ) {want}");
}

#[test]
fn atmosphere_media_report_bad_input() {
    let e = scene_error(&black_earth(200.0, 800.0, ZENITH_BEAM));
    assert!(e.contains("230") && e.contains("1690") && e.contains("min_nm"), "{e}");
    let e = scene_error(&black_earth(400.0, 700.0, ZENITH_BEAM).replace("co2_ppm = 360", "co2_ppm = -5.0"));
    assert!(e.contains("co2_ppm") && e.contains("out of range"), "{e}");
    let e = scene_error(&black_earth(400.0, 700.0, ZENITH_BEAM).replace("co2_ppm = 360", "sigma_s = 0.1"));
    assert!(e.contains("sigma_s") && e.contains("not used here"), "{e}");
    let e =
        scene_error(&black_earth(400.0, 700.0, ZENITH_BEAM).replace("atmosphere = \"usa76\"", "atmosphere = \"mars\""));
    assert!(e.contains("atmosphere") && e.contains("mars"), "{e}");
    let e = scene_error(&black_earth(400.0, 700.0, ZENITH_BEAM).replace("type = \"atmosphere\"", "type = \"fog\""));
    assert!(e.contains("\"fog\" is not known") && e.contains("atmosphere"), "{e}");
    let plain = black_earth(400.0, 700.0, ZENITH_BEAM)
        .replace("type = \"atmosphere\"\natmosphere = \"usa76\"\n", "sigma_a = 0\nsigma_s = 0.1\n");
    let e = scene_error(&plain);
    assert!(e.contains("rayleigh") && e.contains("only with type = \"atmosphere\""), "{e}");
}

/// The `[integrator]` (path tracer, `spp` samples, no photons) and the world of the
/// single-scattering tests: Rayleigh air over a flat black ground 4000 km across.
fn flat_black_ground(spp: u32) -> String {
    format!("[integrator]\nphotons = 0\nmarch_step = 200.0\nspp = {spp}\n{}", common::sky::flat_air_over_black_ground())
}

/// A flat-Earth USA76 Rayleigh atmosphere over black ground, lit by a collimated beam of
/// spectral irradiance E = 1 W m⁻² nm⁻¹ at solar zenith θ₀, seen from 100 km (above the 86 km
/// top) looking down at view zenith θ: `photons = 0` leaves only single scattering (ray marching
/// with shadow rays), whose radiance leaving the top of a plane-parallel layer of vertical
/// optical depth τ over a black surface is, for any vertical profile of σ_s (the layer is
/// homogeneous in τ),
///
/// L(μ, Θ) = E ω p(Θ) μ₀/(μ₀ + μ) [1 − exp(−τ (1/μ₀ + 1/μ))],
///
/// μ₀ = cos θ₀, μ = cos θ, p per steradian: the source ω p E e^{−t/μ₀} at optical depth t, seen
/// through e^{−t/μ}, integrated as ∫₀^τ ω p E e^{−t/μ₀} e^{−t/μ} dt/μ (Liou, *An Introduction to
/// Atmospheric Radiation*, 2nd ed. 2002, ch. 6, the single-scattering approximation).
/// Here ω = 1, p is Rayleigh's with Bodhaine's depolarisation at 550 nm, and τ(λ) = σ(λ) ∫N dh
/// with the column by Simpson's rule on the standard; averaged over the 545–555 nm band.
/// Returns the march steps per eye ray.
fn single_scattering_case(sun_zenith_deg: f64, view_zenith_deg: f64, azimuth_deg: f64) -> f64 {
    single_scattering_seen_from(100_000.0, (sun_zenith_deg, view_zenith_deg, azimuth_deg))
}

/// [`single_scattering_case`] with the camera `height_m` above the ground.
fn single_scattering_seen_from(height_m: f64, (sun_zenith_deg, view_zenith_deg, azimuth_deg): (f64, f64, f64)) -> f64 {
    let (t0, tv, phi) = (sun_zenith_deg.to_radians(), view_zenith_deg.to_radians(), azimuth_deg.to_radians());
    // The sun's rays travel down toward −x; the camera looks down with its view rotated by φ
    // about the vertical from the sun's side.
    let sun = DVec3::new(-t0.sin(), -t0.cos(), 0.0);
    let view = DVec3::new(tv.sin() * phi.cos(), -tv.cos(), tv.sin() * phi.sin());
    let camera = DVec3::new(0.0, height_m, 0.0);
    let look = camera + view;
    let toml = format!(
        r#"
[camera]
position = [{cx:?}, {cy:?}, {cz:?}]
look_at = [{lx:?}, {ly:?}, {lz:?}]
up = [0.0, 0.0, 1.0]
fov_deg = 0.01
width = 1
height = 1

[output]
bands = 1
min_nm = 545.0
max_nm = 555.0

{ground}

[[light]]
type = "directional"
direction = [{sx:?}, {sy:?}, {sz:?}]
spectrum = 1.0
scale = 1.0
"#,
        ground = flat_black_ground(256),
        cx = camera.x,
        cy = camera.y,
        cz = camera.z,
        lx = look.x,
        ly = look.y,
        lz = look.z,
        sx = sun.x,
        sy = sun.y,
        sz = sun.z,
    );
    let s = scene(&toml);
    assert!(s.plan.participating_media.on && !s.plan.volume_map.on);
    let r = common::render_with(&s, 2);
    let rendered = r.image.data[0] as f64;
    // Expected: band average of the closed form.
    let column = column_per_m2(0.0);
    let (mu0, mu) = (t0.cos(), tv.cos());
    let cos_theta = sun.dot(-view);
    let rho = morgana::media::rayleigh_air::depolarisation(550.0, 360.0);
    let gamma = rho / (2.0 - rho);
    let p = 3.0 / (4.0 * (1.0 + 2.0 * gamma)) * ((1.0 + 3.0 * gamma) + (1.0 - gamma) * cos_theta * cos_theta)
        / (4.0 * std::f64::consts::PI);
    let l = |nm: f64| {
        let tau = cross_section_m2(nm, 360.0) * column;
        p * mu0 / (mu0 + mu) * (1.0 - (-tau * (1.0 / mu0 + 1.0 / mu)).exp())
    };
    let want = (0..=100).map(|i| l(545.0 + 0.1 * i as f64)).sum::<f64>() / 101.0;
    println!(
        "θ₀ {sun_zenith_deg}°, θ {view_zenith_deg}°, φ {azimuth_deg}°: rendered {rendered:.6e}, closed form {want:.6e}"
    );
    assert!((rendered / want - 1.0).abs() < 1e-3, "rendered {rendered}, closed form {want}");
    r.stats.rays.medium_steps as f64 / r.stats.rays.eye as f64
}

#[test]
fn single_scattering_leaving_a_plane_parallel_rayleigh_atmosphere_matches_the_closed_form() {
    single_scattering_case(30.0, 40.0, 60.0);
    single_scattering_case(60.0, 0.0, 0.0);
}

/// A camera 2000 km up, looking straight down through the 86 km of air (200 m march steps):
/// the march covers the air alone, ≈ 430 steps per eye ray, not the 10 000 it would take from
/// the camera down (the empty space above the top holds nothing to scatter), and the radiance
/// is still the closed form's.
#[test]
fn a_march_covers_only_the_air_below_the_atmospheres_top() {
    let steps = single_scattering_seen_from(2.0e6, (60.0, 0.0, 0.0));
    println!("{steps:.1} march steps per eye ray");
    let in_air = TOP_M / 200.0;
    assert!(steps > 0.9 * in_air && steps < 1.5 * in_air, "{steps} march steps per eye ray, {in_air} in the air");
}

/// Rayleigh's phase function with Bodhaine's depolarisation at 550 nm, Chandrasekhar's form.
fn air_phase(cos_theta: f64) -> f64 {
    let rho = morgana::media::rayleigh_air::depolarisation(550.0, 360.0);
    let gamma = rho / (2.0 - rho);
    3.0 / (4.0 * (1.0 + 2.0 * gamma)) * ((1.0 + 3.0 * gamma) + (1.0 - gamma) * cos_theta * cos_theta)
        / (4.0 * std::f64::consts::PI)
}

/// A `sky_radiance` sensor on the ground of the flat Rayleigh atmosphere (sun at 30° from the
/// zenith toward azimuth 90°, E = 1 W m⁻² nm⁻¹, `photons = 0`: single scattering) reads, looking
/// up at view zenith θ (μ = cos θ), the single-scattered radiance reaching the bottom of a
/// plane-parallel layer, ∫₀^τ ω p E e^{−t/μ₀} e^{−(τ − t)/μ} dt/μ =
/// E ω p(Θ) μ₀/(μ₀ − μ) [e^{−τ/μ₀} − e^{−τ/μ}] (Liou 2002, ch. 6); and a second sensor above the
/// top, looking down, the radiance leaving the top (as the camera test). Band average over
/// 545–555 nm. Eight runs with different seeds: the mean within 4 standard errors of the closed
/// form, and the standard error below 5e-4 of it (so the test can see a 0.2 % error).
#[test]
fn a_sky_radiance_sensor_reads_the_single_scattered_sky() {
    let sun_zenith: f64 = 30.0;
    let up = [[0.0, 0.0], [45.0, 90.0], [60.0, 200.0], [80.0, 270.0]];
    let down = [[140.0, 30.0], [180.0, 0.0]];
    let toml = format!(
        r#"
{pixel}
{ground}
{sun}
{sensors}"#,
        pixel = common::sky::zenith_pixel(1, 545.0, 555.0),
        ground = flat_black_ground(1),
        sun = common::sky::point_sun(90.0 - sun_zenith),
        sensors = common::sky::ground_and_space_sensors(&up, &down, 32),
    );
    let runs = common::sky::readings_over_seeds(&mut scene(&toml), 8);
    let sun = -morgana::sensor::sky_radiance::view_direction(sun_zenith, 90.0);
    // The ground sensor, 1 m up, sees the air above it: the column less the lowest metre's
    // (1.2 × 10⁻⁴ of it, which a standard error of 7 × 10⁻⁵ shows).
    let (column, above_sensor) = (column_per_m2(0.0), column_per_m2(0.0) - usa76_n(0.5));
    let mu0 = sun_zenith.to_radians().cos();
    let band = |column: f64, f: &dyn Fn(f64) -> f64| {
        (0..=100).map(|i| f(cross_section_m2(545.0 + 0.1 * i as f64, 360.0) * column)).sum::<f64>() / 101.0
    };
    for (r, dirs) in [&up[..], &down[..]].into_iter().enumerate() {
        let name = &runs[0][r].name;
        assert!(runs[0][r].columns[3].0.starts_with("L_545"), "{:?}", runs[0][r].columns[3].0);
        for (k, [z, a]) in dirs.iter().enumerate() {
            let d = morgana::sensor::sky_radiance::view_direction(*z, *a);
            let p = air_phase(sun.dot(-d));
            let mu = d.y.abs();
            let want = if d.y > 0.0 {
                band(above_sensor, &|tau| p * mu0 / (mu0 - mu) * ((-tau / mu0).exp() - (-tau / mu).exp()))
            } else {
                band(column, &|tau| p * mu0 / (mu0 + mu) * (1.0 - (-tau * (1.0 / mu0 + 1.0 / mu)).exp()))
            };
            let values: Vec<f64> = runs.iter().map(|run| run[r].columns[3].1[k]).collect();
            let (mean, se) = common::mean_and_sem(&values);
            println!(
                "{name} [{z}, {a}]: sensor {mean:.6e} ± {se:.1e}, closed form {want:.6e}, ratio − 1 = {:.1e}",
                mean / want - 1.0
            );
            assert!((mean - want).abs() < 4.0 * se, "{name} [{z}, {a}]: {mean} ± {se} vs {want}");
            assert!(se < 5e-4 * want, "{name} [{z}, {a}]: standard error {se} is too large to test");
        }
    }
}

#[test]
fn sky_radiance_sensors_report_bad_input() {
    let with = |sensor: &str| {
        format!(
            "{}\n[[sensor]]\nname = \"sky\"\ntype = \"sky_radiance\"\n{sensor}\n",
            black_earth(400.0, 700.0, ZENITH_BEAM)
        )
    };
    let e = scene_error(&with("origin = [0.0, 1.0, 0.0]\ndirections_deg = [[0.0, 0.0], [190.0, 0.0]]"));
    assert!(e.contains("[190, 0]") && e.contains("zenith 0 to 180"), "{e}");
    let e = scene_error(&with("origin = [0.0, 1.0, 0.0]\ndirections_deg = []"));
    assert!(e.contains("directions_deg must list 1 to 4096"), "{e}");
    let e = scene_error(&with("origin = [0.0, 1.0, 0.0]"));
    assert!(e.contains("missing field `directions_deg`"), "{e}");
    let e = scene_error(&with("origin = [0.0, 1.0, 0.0]\ndirections_deg = [[10.0, 0.0]]\nresolution = [2, 2]"));
    assert!(e.contains("resolution") && e.contains("not used here"), "{e}");
    let ok = scene(&with("origin = [0.0, 1.0, 0.0]\ndirections_deg = [[10.0, 0.0]]"));
    assert_eq!(ok.sensors.len(), 1);
}

#[test]
fn limb_sensors_report_bad_input() {
    let limb = |world: &str, sensor: &str| format!("{world}\n[[sensor]]\nname = \"limb\"\ntype = \"limb\"\n{sensor}\n");
    let round = black_earth(400.0, 700.0, ZENITH_BEAM);
    let e = scene_error(&limb(&round, "tangent_heights_m = [1000.0, 86000.0]"));
    assert!(e.contains("tangent height 86000 m") && e.contains("below the atmosphere's top (86000 m)"), "{e}");
    let e = scene_error(&limb(&round, "tangent_heights_m = [-5.0]"));
    assert!(e.contains("tangent height -5 m is out of range"), "{e}");
    let e = scene_error(&limb(&round, "tangent_heights_m = []"));
    assert!(e.contains("tangent_heights_m must list 1 to 4096"), "{e}");
    let e = scene_error(&limb(&round, "azimuth_deg = 10.0"));
    assert!(e.contains("missing field `tangent_heights_m`"), "{e}");
    let e = scene_error(&limb(&round, "tangent_heights_m = [1000.0]\nazimuth_deg = 400.0"));
    assert!(e.contains("azimuth_deg") && e.contains("out of range"), "{e}");
    let e = scene_error(&limb(&round, "tangent_heights_m = [1000.0]\norigin = [0.0, 1.0, 0.0]"));
    assert!(e.contains("origin") && e.contains("not used here"), "{e}");
    let flat = format!(
        "{}\n[camera]\nposition = [0.0, 1.0, 0.0]\nlook_at = [0.0, 2.0, 0.001]\nfov_deg = 10.0\nwidth = 2\nheight = 2\n{ZENITH_BEAM}",
        common::sky::flat_air_over_black_ground()
    );
    let e = scene_error(&limb(&flat, "tangent_heights_m = [1000.0]"));
    assert!(e.contains("a limb needs") && e.contains("earth = \"spherical\""), "{e}");
    assert!(e.contains("test.toml:"), "{e}");
    let ok = scene(&limb(&round, "tangent_heights_m = [500.0, 20000.0]\nazimuth_deg = 45.0"));
    let morgana::sensor::Sensor::SkyRadiance(sky) = &ok.sensors[0].sensor else { panic!("a limb is a sky sensor") };
    assert_eq!(sky.directions_deg, vec![[90.0, 45.0]; 2]);
    // The default march steps are long along a limb: a note says so, unless march_step is given.
    assert!(
        ok.warnings.iter().any(|w| w.contains("sensor \"limb\"") && w.contains("march_step = 1000")),
        "{:?}",
        ok.warnings
    );
    let stepped = scene(&limb(&format!("{round}\n[integrator]\nmarch_step = 1000.0\n"), "tangent_heights_m = [500.0]"));
    assert!(!stepped.warnings.iter().any(|w| w.contains("limb")), "{:?}", stepped.warnings);
}

/// `refraction = true` gives the medium the same atmosphere's index field (n − 1 at sea level
/// 2.78 × 10⁻⁴ at 550 nm: Ciddor's air at 288.15 K, 101325 Pa) and the plan curves paths;
/// `rayleigh = false` leaves clear air, which the plan does not count as participating.
#[test]
fn refraction_and_rayleigh_switches_do_what_they_say() {
    let base = black_earth(400.0, 700.0, ZENITH_BEAM);
    let s = scene(&base);
    assert!(air(&s).index.is_none() && air(&s).scatters() && !s.plan.curved_paths.on);
    let s = scene(&base.replace("co2_ppm = 360", "co2_ppm = 360\nrefraction = true"));
    let m = air(&s);
    assert!(m.bends_light() && s.plan.curved_paths.on && s.plan.participating_media.on);
    let (n, grad) = m.index.as_ref().unwrap().n_grad(550.0, DVec3::new(0.0, 0.0, 0.0));
    assert!((n - 1.0 - 2.78e-4).abs() < 3e-6, "n − 1 = {}", n - 1.0);
    assert!(grad.y < 0.0, "n falls with height");
    let s = scene(&base.replace("rayleigh = true", "rayleigh = false"));
    assert!(air(&s).is_clear() && !s.plan.participating_media.on);
}

/// `rayleigh = { cross_section_cm2 = ..., depolarisation = ρ }`: a benchmark's cross-sections,
/// read as a power law between samples, and its phase function, in place of Bodhaine's.
#[test]
fn a_given_cross_section_table_and_depolarisation_replace_bodhaines() {
    let table = "rayleigh = { cross_section_cm2 = { nm = [351, 435, 700], values = [2.87884699e-26, 1.17740547e-26, 1.8e-27] }, depolarisation = 0.0 }";
    let s = scene(&black_earth(400.0, 600.0, ZENITH_BEAM).replace("rayleigh = true\nco2_ppm = 360", table));
    let m = air(&s);
    let n_s = morgana::media::rayleigh_air::N_STANDARD_PER_M3;
    let power_law =
        |nm: f64| 2.87884699e-30 * (1.17740547f64 / 2.87884699).powf((nm / 351.0).ln() / (435.0f64 / 351.0).ln());
    for nm in [400.0, 420.0, 435.0] {
        let sigma = m.sigma_s(nm) / n_s;
        assert!(
            (sigma / power_law(nm) - 1.0).abs() < 1e-12,
            "{nm} nm: σ = {sigma:e} m², power law {:e}",
            power_law(nm)
        );
    }
    let late = 1.17740547e-30 * (1.8e-27f64 / 1.17740547e-26).powf((600.0f64 / 435.0).ln() / (700.0f64 / 435.0).ln());
    assert!((m.sigma_s(600.0) / n_s / late - 1.0).abs() < 1e-12);
    // ρ = 0: the classical 3/(16π)(1 + μ²).
    for mu in [-1.0, -0.3, 0.0, 0.5, 1.0] {
        let p = m.phase.eval(500.0, mu);
        assert!((p - 3.0 / (16.0 * PI) * (1.0 + mu * mu)).abs() < 1e-15, "μ = {mu}: {p}");
    }
    // ρ alone keeps Bodhaine's σ; the table alone keeps his King factor's ρ.
    let s = scene(
        &black_earth(400.0, 600.0, ZENITH_BEAM).replace("rayleigh = true", "rayleigh = { depolarisation = 0.1 }"),
    );
    assert_eq!(air(&s).sigma_s(500.0), cross_section_m2(500.0, 360.0) * n_s);
    let c = (1.0 - 0.1) / (1.0 + 0.1);
    let p = air(&s).phase.eval(500.0, 1.0) / air(&s).phase.eval(500.0, 0.0);
    assert!((p - (1.0 + c)).abs() < 1e-12, "{p}");
    let only_table = table.replace(", depolarisation = 0.0", "");
    let s = scene(&black_earth(400.0, 600.0, ZENITH_BEAM).replace("rayleigh = true", &only_table));
    let c = morgana::media::rayleigh_air::phase_c(morgana::media::rayleigh_air::depolarisation(500.0, 360.0));
    let p = air(&s).phase.eval(500.0, 1.0) / air(&s).phase.eval(500.0, 0.0);
    assert!((p - (1.0 + c)).abs() < 1e-12, "{p}");
}

#[test]
fn a_bad_rayleigh_table_is_refused_naming_the_key() {
    let bad =
        |rayleigh: &str| scene_error(&black_earth(400.0, 600.0, ZENITH_BEAM).replace("rayleigh = true", rayleigh));
    let xs = |nm: &str, v: &str| format!("rayleigh = {{ cross_section_cm2 = {{ nm = [{nm}], values = [{v}] }} }}");
    let e = bad(&xs("450, 700", "1e-26, 2e-27"));
    assert!(e.contains("rayleigh: cross_section_cm2") && e.contains("450–700 nm") && e.contains("400–600"), "{e}");
    let e = bad(&xs("300, 700", "1e-26, 0"));
    assert!(e.contains("cross_section_cm2") && e.contains("value #2 (at 700 nm) is 0"), "{e}");
    let e = bad(&xs("700, 300", "1e-26, 2e-27"));
    assert!(e.contains("cross_section_cm2") && e.contains("strictly increasing"), "{e}");
    let e = bad("rayleigh = { cross_section_cm2 = 3e-27 }");
    assert!(e.contains("cross_section_cm2") && e.contains("give a table") && e.contains("power law"), "{e}");
    let e = bad("rayleigh = { cross_section_cm2 = { file = \"no_such_sigma.csv\" } }");
    assert!(e.contains("cross_section_cm2") && e.contains("no_such_sigma.csv"), "{e}");
    let e = bad("rayleigh = { depolarisation = 0.7 }");
    assert!(e.contains("depolarisation = 0.7") && e.contains("[0, 0.5]"), "{e}");
    let e = bad("rayleigh = { king = 1.05 }");
    assert!(e.contains("rayleigh") && e.contains("unknown key `king`"), "{e}");
    let e = bad("rayleigh = 1.0");
    assert!(e.contains("rayleigh") && e.contains("give true, false or"), "{e}");
    let e = bad(&(xs("300, 700", "1e-26, 2e-27").replace(" } }", " }, depolarisation = 0.0 }")));
    assert!(e.contains("co2_ppm changes nothing"), "{e}");
    assert!(e.contains("test.toml:"), "{e}");
    // Outside Peck & Reeder's range a table needs its own ρ (Bodhaine's King factor stops there).
    let far = common::sky::black_earth(1700.0, 1800.0, &xs("1600, 1900", "5e-29, 2e-29"), ZENITH_BEAM);
    let e = scene_error(&far);
    assert!(e.contains("give `depolarisation`") && e.contains("1690") && e.contains("1750"), "{e}");
    let ok = far.replace(" } }", " }, depolarisation = 0.03 }");
    assert!(
        morgana::scene::load_scene_str(&ok, std::path::Path::new("t.toml"), std::path::Path::new("."), "t").is_ok()
    );
}
