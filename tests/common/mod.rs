//! Helpers shared by the integration tests.
#![allow(dead_code)]

pub mod shared;
pub mod sky;

use morgana::render::{RenderOptions, Rendered, render};
use morgana::scene::{Scene, load_scene_str};
use std::path::Path;

/// A scene from TOML text (errors name "test.toml").
pub fn scene(toml: &str) -> Scene {
    match load_scene_str(toml, Path::new("test.toml"), Path::new("."), "test") {
        Ok(s) => s,
        Err(e) => panic!("test scene does not load: {e}"),
    }
}

/// The error message a scene produces.
pub fn scene_error(toml: &str) -> String {
    match load_scene_str(toml, Path::new("test.toml"), Path::new("."), "test") {
        Ok(_) => panic!("scene was accepted but should have been rejected:\n{toml}"),
        Err(e) => e.to_string(),
    }
}

/// Renders on a pool of `threads` threads without progress bars.
pub fn render_with(scene: &Scene, threads: usize) -> Rendered {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("thread pool");
    pool.install(|| render(scene, &RenderOptions { quiet: true, ..RenderOptions::default() }))
}

/// The `[camera]` and `[output]` tables of a pinhole at the origin looking down −z with a 90°
/// field of view over `side` × `side` pixels, one band (500–600 nm). With tan 45° = 1 the ray
/// through pixel coordinates (px, py) meets the plane z = −1 at X = 2 px/side − 1,
/// Y = 1 − 2 py/side: a shape in that plane maps to pixels linearly.
pub fn pinhole_90(side: usize) -> String {
    format!(
        r#"
[camera]
position = [0.0, 0.0, 0.0]
look_at = [0.0, 0.0, -1.0]
up = [0.0, 1.0, 0.0]
fov_deg = 90.0
width = {side}
height = {side}

[output]
bands = 1
min_nm = 500.0
max_nm = 600.0
"#
    )
}

/// Mean and standard error of the mean of `xs`.
pub fn mean_and_sem(xs: &[f64]) -> (f64, f64) {
    let n = xs.len() as f64;
    let mean = xs.iter().sum::<f64>() / n;
    let var = xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, (var / n).sqrt())
}

/// The small scene of the input tests: a 2 m × 2 m plate of reflectance 0.7 under a 10 W,
/// 4000 K point light 2 m above it, seen by a `width` × `height` camera, with `extra` (TOML
/// sections) between the camera and the integrator. Tests edit its text to make bad input.
pub fn lit_plate(width: u32, height: u32, extra: &str) -> String {
    format!(
        r#"[camera]
position = [0.0, 1.0, 3.0]
look_at = [0.0, 0.5, 0.0]
fov_deg = 40.0
width = {width}
height = {height}
{extra}
[integrator]
photons = 2000
caustic_photons = 2000
spp = 1
gather_rays = 2

[[material]]
name = "white"
type = "lambertian"
reflectance = 0.7

[[shape]]
type = "quad"
origin = [-1.0, 0.0, -1.0]
u = [0.0, 0.0, 2.0]
v = [2.0, 0.0, 0.0]
material = "white"

[[light]]
type = "point"
position = [0.0, 2.0, 0.0]
spectrum = {{ blackbody_k = 4000 }}
power_w = 10.0
"#
    )
}

/// A black Lambertian sphere of `radius_m` at the origin: the enclosure of the tests that count
/// what a source inside it delivers.
pub fn black_sphere(radius_m: f64) -> String {
    black_sphere_at([0.0, 0.0, 0.0], radius_m)
}

/// The material "black": Lambertian of reflectance 0.
const BLACK: &str = "\n[[material]]\nname = \"black\"\ntype = \"lambertian\"\nreflectance = 0.0\n";

/// A black Lambertian sphere of `radius_m` about `centre` (e.g. a black Earth under the air).
pub fn black_sphere_at(centre: [f64; 3], radius_m: f64) -> String {
    format!(
        "{BLACK}\n[[shape]]\ntype = \"sphere\"\ncenter = {}\nradius = {radius_m:?}\nmaterial = \"black\"\n",
        toml_vec(centre)
    )
}

/// A black Lambertian quad at `origin` spanned by `u` and `v` (m): a ground or a wall that
/// absorbs all it receives.
pub fn black_quad(origin: [f64; 3], u: [f64; 3], v: [f64; 3]) -> String {
    let [o, u, v] = [origin, u, v].map(toml_vec);
    format!("{BLACK}\n[[shape]]\ntype = \"quad\"\norigin = {o}\nu = {u}\nv = {v}\nmaterial = \"black\"\n")
}

/// A 3-vector as a TOML array of floats.
fn toml_vec([x, y, z]: [f64; 3]) -> String {
    format!("[{x:?}, {y:?}, {z:?}]")
}

/// The six walls of the box [−1, 1]³ as area lights of radiance `le` on both sides, each with
/// the material named "wall" (which the scene defines).
pub fn emitting_box_walls(le: f64) -> String {
    let faces = [
        ([-1, -1, -1], [2, 0, 0], [0, 2, 0]),
        ([-1, -1, 1], [2, 0, 0], [0, 2, 0]),
        ([-1, -1, -1], [0, 2, 0], [0, 0, 2]),
        ([1, -1, -1], [0, 2, 0], [0, 0, 2]),
        ([-1, -1, -1], [2, 0, 0], [0, 0, 2]),
        ([-1, 1, -1], [2, 0, 0], [0, 0, 2]),
    ];
    let v = |a: [i32; 3]| toml_vec(a.map(f64::from));
    faces
        .iter()
        .map(|(o, u, w)| {
            format!(
                "\n[[light]]\ntype = \"area\"\nshape = \"quad\"\norigin = {}\nu = {}\nv = {}\nside = \"both\"\n\
                 material = \"wall\"\nspectrum = 1.0\nscale = {le:?}\n",
                v(*o),
                v(*u),
                v(*w)
            )
        })
        .collect()
}
