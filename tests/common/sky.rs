//! Scene blocks shared by the sky tests: a USA76 Rayleigh atmosphere over black ground, flat or
//! round, and a point sun.
#![allow(dead_code)]

/// The Earth's radius of the round-Earth scenes, m.
pub const R_EARTH_M: f64 = 6_371_000.0;

/// `[world]` in the medium "air" on a flat Earth, the USA76 Rayleigh `[[medium]]` "air", and a
/// black quad 4000 km across at y = 0: the ground of the plane-parallel sky tests.
pub fn flat_air_over_black_ground() -> String {
    let ground = super::black_quad([-2.0e6, 0.0, -2.0e6], [0.0, 0.0, 4.0e6], [4.0e6, 0.0, 0.0]);
    format!(
        "\n[world]\nmedium = \"air\"\nearth = \"flat\"\n\n[[medium]]\nname = \"air\"\ntype = \"atmosphere\"\n{ground}"
    )
}

/// A point sun (`angular_diameter_deg = 0`) at `elevation_deg`, azimuth 90° (toward +x), of
/// flat spectrum 1 W m⁻² nm⁻¹.
pub fn point_sun(elevation_deg: f64) -> String {
    format!(
        r#"
[[light]]
type = "sun"
elevation_deg = {elevation_deg:?}
azimuth_deg = 90.0
angular_diameter_deg = 0.0
spectrum = 1.0
scale = 1.0
"#
    )
}

/// A black Earth of radius 6371 km centred at (0, −R, 0) in a USA76 atmosphere whose
/// `[[medium]]` gets the lines `medium_lines`, simulated over `min_nm`–`max_nm` in 4 bands,
/// lit by `light` (TOML), seen by a 4 × 4 camera 1 m up looking at the zenith.
pub fn black_earth(min_nm: f64, max_nm: f64, medium_lines: &str, light: &str) -> String {
    format!(
        r#"
[camera]
position = [0.0, 1.0, 0.0]
look_at = [0.0, 2.0, 0.001]
fov_deg = 40.0
width = 4
height = 4

[output]
bands = 4
min_nm = {min_nm:?}
max_nm = {max_nm:?}

{air}{earth}
{light}
"#,
        air = round_air(medium_lines),
        earth = super::black_sphere_at([0.0, -R_EARTH_M, 0.0], R_EARTH_M),
    )
}

/// A collimated beam of 1 W m⁻² nm⁻¹ travelling along `direction`, aimed at a 2 km square
/// about the origin (the photon tests' light).
pub fn directional_beam(direction: [f64; 3]) -> String {
    let [x, y, z] = direction;
    format!(
        r#"
[[light]]
type = "directional"
direction = [{x:?}, {y:?}, {z:?}]
spectrum = 1.0
irradiance_w_m2 = 1.0
target_min = [-1000.0, 0.0, -1000.0]
target_max = [1000.0, 1.0, 1000.0]
"#
    )
}

/// Two `sky_radiance` sensors of `samples` estimates per direction: "ground", 1 m up, at the
/// [view zenith, azimuth] pairs `up`, and "space", at 100 km (above the 86 km top of USA76), at
/// the pairs `down`.
pub fn ground_and_space_sensors(up: &[[f64; 2]], down: &[[f64; 2]], samples: usize) -> String {
    let sensor = |name: &str, height_m: f64, directions: &[[f64; 2]]| {
        let list = directions.iter().map(|[z, a]| format!("[{z:?}, {a:?}]")).collect::<Vec<_>>().join(", ");
        format!(
            "\n[[sensor]]\nname = \"{name}\"\ntype = \"sky_radiance\"\norigin = [0.0, {height_m:?}, 0.0]\ndirections_deg = [{list}]\nsamples = {samples}\n"
        )
    };
    sensor("ground", 1.0, up) + &sensor("space", 100_000.0, down)
}

/// The sensor readings of `s` rendered on 2 threads with each seed 1 ..= `seeds`: independent
/// estimates whose spread gives the standard error of their mean.
pub fn readings_over_seeds(s: &mut morgana::scene::Scene, seeds: u64) -> Vec<Vec<morgana::sensor::Reading>> {
    (1..=seeds)
        .map(|seed| {
            s.apply_overrides(None, Some(seed));
            super::render_with(s, 2).sensors
        })
        .collect()
}

/// A collimated beam from the zenith (scenes need a light to load).
pub const ZENITH_BEAM: &str =
    "[[light]]\ntype = \"directional\"\ndirection = [0.0, -1.0, 0.0]\nspectrum = 1.0\nscale = 1.0\n";

/// USA76 number density N = P N_A/(R* T) at geometric height `h` (the standard's constants,
/// Table 2: N_A = 6.022169e23 mol⁻¹, R* = 8.31432 J mol⁻¹ K⁻¹), m⁻³.
pub fn usa76_n(h: f64) -> f64 {
    let s = morgana::atmosphere::usa76::at_geometric(h);
    s.pressure_pa * 6.022_169e23 / (8.314_32 * s.temperature_k)
}

/// A 1 × 1 camera 1 m up looking at the zenith (a scene needs one; its sensors measure) and an
/// `[output]` of `bands` bands over `min_nm`–`max_nm`.
pub fn zenith_pixel(bands: usize, min_nm: f64, max_nm: f64) -> String {
    format!(
        "\n[camera]\nposition = [0.0, 1.0, 0.0]\nlook_at = [0.0, 2.0, 0.001]\nfov_deg = 1.0\nwidth = 1\nheight = 1\n\n[output]\nbands = {bands}\nmin_nm = {min_nm:?}\nmax_nm = {max_nm:?}\n"
    )
}

/// `[world]` in the medium "air" on a round Earth, and the USA76 `[[medium]]` "air" with the
/// lines `medium_lines`.
pub fn round_air(medium_lines: &str) -> String {
    format!(
        "\n[world]\nmedium = \"air\"\nearth = \"spherical\"\n\n[[medium]]\nname = \"air\"\ntype = \"atmosphere\"\natmosphere = \"usa76\"\n{medium_lines}\n"
    )
}

/// `morgana render SCENE --out OUT --seed SEED --threads 2 --quiet --sun-zenith-deg ZENITHS`.
pub fn sweep_args(
    scene: std::path::PathBuf,
    out: std::path::PathBuf,
    seed: u64,
    zeniths: Vec<f64>,
) -> morgana::cli::render::RenderArgs {
    morgana::cli::render::RenderArgs {
        scene: Some(scene),
        out: Some(out),
        photons: None,
        seed: Some(seed),
        threads: Some(2),
        quiet: true,
        max_map_memory: None,
        max_memory: None,
        max_seconds: None,
        schedule: morgana::distributed::Schedule::Dynamic,
        sun_zenith_deg: zeniths,
        stop: Default::default(),
    }
}
