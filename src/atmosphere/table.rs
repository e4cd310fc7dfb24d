//! Numeric CSV tables: `#` comment lines and blank lines are skipped, the first data row may be a
//! header, separators are commas, semicolons or tabs. Errors carry the 1-based line number.

/// Parses exactly `names.len()` numeric columns; returns one vector per column.
pub fn parse_numeric_columns(text: &str, names: &[&str]) -> Result<Vec<Vec<f64>>, (usize, String)> {
    let mut cols = vec![Vec::new(); names.len()];
    let mut seen_row = false;
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = line.split([',', ';', '\t']).map(str::trim).collect();
        let parsed: Option<Vec<f64>> = fields.iter().map(|c| c.parse().ok()).collect();
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
    if cols[0].is_empty() {
        return Err((1, format!("no data rows ({})", names.join(", "))));
    }
    Ok(cols)
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
}
