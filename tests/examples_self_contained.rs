//! Every example renders from a plain clone: each file an example names (meshes, luminaires,
//! spectra, atmospheres and their profiles, grids, phase tables, ocean data folders, …) exists
//! inside this repository — not in `../shared`, not anywhere else — and every example loads.
//!
//! The walk reads the TOML itself: every string under a key `file` or `data_dir`, and under
//! `profile` where it names a `.csv`, is a path relative to the file it appears in; a referenced
//! `.toml` (an atmosphere) is walked in turn.

use std::path::{Path, PathBuf};

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).canonicalize().expect("the repository folder")
}

fn examples() -> Vec<PathBuf> {
    let dir = repo().join("examples");
    let mut out: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("cannot list {}: {e}", dir.display()))
        .map(|e| e.expect("a directory entry").path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    out.sort();
    out
}

/// (key path, referenced path as written) for every file reference in a TOML value.
fn references(v: &toml::Value, at: &str, out: &mut Vec<(String, String)>) {
    match v {
        toml::Value::Table(t) => {
            for (k, x) in t {
                let here = if at.is_empty() { k.clone() } else { format!("{at}.{k}") };
                match (k.as_str(), x) {
                    ("file" | "data_dir", toml::Value::String(s)) => out.push((here, s.clone())),
                    ("profile", toml::Value::String(s)) if s.ends_with(".csv") => out.push((here, s.clone())),
                    _ => references(x, &here, out),
                }
            }
        }
        toml::Value::Array(a) => {
            for (i, x) in a.iter().enumerate() {
                references(x, &format!("{at}[{i}]"), out);
            }
        }
        _ => {}
    }
}

/// Problems with the files `toml_path` names (recursively); `seen` counts the references.
fn check_file(toml_path: &Path, root: &Path, seen: &mut usize, problems: &mut Vec<String>) {
    let text =
        std::fs::read_to_string(toml_path).unwrap_or_else(|e| panic!("cannot read {}: {e}", toml_path.display()));
    let value: toml::Value = toml::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", toml_path.display()));
    let mut refs = Vec::new();
    references(&value, "", &mut refs);
    let dir = toml_path.parent().expect("a file has a folder");
    for (key, written) in refs {
        *seen += 1;
        let what = format!("{}: {key} = \"{written}\"", toml_path.strip_prefix(root).unwrap_or(toml_path).display());
        if written.contains("shared/") {
            problems.push(format!("{what}: names the project's shared data, which a clone does not have"));
            continue;
        }
        let Ok(target) = dir.join(&written).canonicalize() else {
            problems.push(format!("{what}: does not exist"));
            continue;
        };
        if !target.starts_with(root) {
            problems.push(format!("{what}: resolves to {}, outside the repository", target.display()));
        } else if target.extension().is_some_and(|x| x == "toml") {
            check_file(&target, root, seen, problems);
        }
    }
}

#[test]
fn every_file_an_example_names_is_inside_the_repository() {
    let root = repo();
    let (mut seen, mut problems) = (0, Vec::new());
    let list = examples();
    assert!(list.len() >= 20, "only {} examples found", list.len());
    for path in &list {
        check_file(path, &root, &mut seen, &mut problems);
    }
    assert!(problems.is_empty(), "examples name files a plain clone lacks:\n{}", problems.join("\n"));
    // The walk found the references it should (a mesh, luminaires, spectra, atmospheres, a profile).
    assert!(seen >= 10, "only {seen} file references found: the walk is missing keys");
}

#[test]
fn the_walk_catches_shared_missing_and_outside_paths() {
    let root = repo();
    let dir = std::env::temp_dir().join(format!("morgana_examples_walk_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let scene = dir.join("bad.toml");
    let text = "[[shape]]\nfile = \"../../shared/data/x.obj\"\n[[light]]\nfile = \"missing.ies\"\n\
                [[medium]]\ndata_dir = \".\"\nphase = { type = \"tabulated\", file = \"bad.toml\" }\n";
    std::fs::write(&scene, text).unwrap();
    let (mut seen, mut problems) = (0, Vec::new());
    check_file(&scene, &root, &mut seen, &mut problems);
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(seen, 4, "{problems:?}");
    let joined = problems.join("\n");
    assert!(joined.contains("x.obj\": names the project's shared data"), "{joined}");
    assert!(joined.contains("missing.ies\": does not exist"), "{joined}");
    assert!(joined.contains("data_dir = \".\": resolves to") && joined.contains("outside the repository"), "{joined}");
}

/// Loading resolves every file against the example's own folder, whatever the working
/// directory: run from a temporary folder, as after `cargo install` from anywhere.
#[test]
fn every_example_loads_from_any_working_directory() {
    let list = examples();
    let elsewhere = std::env::temp_dir();
    let failures: Vec<String> = list
        .iter()
        .filter_map(|path| {
            let out = std::process::Command::new(env!("CARGO_BIN_EXE_morgana"))
                .arg("check")
                .arg(path)
                .current_dir(&elsewhere)
                .output()
                .expect("run morgana check");
            (!out.status.success())
                .then(|| format!("{}: {}", path.display(), String::from_utf8_lossy(&out.stderr).trim()))
        })
        .collect();
    assert!(failures.is_empty(), "examples that do not load:\n{}", failures.join("\n"));
}
