//! Every shared photometric file (`../shared/data/luminaires/`) loads, with the header facts the
//! file states and a flux that agrees with the file's own numbers:
//! - EULUMDAT: the web's flux against LORL × lamp flux, and its downward fraction against DFF;
//! - IES: the web's flux against a zonal-lumen sum over the file's own table, computed here from
//!   the raw numbers by a parser and quadrature independent of the reader (relative files state
//!   only the lamp flux, absolute files none).
//!
//! `cargo test --release --test luminaire_files -- --nocapture` prints the mismatches. Without
//! `../shared` these tests skip (tests/common/shared.rs); the CIE LED spectra are the project's own.

mod common;

use morgana::luminaire::{PhotometricType, Photometry, Symmetry, load_file};
use std::path::PathBuf;

fn shared(rel: &str) -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../shared/data/luminaires")).join(rel)
}

fn load(rel: &str) -> Photometry {
    load_file(&shared(rel)).unwrap_or_else(|e| panic!("{rel} does not load: {e}"))
}

/// What an EULUMDAT file's header says.
struct Ldt {
    file: &'static str,
    maker: &'static str,
    name: &'static str,
    symmetry: Symmetry,
    stored: (usize, usize),
    lamp_sets: usize,
    lamp_flux_lm: f64,
    lorl: f64,
    dff: f64,
    absolute: bool,
}

/// Relative flux mismatch allowed between the web and LORL × lamp flux. The files' tables agree
/// with their stated flux to 0.3% (see the README); the tolerance is well below any scaling
/// error (a lamp set, the cd/klm factor, a symmetry).
const LDT_FLUX_TOLERANCE: f64 = 0.005;

fn check_ldt(x: Ldt) -> Photometry {
    let p = load(x.file);
    assert_eq!(p.format, "EULUMDAT");
    assert_eq!(p.photometric_type, PhotometricType::C);
    assert_eq!(p.manufacturer, x.maker);
    assert_eq!(p.luminaire, x.name);
    assert_eq!(p.symmetry, x.symmetry, "{}", x.file);
    assert_eq!(p.stored_grid, x.stored, "{}", x.file);
    assert_eq!(p.lamps.len(), x.lamp_sets);
    assert_eq!(p.lamp_flux_lm, Some(x.lamp_flux_lm));
    assert_eq!(p.absolute, x.absolute);
    assert_eq!(p.lorl_percent, Some(x.lorl));
    assert_eq!(p.dff_percent, Some(x.dff));
    let stated = x.lorl / 100.0 * x.lamp_flux_lm;
    let web = p.flux_lm();
    let mismatch = web / stated - 1.0;
    println!("{}: stated {stated:.1} lm, web {web:.1} lm, mismatch {:+.3}%", x.file, 100.0 * mismatch);
    assert!(mismatch.abs() < LDT_FLUX_TOLERANCE, "{}: web {web} lm vs stated {stated} lm", x.file);
    p
}

/// The web's downward flux fraction, %.
fn downward_percent(p: &Photometry) -> f64 {
    100.0 * p.web.flux_between_lm(0.0, 1.0) / p.flux_lm()
}

#[test]
fn eulumdatpy_sample1_isym4_two_lamp_sets() {
    if common::shared::shared_data("luminaires").is_none() {
        return;
    }
    let p = check_ldt(Ldt {
        file: "ldt/eulumdatpy_sample1.ldt",
        maker: "Tulux",
        name: "SET",
        symmetry: Symmetry::Quadrant,
        stored: (37, 73),
        lamp_sets: 2,
        lamp_flux_lm: 1983.0,
        lorl: 100.0,
        dff: 87.0,
        absolute: false,
    });
    assert_eq!(p.lamps[1].flux_lm, Some(2643.0));
    assert_eq!(p.web.c_deg().len(), 144);
    assert!((downward_percent(&p) - 87.0).abs() < 0.5);
}

#[test]
fn eulumdatpy_sample2_isym2() {
    if common::shared::shared_data("luminaires").is_none() {
        return;
    }
    let p = check_ldt(Ldt {
        file: "ldt/eulumdatpy_sample2.ldt",
        maker: "Regent",
        name: "TRAQ INS m1200 LED4600-840 AB WH ONF",
        symmetry: Symmetry::C0C180,
        stored: (37, 37),
        lamp_sets: 1,
        lamp_flux_lm: 4600.0,
        lorl: 100.0,
        dff: 100.0,
        absolute: false,
    });
    assert_eq!(p.web.c_deg().len(), 72);
    assert!((downward_percent(&p) - 100.0).abs() < 0.5);
    // Mirror symmetry about C0–C180: I(C, γ) = I(360° − C, γ).
    assert!((p.web.intensity_at(25.0, 20.0) - p.web.intensity_at(335.0, 20.0)).abs() < 1e-9);
}

