//! Photometric files as text: bytes → characters → numbered lines → numbers.
//!
//! Real files come with UTF-8 byte-order marks, in Latin-1 (Windows code page 1252) rather than
//! UTF-8, with CRLF, LF or lone CR line ends, and with lines longer than LM-63's 132 columns. The
//! readers see none of that: [`SourceText::decode`] strips the BOM, decodes UTF-8 when the bytes
//! are valid UTF-8 and Latin-1 otherwise (every byte is a character, so decoding never fails),
//! and splits lines on any of the three line ends. Line numbers are 1-based, as editors show
//! them.

use super::ParseError;

/// A decoded file, split into lines.
#[derive(Clone, Debug)]
pub struct SourceText {
    /// The lines, without line ends; `lines[0]` is line 1.
    pub lines: Vec<String>,
    /// How the bytes were decoded, for reports ("UTF-8", "UTF-8 with BOM", "Latin-1").
    pub encoding: &'static str,
}

impl SourceText {
    /// Decodes `bytes` (never fails; see the module docs).
    pub fn decode(bytes: &[u8]) -> SourceText {
        let (text, encoding) = decode_bytes(bytes);
        SourceText { lines: split_lines(&text), encoding }
    }

    /// The 1-based line `n`, if the file has it.
    pub fn line(&self, n: usize) -> Option<&str> {
        n.checked_sub(1).and_then(|i| self.lines.get(i)).map(String::as_str)
    }
}

fn decode_bytes(bytes: &[u8]) -> (String, &'static str) {
    const BOM: &[u8] = &[0xEF, 0xBB, 0xBF];
    if let Some(rest) = bytes.strip_prefix(BOM) {
        return match std::str::from_utf8(rest) {
            Ok(s) => (s.to_string(), "UTF-8 with BOM"),
            Err(_) => (latin1(rest), "Latin-1 after a UTF-8 BOM"),
        };
    }
    match std::str::from_utf8(bytes) {
        Ok(s) => (s.to_string(), "UTF-8"),
        Err(_) => (latin1(bytes), "Latin-1"),
    }
}

/// ISO 8859-1: byte b is the character U+00b.
fn latin1(bytes: &[u8]) -> String {
    bytes.iter().map(|&b| char::from(b)).collect()
}

/// Splits on CRLF, LF or a lone CR. A final line end does not start another line.
fn split_lines(text: &str) -> Vec<String> {
    let mut lines = Vec::new();
    let mut current = String::new();
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '\r' => {
                if chars.peek() == Some(&'\n') {
                    chars.next();
                }
                lines.push(std::mem::take(&mut current));
            }
            '\n' => lines.push(std::mem::take(&mut current)),
            _ => current.push(c),
        }
    }
    if !current.is_empty() {
        lines.push(current);
    }
    lines
}

/// A finite number written with a decimal point or, as some European writers do, a decimal
/// comma ("0,5" when the text has no point and one comma). Leading '+' and exponents are
/// accepted; "nan", "inf" and empty text are not.
pub fn parse_number(s: &str) -> Option<f64> {
    let s = s.trim();
    if s.is_empty() || s.chars().any(|c| c.is_ascii_alphabetic() && c != 'e' && c != 'E') {
        return None;
    }
    let owned;
    let s = if !s.contains('.') && s.matches(',').count() == 1 {
        owned = s.replace(',', ".");
        owned.as_str()
    } else {
        s
    };
    s.parse::<f64>().ok().filter(|x| x.is_finite())
}

/// A whitespace- or comma-separated value and the line it stands on.
#[derive(Clone, Debug, PartialEq)]
pub struct Token {
    /// The value as written.
    pub text: String,
    /// 1-based line it stands on.
    pub line: usize,
}

/// Reads values one by one from lines `first_line..` (1-based), across line breaks. LM-63 lets
/// values wrap freely and separates them with spaces, tabs or commas (`commas` true); EULUMDAT
/// has one value per line and some writers use a decimal comma (`commas` false).
pub struct Tokens {
    tokens: Vec<Token>,
    next: usize,
    /// Line after the last one, for "end of file" errors.
    end_line: usize,
}

impl Tokens {
    /// The values of lines `first_line..` (1-based); `commas` says whether commas separate values.
    pub fn new(src: &SourceText, first_line: usize, commas: bool) -> Tokens {
        let mut tokens = Vec::new();
        for (i, line) in src.lines.iter().enumerate().skip(first_line.saturating_sub(1)) {
            for t in line.split(|c: char| c.is_whitespace() || (commas && c == ',')).filter(|t| !t.is_empty()) {
                tokens.push(Token { text: t.to_string(), line: i + 1 });
            }
        }
        Tokens { tokens, next: 0, end_line: src.lines.len() + 1 }
    }

    /// The next value as a number, or an error naming `field` and what was expected.
    pub fn number(&mut self, field: &str, expected: &str) -> Result<(f64, usize), ParseError> {
        let Some(t) = self.tokens.get(self.next) else {
            return Err(ParseError::new(self.end_line, field, "the end of the file", expected));
        };
        self.next += 1;
        match parse_number(&t.text) {
            Some(x) => Ok((x, t.line)),
            None => Err(ParseError::new(t.line, field, format!("\"{}\"", t.text), expected)),
        }
    }

