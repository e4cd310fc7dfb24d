//! The supervisor: starts worker processes (each under a virtual-memory limit, in its own
//! process group), hands them cases, enforces each case's deadline, and restarts a worker
//! that crashed or hung, recording that case's outcome.

use crate::outcome::{Class, Outcome};
use crate::targets::Target;
use std::io::{BufRead, BufReader, Read, Write};
use std::os::unix::process::CommandExt;
use std::path::PathBuf;
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc::{Receiver, RecvTimeoutError, Sender, channel};
use std::sync::{Arc, Mutex};
use std::time::Duration;

/// How workers run.
#[derive(Clone, Debug)]
pub struct Limits {
    /// Per-case deadline.
    pub deadline: Duration,
    /// Virtual memory of a worker (and the processes it starts), MiB.
    pub memory_mib: u64,
    /// The repository (seeds and resources).
    pub repo: PathBuf,
    /// Where workers make their scratch trees.
    pub scratch: PathBuf,
}

/// One case's result as the supervisor records it.
#[derive(Clone, Debug)]
pub struct Record {
    /// The case's id: its index, or `@file mode`.
    pub id: String,
    /// The outcome.
    pub outcome: Outcome,
    /// The case's description (seed and mutations), when the worker gave it.
    pub what: String,
    /// Time the case took in the worker, µs (the deadline for timeouts).
    pub micros: u64,
}

struct Worker {
    child: Child,
    stdin: ChildStdin,
    lines: Receiver<String>,
    stderr: Arc<Mutex<String>>,
}

impl Worker {
    fn start(target: Target, seed: u64, limits: &Limits) -> Result<Worker, String> {
        let exe = std::env::current_exe().map_err(|e| e.to_string())?;
        let kib = limits.memory_mib * 1024;
        let mut child = Command::new("sh")
            .arg("-c")
            .arg(format!("ulimit -v {kib} && exec \"$0\" \"$@\""))
            .arg(&exe)
            .args(["worker", "--target", target.name(), "--seed", &seed.to_string()])
            .arg("--repo")
            .arg(&limits.repo)
            .arg("--scratch")
            .arg(&limits.scratch)
            .args(["--deadline-s", &limits.deadline.as_secs_f64().to_string()])
            .env("RAYON_NUM_THREADS", "1")
            .env("RUST_BACKTRACE", "0")
            .process_group(0)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .map_err(|e| format!("cannot start a worker: {e}"))?;
        let stdin = child.stdin.take().ok_or("no worker stdin")?;
        let stdout = child.stdout.take().ok_or("no worker stdout")?;
        let mut stderr_pipe = child.stderr.take().ok_or("no worker stderr")?;
        let (tx, rx): (Sender<String>, Receiver<String>) = channel();
        std::thread::spawn(move || {
            for line in BufReader::new(stdout).lines() {
                match line {
                    Ok(l) => {
                        if tx.send(l).is_err() {
                            break;
                        }
                    }
                    Err(_) => break,
                }
            }
        });
        let stderr = Arc::new(Mutex::new(String::new()));
        let keep = Arc::clone(&stderr);
        std::thread::spawn(move || {
            let mut buf = [0u8; 4096];
            while let Ok(n) = stderr_pipe.read(&mut buf) {
                if n == 0 {
                    break;
                }
                if let Ok(mut s) = keep.lock() {
                    s.push_str(&String::from_utf8_lossy(&buf[..n]));
                    if s.len() > 8192 {
                        let cut = s.len() - 4096;
                        let cut = (cut..s.len()).find(|&i| s.is_char_boundary(i)).unwrap_or(s.len());
                        s.drain(..cut);
                    }
                }
            }
        });
        Ok(Worker { child, stdin, lines: rx, stderr })
    }

    /// Kills the worker's process group (the worker and any `morgana` it started) and reaps
    /// the worker.
    fn kill(&mut self) {
        self.kill_group();
        let _ = self.child.kill();
        let _ = self.child.wait();
    }

    /// Sends SIGKILL to the worker's process group. Only while the worker is not yet reaped:
    /// its pid is the group's id.
    fn kill_group(&self) {
        // kill(2) on the negated group id, never on 0 or −1 (the caller's group, or every
        // process). Not the `kill` program: procps-ng 4.0.2 took `kill -KILL -PGID` as a kill
        // of every process the user may signal.
        let Ok(pgid) = libc::pid_t::try_from(self.child.id()) else { return };
        if pgid > 1 {
            // SAFETY: kill(2) takes plain integers and touches no memory of this process.
            unsafe {
                libc::kill(-pgid, libc::SIGKILL);
            }
        }
    }

