//! The lattice file format for 3-D scalar fields (temperature grids).
//!
//! # Format (`.mfield`)
//! Six ASCII header lines, then the values:
//! ```text
//! MORGANA-FIELD 1
//! quantity temperature_k        (or delta_temperature_k: a perturbation in K)
//! dims 64 32 64                 (lattice points per axis, each ≥ 2)
//! origin -10 0 -10              (position of lattice point (0, 0, 0), m)
//! spacing 0.5 0.25 0.5          (distance between neighbouring points per axis, m)
//! encoding f64le                (or ascii)
//! <nx·ny·nz values, x varying fastest, then y, then z>
//! ```
//! With `encoding f64le` the values are little-endian IEEE-754 doubles starting right after the
//! newline of the `encoding` line; with `ascii` they are whitespace-separated numbers (any line
//! breaks). Values must be finite; temperatures must be positive. [`write()`] writes this format
//! (atomically, through [`crate::atomic::Staged`]).

use super::Lattice;
use crate::atomic::Staged;
use crate::error::{Error, Location, Result};
use glam::DVec3;
use std::path::Path;

/// First line of an `.mfield` file.
pub const FIELD_MAGIC: &str = "MORGANA-FIELD 1";

/// What a lattice file holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Quantity {
    /// Absolute temperature, K (> 0).
    TemperatureK,
    /// A temperature difference, K.
    DeltaTemperatureK,
}

impl Quantity {
    /// The name the `quantity` header line uses.
    pub fn name(&self) -> &'static str {
        match self {
            Quantity::TemperatureK => "temperature_k",
            Quantity::DeltaTemperatureK => "delta_temperature_k",
        }
    }

    fn parse(s: &str) -> Option<Quantity> {
        match s {
            "temperature_k" => Some(Quantity::TemperatureK),
            "delta_temperature_k" => Some(Quantity::DeltaTemperatureK),
            _ => None,
        }
    }
}

/// How the values are stored.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Encoding {
    /// Little-endian IEEE-754 doubles (`encoding f64le`).
    F64Le,
    /// Whitespace-separated numbers (`encoding ascii`).
    Ascii,
}

/// Reads a lattice file; errors name the file and line.
pub fn read(path: &Path) -> Result<(Quantity, Lattice)> {
    let bytes = std::fs::read(path)
        .map_err(|e| Error::input(Some(Location::file(path)), format!("cannot read field grid: {e}")))?;
    parse(&bytes)
        .map_err(|(line, msg)| Error::input(Some(Location { file: path.to_path_buf(), line, column: None }), msg))
}

/// Parses the bytes of a lattice file; errors carry the 1-based line when there is one.
pub fn parse(bytes: &[u8]) -> std::result::Result<(Quantity, Lattice), (Option<usize>, String)> {
    let mut rest = bytes;
    let mut lines = Vec::with_capacity(6);
    for n in 1..=6 {
        let end =
            rest.iter().position(|&b| b == b'\n').ok_or((Some(n), "the header ends early: it has six lines".into()))?;
        let line = std::str::from_utf8(&rest[..end]).map_err(|_| (Some(n), "header line is not text".to_string()))?;
        lines.push(line.trim_end_matches('\r').to_string());
        rest = &rest[end + 1..];
    }
    if lines[0].trim() != FIELD_MAGIC {
        return Err((Some(1), format!("expected \"{FIELD_MAGIC}\", found \"{}\"", lines[0])));
    }
    let quantity = keyed(&lines[1], 2, "quantity")?;
    let quantity = Quantity::parse(quantity.trim()).ok_or((
        Some(2),
        format!("quantity \"{}\" is not known; allowed: temperature_k, delta_temperature_k", quantity.trim()),
    ))?;
    let dims = numbers::<3>(&lines[2], 3, "dims")?;
    let origin = DVec3::from_array(numbers::<3>(&lines[3], 4, "origin")?);
    let spacing = DVec3::from_array(numbers::<3>(&lines[4], 5, "spacing")?);
    let dims = dims_of(dims)?;
    check_header(dims, origin, spacing)?;
    let header_bytes = bytes.len() - rest.len();
    let (values, places) = match keyed(&lines[5], 6, "encoding")?.trim() {
        "f64le" => binary_values(rest, header_bytes)?,
        "ascii" => ascii_values(rest)?,
        other => return Err((Some(6), format!("encoding \"{other}\" is not known; allowed: f64le, ascii"))),
    };
    check_values(quantity, dims, &values, &places)?;
    let lattice = Lattice::new(dims, origin, spacing, values).map_err(|e| (None, e))?;
    Ok((quantity, lattice))
}

/// Where a value sits in the file: its 1-based line (ascii) or its byte offset (f64le).
#[derive(Clone, Copy, Debug)]
enum Place {
    Line(usize),
    Byte(usize),
}

