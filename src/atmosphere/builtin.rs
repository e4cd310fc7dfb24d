//! The atmospheres shipped in `atmospheres/`, embedded so they work from any directory:
//! `Atmosphere::builtin("usa76")`, and [`resolve`] for a command-line argument that is either a
//! file or a built-in name.

use super::Atmosphere;
use super::file::{self, Files};
use crate::error::{Error, Result};
use std::path::Path;

/// (name, TOML source).
const ATMOSPHERES: &[(&str, &str)] = &[
    ("usa76", include_str!("../../atmospheres/usa76.toml")),
    ("hot_road", include_str!("../../atmospheres/hot_road.toml")),
    ("inversion", include_str!("../../atmospheres/inversion.toml")),
    ("fata_morgana", include_str!("../../atmospheres/fata_morgana.toml")),
    ("tropical", include_str!("../../atmospheres/tropical.toml")),
];

/// Data files the built-in atmospheres refer to.
const FILES: &[(&str, &str)] = &[("tropical_afgl1986.csv", include_str!("../../atmospheres/tropical_afgl1986.csv"))];

/// Names accepted by [`Atmosphere::builtin`].
pub const BUILTIN_NAMES: &[&str] = &["usa76", "hot_road", "inversion", "fata_morgana", "tropical"];

impl Atmosphere {
    /// A built-in atmosphere by name (see [`BUILTIN_NAMES`]).
    pub fn builtin(name: &str) -> Result<Atmosphere> {
        let Some((_, source)) = ATMOSPHERES.iter().find(|(n, _)| *n == name) else {
            return Err(Error::input(
                None,
                format!("no built-in atmosphere \"{name}\"; built-in: {}", BUILTIN_NAMES.join(", ")),
            ));
        };
        let label = format!("<built-in atmosphere {name}>");
        file::load_str(source, Path::new(&label), &Files::Embedded(FILES))
    }
}

/// An atmosphere file when `arg` names an existing file, else the built-in atmosphere of that name.
pub fn resolve(arg: &str) -> Result<Atmosphere> {
    let path = Path::new(arg);
    if path.is_file() {
        return file::load(path);
    }
    if BUILTIN_NAMES.contains(&arg) {
        return Atmosphere::builtin(arg);
    }
    Err(Error::input(
        None,
        format!("--atmosphere {arg}: no such file, and not a built-in atmosphere ({})", BUILTIN_NAMES.join(", ")),
    ))
}
