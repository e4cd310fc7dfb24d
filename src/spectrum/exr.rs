//! Spectral OpenEXR in the layout of Fichet, Pacanowski & Wilkie 2021.
//!
//! One single-part, scan-line, ZIP-compressed, 32-bit float image holding:
//! - one emissive (Stokes S0) channel per band, named `S0.<centre>nm` with the band centre in nm
//!   written with a comma as decimal separator (`S0.392,5nm`, `S0.400,0nm`), holding the band's
//!   spectral radiance in W m⁻² sr⁻¹ nm⁻¹ (the value of the spectral density at the centre, as
//!   the layout stores it);
//! - `R`, `G`, `B`: the linear-sRGB rendering of the same pixel from
//!   [`BandsToColour`](crate::spectrum::colour::BandsToColour), absolute (Y in cd m⁻²), with
//!   the `chromaticities` of sRGB/D65 and `whiteLuminance` = 1 (cd m⁻² of RGB = (1, 1, 1));
//! - the header attributes the layout requires for emissive images: `spectralLayoutVersion` =
//!   "1.0" and `emissiveUnits` = "W.m^-2.sr^-1" (the layout's only defined value, spectral
//!   radiance per unit wavelength; also what its reference implementation, ART, pbrt-v4 and
//!   colour-science write); and morgana's own `morganaBandMinNm` / `morganaBandMaxNm` (double),
//!   the outer band edges, which the layout does not record. Channel names follow the layout's pattern
//!   `^S[0-3]\.(\d*,?\d*([Ee][+-]?\d+)?)(Y|Z|E|P|T|G|M|k|h|da|d|c|m|u|n|p)?(m|Hz)$`.
//!
//! colour-science's `read_spectral_image_Fichet2021` reads these files (checked by
//! `scripts/colour_check.py`).
//!
//! # References
//! - A. Fichet, R. Pacanowski, A. Wilkie (2021), "An OpenEXR Layout for Spectral Images",
//!   Journal of Computer Graphics Techniques 10(3), 1–18, §3 (channel naming) and §4
//!   (attributes).

use crate::spectrum::SpectralImage;
use exr::prelude::*;
use std::io;
use std::path::Path;

/// The layout version this writer follows.
pub const SPECTRAL_LAYOUT_VERSION: &str = "1.0";
/// The `emissiveUnits` attribute value.
pub const EMISSIVE_UNITS: &str = "W.m^-2.sr^-1";

/// Header attribute (double) holding the lower edge of the first band, nm. The layout stores
/// only band centres; with the edges a reader can rebuild the band reconstruction of
/// [`BandsToColour`](crate::spectrum::colour::BandsToColour) exactly (also for one band).
pub const BAND_MIN_ATTRIBUTE: &str = "morganaBandMinNm";
/// Header attribute (double) holding the upper edge of the last band, nm.
pub const BAND_MAX_ATTRIBUTE: &str = "morganaBandMaxNm";

/// The channel name of emissive band centre `centre_nm`: `S0.<nm>nm`, decimal comma, rounded
/// to 10⁻⁴ nm, at least one decimal (`S0.550,0nm`).
pub fn emissive_channel_name(centre_nm: f64) -> String {
    let rounded = (centre_nm * 1e4).round() / 1e4;
    let text = if rounded.fract() == 0.0 { format!("{rounded:.1}") } else { format!("{rounded}") };
    format!("S0.{}nm", text.replace('.', ","))
}

/// The prefix of the standard-error layer: channel `stderr.S0.550,0nm` holds the standard error
/// of channel `S0.550,0nm` (same units). Readers of the Fichet et al. layout skip it: its
/// names do not match the layout's `^S[0-3]\.` pattern, and EXR reads `stderr` as a layer name.
pub const STDERR_LAYER: &str = "stderr";

/// The standard-error channel of emissive band centre `centre_nm`: `stderr.S0.<nm>nm`.
pub fn stderr_channel_name(centre_nm: f64) -> String {
    format!("{STDERR_LAYER}.{}", emissive_channel_name(centre_nm))
}

/// Writes `image` to `path` (not atomically: callers write to a staged temporary path).
pub fn write_spectral_exr(path: &Path, image: &SpectralImage) -> io::Result<()> {
    write_spectral_exr_with_error(path, image, None)
}

