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
    /// Output directory (default: out, or the directory given to --resume).
    #[arg(long)]
    pub out: Option<PathBuf>,
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
    /// Stop the run after this many seconds of wall time: a progressive run keeps the passes
    /// it finished (its outputs are theirs); a run with none finished ends with exit code 1,
    /// nothing written, and a message saying how far it got.
    #[arg(long)]
    pub max_seconds: Option<f64>,
    /// How rank 0 hands out eye-pass rows under MPI: "dynamic" (guided self-scheduling) or
    /// "static" (interleaved blocks). The image does not depend on it.
    #[arg(long, default_value = "dynamic", value_parser = parse_schedule)]
    pub schedule: Schedule,
    /// Render once per solar zenith angle, the scene's sun moved to each (degrees, comma
    /// separated, e.g. 0,30,60,85,90): outputs per angle in OUT/sun_zenith_ANGLE/ and every
    /// sky_radiance sensor's reading in OUT/NAME_sun_sweep.csv. One process only.
    #[arg(long, value_delimiter = ',', allow_negative_numbers = true)]
    pub sun_zenith_deg: Vec<f64>,
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
    /// What --target-rel-error is measured on: "image" (default: the image's mean), "pixels"
    /// (95 % of the pixels each, for a picture), a sensor's name, or a pixel region
    /// x0,y0,x1,y1 (x1, y1 exclusive).
    #[arg(long)]
    pub target: Option<String>,
    /// From the second pass on, spend each pass's eye samples (spp × pixels) where the pixels'
    /// samples spread most: at least one a pixel, at most 32 × spp (adaptive sampling; the
    /// same as `[integrator] adaptive = true`).
    #[arg(long)]
    pub adaptive: bool,
    /// Continue the progressive run whose output directory (with its checkpoint) is DIR, with
    /// the same scene and options; --passes counts the passes already done.
    #[arg(long, value_name = "DIR")]
    pub resume: Option<PathBuf>,
    /// Plot the relative standard error after each pass against elapsed time here (PNG,
    /// log-log, with the least-squares slope); needs a progressive run.
    #[arg(long, value_name = "PNG")]
    pub convergence: Option<PathBuf>,
}

