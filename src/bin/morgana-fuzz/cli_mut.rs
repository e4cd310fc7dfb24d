//! The command-line target: valid `morgana` command lines over small fixtures (a 4×4 scene, a
//! 4×3 spectral EXR, the repository's luminaires and atmospheres), mutated (a flag's value
//! set to an extreme or junk, a flag deleted, duplicated or added, arguments swapped, the
//! subcommand changed, non-UTF-8 bytes) and run as the real binary under a deadline.

use crate::outcome::{Class, Outcome, has_non_finite_word, locates, names_argument};
use crate::targets::Case;
use crate::text_mut::{clip, extreme_number};
use crate::workspace::{Workspace, non_finite_in};
use rand::Rng;
use rand_pcg::Pcg64;
use std::ffi::OsString;
use std::io::Read;
use std::os::unix::ffi::{OsStrExt, OsStringExt};
use std::path::PathBuf;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Valid command lines the mutations start from (paths relative to the case directory).
const BASES: &[&[&str]] = &[
    &["check", "s.toml"],
    &["check", "s.toml", "--out", "out"],
    &["render", "s.toml", "--out", "out", "--photons", "500", "--quiet", "--threads", "1"],
    &["render", "s.toml", "--out", "out", "--seed", "3", "--quiet", "--threads", "2", "--schedule", "static"],
    &["grid", "--out", "g.mgrid", "--res", "8", "--octaves", "2"],
    &[
        "grid",
        "--out",
        "g.mgrid",
        "--res",
        "4",
        "--min",
        "-1,-1,-1",
        "--max",
        "1,1,1",
        "--base",
        "0.5",
        "--amplitude",
        "0.5",
        "--frequency-per-m",
        "2",
        "--seed",
        "7",
    ],
    &["tonemap", "a.exr", "--out", "a.png"],
    &["tonemap", "a.exr", "--out", "a.png", "--region", "0,0,2,2", "--csv", "r.csv", "--operator", "reinhard"],
    &[
        "tonemap",
        "a.exr",
        "--out",
        "a.png",
        "--operator",
        "pattanaik",
        "--adaptation-time-s",
        "1",
        "--adapt-from-cd-m2",
        "10",
        "--scotopic",
        "auto",
    ],
    &[
        "tonemap",
        "a.exr",
        "--out",
        "a.png",
        "--exposure",
        "-1",
        "--adapt-to",
        "0.31,0.33",
        "--cat",
        "bradford",
        "--adaptation-degree",
        "0.5",
        "--fov-deg",
        "30",
    ],
    &["luminaire", "../luminaires/road_batwing.ies", "--png", "p.png"],
    &["luminaire", "../luminaires/office_pendant.ldt"],
    &["accuracy", "--quick", "--k", "0.001", "--length-m", "100"],
    &["accuracy", "--quick", "--field", "usa76", "--elevation-deg", "1", "--length-m", "20000"],
    &["refraction", "--atmosphere", "usa76", "--apparent-altitudes-deg", "0,5", "--wavelength-nm", "550"],
    &[
        "refraction",
        "--atmosphere",
        "../atmospheres/hot_road.toml",
        "--observer-height-m",
        "1.5",
        "--apparent-altitudes-deg",
        "0",
        "--wavelengths-nm",
        "450,650",
        "--csv",
        "r.csv",
    ],
    &["trace", "s.toml", "--from", "0,1,3", "--dir", "0,0,-1"],
    &[
        "trace",
        "s.toml",
        "--from",
        "0,1,3",
        "--toward",
        "0,0,0",
        "--events",
        "4",
        "--max-length-m",
        "100",
        "--csv",
        "t.csv",
        "--wavelength-nm",
        "500",
    ],
];

