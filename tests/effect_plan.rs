//! The effect plan is the one source of truth: for each of its entries, a scene where the plan
//! turns it off records no work of that kind in `report.json`, and one where it is on records
//! some. The scenes are tiny (8 × 8 pixels, a few thousand photons); what is checked is whether
//! work was done, not its result.

use morgana::output::report::Report;
use morgana::render::{RenderOptions, render};
use morgana::scene::{Scene, load_scene_str};
use serde_json::Value;
use std::path::Path;

/// A closed box of diffuse (or mirror) walls lit by a point light, with optional extra TOML.
fn scene(walls: &str, extra: &str, integrator: &str) -> Scene {
    let toml = format!(
        r#"
[camera]
position = [0.0, 0.0, 0.9]
look_at = [0.0, 0.0, -1.0]
fov_deg = 60.0
width = 8
height = 8

[output]
bands = 4
min_nm = 400.0
max_nm = 700.0

[integrator]
photons = 4000
caustic_photons = 4000
gather_rays = 4
spp = 1
march_step = 0.2
seed = 3
{integrator}

[[material]]
name = "walls"
{walls}

[[shape]]
name = "room"
type = "box"
min = [-1.0, -1.0, -1.0]
max = [1.0, 1.0, 1.0]
material = "walls"

[[light]]
name = "lamp"
type = "point"
position = [0.0, 0.8, 0.0]
spectrum = 1.0
power_w = 10.0
{extra}
"#
    );
    load_scene_str(&toml, Path::new("plan-test.toml"), Path::new("."), "plan").expect("test scene")
}

const DIFFUSE: &str = "type = \"lambertian\"\nreflectance = 0.5";
const MIRROR: &str = "type = \"mirror\"\nreflectance = 0.9";

const FOG: &str = r#"
[world]
medium = "fog"

[[medium]]
name = "fog"
sigma_t = 0.5
albedo = 0.8
phase = "isotropic"
"#;

/// A glass sphere in front of the camera.
fn glass(ior: &str) -> String {
    format!(
        r#"
[[material]]
name = "glass"
type = "dielectric"
ior = {ior}

[[shape]]
name = "ball"
type = "sphere"
center = [0.0, 0.0, -0.3]
radius = 0.35
material = "glass"
"#
    )
}

/// The render's report as JSON.
fn report(scene: &Scene) -> Value {
    let rendered = render(scene, &RenderOptions { quiet: true, ..RenderOptions::default() });
    let report = Report::new(scene, &rendered.stats, 1, 0.0, Vec::new());
    serde_json::to_value(&report).expect("report.json")
}

fn plan_on(r: &Value, entry: &str) -> bool {
    r["effects"][entry]["on"].as_bool().unwrap_or_else(|| panic!("effects.{entry}.on in {}", r["effects"]))
}

fn stored(r: &Value, map: &str) -> u64 {
    r["maps"].as_array().expect("maps").iter().filter(|m| m["map"] == map).map(|m| m["stored"].as_u64().unwrap()).sum()
}

fn maps_stat(r: &Value, key: &str) -> u64 {
    r["maps"].as_array().expect("maps").iter().map(|m| m["stats"][key].as_u64().unwrap_or(0)).sum()
}

fn rays(r: &Value, key: &str) -> u64 {
    r["rays"][key].as_u64().unwrap_or_else(|| panic!("rays.{key} in {}", r["rays"]))
}

/// Checks one entry: off in `off`, on in `on`, and `work` zero and positive accordingly.
fn check(entry: &str, off: &Scene, on: &Scene, work: &dyn Fn(&Value) -> u64) {
    let (r_off, r_on) = (report(off), report(on));
    assert!(!plan_on(&r_off, entry), "{entry} should be off: {}", r_off["effects"][entry]);
    assert!(plan_on(&r_on, entry), "{entry} should be on: {}", r_on["effects"][entry]);
    assert_eq!(work(&r_off), 0, "{entry} is off but did work");
    assert!(work(&r_on) > 0, "{entry} is on but did no work");
}

