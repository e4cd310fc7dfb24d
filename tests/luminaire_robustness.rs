//! Real files are messy, and malformed ones must never crash morgana.
//!
//! - The quirks real files carry (Latin-1 text, CRLF, a BOM, an empty first line, uneven γ steps
//!   with Dg = 0, lines far beyond 132 columns, junk after the table, Isym 3 planes stored from
//!   C270), applied to the shared files: each variant loads and gives the original's web.
//! - A property test over mutated shared files (lines deleted, duplicated or swapped, values
//!   replaced by junk, bytes flipped or inserted, files cut short): every mutant either loads to
//!   a finite web or gets an input error naming the file — never a panic.
//! - The same for this project's TM-33-18, TM-33-23 and GLDF test files (the containers mutated
//!   as bytes, or rebuilt around a mutated product.xml, EULUMDAT or spectrum entry).

mod common;

use morgana::error::Error;
use morgana::luminaire::{Photometry, Symmetry, WebSampler, read_bytes, summary};
use morgana::rng::{Rng, Stream};
use std::path::{Path, PathBuf};

fn shared(rel: &str) -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../shared/data/luminaires")).join(rel)
}

fn bytes(rel: &str) -> Vec<u8> {
    let path = shared(rel);
    std::fs::read(&path).unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()))
}

