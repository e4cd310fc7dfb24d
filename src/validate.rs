//! The one validation context for TOML documents (scenes, atmosphere files): turns spans into
//! `file:line:column` errors, names the field of a TOML or type error, checks which fields a
//! typed record uses, and reads values with range checks.

use crate::error::{Error, Location};
use glam::DVec3;
use std::ops::Range;
use std::path::{Path, PathBuf};
use toml::Spanned;

/// The document being validated.
pub struct Ctx<'a> {
    /// The document's path, as errors name it.
    pub file: PathBuf,
    /// The document's text (spans index into it).
    pub source: &'a str,
    /// Directory that relative paths in the document are resolved against.
    pub dir: PathBuf,
}

/// The result of a validation step.
pub type R<T> = Result<T, Error>;

/// The largest magnitude of a coordinate or length of a scene's geometry (positions, edges,
/// radii, mesh vertices), m: 10¹⁵ m, about 6,700 au — far beyond any scene (the sun at 1 au is
/// 1.5 × 10¹¹ m away) and far below where the product of two lengths overflows (≈ 10¹⁵⁴ m), which
/// turned a quad edge of 1.8 × 10³⁰⁸ m into NaN pixels.
pub const MAX_LENGTH_M: f64 = 1e15;

/// The smallest radius or thickness of a scene's geometry and sensors, m: 1 nm. Below it areas
/// and volumes underflow (a slab of 5 × 10⁻³²⁴ m gave NaN readings).
pub const MIN_LENGTH_M: f64 = 1e-9;

/// A TOML array of exactly `N` values. serde's fixed-size arrays read the first `N` elements of a
/// TOML array and the `toml` crate does not complain about the rest, so `position = [0, 0, 0, 7]`
/// passed as a point; this type refuses any other length at the array's line ("invalid length 4,
/// expected an array of length 3"), as serde does for a shorter array.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Exactly<T, const N: usize>(pub [T; N]);

impl<'de, T: serde::Deserialize<'de>, const N: usize> serde::Deserialize<'de> for Exactly<T, N> {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let values = Vec::<T>::deserialize(d)?;
        let len = values.len();
        let expected = format!("an array of length {N}");
        values.try_into().map(Exactly).map_err(|_| serde::de::Error::invalid_length(len, &expected.as_str()))
    }
}

/// Three numbers, exactly: a point, a direction or three coefficients.
pub type Vec3Raw = Exactly<f64, 3>;