/// Writes `image` to `path` and, when given, the standard error of each band value (laid out
/// as `image.data`) as the [`STDERR_LAYER`] channels.
pub fn write_spectral_exr_with_error(path: &Path, image: &SpectralImage, std_error: Option<&[f32]>) -> io::Result<()> {
    check_shape(image)?;
    let (w, h, n) = (image.width, image.height, image.bands.count);
    let pixels = w * h;
    let mut channels: Vec<AnyChannel<FlatSamples>> = Vec::with_capacity(n + 3);
    for (k, name) in ["R", "G", "B"].iter().enumerate() {
        let samples = (0..pixels).map(|p| image.rgb[3 * p + k]).collect();
        channels.push(AnyChannel::new(*name, FlatSamples::F32(samples)));
    }
    let mut names = Vec::with_capacity(n);
    for b in 0..n {
        let name = emissive_channel_name(image.bands.centre_nm(b));
        if names.contains(&name) {
            return Err(invalid(format!(
                "bands {:?} are narrower than the 1e-4 nm resolution of channel names ({name} twice)",
                image.bands
            )));
        }
        let samples = (0..pixels).map(|p| image.data[p * n + b]).collect();
        channels.push(AnyChannel::new(name.as_str(), FlatSamples::F32(samples)));
        if let Some(se) = std_error.filter(|se| se.len() == image.data.len()) {
            let samples = (0..pixels).map(|p| se[p * n + b]).collect();
            channels.push(AnyChannel::new(
                stderr_channel_name(image.bands.centre_nm(b)).as_str(),
                FlatSamples::F32(samples),
            ));
        }
        names.push(name);
    }
    let mut layer_attributes = LayerAttributes {
        software_name: Some(Text::from("morgana")),
        white_luminance: Some(1.0),
        ..LayerAttributes::default()
    };
    layer_attributes
        .other
        .insert(Text::from("spectralLayoutVersion"), AttributeValue::Text(Text::from(SPECTRAL_LAYOUT_VERSION)));
    layer_attributes.other.insert(Text::from("emissiveUnits"), AttributeValue::Text(Text::from(EMISSIVE_UNITS)));
    layer_attributes.other.insert(Text::from(BAND_MIN_ATTRIBUTE), AttributeValue::F64(image.bands.min_nm));
    layer_attributes.other.insert(Text::from(BAND_MAX_ATTRIBUTE), AttributeValue::F64(image.bands.max_nm));
    // Increasing line order, compressed on one thread: the file's bytes do not depend on thread
    // timing (the exr crate's parallel writer emits chunks in completion order).
    let encoding = Encoding { line_order: exr::meta::attribute::LineOrder::Increasing, ..Encoding::SMALL_LOSSLESS };
    let layer = Layer::new((w, h), layer_attributes, encoding, AnyChannels::sort(channels.into()));
    let mut exr_image = Image::from_layer(layer);
    exr_image.attributes.chromaticities = Some(exr::meta::attribute::Chromaticities {
        red: Vec2(0.64, 0.33),
        green: Vec2(0.30, 0.60),
        blue: Vec2(0.15, 0.06),
        white: Vec2(0.3127, 0.3290),
    });
    exr_image.write().non_parallel().to_file(path).map_err(|e| match e {
        exr::error::Error::Io(io) => io,
        other => io::Error::other(format!("cannot write spectral EXR '{}': {other}", path.display())),
    })?;
    let mut bytes = std::fs::read(path)?;
    sort_header_attributes(&mut bytes)?;
    std::fs::write(path, bytes)
}

/// Sorts the attributes of a single-part EXR header by name, in place.
///
/// The exr crate writes custom attributes in `HashMap` order, which changes from run to run; the
/// header is a sequence of `name\0 type\0 size:i32le value` records ended by a zero byte
/// (OpenEXR file layout, §"Header"), and offsets after it are absolute, so permuting the records
/// leaves the file valid and makes its bytes reproducible.
fn sort_header_attributes(bytes: &mut [u8]) -> io::Result<()> {
    let bad = || invalid("EXR header could not be parsed for canonical ordering".to_string());
    let start = 8;
    let mut pos = start;
    let mut records: Vec<(Vec<u8>, Vec<u8>)> = Vec::new();
    let cstr_end = |from: usize| bytes[from..].iter().position(|b| *b == 0).map(|i| from + i);
    while *bytes.get(pos).ok_or_else(bad)? != 0 {
        let name_end = cstr_end(pos).ok_or_else(bad)?;
        let type_end = cstr_end(name_end + 1).ok_or_else(bad)?;
        let size_bytes: [u8; 4] =
            bytes.get(type_end + 1..type_end + 5).ok_or_else(bad)?.try_into().map_err(|_| bad())?;
        let size = usize::try_from(i32::from_le_bytes(size_bytes)).map_err(|_| bad())?;
        let end = type_end + 5 + size;
        let record = bytes.get(pos..end).ok_or_else(bad)?.to_vec();
        records.push((bytes[pos..name_end].to_vec(), record));
        pos = end;
    }
    records.sort();
    let mut out = start;
    for (_, r) in records {
        bytes[out..out + r.len()].copy_from_slice(&r);
        out += r.len();
    }
    Ok(())
}

