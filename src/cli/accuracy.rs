//! `morgana accuracy`: the ray integrators' accuracy and speed against a closed-form ray
//! (Gutierrez et al. 2005, Fig. 1, extended; the study is [`crate::ode::accuracy`]).

use crate::error::{Error, Result};
use crate::ode::accuracy::{Plan, Problem, measure, plot, summary, write_atomically, write_csv};
use std::fmt::Write as _;
use std::path::PathBuf;

/// The command line of `morgana accuracy`.
/// The command line of `morgana accuracy` (parsed by clap in `main`).
#[derive(clap::Args, Clone, Debug)]
pub struct AccuracyArgs {
    /// Index field: "linear" (n = 1 + k·y, the paper's test field; the only one with a closed form here).
    #[arg(long, default_value = "linear")]
    pub field: String,
    /// Gradient k of n = 1 + k·y, m⁻¹ (nonzero; the paper uses −0.1…0.1).
    #[arg(long, default_value_t = 1e-3, allow_hyphen_values = true)]
    pub k: f64,
    /// Arc length of the test ray, m.
    #[arg(long, default_value_t = 1000.0, allow_hyphen_values = true)]
    pub length_m: f64,
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
    if args.field != "linear" {
        return Err(Error::input(
            None,
            format!("--field: found \"{}\"; expected \"linear\" (n = 1 + k*y)", args.field),
        ));
    }
    let problem = Problem::new(args.k, args.length_m)?;
    let mut plan = if args.quick { Plan::quick(&problem) } else { Plan::standard(&problem) };
    plan.project = args.project;
    let report = measure(&problem, &plan);
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
