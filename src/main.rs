//! The `morgana` command line: parses arguments, calls the library, reports errors.
//! Exit codes: 0 success, 2 bad input, 1 internal failure.

use clap::{Parser, Subcommand};
use morgana::distributed::{self, MapMemory, Schedule, World};
use morgana::error::{Error, Result};
use morgana::render::{RenderOptions, render_on};
use morgana::scene::{Scene, default_scene, load_scene_file};
use std::path::{Path, PathBuf};
use std::time::Instant;

#[derive(Parser)]
#[command(name = "morgana", version, about = "Spectral light transport through media that bend and re-colour light")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Render a scene (the embedded default scene when SCENE is omitted) into --out.
    Render {
        /// Scene file (TOML).
        scene: Option<PathBuf>,
        /// Output directory.
        #[arg(long, default_value = "out")]
        out: PathBuf,
        /// Photons to emit for each photon map (overrides [integrator] photons and caustic_photons).
        #[arg(long)]
        photons: Option<u64>,
        /// Random seed (overrides [integrator] seed).
        #[arg(long)]
        seed: Option<u64>,
        /// Worker threads (default: all cores). The output does not depend on it.
        #[arg(long)]
        threads: Option<usize>,
        /// No progress bars.
        #[arg(long)]
        quiet: bool,
        /// Photon-map memory each rank may hold, e.g. 8G or 512M (default: what its host has
        /// available, shared by the ranks there). Every rank holds every map.
        #[arg(long, value_parser = morgana::distributed::budget::parse_bytes)]
        max_map_memory: Option<u64>,
        /// How rank 0 hands out eye-pass rows under MPI: "dynamic" (guided self-scheduling) or
        /// "static" (interleaved blocks). The image does not depend on it.
        #[arg(long, default_value = "dynamic", value_parser = parse_schedule)]
        schedule: Schedule,
    },
    /// Write a density grid (.mgrid, documented in src/media/density/grid.rs) of procedural fBm
    /// turbulence, for `density = { type = "grid", file = ... }`.
    Grid {
        /// Output file.
        #[arg(long)]
        out: PathBuf,
        /// Lattice points per axis.
        #[arg(long, default_value_t = 64)]
        res: usize,
        /// Box corner, metres: x,y,z.
        #[arg(long, value_parser = parse_vec3, default_value = "-1,-1,-1")]
        min: [f64; 3],
        /// Opposite box corner, metres: x,y,z.
        #[arg(long, value_parser = parse_vec3, default_value = "1,1,1")]
        max: [f64; 3],
        #[arg(long, default_value_t = 0.5)]
        base: f64,
        #[arg(long, default_value_t = 0.5)]
        amplitude: f64,
        #[arg(long, default_value_t = 2.0)]
        frequency_per_m: f64,
        #[arg(long, default_value_t = 5)]
        octaves: u32,
        #[arg(long, default_value_t = 1)]
        seed: u64,
    },
    /// Tone-map a spectral (or RGB) EXR into an sRGB PNG as an eye would see it.
    Tonemap(morgana::tonemap::cli::TonemapArgs),
    /// Validate a scene and print what will be simulated and why.
    Check {
        /// Scene file (TOML); the embedded default scene when omitted.
        scene: Option<PathBuf>,
    },
    /// Read a luminaire photometry file (IES LM-63, EULUMDAT, IES TM-33, GLDF) and print what it
    /// says: format, flux, symmetry, spectrum, peak, beam and field angles; optionally draw its
    /// polar curves.
    Luminaire {
        /// Photometric file (.ies, .ldt, .xml TM-33, .gldf).
        file: PathBuf,
        /// Write the C0–C180 and C90–C270 polar intensity curves to this PNG.
        #[arg(long)]
        png: Option<PathBuf>,
        /// GLDF only: the id of the variant to read (default: the first).
        #[arg(long)]
        variant: Option<String>,
    },
    /// Ray-integrator accuracy and speed against the closed-form ray in n = 1 + k*y: Dormand-Prince
    /// over tolerances, Euler and RK4 over step sizes (Gutierrez et al. 2005, Fig. 1, extended).
    Accuracy(morgana::raypath::accuracy::AccuracyArgs),
    /// Astronomical refraction: trace rays from an observer out of an atmosphere and print the
    /// true altitude and refraction for each apparent altitude.
    Refraction(morgana::atmosphere::refraction::cli::RefractionArgs),
    /// Follow one ray through a scene's media (curved where their index fields bend it) without
    /// scattering: each surface, boundary and the escape, with path length and direction.
    Trace(morgana::raypath::trace_cli::TraceArgs),
}