impl StopArgs {
    /// The flags as the scene's stopping rules take them.
    pub fn flags(&self) -> crate::scene::progressive::Flags {
        crate::scene::progressive::Flags {
            passes: self.passes,
            time: self.time.clone(),
            target_rel_error: self.target_rel_error,
            target: self.target.clone(),
            adaptive: self.adaptive,
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
    if comm.size() > 1 {
        // `mpirun` ends the whole job as soon as one rank exits non-zero, so no rank may leave
        // before rank 0 has printed: an error every rank shares (from a collective check) or
        // rank 0's own (writing the outputs, while the others succeeded). Every rank meets at
        // the all-gather, after rank 0's message, whatever its result.
        if let (true, Err(e)) = (comm.is_root(), &result) {
            eprintln!("morgana: {e}");
        }
        comm.all_gather(&[]);
        drop(comm); // MPI_Finalize on every rank
        if let Err(e) = &result {
            std::process::exit(e.exit_code());
        }
        return result;
    }
    drop(comm); // MPI_Finalize
    result
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
    if !args.sun_zenith_deg.is_empty() {
        return sweep(comm, args, &pool, start);
    }
    let mut scene = distributed::scene::load(comm, args.scene.as_deref(), args.photons, args.seed)?;
    scene.apply_stopping_rules(&args.stop.flags())?;
    let out = args.out.clone().or_else(|| args.stop.resume.clone()).unwrap_or_else(|| PathBuf::from("out"));
    // Rank 0 writes the outputs: it checks where, before any work, and every rank learns.
    let destination = if comm.is_root() { crate::output::check_destination(&scene, &out, true) } else { Ok(()) };
    distributed::fault::agree(comm, destination)?;
    let checkpoint = checkpoint_plan(comm, &scene, args, &out)?;
    if let Some(png) = &args.stop.convergence {
        let checked = if comm.is_root() { check_convergence(&scene, png) } else { Ok(()) };
        distributed::fault::agree(comm, checked)?;
    }
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
        checkpoint,
    };
    let rendered = pool.install(|| render_on(comm, &scene, &opts, dist))?;
    let Some(rendered) = rendered else { return Ok(String::new()) };
    for w in &rendered.stats.warnings {
        eprintln!("morgana: note: {w}");
    }
    let threads = pool.current_num_threads();
    let seconds = start.elapsed().as_secs_f64();
    let convergence = args.stop.convergence.as_deref();
    let outputs = crate::output::write_outputs_with(&scene, &rendered, &out, (threads, seconds), convergence)?;
    Ok(outputs.iter().map(|p| format!("wrote {}\n", p.display())).collect())
}

/// `--sun-zenith-deg`: the scene once per solar zenith angle ([`super::sun_sweep`]).
fn sweep(comm: &Comm, args: &RenderArgs, pool: &rayon::ThreadPool, start: Instant) -> Result<String> {
    let refuse = |why: &str| Err(Error::input(None, format!("--sun-zenith-deg: {why}")));
    if comm.size() > 1 {
        return refuse("runs on one process; start it without mpirun");
    }
    if args.stop.resume.is_some() || args.stop.convergence.is_some() {
        return refuse("cannot be combined with --resume or --convergence");
    }
    let Some(path) = args.scene.as_deref() else { return refuse("give a scene file with a sun") };
    let out = args.out.clone().unwrap_or_else(|| PathBuf::from("out"));
    let prepare = |scene: &mut crate::scene::Scene| {
        scene.apply_overrides(args.photons, args.seed);
        scene.apply_stopping_rules(&args.stop.flags())
    };
    let opts = RenderOptions {
        quiet: args.quiet,
        max_memory: args.max_memory.map_or(MemoryLimit::Available, MemoryLimit::Limit),
        deadline: args.max_seconds.map(|s| start + std::time::Duration::from_secs_f64(s)),
        cancel: None,
        observer: None,
        started: None,
        checkpoint: None,
    };
    let written = super::sun_sweep::run(path, &args.sun_zenith_deg, &prepare, &opts, pool, &out)?;
    Ok(written.iter().map(|p| format!("wrote {}\n", p.display())).collect())
}

/// Where a progressive run (one with a stopping rule) writes its checkpoints — its output
/// directory `out` — and, with `--resume DIR`, the checkpoint read from DIR on rank 0 and
/// checked against this run's scene and options. `None` for a run without stopping rules.
/// Collective: a checkpoint that cannot be read or does not match ends every rank.
fn checkpoint_plan(
    comm: &Comm,
    scene: &crate::scene::Scene,
    args: &RenderArgs,
    out: &std::path::Path,
) -> Result<Option<crate::render::checkpoint::Plan>> {
    use crate::render::checkpoint::{Checkpoint, Fingerprint, Plan};
    let progressive = scene.integrator.progressive.has_rules();
    let resume = args.stop.resume.as_deref();
    if let Some(dir) = resume.filter(|_| !progressive) {
        return Err(Error::input(
            None,
            format!(
                "--resume {}: give a stopping rule for the resumed run: --passes N (counting the passes already done), --time or --target-rel-error",
                dir.display()
            ),
        ));
    }
    if !progressive {
        return Ok(None);
    }
    let mut plan = Plan { dir: out.to_path_buf(), fingerprint: Fingerprint::default(), resume: None };
    if comm.is_root() {
        let read = fingerprint(scene).and_then(|f| {
            plan.fingerprint = f;
            resume.map(|dir| Checkpoint::read(dir, &plan.fingerprint)).transpose()
        });
        let read = read.and_then(|c| match (c, scene.integrator.progressive.passes) {
            (Some(c), Some(n)) if n < c.passes => Err(Error::input(
                None,
                format!(
                    "--passes {n}: the checkpoint in {} already holds {} passes; ask for at least as many",
                    resume.map_or(String::new(), |d| d.display().to_string()),
                    c.passes
                ),
            )),
            (c, _) => Ok(c),
        });
        plan.resume = distributed::fault::agree(comm, read)?;
    } else {
        distributed::fault::agree(comm, Ok(()))?;
    }
    Ok(Some(plan))
}

/// Checks, before any work, that `--convergence PNG` can be written and has passes to plot.
fn check_convergence(scene: &crate::scene::Scene, png: &std::path::Path) -> Result<()> {
    super::check_output_file("--convergence", png)?;
    if scene.integrator.progressive.has_rules() {
        return Ok(());
    }
    Err(Error::input(
        None,
        format!(
            "--convergence {}: one pass has no error estimate to plot; give --passes N (3 or more for a slope), --time or --target-rel-error",
            png.display()
        ),
    ))
}

/// The fingerprint of the scene as rank 0 loaded it: its file's text (or the embedded default
/// scene's), the files it names, and the effective settings.
fn fingerprint(scene: &crate::scene::Scene) -> Result<crate::render::checkpoint::Fingerprint> {
    use crate::render::checkpoint::Fingerprint;
    match &scene.file {
        None => Ok(Fingerprint::of(scene, crate::scene::DEFAULT_SCENE, None)),
        Some(file) => {
            let text = crate::error::read_utf8(file, "scene file")?;
            let dir = file.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(std::path::Path::new("."));
            Ok(Fingerprint::of(scene, &text, Some(dir)))
        }
    }
}

fn parse_schedule(s: &str) -> std::result::Result<Schedule, String> {
    match s {
        "dynamic" => Ok(Schedule::Dynamic),
        "static" => Ok(Schedule::Static),
        _ => Err(format!("expected \"dynamic\" or \"static\", found \"{s}\"")),
    }
}
