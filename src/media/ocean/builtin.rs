//! The ocean tables morgana carries in its binary, and where a scene's own tables come from.
//!
//! Each table is a CSV in `src/media/ocean/data/`, embedded with `include_str!`; its `#` header
//! cites the paper, the table, the units and where the numbers were transcribed from:
//!
//! | file | what | source |
//! |---|---|---|
//! | [`POPE_FRY_FILE`] | pure-water absorption a_w(λ), 380–727.5 nm, m⁻¹ | Pope & Fry (1997) |
//! | [`SMITH_BAKER_FILE`] | clearest natural water a_w(λ), 200–800 nm, m⁻¹ | Smith & Baker (1981) |
//! | [`BRICAUD_FILE`] | A_p, E_p, A_φ, E_φ, 400–700 nm | Bricaud et al. (1998) |
//! | [`FA7_FILE`] | CDOM fluorescence amplitude A₀(λ'), 310–550 nm, nm⁻¹ | Hawes (1992), FA7 |
//! | [`PETZOLD_FILE`] | average-particle phase function, 0.1–180°, sr⁻¹ | Mobley et al. (1993), Table 2 |
//!
//! A scene may name a folder of its own tables (`data_dir`): it must hold files of these names
//! in the same layout. Nothing is read from outside the binary otherwise.
//!
//! `tests/builtin_ocean_data.rs` compares each embedded table with the project's shared copies
//! (`../shared/data/ocean`, where present) to the printed precision.
//!
//! # References
//! - Pope & Fry, Appl. Opt. 36 (1997), 8710–8723; Smith & Baker, Appl. Opt. 20 (1981), 177–184.
//! - Bricaud, Morel, Babin, Allali & Claustre, JGR 103 (1998), 31033–31044.
//! - Hawes, MS thesis, University of South Florida (1992), Table 3; Mobley, *Light and Water*
//!   (1994), §5.12.
//! - Mobley et al., Appl. Opt. 32 (1993), 7484–7504, Table 2; Petzold, SIO Ref. 72-78 (1972).

use super::tables::{column, numeric_rows_text};
use crate::media::inelastic::Fa7;
use crate::media::phase::{PhaseFunction, TabulatedPhase};
use crate::spectrum::Tabulated;
use std::borrow::Cow;
use std::path::{Path, PathBuf};

/// File name of Pope & Fry's (1997) pure-water absorption table, m⁻¹.
pub const POPE_FRY_FILE: &str = "pope_fry_1997_water_absorption.csv";
/// File name of Smith & Baker's (1981) clearest-natural-water absorption table, m⁻¹.
pub const SMITH_BAKER_FILE: &str = "smith_baker_1981_water_absorption.csv";
/// File name of Bricaud et al.'s (1998) particle and phytoplankton absorption coefficients.
pub const BRICAUD_FILE: &str = "bricaud_1998_particle_phytoplankton_absorption.csv";
/// File name of Hawes' (1992) FA7 CDOM fluorescence amplitude A₀(λ'), nm⁻¹.
pub const FA7_FILE: &str = "hawes_1992_cdom_fluorescence_FA7.csv";
/// File name of Petzold's average-particle phase function, sr⁻¹.
pub const PETZOLD_FILE: &str = "petzold_average_particle_phase_function.csv";

/// Every embedded table: (file name, text).
pub const TABLES: &[(&str, &str)] = &[
    (POPE_FRY_FILE, include_str!("data/pope_fry_1997_water_absorption.csv")),
    (SMITH_BAKER_FILE, include_str!("data/smith_baker_1981_water_absorption.csv")),
    (BRICAUD_FILE, include_str!("data/bricaud_1998_particle_phytoplankton_absorption.csv")),
    (FA7_FILE, include_str!("data/hawes_1992_cdom_fluorescence_FA7.csv")),
    (PETZOLD_FILE, include_str!("data/petzold_average_particle_phase_function.csv")),
];

