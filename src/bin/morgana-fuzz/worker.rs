//! The worker: a process that runs many cases of one target, one after another, as the
//! supervisor hands them out on standard input, and answers each with one line on standard
//! output. Panics are caught and reported (their message captured by a panic hook); a crash,
//! an abort for memory or a hang ends or stalls the process, and the supervisor sees it.
//!
//! Protocol: the supervisor writes `N` (generate and run case N) or `@PATH MODE` (run the file
//! PATH as the target's input, read in MODE); the worker answers
//! `N<TAB>class<TAB>microseconds<TAB>what<TAB>message`.

use crate::outcome::Outcome;
use crate::targets::{self, Seeds, Target};
use crate::workspace::Workspace;
use std::io::{BufRead, Write};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::Path;
use std::sync::Mutex;
use std::time::{Duration, Instant};

static PANIC_MESSAGE: Mutex<Option<String>> = Mutex::new(None);

/// Installs a panic hook that records the message and place instead of printing them.
pub fn quiet_panics() {
    std::panic::set_hook(Box::new(|info| {
        let msg = if let Some(s) = info.payload().downcast_ref::<&str>() {
            s.to_string()
        } else if let Some(s) = info.payload().downcast_ref::<String>() {
            s.clone()
        } else {
            "a panic without a message".to_string()
        };
        let at = info.location().map(|l| format!(" at {}:{}", l.file(), l.line())).unwrap_or_default();
        if let Ok(mut m) = PANIC_MESSAGE.lock() {
            *m = Some(format!("{msg}{at}"));
        }
    }));
}

/// Runs `f`, turning a panic into `Err(message)`.
pub fn catching<T>(f: impl FnOnce() -> T) -> Result<T, String> {
    catch_unwind(AssertUnwindSafe(f))
        .map_err(|_| PANIC_MESSAGE.lock().ok().and_then(|mut m| m.take()).unwrap_or_else(|| "panic".to_string()))
}

/// The worker's loop; returns when standard input closes.
pub fn serve(target: Target, seed: u64, repo: &Path, scratch: &Path, deadline: Duration) -> Result<(), String> {
    quiet_panics();
    let seeds = Seeds::load(target, repo)?;
    let fixtures = if target == Target::Cli { targets::cli_fixtures()? } else { Vec::new() };
    let ws = Workspace::new(scratch, &format!("w{}", std::process::id()), repo, fixtures)?;
    let stdin = std::io::stdin();
    let mut out = std::io::stdout().lock();
    for line in stdin.lock().lines() {
        let line = line.map_err(|e| e.to_string())?;
        let line = line.trim();
        if line.is_empty() {
            continue;
        }
        let (id, case) = if let Some(spec) = line.strip_prefix('@') {
            let (path, mode) = spec.rsplit_once(' ').unwrap_or((spec, "0"));
            let bytes = std::fs::read(path).map_err(|e| format!("{path}: {e}"))?;
            let name = Path::new(path).file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
            (line.to_string(), targets::case_of_file(target, &name, bytes, mode.parse().unwrap_or(0)))
        } else {
            let index: u64 = line.parse().map_err(|_| format!("bad case index {line:?}"))?;
            (line.to_string(), targets::generate(target, &seeds, seed, index))
        };
        let start = Instant::now();
        let outcome: Outcome = targets::run(target, &ws, &case, deadline);
        let us = start.elapsed().as_micros();
        let what = case.what.replace(['\t', '\n', '\r'], " ");
        let what: String = what.chars().take(300).collect();
        writeln!(out, "{id}\t{}\t{us}\t{what}\t{}", outcome.class.name(), outcome.message)
            .map_err(|e| e.to_string())?;
        out.flush().map_err(|e| e.to_string())?;
    }
    Ok(())
}
