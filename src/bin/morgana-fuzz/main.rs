//! `morgana-fuzz`: a structure-aware mutation fuzzer for every reader of outside input of
//! morgana (scene TOML, OBJ meshes, luminaire files, atmosphere files, density and lattice
//! grids, EXR input to `tonemap`) and for its command line.
//!
//! ```sh
//! morgana-fuzz run --target scene --cases 100000 --seed 1 --jobs 2   # prints a histogram
//! morgana-fuzz case --target scene --seed 1 --index 4711 --dump /tmp/c # one case, replayed
//! morgana-fuzz minimize --target scene --seed 1 --index 4711 --out tests/fuzz_corpus/scene/x.toml
//! morgana-fuzz replay --target scene tests/fuzz_corpus/scene/*          # the regression corpus
//! ```
//!
//! Every case is made from the run's seed and its index alone, so any case can be printed and
//! run again. Cases run in worker processes (each reading many cases in process, under a
//! virtual-memory limit); the supervisor gives each case a deadline and restarts a worker that
//! crashed or hung. The command line is fuzzed through the real `morgana` binary. Outcomes are
//! classified (`outcome.rs`): only success and input errors that locate the problem are
//! allowed. The book's "Checked" chapter has the histogram of the last long run.

mod cli_mut;
mod formats;
mod outcome;
mod supervisor;
mod targets;
mod text_mut;
mod toml_mut;
mod worker;
mod workspace;

use clap::{Parser, Subcommand};
use outcome::{CLASSES, Class, Histogram};
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::{Duration, Instant};
use supervisor::{Limits, Record};
use targets::{TARGETS, Target};

#[derive(Parser)]
#[command(name = "morgana-fuzz", about = "Structure-aware mutation fuzzing of morgana's readers and command line")]
struct Cli {
    #[command(subcommand)]
    command: Cmd,
}

#[derive(clap::Args, Clone)]
struct Common {
    /// Target: scene, render, obj, luminaire, atmosphere, grid, tonemap, cli (or "all" for run).
    #[arg(long)]
    target: String,
    /// Seed of the run: with the index, it decides every case.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Deadline of one case, seconds.
    #[arg(long, default_value_t = 10.0)]
    deadline_s: f64,
    /// Virtual memory of a worker and what it starts, MiB.
    #[arg(long, default_value_t = 3072)]
    memory_mib: u64,
    /// The repository whose examples, luminaires and atmospheres seed the cases.
    #[arg(long, default_value = env!("CARGO_MANIFEST_DIR"))]
    repo: PathBuf,
    /// The folder in which the run makes its scratch folder (removed at the end; what else the
    /// folder holds is left alone). Default: the system's temporary folder.
    #[arg(long)]
    scratch: Option<PathBuf>,
}

#[derive(Subcommand)]
enum Cmd {
    /// Run cases and print the histogram of outcomes; exit 1 when a case's outcome is not
    /// allowed.
    Run {
        #[command(flatten)]
        common: Common,
        /// Number of cases per target.
        #[arg(long, default_value_t = 1000)]
        cases: u64,
        /// First case index.
        #[arg(long, default_value_t = 0)]
        start: u64,
        /// Worker processes.
        #[arg(long, default_value_t = 2)]
        jobs: usize,
        /// Append every disallowed outcome here (tab-separated: target, case, class, what, message).
        #[arg(long)]
        log: Option<PathBuf>,
        /// Also log cases slower than this many milliseconds (class "slow").
        #[arg(long)]
        slow_ms: Option<f64>,
    },
    /// Print one case (what it is made of), write its files with --dump, and run it.
    Case {
        #[command(flatten)]
        common: Common,
        /// The case's index.
        #[arg(long)]
        index: u64,
        /// Write the case's files (and, for the command line, its arguments as `args`) here.
        #[arg(long)]
        dump: Option<PathBuf>,
    },
    /// Run files as the target's input (every way the target reads them); exit 1 when any
    /// outcome is not allowed. The regression corpus is run this way.
    Replay {
        #[command(flatten)]
        common: Common,
        /// Input files (for `cli`: one argument per line).
        files: Vec<PathBuf>,
    },
    /// Shrink a failing case (deleting lines, then bytes, while the outcome stays the same)
    /// and write it to --out.
    Minimize {
        #[command(flatten)]
        common: Common,
        /// The case's index (or give --input).
        #[arg(long)]
        index: Option<u64>,
        /// A file to shrink instead of a generated case.
        #[arg(long)]
        input: Option<PathBuf>,
        /// The mode to read --input in.
        #[arg(long, default_value_t = 0)]
        mode: u32,
        /// Where to write the shrunk input.
        #[arg(long)]
        out: PathBuf,
    },
    /// (internal) A worker process: reads case ids on stdin, answers on stdout.
    Worker {
        #[arg(long)]
        target: String,
        #[arg(long)]
        seed: u64,
        #[arg(long)]
        repo: PathBuf,
        #[arg(long)]
        scratch: PathBuf,
        #[arg(long)]
        deadline_s: f64,
    },
}

