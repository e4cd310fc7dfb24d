//! The tabulated phase function: Petzold's average particle phase function from the shared CSV
//! against the published numbers, exact results for a table that is a pure power law, a table
//! of Henyey–Greenstein values, and loader errors that name the file and line.

mod phase_common;

use morgana::media::phase::{PhaseFunction, TabulatedPhase};
use phase_common::{one_minus_cos_deg, petzold_path, petzold_rows, sampled_mean_cosine, sphere_integral};
use std::f64::consts::PI;
use std::path::PathBuf;

const NM: f64 = 550.0;

fn petzold_table() -> TabulatedPhase {
    TabulatedPhase::from_csv(&petzold_path()).unwrap_or_else(|e| panic!("{e}"))
}

/// Quadrature breakpoints: the table's angles and the documented floor angle θ₀/1000.
fn breaks(rows: &[(f64, f64)]) -> Vec<f64> {
    let mut b: Vec<f64> = rows.iter().map(|r| r.0).collect();
    b.push(rows[0].0 / 1000.0);
    b
}

#[test]
fn petzold_is_normalised_over_the_sphere() {
    let t = petzold_table();
    let rows = petzold_rows();
    let integral = sphere_integral(&|mu| t.eval(mu), &breaks(&rows));
    assert!((integral - 1.0).abs() < 1e-9, "∫ p dω = {integral}");
    // Mobley et al. (1993) publish the table as a normalised phase function: with the forward
    // extension it integrates to 1 within 1 %.
    let raw = t.raw_integral();
    assert!((raw - 1.0).abs() < 0.01, "raw integral of the published table {raw}");
    println!("Petzold: raw integral {raw:.5}");
}

#[test]
fn petzold_passes_through_the_table_and_interpolates_log_log_between_its_angles() {
    let t = petzold_table();
    let rows = petzold_rows();
    let raw = t.raw_integral();
    for &(deg, value) in &rows {
        let got = t.eval(deg.to_radians().cos()) * raw;
        assert!((got / value - 1.0).abs() < 1e-9, "at {deg}°: {got} vs table {value}");
    }
    // Between log-spaced angles a power law in θ gives the geometric mean at the geometric-mean
    // angle; the interpolation (a power law in 1 − cos θ) agrees to 0.5 % everywhere.
    for w in rows.windows(2) {
        let (a, b) = (w[0], w[1]);
        let mid = (a.0 * b.0).sqrt();
        let s = (b.1 / a.1).ln() / (b.0 / a.0).ln();
        let want = a.1 * (mid / a.0).powf(s);
        let got = t.eval(mid.to_radians().cos()) * raw;
        assert!((got / want - 1.0).abs() < 5e-3, "at {mid:.4}°: {got} vs log-log-in-θ {want}");
    }
}

#[test]
fn petzold_mean_cosine_and_backscatter_match_the_published_values() {
    let t = petzold_table();
    let g = t.mean_cosine();
    // Mobley (1994) and the Ocean Optics Web Book: the mean cosine of the average particle phase
    // function is 0.924 (Lucifer's HG g).
    assert!((g - 0.924).abs() < 1e-3, "mean cosine {g}");
    let rows = petzold_rows();
    let quadrature = sphere_integral(&|mu| mu * t.eval(mu), &breaks(&rows));
    assert!((quadrature - g).abs() < 1e-9, "∫ μ p dω = {quadrature} vs mean_cosine() {g}");
    let (mean, sem) = sampled_mean_cosine(&PhaseFunction::Tabulated(t.clone()), NM, 400_000, 80);
    assert!((mean - g).abs() < 5.0 * sem, "sampled {mean} ± {sem}");
    // The backscatter fraction quoted for this phase function is 0.0183 (Mobley 1994).
    let back = 1.0 - t.scattered_within(90.0);
    let back_quadrature = sphere_integral(&|mu| if mu < 0.0 { t.eval(mu) } else { 0.0 }, &breaks(&rows));
    assert!((back - back_quadrature).abs() < 1e-9, "B = {back} vs quadrature {back_quadrature}");
    assert!((back - 0.0183).abs() < 3e-4, "backscatter fraction {back}");
    println!("Petzold: mean cosine {g:.5} (published 0.924), sampled {mean:.5} ± {sem:.5}; B = {back:.5} (0.0183)");
}

