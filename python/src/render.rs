//! `morgana.render`'s native part: the CLI's render (`morgana::render::render_on` on one
//! process) on a worker thread while the calling thread, without the GIL, waits for it, reports
//! progress and checks for Ctrl-C; a signal raises the render's cancel flag, the render stops
//! within a batch of photons or a row of pixels, and the signal's exception is raised.

use crate::errors::{arg_error, panic_text};
use crate::scene::{NativeScene, band_edges};
use morgana::distributed::{self, Comm, MapMemory};
use morgana::render::progress::Observer;
use morgana::render::{MemoryLimit, RenderOptions, Rendered, render_on};
use morgana::scene::Scene;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyBytes;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, mpsc};
use std::time::{Duration, Instant};

/// How often the waiting thread wakes to report progress and check for signals.
const POLL: Duration = Duration::from_millis(100);

/// A finished render (native part of `morgana.Result`).
#[pyclass(module = "morgana._native", frozen)]
pub struct NativeResult {
    /// The scene rendered.
    pub scene: Arc<Scene>,
    /// The image, statistics and sensor readings.
    pub rendered: Rendered,
    /// Worker threads used.
    pub threads: usize,
    /// Wall time of the render, s.
    pub seconds: f64,
}

/// One sensor's tables as the CLI writes them: (name, kind, CSV text, derived CSV text).
pub type SensorTables = (String, String, String, Option<String>);

type Outcome = std::thread::Result<morgana::error::Result<Option<Rendered>>>;

/// Renders `scene` as `morgana render` does (same seed, same image for any number of threads).
#[pyfunction]
#[pyo3(signature = (scene, threads=None, progress=None, quiet=false, max_seconds=None, max_memory=None))]
pub fn render(
    py: Python<'_>,
    scene: &NativeScene,
    threads: Option<usize>,
    progress: Option<Py<PyAny>>,
    quiet: bool,
    max_seconds: Option<f64>,
    max_memory: Option<String>,
) -> PyResult<NativeResult> {
    let start = Instant::now();
    let pool = pool(threads)?;
    let threads = pool.current_num_threads();
    let deadline = deadline(start, max_seconds)?;
    let max_memory = match max_memory {
        None => MemoryLimit::Available,
        Some(s) => MemoryLimit::Limit(
            morgana::memory::parse_bytes(&s).map_err(|m| PyValueError::new_err(format!("max_memory: {m}")))?,
        ),
    };
    let cancel = Arc::new(AtomicBool::new(false));
    let observer = progress.as_ref().map(|_| Arc::new(Observer::default()));
    let opts = RenderOptions {
        quiet,
        max_memory,
        deadline,
        cancel: Some(cancel.clone()),
        observer: observer.clone(),
        started: Some(start),
        checkpoint: None,
    };
    let shared = scene.scene.clone();
    let (tx, rx) = mpsc::channel::<Outcome>();
    std::thread::Builder::new()
        .name("morgana-render".into())
        .spawn(move || {
            let dist = distributed::Options { map_memory: MapMemory::Available, ..distributed::Options::default() };
            let out = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                pool.install(|| render_on(&Comm::local(), &shared, &opts, &dist))
            }));
            let _ = tx.send(out);
        })
        .map_err(|e| PyRuntimeError::new_err(format!("cannot start the render thread: {e}")))?;
    let outcome = wait(py, &std::sync::Mutex::new(rx), &cancel, observer.as_deref(), progress.as_ref())?;
    let rendered = match outcome {
        Err(payload) => {
            return Err(PyRuntimeError::new_err(format!(
                "internal error (a panic in morgana): {}",
                panic_text(&payload)
            )));
        }
        Ok(Err(e)) => return Err(arg_error(e)),
        Ok(Ok(None)) => return Err(PyRuntimeError::new_err("internal error: a one-process render returned no image")),
        Ok(Ok(Some(r))) => r,
    };
    Ok(NativeResult { scene: scene.scene.clone(), rendered, threads, seconds: start.elapsed().as_secs_f64() })
}

