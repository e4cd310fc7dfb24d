//! One scene on every rank: rank 0 reads the scene file and broadcasts its text; every rank
//! validates that same text and then checks that it resolved the same files.
//!
//! Rank 0 sends the file name as given, its own working directory and the text. Every rank
//! loads the text with the scene's directory (relative to rank 0's working directory when its
//! own differs, e.g. on another host), applies the command line's overrides, and fingerprints
//! what it rendered from: the morgana version, the text, the overrides and the bytes of every
//! file the scene names ([`referenced_files`]). The fingerprints are gathered; a rank whose
//! files differ (a stale copy on one node) stops the run on every rank with an error naming the
//! rank, its host and the file, instead of rendering a silently wrong image. Errors while
//! loading on any rank end the run on every rank ([`super::fault::agree`]).
//!
//! On a cluster the scene's directory (with the files it names) must therefore be reachable at
//! the same path on every host: a shared file system, or identical copies.

use super::Comm;
use super::fault::agree;
use super::fingerprint::Fnv64;
use crate::error::{Error, Result};
use crate::scene::{DEFAULT_SCENE, Scene, load_scene_str};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// What rank 0 broadcasts.
#[derive(Serialize, Deserialize)]
struct SceneText {
    /// The scene file as given on the command line; `None` for the embedded default scene.
    file: Option<String>,
    /// Rank 0's working directory.
    cwd: String,
    text: String,
}

/// One rank's view of the files it loaded, for comparison.
#[derive(Serialize, Deserialize, Clone, PartialEq, Eq)]
struct Seen {
    /// Fingerprint of version, text and overrides.
    base: u64,
    /// (path, fingerprint of its bytes) for every referenced file, sorted by path.
    files: Vec<(String, u64)>,
}

/// Loads the scene on every rank (`path` matters on rank 0 only; `None` = the embedded default
/// scene) and applies the overrides. Collective; every rank gets the same scene or an error.
pub fn load(comm: &Comm, path: Option<&Path>, photons: Option<u64>, seed: Option<u64>) -> Result<Scene> {
    let payload = match comm.is_root() {
        true => read(path)
            .and_then(|t| serde_json::to_vec(&t).map_err(|e| Error::internal(format!("scene broadcast: {e}")))),
        false => Ok(Vec::new()),
    };
    // A read error on rank 0 ends every rank here, before the broadcast.
    let payload = agree(comm, payload)?;
    let bytes = comm.broadcast(payload);
    let text: SceneText = serde_json::from_slice(&bytes)
        .map_err(|e| Error::internal(format!("scene broadcast from rank 0 does not decode: {e}")))?;
    let loaded = build(&text, photons, seed);
    let scene = agree(comm, loaded)?;
    let seen = Seen { base: base_fingerprint(&text, photons, seed), files: file_fingerprints(&text) };
    let all = comm.all_gather_json(&seen);
    let hosts = comm.all_gather_json(&comm.host());
    agree(comm, compare(&all, &hosts).map_or(Ok(()), Err)).map(|()| scene)
}

fn read(path: Option<&Path>) -> Result<SceneText> {
    let cwd = std::env::current_dir().map(|p| p.display().to_string()).unwrap_or_default();
    match path {
        None => Ok(SceneText { file: None, cwd, text: DEFAULT_SCENE.to_string() }),
        Some(p) => {
            let text = crate::error::read_utf8(p, "scene file")?;
            Ok(SceneText { file: Some(p.display().to_string()), cwd, text })
        }
    }
}

/// The scene from the broadcast text, as [`crate::scene::load_scene_file`] builds it.
fn build(t: &SceneText, photons: Option<u64>, seed: Option<u64>) -> Result<Scene> {
    let mut scene = match &t.file {
        None => load_scene_str(&t.text, Path::new("<embedded default scene>"), Path::new("."), "default")?,
        Some(f) => {
            let file = Path::new(f);
            let stem = file.file_stem().and_then(|s| s.to_str()).unwrap_or("scene").to_string();
            let mut s = load_scene_str(&t.text, file, &scene_dir(t, file), &stem)?;
            s.file = Some(file.to_path_buf());
            s
        }
    };
    scene.apply_overrides(photons, seed);
    Ok(scene)
}

/// The directory the scene's relative paths resolve against, on this rank.
fn scene_dir(t: &SceneText, file: &Path) -> PathBuf {
    let dir = file.parent().map_or_else(|| PathBuf::from("."), Path::to_path_buf);
    let same_cwd = std::env::current_dir().is_ok_and(|c| c.display().to_string() == t.cwd);
    if same_cwd || dir.is_absolute() { dir } else { Path::new(&t.cwd).join(dir) }
}

fn base_fingerprint(t: &SceneText, photons: Option<u64>, seed: Option<u64>) -> u64 {
    let mut h = Fnv64::new();
    h.write(env!("CARGO_PKG_VERSION").as_bytes());
    h.write(t.text.as_bytes());
    h.write(format!("{photons:?} {seed:?}").as_bytes());
    h.finish()
}

