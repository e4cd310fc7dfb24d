//! A worker's scratch tree: copies of the repository's resources that seed documents refer to
//! (`luminaires/`, `atmospheres/`, `case/meshes/`), and the case directory where each case's
//! files are written and run. After every case the tree is compared with its state before:
//! a file left behind after a failure, a staging file after a success, or a changed file the
//! case did not own is a finding; then the tree is put back.

use crate::outcome::{Class, Outcome, has_non_finite_word};
use crate::targets::Target;
use std::cell::RefCell;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::SystemTime;

/// A worker's scratch tree.
pub struct Workspace {
    /// The tree's root (removed when the workspace is dropped).
    pub root: PathBuf,
    /// Where each case's files are written and run (the "examples" folder of the tree).
    pub case: PathBuf,
    /// The repository the resources were copied from.
    pub repo: PathBuf,
    /// Files written into every case directory (the command line's fixtures).
    pub fixtures: Vec<(String, Vec<u8>)>,
    baseline: RefCell<BTreeMap<PathBuf, (u64, Option<SystemTime>)>>,
}

fn copy_dir(from: &Path, to: &Path) -> std::io::Result<()> {
    std::fs::create_dir_all(to)?;
    for e in std::fs::read_dir(from)? {
        let e = e?;
        let p = e.path();
        if p.is_dir() {
            copy_dir(&p, &to.join(e.file_name()))?;
        } else {
            std::fs::copy(&p, to.join(e.file_name()))?;
        }
    }
    Ok(())
}

fn walk(dir: &Path, out: &mut BTreeMap<PathBuf, (u64, Option<SystemTime>)>) {
    let Ok(rd) = std::fs::read_dir(dir) else { return };
    for e in rd.flatten() {
        let p = e.path();
        let Ok(m) = std::fs::symlink_metadata(&p) else { continue };
        if m.is_dir() {
            out.insert(p.clone(), (0, None));
            walk(&p, out);
        } else {
            out.insert(p, (m.len(), m.modified().ok()));
        }
    }
}

impl Workspace {
    /// Makes the tree under `parent` (a fresh `tag` folder).
    pub fn new(parent: &Path, tag: &str, repo: &Path, fixtures: Vec<(String, Vec<u8>)>) -> Result<Workspace, String> {
        let root = parent.join(tag);
        let _ = std::fs::remove_dir_all(&root);
        let case = root.join("case");
        let io = |e: std::io::Error| format!("workspace {}: {e}", root.display());
        std::fs::create_dir_all(&case).map_err(io)?;
        copy_dir(&repo.join("luminaires"), &root.join("luminaires")).map_err(io)?;
        copy_dir(&repo.join("atmospheres"), &root.join("atmospheres")).map_err(io)?;
        copy_dir(&repo.join("examples/meshes"), &case.join("meshes")).map_err(io)?;
        // tropical.toml reads its profile beside itself.
        std::fs::copy(repo.join("atmospheres/tropical_afgl1986.csv"), case.join("tropical_afgl1986.csv"))
            .map_err(io)?;
        for (n, b) in &fixtures {
            std::fs::write(case.join(n), b).map_err(io)?;
        }
        let mut ws =
            Workspace { root, case, repo: repo.to_path_buf(), fixtures, baseline: RefCell::new(BTreeMap::new()) };
        ws.baseline = RefCell::new(ws.snapshot());
        Ok(ws)
    }

    fn snapshot(&self) -> BTreeMap<PathBuf, (u64, Option<SystemTime>)> {
        let mut m = BTreeMap::new();
        walk(&self.root, &mut m);
        m
    }

