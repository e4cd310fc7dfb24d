//! Outputs: spectral EXR, PNG preview, JSON report; all written atomically.

pub mod convergence;
pub mod report;

use crate::atomic::Staged;
use crate::error::{Error, Location, Result};
use crate::render::Rendered;
use crate::scene::Scene;
use crate::spectrum::SpectralImage;
use std::io::Write;
use std::path::{Path, PathBuf};

/// The longest name of one directory in an output path, bytes (`NAME_MAX` of Linux file
/// systems: ext4, XFS, Btrfs, tmpfs).
pub const MAX_DIRECTORY_NAME_BYTES: usize = 255;

/// Checks, before any work, that a render of `scene` can write its outputs into `dir`: `dir`
/// is (or can be created as) a directory, a file can be created there, and no output's name is
/// taken by a directory. With `create`, a missing `dir` is created (as the render would);
/// without, its nearest existing ancestor must be a writable directory (`morgana check`). Every
/// failure is an input error naming the path.
pub fn check_destination(scene: &Scene, dir: &Path, create: bool) -> Result<()> {
    let at = |what: String| Error::input(Some(Location::file(dir)), what);
    if dir.exists() && !dir.is_dir() {
        return Err(at("--out names a file, not a directory; give a directory for the outputs".into()));
    }
    // Directories `check` does not create must still be creatable: no name too long.
    if let Some(long) = dir.components().map(|c| c.as_os_str()).find(|c| c.len() > MAX_DIRECTORY_NAME_BYTES) {
        return Err(at(format!(
            "--out: the directory name \"{}\" is {} bytes long; file systems allow {MAX_DIRECTORY_NAME_BYTES}",
            long.to_string_lossy(),
            long.len()
        )));
    }
    let probe_dir = if create || dir.is_dir() {
        std::fs::create_dir_all(dir).map_err(|e| at(format!("cannot create the output directory: {e}")))?;
        dir.to_path_buf()
    } else {
        let ancestor = dir.ancestors().skip(1).find(|a| a.as_os_str().is_empty() || a.exists());
        match ancestor {
            Some(a) if a.as_os_str().is_empty() => PathBuf::from("."),
            Some(a) if a.is_dir() => a.to_path_buf(),
            Some(a) => return Err(at(format!("cannot create the output directory: {} is a file", a.display()))),
            None => PathBuf::from("/"),
        }
    };
    let probe = Staged::new(&probe_dir.join(".morgana-write-check"))
        .map_err(|e| at(format!("cannot write in the output directory: {e}")))?;
    drop(probe);
    for name in scene.output_file_names() {
        let target = dir.join(&name);
        if target.is_dir() {
            return Err(Error::input(
                Some(Location::file(&target)),
                format!("a directory is in the way of the output file {name}; remove it or choose another --out"),
            ));
        }
    }
    Ok(())
}

/// Writes the outputs the scene asks for (spectral EXR, PNG preview, per-pixel CSV, sensor
/// files) and `report.json` into `dir`, all or nothing: every file is written to a temporary
/// name first; only when all are written are they renamed into place, and if a rename fails
/// the files this call already renamed are removed again (with the remaining temporaries), so
/// a failed call leaves none of its outputs behind.
pub fn write_outputs(
    scene: &Scene,
    r: &Rendered,
    dir: &Path,
    threads: usize,
    total_seconds: f64,
) -> Result<Vec<PathBuf>> {
    write_outputs_with(scene, r, dir, (threads, total_seconds), None)
}

