//! Numerically hard cases of curved light paths, followed through the propagator on small
//! scenes: grazing rays over the spherical Earth, ducting for 1000 km, a 10 K-per-centimetre hot
//! road, a ray from space tangent to the Earth, exactly tangential hits, zero-length steps, rays
//! starting on a region boundary, and impossible atmospheres. Each test states what it expects.

mod common;

use common::{scene, scene_error};
use glam::DVec3;
use morgana::atmosphere::refraction::{ARCSEC_PER_RAD, Outcome, Settings, Tracer};
use morgana::atmosphere::{Atmosphere, EARTH_RADIUS_M, Earth};
use morgana::ode::{Integrator, Method, OdeState};
use morgana::photon::PassSettings;
use morgana::photon::{MapKind, shoot};
use morgana::raypath::{Chord, Event, Propagator, RayState};
use morgana::scene::Scene;
use std::path::PathBuf;

const R: f64 = EARTH_RADIUS_M;
const LAMBDA_NM: f64 = 550.0;

/// The sea: a sphere of the Earth's radius with its top at the origin.
fn sea(material: &str) -> String {
    format!("[[shape]]\ntype = \"sphere\"\ncenter = [0.0, {}, 0.0]\nradius = {R}\nmaterial = \"{material}\"\n", -R)
}

/// A scene in air of index field `index` with `shapes`, `[integrator]` lines and `[world]` lines.
fn air_scene(index: &str, integrator: &str, world: &str, shapes: &str) -> String {
    format!(
        r#"
[camera]
position = [0.0, 2.0, 0.0]
look_at = [1.0, 2.0, 0.0]
fov_deg = 10.0
width = 4
height = 4

[output]
bands = 1
min_nm = 545.0
max_nm = 555.0

[integrator]
{integrator}

[world]
medium = "air"
{world}

[[medium]]
name = "air"
sigma_a = 0.0
sigma_s = 0.0
index = {index}

[[material]]
name = "grey"
type = "lambertian"
reflectance = 0.5

[[material]]
name = "mirror"
type = "mirror"
reflectance = 1.0

{shapes}

[[light]]
type = "point"
position = [0.0, 50.0, 0.0]
spectrum = 1.0
power_w = 1.0
"#
    )
}

/// A directory for this test's files.
fn temp_dir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("morgana-curved-hard-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

/// Writes an atmosphere file and returns the `index` value that loads it.
fn atmosphere_index(dir: &std::path::Path, name: &str, toml: &str) -> String {
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, toml).expect("write atmosphere");
    format!("{{ type = \"atmosphere\", file = \"{}\" }}", path.display())
}

fn start(p: DVec3, d: DVec3) -> RayState {
    RayState { position: p, dir: d.normalize(), wavelength_nm: Some(LAMBDA_NM), medium: Some(0) }
}

/// A unit vector in the x–y plane at `elevation_deg` above +x.
fn at_elevation(elevation_deg: f64) -> DVec3 {
    let e = elevation_deg.to_radians();
    DVec3::new(e.cos(), e.sin(), 0.0)
}

/// Distance along the ground (radius R) from the origin's foot to below `p`.
fn ground_distance(p: DVec3) -> f64 {
    let (a, b) = (DVec3::Y, p - DVec3::new(0.0, -R, 0.0));
    R * a.cross(b).length().atan2(a.dot(b))
}

fn height(p: DVec3) -> f64 {
    Earth::standard().height(p)
}

fn index_of(s: &Scene) -> &morgana::media::refractive_index::IndexField {
    s.world.media[0].index.as_ref().expect("index field")
}

