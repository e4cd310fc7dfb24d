//! Reading the tone mapper's input from OpenEXR: spectral (Fichet et al. 2021) or RGB.
//!
//! - **Spectral**: the emissive channels `S0.<λ><unit>` of the first layer holding them are band
//!   values of spectral radiance in W m⁻² sr⁻¹ nm⁻¹ (the layout's `emissiveUnits`), the number
//!   written with a decimal comma or point and an optional exponent, the unit a metre with an SI
//!   prefix (`nm`, `um`, `m`, …) or a frequency (`Hz`, `THz`, …). Band edges are morgana's
//!   `morganaBandMinNm`/`morganaBandMaxNm` attributes when present; otherwise the bands are taken
//!   to extend half the spacing of the neighbouring centres beyond the outer ones (a single
//!   band needs the attributes). Colour and scotopic luminance come from
//!   [`BandWeights`].
//! - **RGB**: channels `R`, `G`, `B` are linear values in the file's `chromaticities` (sRGB /
//!   D65 when absent) and `whiteLuminance` cd m⁻² for RGB = (1, 1, 1) (1 when absent, morgana's
//!   convention); the RGB → XYZ matrix follows SMPTE RP 177 from the primaries and white. A
//!   lone `Y` channel is read as a D65-grey luminance image. The scotopic luminance is then
//!   estimated from XYZ.
//!
//! # References
//! - A. Fichet, R. Pacanowski, A. Wilkie (2021), "An OpenEXR Layout for Spectral Images", JCGT
//!   10(3), §3–4.
//! - SMPTE RP 177-1993, *Derivation of Basic Television Color Equations*, §3.3.

use super::matrix::{Mat3, diagonal, invert, mul, mul_vec, xy_to_xyz};
use super::scene_image::SceneImage;
use super::spectral_weights::BandWeights;
use crate::spectrum::colour::linear_srgb_to_xyz;
use crate::spectrum::exr::{BAND_MAX_ATTRIBUTE, BAND_MIN_ATTRIBUTE};
use exr::prelude::{AttributeValue, FlatSamples, Text};
use std::path::Path;

type FlatLayer = exr::prelude::Layer<exr::prelude::AnyChannels<FlatSamples>>;

/// The most samples (pixels × channels, over every layer) an input image may hold: 2²⁹, 2 GiB
/// of 32-bit samples — a 3840 × 2160 image of 64 bands fits. The header is read first, so a
/// corrupt `dataWindow` is refused before the decoder allocates for it.
pub const MAX_EXR_SAMPLES: u64 = 1 << 29;

/// Reads `path` into a [`SceneImage`]; errors say what the file lacks.
pub fn read_exr(path: &Path) -> Result<SceneImage, String> {
    check_size(path)?;
    let image = exr::prelude::read_all_flat_layers_from_file(path).map_err(|e| match e {
        exr::error::Error::Io(io) => format!("cannot read it: {io}"),
        other => format!("not a readable OpenEXR file ({other}); give an EXR written by morgana render"),
    })?;
    let chroma = image.attributes.chromaticities;
    for layer in &image.layer_data {
        check_finite(layer)?;
    }
    if let Some(layer) = image.layer_data.iter().find(|l| !spectral_channels(l).is_empty()) {
        return read_spectral(layer);
    }
    match image.layer_data.first() {
        Some(layer) => read_tristimulus(layer, chroma),
        None => Err("the file has no image layer".into()),
    }
}

/// Refuses a file whose headers ask for more than [`MAX_EXR_SAMPLES`] samples, or for more memory
/// than [`crate::memory::available_bytes`], naming the `dataWindow` attribute and the sizes.
fn check_size(path: &Path) -> Result<(), String> {
    let meta = exr::meta::MetaData::read_from_file(path, false).map_err(|e| match e {
        exr::error::Error::Io(io) => format!("cannot read it: {io}"),
        other => format!("not a readable OpenEXR file ({other}); give an EXR written by morgana render"),
    })?;
    let mut total: u64 = 0;
    for h in meta.headers.iter() {
        let (w, ht) = (h.layer_size.0 as u64, h.layer_size.1 as u64);
        let n = h.channels.list.len() as u64;
        total = total.saturating_add(w.saturating_mul(ht).saturating_mul(n));
        if total > MAX_EXR_SAMPLES {
            return Err(format!(
                "attribute dataWindow: {w} × {ht} pixels of {n} channels make more than {MAX_EXR_SAMPLES} samples, the most the tone mapper reads; is the header corrupt?"
            ));
        }
    }
    // The decoded samples, the band-interleaved copy and the colour planes: three 32-bit copies.
    let need = total.saturating_mul(3 * 4);
    if let Some(avail) = crate::memory::available_bytes().filter(|&a| need > a) {
        let mib = |b: u64| b / (1 << 20);
        return Err(format!(
            "attribute dataWindow: {total} samples need about {} MiB to tone-map, and {} MiB are available; is the header corrupt?",
            mib(need),
            mib(avail)
        ));
    }
    Ok(())
}

