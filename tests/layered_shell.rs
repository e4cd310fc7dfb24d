//! The layered upper air crossed by Bouguer's invariant (`raypath::shell`) against the ray
//! equation integrated step by step through the same air, and the photon pass with and without it.

use glam::DVec3;
use morgana::atmosphere::RadialTable;
use morgana::media::refractive_index::IndexField;
use morgana::photon::{MapKind, PassSettings, PhotonSink, PhotonStats, shoot};
use morgana::photon_map::{PhotonPath, PhotonRecord};
use morgana::raypath::shell::LayeredShell;
use morgana::raypath::{Event, Propagator, RayState};
use morgana::scene::{Scene, load_scene_str};
use std::path::Path;

const R: f64 = 6_371_000.0;

/// `sunset_sea` as shipped, with `extra` appended to its text.
fn sunset_sea(extra: &str) -> Scene {
    sunset_sea_with(extra, &[])
}

/// `sunset_sea` with `extra` appended and each (from, to) of `edits` replaced in its text.
fn sunset_sea_with(extra: &str, edits: &[(&str, &str)]) -> Scene {
    let path = "examples/sunset_sea.toml";
    let mut text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path}: {e}")) + extra;
    for (from, to) in edits {
        assert!(text.contains(from), "{from}");
        text = text.replace(from, to);
    }
    load_scene_str(&text, Path::new(path), Path::new("examples"), "sunset_sea")
        .unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// `examples/mirage_hot_road.toml` (air as the world medium, no top sphere) with each (from, to)
