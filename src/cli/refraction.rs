//! `morgana refraction`: astronomical refraction through an atmosphere, as a table, a CSV, a
//! dispersion line or the flattened sun (the work is [`crate::atmosphere::refraction`]); without
//! `--atmosphere`, through the model atmosphere of the observer's conditions, by quadrature of
//! the refraction integral or by the ray trace. With `--ground-distances-km`, terrestrial
//! refraction: where the rays are at those distances along the ground.

use crate::atmosphere::dispersion::Ciddor;
use crate::atmosphere::refraction::model::{
    MODEL_EARTH_RADIUS_M, ModelAtmosphere, Observer, Refractivity, TOP_M, TROPOPAUSE_M,
};
use crate::atmosphere::refraction::model_table::{ModelMethod, model_table};
use crate::atmosphere::refraction::refractor::{Method, Refractor};
use crate::atmosphere::refraction::report::{dispersion, sun_text, table};
use crate::atmosphere::refraction::terrestrial::{RadialAir, RadialIndex, radial_air};
use crate::atmosphere::refraction::terrestrial_table::{sight_table, terrestrial_table};
use crate::atmosphere::refraction::{Settings, Tracer};
use crate::error::{Error, Result};
use std::path::PathBuf;

/// How the refraction is computed in the model atmosphere.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum MethodArg {
    /// Adaptive quadrature of the refraction integral over the zenith distance.
    Quadrature,
    /// The ray trace through the same model (the quadrature's oracle).
    Trace,
}

/// The refractivity law of the model atmosphere.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum RefractivityArg {
    /// Ciddor 1996, moist air, 450 µmol/mol CO₂.
    Ciddor,
    /// The optical formula of SLALIB slaRefro (IAG 1999 dry air, Hohenkerk & Sinclair water term).
    HohenkerkSinclair,
}

/// `morgana refraction --atmosphere usa76 --wavelength-nm 550 --apparent-altitudes-deg 0,1,45`.
#[derive(clap::Args, Clone, Debug)]
pub struct RefractionArgs {
    /// An atmosphere file (TOML, see atmospheres/README.md) or a built-in name: usa76, hot_road,
    /// inversion, fata_morgana, tropical. Without it: the model atmosphere of the observer's
    /// conditions (--pressure-hpa, --temperature-c, --humidity, --latitude-deg,
    /// --lapse-rate-k-per-m).
    #[arg(long)]
    pub atmosphere: Option<String>,
    /// Model atmosphere: air pressure at the observer, hPa [default: 1013.25].
    #[arg(long, conflicts_with = "atmosphere")]
    pub pressure_hpa: Option<f64>,
    /// Model atmosphere: air temperature at the observer, °C [default: 15].
    #[arg(long, conflicts_with = "atmosphere", allow_negative_numbers = true)]
    pub temperature_c: Option<f64>,
    /// Model atmosphere: relative humidity at the observer, 0–1 [default: 0].
    #[arg(long, conflicts_with = "atmosphere")]
    pub humidity: Option<f64>,
    /// Model atmosphere: the observer's latitude (gravity), degrees [default: 45].
    #[arg(long, conflicts_with = "atmosphere", allow_negative_numbers = true)]
    pub latitude_deg: Option<f64>,
    /// Model atmosphere: tropospheric lapse rate −dT/dh, K/m (0.001–0.01) [default: 0.0065].
    #[arg(long, conflicts_with = "atmosphere")]
    pub lapse_rate_k_per_m: Option<f64>,
    /// Model atmosphere: the refractivity law.
    #[arg(long, value_enum, conflicts_with = "atmosphere", default_value_t = RefractivityArg::Ciddor)]
    pub refractivity: RefractivityArg,
    /// Quadrature of the refraction integral or the ray trace [default: quadrature; with
    /// --atmosphere that is Bouguer's invariant through the file's air, rays it does not follow
    /// (into the ground, ducted) traced, and the trace where the air is not spherically
    /// symmetric (a flat Earth, edits along the ground)].
    #[arg(long, value_enum)]
    pub method: Option<MethodArg>,
    /// Model atmosphere: a table over apparent zenith distances FROM,TO,STEP in degrees (0–90),
    /// e.g. 0,90,0.1; replaces --apparent-altitudes-deg.
    #[arg(long, value_delimiter = ',', conflicts_with = "atmosphere")]
    pub zenith_table_deg: Option<Vec<f64>>,
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
    /// Terrestrial refraction instead: where each ray of --apparent-altitudes-deg is at these
    /// distances along the ground (km, comma-separated) — its height, its elevation, and the
    /// straight line's height beside it — by quadrature of Bouguer's invariant (air whose index
    /// depends on height alone; a duct on a ray's path is an error).
    #[arg(long, value_delimiter = ',', allow_negative_numbers = true)]
    pub ground_distances_km: Option<Vec<f64>>,
    /// Lines of sight instead: for each target DISTANCE_KM:HEIGHT_M (comma-separated, e.g.
    /// 50:300,120:1500) the apparent elevation(s) at which it is seen (several in a mirage, none
    /// when hidden), the straight line's elevation, and how high the horizon hides things at
    /// that distance; the header gives the horizon's distance and dip.
    #[arg(long, value_delimiter = ',')]
    pub targets: Option<Vec<String>>,
}

