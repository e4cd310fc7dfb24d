//! Tone reproduction and chromatic adaptation: from spectral radiance to what an eye sees.
//!
//! A rendered spectral image (or a spectral or RGB EXR) becomes an 8-bit sRGB picture in five
//! steps, each in its own module:
//!
//! 1. **Colorimetry** ([`SceneImage`]): absolute XYZ (Y in cd m⁻²) and the scotopic luminance
//!    L′ from the CIE 1951 V′(λ), both integrated over the spectral bands.
//! 2. **Chromatic adaptation** ([`chromatic`], [`white`]): von Kries scaling (von Kries LMS,
//!    Bradford or CAT16) from the scene white — given, or estimated from the image — to the
//!    display's D65 white.
//! 3. **Rod vision** ([`acuity`], [`mesopic`]; `scotopic = auto | on`): loss of acuity in dim
//!    light by a luminance-dependent blur, and loss of colour through the mesopic range
//!    (the Pattanaik operator models rods itself and skips the mesopic blend).
//! 4. **Tone reproduction**: one operator maps luminance to display luminance, y ∈ [0, 1]
//!    (1 = display white): [`exposure`], [`reinhard`] (Reinhard et al. 2002),
//!    [`ward_histogram`] (Ward Larson et al. 1997), [`pattanaik`] (Pattanaik et al. 2000).
//!    Every pixel keeps its chromaticity: XYZ_d = y · XYZ / Y; the share of the response that
//!    comes from rods (Pattanaik) is shown as a grey.
//! 5. **Display**: XYZ_d → linear sRGB, clipped to [0, 1], sRGB transfer function, 8 bits.
//!
//! Or, instead of 2–5, **false colour** ([`crate::raster::false_colour`]): luminance on a log scale with a
//! legend. [`region`] exports luminance and illuminance of a pixel rectangle as CSV.
//!
//! `morgana tonemap IN.exr --out OUT.png [options]` runs this on a file (`crate::cli::tonemap`); `render` runs
//! it on its own image when `[output]` asks for it ([`write_png`]).

pub mod acuity;
pub mod blur;
pub mod chromatic;
pub mod cie_scotopic_data;
pub mod delta_e;
pub mod exposure;
pub mod exr_read;
pub mod foveal;
pub mod matrix;
pub mod mesopic;
pub mod pattanaik;
pub mod preview;
pub mod region;
pub mod reinhard;
pub mod scene_image;
pub mod scotopic;
pub mod settings;
pub mod spectral_weights;
pub mod stderr_map;
pub mod threshold;
pub mod ward_histogram;
pub mod white;

pub use preview::Exposure;
pub use scene_image::SceneImage;
pub use settings::{Operator, ToneOptions, ToneSettings};

use crate::spectrum::SpectralImage;
use crate::spectrum::colour::{srgb_encode, xyz_to_linear_srgb};
use chromatic::adaptation_matrix;
use foveal::FovealImage;
use matrix::{mul_vec, xy_to_xyz, xyz_to_xy};
use mesopic::ScotopicMode;
use pattanaik::{AdaptationState, PattanaikCurve, Receptors};
use scotopic::SCOTOPIC_PER_PHOTOPIC_WHITE;
use white::DISPLAY_WHITE_XY;

/// An operator's verdict on one pixel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Display {
    /// Display luminance relative to the display white (1 = white; more clips).
    pub y: f64,
    /// The share of the response due to rods, shown achromatic.
    pub rod_fraction: f64,
}

/// A prepared tone-reproduction operator: a map from a pixel's photopic luminance and its
/// photopic-equivalent rod luminance L′/2.26 (both cd m⁻²) to display luminance.
pub trait ToneCurve {
    /// Display luminance of a pixel of photopic luminance `luminance` and rod luminance `rod` (cd
    /// m⁻²).
    fn display(&self, luminance: f64, rod: f64) -> Display;
}

/// An 8-bit sRGB picture and what was done to make it.
#[derive(Clone, Debug)]
pub struct ToneOutput {
    /// Width, pixels.
    pub width: usize,
    /// Height, pixels.
    pub height: usize,
    /// Row-major, 3 bytes per pixel, sRGB-encoded.
    pub rgb: Vec<u8>,
    /// One line per step, for the user.
    pub notes: Vec<String>,
}

