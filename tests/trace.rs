//! `morgana trace`: one ray followed through a scene's media, against closed forms — the
//! catenary of a linear index field, Snell's law and total internal reflection at a boundary
//! between media — and its errors.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn morgana() -> Command {
    Command::new(env!("CARGO_BIN_EXE_morgana"))
}

fn scratch(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("morgana-trace-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn trace(dir: &Path, args: &[&str]) -> Output {
    morgana().current_dir(dir).arg("trace").args(args).output().unwrap()
}

fn stdout_of(out: &Output) -> String {
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(out.status.success(), "{text}\n{}", String::from_utf8_lossy(&out.stderr));
    text
}

/// The CSV rows (s_m, x, y, z, dx, dy, dz, n) after checking the header.
fn csv_rows(path: &Path) -> Vec<[f64; 8]> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("s_m,x,y,z,dx,dy,dz,n"));
    lines
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
            v.try_into().unwrap()
        })
        .collect()
}

const CAMERA: &str = r#"
[camera]
position = [0.0, 0.0, 5.0]
look_at = [10.0, 0.0, 0.0]
fov_deg = 40.0
width = 8
height = 8

[output]
bands = 1
min_nm = 540.0
max_nm = 560.0

[world]
medium = "air"

[[material]]
name = "grey"
type = "lambertian"
reflectance = 0.5

[[light]]
type = "point"
position = [5.0, 2.0, 0.0]
spectrum = 1.0
power_w = 1.0
"#;

/// Clear air of index n = 2 + 0.01·y and a wall "wall" at x = 10.
fn linear_scene() -> String {
    format!(
        r#"{CAMERA}
[[medium]]
name = "air"
sigma_a = 0.0
sigma_s = 0.0
index = {{ type = "linear", n0 = 2.0, k_per_m = 0.01, direction = [0.0, 1.0, 0.0] }}

[[shape]]
name = "wall"
type = "quad"
origin = [10.0, -5.0, -5.0]
u = [0.0, 10.0, 0.0]
v = [0.0, 0.0, 10.0]
material = "grey"
"#
    )
}

/// Air of n = 1 around a slab −2 ≤ y ≤ 0 of medium "dense" (n = 1.5, no material on its
/// boundary).
fn slab_scene() -> String {
    format!(
        r#"{CAMERA}
[[medium]]
name = "air"
sigma_a = 0.0
sigma_s = 0.0
index = 1.0

[[medium]]
name = "dense"
sigma_a = 0.0
sigma_s = 0.0
index = 1.5

[[shape]]
name = "slab"
type = "box"
min = [-50.0, -2.0, -50.0]
max = [50.0, 0.0, 50.0]
interior = "dense"
"#
    )
}

