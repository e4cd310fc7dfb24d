//! The n² law of radiance: a camera under a flat water surface looking straight up sees the sky
//! n² times brighter, less the Fresnel loss (Mobley 1994, *Light and Water*, §4.3; Veach 1997,
//! §5.2: L/n² is what a refracting boundary conserves).
//!
//! The camera sits inside a water box (n = 1.34, clear) under a uniform sky of radiance L. At
//! normal incidence the top face transmits T = 1 − F with F = ((n − 1)/(n + 1))²; the part it
//! reflects goes down, leaves through the bottom (the sky is dark below) or is reflected up again
//! by F, so the camera sees
//!   L_cam = n² T L (1 + F² + F⁴ + …) = n² T L / (1 − F²).
//! Checked for the water surface as a dielectric material and as a boundary between media of
//! different n, with the photon-map integrator's eye pass and with the path tracer.

mod common;

use common::{render_with, scene};

const N: f64 = 1.34;
const L_SKY: f64 = 2.0;

/// The water body: a dielectric box, or a box whose interior medium has index n.
#[derive(Clone, Copy, Debug)]
enum Water {
    Material,
    Medium,
}

fn under_water(water: Water, integrator: &str) -> String {
    let body = match water {
        Water::Material => "material = \"water\"",
        Water::Medium => "interior = \"water\"",
    };
    format!(
        r#"
[camera]
position = [0.0, -1.0, 0.0]
look_at = [0.0, 0.0, 0.001]
fov_deg = 2.0
width = 4
height = 4

[output]
bands = 2
min_nm = 450.0
max_nm = 650.0

[integrator]
{integrator}

[[medium]]
name = "water"
sigma_a = 0.0
sigma_s = 0.0
index = {N}

[[material]]
name = "water"
type = "dielectric"
ior = {N}

[[shape]]
type = "box"
min = [-50.0, -10.0, -50.0]
max = [50.0, 0.0, 50.0]
{body}

[[light]]
type = "sky"
spectrum = 1.0
scale = {L_SKY}
target_min = [-50.0, -0.01, -50.0]
target_max = [50.0, 0.01, 50.0]
"#
    )
}

fn expected() -> f64 {
    let f = ((N - 1.0) / (N + 1.0)).powi(2);
    N * N * (1.0 - f) * L_SKY / (1.0 - f * f)
}

fn image_mean(values: &[f32]) -> f64 {
    values.iter().map(|v| *v as f64).sum::<f64>() / values.len() as f64
}

#[test]
fn a_camera_under_water_sees_the_sky_n_squared_times_brighter() {
    // The photon-map eye pass splits at a dielectric material deterministically (Fresnel split):
    // exact up to the degree of the view (F changes by < 1e-5 within 1° of normal incidence).
    // Elsewhere reflection or refraction is chosen by F: binomial noise, σ/mean ≈
    // sqrt(F/(spp·pixels)) ≈ 0.2 % here.
    let cases =
        [("photon map", "photons = 0\nspp = 256\nseed = 1"), ("path", "method = \"path\"\nspp = 256\nseed = 2")];
    for water in [Water::Material, Water::Medium] {
        for (name, integrator) in cases {
            let tol = if matches!(water, Water::Material) && name == "photon map" { 1e-3 } else { 0.015 };
            let s = scene(&under_water(water, integrator));
            let mean = image_mean(&render_with(&s, 2).image.data);
            let want = expected();
            assert!((mean / want - 1.0).abs() < tol, "{water:?}, {name}: mean {mean}, expected n²TL/(1−F²) = {want}");
        }
    }
}
