//! The sun: a directional light of finite angular size, seen directly and lighting a plane.

mod common;

use common::{render_with, scene};
use glam::DVec3;
use morgana::photon::PassSettings;
use morgana::photon::{MapKind, shoot};

/// A camera looking straight at a sun 30° up, with a field of view of 1.2° (the disc is 0.53°
/// across), over a black floor far below.
fn sun_in_view(method: &str) -> String {
    format!(
        r#"
[camera]
position = [0.0, 0.0, 0.0]
look_at = [0.0, 0.5, -0.8660254037844386]
fov_deg = 1.2
width = 48
height = 48

[output]
bands = 1
min_nm = 540.0
max_nm = 560.0

[integrator]
method = "{method}"
photons = 1000
spp = 16

[[material]]
name = "black"
type = "lambertian"
reflectance = 0.0

[[shape]]
type = "quad"
origin = [-1.0, -10.0, -1.0]
u = [0.0, 0.0, 2.0]
v = [2.0, 0.0, 0.0]
material = "black"

[[light]]
type = "sun"
elevation_deg = 30.0
azimuth_deg = 0.0
spectrum = 1.0
scale = 2.0
"#
    )
}

/// Σ L·Ω over the pixels: the irradiance normal to the view axis that the image collects.
fn collected_irradiance(toml: &str) -> f64 {
    let s = scene(toml);
    let r = render_with(&s, 2);
    let c = &s.camera;
    let tan_half = (0.5 * c.fov_deg.to_radians()).tan();
    let pixel = 2.0 * tan_half / c.height as f64;
    let mut e = 0.0;
    for y in 0..c.height {
        for x in 0..c.width {
            let sx = (x as f64 + 0.5 - 0.5 * c.width as f64) * pixel;
            let sy = (y as f64 + 0.5 - 0.5 * c.height as f64) * pixel;
            // Solid angle of a pixel of side `pixel` on the image plane at distance 1, times the
            // cosine to the axis: Ω cos θ = pixel² cos⁴θ.
            let cos = 1.0 / (1.0 + sx * sx + sy * sy).sqrt();
            e += r.image.data[y * c.width + x] as f64 * pixel * pixel * cos.powi(4);
        }
    }
    e
}

#[test]
fn the_camera_sees_a_disc_whose_radiance_integrates_to_the_suns_irradiance() {
    // E = ∫_disc L cos θ dω with L = E/(π sin²θ_m): summing the image gives E = 2 W m⁻² nm⁻¹
    // back, up to the disc's edge pixels (16 jittered samples each: ≈ 0.1% over the ~100 edge
    // pixels of a disc covering ~600).
    for method in ["photon_map", "path"] {
        let e = collected_irradiance(&sun_in_view(method));
        assert!((e / 2.0 - 1.0).abs() < 0.01, "{method}: collected {e}, expected 2");
    }
}

#[test]
fn the_disc_is_as_wide_as_the_suns_angular_diameter() {
    // The middle row crosses the disc's diameter: 0.533° of the 1.2° field, so 21.3 of 48 pixels.
    let s = scene(&sun_in_view("path"));
    let r = render_with(&s, 2);
    let row = s.camera.height / 2;
    let lit = (0..s.camera.width).filter(|x| r.image.data[row * s.camera.width + x] > 0.0).count() as f64;
    let expected = morgana::spectrum::solar::ANGULAR_DIAMETER_DEG / 1.2 * s.camera.width as f64;
    assert!((lit - expected).abs() <= 1.5, "{lit} pixels lit, expected {expected:.1}");
}

#[test]
fn sun_photons_carry_its_irradiance_within_its_disc() {
    // A black 2 m plate under a sun at the zenith: 4 m² × E = 8 W arrive, and every photon's
    // direction lies within the disc's 0.2665° radius of straight down.
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
type = "sun"
direction = [0.0, -1.0, 0.0]
spectrum = "D65"
irradiance_w_m2 = 2.0
target_min = [-1.0, -0.01, -1.0]
target_max = [1.0, 0.01, 1.0]
"#;
    let s = scene(toml);
    let (sink, _) = shoot(&s.world, &PassSettings::of(&s), MapKind::Global, 20_000, 8, &|_| {});
    let stored: f64 = sink.surface.iter().map(|p| p.power_w).sum();
    // Photons tilted off the axis can miss the plate's edge: the share is ~ the edge strip of
    // width h·tan θ over the plate (h ≈ 2.5 m upstream: under 1%).
    assert!((stored / 8.0 - 1.0).abs() < 0.01, "stored {stored} W, expected 8 W");
    let cos_max = (0.5 * morgana::spectrum::solar::ANGULAR_DIAMETER_DEG).to_radians().cos();
    assert!(sink.surface.iter().all(|p| -p.dir.y >= cos_max - 1e-12));
    let tilted = sink.surface.iter().filter(|p| -p.dir.y < 1.0 - 1e-9).count();
    assert!(tilted > sink.surface.len() / 2, "directions should spread over the disc");
    assert!(s.world.lights[0].incident(DVec3::new(0.5, 0.0, 0.2), [0.3, 0.7]).is_some_and(|i| i.wi.y >= cos_max));
}

#[test]
fn a_sun_needs_a_direction_or_both_angles() {
    let bad = sun_in_view("path").replace("azimuth_deg = 0.0\n", "");
    let e = common::scene_error(&bad);
    assert!(e.contains("elevation_deg and azimuth_deg"), "{e}");
}

#[test]
fn a_sun_without_a_spectrum_shines_with_the_extraterrestrial_solar_irradiance() {
    // Over 380–780 nm (the default output range) ASTM G173-03's extraterrestrial column carries
    // 655.9 W m⁻² (the integral its generator recorded).
    let toml = sun_in_view("path")
        .replace("spectrum = 1.0\nscale = 2.0\n", "")
        .replace("[output]\nbands = 1\nmin_nm = 540.0\nmax_nm = 560.0\n", "");
    let s = scene(&toml);
    let e = s.world.lights[0].spectrum().integral();
    let want = morgana::spectrum::solar::ETR_INTEGRAL_380_780_W_M2;
    assert!((e / want - 1.0).abs() < 1e-6, "∫E dλ = {e} W/m², table {want}");
}
