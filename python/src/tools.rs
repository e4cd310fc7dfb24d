//! The other commands as functions: `refraction`, `trace`, `luminaire` and `tonemap`, each
//! calling the library as its `morgana` command does and returning plain Python values.

use crate::errors::{arg_error, guard, located_error, must_exist};
use crate::render::NativeResult;
use crate::scene::NativeScene;
use glam::DVec3;
use morgana::atmosphere::refraction::refractor::{Method, Refractor};
use morgana::atmosphere::refraction::report::table;
use morgana::atmosphere::refraction::sun::{SUN_DIAMETER_RAD, flattened_disc};
use morgana::atmosphere::refraction::terrestrial::radial_air;
use morgana::atmosphere::refraction::terrestrial_table::{Place, sight_table, terrestrial_table};
use morgana::atmosphere::refraction::{ARCSEC_PER_RAD, Settings, Tracer};
use morgana::raypath::trace::{End, Limits, trace as trace_ray};
use morgana::tonemap::SceneImage;
use morgana::tonemap::settings::ToneOptions;
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};
use std::path::PathBuf;

/// Astronomical refraction through an atmosphere (`morgana refraction`).
#[pyfunction]
#[pyo3(signature = (atmosphere, apparent_altitudes_deg, wavelength_nm=550.0, observer_height_m=0.0, sun_lower_limb_deg=0.0, method=None))]
pub fn refraction<'py>(
    py: Python<'py>,
    atmosphere: String,
    apparent_altitudes_deg: Vec<f64>,
    wavelength_nm: f64,
    observer_height_m: f64,
    sun_lower_limb_deg: f64,
    method: Option<String>,
) -> PyResult<Bound<'py, PyDict>> {
    let method = match method.as_deref() {
        None => None,
        Some("quadrature") => Some(Method::Quadrature),
        Some("trace") => Some(Method::Trace),
        Some(other) => {
            return Err(PyValueError::new_err(format!(
                "method: unknown \"{other}\"; expected \"quadrature\", \"trace\" or None (quadrature where the air allows it)"
            )));
        }
    };
    if let Some(a) =
        apparent_altitudes_deg.iter().chain([&sun_lower_limb_deg]).find(|a| !(a.is_finite() && a.abs() <= 90.0))
    {
        return Err(PyValueError::new_err(format!("altitude {a}° is out of range; expected −90 … 90")));
    }
    guard(|| {
        let atm = morgana::atmosphere::resolve(&atmosphere).map_err(|e| located_error(py, e))?;
        Tracer::new(&atm, wavelength_nm, 0.0, Settings::default())
            .map_err(|e| arg_error(e.at_flag("wavelength_nm")))?;
        let tracer = Tracer::new(&atm, wavelength_nm, observer_height_m, Settings::default())
            .map_err(|e| arg_error(e.at_flag("observer_height_m")))?;
        let refractor = Refractor::new(tracer, method)
            .map_err(|e| PyValueError::new_err(format!("method=\"quadrature\": {e}; use method=\"trace\"")))?;
        let t = table(&refractor, &apparent_altitudes_deg).map_err(arg_error)?;
        let d = PyDict::new(py);
        d.set_item("atmosphere", &t.atmosphere)?;
        d.set_item("wavelength_nm", t.wavelength_nm)?;
        d.set_item("observer_height_m", t.observer_height_m)?;
        d.set_item("pressure_hpa", t.pressure_hpa)?;
        d.set_item("temperature_c", t.temperature_c)?;
        let by = if refractor.method() == Method::Quadrature { "quadrature" } else { "trace" };
        d.set_item("method", by)?;
        let col = |f: &dyn Fn(&morgana::atmosphere::refraction::report::Row) -> Option<f64>| -> Vec<f64> {
            t.rows.iter().map(|r| f(r).unwrap_or(f64::NAN)).collect()
        };
        d.set_item("apparent_altitude_deg", col(&|r| Some(r.apparent_altitude_deg)))?;
        d.set_item("true_altitude_deg", col(&|r| r.trace.true_altitude_rad().map(f64::to_degrees)))?;
        d.set_item("refraction_arcsec", col(&|r| r.trace.refraction_rad().map(|x| x * ARCSEC_PER_RAD)))?;
        d.set_item("bennett_arcsec", col(&|r| r.bennett_rad.map(|x| x * ARCSEC_PER_RAD)))?;
        d.set_item("saemundsson_arcsec", col(&|r| r.saemundsson_rad.map(|x| x * ARCSEC_PER_RAD)))?;
        let sun = flattened_disc(&refractor, sun_lower_limb_deg.to_radians(), SUN_DIAMETER_RAD).map_err(arg_error)?;
        match sun {
            None => d.set_item("sun", py.None())?,
            Some(f) => {
                let s = PyDict::new(py);
                s.set_item("lower_apparent_deg", f.lower_apparent_rad.to_degrees())?;
                s.set_item("lower_true_deg", f.lower_true_rad.to_degrees())?;
                s.set_item("upper_apparent_deg", f.upper_apparent_rad.to_degrees())?;
                s.set_item("upper_true_deg", f.upper_true_rad.to_degrees())?;
                s.set_item("ratio", f.ratio)?;
                d.set_item("sun", s)?;
            }
        }
        Ok(d)
    })
}

