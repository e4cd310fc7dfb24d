//! Luminaires as lights: photons carry exactly the file's flux in watts, leave in the file's
//! intensity distribution, and light a plane as E = I(C, γ) cos³γ / h²; the scene keys and the
//! `morgana luminaire` command.

mod common;

use common::{scene, scene_error};
use glam::DVec3;
use morgana::light::Light;
use morgana::photon::PassSettings;
use morgana::photon::{MapKind, shoot};
use morgana::photon_map::Filter;
use morgana::photon_map::{Estimator, Neighbours, Paths, PhotonMap};
use morgana::quadrature::gauss_legendre;
use morgana::rng::{Rng, Stream};
use morgana::spectrum::cie::cmf_1931_at_nm;
use morgana::spectrum::colour::K_M;
use morgana::testing::chi2::chi2_sphere;
use std::f64::consts::PI;
use std::path::PathBuf;

const DATA: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../shared/data/luminaires");

/// A camera, one band around 555 nm and a black sphere of radius 20 m around the origin.
fn black_sphere(bands: &str) -> String {
    let black = common::black_sphere(20.0);
    format!(
        r#"
[camera]
position = [0.0, 0.0, 0.0]
look_at = [0.0, 0.0, -1.0]
fov_deg = 60.0
width = 8
height = 8

[output]
{bands}
{black}"#
    )
}

/// A spectral line at 555 nm, where ȳ = 1: one lumen is exactly 1/683.002 W.
const LINE_555: &str = "{ nm = [550.0, 554.0, 555.0, 556.0, 560.0], values = [0.0, 0.0, 1.0, 0.0, 0.0] }";
const BANDS_555: &str = "bands = 1\nmin_nm = 550.0\nmax_nm = 560.0";

fn luminaire(file: &str, extra: &str) -> String {
    format!(
        "[[light]]\nname = \"lum\"\ntype = \"luminaire\"\nfile = \"{DATA}/{file}\"\nposition = [0.0, 2.0, 0.0]\n{extra}\n"
    )
}

fn the_luminaire(s: &morgana::scene::Scene) -> &morgana::light::LuminaireLight {
    match &s.world.lights[0] {
        Light::Luminaire(l) => l,
        _ => panic!("not a luminaire"),
    }
}

#[test]
fn photons_carry_the_stated_lumens_in_watts_at_555_nm() {
    if common::shared::shared_data("luminaires").is_none() {
        return;
    }
    // sample8 states 400 lm × LORL 88.629% = 354.52 lm; its table integrates to within 0.002%.
    let s =
        scene(&(black_sphere(BANDS_555) + &luminaire("ldt/eulumdatpy_sample8.ldt", &format!("spectrum = {LINE_555}"))));
    let stated_w = 400.0 * 0.88629073034905 / K_M;
    let power = s.world.lights[0].power_w();
    assert!((power / stated_w - 1.0).abs() < 1e-4, "{power} W vs {stated_w} W");
    let n = 100_000;
    let (sink, stats) = shoot(&s.world, &PassSettings::of(&s), MapKind::Global, n, 3, &|_| {});
    let photons = sink.surface;
    assert_eq!(photons.len() as u64, n, "each photon stored once");
    let stored: f64 = photons.iter().map(|p| p.power_w).sum();
    assert!((stored / power - 1.0).abs() < 1e-9, "{stored} W of {power} W");
    assert_eq!(stats.escaped_w, 0.0);
}

