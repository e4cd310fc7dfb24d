//! The library's errors as Python exceptions: input errors in a scene become
//! `morgana.SceneError` with `.file`, `.line`, `.column` and `.field`; other input errors
//! `ValueError`; internal failures `RuntimeError`; a panic in the library is caught at the
//! boundary and becomes `RuntimeError` (the interpreter survives).

use morgana::error::{Error, InputError};
use pyo3::IntoPyObjectExt;
use pyo3::exceptions::{PyFileNotFoundError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::Path;

pyo3::create_exception!(
    _native,
    SceneError,
    pyo3::exceptions::PyValueError,
    "A scene (file, string or dict) is wrong.\n\nAttributes: file (the file named in the message, or <string>/<dict>), line and column (1-based, or None), field (the TOML key at fault, or None) and message (the text without its location). str(e) is the CLI's message, file:line:column: message."
);

/// The key a TOML error points at: the first `` field `name` `` in the message, else the key
/// written on the error's line of `source` (`name = value`), else the table of a `[table]` line.
pub fn field_of(e: &InputError, source: Option<&str>) -> Option<String> {
    if let Some(i) = e.message.find("field `") {
        let rest = &e.message[i + 7..];
        if let Some(j) = rest.find('`') {
            return Some(rest[..j].to_string());
        }
    }
    let line = e.location.as_ref()?.line?;
    let text = source?.lines().nth(line - 1)?.split('#').next()?.trim();
    if let Some((k, _)) = text.split_once('=') {
        let k = k.trim().trim_matches('"');
        return (!k.is_empty()).then(|| k.rsplit('.').next().unwrap_or(k).trim().to_string());
    }
    let table = text.trim_start_matches('[').trim_end_matches(']').trim();
    (!table.is_empty()).then(|| table.to_string())
}

/// A `SceneError` for an error found while loading a scene whose text is `source`.
pub fn scene_error(py: Python<'_>, e: Error, source: Option<&str>) -> PyErr {
    match e {
        Error::Input(ie) => {
            let field = field_of(&ie, source);
            let loc = ie.location.clone();
            let file = loc.as_ref().map(|l| l.file.display().to_string());
            let (line, column) = loc.map_or((None, None), |l| (l.line, l.column));
            let text = ie.to_string();
            let err = SceneError::new_err(text.clone());
            let value = err.value(py);
            let set = |name: &str, v: Bound<'_, PyAny>| value.setattr(name, v).ok();
            set("message", opt(py, Some(ie.message.clone())));
            set("file", opt(py, file));
            set("line", opt(py, line));
            set("column", opt(py, column));
            set("field", opt(py, field));
            err
        }
        Error::Internal(m) => PyRuntimeError::new_err(format!("internal error: {m}")),
    }
}

fn opt<'py, T: IntoPyObject<'py>>(py: Python<'py>, v: Option<T>) -> Bound<'py, PyAny> {
    match v.and_then(|v| v.into_bound_py_any(py).ok()) {
        Some(b) => b,
        None => py.None().into_bound(py),
    }
}

/// A `SceneError` for an input error placed in a file (an atmosphere or luminaire file), else as
/// [`arg_error`].
pub fn located_error(py: Python<'_>, e: Error) -> PyErr {
    match e {
        Error::Input(ie) if ie.location.is_some() => {
            let source = ie.location.as_ref().and_then(|l| std::fs::read_to_string(&l.file).ok());
            scene_error(py, Error::Input(ie), source.as_deref())
        }
        e => arg_error(e),
    }
}

/// A `ValueError` (bad argument) or `RuntimeError` (internal failure) for a library error.
pub fn arg_error(e: Error) -> PyErr {
    match e {
        Error::Input(ie) => PyValueError::new_err(ie.to_string()),
        Error::Internal(m) => PyRuntimeError::new_err(format!("internal error: {m}")),
    }
}

/// `FileNotFoundError` when `path` does not exist (before the library reports it as bad input).
pub fn must_exist(path: &Path) -> PyResult<()> {
    if path.exists() {
        return Ok(());
    }
    Err(PyFileNotFoundError::new_err((2i32, "No such file or directory", path.display().to_string())))
}

/// Runs `f`, turning a panic into `RuntimeError` (never a crash of the interpreter, and not
/// pyo3's `PanicException`, which `except Exception` does not catch).
pub fn guard<T>(f: impl FnOnce() -> PyResult<T>) -> PyResult<T> {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(r) => r,
        Err(payload) => {
            Err(PyRuntimeError::new_err(format!("internal error (a panic in morgana): {}", panic_text(&payload))))
        }
    }
}

/// The message of a panic's payload.
pub fn panic_text(payload: &Box<dyn std::any::Any + Send>) -> String {
    if let Some(s) = payload.downcast_ref::<&str>() {
        (*s).to_string()
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s.clone()
    } else {
        "unknown panic".to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use morgana::error::Location;

    #[test]
    fn the_field_comes_from_the_message_or_the_line() {
        let at = |line| Some(Location { file: "s.toml".into(), line: Some(line), column: Some(1) });
        let e = InputError { location: at(1), message: "camera: field `fov_deg` is not used here".into() };
        assert_eq!(field_of(&e, None).as_deref(), Some("fov_deg"));
        let src = "[camera]\nwidth = -3 # a comment\n";
        let e = InputError { location: at(2), message: "out of range".into() };
        assert_eq!(field_of(&e, Some(src)).as_deref(), Some("width"));
        let e = InputError { location: at(1), message: "missing".into() };
        assert_eq!(field_of(&e, Some(src)).as_deref(), Some("camera"));
        let e = InputError { location: None, message: "no place".into() };
        assert_eq!(field_of(&e, Some(src)), None);
    }
}
