//! Regressions of issue 15: hostile or extreme input and faults found by trying morgana as a new
//! user would. Each test is named after what broke; each failed before its fix. The command
//! line is run as a user runs it (the built `morgana` binary), and every refusal must be exit
//! code 2 with a message naming the flag, file or field — never a panic, a hang or a partial
//! output.

mod common;

use morgana::render::{RenderOptions, render};
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

/// The scene the checks start from (`common::lit_plate`).
static SCENE: std::sync::LazyLock<String> = std::sync::LazyLock::new(|| common::lit_plate(4, 4, ""));

/// A fresh scratch directory for one test.
fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("morgana-hostile-{name}-{}", std::process::id()));
    std::fs::remove_dir_all(&d).ok();
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn morgana(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_morgana")).current_dir(dir).args(args).output().expect("run morgana")
}

/// Runs `args` in `dir` and asserts exit code 2 with every one of `wants` in the message and
/// no panic.
fn refused(dir: &Path, args: &[&str], wants: &[&str]) -> String {
    let out = morgana(dir, args);
    let err = String::from_utf8_lossy(&out.stderr).to_string();
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert!(!err.contains("panicked"), "{args:?}: {err}");
    for w in wants {
        assert!(err.contains(w), "{args:?}: missing {w:?} in: {err}");
    }
    err
}

fn files_in(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .map(|r| r.map(|e| e.unwrap().file_name().to_string_lossy().to_string()).collect())
        .unwrap_or_default();
    v.sort();
    v
}

#[test]
fn photons_beyond_the_cap_are_refused_not_rendered_forever() {
    let d = scratch("photons");
    std::fs::write(d.join("s.toml"), &*SCENE).unwrap();
    refused(&d, &["render", "s.toml", "--photons", "18446744073709551615", "--quiet"], &["--photons", "2^40"]);
    refused(&d, &["render", "s.toml", "--photons", "0", "--quiet"], &["--photons 0"]);
    assert!(!d.join("out").exists(), "no output directory for a refused run");
}

#[test]
fn a_hundred_thousand_threads_are_refused() {
    let d = scratch("threads");
    std::fs::write(d.join("s.toml"), &*SCENE).unwrap();
    refused(&d, &["render", "s.toml", "--threads", "100000", "--quiet"], &["--threads 100000", "1024"]);
}

#[test]
fn accuracy_refuses_a_gradient_that_would_wind_the_ray_up() {
    let d = scratch("accuracy");
    refused(&d, &["accuracy", "--k", "1e300", "--quick"], &["--k", "|k|·L"]);
}

