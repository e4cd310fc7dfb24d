//! The `morgana` command line: parses arguments, runs the command (`morgana::cli`), prints what
//! it returns and turns errors into exit codes: 0 success, 2 bad input, 1 internal failure.

use clap::{Parser, Subcommand};
use morgana::cli;
use std::io::Write;

#[derive(Parser)]
#[command(name = "morgana", version, about = "Spectral light transport through media that bend and re-colour light")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Render a scene (the embedded default scene when SCENE is omitted) into --out.
    Render(cli::render::RenderArgs),
    /// Write a density grid (.mgrid) of procedural fBm turbulence, for
    /// `density = { type = "grid", file = ... }`.
    Grid(cli::grid::GridArgs),
    /// Tone-map a spectral (or RGB) EXR into an sRGB PNG as an eye would see it.
    Tonemap(cli::tonemap::TonemapArgs),
    /// Validate a scene and print what will be simulated and why.
    Check(cli::check::CheckArgs),
    /// Read a luminaire photometry file (IES LM-63, EULUMDAT, IES TM-33, GLDF) and print what it
    /// says: format, flux, symmetry, spectrum, peak, beam and field angles; optionally draw its
    /// polar curves.
    Luminaire(cli::luminaire::LuminaireArgs),
    /// Ray-integrator accuracy and speed against the closed-form ray in n = 1 + k*y: Dormand-Prince
    /// over tolerances, Euler and RK4 over step sizes (Gutierrez et al. 2005, Fig. 1, extended).
    Accuracy(cli::accuracy::AccuracyArgs),
    /// Astronomical refraction: trace rays from an observer out of an atmosphere and print the
    /// true altitude and refraction for each apparent altitude.
    Refraction(cli::refraction::RefractionArgs),
    /// Follow one ray through a scene's media (curved where their index fields bend it) without
    /// scattering: each surface, boundary and the escape, with path length and direction.
    Trace(cli::trace::TraceArgs),
}

fn main() {
    let result = match Cli::parse().command {
        Command::Render(args) => cli::render::run(&args),
        Command::Grid(args) => cli::grid::run(&args),
        Command::Tonemap(args) => cli::tonemap::run_args(&args),
        Command::Check(args) => cli::check::run(&args),
        Command::Luminaire(args) => cli::luminaire::run(&args),
        Command::Accuracy(args) => cli::accuracy::run(&args),
        Command::Refraction(args) => cli::refraction::run(&args),
        Command::Trace(args) => cli::trace::run(&args),
    };
    match result {
        Ok(text) => {
            // A closed pipe or a full disk is reported, not a panic (print! would panic).
            let mut out = std::io::stdout().lock();
            if let Err(e) = out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
                eprintln!("morgana: cannot write to standard output: {e}");
                std::process::exit(1);
            }
        }
        Err(e) => {
            eprintln!("morgana: {e}");
            std::process::exit(e.exit_code());
        }
    }
}
