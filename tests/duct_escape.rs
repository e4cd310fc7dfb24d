//! The performance cliff of issue 15: `examples/mirage_superior.toml` without its "shore" box.
//! Rays trapped in the inversion's duct used to circle the Earth (twice, ~8·10⁷ m and ~5·10⁴
//! integrator steps for one ray) before meeting a surface again. Now a path trapped past all
//! finite geometry escapes after one period of its radial motion (`morgana::raypath::far`).
//!
//! The bound asserted comes from the scene's geometry: with the shore in place those rays end on
//! it, 40 km away; without it they go on past the cone of finite geometry (which ends at the
//! coast's far side, 40.05 km, widened by 1 %) and are recognised as trapped within two periods
//! of the duct's oscillation. That period is about 40 km (`morgana trace` of the +0.037° ray:
//! successive lowest points 36–44 km apart), so their paths are at most ≈ 40.5 + 2·44 ≈ 129 km,
//! 3.2 times the 40 km to the shore, and their integrator steps at most 4 times as many as on
//! the way to the shore (the step size in the duct does not depend on the distance travelled).
//! Every ray that meets something other than the shore meets the same surface at the same
//! point in both scenes (the same image where rays hit something).
//!
//!   cargo test --release --test duct_escape

use glam::DVec3;
use morgana::raypath::trace::{End, Limits, Traced, trace};
use morgana::scene::{Scene, load_scene_str};
use std::path::Path;

fn load(text: &str) -> Scene {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    match load_scene_str(text, &dir.join("mirage_superior.toml"), &dir, "mirage_superior") {
        Ok(s) => s,
        Err(e) => panic!("scene does not load: {e}"),
    }
}

/// The shipped scene and the same without its "shore" box.
fn scenes() -> (Scene, Scene) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/mirage_superior.toml");
    let text = std::fs::read_to_string(&path).expect("examples/mirage_superior.toml is readable");
    let start = text.find("[[shape]]\nname = \"shore\"").expect("the scene has a shore box");
    let end = start + 9 + text[start + 9..].find("[[shape]]").expect("a shape follows the shore");
    let without = format!("{}{}", &text[..start], &text[end..]);
    (load(&text), load(&without))
}

fn follow(scene: &Scene, elevation_deg: f64, azimuth_deg: f64) -> Traced {
    let (e, a) = (elevation_deg.to_radians(), azimuth_deg.to_radians());
    let dir = DVec3::new(e.cos() * a.sin(), e.sin(), -e.cos() * a.cos());
    let limits = Limits { events: 1, length_m: 1e8 };
    trace(&scene.world, scene.curved(), DVec3::new(0.0, 10.0, 0.0), dir, 550.0, limits)
}

fn end_point(t: &Traced) -> DVec3 {
    t.points.last().expect("a traced path has points").position
}

#[test]
fn rays_trapped_past_the_geometry_escape_within_a_bound_set_by_the_geometry() {
    let (shore, open) = scenes();
    let (mut on_shore, mut trapped) = (0, 0);
    for azimuth_deg in [0.0, 0.2] {
        for i in 0..=80 {
            let elevation_deg = -0.12 + 0.005 * i as f64;
            let (a, b) = (follow(&shore, elevation_deg, azimuth_deg), follow(&open, elevation_deg, azimuth_deg));
            let at = format!("elevation {elevation_deg:.3}°, azimuth {azimuth_deg}°");
            match &a.end {
                End::Surface(name) if name == "shape \"shore\"" => {
                    on_shore += 1;
                    let (sa, sb) = (a.work.ode_steps + a.work.ode_rejected, b.work.ode_steps + b.work.ode_rejected);
                    assert!(sb <= 4 * sa, "{at}: {sb} integrator steps without the shore, {sa} to the shore");
                    if matches!(b.end, End::Escape(_)) {
                        trapped += b.work.trapped;
                    }
                }
                End::Surface(_) | End::Escape(_) => {
                    assert_eq!(a.end.clone(), b.end.clone(), "{at}: the ray ends differently without the shore");
                    if let (End::Escape(da), End::Escape(db)) = (&a.end, &b.end) {
                        assert!((*da - *db).length() < 1e-9, "{at}: escapes along {da} and {db}");
                    } else {
                        let d = (end_point(&a) - end_point(&b)).length();
                        assert!(d < 1e-3, "{at}: the hit points differ by {d} m");
                    }
                }
                other => panic!("{at}: the ray ends as {other:?}"),
            }
        }
    }
    assert!(on_shore >= 10, "only {on_shore} rays reach the shore: the test no longer probes the duct");
    assert!(trapped >= 10, "only {trapped} rays were recognised as trapped");
}