impl Place {
    /// The line for the error's location, and the words that place the value in the message.
    fn locate(self, index: usize) -> (Option<usize>, String) {
        match self {
            Place::Line(n) => (Some(n), format!("value #{index}")),
            Place::Byte(b) => (None, format!("value #{index} (the f64 at byte {b})")),
        }
    }
}

/// The header's shape checks, each on its own line: at most [`super::MAX_LATTICE_POINTS`]
/// points (line 3), a finite origin (line 4), finite positive spacing (line 5).
fn check_header(dims: [usize; 3], origin: DVec3, spacing: DVec3) -> ParseResult<()> {
    let count = dims.iter().try_fold(1usize, |acc, &n| acc.checked_mul(n));
    if count.is_none_or(|c| c > super::MAX_LATTICE_POINTS) {
        let max = super::MAX_LATTICE_POINTS;
        return Err((Some(3), format!("dims {dims:?}: more than {max} points; make the lattice coarser")));
    }
    if !origin.is_finite() {
        return Err((Some(4), format!("origin {origin} must be finite")));
    }
    if !(spacing.is_finite() && spacing.cmpgt(DVec3::ZERO).all()) {
        return Err((Some(5), format!("spacing {spacing} must be finite and positive on every axis")));
    }
    Ok(())
}

/// One value per lattice point, each finite (and positive for temperatures); errors name the
/// line (ascii) or byte offset (f64le) of the value at fault.
fn check_values(quantity: Quantity, dims: [usize; 3], values: &[f64], places: &[Place]) -> ParseResult<()> {
    let count = dims[0] * dims[1] * dims[2];
    if values.len() != count {
        let [nx, ny, nz] = dims;
        // Ascii: the line where the values run over or stop; f64le: the dims line.
        let line = match places.get(count.min(values.len())).or(places.last()) {
            Some(Place::Line(n)) => *n,
            _ => 3,
        };
        let found = values.len();
        return Err((
            Some(line),
            format!("{found} values for a {nx}×{ny}×{nz} lattice (dims, line 3): expected {count}"),
        ));
    }
    for (i, (&v, &place)) in values.iter().zip(places).enumerate() {
        let (line, what) = place.locate(i);
        if !v.is_finite() {
            return Err((line, format!("{what} is {v}; values must be finite")));
        }
        if quantity == Quantity::TemperatureK && v <= 0.0 {
            return Err((line, format!("{what} is {v} K; temperatures must be positive")));
        }
    }
    Ok(())
}

/// Writes `lattice` as a lattice file, atomically.
pub fn write(path: &Path, quantity: Quantity, lattice: &Lattice, encoding: Encoding) -> Result<()> {
    let io = |e: std::io::Error| Error::internal(format!("cannot write {}: {e}", path.display()));
    let staged = Staged::new(path).map_err(io)?;
    std::fs::write(&staged.temp, to_bytes(quantity, lattice, encoding)).map_err(io)?;
    staged.commit().map_err(io)
}

/// The bytes of a lattice file.
pub fn to_bytes(quantity: Quantity, lattice: &Lattice, encoding: Encoding) -> Vec<u8> {
    let [nx, ny, nz] = lattice.dims;
    let (o, s) = (lattice.origin, lattice.spacing);
    let enc = match encoding {
        Encoding::F64Le => "f64le",
        Encoding::Ascii => "ascii",
    };
    let mut out = format!(
        "{FIELD_MAGIC}\nquantity {}\ndims {nx} {ny} {nz}\norigin {:?} {:?} {:?}\nspacing {:?} {:?} {:?}\nencoding {enc}\n",
        quantity.name(),
        o.x,
        o.y,
        o.z,
        s.x,
        s.y,
        s.z
    )
    .into_bytes();
    match encoding {
        Encoding::F64Le => lattice.values().iter().for_each(|v| out.extend_from_slice(&v.to_le_bytes())),
        Encoding::Ascii => {
            for row in lattice.values().chunks(nx) {
                let line: Vec<String> = row.iter().map(|v| format!("{v:?}")).collect();
                out.extend_from_slice(line.join(" ").as_bytes());
                out.push(b'\n');
            }
        }
    }
    out
}

type ParseResult<T> = std::result::Result<T, (Option<usize>, String)>;

fn keyed<'a>(line: &'a str, n: usize, key: &str) -> ParseResult<&'a str> {
    line.trim()
        .strip_prefix(key)
        .filter(|r| r.starts_with(char::is_whitespace))
        .ok_or((Some(n), format!("expected \"{key} …\", found \"{line}\"")))
}

fn numbers<const N: usize>(line: &str, n: usize, key: &str) -> ParseResult<[f64; N]> {
    let rest = keyed(line, n, key)?;
    let v: Vec<f64> = rest
        .split_whitespace()
        .map(str::parse)
        .collect::<std::result::Result<_, _>>()
        .map_err(|_| (Some(n), format!("{key}: expected {N} numbers, found \"{}\"", rest.trim())))?;
    <[f64; N]>::try_from(v).map_err(|v| (Some(n), format!("{key}: expected {N} numbers, found {}", v.len())))
}

