//! What a case did, and whether that is allowed.
//!
//! Allowed: success (exit 0), or an input error (exit 2) whose message locates the problem:
//! it names an input file with a line (`file:12`), or an XML element (`<Tag>`) or zip entry of
//! a named file, or a part of a named binary file (an EXR channel, attribute or pixel), or a
//! command-line flag (`--photons`). Everything else is a finding.

use std::collections::BTreeMap;
use std::fmt;

/// The class of one case's outcome.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Class {
    /// Exit 0 (or `Ok` in process), outputs finite, nothing left behind.
    Ok,
    /// Exit 2 with a message that locates the problem.
    InputLocated,
    /// Exit 2 with a message that names neither a line nor an element nor a flag.
    InputUnlocated,
    /// Exit 1 (an internal error) for a problem of the input.
    Internal,
    /// A panic (caught in process, or exit 101 of a child).
    Panic,
    /// The case ran past its deadline.
    Timeout,
    /// The process died: a signal, an abort for memory, a stack overflow.
    Crash,
    /// A file was left behind after a failure, or a staging file after a success, or a file
    /// outside the case's directory was changed.
    Leftover,
    /// A NaN or infinity in an output (file or printed text).
    NonFinite,
}

/// Every class, in the order the histogram prints them.
pub const CLASSES: [Class; 9] = [
    Class::Ok,
    Class::InputLocated,
    Class::InputUnlocated,
    Class::Internal,
    Class::Panic,
    Class::Timeout,
    Class::Crash,
    Class::Leftover,
    Class::NonFinite,
];

impl Class {
    /// The short name used in reports and in the worker protocol.
    pub fn name(self) -> &'static str {
        match self {
            Class::Ok => "ok",
            Class::InputLocated => "input-error-located",
            Class::InputUnlocated => "input-error-unlocated",
            Class::Internal => "internal-error",
            Class::Panic => "panic",
            Class::Timeout => "timeout",
            Class::Crash => "crash",
            Class::Leftover => "leftover-file",
            Class::NonFinite => "non-finite-output",
        }
    }

    /// The class of a name written by [`Class::name`].
    pub fn parse(s: &str) -> Option<Class> {
        CLASSES.iter().copied().find(|c| c.name() == s)
    }

    /// Whether this outcome is allowed.
    pub fn allowed(self) -> bool {
        matches!(self, Class::Ok | Class::InputLocated)
    }
}

impl fmt::Display for Class {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// One case's outcome: its class and the message that decided it.
#[derive(Clone, Debug)]
pub struct Outcome {
    /// The class.
    pub class: Class,
    /// The error message, panic message or reason (shortened).
    pub message: String,
}

impl Outcome {
    /// An outcome of `class` with `message` (kept to its first 400 characters, one line).
    pub fn new(class: Class, message: impl Into<String>) -> Outcome {
        let m: String = message.into();
        let mut m: String = m.replace(['\n', '\t', '\r'], " ");
        if m.chars().count() > 400 {
            m = m.chars().take(400).collect::<String>() + "…";
        }
        Outcome { class, message: m }
    }