/// Waits for the render thread without the GIL, waking every [`POLL`] to call `progress` and to
/// run Python's signal handlers; if one raises (Ctrl-C: `KeyboardInterrupt`), the render is
/// cancelled, waited for, and the exception returned.
fn wait(
    py: Python<'_>,
    rx: &std::sync::Mutex<mpsc::Receiver<Outcome>>,
    cancel: &AtomicBool,
    observer: Option<&Observer>,
    progress: Option<&Py<PyAny>>,
) -> PyResult<Outcome> {
    let mut sent = Vec::new();
    loop {
        let received = py.detach(|| match rx.lock() {
            Ok(r) => r.recv_timeout(POLL),
            Err(_) => Err(mpsc::RecvTimeoutError::Disconnected),
        });
        match received {
            Ok(out) => {
                report(py, observer, progress, &mut sent)?;
                return Ok(out);
            }
            Err(mpsc::RecvTimeoutError::Disconnected) => {
                return Err(PyRuntimeError::new_err("internal error: the render thread ended without a result"));
            }
            Err(mpsc::RecvTimeoutError::Timeout) => {}
        }
        let checked = py.check_signals().and_then(|_| report(py, observer, progress, &mut sent));
        if let Err(e) = checked {
            cancel.store(true, Ordering::Relaxed);
            py.detach(|| {
                if let Ok(r) = rx.lock() {
                    let _ = r.recv();
                }
            });
            return Err(e);
        }
    }
}

/// Calls `progress(phase, done, total)` for each phase whose progress changed.
/// Phases are reported in the order they started, each when its progress changed since the
/// last call (`sent` holds what was sent), so a phase that began and ended between two polls is
/// still reported at its end.
fn report(
    py: Python<'_>,
    observer: Option<&Observer>,
    progress: Option<&Py<PyAny>>,
    sent: &mut Vec<(u64, u64)>,
) -> PyResult<()> {
    let (Some(o), Some(cb)) = (observer, progress) else { return Ok(()) };
    for (i, p) in o.read_all().into_iter().enumerate() {
        if sent.get(i) == Some(&(p.done, p.total)) {
            continue;
        }
        if i >= sent.len() {
            sent.resize(i + 1, (u64::MAX, u64::MAX));
        }
        sent[i] = (p.done, p.total);
        cb.call1(py, (p.phase, p.done, p.total))?;
    }
    Ok(())
}

/// The worker pool: `threads` threads (1 … 1024), or one per core.
fn pool(threads: Option<usize>) -> PyResult<rayon::ThreadPool> {
    let mut builder = rayon::ThreadPoolBuilder::new();
    if let Some(t) = threads {
        if !(1..=morgana::cli::render::MAX_THREADS).contains(&t) {
            return Err(PyValueError::new_err(format!(
                "threads={t} is out of range: it must be between 1 and {} (the output does not depend on it)",
                morgana::cli::render::MAX_THREADS
            )));
        }
        builder = builder.num_threads(t);
    }
    builder.build().map_err(|e| PyRuntimeError::new_err(format!("cannot start worker threads: {e}")))
}

fn deadline(start: Instant, max_seconds: Option<f64>) -> PyResult<Option<Instant>> {
    let max = morgana::cli::render::MAX_SECONDS;
    match max_seconds {
        None => Ok(None),
        Some(s) if s.is_finite() && s > 0.0 && s <= max => Ok(Some(start + Duration::from_secs_f64(s))),
        Some(s) => {
            Err(PyValueError::new_err(format!("max_seconds={s}: expected a positive number of seconds, at most {max}")))
        }
    }
}

#[pymethods]
impl NativeResult {
    /// (height, width, bands).
    #[getter]
    fn shape(&self) -> (usize, usize, usize) {
        let i = &self.rendered.image;
        (i.height, i.width, i.bands.count)
    }