fn target_of(name: &str) -> Result<Target, String> {
    Target::parse(name).ok_or_else(|| {
        format!(
            "unknown target \"{name}\"; targets: {}",
            TARGETS.iter().map(|t| t.name()).collect::<Vec<_>>().join(", ")
        )
    })
}

fn limits(c: &Common) -> Limits {
    // The pid alone is not unique across pid namespaces (a run under `unshare --pid`).
    let nanos = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.subsec_nanos());
    // The run's own folder, inside the one given: removing it at the end never touches files the
    // user keeps there (a replayed input, or the whole folder given as `--scratch .`).
    let parent = c.scratch.clone().unwrap_or_else(std::env::temp_dir);
    let scratch = parent.join(format!("morgana-fuzz-{}-{nanos}", std::process::id()));
    Limits { deadline: Duration::from_secs_f64(c.deadline_s), memory_mib: c.memory_mib, repo: c.repo.clone(), scratch }
}

fn main() -> ExitCode {
    match real_main() {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => ExitCode::from(1),
        Err(e) => {
            eprintln!("morgana-fuzz: {e}");
            ExitCode::from(2)
        }
    }
}

/// Runs the command; `Ok(false)` when a disallowed outcome was seen.
fn real_main() -> Result<bool, String> {
    match Cli::parse().command {
        Cmd::Worker { target, seed, repo, scratch, deadline_s } => {
            worker::serve(target_of(&target)?, seed, &repo, &scratch, Duration::from_secs_f64(deadline_s))
                .map_err(|e| format!("worker: {e}"))?;
            Ok(true)
        }
        Cmd::Run { common, cases, start, jobs, log, slow_ms } => {
            let targets: Vec<Target> =
                if common.target == "all" { TARGETS.to_vec() } else { vec![target_of(&common.target)?] };
            let lim = limits(&common);
            let mut all_ok = true;
            for t in targets {
                let items: Vec<String> = (start..start + cases).map(|i| i.to_string()).collect();
                let (hist, secs) = run_and_count(t, common.seed, items, jobs, &lim, log.as_ref(), slow_ms)?;
                print_histogram(t, &hist, secs, common.seed, jobs, start);
                all_ok &= hist.findings() == 0;
            }
            let _ = std::fs::remove_dir_all(&lim.scratch);
            Ok(all_ok)
        }
        Cmd::Case { common, index, dump } => {
            let t = target_of(&common.target)?;
            let seeds = targets::Seeds::load(t, &common.repo)?;
            let case = targets::generate(t, &seeds, common.seed, index);
            println!("case {index} of {} (seed {}): {}", t.name(), common.seed, case.what);
            println!("  mode {}", case.mode);
            for (n, b) in &case.files {
                println!("  file {n}: {} bytes", b.len());
            }
            if !case.args.is_empty() {
                println!("  morgana {}", case.args.iter().map(|a| format!("{:?}", a)).collect::<Vec<_>>().join(" "));
            }
            if let Some(d) = dump {
                std::fs::create_dir_all(&d).map_err(|e| e.to_string())?;
                for (n, b) in &case.files {
                    std::fs::write(d.join(n), b).map_err(|e| e.to_string())?;
                }
                if !case.args.is_empty() {
                    std::fs::write(d.join("args"), cli_mut::args_file(&case.args)).map_err(|e| e.to_string())?;
                }
                println!("  written to {}", d.display());
            }
            let lim = limits(&common);
            let records = collect(t, common.seed, vec![index.to_string()], 1, &lim)?;
            let _ = std::fs::remove_dir_all(&lim.scratch);
            let r = &records[0];
            println!("outcome: {} ({:.1} ms) {}", r.outcome.class, r.micros as f64 / 1000.0, r.outcome.message);
            Ok(r.outcome.class.allowed())
        }
        Cmd::Replay { common, files } => {
            let t = target_of(&common.target)?;
            let mut items = Vec::new();
            for f in &files {
                let abs = std::fs::canonicalize(f).map_err(|e| format!("{}: {e}", f.display()))?;
                for mode in 0..targets::modes(t) {
                    items.push(format!("@{} {mode}", abs.display()));
                }
            }
            let lim = limits(&common);
            let records = collect(t, common.seed, items, 1, &lim)?;
            let _ = std::fs::remove_dir_all(&lim.scratch);
            let mut ok = true;
            for r in &records {
                println!("{}\t{}\t{}", r.id, r.outcome.class, r.outcome.message);
                ok &= r.outcome.class.allowed();
            }
            Ok(ok)
        }
        Cmd::Minimize { common, index, input, mode, out } => {
            let t = target_of(&common.target)?;
            let lim = limits(&common);
            let (bytes, mode) = match (index, &input) {
                (_, Some(p)) => (std::fs::read(p).map_err(|e| e.to_string())?, mode),
                (Some(i), None) => {
                    let seeds = targets::Seeds::load(t, &common.repo)?;
                    let case = targets::generate(t, &seeds, common.seed, i);
                    let bytes = if t == Target::Cli { cli_mut::args_file(&case.args) } else { case.files[0].1.clone() };
                    (bytes, case.mode)
                }
                (None, None) => return Err("give --index or --input".into()),
            };
            let name = out.file_name().map(|n| n.to_string_lossy().into_owned()).ok_or("--out needs a file name")?;
            let shrunk = minimize(t, &bytes, &name, mode, &lim)?;
            let _ = std::fs::remove_dir_all(&lim.scratch);
            if let Some(dir) = out.parent() {
                std::fs::create_dir_all(dir).map_err(|e| e.to_string())?;
            }
            std::fs::write(&out, &shrunk.0).map_err(|e| e.to_string())?;
            println!(
                "{} bytes -> {} bytes, outcome {}: {}",
                bytes.len(),
                shrunk.0.len(),
                shrunk.1.class,
                shrunk.1.message
            );
            println!("written to {}", out.display());
            Ok(true)
        }
    }
}