#[test]
fn grazing_rays_meet_the_sea_where_geometry_and_refraction_put_them() {
    // USA76 over the spherical sea. From 2 m at 0.1° down, a straight ray meets the sphere at
    // d = R(θ − √(θ² − 2h/R)) ≈ 1210 m; the air bends it down with curvature κ = |∇n|/n (k ≈ 0.17),
    // as if the Earth had radius R' = 1/(1/R − κ): d = R'(θ − √(θ² − 2h/R')), about 12 m nearer.
    // Expected: the hit within 5 cm of that (the parabolic approximation and the change of κ over
    // 2 m are millimetres). A level ray from 2 m escapes to space, leaving at the true altitude the
    // refraction tracer finds for that observer (−33′), within 0.01″.
    let s = scene(&air_scene(
        r#"{ type = "atmosphere", name = "usa76" }"#,
        "ode_rtol = 1e-12\node_atol = 1e-12",
        "",
        &sea("grey"),
    ));
    let prop = Propagator::new(&s.world, s.curved());
    let p0 = DVec3::new(0.0, 2.0, 0.0);
    let theta = 0.1f64.to_radians();
    let Event::Surface { hit, .. } = prop.next_event(&start(p0, at_elevation(-0.1))) else {
        panic!("must meet the sea")
    };
    let (n, g) = index_of(&s).n_grad(LAMBDA_NM, p0);
    let r_eff = 1.0 / (1.0 / R - g.length() / n);
    let bent = r_eff * (theta - (theta * theta - 4.0 / r_eff).sqrt());
    let straight = R * (theta - (theta * theta - 4.0 / R).sqrt());
    let d = ground_distance(hit.point);
    eprintln!("−0.1° from 2 m meets the sea at {d:.3} m (refracted estimate {bent:.3} m, straight {straight:.3} m)");
    assert!((d - bent).abs() < 0.05 && (d - straight).abs() > 10.0, "d = {d}, bent {bent}, straight {straight}");
    assert!(height(hit.point).abs() < 1e-6, "on the sea: {}", hit.point);

    let Event::Escape { dir } = prop.next_event(&start(p0, DVec3::X)) else { panic!("a level ray goes on") };
    let atm = Atmosphere::builtin("usa76").expect("usa76");
    let tracer = Tracer::new(&atm, LAMBDA_NM, 2.0, Settings::default()).expect("tracer");
    let want = tracer.trace(0.0).expect("trace").true_altitude_rad().expect("escapes");
    let got = dir.y.atan2(dir.x);
    eprintln!("level from 2 m leaves at {:.4}′ (tracer {:.4}′)", got.to_degrees() * 60.0, want.to_degrees() * 60.0);
    assert!((got - want).abs() * ARCSEC_PER_RAD < 0.01, "{got} vs {want}");
    let w = prop.work.totals();
    assert!(w.lost == 0 && w.ode_steps < 2000, "{w:?}");
}

/// The apex of the arc leaving `state` (upward or level) in scene `s`'s air: the height where its
/// vertical velocity v·û (û the local vertical) goes from positive to negative, located by
/// bisection on the dense output of an integration with the scene's own method. Chord ends sample
/// a path only where steps end, and a step in clear air away from geometry is one chord, so they
/// can miss an apex by the arc's drop over half a step; the dense output holds the whole arc.
fn apex_height(s: &Scene, state: &RayState) -> f64 {
    let field = |p: DVec3| index_of(s).n_grad(LAMBDA_NM, p);
    let climb = |r: DVec3, d: DVec3| d.dot((r - DVec3::new(0.0, -R, 0.0)).normalize());
    let rate = climb(state.position, state.dir);
    assert!(rate >= 0.0, "the arc starts descending ({rate})");
    if rate == 0.0 {
        return height(state.position);
    }
    let mut ode = Integrator::new(s.curved().expect("curved paths").method).expect("method");
    let mut y = OdeState::launch(&field, state.position, state.dir).expect("launch");
    for _ in 0..100_000 {
        let step = ode.step(&field, &mut y, 1.0e5).expect("step");
        let at = |t: f64| climb(step.position_at(t), step.direction_at(t));
        if at(1.0) > 0.0 {
            continue;
        }
        let (mut a, mut b) = (0.0, 1.0);
        for _ in 0..60 {
            let m = 0.5 * (a + b);
            if at(m) > 0.0 { a = m } else { b = m }
        }
        return height(step.position_at(0.5 * (a + b)));
    }
    panic!("no apex within 100 000 steps")
}

/// The lowest point of the arc leaving `state` (descending or level) in scene `s`'s air: the
/// height where its vertical velocity goes from negative to positive, located as in
/// [`apex_height`] on the dense output.
fn perigee_height(s: &Scene, state: &RayState) -> f64 {
    let field = |p: DVec3| index_of(s).n_grad(LAMBDA_NM, p);
    let climb = |r: DVec3, d: DVec3| d.dot((r - DVec3::new(0.0, -R, 0.0)).normalize());
    let rate = climb(state.position, state.dir);
    assert!(rate <= 0.0, "the arc starts climbing ({rate})");
    if rate == 0.0 {
        return height(state.position);
    }
    let mut ode = Integrator::new(s.curved().expect("curved paths").method).expect("method");
    let mut y = OdeState::launch(&field, state.position, state.dir).expect("launch");
    for _ in 0..100_000 {
        let step = ode.step(&field, &mut y, 1.0e5).expect("step");
        let at = |t: f64| climb(step.position_at(t), step.direction_at(t));
        if at(1.0) < 0.0 {
            continue;
        }
        let (mut a, mut b) = (0.0, 1.0);
        for _ in 0..60 {
            let m = 0.5 * (a + b);
            if at(m) < 0.0 { a = m } else { b = m }
        }
        return height(step.position_at(0.5 * (a + b)));
    }
    panic!("no lowest point within 100 000 steps")
}

