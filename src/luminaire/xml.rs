//! XML for the TM-33 and GLDF readers: decoding, parsing with roxmltree, and the look-ups both
//! need, each failing with a [`ParseError`] that names the element by its path from the root
//! (`IESTM33-22/Emitter/LuminousData/LuminousIntensity/NumberHorz`), the line it starts on and
//! what was expected.
//!
//! Decoding: a UTF-8 byte-order mark is dropped; text that is not UTF-8 is read as Latin-1
//! (with a note), as the text readers do ([`super::text`]); UTF-16 is refused. Parsing refuses
//! document type declarations (so no entity expansion) and documents of more than
//! [`MAX_NODES`] nodes, which bounds memory for any input.

use super::ParseError;
use roxmltree::{Document, Node, ParsingOptions};

/// Nodes (elements, attributes' owners, text) a document may have: far above any photometric
/// file (a TM-33 file with a 73 × 37 × 81 angular spectral table has ≈ 220 000).
pub const MAX_NODES: u32 = 4_000_000;

/// The document's text and how it was decoded ("UTF-8", "UTF-8 with BOM", "Latin-1").
pub fn decode(bytes: &[u8], what: &str) -> Result<(String, &'static str), ParseError> {
    if bytes.starts_with(&[0xFF, 0xFE]) || bytes.starts_with(&[0xFE, 0xFF]) {
        return Err(ParseError::whole_file(
            format!("{what} encoding"),
            "a UTF-16 byte-order mark",
            "UTF-8 (or Latin-1) text; save the file as UTF-8",
        ));
    }
    let (body, bom) = match bytes.strip_prefix(&[0xEF, 0xBB, 0xBF]) {
        Some(rest) => (rest, true),
        None => (bytes, false),
    };
    Ok(match std::str::from_utf8(body) {
        Ok(s) => (s.to_string(), if bom { "UTF-8 with BOM" } else { "UTF-8" }),
        Err(_) => (body.iter().map(|&b| char::from(b)).collect(), "Latin-1"),
    })
}

/// Parses `text` as XML; a syntax error names the line and column the parser stopped at.
pub fn parse<'a>(text: &'a str, what: &str) -> Result<Document<'a>, ParseError> {
    let options = ParsingOptions { allow_dtd: false, nodes_limit: MAX_NODES, ..ParsingOptions::default() };
    Document::parse_with_options(text, options).map_err(|e| match e {
        // The parser places these at 1:1; the file's end is where they happened.
        roxmltree::Error::UnclosedRootNode | roxmltree::Error::UnexpectedEndOfStream => ParseError::new(
            text.lines().count().max(1),
            format!("{what} XML"),
            format!("the end of the file with elements still open ({e}): a cut-off file?"),
            "well-formed XML, every element closed",
        ),
        _ => {
            let pos = e.pos();
            ParseError::new(
                pos.row as usize,
                format!("{what} XML (column {})", pos.col),
                e.to_string(),
                "well-formed XML without a DOCTYPE",
            )
        }
    })
}

/// The 1-based line an element starts on.
pub fn line(n: Node) -> usize {
    n.document().text_pos_at(n.range().start).row as usize
}

/// The element's path from the root, e.g. `Root/GeneralDefinitions/Files/File`.
pub fn path(n: Node) -> String {
    let mut names: Vec<&str> = n.ancestors().filter(Node::is_element).map(|a| a.tag_name().name()).collect();
    names.reverse();
    names.join("/")
}

