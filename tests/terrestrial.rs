//! Terrestrial refraction by Bouguer's quadrature (`atmosphere::refraction::terrestrial`)
//! against two independent integrations of the same air: morgana's ray equation (Dormand–Prince
//! at rtol = atol = 10⁻¹², steps cut at the layer boundaries, the end found on the dense output)
//! and atm-refraction 0.6.1 (fixed-step RK4 in the ground distance, its own US-1976 air).

use atm_refraction::{EarthShape, Environment, air::us76_atmosphere};
use glam::DVec3;
use morgana::atmosphere::Atmosphere;
use morgana::atmosphere::refraction::terrestrial::{RadialAir, Reach, follow, radial_air};
use morgana::ode::kink::KinkSpheres;
use morgana::ode::{Integrator, Method, OdeState};

const LAMBDA: f64 = 550.0;
/// The quadrature's tolerance, rad (6·10⁻⁸ m at the Earth's radius).
const TOL: f64 = 1e-14;

/// Where the ray equation puts the ray from height `h0` above the ground (radius `ground`) at
/// elevation `e0` after central angle `phi`: (height, elevation), or Err(angle) where it went
/// below the ground. The frame is a scene's: the start at the origin, the ray going +x, the
/// Earth's centre at (0, −(R + h₀), 0), so that coordinates stay small; `field` takes points in
/// that frame.
fn traced(
    field: &impl Fn(DVec3) -> (f64, DVec3),
    kinks: &[f64],
    ground: f64,
    h0: f64,
    e0: f64,
    phi: f64,
) -> Result<(f64, f64), f64> {
    let method =
        Method::DormandPrince { rtol: 1e-15, atol: 1e-15, pi: true, h0: None, h_min: 0.0, h_max: f64::INFINITY };
    let mut ode = Integrator::new(method).unwrap();
    let centre = DVec3::new(0.0, -(ground + h0), 0.0);
    let radii: Vec<f64> = kinks.iter().map(|h| ground + h).collect();
    let spheres = KinkSpheres::new(field, centre, &radii);
    let mut state = OdeState::launch(field, DVec3::ZERO, DVec3::new(e0.cos(), e0.sin(), 0.0)).unwrap();
    let mut grad = ode.prime(field, &state.y).unwrap().v;
    // Height without cancelling Earth-sized coordinates: |q|² − R² = x² + z² + u(u + 2R), u = y + h₀.
    let height = |p: DVec3| {
        let u = p.y + h0;
        (p.x * p.x + p.z * p.z + u * (u + 2.0 * ground)) / ((p - centre).length() + ground)
    };
    let polar = |p: DVec3| p.x.atan2(p.y - centre.y);
    for _ in 0..1_000_000 {
        let tol = method.kink_tolerance(state.y.v.length());
        let cut = spheres.next_cut(state.y.r, state.y.direction(), state.y.curvature(grad), 1e-6, tol);
        let step = ode.step(field, &mut state, cut.unwrap_or(f64::INFINITY)).unwrap();
        grad = step.dense.f1.v;
        if height(step.y1().r) < 0.0 {
            let t = bisect(|t| -height(step.position_at(t)), 0.0, 1.0);
            return Err(polar(step.position_at(t)));
        }
        if polar(step.y1().r) >= phi {
            let t = bisect(|t| polar(step.position_at(t)) - phi, 0.0, 1.0);
            let (p, d) = (step.position_at(t), step.direction_at(t));
            return Ok((height(p), d.dot((p - centre).normalize()).asin()));
        }
    }
    panic!("the trace did not get there");
}

/// The root of an increasing `f` on [a, b], to rounding.
fn bisect(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        if m <= a || m >= b {
            break;
        }
        if f(m) < 0.0 { a = m } else { b = m }
    }
    0.5 * (a + b)
}

/// The atmosphere's field in the frame of a start `h0` above the ground (the atmosphere's own frame
/// puts the ground's top at the origin).
fn field_from(air: &Atmosphere, h0: f64) -> impl Fn(DVec3) -> (f64, DVec3) + '_ {
    move |p: DVec3| air.n_grad(LAMBDA, p + DVec3::new(0.0, h0, 0.0))
}

