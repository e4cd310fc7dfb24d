//! `morgana render SCENE --sun-zenith-deg 0,30,60,85,90`: the scene rendered once per solar
//! zenith angle, its sun moved to each in turn (elevation 90° − zenith, azimuth kept), with one
//! CSV gathering every `sky_radiance` sensor's reading at every angle (none without such a
//! sensor: the frames, e.g. a setting sun's images, are then the whole result).
//!
//! Each angle is a whole run (photon and eye passes, with the command's stopping rules), whose
//! outputs go to `OUT/sun_zenith_<angle>/` as a single render's would. `OUT/<name>_sun_sweep.csv`
//! then holds one row per angle, sensor and direction:
//! `sun_zenith_deg,sensor,view_zenith_deg,view_azimuth_deg,L_mean,L_<lo>_<hi>nm…`, radiance in
//! W m⁻² sr⁻¹ nm⁻¹: list [0, 0] (the zenith) and [90, φ] (the horizon) in the sensor for zenith
//! and horizon radiance against solar zenith angle. With a `limb` sensor a `tangent_height_m`
//! column follows `view_azimuth_deg` (empty in the rows of other sensors).

use crate::error::{Error, Result};
use crate::render::{RenderOptions, Rendered};
use crate::scene::{Scene, load_scene_str_at_sun_zenith};
use crate::sensor::Reading;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// The scene at `path` with its sun at each of `zeniths_deg`: renders each with `opts` in
/// `pool`, writes its outputs under `out`, and the sweep's CSV; returns the files written.
pub fn run(
    path: &Path,
    zeniths_deg: &[f64],
    prepare: &dyn Fn(&mut Scene) -> Result<()>,
    opts: &RenderOptions,
    pool: &rayon::ThreadPool,
    out: &Path,
) -> Result<Vec<PathBuf>> {
    let source = crate::error::read_utf8(path, "scene file")?;
    let dir = path.parent().map_or_else(|| PathBuf::from("."), Path::to_path_buf);
    let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("scene").to_string();
    // Every angle's scene is loaded first, so bad input stops the sweep before any work.
    let mut scenes = Vec::with_capacity(zeniths_deg.len());
    for &z in zeniths_deg {
        let mut scene = load_scene_str_at_sun_zenith(&source, path, &dir, &stem, z)?;
        scene.file = Some(path.to_path_buf());
        prepare(&mut scene)?;
        scenes.push(scene);
    }
    let name = scenes.first().map(|s| s.output.name.clone()).unwrap_or(stem);
    let mut written = Vec::new();
    let mut rows = Vec::new();
    for (scene, &z) in scenes.iter().zip(zeniths_deg) {
        let start = std::time::Instant::now();
        let local = crate::distributed::Comm::local();
        let rendered = pool
            .install(|| crate::render::render_on(&local, scene, opts, &crate::distributed::Options::default()))?
            .ok_or_else(|| Error::internal("a one-process render returned no image"))?;
        let seconds = start.elapsed().as_secs_f64();
        let sub = out.join(format!("sun_zenith_{z}"));
        written.extend(crate::output::write_outputs_with(
            scene,
            &rendered,
            &sub,
            (pool.current_num_threads(), seconds),
            None,
        )?);
        rows.push((z, sky_readings(&rendered)));
    }
    // Without a sky_radiance sensor the frames are the result (a sequence of images): no CSV.
    if let Some(text) = sweep_csv(&rows) {
        let csv_path = out.join(format!("{name}_sun_sweep.csv"));
        write_atomically(&csv_path, &text)?;
        written.push(csv_path);
    }
    Ok(written)
}

/// The readings of `sky_radiance` sensors (those with view directions).
fn sky_readings(r: &Rendered) -> Vec<Reading> {
    r.sensors.iter().filter(|s| s.columns.iter().any(|(c, _)| c == "view_zenith_deg")).cloned().collect()
}

/// The sweep's CSV text (module docs), `None` when no reading has view directions (the scene
/// has no `sky_radiance` sensor); the band columns of every reading agree (one scene).
fn sweep_csv(rows: &[(f64, Vec<Reading>)]) -> Option<String> {
    let first = rows.iter().flat_map(|(_, r)| r.first()).next()?;
    let bands: Vec<&str> =
        first.columns.iter().map(|(c, _)| c.as_str()).filter(|c| c.starts_with("L_") && *c != "L_mean").collect();
    let limb = rows.iter().flat_map(|(_, r)| r).any(|r| r.columns.iter().any(|(c, _)| c == "tangent_height_m"));
    let height_column = if limb { "tangent_height_m," } else { "" };
    let mut text =
        format!("sun_zenith_deg,sensor,view_zenith_deg,view_azimuth_deg,{height_column}L_mean,{}\n", bands.join(","));
    for (z, readings) in rows {
        for r in readings {
            let col = |name: &str| r.columns.iter().find(|(c, _)| c == name).map(|(_, v)| v.as_slice());
            let (Some(vz), Some(va), Some(mean)) = (col("view_zenith_deg"), col("view_azimuth_deg"), col("L_mean"))
            else {
                continue;
            };
            let heights = col("tangent_height_m");
            for k in 0..vz.len() {
                let _ = write!(text, "{z},{},{},{},", r.name, vz[k], va[k]);
                if limb {
                    let _ = write!(text, "{},", heights.map_or(String::new(), |h| h[k].to_string()));
                }
                let _ = write!(text, "{:e}", mean[k]);
                for b in &bands {
                    let _ = write!(text, ",{:e}", col(b).map_or(f64::NAN, |v| v[k]));
                }
                text.push('\n');
            }
        }
    }
    Some(text)
}

/// Writes `text` to `path` through a temporary file renamed into place ([`crate::atomic`]).
fn write_atomically(path: &Path, text: &str) -> Result<()> {
    let fail = |e: std::io::Error| Error::internal(format!("cannot write {}: {e}", path.display()));
    let staged = crate::atomic::Staged::new(path).map_err(fail)?;
    std::fs::write(&staged.temp, text).map_err(fail)?;
    staged.commit().map_err(fail)
}
