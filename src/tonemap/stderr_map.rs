//! The relative standard error of a progressive render as a false-colour map
//! (`morgana tonemap --stderr`).
//!
//! A render of several passes writes, beside each emissive channel `S0.<λ>nm`, the standard
//! error of its value as `stderr.S0.<λ>nm` ([`crate::spectrum::exr::STDERR_LAYER`]). A pixel's
//! relative error is that of a typical band: the RMS of its bands' standard errors over the mean
//! of its band values,
//!
//! e = √(Σ_b SE_b² / n) / (Σ_b L_b / n),
//!
//! undefined (drawn black) where the pixel is black. It is drawn on a logarithmic scale of whole
//! decades with the false-colour renderer of [`crate::raster::false_colour`].

use super::exr_read::parse_emissive_wavelength_nm;
use crate::spectrum::exr::STDERR_LAYER;
use std::path::Path;

/// Per-pixel relative standard errors, row-major, and the image's width and height.
pub struct RelativeError {
    /// Width, pixels.
    pub width: usize,
    /// Height, pixels.
    pub height: usize,
    /// e per pixel (NaN where the pixel is black).
    pub values: Vec<f64>,
}

/// Reads the emissive and standard-error channels of `path` and returns e per pixel; errors
/// say what the file lacks.
pub fn read_relative_error(path: &Path) -> Result<RelativeError, String> {
    let image = exr::prelude::read_all_flat_layers_from_file(path).map_err(|e| match e {
        exr::error::Error::Io(io) => format!("cannot read it: {io}"),
        other => format!("not a readable OpenEXR file ({other}); give an EXR written by morgana render"),
    })?;
    let prefix = format!("{STDERR_LAYER}.");
    for layer in &image.layer_data {
        let names: Vec<String> = layer.channel_data.list.iter().map(|c| c.name.to_string()).collect();
        let index = |n: &str| names.iter().position(|x| x == n);
        let pairs: Vec<(usize, usize)> = names
            .iter()
            .enumerate()
            .filter(|(_, n)| parse_emissive_wavelength_nm(n).is_some())
            .filter_map(|(i, n)| index(&format!("{prefix}{n}")).map(|j| (i, j)))
            .collect();
        if pairs.is_empty() {
            continue;
        }
        let (w, h) = (layer.size.0, layer.size.1);
        let values_of = |c: usize| -> Vec<f32> { layer.channel_data.list[c].sample_data.values_as_f32().collect() };
        let mut sum = vec![0.0f64; w * h];
        let mut sq = vec![0.0f64; w * h];
        for (i, j) in &pairs {
            for (p, (v, e)) in values_of(*i).into_iter().zip(values_of(*j)).enumerate().take(w * h) {
                sum[p] += f64::from(v);
                sq[p] += f64::from(e) * f64::from(e);
            }
        }
        // √(Σ SE²/n)/(Σ L/n) = √n · √(Σ SE²)/Σ L.
        let root_n = (pairs.len() as f64).sqrt();
        let values =
            sum.iter().zip(&sq).map(|(s, q)| if *s > 0.0 { root_n * q.sqrt() / s } else { f64::NAN }).collect();
        return Ok(RelativeError { width: w, height: h, values });
    }
    Err(format!(
        "it has no standard-error channels ({prefix}S0.<wavelength>nm): render with several passes (--passes 2 or more, --time or --target-rel-error) to get them"
    ))
}