#[test]
fn a_black_body_lamp_gets_watts_by_its_luminous_efficacy() {
    if common::shared::shared_data("luminaires").is_none() {
        return;
    }
    // Φ_e(380–780) = Φ_v ∫ B dλ / (K_m Σ B ȳ Δλ): the integral by a 0.05 nm midpoint rule and the
    // CIE sum from the 1 nm table, here, independently of the light's code.
    let s = scene(&(black_sphere("bands = 8") + &luminaire("ldt/eulumdatpy_sample5.ldt", "cct_k = 4000")));
    let b = |l: f64| morgana::spectrum::planck_radiance(4000.0, l);
    let in_range: f64 = (0..8000).map(|i| b(380.0 + 0.05 * (i as f64 + 0.5)) * 0.05).sum();
    let luminous: f64 = (360..=830).map(|nm| b(nm as f64) * cmf_1931_at_nm(nm)[1]).sum();
    let flux_lm = the_luminaire(&s).flux_lm();
    assert!((flux_lm / 611.9 - 1.0).abs() < 0.001, "the ERCO file's table gives {flux_lm} lm for 611.9 lm");
    let want = flux_lm * in_range / (K_M * luminous);
    // The light integrates a smooth spectrum to the sampler's stated 1e-4.
    assert!((s.world.lights[0].power_w() / want - 1.0).abs() < 1e-4, "{} W vs {want} W", s.world.lights[0].power_w());
}

#[test]
fn emission_from_the_opening_still_delivers_every_watt() {
    if common::shared::shared_data("luminaires").is_none() {
        return;
    }
    let s = scene(
        &(black_sphere("bands = 4")
            + &luminaire(
                "ies/eulumdatrs_edge_ABSOLUTE_LED.ies",
                "cct_k = 3000\nemitter = \"opening\"\nrotation_deg = [30.0, 0.0, 0.0]",
            )),
    );
    let power = s.world.lights[0].power_w();
    let photons = shoot(&s.world, &PassSettings::of(&s), MapKind::Global, 50_000, 4, &|_| {}).0.surface;
    let stored: f64 = photons.iter().map(|p| p.power_w).sum();
    assert_eq!(photons.len(), 50_000);
    assert!((stored / power - 1.0).abs() < 1e-9);
    // Start points fill the 0.2 × 0.2 × 0.1 m box: photons hit the wall from up to ~0.15 m apart.
    let l = the_luminaire(&s);
    let mut rng = Rng::for_task(1, Stream::Test, 0);
    let spread = (0..2000).map(|_| (l.start(&mut rng) - DVec3::new(0.0, 2.0, 0.0)).length()).fold(0.0, f64::max);
    assert!(spread > 0.1 && spread <= 0.151, "{spread}");
}

/// p-value of the emitted directions against I(ω)/Φ for a shared file, placed turned.
fn chi2_of(file: &str) -> f64 {
    let s = scene(&(black_sphere("bands = 4") + &luminaire(file, "cct_k = 3000\nrotation_deg = [20.0, 35.0, 0.0]")));
    let l = the_luminaire(&s);
    let mut rng = Rng::for_task(17, Stream::Test, 0);
    let p = chi2_sphere(48, 48, 400_000, || Some(l.emit(&mut rng).1), |w| l.intensity_cd(w) / l.flux_lm());
    println!("{file}: chi-square p = {p:.3}");
    p
}

#[test]
fn emitted_directions_follow_real_webs() {
    if common::shared::shared_data("luminaires").is_none() {
        return;
    }
    // Šidák-corrected 1% level over the six files.
    let level = 1.0 - 0.99f64.powf(1.0 / 6.0);
    for file in [
        "ldt/eulumdatpy_sample1.ldt",
        "ldt/eulumdatpy_sample2.ldt",
        "ldt/eulumdatpy_sample5.ldt",
        "ldt/ledvance_4058075580657_ASYM_50X110.ldt",
        "ies/aec_ITALO_1_5P5_S05_3.140-3M.IES",
        "ies/lm63_2002_spec_example_tilt_include.ies",
    ] {
        let p = chi2_of(file);
        assert!(p > level, "{file}: p = {p}");
    }
}

/// An analytic luminaire written as an LM-63 file: I = 800 (1 + 0.6 cos γ)(1 + 0.3 sin γ cos C) cd
/// for γ ≤ 90°, nothing upward (continuous at the nadir); C every 5°, γ every 2.5°, where the
/// web's interpolation errs by < 3e-4.
fn analytic(c_deg: f64, gamma_deg: f64) -> f64 {
    if gamma_deg > 90.0 {
        return 0.0;
    }
    let g = gamma_deg.to_radians();
    800.0 * (1.0 + 0.6 * g.cos()) * (1.0 + 0.3 * g.sin() * c_deg.to_radians().cos())
}

