//! The one reader of numeric CSV tables (spectra, atmosphere profiles, index profiles, inelastic
//! redistribution tables): `#` comment lines and blank lines are skipped, the first data row may
//! be a header (a row that is not all numbers), separators are commas, semicolons or tabs.
//! Errors carry the 1-based line number.

/// Whether a row may hold more columns than are named (the extra ones are ignored).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Extra {
    /// Every row holds exactly the named columns.
    Refused,
    /// Rows may hold more columns; only the first ones are read.
    Ignored,
}

/// Parses the columns `names` from every data row; returns one vector per column.
pub fn parse_columns(text: &str, names: &[&str], extra: Extra) -> Result<Vec<Vec<f64>>, (usize, String)> {
    let mut cols = vec![Vec::new(); names.len()];
    let mut seen_row = false;
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = line.split([',', ';', '\t']).map(str::trim).collect();
        let wanted = match extra {
            Extra::Ignored => names.len().min(fields.len()),
            Extra::Refused => fields.len(),
        };
        let parsed: Option<Vec<f64>> = fields[..wanted].iter().map(|c| c.parse().ok()).collect();
        match parsed {
            Some(row) if row.len() == names.len() => {
                for (c, v) in cols.iter_mut().zip(row) {
                    c.push(v);
                }
            }
            None if !seen_row => {}
            _ => {
                return Err((
                    i + 1,
                    format!("expected {} numbers ({}), found \"{line}\"", names.len(), names.join(", ")),
                ));
            }
        }
        seen_row = true;
    }
    if cols.first().is_none_or(Vec::is_empty) {
        return Err((1, format!("no data rows ({})", names.join(", "))));
    }
    Ok(cols)
}

/// Exactly the columns `names` (a row with more or fewer is an error).
pub fn parse_numeric_columns(text: &str, names: &[&str]) -> Result<Vec<Vec<f64>>, (usize, String)> {
    parse_columns(text, names, Extra::Refused)
}

/// Two columns (wavelength_nm, value) from rows that may hold more.
pub fn parse_two_column_csv(text: &str) -> Result<(Vec<f64>, Vec<f64>), (usize, String)> {
    let mut cols = parse_columns(text, &["wavelength_nm", "value"], Extra::Ignored)?.into_iter();
    match (cols.next(), cols.next()) {
        (Some(nm), Some(values)) => Ok((nm, values)),
        _ => Err((1, "no data rows (wavelength_nm, value)".into())),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_columns_skips_comments_and_one_header_and_names_bad_lines() {
        let t = "# source: x\nheight_m,n\n0, 1.0003\n10;1.0002\n";
        let c = parse_numeric_columns(t, &["height_m", "n"]).unwrap();
        assert_eq!(c, vec![vec![0.0, 10.0], vec![1.0003, 1.0002]]);
        let e = parse_numeric_columns("0,1\n1,2,3\n", &["a", "b"]).unwrap_err();
        assert_eq!(e.0, 2);
        assert!(e.1.contains("expected 2 numbers (a, b)"), "{}", e.1);
        assert_eq!(parse_numeric_columns("0,1\nx,y\n", &["a", "b"]).unwrap_err().0, 2);
        assert!(parse_numeric_columns("# nothing\n", &["a"]).is_err());
    }

    #[test]
    fn two_columns_skip_comments_a_header_and_extra_columns_and_report_bad_lines() {
        let (nm, v) = parse_two_column_csv("# source: x\nwavelength_nm,value\n400,0.1,x\n500, 0.2\n").unwrap();
        assert_eq!(nm, vec![400.0, 500.0]);
        assert_eq!(v, vec![0.1, 0.2]);
        let e = parse_two_column_csv("400,0.1\n500,abc\n").unwrap_err();
        assert_eq!(e.0, 2);
        assert_eq!(parse_two_column_csv("400,0.1\n500\n").unwrap_err().0, 2);
        assert!(parse_two_column_csv("# nothing\n").is_err());
    }
}