/// of `edits` replaced in its text.
fn mirage_with(edits: &[(&str, &str)]) -> Scene {
    let path = "examples/mirage_hot_road.toml";
    let mut text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    for (from, to) in edits {
        assert!(text.contains(from), "{from}");
        text = text.replace(from, to);
    }
    load_scene_str(&text, Path::new(path), Path::new("examples"), "mirage_hot_road")
        .unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// A global photon pass of `scene` with the layered shell and one without it, each of
/// `emitted` photons from `seed` (the second crosses nothing in one move).
fn with_and_without(scene: &Scene, emitted: u64, seed: u64) -> ((PhotonSink, PhotonStats), (PhotonSink, PhotonStats)) {
    let mut pass = PassSettings::of(scene);
    let with = shoot(&scene.world, &pass, MapKind::Global, emitted, seed, &|_| {});
    pass.layered_shell = false;
    let without = shoot(&scene.world, &pass, MapKind::Global, emitted, seed, &|_| {});
    assert_eq!(without.1.shell_descents, 0);
    (with, without)
}

/// Each named pair of powers (W), as shares of `total`, agrees within 4 binomial σ of
/// `emitted` photons.
fn assert_shares_agree(pairs: &[(&str, f64, f64)], total: f64, emitted: u64) {
    for (name, a, b) in pairs {
        let (pa, pb) = (a / total, b / total);
        let sigma = ((pa * (1.0 - pa) + pb * (1.0 - pb)) / emitted as f64).sqrt().max(1.0 / emitted as f64);
        assert!((pa - pb).abs() < 4.0 * sigma, "{name}: {pa} with, {pb} without (σ {sigma})");
    }
}

/// One coordinate of a stored photon.
type Coordinate = fn(&PhotonRecord) -> f64;

fn air(scene: &Scene) -> u32 {
    scene.world.media.iter().position(|m| m.name == "air").expect("air") as u32
}

/// The shipped scene has a shell from 1 m above the sea (its highest other shape) to its top at
/// 90 km, and a photon pass crosses it: the propagator of a photon pass finds it.
#[test]
fn sunset_sea_has_a_shell_from_a_metre_above_the_sea_to_its_top() {
    let scene = sunset_sea("");
    let prop = Propagator::new(&scene.world, scene.curved()).with_layered_shell((400.0, 700.0));
    let shell = prop.layered_shell().expect("a shell");
    assert_eq!(shell.medium(), air(&scene));
    let (low, top) = shell.heights_m();
    assert!((low - 1.0).abs() < 1e-6 && (top - 90_000.0).abs() < 1e-6, "{low} {top}");
    // Without curved paths there is nothing to cross in one move.
    assert!(Propagator::new(&scene.world, None).with_layered_shell((400.0, 700.0)).layered_shell().is_none());
}

/// Paths entering the top of the air at 400, 550 and 700 nm, from straight down to 10⁻⁵ short of
/// tangent at the bottom (impact parameters b = f·n_low·r_low): where the shell puts them on
/// its bottom, and the density column they crossed, against the ray equation (Dormand–Prince at
/// rtol = 10⁻¹¹, chords within 1 mm of the arc) followed to an index-matched sphere at the same
/// radius, summing the density integral of each chord. The shell's table (rtol = 10⁻⁹) holds Δθ
/// to rtol (6.4 mm at the Earth's radius) and C to 10·rtol (see the module notes).
#[test]
fn the_invariant_puts_a_path_where_the_ray_equation_does() {
    let edits = [("arc_tolerance_m = 0.5", "arc_tolerance_m = 0.001\node_rtol = 1e-11\node_atol = 1e-11")];
    let scene = sunset_sea_with(
        "\n[[shape]]\nname = \"bottom\"\ntype = \"sphere\"\ncenter = [0.0, -6371000.0, 0.0]\nradius = 6371001.0\n\
         interior = \"air\"\nexterior = \"air\"\n",
        &edits,
    );
    let id = air(&scene);
    let medium = &scene.world.media[id as usize];
    let Some(IndexField::Atmosphere(atmosphere)) = &medium.index else { panic!("air has an atmosphere") };
    let curved = scene.curved().expect("curved paths");
    let rtol = 1e-9;
    let table = RadialTable::new(atmosphere, rtol).expect("table");
    let centre = DVec3::new(0.0, -R, 0.0);
    let (r_low, r_top) = (R + 1.0, R + 90_000.0);
    let shell =
        LayeredShell::between(medium, id, &table, centre, (r_low, r_top), (400.0, 700.0), rtol).expect("a shell");
    let prop = Propagator::new(&scene.world, Some(curved));
    let r0 = r_top - 1e-3;
    let mut worst = (0.0f64, 0.0f64, 0.0f64);
    for lambda in [400.0, 550.0, 700.0] {
        let k = table.k(lambda);
        let q = |r: f64| table.at(r - R).expect("inside the table").0;
        let (n0, n_low) = (1.0 + k * q(r0), 1.0 + k * q(r_low));
        for f in [0.0, 0.3, 0.6, 0.9, 0.99, 0.999, 0.9999, 0.99999] {
            let sin0 = f * n_low * r_low / (n0 * r0);
            let dir = DVec3::new(sin0, -(1.0 - sin0 * sin0).sqrt(), 0.0);
            let start = centre + DVec3::new(0.0, r0, 0.0);
            let d = shell.descend(start, dir, lambda).unwrap_or_else(|| panic!("{lambda} nm, f = {f}: no descent"));
            let mut column = 0.0;
            let state = RayState { position: start, dir, wavelength_nm: Some(lambda), medium: Some(id) };
            let event = prop.next_event_with(&state, &mut |c| {
                column += medium.density.integral_exact(c.origin, c.dir, c.length).expect("column");
                None
            });
            let Event::Surface { hit, dir: end_dir, .. } = event else { panic!("{lambda} nm, f = {f}: {event:?}") };
            let (dp, dd) = ((d.position - hit.point).length(), d.dir.angle_between(end_dir));
            let dc = (d.column_m - column).abs() / column;
            worst = (worst.0.max(dp), worst.1.max(dd), worst.2.max(dc));
            assert!((d.position - centre).length() - r_low < 1e-6, "on the bottom");
            // Position: the table's bound on Δθ (rtol·r_low, 6.4 mm) twice over for the
            // reference's own error; direction: above the 1.5·10⁻⁸ rad floor of `angle_between`;
            // column: the reference sums straight chords within 1 mm of the arc, up to
            // ~1 mm / 8 km ≈ 10⁻⁷ of the column on the longest paths (measured: ≤ 3.5·10⁻⁷ at
            // f = 0.99999, ≤ 3.3·10⁻⁸ elsewhere).
            assert!(
                dp < 2.0 * rtol * r_low && dd < 1e-7 && dc < 1e-6,
                "{lambda} nm, f = {f}: {dp} m, {dd} rad, column {dc:e}"
            );
        }
    }
    eprintln!("largest differences: position {:.3e} m, direction {:.3e} rad, column {:.3e}", worst.0, worst.1, worst.2);
}

/// What happens to a photon pass's photons does not depend on whether the shell is crossed in
/// one move: the shares of the emitted power absorbed in the air, absorbed at the sea and
/// escaped, and the photons stored, agree within their binomial noise (4 σ), each pass with its
/// own photons (the shell draws one number per crossing where the steps drew one per tentative
/// collision, so the two passes' random streams part at the first photon).
#[test]
fn a_photon_pass_ends_the_same_with_and_without_the_shell() {
    let scene = sunset_sea("");
    let emitted = 40_000u64;
    let ((with, st_with), (without, st_without)) = with_and_without(&scene, emitted, 11);
    assert!(st_with.shell_descents > emitted / 2, "the shell was used: {}", st_with.shell_descents);
    assert_shares_agree(
        &[
            ("absorbed in the air", st_with.absorbed_medium_w, st_without.absorbed_medium_w),
            ("absorbed at the sea", st_with.absorbed_surface_w, st_without.absorbed_surface_w),
            ("escaped", st_with.escaped_w, st_without.escaped_w),
        ],
        st_with.power_per_photon_w * emitted as f64,
        emitted,
    );
    let (a, b) = (with.surface.len() as f64 / emitted as f64, without.surface.len() as f64 / emitted as f64);
    let sigma = ((a * (1.0 - a) + b * (1.0 - b)) / emitted as f64).sqrt();
    assert!((a - b).abs() < 4.0 * sigma, "stored: {a} with, {b} without");
}

/// Air that is the world medium has no top sphere; its shell's top is then its atmosphere's
/// (86 km in `mirage_hot_road`), open to the world above, where n = 1 and, the air being clear,
/// nothing absorbs. The bottom is 1 m above the farthest corner of the highest shape's box from
/// the Earth's centre: the skyline's, 120 m up 15 km away, R + 120 + 15 045²/(2R) = R + 137.8 m
/// (its farthest corner), so 138.8 m less the box's own offsets — between 130 and 140 m.
/// Absorbing air whose density is uniform would absorb above the top too: no shell there.
#[test]
fn world_air_has_a_shell_open_above_its_atmospheres_top() {
    let scene = mirage_with(&[]);
    let prop = Propagator::new(&scene.world, scene.curved()).with_layered_shell((400.0, 700.0));
    let shell = prop.layered_shell().expect("a shell");
    assert_eq!(shell.medium(), air(&scene));
    let (low, top) = shell.heights_m();
    assert!((130.0..140.0).contains(&low) && (top - 86_000.0).abs() < 1e-6, "{low} {top}");
    let absorbing = mirage_with(&[("sigma_a = 0.0\nsigma_s = 0.0", "sigma_a = 1e-6\nsigma_s = 0.0")]);
    let prop = Propagator::new(&absorbing.world, absorbing.curved()).with_layered_shell((400.0, 700.0));
    assert!(prop.layered_shell().is_none(), "uniform absorbing air above the top");
}

/// `enter` moves a path from above an open top straight onto the top sphere, 1 µm inside it,
/// on its own line; a path that starts inside the top, leaves it, or misses it is left alone.
#[test]
fn a_path_from_above_enters_the_open_top_on_its_own_line() {
    let scene = mirage_with(&[]);
    let prop = Propagator::new(&scene.world, scene.curved()).with_layered_shell((400.0, 700.0));
    let shell = prop.layered_shell().expect("a shell");
    let centre = DVec3::new(0.0, -R, 0.0);
    let r_top = R + 86_000.0;
    for (from, dir) in [
        (DVec3::new(3.0e5, 2.0e6, -1.0e5), DVec3::new(-0.1, -1.0, 0.05)),
        (DVec3::new(0.0, 1.0e7, 0.0), DVec3::new(0.0, -1.0, 0.0)),
        // Grazing: aimed 1 km inside the top's edge.
        (DVec3::new(-5.0e6, 86_000.0 - 1000.0, 0.0), DVec3::new(1.0, 0.0, 0.0)),
    ] {
        let dir = dir.normalize();
        let p = shell.enter(from, dir).unwrap_or_else(|| panic!("{from} {dir}: no entry"));
        let off_line = (p - from).cross(dir).length();
        let r = (p - centre).length();
        assert!((r - (r_top - 1e-6)).abs() < 1e-7, "{from}: r − r_top = {}", r - r_top);
        // Off the line by the radial nudge at most (all of it for a grazing path).
        assert!(off_line < 1.001e-6 && (p - from).dot(dir) > 0.0, "{from}: {off_line} m off its line");
    }
    let up = DVec3::Y;
    assert!(shell.enter(DVec3::new(0.0, 1000.0, 0.0), -up).is_none(), "starts inside the top");
    assert!(shell.enter(DVec3::new(0.0, 2.0e5, 0.0), up).is_none(), "going away");
    assert!(shell.enter(DVec3::new(-5.0e6, 2.0e5, 0.0), DVec3::X).is_none(), "passes above the top");
}

/// The photon pass of `mirage_hot_road` (sun and sky photons starting far above the air) ends
/// the same with and without the open shell: the shares of the emitted power absorbed at the
/// surfaces and escaped within their binomial noise (4 σ), the photons stored per photon emitted
/// within 4 σ of a count whose variance is at most its mean, and where and how the sun's photons
/// first land — the mean of each coordinate of their positions and directions — within 4
/// standard errors of the difference (±6.4 m in x: entry points moved 10 m sideways fail it);
/// every photon that reaches the top crosses it in one move.
#[test]
fn a_photon_pass_from_above_an_open_top_ends_the_same_with_and_without_it() {
    let scene = mirage_with(&[]);
    let emitted = 20_000u64;
    let ((with, st_with), (without, st_without)) = with_and_without(&scene, emitted, 5);
    assert!(st_with.shell_descents > emitted * 9 / 10, "the shell was used: {}", st_with.shell_descents);
    assert_shares_agree(
        &[
            ("absorbed at surfaces", st_with.absorbed_surface_w, st_without.absorbed_surface_w),
            ("escaped", st_with.escaped_w, st_without.escaped_w),
        ],
        st_with.power_per_photon_w * emitted as f64,
        emitted,
    );
    let (a, b) = (with.surface.len() as f64 / emitted as f64, without.surface.len() as f64 / emitted as f64);
    assert!((a - b).abs() < 4.0 * ((a + b) / emitted as f64).sqrt(), "stored: {a} with, {b} without");
    let coordinates: [(&str, Coordinate); 5] = [
        ("x", |p| p.position.x),
        ("z", |p| p.position.z),
        ("dir x", |p| p.dir.x),
        ("dir y", |p| p.dir.y),
        ("dir z", |p| p.dir.z),
    ];
    for (name, c) in coordinates {
        // The sun's photons where they first land (at its elevation of 40°, on the road or the
        // skyline): their spread is the targets', where the sky's and the reflected ones' is
        // kilometres.
        let sun_elevation = 40f64.to_radians().sin();
        let on_road = |p: &&PhotonRecord| p.path == PhotonPath::Direct && (p.dir.y + sun_elevation).abs() < 1e-3;
        let stats = |ps: &[PhotonRecord]| {
            let xs: Vec<f64> = ps.iter().filter(on_road).map(c).collect();
            let n = xs.len() as f64;
            let mean = xs.iter().sum::<f64>() / n;
            (mean, xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0) / n)
        };
        let ((ma, va), (mb, vb)) = (stats(&with.surface), stats(&without.surface));
        assert!((ma - mb).abs() < 4.0 * (va + vb).sqrt(), "{name}: {ma} with, {mb} without (se {})", (va + vb).sqrt());
    }
}

