//! `morgana grid`: writes a density grid (`.mgrid`, documented in `media::density::grid`) of
//! procedural fBm turbulence, for `density = { type = "grid", file = ... }`.

use super::parse_vec3;
use crate::error::Result;
use crate::media::density::{Fbm, write_grid_atomically};
use std::path::PathBuf;

/// The command line of `morgana grid`.
#[derive(clap::Args, Clone, Debug)]
pub struct GridArgs {
    /// Output file.
    #[arg(long)]
    pub out: PathBuf,
    /// Lattice points per axis.
    #[arg(long, default_value_t = 64)]
    pub res: usize,
    /// Box corner, metres: x,y,z.
    #[arg(long, value_parser = parse_vec3, default_value = "-1,-1,-1")]
    pub min: [f64; 3],
    /// Opposite box corner, metres: x,y,z.
    #[arg(long, value_parser = parse_vec3, default_value = "1,1,1")]
    pub max: [f64; 3],
    /// Mean density.
    #[arg(long, default_value_t = 0.5)]
    pub base: f64,
    /// Amplitude of the turbulence around the mean.
    #[arg(long, default_value_t = 0.5)]
    pub amplitude: f64,
    /// Frequency of the first octave, per metre.
    #[arg(long, default_value_t = 2.0)]
    pub frequency_per_m: f64,
    /// Octaves of noise summed.
    #[arg(long, default_value_t = 5)]
    pub octaves: u32,
    /// Seed of the noise.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
}

/// Writes the grid and returns the line to print.
pub fn run(a: &GridArgs) -> Result<String> {
    let fbm = Fbm::new(a.base, a.amplitude, a.frequency_per_m, a.octaves, a.seed);
    write_grid_atomically(&a.out, [a.res; 3], a.min.into(), a.max.into(), |p| fbm.at(p))?;
    Ok(format!("wrote {}\n", a.out.display()))
}