fn write_analytic_ies() -> PathBuf {
    let v: Vec<f64> = (0..=36).map(|j| 2.5 * j as f64).collect();
    let h: Vec<f64> = (0..=72).map(|i| 5.0 * i as f64).collect();
    let mut s =
        format!("IESNA:LM-63-2002\n[MANUFAC] test\nTILT=NONE\n1 -1 1 {} {} 1 2 0 0 0\n1 1 0\n", v.len(), h.len());
    let list = |a: &[f64]| a.iter().map(|x| x.to_string()).collect::<Vec<_>>().join(" ") + "\n";
    s += &list(&v);
    s += &list(&h);
    for c in &h {
        s += &list(&v.iter().map(|g| analytic(*c, *g)).collect::<Vec<_>>());
    }
    let path = std::env::temp_dir().join(format!("morgana-analytic-{}.ies", std::process::id()));
    std::fs::write(&path, s).unwrap();
    path
}

/// E at (x, 0, z) from the analytic luminaire hanging at height h (C0 = +X, C90 = −Z).
fn illuminance(h: f64, x: f64, z: f64) -> f64 {
    let r = (x * x + z * z).sqrt();
    let gamma = r.atan2(h).to_degrees();
    let c = (-z).atan2(x).to_degrees();
    let cos = h / (r * r + h * h).sqrt();
    analytic(c, gamma) * cos.powi(3) / (h * h)
}

#[test]
fn photon_map_illuminance_under_a_luminaire_is_i_cos3_over_h2() {
    let ies = write_analytic_ies();
    let toml = format!(
        "{}\n[[shape]]\ntype = \"quad\"\norigin = [-15.0, 0.0, -15.0]\nu = [0.0, 0.0, 30.0]\nv = [30.0, 0.0, 0.0]\nmaterial = \"black\"\n\n[[light]]\ntype = \"luminaire\"\nfile = \"{}\"\nposition = [0.0, 2.0, 0.0]\nspectrum = {LINE_555}\n",
        black_sphere(BANDS_555).replace("radius = 20.0", "radius = 30.0"),
        ies.display()
    );
    let s = scene(&toml);
    let records = shoot(&s.world, &PassSettings::of(&s), MapKind::Global, 2_000_000, 21, &|_| {}).0.surface;
    let map = PhotonMap::build(&records);
    // Relative standard deviation of a cone-filtered k-photon estimate ≈ 1.14/√k = 3.6%.
    let (k, k_cone) = (1000, 1.1);
    let est = Estimator {
        map: &map,
        k,
        max_radius: 1.0,
        filter: Filter::Cone { k: k_cone },
        bands: s.bands,
        paths: Paths::All,
        scatter_rows: None,
        disc_share: None,
    };
    let mut nb = Neighbours::default();
    let h = 2.0;
    for (x, z) in [(0.0, 0.0), (1.0, 0.0), (-1.5, 0.0), (0.0, -1.2), (1.5, 1.5), (2.5, -0.5)] {
        // W m⁻² nm⁻¹ over the 10 nm band → W m⁻² → lux (the 555 nm line: 683.002 lm/W).
        let lux = est.irradiance(DVec3::new(x, 0.0, z), DVec3::Y, &mut nb)[0] * 10.0 * K_M;
        let r = (nb.max_dist2() as f64).sqrt();
        let filtered = gauss_legendre(
            &|rho: f64| {
                gauss_legendre(&|phi: f64| illuminance(h, x + rho * phi.cos(), z + rho * phi.sin()), 0.0, 2.0 * PI, 4)
                    * (1.0 - rho / (k_cone * r))
                    * rho
            },
            0.0,
            r,
            4,
        ) / ((1.0 - 2.0 / (3.0 * k_cone)) * PI * r * r);
        let exact = illuminance(h, x, z);
        let err = lux / filtered - 1.0;
        println!(
            "({x}, {z}): photon map {lux:.2} lx, filtered closed form {filtered:.2} lx, point {exact:.2} lx, error {:+.2}%",
            100.0 * err
        );
        assert!(err.abs() < 4.0 / (k as f64).sqrt(), "({x}, {z}): {lux} lx vs {filtered} lx");
        assert!((filtered / exact - 1.0).abs() < 0.03, "disc radius {r} too large at ({x}, {z})");
    }
    std::fs::remove_file(ies).ok();
}

