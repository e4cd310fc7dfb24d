//! The project's own photometric files (`luminaires/*.ies`, `*.ldt`, written by
//! `scripts/gen_luminaires.py` from analytic distributions) load, and their webs carry the flux
//! the generator integrated from the analytic functions by its own quadrature (stated in each
//! file: LORL × lamp flux in EULUMDAT, lamp lumens × LOR or `[_FLUX_ANALYTIC_LM]` in LM-63), with
//! the shape facts each was designed for.

use morgana::luminaire::{Photometry, Symmetry, load_file};
use std::path::PathBuf;

fn path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("luminaires").join(name)
}

fn load(name: &str) -> Photometry {
    load_file(&path(name)).unwrap_or_else(|e| panic!("{name} does not load: {e}"))
}

/// The value of an LM-63 keyword line `[KEY] value`.
fn keyword(name: &str, key: &str) -> f64 {
    let text = std::fs::read_to_string(path(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
    let line =
        text.lines().find(|l| l.starts_with(&format!("[{key}]"))).unwrap_or_else(|| panic!("{name}: no [{key}]"));
    line[key.len() + 2..].trim().parse().unwrap_or_else(|e| panic!("{name}: [{key}]: {e}"))
}

/// The generator's midpoint quadrature of the analytic function against morgana's trapezoidal
/// web: they differ by the web's sampling (5° × 15° for the EULUMDAT files), well under 1 %.
const FLUX_TOLERANCE: f64 = 0.005;

fn close(name: &str, web: f64, want: f64) {
    println!("{name}: web {web:.1} lm, generator {want:.1} lm, {:+.3}%", 100.0 * (web / want - 1.0));
    assert!((web / want - 1.0).abs() < FLUX_TOLERANCE, "{name}: web {web} lm vs {want} lm");
}

#[test]
fn road_batwing_carries_its_flux_along_the_road() {
    let name = "road_batwing.ies";
    let p = load(name);
    assert!(p.absolute, "{name}: absolute photometry");
    assert_eq!(p.symmetry, Symmetry::C0C180);
    close(name, p.flux_lm(), keyword(name, "_FLUX_ANALYTIC_LM"));
    // The batwing: peak along the road (C90) near γ = 65°, more light to the street side (C0)
    // than to the house side (C180) at 60°, nothing above the horizon.
    let (_, c, g) = p.web.peak();
    assert!((c - 90.0).abs() < 1e-9 || (c - 270.0).abs() < 1e-9, "peak at C = {c}");
    assert!((g - 65.0).abs() <= 1.0, "peak at γ = {g}");
    assert!(p.web.intensity_at(0.0, 60.0) > 2.0 * p.web.intensity_at(180.0, 60.0));
    assert_eq!(p.web.flux_between_lm(-1.0, 0.0), 0.0, "upward flux");
}

#[test]
fn underwater_flood_is_a_54_degree_beam_with_85_percent_lor() {
    let name = "underwater_flood_54.ies";
    let p = load(name);
    assert!(!p.absolute);
    assert_eq!(p.symmetry, Symmetry::Rotational);
    let lamp = p.lamp_flux_lm.expect("lamp lumens");
    close(name, p.flux_lm(), 0.85 * lamp);
    // Half maximum at γ = 27° (FWHM 54°).
    let peak = p.web.intensity_at(0.0, 0.0);
    assert!((p.web.intensity_at(0.0, 27.0) / peak - 0.5).abs() < 0.005);
}

#[test]
fn office_pendant_sends_a_third_down() {
    let name = "office_pendant.ldt";
    let p = load(name);
    assert_eq!(p.symmetry, Symmetry::Quadrant);
    close(name, p.flux_lm(), p.lorl_percent.unwrap() / 100.0 * p.lamp_flux_lm.unwrap());
    let down = 100.0 * p.web.flux_between_lm(0.0, 1.0) / p.flux_lm();
    assert!((down - p.dff_percent.unwrap()).abs() < 0.5, "downward {down}% vs DFF {}", p.dff_percent.unwrap());
    assert!((p.dff_percent.unwrap() - 33.0).abs() < 1e-9);
}

#[test]
fn office_linear_led_is_all_downward_from_a_1500_mm_opening() {
    let name = "office_linear_led.ldt";
    let p = load(name);
    close(name, p.flux_lm(), p.lorl_percent.unwrap() / 100.0 * p.lamp_flux_lm.unwrap());
    assert_eq!(p.web.flux_between_lm(-1.0, 0.0), 0.0);
    // Narrower along the length (C0) than across it (C90).
    assert!(p.web.intensity_at(0.0, 60.0) < p.web.intensity_at(90.0, 60.0));
}
