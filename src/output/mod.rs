//! Outputs: spectral EXR, PNG preview, JSON report; all written atomically.

pub mod report;

use crate::atomic::Staged;
use crate::error::{Error, Result};
use crate::render::Rendered;
use crate::scene::Scene;
use crate::spectrum::SpectralImage;
use std::io::Write;
use std::path::{Path, PathBuf};

/// Writes the outputs the scene asks for (spectral EXR, PNG preview, per-pixel CSV) and
/// `report.json` into `dir`. All files are written to temporary names first and renamed into
/// place only when every one of them was written, so an error leaves no partial output.
pub fn write_outputs(
    scene: &Scene,
    r: &Rendered,
    dir: &Path,
    threads: usize,
    total_seconds: f64,
) -> Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir)
        .map_err(|e| Error::internal(format!("cannot create output directory {}: {e}", dir.display())))?;
    let o = &scene.output;
    let mut staged: Vec<Staged> = Vec::new();
    if o.exr {
        stage(&mut staged, dir, format!("{}.exr", o.name), &|p| crate::spectrum::exr::write_spectral_exr(p, &r.image))?;
    }
    if o.png {
        stage(&mut staged, dir, format!("{}.png", o.name), &|p| match &o.tone {
            None => crate::tonemap::preview::write_png_preview(p, &r.image, o.exposure),
            Some(tone) => crate::tonemap::write_png(p, &r.image, tone).map(|_| ()),
        })?;
    }
    if let Some(region) = &o.region {
        let image = crate::tonemap::SceneImage::from_spectral(&r.image);
        stage(&mut staged, dir, format!("{}.region.csv", o.name), &|p| region.write_csv(&image, p))?;
    }
    if o.csv {
        stage(&mut staged, dir, format!("{}.csv", o.name), &|p| write_csv(p, &r.image))?;
    }
    for s in &r.sensors {
        let stem = format!("{}_{}", o.name, crate::sensor::file_stem(&s.name));
        stage(&mut staged, dir, format!("{stem}.csv"), &|p| s.write_csv(p))?;
        stage(&mut staged, dir, format!("{stem}.png"), &|p| s.write_png(p))?;
    }
    for s in &r.profiles {
        let stem = format!("{}_{}", o.name, crate::sensor::file_stem(&s.name));
        stage(&mut staged, dir, format!("{stem}.csv"), &|p| s.write_csv(p))?;
        stage(&mut staged, dir, format!("{stem}_derived.csv"), &|p| s.write_derived_csv(p))?;
    }
    let mut outputs: Vec<PathBuf> = staged.iter().map(|s| s.target.clone()).collect();
    outputs.push(dir.join("report.json"));
    let names = outputs.iter().map(|p| p.display().to_string()).collect();
    let report = report::Report::new(scene, &r.stats, threads, total_seconds, names);
    let json = serde_json::to_string_pretty(&report).map_err(|e| Error::internal(format!("report.json: {e}")))?;
    stage(&mut staged, dir, "report.json".into(), &|p| std::fs::write(p, json.as_bytes()))?;
    for s in staged {
        let target = s.target.clone();
        s.commit().map_err(|e| io_error(&target, e))?;
    }
    Ok(outputs)
}

fn io_error(path: &Path, e: std::io::Error) -> Error {
    Error::internal(format!("cannot write {}: {e}", path.display()))
}

/// Writes `name` in `dir` to a staged temporary file.
fn stage(
    staged: &mut Vec<Staged>,
    dir: &Path,
    name: String,
    write: &dyn Fn(&Path) -> std::io::Result<()>,
) -> Result<()> {
    let target = dir.join(name);
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