/// Runs the items and returns every record, in item order.
fn collect(t: Target, seed: u64, items: Vec<String>, jobs: usize, lim: &Limits) -> Result<Vec<Record>, String> {
    let order: Vec<String> = items.clone();
    let (tx, rx) = std::sync::mpsc::channel();
    let lim2 = lim.clone();
    let h = std::thread::spawn(move || supervisor::run(t, seed, items, jobs, &lim2, tx));
    let mut records: Vec<Record> = rx.iter().collect();
    h.join().map_err(|_| "supervisor panicked")??;
    records.sort_by_key(|r| order.iter().position(|i| *i == r.id).unwrap_or(usize::MAX));
    Ok(records)
}

fn run_and_count(
    t: Target,
    seed: u64,
    items: Vec<String>,
    jobs: usize,
    lim: &Limits,
    log: Option<&PathBuf>,
    slow_ms: Option<f64>,
) -> Result<(Histogram, f64), String> {
    let n = items.len();
    let start = Instant::now();
    let (tx, rx) = std::sync::mpsc::channel();
    let lim2 = lim.clone();
    let h = std::thread::spawn(move || supervisor::run(t, seed, items, jobs, &lim2, tx));
    let mut hist = Histogram::default();
    let mut logf = match log {
        Some(p) => Some(
            std::fs::OpenOptions::new()
                .create(true)
                .append(true)
                .open(p)
                .map_err(|e| format!("{}: {e}", p.display()))?,
        ),
        None => None,
    };
    let mut seeds: Option<targets::Seeds> = None;
    let mut done = 0usize;
    let mut last_report = Instant::now();
    for mut r in rx.iter() {
        done += 1;
        if !r.outcome.class.allowed() && r.what.is_empty() && !r.id.starts_with('@') {
            // A crash or a hang: describe the case from its index.
            if seeds.is_none() {
                seeds = targets::Seeds::load(t, &lim.repo).ok();
            }
            if let (Some(s), Ok(i)) = (&seeds, r.id.parse::<u64>()) {
                r.what = targets::generate(t, s, seed, i).what;
            }
        }
        hist.add(&r.id, &r.outcome);
        hist.time(r.what.split(';').next().unwrap_or("").split(',').next().unwrap_or(""), r.micros);
        let slow = slow_ms.is_some_and(|ms| r.micros as f64 > ms * 1000.0);
        if (!r.outcome.class.allowed() || slow)
            && let Some(f) = logf.as_mut()
        {
            use std::io::Write;
            let class = if r.outcome.class.allowed() {
                format!("slow {:.0} ms, {}", r.micros as f64 / 1000.0, r.outcome.class)
            } else {
                r.outcome.class.to_string()
            };
            let _ = writeln!(f, "{}\t{}\t{class}\t{}\t{}", t.name(), r.id, r.what, r.outcome.message);
        }
        if last_report.elapsed() > Duration::from_secs(30) {
            last_report = Instant::now();
            eprintln!(
                "morgana-fuzz: {}: {done}/{n} cases, {:.0} s, {} findings",
                t.name(),
                start.elapsed().as_secs_f64(),
                hist.findings()
            );
        }
    }
    h.join().map_err(|_| "supervisor panicked")??;
    Ok((hist, start.elapsed().as_secs_f64()))
}