/// [`write_outputs`], and the convergence plot ([`convergence`]) at `convergence` when given,
/// staged and committed with the other outputs (all or nothing).
pub fn write_outputs_with(
    scene: &Scene,
    r: &Rendered,
    dir: &Path,
    (threads, total_seconds): (usize, f64),
    convergence: Option<&Path>,
) -> Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir)
        .map_err(|e| Error::internal(format!("cannot create output directory {}: {e}", dir.display())))?;
    let o = &scene.output;
    let names = scene.output_file_names();
    let mut files = names.iter();
    let mut next = || dir.join(files.next().map_or("unplanned", |n| n.as_str()));
    let mut staged: Vec<Staged> = Vec::new();
    if o.exr {
        stage(&mut staged, next(), &|p| {
            crate::spectrum::exr::write_spectral_exr_with_error(p, &r.image, r.std_error.as_deref())
        })?;
    }
    if o.png {
        stage(&mut staged, next(), &|p| match &o.tone {
            None => crate::tonemap::preview::write_png_preview(p, &r.image, o.exposure),
            Some(tone) => crate::tonemap::write_png(p, &r.image, tone).map(|_| ()),
        })?;
    }
    if let Some(region) = &o.region {
        let image = crate::tonemap::SceneImage::from_spectral(&r.image);
        stage(&mut staged, next(), &|p| region.write_csv(&image, p))?;
    }
    if o.csv {
        stage(&mut staged, next(), &|p| write_csv(p, &r.image))?;
    }
    // Sensors in the scene's order, as `output_file_names` lists their files.
    let (mut readings, mut profiles) = (r.sensors.iter(), r.profiles.iter());
    for s in &scene.sensors {
        match s.sensor {
            crate::sensor::Sensor::IlluminancePlane(_) => {
                let Some(reading) = readings.next() else { continue };
                stage(&mut staged, next(), &|p| reading.write_csv(p))?;
                stage(&mut staged, next(), &|p| reading.write_png(p))?;
            }
            crate::sensor::Sensor::SkyRadiance(_) => {
                let Some(reading) = readings.next() else { continue };
                stage(&mut staged, next(), &|p| reading.write_csv(p))?;
            }
            crate::sensor::Sensor::OceanProfile(_) => {
                let Some(profile) = profiles.next() else { continue };
                stage(&mut staged, next(), &|p| profile.write_csv(p))?;
                stage(&mut staged, next(), &|p| profile.write_derived_csv(p))?;
            }
        }
    }
    if let Some(path) = convergence {
        stage(&mut staged, path.to_path_buf(), &|p| convergence::figure(&r.stats.progressive).write_png(p))?;
    }
    let mut outputs: Vec<PathBuf> = names.iter().map(|n| dir.join(n)).collect();
    outputs.extend(convergence.map(Path::to_path_buf));
    let listed = outputs.iter().map(|p| p.display().to_string()).collect();
    let report = report::Report::new(scene, &r.stats, threads, total_seconds, listed);
    let json = serde_json::to_string_pretty(&report).map_err(|e| Error::internal(format!("report.json: {e}")))?;
    stage(&mut staged, next(), &|p| std::fs::write(p, json.as_bytes()))?;
    commit_all(staged)?;
    Ok(outputs)
}

/// Renames every staged file into place; if one fails, removes the ones already renamed (and,
/// by dropping them, the remaining temporaries) and reports the failure.
fn commit_all(staged: Vec<Staged>) -> Result<()> {
    let mut done: Vec<PathBuf> = Vec::with_capacity(staged.len());
    let mut rest = staged.into_iter();
    for s in rest.by_ref() {
        let target = s.target.clone();
        if let Err(e) = s.commit() {
            for d in &done {
                std::fs::remove_file(d).ok();
            }
            return Err(Error::internal(format!(
                "cannot write {}: {e}; none of this render's outputs were kept",
                target.display()
            )));
        }
        done.push(target);
    }
    Ok(())
}

fn io_error(path: &Path, e: std::io::Error) -> Error {
    Error::internal(format!("cannot write {}: {e}", path.display()))
}

/// Writes `target` to a staged temporary file.
fn stage(staged: &mut Vec<Staged>, target: PathBuf, write: &dyn Fn(&Path) -> std::io::Result<()>) -> Result<()> {
    let s = Staged::new(&target).map_err(|e| io_error(&target, e))?;
    write(&s.temp).map_err(|e| io_error(&target, e))?;
    staged.push(s);
    Ok(())
}

/// One row per pixel: x, y, then the spectral radiance of each band (W m⁻² sr⁻¹ nm⁻¹), with a
/// header naming each band by its centre wavelength.
fn write_csv(path: &Path, img: &SpectralImage) -> std::io::Result<()> {
    let mut f = std::io::BufWriter::new(std::fs::File::create(path)?);
    write!(f, "x,y")?;
    for b in 0..img.bands.count {
        write!(f, ",L_{:.2}nm", img.bands.centre_nm(b))?;
    }
    writeln!(f)?;
    let nb = img.bands.count;
    for y in 0..img.height {
        for x in 0..img.width {
            write!(f, "{x},{y}")?;
            for v in &img.data[(y * img.width + x) * nb..][..nb] {
                write!(f, ",{v:e}")?;
            }
            writeln!(f)?;
        }
    }
    f.flush()
}
