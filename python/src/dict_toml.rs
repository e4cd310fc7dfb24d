//! A scene given as Python dicts and lists (the TOML structure: tables are dicts, arrays of
//! tables are lists of dicts) written as TOML text, which the library then reads as it reads a
//! file: `Scene.from_dict(d)` is `Scene.from_str(toml_text(d))`.

use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use toml::Value;

/// The deepest nesting of dicts and lists accepted (a scene needs four or five levels).
const MAX_DEPTH: usize = 64;

/// The TOML text of `d`, a dict of TOML values; a value TOML cannot hold (None, a set, an
/// object) is a `TypeError` naming its key path.
pub fn toml_text(d: &Bound<'_, PyAny>) -> PyResult<String> {
    let v = value(d, "", 0)?;
    if !v.is_table() {
        return Err(PyTypeError::new_err(format!("a scene is a dict of TOML tables, not {}", type_name(d))));
    }
    toml::to_string(&v).map_err(|e| PyTypeError::new_err(format!("the dict cannot be written as TOML: {e}")))
}

fn type_name(v: &Bound<'_, PyAny>) -> String {
    v.get_type().name().map(|n| n.to_string()).unwrap_or_else(|_| "an object".into())
}

fn value(v: &Bound<'_, PyAny>, path: &str, depth: usize) -> PyResult<Value> {
    let at = if path.is_empty() { "the scene".to_string() } else { format!("`{path}`") };
    if depth > MAX_DEPTH {
        return Err(PyTypeError::new_err(format!("{at}: nested deeper than {MAX_DEPTH} levels")));
    }
    if v.is_instance_of::<PyBool>() {
        return Ok(Value::Boolean(v.extract()?));
    }
    if v.is_instance_of::<PyInt>() {
        let i: i64 =
            v.extract().map_err(|_| PyTypeError::new_err(format!("{at}: the integer does not fit in 64 bits")))?;
        return Ok(Value::Integer(i));
    }
    if v.is_instance_of::<PyFloat>() {
        return Ok(Value::Float(v.extract()?));
    }
    if v.is_instance_of::<PyString>() {
        return Ok(Value::String(v.extract()?));
    }
    if let Ok(d) = v.cast::<PyDict>() {
        let mut t = toml::map::Map::new();
        for (k, x) in d.iter() {
            let Ok(key) = k.extract::<String>() else {
                return Err(PyTypeError::new_err(format!("{at}: keys must be strings, found {}", type_name(&k))));
            };
            let sub = if path.is_empty() { key.clone() } else { format!("{path}.{key}") };
            t.insert(key, value(&x, &sub, depth + 1)?);
        }
        return Ok(Value::Table(t));
    }
    if v.is_instance_of::<PyList>() || v.is_instance_of::<PyTuple>() {
        let mut a = Vec::new();
        for (i, x) in v.try_iter()?.enumerate() {
            a.push(value(&x?, &format!("{path}[{i}]"), depth + 1)?);
        }
        return Ok(Value::Array(a));
    }
    // NumPy scalars and other numbers: integers by `__index__`, reals by `__float__`.
    if v.hasattr("__index__")? {
        return value(&v.call_method0("__index__")?, path, depth + 1);
    }
    if v.hasattr("__float__")? && !v.hasattr("__len__")? {
        return Ok(Value::Float(v.call_method0("__float__")?.extract()?));
    }
    Err(PyTypeError::new_err(format!(
        "{at}: {} has no TOML form; use dicts, lists, str, int, float and bool",
        type_name(v)
    )))
}
