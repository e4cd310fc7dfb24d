//! `morgana render [SCENE]`: renders a scene (the embedded default scene when none is given)
//! into `--out`, on one process or on every rank of an MPI job; rank 0 writes the outputs.

use crate::distributed::{self, Comm, MapMemory, Schedule};
use crate::error::{Error, Result};
use crate::render::{MemoryLimit, RenderOptions, render_on};
use std::path::PathBuf;
use std::time::Instant;

/// The command line of `morgana render`.
#[derive(clap::Args, Clone, Debug)]
pub struct RenderArgs {
    /// Scene file (TOML).
    pub scene: Option<PathBuf>,
    /// Output directory.
    #[arg(long, default_value = "out")]
    pub out: PathBuf,
    /// Photons to emit for each photon map (overrides the scene's integrator photons and
    /// caustic_photons).
    #[arg(long)]
    pub photons: Option<u64>,
    /// Random seed (overrides the scene's integrator seed).
    #[arg(long)]
    pub seed: Option<u64>,
    /// Worker threads (default: all cores; at most 1024). The output does not depend on it.
    #[arg(long)]
    pub threads: Option<usize>,
    /// No progress bars.
    #[arg(long)]
    pub quiet: bool,
    /// Photon-map memory each rank may hold, e.g. 8G or 512M (default: what its host has
    /// available, shared by the ranks there). Every rank holds every map.
    #[arg(long, value_parser = crate::distributed::budget::parse_bytes)]
    pub max_map_memory: Option<u64>,
    /// Memory the whole run may use, e.g. 8G or 512M (default: what the machine has available).
    /// The need is estimated before the photon maps are allocated; a run that would exceed it
    /// is refused with the numbers.
    #[arg(long, value_parser = crate::memory::parse_bytes)]
    pub max_memory: Option<u64>,
    /// Stop the run after this many seconds of wall time (exit code 1, nothing written, a
    /// message saying how far it got).
    #[arg(long)]
    pub max_seconds: Option<f64>,
    /// How rank 0 hands out eye-pass rows under MPI: "dynamic" (guided self-scheduling) or
    /// "static" (interleaved blocks). The image does not depend on it.
    #[arg(long, default_value = "dynamic", value_parser = parse_schedule)]
    pub schedule: Schedule,
    /// Progressive passes and when they stop.
    #[command(flatten)]
    pub stop: StopArgs,
}

/// When progressive passes stop (each flag overrides its `[integrator]` key; without any, one
/// pass). See the book's "Convergence" page.
#[derive(clap::Args, Clone, Debug, Default)]
pub struct StopArgs {
    /// Progressive passes to run (each with fresh photon maps and smaller gather radii).
    #[arg(long, allow_negative_numbers = true)]
    pub passes: Option<i64>,
    /// Wall-clock budget of the whole run, e.g. 90s, 1.5min, 2h: passes run while the next is
    /// predicted (from the last one's time) to end within it.
    #[arg(long, allow_hyphen_values = true)]
    pub time: Option<String>,
    /// Stop when the relative standard error of the target's mean falls below this, e.g. 0.01.
    #[arg(long, allow_negative_numbers = true)]
    pub target_rel_error: Option<f64>,
    /// What --target-rel-error is measured on: "image" (default), a sensor's name, or a pixel
    /// region x0,y0,x1,y1 (x1, y1 exclusive).
    #[arg(long)]
    pub target: Option<String>,
}

impl StopArgs {
    /// The flags as the scene's stopping rules take them.
    pub fn flags(&self) -> crate::scene::progressive::Flags {
        crate::scene::progressive::Flags {
            passes: self.passes,
            time: self.time.clone(),
            target_rel_error: self.target_rel_error,
            target: self.target.clone(),
            style: crate::scene::progressive::FlagStyle::Cli,
        }
    }
}

/// Renders on every rank of this run's comm (one process, or an MPI job under `mpirun`); rank
/// 0 writes the outputs and returns the lines to print. Errors are collective: every rank ends
/// with the same exit code, and only rank 0 prints.
pub fn run(args: &RenderArgs) -> Result<String> {
    let start = Instant::now();
    let map_memory = args.max_map_memory.map_or(MapMemory::Available, MapMemory::Limit);
    let dist = distributed::Options { map_memory, schedule: args.schedule };
    let comm = Comm::start()?;
    let result = render_and_write(&comm, args, &dist, start);
    let root = comm.is_root();
    drop(comm); // MPI_Finalize on every rank, also after an error
    match result {
        Err(e) if !root => std::process::exit(e.exit_code()),
        r => r,
    }
}

/// The longest `--max-seconds` (a year).
pub const MAX_SECONDS: f64 = 3.2e7;

/// The most worker threads `--threads` may ask for.
pub const MAX_THREADS: usize = 1024;

fn render_and_write(comm: &Comm, args: &RenderArgs, dist: &distributed::Options, start: Instant) -> Result<String> {
    if let Some(n) = args.photons {
        crate::scene::check_photons_override(n)?;
    }
    if let Some(s) = args.max_seconds
        && !(s.is_finite() && s > 0.0 && s <= MAX_SECONDS)
    {
        return Err(Error::input(
            None,
            format!("--max-seconds {s}: expected a positive number of seconds, at most {MAX_SECONDS}"),
        ));
    }
    let mut builder = rayon::ThreadPoolBuilder::new();
    if let Some(t) = args.threads {
        if !(1..=MAX_THREADS).contains(&t) {
            return Err(Error::input(
                None,
                format!(
                    "--threads {t} is out of range: it must be between 1 and {MAX_THREADS} (the output does not depend on it)"
                ),
            ));
        }
        builder = builder.num_threads(t);
    }
    let pool = builder.build().map_err(|e| Error::internal(format!("cannot start worker threads: {e}")))?;
    let mut scene = distributed::scene::load(comm, args.scene.as_deref(), args.photons, args.seed)?;
    scene.apply_stopping_rules(&args.stop.flags())?;
    // Rank 0 writes the outputs: it checks where, before any work, and every rank learns.
    let destination = if comm.is_root() { crate::output::check_destination(&scene, &args.out, true) } else { Ok(()) };
    distributed::fault::agree(comm, destination)?;
    if comm.is_root() {
        super::print_warnings(&scene);
        if comm.size() > 1 && !args.quiet {
            eprintln!("morgana: {} ranks ({}), eye pass {:?}", comm.size(), comm.kind(), dist.schedule);
        }
    }
    let opts = RenderOptions {
        quiet: args.quiet,
        max_memory: args.max_memory.map_or(MemoryLimit::Available, MemoryLimit::Limit),
        deadline: args.max_seconds.map(|s| start + std::time::Duration::from_secs_f64(s)),
        cancel: None,
        observer: None,
        started: Some(start),
    };
    let rendered = pool.install(|| render_on(comm, &scene, &opts, dist))?;
    let Some(rendered) = rendered else { return Ok(String::new()) };
    for w in &rendered.stats.warnings {
        eprintln!("morgana: note: {w}");
    }
    let threads = pool.current_num_threads();
    let outputs = crate::output::write_outputs(&scene, &rendered, &args.out, threads, start.elapsed().as_secs_f64())?;
    Ok(outputs.iter().map(|p| format!("wrote {}\n", p.display())).collect())
}

fn parse_schedule(s: &str) -> std::result::Result<Schedule, String> {
    match s {
        "dynamic" => Ok(Schedule::Dynamic),
        "static" => Ok(Schedule::Static),
        _ => Err(format!("expected \"dynamic\" or \"static\", found \"{s}\"")),
    }
}