/// Every long flag of every subcommand, for insertions.
const FLAGS: &[&str] = &[
    "--out",
    "--photons",
    "--seed",
    "--threads",
    "--quiet",
    "--max-map-memory",
    "--schedule",
    "--res",
    "--min",
    "--max",
    "--base",
    "--amplitude",
    "--frequency-per-m",
    "--octaves",
    "--operator",
    "--exposure",
    "--adapt-to",
    "--cat",
    "--adaptation-degree",
    "--adaptation-time-s",
    "--adapt-from-cd-m2",
    "--scotopic",
    "--false-colour",
    "--fov-deg",
    "--region",
    "--csv",
    "--png",
    "--variant",
    "--field",
    "--k",
    "--length-m",
    "--quick",
    "--project",
    "--atmosphere",
    "--wavelength-nm",
    "--apparent-altitudes-deg",
    "--observer-height-m",
    "--wavelengths-nm",
    "--from",
    "--toward",
    "--dir",
    "--events",
    "--max-length-m",
    "--help",
    "--version",
    "--nonexistent-flag",
];

const SUBCOMMANDS: &[&str] =
    &["render", "grid", "tonemap", "check", "luminaire", "accuracy", "refraction", "trace", "help", "x"];

/// A value for a flag: an extreme number, a vector of them, a path, junk.
fn value(rng: &mut Pcg64) -> OsString {
    match rng.random_range(0..12) {
        0..=4 => extreme_number(rng).into(),
        5 => format!("{},{},{}", extreme_number(rng), extreme_number(rng), extreme_number(rng)).into(),
        6 => ["", " ", "x", "1,2", "1,,2", "0,0,0,0", "1e", "--", "-", "=", "auto", "none"][rng.random_range(0..12)]
            .into(),
        // Paths stay inside the scratch tree: never /dev or another system path, which a
        // command run as root could replace.
        7 => [
            "out",
            "s.toml",
            "a.exr",
            "sub/dir/x.png",
            "../nonexistent/x",
            ".",
            "..",
            "meshes",
            "meshes/prism.obj",
            "nonexistent.toml",
            "a.png",
            "out/",
        ][rng.random_range(0..12)]
        .into(),
        8 => "x".repeat([300, 5000, 100_000][rng.random_range(0..3)]).into(),
        9 => OsString::from_vec(vec![b'a', 0xFF, 0xFE, b'b']),
        10 => ["1G", "0", "1K", "18446744073709551615", "8E", "-1M"][rng.random_range(0..6)].into(),
        _ => "é日本😀".into(),
    }
}

/// Case: a base command line with one to four mutations.
pub fn case(rng: &mut Pcg64) -> Case {
    let base = BASES[rng.random_range(0..BASES.len())];
    let mut args: Vec<OsString> = base.iter().map(OsString::from).collect();
    let mut what = vec![base.join(" ")];
    let n = match rng.random_range(0..100) {
        0..=59 => 1,
        60..=84 => 2,
        _ => rng.random_range(3..5),
    };
    for _ in 0..n {
        let len = args.len();
        if len == 0 {
            break;
        }
        let i = rng.random_range(0..len);
        match rng.random_range(0..10) {
            0..=3 => {
                // A flag's value (or a positional argument) replaced.
                let k =
                    if i + 1 < len && args[i].as_bytes().starts_with(b"--") { i + 1 } else { i.max(1).min(len - 1) };
                let v = value(rng);
                what.push(format!("arg {k} = {}", clip(&v.to_string_lossy())));
                args[k] = v;
            }
            4 => {
                let removed = args.remove(i.max(1).min(len - 1));
                what.push(format!("remove {}", removed.to_string_lossy()));
            }
            5 => {
                let a = args[i].clone();
                args.insert(i, a.clone());
                what.push(format!("duplicate {}", a.to_string_lossy()));
            }
            6 | 7 => {
                let f = FLAGS[rng.random_range(0..FLAGS.len())];
                let v = value(rng);
                let at = rng.random_range(1..=len);
                if rng.random_bool(0.3) {
                    let mut joined = OsString::from(format!("{f}="));
                    joined.push(&v);
                    args.insert(at, joined);
                } else {
                    args.insert(at, v.clone());
                    args.insert(at, f.into());
                }
                what.push(format!("insert {f} {}", clip(&v.to_string_lossy())));
            }
            8 => {
                let j = rng.random_range(0..len);
                args.swap(i, j);
                what.push(format!("swap args {i} and {j}"));
            }
            _ => {
                let s = SUBCOMMANDS[rng.random_range(0..SUBCOMMANDS.len())];
                args[0] = s.into();
                what.push(format!("subcommand {s}"));
            }
        }
    }
    keep_bounded(&mut args, &mut what);
    Case { files: Vec::new(), args, what: what.join("; "), mode: 0 }
}