impl<'a> Ctx<'a> {
    /// A context for `source`, read from `file`, resolving relative paths against `dir`.
    pub fn new(file: &Path, source: &'a str, dir: &Path) -> Ctx<'a> {
        Ctx { file: file.to_path_buf(), source, dir: dir.to_path_buf() }
    }

    /// The location of `span`; the file alone for the empty span at 0 (no place in the text).
    pub fn loc(&self, span: &Range<usize>) -> Location {
        if span.is_empty() && span.start == 0 {
            Location::file(&self.file)
        } else {
            Location::at_offset(&self.file, self.source, span.start)
        }
    }

    /// A TOML syntax or type error, naming the key written on the offending line (serde's type
    /// errors do not).
    pub fn toml_error(&self, e: &toml::de::Error) -> Error {
        let message = e.message().trim().to_string();
        let Some(span) = e.span() else {
            return Error::input(Some(Location::file(&self.file)), message);
        };
        let loc = Location::at_offset(&self.file, self.source, span.start);
        // The key is named only for an error on one `key = value` line: not for one spanning
        // the document (a missing table) and never from a comment.
        let whole_document = span.start == 0 && span.end >= self.source.trim_end().len();
        let line = loc.line.and_then(|l| self.source.lines().nth(l - 1)).unwrap_or("");
        let line = line.split('#').next().unwrap_or("");
        let key = line
            .split_once('=')
            .map(|(k, _)| k.trim())
            .filter(|k| !whole_document && !k.is_empty() && !k.starts_with('[') && !k.contains(['"', ' ']));
        let message = match key {
            Some(k) if !message.contains(&format!("`{k}`")) => format!("field `{k}`: {message}"),
            _ => message,
        };
        Error::input(Some(loc), message)
    }

    /// An input error at `span`.
    pub fn err(&self, span: &Range<usize>, message: impl Into<String>) -> Error {
        Error::input(Some(self.loc(span)), message)
    }

    /// An input error found inside a file that the field `what` at `span` names (a `kind`
    /// file: "luminaire", "atmosphere", …): it stays located in that file, and its message
    /// says which field of this file named it and where, e.g. `data.toml:1:17: key with no
    /// value (atmosphere file of medium[0]: index, scene.toml:58:9)`. Other errors pass.
    pub fn in_named_file(&self, e: Error, span: &Range<usize>, what: &str, kind: &str) -> Error {
        match e {
            Error::Input(mut i) => {
                i.message = format!("{} ({kind} file of {what}, {})", i.message, self.loc(span));
                Error::Input(i)
            }
            other => other,
        }
    }

    /// The value of a required field, or an error at the owner's span.
    pub fn require<'v, T>(
        &self,
        f: &'v Option<Spanned<T>>,
        name: &str,
        owner: &Range<usize>,
        what: &str,
    ) -> R<&'v Spanned<T>> {
        f.as_ref().ok_or_else(|| self.err(owner, format!("{what}: missing field `{name}`")))
    }

    /// Rejects fields present in `present` but absent from `allowed`.
    pub fn only(&self, present: &[(&str, Option<Range<usize>>)], allowed: &[&str], what: &str) -> R<()> {
        for (name, span) in present {
            if let Some(span) = span
                && !allowed.contains(name)
            {
                return Err(self.err(
                    span,
                    format!("{what}: field `{name}` is not used here; allowed fields: {}", allowed.join(", ")),
                ));
            }
        }
        Ok(())
    }

    /// A finite number within [lo, hi] (bounds inclusive unless `open` says otherwise).
    pub fn number(&self, v: &Spanned<f64>, what: &str, lo: f64, hi: f64, open: bool) -> R<f64> {
        let x = *v.get_ref();
        let ok = x.is_finite() && if open { x > lo && x < hi } else { x >= lo && x <= hi };
        if ok {
            return Ok(x);
        }
        let range = match (open, hi.is_infinite()) {
            (true, true) => format!("greater than {lo}"),
            (false, true) => format!("at least {lo}"),
            (true, false) => format!("strictly between {lo} and {hi}"),
            (false, false) => format!("between {lo} and {hi}"),
        };
        Err(self.err(&v.span(), format!("{what} = {x} is out of range: it must be {range}")))
    }

    /// A finite number in (lo, hi]: above `lo`, at most `hi`.
    pub fn number_above(&self, v: &Spanned<f64>, what: &str, lo: f64, hi: f64) -> R<f64> {
        let x = *v.get_ref();
        if x.is_finite() && x > lo && x <= hi {
            return Ok(x);
        }
        let range =
            if hi.is_infinite() { format!("greater than {lo}") } else { format!("greater than {lo} and at most {hi}") };
        Err(self.err(&v.span(), format!("{what} = {x} is out of range: it must be {range}")))
    }

    /// An integer within [lo, hi].
    pub fn integer(&self, v: &Spanned<i64>, what: &str, lo: i64, hi: i64) -> R<i64> {
        let x = *v.get_ref();
        if (lo..=hi).contains(&x) {
            Ok(x)
        } else {
            Err(self.err(&v.span(), format!("{what} = {x} is out of range: allowed {lo} to {hi}")))
        }
    }

    /// A vector of three finite numbers of magnitude at most [`MAX_LENGTH_M`].
    pub fn vec3(&self, v: &Spanned<Vec3Raw>, what: &str) -> R<DVec3> {
        let a = &v.get_ref().0;
        if a.iter().all(|x| x.abs() <= MAX_LENGTH_M) {
            Ok(DVec3::from_array(*a))
        } else {
            Err(self.err(&v.span(), format!("{what} = {a:?} must have three finite numbers within ±{MAX_LENGTH_M:e}")))
        }
    }

    /// A finite non-zero vector, normalised.
    pub fn direction(&self, v: &Spanned<Vec3Raw>, what: &str) -> R<DVec3> {
        let d = self.vec3(v, what)?;
        if d.length_squared() > 0.0 {
            Ok(d.normalize())
        } else {
            Err(self.err(&v.span(), format!("{what} must not be the zero vector")))
        }
    }

    /// One of the allowed strings.
    pub fn choice<'s>(&self, v: &'s Spanned<String>, what: &str, allowed: &[&str]) -> R<&'s str> {
        let s = v.get_ref().as_str();
        if allowed.contains(&s) {
            Ok(s)
        } else {
            Err(self.err(&v.span(), format!("{what} \"{s}\" is not known; allowed: {}", allowed.join(", "))))
        }
    }

    /// A path from the document, resolved relative to its directory.
    pub fn path(&self, v: &Spanned<String>) -> PathBuf {
        let p = Path::new(v.get_ref());
        if p.is_absolute() { p.to_path_buf() } else { self.dir.join(p) }
    }
}

/// `(name, span)` pairs of a record's optional fields, for [`Ctx::only`].
macro_rules! present_fields {
    ($rec:expr; $($field:ident),* $(,)?) => {
        [$( (stringify!($field), $rec.$field.as_ref().map(|v| v.span())) ),*]
    };
}
pub(crate) use present_fields;
