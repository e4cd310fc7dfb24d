//! Lines of sight (`atmosphere::refraction::sight`): the horizon, the hidden height and the
//! images of a distant point, against closed forms — straight rays in air of n = 1, and the
//! exact paths in n = n_s (r/R)^(−k) — and the hot road's mirage.

use morgana::atmosphere::Atmosphere;
use morgana::atmosphere::refraction::sight::{hidden_height, horizon, images, straight_elevation};
use morgana::atmosphere::refraction::terrestrial::{RadialAir, Reach, follow, radial_air};

const R: f64 = 6_371_000.0;

/// n = n_s (r/R)^(−k) as n − 1 and dn/dh at height h (expm1/ln1p keep n − 1 precise).
fn power_law(k: f64, n_s: f64) -> impl Fn(f64) -> (f64, f64) {
    move |h: f64| {
        let rel = (-k * (h / R).ln_1p()).exp_m1();
        ((n_s - 1.0) + n_s * rel, -k * n_s * (1.0 + rel) / (R + h))
    }
}

/// Without refraction (n = 1, k = 0) the grazing ray is the tangent: dip = horizon angle =
/// arccos(R/r₀), hidden height R/cos(φ − φ_h) − R, and a point is seen along the straight line.
/// In n ∝ r^(−k) the path W = n r = c / cos((1 − k)(φ − φ_p)) gives, for the ray grazing the
/// ground, cos e_g = (R/r₀)^(1−k), φ_h = −e_g/(1 − k), hidden height R cos((1 − k)(φ − φ_h))^(−1/(1−k)) − R,
/// and any ray's height at φ in closed form, which each image must match. Measured: dip and
/// horizon within 3·10⁻¹⁰ rad, hidden heights within 1.5·10⁻⁶ m (both the grazing ray's 1 µm
/// clearance), images' rays within 1.1·10⁻⁷ m of the point.
#[test]
fn the_horizon_hidden_heights_and_images_follow_the_closed_forms() {
    for (k, n_s) in [(0.0, 1.0), (0.17, 1.0003), (0.6, 1.0003)] {
        let air = RadialAir { refractivity: power_law(k, n_s), kink_heights_m: vec![], ground_radius_m: R, top_m: 1e5 };
        for h0 in [2.0, 100.0, 3000.0] {
            let r0 = R + h0;
            let h = horizon(&air, h0).unwrap().unwrap();
            // cos e_g = (R/r₀)^(1−k); 1 − cos e_g = −expm1((1 − k) ln(R/r₀)).
            let one_minus_cos = -((1.0 - k) * (-(h0 / R).ln_1p())).exp_m1();
            let e_g = -2.0 * (0.5 * one_minus_cos).sqrt().asin();
            let phi_h = -e_g / (1.0 - k);
            eprintln!(
                "k {k}, {h0} m: dip {:.6}° (closed {:.6}°), horizon {:.4} km (closed {:.4})",
                h.elevation_rad.to_degrees(),
                e_g.to_degrees(),
                h.angle_rad * R / 1e3,
                phi_h * R / 1e3
            );
            // The grazing ray's perigee is 1 µm up (GRAZE_M), which raises the dip by about
            // 10⁻⁶ m/(R |e_g|): 2·10⁻¹⁰ rad from 2 m.
            assert!((h.elevation_rad - e_g).abs() < 1e-9, "k {k}, {h0} m: dip {} vs {e_g}", h.elevation_rad);
            assert!((h.angle_rad - phi_h).abs() < 1e-9, "k {k}, {h0} m: horizon {} vs {phi_h}", h.angle_rad);
            let phi = 1.5 * phi_h;
            let hidden = hidden_height(&air, h0, phi).unwrap();
            let closed = R * (-(((1.0 - k) * (phi - phi_h)).cos().ln()) / (1.0 - k)).exp_m1();
            eprintln!("  hidden at {:.3} km: {hidden:.6} m (closed {closed:.6})", phi * R / 1e3);
            assert!((hidden - closed).abs() < 1e-5, "k {k}, {h0} m: hidden {hidden} vs {closed}");
            assert_eq!(hidden_height(&air, h0, 0.5 * phi_h).unwrap(), 0.0);
            // A point twice the hidden height up is seen once; the image's ray reaches it by the
            // closed form: W(φ)/W₀ = cos e / cos((1 − k)φ + e).
            let target = 2.0 * closed + 1.0;
            let seen = images(&air, h0, phi, target).unwrap();
            assert_eq!(seen.len(), 1, "k {k}, {h0} m: {seen:?}");
            let e = seen[0];
            let ratio = e.cos() / ((1.0 - k) * phi + e).cos();
            let height = r0 * (ratio.ln() / (1.0 - k)).exp() - R;
            eprintln!(
                "  Δdip {:.1e} rad, Δhorizon {:.1e} rad, Δhidden {:.1e} m, image's Δh {:.1e} m",
                h.elevation_rad - e_g,
                h.angle_rad - phi_h,
                hidden - closed,
                height - target
            );
            // The image is bisected to 10⁻¹² rad: ≤ 10⁻¹²·φR in height (5·10⁻⁷ m at 460 km).
            assert!((height - target).abs() < 1e-6, "k {k}, {h0} m: the image's ray is at {height} m, not {target}");
            if k == 0.0 {
                let straight = straight_elevation(R, h0, phi, target);
                assert!((e - straight).abs() < 1e-10, "{e} vs {straight}");
            }
            // Half the hidden height up: hidden.
            assert!(images(&air, h0, phi, 0.5 * closed).unwrap().is_empty());
        }
    }
}