#[test]
fn eulumdatpy_sample3_isym0() {
    if common::shared::shared_data("luminaires").is_none() {
        return;
    }
    let p = check_ldt(Ldt {
        file: "ldt/eulumdatpy_sample3.ldt",
        maker: "Regent",
        name: "NEO U LED12800-840 BK 0IF CH",
        symmetry: Symmetry::None,
        stored: (24, 37),
        lamp_sets: 1,
        lamp_flux_lm: 12800.0,
        lorl: 100.0,
        dff: 18.3,
        absolute: false,
    });
    assert!((downward_percent(&p) - 18.3).abs() < 0.5);
}

#[test]
fn eulumdatpy_sample4_isym4() {
    if common::shared::shared_data("luminaires").is_none() {
        return;
    }
    let p = check_ldt(Ldt {
        file: "ldt/eulumdatpy_sample4.ldt",
        maker: "ZUMTOBEL",
        name: "TECTON DC 5500-840 L1500 WB 650V WH",
        symmetry: Symmetry::Quadrant,
        stored: (7, 37),
        lamp_sets: 1,
        lamp_flux_lm: 5540.0,
        lorl: 100.0,
        dff: 99.9,
        absolute: false,
    });
    assert!((downward_percent(&p) - 99.9).abs() < 0.5);
    // The table's first values, C0 at γ 0° and 5°, are 509.64 and 514.64 cd/klm (lines 104–105
    // of the file), × 5540 lm / 1000.
    assert!((p.web.intensity_at(0.0, 5.0) - 514.64 * 5.54).abs() < 1e-6);
    assert!((p.web.intensity_at(0.0, 0.0) - 509.64 * 5.54).abs() < 1e-6, "{}", p.web.intensity_at(0.0, 0.0));
}

#[test]
fn eulumdatpy_sample5_bom_rotational_absolute() {
    if common::shared::shared_data("luminaires").is_none() {
        return;
    }
    let p = check_ldt(Ldt {
        file: "ldt/eulumdatpy_sample5.ldt",
        maker: "ERCO GmbH",
        name: "Iku Surface-mounted downlight",
        symmetry: Symmetry::Rotational,
        stored: (1, 91),
        lamp_sets: 1,
        lamp_flux_lm: 611.9,
        lorl: 100.0,
        dff: 100.0,
        absolute: true,
    });
    assert_eq!(p.encoding, "UTF-8 with BOM");
    assert_eq!(p.lamps[0].count, -1);
}

#[test]
fn eulumdatpy_sample8_ityp1_fine_gamma() {
    if common::shared::shared_data("luminaires").is_none() {
        return;
    }
    let p = check_ldt(Ldt {
        file: "ldt/eulumdatpy_sample8.ldt",
        maker: "LEDiL Oy",
        name: "FP15812_STRADA-2X2MXS-VSM_460_2X2MX_HV(V3HD_GEN8)_simulation",
        symmetry: Symmetry::None,
        stored: (72, 181),
        lamp_sets: 1,
        lamp_flux_lm: 400.0,
        lorl: 88.629073034905,
        dff: 100.0,
        absolute: false,
    });
    assert_eq!(p.web.gamma_deg().len(), 181);
}

#[test]
fn eulumdatpy_sample10_up_down_pendant() {
    if common::shared::shared_data("luminaires").is_none() {
        return;
    }
    let p = check_ldt(Ldt {
        file: "ldt/eulumdatpy_sample10.ldt",
        maker: "Waldmann",
        name: "IDOO.pendant - IPP 7000/840/D",
        symmetry: Symmetry::Quadrant,
        stored: (7, 37),
        lamp_sets: 1,
        lamp_flux_lm: 7000.0,
        lorl: 100.0,
        dff: 33.0,
        absolute: false,
    });
    assert!((downward_percent(&p) - 33.0).abs() < 0.5);
}

