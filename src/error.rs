//! Errors: bad input (exit code 2) versus internal failure (exit code 1).
//!
//! Input errors name the file, line and column, the field, what was wrong and what is allowed,
//! e.g. `scene.toml:14:9: material "glass": ior_model "cauchy" needs both a and b`.

use std::fmt;
use std::path::{Path, PathBuf};

/// Where in an input file something was found (1-based line and column).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Location {
    /// The file.
    pub file: PathBuf,
    /// 1-based line, when known.
    pub line: Option<usize>,
    /// 1-based column, when known.
    pub column: Option<usize>,
}

impl Location {
    /// The file as a whole, without line or column.
    pub fn file(file: &Path) -> Self {
        Location { file: file.to_path_buf(), line: None, column: None }
    }

    /// The location of byte `offset` in `source`, read from `file`.
    pub fn at_offset(file: &Path, source: &str, offset: usize) -> Self {
        let (line, column) = line_column(source, offset);
        Location { file: file.to_path_buf(), line: Some(line), column: Some(column) }
    }
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.file.display())?;
        if let Some(line) = self.line {
            write!(f, ":{line}")?;
            if let Some(column) = self.column {
                write!(f, ":{column}")?;
            }
        }
        Ok(())
    }
}

/// 1-based line and column (in characters) of byte `offset` in `source`.
pub fn line_column(source: &str, offset: usize) -> (usize, usize) {
    let offset = offset.min(source.len());
    let before = &source[..floor_char_boundary(source, offset)];
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    let column = before[line_start..].chars().count() + 1;
    (line, column)
}

fn floor_char_boundary(s: &str, mut i: usize) -> usize {
    while i > 0 && !s.is_char_boundary(i) {
        i -= 1;
    }
    i
}

/// A user's input was wrong: a scene, a data file, a command-line value.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct InputError {
    /// Where, when the error has a place in a file.
    pub location: Option<Location>,
    /// What was wrong and what is allowed.
    pub message: String,
}

impl fmt::Display for InputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.location {
            Some(loc) => write!(f, "{loc}: {}", self.message),
            None => write!(f, "{}", self.message),
        }
    }
}

/// Every failure morgana reports.
#[derive(Debug)]
pub enum Error {
    /// The user's input is wrong; the message says where and how to fix it. Exit code 2.
    Input(InputError),
    /// Something failed that is not the input's fault (I/O on outputs, a broken invariant). Exit code 1.
    Internal(String),
}

impl Error {
    /// An input error at `location`.
    pub fn input(location: Option<Location>, message: impl Into<String>) -> Self {
        Error::Input(InputError { location, message: message.into() })
    }

    /// An internal failure (I/O on outputs, a broken invariant: not the input's fault).
    pub fn internal(message: impl Into<String>) -> Self {
        Error::Internal(message.into())
    }

    /// The process exit code: 2 for bad input, 1 for internal failures.
    pub fn exit_code(&self) -> i32 {
        match self {
            Error::Input(_) => 2,
            Error::Internal(_) => 1,
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Input(e) => write!(f, "{e}"),
            Error::Internal(m) => write!(f, "internal error: {m}"),
        }
    }
}

impl std::error::Error for Error {}

impl From<InputError> for Error {
    fn from(e: InputError) -> Self {
        Error::Input(e)
    }
}

/// The crate's result type.
pub type Result<T> = std::result::Result<T, Error>;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_column_counts_from_one_and_in_characters() {
        let src = "a = 1\nbé = 2\n";
        assert_eq!(line_column(src, 0), (1, 1));
        assert_eq!(line_column(src, 6), (2, 1));
        // 'é' is two bytes; the '=' after "bé " is the 4th character.
        let eq = src[6..].find('=').unwrap() + 6;
        assert_eq!(line_column(src, eq), (2, 4));
    }
}
