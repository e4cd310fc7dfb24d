//! `morgana render --sun-zenith-deg`: one run per solar zenith angle, gathered in one CSV.

mod common;

use morgana::cli::render::{RenderArgs, run};
use std::path::PathBuf;

/// A flat USA76 Rayleigh sky over black ground (single scattering), a one-pixel camera and a
/// sky_radiance sensor at the zenith and the horizon, with the sun at `elevation`.
fn scene_text(elevation_deg: f64) -> String {
    format!(
        r#"
{pixel}
[integrator]
photons = 0
march_step = 2000.0
spp = 1

{ground}
{sun}
[[sensor]]
name = "sky"
type = "sky_radiance"
origin = [0.0, 1.0, 0.0]
directions_deg = [[0.0, 0.0], [90.0, 90.0]]
samples = 4
"#,
        pixel = common::sky::zenith_pixel(2, 450.0, 650.0),
        ground = common::sky::flat_air_over_black_ground(),
        sun = common::sky::point_sun(elevation_deg),
    )
}

fn args(scene: PathBuf, out: PathBuf, zeniths: Vec<f64>) -> RenderArgs {
    common::sky::sweep_args(scene, out, 3, zeniths)
}

#[test]
fn a_sweep_gathers_what_separate_runs_at_each_angle_read() {
    // The sweep at solar zeniths 30° and 75° must hold, row for row, the sky sensor's readings of
    // two ordinary renders of the scene with elevation 60° and 15° (same seed: deterministic).
    let dir = std::env::temp_dir().join(format!("morgana_sweep_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    let sweep_scene = dir.join("sweep.toml");
    std::fs::write(&sweep_scene, scene_text(10.0)).expect("scene");
    run(&args(sweep_scene, dir.join("out"), vec![30.0, 75.0])).expect("sweep");
    let csv = std::fs::read_to_string(dir.join("out/sweep_sun_sweep.csv")).expect("the sweep's CSV");
    let lines: Vec<&str> = csv.lines().collect();
    assert!(
        lines[0].starts_with("sun_zenith_deg,sensor,view_zenith_deg,view_azimuth_deg,L_mean,L_450_550nm"),
        "{}",
        lines[0]
    );
    assert_eq!(lines.len(), 5, "{csv}");
    for (k, (zenith, elevation)) in [(30.0, 60.0), (75.0, 15.0)].into_iter().enumerate() {
        let mut s = common::scene(&scene_text(elevation));
        s.apply_overrides(None, Some(3));
        let r = common::render_with(&s, 2);
        let reading = &r.sensors[0];
        for d in 0..2 {
            let row: Vec<&str> = lines[1 + 2 * k + d].split(',').collect();
            assert_eq!(row[0].parse::<f64>().expect("zenith"), zenith);
            assert_eq!(row[1], "sky");
            for (col, (name, values)) in [(4, &reading.columns[0]), (5, &reading.columns[3]), (6, &reading.columns[4])]
            {
                let got: f64 = row[col].parse().expect("a number");
                assert_eq!(got, values[d], "zenith {zenith}, direction {d}, {name}");
            }
        }
    }
    assert!(
        dir.join("out/sun_zenith_30").is_dir() && dir.join("out/sun_zenith_75").is_dir(),
        "each angle's own outputs"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_sweep_needs_one_sun_placed_by_elevation() {
    let dir = std::env::temp_dir().join(format!("morgana_sweep_bad_{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let by_direction =
        scene_text(10.0).replace("elevation_deg = 10.0\nazimuth_deg = 90.0", "direction = [0.0, -1.0, 0.0]");
    std::fs::write(dir.join("d.toml"), by_direction).expect("scene");
    let e = run(&args(dir.join("d.toml"), dir.join("out"), vec![30.0])).expect_err("refused").to_string();
    assert!(e.contains("place the sun by elevation_deg and azimuth_deg") && e.contains("d.toml:"), "{e}");
    let no_sun = scene_text(10.0).replace("type = \"sun\"", "type = \"directional\"").replace(
        "elevation_deg = 10.0\nazimuth_deg = 90.0\nangular_diameter_deg = 0.0\n",
        "direction = [0.0, -1.0, 0.0]\n",
    );
    std::fs::write(dir.join("n.toml"), no_sun).expect("scene");
    let e = run(&args(dir.join("n.toml"), dir.join("out"), vec![30.0])).expect_err("refused").to_string();
    assert!(e.contains("has 0 [[light]] of type \"sun\""), "{e}");
    std::fs::write(dir.join("z.toml"), scene_text(10.0)).expect("scene");
    let e = run(&args(dir.join("z.toml"), dir.join("out"), vec![30.0, 200.0])).expect_err("refused").to_string();
    assert!(e.contains("--sun-zenith-deg 200"), "{e}");
    assert!(!dir.join("out/sun_zenith_30").exists(), "nothing rendered before the bad angle was found");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_sweep_without_a_sky_sensor_writes_each_angles_image_and_no_csv() {
    // A sequence of images (e.g. a setting sun) needs no sensor: each angle's image is the
    // result, the one an ordinary render of the scene with the sun at that angle writes.
    let dir = std::env::temp_dir().join(format!("morgana_sweep_frames_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    let text = scene_text(10.0).replace("[output]\n", "[output]\ncsv = true\n");
    let frames = &text[..text.find("[[sensor]]").expect("the sensor")];
    assert!(frames.contains("csv = true"), "{frames}");
    std::fs::write(dir.join("frames.toml"), frames).expect("scene");
    std::fs::write(dir.join("one.toml"), frames.replace("elevation_deg = 10.0", "elevation_deg = 15.0"))
        .expect("scene");
    let said = run(&args(dir.join("frames.toml"), dir.join("out"), vec![30.0, 75.0])).expect("sweep");
    assert!(!said.contains("sun_sweep.csv") && !dir.join("out/frames_sun_sweep.csv").exists(), "{said}");
    run(&args(dir.join("one.toml"), dir.join("one"), vec![])).expect("an ordinary render");
    let csv = |p: &str| std::fs::read_to_string(dir.join(p)).expect(p);
    assert_eq!(csv("out/sun_zenith_75/frames.csv"), csv("one/one.csv"), "the 75° frame is the render at elevation 15°");
    assert!(dir.join("out/sun_zenith_30/frames.csv").exists(), "the 30° frame");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A round USA76 Rayleigh atmosphere over a black Earth, single scattering, seen edge-on by a
/// `limb` sensor at tangent heights 10 and 30 km, with the sun at `elevation_deg`.
fn limb_scene_text(elevation_deg: f64) -> String {
    format!(
        "{pixel}\n[integrator]\nphotons = 0\nmarch_step = 2000.0\nspp = 1\n{air}{earth}{sun}\n[[sensor]]\nname = \"limb\"\ntype = \"limb\"\ntangent_heights_m = [10000.0, 30000.0]\nazimuth_deg = 90.0\nsamples = 2\n",
        pixel = common::sky::zenith_pixel(2, 450.0, 650.0),
        air = common::sky::round_air(""),
        earth = common::black_sphere_at([0.0, -common::sky::R_EARTH_M, 0.0], common::sky::R_EARTH_M),
        sun = common::sky::point_sun(elevation_deg),
    )
}

#[test]
fn a_sweep_of_a_limb_lists_its_tangent_heights() {
    let dir = std::env::temp_dir().join(format!("morgana_limb_sweep_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    let scene = dir.join("limb.toml");
    std::fs::write(&scene, limb_scene_text(10.0)).expect("scene");
    run(&args(scene, dir.join("out"), vec![60.0])).expect("sweep");
    let csv = std::fs::read_to_string(dir.join("out/limb_sun_sweep.csv")).expect("the sweep's CSV");
    let lines: Vec<&str> = csv.lines().collect();
    assert!(
        lines[0]
            .starts_with("sun_zenith_deg,sensor,view_zenith_deg,view_azimuth_deg,tangent_height_m,L_mean,L_450_550nm"),
        "{}",
        lines[0]
    );
    let mut s = common::scene(&limb_scene_text(30.0));
    s.apply_overrides(None, Some(3));
    let reading = &common::render_with(&s, 2).sensors[0];
    for (k, height) in [10000.0, 30000.0].into_iter().enumerate() {
        let row: Vec<f64> = lines[1 + k].split(',').filter_map(|x| x.parse().ok()).collect();
        // sun_zenith, view zenith, view azimuth, tangent height, L_mean, the bands.
        assert_eq!(row[..4], [60.0, 90.0, 90.0, height], "{}", lines[1 + k]);
        assert_eq!(row[4], reading.columns[0].1[k], "L_mean as an ordinary render's");
        assert!(row[4] > 0.0);
    }
    let _ = std::fs::remove_dir_all(&dir);
}