    fn stderr_tail(&self) -> String {
        let s = self.stderr.lock().map(|s| s.clone()).unwrap_or_default();
        s.lines()
            .rev()
            .filter(|l| !l.trim().is_empty())
            .take(2)
            .collect::<Vec<_>>()
            .into_iter()
            .rev()
            .collect::<Vec<_>>()
            .join(" | ")
    }
}

fn parse_line(line: &str) -> Option<Record> {
    let mut f = line.splitn(5, '\t');
    let id = f.next()?.to_string();
    let class = Class::parse(f.next()?)?;
    let micros = f.next()?.parse().ok()?;
    let what = f.next()?.to_string();
    let message = f.next().unwrap_or("").to_string();
    Some(Record { id, outcome: Outcome::new(class, message), what, micros })
}

/// Runs `items` (case indices as text, or `@path mode`) on `jobs` workers; every record is
/// sent to `results` as it comes.
pub fn run(
    target: Target,
    seed: u64,
    items: Vec<String>,
    jobs: usize,
    limits: &Limits,
    results: Sender<Record>,
) -> Result<(), String> {
    std::fs::create_dir_all(&limits.scratch).map_err(|e| format!("{}: {e}", limits.scratch.display()))?;
    let jobs = jobs.max(1);
    let mut shares: Vec<Vec<String>> = vec![Vec::new(); jobs];
    for (i, it) in items.into_iter().enumerate() {
        shares[i % jobs].push(it);
    }
    let handles: Vec<_> = shares
        .into_iter()
        .map(|share| {
            let (limits, results) = (limits.clone(), results.clone());
            std::thread::spawn(move || drive(target, seed, share, &limits, &results))
        })
        .collect();
    drop(results);
    for h in handles {
        h.join().map_err(|_| "a supervisor thread panicked".to_string())??;
    }
    Ok(())
}

/// One worker's share: hands out items one by one, restarting the worker after a crash or a
/// hang.
fn drive(
    target: Target,
    seed: u64,
    items: Vec<String>,
    limits: &Limits,
    results: &Sender<Record>,
) -> Result<(), String> {
    let mut worker: Option<Worker> = None;
    let wait = limits.deadline + Duration::from_secs(3);
    for item in items {
        if worker.is_none() {
            worker = Some(Worker::start(target, seed, limits)?);
        }
        let w = worker.as_mut().expect("a worker");
        let sent = writeln!(w.stdin, "{item}").and_then(|()| w.stdin.flush());
        let got = if sent.is_ok() { w.lines.recv_timeout(wait) } else { Err(RecvTimeoutError::Disconnected) };
        let record = match got {
            Ok(line) => parse_line(&line).unwrap_or_else(|| Record {
                id: item.clone(),
                outcome: Outcome::new(Class::Internal, format!("harness: unreadable worker line {line:?}")),
                what: String::new(),
                micros: 0,
            }),
            Err(RecvTimeoutError::Timeout) => {
                let mut w = worker.take().expect("a worker");
                w.kill();
                Record {
                    id: item.clone(),
                    outcome: Outcome::new(Class::Timeout, format!("no answer within {:.0} s", wait.as_secs_f64())),
                    what: String::new(),
                    micros: wait.as_micros() as u64,
                }
            }
            Err(RecvTimeoutError::Disconnected) => {
                let mut w = worker.take().expect("a worker");
                // Kill what the worker started before reaping it: until it is reaped its pid
                // (the group's id) cannot be given to another process, which a group kill
                // after the reaping could hit.
                w.kill_group();
                let status = w.child.wait().ok();
                // Give the stderr reader a moment to take the last words.
                std::thread::sleep(Duration::from_millis(50));
                let tail = w.stderr_tail();
                let how = match status {
                    Some(s) => {
                        use std::os::unix::process::ExitStatusExt;
                        match (s.code(), s.signal()) {
                            (_, Some(sig)) => format!("signal {sig}"),
                            (Some(c), _) => format!("exit {c}"),
                            _ => "ended".into(),
                        }
                    }
                    None => "ended".into(),
                };
                if tail.contains("harness:") || tail.contains("worker:") {
                    return Err(format!("the worker failed: {tail}"));
                }
                Record {
                    id: item.clone(),
                    outcome: Outcome::new(Class::Crash, format!("worker {how}: {tail}")),
                    what: String::new(),
                    micros: 0,
                }
            }
        };
        if results.send(record).is_err() {
            break;
        }
    }
    if let Some(mut w) = worker {
        drop(w.stdin);
        let _ = w.child.wait();
    }
    Ok(())
}