fn dims_of(d: [f64; 3]) -> ParseResult<[usize; 3]> {
    if d.iter().any(|&v| v.fract() != 0.0 || !(2.0..=1e9).contains(&v)) {
        return Err((Some(3), format!("dims {d:?}: expected three whole numbers ≥ 2")));
    }
    Ok(d.map(|v| v as usize))
}

fn binary_values(rest: &[u8], offset: usize) -> ParseResult<(Vec<f64>, Vec<Place>)> {
    if !rest.len().is_multiple_of(8) {
        let whole = rest.len() / 8;
        return Err((
            None,
            format!(
                "the f64le data from byte {offset} holds {} bytes: {whole} whole values and {} bytes over",
                rest.len(),
                rest.len() % 8
            ),
        ));
    }
    let values = rest.chunks_exact(8).map(|c| f64::from_le_bytes(c.try_into().unwrap_or([0; 8]))).collect();
    let places = (0..rest.len() / 8).map(|i| Place::Byte(offset + 8 * i)).collect();
    Ok((values, places))
}

fn ascii_values(rest: &[u8]) -> ParseResult<(Vec<f64>, Vec<Place>)> {
    let (mut values, mut places) = (Vec::new(), Vec::new());
    for (i, raw) in rest.split(|&b| b == b'\n').enumerate() {
        let line = 7 + i;
        let text = std::str::from_utf8(raw).map_err(|e| {
            (Some(line), format!("byte {} of the line is not UTF-8 text (encoding ascii)", e.valid_up_to() + 1))
        })?;
        for tok in text.split_whitespace() {
            let v = tok.parse().map_err(|_| (Some(line), format!("\"{}\" is not a number", clip(tok))))?;
            values.push(v);
            places.push(Place::Line(line));
        }
    }
    Ok((values, places))
}

/// A token shortened for a message.
fn clip(tok: &str) -> String {
    if tok.chars().count() <= 40 { tok.to_string() } else { format!("{}…", tok.chars().take(40).collect::<String>()) }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> Lattice {
        Lattice::from_fn([3, 2, 4], DVec3::new(-1.0, 0.5, 2.0), DVec3::new(0.5, 0.25, 1.0), |p| 280.0 + p.x + 0.1 * p.z)
            .unwrap()
    }

    #[test]
    fn round_trips_in_both_encodings() {
        for enc in [Encoding::F64Le, Encoding::Ascii] {
            let l = sample();
            let (q, back) = parse(&to_bytes(Quantity::TemperatureK, &l, enc)).unwrap();
            assert_eq!(q, Quantity::TemperatureK);
            assert_eq!(back, l, "{enc:?}");
        }
    }

    #[test]
    fn errors_name_the_line_and_what_is_expected() {
        let good = String::from_utf8(to_bytes(Quantity::TemperatureK, &sample(), Encoding::Ascii)).unwrap();
        let bad = good.replace("quantity temperature_k", "quantity pressure");
        let e = parse(bad.as_bytes()).unwrap_err();
        assert_eq!(e.0, Some(2));
        assert!(e.1.contains("allowed: temperature_k"), "{}", e.1);
        let e = parse(good.replace("dims 3 2 4", "dims 3 2").as_bytes()).unwrap_err();
        assert_eq!(e.0, Some(3));
        let e = parse(good.replace("encoding ascii", "encoding hex").as_bytes()).unwrap_err();
        assert_eq!(e.0, Some(6));
        let e = parse(good.replacen("279", "x79", 1).as_bytes()).unwrap_err();
        assert!(e.1.contains("not a number"), "{}", e.1);
        let e = parse(b"MORGANA-FIELD 1\nquantity temperature_k\n").unwrap_err();
        assert!(e.1.contains("header ends early"), "{}", e.1);
        let cold = Lattice::from_fn([2, 2, 2], DVec3::ZERO, DVec3::ONE, |p| p.x - 0.5).unwrap();
        let e = parse(&to_bytes(Quantity::TemperatureK, &cold, Encoding::F64Le)).unwrap_err();
        assert!(e.1.contains("must be positive"), "{}", e.1);
        assert!(parse(&to_bytes(Quantity::DeltaTemperatureK, &cold, Encoding::F64Le)).is_ok());
    }

    #[test]
    fn writes_atomically_to_disk() {
        let dir = std::env::temp_dir().join(format!("morgana-field-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("t.mfield");
        write(&path, Quantity::DeltaTemperatureK, &sample(), Encoding::F64Le).unwrap();
        let (q, l) = read(&path).unwrap();
        assert_eq!((q, l), (Quantity::DeltaTemperatureK, sample()));
        std::fs::remove_dir_all(&dir).unwrap();
        let e = read(&dir.join("missing.mfield")).unwrap_err().to_string();
        assert!(e.contains("missing.mfield") && e.contains("cannot read"), "{e}");
    }
}
