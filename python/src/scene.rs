//! `morgana.Scene`'s native part: a validated scene with the text it was read from, so that
//! overrides re-read the same text (a scene is built once and never mutated in place).

use crate::errors::{arg_error, guard, must_exist, scene_error};
use morgana::scene::progressive::{FlagStyle, Flags};
use morgana::scene::{Scene, load_scene_str};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Where a scene's text came from and how the library reads it.
#[derive(Clone, Debug)]
pub struct Source {
    /// The TOML text.
    pub text: String,
    /// The file named in errors (the scene file, `<string>` or `<dict>`).
    pub file: PathBuf,
    /// The directory relative paths are resolved against.
    pub dir: PathBuf,
    /// The output stem when `[output] name` is absent.
    pub stem: String,
    /// Whether it was read from a file (then the scene's label is the file).
    pub from_file: bool,
}

/// The overrides the CLI's `morgana render` flags apply to a scene (`--photons`, `--seed` and the
/// stopping rules `--passes`, `--time`, `--target-rel-error`, `--target`).
#[derive(Clone, Debug, Default)]
pub struct Overrides {
    /// `--photons`: photons of each photon map.
    pub photons: Option<u64>,
    /// `--seed`: the random seed.
    pub seed: Option<u64>,
    /// `--passes`, `--time`, `--target-rel-error`, `--target`, `--adaptive`.
    pub stop: Flags,
}

/// The names `with_overrides` accepts (the scene-changing flags of `morgana render`).
pub const OVERRIDES: [&str; 7] = ["photons", "seed", "passes", "time", "target_rel_error", "target", "adaptive"];

/// A validated scene (native part of `morgana.Scene`).
#[pyclass(module = "morgana._native", frozen)]
pub struct NativeScene {
    /// The validated scene, shared with renders running on other threads.
    pub scene: Arc<Scene>,
    /// Its text and where it came from.
    pub source: Source,
    /// The overrides applied.
    pub overrides: Overrides,
}

impl NativeScene {
    /// Reads `source` and applies `overrides` as `morgana render` does.
    pub fn build(py: Python<'_>, source: Source, overrides: Overrides) -> PyResult<NativeScene> {
        let loaded = guard(|| Ok(load_scene_str(&source.text, &source.file, &source.dir, &source.stem)))?;
        let mut scene = loaded.map_err(|e| scene_error(py, e, Some(&source.text)))?;
        if source.from_file {
            scene.file = Some(source.file.clone());
        }
        if let Some(n) = overrides.photons {
            morgana::scene::check_photons_override(n).map_err(|e| arg_error(e.at_flag("photons")))?;
        }
        scene.apply_overrides(overrides.photons, overrides.seed);
        scene.apply_stopping_rules(&overrides.stop).map_err(arg_error)?;
        Ok(NativeScene { scene: Arc::new(scene), source, overrides })
    }
}

#[pymethods]
impl NativeScene {
    /// Reads a scene file.
    #[staticmethod]
    fn from_file(py: Python<'_>, path: PathBuf) -> PyResult<NativeScene> {
        must_exist(&path)?;
        let text = morgana::error::read_utf8(&path, "scene file").map_err(|e| scene_error(py, e, None))?;
        let dir = path.parent().map_or_else(|| PathBuf::from("."), Path::to_path_buf);
        let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("scene").to_string();
        NativeScene::build(py, Source { text, file: path, dir, stem, from_file: true }, Overrides::default())
    }

    /// Reads scene text; `file` names it in errors, `base_dir` resolves relative paths, `name`
    /// is the output stem when `[output] name` is absent.
    #[staticmethod]
    fn from_str(py: Python<'_>, text: String, base_dir: PathBuf, file: PathBuf, name: String) -> PyResult<NativeScene> {
        NativeScene::build(py, Source { text, file, dir: base_dir, stem: name, from_file: false }, Overrides::default())
    }

    /// The TOML text of a dict (as `Scene.from_dict` reads it).
    #[staticmethod]
    fn dict_to_toml(d: &Bound<'_, PyAny>) -> PyResult<String> {
        crate::dict_toml::toml_text(d)
    }