#[test]
fn petzold_forward_peak_below_the_table_is_an_extrapolated_power_law() {
    let t = petzold_table();
    let rows = petzold_rows();
    let (theta0, beta0) = rows[0];
    let m = -(rows[1].1 / beta0).ln() / (rows[1].0 / theta0).ln(); // β ∝ θ^−m, m ≈ 1.347
    // Small-angle closed form of the power law's share below θ₀: 2π β₀ θ₀² / (2 − m).
    let th0 = theta0.to_radians();
    let want = 2.0 * PI * beta0 * th0 * th0 / (2.0 - m) / t.raw_integral();
    let got = t.fraction_below_first_angle();
    assert!((got / want - 1.0).abs() < 0.01, "share below {theta0}°: {got} vs power law {want}");
    assert!((t.scattered_within(theta0) - got).abs() < 1e-12);
    // The power law continues to θ₀/1000 and is constant below, so p(cos 0) is finite.
    let (first, floor) = t.forward_angles_deg();
    assert_eq!((first, floor), (0.1, 1e-4));
    let at_floor = beta0 * (floor / theta0).powf(-m) / t.raw_integral();
    for mu in [1.0, one_minus_cos_deg(floor * 0.5).mul_add(-1.0, 1.0)] {
        let p = t.eval(mu);
        assert!(p.is_finite() && (p / at_floor - 1.0).abs() < 1e-5, "p({mu}) = {p} vs {at_floor}");
    }
    let below_floor = t.scattered_within(floor);
    println!(
        "Petzold: {:.3} % of scattering below {theta0}° (power law θ^-{m:.3}), {:.4} % below {floor}°; p(0°) = {:.4e} sr⁻¹",
        100.0 * got,
        100.0 * below_floor,
        t.eval(1.0)
    );
}

#[test]
fn a_power_law_table_is_reproduced_exactly() {
    // β = x^−1/2 with x = 1 − cos θ: the interpolation is exact, so with the constant below the
    // floor x_c the normalised density is x^−1/2 / (2π (2√2 − √x_c)) and
    // 1 − ⟨μ⟩ = 2π [(2/3)(2^{3/2} − x_c^{3/2}) + x_c^{3/2}/2] / (2π (2√2 − √x_c)).
    let angles = [1.0, 2.0, 5.0, 10.0, 30.0, 60.0, 90.0, 120.0, 150.0, 180.0];
    let values: Vec<f64> = angles.iter().map(|a| one_minus_cos_deg(*a).powf(-0.5)).collect();
    let t = TabulatedPhase::from_samples(&angles, &values).unwrap();
    let xc = one_minus_cos_deg(1.0 / 1000.0);
    let total = 2.0 * PI * (2.0 * 2f64.sqrt() - xc.sqrt());
    for deg in [0.01, 0.7, 3.3, 45.0, 100.0, 179.0] {
        let mu = 1.0 - one_minus_cos_deg(deg);
        let want = (1.0 - mu).powf(-0.5) / total;
        let got = t.eval(mu);
        assert!((got / want - 1.0).abs() < 1e-9, "at {deg}°: {got} vs {want}");
    }
    let moment = 2.0 * PI * ((2.0 / 3.0) * (2f64.powf(1.5) - xc.powf(1.5)) + xc.powf(1.5) / 2.0) / total;
    assert!((t.mean_cosine() - (1.0 - moment)).abs() < 1e-12, "{} vs {}", t.mean_cosine(), 1.0 - moment);
    assert!((t.raw_integral() - total).abs() < 1e-12 * total);
}