fn main() {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Render { scene, out, photons, seed, threads, quiet, max_map_memory, schedule } => {
            let map_memory = max_map_memory.map_or(MapMemory::Available, MapMemory::Limit);
            let dist = distributed::Options { map_memory, schedule };
            run_render(scene.as_deref(), &out, photons, seed, threads, quiet, dist)
        }
        Command::Check { scene } => run_check(scene.as_deref()),
        Command::Grid { out, res, min, max, base, amplitude, frequency_per_m, octaves, seed } => {
            let fbm = morgana::media::density::Fbm::new(base, amplitude, frequency_per_m, octaves, seed);
            morgana::media::density::write_grid_atomically(&out, [res; 3], min.into(), max.into(), |p| fbm.at(p))
                .map(|()| println!("wrote {}", out.display()))
        }
        Command::Tonemap(args) => run_tonemap(&args),
        Command::Luminaire { file, png, variant } => {
            morgana::luminaire::inspect_variant(&file, png.as_deref(), variant.as_deref()).map(|s| print!("{s}"))
        }
        Command::Accuracy(args) => morgana::raypath::accuracy::run_cli(&args).map(|s| print!("{s}")),
        Command::Refraction(args) => morgana::atmosphere::refraction::cli::run(&args).map(|s| print!("{s}")),
        Command::Trace(args) => morgana::raypath::trace_cli::run(&args).map(|s| print!("{s}")),
    };
    if let Err(e) = result {
        eprintln!("morgana: {e}");
        std::process::exit(e.exit_code());
    }
}

fn parse_vec3(s: &str) -> std::result::Result<[f64; 3], String> {
    let v: Vec<f64> = s
        .split(',')
        .map(|x| x.trim().parse::<f64>())
        .collect::<std::result::Result<_, _>>()
        .map_err(|e| format!("{e}"))?;
    match v.as_slice() {
        [x, y, z] if v.iter().all(|c| c.is_finite()) => Ok([*x, *y, *z]),
        _ => Err(format!("expected three finite numbers x,y,z, found \"{s}\"")),
    }
}

fn load(path: Option<&Path>) -> Result<Scene> {
    let scene = match path {
        Some(p) => load_scene_file(p),
        None => default_scene(),
    }?;
    print_warnings(&scene);
    Ok(scene)
}

fn print_warnings(scene: &Scene) {
    for w in &scene.warnings {
        eprintln!("morgana: note: {w}");
    }
}

fn run_tonemap(args: &morgana::tonemap::cli::TonemapArgs) -> Result<()> {
    for line in morgana::tonemap::cli::run(&args.command()?)? {
        println!("{line}");
    }
    Ok(())
}

fn run_check(path: Option<&Path>) -> Result<()> {
    let scene = load(path)?;
    println!("{}: valid", scene.label());
    println!(
        "  {}x{} pixels, {} bands over {}–{} nm ({:?} sampling), {} lights, {} shapes",
        scene.camera.width,
        scene.camera.height,
        scene.bands.count,
        scene.bands.min_nm,
        scene.bands.max_nm,
        scene.sampling,
        scene.lights.len(),
        scene.shapes.len()
    );
    println!("effect plan:");
    print!("{}", scene.plan);
    Ok(())
}

/// Renders on every rank of this run's world (one process, or an MPI job under `mpirun`); rank
/// 0 writes the outputs. Errors are collective: every rank ends with the same exit code, and
/// only rank 0 prints.
fn run_render(
    path: Option<&Path>,
    out: &Path,
    photons: Option<u64>,
    seed: Option<u64>,
    threads: Option<usize>,
    quiet: bool,
    dist: distributed::Options,
) -> Result<()> {
    let start = Instant::now();
    let world = World::start()?;
    let result = (|| {
        let mut builder = rayon::ThreadPoolBuilder::new();
        if let Some(t) = threads {
            if t == 0 {
                return Err(Error::input(None, "--threads must be at least 1"));
            }
            builder = builder.num_threads(t);
        }
        let pool = builder.build().map_err(|e| Error::internal(format!("cannot start worker threads: {e}")))?;
        let scene = distributed::scene::load(&world, path, photons, seed)?;
        if world.is_root() {
            print_warnings(&scene);
            if world.size() > 1 && !quiet {
                eprintln!("morgana: {} ranks ({}), eye pass {:?}", world.size(), world.kind(), dist.schedule);
            }
        }
        let rendered = pool.install(|| render_on(&world, &scene, &RenderOptions { quiet }, &dist))?;
        let Some(rendered) = rendered else { return Ok(()) };
        let threads = pool.current_num_threads();
        let outputs = morgana::output::write_outputs(&scene, &rendered, out, threads, start.elapsed().as_secs_f64())?;
        for p in outputs {
            println!("wrote {}", p.display());
        }
        Ok(())
    })();
    let root = world.is_root();
    drop(world); // MPI_Finalize on every rank, also after an error
    match result {
        Err(e) if !root => std::process::exit(e.exit_code()),
        r => r,
    }
}

fn parse_schedule(s: &str) -> std::result::Result<Schedule, String> {
    match s {
        "dynamic" => Ok(Schedule::Dynamic),
        "static" => Ok(Schedule::Static),
        _ => Err(format!("expected \"dynamic\" or \"static\", found \"{s}\"")),
    }
}
