//! The native module `morgana._native` of the Python package `morgana` (python/morgana/ wraps
//! it in documented Python classes and NumPy arrays). Every entry point calls the same library
//! code as the `morgana` command, so Python and the CLI give identical results for the same
//! scene and seed. Errors become Python exceptions (module `errors`); panics are caught at the
//! boundary.

mod dict_toml;
mod errors;
mod render;
mod scene;
mod tools;

use pyo3::prelude::*;

/// The native module.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("SceneError", m.py().get_type::<errors::SceneError>())?;
    m.add("VERSION", env!("CARGO_PKG_VERSION"))?;
    m.add_class::<scene::NativeScene>()?;
    m.add_class::<render::NativeResult>()?;
    m.add_function(wrap_pyfunction!(render::render, m)?)?;
    m.add_function(wrap_pyfunction!(tools::refraction, m)?)?;
    m.add_function(wrap_pyfunction!(tools::terrestrial, m)?)?;
    m.add_function(wrap_pyfunction!(tools::lines_of_sight, m)?)?;
    m.add_function(wrap_pyfunction!(tools::trace, m)?)?;
    m.add_function(wrap_pyfunction!(tools::luminaire, m)?)?;
    m.add_function(wrap_pyfunction!(tools::tonemap, m)?)?;
    Ok(())
}
