//! Tests that read the project's shared data (`../shared/data/…`, beside the repository: the
//! real manufacturers' luminaire files and the reference copies of the ocean tables) call
//! [`shared_data`] first. Where the folder is missing the test skips:
//! - it prints `MORGANA-SKIP <test>: ../shared/data/<sub> is missing` to stderr;
//! - it appends that line to the file named by `MORGANA_SKIP_LOG`, if set (`scripts/test` sets it
//!   and prints one line counting them);
//! - with `MORGANA_REQUIRE_SHARED=1` (CI, `.ci/run`) a missing folder fails the test instead.
#![allow(dead_code)]

use std::io::Write;
use std::path::PathBuf;

/// The marker that starts every skip line.
pub const SKIP_MARKER: &str = "MORGANA-SKIP";

/// `../shared/data/<sub>` if it exists; `None` (after logging the skip) if not.
pub fn shared_data(sub: &str) -> Option<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../shared/data").join(sub);
    if dir.is_dir() {
        return Some(dir);
    }
    let test = std::thread::current().name().unwrap_or("?").to_string();
    let line = format!("{SKIP_MARKER} {test}: ../shared/data/{sub} is missing");
    if std::env::var("MORGANA_REQUIRE_SHARED").is_ok_and(|v| v == "1") {
        panic!("{line}, and MORGANA_REQUIRE_SHARED=1 forbids skipping (put the shared data beside the repository)");
    }
    eprintln!("{line}");
    if let Some(log) = std::env::var_os("MORGANA_SKIP_LOG") {
        let written = std::fs::OpenOptions::new()
            .create(true)
            .append(true)
            .open(&log)
            .and_then(|mut f| f.write_all(format!("{line}\n").as_bytes()));
        if let Err(e) = written {
            panic!("cannot append to MORGANA_SKIP_LOG {}: {e}", PathBuf::from(log).display());
        }
    }
    None
}
