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
    /// Bad input at `location`; words of the message longer than [`MAX_ECHOED_CHARS`] (a
    /// 100 KB string or a 309-digit number echoed from the input) are shortened.
    pub fn input(location: Option<Location>, message: impl Into<String>) -> Self {
        Error::Input(InputError { location, message: clip_long_words(&message.into()) })
    }

    /// The same error placed at a command-line flag: an input error without a file location
    /// gets `flag: ` in front of its message (the flag is where the user fixes it); other errors
    /// pass unchanged.
    pub fn at_flag(self, flag: &str) -> Self {
        match self {
            Error::Input(InputError { location: None, message }) => {
                Error::Input(InputError { location: None, message: format!("{flag}: {message}") })
            }
            e => e,
        }
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

/// The longest word of an input error's message echoed whole; longer ones keep their first
/// [`ECHOED_HEAD_CHARS`] characters and say how long they were.
pub const MAX_ECHOED_CHARS: usize = 200;
/// See [`MAX_ECHOED_CHARS`].
pub const ECHOED_HEAD_CHARS: usize = 60;

fn clip_long_words(message: &str) -> String {
    if message.chars().count() <= MAX_ECHOED_CHARS {
        return message.to_string();
    }
    let mut out = String::with_capacity(message.len().min(4 * MAX_ECHOED_CHARS));
    let mut word = String::new();
    let flush = |word: &mut String, out: &mut String| {
        let n = word.chars().count();
        if n > MAX_ECHOED_CHARS {
            out.extend(word.chars().take(ECHOED_HEAD_CHARS));
            out.push_str(&format!("… ({n} characters)"));
        } else {
            out.push_str(word);
        }
        word.clear();
    };
    for c in message.chars() {
        if c.is_whitespace() {
            flush(&mut word, &mut out);
            out.push(c);
        } else {
            word.push(c);
        }
    }
    flush(&mut word, &mut out);
    out
}

/// The largest text input (scene or atmosphere file) read, bytes: far above any real scene
/// (long tables live in CSV files), and small enough that a file at the limit is parsed in about
/// a second; a larger file is refused before it is read.
pub const MAX_TEXT_FILE_BYTES: u64 = 16 << 20;

/// Reads a text file that must be UTF-8 and at most [`MAX_TEXT_FILE_BYTES`] long; invalid UTF-8
/// is an input error at the line and column of the first bad byte. `what` names the file's role
/// ("scene file").
pub fn read_utf8(path: &Path, what: &str) -> Result<String> {
    let cannot = |e: std::io::Error| Error::input(Some(Location::file(path)), format!("cannot read {what}: {e}"));
    let size = std::fs::metadata(path).map_err(cannot)?.len();
    if size > MAX_TEXT_FILE_BYTES {
        return Err(Error::input(
            Some(Location::file(path)),
            format!(
                "{what} is {size} bytes, past the limit at byte {MAX_TEXT_FILE_BYTES} (16 MiB) up to which text files are read: keep long tables in the CSV files a scene names (`file = \"…\"`)"
            ),
        ));
    }
    let bytes = std::fs::read(path).map_err(cannot)?;
    String::from_utf8(bytes).map_err(|e| {
        let good = e.utf8_error().valid_up_to();
        let text = String::from_utf8_lossy(&e.as_bytes()[..good]).into_owned();
        let (line, column) = line_column(&text, good);
        Error::input(
            Some(Location { file: path.to_path_buf(), line: Some(line), column: Some(column) }),
            format!("{what} is not valid UTF-8 here (byte 0x{:02X}); save it as UTF-8", e.as_bytes()[good]),
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A text file over the limit is refused, before it is read, with its size and the fix
    /// (found by the fuzzer: an 89 MB mutated scene took 6 s to parse).
    #[test]
    fn a_text_file_over_the_limit_is_refused_unread() {
        let dir = std::env::temp_dir().join(format!("morgana-read-limit-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        let path = dir.join("huge.toml");
        let file = std::fs::File::create(&path).expect("create");
        file.set_len(MAX_TEXT_FILE_BYTES + 1).expect("sparse file"); // zeros: valid UTF-8 if read
        let e = read_utf8(&path, "scene file").expect_err("over the limit");
        let text = e.to_string();
        assert!(
            text.contains(&format!("scene file is {} bytes, past the limit at byte", MAX_TEXT_FILE_BYTES + 1)),
            "{text}"
        );
        assert!(text.contains("CSV files") && e.exit_code() == 2, "{text}");
        file.set_len(16).expect("shrink");
        assert_eq!(read_utf8(&path, "scene file").expect("under the limit").len(), 16);
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn a_flag_places_only_errors_without_a_file() {
        let e = Error::input(None, "height 5 m is out of range").at_flag("--observer-height-m");
        assert_eq!(e.to_string(), "--observer-height-m: height 5 m is out of range");
        let at_file = Error::input(Some(Location::file(Path::new("a.toml"))), "bad").at_flag("--x");
        assert_eq!(at_file.to_string(), "a.toml: bad");
        assert_eq!(Error::internal("disk").at_flag("--x").to_string(), "internal error: disk");
    }

    #[test]
    fn long_words_are_clipped_and_short_messages_kept() {
        let long = "x".repeat(100_000);
        let e = Error::input(None, format!("field `name`: invalid value \"{long}\""));
        let text = e.to_string();
        assert!(text.len() < 200, "{}", text.len());
        assert!(text.contains("(100002 characters)"), "{text}");
        assert!(text.starts_with("field `name`: invalid value \"xxx"), "{text}");
        let short = Error::input(None, "missing field `camera`").to_string();
        assert_eq!(short, "missing field `camera`");
    }

    #[test]
    fn invalid_utf8_is_located() {
        let path = std::env::temp_dir().join(format!("morgana-utf8-{}.toml", std::process::id()));
        std::fs::write(&path, b"a = 1\nb = \"\xFF\"\n").unwrap();
        let e = read_utf8(&path, "scene file").unwrap_err();
        std::fs::remove_file(&path).ok();
        let Error::Input(e) = e else { panic!("an input error") };
        let loc = e.location.expect("a location");
        assert_eq!((loc.line, loc.column), (Some(2), Some(6)));
        assert!(e.message.contains("0xFF"), "{}", e.message);
    }

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
