//! A wind-roughened sea surface (Cox–Munk facets on a rough dielectric): what the photon pass
//! and the eye pass reflect, against the reflectance integrated from the BSDF, and bad input.

mod common;

use common::{mean_and_sem, render_with, scene, scene_error};
use glam::DVec3;
use morgana::material::{Beckmann, Ior, RoughDielectric};
use morgana::photon::PassSettings;
use morgana::photon::{MapKind, shoot};
use morgana::quadrature::gauss_legendre;
use std::f64::consts::PI;

const WIND_M_S: f64 = 7.0;

/// Directional-hemispherical reflectance ∫ f_r cos θ_o dω_o of water (n = 1.333) under Cox–Munk
/// facets for light arriving along `dir`, by quadrature of Walter et al.'s f_r (independent of
/// the sampler the renderer uses).
fn reflectance(dir: DVec3) -> f64 {
    let sea = RoughDielectric { ior: Ior::Constant { n: 1.333 }, facets: Beckmann::cox_munk(WIND_M_S) };
    let f = |mu: f64| {
        let r = (1.0 - mu * mu).max(0.0).sqrt();
        gauss_legendre(
            &|phi: f64| sea.eval(dir, DVec3::new(r * phi.cos(), mu, r * phi.sin()), DVec3::Y, 550.0, 1.0) * mu,
            0.0,
            2.0 * PI,
            24,
        )
    };
    gauss_legendre(&f, 0.0, 1.0, 64)
}

/// The sea: a rough water surface at y = 0 over a black floor 1 m below, and `light`.
fn sea_scene(camera: &str, light: &str, method: &str, spp: u32) -> String {
    format!(
        r#"
{camera}

[output]
bands = 1
min_nm = 540.0
max_nm = 560.0

[integrator]
method = "{method}"
photons = 1000
spp = {spp}

[[material]]
name = "sea"
type = "rough_dielectric"
ior = 1.333
wind_speed_m_s = {WIND_M_S}

[[material]]
name = "black"
type = "lambertian"
reflectance = 0.0

[[shape]]
type = "quad"
origin = [-50.0, 0.0, -50.0]
u = [0.0, 0.0, 100.0]
v = [100.0, 0.0, 0.0]
material = "sea"

[[shape]]
type = "quad"
origin = [-500.0, -1.0, -500.0]
u = [0.0, 0.0, 1000.0]
v = [1000.0, 0.0, 0.0]
material = "black"

{light}
"#
    )
}

const CAMERA_8: &str = r#"[camera]
position = [0.0, 1.0, 0.0]
look_at = [0.0, 0.0, -1.0]
fov_deg = 10.0
width = 8
height = 8"#;

#[test]
fn sunlight_reflected_by_the_rough_sea_is_the_bsdfs_reflectance() {
    // Every photon reflected by the surface escapes (nothing above it); every transmitted one
    // ends on the black floor. So escaped/emitted = R(θ) of the facets, at 30° and 75° from the
    // vertical (the second grazing, where shadowing matters).
    for zenith_deg in [30.0f64, 75.0] {
        let t = zenith_deg.to_radians();
        let dir = DVec3::new(t.sin(), -t.cos(), 0.0);
        let light = format!(
            "[[light]]\ntype = \"directional\"\ndirection = [{}, {}, 0.0]\nspectrum = 1.0\nirradiance_w_m2 = 1.0\ntarget_min = [-1.0, -0.01, -1.0]\ntarget_max = [1.0, 0.01, 1.0]",
            dir.x, dir.y
        );
        let s = scene(&sea_scene(CAMERA_8, &light, "photon_map", 1));
        let n = 400_000;
        let (_, stats) = shoot(&s.world, &PassSettings::of(&s), MapKind::Global, n, 8, &|_| {});
        let power = s.world.lights[0].power_w();
        let escaped = stats.escaped_w / power;
        let expected = reflectance(dir);
        // Each photon escapes with its facet weight (≈ 1) with probability ≈ R: binomial error.
        let se = (expected * (1.0 - expected) / n as f64).sqrt();
        assert!(
            (escaped - expected).abs() < 4.0 * se + 2e-4,
            "{zenith_deg}°: escaped fraction {escaped}, expected R = {expected} ± {se}"
        );
        assert!(escaped.is_finite() && stats.absorbed_surface_w.is_finite());
    }
}

#[test]
fn the_sky_seen_in_the_rough_sea_is_the_reflectance_times_its_radiance() {
    // Looking down at 40° below the horizontal under a uniform sky of radiance L over the whole
    // upper hemisphere: every reflected path escapes to the sky, so each pixel sees R(θ_v)·L
    // with θ_v the view's zenith angle at the surface (a 2° field of view keeps it near 50°).
    let l_sky = 3.0;
    let t = 40f64.to_radians();
    let camera = format!(
        "[camera]\nposition = [0.0, 1.0, 0.0]\nlook_at = [0.0, {}, {}]\nfov_deg = 2.0\nwidth = 16\nheight = 16",
        1.0 - t.sin(),
        -t.cos()
    );
    let sky = format!(
        "[[light]]\ntype = \"sky\"\nspectrum = 1.0\nscale = {l_sky}\ntarget_min = [-5.0, -0.01, -5.0]\ntarget_max = [5.0, 0.01, 5.0]"
    );
    let view = DVec3::new(0.0, -t.sin(), -t.cos());
    let expected = reflectance(view) * l_sky;
    for method in ["photon_map", "path"] {
        let s = scene(&sea_scene(&camera, &sky, method, 256));
        let px: Vec<f64> = render_with(&s, 2).image.data.iter().map(|v| *v as f64).collect();
        assert!(px.iter().all(|v| v.is_finite() && *v >= 0.0));
        let (mean, se) = mean_and_sem(&px);
        assert!((mean - expected).abs() < 4.0 * se + 0.002 * expected, "{method}: {mean} ± {se} vs {expected}");
    }
}

#[test]
fn rough_surfaces_need_exactly_one_roughness_and_sane_values() {
    let with = |fields: &str| {
        sea_scene(
            CAMERA_8,
            "[[light]]\ntype = \"point\"\nposition = [0.0, 5.0, 0.0]\nspectrum = 1.0\nscale = 1.0",
            "photon_map",
            1,
        )
        .replace(&format!("wind_speed_m_s = {WIND_M_S}"), fields)
    };
    let e = scene_error(&with(""));
    assert!(e.contains("needs wind_speed_m_s") && e.contains("test.toml:"), "{e}");
    let e = scene_error(&with("wind_speed_m_s = 5.0\nrms_slope = 0.1"));
    assert!(e.contains("not both"), "{e}");
    let e = scene_error(&with("wind_speed_m_s = 45.0"));
    assert!(e.contains("wind_speed_m_s = 45") && e.contains("[0, 30]"), "{e}");
    let e = scene_error(&with("rms_slope = 0.0"));
    assert!(e.contains("rms_slope = 0") && e.contains("(0, 1]"), "{e}");
    let smooth = with("rms_slope = 0.1").replace("type = \"rough_dielectric\"", "type = \"dielectric\"");
    let e = scene_error(&smooth);
    assert!(e.contains("rms_slope"), "a smooth dielectric has no roughness: {e}");
}
