//! IES TM-33 and GLDF: files this project authored (tests/data/luminaires/, see each file's
//! comment) carry one analytic luminaire,
//! I(C, γ) = 1000 cd cos γ (1 + 0.25 sin²γ cos 2C) below the horizon, 0 above,
//! as IES LM-63-2002, EULUMDAT, TM-33-18, TM-33-23 and (zipped here) GLDF. Its flux is 1000π lm
//! (the cos 2C term sums to zero over the 16 planes, and the web is linear in cos γ), which the
//! TM-33 and EULUMDAT files state. Round-trip facts, then malformed files and containers through
//! `morgana luminaire` (exit code 2 and a message naming the element or entry).

mod common;

use common::{scene, scene_error};
use morgana::light::Light;
use morgana::luminaire::{
    GLDF_MAX_ENTRY_BYTES, Opening, Photometry, Symmetry, load_file, load_file_variant, per_candela, read_bytes,
};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::Command;

const FLUX_LM: f64 = 1000.0 * std::f64::consts::PI;
/// The IES tests' tolerance between the web's flux and an independent integral of the table.
const FLUX_TOLERANCE: f64 = 1e-3;

fn data(name: &str) -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/luminaires")).join(name)
}

fn bytes(name: &str) -> Vec<u8> {
    std::fs::read(data(name)).unwrap()
}

fn text(name: &str) -> String {
    String::from_utf8(bytes(name)).unwrap()
}

