//! The sky: uniform radiance from the upper hemisphere, against closed forms.

mod common;

use common::{render_with, scene};

const L_SKY: f64 = 3.0;
const RHO: f64 = 0.5;

/// A camera 1 m above a 4 m × 4 m Lambertian plate of reflectance ρ under a uniform sky of
/// radiance L: the plate receives E = πL and reflects ρE/π = ρL toward the camera.
fn plate_under_sky(integrator: &str, look_up: bool) -> String {
    let look_at = if look_up { "[0.0, 2.0, 0.001]" } else { "[0.0, 0.0, 0.001]" };
    format!(
        r#"
[camera]
position = [0.0, 1.0, 0.0]
look_at = {look_at}
fov_deg = 40.0
width = 16
height = 16

[output]
bands = 2
min_nm = 450.0
max_nm = 650.0

[integrator]
{integrator}

[[material]]
name = "grey"
type = "lambertian"
reflectance = {RHO}

[[shape]]
type = "quad"
origin = [-2.0, 0.0, -2.0]
u = [0.0, 0.0, 4.0]
v = [4.0, 0.0, 0.0]
material = "grey"

[[light]]
type = "sky"
spectrum = 1.0
scale = {L_SKY}
target_min = [-2.0, -0.01, -2.0]
target_max = [2.0, 0.01, 2.0]
"#
    )
}

fn image_mean(values: &[f32]) -> f64 {
    values.iter().map(|v| *v as f64).sum::<f64>() / values.len() as f64
}

#[test]
fn a_plate_under_the_sky_reflects_rho_times_its_radiance() {
    let cases = [
        ("path", "method = \"path\"\nspp = 64\nseed = 1", 0.02),
        ("shadow rays", "photons = 0\nspp = 64\nfinal_gather = false\nseed = 2", 0.02),
        // The photon map's own noise: k = 400 photons per estimate, correlated over the view.
        ("photon map", "photons = 400000\nk = 400\nmax_radius = 0.5\ndirect = \"photon_map\"\nspp = 1\nseed = 3", 0.03),
    ];
    for (name, integrator, tol) in cases {
        let s = scene(&plate_under_sky(integrator, false));
        let mean = image_mean(&render_with(&s, 2).image.data);
        let expected = RHO * L_SKY;
        assert!((mean / expected - 1.0).abs() < tol, "{name}: mean {mean}, expected {expected}");
    }
}

#[test]
fn a_camera_looking_up_sees_the_skys_radiance() {
    let s = scene(&plate_under_sky("photons = 0\nspp = 1", true));
    let r = render_with(&s, 2);
    assert!(r.image.data.iter().all(|v| (*v as f64 - L_SKY).abs() < 1e-9 * L_SKY), "every pixel sees L");
}

#[test]
fn the_sky_accepts_only_a_scale() {
    let bad = plate_under_sky("", false).replace("scale = 3", "power_w = 3");
    let e = common::scene_error(&bad);
    assert!(e.contains("power_w"), "{e}");
}
