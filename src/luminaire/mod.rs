//! Luminaire photometry: readers for the files manufacturers publish, one photometric web model,
//! and what emission needs from it.
//!
//! Every reader turns its format into a [`Photometry`]: header facts (maker, name, lamps, stated
//! flux, symmetry, opening), a [`PhotometricWeb`], the intensity I(C, γ) in candela on a full
//! grid of angles, and the emission spectrum when the file carries one (TM-33, GLDF). The
//! formats are the closed set [`Format`], one reader file each: IES LM-63 (`ies.rs`), EULUMDAT
//! (`eulumdat.rs`), IES TM-33-18/-23 (`tm33.rs`), GLDF containers (`gldf.rs`, which reads its
//! photometry with the others), and CIBSE TM14, recognised but not read (`tm14.rs`).
//!
//! # Conventions
//! The luminaire frame has x along the luminaire's length (the C0 direction), y along C90 and z
//! up, so the nadir (γ = 0) is −z; C turns counterclockwise seen from above. This is the C-γ
//! system of CIE 121 and LM-63 type C, with C0 along the luminaire's length as both LM-63 and
//! EULUMDAT define it. How the frame is placed in a scene is [`Placement`].
//!
//! # Units
//! Intensities in cd (EULUMDAT's cd/klm are scaled by the lamp flux of the first lamp set and the
//! conversion factor; LM-63 values by the candela multiplier and ballast factor), flux in lm,
//! dimensions in m.

mod beam;
mod emission;
mod eulumdat;
mod format;
mod gldf;
mod ies;
mod opening;
mod parse_error;
mod photometric;
mod placement;
mod planes;
mod polar_png;
mod report;
mod sampler;
mod symmetry;
pub mod text;
mod tilt;
mod tm14;
mod tm33;
mod web;
mod xml;

pub use beam::{PlaneCurve, plane_curve, spread_angle_deg};
pub use emission::EmissionSpectrum;
pub use format::Format;
pub use gldf::MAX_ENTRY_BYTES as GLDF_MAX_ENTRY_BYTES;
pub use opening::{Kind as OpeningKind, Opening};
pub use parse_error::ParseError;
pub use photometric::{luminous_fraction_in, per_candela};
pub use placement::Placement;
pub use polar_png::{nice_ceiling, write_polar_png};
pub use report::summary;
pub use sampler::{WebSampler, sample_linear};
pub use symmetry::Symmetry;
pub use text::SourceText;
pub use tilt::Tilt;
pub use web::{Cell, PhotometricWeb, WebAxes};

use crate::error::{Error, Location, Result};
use std::path::Path;

/// LM-63 photometric types (LM-63-2002 §3): how the web's angles are laid out.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PhotometricType {
    /// Type A: vertical angles are elevations, horizontal angles about the vertical axis
    /// (automotive).
    A,
    /// Type B: angles about the luminaire's horizontal transverse axis (floodlights).
    B,
    /// Type C: C-planes about the vertical axis, γ from the nadir (most luminaires).
    C,
}

/// One lamp set as the file lists it.
#[derive(Clone, Debug, PartialEq)]
pub struct LampSet {
    /// Number of lamps (negative in EULUMDAT files that mark absolute photometry).
    pub count: i64,
    /// Lamp type as the file names it.
    pub description: String,
    /// Total rated flux of the set, lm (`None` for absolute photometry).
    pub flux_lm: Option<f64>,
    /// Colour temperature as the file writes it (free text).
    pub colour_temperature: String,
    /// Colour rendering as the file writes it (free text).
    pub colour_rendering: String,
    /// Wattage including ballast, W.
    pub watts: Option<f64>,
}

/// A photometric file, read and checked.
#[derive(Clone, Debug)]
pub struct Photometry {
    /// E.g. "IES LM-63-2002", "EULUMDAT".
    pub format: String,
    /// How the bytes were decoded (see [`text`]).
    pub encoding: &'static str,
    /// Manufacturer as the file names it.
    pub manufacturer: String,
    /// Luminaire name.
    pub luminaire: String,
    /// Catalogue or luminaire number.
    pub catalogue: String,
    /// Lamp sets as the file lists them; the first is the one the intensities refer to.
    pub lamps: Vec<LampSet>,
    /// Rated lamp flux the intensities refer to, lm (`None` for absolute photometry).
    pub lamp_flux_lm: Option<f64>,
    /// Luminaire flux the file states (EULUMDAT: LORL × lamp flux), lm.
    pub stated_flux_lm: Option<f64>,
    /// Absolute photometry: the intensities are candela of this luminaire, not per rated lamp flux.
    pub absolute: bool,
    /// How the file lays out its angles.
    pub photometric_type: PhotometricType,
    /// The symmetry the file declares.
    pub symmetry: Symmetry,
    /// Planes × angles as stored in the file (before symmetry expansion).
    pub stored_grid: (usize, usize),
    /// The luminous opening, from the file's dimensions.
    pub opening: Opening,
    /// Input power the file states, W.
    pub input_watts: Option<f64>,
    /// LM-63 lamp tilt data, when the file has any.
    pub tilt: Option<Tilt>,
    /// Downward flux fraction the file states, %.
    pub dff_percent: Option<f64>,
    /// Light output ratio of the luminaire the file states, %.
    pub lorl_percent: Option<f64>,
    /// Tilt of the luminaire during measurement (EULUMDAT field 25), degrees.
    pub measurement_tilt_deg: Option<f64>,
    /// The intensity I(C, γ), cd, on the full grid.
    pub web: PhotometricWeb,
    /// Things a reader tolerated (junk after the table, a leading blank line, …).
    pub notes: Vec<String>,
    /// The emission spectrum the file carries (TM-33 `SpectralData`, GLDF `Spectrum`).
    pub spectrum: Option<EmissionSpectrum>,
}