    /// The scene with some of `morgana render`'s overrides applied (a new scene).
    fn with_overrides(&self, py: Python<'_>, kwargs: &Bound<'_, PyDict>) -> PyResult<NativeScene> {
        let mut o = self.overrides.clone();
        for (k, v) in kwargs.iter() {
            let key: String = k.extract()?;
            if v.is_none() {
                continue;
            }
            let wrong = |what: &str| PyTypeError::new_err(format!("{key}: expected {what}"));
            match key.as_str() {
                "photons" => o.photons = Some(v.extract().map_err(|_| wrong("a non-negative integer"))?),
                "seed" => o.seed = Some(v.extract().map_err(|_| wrong("a non-negative integer"))?),
                "passes" => o.stop.passes = Some(v.extract().map_err(|_| wrong("an integer"))?),
                "time" => {
                    o.stop.time = Some(duration_text(&v).ok_or_else(|| wrong("seconds or a text such as '90s'"))?)
                }
                "target_rel_error" => o.stop.target_rel_error = Some(v.extract().map_err(|_| wrong("a number"))?),
                "adaptive" => o.stop.adaptive = v.extract().map_err(|_| wrong("True or False"))?,
                "target" => {
                    o.stop.target =
                        Some(target_text(&v).ok_or_else(|| wrong("'image', a sensor name or (x0, y0, x1, y1)"))?)
                }
                _ => {
                    return Err(PyTypeError::new_err(format!(
                        "with_overrides() got an unexpected keyword argument '{key}'; accepted: {}",
                        OVERRIDES.join(", ")
                    )));
                }
            }
        }
        o.stop.style = FlagStyle::Keyword;
        NativeScene::build(py, self.source.clone(), o)
    }

    /// The effect plan as JSON text (what report.json's `effects` holds).
    fn plan_json(&self) -> PyResult<String> {
        serde_json::to_string(&self.scene.plan).map_err(|e| PyTypeError::new_err(e.to_string()))
    }

    /// The integrator settings as JSON text.
    fn integrator_json(&self) -> PyResult<String> {
        serde_json::to_string(&self.scene.integrator).map_err(|e| PyTypeError::new_err(e.to_string()))
    }

    /// The scene's TOML text.
    #[getter]
    fn text(&self) -> String {
        self.source.text.clone()
    }

    /// The scene's label: its file, `<string>` or `<dict>`.
    #[getter]
    fn label(&self) -> String {
        self.scene.label()
    }

    /// The notes the scene's validation made (things that do not stop a render).
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.scene.warnings.clone()
    }

    /// (width, height) of the image, pixels.
    #[getter]
    fn size(&self) -> (usize, usize) {
        (self.scene.camera.width, self.scene.camera.height)
    }

    /// The band centres, nm.
    #[getter]
    fn wavelengths_nm(&self) -> Vec<f64> {
        let b = &self.scene.bands;
        (0..b.count).map(|i| b.centre_nm(i)).collect()
    }

    /// The band edges, nm (one more than bands).
    #[getter]
    fn band_edges_nm(&self) -> Vec<f64> {
        band_edges(&self.scene.bands)
    }

    /// The names of the files a render writes, in order (report.json last).
    #[getter]
    fn output_files(&self) -> Vec<String> {
        self.scene.output_file_names()
    }

    /// The overrides applied, as a dict.
    #[getter]
    fn overrides<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        d.set_item("photons", self.overrides.photons)?;
        d.set_item("seed", self.overrides.seed)?;
        Ok(d)
    }
}

/// The band edges, nm: the lower edge of each band and the upper edge of the last.
pub fn band_edges(b: &morgana::spectrum::Bands) -> Vec<f64> {
    let mut e: Vec<f64> = (0..b.count).map(|i| b.edges_nm(i).0).collect();
    if b.count > 0 {
        e.push(b.edges_nm(b.count - 1).1);
    }
    e
}

/// `time=`: seconds as a number, or a text such as `"90s"` or `"1.5min"` (as `--time` reads it).
fn duration_text(v: &Bound<'_, PyAny>) -> Option<String> {
    if let Ok(t) = v.extract::<String>() {
        return Some(t);
    }
    if v.is_instance_of::<pyo3::types::PyBool>() {
        return None;
    }
    v.extract::<f64>().ok().map(|x| x.to_string())
}

/// `target=`: `"image"`, `"pixels"`, a sensor's name, or a pixel region as four integers (as `--target`
/// reads `x0,y0,x1,y1`).
fn target_text(v: &Bound<'_, PyAny>) -> Option<String> {
    if let Ok(t) = v.extract::<String>() {
        return Some(t);
    }
    let r: [i64; 4] = v.extract().ok()?;
    Some(r.map(|x| x.to_string()).join(","))
}