/// Tone-maps `input` with `settings`.
pub fn tonemap(input: &SceneImage, settings: &ToneSettings) -> ToneOutput {
    if settings.false_colour {
        let lum = input.luminances();
        return false_colour(&lum, input.width, input.height);
    }
    let mut img = input.clone();
    let mut notes = Vec::new();
    notes.extend(adapt_colour(&mut img, settings));
    simulate_rods(&mut img, settings, &mut notes);
    let luminance = img.luminances();
    let rod: Vec<f64> = img.scotopic.iter().map(|s| s / SCOTOPIC_PER_PHOTOPIC_WHITE).collect();
    let curve = prepare(&img, &luminance, &rod, settings, &mut notes);
    let rgb = encode(&img, &luminance, &rod, curve.as_ref());
    ToneOutput { width: img.width, height: img.height, rgb, notes }
}

/// Luminance in cd m⁻² as a meter would read it (before any adaptation or tone mapping), on a
/// logarithmic scale of whole decades with the luminance ramp and a legend
/// ([`crate::raster::false_colour`]).
fn false_colour(lum: &[f64], width: usize, height: usize) -> ToneOutput {
    false_colour_of(lum, (width, height), "luminance", "cd/m2")
}

/// The relative standard error per pixel ([`stderr_map`]) in false colour, on a logarithmic
/// scale of whole decades with a legend.
pub fn relative_error_false_colour(e: &stderr_map::RelativeError) -> ToneOutput {
    false_colour_of(&e.values, (e.width, e.height), "relative standard error", "rel. SE")
}

/// `values` (row-major, `width × height`) in false colour on a log scale with a legend;
/// `what` and `unit` name them in the note and on the colour bar.
fn false_colour_of(values: &[f64], (width, height): (usize, usize), what: &str, unit: &str) -> ToneOutput {
    use crate::raster::false_colour::{ColourMap, Grid, Look, Rows, Scale, draw};
    let scale = Scale::log_decades_for(values);
    let grid = Grid { nx: width, ny: height, values, rows: Rows::Downward };
    let look = Look {
        scale,
        map: ColourMap::Ramp,
        unit,
        heading: None,
        cell: 1,
        background: crate::raster::BLACK,
        text: crate::raster::WHITE,
        text_scale: if height >= 160 { 2 } else { 1 },
    };
    let canvas = draw(&grid, &look);
    let note = match scale {
        Scale::LogDecades { lo, hi } => format!("false colour: {what} 10^{lo} to 10^{hi} {unit}, log scale"),
        Scale::Linear { top } => format!("false colour: {what} 0 to {top} {unit}"),
    };
    ToneOutput { width: canvas.width, height: canvas.height, rgb: canvas.pixels.concat(), notes: vec![note] }
}

/// Step 2: chromatic adaptation of `img` from its scene white to the display white, as
/// `s.adapt_to`, `s.cat` and `s.adaptation_degree` say; returns a note on what was done.
pub fn adapt_colour(img: &mut SceneImage, s: &ToneSettings) -> Option<String> {
    if s.adapt_to == white::AdaptTo::None {
        return None;
    }
    let Some(w) = s.adapt_to.white(img) else {
        return Some(format!("chromatic adaptation skipped: no scene white from {}", s.adapt_to.describe()));
    };
    let target = xy_to_xyz(DISPLAY_WHITE_XY);
    let Some(m) = adaptation_matrix(s.cat, w, target, s.adaptation_degree) else {
        return Some(format!("chromatic adaptation skipped: the scene white {w:?} has no usable cone response"));
    };
    for c in img.xyz.iter_mut() {
        *c = mul_vec(&m, *c);
    }
    let xy = xyz_to_xy(w).unwrap_or([0.0; 2]);
    Some(format!(
        "chromatic adaptation: scene white x,y = {:.4},{:.4} ({}) to D65 by {}, degree {}",
        xy[0],
        xy[1],
        s.adapt_to.describe(),
        s.cat.name(),
        s.adaptation_degree
    ))
}

/// Step 3: acuity loss and, except for Pattanaik, the mesopic colour loss.
fn simulate_rods(img: &mut SceneImage, s: &ToneSettings, notes: &mut Vec<String>) {
    if s.scotopic == ScotopicMode::Off {
        return;
    }
    let deg_per_pixel = (2.0 * (0.5 * s.fov_deg).to_radians().tan() / img.height as f64).to_degrees();
    let sigma = acuity::apply_acuity(img, &FovealImage::new(img, s.fov_deg), deg_per_pixel);
    notes
        .push(format!("acuity: blur up to σ = {sigma:.2} px ({:.3}°/px, field of view {}°)", deg_per_pixel, s.fov_deg));
    if s.operator != Operator::Pattanaik {
        mesopic::apply_mesopic(img, s.scotopic);
        notes.push(format!("rod vision: {} (mesopic range 0.00562–5.62 cd/m2)", s.scotopic.name()));
    }
    if img.scotopic_source == scene_image::ScotopicSource::EstimatedFromXyz {
        notes.push("scotopic luminance estimated from XYZ: the input has no spectral channels".into());
    }
}

