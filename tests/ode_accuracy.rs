//! `morgana accuracy`: the measurement runs, its numbers obey the closed form and the orders of
//! the methods, the CSV and PNG are written, and bad options exit with code 2.

use morgana::atmosphere::horizon_ray::HorizonRay;
use morgana::cli::accuracy::{AccuracyArgs, run as run_cli};
use morgana::ode::accuracy::{Plan, Problem, TestRay, measure};
use morgana::ode::{Integrator, Method, OdeState};
use std::path::PathBuf;
use std::process::Command;

fn scratch(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("morgana-accuracy-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The quick plan on the default problem: every configuration succeeds, Dormand–Prince's error
/// falls with the tolerance, Euler's falls tenfold per tenfold smaller step (order 1), and the
/// step counts are L/h for the fixed-step methods.
#[test]
fn quick_measurement_obeys_the_orders() {
    let problem = Problem::new(1e-3, 1000.0).unwrap();
    let report = measure(&problem, &Plan::quick(&problem));
    assert!(report.failures.is_empty(), "{:?}", report.failures);
    let of = |m: &str| report.points.iter().filter(|p| p.method == m).copied().collect::<Vec<_>>();
    let dp = of("dopri5");
    assert_eq!(dp.len(), 4);
    assert!(dp.windows(2).all(|w| w[1].endpoint_error_m < w[0].endpoint_error_m), "{dp:?}");
    let euler = of("euler");
    for w in euler.windows(2) {
        let order = (w[0].endpoint_error_m / w[1].endpoint_error_m).log10() / (w[0].parameter / w[1].parameter).log10();
        assert!((order - 1.0).abs() < 0.1, "Euler order {order}");
    }
    for p in euler.iter().chain(&of("rk4")) {
        assert_eq!(p.steps, (1000.0 / p.parameter).ceil() as u64, "{p:?}");
    }
    assert!(report.points.iter().all(|p| p.time_s > 0.0 && p.time_s.is_finite()));
    assert!(!report.speedups.is_empty());
    assert!(report.speedups.iter().all(|s| s.over_rk4.is_some() || s.over_euler.is_some()));
}

#[test]
fn cli_writes_csv_and_png() {
    let dir = scratch("cli");
    let (csv, png) = (dir.join("acc.csv"), dir.join("acc.png"));
    let out = Command::new(env!("CARGO_BIN_EXE_morgana"))
        .args(["accuracy", "--quick", "--k", "-2e-3", "--length-m", "500", "--csv"])
        .arg(&csv)
        .arg("--png")
        .arg(&png)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("goal dopri5 >= 100x faster than euler") && text.contains("wrote"), "{text}");
    let table = std::fs::read_to_string(&csv).unwrap();
    let mut lines = table.lines();
    assert_eq!(lines.next(), Some("method,parameter,endpoint_error_m,time_s,steps,rhs_evals"));
    assert_eq!(lines.count(), 10, "4 tolerances + 3 + 3 step sizes");
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(&png).unwrap()));
    let info = decoder.read_info().unwrap().info().clone();
    assert_eq!((info.width, info.height), (1320, 428));
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 2, "no temporary files left");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_options_exit_2_and_write_nothing() {
    let dir = scratch("bad");
    let csv = dir.join("acc.csv");
    for (args, says) in [
        (vec!["--field", "tanh"], "--field: found \"tanh\""),
        (vec!["--k", "0"], "--k: found 0"),
        (vec!["--length-m", "-5"], "--length-m: found -5"),
        (vec!["--height-m", "10"], "--height-m: only with --field usa76"),
        (vec!["--field", "usa76", "--k", "1e-3"], "--k: only with --field linear"),
        (vec!["--field", "usa76", "--elevation-deg", "0"], "--elevation-deg: found 0"),
        (vec!["--field", "usa76", "--elevation-deg", "5", "--length-m", "1e6"], "tropopause"),
    ] {
        let out = Command::new(env!("CARGO_BIN_EXE_morgana"))
            .arg("accuracy")
            .args(&args)
            .arg("--csv")
            .arg(&csv)
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(says), "{args:?}: {err}");
    }
    assert!(!csv.exists());
    let args = AccuracyArgs {
        field: "linear".into(),
        k: Some(f64::NAN),
        length_m: Some(1.0),
        height_m: None,
        elevation_deg: None,
        wavelength_nm: None,
        csv: None,
        png: None,
        quick: true,
        project: false,
    };
    assert!(run_cli(&args).is_err());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The USA76 ray near the horizon: Dormand–Prince at a tight tolerance lands where Bouguer's
/// invariant by quadrature puts the end (two independent estimates of one point), and RK4 and
/// Euler converge toward that end at their orders, 4 and 1.
#[test]
fn a_ray_near_the_horizon_lands_where_bouguers_invariant_puts_it() {
    let ray = HorizonRay::new(10.0, 0.5, 550.0, 100_000.0).unwrap();
    let field = |p| ray.n_grad(p);
    let (p0, d0) = ray.start();
    let mut state = OdeState::launch(&field, p0, d0).unwrap();
    let mut ode = Integrator::new(Method::dormand_prince(1e-12, 1e-12)).unwrap();
    ode.integrate_to(&field, &mut state, ray.length_m()).unwrap();
    let miss = (state.y.r - ray.end()).length();
    assert!(miss < 1e-7, "Dormand–Prince at 1e-12 ends {miss:e} m from the quadrature's end");
    // RK4 at 10 and 5 km steps and Euler at 1 km and 100 m: errors far above the floor of
    // ~1e-10 m that rounding in 100 km coordinates and the quadrature leave.
    let plan = Plan {
        tolerances: vec![1e-6, 1e-9],
        euler_steps_m: vec![1000.0, 100.0],
        rk4_steps_m: vec![10_000.0, 5_000.0],
        samples: 1,
        min_sample_s: 0.0,
        project: false,
    };
    let report = measure(&ray, &plan);
    assert!(report.failures.is_empty(), "{:?}", report.failures);
    let of = |m: &str| report.points.iter().filter(|p| p.method == m).copied().collect::<Vec<_>>();
    let order = |w: &[morgana::ode::accuracy::Point]| {
        (w[0].endpoint_error_m / w[1].endpoint_error_m).log10() / (w[0].parameter / w[1].parameter).log10()
    };
    let rk4 = of("rk4");
    assert!((order(&rk4[..2]) - 4.0).abs() < 0.2, "RK4 order {} ({rk4:?})", order(&rk4[..2]));
    let euler = of("euler");
    assert!((order(&euler[..2]) - 1.0).abs() < 0.1, "Euler order {}", order(&euler[..2]));
    assert!(report.ray.contains("USA76") && report.title.contains("USA76"));
}
