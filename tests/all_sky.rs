//! The all-sky camera (`[camera] projection = "equal_area"`): a uniform sky gives a uniform
//! image of its radiance, the image's pixels hold equal solid angles that add up to the field,
//! and on a Rayleigh sky its pixels agree with the `sky_radiance` sensor looking the same way.

mod common;

use common::{mean_and_sem, render_with, scene, scene_error};
use std::f64::consts::PI;

/// An all-sky camera at the origin looking up (azimuth 0° at the image's top), `n` × `n`
/// pixels over a field of `fov` degrees, under a uniform sky of radiance 3 W m⁻² sr⁻¹ nm⁻¹,
/// over a black plate 1 m below, with `method` as the eye pass.
fn uniform_sky(method: &str, fov: f64, n: u32) -> String {
    format!(
        r#"
[camera]
position = [0.0, 0.0, 0.0]
look_at = [0.0, 1.0, 0.0]
up = [0.0, 0.0, -1.0]
projection = "equal_area"
fov_deg = {fov:?}
width = {n}
height = {n}

[output]
bands = 1
min_nm = 540.0
max_nm = 560.0

[integrator]
method = "{method}"
photons = 1000
spp = 64

{box_floor}

[[light]]
type = "sky"
spectrum = 3.0
scale = 1.0
"#,
        box_floor = common::black_quad([-1.0, -1.0, -1.0], [0.0, 0.0, 2.0], [2.0, 0.0, 0.0]),
    )
}

#[test]
fn a_uniform_sky_gives_a_uniform_image_of_its_radiance() {
    // Every pixel wholly inside the image circle looks at the sky only (the plate is below the
    // horizon): L = 3 exactly, whatever the eye pass. The whole image, L Ω summed over the
    // pixels (rim pixels partly covered, by their jittered samples), is 2π L: the hemisphere.
    for method in ["path", "photon_map"] {
        let s = scene(&uniform_sky(method, 180.0, 48));
        let r = render_with(&s, 2);
        let omega = s.camera.all_sky_pixel_sr().expect("all-sky");
        let (n, rr) = (48usize, 24.0f64);
        let mut total = 0.0;
        for y in 0..n {
            for x in 0..n {
                let v = r.image.data[y * n + x] as f64;
                total += v * omega;
                let (dx, dy) = ((x as f64 + 0.5 - rr).abs() + 0.5, (y as f64 + 0.5 - rr).abs() + 0.5);
                if (dx * dx + dy * dy).sqrt() < rr - 1.0 {
                    assert!((v / 3.0 - 1.0).abs() < 1e-6, "{method}: pixel ({x}, {y}) = {v}, expected 3");
                }
            }
        }
        // Rim pixels: ~190 of them, each covered to a fraction estimated from 64 samples
        // (σ ≈ 0.06 each): the sum's noise is ≈ 0.1% of the total.
        assert!((total / (2.0 * PI * 3.0) - 1.0).abs() < 0.005, "{method}: Σ L Ω = {total}, 2π L = {}", 6.0 * PI);
    }
}

#[test]
fn a_whole_sphere_image_sees_the_ground_below_the_horizon() {
    // fov 360°: the outer ring of the circle (θ > 90°, ρ > sin 45°/sin 90° = 0.707 of its
    // radius) looks below the horizon: the black plate or (past its edge) nothing — zero.
    let s = scene(&uniform_sky("path", 360.0, 40));
    let r = render_with(&s, 2);
    for (x, y, want) in [(20usize, 20usize, 3.0), (20, 12, 3.0), (20, 1, 0.0), (38, 20, 0.0)] {
        let v = r.image.data[y * 40 + x] as f64;
        assert!((v - want).abs() < 1e-6, "pixel ({x}, {y}) = {v}, expected {want}");
    }
}

#[test]
fn all_sky_cameras_report_bad_input() {
    let e = scene_error(&uniform_sky("path", 180.0, 8).replace("\"equal_area\"", "\"fisheye\""));
    assert!(e.contains("projection \"fisheye\" is not known; allowed: pinhole, equal_area"), "{e}");
    let e = scene_error(&uniform_sky("path", 400.0, 8));
    assert!(e.contains("fov_deg = 400 is out of range"), "{e}");
    let e = scene_error(&uniform_sky("path", 180.0, 8).replace("up = [0.0, 0.0, -1.0]\n", ""));
    assert!(e.contains("up = [0, 0, -1] puts azimuth 0°"), "{e}");
}

