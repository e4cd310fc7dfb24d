//! Flux conservation and irradiance against closed forms.

mod common;

use common::scene;
use glam::DVec3;
use morgana::photon::PassSettings;
use morgana::photon::{MapKind, shoot};
use morgana::photon_map::Filter;
use morgana::photon_map::{Estimator, Neighbours, Paths, PhotonMap};
use morgana::quadrature::gauss_legendre;
use std::f64::consts::PI;

const BLACK_SPHERE: &str = r#"
[camera]
position = [0.0, 0.0, 0.0]
look_at = [0.0, 0.0, -1.0]
fov_deg = 60.0
width = 8
height = 8

[output]
bands = 8
min_nm = 400.0
max_nm = 700.0

[[material]]
name = "black"
type = "lambertian"
reflectance = 0.0

[[shape]]
type = "sphere"
center = [0.0, 0.0, 0.0]
radius = 5.0
material = "black"
"#;

/// Shoots `n` global photons and checks that each was stored exactly once and that the stored
/// power equals the lights' power.
fn all_power_arrives(lights: &str, expected_power: f64) -> Vec<morgana::photon_map::PhotonRecord> {
    let s = scene(&format!("{BLACK_SPHERE}\n{lights}"));
    let total: f64 = s.world.lights.iter().map(|l| l.power_w()).sum();
    assert!((total - expected_power).abs() < 1e-9 * total, "light power {total}, expected {expected_power}");
    let n = 100_000;
    let (sink, stats) = shoot(&s.world, &PassSettings::of(&s), MapKind::Global, n, 5, &|_| {});
    let photons = sink.surface;
    assert_eq!(photons.len() as u64, n, "each photon stored exactly once");
    let stored: f64 = photons.iter().map(|p| p.power_w).sum();
    assert!((stored - total).abs() < 1e-9 * total, "stored {stored} W of {total} W");
    assert!((stats.absorbed_surface_w - total).abs() < 1e-9 * total);
    assert_eq!(stats.escaped_w, 0.0);
    photons
}

#[test]
fn every_emitted_watt_arrives_once_in_a_black_enclosure() {
    // Inside a black sphere each photon hits the wall once, is stored once and absorbed.
    let point =
        "[[light]]\ntype = \"point\"\nposition = [0.5, 0.0, 0.0]\nspectrum = { blackbody_k = 3000 }\npower_w = 25.0\n";
    let photons = all_power_arrives(point, 25.0);
    // The photons' wavelengths follow the spectrum: a 3000 K black body rises toward the red.
    let red = photons.iter().filter(|p| p.wavelength_nm > 550.0).count();
    assert!(red > photons.len() / 2);
    // A quad area light given by its radiance: Φ = π A ∫L dλ = π · 0.2 m² · 0.01 · 300 nm.
    let quad = "[[light]]\ntype = \"area\"\nshape = \"quad\"\norigin = [-1.0, 1.0, -1.0]\nu = [0.5, 0.0, 0.0]\nv = [0.0, 0.0, 0.4]\nspectrum = 1.0\nscale = 0.01\n";
    all_power_arrives(quad, PI * 0.2 * 0.01 * 300.0);
    // A spot light given by its power.
    let spot = "[[light]]\ntype = \"spot\"\nposition = [0.0, 0.0, 0.0]\ndirection = [0.0, -1.0, 0.0]\ncone_deg = 30.0\nfalloff_start_deg = 20.0\nspectrum = \"D65\"\npower_w = 3.0\n";
    all_power_arrives(spot, 3.0);
}

/// Irradiance at (x, 0, 0) on the plane y = 0 from a point light of intensity I at height h:
/// E = I cos θ / r² = I h / (x² + h²)^{3/2}.
fn irradiance(i: f64, h: f64, x: f64, z: f64) -> f64 {
    i * h / (x * x + z * z + h * h).powf(1.5)
}