/// Child elements called `name`.
pub fn children<'a, 'i>(n: Node<'a, 'i>, name: &'a str) -> impl Iterator<Item = Node<'a, 'i>> + 'a {
    n.children().filter(move |c| c.is_element() && c.tag_name().name() == name)
}

/// The first child element called `name`.
pub fn child<'a, 'i>(n: Node<'a, 'i>, name: &str) -> Option<Node<'a, 'i>> {
    n.children().find(|c| c.is_element() && c.tag_name().name() == name)
}

/// The first child element called `name`, or an error naming the parent, its line and `expected`.
pub fn require<'a, 'i>(n: Node<'a, 'i>, name: &str, what: &str, expected: &str) -> Result<Node<'a, 'i>, ParseError> {
    child(n, name).ok_or_else(|| {
        ParseError::new(
            line(n),
            format!("{what} {}/{name}", path(n)),
            format!("no <{name}> in <{}>", n.tag_name().name()),
            expected,
        )
    })
}

/// The element's text, trimmed ("" for an empty element).
pub fn text(n: Node) -> String {
    n.children().filter(Node::is_text).filter_map(|t| t.text()).collect::<String>().trim().to_string()
}

/// The text of the child `name`, when there is one and it is not empty.
pub fn child_text(n: Node, name: &str) -> Option<String> {
    child(n, name).map(text).filter(|t| !t.is_empty())
}

/// The element's text as a finite number within [lo, hi].
pub fn number(n: Node, what: &str, lo: f64, hi: f64) -> Result<f64, ParseError> {
    parse_number(&text(n), line(n), &format!("{what} {}", path(n)), lo, hi)
}

/// The child `name` as a number within [lo, hi], when present.
pub fn child_number(n: Node, name: &str, what: &str, lo: f64, hi: f64) -> Result<Option<f64>, ParseError> {
    child(n, name).map(|c| number(c, what, lo, hi)).transpose()
}

/// The element's text as a whole number within [lo, hi] ("3" or "3.0").
pub fn integer(n: Node, what: &str, lo: i64, hi: i64) -> Result<i64, ParseError> {
    let x = number(n, what, lo as f64, hi as f64)
        .map_err(|e| ParseError { expected: format!("an integer from {lo} to {hi}"), ..e })?;
    if x.fract() != 0.0 {
        return Err(ParseError::new(
            line(n),
            format!("{what} {}", path(n)),
            text(n),
            format!("an integer from {lo} to {hi}"),
        ));
    }
    Ok(x as i64)
}

/// The attribute `name` as a finite number within [lo, hi].
pub fn attr_number(n: Node, name: &str, what: &str, lo: f64, hi: f64) -> Result<f64, ParseError> {
    let field = format!("{what} {} attribute {name}", path(n));
    match n.attribute(name) {
        Some(v) => parse_number(v, line(n), &field, lo, hi),
        None => Err(ParseError::new(line(n), field, "no such attribute", super::text::range_text(lo, hi, false))),
    }
}

/// xs:boolean: true, false, 1 or 0 (any case, as writers vary).
pub fn boolean(n: Node, what: &str) -> Result<bool, ParseError> {
    match text(n).to_ascii_lowercase().as_str() {
        "true" | "1" => Ok(true),
        "false" | "0" => Ok(false),
        other => Err(ParseError::new(line(n), format!("{what} {}", path(n)), format!("\"{other}\""), "true or false")),
    }
}

fn parse_number(s: &str, line: usize, field: &str, lo: f64, hi: f64) -> Result<f64, ParseError> {
    let expected = super::text::range_text(lo, hi, false);
    let t = s.trim();
    // XML numbers use a decimal point; a lone comma is read as one, as the text readers do.
    match super::text::parse_number(t) {
        Some(x) if (lo..=hi).contains(&x) => Ok(x),
        Some(x) => Err(ParseError::new(line, field, x.to_string(), expected)),
        None => Err(ParseError::new(line, field, format!("\"{}\"", truncate(t, 40)), expected)),
    }
}

/// At most `n` characters of `s`, with "…" when cut.
pub fn truncate(s: &str, n: usize) -> String {
    if s.chars().count() <= n { s.to_string() } else { s.chars().take(n).collect::<String>() + "…" }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn syntax_errors_name_line_and_column() {
        let e = parse("<a>\n  <b>1</b>\n  <c>\n</a>", "TM-33").unwrap_err();
        assert_eq!(e.line, Some(4), "{e}");
        assert!(e.field.starts_with("TM-33 XML (column"), "{e}");
        let e = parse("<a>\n  <b>1</b>\n  <c>", "TM-33").unwrap_err();
        assert_eq!(e.line, Some(3), "{e}");
        assert!(e.found.starts_with("the end of the file"), "{e}");
        let e = parse("<!DOCTYPE a [<!ENTITY x \"y\">]><a>&x;</a>", "TM-33").unwrap_err();
        assert!(e.found.to_lowercase().contains("dtd"), "{e}");
    }

    #[test]
    fn look_ups_name_the_element_path_and_line() {
        let doc =
            parse("<r>\n <e>\n  <n> 3 </n>\n  <x>abc</x>\n  <f>2.5</f>\n  <t>False</t>\n </e>\n</r>", "T").unwrap();
        let e = child(doc.root_element(), "e").unwrap();
        assert_eq!(integer(child(e, "n").unwrap(), "T", 1, 9).unwrap(), 3);
        let err = number(child(e, "x").unwrap(), "T", 0.0, 1.0).unwrap_err();
        assert_eq!((err.line, err.field.as_str(), err.found.as_str()), (Some(4), "T r/e/x", "\"abc\""));
        let err = integer(child(e, "f").unwrap(), "T", 1, 9).unwrap_err();
        assert_eq!(err.expected, "an integer from 1 to 9");
        assert!(!boolean(child(e, "t").unwrap(), "T").unwrap());
        let err = require(e, "NumberHorz", "T", "the number of planes").unwrap_err();
        assert_eq!(err.to_string(), "2: T r/e/NumberHorz: found no <NumberHorz> in <e>, expected the number of planes");
    }

    #[test]
    fn decoding() {
        assert_eq!(decode(b"\xEF\xBB\xBF<a/>", "T").unwrap(), ("<a/>".to_string(), "UTF-8 with BOM"));
        assert_eq!(decode(b"<a>f\xFCr</a>", "T").unwrap(), ("<a>für</a>".to_string(), "Latin-1"));
        assert!(decode(b"\xFF\xFE<\0a\0", "T").is_err());
    }
}