#[test]
fn ledvance_sym_30_crlf() {
    if common::shared::shared_data("luminaires").is_none() {
        return;
    }
    let p = check_ldt(Ldt {
        file: "ldt/ledvance_4058075580596_SYM_30.ldt",
        maker: "LEDVANCE GmbH",
        name: "FL MAX LUM 600W 757 SYM 30 WAL",
        symmetry: Symmetry::None,
        stored: (16, 37),
        lamp_sets: 1,
        lamp_flux_lm: 81000.0,
        lorl: 99.9,
        dff: 100.0,
        absolute: false,
    });
    assert_eq!(p.lamps[0].watts, Some(600.0));
}

#[test]
fn ledvance_asym_8_planes() {
    if common::shared::shared_data("luminaires").is_none() {
        return;
    }
    check_ldt(Ldt {
        file: "ldt/ledvance_4058075580657_ASYM_50X110.ldt",
        maker: "LEDVANCE GmbH",
        name: "FL MAX LUM 900W 757 ASYM 50X110 WAL",
        symmetry: Symmetry::None,
        stored: (8, 19),
        lamp_sets: 1,
        lamp_flux_lm: 123000.0,
        lorl: 99.8,
        dff: 100.0,
        absolute: false,
    });
}

#[test]
fn ledvance_sym_10_narrow_beam() {
    if common::shared::shared_data("luminaires").is_none() {
        return;
    }
    let p = check_ldt(Ldt {
        file: "ldt/ledvance_4058075580664_SYM_10.ldt",
        maker: "LEDVANCE GmbH",
        name: "FL MAX LUM 1200W 757 SYM 10 WAL",
        symmetry: Symmetry::None,
        stored: (16, 91),
        lamp_sets: 1,
        lamp_flux_lm: 155000.0,
        lorl: 99.9,
        dff: 100.0,
        absolute: false,
    });
    assert_eq!(p.web.gamma_deg().len(), 91);
}

#[test]
fn lidrs_prolicht_20_planes_and_a_wrong_dff() {
    if common::shared::shared_data("luminaires").is_none() {
        return;
    }
    let p = check_ldt(Ldt {
        file: "ldt/lidrs_prolicht_E30-0019.ldt",
        maker: "Ingemann",
        name: "Prolicht E30-0019 - AGP + I-Diff 20 Combined",
        symmetry: Symmetry::None,
        stored: (20, 37),
        lamp_sets: 1,
        lamp_flux_lm: 5134.0,
        lorl: 100.0,
        dff: 100.0,
        absolute: false,
    });
    assert_eq!(p.web.c_deg()[1], 18.0);
    // The file states DFF 100% but its table sends ~97 cd/klm upward at γ 95°–180° in every
    // plane (an up/down luminaire): the web's downward fraction is far from the stated one.
    let down = downward_percent(&p);
    println!("prolicht: DFF stated 100%, web {down:.1}%");
    assert!(down < 70.0 && down > 40.0, "{down}");
}

/// An IES file's numbers after TILT (parsed here independently of the reader): vertical and
/// horizontal angles and the candela table (one row per horizontal angle), with the multiplier
/// and ballast factor applied.
struct RawIes {
    v: Vec<f64>,
    h: Vec<f64>,
    rows: Vec<Vec<f64>>,
    lamps: f64,
    lumens: f64,
    ptype: f64,
}

fn raw_ies(rel: &str) -> RawIes {
    let text = std::fs::read_to_string(shared(rel)).unwrap();
    let mut lines = text.lines().skip_while(|l| !l.starts_with("TILT"));
    let tilt = lines.next().unwrap().to_string();
    let nums: Vec<f64> = lines
        .flat_map(|l| {
            l.split([' ', '\t', ',']).filter(|t| !t.is_empty()).map(|t| t.parse::<f64>().unwrap()).collect::<Vec<_>>()
        })
        .collect();
    let mut k = 0;
    if tilt.contains("INCLUDE") {
        let n = nums[1] as usize;
        k = 2 + 2 * n;
    }
    let p = &nums[k..];
    let (nv, nh) = (p[3] as usize, p[4] as usize);
    let scale = p[2] * p[10];
    let v = p[13..13 + nv].to_vec();
    let h = p[13 + nv..13 + nv + nh].to_vec();
    let t = &p[13 + nv + nh..];
    let rows = (0..nh).map(|i| t[i * nv..(i + 1) * nv].iter().map(|x| x * scale).collect()).collect();
    RawIes { v, h, rows, lamps: p[0], lumens: p[1], ptype: p[5] }
}