#[test]
fn a_sensor_reads_direct_illuminance_i_cos3_over_h2() {
    // Direct light only (gather_rays = 0): exact for a point emitter but for the stratified
    // wavelength samples of the lux integral (64 × 16 over 380–780 nm, which hold 99.997% of a
    // 4000 K black body's lumens).
    let ies = write_analytic_ies();
    let toml = format!(
        "{}\n[[light]]\ntype = \"luminaire\"\nfile = \"{}\"\nposition = [0.0, 2.0, 0.0]\ncct_k = 4000\n\n[[sensor]]\nname = \"floor\"\ntype = \"illuminance_plane\"\norigin = [-2.0, -1.0, 2.0]\nu = [4.0, 0.0, 0.0]\nv = [0.0, 0.0, -4.0]\nresolution = [4, 4]\nsamples = 64\ngather_rays = 0\n",
        black_sphere("bands = 16"),
        ies.display()
    );
    let s = scene(&toml);
    let maps = morgana::render::photon_pass::Maps::default();
    let r = &morgana::render::sensors::evaluate_all(&s, &s.integrator, &maps)[0];
    assert_eq!(r.columns[0].0, "E_lx");
    for (p, e) in r.points.iter().zip(&r.columns[0].1) {
        let want = illuminance(3.0, p.x, p.z);
        assert!((e / want - 1.0).abs() < 0.001, "{p}: {e} lx vs {want} lx");
    }
    assert!(r.columns[2].1.iter().all(|x| *x == 0.0), "no indirect light without gather rays");
    std::fs::remove_file(ies).ok();
}

#[test]
fn a_sensor_in_an_integrating_sphere_reads_the_sphere_formula() {
    // An isotropic 100 cd source (Φ = 400π lm) at the centre of a diffuse sphere (R = 1 m,
    // ρ = 0.5): light reflected at least once gives every inner point the irradiance
    // ρ Φ / (4π R² (1 − ρ)) = 100 lx from any direction; direct light adds I cos θ / d².
    let ies = std::env::temp_dir().join(format!("morgana-isotropic-{}.ies", std::process::id()));
    std::fs::write(&ies, "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 2 1 1 2 0 0 0\n1 1 0\n0 180\n0\n100 100\n").unwrap();
    let toml = format!(
        r#"
[camera]
position = [0.0, 0.0, 0.5]
look_at = [0.0, 0.0, -1.0]
fov_deg = 60.0
width = 4
height = 4

[output]
bands = 8

[integrator]
photons = 400000
k = 200

[[material]]
name = "wall"
type = "lambertian"
reflectance = 0.5

[[shape]]
type = "sphere"
center = [0.0, 0.0, 0.0]
radius = 1.0
material = "wall"

[[light]]
type = "luminaire"
file = "{}"
position = [0.0, 0.0, 0.0]
cct_k = 5000

[[sensor]]
name = "probe"
type = "illuminance_plane"
origin = [-0.3, -0.5, 0.3]
u = [0.6, 0.0, 0.0]
v = [0.0, 0.0, -0.6]
resolution = [3, 3]
samples = 16
gather_rays = 256
"#,
        ies.display()
    );
    let s = scene(&toml);
    let rendered = common::render_with(&s, 2);
    let r = &rendered.sensors[0];
    let fraction = morgana::luminaire::luminous_fraction_in(
        &morgana::spectrum::Spectrum::Blackbody { temperature_k: 5000.0 },
        380.0,
        780.0,
    );
    let indirect = r.columns[2].1.iter().sum::<f64>() / 9.0;
    println!("integrating sphere: indirect {indirect:.2} lx (closed form {:.2} lx)", 100.0 * fraction);
    assert!((indirect / (100.0 * fraction) - 1.0).abs() < 0.05, "{indirect} lx");
    for (p, d) in r.points.iter().zip(&r.columns[1].1) {
        let want = 100.0 * fraction * 0.5 / p.length().powi(3);
        // Only 16 jittered wavelengths per 50 nm band estimate the lux integral here.
        assert!((d / want - 1.0).abs() < 0.01, "{p}: direct {d} lx vs {want} lx");
    }
    std::fs::remove_file(ies).ok();
}