/// Terrestrial refraction: where rays are along the ground
/// (`morgana refraction --ground-distances-km`).
#[pyfunction]
#[pyo3(signature = (atmosphere, apparent_altitudes_deg, ground_distances_km, wavelength_nm=550.0, observer_height_m=0.0))]
pub fn terrestrial<'py>(
    py: Python<'py>,
    atmosphere: String,
    apparent_altitudes_deg: Vec<f64>,
    ground_distances_km: Vec<f64>,
    wavelength_nm: f64,
    observer_height_m: f64,
) -> PyResult<Bound<'py, PyDict>> {
    guard(|| {
        let atm = morgana::atmosphere::resolve(&atmosphere).map_err(|e| located_error(py, e))?;
        let air = radial_air(&atm, wavelength_nm).map_err(|e| PyValueError::new_err(format!("{atmosphere}: {e}")))?;
        let title = atm.name.clone();
        let t = terrestrial_table(&air, title, observer_height_m, &apparent_altitudes_deg, &ground_distances_km)
            .map_err(arg_error)?;
        let pick = |f: &dyn Fn(&Place) -> Option<f64>| -> Vec<f64> {
            t.rows.iter().map(|r| f(&r.place).unwrap_or(f64::NAN)).collect()
        };
        let d = PyDict::new(py);
        d.set_item("apparent_altitude_deg", apparent_altitudes_deg.clone())?;
        d.set_item("ground_distance_km", ground_distances_km.clone())?;
        d.set_item(
            "height_m",
            pick(&|p| match p {
                Place::Aloft { height_m, .. } => Some(*height_m),
                _ => None,
            }),
        )?;
        d.set_item(
            "elevation_deg",
            pick(&|p| match p {
                Place::Aloft { elevation_deg, .. } => Some(*elevation_deg),
                _ => None,
            }),
        )?;
        d.set_item(
            "straight_height_m",
            pick(&|p| match p {
                Place::Aloft { straight_height_m, .. } => *straight_height_m,
                _ => None,
            }),
        )?;
        d.set_item(
            "ground_at_km",
            pick(&|p| match p {
                Place::Ground { at_km } => Some(*at_km),
                _ => None,
            }),
        )?;
        Ok(d)
    })
}