#[test]
fn a_table_of_henyey_greenstein_values_behaves_like_henyey_greenstein() {
    let g: f64 = 0.8;
    let hg = |mu: f64| (1.0 - g * g) / (4.0 * PI * (1.0 + g * g - 2.0 * g * mu).powf(1.5));
    let angles: Vec<f64> = (1..=360).map(|i| i as f64 * 0.5).collect();
    let values: Vec<f64> = angles.iter().map(|a| hg(a.to_radians().cos())).collect();
    let t = TabulatedPhase::from_samples(&angles, &values).unwrap();
    assert!((t.mean_cosine() - g).abs() < 1e-4, "mean cosine {}", t.mean_cosine());
    // Log–log interpolation of HG at 0.5° steps is accurate to a few 1e-4.
    assert!((t.raw_integral() - 1.0).abs() < 5e-4, "raw integral {}", t.raw_integral());
    for deg in [0.5, 0.75, 13.3, 90.25, 179.9] {
        let mu = f64::cos(deg * PI / 180.0);
        assert!((t.eval(mu) / hg(mu) - 1.0).abs() < 1e-3, "at {deg}°: {} vs {}", t.eval(mu), hg(mu));
    }
    // Below the first angle the slope of the first two rows is extended: HG is flat there, so
    // a slight slope carried over six decades of 1 − cos θ overshoots at 0° (by 7 %), on a share
    // of the scattering close to HG's own 2π p(1) (1 − cos 0.5°) = 8.6e-4.
    let hg_share = 2.0 * PI * hg(1.0) * one_minus_cos_deg(0.5);
    assert!((t.fraction_below_first_angle() - hg_share).abs() < 1e-4, "{}", t.fraction_below_first_angle());
}

/// A CSV file with `text`, in the temporary directory, unique per test.
fn temp_csv(name: &str, text: &str) -> PathBuf {
    let path = std::env::temp_dir().join(format!("morgana-phase-{}-{name}.csv", std::process::id()));
    std::fs::write(&path, text).unwrap();
    path
}

fn csv_error(name: &str, text: &str) -> String {
    let path = temp_csv(name, text);
    let e = PhaseFunction::tabulated_csv(&path).map(|_| ()).unwrap_err();
    std::fs::remove_file(&path).ok();
    e
}

#[test]
fn table_errors_name_the_file_and_line() {
    let missing = PathBuf::from("/nonexistent/petzold_average_particle_phase_function.csv");
    let e = PhaseFunction::tabulated_csv(&missing).map(|_| ()).unwrap_err();
    assert!(e.contains("/nonexistent/petzold_average_particle_phase_function.csv not found"), "{e}");
    let e = csv_error("garbage", "# comment\nangle,value\n1,2\n2;3\n180,1\n");
    assert!(e.ends_with("garbage.csv:4: expected two numbers 'angle_deg,value_per_sr', found '2;3'"), "{e}");
    let e = csv_error("second-header", "1,2\nangle,value\n180,1\n");
    assert!(e.contains("second-header.csv:2: expected two numbers"), "{e}");
    let e = csv_error("decreasing", "#\n1,2\n5,1\n4,1\n180,1\n");
    assert!(e.contains("decreasing.csv:4: angle 4° follows 5°: angles must increase strictly"), "{e}");
    let e = csv_error("negative", "1,2\n5,-1\n180,1\n");
    assert!(e.contains("negative.csv:2: value -1 at 5° is not allowed: values must be positive and finite"), "{e}");
    let e = csv_error("zero-angle", "0,2\n5,1\n180,1\n");
    assert!(e.contains("zero-angle.csv:1: angle 0° is out of range: angles must lie in (0°, 180°]"), "{e}");
    let e = csv_error("short", "1,2\n5,1\n170,1\n");
    assert!(e.contains("short.csv:3: the last angle is 170°: the table must end at 180°"), "{e}");
    let e = csv_error("empty", "# nothing\n");
    assert!(e.contains("empty.csv: 0 row(s): need at least 2 angles"), "{e}");
    let e = TabulatedPhase::from_samples(&[1.0, 180.0], &[1.0]).unwrap_err();
    assert!(e.contains("2 angles but 1 values"), "{e}");
}