#[test]
fn diffuse_plane_under_a_point_light_gets_i_cos_theta_over_r_squared() {
    let (intensity, h) = (2.0, 1.0);
    let toml = r#"
[camera]
position = [0.0, 3.0, 3.0]
look_at = [0.0, 0.0, 0.0]
fov_deg = 60.0
width = 8
height = 8

[output]
bands = 1
min_nm = 500.0
max_nm = 600.0

[[material]]
name = "black"
type = "lambertian"
reflectance = 0.0

[[shape]]
type = "quad"
origin = [-20.0, 0.0, -20.0]
u = [0.0, 0.0, 40.0]
v = [40.0, 0.0, 0.0]
material = "black"

[[light]]
type = "point"
position = [0.0, 1.0, 0.0]
spectrum = 1.0
scale = 0.02
"#;
    let s = scene(toml);
    // Intensity per nm 0.02 over 100 nm: I = 2 W/sr; the photon map's band value is E per nm.
    let records = shoot(&s.world, &PassSettings::of(&s), MapKind::Global, 2_000_000, 11, &|_| {}).0.surface;
    let map = PhotonMap::build(&records);
    let k = 1000;
    let filter = Filter::Cone { k: 1.1 };
    let est = Estimator {
        map: &map,
        k,
        max_radius: 1.0,
        filter,
        bands: s.bands,
        paths: Paths::All,
        scatter_rows: None,
        disc_share: None,
    };
    let mut nb = Neighbours::default();
    for x in [0.0, 0.4, 0.8, 1.2] {
        let e_band = est.irradiance(DVec3::new(x, 0.0, 0.0), DVec3::Y, &mut nb)[0] * 100.0;
        // The estimate's expectation given its radius r is the cone-filtered irradiance over
        // the disc, computed here by quadrature of the closed form.
        let r = (nb.max_dist2() as f64).sqrt();
        let k_cone = 1.1;
        let filtered = gauss_legendre(
            &|rho: f64| {
                gauss_legendre(
                    &|phi: f64| irradiance(intensity, h, x + rho * phi.cos(), rho * phi.sin()),
                    0.0,
                    2.0 * PI,
                    4,
                ) * (1.0 - rho / (k_cone * r))
                    * rho
            },
            0.0,
            r,
            4,
        ) / ((1.0 - 2.0 / (3.0 * k_cone)) * PI * r * r);
        let exact = irradiance(intensity, h, x, 0.0);
        // Relative standard deviation of a k-photon estimate is about 1/√k = 3.2%; allow 4σ.
        let tol = 4.0 / (k as f64).sqrt();
        assert!(
            (e_band / filtered - 1.0).abs() < tol,
            "x = {x}: estimate {e_band}, filtered closed form {filtered} (point value {exact})"
        );
        assert!((filtered / exact - 1.0).abs() < 0.05, "disc radius {r} too large for a point comparison at x = {x}");
    }
}

#[test]
fn a_directional_light_delivers_its_irradiance_times_the_area_it_lights() {
    // E = 3 W/m² straight down onto a black 2 m × 2 m plate: 12 W arrive. Photons start on a disk
    // covering the scene's bounding sphere, so a fraction of them hit the plate; the stored power
    // estimates 12 W with relative standard error √((1 − p)/(pN)) ≈ 0.24% for p = 4/(π·2).
    let toml = r#"
[camera]
position = [0.0, 3.0, 3.0]
look_at = [0.0, 0.0, 0.0]
fov_deg = 60.0
width = 8
height = 8

[[material]]
name = "black"
type = "lambertian"
reflectance = 0.0

[[shape]]
type = "quad"
origin = [-1.0, 0.0, -1.0]
u = [0.0, 0.0, 2.0]
v = [2.0, 0.0, 0.0]
material = "black"

[[light]]
type = "directional"
direction = [0.0, -1.0, 0.0]
spectrum = "D65"
irradiance_w_m2 = 3.0
"#;
    let s = scene(toml);
    let (sink, stats) = shoot(&s.world, &PassSettings::of(&s), MapKind::Global, 100_000, 8, &|_| {});
    let photons = sink.surface;
    let stored: f64 = photons.iter().map(|p| p.power_w).sum();
    assert!((stored / 12.0 - 1.0).abs() < 0.01, "stored {stored} W, expected 12 W");
    assert!(
        (stats.escaped_w + stats.absorbed_surface_w - s.world.lights[0].power_w()).abs()
            < 1e-9 * s.world.lights[0].power_w()
    );
    assert!(photons.iter().all(|p| p.dir.y < -0.999_999));
}

#[test]
fn a_directional_light_limited_to_a_target_box_spends_every_photon_on_it() {
    // The beam limited to the plate's box: every photon hits the plate, and the plate receives
    // exactly E × its area; shadow rays see the light only inside the beam.
    let toml = r#"
[camera]
position = [0.0, 3.0, 3.0]
look_at = [0.0, 0.0, 0.0]
fov_deg = 60.0
width = 8
height = 8

[[material]]
name = "black"
type = "lambertian"
reflectance = 0.0

[[shape]]
type = "quad"
origin = [-5.0, 0.0, -5.0]
u = [0.0, 0.0, 10.0]
v = [10.0, 0.0, 0.0]
material = "black"

[[light]]
type = "directional"
direction = [0.0, -1.0, 0.0]
spectrum = "D65"
irradiance_w_m2 = 3.0
target_min = [-1.0, -0.01, -0.5]
target_max = [1.0, 0.01, 0.5]
"#;
    let s = scene(toml);
    assert!((s.world.lights[0].power_w() - 6.0).abs() < 1e-9, "beam power {}", s.world.lights[0].power_w());
    let (sink, _) = shoot(&s.world, &PassSettings::of(&s), MapKind::Global, 10_000, 8, &|_| {});
    assert_eq!(sink.surface.len(), 10_000);
    assert!(sink.surface.iter().all(|p| p.position.x.abs() <= 1.0 + 1e-9 && p.position.z.abs() <= 0.5 + 1e-9));
    let stored: f64 = sink.surface.iter().map(|p| p.power_w).sum();
    assert!((stored - 6.0).abs() < 1e-9);
    assert!(s.world.lights[0].incident(glam::DVec3::new(0.5, 0.0, 0.2), [0.5, 0.5]).is_some());
    assert!(s.world.lights[0].incident(glam::DVec3::new(2.0, 0.0, 0.2), [0.5, 0.5]).is_none());
}