fn file_fingerprints(t: &SceneText) -> Vec<(String, u64)> {
    let Some(f) = &t.file else { return Vec::new() };
    let dir = scene_dir(t, Path::new(f));
    let mut files: Vec<(String, u64)> = referenced_files(&t.text, &dir)
        .into_iter()
        .map(|(name, path)| {
            let hash = std::fs::read(&path).map_or(0, |b| Fnv64::of(&b));
            (name, hash)
        })
        .collect();
    files.sort();
    files
}

/// The files a scene names: every string value in the TOML (at any depth) that, resolved
/// against `dir`, is an existing file. (name as written, resolved path)
pub fn referenced_files(text: &str, dir: &Path) -> Vec<(String, PathBuf)> {
    let mut out = Vec::new();
    if let Ok(value) = toml::from_str::<toml::Value>(text) {
        collect_strings(&value, &mut |s| {
            let p = Path::new(s);
            let path = if p.is_absolute() { p.to_path_buf() } else { dir.join(p) };
            if !s.is_empty() && path.is_file() && !out.iter().any(|(n, _)| n == s) {
                out.push((s.to_string(), path));
            }
        });
    }
    out
}

fn collect_strings(v: &toml::Value, f: &mut dyn FnMut(&str)) {
    match v {
        toml::Value::String(s) => f(s),
        toml::Value::Array(a) => a.iter().for_each(|x| collect_strings(x, f)),
        toml::Value::Table(t) => t.values().for_each(|x| collect_strings(x, f)),
        _ => {}
    }
}

/// The first disagreement between rank 0's view and another rank's, as an error.
fn compare(all: &[Seen], hosts: &[String]) -> Option<Error> {
    let (first, rest) = all.split_first()?;
    let (r, other) = rest.iter().enumerate().map(|(i, s)| (i + 1, s)).find(|(_, s)| *s != first)?;
    let host = |i: usize| hosts.get(i).map_or("?", String::as_str);
    let what = if other.base != first.base {
        "the morgana version or the command line".to_string()
    } else {
        let differs = first
            .files
            .iter()
            .zip(&other.files)
            .find(|(a, b)| a != b)
            .map(|(a, b)| if a.0 == b.0 { a.0.clone() } else { format!("{} / {}", a.0, b.0) });
        match differs {
            Some(name) => format!("file \"{name}\""),
            None => "the set of files the scene names (one rank lacks some)".to_string(),
        }
    };
    Some(Error::input(
        None,
        format!(
            "rank {r} (host {}) and rank 0 (host {}) do not see the same scene: {what} differs; \
             every host must see the scene and its files at the same path with the same contents",
            host(r),
            host(0)
        ),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn seen(base: u64, files: &[(&str, u64)]) -> Seen {
        Seen { base, files: files.iter().map(|(n, h)| (n.to_string(), *h)).collect() }
    }

    #[test]
    fn a_differing_file_is_named_with_its_rank_and_host() {
        let hosts: Vec<String> = ["a", "b", "c"].iter().map(|s| s.to_string()).collect();
        let good = seen(1, &[("lamp.ies", 5), ("sky.csv", 6)]);
        assert!(compare(&[good.clone(), good.clone(), good.clone()], &hosts).is_none());
        let stale = seen(1, &[("lamp.ies", 5), ("sky.csv", 7)]);
        let msg = compare(&[good.clone(), good.clone(), stale], &hosts).unwrap().to_string();
        assert!(msg.contains("rank 2 (host c)") && msg.contains("\"sky.csv\""), "{msg}");
        let missing = seen(1, &[("lamp.ies", 5)]);
        let msg = compare(&[good.clone(), missing], &hosts).unwrap().to_string();
        assert!(msg.contains("rank 1 (host b)") && msg.contains("lacks"), "{msg}");
        let msg = compare(&[good, seen(2, &[])], &hosts).unwrap().to_string();
        assert!(msg.contains("version or the command line"), "{msg}");
    }

    #[test]
    fn referenced_files_are_the_strings_that_name_files() {
        let dir = std::env::temp_dir().join(format!("morgana-refs-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("sub")).unwrap();
        std::fs::write(dir.join("sub/lamp.ies"), "x").unwrap();
        let text = "name = \"lamp\"\n[[light]]\nfile = \"sub/lamp.ies\"\nother = [\"sub/lamp.ies\", \"nope.csv\"]\n";
        let refs = referenced_files(text, &dir);
        assert_eq!(refs, vec![("sub/lamp.ies".to_string(), dir.join("sub/lamp.ies"))]);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_local_world_loads_the_default_scene() {
        let s = load(&Comm::local(), None, Some(1000), Some(3)).unwrap();
        assert_eq!((s.integrator.photons, s.integrator.seed), (1000, 3));
        assert!(s.file.is_none());
    }
}
