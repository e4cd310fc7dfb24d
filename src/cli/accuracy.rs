//! `morgana accuracy`: the ray integrators' accuracy and speed against a closed-form ray
//! (Gutierrez et al. 2005, Fig. 1, extended; the study is [`crate::ode::accuracy`]).

use crate::atmosphere::horizon_ray::HorizonRay;
use crate::error::{Error, Result};
use crate::ode::accuracy::{Plan, Problem, Report, TestRay, measure, plot, summary, write_atomically, write_csv};
use std::fmt::Write as _;
use std::path::PathBuf;

/// The command line of `morgana accuracy` (parsed by clap in `main`).
#[derive(clap::Args, Clone, Debug)]
pub struct AccuracyArgs {
    /// Test ray: "linear" (n = 1 + k·y, the paper's test field, against its closed form) or
    /// "usa76" (a ray near the horizon through USA76 air, against Bouguer's invariant by quadrature).
    #[arg(long, default_value = "linear")]
    pub field: String,
    /// linear: gradient k of n = 1 + k·y, m⁻¹ (nonzero; the paper uses −0.1…0.1) [default: 0.001].
    #[arg(long, allow_hyphen_values = true)]
    pub k: Option<f64>,
    /// Arc length of the test ray, m [default: 1000 for linear, 100000 for usa76].
    #[arg(long, allow_hyphen_values = true)]
    pub length_m: Option<f64>,
    /// usa76: the ray's start height above the ground, m [default: 10].
    #[arg(long, allow_hyphen_values = true)]
    pub height_m: Option<f64>,
    /// usa76: the ray's start elevation above the horizontal, degrees (0.1–10) [default: 0.5].
    #[arg(long, allow_hyphen_values = true)]
    pub elevation_deg: Option<f64>,
    /// usa76: the wavelength, nm [default: 550].
    #[arg(long, allow_hyphen_values = true)]
    pub wavelength_nm: Option<f64>,
    /// Write the measurements here (columns method,parameter,endpoint_error_m,time_s,steps,rhs_evals).
    #[arg(long)]
    pub csv: Option<PathBuf>,
    /// Write the log-log figure here (PNG).
    #[arg(long)]
    pub png: Option<PathBuf>,
    /// Fewer points and shorter timings (a smoke run).
    #[arg(long)]
    pub quick: bool,
    /// Rescale v to |v| = n(r) after every step (all methods).
    #[arg(long)]
    pub project: bool,
}

/// What `morgana accuracy` does: measures, writes the CSV and PNG when asked, and returns the
/// text to print.
pub fn run(args: &AccuracyArgs) -> Result<String> {
    for (flag, path) in [("--csv", &args.csv), ("--png", &args.png)] {
        if let Some(p) = path {
            super::check_output_file(flag, p)?;
        }
    }
    let report = match args.field.as_str() {
        "linear" => {
            let usa76_only = [
                ("--height-m", args.height_m),
                ("--elevation-deg", args.elevation_deg),
                ("--wavelength-nm", args.wavelength_nm),
            ];
            if let Some((flag, _)) = usa76_only.iter().find(|f| f.1.is_some()) {
                return Err(Error::input(
                    None,
                    format!("{flag}: only with --field usa76 (the linear field has no height or wavelength)"),
                ));
            }
            let problem = Problem::new(args.k.unwrap_or(1e-3), args.length_m.unwrap_or(1000.0))?;
            run_on(&problem, args)
        }
        "usa76" => {
            if args.k.is_some() {
                return Err(Error::input(None, "--k: only with --field linear (n = 1 + k*y)".to_string()));
            }
            let ray = HorizonRay::new(
                args.height_m.unwrap_or(10.0),
                args.elevation_deg.unwrap_or(0.5),
                args.wavelength_nm.unwrap_or(550.0),
                args.length_m.unwrap_or(100_000.0),
            )
            .map_err(|e| Error::input(None, e))?;
            run_on(&ray, args)
        }
        other => {
            return Err(Error::input(
                None,
                format!(
                    "--field: found \"{other}\"; expected \"linear\" (n = 1 + k*y) or \"usa76\" (a ray near the horizon)"
                ),
            ));
        }
    };
    let mut text = summary(&report);
    if let Some(path) = &args.csv {
        write_csv(&report, path)?;
        let _ = writeln!(text, "wrote {}", path.display());
    }
    if let Some(path) = &args.png {
        write_atomically(path, |tmp| plot::figure(&report).write_png(tmp))?;
        let _ = writeln!(text, "wrote {}", path.display());
    }
    Ok(text)
}

/// The measurement of `ray` with the plan the flags ask for.
fn run_on(ray: &impl TestRay, args: &AccuracyArgs) -> Report {
    let mut plan = if args.quick { Plan::quick(ray) } else { Plan::standard(ray) };
    plan.project = args.project;
    measure(ray, &plan)
}