/// Lines of sight to targets on the Earth (`morgana refraction --targets`).
#[pyfunction]
#[pyo3(signature = (atmosphere, targets, wavelength_nm=550.0, observer_height_m=2.0))]
pub fn lines_of_sight<'py>(
    py: Python<'py>,
    atmosphere: String,
    targets: Vec<(f64, f64)>,
    wavelength_nm: f64,
    observer_height_m: f64,
) -> PyResult<Bound<'py, PyDict>> {
    if let Some((d, h)) = targets.iter().find(|(d, h)| !(d.is_finite() && *d > 0.0 && h.is_finite() && *h >= 0.0)) {
        return Err(PyValueError::new_err(format!("target ({d} km, {h} m): expected a distance > 0 and a height ≥ 0")));
    }
    guard(|| {
        let atm = morgana::atmosphere::resolve(&atmosphere).map_err(|e| located_error(py, e))?;
        let air = radial_air(&atm, wavelength_nm).map_err(|e| PyValueError::new_err(format!("{atmosphere}: {e}")))?;
        let t = sight_table(&air, atm.name.clone(), observer_height_m, &targets).map_err(arg_error)?;
        let d = PyDict::new(py);
        let r_e = t.ground_radius_m;
        d.set_item("horizon_km", t.horizon.map_or(0.0, |h| h.angle_rad * r_e / 1e3))?;
        d.set_item("dip_deg", t.horizon.map_or(0.0, |h| -h.elevation_rad.to_degrees()))?;
        d.set_item("distance_km", t.rows.iter().map(|r| r.distance_km).collect::<Vec<_>>())?;
        d.set_item("height_m", t.rows.iter().map(|r| r.height_m).collect::<Vec<_>>())?;
        d.set_item("hidden_height_m", t.rows.iter().map(|r| r.hidden_height_m).collect::<Vec<_>>())?;
        d.set_item("straight_elevation_deg", t.rows.iter().map(|r| r.straight_elevation_deg).collect::<Vec<_>>())?;
        d.set_item("images_deg", t.rows.iter().map(|r| r.images_deg.clone()).collect::<Vec<_>>())?;
        Ok(d)
    })
}

/// One ray followed through a scene's media without scattering (`morgana trace`).
#[pyfunction]
#[pyo3(signature = (scene, origin, direction, wavelength_nm=550.0, events=32, max_length_m=1.0e8))]
pub fn trace<'py>(
    py: Python<'py>,
    scene: &NativeScene,
    origin: [f64; 3],
    direction: [f64; 3],
    wavelength_nm: f64,
    events: usize,
    max_length_m: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let from = DVec3::from(origin);
    let dir = DVec3::from(direction);
    if !from.is_finite() || !dir.is_finite() {
        return Err(PyValueError::new_err("origin and direction: expected three finite numbers each"));
    }
    let len = dir.length();
    if len <= 1e-12 * (1.0 + from.length()) {
        return Err(PyValueError::new_err("direction: expected a direction of non-zero length"));
    }
    let s = &scene.scene;
    let (lo, hi) = (s.bands.min_nm, s.bands.max_nm);
    if !(wavelength_nm.is_finite() && (lo..=hi).contains(&wavelength_nm)) {
        return Err(PyValueError::new_err(format!(
            "wavelength_nm={wavelength_nm}: expected a wavelength within the scene's range {lo}–{hi} nm"
        )));
    }
    if events == 0 {
        return Err(PyValueError::new_err("events=0: give at least 1 event to follow"));
    }
    if !(max_length_m.is_finite() && max_length_m > 0.0) {
        return Err(PyValueError::new_err(format!(
            "max_length_m={max_length_m}: expected a positive finite length in metres"
        )));
    }
    let limits = Limits { events, length_m: max_length_m };
    let t = guard(|| Ok(py.detach(|| trace_ray(&s.world, s.curved(), from, dir / len, wavelength_nm, limits))))?;
    let d = PyDict::new(py);
    d.set_item("events", t.lines.clone())?;
    d.set_item("end", end_text(&t.end))?;
    d.set_item("s_m", t.points.iter().map(|p| p.s_m).collect::<Vec<_>>())?;
    d.set_item("position", t.points.iter().map(|p| p.position.to_array()).collect::<Vec<_>>())?;
    d.set_item("direction", t.points.iter().map(|p| p.dir.to_array()).collect::<Vec<_>>())?;
    d.set_item("n", t.points.iter().map(|p| p.n).collect::<Vec<_>>())?;
    let w = &t.work;
    let work = PyDict::new(py);
    work.set_item("ode_steps", w.ode_steps)?;
    work.set_item("ode_rejected", w.ode_rejected)?;
    work.set_item("rhs_evals", w.rhs_evals)?;
    work.set_item("chords", w.chords)?;
    d.set_item("work", work)?;
    Ok(d)
}

fn end_text(e: &End) -> String {
    match e {
        End::Surface(name) => format!("surface {name}"),
        End::Escape(d) => format!("escape {},{},{}", d.x, d.y, d.z),
        End::Lost(p) => format!("lost {},{},{}", p.x, p.y, p.z),
        End::EventLimit => "event limit".into(),
        End::LengthLimit => "length limit".into(),
    }
}