    /// A number within [lo, hi].
    pub fn number_in(&mut self, field: &str, lo: f64, hi: f64) -> Result<(f64, usize), ParseError> {
        let expected = range_text(lo, hi, false);
        let (x, line) = self.number(field, &expected)?;
        if x < lo || x > hi {
            return Err(ParseError::new(line, field, fmt_num(x), expected));
        }
        Ok((x, line))
    }

    /// An integer within [lo, hi] (written as "3" or "3.0").
    pub fn integer_in(&mut self, field: &str, lo: i64, hi: i64) -> Result<(i64, usize), ParseError> {
        let expected = format!("an integer from {lo} to {hi}");
        let (x, line) = self.number(field, &expected)?;
        if x.fract() != 0.0 || x < lo as f64 || x > hi as f64 {
            return Err(ParseError::new(line, field, fmt_num(x), expected));
        }
        Ok((x as i64, line))
    }

    /// Values not consumed, with the line of the first one.
    pub fn rest(&self) -> (usize, Option<usize>) {
        let left = &self.tokens[self.next.min(self.tokens.len())..];
        (left.len(), left.first().map(|t| t.line))
    }
}

/// "a number from lo to hi" with infinite bounds spelled out.
pub fn range_text(lo: f64, hi: f64, integer: bool) -> String {
    let kind = if integer { "an integer" } else { "a number" };
    match (lo.is_finite(), hi.is_finite()) {
        (true, true) => format!("{kind} from {} to {}", fmt_num(lo), fmt_num(hi)),
        (true, false) => format!("{kind} ≥ {}", fmt_num(lo)),
        (false, true) => format!("{kind} ≤ {}", fmt_num(hi)),
        (false, false) => kind.to_string(),
    }
}

/// A number as a person would write it (no trailing ".0" noise beyond what is needed).
pub fn fmt_num(x: f64) -> String {
    let a = x.abs();
    if a != 0.0 && a.is_finite() && !(1e-6..1e15).contains(&a) { format!("{x:e}") } else { format!("{x}") }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strips_a_bom_and_falls_back_to_latin1() {
        let s = SourceText::decode(b"\xEF\xBB\xBFERCO\r\n1\r\n");
        assert_eq!(s.lines, vec!["ERCO", "1"]);
        assert_eq!(s.encoding, "UTF-8 with BOM");
        // "Leuchte für Büro" in Latin-1: 0xFC is 'ü'.
        let s = SourceText::decode(b"Leuchte f\xFCr B\xFCro\n2\n");
        assert_eq!(s.lines[0], "Leuchte für Büro");
        assert_eq!(s.encoding, "Latin-1");
    }

    #[test]
    fn splits_crlf_lf_and_lone_cr_and_keeps_empty_lines() {
        let s = SourceText::decode(b"a\r\nb\nc\rd\n\ne");
        assert_eq!(s.lines, vec!["a", "b", "c", "d", "", "e"]);
        assert_eq!(s.line(1), Some("a"));
        assert_eq!(s.line(6), Some("e"));
        assert_eq!(s.line(7), None);
        assert_eq!(s.line(0), None);
    }

    #[test]
    fn numbers_with_points_commas_and_exponents() {
        assert_eq!(parse_number(" 1.5 "), Some(1.5));
        assert_eq!(parse_number(".95"), Some(0.95));
        assert_eq!(parse_number("0,5"), Some(0.5));
        assert_eq!(parse_number("-1"), Some(-1.0));
        assert_eq!(parse_number("1e3"), Some(1000.0));
        assert_eq!(parse_number("+2"), Some(2.0));
        for bad in ["", "nan", "inf", "-inf", "abc", "1.2.3", "1,2,3", "infinity"] {
            assert_eq!(parse_number(bad), None, "{bad}");
        }
    }

    #[test]
    fn tokens_wrap_across_lines_and_report_their_line() {
        let s = SourceText::decode(b"skip me\n1 2,3\n\n 4\tx\n");
        let mut t = Tokens::new(&s, 2, true);
        assert_eq!(t.number("a", "n").unwrap(), (1.0, 2));
        assert_eq!(t.integer_in("b", 0, 9).unwrap(), (2, 2));
        assert_eq!(t.number_in("c", 0.0, 5.0).unwrap(), (3.0, 2));
        assert_eq!(t.number("d", "n").unwrap(), (4.0, 4));
        let e = t.number("e", "a number").unwrap_err();
        assert_eq!((e.line, e.found.as_str()), (Some(4), "\"x\""));
        let e = t.number("f", "a number").unwrap_err();
        assert_eq!(e.found, "the end of the file");
        assert_eq!(e.line, Some(5));
    }

    #[test]
    fn range_checks_name_the_allowed_range() {
        let s = SourceText::decode(b"7 2.5\n");
        let mut t = Tokens::new(&s, 1, true);
        let e = t.integer_in("photometric type", 1, 3).unwrap_err();
        assert_eq!(e.found, "7");
        assert_eq!(e.expected, "an integer from 1 to 3");
        let e = t.integer_in("count", 0, 9).unwrap_err();
        assert_eq!(e.found, "2.5");
    }
}