/// The image's buffers must match its size and band count.
pub(super) fn check_shape(image: &SpectralImage) -> io::Result<()> {
    let pixels = image.width.saturating_mul(image.height);
    if image.width == 0 || image.height == 0 {
        return Err(invalid(format!(
            "image is {}×{} pixels: width and height must be at least 1",
            image.width, image.height
        )));
    }
    if Some(image.data.len()) != pixels.checked_mul(image.bands.count) {
        return Err(invalid(format!(
            "spectral data holds {} values: a {}×{} image with {} bands needs {}",
            image.data.len(),
            image.width,
            image.height,
            image.bands.count,
            pixels.saturating_mul(image.bands.count)
        )));
    }
    if Some(image.rgb.len()) != pixels.checked_mul(3) {
        return Err(invalid(format!(
            "RGB data holds {} values: a {}×{} image needs {}",
            image.rgb.len(),
            image.width,
            image.height,
            pixels.saturating_mul(3)
        )));
    }
    Ok(())
}

fn invalid(message: String) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidInput, message)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectrum::Bands;

    #[test]
    fn channel_names_follow_the_layout() {
        assert_eq!(emissive_channel_name(392.5), "S0.392,5nm");
        assert_eq!(emissive_channel_name(550.0), "S0.550,0nm");
        assert_eq!(emissive_channel_name(392.499_999_999_999_94), "S0.392,5nm");
        assert_eq!(emissive_channel_name(401.234_56), "S0.401,2346nm");
    }

    #[test]
    fn writes_a_file_the_exr_crate_reads_back() {
        let bands = Bands::new(400.0, 700.0, 3).unwrap();
        let image = SpectralImage {
            width: 2,
            height: 1,
            bands,
            data: vec![1.0, 2.0, 3.0, 4.0, 5.0, 6.0],
            rgb: vec![0.1, 0.2, 0.3, 0.4, 0.5, 0.6],
        };
        let path = std::env::temp_dir().join(format!("morgana-exr-{}.exr", std::process::id()));
        write_spectral_exr(&path, &image).unwrap();
        let read = exr::prelude::read_all_flat_layers_from_file(&path).unwrap();
        std::fs::remove_file(&path).unwrap();
        let layer = &read.layer_data[0];
        let get = |name: &str| -> Vec<f32> {
            let ch =
                layer.channel_data.list.iter().find(|c| c.name == *name).unwrap_or_else(|| panic!("no channel {name}"));
            ch.sample_data.values_as_f32().collect()
        };
        assert_eq!(get("S0.450,0nm"), vec![1.0, 4.0]);
        assert_eq!(get("S0.550,0nm"), vec![2.0, 5.0]);
        assert_eq!(get("S0.650,0nm"), vec![3.0, 6.0]);
        assert_eq!(get("G"), vec![0.2, 0.5]);
        let other = &layer.attributes.other;
        assert_eq!(layer.attributes.white_luminance, Some(1.0));
        assert_eq!(other.get(&Text::from("spectralLayoutVersion")), Some(&AttributeValue::Text(Text::from("1.0"))));
        assert_eq!(other.get(&Text::from("emissiveUnits")), Some(&AttributeValue::Text(Text::from("W.m^-2.sr^-1"))));
        assert_eq!(other.get(&Text::from(BAND_MAX_ATTRIBUTE)), Some(&AttributeValue::F64(700.0)));
    }

    #[test]
    fn rejects_mismatched_buffers() {
        let image = SpectralImage {
            width: 2,
            height: 2,
            bands: Bands::new(400.0, 700.0, 3).unwrap(),
            data: vec![0.0; 11],
            rgb: vec![0.0; 12],
        };
        let err = write_spectral_exr(Path::new("/nonexistent/x.exr"), &image).unwrap_err();
        assert_eq!(err.kind(), io::ErrorKind::InvalidInput);
        assert!(err.to_string().contains("needs 12"), "{err}");
    }
}
