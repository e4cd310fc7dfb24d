//! Curved light paths through refractive-index fields, followed by the propagator that photons
//! and eye rays share, against closed forms.

mod common;

use common::{scene, scene_error};
use glam::DVec3;
use morgana::media::tracking;
use morgana::raypath::{Event, Propagator, RayState};
use morgana::rng::{Rng, Stream};

/// n at y = 0 of the linear test fields (a gradient-index medium: n stays above 1 everywhere
/// in the world for the gradients used).
const N0: f64 = 2.0;

/// A clear medium of index n = n₀ + a·y filling the world, a wall at x = 10 and a light.
fn linear_air(a: f64, extra_medium: &str) -> String {
    format!(
        r#"
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

[[medium]]
name = "air"
sigma_a = 0.0
sigma_s = 0.0
{extra_medium}
index = {{ type = "linear", n0 = {N0}, k_per_m = {a}, direction = [0.0, 1.0, 0.0] }}

[[material]]
name = "grey"
type = "lambertian"
reflectance = 0.5

[[shape]]
type = "quad"
origin = [10.0, -5.0, -5.0]
u = [0.0, 10.0, 0.0]
v = [0.0, 0.0, 10.0]
material = "grey"

[[light]]
type = "point"
position = [5.0, 2.0, 0.0]
spectrum = 1.0
power_w = 1.0
"#
    )
}

fn start(p: DVec3, d: DVec3, medium: Option<u32>) -> RayState {
    RayState { position: p, dir: d.normalize(), wavelength_nm: Some(550.0), medium }
}

#[test]
fn a_horizontal_ray_in_a_linear_field_hits_the_wall_on_the_catenary() {
    // n = n₀ + a y, launched along +x at the origin: y = (n₀/a)(cosh(a x/n₀) − 1), arc length
    // s = (n₀/a) sinh(a x/n₀), slope dy/dx = sinh(a x/n₀) (n cos e = n₀ along the path; the
    // test case of Gutierrez et al. 2005, Fig. 1).
    let a = 0.01;
    let s = scene(&linear_air(a, ""));
    assert!(s.plan.curved_paths.on, "{}", s.plan.curved_paths.why);
    assert!(!s.plan.participating_media.on, "clear air only bends light: {}", s.plan.participating_media.why);
    let prop = Propagator::new(&s.world, s.curved());
    let Event::Surface { hit, dir, path_length, .. } = prop.next_event(&start(DVec3::ZERO, DVec3::X, s.camera_medium))
    else {
        panic!("the ray must hit the wall");
    };
    let x = 10.0f64;
    let y = N0 / a * ((a * x / N0).cosh() - 1.0);
    assert!((hit.point.x - x).abs() < 1e-9, "hit at {}", hit.point);
    // The crossing is refined on the arc far below the 0.1 mm arc tolerance; what remains is the
    // integrator's error (rtol 1e-9) and the chords' shortfall against the arc length.
    assert!((hit.point.y - y).abs() < 1e-6, "y = {}, catenary {y}", hit.point.y);
    let arc = N0 / a * (a * x / N0).sinh();
    assert!((path_length - arc).abs() < 1e-5, "path length {path_length}, arc {arc}");
    let slope = dir.y / dir.x;
    assert!((slope - (a * x / N0).sinh()).abs() < 1e-6, "arrival slope {slope}");
    let work = prop.work.totals();
    assert!(work.ode_steps > 0 && work.ode_steps < 100 && work.lost == 0, "{work:?}");
}

#[test]
fn an_arc_tolerance_below_a_micrometre_is_refused_naming_the_key() {
    // The fuzzer's scene target found arc_tolerance_m = 1e-11 on the fog sunset past a minute
    // of `morgana check` (the chords per path grow as 1/√tolerance).
    let text = linear_air(0.05, "").replace("[world]", "[integrator]\narc_tolerance_m = 1e-11\n\n[world]");
    let e = common::scene_error(&text);
    assert!(e.contains("test.toml:") && e.contains("arc_tolerance_m") && e.contains("out of range"), "{e}");
    scene(&linear_air(0.05, "").replace("[world]", "[integrator]\narc_tolerance_m = 1e-6\n\n[world]"));
}