/// Refuses a layer holding NaN or infinite samples, naming the first (pixel and channel) and
/// how many there are: a tone-mapped picture of them would be meaningless.
fn check_finite(layer: &FlatLayer) -> Result<(), String> {
    let w = layer.size.0.max(1);
    let mut first = None;
    let mut count = 0usize;
    for c in &layer.channel_data.list {
        for (p, v) in c.sample_data.values_as_f32().enumerate() {
            if !v.is_finite() {
                count += 1;
                first.get_or_insert((p % w, p / w, c.name.to_string(), v));
            }
        }
    }
    match first {
        None => Ok(()),
        Some((x, y, channel, v)) => Err(format!(
            "pixel ({x}, {y}) of channel {channel} is {v}, and {count} samples in all are not finite; the tone mapper needs finite radiance"
        )),
    }
}

/// (wavelength nm, channel index) of the `S0` channels, sorted by wavelength.
fn spectral_channels(layer: &FlatLayer) -> Vec<(f64, usize)> {
    let mut v: Vec<(f64, usize)> = layer
        .channel_data
        .list
        .iter()
        .enumerate()
        .filter_map(|(i, c)| parse_emissive_wavelength_nm(&c.name.to_string()).map(|nm| (nm, i)))
        .collect();
    v.sort_by(|a, b| a.0.total_cmp(&b.0));
    v
}

fn read_spectral(layer: &FlatLayer) -> Result<SceneImage, String> {
    let channels = spectral_channels(layer);
    let centres: Vec<f64> = channels.iter().map(|c| c.0).collect();
    let (min_nm, max_nm) = band_edges(layer, &centres)?;
    let weights = BandWeights::new(&centres, min_nm, max_nm).map_err(|e| format!("spectral channels: {e}"))?;
    let (w, h) = (layer.size.0, layer.size.1);
    let n = centres.len();
    let mut data = vec![0f32; w * h * n];
    for (b, &(_, ci)) in channels.iter().enumerate() {
        for (p, v) in layer.channel_data.list[ci].sample_data.values_as_f32().enumerate().take(w * h) {
            data[p * n + b] = v;
        }
    }
    SceneImage::from_bands(w, h, &weights, n, &data)
}

fn band_edges(layer: &FlatLayer, c: &[f64]) -> Result<(f64, f64), String> {
    let attr = |name: &str| match layer.attributes.other.get(&Text::from(name)) {
        Some(AttributeValue::F64(v)) => Some(*v),
        Some(AttributeValue::F32(v)) => Some(f64::from(*v)),
        _ => None,
    };
    if let (Some(lo), Some(hi)) = (attr(BAND_MIN_ATTRIBUTE), attr(BAND_MAX_ATTRIBUTE)) {
        return Ok((lo, hi));
    }
    let n = c.len();
    if n < 2 {
        return Err(format!(
            "one spectral channel ({} nm) and no {BAND_MIN_ATTRIBUTE}/{BAND_MAX_ATTRIBUTE} attributes: the band width is unknown",
            c[0]
        ));
    }
    Ok((c[0] - 0.5 * (c[1] - c[0]), c[n - 1] + 0.5 * (c[n - 1] - c[n - 2])))
}

/// The wavelength in nm of an emissive channel name `S0.<number><unit>`, if it is one.
pub fn parse_emissive_wavelength_nm(name: &str) -> Option<f64> {
    let rest = name.strip_prefix("S0.")?;
    let (body, hertz) = match rest.strip_suffix("Hz") {
        Some(b) => (b, true),
        None => (rest.strip_suffix('m')?, false),
    };
    const PREFIXES: [(&str, f64); 16] = [
        ("da", 1e1),
        ("Y", 1e24),
        ("Z", 1e21),
        ("E", 1e18),
        ("P", 1e15),
        ("T", 1e12),
        ("G", 1e9),
        ("M", 1e6),
        ("k", 1e3),
        ("h", 1e2),
        ("d", 1e-1),
        ("c", 1e-2),
        ("m", 1e-3),
        ("u", 1e-6),
        ("n", 1e-9),
        ("p", 1e-12),
    ];
    let (number, factor) = PREFIXES
        .iter()
        .find_map(|(p, f)| body.strip_suffix(p).filter(|n| parse_number(n).is_some()).map(|n| (n, *f)))
        .unwrap_or((body, 1.0));
    let value = parse_number(number)? * factor;
    let nm = if hertz { 299_792_458.0 / value * 1e9 } else { value * 1e9 };
    (nm.is_finite() && nm > 0.0).then_some(nm)
}

/// A number with a decimal comma or point and an optional exponent.
fn parse_number(s: &str) -> Option<f64> {
    let ok = !s.is_empty() && s.chars().all(|c| c.is_ascii_digit() || ",.eE+-".contains(c));
    if ok { s.replace(',', ".").parse().ok() } else { None }
}

