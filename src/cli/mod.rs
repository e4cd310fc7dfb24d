//! The `morgana` commands, one file each: what a subcommand reads from its arguments, which
//! library calls it makes, and what it prints. `main.rs` only parses the command line, calls
//! the subcommand's `run` (e.g. [`render::run`]) and turns errors into exit codes (0 success,
//! 2 bad input, 1 internal failure).
//!
//! This is the top layer: a command may use any module of the library; nothing in the library
//! uses a command.

pub mod accuracy;
pub mod check;
pub mod colour_check;
pub mod grid;
pub mod luminaire;
pub mod refraction;
pub mod render;
pub mod sun_sweep;
pub mod tonemap;
pub mod trace;

use crate::error::{Error, Result};
use crate::scene::{Scene, default_scene, load_scene_file};
use std::path::Path;

/// Checks, before any work, that the output file `path` given by `flag` can be written: it
/// names a file (not `..` or `dir/`), not an existing directory, its name fits the file system
/// (at most [`crate::output::MAX_DIRECTORY_NAME_BYTES`] bytes), and its directory exists and
/// takes a new file. Errors are input errors naming the flag and the path (exit code 2), so no
/// work is thrown away at the end.
pub fn check_output_file(flag: &str, path: &Path) -> Result<()> {
    let bad = |why: String| Error::input(None, format!("{flag} {}: {why}", path.display()));
    let names_a_dir = path.as_os_str().to_string_lossy().ends_with('/');
    let Some(name) = path.file_name().filter(|_| !names_a_dir) else {
        return Err(bad("does not name a file; give a file path such as out/result.png".into()));
    };
    let max = crate::output::MAX_DIRECTORY_NAME_BYTES;
    if name.len() > max {
        return Err(bad(format!("the file name is {} bytes long; file systems allow {max}", name.len())));
    }
    if path.is_dir() {
        return Err(bad("is a directory; give a file path inside it".into()));
    }
    // Missing directories are created when the file is written: check the nearest one that
    // exists (it must be a directory, and writable).
    let mut dir = path.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
    while !dir.exists() {
        dir = dir.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
    }
    if !dir.is_dir() {
        return Err(bad(format!("{} is not a directory", dir.display())));
    }
    let probe = crate::atomic::Staged::new(&dir.join(".morgana-write-check"))
        .map_err(|e| bad(format!("cannot write in {}: {e}", dir.display())))?;
    drop(probe);
    Ok(())
}

/// A comma-separated vector of three finite numbers, `x,y,z` (clap's value parser for points
/// and directions).
pub fn parse_vec3(s: &str) -> std::result::Result<[f64; 3], String> {
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

/// The scene at `path`, or the embedded default scene; its warnings are printed on stderr.
pub fn load(path: Option<&Path>) -> Result<Scene> {
    let scene = match path {
        Some(p) => load_scene_file(p),
        None => default_scene(),
    }?;
    print_warnings(&scene);
    Ok(scene)
}

/// Prints a scene's warnings (things that do not stop a run) on stderr.
pub fn print_warnings(scene: &Scene) {
    for w in &scene.warnings {
        eprintln!("morgana: note: {w}");
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vectors_need_three_finite_numbers() {
        assert_eq!(parse_vec3("1, -2,3e2"), Ok([1.0, -2.0, 300.0]));
        assert!(parse_vec3("1,2").is_err());
        assert!(parse_vec3("1,2,3,4").is_err());
        assert!(parse_vec3("1,nan,3").is_err());
        assert!(parse_vec3("1,inf,3").is_err());
        assert!(parse_vec3("1,x,3").is_err());
    }
}