#[test]
fn the_path_is_as_accurate_as_the_arc_tolerance_asks() {
    // Tighter arc tolerance → the hit approaches the catenary; the default 0.1 mm is met.
    let a = 0.05;
    let x = 10.0f64;
    let y = N0 / a * ((a * x / N0).cosh() - 1.0);
    for tol in [1e-2, 1e-4, 1e-6] {
        let text = linear_air(a, "").replace("[world]", &format!("[integrator]\narc_tolerance_m = {tol}\n\n[world]"));
        let s = scene(&text);
        let prop = Propagator::new(&s.world, s.curved());
        let Event::Surface { hit, .. } = prop.next_event(&start(DVec3::ZERO, DVec3::X, s.camera_medium)) else {
            panic!("must hit");
        };
        assert!((hit.point.y - y).abs() <= tol, "tol {tol}: y = {}, catenary {y}", hit.point.y);
    }
}

#[test]
fn free_flights_are_measured_along_the_arc() {
    // In a scattering medium with the same field, every interaction lies on the catenary and its
    // path length is the catenary's arc length up to it.
    let a = 0.02;
    let s = scene(&linear_air(a, "").replace("sigma_s = 0.0", "sigma_s = 0.2"));
    let prop = Propagator::new(&s.world, s.curved());
    let m = &s.world.media[0];
    let mut rng = Rng::for_task(3, Stream::Test, 0);
    let mut interactions = 0;
    for _ in 0..400 {
        let event = prop.next_event_with(&start(DVec3::ZERO, DVec3::X, Some(0)), &mut |c| {
            tracking::sample_interaction(m, 550.0, c.origin, c.dir, c.length, &mut rng)
        });
        if let Event::Medium { position: p, path_length, .. } = event {
            interactions += 1;
            let y = N0 / a * ((a * p.x / N0).cosh() - 1.0);
            assert!((p.y - y).abs() < 2e-4, "interaction at {p} off the catenary y = {y}");
            let arc = N0 / a * (a * p.x / N0).sinh();
            assert!((path_length - arc).abs() < 1e-4, "path length {path_length}, arc {arc}");
        }
    }
    // P(interaction before the wall) = 1 − exp(−0.2·s(10)) ≈ 0.87.
    assert!((300..=390).contains(&interactions), "{interactions} interactions of 400");
}

/// Air whose index changes only in the slab 0 ≤ y ≤ 10 (a tabulated profile from 1.0003 at the
/// ground to 1 at 10 m), a floor at y = −5, and a ray coming down from y = 20.
fn slab_profile(dir: &std::path::Path) -> String {
    let csv = dir.join("n_profile.csv");
    std::fs::write(&csv, "height_m,n\n0,1.0003\n2,1.0002\n5,1.00008\n10,1.0\n").expect("write profile");
    format!(
        r#"
[camera]
position = [0.0, 30.0, 5.0]
look_at = [0.0, 0.0, 0.0]
fov_deg = 40.0
width = 8
height = 8

[world]
medium = "air"

[[medium]]
name = "air"
sigma_a = 0.0
sigma_s = 0.0
index = {{ type = "profile", file = "{}" }}

[[material]]
name = "grey"
type = "lambertian"
reflectance = 0.5

[[shape]]
type = "quad"
origin = [-1000.0, -5.0, -1000.0]
u = [0.0, 0.0, 2000.0]
v = [2000.0, 0.0, 0.0]
material = "grey"

[[light]]
type = "point"
position = [0.0, 40.0, 0.0]
spectrum = 1.0
power_w = 1.0
"#,
        csv.display()
    )
}

