//! The reference path tracer against closed forms, and the photon-map integrator converging to
//! it as photons grow.

mod common;

use common::{render_with, scene};

fn mean(v: &[f32]) -> f64 {
    v.iter().map(|x| *x as f64).sum::<f64>() / v.len() as f64
}

/// The volumetric furnace of tests/media.rs (sphere wall emitting 2 and reflecting 0.5, filled
/// with a non-absorbing medium): L = L_e/(1 − ρ) = 4.
#[test]
fn path_tracer_gives_the_volumetric_furnace_radiance() {
    let toml = r#"
[camera]
position = [0.0, 0.0, 0.0]
look_at = [0.2, 0.1, -1.0]
fov_deg = 80.0
width = 16
height = 16

[output]
bands = 2
min_nm = 450.0
max_nm = 650.0

[integrator]
method = "path"
spp = 64
seed = 5

[world]
medium = "fog"

[[medium]]
name = "fog"
sigma_t = 1.0
albedo = 1.0
phase = { type = "hg", g = 0.5 }

[[material]]
name = "wall"
type = "lambertian"
reflectance = 0.5

[[light]]
type = "area"
shape = "sphere"
center = [0.0, 0.0, 0.0]
radius = 1.0
side = "back"
material = "wall"
spectrum = 1.0
scale = 2.0
"#;
    let s = scene(toml);
    assert!(!s.plan.volume_map.on && !s.plan.global_map.on);
    let r = render_with(&s, 2);
    let m = mean(&r.image.data);
    // 16·16·64 paths; per-path relative spread is about 1, so the mean is good to ~0.5%.
    assert!((m / 4.0 - 1.0).abs() < 0.02, "path tracer mean {m}, expected 4");
}

/// On the fog box, the photon-map image mean approaches the path tracer's as photons grow (the
/// bias of density estimation shrinks with the radius); the trend is printed for the record.
#[test]
fn photon_map_converges_to_the_path_tracer() {
    let base = std::fs::read_to_string("examples/fog_box.toml").expect("examples/fog_box.toml");
    let small = base
        .replace("width = 128", "width = 16")
        .replace("height = 128", "height = 16")
        .replace("gather_rays = 16\n", "gather_rays = 8\n");
    let reference = scene(&small.replace("photons = 400000", "method = \"path\"").replace("spp = 8", "spp = 1024"));
    let r = render_with(&reference, 2);
    let m_ref = mean(&r.image.data);
    let mut errors = Vec::new();
    for photons in [5_000, 40_000, 320_000] {
        let s =
            scene(&small.replace("photons = 400000", &format!("photons = {photons}")).replace("spp = 8", "spp = 4"));
        let m = mean(&render_with(&s, 2).image.data);
        errors.push((photons, (m / m_ref - 1.0).abs()));
    }
    eprintln!("photon-map image mean vs path tracer (relative error by photons): {errors:?}");
    let last = errors.last().unwrap().1;
    assert!(last < 0.03, "photon map at 320k photons differs from the path tracer by {last}");
    assert!(last < errors[0].1, "error did not shrink with photons: {errors:?}");
}