/// Paths from `mirage_hot_road`'s camera (10 m up) that climb out of its clear air — grazing at
/// 0.05° to nearly straight up, at 400, 550 and 700 nm — escape in the direction the same path
/// stepped through the whole atmosphere escapes in, when they leave the shell (136 m to 86 km)
/// upward in one move by Bouguer's invariant; the propagator counts each such ascent. Paths
/// that meet the skyline on the way are the same event either way. Grazing paths that meet the
/// bottom within 5·10⁻⁶ rad of tangent, or after a perigee just under it, leave in one move too,
/// in unit, finite directions within the same bound.
#[test]
fn paths_that_climb_out_escape_where_the_stepped_paths_do() {
    // The angle between two unit vectors, accurate at small angles (atan2 of |a × b| and a·b).
    let angle_between = |a: DVec3, b: DVec3| a.cross(b).length().atan2(a.dot(b));
    let scene = mirage_with(&[]);
    let stepped = Propagator::new(&scene.world, scene.curved());
    let quick = Propagator::new(&scene.world, scene.curved()).with_upward_shell((400.0, 700.0), false);
    assert!(quick.layered_shell().is_some() && stepped.layered_shell().is_none());
    let (mut worst, mut escapes) = (0.0f64, 0u64);
    for elevation_deg in [0.05, 0.2, 0.5, 1.0, 3.0, 10.0, 45.0, 89.9] {
        for azimuth_deg in [0.0, 3.0, 100.0, 200.0] {
            for lambda in [400.0, 550.0, 700.0] {
                let (e, a) = (f64::to_radians(elevation_deg), f64::to_radians(azimuth_deg));
                let dir = DVec3::new(e.cos() * a.sin(), e.sin(), -e.cos() * a.cos());
                let state = RayState {
                    position: DVec3::new(0.0, 10.0, 0.0),
                    dir,
                    wavelength_nm: Some(lambda),
                    medium: Some(air(&scene)),
                };
                match (stepped.next_event(&state), quick.next_event(&state)) {
                    (Event::Escape { dir: d0 }, Event::Escape { dir: d1 }) => {
                        let angle = angle_between(d0, d1);
                        worst = worst.max(angle);
                        escapes += 1;
                        assert!(angle < 1e-7, "{elevation_deg}°, {azimuth_deg}°, {lambda} nm: {angle} rad apart");
                    }
                    (Event::Surface { hit: h0, .. }, Event::Surface { hit: h1, .. }) => {
                        assert_eq!(h0.prim, h1.prim);
                        assert!((h0.point - h1.point).length() < 1e-6);
                    }
                    other => panic!("{elevation_deg}°, {azimuth_deg}°, {lambda} nm: {other:?}"),
                }
            }
        }
    }
    assert!(escapes > 60, "{escapes} escapes");
    assert_eq!(quick.work.totals().shell_ascents, escapes);
    eprintln!("{escapes} escapes; largest angle between the directions {worst:.2e} rad");
    // Grazing: level or slightly down from just under the bottom, so the path meets it within
    // 5·10⁻⁶ rad of tangent (10⁻⁴ m under it, level: cos z ≈ √(2·10⁻⁴/R)), or after a perigee.
    let (h_low, _) = quick.layered_shell().expect("a shell").heights_m();
    for (depth_m, elevation_rad) in [(1e-4, 0.0), (1e-2, 0.0), (1.0, 0.0), (1e-3, -1e-6), (0.5, -1e-4)] {
        let y = h_low - depth_m;
        let state = RayState {
            position: DVec3::new(0.0, y, 0.0),
            dir: DVec3::new(0.0, elevation_rad, -1.0).normalize(),
            wavelength_nm: Some(550.0),
            medium: Some(air(&scene)),
        };
        match (stepped.next_event(&state), quick.next_event(&state)) {
            (Event::Escape { dir: d0 }, Event::Escape { dir: d1 }) => {
                let angle = angle_between(d0, d1);
                eprintln!("grazing, {depth_m} m under the bottom, {elevation_rad} rad: {angle:.2e} rad apart");
                assert!(d1.is_finite() && (d1.length() - 1.0).abs() < 1e-12, "{depth_m} m: {d1}");
                assert!(angle < 1e-7, "{depth_m} m under the bottom, {elevation_rad} rad: {angle} rad apart");
            }
            other => panic!("{depth_m} m under the bottom, {elevation_rad} rad: {other:?}"),
        }
    }
    assert_eq!(quick.work.totals().shell_ascents, escapes + 5, "each grazing path left in one move");
}