#[test]
fn grid_refuses_a_billion_octaves_and_takes_negative_corners() {
    let d = scratch("grid");
    refused(&d, &["grid", "--out", "g.mgrid", "--octaves", "1000000000"], &["--octaves 1000000000", "24"]);
    assert!(!d.join("g.mgrid").exists());
    // The book's own example: clap must not read "-1,-1,-1" as a flag.
    let out = morgana(&d, &["grid", "--out", "smoke.mgrid", "--res", "8", "--min", "-1,-1,-1", "--max", "1,1,1"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(d.join("smoke.mgrid").exists());
}

#[test]
fn check_refuses_max_nm_1e308_at_once() {
    let d = scratch("max-nm");
    std::fs::write(d.join("s.toml"), format!("{}\n[output]\nmax_nm = 1e308\n", *SCENE)).unwrap();
    refused(&d, &["check", "s.toml"], &["s.toml:", "max_nm"]);
}

#[test]
fn a_full_or_closed_stdout_is_an_error_not_a_panic() {
    let d = scratch("stdout");
    std::fs::write(d.join("s.toml"), &*SCENE).unwrap();
    let full = std::fs::OpenOptions::new().write(true).open("/dev/full").expect("/dev/full");
    let out = Command::new(env!("CARGO_BIN_EXE_morgana"))
        .current_dir(&d)
        .args(["check", "s.toml"])
        .stdout(Stdio::from(full))
        .output()
        .expect("run morgana");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("cannot write to standard output"), "{err}");
    assert!(!err.contains("panicked"), "{err}");
}

#[test]
fn output_problems_are_found_before_the_render() {
    let d = scratch("out");
    std::fs::write(d.join("s.toml"), &*SCENE).unwrap();
    // --out naming a file.
    std::fs::write(d.join("afile"), "x").unwrap();
    refused(&d, &["render", "s.toml", "--out", "afile", "--quiet"], &["afile", "names a file"]);
    refused(&d, &["check", "s.toml", "--out", "afile"], &["afile", "names a file"]);
    // A directory where an output file goes (the render used to leave the EXR and no report).
    std::fs::create_dir_all(d.join("o").join("s.png")).unwrap();
    refused(&d, &["render", "s.toml", "--out", "o", "--quiet"], &["s.png", "directory is in the way"]);
    assert_eq!(files_in(&d.join("o")), vec!["s.png".to_string()], "nothing written beside the obstacle");
    // An [output] name too long for the file system, which `check` used to call valid.
    let long = "n".repeat(300);
    std::fs::write(d.join("long.toml"), format!("{}\n[output]\nname = \"{long}\"\n", *SCENE)).unwrap();
    refused(&d, &["check", "long.toml"], &["long.toml:", "[output] name", "bytes"]);
    refused(&d, &["render", "long.toml", "--quiet"], &["[output] name"]);
    // A directory name in --out too long for the file system, which `check` called valid
    // (morgana-fuzz, the command-line target) while `render` refused it.
    let long_dir = format!("{}/a", "x".repeat(300));
    for cmd in ["check", "render"] {
        refused(
            &d,
            &[cmd, "s.toml", "--out", &long_dir, "--quiet"][..if cmd == "check" { 4 } else { 5 }],
            &["--out", "300 bytes"],
        );
    }
}

#[test]
fn outputs_are_all_or_nothing_when_any_one_cannot_be_written() {
    let scene = common::scene(&format!("{}\n[output]\nname = \"r\"\ncsv = true\n", *SCENE));
    let rendered = render(&scene, &RenderOptions { quiet: true, ..RenderOptions::default() });
    let names = scene.output_file_names();
    assert_eq!(names, ["r.exr", "r.png", "r.csv", "report.json"]);
    for (k, name) in names.iter().enumerate() {
        let d = scratch(&format!("commit-{k}"));
        // A non-empty directory where output k goes: its rename fails after the others staged
        // (and, for k > 0, after earlier ones were renamed into place).
        std::fs::create_dir_all(d.join(name).join("keep")).unwrap();
        let r = morgana::output::write_outputs(&scene, &rendered, &d, 1, 0.0);
        let e = r.expect_err("a blocked output must fail the whole write");
        assert!(e.to_string().contains(name.as_str()), "{e}");
        assert_eq!(files_in(&d), vec![name.clone()], "output {k} ({name}) blocked: only the obstacle may remain");
        assert_eq!(files_in(&d.join(name)), vec!["keep".to_string()]);
    }
}

#[test]
fn a_missing_atmosphere_file_names_the_scene_line_and_field() {
    let d = scratch("atmosphere");
    let scene = format!(
        "{SCENE}\n[world]\nmedium = \"air\"\n\n[[medium]]\nname = \"air\"\nsigma_a = 0.0\nsigma_s = 0.0\nindex = {{ type = \"atmosphere\", file = \"nowhere.toml\" }}\n",
        SCENE = *SCENE
    );
    std::fs::write(d.join("s.toml"), scene).unwrap();
    let err = refused(&d, &["check", "s.toml"], &["s.toml:", "nowhere.toml", "index"]);
    assert!(!err.starts_with("morgana: nowhere.toml"), "{err}");
}

#[test]
fn an_atmosphere_file_that_is_not_one_names_its_own_line_and_the_scenes() {
    // The fuzzer (render, seed 6, case 35506) pointed a medium's `index.file` at a luminaire
    // file: refused at that file's line only, without the scene's line and field that name it.
    let d = scratch("atmosphere-not-toml");
    std::fs::write(d.join("lamp.ies"), "IESNA:LM-63-2002\nTILT=NONE\n").unwrap();
    let scene = format!(
        "{SCENE}\n[world]\nmedium = \"air\"\n\n[[medium]]\nname = \"air\"\nsigma_a = 0.0\nsigma_s = 0.0\nindex = {{ type = \"atmosphere\", file = \"lamp.ies\" }}\n",
        SCENE = *SCENE
    );
    std::fs::write(d.join("s.toml"), scene).unwrap();
    refused(&d, &["check", "s.toml"], &["lamp.ies:1", "atmosphere file of", "index", "s.toml:"]);
}

#[test]
fn a_bad_spectrum_file_names_the_scene_line_and_its_own() {
    // The fuzzer found a light's spectrum = { file = … } pointed at a luminaire file refused at
    // that file's line only, without the scene's line that names it.
    let d = scratch("spectrum-file");
    std::fs::write(d.join("bad.csv"), "wavelength_nm,value\n400,1\n2\n").unwrap();
    let scene = SCENE.replacen("spectrum = ", "spectrum = { file = \"bad.csv\" }\n# was: ", 1);
    assert_ne!(scene, *SCENE, "the test scene has no spectrum key");
    std::fs::write(d.join("s.toml"), scene).unwrap();
    let err = refused(&d, &["check", "s.toml"], &["s.toml:", "bad.csv:3", "expected 2 numbers"]);
    assert!(err.starts_with("morgana: s.toml:"), "{err}");
}

#[test]
fn a_comment_with_an_equals_sign_is_never_named_as_a_field() {
    let d = scratch("comment");
    std::fs::write(d.join("s.toml"), "# radiance L_e = 2 W m-2 sr-1\n[output]\nbands = 4\n").unwrap();
    let err = refused(&d, &["check", "s.toml"], &["camera"]);
    assert!(!err.contains("# radiance"), "{err}");
}

#[test]
fn invalid_utf8_is_located() {
    let d = scratch("utf8");
    let mut bytes = SCENE.as_bytes().to_vec();
    let at = SCENE.find("white").unwrap();
    bytes[at] = 0xFF;
    std::fs::write(d.join("s.toml"), bytes).unwrap();
    refused(&d, &["check", "s.toml"], &["s.toml:15:9:", "UTF-8", "0xFF"]);
}

#[test]
fn long_strings_and_numbers_are_not_echoed_whole() {
    let d = scratch("long");
    let long = "x".repeat(100_000);
    std::fs::write(d.join("s.toml"), SCENE.replace("type = \"lambertian\"", &format!("type = \"{long}\""))).unwrap();
    let err = refused(&d, &["check", "s.toml"], &["s.toml:", "characters)"]);
    assert!(err.len() < 2000, "{} bytes echoed", err.len());
    let digits = "9".repeat(309);
    std::fs::write(d.join("n.toml"), SCENE.replace("power_w = 10.0", &format!("power_w = {digits}"))).unwrap();
    let err = refused(&d, &["check", "n.toml"], &["n.toml:"]);
    assert!(err.len() < 2000, "{} bytes echoed", err.len());
}

#[test]
fn a_luminaire_value_of_1e308_names_its_line() {
    let d = scratch("ies");
    let ies = "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 3 1 1 2 0 0 0\n1 1 0\n0 45 90\n0\n100 1e308 10\n";
    std::fs::write(d.join("l.ies"), ies).unwrap();
    refused(&d, &["luminaire", "l.ies"], &["l.ies:7", "1e308"]);
}

#[test]
fn lights_of_infinite_power_are_refused_and_maps_that_store_nothing_are_noted() {
    let d = scratch("power");
    let area = "[[light]]\ntype = \"area\"\nshape = \"quad\"\norigin = [-0.1, 1.9, -0.1]\nu = [0.2, 0.0, 0.0]\nv = [0.0, 0.0, 0.2]\nspectrum = 1e300\nscale = 1e300\n";
    std::fs::write(d.join("inf.toml"), format!("{}\n{area}", *SCENE)).unwrap();
    refused(&d, &["check", "inf.toml"], &["inf.toml:", "light"]);
    // A light far beyond the scene: its photons never reach the plate, and the run says so.
    std::fs::write(d.join("far.toml"), SCENE.replace("position = [0.0, 2.0, 0.0]", "position = [0.0, -1e14, 0.0]"))
        .unwrap();
    let out = morgana(&d, &["render", "far.toml", "--quiet"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(err.contains("stored none of its"), "{err}");
}

#[test]
fn tonemap_refuses_nan_and_infinite_pixels() {
    let d = scratch("tonemap");
    let mut image = morgana::spectrum::SpectralImage {
        width: 2,
        height: 2,
        bands: morgana::spectrum::Bands::new(400.0, 700.0, 2).unwrap(),
        data: vec![0.1; 8],
        rgb: vec![0.1; 12],
    };
    image.data[5] = f32::NAN;
    morgana::spectrum::exr::write_spectral_exr(&d.join("nan.exr"), &image).unwrap();
    refused(&d, &["tonemap", "nan.exr", "--out", "nan.png"], &["nan.exr", "pixel (0, 1)", "NaN"]);
    assert!(!d.join("nan.png").exists());
}

#[test]
fn a_run_that_would_not_fit_in_max_memory_is_refused_before_it_allocates() {
    let d = scratch("mem");
    std::fs::write(d.join("s.toml"), &*SCENE).unwrap();
    // 2,000 photons cannot fit in 1 MB beside the scene (the process alone holds several MB).
    let err =
        refused(&d, &["render", "s.toml", "--out", "o", "--quiet", "--max-memory", "1M"], &["--max-memory", "MB"]);
    assert!(err.contains("photons expected"), "the message gives the numbers: {err}");
    assert!(files_in(&d.join("o")).is_empty(), "nothing written: {:?}", files_in(&d.join("o")));
    for bad in ["0", "-5", "lots", "1e400G"] {
        refused(&d, &["render", "s.toml", "--quiet", &format!("--max-memory={bad}")], &["--max-memory"]);
    }
    // A generous limit renders, and report.json records the estimate against the measured peak.
    let out = morgana(&d, &["render", "s.toml", "--out", "ok", "--quiet", "--max-memory", "16G"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.join("ok").join("report.json")).unwrap()).unwrap();
    let est = report["memory"]["estimated_peak_bytes"].as_u64().expect("estimate in report.json");
    let peak = report["peak_memory_bytes"].as_u64().expect("measured peak in report.json");
    assert!(est > 0 && peak > 0);
    assert_eq!(report["memory"]["limit_bytes"].as_u64(), Some(16 << 30));
}

#[test]
fn max_seconds_stops_a_run_cleanly_and_writes_nothing() {
    let d = scratch("time");
    // Enough photons that 0.2 s cannot trace them even on a fast machine (about 10 s here).
    let slow = SCENE.replace("photons = 2000\ncaustic_photons = 2000", "photons = 20000000\ncaustic_photons = 2000");
    std::fs::write(d.join("s.toml"), slow).unwrap();
    let t = std::time::Instant::now();
    let out = morgana(&d, &["render", "s.toml", "--out", "o", "--quiet", "--max-seconds", "0.2"]);
    let err = String::from_utf8_lossy(&out.stderr).to_string();
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("--max-seconds") && err.contains("photon pass") && err.contains("no output"), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(files_in(&d.join("o")).is_empty(), "nothing written: {:?}", files_in(&d.join("o")));
    // The batches in flight finish (4096 photons each): the run stops within seconds, not after
    // tracing 2e7 photons.
    assert!(t.elapsed().as_secs_f64() < 30.0, "stopped after {:?}", t.elapsed());
    for bad in ["0", "-1", "nan", "inf", "1e9"] {
        refused(&d, &["render", "s.toml", "--quiet", &format!("--max-seconds={bad}")], &["--max-seconds"]);
    }
}

#[test]
fn a_profile_sensor_with_more_than_4096_depths_is_refused_naming_depths_m() {
    // The fuzzer's render target found 100,000 depths accepted and a 4 × 4 render of them past
    // its deadline (every stored photon is tallied at every depth).
    let example =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/mobley1993_problem1.toml"))
            .expect("examples/mobley1993_problem1.toml");
    let list = |n: usize| (0..n).map(|i| format!("{}.0", i % 50)).collect::<Vec<_>>().join(", ");
    let at_cap = example.replace("depths_m = [1.0, 5.0, 10.0]", &format!("depths_m = [{}]", list(4096)));
    assert!(at_cap.contains("depths_m = [0.0, 1.0"), "the example's depths line moved");
    common::scene(&at_cap);
    let over = example.replace("depths_m = [1.0, 5.0, 10.0]", &format!("depths_m = [{}]", list(4097)));
    let e = common::scene_error(&over);
    assert!(e.contains("test.toml:62:") && e.contains("depths_m") && e.contains("4096"), "{e}");
}

#[test]
fn every_command_writes_into_missing_directories_its_check_accepted() {
    // The fuzzer's cli target: `check_output_file` accepts a path whose missing directories can
    // be made, but `grid --out` and `luminaire --png` then failed with an internal error
    // ("cannot create a temporary file in 'sub/dir'") after the work.
    let d = scratch("missing-dirs");
    let ies = Path::new(env!("CARGO_MANIFEST_DIR")).join("luminaires/road_batwing.ies");
    let ies = ies.to_str().expect("utf-8 path");
    for args in [
        vec!["grid", "--out", "a/b/g.mgrid", "--res", "4", "--octaves", "1"],
        vec!["luminaire", ies, "--png", "c/d/p.png"],
    ] {
        let out = morgana(&d, &args);
        assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    }
    assert!(d.join("a/b/g.mgrid").is_file() && d.join("c/d/p.png").is_file());
}

#[test]
fn values_that_rendered_nan_are_refused_naming_their_line() {
    // The fuzzer's render target (10^5 cases, 2026-12-02) found these accepted and rendered to NaN
    // pixels or readings: a quad edge and a quad origin of 1.8e308 m (u × v overflowed), a glass
    // of ior 9.2e18, a light of 1e308 W, and a profile sensor's slab of 5e-324 m. Coordinates,
    // edges and radii are now within ±1e15 m (validate::MAX_LENGTH_M, which still takes the sun
    // as a sphere at 1 au), radii and slabs at least 1e-9 m, indices at most 10 and lights at
    // most 1e27 W (the sun's luminosity is 3.8e26 W).
    let example = |name: &str| {
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("examples").join(name)).expect(name)
    };
    let fog = example("fog_box.toml");
    let with = |text: &str, old: &str, new: &str| {
        assert!(text.contains(old), "{old:?} not in the example");
        text.replacen(old, new, 1)
    };
    let floor_v = "v = [2.0, 0.0, 0.0]\nmaterial = \"white\"";
    let glass = "\n[[material]]\nname = \"glass\"\ntype = \"dielectric\"\nior = 9223372036854775807\n";
    let profile = example("mobley1993_problem1.toml");
    for (scene, line, field, limit) in [
        (with(&fog, floor_v, "v = [1.7976931348623157e308, 0.0, 0.0]\nmaterial = \"white\""), 56, "v =", "1e15"),
        (with(&fog, "origin = [-1.0, -1.0, -1.0]", "origin = [-1.0, -1.0, 1.1e15]"), 54, "origin =", "1e15"),
        (with(&fog, "position = [0.0, 0.0, 0.9]", "position = [0.0, -2e15, 0.9]"), 7, "camera position", "1e15"),
        (with(&fog, "scale = 10.0", "power_w = 1e308"), 107, "ceiling light", "1e27 W"),
        (with(&fog, "\n[[material]]", &format!("{glass}\n[[material]]")), 39, "ior", "between 1 and 10"),
        (with(&profile, "slab_m = 0.2", "slab_m = 5e-324"), 63, "slab_m", "between 0.000000001 and"),
    ] {
        let e = common::scene_error(&scene);
        assert!(e.contains(&format!("test.toml:{line}:")) && e.contains(field) && e.contains(limit), "{e}");
    }
    // The sun as a sphere at 1 au fits (beside a lit plate: a world filled with fog would have
    // to be marched across 3e11 m, which check_march_work refuses).
    let plate = common::lit_plate(4, 4, "");
    let sun = "\n[[shape]]\nname = \"sun\"\ntype = \"sphere\"\ncenter = [0.0, 1.496e11, 0.0]\nradius = RADIUS\nmaterial = \"white\"\n";
    let radius_line = plate.matches('\n').count() + 6;
    common::scene(&format!("{plate}{}", sun.replace("RADIUS", "6.957e8")));
    for radius in ["1e300", "5e-324"] {
        let e = common::scene_error(&format!("{plate}{}", sun.replace("RADIUS", radius)));
        assert!(
            e.contains(&format!("test.toml:{radius_line}:")) && e.contains("radius = ") && e.contains("out of range"),
            "{e}"
        );
    }
}

#[test]
fn arrays_longer_than_their_field_takes_are_refused_at_their_line() {
    // The render fuzzer (seed 3, 2026-12-03) found `max = [0.1, 0.1, 0.1, 7.0]` accepted: serde
    // reads the first three numbers of a TOML array into a point and the `toml` crate ignored the
    // rest. Every fixed-length array of a scene now refuses another length, longer or shorter.
    let plate = common::lit_plate(4, 4, "");
    let tail = concat!(
        "[[sensor]]\nname = \"desk\"\ntype = \"illuminance_plane\"\norigin = [-0.5, 0.01, 0.5]\n",
        "u = [1.0, 0.0, 0.0]\nv = [0.0, 0.0, -1.0]\nresolution = [2, 2]\nsamples = 1\ngather_rays = 1\n\n",
        "[[sensor]]\nname = \"sky\"\ntype = \"sky_radiance\"\norigin = [0.0, 1.0, 0.0]\n",
        "directions_deg = [[0.0, 0.0], [60.0, 90.0]]\nsamples = 1\n\n",
        "[[shape]]\ntype = \"triangle\"\nvertices = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]\n",
        "material = \"white\"\n\n[output]\nregion = [0, 0, 2, 2]\n",
    );
    let scene = format!("{plate}\n{tail}");
    common::scene(&scene);
    for (old, new, length, wanted) in [
        ("position = [0.0, 1.0, 3.0]", "position = [0.0, 1.0, 3.0, 7.0]", 4, 3),
        ("u = [0.0, 0.0, 2.0]", "u = [0.0, 0.0]", 2, 3),
        ("resolution = [2, 2]", "resolution = [2, 2, 2]", 3, 2),
        ("[60.0, 90.0]]", "[60.0, 90.0, 1.0]]", 3, 2),
        ("[0.0, 1.0, 0.0]]", "[0.0, 1.0, 0.0, 0.0]]", 4, 3),
        ("region = [0, 0, 2, 2]", "region = [0, 0, 2, 2, 9]", 5, 4),
    ] {
        assert_eq!(scene.matches(old).count(), 1, "{old}");
        let line = scene[..scene.find(old).unwrap()].matches('\n').count() + 1;
        let e = common::scene_error(&scene.replacen(old, new, 1));
        assert!(
            e.contains(&format!("test.toml:{line}:"))
                && e.contains(&format!("invalid length {length}, expected an array of length {wanted}")),
            "{new}: {e}"
        );
    }
}

#[test]
fn a_march_step_far_below_the_medium_it_crosses_is_refused_naming_the_key() {
    // The render fuzzer (seed 3) found the glass block of examples/fluorescent_glass_block.toml
    // grown to 2e9 m and still marched in 5 mm steps (4e11 steps a camera ray), and the sunset
    // sky's air marched in 0.25 m steps across its 4.4e7 m world: each past the deadline for 4 × 4
    // pixels. A march step must cross a scattering medium's extent in at most 1e5 steps.
    let example = |name: &str| {
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("examples").join(name)).expect(name)
    };
    let block = example("fluorescent_glass_block.toml");
    let corners = "min = [-0.15, 0.0005, -0.08]\nmax = [0.15, 0.16, 0.08]";
    assert!(block.contains(corners) && block.contains("march_step = 0.005"), "the example changed");
    let step_line = |text: &str| text.lines().position(|l| l.starts_with("march_step")).expect("march_step") + 1;
    let huge = block.replacen(corners, "min = [-1.05e9, 0.0005, -0.08]\nmax = [1.05e9, 0.16, 0.08]", 1);
    let e = common::scene_error(&huge);
    assert!(
        e.contains(&format!("test.toml:{}:", step_line(&huge)))
            && e.contains("march_step = 0.005 m")
            && e.contains("medium \"uranium glass\"")
            && e.contains("use march_step ≥ 2.100e4 m"),
        "{e}"
    );
    common::scene(&huge.replacen("march_step = 0.005", "march_step = 21001", 1));
    // The world medium's extent is the world sphere's diameter (4.414e7 m for the sunset sky).
    let sky = example("sky_sunset.toml");
    let fine = sky.replacen("[integrator]\n", "[integrator]\nmarch_step = 0.25\n", 1);
    let e = common::scene_error(&fine);
    assert!(e.contains(&format!("test.toml:{}:", step_line(&fine))) && e.contains("medium \"air\""), "{e}");
    common::scene(&sky.replacen("[integrator]\n", "[integrator]\nmarch_step = 450\n", 1));
    // The default step (1 % of the geometry's diagonal) from a camera 1e12 m away (seed 4, case
    // 8938): the world sphere then spans 2e12 m, and the error names the camera's position.
    let camera = "position = [0.0, 2.0, 0.0]";
    assert!(sky.contains(camera), "the example's camera moved");
    let far = sky.replacen(camera, "position = [1e12, 2.0, 1e9]", 1);
    let camera_line = far.lines().position(|l| l.starts_with("position = [1e12")).expect("camera") + 1;
    let e = common::scene_error(&far);
    assert!(e.contains(&format!("test.toml:{camera_line}:")) && e.contains("the default march_step"), "{e}");
    // A scattering medium that no shape bounds (named, never used) is never marched: no refusal.
    let unused = "\n[[medium]]\nname = \"unused fog\"\nsigma_t = 0.5\nalbedo = 0.8\n";
    common::scene(&format!("{}{unused}", common::lit_plate(4, 4, "")));
    common::scene(&format!(
        "{}{unused}",
        common::lit_plate(4, 4, "").replace("[integrator]\n", "[integrator]\nmarch_step = 0.01\n")
    ));
}

#[test]
fn spherical_air_that_no_ground_closes_is_refused_naming_the_medium() {
    // The render fuzzer (seed 2, cases 349, 25461, 31526) changed the radius or centre of the
    // ground of examples/sky_sunset.toml: the sky's air, held at its sea-level density below the
    // ground, then filled the 6371 km between the camera and a 65 km "Earth", and a 4 × 4 render
    // took 16 s of CPU (0.2 s with the real ground) — past the fuzzer's deadline under load.
    let sky = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/sky_sunset.toml"))
        .expect("examples/sky_sunset.toml");
    let ground = "center = [0.0, -6371000.0, 0.0]\nradius = 6371000.0";
    assert!(sky.contains(ground), "the example's ground changed");
    let with_ground = |g: &str| sky.replacen(ground, g, 1);
    let medium_line = sky.lines().position(|l| l == "[[medium]]").expect("a [[medium]]") + 1;
    for bad in [
        "center = [0.0, -6371000.0, 0.0]\nradius = 65536",
        "center = [0.0, -6371000.0, 0.0]\nradius = 637100.0",
        "center = [0.0, -637100000000000.0, 0.0]\nradius = 6371000.0",
        "center = [0.0, -6371000.0, 0.0]\nradius = 6360000.0",
    ] {
        let e = common::scene_error(&with_ground(bad));
        assert!(
            e.contains(&format!("test.toml:{medium_line}:"))
                && e.contains("medium \"air\"")
                && e.contains("no sphere closes it from below")
                && e.contains("6361000 m"),
            "{bad}: {e}"
        );
    }
    // Air with ozone and aerosols (constituents, each on its own height profile) likewise.
    let hazy = |g: &str| {
        with_ground(g).replacen(
            "\nrefraction = true\n",
            "\nrefraction = true\nozone_du = 300\naerosol = { angstrom_beta = 0.05, scale_height_m = 1200, albedo = 0.95, g = 0.7 }\n",
            1,
        )
    };
    let e = common::scene_error(&hazy("center = [0.0, -6371000.0, 0.0]\nradius = 65536"));
    assert!(e.contains("no sphere closes it from below"), "{e}");
    common::scene(&hazy(ground));
    // Ground 430 m below sea level (the Dead Sea's shore) or above it closes the air.
    for good in
        ["center = [0.0, -6371000.0, 0.0]\nradius = 6370570.0", "center = [0.0, -6371000.0, 0.0]\nradius = 6371500.0"]
    {
        common::scene(&with_ground(good));
    }
    // A glass Earth with the air itself inside does not close it; with vacuum inside it does.
    let glass = "\n[[material]]\nname = \"glass\"\ntype = \"dielectric\"\nior = 1.5\n";
    let glass_earth = with_ground(ground).replacen("material = \"ground\"", "material = \"glass\"", 1) + glass;
    common::scene(&glass_earth);
    let e = common::scene_error(&glass_earth.replacen(
        "material = \"glass\"",
        "material = \"glass\"\ninterior = \"air\"",
        1,
    ));
    assert!(e.contains("no sphere closes it from below"), "{e}");
}