    /// The spectral radiance, float32 native-endian, row-major (y, x, band), W m⁻² sr⁻¹ nm⁻¹.
    fn radiance_bytes<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        f32_bytes(py, &self.rendered.image.data)
    }

    /// The radiance's standard error from the pass-to-pass spread, laid out like the radiance;
    /// `None` after a single pass.
    fn stderr_bytes<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyBytes>> {
        self.rendered.std_error.as_deref().map(|se| f32_bytes(py, se))
    }

    /// Linear sRGB (D65; Y in cd m⁻²), float32, row-major (y, x, channel).
    fn rgb_bytes<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        f32_bytes(py, &self.rendered.image.rgb)
    }

    /// The band centres, nm.
    #[getter]
    fn wavelengths_nm(&self) -> Vec<f64> {
        let b = &self.rendered.image.bands;
        (0..b.count).map(|i| b.centre_nm(i)).collect()
    }

    /// The band edges, nm.
    #[getter]
    fn band_edges_nm(&self) -> Vec<f64> {
        band_edges(&self.rendered.image.bands)
    }

    /// Worker threads used.
    #[getter]
    fn threads(&self) -> usize {
        self.threads
    }

    /// Notes the run made (e.g. a photon map that stored nothing).
    #[getter]
    fn run_warnings(&self) -> Vec<String> {
        self.rendered.stats.warnings.clone()
    }

    /// report.json's content as JSON text, listing `outputs` as the files written.
    fn report_json(&self, outputs: Vec<String>) -> PyResult<String> {
        let r = morgana::output::report::Report::new(
            &self.scene,
            &self.rendered.stats,
            self.threads,
            self.seconds,
            outputs,
        );
        serde_json::to_string(&r).map_err(|e| PyRuntimeError::new_err(format!("report.json: {e}")))
    }

    /// The sensors' CSV files as the CLI writes them: (name, kind, csv text, derived csv text
    /// or None) per sensor, in the scene's order.
    fn sensor_csvs(&self) -> PyResult<Vec<SensorTables>> {
        let dir = scratch_dir()?;
        let out = sensor_csvs(&self.rendered, &dir);
        std::fs::remove_dir_all(&dir).ok();
        out.map_err(|e| PyRuntimeError::new_err(format!("cannot write the sensor tables: {e}")))
    }

    /// Writes the files `morgana render --out dir` writes; returns their paths.
    fn save(&self, py: Python<'_>, dir: PathBuf) -> PyResult<Vec<String>> {
        morgana::output::check_destination(&self.scene, &dir, true).map_err(arg_error)?;
        let written =
            py.detach(|| morgana::output::write_outputs(&self.scene, &self.rendered, &dir, self.threads, self.seconds));
        Ok(written.map_err(arg_error)?.iter().map(|p| p.display().to_string()).collect())
    }
}

fn f32_bytes<'py>(py: Python<'py>, v: &[f32]) -> Bound<'py, PyBytes> {
    let mut b = Vec::with_capacity(v.len() * 4);
    for x in v {
        b.extend_from_slice(&x.to_ne_bytes());
    }
    PyBytes::new(py, &b)
}

/// A fresh private directory for temporary files.
fn scratch_dir() -> PyResult<PathBuf> {
    static NEXT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
    let n = NEXT.fetch_add(1, Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!("morgana-py-{}-{n}", std::process::id()));
    std::fs::create_dir_all(&dir)
        .map_err(|e| PyRuntimeError::new_err(format!("cannot create {}: {e}", dir.display())))?;
    Ok(dir)
}

fn sensor_csvs(r: &Rendered, dir: &std::path::Path) -> std::io::Result<Vec<SensorTables>> {
    let mut out = Vec::new();
    let (a, b) = (dir.join("a.csv"), dir.join("b.csv"));
    for s in &r.sensors {
        s.write_csv(&a)?;
        out.push((s.name.clone(), "illuminance_plane".into(), std::fs::read_to_string(&a)?, None));
    }
    for p in &r.profiles {
        p.write_csv(&a)?;
        p.write_derived_csv(&b)?;
        out.push((
            p.name.clone(),
            "ocean_profile".into(),
            std::fs::read_to_string(&a)?,
            Some(std::fs::read_to_string(&b)?),
        ));
    }
    Ok(out)
}
