//! Tone reproduction end to end: spectral images through colorimetry, chromatic adaptation and
//! the operators; the `tonemap` command and the `[output]` keys, with their errors.

mod common;

use morgana::spectrum::SpectralImage;
use morgana::spectrum::exr::write_spectral_exr;
use morgana::spectrum::{Bands, named_illuminant};
use morgana::tonemap::chromatic::Cat;
use morgana::tonemap::delta_e::{delta_e_2000, xyz_to_lab};
use morgana::tonemap::matrix::xy_to_xyz;
use morgana::tonemap::scotopic::{K_M_SCOTOPIC, v_prime_at_nm};
use morgana::tonemap::white::{AdaptTo, DISPLAY_WHITE_XY};
use morgana::tonemap::{SceneImage, ToneSettings, adapt_colour, tonemap};
use std::path::{Path, PathBuf};
use std::process::Command;

/// A spectral image whose pixels are reflectances `rho` under illuminant `name`, scaled to
/// radiance (W m⁻² sr⁻¹ nm⁻¹), sampled at the band centres.
fn lit_cards(name: &str, rho: &[f64], bands: Bands) -> SpectralImage {
    let s = &named_illuminant(name).unwrap();
    let data = rho
        .iter()
        .flat_map(|&r| (0..bands.count).map(move |b| (r * 1e-2 * s.eval(bands.centre_nm(b))) as f32))
        .collect();
    SpectralImage { width: rho.len(), height: 1, bands, data, rgb: vec![0.0; 3 * rho.len()] }
}