fn read_tristimulus(
    layer: &FlatLayer,
    chroma: Option<exr::meta::attribute::Chromaticities>,
) -> Result<SceneImage, String> {
    let (w, h) = (layer.size.0, layer.size.1);
    let get = |name: &str| -> Option<Vec<f32>> {
        let c = layer.channel_data.list.iter().find(|c| c.name == *name)?;
        Some(c.sample_data.values_as_f32().collect())
    };
    let names: Vec<String> = layer.channel_data.list.iter().map(|c| c.name.to_string()).collect();
    let white_luminance = f64::from(layer.attributes.white_luminance.unwrap_or(1.0));
    let xyz: Vec<[f64; 3]> = match (get("R"), get("G"), get("B"), get("Y")) {
        (Some(r), Some(g), Some(b), _) => {
            let m = rgb_to_xyz(chroma)?;
            (0..w * h).map(|i| mul_vec(&m, [r[i], g[i], b[i]].map(|v| white_luminance * f64::from(v)))).collect()
        }
        (_, _, _, Some(y)) => {
            let white = xy_to_xyz([0.3127, 0.3290]);
            y.iter().map(|&v| white.map(|c| c * white_luminance * f64::from(v))).collect()
        }
        _ => {
            return Err(format!(
                "it has neither spectral S0.<wavelength>nm channels nor R, G, B (or Y); its channels are {}",
                names.join(", ")
            ));
        }
    };
    SceneImage::from_xyz(w, h, xyz)
}

/// RGB → XYZ for the file's primaries (morgana's own sRGB matrix when they are sRGB's).
fn rgb_to_xyz(chroma: Option<exr::meta::attribute::Chromaticities>) -> Result<Mat3, String> {
    let srgb = [[0.64, 0.33], [0.30, 0.60], [0.15, 0.06], [0.3127, 0.3290]];
    let given = chroma.map(|c| [c.red, c.green, c.blue, c.white].map(|v| [f64::from(v.0), f64::from(v.1)]));
    let p = given.unwrap_or(srgb);
    let same = p.iter().flatten().zip(srgb.iter().flatten()).all(|(a, b)| (a - b).abs() < 1e-4);
    if same {
        let cols = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]].map(linear_srgb_to_xyz);
        return Ok([0, 1, 2].map(|r| [cols[0][r], cols[1][r], cols[2][r]]));
    }
    let bad = || format!("its chromaticities {p:?} are not usable primaries");
    if p.iter().any(|xy| !(xy[1] > 0.0 && xy[1].is_finite() && xy[0].is_finite())) {
        return Err(bad());
    }
    let prim = [0, 1, 2].map(|r| [0, 1, 2].map(|k| xy_to_xyz(p[k])[r]));
    let s = mul_vec(&invert(&prim).ok_or_else(bad)?, xy_to_xyz(p[3]));
    Ok(mul(&prim, &diagonal(s)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_the_layouts_channel_names() {
        assert_eq!(parse_emissive_wavelength_nm("S0.550,0nm"), Some(550.0));
        assert_eq!(parse_emissive_wavelength_nm("S0.392,5nm"), Some(392.5));
        assert_eq!(parse_emissive_wavelength_nm("S0.550nm"), Some(550.0));
        assert_eq!(parse_emissive_wavelength_nm("S0.5,5e2nm"), Some(550.0));
        let um = parse_emissive_wavelength_nm("S0.0,55um").unwrap();
        assert!((um - 550.0).abs() < 1e-9);
        let thz = parse_emissive_wavelength_nm("S0.545,077THz").unwrap();
        assert!((thz - 550.0).abs() < 1e-3, "{thz}");
        for bad in ["S1.550nm", "R", "S0.nm", "S0.abcnm", "S0.550", "S0.-5nm"] {
            assert_eq!(parse_emissive_wavelength_nm(bad), None, "{bad}");
        }
    }

    #[test]
    fn srgb_primaries_give_morganas_matrix_and_others_are_derived() {
        let m = rgb_to_xyz(None).unwrap();
        let white = mul_vec(&m, [1.0; 3]);
        assert!((white[0] - 0.9505).abs() < 2e-4 && (white[1] - 1.0).abs() < 2e-4, "{white:?}");
        // Rec. 2020 primaries: white maps to the D65 white with Y = 1 (SMPTE RP 177).
        let c = exr::meta::attribute::Chromaticities {
            red: exr::math::Vec2(0.708, 0.292),
            green: exr::math::Vec2(0.170, 0.797),
            blue: exr::math::Vec2(0.131, 0.046),
            white: exr::math::Vec2(0.3127, 0.3290),
        };
        let m = rgb_to_xyz(Some(c)).unwrap();
        let w = mul_vec(&m, [1.0; 3]);
        let d65 = xy_to_xyz([0.3127, 0.3290]);
        assert!((0..3).all(|k| (w[k] - d65[k]).abs() < 1e-6), "{w:?}");
        // ITU-R BT.2020 luminance row: 0.2627, 0.6780, 0.0593.
        for (a, b) in m[1].iter().zip([0.2627, 0.6780, 0.0593]) {
            assert!((a - b).abs() < 2e-4, "{:?}", m[1]);
        }
    }
}