/// Step 4: the operator, prepared for this image.
fn prepare(
    img: &SceneImage,
    luminance: &[f64],
    rod: &[f64],
    s: &ToneSettings,
    notes: &mut Vec<String>,
) -> Box<dyn ToneCurve> {
    match s.operator {
        Operator::Exposure(e) => {
            let c = exposure::ExposureCurve::new(e, luminance);
            notes.push(format!("exposure: display white at {:.4e} cd/m2", 1.0 / c.scale));
            Box::new(c)
        }
        Operator::Reinhard => {
            let c = reinhard::ReinhardCurve::new(luminance);
            notes.push(format!("reinhard: key 0.18 at log-average {:.4e} cd/m2", reinhard::KEY / c.scale));
            Box::new(c)
        }
        Operator::WardHistogram => {
            let c = ward_histogram::WardHistogram::default().curve(&FovealImage::new(img, s.fov_deg), luminance);
            let kind = match c.mapping {
                ward_histogram::WardMapping::Linear { .. } => "linear (the scene fits the display range)",
                ward_histogram::WardMapping::Adjusted { .. } => "histogram adjustment, human contrast ceiling",
            };
            notes.push(format!("ward_histogram: {kind}"));
            Box::new(c)
        }
        Operator::Pattanaik => Box::new(pattanaik_curve(luminance, rod, s, notes)),
    }
}

fn pattanaik_curve(luminance: &[f64], rod: &[f64], s: &ToneSettings, notes: &mut Vec<String>) -> PattanaikCurve {
    let g_cone = reinhard::log_average(luminance).unwrap_or(1e-6);
    let g_rod = reinhard::log_average(rod).unwrap_or(1e-6);
    let state = match s.time {
        None => AdaptationState::steady(g_cone, g_rod),
        Some(t) => AdaptationState::steady(t.from_cd_m2, t.from_cd_m2).advance(g_cone, g_rod, t.time_s),
    };
    let receptors = Receptors { cones: s.scotopic != ScotopicMode::On, rods: s.scotopic != ScotopicMode::Off };
    let when = match s.time {
        None => "fully adapted".to_string(),
        Some(t) => format!("{} s after leaving {} cd/m2", t.time_s, t.from_cd_m2),
    };
    notes.push(format!(
        "pattanaik: {when}; image log-average {g_cone:.4e} cd/m2 (rods {g_rod:.4e}); eye at cones {:.4e}, rods {:.4e} cd/m2, unbleached {:.3}/{:.3}",
        state.cone_cd_m2, state.rod_cd_m2, state.cone_pigment, state.rod_pigment
    ));
    PattanaikCurve::new(&state, receptors)
}

/// Step 5: display colours, 8-bit sRGB.
fn encode(img: &SceneImage, luminance: &[f64], rod: &[f64], curve: &dyn ToneCurve) -> Vec<u8> {
    let white = xy_to_xyz(DISPLAY_WHITE_XY);
    let mut out = Vec::with_capacity(3 * luminance.len());
    for (i, c) in img.xyz.iter().enumerate() {
        let y = luminance[i];
        let d = curve.display(y, rod[i]);
        let chroma = if y > 0.0 { c.map(|v| v / y) } else { white };
        let xyz = [0, 1, 2].map(|k| d.y * ((1.0 - d.rod_fraction) * chroma[k] + d.rod_fraction * white[k]));
        for v in xyz_to_linear_srgb(xyz) {
            let v = if v.is_finite() { v.clamp(0.0, 1.0) } else { 0.0 };
            out.push((255.0 * srgb_encode(v)).round() as u8);
        }
    }
    out
}

/// Writes the PNG of a rendered image with `settings` (not atomically: callers stage the
/// file). Returns the notes of [`tonemap`].
pub fn write_png(
    path: &std::path::Path,
    image: &SpectralImage,
    settings: &ToneSettings,
) -> std::io::Result<Vec<String>> {
    let out = tonemap(&SceneImage::from_spectral(image), settings);
    crate::raster::png::write_rgb8(path, out.width, out.height, &out.rgb)?;
    Ok(out.notes)
}
