//! Wall and CPU time of a span of work on this process (an MPI rank), and the times of a run's
//! phases.
//!
//! Wall time is what a user waits for; on a machine shared with other jobs it also counts the
//! time the rank was not scheduled. CPU time (user + system, over all threads of the process)
//! counts the work alone, so phase times measured on a loaded machine can still feed the
//! cluster model (`scripts/mpi_model.py`): with one worker thread per rank and no other rank to
//! wait for, a phase's CPU time is its wall time on a core of its own. (A rank waiting in an MPI
//! call may spin, which counts as CPU time: compare CPU times of waits with care.)
//!
//! CPU time is read from `/proc/self/stat` (fields 14 and 15, `utime` and `stime`, in clock
//! ticks of 1/100 s — Linux's fixed `USER_HZ`, see proc(5)), so its resolution is 10 ms; where
//! that file is missing it reads as zero.

use serde::{Deserialize, Serialize};
use std::time::Instant;

/// Clock ticks per second in `/proc/<pid>/stat` (`USER_HZ`; proc(5), `sysconf(_SC_CLK_TCK)`).
const TICKS_PER_SECOND: f64 = 100.0;

/// How long a span of work took.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Took {
    /// Wall time.
    pub seconds: f64,
    /// CPU time of this process's threads over the span.
    pub cpu_seconds: f64,
}

/// A span of work started at some moment.
#[derive(Clone, Copy, Debug)]
pub struct Span {
    wall: Instant,
    cpu: f64,
}

impl Span {
    /// A span starting now.
    pub fn start() -> Span {
        Span { wall: Instant::now(), cpu: process_cpu_seconds().unwrap_or(0.0) }
    }

    /// Wall and CPU time since [`Span::start`].
    pub fn took(&self) -> Took {
        let cpu = process_cpu_seconds().map_or(0.0, |c| (c - self.cpu).max(0.0));
        Took { seconds: self.wall.elapsed().as_secs_f64(), cpu_seconds: cpu }
    }
}

/// User + system CPU seconds of this process so far, or `None` where `/proc/self/stat` is
/// unreadable.
pub fn process_cpu_seconds() -> Option<f64> {
    parse_stat(&std::fs::read_to_string("/proc/self/stat").ok()?)
}

/// `utime + stime` from a `/proc/<pid>/stat` line, in seconds. The command name (field 2) is in
/// parentheses and may contain spaces, so fields are counted after the last `)`.
fn parse_stat(line: &str) -> Option<f64> {
    let rest = &line[line.rfind(')')? + 1..];
    let mut fields = rest.split_whitespace().skip(11);
    let utime: u64 = fields.next()?.parse().ok()?;
    let stime: u64 = fields.next()?.parse().ok()?;
    Some((utime + stime) as f64 / TICKS_PER_SECOND)
}

/// One phase of a run and how long it took.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct PhaseTime {
    /// The phase's name, e.g. "global photon tracing".
    pub phase: String,
    /// Wall time.
    pub seconds: f64,
    /// CPU time of this process over the phase (see [`Took`]).
    #[serde(default)]
    pub cpu_seconds: f64,
}

/// Wall (and CPU) time per phase, in the order the phases ran.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Phases(pub Vec<PhaseTime>);

impl Phases {
    /// Records the time since `start` under `phase` and returns its wall time in seconds.
    pub fn add(&mut self, phase: &str, start: Span) -> f64 {
        self.push(phase, start.took())
    }

    /// Records `took` under `phase` and returns its wall time in seconds.
    pub fn push(&mut self, phase: &str, took: Took) -> f64 {
        self.0.push(PhaseTime { phase: phase.to_string(), seconds: took.seconds, cpu_seconds: took.cpu_seconds });
        took.seconds
    }
}

/// When a run must stop early: at a wall-clock deadline (`--max-seconds`), when another thread
/// raises a cancel flag (Ctrl-C in the Python package), either, or never. Work checks it between
/// batches of photons and rows of pixels, so a run stops within one batch or row of the signal.
#[derive(Clone, Copy, Debug, Default)]
pub struct Stop<'a> {
    /// The moment the time budget ends.
    pub deadline: Option<Instant>,
    /// A flag that, once true, stops the run.
    pub cancel: Option<&'a std::sync::atomic::AtomicBool>,
}

impl Stop<'_> {
    /// Whether the run must stop now.
    pub fn reached(&self) -> bool {
        self.deadline.is_some_and(|d| Instant::now() >= d)
            || self.cancel.is_some_and(|c| c.load(std::sync::atomic::Ordering::Relaxed))
    }

    /// Whether it stopped (or must stop) because of the cancel flag rather than the deadline.
    pub fn cancelled(&self) -> bool {
        self.cancel.is_some_and(|c| c.load(std::sync::atomic::Ordering::Relaxed))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_utime_and_stime_after_the_command_name() {
        // proc(5): pid (comm) state ppid pgrp session tty_nr tpgid flags minflt cminflt majflt
        // cmajflt utime stime ...; a command name with spaces and parentheses.
        let line = "4242 (my (odd) cmd) R 1 4242 4242 0 -1 4194560 100 0 0 0 250 37 0 0 20 0 3 0";
        assert_eq!(parse_stat(line), Some(2.87));
        assert_eq!(parse_stat("4242 (cmd) R 1"), None);
    }

    #[test]
    fn cpu_time_grows_with_work() {
        // (Other tests run in this process at the same time, so only growth is checked.)
        let s = Span::start();
        let mut x = 0u64;
        while s.took().cpu_seconds < 0.05 {
            for _ in 0..100_000 {
                x = std::hint::black_box(x.wrapping_mul(6364136223846793005).wrapping_add(1));
            }
            assert!(s.took().seconds < 30.0, "no CPU time counted after 30 s of work");
        }
        assert!(s.took().seconds > 0.0);
    }

    #[test]
    fn a_stop_is_reached_by_its_deadline_or_its_flag() {
        use std::sync::atomic::{AtomicBool, Ordering};
        assert!(!Stop::default().reached());
        let past = Stop { deadline: Some(Instant::now()), cancel: None };
        assert!(past.reached() && !past.cancelled());
        let far = Instant::now() + std::time::Duration::from_secs(3600);
        let flag = AtomicBool::new(false);
        let stop = Stop { deadline: Some(far), cancel: Some(&flag) };
        assert!(!stop.reached());
        flag.store(true, Ordering::Relaxed);
        assert!(stop.reached() && stop.cancelled());
    }
}