/// A luminaire photometry file read as `morgana luminaire` reads it.
#[pyfunction]
#[pyo3(signature = (path, variant=None))]
pub fn luminaire<'py>(py: Python<'py>, path: PathBuf, variant: Option<String>) -> PyResult<Bound<'py, PyDict>> {
    must_exist(&path)?;
    let p =
        guard(|| morgana::luminaire::load_file_variant(&path, variant.as_deref()).map_err(|e| located_error(py, e)))?;
    let d = PyDict::new(py);
    d.set_item("format", &p.format)?;
    d.set_item("manufacturer", &p.manufacturer)?;
    d.set_item("luminaire", &p.luminaire)?;
    d.set_item("catalogue", &p.catalogue)?;
    d.set_item("photometric_type", format!("{:?}", p.photometric_type))?;
    d.set_item("symmetry", p.symmetry.to_string())?;
    d.set_item("absolute", p.absolute)?;
    d.set_item("lamp_flux_lm", p.lamp_flux_lm)?;
    d.set_item("stated_flux_lm", p.stated_flux_lm)?;
    d.set_item("flux_lm", p.flux_lm())?;
    d.set_item("input_watts", p.input_watts)?;
    let web = &p.web;
    let (c, g) = (web.c_deg().to_vec(), web.gamma_deg().to_vec());
    let rows: Vec<Vec<f64>> = (0..c.len()).map(|i| (0..g.len()).map(|j| web.node(i, j)).collect()).collect();
    d.set_item("c_deg", c)?;
    d.set_item("gamma_deg", g)?;
    d.set_item("intensity_cd", rows)?;
    let (peak_cd, peak_c, peak_gamma) = web.peak();
    d.set_item("peak", (peak_c, peak_gamma, peak_cd))?;
    d.set_item("notes", p.notes.clone())?;
    let summary = morgana::luminaire::inspect_variant(&path, None, variant.as_deref()).map_err(arg_error)?;
    d.set_item("summary", summary)?;
    Ok(d)
}

/// Tone-maps a render or an EXR file (`morgana tonemap`): (height, width, RGB bytes, notes).
#[pyfunction]
#[pyo3(signature = (source, operator=None, exposure=None, adapt_to=None, cat=None, adaptation_degree=None,
    adaptation_time_s=None, adapt_from_cd_m2=None, scotopic=None, false_colour=false, fov_deg=None))]
#[allow(clippy::too_many_arguments)]
pub fn tonemap<'py>(
    py: Python<'py>,
    source: &Bound<'py, PyAny>,
    operator: Option<String>,
    exposure: Option<String>,
    adapt_to: Option<String>,
    cat: Option<String>,
    adaptation_degree: Option<f64>,
    adaptation_time_s: Option<f64>,
    adapt_from_cd_m2: Option<f64>,
    scotopic: Option<String>,
    false_colour: bool,
    fov_deg: Option<f64>,
) -> PyResult<(usize, usize, Bound<'py, PyBytes>, Vec<String>)> {
    let exposure = match exposure {
        None => None,
        Some(e) => Some(morgana::cli::tonemap::parse_exposure(&e).ok_or_else(|| {
            PyValueError::new_err(format!("exposure: \"{e}\" is neither \"auto\" nor a number of stops (EV)"))
        })?),
    };
    let options = ToneOptions {
        operator,
        exposure,
        adapt_to,
        cat,
        adaptation_degree,
        adaptation_time_s,
        adapt_from_cd_m2,
        scotopic,
        false_colour,
        fov_deg,
    };
    let settings = options.validate().map_err(|e| PyValueError::new_err(format!("{}: {}", e.field, e.message)))?;
    let image: SceneImage = if let Ok(r) = source.cast::<NativeResult>() {
        SceneImage::from_spectral(&r.get().rendered.image)
    } else if let Ok(path) = source.extract::<PathBuf>() {
        must_exist(&path)?;
        morgana::tonemap::exr_read::read_exr(&path)
            .map_err(|m| PyValueError::new_err(format!("{}: {m}", path.display())))?
    } else {
        return Err(PyTypeError::new_err("tonemap: give a render result or the path of an EXR file"));
    };
    let out = guard(|| Ok(py.detach(|| morgana::tonemap::tonemap(&image, &settings))))?;
    Ok((out.height, out.width, PyBytes::new(py, &out.rgb), out.notes))
}