/// Rays up, down through a perigee, ending on the way down, level, into the ground and out of
/// the top, through USA76 (its layer boundaries crossed): the quadrature's end within 2·10⁻⁸ m
/// in height and 10⁻¹³ rad in elevation of the ray equation's (measured: ≤ 7.8·10⁻¹⁰ m, and
/// 7.1·10⁻⁹ m on the 1 500 km ray that leaves the top — the oracle's own error there, which
/// falls from 1.1·10⁻⁶ to that as its tolerance goes from 10⁻¹⁴ to 10⁻¹⁵; ≤ 10⁻¹⁴ rad), its
/// ground angle within 10⁻¹⁵ rad.
#[test]
fn the_quadrature_puts_the_ray_where_the_ray_equation_does() {
    // (start height m, elevation deg, ground distance km)
    let cases = [
        (10.0, 0.5, 100.0),
        (100.0, 5.0, 300.0),
        (2000.0, -0.5, 300.0),
        (2000.0, -0.5, 20.0),
        (100.0, 0.0, 200.0),
        (5000.0, -1.2, 150.0),
        (10.0, 10.0, 1500.0),
        (30_000.0, -2.0, 400.0),
    ];
    compare_with_the_ray_equation(&Atmosphere::usa76(), &cases, 2e-8, 1e-13);
    // A table profile (AFGL tropical, monotone cubic between its knots, ∇n continuous, its
    // derivative not) whose derivative at its lowest knot, the ground, is the constant
    // extrapolation's below it: rays from there. Within 10⁻⁷ m and 10⁻¹² rad (measured
    // 7.8·10⁻⁸ m, 1.9·10⁻¹³ rad; the quadrature's heights move by 2·10⁻⁹ m whether or not its
    // pieces end at the table's rows, so most of that is the oracle's).
    let tropical = [(0.0, 0.0, 100.0), (0.0, 0.5, 200.0), (1000.0, -0.5, 300.0), (0.0, 3.0, 400.0)];
    compare_with_the_ray_equation(&Atmosphere::builtin("tropical").unwrap(), &tropical, 1e-7, 1e-12);
    let atmosphere = Atmosphere::usa76();
    let air = radial_air(&atmosphere, LAMBDA).unwrap();
    let r_e = air.ground_radius_m;
    for (h0, e_deg) in [(10.0, -0.5), (1000.0, -1.5)] {
        let e0 = f64::to_radians(e_deg);
        let path = follow(&air, h0, e0, 0.1, TOL).unwrap();
        let Reach::Ground { angle_rad } = path.reach else { panic!("{h0} {e_deg}: {path:?}") };
        let reference = traced(&field_from(&atmosphere, h0), &air.kink_heights_m, r_e, h0, e0, 0.1).unwrap_err();
        eprintln!("{h0} m {e_deg}°: ground at {:.6} km, Δ {:.2e} rad", angle_rad * r_e / 1e3, angle_rad - reference);
        assert!((angle_rad - reference).abs() < 1e-15, "{h0} m {e_deg}°: {angle_rad} vs {reference}");
    }
}