/// Over the hot road a point half a metre up a kilometre off is seen once, from an eye 1.5 m
/// up, along a ray that dips towards the hot asphalt, turns up before it and climbs to the
/// point: the point appears lower than the straight line to it (the inferior mirage), where in
/// standard air it appears higher. The image's ray reaches the point (followed again, within
/// 1 µm). A layer ten times thinner and twice as hot (synthetic) makes rays cross: the same
/// point is seen twice, each image's ray reaching it.
#[test]
fn mirages_show_a_distant_point_below_its_place_and_twice() {
    let road = Atmosphere::builtin("hot_road").unwrap();
    let air = radial_air(&road, 550.0).unwrap();
    let (h0, d, target) = (1.5, 1000.0, 0.5);
    let phi = d / air.ground_radius_m;
    let straight = straight_elevation(air.ground_radius_m, h0, phi, target);
    let seen = images(&air, h0, phi, target).unwrap();
    eprintln!(
        "hot road: {:?} deg, straight {:.6} deg",
        seen.iter().map(|e| e.to_degrees()).collect::<Vec<_>>(),
        straight.to_degrees()
    );
    assert_eq!(seen.len(), 1, "{seen:?}");
    let p = follow(&air, h0, seen[0], phi, 1e-12).unwrap();
    let Reach::Aloft { height_m, .. } = p.reach else { panic!("{p:?}") };
    assert!((height_m - target).abs() < 1e-6 && p.perigee_angle_rad.is_some_and(|a| a < phi), "{p:?}");
    assert!(seen[0] < straight - 1e-3, "{} vs {straight}", seen[0]);
    let usa76 = Atmosphere::usa76();
    let plain = radial_air(&usa76, 550.0).unwrap();
    let seen_plain = images(&plain, h0, phi, target).unwrap();
    assert!(seen_plain.len() == 1 && seen_plain[0] > straight, "{seen_plain:?} vs {straight}");
    // n − 1 = N_a(1 − 0.2 e^(−h/L)): 20 % less refractivity at the surface, over L = 0.67 m.
    let (n_a, l) = (2.8e-4, 0.667);
    let thin = RadialAir {
        refractivity: move |h: f64| (n_a * (1.0 - 0.2 * (-h / l).exp()), n_a * 0.2 * (-h / l).exp() / l),
        kink_heights_m: vec![],
        ground_radius_m: R,
        top_m: 1e4,
    };
    let (h0, d, target) = (1.0, 500.0, 2.1);
    let seen = images(&thin, h0, d / R, target).unwrap();
    eprintln!("thin layer: {:?} deg", seen.iter().map(|e| e.to_degrees()).collect::<Vec<_>>());
    assert_eq!(seen.len(), 2, "{seen:?}");
    for &e in &seen {
        let p = follow(&thin, h0, e, d / R, 1e-12).unwrap();
        let Reach::Aloft { height_m, .. } = p.reach else { panic!("{p:?}") };
        assert!((height_m - target).abs() < 1e-6, "{e}: {height_m}");
    }
}

/// `morgana refraction --targets` prints the horizon and each target's images with the library's
/// numbers, marks a hidden target as such, writes the CSV, and names a malformed target.
#[test]
fn the_command_writes_the_lines_of_sight() {
    let dir = std::env::temp_dir().join(format!("morgana-sight-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let csv = dir.join("s.csv");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_morgana"))
        .args(["refraction", "--atmosphere", "usa76", "--observer-height-m", "2", "--targets", "10:5,40:30", "--csv"])
        .arg(&csv)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("horizon") && text.contains("hidden below the horizon"), "{text}");
    let table = std::fs::read_to_string(&csv).unwrap();
    let rows: Vec<Vec<&str>> = table.lines().skip(1).map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 2, "{table}");
    let usa76 = Atmosphere::usa76();
    let air = radial_air(&usa76, 550.0).unwrap();
    let phi = 10e3 / air.ground_radius_m;
    let e = images(&air, 2.0, phi, 5.0).unwrap();
    assert_eq!(rows[0][5], format!("{:.12}", e[0].to_degrees()), "{:?}", rows[0]);
    assert_eq!(rows[0][2], format!("{:.9}", hidden_height(&air, 2.0, phi).unwrap()));
    assert!(rows[1][4].is_empty() && rows[1][5].is_empty(), "{:?}", rows[1]);
    let bad = std::process::Command::new(env!("CARGO_BIN_EXE_morgana"))
        .args(["refraction", "--targets", "10"])
        .output()
        .unwrap();
    assert!(!bad.status.success() && String::from_utf8_lossy(&bad.stderr).contains("DISTANCE_KM:HEIGHT_M"));
    let _ = std::fs::remove_dir_all(&dir);
}

