//! The morgana side of the colour-science cross-check (`scripts/colour_check.py`).
//!
//! The script sends one JSON request; every field is optional and asks for one group of
//! results, computed with morgana's own tables and code paths:
//!
//! ```json
//! {
//!   "cmf_integrals": true,
//!   "illuminant_samples_nm": [300, 305],
//!   "illuminants": ["D65", "A"],
//!   "reflectances": [{"name": "dark skin", "nm": [360, 361], "values": [0.05, 0.05]}],
//!   "blackbodies_k": [1000, 6500],
//!   "rgb_albedos": [[0.2, 0.5, 0.9]],
//!   "exr": [{"path": "out.exr", "min_nm": 380, "max_nm": 780, "count": 2,
//!            "width": 2, "height": 1, "pixels": [[0.1, 0.2], [0.3, 0.4]]}],
//!   "chromatic_adaptation": [{"method": "bradford", "xyz": [0.2, 0.1, 0.05],
//!                             "xyz_w": [1.1, 1.0, 0.36], "xyz_wr": [0.95, 1.0, 1.09]}],
//!   "scotopic": [{"name": "D65", "nm": [360, 361], "values": [0.05, 0.05]}]
//! }
//! ```
//!
//! and gets back, for the fields it sent:
//! - `cmf_integrals`: Σ x̄, Σ ȳ, Σ z̄ over 360–830 nm at 1 nm;
//! - `illuminant_values`: each named illuminant at the requested wavelengths;
//! - `illuminant_white`: relative XYZ of the perfect reflector (Y = 100) per illuminant;
//! - `reflectances`: per illuminant, each reflectance's relative XYZ (Y_white = 100, piecewise
//!   linear through the given samples) and linear sRGB of XYZ/100;
//! - `blackbodies`: absolute XYZ/Y of Planck radiance per temperature;
//! - `rgb_albedos`: the Jakob–Hanika coefficients and the fitted reflectance at 360..830 nm;
//! - `exr`: per image, the path written (through [`Staged`],
//!   [`write_spectral_exr`] and
//!   [`BandsToColour`]), the channel names and the RGB written, and the scotopic luminance of
//!   each pixel as `morgana tonemap` reads the file back ([`read_exr`]);
//! - `chromatic_adaptation`: each XYZ adapted from white `xyz_w` to `xyz_wr` by complete von Kries
//!   adaptation in the named space (`von_kries`, `bradford`, `cat16`;
//!   [`adaptation_matrix`]);
//! - `scotopic`: each spectral radiance's scotopic luminance K′_m Σ L(λ) V′(λ) · 1 nm
//!   ([`scotopic_luminance`]).

