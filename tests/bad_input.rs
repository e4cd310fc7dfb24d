//! Every class of bad input gets a clear error naming file, line, column and field — never a
//! panic — and the CLI exits with code 2 without creating any output file.

mod common;

use common::scene_error;
use std::process::Command;

/// A scene every check here starts from (`common::lit_plate`).
static GOOD: std::sync::LazyLock<String> = std::sync::LazyLock::new(|| common::lit_plate(16, 16, ""));

/// GOOD with its `line`-th line (1-based) replaced.
fn with_line(line: usize, text: &str) -> String {
    GOOD.lines().enumerate().map(|(i, l)| if i + 1 == line { text } else { l }).collect::<Vec<_>>().join("\n")
}

#[test]
fn the_good_scene_loads() {
    common::scene(&GOOD);
}

#[test]
fn unknown_key_names_it_with_its_line() {
    let e = scene_error(&with_line(5, "widht = 16"));
    assert!(e.starts_with("test.toml:5:"), "{e}");
    assert!(e.contains("widht"), "{e}");
}

#[test]
fn wrong_type_names_the_field_and_line() {
    let e = scene_error(&with_line(4, "fov_deg = \"wide\""));
    assert!(e.starts_with("test.toml:4:"), "{e}");
    assert!(e.contains("fov_deg"), "{e}");
}

#[test]
fn out_of_range_values_say_what_is_allowed() {
    let e = scene_error(&with_line(4, "fov_deg = 200.0"));
    assert!(e.starts_with("test.toml:4:11:") && e.contains("fov_deg = 200") && e.contains("between 0 and 180"), "{e}");
    let e = scene_error(&GOOD.replace("reflectance = 0.7", "reflectance = 1.5"));
    assert!(e.contains("test.toml:17:") && e.contains("values must be in [0, 1]"), "{e}");
    let e = scene_error(&GOOD.replace("photons = 2000\ncaustic", "photons = -5\ncaustic"));
    assert!(e.contains("test.toml:9:") && e.contains("photons = -5"), "{e}");
}

#[test]
fn missing_fields_and_unused_fields_are_errors() {
    let e = scene_error(&GOOD.replace("position = [0.0, 2.0, 0.0]\n", ""));
    assert!(e.contains("test.toml:26:1:") && e.contains("missing field `position`"), "{e}");
    let e = scene_error(
        &GOOD.replace("material = \"white\"\n\n[[light]]", "material = \"white\"\nradius = 2.0\n\n[[light]]"),
    );
    assert!(e.contains("field `radius` is not used") && e.contains("allowed fields: origin, u, v"), "{e}");
}

#[test]
fn references_and_models_are_checked() {
    let e = scene_error(&GOOD.replace("material = \"white\"", "material = \"whtie\""));
    assert!(e.contains("no material named \"whtie\"") && e.contains("defined: white"), "{e}");
    let glass = "[[material]]\nname = \"glass\"\ntype = \"dielectric\"\nior_model = \"cauchy\"\na = 1.5\n\n";
    let e = scene_error(&GOOD.replace("[[shape]]", &format!("{glass}[[shape]]")));
    assert!(e.contains("material \"glass\": ior_model \"cauchy\" needs both a and b_um2"), "{e}");
    let e = scene_error(&GOOD.replace("{ blackbody_k = 4000 }", "{ nm = [500.0, 600.0], values = [1.0, 1.0] }"));
    assert!(e.contains("tabulated over 500–600 nm but the scene simulates 380–780 nm"), "{e}");
    let e = scene_error(&GOOD.replace("power_w = 10.0", "power_w = 10.0\nscale = 2.0"));
    assert!(e.contains("give exactly one of power_w or scale"), "{e}");
}

#[test]
fn an_empty_or_missing_mesh_is_an_error() {
    let dir = std::env::temp_dir().join(format!("morgana-bad-mesh-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("empty.obj"), "# no faces\nv 0 0 0\nv 1 0 0\n").unwrap();
    let mesh = |file: &str| {
        GOOD.replace(
            "type = \"quad\"\norigin = [-1.0, 0.0, -1.0]\nu = [0.0, 0.0, 2.0]\nv = [2.0, 0.0, 0.0]",
            &format!("type = \"mesh\"\nfile = \"{}\"", dir.join(file).display()),
        )
    };
    let e = scene_error(&mesh("empty.obj"));
    assert!(e.contains("test.toml:21:8:") && e.contains("empty.obj") && e.contains("no triangles"), "{e}");
    let e = scene_error(&mesh("missing.obj"));
    assert!(e.contains("missing.obj"), "{e}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn toml_syntax_errors_point_at_the_line() {
    let e = scene_error(&with_line(6, "height = = 16"));
    assert!(e.starts_with("test.toml:6:"), "{e}");
}

fn morgana() -> Command {
    Command::new(env!("CARGO_BIN_EXE_morgana"))
}

#[test]
fn cli_exits_2_on_bad_input_and_writes_nothing() {
    let dir = std::env::temp_dir().join(format!("morgana-cli-bad-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let scene = dir.join("bad.toml");
    std::fs::write(&scene, with_line(4, "fov_deg = 200.0")).unwrap();
    let out_dir = dir.join("out");
    let o = morgana()
        .args(["render", scene.to_str().unwrap(), "--quiet", "--out", out_dir.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(stderr.contains("bad.toml:4:11") && stderr.contains("fov_deg"), "{stderr}");
    assert!(!out_dir.exists() || std::fs::read_dir(&out_dir).unwrap().next().is_none(), "outputs were created");
    let o = morgana().args(["render", dir.join("nope.toml").to_str().unwrap(), "--quiet"]).output().unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("cannot read scene file"));
    let o =
        morgana().args(["render", "--threads", "0", "--quiet", "--out", out_dir.to_str().unwrap()]).output().unwrap();
    assert_eq!(o.status.code(), Some(2));
    let o = morgana().args(["check", scene.to_str().unwrap()]).output().unwrap();
    assert_eq!(o.status.code(), Some(2));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn cli_renders_and_checks_a_scene() {
    let dir = std::env::temp_dir().join(format!("morgana-cli-good-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let scene = dir.join("good.toml");
    std::fs::write(&scene, &*GOOD).unwrap();
    let o = morgana().args(["check", scene.to_str().unwrap()]).output().unwrap();
    assert_eq!(o.status.code(), Some(0));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        stdout.contains("global photon map") && stdout.contains("caustic photon map") && stdout.contains("off"),
        "{stdout}"
    );
    let out_dir = dir.join("out");
    let o = morgana()
        .args(["render", scene.to_str().unwrap(), "--quiet", "--out", out_dir.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(0), "{}", String::from_utf8_lossy(&o.stderr));
    let mut files: Vec<String> =
        std::fs::read_dir(&out_dir).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).collect();
    files.sort();
    assert_eq!(files, vec!["good.exr", "good.png", "report.json"]);
    let report: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out_dir.join("report.json")).unwrap()).unwrap();
    assert_eq!(report["effects"]["caustic_map"]["on"], false);
    assert_eq!(report["effects"]["global_map"]["on"], true);
    assert!(report["phases"].as_array().unwrap().iter().any(|p| p["phase"] == "eye pass"));
    assert_eq!(report["maps"][0]["emitted"], 2000);
    let _ = std::fs::remove_dir_all(&dir);
}
