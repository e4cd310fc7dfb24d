//! `morgana grid`: writes a density grid (`.mgrid`, documented in `media::density::grid`) of
//! procedural fBm turbulence, for `density = { type = "grid", file = ... }`.

use super::parse_vec3;
use crate::error::{Error, Result};
use crate::media::density::{Fbm, write_grid_atomically};
use std::path::PathBuf;

/// The command line of `morgana grid`.
#[derive(clap::Args, Clone, Debug)]
pub struct GridArgs {
    /// Output file.
    #[arg(long)]
    pub out: PathBuf,
    /// Lattice points per axis (2 to 1024).
    #[arg(long, default_value_t = 64)]
    pub res: usize,
    /// Box corner, metres: x,y,z.
    #[arg(long, value_parser = parse_vec3, default_value = "-1,-1,-1", allow_hyphen_values = true)]
    pub min: [f64; 3],
    /// Opposite box corner, metres: x,y,z.
    #[arg(long, value_parser = parse_vec3, default_value = "1,1,1", allow_hyphen_values = true)]
    pub max: [f64; 3],
    /// Mean density.
    #[arg(long, default_value_t = 0.5, allow_hyphen_values = true)]
    pub base: f64,
    /// Amplitude of the turbulence around the mean.
    #[arg(long, default_value_t = 0.5, allow_hyphen_values = true)]
    pub amplitude: f64,
    /// Frequency of the first octave, per metre.
    #[arg(long, default_value_t = 2.0)]
    pub frequency_per_m: f64,
    /// Octaves of noise summed (1 to 24).
    #[arg(long, default_value_t = 5)]
    pub octaves: u32,
    /// Seed of the noise.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
}

/// The most octaves `--octaves` may ask for: with lacunarity 2 the 24th has 2²³ times the first
/// one's frequency, far finer than a 1024-point lattice resolves.
pub const MAX_OCTAVES: u32 = 24;

/// Writes the grid and returns the line to print.
pub fn run(a: &GridArgs) -> Result<String> {
    if !(1..=MAX_OCTAVES).contains(&a.octaves) {
        return Err(Error::input(None, format!("--octaves {}: expected 1 to {MAX_OCTAVES}", a.octaves)));
    }
    for (flag, v) in [("--base", a.base), ("--amplitude", a.amplitude)] {
        if !v.is_finite() {
            return Err(Error::input(None, format!("{flag} {v}: expected a finite number")));
        }
    }
    if !(a.frequency_per_m.is_finite() && a.frequency_per_m > 0.0) {
        let f = a.frequency_per_m;
        return Err(Error::input(
            None,
            format!("--frequency-per-m {f}: expected a positive finite frequency, per metre"),
        ));
    }
    if (0..3).any(|i| a.max[i] <= a.min[i]) {
        let (min, max) = (a.min, a.max);
        return Err(Error::input(None, format!("--min {min:?}, --max {max:?}: max must exceed min on every axis")));
    }
    if !(2..=1024).contains(&a.res) {
        return Err(Error::input(None, format!("--res {}: the grid needs 2 to 1024 points per axis", a.res)));
    }
    if !(a.base.abs() + a.amplitude.abs()).is_finite() {
        return Err(Error::input(None, format!("--base {}, --amplitude {}: their sum overflows", a.base, a.amplitude)));
    }
    super::check_output_file("--out", &a.out)?;
    let fbm = Fbm::new(a.base, a.amplitude, a.frequency_per_m, a.octaves, a.seed);
    // A density below zero comes from --base and --amplitude: name them.
    write_grid_atomically(&a.out, [a.res; 3], a.min.into(), a.max.into(), |p| fbm.at(p))
        .map_err(|e| e.at_flag("--base, --amplitude"))?;
    Ok(format!("wrote {}\n", a.out.display()))
}