/// Zone bounds: each angle stands for the interval between the midpoints to its neighbours,
/// clipped to the first and last angle.
fn zones(a: &[f64]) -> Vec<(f64, f64)> {
    let n = a.len();
    (0..n)
        .map(|i| {
            let lo = if i == 0 { a[0] } else { 0.5 * (a[i - 1] + a[i]) };
            let hi = if i == n - 1 { a[n - 1] } else { 0.5 * (a[i] + a[i + 1]) };
            (lo, hi)
        })
        .collect()
}

/// The zonal-lumen sum Φ = Σ I ΔC (cos γ_lo − cos γ_hi) over the stored part of a type C web,
/// times 360°/(stored span) for the symmetry (a single plane: 2π).
fn zonal_flux(r: &RawIes) -> f64 {
    let vz = zones(&r.v);
    let hz = zones(&r.h);
    let span = r.h[r.h.len() - 1] - r.h[0];
    let (widths, factor): (Vec<f64>, f64) = if r.h.len() == 1 {
        (vec![2.0 * std::f64::consts::PI], 1.0)
    } else {
        (hz.iter().map(|(a, b)| (b - a).to_radians()).collect(), 360.0 / span)
    };
    let mut sum = 0.0;
    for (row, w) in r.rows.iter().zip(&widths) {
        for (i, (lo, hi)) in row.iter().zip(&vz) {
            sum += i * w * (lo.to_radians().cos() - hi.to_radians().cos());
        }
    }
    factor * sum
}

/// ∫ I dω of the table interpolated linearly in (C, cos γ): Σ ΔC Δ(cos γ) × (mean of the four
/// corners) over the stored cells, times 360°/(stored span) for the symmetry (one plane: 2π).
fn trapezoid_flux(r: &RawIes) -> f64 {
    let z: Vec<f64> = r.v.iter().map(|g| g.to_radians().cos()).collect();
    let column = |a: &[f64], b: &[f64]| -> f64 {
        (0..z.len() - 1).map(|j| (z[j] - z[j + 1]) * 0.25 * (a[j] + a[j + 1] + b[j] + b[j + 1])).sum()
    };
    if r.h.len() == 1 {
        return 2.0 * std::f64::consts::PI * column(&r.rows[0], &r.rows[0]);
    }
    let span = r.h[r.h.len() - 1] - r.h[0];
    let sum: f64 =
        (0..r.h.len() - 1).map(|i| (r.h[i + 1] - r.h[i]).to_radians() * column(&r.rows[i], &r.rows[i + 1])).sum();
    360.0 / span * sum
}

/// The web's flux against the same rule applied here to the raw table (exact but for pole
/// values the web averages), and the zonal-lumen sum for information (the two quadratures differ
/// by O(Δγ²): 0.1% on 1–5° grids, 10% on the LM-63 example's 22.5° grid).
fn check_ies_flux(rel: &str, p: &Photometry) {
    let r = raw_ies(rel);
    assert_eq!(r.ptype, 1.0, "type C");
    let trapezoid = trapezoid_flux(&r);
    let zonal = zonal_flux(&r);
    let web = p.flux_lm();
    println!(
        "{rel}: web {web:.1} lm, trapezoid over the raw table {trapezoid:.1} lm, zonal sum {zonal:.1} lm ({:+.2}%)",
        100.0 * (web / zonal - 1.0)
    );
    assert!((web / trapezoid - 1.0).abs() < 1e-3, "{rel}: web {web} lm, raw-table trapezoid {trapezoid} lm");
    if r.lumens > 0.0 {
        let lamps = r.lamps * r.lumens;
        println!("{rel}: lamp flux {lamps} lm; the table gives {:.1}% of it", 100.0 * web / lamps);
    }
}

#[test]
fn aec_italo_absolute_street_light() {
    if common::shared::shared_data("luminaires").is_none() {
        return;
    }
    let rel = "ies/aec_ITALO_1_5P5_S05_3.140-3M.IES";
    let p = load(rel);
    assert_eq!(p.format, "IES LM-63-2002");
    assert_eq!(p.manufacturer, "AEC");
    assert_eq!(p.luminaire, "ITALO 1 X 5P5 S05 3.140-3M");
    assert!(p.absolute);
    assert_eq!(p.lamp_flux_lm, None);
    assert_eq!(p.stored_grid, (73, 181));
    assert_eq!(p.symmetry, Symmetry::None);
    assert_eq!(p.input_watts, Some(76.7));
    // Width 0.230 m along C90, length 0.146 m along C0.
    assert!((p.opening.size_m.x - 0.146).abs() < 1e-12 && (p.opening.size_m.y - 0.230).abs() < 1e-12);
    assert_eq!(p.web.c_deg().len(), 72, "C360 repeats C0");
    check_ies_flux(rel, &p);
}