fn load(name: &str) -> Photometry {
    load_file(&data(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// A zip archive of `entries` (deflated).
fn zip(entries: &[(&str, &[u8])]) -> Vec<u8> {
    let mut w = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let options = zip::write::SimpleFileOptions::default().compression_method(zip::CompressionMethod::Deflated);
    for (name, content) in entries {
        w.start_file(*name, options).unwrap();
        w.write_all(content).unwrap();
    }
    w.finish().unwrap().into_inner()
}

/// The test downlight's GLDF container, with `product` as its product.xml.
fn gldf_with(product: &[u8]) -> Vec<u8> {
    zip(&[
        ("product.xml", product),
        ("ldc/quad_downlight.ldt", &bytes("quad_downlight.ldt")),
        ("ldc/quad_downlight.ies", &bytes("quad_downlight.ies")),
        ("spectrum/quad_downlight_spectrum.txt", &bytes("quad_downlight_spectrum.txt")),
    ])
}

fn gldf() -> Vec<u8> {
    gldf_with(&bytes("quad_downlight_gldf_product.xml"))
}

/// Writes `content` to a fresh file `name` in this test's temporary folder.
fn temp(test: &str, name: &str, content: &[u8]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("morgana-tm33-gldf-{}-{test}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, content).unwrap();
    p
}

/// `morgana luminaire ARGS`: exit code, stdout, stderr.
fn morgana_luminaire(args: &[&str]) -> (Option<i32>, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_morgana")).arg("luminaire").args(args).output().unwrap();
    (out.status.code(), String::from_utf8_lossy(&out.stdout).into(), String::from_utf8_lossy(&out.stderr).into())
}

/// (wavelength, value) pairs from `<PwrData w="…">value</PwrData>` lines, parsed here.
fn pwr_data(xml: &str) -> Vec<(f64, f64)> {
    xml.lines()
        .filter_map(|l| l.trim().strip_prefix("<PwrData w=\""))
        .map(|l| {
            let (w, rest) = l.split_once("\">").unwrap();
            (w.parse().unwrap(), rest.trim_end_matches("</PwrData>").parse().unwrap())
        })
        .collect()
}

fn normalised(samples: &[(f64, f64)]) -> Vec<f64> {
    let peak = samples.iter().map(|s| s.1).fold(0.0, f64::max);
    samples.iter().map(|s| s.1 / peak).collect()
}

fn assert_same_values(a: &[f64], b: &[f64], what: &str) {
    assert_eq!(a.len(), b.len(), "{what}");
    for (x, y) in a.iter().zip(b) {
        assert!((x - y).abs() <= 1e-12 * x.abs().max(1.0), "{what}: {x} vs {y}");
    }
}

#[test]
fn tm33_18_gives_the_ies_web_its_stated_flux_symmetry_and_spectrum() {
    let ies = load("quad_downlight.ies");
    let p = load("quad_downlight_tm33_18.xml");
    assert_eq!(p.format, "IES TM-33-18");
    assert_eq!((p.manufacturer.as_str(), p.catalogue.as_str()), ("morgana", "QUAD-1"));
    assert_eq!(p.symmetry, Symmetry::Quadrant);
    assert_eq!(p.stored_grid, (5, 37));
    assert!(!p.absolute);
    assert_eq!(p.lamp_flux_lm, Some(4000.0));
    assert_eq!(p.lamps[0].colour_temperature, "4000 K");
    assert_eq!(p.web, ies.web, "the same table as the IES file gives the same web");
    assert_eq!(p.opening, ies.opening);
    assert_eq!(p.opening, Opening::from_lm63(0.3, 0.6, 0.0).0);
    let stated = p.stated_flux_lm.unwrap();
    assert_eq!(stated, 3141.6);
    let web = p.flux_lm();
    println!("TM-33-18: web {web:.3} lm, stated {stated} lm, 1000π = {FLUX_LM:.3} lm");
    assert!((web / stated - 1.0).abs() < FLUX_TOLERANCE, "web {web} lm vs stated {stated} lm");
    assert!((web / FLUX_LM - 1.0).abs() < 1e-6, "web {web} lm vs 1000π lm");
    // The spectrum: the file's PwrData, sorted by wavelength and scaled to a peak of 1.
    let s = p.spectrum.as_ref().expect("a spectrum");
    let file = pwr_data(&text("quad_downlight_tm33_18.xml"));
    assert_eq!(file.len(), 81);
    assert_eq!(s.samples().0, file.iter().map(|f| f.0).collect::<Vec<_>>().as_slice());
    assert_same_values(s.samples().1, &normalised(&file), "spectrum");
    assert_eq!((s.peak_nm(), s.domain_nm()), (450.0, (380.0, 780.0)));
    assert!(p.notes.is_empty(), "{:?}", p.notes);
}

#[test]
fn tm33_23_with_symm_and_multipliers_gives_the_same_luminaire() {
    let ies = load("quad_downlight.ies");
    let t18 = load("quad_downlight_tm33_18.xml");
    let p = load("quad_downlight_tm33_23.xml");
    assert_eq!(p.format, "IES TM-33-23");
    assert_eq!(p.symmetry, Symmetry::Quadrant);
    assert!(p.absolute);
    assert_eq!(p.lamp_flux_lm, None);
    // Values stored halved with Multiplier 2.
    assert_eq!(p.web.c_deg(), ies.web.c_deg());
    for i in 0..p.web.c_deg().len() {
        for j in 0..p.web.gamma_deg().len() {
            let (a, b) = (p.web.node(i, j), ies.web.node(i, j));
            assert!((a - b).abs() <= 1e-12 * b.max(1.0), "node {i} {j}: {a} vs {b}");
        }
    }
    assert!((p.flux_lm() / p.stated_flux_lm.unwrap() - 1.0).abs() < FLUX_TOLERANCE);
    // Spectrum stored divided by 4 with Multiplier 4: the same normalised spectrum.
    let (a, b) = (p.spectrum.as_ref().unwrap(), t18.spectrum.as_ref().unwrap());
    assert_eq!(a.samples().0, b.samples().0);
    assert_same_values(a.samples().1, b.samples().1, "TM-33-23 spectrum");
    assert!(p.notes.is_empty(), "{:?}", p.notes);
}

#[test]
fn formats_are_recognised_by_content_without_an_extension() {
    let p = read_bytes(&bytes("quad_downlight_tm33_23.xml"), Path::new("lamp.dat")).unwrap();
    assert_eq!(p.format, "IES TM-33-23");
    let p = read_bytes(&gldf(), Path::new("lamp.bin")).unwrap();
    assert!(p.format.starts_with("GLDF 1.0"), "{}", p.format);
}

#[test]
fn gldf_with_an_ldt_inside_gives_the_ldt_web_and_the_spectrum_file() {
    let ldt = load("quad_downlight.ldt");
    let path = temp("ldt", "quad.gldf", &gldf());
    let p = load_file(&path).unwrap();
    assert_eq!(p.format, "GLDF 1.0 (variant \"surface\": EULUMDAT, ldc/quad_downlight.ldt)");
    assert_eq!(p.web, ldt.web);
    assert_eq!(p.symmetry, Symmetry::Quadrant);
    assert_eq!(p.stated_flux_lm, ldt.stated_flux_lm);
    assert_eq!(p.luminaire, "Quadrant-symmetric test downlight, Surface-mounted, LED");
    assert!((p.flux_lm() / p.stated_flux_lm.unwrap() - 1.0).abs() < FLUX_TOLERANCE);
    let s = p.spectrum.as_ref().unwrap();
    let file: Vec<(f64, f64)> = text("quad_downlight_spectrum.txt")
        .lines()
        .map(|l| {
            let (a, b) = l.split_once(' ').unwrap();
            (a.parse().unwrap(), b.parse().unwrap())
        })
        .collect();
    assert_same_values(s.samples().1, &normalised(&file), "GLDF spectrum file");
    assert!(s.source.contains("spectrum/quad_downlight_spectrum.txt"), "{}", s.source);
    assert!(p.notes.iter().any(|n| n.contains("2 variants (surface, recessed)")), "{:?}", p.notes);
    // The other variant: IES photometry through an equipment, an inline spectrum.
    let p = load_file_variant(&path, Some("recessed")).unwrap();
    assert_eq!(p.format, "GLDF 1.0 (variant \"recessed\": IES LM-63-2002, ldc/quad_downlight.ies)");
    assert_eq!(p.web, load("quad_downlight.ies").web);
    assert_eq!(p.spectrum.as_ref().unwrap().samples(), (&[400.0, 500.0, 600.0, 700.0][..], &[0.2, 0.6, 1.0, 0.8][..]));
    // A variant the file does not have, and a variant for a file that has none.
    let e = load_file_variant(&path, Some("pendant")).unwrap_err();
    assert_eq!(e.exit_code(), 2);
    assert!(
        e.to_string().contains(
            "\"pendant\", which the file does not define, expected one of its variant ids: surface, recessed"
        ),
        "{e}"
    );
    let e = load_file_variant(&data("quad_downlight.ldt"), Some("surface")).unwrap_err().to_string();
    assert!(e.contains("variants are chosen in GLDF containers"), "{e}");
}

#[test]
fn the_command_reports_and_plots_tm33_and_gldf() {
    let png = std::env::temp_dir().join(format!("morgana-tm33-polar-{}.png", std::process::id()));
    let tm33 = data("quad_downlight_tm33_23.xml");
    let (code, out, err) = morgana_luminaire(&[tm33.to_str().unwrap(), "--png", png.to_str().unwrap()]);
    assert_eq!(code, Some(0), "{err}");
    for want in [
        "IES TM-33-23",
        "spectrum      TM-33 Emitter 1",
        "peak at 450 nm",
        "3141.6 lm (absolute photometry)",
        "quadrant",
    ] {
        assert!(out.contains(want), "missing {want:?} in\n{out}");
    }
    assert!(std::fs::metadata(&png).unwrap().len() > 1000);
    let path = temp("cli", "quad.gldf", &gldf());
    let (code, out, err) =
        morgana_luminaire(&[path.to_str().unwrap(), "--variant", "recessed", "--png", png.to_str().unwrap()]);
    assert_eq!(code, Some(0), "{err}");
    for want in ["GLDF 1.0 (variant \"recessed\": IES LM-63-2002", "GLDF Spectrum \"lampSpectrum\"", "catalogue QUAD-1"]
    {
        assert!(out.contains(want), "missing {want:?} in\n{out}");
    }
    std::fs::remove_file(&png).ok();
}

/// `morgana luminaire` on `content` saved as `name`: exit code 2, and the message.
fn rejected(test: &str, name: &str, content: &[u8]) -> String {
    let path = temp(test, name, content);
    let (code, out, err) = morgana_luminaire(&[path.to_str().unwrap()]);
    assert_eq!(code, Some(2), "{name}: exit code {code:?}\n{out}{err}");
    assert!(err.starts_with(&format!("morgana: {}", path.display())), "{err}");
    err
}

#[test]
fn malformed_tm33_files_exit_2_naming_the_element() {
    let good = text("quad_downlight_tm33_18.xml");
    // Malformed XML: cut in the middle of the table.
    let cut = &good[..good.len() / 2];
    let e = rejected("xml", "cut.xml", cut.as_bytes());
    let last = cut.lines().count();
    assert!(e.contains(&format!("cut.xml:{last}: TM-33 XML")) && e.contains("expected well-formed XML"), "{e}");
    // A missing required element.
    let e = rejected("missing", "missing.xml", good.replace("<NumberHorz>5</NumberHorz>", "").as_bytes());
    assert!(
        e.contains(
            "IESTM33/Emitter/LuminousData/LuminousIntensity/NumberHorz: found no <NumberHorz> in <LuminousIntensity>"
        ),
        "{e}"
    );
    // A wrong number of values.
    let one = good.lines().find(|l| l.contains("<IntData h=\"45\" v=\"30\">")).unwrap();
    let e = rejected("count", "count.xml", good.replace(&format!("{one}\n"), "").as_bytes());
    assert!(
        e.contains(
            "LuminousIntensity/IntData: found 184 IntData values, expected NumberHorz × NumberVert = 5 × 37 = 185"
        ),
        "{e}"
    );
    // A spectrum with the wrong count names its element and line.
    let e =
        rejected("spectrum", "spectrum.xml", good.replace("<NumberWavelength>81", "<NumberWavelength>80").as_bytes());
    assert!(e.contains("SpectralData/EmitterSpectral/PwrData: found 81 PwrData values"), "{e}");
    // Junk in a value: the element's line.
    let line = good.lines().position(|l| l.contains("<IntData h=\"0\" v=\"5\">")).unwrap() + 1;
    let e = rejected("junk", "junk.xml", good.replace("v=\"5\">998.0865<", "v=\"5\">998,08,65<").as_bytes());
    assert!(
        e.contains(&format!("junk.xml:{line}: TM-33 IESTM33/Emitter/LuminousData/LuminousIntensity/IntData")),
        "{e}"
    );
}

#[test]
fn malformed_gldf_containers_exit_2_naming_the_entry() {
    let good = gldf();
    let e = rejected("truncated", "cut.gldf", &good[..good.len() * 2 / 3]);
    assert!(e.contains("GLDF container: found a damaged or incomplete zip archive"), "{e}");
    let e = rejected("noproduct", "none.gldf", &zip(&[("ldc/quad_downlight.ldt", &bytes("quad_downlight.ldt"))]));
    assert!(
        e.contains("GLDF container entry product.xml: found no such entry (the archive has: ldc/quad_downlight.ldt)"),
        "{e}"
    );
    // Malformed product.xml: the error is inside the container, at its line.
    let product = text("quad_downlight_gldf_product.xml");
    let e = rejected("badxml", "badxml.gldf", &gldf_with(product.replace("</Emitters>", "").as_bytes()));
    assert!(e.contains("badxml.gldf!/product.xml:") && e.contains("GLDF product.xml XML (column"), "{e}");
    // A reference to nothing.
    let e = rejected(
        "dangling",
        "dangling.gldf",
        &gldf_with(product.replace("photometryId=\"photometryLdt\"", "photometryId=\"nope\"").as_bytes()),
    );
    assert!(e.contains("FixedLightEmitter photometryId: found \"nope\", expected the id of a Photometry"), "{e}");
    // A photometry file named but missing from the container.
    let missing = zip(&[("product.xml", product.as_bytes())]);
    let e = rejected("noldt", "noldt.gldf", &missing);
    assert!(e.contains("GLDF container entry ldc/quad_downlight.ldt: found no such entry"), "{e}");
    // A malformed EULUMDAT inside: its own reader's message, located in the container.
    let bad_ldt = text("quad_downlight.ldt").replacen("\r\n16\r\n", "\r\nsixteen\r\n", 1);
    let inner = zip(&[("product.xml", product.as_bytes()), ("ldc/quad_downlight.ldt", bad_ldt.as_bytes())]);
    let e = rejected("badldt", "badldt.gldf", &inner);
    assert!(e.contains("badldt.gldf!/ldc/quad_downlight.ldt:4: EULUMDAT field 4 (Mc"), "{e}");
}

#[test]
fn a_zip_bomb_entry_is_refused_at_the_size_limit() {
    // product.xml of 65 MiB of spaces deflates to ≈ 65 kB; morgana stops reading at 64 MiB.
    let huge = vec![b' '; (GLDF_MAX_ENTRY_BYTES + (1 << 20)) as usize];
    let bomb = zip(&[("product.xml", &huge)]);
    assert!(bomb.len() < 1 << 20, "{} bytes", bomb.len());
    let e = rejected("bomb", "bomb.gldf", &bomb);
    assert!(
        e.contains("GLDF container entry product.xml: found 68157440 bytes uncompressed, expected at most 64 MiB"),
        "{e}"
    );
}

/// A camera, one band at 550–560 nm, a black sphere around the origin.
fn black_sphere() -> String {
    "[camera]\nposition = [0.0, 0.0, 0.0]\nlook_at = [0.0, 0.0, -1.0]\nfov_deg = 60.0\nwidth = 8\nheight = 8\n\n\
     [output]\nbands = 1\nmin_nm = 550.0\nmax_nm = 560.0\n\n\
     [[material]]\nname = \"black\"\ntype = \"lambertian\"\nreflectance = 0.0\n\n\
     [[shape]]\ntype = \"sphere\"\ncenter = [0.0, 0.0, 0.0]\nradius = 20.0\nmaterial = \"black\"\n"
        .to_string()
}

fn light(file: &Path, extra: &str) -> String {
    format!(
        "[[light]]\nname = \"lum\"\ntype = \"luminaire\"\nfile = \"{}\"\nposition = [0.0, 2.0, 0.0]\n{extra}\n",
        file.display()
    )
}

#[test]
fn a_scene_light_uses_the_files_spectrum_unless_the_scene_gives_one() {
    let file = data("quad_downlight_tm33_18.xml");
    let p = load_file(&file).unwrap();
    let s = scene(&(black_sphere() + &light(&file, "")));
    let Light::Luminaire(l) = &s.world.lights[0] else { panic!("not a luminaire") };
    // Watts in 550–560 nm: Φ ∫ s / (K_m ∫ s ȳ) dλ, with s the file's spectrum.
    let want = p.flux_lm() * per_candela(&p.spectrum.as_ref().unwrap().spectrum()).unwrap().integral(550.0, 560.0);
    assert!((l.power_w() / want - 1.0).abs() < 1e-9, "{} W vs {want} W", l.power_w());
    assert!(
        s.warnings.iter().any(|w| w.contains("emission spectrum from") && w.contains("peak at 450 nm")),
        "{:?}",
        s.warnings
    );
    // The scene's cct_k overrides it, and says so.
    let s = scene(&(black_sphere() + &light(&file, "cct_k = 3000")));
    let black =
        per_candela(&morgana::spectrum::Spectrum::Blackbody { temperature_k: 3000.0 }).unwrap().integral(550.0, 560.0);
    // A black body is integrated to the sampler's stated 1e-4.
    assert!((s.world.lights[0].power_w() / (p.flux_lm() * black) - 1.0).abs() < 1e-4);
    assert!(s.warnings.iter().any(|w| w.contains("the scene's cct_k overrides the spectrum in")), "{:?}", s.warnings);
    // A file without a spectrum still needs one from the scene.
    let e = scene_error(&(black_sphere() + &light(&data("quad_downlight.ies"), "")));
    assert!(e.contains("the luminaire file carries no spectrum"), "{e}");
}

#[test]
fn a_scene_names_a_gldf_variant() {
    let path = temp("scene", "quad.gldf", &gldf());
    let s = scene(&(black_sphere() + &light(&path, "variant = \"recessed\"")));
    assert!(s.warnings.iter().any(|w| w.contains("GLDF Spectrum \"lampSpectrum\"")), "{:?}", s.warnings);
    let e = scene_error(&(black_sphere() + &light(&path, "variant = \"pendant\"")));
    assert!(
        e.contains("expected one of its variant ids: surface, recessed")
            && e.contains("luminaire file of light \"lum\""),
        "{e}"
    );
}