    /// Success.
    pub fn ok() -> Outcome {
        Outcome::new(Class::Ok, "")
    }
}

/// Whether an input error's message locates the problem, given the names of the files the
/// case read (base names) and whether flags count (the command line).
///
/// A text file is located by `file:line`; a zip container by `file!/entry`; a binary file
/// (EXR, the samples of a `.mgrid`) by its name used as the message's place (`file: ...`),
/// there being no line to give; any file also by naming an XML element, an EXR channel,
/// attribute or pixel, or a byte offset in it.
pub fn locates(message: &str, files: &[String], flags: bool) -> bool {
    if flags && has_flag(message) {
        return true;
    }
    for f in files {
        let binary = [".exr", ".gldf", ".mgrid"].iter().any(|e| f.ends_with(e));
        let mut rest = message;
        while let Some(i) = rest.find(f.as_str()) {
            let after = &rest[i + f.len()..];
            if let Some(d) = after.strip_prefix(':')
                && (d.starts_with(|c: char| c.is_ascii_digit()) || (binary && d.starts_with(' ')))
            {
                return true;
            }
            if after.starts_with("!/") {
                return true;
            }
            rest = after;
        }
    }
    let names_file = files.iter().any(|f| message.contains(f.as_str()));
    (names_file && names_part(message)) || names_table(message, files)
}

/// Whether the message names one of the command line's arguments as the place of the
/// problem: `ARG: …` (an argument that names a missing file, for one), or its first 40
/// characters followed by an ellipsis when the message clips a long argument.
pub fn names_argument(message: &str, args: &[String]) -> bool {
    args.iter().filter(|a| !a.is_empty()).any(|a| {
        if message.contains(&format!("{a}:")) || message.contains(&format!("'{a}'")) {
            return true;
        }
        let head: String = a.chars().take(40).collect();
        a.chars().count() > 40 && message.contains(&head) && message.contains('…')
    })
}

/// Whether the message names a file and, as the thing that is missing or wrong, a whole TOML
/// table (`[camera]`, `[[light]]`): something absent has no line to point at.
fn names_table(message: &str, files: &[String]) -> bool {
    let names_file = files.iter().any(|f| message.contains(f.as_str()));
    names_file
        && message.match_indices('[').any(|(i, _)| {
            let rest = message[i..].trim_start_matches('[');
            let name: String = rest.chars().take_while(|c| c.is_ascii_lowercase() || *c == '_').collect();
            !name.is_empty() && rest[name.len()..].starts_with(']')
        })
}

/// `--name` somewhere in the message.
fn has_flag(message: &str) -> bool {
    message.match_indices("--").any(|(i, _)| {
        let before_ok = i == 0 || !message.as_bytes()[i - 1].is_ascii_alphanumeric();
        let next = message[i + 2..].chars().next();
        before_ok && next.is_some_and(|c| c.is_ascii_lowercase())
    })
}

/// An XML element, a zip entry, or a part of a binary file (EXR channel, attribute, pixel, a
/// byte offset).
fn names_part(message: &str) -> bool {
    let element = message.match_indices('<').any(|(i, _)| {
        message[i + 1..].chars().next().is_some_and(|c| c.is_ascii_alphabetic() || c == '/')
            && message[i + 1..].contains('>')
    });
    element || ["entry ", "channel ", "attribute ", "pixel (", "byte ", "element "].iter().any(|w| message.contains(w))
}

/// Whether printed text holds a NaN or an infinity as a word (`NaN`, `inf`, `-inf`,
/// `infinity`), outside words like "info".
pub fn has_non_finite_word(text: &str) -> bool {
    text.split(|c: char| !(c.is_ascii_alphanumeric() || c == '.' || c == '_'))
        .any(|w| matches!(w.to_ascii_lowercase().as_str(), "nan" | "inf" | "infinity"))
}

/// The non-finite words of a line (as [`has_non_finite_word`] finds them), with their signs,
/// joined by spaces: `+inf`, `NaN`.
pub fn non_finite_words(line: &str) -> String {
    // Split at anything that cannot be part of a signed number ("(catalogue -inf)" gives "-inf").
    line.split(|c: char| !(c.is_ascii_alphanumeric() || matches!(c, '+' | '-' | '.' | '_')))
        .filter(|w| has_non_finite_word(w))
        .collect::<Vec<_>>()
        .join(" ")
}

/// Counts of outcomes by class, with examples of each finding.
#[derive(Default)]
pub struct Histogram {
    /// Cases per class.
    pub counts: BTreeMap<Class, u64>,
    /// Up to a few (case, message) examples per disallowed class.
    pub examples: BTreeMap<Class, Vec<(String, String)>>,
    /// Distinct messages of disallowed outcomes, with their count and first case.
    pub distinct: BTreeMap<(Class, String), (u64, String)>,
    /// Cases and total time (µs) per seed document.
    pub seeds: BTreeMap<String, (u64, u64)>,
}

impl Histogram {
    /// Records case `id` with `outcome`.
    pub fn add(&mut self, id: &str, outcome: &Outcome) {
        *self.counts.entry(outcome.class).or_default() += 1;
        if !outcome.class.allowed() {
            let key = (outcome.class, shape_of(&outcome.message));
            let e = self.distinct.entry(key).or_insert((0, id.to_string()));
            e.0 += 1;
            let ex = self.examples.entry(outcome.class).or_default();
            if ex.len() < 5 {
                ex.push((id.to_string(), outcome.message.clone()));
            }
        }
    }

    /// Records the time a case of `seed` took.
    pub fn time(&mut self, seed: &str, micros: u64) {
        let e = self.seeds.entry(seed.to_string()).or_default();
        e.0 += 1;
        e.1 += micros;
    }

    /// Cases recorded.
    pub fn total(&self) -> u64 {
        self.counts.values().sum()
    }

    /// Cases with a disallowed outcome.
    pub fn findings(&self) -> u64 {
        self.counts.iter().filter(|(c, _)| !c.allowed()).map(|(_, n)| n).sum()
    }
}

/// A message with its digits replaced, so findings that differ only in numbers group together.
fn shape_of(message: &str) -> String {
    let mut out = String::new();
    let mut last_digit = false;
    for c in message.chars().take(160) {
        if c.is_ascii_digit() {
            if !last_digit {
                out.push('#');
            }
            last_digit = true;
        } else {
            out.push(c);
            last_digit = false;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn locations_are_recognised() {
        let files = vec!["scene.toml".to_string(), "a.exr".to_string()];
        assert!(locates("/tmp/x/scene.toml:12:3: field `width`: bad", &files, false));
        assert!(!locates("/tmp/x/scene.toml: missing camera", &files, false));
        assert!(locates("a.exr: channel S0.550nm: bad", &files, false));
        assert!(locates("/x/a.exr: not readable", &files, false));
        assert!(!locates("not readable (a.exr)", &files, false));
        assert!(locates("/x/lum.gldf!/ldc/a.ldt: bad", &["lum.gldf".to_string()], false));
        assert!(locates("--photons 0: expected 1 to 2^40", &files, true));
        assert!(!locates("--photons 0: expected 1 to 2^40", &files, false));
        assert!(!locates("error: x-- y", &files, true));
        assert!(locates("/tmp/x/scene.toml: the scene has no [[light]]: add one", &files, false));
        assert!(!locates("/tmp/x/other.toml: the scene has no [[light]]", &files, false));
        assert!(!locates("/tmp/x/scene.toml: value [1, 2] is bad", &files, false));
        let args = vec!["8E".to_string(), "x".repeat(300)];
        assert!(names_argument("morgana: 8E: cannot read scene file: not found", &args));
        assert!(names_argument(&format!("morgana: {}… (300 characters): bad", "x".repeat(60)), &args));
        assert!(!names_argument("morgana: cannot read scene file 8E", &args));
    }

    #[test]
    fn non_finite_words() {
        assert!(has_non_finite_word("flux NaN lm"));
        assert!(has_non_finite_word("peak -inf cd"));
        assert!(!has_non_finite_word("info: influx 3.5"));
        assert_eq!(super::non_finite_words("downlight (catalogue -inf), nan"), "-inf nan");
    }
}