#[test]
fn a_ray_grazing_the_sea_in_a_surface_duct_bounces_for_1000_km() {
    // A duct at the sea: an inversion of 10 K centred at 10 m, w = 5 m, so dT/dz = 0.21 K/m at
    // the sea and 0.5 K/m at 10 m, above the 0.129 K/m at which a level ray curves with the Earth.
    // A ray launched level at 5 m is at the top of its arc (Bouguer: n·r·cos e is conserved, so
    // it can never rise above a level start where it bends down faster than the Earth curves). It
    // comes down to the mirror sea, reflects (a reflection about the radial normal keeps cos e),
    // and repeats. Expected, event by event for 1000 km: the invariant n·r·cos e the same at every
    // bounce (to 10⁻⁹ of it, the scene's rtol), so every bounce at the same grazing angle (the
    // angle, 1.2 × 10⁻³ rad, is ill-conditioned in the invariant: δe/e = (δC/C)/e², so only to
    // 10⁻³), every apex at 5 m (to 1 mm), no lost path, no NaN, a bounded count of steps.
    let dir = temp_dir("duct");
    let index = atmosphere_index(
        &dir,
        "surface_duct",
        "base = \"usa76\"\n[[edit]]\ntype = \"inversion\"\ndT_k = 10.0\nheight_m = 10.0\nthickness_m = 5.0\n",
    );
    let s = scene(&air_scene(&index, "", "", &sea("mirror")));
    let prop = Propagator::new(&s.world, s.curved());
    let mut state = start(DVec3::new(0.0, 5.0, 0.0), DVec3::X);
    let (mut bounces, mut angles, mut invariants, mut top) = (0, Vec::new(), Vec::new(), f64::NEG_INFINITY);
    let mut apexes = Vec::new();
    loop {
        let mut visit = |c: &Chord| {
            let h = height(c.origin + c.length * c.dir);
            assert!(h.is_finite(), "chord {c:?}");
            top = top.max(h);
            None
        };
        let event = prop.next_event_with(&state, &mut visit);
        let Event::Surface { hit, dir: d, .. } = event else { panic!("after {bounces} bounces: {event:?}") };
        apexes.push(apex_height(&s, &state));
        let sin_e = -d.dot(hit.normal);
        angles.push(sin_e.asin());
        let r = (hit.point - DVec3::new(0.0, -R, 0.0)).length();
        invariants.push(index_of(&s).n(LAMBDA_NM, hit.point) * r * (1.0 - sin_e * sin_e).sqrt());
        bounces += 1;
        if ground_distance(hit.point) >= 1.0e6 {
            break;
        }
        assert!(bounces < 1000, "too many bounces");
        let out = d - 2.0 * d.dot(hit.normal) * hit.normal;
        state = prop.leave(&hit, out, Some(LAMBDA_NM), Some(0));
    }
    let w = prop.work.totals();
    eprintln!(
        "surface duct: {bounces} bounces in 1000 km at {:.5}° grazing, apexes {:.4}–{:.4} m (highest chord end {top:.4} m), {} ODE steps, {} chords",
        angles[0].to_degrees(),
        apexes.iter().copied().fold(f64::INFINITY, f64::min),
        apexes.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        w.ode_steps,
        w.chords
    );
    let drift = |v: &[f64]| v.iter().map(|a| (a / v[0] - 1.0).abs()).fold(0.0, f64::max);
    let (dc, de) = (drift(&invariants), drift(&angles));
    eprintln!("invariant n·r·cos e drifts by {dc:e}, grazing angle by {de:e} (relative)");
    assert!(dc < 1e-9, "the invariant drifts by {dc} of the first");
    assert!(de < 1e-3, "grazing angles drift by {de} of the first");
    // The first arc starts at its apex; later apexes are between bounces, where the vertical
    // velocity of the arc leaving each bounce changes sign (located on dense output:
    // `apex_height`). Chord ends lie on the path, so none may be above the apex. An invariant
    // off by δC/C moves the apex by (δC/C)·R/|1 − k| with k ≈ 1.6 in the duct: 10⁻⁹ of it is
    // 1 cm.
    for a in &apexes {
        assert!((a - 5.0).abs() < 1e-2, "apex {a} m");
    }
    assert!(top < 5.0 + 1e-2, "a chord end at {top} m, above the apex");
    assert!(bounces > 10 && w.lost == 0 && w.ode_steps < 200_000, "{bounces} bounces, {w:?}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_ray_in_an_elevated_duct_oscillates_between_turning_points_for_1000_km() {
    // The shipped inversion atmosphere (10 K at 30 m over 2 °C air): launched level at 2 m the ray
    // is at its lowest point; it climbs into the layer, turns down below 30 m, comes back to 2 m
    // level, and so on — both turning points inside the air, the sea never touched. Bouguer's
    // invariant puts the upper turning point where n(h)(R + h) = n(2 m)(R + 2 m), found here by
    // bisection on the field. Expected: the first event is a wall 1000 km away, hit between the
    // turning points; the path's lowest and highest chord ends within 1 mm of 2 m and of the
    // upper root; no lost path; bounded steps.
    let phi = 1.0e6 / R;
    let radial = DVec3::new(phi.sin(), phi.cos(), 0.0);
    let centre = DVec3::new(0.0, -R, 0.0);
    let origin = centre + (R - 1000.0) * radial - DVec3::new(0.0, 0.0, 1000.0);
    let u = 2000.0 * radial;
    let wall = format!(
        "[[shape]]\ntype = \"quad\"\norigin = [{}, {}, {}]\nu = [{}, {}, 0.0]\nv = [0.0, 0.0, 2000.0]\nmaterial = \"grey\"\n",
        origin.x, origin.y, origin.z, u.x, u.y
    );
    let s = scene(&air_scene(
        r#"{ type = "atmosphere", name = "inversion" }"#,
        "",
        "",
        &format!("{}\n{wall}", sea("grey")),
    ));
    let field = index_of(&s);
    let nr = |h: f64| field.n(LAMBDA_NM, DVec3::new(0.0, h, 0.0)) * (R + h);
    let c = nr(2.0);
    let (mut lo, mut hi) = (10.0, 40.0);
    for _ in 0..80 {
        let m = 0.5 * (lo + hi);
        if nr(m) < c { hi = m } else { lo = m }
    }
    let upper = 0.5 * (lo + hi);
    let prop = Propagator::new(&s.world, s.curved());
    let (mut h_min, mut h_max) = (f64::INFINITY, f64::NEG_INFINITY);
    let mut visit = |ch: &Chord| {
        let h = height(ch.origin + ch.length * ch.dir);
        h_min = h_min.min(h);
        h_max = h_max.max(h);
        None
    };
    let event = prop.next_event_with(&start(DVec3::new(0.0, 2.0, 0.0), DVec3::X), &mut visit);
    let Event::Surface { hit, .. } = event else { panic!("{event:?}") };
    let w = prop.work.totals();
    eprintln!(
        "elevated duct: wall at {:.1} km hit at {:.3} m; path between {h_min:.4} m and {h_max:.4} m (Bouguer {upper:.4} m); {} steps",
        ground_distance(hit.point) / 1e3,
        height(hit.point),
        w.ode_steps
    );
    assert!((ground_distance(hit.point) - 1.0e6).abs() < 1.0, "the wall: {}", hit.point);
    assert!((2.0 - 1e-3..upper + 1e-3).contains(&height(hit.point)));
    assert!((h_min - 2.0).abs() < 1e-3 && (h_max - upper).abs() < 1e-3, "{h_min} … {h_max}, Bouguer {upper}");
    assert!(w.lost == 0 && w.ode_steps < 50_000, "{w:?}");
}

/// A hot road on flat ground: USA76 air heated by 10 K at the road, decaying as exp(−z/3 mm)
/// (10 K over a centimetre: −3300 K/m at the road).
fn hot_road_index(dir: &std::path::Path) -> String {
    atmosphere_index(
        dir,
        "steep_road",
        "base = \"usa76\"\nearth = \"flat\"\n[[edit]]\ntype = \"hot_surface\"\ndT_k = 10.0\nz0_m = 0.003\n",
    )
}

#[test]
fn a_ray_skimming_a_road_ten_kelvin_per_centimetre_hot_turns_up_inside_the_air() {
    // From 2 cm, 0.1° down: the layer's n rises by Δn ≈ (n − 1)·10 K/T ≈ 10⁻⁵ toward the air
    // above, so rays flatter than √(2Δn) ≈ 0.25° turn back (total internal reflection inside the
    // gradient). Flat layers keep n·cos e (Bouguer), so the lowest point is where
    // n(y) = n(2 cm)·cos 0.1° — about 5 mm up, found by bisection on the field — and the ray
    // leaves at the height of its start climbing at 0.1°. Expected: lowest chord end within
    // 0.2 mm of it (arc tolerance 0.1 mm), arrival at the wall (x = 30 m) climbing at the angle
    // Bouguer gives for the arrival height (to 10⁻⁶ rad), no NaN, bounded steps. A ray at 0.5°
    // (beyond the critical angle) reaches the road.
    let dir = temp_dir("road");
    let road = "[[shape]]\ntype = \"quad\"\norigin = [-1.0, 0.0, -10.0]\nu = [0.0, 0.0, 20.0]\nv = [100.0, 0.0, 0.0]\nmaterial = \"grey\"\n";
    let wall = "[[shape]]\ntype = \"quad\"\norigin = [30.0, -1.0, -10.0]\nu = [0.0, 5.0, 0.0]\nv = [0.0, 0.0, 20.0]\nmaterial = \"grey\"\n";
    let s = scene(&air_scene(&hot_road_index(&dir), "", "", &format!("{road}\n{wall}")));
    let field = index_of(&s);
    let n_at = |y: f64| field.n(LAMBDA_NM, DVec3::new(0.0, y, 0.0));
    let (y0, e0) = (0.02, 0.1f64.to_radians());
    let invariant = n_at(y0) * e0.cos();
    let (mut lo, mut hi) = (0.0, y0);
    for _ in 0..80 {
        let m = 0.5 * (lo + hi);
        if n_at(m) < invariant { lo = m } else { hi = m }
    }
    let y_turn = 0.5 * (lo + hi);
    let prop = Propagator::new(&s.world, s.curved());
    let mut y_min = f64::INFINITY;
    let mut visit = |c: &Chord| {
        let end = c.origin + c.length * c.dir;
        assert!(end.is_finite() && c.dir.is_finite(), "{c:?}");
        y_min = y_min.min(end.y);
        None
    };
    let event = prop.next_event_with(&start(DVec3::new(0.0, y0, 0.0), at_elevation(-0.1)), &mut visit);
    let Event::Surface { hit, dir: arrive, .. } = event else { panic!("{event:?}") };
    let w = prop.work.totals();
    let e_end = (invariant / n_at(hit.point.y)).acos();
    eprintln!(
        "hot road: turns at {:.3} mm (Bouguer {:.3} mm), reaches the wall at y = {:.4} m climbing {:.5}° (Bouguer {:.5}°); {} steps",
        y_min * 1e3,
        y_turn * 1e3,
        hit.point.y,
        arrive.y.asin().to_degrees(),
        e_end.to_degrees(),
        w.ode_steps
    );
    assert!((hit.point.x - 30.0).abs() < 1e-9, "the wall, not the road: {}", hit.point);
    assert!((y_min - y_turn).abs() < 2e-4 && y_min > 0.0, "lowest {y_min}, Bouguer {y_turn}");
    assert!((arrive.y.asin() - e_end).abs() < 1e-6, "arrives at {} rad, Bouguer {e_end}", arrive.y.asin());
    assert!(w.lost == 0 && w.ode_steps < 10_000, "{w:?}");
    let Event::Surface { hit, .. } = prop.next_event(&start(DVec3::new(0.0, y0, 0.0), at_elevation(-0.5))) else {
        panic!("a steeper ray reaches the road")
    };
    assert!(hit.point.y.abs() < 1e-9 && hit.point.x < 30.0, "{}", hit.point);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn photons_turned_back_by_the_hot_road_keep_their_power() {
    // Total internal reflection inside a gradient is not a surface event: nothing takes power
    // away. A point light 1 cm above the 10 K/cm road inside a black sphere: every photon (many of
    // them skimming the layer and turned up) is stored once on the sphere, and the stored power
    // equals the emitted power to rounding; no path is lost.
    let dir = temp_dir("photons");
    let text = air_scene(
        &hot_road_index(&dir),
        "direct = \"photon_map\"",
        "",
        "[[material]]\nname = \"black\"\ntype = \"lambertian\"\nreflectance = 0.0\n\n[[shape]]\ntype = \"sphere\"\ncenter = [0.0, 0.0, 0.0]\nradius = 5.0\nmaterial = \"black\"\n",
    )
    .replace("position = [0.0, 50.0, 0.0]", "position = [0.0, 0.01, 0.0]")
    .replace("position = [0.0, 2.0, 0.0]", "position = [0.0, 1.0, 0.0]");
    let s = scene(&text);
    let n = 20_000;
    let (sink, stats) = shoot(&s.world, &PassSettings::of(&s), MapKind::Global, n, 7, &|_| {});
    let total: f64 = s.world.lights.iter().map(|l| l.power_w()).sum();
    let stored: f64 = sink.surface.iter().map(|p| p.power_w).sum();
    eprintln!(
        "hot-road photons: {} stored, {stored} W of {total} W, curved work {:?}",
        sink.surface.len(),
        stats.curved
    );
    assert_eq!(sink.surface.len() as u64, n, "each photon stored exactly once");
    assert!((stored - total).abs() < 1e-9 * total, "stored {stored} W of {total} W");
    assert!(stats.escaped_w == 0.0 && stats.curved.lost == 0, "{stats:?}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_ray_from_space_tangent_at_one_kilometre_is_deflected_by_twice_the_horizon_refraction() {
    // Outside the atmosphere (n = 1) a straight line with impact parameter b passes the Earth's
    // centre at distance b; inside, Bouguer's n·r·cos e = b, so the refracted ray is tangent where
    // n(r)·r = b. Aiming with b = n(1 km)·(R + 1 km) puts the tangent point at 1 km. The path is
    // symmetric about it, and each half is the path of a star seen on the horizon from 1 km, so
    // the total deflection is 2 R(1 km, 0°) from the refraction tracer (≈ 2 × 30′). Expected: the
    // ray starts 100 km up, enters the shell, bends, leaves and escapes deflected by that within
    // 0.05″, never touching the sea; bounded steps.
    let s = scene(&air_scene(
        r#"{ type = "atmosphere", name = "usa76" }"#,
        "ode_rtol = 1e-12\node_atol = 1e-12",
        "",
        &sea("grey"),
    ));
    let atm = Atmosphere::builtin("usa76").expect("usa76");
    let b = index_of(&s).n(LAMBDA_NM, DVec3::new(0.0, 1000.0, 0.0)) * (R + 1000.0);
    let x0 = -((R + 100e3).powi(2) - b * b).sqrt();
    let p0 = DVec3::new(x0, b - R, 0.0);
    let prop = Propagator::new(&s.world, s.curved());
    let event = prop.next_event(&start(p0, DVec3::X));
    // The lowest point along the path, on the dense output (chord ends are step ends here, in
    // clear air far from geometry, and miss it by the arc's drop over part of a step).
    let lowest = perigee_height(&s, &start(p0, DVec3::X));
    let Event::Escape { dir } = event else { panic!("{event:?}") };
    let deflection = dir.cross(DVec3::X).length().atan2(dir.dot(DVec3::X)) * ARCSEC_PER_RAD;
    let tracer = Tracer::new(&atm, LAMBDA_NM, 1000.0, Settings::default()).expect("tracer");
    let half = tracer.refraction_rad(0.0).expect("trace").expect("escapes") * ARCSEC_PER_RAD;
    let w = prop.work.totals();
    eprintln!(
        "tangent at 1 km: deflection {deflection:.4}″ = {:.3}′ (2 × {half:.4}″), lowest {lowest:.2} m, {} steps",
        deflection / 60.0,
        w.ode_steps
    );
    assert!(dir.y < 0.0, "bent towards the Earth");
    assert!((deflection - 2.0 * half).abs() < 0.05, "{deflection}″ vs {}″", 2.0 * half);
    assert!((lowest - 1000.0).abs() < 1.0, "tangent point {lowest} m");
    assert!(w.lost == 0 && w.ode_steps < 5000, "{w:?}");
}

/// The catenary of a ray launched along +x at the origin in n = 2 + 0.01·y, its point and unit
/// normal (towards the concave side) at x.
fn catenary(x: f64) -> (DVec3, DVec3) {
    let k = 0.01 / 2.0;
    let p = DVec3::new(x, ((k * x).cosh() - 1.0) / k, 0.0);
    let s = (k * x).sinh();
    (p, DVec3::new(-s, 1.0, 0.0).normalize())
}

#[test]
fn a_sphere_grazed_by_the_arc_is_hit_or_missed_never_both_and_never_twice() {
    // A ball of radius 0.5 m touching the catenary at x = 5 m from below (the convex side) or from
    // above (the concave side), then moved by δ along the normal: δ < 0 cuts into the path. The
    // propagator hits a surface the arc crosses by more than the arc tolerance (0.1 mm) and misses
    // one it clears by more; in between either is allowed. Expected for every δ: exactly one first
    // event, a hit on the ball or the wall at x = 10; and after a hit, a second query from the
    // hit point along the arriving direction never finds the same crossing again (its event is at
    // least 10 µm further on: the ball's far side or the wall).
    let tol = 1e-4;
    let wall = "[[shape]]\ntype = \"quad\"\norigin = [10.0, -5.0, -5.0]\nu = [0.0, 10.0, 0.0]\nv = [0.0, 0.0, 10.0]\nmaterial = \"grey\"\n";
    let (p, normal) = catenary(5.0);
    let index = "{ type = \"linear\", n0 = 2.0, k_per_m = 0.01, direction = [0.0, 1.0, 0.0] }";
    for side in [-1.0, 1.0] {
        for delta in [-1e-2, -1e-3, -1e-5, -1e-8, 0.0, 1e-8, 1e-5, 1e-3, 1e-2] {
            let c = p + side * (0.5 + delta) * normal;
            let ball = format!(
                "[[shape]]\ntype = \"sphere\"\ncenter = [{}, {}, 0.0]\nradius = 0.5\nmaterial = \"grey\"\n",
                c.x, c.y
            );
            let s = scene(&air_scene(index, "", "", &format!("{ball}\n{wall}")));
            let prop = Propagator::new(&s.world, s.curved());
            let event = prop.next_event(&start(DVec3::ZERO, DVec3::X));
            let Event::Surface { hit, dir, .. } = event else { panic!("side {side}, δ {delta}: {event:?}") };
            let on_ball = hit.prim == 0;
            if delta <= -10.0 * tol {
                assert!(on_ball, "side {side}, δ {delta}: a path cutting {delta} m into the ball must hit it");
            }
            if delta >= 10.0 * tol {
                assert!(!on_ball, "side {side}, δ {delta}: a path clearing the ball must miss it");
            }
            if on_ball {
                let next = prop.next_event(&prop.leave(&hit, dir, Some(LAMBDA_NM), Some(0)));
                let Event::Surface { hit: h2, .. } = next else { panic!("side {side}, δ {delta}: {next:?}") };
                assert!((h2.point - hit.point).length() > 1e-5, "side {side}, δ {delta}: the same crossing twice");
            }
            assert_eq!(prop.work.totals().lost, 0);
        }
    }
}

#[test]
fn a_zero_length_step_in_the_middle_of_a_path_changes_nothing() {
    // Integrator on the USA76 field: twenty steps with and without a zero-length request
    // (h_limit = 0) after the tenth. Expected: the zero step moves nothing and costs no field
    // sample, and the two paths end bit for bit in the same state.
    let atm = Atmosphere::builtin("usa76").expect("usa76");
    let field = |p: DVec3| atm.n_grad(LAMBDA_NM, p);
    let run = |zero_at: Option<usize>| {
        let mut ode = Integrator::new(Method::dormand_prince(1e-10, 1e-10)).expect("method");
        let mut s = OdeState::launch(&field, DVec3::new(0.0, 2.0, 0.0), at_elevation(0.5)).expect("launch");
        for i in 0..20 {
            if Some(i) == zero_at {
                let before = (s, ode.counters().rhs_evals);
                let step = ode.step(&field, &mut s, 0.0).expect("zero step");
                assert_eq!((step.h(), s, ode.counters().rhs_evals), (0.0, before.0, before.1));
            }
            ode.step(&field, &mut s, 1e5).expect("step");
        }
        s
    };
    assert_eq!(run(None), run(Some(10)));
}

#[test]
fn rays_starting_exactly_on_a_region_boundary_go_on_as_if_they_had_arrived_there() {
    // (1) The top of the USA76 shell (86 km above the origin): a ray starting there and one
    // started 1 km back along the same line meet the sea at the same point, to the integrator's
    // accuracy over the ~320 km path (rtol 1e-9: a few times 1e-9 × 3.2e5 m ≈ 0.3 mm; the two
    // take different step sequences) — the start on the boundary is neither skipped nor doubled
    // (either would move the landing point by kilometres). (2) A ray starting on the boundary heading
    // straight out, and one tangent to it, escape unbent (direction unchanged to 10⁻¹²).
    let s = scene(&air_scene(r#"{ type = "atmosphere", name = "usa76" }"#, "", "", &sea("grey")));
    let prop = Propagator::new(&s.world, s.curved());
    let top = DVec3::new(0.0, 86_000.0, 0.0);
    let d = DVec3::new(1.0, -0.3, 0.0).normalize();
    let Event::Surface { hit: a, .. } = prop.next_event(&start(top, d)) else { panic!("must reach the sea") };
    let Event::Surface { hit: b, .. } = prop.next_event(&start(top - 1000.0 * d, d)) else {
        panic!("must reach the sea")
    };
    eprintln!("from the top: sea at {} and {} ({:e} m apart)", a.point, b.point, (a.point - b.point).length());
    assert!((a.point - b.point).length() < 10.0 * 1e-9 * 3.2e5);
    for out in [DVec3::Y, DVec3::X] {
        let Event::Escape { dir } = prop.next_event(&start(top, out)) else { panic!("{out} must escape") };
        assert!((dir - out).length() < 1e-12, "{out} left as {dir}");
    }
    assert_eq!(prop.work.totals().lost, 0);

    // (3) A tabulated profile n(h) between 0 and 10 m (slab region) and a ray starting on its top
    // face, level, tangent to the region. Expected: it is followed (not lost, not stuck switching
    // between straight and curved legs), and wherever it ends Bouguer's n·cos e = n(10 m) holds
    // for its final direction (to 10⁻⁷): level if the field does not bend it there, else leaving
    // the slab's bottom at acos(n(10)/n(0)).
    let dir = temp_dir("slab");
    let csv = dir.join("n_profile.csv");
    std::fs::write(&csv, "height_m,n\n0,1.0003\n2,1.0002\n5,1.00008\n10,1.0\n").expect("profile");
    let floor = "[[shape]]\ntype = \"quad\"\norigin = [-1000.0, -5.0, -1000.0]\nu = [0.0, 0.0, 2000.0]\nv = [2000.0, 0.0, 0.0]\nmaterial = \"grey\"\n";
    let s = scene(&air_scene(&format!("{{ type = \"profile\", file = \"{}\" }}", csv.display()), "", "", floor));
    let prop = Propagator::new(&s.world, s.curved());
    let field = index_of(&s);
    let n_at = |y: f64| field.n(LAMBDA_NM, DVec3::new(0.0, y, 0.0));
    let event = prop.next_event(&start(DVec3::new(0.0, 10.0, 0.0), DVec3::X));
    let (d, y_end) = match event {
        Event::Surface { hit, dir, .. } => (dir, hit.point.y),
        Event::Escape { dir } => (dir, 10.0),
        e => panic!("{e:?}"),
    };
    let e_end = d.y.asin().abs();
    let n_end = n_at(y_end.clamp(0.0, 10.0));
    eprintln!(
        "level on the slab's top: ends at y = {y_end} going {d}; n·cos e = {} (n(10) = {})",
        n_end * e_end.cos(),
        n_at(10.0)
    );
    assert!((n_end * e_end.cos() - n_at(10.0)).abs() < 1e-7, "{event:?}");
    assert_eq!(prop.work.totals().lost, 0);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn atmospheres_that_would_make_air_colder_than_absolute_zero_or_of_negative_pressure_are_rejected() {
    // n − 1 = K·ρ with ρ = P M/(R* T): T ≤ 0 or P ≤ 0 would give n ≤ 1 or n undefined. The loader
    // refuses such a file, and the scene error names the atmosphere file and the fix.
    let dir = temp_dir("bad");
    let cold = atmosphere_index(&dir, "cold", "base = \"usa76\"\n[[edit]]\ntype = \"offset\"\ndT_k = -300.0\n");
    let e = scene_error(&air_scene(&cold, "", "", &sea("grey")));
    assert!(e.contains("cold.toml") && e.contains("must stay positive"), "{e}");
    let icy = atmosphere_index(
        &dir,
        "icy_road",
        "base = \"usa76\"\nearth = \"flat\"\n[[edit]]\ntype = \"hot_surface\"\ndT_k = -290.0\nz0_m = 0.1\n",
    );
    let e = scene_error(&air_scene(&icy, "", "", &sea("grey")));
    assert!(e.contains("icy_road.toml") && e.contains("must stay positive"), "{e}");
    std::fs::write(dir.join("vacuum.csv"), "altitude_m,temperature_k,pressure_pa\n0,288,101325\n1000,280,-5\n")
        .expect("csv");
    let vac = atmosphere_index(&dir, "vacuum", "profile = \"vacuum.csv\"\n");
    let e = scene_error(&air_scene(&vac, "", "", &sea("grey")));
    eprintln!("{e}");
    assert!(e.contains("vacuum") && e.contains("pressure -5 Pa must be positive"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn the_refraction_tracer_calls_a_ducted_horizon_ray_trapped() {
    // The same surface duct as above, seen by `morgana refraction` from 5 m: a level ray turns
    // down at once (5 m is its apex) and meets the sea — trapped, not "into the ground"; a ray
    // aimed 1° up escapes with a finite refraction.
    let dir = temp_dir("duct-refraction");
    let path = dir.join("duct.toml");
    std::fs::write(
        &path,
        "base = \"usa76\"\n[[edit]]\ntype = \"inversion\"\ndT_k = 10.0\nheight_m = 10.0\nthickness_m = 5.0\n",
    )
    .expect("write");
    let atm = morgana::atmosphere::load(&path).expect("load");
    let t = Tracer::new(&atm, LAMBDA_NM, 5.0, Settings::default()).expect("tracer");
    let tr = t.trace(0.0).expect("trace");
    let Outcome::Trapped { max_height_m, ground_distance_m: Some(d) } = tr.outcome else { panic!("{tr:?}") };
    assert!((max_height_m - 5.0).abs() < 1e-6 && d > 1000.0, "{tr:?}");
    assert!(t.refraction_rad(1f64.to_radians()).expect("trace").is_some_and(|r| r.is_finite() && r > 0.0));
    std::fs::remove_dir_all(&dir).ok();
}