impl Photometry {
    /// Φ of the web by its own quadrature, lm.
    pub fn flux_lm(&self) -> f64 {
        self.web.flux_lm()
    }

    /// (web flux − stated flux)/stated flux, when the file states a luminaire flux.
    pub fn flux_mismatch(&self) -> Option<f64> {
        self.stated_flux_lm.filter(|s| *s > 0.0).map(|s| self.flux_lm() / s - 1.0)
    }
}

/// How a text format is recognised and read (LM-63, EULUMDAT, TM14; [`Format`] dispatches).
pub struct Reader {
    /// Format name for messages, e.g. "IES LM-63".
    pub name: &'static str,
    /// Lower-case file extensions, without the dot.
    pub extensions: &'static [&'static str],
    /// Whether the decoded text looks like this format (for files with other extensions).
    pub sniff: fn(&SourceText) -> bool,
    /// Reads the decoded text of the file at `path` (whose directory resolves files it names).
    pub read: fn(&SourceText, &Path) -> std::result::Result<Photometry, ParseError>,
    /// False for a format morgana recognises but cannot read (its `read` explains why).
    pub implemented: bool,
}

/// The largest intensity-table value a photometric file may hold (cd, or cd/klm): a thousand
/// times the brightest searchlights (~10⁹ cd). Larger values are input errors at their line,
/// so that no multiplier can carry a table to infinity.
pub const MAX_TABLE_VALUE: f64 = 1e12;
/// The largest candela multiplier or conversion factor a photometric file may state.
pub const MAX_MULTIPLIER: f64 = 1e6;
/// The largest luminous-opening dimension a file may give, in its own units (feet or metres):
/// 10 km or 10,000 ft, far beyond any luminaire, and a bound that keeps sizes finite in mm.
pub const MAX_OPENING: f64 = 1e4;

/// The formats morgana can read, for messages ("IES LM-63 (.ies), EULUMDAT (.ldt, .eul), …").
pub fn supported_formats() -> String {
    Format::ALL
        .iter()
        .copied()
        .filter(|f| f.implemented())
        .map(|f| {
            format!("{} ({})", f.name(), f.extensions().iter().map(|e| format!(".{e}")).collect::<Vec<_>>().join(", "))
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// Photometric files larger than this are refused before they are read, MiB.
pub const MAX_FILE_MIB: u64 = 256;

/// Reads a photometric file: the reader is chosen by extension, else by content.
pub fn load_file(path: &Path) -> Result<Photometry> {
    load_file_variant(path, None)
}

/// [`load_file`], choosing a GLDF container's `variant` (by its id) instead of the first.
pub fn load_file_variant(path: &Path, variant: Option<&str>) -> Result<Photometry> {
    let located = |m: String| Error::input(Some(Location::file(path)), m);
    let len = std::fs::metadata(path).map_err(|e| located(format!("cannot read luminaire file: {e}")))?.len();
    if len > MAX_FILE_MIB << 20 {
        return Err(located(format!(
            "luminaire file of {} MiB; photometric files are far smaller (morgana's limit is {MAX_FILE_MIB} MiB)",
            len >> 20
        )));
    }
    let bytes = std::fs::read(path).map_err(|e| located(format!("cannot read luminaire file: {e}")))?;
    read_bytes_variant(&bytes, path, variant)
}

/// Reads a photometric file's bytes; `path` names it in errors, chooses the reader by its
/// extension and resolves files it refers to.
pub fn read_bytes(bytes: &[u8], path: &Path) -> Result<Photometry> {
    read_bytes_variant(bytes, path, None)
}

/// [`read_bytes`], choosing a GLDF container's `variant`; naming one for another format is an
/// error.
pub fn read_bytes_variant(bytes: &[u8], path: &Path, variant: Option<&str>) -> Result<Photometry> {
    let format = Format::by_extension(path).or_else(|| Format::sniff(bytes)).ok_or_else(|| {
        Error::input(
            Some(Location::file(path)),
            format!("not a photometric file morgana recognises; supported formats: {}", supported_formats()),
        )
    })?;
    if let Some(v) = variant
        && format != Format::Gldf
    {
        return Err(Error::input(
            Some(Location::file(path)),
            format!(
                "variant \"{v}\" is given but this is a {} file; variants are chosen in GLDF containers",
                format.name()
            ),
        ));
    }
    format.read(bytes, path, variant).map_err(|e| e.into_error(path))
}

/// What `morgana luminaire FILE [--png PNG]` does: reads the file, writes the polar diagram
/// (atomically) when asked, and returns the summary to print.
pub fn inspect(file: &Path, png: Option<&Path>) -> Result<String> {
    inspect_variant(file, png, None)
}

/// [`inspect`] for a chosen GLDF `variant`.
pub fn inspect_variant(file: &Path, png: Option<&Path>, variant: Option<&str>) -> Result<String> {
    let p = load_file_variant(file, variant)?;
    let mut text = summary(&p);
    if let Some(png) = png {
        let staged = crate::atomic::Staged::new(png)
            .map_err(|e| Error::internal(format!("cannot write {}: {e}", png.display())))?;
        write_polar_png(&p, &staged.temp)
            .map_err(|e| Error::internal(format!("cannot write {}: {e}", png.display())))?;
        staged.commit().map_err(|e| Error::internal(format!("cannot write {}: {e}", png.display())))?;
        text.push_str(&format!("wrote {}\n", png.display()));
    }
    Ok(text)
}