/// Work that is long by design, not a hang, is kept short: `render` without a scene file renders
/// the embedded default scene (minutes), `accuracy` without `--quick` runs the full study, and a
/// grid of `--res` 65 to 1024 (the documented range) takes up to minutes to fill. Such a command
/// gets `s.toml`, `--quick` or `--res 64`; extreme and invalid values are left as they are.
fn keep_bounded(args: &mut Vec<OsString>, what: &mut Vec<String>) {
    let sub = args.first().map(|a| a.to_string_lossy().into_owned()).unwrap_or_default();
    let has = |args: &[OsString], f: &dyn Fn(&str) -> bool| args.iter().any(|a| f(&a.to_string_lossy()));
    if sub == "render" && !has(args, &|a| a.ends_with(".toml")) {
        args.insert(1, "s.toml".into());
        what.push("(bounded: render s.toml)".into());
    }
    if sub == "accuracy" && !has(args, &|a| a == "--quick") {
        args.push("--quick".into());
        what.push("(bounded: --quick)".into());
    }
    for i in 1..args.len() {
        let res = args[i - 1] == "--res"
            && args[i].to_str().and_then(|v| v.parse::<u64>().ok()).is_some_and(|r| (65..=1024).contains(&r));
        if res {
            args[i] = "64".into();
            what.push("(bounded: --res 64)".into());
        }
    }
}

/// The case of a corpus file: one argument per line.
pub fn case_of_args_file(bytes: &[u8]) -> Case {
    let body = bytes.strip_suffix(b"\n").unwrap_or(bytes);
    let args: Vec<OsString> = body.split(|&b| b == b'\n').map(|l| OsString::from_vec(l.to_vec())).collect();
    Case { files: Vec::new(), what: format!("{args:?}"), args, mode: 0 }
}

/// The bytes of a corpus file for `args`.
pub fn args_file(args: &[OsString]) -> Vec<u8> {
    let mut out = Vec::new();
    for a in args {
        out.extend_from_slice(a.as_bytes());
        out.push(b'\n');
    }
    out
}

/// The `morgana` binary: `MORGANA_BIN`, else beside this one.
pub fn morgana_bin() -> PathBuf {
    if let Some(p) = std::env::var_os("MORGANA_BIN") {
        return PathBuf::from(p);
    }
    let me = std::env::current_exe().unwrap_or_default();
    me.with_file_name("morgana")
}