/// n = n_s (r/R)^(−k): with W = n r = n_s R^k r^(1−k), Bouguer's invariant W cos e = c integrates
/// in closed form, dφ = c dW/((1 − k) W √(W² − c²)), to W(φ) = c / cos((1 − k)φ + e₀): the
/// elevation grows exactly as e = e₀ + (1 − k)φ, and r(φ) = (W/(n_s R^k))^(1/(1−k)). Rays up,
/// level, and down through a perigee, for k = 0.17 (about the standard air's bending at the
/// ground) and k = 0.9 (close to ducting, k = 1) agree with it to 2·10⁻¹⁰ m and 10⁻¹⁴ rad
/// (measured: ≤ 4.1·10⁻¹¹ m, ≤ 1.8·10⁻¹⁶ rad); for
/// k = 1.2 (n·r falling with r: a duct) a ray that would turn back is refused.
#[test]
fn rays_in_a_power_law_index_follow_the_closed_form() {
    let (big_r, n_s) = (6_371_000.0f64, 1.0003f64);
    for k in [0.17, 0.9] {
        // N = n − 1 = (n_s − 1) + n_s((r/R)^(−k) − 1) at r = R + h, the last factor by expm1
        // and ln1p.
        let index = move |h: f64| {
            let rel = (-k * (h / big_r).ln_1p()).exp_m1();
            ((n_s - 1.0) + n_s * rel, -k * n_s * (1.0 + rel) / (big_r + h))
        };
        let air = RadialAir { refractivity: index, kink_heights_m: vec![], ground_radius_m: big_r, top_m: 1e5 };
        for (h0, e_deg, d_km) in [(10.0, 0.5, 100.0), (10.0, 0.0, 60.0), (2000.0, -0.5, 30.0), (2000.0, -0.5, 300.0)] {
            let (r0, e0, phi) = (big_r + h0, f64::to_radians(e_deg), d_km * 1e3 / big_r);
            let path = follow(&air, h0, e0, phi, TOL).unwrap();
            let Reach::Aloft { height_m, elevation_rad } = path.reach else { panic!("{k} {h0} {e_deg}: {path:?}") };
            let e = e0 + (1.0 - k) * phi;
            // r/r₀ = (cos e₀/cos e)^(1/(1−k)) from W/W₀ = cos e₀/cos e; r − r₀ by ln1p and expm1,
            // with cos e₀/cos e − 1 = 2 sin((e + e₀)/2) sin((e − e₀)/2)/cos e.
            let ratio = 2.0 * (0.5 * (e + e0)).sin() * (0.5 * (e - e0)).sin() / e.cos();
            let rise = r0 * (ratio.ln_1p() / (1.0 - k)).exp_m1();
            let (dr, de) = (height_m - h0 - rise, elevation_rad - e);
            eprintln!(
                "k {k}: {h0} m {e_deg}° {d_km} km: Δr {dr:.2e} m, Δe {de:.2e} rad, {} evaluations",
                path.evaluations
            );
            assert!(
                dr.abs() < 2e-10 && de.abs() < 1e-14,
                "k {k}, {h0} m {e_deg}° {d_km} km: Δr {dr:e} m, Δe {de:e} rad"
            );
        }
    }
    let duct = move |h: f64| {
        let rel = (-1.2 * (h / big_r).ln_1p()).exp_m1();
        ((n_s - 1.0) + n_s * rel, -1.2 * n_s * (1.0 + rel) / (big_r + h))
    };
    let air = RadialAir { refractivity: duct, kink_heights_m: vec![], ground_radius_m: big_r, top_m: 1e5 };
    let e = follow(&air, 0.0, 0.001, 0.05, TOL).unwrap_err();
    assert!(e.contains("duct"), "{e}");
}

/// The inferior mirage: over the hot road (30 K warmer at the surface, the excess falling off
/// over metres) a ray from an eye 1.5 m up aimed slightly down turns above the road and climbs
/// — the "reflection". Where the field's length scale is metres, not kilometres, the ends agree
/// with the ray equation's within 10⁻¹⁰ m and 10⁻¹³ rad (measured: ≤ 10⁻¹² m, ≤ 1.4·10⁻¹⁴ rad).
#[test]
fn the_quadrature_follows_the_hot_roads_mirage_rays() {
    let cases = [(1.5, -0.1, 0.2), (1.5, -0.1, 0.6), (1.5, -0.25, 0.3), (0.5, 0.0, 0.4)];
    compare_with_the_ray_equation(&Atmosphere::builtin("hot_road").unwrap(), &cases, 1e-10, 1e-13);
}