fn scratch(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("morgana-tonemap-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn grey_under_illuminant_a_adapted_to_d65_comes_out_neutral() {
    // A grey (18 %) and a white (90 %) card under A, rendered in 16 bands; the scene white given
    // (A), estimated from the brightest pixels (the white card) or from the mean of the image.
    let bands = Bands::new(380.0, 780.0, 16).unwrap();
    let scene = SceneImage::from_spectral(&lit_cards("A", &[0.18, 0.9], bands));
    let d65 = xy_to_xyz(DISPLAY_WHITE_XY);
    let neutrality = |img: &SceneImage| {
        // Lab against the display white at the white card's luminance / 0.9.
        let white = d65.map(|c| c * img.xyz[1][1] / 0.9);
        let lab = xyz_to_lab(img.xyz[0], white);
        delta_e_2000(lab, [lab[0], 0.0, 0.0])
    };
    assert!(neutrality(&scene) > 10.0, "without adaptation the grey is orange: ΔE {}", neutrality(&scene));
    for cat in Cat::ALL {
        for adapt_to in [AdaptTo::Illuminant("A".into()), AdaptTo::WhitePatch, AdaptTo::SceneAverage] {
            let s = ToneSettings { adapt_to: adapt_to.clone(), cat, ..ToneSettings::default() };
            let mut img = scene.clone();
            assert!(adapt_colour(&mut img, &s).is_some());
            let de = neutrality(&img);
            assert!(de <= 0.5, "{cat:?} from {adapt_to:?}: ΔE2000 {de}");
        }
    }
}

#[test]
fn scotopic_luminance_of_a_spectral_image_is_the_v_prime_integral() {
    // D65 at 10⁻³ of its relative values, in 40 bands over 380–780 nm: the band reconstruction
    // against the 1 nm integral K′_m Σ L(λ) V′(λ) of the same piecewise-linear spectrum.
    let bands = Bands::new(380.0, 780.0, 40).unwrap();
    let img = lit_cards("D65", &[0.1], bands);
    let got = SceneImage::from_spectral(&img).scotopic[0];
    let v: Vec<f64> = img.data.iter().map(|&x| f64::from(x)).collect();
    let recon = |l: f64| {
        let c: Vec<f64> = (0..40).map(|b| bands.centre_nm(b)).collect();
        if l <= c[0] {
            v[0]
        } else if l >= c[39] {
            v[39]
        } else {
            let j = c.iter().position(|&x| x > l).unwrap() - 1;
            let t = (l - c[j]) / (c[j + 1] - c[j]);
            (1.0 - t) * v[j] + t * v[j + 1]
        }
    };
    let want: f64 = K_M_SCOTOPIC * (380..=780u32).map(|nm| recon(f64::from(nm)) * v_prime_at_nm(nm)).sum::<f64>();
    assert!((got / want - 1.0).abs() < 1e-6, "{got} vs {want}");
    // And close to the exact spectrum's integral (band sampling of a smooth D65).
    let exact = morgana::tonemap::scotopic::scotopic_luminance(&named_illuminant("D65").unwrap().scaled(1e-3));
    assert!((got / exact - 1.0).abs() < 0.02, "{got} vs {exact}");
}

#[test]
fn every_operator_keeps_a_grey_ramp_ordered_and_neutral() {
    // 64 grey pixels from 10⁻³ to 10⁴ cd m⁻² (D65 chromaticity).
    let d65 = xy_to_xyz(DISPLAY_WHITE_XY);
    let xyz = (0..64).map(|i| d65.map(|c| c * 10f64.powf(-3.0 + 7.0 * f64::from(i) / 63.0))).collect();
    let img = SceneImage::from_xyz(64, 1, xyz).unwrap();
    for op in ["exposure", "reinhard", "ward_histogram", "pattanaik"] {
        for scotopic in ["off", "auto"] {
            let opts = morgana::tonemap::ToneOptions {
                operator: Some(op.into()),
                scotopic: Some(scotopic.into()),
                ..Default::default()
            };
            let out = tonemap(&img, &opts.validate().unwrap());
            let px: Vec<&[u8]> = out.rgb.chunks(3).collect();
            for (i, p) in px.iter().enumerate() {
                assert!(p[0].abs_diff(p[1]) <= 1 && p[1].abs_diff(p[2]) <= 1, "{op}/{scotopic}: pixel {i} {p:?}");
                if i > 0 {
                    assert!(p[1] >= px[i - 1][1], "{op}/{scotopic}: not monotone at {i}");
                }
            }
            assert!(px[63][1] > px[0][1], "{op}/{scotopic}: flat");
        }
    }
}

fn morgana() -> Command {
    Command::new(env!("CARGO_BIN_EXE_morgana"))
}

/// A 6×4 spectral EXR of a bluish scene (D65 through a blue-green filter) at mesopic levels.
fn write_test_exr(path: &Path) {
    let bands = Bands::new(400.0, 700.0, 8).unwrap();
    let d65 = &named_illuminant("D65").unwrap();
    let filter = |l: f64| (-((l - 490.0) / 60.0).powi(2)).exp();
    let data = (0..24)
        .flat_map(|p| {
            let k = 1e-5 * 10f64.powf(f64::from(p) / 6.0);
            (0..8).map(move |b| {
                let l = bands.centre_nm(b);
                (k * d65.eval(l) * filter(l)) as f32
            })
        })
        .collect();
    let img = SpectralImage { width: 6, height: 4, bands, data, rgb: vec![0.0; 72] };
    write_spectral_exr(path, &img).unwrap();
}

#[test]
fn the_tonemap_command_writes_pngs_and_region_csvs() {
    let dir = scratch("cli");
    let exr = dir.join("in.exr");
    write_test_exr(&exr);
    let runs: [&[&str]; 5] = [
        &["--operator", "reinhard", "--adapt-to", "scene-average"],
        &["--operator", "ward-histogram", "--scotopic", "on"],
        &["--operator", "pattanaik", "--adaptation-time-s", "2", "--adapt-from-cd-m2", "5000"],
        &["--exposure", "-3", "--adapt-to", "0.25,0.35", "--cat", "bradford", "--adaptation-degree", "0.5"],
        &["--false-colour", "--region", "1,1,4,3", "--csv", "sub/region.csv"],
    ];
    for (i, args) in runs.iter().enumerate() {
        let png = dir.join(format!("out{i}.png"));
        let out =
            morgana().current_dir(&dir).arg("tonemap").arg(&exr).arg("--out").arg(&png).args(*args).output().unwrap();
        assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
        let decoded =
            png::Decoder::new(std::io::BufReader::new(std::fs::File::open(&png).unwrap())).read_info().unwrap();
        assert!(decoded.info().width >= 6 && decoded.info().height >= 4);
    }
    let csv = std::fs::read_to_string(dir.join("sub/region.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + 3 * 2);
    // Nothing but the outputs: no staged temporary files left behind.
    let names: Vec<String> =
        std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).collect();
    assert!(names.iter().all(|n| !n.ends_with(".tmp")), "{names:?}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn an_rgb_exr_is_read_with_its_white_luminance() {
    use exr::prelude::*;
    let dir = scratch("rgb");
    let path = dir.join("rgb.exr");
    let channels = SpecificChannels::rgb(|Vec2(x, _y)| (x as f32 * 0.1, 0.2f32, 0.3f32));
    let mut image = Image::from_channels((4, 2), channels);
    image.layer_data.attributes.white_luminance = Some(100.0);
    image.write().to_file(&path).unwrap();
    let scene = morgana::tonemap::exr_read::read_exr(&path).unwrap();
    assert_eq!((scene.width, scene.height), (4, 2));
    // Y of RGB (0.1, 0.2, 0.3) × 100 cd m⁻²: 100 (0.2126 · 0.1 + 0.7152 · 0.2 + 0.0722 · 0.3).
    assert!((scene.xyz[1][1] - 100.0 * (0.02126 + 0.14304 + 0.02166)).abs() < 0.02, "{:?}", scene.xyz[1]);
    assert_eq!(scene.scotopic_source, morgana::tonemap::scene_image::ScotopicSource::EstimatedFromXyz);
    let out = morgana().arg("tonemap").arg(&path).arg("--out").arg(dir.join("rgb.png")).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_tonemap_input_exits_with_2_and_writes_nothing() {
    let dir = scratch("bad");
    let exr = dir.join("in.exr");
    write_test_exr(&exr);
    std::fs::write(dir.join("not.exr"), "hello").unwrap();
    let cases: [(&[&str], &str); 10] = [
        (&["--operator", "drago"], "--operator: \"drago\" is not an operator"),
        (&["--operator", "reinhard", "--exposure", "1"], "--exposure: exposure is only used by the exposure operator"),
        (&["--exposure", "bright"], "--exposure: \"bright\""),
        (&["--cat", "bradford"], "--cat: cat is only used together with adapt_to"),
        (&["--adapt-to", "0.8,0.5"], "--adapt-to: chromaticity (0.8, 0.5) is not valid"),
        (&["--operator", "pattanaik", "--adaptation-time-s", "3"], "needs adapt_from_cd_m2"),
        (&["--scotopic", "sometimes"], "--scotopic: \"sometimes\" is not known"),
        (&["--false-colour", "--operator", "reinhard"], "--operator: tonemap has no effect with false colour"),
        (&["--region", "0,0,7,4", "--csv", "r.csv"], "--region: region 0,0,7,4 reaches outside the 6×4 image"),
        (&["--region", "0,0,2,2"], "--region needs --csv"),
    ];
    for (args, want) in cases {
        let out =
            morgana().current_dir(&dir).arg("tonemap").arg(&exr).args(["--out", "o.png"]).args(args).output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(want), "{args:?}: {err}");
    }
    for (file, want) in
        [("missing.exr", "missing.exr: cannot read it"), ("not.exr", "not.exr: not a readable OpenEXR file")]
    {
        let out = morgana().current_dir(&dir).args(["tonemap", file, "--out", "o.png"]).output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{file}: {err}");
        assert!(err.contains(want), "{file}: {err}");
    }
    assert!(!dir.join("o.png").exists() && !dir.join("r.csv").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A small lit plate (`common::lit_plate`) whose [output] asks for a tone map.
static SCENE: std::sync::LazyLock<String> = std::sync::LazyLock::new(|| {
    let output =
        "\n[output]\nname = \"t\"\ntonemap = \"ward_histogram\"\nadapt_to = [0.28, 0.31]\nregion = [2, 2, 6, 5]\n";
    common::lit_plate(12, 8, output).replace("caustic_photons = 2000", "caustic_photons = 0")
});

#[test]
fn render_applies_the_output_tone_keys_and_rejects_bad_ones() {
    let dir = scratch("render");
    std::fs::write(dir.join("s.toml"), &*SCENE).unwrap();
    let out = morgana()
        .current_dir(&dir)
        .args(["render", "s.toml", "--out", "o", "--quiet", "--threads", "1"])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(dir.join("o/t.png").exists());
    assert_eq!(std::fs::read_to_string(dir.join("o/t.region.csv")).unwrap().lines().count(), 1 + 4 * 3);
    let bad = [
        ("tonemap = \"ward_histogram\"", "tonemap = \"drago\"", "test.toml:10:11: [output] tonemap:"),
        ("adapt_to = [0.28, 0.31]", "adapt_to = \"purple\"", "test.toml:11:12: [output] adapt_to:"),
        ("adapt_to = [0.28, 0.31]", "adaptation_time_s = 4.0", "test.toml:11:21: [output] adaptation_time_s:"),
        (
            "region = [2, 2, 6, 5]",
            "region = [2, 2, 13, 5]",
            "test.toml:12:10: [output] region: region 2,2,13,5 reaches outside the 12×8 image",
        ),
    ];
    for (from, to, want) in bad {
        let e = common::scene_error(&SCENE.replace(from, to));
        assert!(e.starts_with(want), "{to}: {e}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
