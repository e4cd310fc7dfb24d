//! `morgana refraction`: astronomical refraction through an atmosphere, as a table, a CSV, a
//! dispersion line or the flattened sun (the work is [`crate::atmosphere::refraction`]).

use crate::atmosphere::refraction::report::{dispersion, sun_text, table};
use crate::atmosphere::refraction::{Settings, Tracer};
use crate::error::{Error, Result};
use std::path::PathBuf;

/// `morgana refraction --atmosphere usa76 --wavelength-nm 550 --apparent-altitudes-deg 0,1,45`.
#[derive(clap::Args, Clone, Debug)]
pub struct RefractionArgs {
    /// An atmosphere file (TOML, see atmospheres/README.md) or a built-in name: usa76, hot_road,
    /// inversion, fata_morgana, tropical.
    #[arg(long)]
    pub atmosphere: String,
    /// Wavelength of the table, nm.
    #[arg(long, default_value_t = 550.0)]
    pub wavelength_nm: f64,
    /// Apparent altitudes, degrees (comma-separated; negative ones look below the astronomical
    /// horizon).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true, default_value = "0,0.5,1,2,5,10,45")]
    pub apparent_altitudes_deg: Vec<f64>,
    /// Observer's height above the ground, m.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub observer_height_m: f64,
    /// Write apparent_altitude_deg,true_altitude_deg,refraction_arcsec to this CSV.
    #[arg(long)]
    pub csv: Option<PathBuf>,
    /// Also print the refraction at these wavelengths (nm, comma-separated) and the difference
    /// between the first and the last: the dispersion behind the green rim of the setting sun.
    #[arg(long, value_delimiter = ',')]
    pub wavelengths_nm: Option<Vec<f64>>,
}

/// Runs the command; the text to print.
pub fn run(args: &RefractionArgs) -> Result<String> {
    if let Some(csv) = &args.csv {
        super::check_output_file("--csv", csv)?;
    }
    if args.apparent_altitudes_deg.is_empty() {
        return Err(Error::input(None, "--apparent-altitudes-deg: give at least one altitude"));
    }
    if let Some(a) = args.apparent_altitudes_deg.iter().find(|a| !(a.is_finite() && a.abs() <= 90.0)) {
        return Err(Error::input(None, format!("--apparent-altitudes-deg: {a} is out of range; expected −90 … 90")));
    }
    let atmosphere = crate::atmosphere::resolve(&args.atmosphere)?;
    // Each flag's problem is named at its flag: the wavelength first, then the height.
    Tracer::new(&atmosphere, args.wavelength_nm, 0.0, Settings::default()).map_err(|e| e.at_flag("--wavelength-nm"))?;
    let tracer = Tracer::new(&atmosphere, args.wavelength_nm, args.observer_height_m, Settings::default())
        .map_err(|e| e.at_flag("--observer-height-m"))?;
    let t = table(&tracer, &args.apparent_altitudes_deg)?;
    let mut out = t.to_text();
    if let Some(ls) = args.wavelengths_nm.as_deref().filter(|l| !l.is_empty()) {
        for &l in ls {
            tracer.at_wavelength(l).map_err(|e| e.at_flag("--wavelengths-nm"))?;
        }
        out.push_str(&dispersion(&tracer, &args.apparent_altitudes_deg, ls)?.to_text());
    }
    out.push_str(&sun_text(&tracer)?);
    if let Some(path) = &args.csv {
        t.write_csv(path)?;
        out.push_str(&format!("wrote {}\n", path.display()));
    }
    Ok(out)
}