#[test]
fn a_ray_through_a_layer_keeps_bouguers_invariant_and_switches_seamlessly() {
    // Above and below the slab n is constant, so the path is straight there and no ODE runs; in
    // the slab n(y) cos(elevation) is conserved (Snell's law for layers), so the ray leaves the
    // slab at n(0)·cos e_out = n(10)·cos e_in and the horizontal distance it covers is
    // ∫ cot e(y) dy, which quadrature of the invariant gives independently of the integrator.
    let dir = std::env::temp_dir().join(format!("morgana-curved-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let s = scene(&slab_profile(&dir));
    let prop = Propagator::new(&s.world, s.curved());
    let m = &s.world.media[0];
    let n_of = |y: f64| m.index.as_ref().expect("index").n(550.0, DVec3::new(0.0, y, 0.0));
    let e_in = 2.0f64.to_radians();
    let d = DVec3::new(e_in.cos(), -e_in.sin(), 0.0);
    let Event::Surface { hit, dir: arrive, .. } = prop.next_event(&start(DVec3::new(0.0, 20.0, 0.0), d, Some(0)))
    else {
        panic!("must reach the floor");
    };
    let invariant = n_of(10.0) * e_in.cos();
    let e_out = (invariant / n_of(0.0)).acos();
    let elevation = (-arrive.y).asin();
    assert!((elevation - e_out).abs() < 1e-7, "leaves at {elevation} rad, Snell says {e_out}");
    // Horizontal distance: 10/tan e_in above the slab, the slab's ∫ cot e dy, 5/tan e_out below.
    let steps = 20_000;
    let slab: f64 = (0..steps)
        .map(|i| {
            let y = 10.0 * (i as f64 + 0.5) / steps as f64;
            let c = invariant / n_of(y);
            c / (1.0 - c * c).sqrt() * (10.0 / steps as f64)
        })
        .sum();
    let x = 10.0 / e_in.tan() + slab + 5.0 / e_out.tan();
    assert!((hit.point.x - x).abs() < 1e-3, "lands at x = {}, expected {x}", hit.point.x);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn paths_outside_a_local_bump_stay_straight_and_run_no_ode() {
    // A bump of radius 1 m at (5, 3, 0): a ray along y = 0 never enters its region.
    let bump = r#"index = { type = "constant", n = 1.0, bumps = [{ center = [5.0, 3.0, 0.0], radius_m = 1.0, delta_n = 1e-3 }] }"#;
    let text = linear_air(0.0, "")
        .replace(r#"index = { type = "linear", n0 = 2, k_per_m = 0, direction = [0.0, 1.0, 0.0] }"#, bump);
    let s = scene(&text);
    assert!(s.plan.curved_paths.on);
    let prop = Propagator::new(&s.world, s.curved());
    let Event::Surface { hit, .. } = prop.next_event(&start(DVec3::ZERO, DVec3::X, Some(0))) else {
        panic!("must hit");
    };
    assert_eq!(hit.point.y, 0.0);
    assert_eq!(prop.work.totals().ode_steps, 0);
    // Through the bump the ray is deflected, and the integrator runs.
    let through = prop.next_event(&start(DVec3::new(0.0, 3.3, 0.0), DVec3::X, Some(0)));
    let Event::Surface { hit, .. } = through else { panic!("must hit") };
    assert!(hit.point.y != 3.3 && prop.work.totals().ode_steps > 0);
}

#[test]
fn curved_scenes_refuse_shadow_rays_and_the_path_tracer() {
    let with =
        |integrator: &str| linear_air(0.01, "").replace("[world]", &format!("[integrator]\n{integrator}\n\n[world]"));
    let e = scene_error(&with("direct = \"shadow_rays\""));
    assert!(e.contains("shadow rays cannot follow curved paths") && e.contains("photon_map"), "{e}");
    let e = scene_error(&with("method = \"path\""));
    assert!(e.contains("method = \"path\"") && e.contains("photon_map"), "{e}");
    let s = scene(&linear_air(0.01, ""));
    assert_eq!(s.integrator.direct, morgana::scene::DirectLighting::PhotonMap);
    assert!(!s.plan.shadow_rays.on);
}

#[test]
fn n_below_one_is_rejected_with_the_fix() {
    // n = 2 − 0.1·y drops below 1 at y = 10, inside the world's box (|y| ≤ 17 m).
    let e = scene_error(&linear_air(-0.1, ""));
    assert!(e.contains("below 1") && e.contains("allow_below_one"), "{e}");
    // n ≤ 0 is never allowed: n = 2 − 0.2 y reaches 0 at y = 10.
    let e = scene_error(
        &linear_air(-0.2, "")
            .replace("direction = [0.0, 1.0, 0.0] }", "direction = [0.0, 1.0, 0.0], allow_below_one = true }"),
    );
    assert!(e.contains("must be positive"), "{e}");
}

/// A box of medium "dense" (constant n = 1.5, no material on its boundary) in clear air of
/// n = 1 — or of n = `outside` — with a glass ball of n = 1.5 beside it.
fn boundary_scene(outside: f64) -> String {
    format!(
        r#"
[camera]
position = [0.0, 5.0, 5.0]
look_at = [0.0, 0.0, 0.0]
fov_deg = 40.0
width = 8
height = 8

[world]
medium = "air"

[[medium]]
name = "air"
sigma_a = 0.0
sigma_s = 0.0
index = {outside}

[[medium]]
name = "dense"
sigma_a = 0.0
sigma_s = 0.0
index = 1.5

[[material]]
name = "glass"
type = "dielectric"
ior = 1.5

[[shape]]
type = "box"
min = [-1.0, -2.0, -1.0]
max = [1.0, 0.0, 1.0]
interior = "dense"

[[shape]]
type = "sphere"
center = [5.0, 0.0, 0.0]
radius = 1.0
material = "glass"

[[light]]
type = "point"
position = [0.0, 3.0, 0.0]
spectrum = 1.0
power_w = 1.0
"#
    )
}

#[test]
fn a_boundary_between_media_of_different_n_refracts_by_snell_and_reflects_by_fresnel() {
    let s = scene(&boundary_scene(1.0));
    assert!(!s.plan.curved_paths.on, "constant indices need no ODE: {}", s.plan.curved_paths.why);
    let prop = Propagator::new(&s.world, s.curved());
    let theta = 40f64.to_radians();
    let d = DVec3::new(theta.sin(), -theta.cos(), 0.0);
    let Event::Surface { hit, dir, medium, .. } = prop.next_event(&start(DVec3::new(-0.5, 1.0, 0.0), d, Some(0)))
    else {
        panic!("must reach the box top");
    };
    let n = 100_000;
    let mut reflected = 0;
    for i in 0..n {
        let (out, m) = prop.cross(&hit, dir, medium, 550.0, (i as f64 + 0.5) / n as f64);
        if m == medium {
            reflected += 1;
            assert!((out.y - theta.cos()).abs() < 1e-12, "mirror reflection");
        } else {
            assert_eq!(m, Some(1));
            let sin_t = (1.0 - out.y * out.y).sqrt();
            assert!((1.5 * sin_t - theta.sin()).abs() < 1e-12, "Snell: 1.5 sin θt = sin θi");
        }
    }
    let f = morgana::material::fresnel_dielectric(theta.cos(), 1.5);
    assert!((reflected as f64 / n as f64 - f).abs() < 2.0 / n as f64, "reflected {reflected}, Fresnel {f}");
}

#[test]
fn glass_refracts_relative_to_the_medium_around_it() {
    // Glass of n = 1.5 in a medium of n = 1.5 does not bend light at all; in n = 1 it does.
    for (outside, bends) in [(1.5, false), (1.0, true)] {
        let s = scene(&boundary_scene(outside));
        let prop = Propagator::new(&s.world, s.curved());
        let d = DVec3::new(1.0, -0.3, 0.0).normalize();
        let Event::Surface { hit, dir, .. } = prop.next_event(&start(DVec3::new(3.0, 1.0, 0.0), d, Some(0))) else {
            panic!("must reach the ball");
        };
        let m = s.world.material_of(hit.prim).expect("glass");
        let n_out = prop.n_outside(hit.prim, 550.0, hit.point);
        let t = m.sample_specular_in(dir, hit.normal, 550.0, [0.999_999, 0.5, 0.5], n_out).expect("specular");
        assert!(t.transmitted);
        assert_eq!((t.dir - dir).length() > 1e-6, bends, "outside n = {outside}: {} vs {}", t.dir, dir);
    }
}

#[test]
fn a_level_ray_in_the_standard_atmosphere_bends_toward_the_earth_as_its_gradient_says() {
    // USA76 air on the spherical Earth (centre (0, −R, 0)); a ray launched level at 2 m along
    // +x meets a wall 10 km away. Its curvature is κ = |∇n|/n at launch (∇n is vertical and the
    // ray horizontal), so it sags κx²/2 below the straight line: about 1.3 m (κ ≈ 0.17/R, the
    // standard refraction coefficient).
    let toml = r#"
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

[world]
medium = "air"

[[medium]]
name = "air"
sigma_a = 0.0
sigma_s = 0.0
index = { type = "atmosphere", name = "usa76" }

[[material]]
name = "grey"
type = "lambertian"
reflectance = 0.5

[[shape]]
type = "quad"
origin = [10000.0, -100.0, -100.0]
u = [0.0, 200.0, 0.0]
v = [0.0, 0.0, 200.0]
material = "grey"

[[light]]
type = "point"
position = [0.0, 50.0, 0.0]
spectrum = 1.0
power_w = 1.0
"#;
    let s = scene(toml);
    assert!(s.plan.curved_paths.on, "{}", s.plan.curved_paths.why);
    let prop = Propagator::new(&s.world, s.curved());
    let p0 = DVec3::new(0.0, 2.0, 0.0);
    let (n, g) = s.world.media[0].index.as_ref().expect("index").n_grad(550.0, p0);
    let kappa = g.length() / n;
    let Event::Surface { hit, .. } = prop.next_event(&start(p0, DVec3::X, Some(0))) else {
        panic!("must hit the wall")
    };
    let sag = 2.0 - hit.point.y;
    let expected = 0.5 * kappa * 1e8;
    assert!((sag / expected - 1.0).abs() < 0.01, "sag {sag} m, κx²/2 = {expected} m");
    assert!((kappa * 6_371_000.0 - 0.17).abs() < 0.01, "refraction coefficient {}", kappa * 6_371_000.0);
}

/// A collimated beam along +x through n = 2 + 0.004·y (curvature 0.002 m⁻¹: over ~60 m the
/// beam rises by metres) onto a black 1 m plate at x = 50, aimed at the box `target`.
fn bent_beam(target: &str) -> String {
    format!(
        r#"
[camera]
position = [0.0, 0.0, 5.0]
look_at = [50.0, 0.0, 0.0]
fov_deg = 10.0
width = 4
height = 4

[output]
bands = 1
min_nm = 540.0
max_nm = 560.0

[world]
medium = "air"

[[medium]]
name = "air"
sigma_a = 0.0
sigma_s = 0.0
index = {{ type = "linear", n0 = 2.0, k_per_m = 0.004, direction = [0.0, 1.0, 0.0] }}

[[material]]
name = "black"
type = "lambertian"
reflectance = 0.0

[[shape]]
type = "quad"
origin = [50.0, -0.5, -0.5]
u = [0.0, 1.0, 0.0]
v = [0.0, 0.0, 1.0]
material = "black"

[[shape]]
type = "sphere"
center = [-10.0, 0.0, 30.0]
radius = 0.1
material = "black"

[[light]]
type = "directional"
direction = [1.0, 0.0, 0.0]
spectrum = 1.0
irradiance_w_m2 = 1.0
{target}
"#
    )
}

/// Power the plate at x = 50 receives from `photons` photons.
fn plate_power(s: &morgana::scene::Scene, photons: u64) -> (f64, u64) {
    let (sink, _) = morgana::photon::shoot(
        &s.world,
        &morgana::photon::PassSettings::of(s),
        morgana::photon::MapKind::Global,
        photons,
        5,
        &|_| {},
    );
    let on: Vec<_> = sink.surface.iter().filter(|p| (p.position.x - 50.0).abs() < 1e-6).collect();
    (on.iter().map(|p| p.power_w).sum(), on.len() as u64)
}

#[test]
fn a_projection_map_aims_a_bent_beam_at_its_target_without_changing_the_light_it_delivers() {
    let s = scene(&bent_beam("target_min = [49.9, -0.5, -0.5]\ntarget_max = [50.1, 0.5, 0.5]"));
    let morgana::light::Light::Directional(d) = &s.world.lights[0] else { panic!("directional") };
    assert!(d.cells.is_some(), "a projection map must be built where paths curve: {:?}", s.warnings);
    let n = 20_000;
    let (power, hits) = plate_power(&s, n);
    assert!(hits as f64 > 0.25 * n as f64, "only {hits} of {n} photons reach the plate");
    // Closed form: the ray starting at height y₀ on the emitting plane (x = x₀) follows
    // y = y₀ + (n/a)(cosh(a(x − x₀)/n) − 1) with n = 2 + a·y₀, rising monotonically with y₀;
    // the plate (|y| ≤ 0.5, 1 m deep) receives E times the band of start heights that lands
    // on it: Φ = E · 1 m · (y₀(0.5) − y₀(−0.5)).
    let (a, x0) = (0.004, d.plane_point(0.0, 0.0).x);
    let land = |y0: f64| {
        let n = 2.0 + a * y0;
        y0 + n / a * ((a * (50.0 - x0) / n).cosh() - 1.0)
    };
    let start_for = |y: f64| {
        let (mut lo, mut hi) = (-50.0, 50.0);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if land(mid) < y { lo = mid } else { hi = mid }
        }
        0.5 * (lo + hi)
    };
    let expected = start_for(0.5) - start_for(-0.5);
    // Each photon carries the same power: the plate's share is binomial, σ ≈ Φ/√hits.
    let sigma = power / (hits as f64).sqrt();
    assert!((power - expected).abs() < 4.0 * sigma, "plate power {power} W, closed form {expected} W (σ {sigma})");
    assert!(start_for(0.0) < -1.0, "the beam must be bent by more than the plate (start {})", start_for(0.0));
}

#[test]
fn a_shared_projection_map_is_the_one_each_light_would_get_alone() {
    // Three more copies of the bent beam's light: one with another spectrum (same map), one
    // with another target (its own map). Sharing must not hand a light another light's cells.
    let target = "target_min = [49.9, -0.5, -0.5]\ntarget_max = [50.1, 0.5, 0.5]";
    let light = |spectrum: f64, t: &str| {
        format!(
            "\n[[light]]\ntype = \"directional\"\ndirection = [1.0, 0.0, 0.0]\nspectrum = {spectrum}\nirradiance_w_m2 = 1.0\n{t}\n"
        )
    };
    let moved = "target_min = [49.9, 0.5, -0.5]\ntarget_max = [50.1, 1.5, 0.5]";
    let text = bent_beam(target) + &light(2.0, target) + &light(1.0, moved);
    let s = scene(&text);
    let cells = |i: usize| {
        let morgana::light::Light::Directional(d) = &s.world.lights[i] else { panic!("directional") };
        d.cells.as_ref().map(|c| (**c).clone()).expect("a projection map")
    };
    assert_eq!(cells(0), cells(1), "same geometry, another spectrum: the same map");
    assert_ne!(cells(0), cells(2), "another target: another map");
    let alone = scene(&bent_beam(moved));
    let morgana::light::Light::Directional(d) = &alone.world.lights[0] else { panic!("directional") };
    assert_eq!(d.cells.as_ref().map(|c| (**c).clone()), Some(cells(2)), "the moved target's map, traced alone");
}

#[test]
fn a_low_suns_disc_photons_reach_the_sea_in_front_of_the_camera() {
    // examples/sunset_sea.toml in clear air with the sun's centre at true altitude 0.35°: its
    // light reaches the sea 0.5–6 km in front of the camera along paths bent by ~0.4°, and the
    // disc's edges cross the air elsewhere and bend differently (by ~0.1° between the limbs).
    // With each photon's cells moved with its direction (the projection map's disc shift),
    // most of the sun's photons land in the box, as many as with a point-like sun.
    let text = std::fs::read_to_string("examples/sunset_sea.toml").expect("examples/sunset_sea.toml");
    let clear = text.replace("sigma_a = \"rayleigh\"", "sigma_a = 0.0");
    // The sun alone: drop the sky light that follows it.
    let sun_alone = &clear[..clear.find("[[light]]\nname = \"sky\"").expect("the sky light")];
    let setting = sun_alone.replace("elevation_deg = -0.2849", "elevation_deg = -0.2849\nscale = 1.0");
    let sun_only = &sun_alone.replace("elevation_deg = -0.2849", "elevation_deg = 0.35\nscale = 1.0");
    let fraction = |toml: &str| {
        let s = scene(toml);
        assert!(s.warnings.is_empty(), "{:?}", s.warnings);
        let morgana::light::Light::Directional(sun) = &s.world.lights[0] else { panic!("the first light is the sun") };
        assert!(sun.cells.as_ref().is_some_and(|c| !c.cells.is_empty()), "a projection map");
        let n = 4000;
        let (sink, _) = morgana::photon::shoot(
            &s.world,
            &morgana::photon::PassSettings::of(&s),
            morgana::photon::MapKind::Global,
            n,
            8,
            &|_| {},
        );
        let in_box = sink
            .surface
            .iter()
            .filter(|p| p.position.x.abs() <= 60.5 && (-6000.5..=-499.5).contains(&p.position.z))
            .count();
        in_box as f64 / n as f64
    };
    let disc = fraction(sun_only);
    let point = fraction(&sun_only.replace("angular_diameter_deg = 0.53", "angular_diameter_deg = 0.0"));
    // The example's own sun, centre 0.28° below the true horizon: the straight shadow runs
    // into the Earth, and the aiming lifts it by bisection until the bent rays pass the target.
    let below = fraction(&setting);
    // The same with Neckel & Labs's limb darkening: directions drawn from the law instead of
    // uniformly, through the same projection map.
    let darkened = fraction(&setting.replace("scale = 1.0", "scale = 1.0\nlimb_darkening = \"neckel_labs_1994\""));
    eprintln!("photons on the target: disc {disc}, point-like {point}; setting sun {below}, limb-darkened {darkened}");
    assert!(below > 0.3, "setting sun: {below} of its photons on the target");
    assert!(darkened > 0.3, "limb-darkened setting sun: {darkened} of its photons on the target");
    assert!(point > 0.5, "point-like sun: {point} of its photons on the target");
    assert!(disc > 0.8 * point, "disc: {disc} of its photons on the target, point-like {point}");
}