/// Runs the command; the text to print.
pub fn run(args: &RefractionArgs) -> Result<String> {
    if let Some(csv) = &args.csv {
        super::check_output_file("--csv", csv)?;
    }
    if args.ground_distances_km.is_some() || args.targets.is_some() {
        return run_terrestrial(args);
    }
    let Some(atmosphere_name) = &args.atmosphere else { return run_model(args) };
    if args.apparent_altitudes_deg.is_empty() {
        return Err(Error::input(None, "--apparent-altitudes-deg: give at least one altitude"));
    }
    if let Some(a) = args.apparent_altitudes_deg.iter().find(|a| !(a.is_finite() && a.abs() <= 90.0)) {
        return Err(Error::input(None, format!("--apparent-altitudes-deg: {a} is out of range; expected −90 … 90")));
    }
    let atmosphere = crate::atmosphere::resolve(atmosphere_name)?;
    // Each flag's problem is named at its flag: the wavelength first, then the height.
    Tracer::new(&atmosphere, args.wavelength_nm, 0.0, Settings::default()).map_err(|e| e.at_flag("--wavelength-nm"))?;
    let tracer = Tracer::new(&atmosphere, args.wavelength_nm, args.observer_height_m, Settings::default())
        .map_err(|e| e.at_flag("--observer-height-m"))?;
    let method = args.method.map(|m| match m {
        MethodArg::Quadrature => Method::Quadrature,
        MethodArg::Trace => Method::Trace,
    });
    let refractor = Refractor::new(tracer, method)
        .map_err(|e| Error::input(None, format!("--method quadrature: {e}; use --method trace")))?;
    let t = table(&refractor, &args.apparent_altitudes_deg)?;
    let mut out = t.to_text();
    if let Some(ls) = args.wavelengths_nm.as_deref().filter(|l| !l.is_empty()) {
        for &l in ls {
            refractor.at_wavelength(l).map_err(|e| e.at_flag("--wavelengths-nm"))?;
        }
        out.push_str(&dispersion(&refractor, &args.apparent_altitudes_deg, ls)?.to_text());
    }
    out.push_str(&sun_text(&refractor)?);
    if let Some(path) = &args.csv {
        t.write_csv(path)?;
        out.push_str(&format!("wrote {}\n", path.display()));
    }
    Ok(out)
}

/// The terrestrial table (`--ground-distances-km`), through `--atmosphere` or the model.
fn run_terrestrial(args: &RefractionArgs) -> Result<String> {
    let mode = if args.targets.is_some() { "--targets" } else { "--ground-distances-km" };
    let refuse = |flag: &str| Err(Error::input(None, format!("{flag} is not used with {mode}; drop it")));
    if args.targets.is_some() && args.ground_distances_km.is_some() {
        return refuse("--ground-distances-km");
    }
    if args.wavelengths_nm.is_some() {
        return refuse("--wavelengths-nm");
    }
    if args.zenith_table_deg.is_some() {
        return refuse("--zenith-table-deg");
    }
    if args.method == Some(MethodArg::Trace) {
        return refuse("--method trace");
    }
    if let Some(name) = &args.atmosphere {
        let atmosphere = crate::atmosphere::resolve(name)?;
        let air = radial_air(&atmosphere, args.wavelength_nm)
            .map_err(|e| Error::input(None, format!("--atmosphere {name}: {e}")))?;
        let title = format!("atmosphere \"{}\", {} nm", atmosphere.name, args.wavelength_nm);
        return terrestrial_report(args, &air, title);
    }
    let model = model_atmosphere(args)?;
    let air = RadialAir {
        refractivity: model,
        kink_heights_m: vec![TROPOPAUSE_M],
        ground_radius_m: MODEL_EARTH_RADIUS_M,
        top_m: TOP_M,
    };
    let o = &model.observer;
    let title = format!(
        "model atmosphere of Hohenkerk & Sinclair, {} nm, {} hPa, {:.2} °C, relative humidity {}, lapse rate {} K/m at the observer",
        o.wavelength_nm,
        o.pressure_hpa,
        o.temperature_k - 273.15,
        o.humidity,
        o.lapse_k_per_m
    );
    terrestrial_report(args, &air, title)
}

/// The rays' table (`--ground-distances-km`) or the targets' (`--targets`) through `air`.
fn terrestrial_report<F: RadialIndex>(args: &RefractionArgs, air: &RadialAir<F>, title: String) -> Result<String> {
    let h0 = args.observer_height_m;
    let (text, written) = if let Some(targets) = &args.targets {
        let targets = parse_targets(targets)?;
        let table = sight_table(air, title, h0, &targets)?;
        (table.to_text(), args.csv.as_ref().map(|p| table.write_csv(p).map(|_| p)))
    } else {
        let distances = args.ground_distances_km.as_deref().unwrap_or_default();
        if distances.is_empty() || args.apparent_altitudes_deg.is_empty() {
            return Err(Error::input(
                None,
                "--ground-distances-km: give at least one distance and one apparent altitude",
            ));
        }
        let table = terrestrial_table(air, title, h0, &args.apparent_altitudes_deg, distances)?;
        (table.to_text(), args.csv.as_ref().map(|p| table.write_csv(p).map(|_| p)))
    };
    let mut out = text;
    if let Some(path) = written.transpose()? {
        out.push_str(&format!("wrote {}\n", path.display()));
    }
    Ok(out)
}