#[test]
fn lm63_tilt_factors_apply_at_the_installed_tilt() {
    if common::shared::shared_data("luminaires").is_none() {
        return;
    }
    // The LM-63 example's tilt table gives 0.95 at 15° and 0.87 at 75°.
    let base = black_sphere("bands = 4");
    let flux = |extra: &str| {
        the_luminaire(&scene(
            &(base.clone()
                + &luminaire("ies/lm63_2002_spec_example_tilt_include.ies", &format!("cct_k = 3000\n{extra}"))),
        ))
        .flux_lm()
    };
    let upright = flux("");
    assert!((flux("rotation_deg = [15.0, 0.0, 0.0]") / upright - 0.95).abs() < 1e-9);
    assert!((flux("rotation_deg = [0.0, 0.0, 75.0]") / upright - 0.87).abs() < 1e-9);
    assert!(
        (flux("rotation_deg = [0.0, 40.0, 0.0]") / upright - 1.0).abs() < 1e-12,
        "a turn about the vertical is no tilt"
    );
}

#[test]
fn orientation_keys_place_the_nadir() {
    if common::shared::shared_data("luminaires").is_none() {
        return;
    }
    let base = black_sphere("bands = 4");
    let at = |extra: &str| {
        let s = scene(&(base.clone() + &luminaire("ldt/eulumdatpy_sample5.ldt", &format!("cct_k = 3000\n{extra}"))));
        let l = the_luminaire(&s);
        // The downlight's peak is near γ = 8°: the brightest of a few directions shows the nadir.
        let dirs = [DVec3::NEG_Y, DVec3::X, DVec3::NEG_X, DVec3::Z, DVec3::NEG_Z, DVec3::Y];
        dirs.into_iter().max_by(|a, b| l.intensity_cd(*a).total_cmp(&l.intensity_cd(*b))).unwrap()
    };
    assert_eq!(at(""), DVec3::NEG_Y);
    assert_eq!(at("direction = [1.0, 0.0, 0.0]"), DVec3::X);
    assert_eq!(at("look_at = [0.0, 2.0, -5.0]"), DVec3::NEG_Z);
    assert_eq!(at("rotation_deg = [90.0, 0.0, 0.0]"), DVec3::NEG_Z);
}