fn compare_with_the_ray_equation(atmosphere: &Atmosphere, cases: &[(f64, f64, f64)], max_dh: f64, max_de: f64) {
    let air = radial_air(atmosphere, LAMBDA).unwrap();
    let r_e = air.ground_radius_m;
    let mut failures = Vec::new();
    for &(h0, e_deg, d_km) in cases {
        let (e0, phi) = (f64::to_radians(e_deg), d_km * 1e3 / r_e);
        let path = follow(&air, h0, e0, phi, TOL).unwrap();
        let Reach::Aloft { height_m, elevation_rad } = path.reach else { panic!("{h0} {e_deg} {d_km}: {path:?}") };
        let (h_ref, e_ref) = traced(&field_from(atmosphere, h0), &air.kink_heights_m, r_e, h0, e0, phi).unwrap();
        let (dh, de) = (height_m - h_ref, elevation_rad - e_ref);
        eprintln!(
            "{} {h0} m {e_deg}° {d_km} km: end {height_m:.9} m, Δh {dh:.2e} m, Δe {de:.2e} rad, {} evaluations",
            atmosphere.name, path.evaluations
        );
        if !(dh.abs() < max_dh && de.abs() < max_de) {
            failures.push(format!("{h0} m {e_deg}° {d_km} km: Δh {dh:e} m, Δe {de:e} rad"));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// Rays through atm-refraction's own air (US-1976, Edlén at 530 nm, as a closure): the
/// quadrature's end height within 5·10⁻⁹ m of its RK4 with 1 m steps, an integration that shares
/// nothing with morgana's (measured: ≤ 1.5·10⁻⁹ m, the printed digits).
#[test]
fn the_quadrature_agrees_with_atm_refraction() {
    let radius = 6_371_000.0;
    let env =
        Environment { shape: EarthShape::Spherical { radius }, atmosphere: us76_atmosphere(), wavelength: 530e-9 };
    let air = RadialAir {
        refractivity: |h: f64| (env.n(h) - 1.0, env.dn(h)),
        kink_heights_m: vec![11_000.0],
        ground_radius_m: radius,
        top_m: 80_000.0,
    };
    for (h0, e_deg, d_km) in [(10.0, 0.5, 100.0), (1000.0, -0.3, 150.0), (50.0, 2.0, 80.0)] {
        let mut stepper = env.cast_ray_stepper(h0, f64::to_radians(e_deg), false);
        stepper.set_step_size(1.0);
        let mut last = None;
        for _ in 0..(d_km * 1e3) as usize {
            last = stepper.next();
        }
        let theirs = last.unwrap().h;
        let path = follow(&air, h0, f64::to_radians(e_deg), d_km * 1e3 / radius, 1e-15).unwrap();
        let Reach::Aloft { height_m: ours, .. } = path.reach else { panic!("{path:?}") };
        eprintln!("{h0} m {e_deg}° {d_km} km: {ours:.9} m against {theirs:.9} m");
        assert!((ours - theirs).abs() < 5e-9, "{h0} m {e_deg}° {d_km} km: {ours} vs {theirs}");
    }
}

/// A duct (the inversion's air, n·r falling with height through its layer at 30 m) is refused
/// with a message that says to trace the ray; bad values name themselves.
#[test]
fn ducts_and_bad_values_are_refused() {
    let inversion = Atmosphere::builtin("inversion").unwrap();
    let air = radial_air(&inversion, LAMBDA).unwrap();
    let e = follow(&air, 25.0, 0.002, 1e-3, 1e-12).unwrap_err();
    assert!(e.contains("duct"), "{e}");
    let atmosphere = Atmosphere::usa76();
    let air = radial_air(&atmosphere, LAMBDA).unwrap();
    assert!(follow(&air, -1.0, 0.0, 0.01, 1e-12).unwrap_err().contains("start height"));
    assert!(follow(&air, 0.0, 2.0, 0.01, 1e-12).unwrap_err().contains("elevation"));
    assert!(follow(&air, 0.0, 0.0, f64::NAN, 1e-12).unwrap_err().contains("central angle"));
    assert!(follow(&air, 0.0, 0.0, 0.01, 0.0).unwrap_err().contains("tolerance"));
    let away = follow(&air, 0.0, 1.5, 1.5, 1e-12).unwrap().reach;
    assert!(matches!(away, Reach::Away { max_angle_rad } if max_angle_rad > 0.0 && max_angle_rad < 1.5), "{away:?}");
}

fn morgana() -> std::process::Command {
    std::process::Command::new(env!("CARGO_BIN_EXE_morgana"))
}

/// `morgana refraction --ground-distances-km` prints the table and writes the CSV with the
/// library's numbers (a ray into the ground as such), through an atmosphere and through the
/// model of the observer's conditions; a duct, and options that do not apply, are clear errors.
#[test]
fn the_command_writes_the_terrestrial_table() {
    let dir = std::env::temp_dir().join(format!("morgana-terrestrial-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let csv = dir.join("t.csv");
    let out = morgana()
        .args(["refraction", "--atmosphere", "usa76", "--ground-distances-km", "1,100"])
        .args(["--apparent-altitudes-deg=-0.5,0.5", "--observer-height-m", "10", "--csv"])
        .arg(&csv)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("terrestrial refraction") && text.contains("meets the ground"), "{text}");
    let table = std::fs::read_to_string(&csv).unwrap();
    let rows: Vec<Vec<&str>> = table.lines().skip(1).map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 4, "{table}");
    let atmosphere = Atmosphere::usa76();
    let air = radial_air(&atmosphere, LAMBDA).unwrap();
    for row in &rows {
        let (a, d): (f64, f64) = (row[0].parse().unwrap(), row[1].parse().unwrap());
        let path = follow(&air, 10.0, a.to_radians(), d * 1e3 / air.ground_radius_m, 1e-12).unwrap();
        match path.reach {
            Reach::Aloft { height_m, .. } => assert_eq!(row[2], format!("{height_m:.9}"), "{row:?}"),
            Reach::Ground { angle_rad } => {
                assert!(row[2].is_empty(), "{row:?}");
                assert_eq!(row[6], format!("{:.9}", angle_rad * air.ground_radius_m / 1e3), "{row:?}");
            }
            Reach::Away { .. } => panic!("{row:?}: every ray of this table reaches its distance"),
        }
    }
    // Standard air bends a ray down: at 100 km it is below the straight line by
    // k·d²/(2R), k ≈ 0.13–0.17 (the refraction coefficient of geodesy).
    let far = rows.iter().find(|r| r[0] == "0.5" && r[1] == "100").unwrap();
    let lift: f64 = far[5].parse().unwrap();
    let k = -2.0 * air.ground_radius_m * lift / 1e10;
    assert!((0.12..0.18).contains(&k), "k = {k}");
    let model = morgana()
        .args(["refraction", "--ground-distances-km", "50", "--apparent-altitudes-deg", "0"])
        .output()
        .unwrap();
    assert!(model.status.success(), "{}", String::from_utf8_lossy(&model.stderr));
    assert!(String::from_utf8_lossy(&model.stdout).contains("Hohenkerk & Sinclair"));
    for (extra, says) in [
        (vec!["--atmosphere", "inversion", "--observer-height-m", "25", "--apparent-altitudes-deg", "0"], "duct"),
        (vec!["--method", "trace"], "--method trace"),
        (vec!["--wavelengths-nm", "450,650"], "--wavelengths-nm"),
        (vec!["--observer-height-m", "-3"], "--observer-height-m"),
    ] {
        let out = morgana().args(["refraction", "--ground-distances-km", "10"]).args(&extra).output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success() && err.contains(says), "{extra:?}: {err}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Hard cases: 3 000 random rays (start heights 0–80 km, elevations from −89° to 89° with a
/// third of them within 0.01° of level, central angles up to 0.2 rad, including exactly 0) through
/// USA76, the hot road and the inversion: every answer is finite and in range — a height between
/// the ground and where a straight line could reach, an elevation within ±90°, a ground angle
/// within the angle asked, a ray that leaves the air upward short of it — or an error naming a
/// duct.
#[test]
fn random_rays_give_finite_answers_or_clear_errors() {
    let mut rng = morgana::rng::Rng::for_task(7, morgana::rng::Stream::Eye, 0);
    for name in ["usa76", "hot_road", "inversion"] {
        let atmosphere = Atmosphere::builtin(name).unwrap();
        let air = radial_air(&atmosphere, LAMBDA).unwrap();
        let (mut ok, mut refused) = (0, 0);
        for i in 0..1000 {
            let h0 = if i % 4 == 0 { 0.0 } else { rng.uniform() * rng.uniform() * 80_000.0 };
            let e_deg = if i % 3 == 0 { (rng.uniform() - 0.5) * 0.02 } else { (rng.uniform() - 0.5) * 178.0 };
            let phi = if i % 10 == 0 { 0.0 } else { rng.uniform() * 0.2 };
            match follow(&air, h0, e_deg.to_radians(), phi, 1e-10) {
                Ok(p) => {
                    ok += 1;
                    match p.reach {
                        Reach::Aloft { height_m, elevation_rad } => {
                            assert!(height_m.is_finite() && height_m >= -1e-6, "{name} {h0} {e_deg} {phi}: {p:?}");
                            assert!(
                                elevation_rad.abs() <= std::f64::consts::FRAC_PI_2,
                                "{name} {h0} {e_deg} {phi}: {p:?}"
                            );
                        }
                        Reach::Ground { angle_rad } => {
                            assert!(
                                angle_rad.is_finite() && (0.0..=phi + 1e-12).contains(&angle_rad),
                                "{name} {h0} {e_deg} {phi}: {p:?}"
                            )
                        }
                        Reach::Away { max_angle_rad } => {
                            assert!(
                                max_angle_rad.is_finite() && max_angle_rad < phi,
                                "{name} {h0} {e_deg} {phi}: {p:?}"
                            )
                        }
                    }
                }
                Err(e) => {
                    refused += 1;
                    assert!(e.contains("duct"), "{name} {h0} {e_deg} {phi}: {e}");
                }
            }
        }
        eprintln!("{name}: {ok} answered, {refused} refused");
        assert!(ok > 500, "{name}: {ok}");
    }
}

/// Astronomical refraction by the quadrature (`true_altitude`) against the ray trace of
/// `morgana refraction --atmosphere` (Dormand–Prince at rtol 10⁻¹², steps cut at the layer
/// boundaries and the taper): USA76, the tropical profile and the hot road, from the ground and
/// from 1 km, at apparent altitudes from −0.5° to 80°: the same rays escape, and the refractions
/// agree within 0.002″.
#[test]
fn astronomical_refraction_by_quadrature_equals_the_ray_trace() {
    use morgana::atmosphere::refraction::terrestrial::true_altitude;
    use morgana::atmosphere::refraction::{ARCSEC_PER_RAD, Settings, Tracer};
    let mut worst = 0.0f64;
    for name in ["usa76", "tropical", "hot_road"] {
        let atmosphere = Atmosphere::builtin(name).unwrap();
        let air = radial_air(&atmosphere, LAMBDA).unwrap();
        for h0 in [0.0, 1000.0] {
            let tracer = Tracer::new(&atmosphere, LAMBDA, h0, Settings::default()).unwrap();
            for a_deg in [-0.5, -0.2, 0.0, 0.5, 1.0, 2.0, 5.0, 10.0, 45.0, 80.0] {
                let a = f64::to_radians(a_deg);
                let traced = tracer.refraction_rad(a).unwrap();
                let ours = true_altitude(&air, h0, a, 1e-13).unwrap().map(|(t, _)| a - t);
                match (traced, ours) {
                    (Some(t), Some(q)) => {
                        let d = (q - t) * ARCSEC_PER_RAD;
                        worst = worst.max(d.abs());
                        assert!(d.abs() < 0.002, "{name} {h0} m {a_deg}°: quadrature {q} vs trace {t} ({d}″)");
                    }
                    (None, None) => {}
                    other => panic!("{name} {h0} m {a_deg}°: {other:?}"),
                }
            }
        }
    }
    eprintln!("largest difference {worst:.2e}″");
}

/// Through air whose index varies along the ground (a warm bubble 2 km off) Bouguer's invariant
/// does not hold: `morgana refraction --atmosphere FILE` then traces every ray, as
/// `--method trace` does (the same CSV, no quadrature rows), and `--method quadrature` named
/// explicitly is refused with what to use instead.
#[test]
fn air_that_varies_along_the_ground_is_traced() {
    let dir = std::env::temp_dir().join(format!("morgana-astro-bubble-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let atm = dir.join("bubble.toml");
    std::fs::write(
        &atm,
        "name = \"bubble\"\nbase = \"usa76\"\ndispersion = \"ciddor\"\nco2_ppm = 450\ntop_m = 86000\n\
         earth = \"spherical\"\n\n[[edit]]\ntype = \"bubble\"\ndT_k = 5.0\ncentre = [2000.0, 200.0, 0.0]\nradius_m = 500.0\n",
    )
    .unwrap();
    let run = |name: &str, extra: &[&str]| {
        let csv = dir.join(format!("{name}.csv"));
        let out = morgana()
            .args(["refraction", "--apparent-altitudes-deg=0,0.5,5", "--atmosphere"])
            .arg(&atm)
            .arg("--csv")
            .arg(&csv)
            .args(extra)
            .output()
            .unwrap();
        let text = String::from_utf8_lossy(&out.stdout).to_string() + &String::from_utf8_lossy(&out.stderr);
        (out.status.success(), text, std::fs::read_to_string(&csv).unwrap_or_default())
    };
    let (ok, text, by_default) = run("d", &[]);
    assert!(ok && !text.contains("Bouguer's quadrature"), "{text}");
    let (ok, _, traced) = run("t", &["--method", "trace"]);
    assert!(ok && traced == by_default && traced.lines().count() == 4, "{traced}\n{by_default}");
    let (ok, text, _) = run("q", &["--method", "quadrature"]);
    assert!(!ok && text.contains("--method quadrature") && text.contains("--method trace"), "{text}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// `morgana refraction --atmosphere A` answers by Bouguer's quadrature unless told
/// `--method trace`, and writes the traced table's numbers (within the CSV's 10⁻⁴″) for USA76;
/// through the inversion, where some rays are ducted and some go into the ground, it traces
/// those and says which rows are the quadrature's. The dispersion table and the flattened sun
/// come out as the trace's to their printed digits (0.01″; 10⁻⁴° and 10⁻⁴ in the ratio).
#[test]
fn the_command_computes_astronomical_refraction_by_quadrature_by_default() {
    let dir = std::env::temp_dir().join(format!("morgana-astro-q-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let altitudes = "--apparent-altitudes-deg=-1,-0.2,0,0.05,0.3,1,3,10,30,60,90";
    let read = |name: &str, extra: &[&str]| {
        let csv = dir.join(format!("{name}.csv"));
        let out = morgana()
            .args(["refraction", altitudes, "--wavelengths-nm", "450,650", "--csv"])
            .arg(&csv)
            .args(extra)
            .output()
            .unwrap();
        assert!(out.status.success(), "{extra:?}: {}", String::from_utf8_lossy(&out.stderr));
        let text = std::fs::read_to_string(&csv).unwrap();
        let column: Vec<Option<f64>> =
            text.lines().skip(1).map(|l| l.split(',').nth(2).and_then(|v| v.parse().ok())).collect();
        (column, String::from_utf8(out.stdout).unwrap())
    };
    // The numbers of the dispersion table and the sun's line, in order.
    let numbers_after = |text: &str, from: &str| -> Vec<f64> {
        let tail = &text[text.find(from).unwrap_or_else(|| panic!("no {from:?} in {text}"))..];
        tail.split(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-'))
            .filter_map(|w| w.parse::<f64>().ok())
            .collect()
    };
    for atmosphere in ["usa76", "inversion"] {
        let (traced, traced_text) = read("t", &["--atmosphere", atmosphere, "--method", "trace"]);
        let (quad, text) = read("q", &["--atmosphere", atmosphere]);
        let (asked, _) = read("a", &["--atmosphere", atmosphere, "--method", "quadrature"]);
        assert_eq!(quad, asked, "{atmosphere}: the default is the quadrature");
        assert!(text.contains("Bouguer's quadrature") && text.contains('q'), "{text}");
        assert!(!traced_text.contains("Bouguer's quadrature"), "{traced_text}");
        for (t, q) in traced.iter().zip(&quad) {
            match (t, q) {
                (Some(t), Some(q)) => assert!((t - q).abs() <= 1.5e-4, "{atmosphere}: {t} vs {q}"),
                (None, None) => {}
                other => panic!("{atmosphere}: {other:?}"),
            }
        }
        assert!(traced.iter().any(Option::is_some));
        let (t, q) = (numbers_after(&traced_text, "dispersion:"), numbers_after(&text, "dispersion:"));
        assert!(t.len() == q.len() && t.len() > 20, "{atmosphere}: {t:?} vs {q:?}");
        for (x, y) in t.iter().zip(&q) {
            assert!((x - y).abs() <= 0.0101, "{atmosphere}: {x} vs {y}\n{traced_text}\n{text}");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}