/// `--targets D:H,...` as (distance km, height m) pairs.
fn parse_targets(items: &[String]) -> Result<Vec<(f64, f64)>> {
    let bad = |item: &str, why: &str| {
        Error::input(None, format!("--targets: \"{item}\" {why}; expected DISTANCE_KM:HEIGHT_M, e.g. 50:300"))
    };
    if items.is_empty() {
        return Err(Error::input(None, "--targets: give at least one DISTANCE_KM:HEIGHT_M, e.g. 50:300"));
    }
    items
        .iter()
        .map(|item| {
            let (d, h) = item.split_once(':').ok_or_else(|| bad(item, "has no ':'"))?;
            let num = |v: &str| v.trim().parse::<f64>().ok().filter(|x| x.is_finite());
            match (num(d), num(h)) {
                (Some(d), Some(h)) if d > 0.0 && h >= 0.0 => Ok((d, h)),
                _ => Err(bad(item, "is not a distance > 0 and a height ≥ 0")),
            }
        })
        .collect()
}

/// The model-atmosphere table (no `--atmosphere`).
fn run_model(args: &RefractionArgs) -> Result<String> {
    if args.wavelengths_nm.is_some() {
        return Err(Error::input(None, "--wavelengths-nm needs --atmosphere; run the model table once per wavelength"));
    }
    let model = model_atmosphere(args)?;
    let zeniths = zenith_list(args)?;
    let method = match args.method {
        Some(MethodArg::Quadrature) | None => ModelMethod::Quadrature,
        Some(MethodArg::Trace) => ModelMethod::Trace,
    };
    let t = model_table(&model, &zeniths, method)?;
    let mut out = t.to_text();
    if let Some(path) = &args.csv {
        t.write_csv(path)?;
        out.push_str(&format!("wrote {}\n", path.display()));
    }
    Ok(out)
}

/// The model atmosphere of the observer's conditions (the options, or their defaults).
fn model_atmosphere(args: &RefractionArgs) -> Result<ModelAtmosphere> {
    let d = Observer::default();
    let observer = Observer {
        pressure_hpa: args.pressure_hpa.unwrap_or(d.pressure_hpa),
        temperature_k: args.temperature_c.map_or(d.temperature_k, |t| t + 273.15),
        humidity: args.humidity.unwrap_or(d.humidity),
        height_m: args.observer_height_m,
        latitude_deg: args.latitude_deg.unwrap_or(d.latitude_deg),
        lapse_k_per_m: args.lapse_rate_k_per_m.unwrap_or(d.lapse_k_per_m),
        wavelength_nm: args.wavelength_nm,
    };
    let law = match args.refractivity {
        RefractivityArg::Ciddor => Refractivity::Ciddor(Ciddor::new(450.0).map_err(|e| Error::input(None, e))?),
        RefractivityArg::HohenkerkSinclair => Refractivity::HohenkerkSinclair,
    };
    ModelAtmosphere::new(observer, law).map_err(|e| Error::input(None, e))
}

/// Most rows of a zenith table.
const MAX_TABLE_ROWS: usize = 1_000_000;

/// The zenith distances asked for: the table FROM,TO,STEP, or 90° minus each apparent altitude.
fn zenith_list(args: &RefractionArgs) -> Result<Vec<f64>> {
    let bad = |m: String| Error::input(None, format!("--zenith-table-deg: {m}"));
    let Some(t) = args.zenith_table_deg.as_deref() else {
        return args
            .apparent_altitudes_deg
            .iter()
            .map(|a| {
                if (0.0..=90.0).contains(a) {
                    Ok(90.0 - a)
                } else {
                    Err(Error::input(None, format!("--apparent-altitudes-deg: {a} is out of range for the model atmosphere; expected 0 … 90 (use --atmosphere for rays below the horizon)")))
                }
            })
            .collect();
    };
    let &[from, to, step] = t else {
        return Err(bad(format!("give FROM,TO,STEP (three numbers, degrees); got {} numbers", t.len())));
    };
    if !(0.0..=90.0).contains(&from) || !(0.0..=90.0).contains(&to) || from > to {
        return Err(bad(format!("{from},{to} is out of range; expected 0 ≤ FROM ≤ TO ≤ 90")));
    }
    if !(step.is_finite() && step > 0.0) || (to - from) / step > MAX_TABLE_ROWS as f64 {
        return Err(bad(format!("step {step} must be positive and give at most {MAX_TABLE_ROWS} rows")));
    }
    let n = ((to - from) / step + 1e-9).floor() as usize;
    Ok((0..=n).map(|i| ((from + i as f64 * step) * 1e9).round() / 1e9).collect())
}