fn print_histogram(t: Target, h: &Histogram, secs: f64, seed: u64, jobs: usize, start: u64) {
    let total = h.total();
    println!(
        "target {}: {total} cases (from index {start}, seed {seed}, {jobs} jobs) in {secs:.1} s, {:.0} cases/s",
        t.name(),
        total as f64 / secs.max(1e-9)
    );
    for c in CLASSES {
        let n = h.counts.get(&c).copied().unwrap_or(0);
        let mark = if c.allowed() || n == 0 { "" } else { "  <- finding" };
        println!("  {:<24} {n:>8}{mark}", c.name());
    }
    let mut slow: Vec<(&String, &(u64, u64))> = h.seeds.iter().collect();
    slow.sort_by_key(|(_, (n, us))| std::cmp::Reverse(us / n.max(&1)));
    let per: Vec<String> = slow
        .iter()
        .take(6)
        .map(|(s, (n, us))| format!("{s} {:.1} ms ×{n}", *us as f64 / 1000.0 / (*n).max(1) as f64))
        .collect();
    println!("  mean time per case by seed (slowest): {}", per.join("; "));
    if h.findings() > 0 {
        println!("  distinct findings (messages with digits masked):");
        for ((class, _), (count, first)) in h.distinct.iter().take(40) {
            let ex = h.examples.get(class).and_then(|v| v.iter().find(|(id, _)| id == first)).map(|(_, m)| m.clone());
            println!("    [{class}] ×{count}, first case {first}: {}", ex.unwrap_or_else(|| "(see the log)".into()));
        }
        if h.distinct.len() > 40 {
            println!("    … {} more", h.distinct.len() - 40);
        }
    }
}

/// Shrinks `bytes` (read as the target's input `name` in `mode`) while the outcome keeps its
/// class: lines first (chunks of decreasing size), then bytes for small inputs.
fn minimize(
    t: Target,
    bytes: &[u8],
    name: &str,
    mode: u32,
    lim: &Limits,
) -> Result<(Vec<u8>, outcome::Outcome), String> {
    let dir = lim.scratch.join("min");
    std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
    let path = dir.join(name);
    let abs = dir.canonicalize().map_err(|e| e.to_string())?.join(name);
    let eval = |b: &[u8]| -> Result<outcome::Outcome, String> {
        std::fs::write(&path, b).map_err(|e| e.to_string())?;
        let r = collect(t, 0, vec![format!("@{} {mode}", abs.display())], 1, lim)?;
        Ok(r[0].outcome.clone())
    };
    let first = eval(bytes)?;
    if first.class.allowed() {
        return Err(format!("the input's outcome is allowed ({}): nothing to minimise", first.class));
    }
    let goal: Class = first.class;
    let mut cur = bytes.to_vec();
    let mut best = first;
    let started = Instant::now();
    let budget = Duration::from_secs(240);
    for unit_lines in [true, false] {
        if !unit_lines && cur.len() > 4096 {
            break;
        }
        let split = |b: &[u8]| -> Vec<Vec<u8>> {
            if unit_lines {
                b.split_inclusive(|&c| c == b'\n').map(<[u8]>::to_vec).collect()
            } else {
                b.iter().map(|&c| vec![c]).collect()
            }
        };
        let mut parts = split(&cur);
        let mut chunk = parts.len().div_ceil(2).max(1);
        while chunk >= 1 && started.elapsed() < budget {
            let mut i = 0;
            let mut removed_any = false;
            while i < parts.len() && started.elapsed() < budget {
                let mut trial: Vec<Vec<u8>> = parts[..i].to_vec();
                trial.extend_from_slice(&parts[(i + chunk).min(parts.len())..]);
                let b: Vec<u8> = trial.concat();
                let o = eval(&b)?;
                if o.class == goal {
                    parts = trial;
                    cur = b;
                    best = o;
                    removed_any = true;
                } else {
                    i += chunk;
                }
            }
            if chunk == 1 && !removed_any {
                break;
            }
            if !removed_any {
                chunk /= 2;
            } else {
                chunk = chunk.min(parts.len().div_ceil(2).max(1));
            }
        }
    }
    Ok((cur, best))
}
