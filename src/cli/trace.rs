//! `morgana trace SCENE --from x,y,z (--toward x,y,z | --dir x,y,z)`: one ray followed through
//! a scene's media without scattering (see [`crate::raypath::trace`]), printed event by event,
//! with its lowest point and the integrator's work; `--csv` writes the chord points.

use super::parse_vec3;
use crate::atmosphere::Earth;
use crate::atomic::Staged;
use crate::error::{Error, Result};
use crate::raypath::Propagator;
use crate::raypath::trace::{Limits, Traced, csv_text, heading, medium_label, trace, world_earth, xyz};
use crate::scene::{Scene, load_scene_file};
use glam::DVec3;
use std::fmt::Write as _;
use std::path::PathBuf;

/// `morgana trace SCENE --from x,y,z (--toward x,y,z | --dir x,y,z)`.
/// `morgana trace SCENE --from x,y,z (--toward x,y,z | --dir x,y,z)`.
#[derive(clap::Args, Clone, Debug)]
pub struct TraceArgs {
    /// Scene file (TOML).
    pub scene: PathBuf,
    /// Start point, m: x,y,z.
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    pub from: [f64; 3],
    /// A point the ray starts toward, m: x,y,z (or give --dir).
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true, conflicts_with = "dir")]
    pub toward: Option<[f64; 3]>,
    /// Start direction x,y,z (need not be unit length).
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    pub dir: Option<[f64; 3]>,
    /// Wavelength, nm (within the scene's wavelength range).
    #[arg(long, default_value_t = 550.0)]
    pub wavelength_nm: f64,
    /// Write the path's chord points (s_m,x,y,z,dx,dy,dz,n) to this CSV.
    #[arg(long)]
    pub csv: Option<PathBuf>,
    /// Most events to follow (surfaces, boundaries, escape).
    #[arg(long, default_value_t = 32)]
    pub events: usize,
    /// Longest path to follow, m (a ray trapped in a duct would circle the Earth; the world of an
    /// Earth-scale scene reaches ~2·10⁷ m from the camera).
    #[arg(long, default_value_t = 1.0e8)]
    pub max_length_m: f64,
}

/// Runs the command; the text to print.
pub fn run(args: &TraceArgs) -> Result<String> {
    if let Some(csv) = &args.csv {
        super::check_output_file("--csv", csv)?;
    }
    let scene = load_scene_file(&args.scene)?;
    let from = finite_point(args.from, "--from")?;
    let dir = start_direction(args, from)?;
    check_wavelength(&scene, args.wavelength_nm)?;
    if args.events == 0 {
        return Err(Error::input(None, "--events 0: give at least 1 event to follow"));
    }
    if !(args.max_length_m.is_finite() && args.max_length_m > 0.0) {
        return Err(Error::input(
            None,
            format!("--max-length-m {}: expected a positive finite length in metres", args.max_length_m),
        ));
    }
    let staged = match &args.csv {
        Some(p) => Some(Staged::new(p).map_err(|e| Error::input(None, format!("--csv {}: {e}", p.display())))?),
        None => None,
    };
    let limits = Limits { events: args.events, length_m: args.max_length_m };
    let traced = trace(&scene.world, scene.curved(), from, dir, args.wavelength_nm, limits);
    let mut out = header(&scene, from, dir, args.wavelength_nm);
    for l in &traced.lines {
        out.push_str(l);
        out.push('\n');
    }
    let (earth, heights) = world_earth(&scene.world);
    let _ = writeln!(out, "heights are {heights}");
    out.push_str(&summary(&traced, &earth));
    let w = &traced.work;
    let _ = writeln!(
        out,
        "integrator: {} steps accepted, {} rejected, {} samples of n and ∇n, {} chords",
        w.ode_steps, w.ode_rejected, w.rhs_evals, w.chords
    );
    if let (Some(staged), Some(path)) = (staged, &args.csv) {
        let fail = |e: std::io::Error| Error::internal(format!("cannot write {}: {e}", path.display()));
        std::fs::write(&staged.temp, csv_text(&traced.points)).map_err(fail)?;
        staged.commit().map_err(fail)?;
        let _ = writeln!(out, "wrote {} ({} points)", path.display(), traced.points.len());
    }
    Ok(out)
}

fn header(scene: &Scene, from: DVec3, dir: DVec3, wavelength_nm: f64) -> String {
    let m = scene.world.medium_at(from);
    let n = Propagator::new(&scene.world, scene.curved()).n_at(m, wavelength_nm, from);
    format!(
        "trace {}: {wavelength_nm} nm from {} going {} in {} (n = {n:.8}); elevations above the scene's xz-plane\n",
        scene.label(),
        xyz(from),
        heading(dir),
        medium_label(&scene.world, m)
    )
}

/// The lowest point of the path above the ground, and the number of points.
fn summary(t: &Traced, earth: &Earth) -> String {
    let lowest = t.points.iter().map(|p| (earth.height(p.position), p)).min_by(|a, b| a.0.total_cmp(&b.0));
    let Some((h, p)) = lowest else { return String::new() };
    format!("lowest point: height {h:.4} m at s = {:.3} m, {}; {} points\n", p.s_m, xyz(p.position), t.points.len())
}

fn finite_point(v: [f64; 3], flag: &str) -> Result<DVec3> {
    let p = DVec3::from(v);
    if p.is_finite() {
        Ok(p)
    } else {
        Err(Error::input(None, format!("{flag}: found {}, expected three finite numbers", xyz(p))))
    }
}

/// The unit start direction from `--dir` or `--toward`.
fn start_direction(args: &TraceArgs, from: DVec3) -> Result<DVec3> {
    let (d, flag) = match (args.dir, args.toward) {
        (Some(d), None) => (finite_point(d, "--dir")?, "--dir"),
        (None, Some(t)) => (finite_point(t, "--toward")? - from, "--toward"),
        _ => return Err(Error::input(None, "give the start direction: --toward x,y,z or --dir x,y,z (one of them)")),
    };
    let len = d.length();
    if !(len.is_finite() && len > 1e-12 * (1.0 + from.length())) {
        let why = if flag == "--dir" { "a zero direction" } else { "the start point itself" };
        return Err(Error::input(None, format!("{flag}: {why}; expected a direction of non-zero length")));
    }
    Ok(d / len)
}

fn check_wavelength(scene: &Scene, nm: f64) -> Result<()> {
    let (lo, hi) = (scene.bands.min_nm, scene.bands.max_nm);
    if nm.is_finite() && (lo..=hi).contains(&nm) {
        return Ok(());
    }
    Err(Error::input(
        None,
        format!(
            "--wavelength-nm {nm}: expected a wavelength within the scene's range {lo}–{hi} nm (its media are checked there)"
        ),
    ))
}
