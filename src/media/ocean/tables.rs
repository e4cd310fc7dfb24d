//! Reading the ocean tables (built in, see [`super::builtin`], or a scene's `data_dir`): every CSV
//! keeps its provenance header in `#` lines, then a header row, then numbers.

use crate::spectrum::Tabulated;
use std::path::Path;

/// Rows of numbers of a CSV file with at least `columns` columns; `#` lines and non-numeric
/// rows before the first numeric one (the header) are skipped. Errors name the file and line.
pub fn numeric_rows(path: &Path, columns: usize) -> Result<Vec<Vec<f64>>, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("cannot read ocean table {}: {e}", path.display()))?;
    numeric_rows_text(path, &text, columns)
}

/// [`numeric_rows`] of a table's text; `path` names it in errors.
pub fn numeric_rows_text(path: &Path, text: &str, columns: usize) -> Result<Vec<Vec<f64>>, String> {
    let mut rows = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let parsed: Option<Vec<f64>> = line.split(',').take(columns).map(|c| c.trim().parse().ok()).collect();
        match parsed {
            Some(v) if v.len() == columns && v.iter().all(|x| x.is_finite()) => rows.push(v),
            _ if rows.is_empty() => {}
            _ => return Err(format!("{}:{}: expected {columns} numbers, found \"{line}\"", path.display(), i + 1)),
        }
    }
    if rows.is_empty() {
        return Err(format!("{}: no data rows", path.display()));
    }
    Ok(rows)
}

/// Column `col` against column 0 as a piecewise-linear table.
pub fn column(path: &Path, rows: &[Vec<f64>], col: usize) -> Result<Tabulated, String> {
    let nm = rows.iter().map(|r| r[0]).collect();
    let v = rows.iter().map(|r| r[col]).collect();
    Tabulated::new(nm, v).map_err(|e| format!("{}: {e}", path.display()))
}

/// `t` at λ, held at its end values outside its domain.
pub fn clamped(t: &Tabulated, wavelength_nm: f64) -> f64 {
    let (lo, hi) = t.domain_nm();
    t.eval(wavelength_nm.clamp(lo, hi))
}