    /// Judges what the case left in the tree (given its outcome so far and the files it
    /// wrote), then restores the tree.
    pub fn settle(&self, outcome: Outcome, written: &[String], target: Target) -> Outcome {
        let now = self.snapshot();
        let baseline = self.baseline.borrow().clone();
        let ours: Vec<PathBuf> = written.iter().map(|n| self.case.join(n)).collect();
        let mut new = Vec::new();
        let mut changed = Vec::new();
        for (p, meta) in &now {
            if ours.contains(p) {
                continue;
            }
            match baseline.get(p) {
                None => new.push(p.clone()),
                Some(b) if b != meta => changed.push(p.clone()),
                _ => {}
            }
        }
        let missing: Vec<PathBuf> = baseline.keys().filter(|p| !now.contains_key(*p)).cloned().collect();
        let success = outcome.class == Class::Ok;
        let rel = |p: &PathBuf| p.strip_prefix(&self.root).unwrap_or(p).display().to_string();
        let mut verdict = outcome;
        if verdict.class.allowed() {
            let staging: Vec<&PathBuf> =
                new.iter().filter(|p| p.file_name().is_some_and(|n| n.to_string_lossy().starts_with('.'))).collect();
            // The command line may be asked to write over its fixtures; a reader may not.
            let owned_changes = target == Target::Cli && success;
            if !success && !new.iter().all(|p| p.is_dir() && is_empty_dir(p)) {
                let files: Vec<String> = new.iter().filter(|p| !p.is_dir()).map(rel).collect();
                if !files.is_empty() {
                    verdict =
                        Outcome::new(Class::Leftover, format!("after a failure: {files:?} ({})", verdict.message));
                }
            } else if let Some(p) = staging.first() {
                verdict = Outcome::new(Class::Leftover, format!("staging file {} left", rel(p)));
            }
            if verdict.class.allowed() && !owned_changes && (!changed.is_empty() || !missing.is_empty()) {
                let list: Vec<String> = changed.iter().chain(&missing).filter(|p| !p.is_dir()).map(rel).collect();
                if !list.is_empty() {
                    verdict = Outcome::new(Class::Leftover, format!("changed files it did not own: {list:?}"));
                }
            }
        }
        // Restore: remove what is new (deepest first), rebuild what changed.
        for p in ours.iter().chain(new.iter().rev()) {
            if p.is_dir() {
                let _ = std::fs::remove_dir_all(p);
            } else {
                let _ = std::fs::remove_file(p);
            }
        }
        if !changed.is_empty() || !missing.is_empty() {
            self.restore();
        }
        verdict
    }

    /// Puts the resources and fixtures back as they were copied.
    fn restore(&self) {
        let _ = copy_dir(&self.repo.join("luminaires"), &self.root.join("luminaires"));
        let _ = copy_dir(&self.repo.join("atmospheres"), &self.root.join("atmospheres"));
        let _ = copy_dir(&self.repo.join("examples/meshes"), &self.case.join("meshes"));
        let _ =
            std::fs::copy(self.repo.join("atmospheres/tropical_afgl1986.csv"), self.case.join("tropical_afgl1986.csv"));
        for (n, b) in &self.fixtures {
            let _ = std::fs::write(self.case.join(n), b);
        }
        // Modification times changed: the restored state is the new baseline.
        *self.baseline.borrow_mut() = self.snapshot();
    }
}

fn is_empty_dir(p: &Path) -> bool {
    std::fs::read_dir(p).map(|mut d| d.next().is_none()).unwrap_or(false)
}

impl Drop for Workspace {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.root);
    }
}

/// A NaN or infinity in an output file: EXR samples, or words in CSV, JSON and text.
pub fn non_finite_in(path: &Path) -> Option<String> {
    let name = path.display().to_string();
    match path.extension().and_then(|e| e.to_str()) {
        Some("exr") => {
            let image = exr::prelude::read_all_flat_layers_from_file(path).ok()?;
            for layer in &image.layer_data {
                for c in &layer.channel_data.list {
                    if let Some((i, v)) = c.sample_data.values_as_f32().enumerate().find(|(_, v)| !v.is_finite()) {
                        return Some(format!("{name}: channel {} sample {i} is {v}", c.name));
                    }
                }
            }
            None
        }
        Some("csv" | "json" | "txt") => {
            let text = std::fs::read_to_string(path).ok()?;
            let line = text.lines().position(has_non_finite_word)?;
            Some(format!("{name}:{}: {}", line + 1, text.lines().nth(line).unwrap_or("")))
        }
        _ => None,
    }
}