fn read(b: &[u8], name: &str) -> Photometry {
    read_bytes(b, Path::new(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn text(rel: &str) -> String {
    String::from_utf8(bytes(rel)).unwrap()
}

#[test]
fn latin1_crlf_a_leading_blank_line_and_junk_after_the_table() {
    if common::shared::shared_data("luminaires").is_none() {
        return;
    }
    let original = read(&bytes("ldt/eulumdatpy_sample2.ldt"), "a.ldt");
    let t = text("ldt/eulumdatpy_sample2.ldt").replacen("Regent", "Régent Lüchtung", 1);
    let t = format!("\n{t}\nEND OF DATA — exported by hand\n").replace('\n', "\r\n");
    let latin1: Vec<u8> = t.chars().map(|c| u8::try_from(c as u32).unwrap_or(b'?')).collect();
    let p = read(&latin1, "b.ldt");
    assert_eq!(p.encoding, "Latin-1");
    assert_eq!(p.manufacturer, "Régent Lüchtung");
    assert_eq!(p.web, original.web);
    assert!(p.notes.iter().any(|n| n.contains("blank line")), "{:?}", p.notes);
    assert!(p.notes.iter().any(|n| n.contains("after the intensity table")), "{:?}", p.notes);
}

/// sample3 (Isym 0, γ every 5°) with Dg = 0 and the γ-angles above 90° thinned to every 10°.
#[test]
fn uneven_gamma_steps_with_dg_zero() {
    if common::shared::shared_data("luminaires").is_none() {
        return;
    }
    let original = read(&bytes("ldt/eulumdatpy_sample3.ldt"), "a.ldt");
    let source = text("ldt/eulumdatpy_sample3.ldt");
    let lines: Vec<&str> = source.lines().collect();
    // Header 32 lines (one lamp set), 10 direct ratios, 24 C-angles, then 37 γ-angles.
    let (g0, t0) = (32 + 10 + 24, 32 + 10 + 24 + 37);
    let keep = |j: usize| j <= 18 || j.is_multiple_of(2);
    let kept = (0..37).filter(|j| keep(*j)).count();
    let mut out: Vec<String> = Vec::new();
    for (k, l) in lines.iter().enumerate() {
        let keep_line = match k {
            5 => {
                out.push(kept.to_string());
                false
            }
            6 => {
                out.push("0".into());
                false
            }
            k if (g0..t0).contains(&k) => keep(k - g0),
            k if k >= t0 && k < t0 + 24 * 37 => keep((k - t0) % 37),
            _ => true,
        };
        if keep_line {
            out.push(l.to_string());
        }
    }
    let p = read(out.join("\n").as_bytes(), "b.ldt");
    assert_eq!(p.web.gamma_deg().len(), kept);
    assert_eq!(p.web.gamma_deg()[19], 100.0);
    assert!(p.notes.is_empty(), "{:?}", p.notes);
    for c in [0.0, 15.0, 90.0, 255.0] {
        for g in [0.0, 45.0, 90.0, 100.0, 140.0, 180.0] {
            assert!((p.web.intensity_at(c, g) - original.web.intensity_at(c, g)).abs() < 1e-9, "C{c} γ{g}");
        }
    }
}

/// sample3's planes C270…C345, C0…C90 written as an Isym 3 file.
#[test]
fn isym_3_stores_planes_from_c270() {
    if common::shared::shared_data("luminaires").is_none() {
        return;
    }
    let original = read(&bytes("ldt/eulumdatpy_sample3.ldt"), "a.ldt");
    let source = text("ldt/eulumdatpy_sample3.ldt");
    let lines: Vec<&str> = source.lines().collect();
    let t0 = 32 + 10 + 24 + 37;
    let mut out: Vec<&str> = lines[..t0].to_vec();
    out[2] = "3";
    for plane in (18..24).chain(0..7) {
        out.extend_from_slice(&lines[t0 + plane * 37..t0 + (plane + 1) * 37]);
    }
    let p = read(out.join("\n").as_bytes(), "b.ldt");
    assert_eq!(p.symmetry, Symmetry::C90C270);
    assert_eq!(p.stored_grid, (13, 37));
    for g in [0.0, 30.0, 75.0, 150.0] {
        for c in [270.0, 300.0, 345.0, 0.0, 30.0, 90.0] {
            let stored = original.web.intensity_at(c, g);
            assert!((p.web.intensity_at(c, g) - stored).abs() < 1e-9, "stored plane C{c} γ{g}");
            let image = (180.0 - c + 360.0) % 360.0;
            assert!((p.web.intensity_at(image, g) - stored).abs() < 1e-9, "C{image} mirrors C{c} at γ{g}");
        }
    }
}

#[test]
fn ies_with_a_bom_blank_lines_latin1_one_long_line_and_junk() {
    if common::shared::shared_data("luminaires").is_none() {
        return;
    }
    let rel = "ies/aec_ITALO_1_5P5_S05_3.140-3M.IES";
    let original = read(&bytes(rel), "a.ies");
    let t = text(rel).replace("\r\n", "\n");
    let (head, numbers) = t.split_at(t.find("TILT=NONE").unwrap() + "TILT=NONE\n".len());
    let one_line = numbers.split_whitespace().collect::<Vec<_>>().join(" ");
    assert!(one_line.len() > 50_000);
    let head = head.replace("[MANUFAC] AEC", "[MANUFAC] AEC Illuminazione — qualità");
    let t = format!("\n\n{head}{one_line}\n-- end of photometry --\n");
    let latin1: Vec<u8> = t.chars().map(|c| u8::try_from(c as u32).unwrap_or(b'?')).collect();
    let p = read(&latin1, "b.ies");
    assert_eq!(p.web, original.web);
    assert_eq!(p.manufacturer, "AEC Illuminazione ? qualità");
    assert!(p.notes.iter().any(|n| n.contains("blank line")) && p.notes.iter().any(|n| n.contains("ignored")));
    let mut bom = vec![0xEF, 0xBB, 0xBF];
    bom.extend(bytes(rel));
    assert_eq!(read(&bom, "c.ies").web, original.web);
}

/// One random edit of a file's bytes.
fn mutate(src: &[u8], rng: &mut Rng) -> Vec<u8> {
    let text = String::from_utf8_lossy(src).to_string();
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let pick = |rng: &mut Rng, n: usize| rng.below(n.max(1) as u64) as usize;
    const JUNK: [&str; 14] =
        ["x", "-1", "0", "1e308", "-1e308", "nan", "inf", "99999999", "", "3.5.6", "1,5", "-0", "4", "360"];
    match rng.below(8) {
        0 if !lines.is_empty() => {
            let i = pick(rng, lines.len());
            lines.remove(i);
        }
        1 if !lines.is_empty() => {
            let i = pick(rng, lines.len());
            lines.insert(i, lines[i].clone());
        }
        2 if lines.len() > 1 => {
            let (i, j) = (pick(rng, lines.len()), pick(rng, lines.len()));
            lines.swap(i, j);
        }
        3 | 4 if !lines.is_empty() => {
            // Header lines are the most sensitive: favour the first 40.
            let i = if rng.uniform() < 0.6 { pick(rng, lines.len().min(40)) } else { pick(rng, lines.len()) };
            let mut tokens: Vec<String> = lines[i].split_whitespace().map(str::to_string).collect();
            let junk = JUNK[pick(rng, JUNK.len())].to_string();
            if tokens.is_empty() {
                lines[i] = junk;
            } else {
                let k = pick(rng, tokens.len());
                tokens[k] = junk;
                lines[i] = tokens.join(" ");
            }
        }
        5 => {
            let cut = pick(rng, src.len());
            return src[..cut].to_vec();
        }
        6 => {
            let mut b = src.to_vec();
            let at = pick(rng, b.len());
            for _ in 0..1 + pick(rng, 8) {
                b.insert(at.min(b.len()), rng.below(256) as u8);
            }
            return b;
        }
        _ => {
            let mut b = src.to_vec();
            if !b.is_empty() {
                let at = pick(rng, b.len());
                b[at] ^= 1 << rng.below(8);
            }
            return b;
        }
    }
    lines.join("\n").into_bytes()
}

/// Every shared file.
fn all_files() -> Vec<String> {
    let mut out = Vec::new();
    for dir in ["ies", "ldt"] {
        let path = shared(dir);
        let entries = std::fs::read_dir(&path).unwrap_or_else(|e| panic!("cannot list {}: {e}", path.display()));
        for e in entries {
            let e = e.unwrap_or_else(|e| panic!("cannot list {}: {e}", path.display()));
            out.push(format!("{dir}/{}", e.file_name().to_string_lossy()));
        }
    }
    out.sort();
    out
}

#[test]
fn mutated_real_files_load_or_fail_cleanly_never_panic() {
    if common::shared::shared_data("luminaires").is_none() {
        return;
    }
    // MORGANA_MUTANTS=5000 for a longer search.
    let per_file: u64 = std::env::var("MORGANA_MUTANTS").ok().and_then(|v| v.parse().ok()).unwrap_or(150);
    let (mut ok, mut rejected) = (0, 0);
    for (f, rel) in all_files().iter().enumerate() {
        let src = bytes(rel);
        let name = format!("mutant.{}", rel.rsplit('.').next().unwrap().to_ascii_lowercase());
        for k in 0..per_file {
            let mut rng = Rng::for_task(f as u64, Stream::Test, k);
            let mut m = mutate(&src, &mut rng);
            if k % 3 == 0 {
                m = mutate(&m, &mut rng);
            }
            let outcome = std::panic::catch_unwind(|| match read_bytes(&m, Path::new(&name)) {
                Ok(p) => {
                    let flux = p.flux_lm();
                    assert!(flux.is_finite() && flux >= 0.0, "flux {flux}");
                    let _ = WebSampler::new(&p.web);
                    let _ = summary(&p);
                    true
                }
                Err(Error::Input(e)) => {
                    let msg = e.to_string();
                    assert!(msg.starts_with(&name), "error does not name the file: {msg}");
                    assert!(msg.contains("expected") || msg.contains("recognise"), "{msg}");
                    false
                }
                Err(other) => panic!("not an input error: {other}"),
            });
            match outcome {
                Ok(true) => ok += 1,
                Ok(false) => rejected += 1,
                Err(_) => {
                    let dump = std::env::temp_dir().join(format!("morgana-mutant-{f}-{k}.{name}"));
                    std::fs::write(&dump, &m).ok();
                    panic!("{rel}: mutant {k} panicked; written to {}", dump.display());
                }
            }
        }
    }
    println!("mutants: {ok} loaded, {rejected} rejected with an input error");
    assert!(ok > 0 && rejected > 0);
}

#[test]
fn a_truncated_file_names_the_field_it_stopped_in() {
    if common::shared::shared_data("luminaires").is_none() {
        return;
    }
    let t = text("ldt/eulumdatpy_sample10.ldt");
    let cut: String = t.lines().take(20).map(|l| format!("{l}\n")).collect();
    let e = read_bytes(cut.as_bytes(), Path::new("cut.ldt")).unwrap_err().to_string();
    assert_eq!(
        e,
        "cut.ldt:21: EULUMDAT field 21 (height of luminous area C270-plane, mm): found the end of the file, expected a line for this field"
    );
}

/// This project's TM-33 and GLDF test files (tests/data/luminaires/).
fn own(name: &str) -> Vec<u8> {
    std::fs::read(PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/luminaires")).join(name)).unwrap()
}

/// A deflated zip archive of `entries`.
fn zip_of(entries: &[(&str, Vec<u8>)]) -> Vec<u8> {
    use std::io::Write;
    let mut w = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let options = zip::write::SimpleFileOptions::default().compression_method(zip::CompressionMethod::Deflated);
    for (name, content) in entries {
        w.start_file(*name, options).unwrap();
        w.write_all(content).unwrap();
    }
    w.finish().unwrap().into_inner()
}

/// Reads a mutant: Ok(true) loaded to a finite web, Ok(false) an input error naming the file and
/// saying what was expected; a panic or any other error fails the test.
fn check_mutant(m: &[u8], name: &str) -> bool {
    match read_bytes(m, Path::new(name)) {
        Ok(p) => {
            let flux = p.flux_lm();
            assert!(flux.is_finite() && flux >= 0.0, "flux {flux}");
            let _ = WebSampler::new(&p.web);
            let _ = summary(&p);
            true
        }
        Err(Error::Input(e)) => {
            let msg = e.to_string();
            assert!(msg.starts_with(name), "error does not name the file: {msg}");
            assert!(msg.contains("expected") || msg.contains("recognise"), "{msg}");
            false
        }
        Err(other) => panic!("not an input error: {other}"),
    }
}

/// TM-33-18 and -23 files mutated as text; GLDF containers mutated as bytes, or rebuilt around a
/// mutated product.xml, EULUMDAT or spectrum entry.
#[test]
fn mutated_tm33_and_gldf_files_load_or_fail_cleanly_never_panic() {
    let per_file: u64 = std::env::var("MORGANA_MUTANTS").ok().and_then(|v| v.parse().ok()).unwrap_or(150);
    let entries = |product: Vec<u8>, ldt: Vec<u8>, spectrum: Vec<u8>| {
        zip_of(&[
            ("product.xml", product),
            ("ldc/quad_downlight.ldt", ldt),
            ("ldc/quad_downlight.ies", own("quad_downlight.ies")),
            ("spectrum/quad_downlight_spectrum.txt", spectrum),
        ])
    };
    let (product, ldt, spectrum) =
        (own("quad_downlight_gldf_product.xml"), own("quad_downlight.ldt"), own("quad_downlight_spectrum.txt"));
    let gldf = entries(product.clone(), ldt.clone(), spectrum.clone());
    let (mut ok, mut rejected) = (0, 0);
    for (f, label) in ["tm33_18", "tm33_23", "gldf"].iter().enumerate() {
        for k in 0..per_file {
            let mut rng = Rng::for_task(100 + f as u64, Stream::Test, k);
            let (m, name) = match *label {
                "tm33_18" => (mutate(&own("quad_downlight_tm33_18.xml"), &mut rng), "mutant.xml"),
                "tm33_23" => (mutate(&own("quad_downlight_tm33_23.xml"), &mut rng), "mutant.xml"),
                _ => {
                    let m = match k % 4 {
                        0 => mutate(&gldf, &mut rng),
                        1 => entries(mutate(&product, &mut rng), ldt.clone(), spectrum.clone()),
                        2 => entries(product.clone(), mutate(&ldt, &mut rng), spectrum.clone()),
                        _ => entries(product.clone(), ldt.clone(), mutate(&spectrum, &mut rng)),
                    };
                    (m, "mutant.gldf")
                }
            };
            match std::panic::catch_unwind(|| check_mutant(&m, name)) {
                Ok(true) => ok += 1,
                Ok(false) => rejected += 1,
                Err(_) => {
                    let dump = std::env::temp_dir().join(format!("morgana-mutant-{label}-{k}.{name}"));
                    std::fs::write(&dump, &m).ok();
                    panic!("{label}: mutant {k} panicked; written to {}", dump.display());
                }
            }
        }
    }
    println!("TM-33 and GLDF mutants: {ok} loaded, {rejected} rejected with an input error");
    assert!(ok > 0 && rejected > 0);
}