#[test]
fn scene_errors_say_what_is_wrong_and_where() {
    if common::shared::shared_data("luminaires").is_none() {
        return;
    }
    let base = black_sphere("bands = 4");
    let file_line = |toml: &str| toml.lines().position(|l| l.starts_with("file =")).unwrap() + 1;
    let toml = base.clone()
        + "[[light]]\ntype = \"luminaire\"\nfile = \"nope/missing.ldt\"\nposition = [0.0, 1.0, 0.0]\ncct_k = 3000\n";
    let e = scene_error(&toml);
    let want = format!(
        "test.toml:{}:8: light \"light #1\" (luminaire): luminaire file ./nope/missing.ldt does not exist",
        file_line(&toml)
    );
    assert!(e.starts_with(&want), "{e}");
    let e = scene_error(&(base.clone() + &luminaire("ldt/eulumdatpy_sample5.ldt", "")));
    assert!(e.contains("give exactly one of spectrum or cct_k"), "{e}");
    let e = scene_error(&(base.clone() + &luminaire("ldt/eulumdatpy_sample5.ldt", "cct_k = 3000\npower_w = 5.0")));
    assert!(e.contains("field `power_w` is not used here"), "{e}");
    let e = scene_error(
        &(base.clone()
            + &luminaire(
                "ldt/eulumdatpy_sample5.ldt",
                "cct_k = 3000\ndirection = [0.0, -1.0, 0.0]\nrotation_deg = [1.0, 0.0, 0.0]",
            )),
    );
    assert!(e.contains("not both"), "{e}");
    let e = scene_error(&(base.clone() + &luminaire("ldt/eulumdatpy_sample5.ldt", "cct_k = 3000\nemitter = \"bulb\"")));
    assert!(e.contains("emitter \"bulb\" is not known; allowed: point, opening"), "{e}");
    // A malformed luminaire file: the error points into it and names the light and scene line.
    let dir = std::env::temp_dir().join(format!("morgana-bad-lum-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bad =
        std::fs::read_to_string(format!("{DATA}/ldt/eulumdatpy_sample2.ldt")).unwrap().replacen("\n72\n", "\n7x2\n", 1);
    std::fs::write(dir.join("bad.ldt"), bad).unwrap();
    std::fs::write(dir.join("lamp.cib"), "whatever").unwrap();
    let light = |f: &str| {
        format!(
            "[[light]]\nname = \"l\"\ntype = \"luminaire\"\nfile = \"{}\"\nposition = [0.0, 1.0, 0.0]\ncct_k = 3000\n",
            dir.join(f).display()
        )
    };
    let toml = base.clone() + &light("bad.ldt");
    let e = scene_error(&toml);
    assert!(e.contains("bad.ldt:4: EULUMDAT field 4 (Mc"), "{e}");
    let scene_at = format!("luminaire file of light \"l\" (luminaire), test.toml:{}:8", file_line(&toml));
    assert!(e.contains("found \"7x2\"") && e.contains(&scene_at), "{e}");
    let e = scene_error(&(base + &light("lamp.cib")));
    assert!(e.contains("TM14") && e.contains("EULUMDAT (.ldt, .eul)"), "{e}");
    std::fs::remove_dir_all(dir).ok();
}

#[test]
fn the_luminaire_command_prints_the_facts_and_draws_the_curves() {
    if common::shared::shared_data("luminaires").is_none() {
        return;
    }
    let png = std::env::temp_dir().join(format!("morgana-polar-{}.png", std::process::id()));
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_morgana"))
        .args(["luminaire", &format!("{DATA}/ldt/eulumdatpy_sample2.ldt"), "--png"])
        .arg(&png)
        .output()
        .unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    for want in [
        "EULUMDAT",
        "Regent",
        "4600 lm",
        "flux, web",
        "about the C0–C180 plane",
        "72 × 37 full",
        "beam (50%)",
        "field (10%)",
    ] {
        assert!(text.contains(want), "missing {want:?} in\n{text}");
    }
    assert!(std::fs::metadata(&png).unwrap().len() > 1000);
    std::fs::remove_file(&png).ok();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_morgana"))
        .args(["luminaire", "/nonexistent.ies"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("cannot read luminaire file"));
}

#[test]
fn a_render_writes_each_sensor_as_csv_and_png() {
    if common::shared::shared_data("luminaires").is_none() {
        return;
    }
    let toml = black_sphere("bands = 4")
        + &luminaire("ldt/eulumdatpy_sample5.ldt", "cct_k = 3000")
        + "\n[[sensor]]\nname = \"floor plane\"\ntype = \"illuminance_plane\"\norigin = [-1.0, 0.0, 1.0]\nu = [2.0, 0.0, 0.0]\nv = [0.0, 0.0, -2.0]\nresolution = [5, 3]\ngather_rays = 0\n";
    let s = scene(&toml);
    let rendered = common::render_with(&s, 2);
    let dir = std::env::temp_dir().join(format!("morgana-sensor-out-{}", std::process::id()));
    let written = morgana::output::write_outputs(&s, &rendered, &dir, 2, 0.0).unwrap();
    let csv = dir.join("test_floor_plane.csv");
    assert!(written.contains(&csv) && written.contains(&dir.join("test_floor_plane.png")), "{written:?}");
    let text = std::fs::read_to_string(&csv).unwrap();
    assert!(text.starts_with("i,j,x_m,y_m,z_m,E_lx,E_direct_lx,E_indirect_lx\n"));
    assert_eq!(text.lines().count(), 1 + 15);
    std::fs::remove_dir_all(dir).ok();
}