/// Absorbing air under a shape's top (`sunset_sea`: the camera 2 m up, 1 m above the shell's
/// bottom; paths reflected off the sea start under it): paths toward the sky at 0.1°–80°, at 400,
/// 550 and 700 nm, leave the air in one move when the visitors take columns, and meet its top
/// sphere where the same paths stepped at rtol 10⁻¹² with chords within 1 mm of the arc meet
/// it — the point within 2·rtol·r_top (13 mm at the scene's rtol 10⁻⁹), the direction within
/// 10⁻⁷ rad — having handed the visitor the same density column within 10⁻⁶ of it. Without columns (a photon pass's visitors) absorbing
/// air is stepped as before.
#[test]
fn absorbing_air_is_left_upward_in_one_move_with_its_column() {
    let scene = sunset_sea("");
    // The oracle: the same paths stepped at rtol 10⁻¹² with chords within 1 mm of the arc.
    let fine = sunset_sea_with(
        "",
        &[("arc_tolerance_m = 0.5", "arc_tolerance_m = 0.001\node_rtol = 1e-12\node_atol = 1e-12")],
    );
    let id = air(&scene);
    let m = &scene.world.media[id as usize];
    let stepped = Propagator::new(&fine.world, fine.curved());
    let quick = Propagator::new(&scene.world, scene.curved()).with_upward_shell((400.0, 700.0), true);
    let refused = Propagator::new(&scene.world, scene.curved()).with_upward_shell((400.0, 700.0), false);
    assert!(quick.layered_shell().is_some() && refused.layered_shell().is_none());
    let rtol = scene.curved().expect("curved").rtol;
    let (mut worst_p, mut worst_d, mut worst_c, mut ascents) = (0.0f64, 0.0f64, 0.0f64, 0u64);
    for start_y in [2.0, 1e-3] {
        for elevation_deg in [0.1, 0.3, 1.0, 5.0, 20.0, 80.0] {
            for lambda in [400.0, 550.0, 700.0] {
                let e = f64::to_radians(elevation_deg);
                let state = RayState {
                    position: DVec3::new(0.0, start_y, 0.0),
                    dir: DVec3::new(0.0, e.sin(), -e.cos()),
                    wavelength_nm: Some(lambda),
                    medium: Some(id),
                };
                let follow = |prop: &Propagator| {
                    let mut column = 0.0;
                    let event = prop.next_event_with(&state, &mut |c| {
                        column += c.column_m.unwrap_or_else(|| {
                            m.density.integral_tabulated(c.origin, c.dir, c.length).expect("an exact integral")
                        });
                        None
                    });
                    (event, column)
                };
                let ((e0, c0), (e1, c1)) = (follow(&stepped), follow(&quick));
                let (Event::Surface { hit: h0, dir: d0, .. }, Event::Surface { hit: h1, dir: d1, .. }) = (e0, e1)
                else {
                    panic!("{start_y} m, {elevation_deg}°, {lambda} nm: {e0:?} / {e1:?}");
                };
                assert_eq!(h0.prim, h1.prim, "the top sphere");
                let dd = d0.cross(d1).length().atan2(d0.dot(d1));
                let (dp, dc) = ((h0.point - h1.point).length(), (c1 - c0).abs() / c0);
                (worst_p, worst_d, worst_c) = (worst_p.max(dp), worst_d.max(dd), worst_c.max(dc));
                assert!(
                    dp < 2.0 * rtol * (R + 90_000.0) && dd < 1e-7 && dc < 1e-6,
                    "{start_y} m, {elevation_deg}°, {lambda} nm: {dp} m, {dd} rad, column {dc:e}"
                );
                ascents += 1;
            }
        }
    }
    assert_eq!(quick.work.totals().shell_ascents, ascents);
    assert_eq!(refused.work.totals().shell_ascents, 0);
    eprintln!("largest differences: point {worst_p:.2e} m, direction {worst_d:.2e} rad, column {worst_c:.2e}");
}
