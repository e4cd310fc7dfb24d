//! What a reader says about a malformed file: where (file, line), which field by its name in
//! the format's standard, what it found and what the standard allows.

use crate::error::{Error, Location};
use std::fmt;
use std::path::{Path, PathBuf};

/// A malformed photometric file. `file` is `None` for the file being read, or names another file
/// the reader opened for it (an LM-63 `TILT=<file>`).
#[derive(Clone, Debug, PartialEq)]
pub struct ParseError {
    /// The file read (`None`: the file the caller opened).
    pub file: Option<PathBuf>,
    /// 1-based line of the offending value (`None`: the file as a whole).
    pub line: Option<usize>,
    /// The field by its standard name, e.g. "EULUMDAT field 4, Mc (number of C-planes)".
    pub field: String,
    /// What was found.
    pub found: String,
    /// What the standard allows.
    pub expected: String,
}

impl ParseError {
    /// An error at `line` of the file being read.
    pub fn new(line: usize, field: impl Into<String>, found: impl Into<String>, expected: impl Into<String>) -> Self {
        ParseError { file: None, line: Some(line), field: field.into(), found: found.into(), expected: expected.into() }
    }

    /// An error about the whole file (no single line to blame).
    pub fn whole_file(field: impl Into<String>, found: impl Into<String>, expected: impl Into<String>) -> Self {
        ParseError { file: None, line: None, field: field.into(), found: found.into(), expected: expected.into() }
    }

    /// The same error, located in `file` (when it is not already located elsewhere).
    pub fn in_file(mut self, file: &Path) -> Self {
        if self.file.is_none() {
            self.file = Some(file.to_path_buf());
        }
        self
    }

    /// The crate's input error (exit code 2), located at `file:line` (`file` being the file
    /// that was read, unless the error names another).
    pub fn into_error(self, file: &Path) -> Error {
        let path = self.file.clone().unwrap_or_else(|| file.to_path_buf());
        let message = self.message();
        Error::input(Some(Location { file: path, line: self.line, column: None }), message)
    }

    /// "field: found …, expected …", without the location.
    pub fn message(&self) -> String {
        format!("{}: found {}, expected {}", self.field, self.found, self.expected)
    }
}

impl fmt::Display for ParseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(p) = &self.file {
            write!(f, "{}:", p.display())?;
        }
        if let Some(l) = self.line {
            write!(f, "{l}: ")?;
        }
        write!(f, "{}", self.message())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_message_names_field_found_and_expected_and_the_location_is_file_and_line() {
        let e = ParseError::new(4, "EULUMDAT field 4, Mc", "\"x\"", "an integer from 1 to 721");
        let err = e.into_error(Path::new("lamp.ldt"));
        assert_eq!(err.to_string(), "lamp.ldt:4: EULUMDAT field 4, Mc: found \"x\", expected an integer from 1 to 721");
        assert_eq!(err.exit_code(), 2);
        let tilt = ParseError::new(2, "tilt", "\"?\"", "a number").in_file(Path::new("t.dat"));
        assert!(tilt.into_error(Path::new("lamp.ies")).to_string().starts_with("t.dat:2: "));
    }
}