#[test]
fn a_level_ray_in_a_linear_field_follows_the_catenary_to_the_wall() {
    // n = n₀ + a y, launched along +x at the origin (Gutierrez et al. 2005, Fig. 1): the path is
    // y = (n₀/a)(cosh(a x/n₀) − 1), with arc length s = (n₀/a) sinh(a x/n₀) and slope
    // dy/dx = sinh(a x/n₀), since n cos e = n₀ along it.
    let (n0, a) = (2.0f64, 0.01f64);
    let dir = scratch("catenary");
    std::fs::write(dir.join("s.toml"), linear_scene()).unwrap();
    let out = trace(&dir, &["s.toml", "--from", "0,0,0", "--dir", "1,0,0", "--csv", "path.csv"]);
    let text = stdout_of(&out);
    assert!(text.contains("surface") && text.contains("shape \"wall\" (material \"grey\")"), "{text}");
    let rows = csv_rows(&dir.join("path.csv"));
    assert!(rows.len() >= 3, "{text}");
    for r in &rows {
        let [_, x, y, z, dx, dy, dz, n] = *r;
        assert!((y - n0 / a * ((a * x / n0).cosh() - 1.0)).abs() < 1e-6, "{r:?}: off the catenary");
        assert!(z.abs() < 1e-12 && dz.abs() < 1e-9, "{r:?}: left the plane");
        // y is written to the µm: n to a·0.5 µm.
        assert!((n - (n0 + a * y)).abs() < 1e-8, "{r:?}: n");
        assert!((dx * dx + dy * dy + dz * dz - 1.0).abs() < 1e-9, "{r:?}: not unit");
    }
    // s_m is the polyline's length; it falls short of the arc length (n₀/a) sinh(a x/n₀) by at
    // most Σ κ² L³ / 24 over its chords, with the curvature κ = a cos e / n ≤ a / n₀.
    let mut shortfall = 0.0;
    for w in rows.windows(2) {
        let l = ((w[1][1] - w[0][1]).powi(2) + (w[1][2] - w[0][2]).powi(2)).sqrt();
        assert!((w[1][0] - w[0][0] - l).abs() < 2e-6, "{w:?}: s_m is not the polyline's length");
        shortfall += (a / n0).powi(2) * l.powi(3) / 24.0;
        let arc = n0 / a * (a * w[1][1] / n0).sinh();
        assert!(w[1][0] <= arc + 2e-6 && w[1][0] >= arc - shortfall - 2e-6, "{w:?}: arc {arc}, bound {shortfall}");
    }
    // The event line gives the arc length itself.
    let arc = n0 / a * (a * 10.0 / n0).sinh();
    let printed: f64 = text.split("s = ").nth(1).and_then(|t| t.split(' ').next()).unwrap().parse().unwrap();
    assert!((printed - arc).abs() < 1e-5, "printed s = {printed}, arc {arc}");
    let last = rows.last().unwrap();
    assert!((last[1] - 10.0).abs() < 1e-9, "ends on the wall: {last:?}");
    assert!((last[5] / last[4] - (a * 10.0 / n0).sinh()).abs() < 1e-6, "arrival slope {last:?}");
    // The chords' directions turn along the catenary too (each chord's direction is its secant,
    // so it lies between the slopes at its ends).
    for w in rows.windows(2) {
        let (x0, x1) = (w[0][1], w[1][1]);
        let slope = w[0][5] / w[0][4];
        if x1 > x0 + 1e-9 {
            assert!(slope >= (a * x0 / n0).sinh() - 1e-9 && slope <= (a * x1 / n0).sinh() + 1e-9, "{w:?}");
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_ray_through_a_slab_refracts_by_snell_and_leaves_parallel() {
    // Into n = 1.5 at 40° from the normal: 1.5 sin θt = sin θi; out of the far face the ray is
    // parallel to the incoming one (parallel faces), then escapes. The slab is 2 m thick, so
    // inside it runs 2 / cos θt.
    let dir = scratch("slab");
    std::fs::write(dir.join("s.toml"), slab_scene()).unwrap();
    let ti = 40f64.to_radians();
    let d = format!("{},{},0", ti.sin(), -ti.cos());
    let out = trace(&dir, &["s.toml", "--from", "0,1,0", "--dir", &d, "--csv", "p.csv"]);
    let text = stdout_of(&out);
    assert_eq!(text.matches("refracted into").count(), 2, "{text}");
    assert!(text.contains("refracted into \"dense\" (n = 1.50000000)"), "{text}");
    assert!(text.contains("escape") && text.contains("sees no light"), "{text}");
    assert!(text.contains("heights are y (no atmosphere in the scene)"), "{text}");
    let rows = csv_rows(&dir.join("p.csv"));
    let inside: Vec<&[f64; 8]> = rows.iter().filter(|r| r[7] == 1.5).collect();
    assert!(!inside.is_empty(), "{rows:?}");
    let tt = (ti.sin() / 1.5).asin();
    for r in &inside {
        assert!((r[4] - tt.sin()).abs() < 1e-8 && (r[5] + tt.cos()).abs() < 1e-8, "Snell: {r:?}");
    }
    let last = rows.last().unwrap();
    assert!((last[4] - ti.sin()).abs() < 1e-8 && (last[5] + ti.cos()).abs() < 1e-8, "parallel: {last:?}");
    // Path length to the bottom face: 1 / cos θi in air, then 2 / cos θt in the slab.
    let bottom = rows.iter().find(|r| r[7] == 1.0 && r[2] < -1.0).unwrap();
    let want = 1.0 / ti.cos() + 2.0 / tt.cos();
    assert!((bottom[0] - want).abs() < 1e-6 && (bottom[2] + 2.0).abs() < 1e-6, "{bottom:?} vs s = {want}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_steep_ray_inside_the_slab_is_totally_reflected() {
    // From inside n = 1.5 at 50° from the normal: sin 50° · 1.5 = 1.15 > 1, so the top face
    // reflects it (the critical angle is asin(1/1.5) = 41.8°); it goes down, mirrored in y,
    // and meets the bottom face at the same angle: reflected again. `--events 2` stops there.
    let dir = scratch("tir");
    std::fs::write(dir.join("s.toml"), slab_scene()).unwrap();
    let t = 50f64.to_radians();
    let d = format!("{},{},0", t.sin(), t.cos());
    let out = trace(&dir, &["s.toml", "--from", "0,-1,0", "--dir", &d, "--events", "2", "--csv", "p.csv"]);
    let text = stdout_of(&out);
    assert_eq!(text.matches("totally reflected back into \"dense\"").count(), 2, "{text}");
    assert!(text.contains("stopped after 2 events (--events)"), "{text}");
    let rows = csv_rows(&dir.join("p.csv"));
    assert!(rows.iter().all(|r| r[7] == 1.5 && r[2] <= 1e-9 && r[2] >= -2.0 - 1e-9), "{rows:?}");
    let down = rows.iter().find(|r| r[5] < 0.0).unwrap();
    assert!((down[4] - t.sin()).abs() < 1e-8 && (down[5] + t.cos()).abs() < 1e-8, "mirrored: {down:?}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_trace_input_exits_with_2_and_writes_nothing() {
    let dir = scratch("bad");
    std::fs::write(dir.join("s.toml"), slab_scene()).unwrap();
    let cases: [(&[&str], &str); 8] = [
        (&["s.toml", "--from", "0,1,0"], "give the start direction"),
        (&["s.toml", "--from", "0,1,0", "--dir", "0,0,0"], "--dir: a zero direction"),
        (&["s.toml", "--from", "0,1,0", "--toward", "0,1,0"], "--toward: the start point itself"),
        (
            &["s.toml", "--from", "0,1,0", "--dir", "1,0,0", "--wavelength-nm", "800"],
            "within the scene's range 540–560",
        ),
        (&["s.toml", "--from", "0,1,0", "--dir", "1,0,0", "--events", "0"], "--events 0"),
        (&["s.toml", "--from", "0,1", "--dir", "1,0,0"], "expected three finite numbers x,y,z"),
        (&["s.toml", "--from", "0,nan,0", "--dir", "1,0,0"], "expected three finite numbers x,y,z"),
        (&["missing.toml", "--from", "0,1,0", "--dir", "1,0,0"], "missing.toml"),
    ];
    for (args, want) in cases {
        let out = trace(&dir, &[args, &["--csv", "p.csv"]].concat());
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(want), "{args:?}: {err}");
    }
    assert!(!dir.join("p.csv").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}