/// View zenith and azimuth (degrees, the `sky_radiance` convention: azimuth 0° toward −z, 90°
/// toward +x) of direction `d`.
fn zenith_azimuth(d: glam::DVec3) -> [f64; 2] {
    [d.y.clamp(-1.0, 1.0).acos().to_degrees(), d.x.atan2(-d.z).to_degrees().rem_euclid(360.0)]
}

#[test]
#[ignore = "slow: minutes on 2 cores; cargo test --release --test all_sky -- --ignored"]
fn all_sky_pixels_agree_with_the_sky_radiance_sensor_on_a_rayleigh_sky() {
    // A USA76 Rayleigh sky (single scattering: photons = 0) over black ground, sun at zenith
    // 60° (azimuth 90°, a point so no pixel sees its disc), 550 nm band. For four pixels of a
    // 12 × 12 hemisphere image (each 0.087 sr), a sky_radiance sensor at the camera looks along
    // 6 × 6 directions at the centres of equal-area sub-squares of the pixel; their mean is the
    // pixel's mean radiance up to the midpoint rule on a smooth sky (< 0.2 %). Six seeds: the
    // mean difference pixel − sensor within 4 standard errors plus 0.2 % of the pixel.
    // Slow (minutes on 2 cores): `cargo test --release --test all_sky -- --ignored`.
    let n = 12usize;
    let pixels = [(6usize, 6usize), (2, 5), (8, 3), (5, 10)];
    let base = scene(&rayleigh_all_sky(n, ""));
    let mut dirs = Vec::new();
    for &(px, py) in &pixels {
        for j in 0..6 {
            for i in 0..6 {
                let (x, y) = (px as f64 + (i as f64 + 0.5) / 6.0, py as f64 + (j as f64 + 0.5) / 6.0);
                dirs.push(zenith_azimuth(base.camera.ray(x, y).expect("inside the circle").dir));
            }
        }
    }
    let list = dirs.iter().map(|[z, a]| format!("[{z:?}, {a:?}]")).collect::<Vec<_>>().join(", ");
    let sensor = format!(
        "[[sensor]]\nname = \"sky\"\ntype = \"sky_radiance\"\norigin = [0.0, 1.0, 0.0]\ndirections_deg = [{list}]\nsamples = 16\n"
    );
    let mut s = scene(&rayleigh_all_sky(n, &sensor));
    let mut diffs = vec![Vec::new(); pixels.len()];
    let mut level = vec![0.0; pixels.len()];
    for seed in 1..=6 {
        s.apply_overrides(None, Some(seed));
        let r = render_with(&s, 2);
        let reading = &r.sensors[0].columns[3].1;
        for (k, &(px, py)) in pixels.iter().enumerate() {
            let pixel = r.image.data[py * n + px] as f64;
            let sensor: f64 = reading[36 * k..36 * (k + 1)].iter().sum::<f64>() / 36.0;
            diffs[k].push(pixel - sensor);
            level[k] += pixel / 6.0;
        }
    }
    for (k, d) in diffs.iter().enumerate() {
        let (mean, se) = mean_and_sem(d);
        println!("pixel {:?}: L = {:.5e}, pixel − sensor = {mean:.2e} ± {se:.1e}", pixels[k], level[k]);
        assert!(mean.abs() < 4.0 * se + 2e-3 * level[k], "pixel {:?}: {mean} ± {se} (L {})", pixels[k], level[k]);
        assert!(se < 0.01 * level[k], "pixel {:?}: standard error {se} too large to test", pixels[k]);
    }
}

/// The all-sky camera 1 m above flat black ground under a USA76 Rayleigh sky, sun at zenith 60°,
/// with `extra` (TOML) appended.
fn rayleigh_all_sky(n: usize, extra: &str) -> String {
    format!(
        r#"
[camera]
position = [0.0, 1.0, 0.0]
look_at = [0.0, 2.0, 0.0]
up = [0.0, 0.0, -1.0]
projection = "equal_area"
fov_deg = 180.0
width = {n}
height = {n}

[output]
bands = 1
min_nm = 545.0
max_nm = 555.0

[integrator]
photons = 0
march_step = 200.0
spp = 64

{ground}
{sun}
{extra}
"#,
        ground = common::sky::flat_air_over_black_ground(),
        sun = common::sky::point_sun(30.0),
    )
}