#[test]
fn global_map() {
    check("global_map", &scene(MIRROR, "", ""), &scene(DIFFUSE, "", ""), &|r| stored(r, "global"));
}

#[test]
fn caustic_map() {
    check("caustic_map", &scene(DIFFUSE, "", ""), &scene(DIFFUSE, &glass("1.5"), ""), &|r| stored(r, "caustic"));
}

#[test]
fn shadow_rays() {
    let off = scene(DIFFUSE, "", "direct = \"photon_map\"");
    check("shadow_rays", &off, &scene(DIFFUSE, "", ""), &|r| rays(r, "shadow"));
    // A fog-filled box of mirrors: no diffuse surface, but the fog's single scattering is
    // lit by shadow rays, and the plan says so.
    check("shadow_rays", &scene(MIRROR, "", ""), &scene(MIRROR, FOG, ""), &|r| rays(r, "shadow"));
}

#[test]
fn final_gather() {
    let off = scene(DIFFUSE, "", "final_gather = false");
    let on = scene(DIFFUSE, "", "final_gather = true");
    check("final_gather", &off, &on, &|r| rays(r, "gather") + r["irradiance_points"].as_u64().unwrap());
}

#[test]
fn dispersion_splitting() {
    let off = scene(DIFFUSE, &glass("1.5"), "");
    let on = scene(DIFFUSE, &glass("\"N-BK7\""), "");
    check("dispersion_splitting", &off, &on, &|r| rays(r, "splits"));
}

#[test]
fn participating_media() {
    let work = |r: &Value| rays(r, "medium_steps") + maps_stat(r, "medium_interactions");
    check("participating_media", &scene(DIFFUSE, "", ""), &scene(DIFFUSE, FOG, ""), &work);
}

#[test]
fn volume_map() {
    check("volume_map", &scene(DIFFUSE, "", ""), &scene(DIFFUSE, FOG, ""), &|r| stored(r, "volume"));
}

#[test]
fn curved_paths() {
    let air = |index: &str| {
        format!(
            "[world]\nmedium = \"air\"\n\n[[medium]]\nname = \"air\"\nsigma_a = 0.0\nsigma_s = 0.0\nindex = {index}\n"
        )
    };
    let off = scene(DIFFUSE, &air("{ type = \"constant\", n = 1.0003 }"), "");
    let on = scene(DIFFUSE, &air("{ type = \"linear\", n0 = 1.01, k_per_m = 1e-3, direction = [0.0, 1.0, 0.0] }"), "");
    let work = |r: &Value| {
        r["eye_curved"]["curved_events"].as_u64().unwrap()
            + r["maps"]
                .as_array()
                .unwrap()
                .iter()
                .map(|m| m["stats"]["curved"]["curved_events"].as_u64().unwrap())
                .sum::<u64>()
    };
    check("curved_paths", &off, &on, &work);
}

#[test]
fn inelastic_scattering() {
    let medium = |inelastic: &str| {
        format!(
            "[world]\nmedium = \"water\"\n\n[[medium]]\nname = \"water\"\nsigma_a = 0.2\nsigma_s = 0.3\n{inelastic}\n"
        )
    };
    let off = scene(DIFFUSE, &medium(""), "");
    let on = scene(
        DIFFUSE,
        &medium(
            "inelastic = [{ process = \"fluorescence\", name = \"dye\", sigma_a = 0.5, yield = 0.8, emission = { type = \"gaussian\", peak_nm = 600.0, sigma_nm = 20.0 } }]",
        ),
        "",
    );
    check("inelastic_scattering", &off, &on, &|r| maps_stat(r, "reemitted") + maps_stat(r, "raman_events"));
}

#[test]
fn progressive_passes() {
    // Work: the passes after the first, and the report says which rule stopped the run.
    let (off, on) = (scene(DIFFUSE, "", ""), scene(DIFFUSE, "", "passes = 3"));
    check("progressive_passes", &off, &on, &|r| r["progressive"]["passes"].as_u64().unwrap_or(0) - 1);
    assert_eq!(report(&on)["progressive"]["stopped"]["rule"], "passes");
}