/// The text of the embedded table `name` (one of the `*_FILE` constants).
pub fn text(name: &str) -> Option<&'static str> {
    TABLES.iter().find(|(n, _)| *n == name).map(|(_, t)| *t)
}

/// Where the ocean model's tables come from.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub enum OceanData {
    /// The tables embedded in morgana.
    #[default]
    BuiltIn,
    /// A folder holding files named like the embedded ones (a scene's `data_dir`).
    Folder(PathBuf),
}

impl OceanData {
    /// The label errors use for table `name` and its text.
    pub fn read(&self, name: &str) -> Result<(PathBuf, Cow<'static, str>), String> {
        match self {
            OceanData::BuiltIn => {
                let t = text(name).ok_or_else(|| format!("morgana has no built-in ocean table {name}"))?;
                Ok((Path::new("<built-in>").join(name), Cow::Borrowed(t)))
            }
            OceanData::Folder(dir) => {
                let path = dir.join(name);
                let t = std::fs::read_to_string(&path).map_err(|e| {
                    format!(
                        "cannot read ocean table {}: {e} (a data_dir must hold {name}; remove data_dir to use the built-in tables)",
                        path.display()
                    )
                })?;
                Ok((path, Cow::Owned(t)))
            }
        }
    }

    /// Rows of table `name` with at least `columns` numbers.
    pub fn rows(&self, name: &str, columns: usize) -> Result<(PathBuf, Vec<Vec<f64>>), String> {
        let (path, text) = self.read(name)?;
        let rows = numeric_rows_text(&path, &text, columns)?;
        Ok((path, rows))
    }

    /// Column `col` of a two-or-more-column table against its first column.
    pub fn column(&self, name: &str, columns: usize, col: usize) -> Result<Tabulated, String> {
        let (path, rows) = self.rows(name, columns)?;
        column(&path, &rows, col)
    }

    /// Hawes' FA7 CDOM fluorescence redistribution.
    pub fn fa7(&self) -> Result<Fa7, String> {
        let (path, text) = self.read(FA7_FILE)?;
        Fa7::from_csv_text(&path, &text)
    }

    /// Petzold's average-particle phase function.
    pub fn petzold(&self) -> Result<PhaseFunction, String> {
        let (path, text) = self.read(PETZOLD_FILE)?;
        TabulatedPhase::from_csv_text(&path, &text).map(PhaseFunction::Tabulated)
    }
}

/// Pope & Fry's pure-water absorption a_w(λ), m⁻¹, 380–727.5 nm (built in).
pub fn pope_fry() -> Tabulated {
    OceanData::BuiltIn.column(POPE_FRY_FILE, 2, 1).expect("the built-in Pope & Fry table parses (tested)")
}

/// Petzold's average-particle phase function (built in).
pub fn petzold() -> PhaseFunction {
    OceanData::BuiltIn.petzold().expect("the built-in Petzold table parses (tested)")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_builtin_table_parses_with_its_reader() {
        let d = OceanData::BuiltIn;
        assert_eq!(d.rows(POPE_FRY_FILE, 2).unwrap().1.len(), 140);
        assert_eq!(d.rows(SMITH_BAKER_FILE, 2).unwrap().1.len(), 61);
        assert_eq!(d.rows(BRICAUD_FILE, 5).unwrap().1.len(), 151);
        assert_eq!(d.fa7().unwrap().excitation_nm(), (310.0, 550.0));
        let PhaseFunction::Tabulated(p) = d.petzold().unwrap() else { panic!("tabulated") };
        assert!((p.mean_cosine() - 0.924).abs() < 0.005, "{}", p.mean_cosine());
    }

    #[test]
    fn a_missing_folder_table_names_the_file_and_the_fix() {
        let e = OceanData::Folder("/no/such/dir".into()).read(FA7_FILE).unwrap_err();
        assert!(e.contains("/no/such/dir/hawes_1992") && e.contains("remove data_dir"), "{e}");
        assert!(OceanData::BuiltIn.read("nope.csv").is_err());
    }
}
