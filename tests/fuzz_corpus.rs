//! The fuzzer's regression corpus (`tests/fuzz_corpus/<target>/`): every input that once gave a
//! disallowed outcome (a panic, a hang, an unlocated error, a file left behind, a NaN in an
//! output), minimised by `morgana-fuzz minimize`. Each file is replayed through `morgana-fuzz
//! replay` in every way its target reads it, and each outcome must be allowed: success, or exit
//! code 2 with a message naming the file and line (or element, byte, flag). A file is named after
//! what broke; the book's "Robustness" chapter says how to add one.
//!
//! Also a check that the harness's verdicts can fail. The CI smoke run (1,000 cases per target)
//! is `scripts/test`'s "fuzz smoke" step, the long run `scripts/fuzz.sh`.

use std::path::{Path, PathBuf};
use std::process::Command;

fn fuzz() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_morgana-fuzz"));
    c.env("MORGANA_BIN", env!("CARGO_BIN_EXE_morgana"));
    c
}

fn corpus() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fuzz_corpus")
}

fn files_of(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.expect("a directory entry").path())
        .filter(|p| p.is_file() && p.file_name().is_none_or(|n| n != "README.md"))
        .collect();
    v.sort();
    v
}

fn scratch(tag: &str) -> PathBuf {
    std::env::temp_dir().join(format!("morgana-fuzz-test-{tag}-{}", std::process::id()))
}

#[test]
fn every_corpus_file_has_an_allowed_outcome() {
    let mut targets: Vec<PathBuf> =
        std::fs::read_dir(corpus()).expect("tests/fuzz_corpus").map(|e| e.expect("entry").path()).collect();
    targets.retain(|p| p.is_dir());
    targets.sort();
    assert!(!targets.is_empty(), "tests/fuzz_corpus holds no target folder");
    let mut failures = Vec::new();
    let mut replayed = 0;
    for dir in targets {
        let target = dir.file_name().expect("a name").to_string_lossy().into_owned();
        let files = files_of(&dir);
        assert!(!files.is_empty(), "{} is empty", dir.display());
        replayed += files.len();
        let out = fuzz()
            .args(["replay", "--target", &target, "--deadline-s", "20", "--scratch"])
            .arg(scratch(&target))
            .args(&files)
            .output()
            .expect("run morgana-fuzz");
        let text = String::from_utf8_lossy(&out.stdout);
        if !out.status.success() {
            failures.push(format!("{target}: {}\n{text}{}", out.status, String::from_utf8_lossy(&out.stderr)));
        }
    }
    assert!(failures.is_empty(), "corpus files with a disallowed outcome:\n{}", failures.join("\n"));
    assert!(replayed >= 8, "only {replayed} corpus files");
}

/// The verdicts can fail: a case that panics, and one that hangs, make `replay` exit 1 with
/// the outcome named (`MORGANA_FUZZ_SELFTEST` makes the worker do so in place of the case; the
/// fuzzer's unit tests check how messages are judged).
#[test]
fn replay_fails_on_a_panic_and_on_a_hang() {
    let dir = scratch("selftest");
    std::fs::create_dir_all(&dir).expect("scratch");
    let path = dir.join("temperature.mfield");
    std::fs::write(&path, "MORGANA-FIELD 1\n").expect("write");
    for (mode, class) in [("", "input-error-located"), ("panic", "panic"), ("hang", "timeout")] {
        let out = fuzz()
            .env("MORGANA_FUZZ_SELFTEST", mode)
            .args(["replay", "--target", "grid", "--deadline-s", "0.5", "--scratch"])
            .arg(dir.join(mode))
            .arg(&path)
            .output()
            .expect("run morgana-fuzz");
        let text = String::from_utf8_lossy(&out.stdout);
        assert_eq!(out.status.success(), mode.is_empty(), "{mode:?}: {text}");
        assert!(text.contains(&format!("\t{class}\t")), "{mode:?}: {text}");
        // The first run's --scratch is the input's own folder: the run removes only what it made.
        assert!(path.exists(), "{mode:?}: the replay removed {} from its --scratch folder", path.display());
    }
    std::fs::remove_dir_all(&dir).ok();
}