/// Runs `morgana` with the case's arguments in the case directory and judges the result.
pub fn run(ws: &Workspace, case: &Case, read: &[String], deadline: Duration) -> Outcome {
    let mut child = match Command::new(morgana_bin())
        .args(&case.args)
        .current_dir(&ws.case)
        .env("RAYON_NUM_THREADS", "2")
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
    {
        Ok(c) => c,
        Err(e) => {
            return Outcome::new(Class::Internal, format!("harness: cannot start {}: {e}", morgana_bin().display()));
        }
    };
    let (mut so, mut se) = (child.stdout.take().expect("stdout"), child.stderr.take().expect("stderr"));
    let out_t = std::thread::spawn(move || {
        let mut b = Vec::new();
        let _ = so.read_to_end(&mut b);
        b
    });
    let err_t = std::thread::spawn(move || {
        let mut b = Vec::new();
        let _ = se.read_to_end(&mut b);
        b
    });
    let start = Instant::now();
    let mut pause = Duration::from_micros(200);
    let status = loop {
        match child.try_wait() {
            Ok(Some(s)) => break Some(s),
            Ok(None) if start.elapsed() > deadline => {
                let _ = child.kill();
                let _ = child.wait();
                break None;
            }
            Ok(None) => {
                std::thread::sleep(pause);
                pause = (pause * 2).min(Duration::from_millis(10));
            }
            Err(_) => break None,
        }
    };
    let stdout = String::from_utf8_lossy(&out_t.join().unwrap_or_default()).into_owned();
    let stderr = String::from_utf8_lossy(&err_t.join().unwrap_or_default()).into_owned();
    let Some(status) = status else {
        return Outcome::new(Class::Timeout, format!("no exit after {:.1} s", deadline.as_secs_f64()));
    };
    let last = stderr.lines().rev().find(|l| !l.trim().is_empty()).unwrap_or("").to_string();
    if stderr.contains("panicked") {
        let p = stderr.lines().find(|l| l.contains("panicked")).unwrap_or("");
        let next = stderr.lines().skip_while(|l| !l.contains("panicked")).nth(1).unwrap_or("");
        return Outcome::new(Class::Panic, format!("{p} {next}"));
    }
    let mut files: Vec<String> = read.to_vec();
    files.extend(ws.fixtures.iter().map(|(n, _)| n.clone()));
    for a in &case.args {
        let s = a.to_string_lossy();
        if let Some(name) = std::path::Path::new(s.as_ref()).file_name() {
            files.push(name.to_string_lossy().into_owned());
        }
    }
    files.retain(|f| f.len() > 2);
    match status.code() {
        Some(0) => {
            // An output may be named "inf": arguments echoed are not numbers the command made.
            let mut stdout = stdout;
            // `--csv=nan` echoes as `nan`. Longest first: removing an argument "0" first would
            // cut the zeros out of a longer one ("0,180,+inf") and leave its "+inf" standing.
            let args: Vec<String> = case.args.iter().map(|a| a.to_string_lossy().into_owned()).collect();
            let mut texts: Vec<&str> =
                args.iter().flat_map(|a| [a.as_str(), a.split_once('=').map_or("", |(_, v)| v)]).collect();
            texts.retain(|t| !t.is_empty());
            texts.sort_by_key(|t| std::cmp::Reverse(t.len()));
            for text in texts {
                stdout = stdout.replace(text, "");
            }
            if has_non_finite_word(&stdout) {
                let l = stdout.lines().find(|l| has_non_finite_word(l)).unwrap_or("");
                return Outcome::new(Class::NonFinite, format!("stdout: {l}"));
            }
            for p in new_outputs(ws) {
                // An output may repeat a path given on the command line ("nan/s.exr").
                if let Some(m) = non_finite_in(&p).filter(|m| !echoes_an_argument(m, &case.args)) {
                    return Outcome::new(Class::NonFinite, m);
                }
            }
            Outcome::ok()
        }
        Some(2) => {
            let args: Vec<String> = case.args.iter().map(|a| a.to_string_lossy().into_owned()).collect();
            let located = locates(&stderr, &files, true) || names_argument(&stderr, &args);
            let class = if located { Class::InputLocated } else { Class::InputUnlocated };
            Outcome::new(
                class,
                stderr.trim().lines().next().unwrap_or("").to_string()
                    + if stderr.lines().count() > 1 { " …" } else { "" },
            )
        }
        Some(1) => Outcome::new(Class::Internal, last),
        Some(c) => Outcome::new(Class::Crash, format!("exit code {c}: {last}")),
        None => {
            use std::os::unix::process::ExitStatusExt;
            Outcome::new(Class::Crash, format!("signal {:?}: {last}", status.signal()))
        }
    }
}

/// Whether a non-finite finding's line (`file:line: text`) holds its non-finite word only inside
/// an argument of the command line, echoed.
fn echoes_an_argument(finding: &str, args: &[OsString]) -> bool {
    let mut text = finding.splitn(3, ':').nth(2).unwrap_or(finding).to_string();
    let mut args: Vec<String> =
        args.iter().map(|a| a.to_string_lossy().into_owned()).filter(|a| !a.is_empty()).collect();
    // Longest first, as for standard output.
    args.sort_by_key(|a| std::cmp::Reverse(a.len()));
    for a in &args {
        text = text.replace(a.as_str(), "");
    }
    !has_non_finite_word(&text)
}

/// Output files under the case directory (CSV, JSON, EXR) written by the command.
fn new_outputs(ws: &Workspace) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![ws.case.clone()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).into_iter().flatten().flatten() {
            let p = e.path();
            if p.is_dir() {
                if p.file_name().is_some_and(|n| n != "meshes") {
                    stack.push(p);
                }
            } else if p.extension().is_some_and(|x| x == "csv" || x == "json" || x == "exr")
                && !p.file_name().is_some_and(|n| n == "tropical_afgl1986.csv" || n == "a.exr")
            {
                out.push(p);
            }
        }
    }
    out
}