/// Hard cases: 150 random observers and targets (eyes 0–3 000 m, targets 0.01–300 km away and
/// 0–5 000 m up, the eye on the ground one time in four) through USA76, the hot road and the
/// inversion: every horizon, hidden height and image is in range — the hidden height ≥ 0 (∞
/// where the grazing ray leaves the air short of the target), images within ±90°, each image's
/// ray reaching its point within 1 µm — or an error that names a duct.
#[test]
fn random_lines_of_sight_are_finite_or_clear_errors() {
    let mut rng = morgana::rng::Rng::for_task(11, morgana::rng::Stream::Eye, 0);
    for name in ["usa76", "hot_road", "inversion"] {
        let atmosphere = Atmosphere::builtin(name).unwrap();
        let air = radial_air(&atmosphere, 550.0).unwrap();
        let mut answered = 0;
        for i in 0..50 {
            let h0 = if i % 4 == 0 { 0.0 } else { rng.uniform() * rng.uniform() * 3000.0 };
            let d = 10.0 + rng.uniform() * rng.uniform() * 300_000.0;
            let target = rng.uniform() * rng.uniform() * 5000.0;
            let phi = d / air.ground_radius_m;
            let result = horizon(&air, h0).and_then(|h| {
                let hidden = hidden_height(&air, h0, phi)?;
                Ok((h, hidden, images(&air, h0, phi, target)?))
            });
            match result {
                Ok((h, hidden, seen)) => {
                    answered += 1;
                    if let Some(h) = h {
                        assert!(
                            h.elevation_rad <= 0.0 && h.angle_rad.is_finite() && h.angle_rad >= 0.0,
                            "{name} {h0}: {h:?}"
                        );
                    }
                    // ∞: the grazing ray leaves the air short of that distance; all is hidden.
                    assert!(hidden >= 0.0, "{name} {h0} {d}: hidden {hidden}");
                    for e in seen {
                        assert!(e.abs() < std::f64::consts::FRAC_PI_2, "{name}: {e}");
                        let p = follow(&air, h0, e, phi, 1e-12).unwrap();
                        let Reach::Aloft { height_m, .. } = p.reach else { panic!("{name} {h0} {d} {target}: {p:?}") };
                        assert!((height_m - target).abs() < 1e-6 + 1e-9 * d, "{name} {h0} {d} {target}: {height_m}");
                    }
                }
                Err(e) => assert!(e.contains("duct"), "{name} {h0} {d} {target}: {e}"),
            }
        }
        eprintln!("{name}: {answered} of 50 answered");
        // Through the inversion, lines of sight that cross its duct are refused.
        assert!(answered >= if name == "inversion" { 10 } else { 45 }, "{name}: {answered}");
    }
}

/// A point far above the air and nearly overhead (100 km up, 5 km along the ground; a satellite,
/// say) is seen, along a ray that reaches it — the rays just steeper leave the air short of its
/// ground distance, which must not read as the horizon's edge — and its refraction, relative to the
/// straight line to it, is below the astronomical refraction at that zenith distance (about
/// 58″·tan z) by the ray's offset over its length: between 80 % and 100 % of it.
#[test]
fn a_point_high_overhead_is_seen() {
    use morgana::atmosphere::refraction::{Settings, Tracer};
    let usa76 = Atmosphere::usa76();
    let air = radial_air(&usa76, 550.0).unwrap();
    let (h0, phi, target) = (2.0, 5e3 / air.ground_radius_m, 1e5);
    let seen = images(&air, h0, phi, target).unwrap();
    assert_eq!(seen.len(), 1, "{seen:?}");
    let p = follow(&air, h0, seen[0], phi, 1e-12).unwrap();
    let Reach::Aloft { height_m, .. } = p.reach else { panic!("{p:?}") };
    assert!((height_m - target).abs() < 1e-3, "{height_m}");
    let refraction = seen[0] - straight_elevation(air.ground_radius_m, h0, phi, target);
    let astronomical =
        Tracer::new(&usa76, 550.0, h0, Settings::default()).unwrap().refraction_rad(seen[0]).unwrap().unwrap();
    let ratio = refraction / astronomical;
    eprintln!(
        "refraction {:.4}″, astronomical {:.4}″, ratio {ratio:.4}",
        refraction * 206_264.8,
        astronomical * 206_264.8
    );
    assert!((0.8..1.0).contains(&ratio), "{ratio}");
}