#[test]
fn luxion_floodlight_relative_lumens() {
    if common::shared::shared_data("luminaires").is_none() {
        return;
    }
    let rel = "ies/luxion_floodlight_12W_3000K_54deg.ies";
    let p = load(rel);
    assert_eq!(p.manufacturer, "LUXION");
    assert_eq!(p.luminaire, "Projetor 12W WB");
    assert!(!p.absolute);
    assert_eq!(p.lamp_flux_lm, Some(1000.0));
    assert_eq!(p.stored_grid, (9, 181));
    assert_eq!(p.lamps[0].colour_temperature, "3000K");
    // Negative width and length: a circular opening 57 mm across.
    assert_eq!(p.opening.kind, morgana::luminaire::OpeningKind::Flat { round: true });
    check_ies_flux(rel, &p);
}

#[test]
fn lm63_2002_spec_example_tilt_include() {
    if common::shared::shared_data("luminaires").is_none() {
        return;
    }
    let rel = "ies/lm63_2002_spec_example_tilt_include.ies";
    let p = load(rel);
    assert_eq!(p.format, "IES LM-63-2002");
    assert_eq!(p.manufacturer, "Aardvark lighting Inc.");
    assert_eq!(p.symmetry, Symmetry::Quadrant);
    assert_eq!(p.stored_grid, (3, 5));
    assert_eq!(p.lamp_flux_lm, Some(50000.0));
    let tilt = p.tilt.as_ref().unwrap();
    assert_eq!((tilt.geometry, tilt.angles_deg.len()), (1, 13));
    assert_eq!(tilt.factors[6], 0.98);
    check_ies_flux(rel, &p);
}

#[test]
fn eulumdatrs_absolute_led() {
    if common::shared::shared_data("luminaires").is_none() {
        return;
    }
    let rel = "ies/eulumdatrs_edge_ABSOLUTE_LED.ies";
    let p = load(rel);
    assert!(p.absolute);
    assert_eq!(p.manufacturer, "Synthetic Test Files");
    assert_eq!(p.stored_grid, (37, 19));
    assert_eq!(p.input_watts, Some(25.0));
    assert_eq!(p.opening.kind, morgana::luminaire::OpeningKind::Box);
    check_ies_flux(rel, &p);
}

/// The CIE LED illuminant tables shipped in `luminaires/spectra/` reproduce the chromaticities
/// CIE 015:2018 publishes for them (stated in each file's header), by morgana's own colorimetry.
#[test]
fn cie_led_illuminant_files_have_their_published_chromaticities() {
    use morgana::spectrum::{Spectrum, Tabulated};
    let dir = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/luminaires/spectra"));
    let mut n = 0;
    for e in std::fs::read_dir(&dir).unwrap() {
        let path = e.unwrap().path();
        let text = std::fs::read_to_string(&path).unwrap();
        let header = text.lines().find(|l| l.contains("chromaticity")).unwrap();
        let num = |key: &str| -> f64 {
            let rest = &header[header.find(key).unwrap() + key.len()..];
            rest.split([',', ' ', ';']).find(|t| !t.is_empty()).unwrap().parse().unwrap()
        };
        let (x, y) = (num("x = "), num("y = "));
        let (nm, values) = morgana::spectrum::table::parse_two_column_csv(&text).unwrap();
        let s = Spectrum::Tabulated(Tabulated::new(nm, values).unwrap());
        let xyz = morgana::spectrum::colour::absolute_xyz(&s);
        let sum = xyz.iter().sum::<f64>();
        let (gx, gy) = (xyz[0] / sum, xyz[1] / sum);
        assert!((gx - x).abs() < 5e-4 && (gy - y).abs() < 5e-4, "{}: ({gx:.4}, {gy:.4}) vs ({x}, {y})", path.display());
        n += 1;
    }
    assert_eq!(n, 9, "LED-B1…B5, BH1, RGB1, V1, V2");
}

/// The examples that use luminaires load (their shared files resolve from `examples/`).
#[test]
fn luminaire_examples_load() {
    for name in ["office_luminaires", "road_ies"] {
        let path = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/examples")).join(format!("{name}.toml"));
        let s = morgana::scene::load_scene_file(&path).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(s.sensors.len(), 1, "{name}");
    }
}