use crate::atomic::Staged;
use crate::spectrum::SpectralImage;
use crate::spectrum::colour::{BandsToColour, absolute_xyz, cmf_sums, relative_xyz, xyz_to_linear_srgb};
use crate::spectrum::exr::{emissive_channel_name, write_spectral_exr};
use crate::spectrum::{Bands, RgbSigmoid, Spectrum, Tabulated, named_illuminant};
use crate::tonemap::chromatic::{Cat, adaptation_matrix};
use crate::tonemap::exr_read::read_exr;
use crate::tonemap::matrix::mul_vec;
use crate::tonemap::scotopic::scotopic_luminance;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::PathBuf;

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct Request {
    #[serde(default)]
    cmf_integrals: bool,
    #[serde(default)]
    illuminant_samples_nm: Vec<f64>,
    #[serde(default)]
    illuminants: Vec<String>,
    #[serde(default)]
    reflectances: Vec<NamedSamples>,
    #[serde(default)]
    blackbodies_k: Vec<f64>,
    #[serde(default)]
    rgb_albedos: Vec<[f64; 3]>,
    #[serde(default)]
    exr: Vec<ExrRequest>,
    #[serde(default)]
    chromatic_adaptation: Vec<CatRequest>,
    #[serde(default)]
    scotopic: Vec<NamedSamples>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CatRequest {
    method: String,
    xyz: [f64; 3],
    xyz_w: [f64; 3],
    xyz_wr: [f64; 3],
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct NamedSamples {
    name: String,
    nm: Vec<f64>,
    values: Vec<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ExrRequest {
    path: PathBuf,
    min_nm: f64,
    max_nm: f64,
    count: usize,
    width: usize,
    height: usize,
    /// Row-major pixels, `count` band values each.
    pixels: Vec<Vec<f64>>,
}

#[derive(Serialize, Default)]
struct Response {
    #[serde(skip_serializing_if = "Option::is_none")]
    cmf_integrals: Option<[f64; 3]>,
    #[serde(skip_serializing_if = "BTreeMap::is_empty")]
    illuminant_values: BTreeMap<String, Vec<f64>>,
    #[serde(skip_serializing_if = "BTreeMap::is_empty")]
    illuminant_white: BTreeMap<String, [f64; 3]>,
    #[serde(skip_serializing_if = "BTreeMap::is_empty")]
    reflectances: BTreeMap<String, Vec<Colour>>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    blackbodies: Vec<Blackbody>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    rgb_albedos: Vec<Albedo>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    exr: Vec<ExrResponse>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    chromatic_adaptation: Vec<[f64; 3]>,
    #[serde(skip_serializing_if = "BTreeMap::is_empty")]
    scotopic: BTreeMap<String, f64>,
}

#[derive(Serialize)]
struct Colour {
    name: String,
    xyz: [f64; 3],
    linear_srgb: [f64; 3],
}

#[derive(Serialize)]
struct Blackbody {
    temperature_k: f64,
    xyz_normalised: [f64; 3],
}

#[derive(Serialize)]
struct Albedo {
    rgb: [f64; 3],
    coefficients: [f64; 3],
    /// The reflectance at 360, 361, …, 830 nm.
    reflectance: Vec<f64>,
}

#[derive(Serialize)]
struct ExrResponse {
    path: PathBuf,
    channels: Vec<String>,
    rgb: Vec<[f32; 3]>,
    /// Scotopic luminance per pixel, read back from the file.
    scotopic: Vec<f64>,
}

/// Reads the check's JSON request and answers with morgana's colorimetry as JSON.
pub fn run(request_json: &str) -> Result<String, String> {
    let req: Request =
        serde_json::from_str(request_json).map_err(|e| format!("colour-check request is not valid: {e}"))?;
    let mut out = Response::default();
    if req.cmf_integrals {
        out.cmf_integrals = Some(cmf_sums(|_| 1.0));
    }
    let illuminants = req
        .illuminants
        .iter()
        .map(|name| {
            named_illuminant(name)
                .map(|s| (name.clone(), s))
                .ok_or_else(|| format!("unknown illuminant '{name}': allowed are D65, A, E"))
        })
        .collect::<Result<Vec<_>, String>>()?;
    let reflectances = req
        .reflectances
        .iter()
        .map(|r| {
            Tabulated::new(r.nm.clone(), r.values.clone())
                .map(|t| (r.name.clone(), Spectrum::Tabulated(t)))
                .map_err(|e| format!("reflectance '{}': {e}", r.name))
        })
        .collect::<Result<Vec<_>, String>>()?;
    for (name, illuminant) in &illuminants {
        if !req.illuminant_samples_nm.is_empty() {
            let values = req.illuminant_samples_nm.iter().map(|&l| illuminant.eval(l));
            out.illuminant_values.insert(name.clone(), values.collect());
        }
        let white = relative_xyz(&Spectrum::Constant(1.0), illuminant);
        out.illuminant_white.insert(name.clone(), white);
        if reflectances.is_empty() {
            continue;
        }
        let colours = reflectances
            .iter()
            .map(|(patch, r)| {
                let xyz = relative_xyz(r, illuminant);
                Colour { name: patch.clone(), xyz, linear_srgb: xyz_to_linear_srgb(xyz.map(|c| c / 100.0)) }
            })
            .collect();
        out.reflectances.insert(name.clone(), colours);
    }
    for &t in &req.blackbodies_k {
        if !(t.is_finite() && t > 0.0) {
            return Err(format!("black-body temperature {t} K: must be positive"));
        }
        let xyz = absolute_xyz(&Spectrum::Blackbody { temperature_k: t });
        out.blackbodies.push(Blackbody { temperature_k: t, xyz_normalised: xyz.map(|c| c / xyz[1]) });
    }
    for &rgb in &req.rgb_albedos {
        let fit = RgbSigmoid::fit(rgb)?;
        let reflectance = (360..=830).map(|nm| fit.eval(f64::from(nm))).collect();
        out.rgb_albedos.push(Albedo { rgb, coefficients: fit.coefficients, reflectance });
    }
    for exr in &req.exr {
        out.exr.push(write_exr(exr)?);
    }
    for c in &req.chromatic_adaptation {
        out.chromatic_adaptation.push(adapt(c)?);
    }
    for s in &req.scotopic {
        let t = Tabulated::new(s.nm.clone(), s.values.clone()).map_err(|e| format!("scotopic '{}': {e}", s.name))?;
        out.scotopic.insert(s.name.clone(), scotopic_luminance(&Spectrum::Tabulated(t)));
    }
    serde_json::to_string(&out).map_err(|e| format!("cannot encode the colour-check answer: {e}"))
}

/// Writes the requested pixels as a spectral EXR through the real output path.
fn write_exr(req: &ExrRequest) -> Result<ExrResponse, String> {
    let bands = Bands::new(req.min_nm, req.max_nm, req.count)?;
    if req.pixels.len() != req.width * req.height {
        return Err(format!("exr: {} pixels given for a {}×{} image", req.pixels.len(), req.width, req.height));
    }
    if let Some(i) = req.pixels.iter().position(|p| p.len() != bands.count) {
        return Err(format!("exr: pixel {i} has {} band values, need {}", req.pixels[i].len(), bands.count));
    }
    let conv = BandsToColour::new(&bands);
    let data: Vec<f32> = req.pixels.iter().flatten().map(|&v| v as f32).collect();
    // Colour from the values as stored (f32), so the RGB matches the spectral channels exactly.
    let rgb: Vec<[f32; 3]> = data
        .chunks_exact(bands.count)
        .map(|p| {
            let v: Vec<f64> = p.iter().map(|&x| f64::from(x)).collect();
            conv.linear_srgb(&v).map(|c| c as f32)
        })
        .collect();
    let image = SpectralImage {
        width: req.width,
        height: req.height,
        bands,
        data,
        rgb: rgb.iter().flatten().copied().collect(),
    };
    let staged = Staged::new(&req.path).map_err(|e| format!("exr: {e}"))?;
    write_spectral_exr(&staged.temp, &image).map_err(|e| format!("exr: {e}"))?;
    staged.commit().map_err(|e| format!("exr: {e}"))?;
    let back = read_exr(&req.path).map_err(|e| format!("exr: reading {} back: {e}", req.path.display()))?;
    Ok(ExrResponse {
        path: req.path.clone(),
        channels: (0..bands.count).map(|b| emissive_channel_name(bands.centre_nm(b))).collect(),
        rgb,
        scotopic: back.scotopic,
    })
}

/// One chromatic-adaptation case.
fn adapt(c: &CatRequest) -> Result<[f64; 3], String> {
    let cat = Cat::parse(&c.method)
        .ok_or_else(|| format!("chromatic adaptation method '{}': allowed are von_kries, bradford, cat16", c.method))?;
    let m = adaptation_matrix(cat, c.xyz_w, c.xyz_wr, 1.0)
        .ok_or_else(|| format!("chromatic adaptation: whites {:?} → {:?} are not usable", c.xyz_w, c.xyz_wr))?;
    Ok(mul_vec(&m, c.xyz))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn answers_each_requested_group() {
        let answer = run(r#"{"cmf_integrals": true, "illuminants": ["D65"],
            "reflectances": [{"name": "grey", "nm": [300, 900], "values": [0.5, 0.5]}],
            "blackbodies_k": [6500]}"#)
        .unwrap();
        let v: serde_json::Value = serde_json::from_str(&answer).unwrap();
        let y = v["cmf_integrals"][1].as_f64().unwrap();
        assert!((y - 106.857).abs() < 1e-3);
        let grey_y = v["reflectances"]["D65"][0]["xyz"][1].as_f64().unwrap();
        assert!((grey_y - 50.0).abs() < 1e-9);
        assert_eq!(v["blackbodies"][0]["xyz_normalised"][1].as_f64(), Some(1.0));
        assert!(v.get("exr").is_none());
        // The white is mapped onto the target white; a flat spectrum's L′ is K′_m Σ V′.
        let answer = run(r#"{"chromatic_adaptation": [{"method": "von_kries", "xyz": [1.1, 1.0, 0.4],
            "xyz_w": [1.1, 1.0, 0.4], "xyz_wr": [0.95, 1.0, 1.09]}],
            "scotopic": [{"name": "flat", "nm": [300, 900], "values": [1, 1]}]}"#)
        .unwrap();
        let v: serde_json::Value = serde_json::from_str(&answer).unwrap();
        let z = v["chromatic_adaptation"][0][2].as_f64().unwrap();
        assert!((z - 1.09).abs() < 1e-12, "{z}");
        let flat = v["scotopic"]["flat"].as_f64().unwrap();
        assert!((flat / (1700.06 * 97.071_316_574) - 1.0).abs() < 1e-9, "{flat}");
    }

    #[test]
    fn writes_the_requested_exr_through_the_staged_writer() {
        let dir = std::env::temp_dir().join(format!("morgana-check-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("c.exr");
        let request = serde_json::json!({"exr": [{"path": path, "min_nm": 400, "max_nm": 700,
            "count": 2, "width": 1, "height": 1, "pixels": [[0.5, 0.25]]}]});
        let answer: serde_json::Value = serde_json::from_str(&run(&request.to_string()).unwrap()).unwrap();
        assert!(path.exists());
        assert_eq!(answer["exr"][0]["channels"][0], "S0.475,0nm");
        assert!(answer["exr"][0]["scotopic"][0].as_f64().unwrap() > 0.0);
        let want = BandsToColour::new(&Bands::new(400.0, 700.0, 2).unwrap()).linear_srgb(&[0.5, 0.25]);
        let got = answer["exr"][0]["rgb"][0][1].as_f64().unwrap();
        assert!((got - want[1]).abs() < 1e-6 * want[1].abs());
        // Only the target is left behind: the temporary file was renamed.
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn rejects_bad_requests_with_reasons() {
        assert!(run("{").unwrap_err().contains("not valid"));
        assert!(run(r#"{"bogus": 1}"#).unwrap_err().contains("bogus"));
        assert!(run(r#"{"illuminants": ["D50"]}"#).unwrap_err().contains("D50"));
        let e = run(r#"{"reflectances": [{"name": "x", "nm": [1], "values": [1]}]}"#);
        assert!(e.unwrap_err().contains("at least 2"));
        let e = run(r#"{"rgb_albedos": [[2, 0, 0]]}"#).unwrap_err();
        assert!(e.contains("[0, 1]"), "{e}");
        let e = run(r#"{"chromatic_adaptation": [{"method": "cat02", "xyz": [1, 1, 1], "xyz_w": [1, 1, 1],
            "xyz_wr": [1, 1, 1]}]}"#);
        assert!(e.unwrap_err().contains("cat02"));
    }
}
