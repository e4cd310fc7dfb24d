//! Structure-aware mutation of TOML documents (scenes, atmosphere files).
//!
//! The document is parsed with the `toml` crate's spanned parser (`toml::de::DeTable`), which
//! gives the byte span of every key and value; edits are then made in the text at those spans,
//! so comments, layout and line numbers stay as they were and an error's `file:line` still
//! points at the edited field. One mutation kind instead parses the document into a
//! `toml::Table`, edits the value tree and serialises it again with `toml::to_string`.

use crate::text_mut::{clip, extreme_number, extreme_strings, mutate_bytes, mutate_lines, related_number};
use rand::Rng;
use rand_pcg::Pcg64;
use std::ops::Range;
use toml::de::{DeTable, DeValue};

/// One key or array element of a document, with the spans of its key and value.
#[derive(Clone, Debug)]
pub struct Slot {
    /// Dotted path, for the mutation's description.
    pub path: String,
    /// The key's span (`None` for an array element).
    pub key: Option<Range<usize>>,
    /// The value's span; the text there parses as the value on its own.
    pub value: Range<usize>,
    /// What the value is: "string", "integer", "float", "boolean", "datetime", "array", "table".
    pub kind: &'static str,
    /// The value's text.
    pub text: String,
}

/// The slots of `src`, or none if it does not parse.
pub fn slots(src: &str) -> Vec<Slot> {
    let Ok(doc) = DeTable::parse(src) else { return Vec::new() };
    let mut out = Vec::new();
    walk_table(src, doc.get_ref(), "", &mut out);
    out
}

fn walk_table(src: &str, t: &DeTable<'_>, prefix: &str, out: &mut Vec<Slot>) {
    for (k, v) in t.iter() {
        let path = if prefix.is_empty() { k.get_ref().to_string() } else { format!("{prefix}.{}", k.get_ref()) };
        push(src, &path, Some(k.span()), v.span(), v.get_ref(), out);
    }
}

fn push(src: &str, path: &str, key: Option<Range<usize>>, span: Range<usize>, v: &DeValue<'_>, out: &mut Vec<Slot>) {
    let text = src.get(span.clone()).unwrap_or("");
    // Only spans whose text is the value on its own are edited (not `[table]` headers, whose
    // value spans are not the value's text).
    let standalone = !text.is_empty() && DeValue::parse(text).is_ok();
    let key = key.filter(|k| src.get(k.clone()).is_some_and(|t| !t.is_empty()));
    if standalone {
        out.push(Slot {
            path: path.to_string(),
            key: key.clone(),
            value: span.clone(),
            kind: v.type_str(),
            text: text.into(),
        });
    }
    match v {
        DeValue::Table(t) => walk_table(src, t, path, out),
        DeValue::Array(a) => {
            for (i, e) in a.iter().enumerate() {
                push(src, &format!("{path}[{i}]"), None, e.span(), e.get_ref(), out);
            }
        }
        _ => {}
    }
}

/// Single-line `key = value` texts of a document, to splice into others.
pub fn entries(src: &str) -> Vec<String> {
    slots(src)
        .into_iter()
        .filter_map(|s| {
            let k = s.key?;
            let t = src.get(k.start..s.value.end)?;
            (!t.contains('\n') && t.contains('=')).then(|| t.to_string())
        })
        .collect()
}

/// A TOML value of some kind, as text: the retyping and extreme values.
pub fn any_value(rng: &mut Pcg64) -> String {
    match rng.random_range(0..12) {
        0 => toml_string(&extreme_strings(rng)),
        1 => extreme_number(rng),
        2 => "true".into(),
        3 => "[]".into(),
        4 => "[1.0, 2.0, 3.0]".into(),
        5 => "[\"a\", 1]".into(),
        6 => "{}".into(),
        7 => "{ type = \"x\", a = 1 }".into(),
        8 => "1979-05-27T07:32:00Z".into(),
        9 => deep_array(rng),
        10 => huge_array(rng),
        _ => format!("[{}, {}, {}]", extreme_number(rng), extreme_number(rng), extreme_number(rng)),
    }
}

fn deep_array(rng: &mut Pcg64) -> String {
    let d = [8, 64, 1000, 100_000][rng.random_range(0..4)];
    if rng.random_bool(0.5) {
        format!("{}1{}", "[".repeat(d), "]".repeat(d))
    } else {
        format!("{}1{}", "{ a = ".repeat(d), " }".repeat(d))
    }
}

fn huge_array(rng: &mut Pcg64) -> String {
    let n = [1000, 100_000][rng.random_range(0..2)];
    let item = if rng.random_bool(0.5) { "1.0".to_string() } else { extreme_number(rng) };
    format!("[{}]", vec![item; n].join(","))
}

/// `s` as a TOML basic string.
pub fn toml_string(s: &str) -> String {
    let mut out = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if (c as u32) < 0x20 || c == '\u{7f}' => out.push_str(&format!("\\u{:04X}", c as u32)),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// A replacement for a value of `slot.kind`: same kind with another value, an extreme, or
/// another kind.
fn new_value(rng: &mut Pcg64, slot: &Slot, strings: &[String]) -> String {
    if rng.random_bool(0.25) {
        return any_value(rng);
    }
    match slot.kind {
        "integer" | "float" => {
            let x: f64 = slot.text.replace('_', "").parse().unwrap_or(1.0);
            related_number(rng, x)
        }
        "string" => {
            if !strings.is_empty() && rng.random_bool(0.5) {
                strings[rng.random_range(0..strings.len())].clone()
            } else {
                toml_string(&extreme_strings(rng))
            }
        }
        "boolean" => if slot.text == "true" { "false" } else { "true" }.into(),
        "array" => {
            let inner = slot.text.trim().trim_start_matches('[').trim_end_matches(']');
            let items: Vec<&str> = split_top(inner);
            match rng.random_range(0..5) {
                0 => "[]".into(),
                1 if !items.is_empty() => format!("[{}]", items[..items.len() - 1].join(",")),
                2 if !items.is_empty() => format!("[{}, {}]", items.join(","), items[items.len() - 1]),
                3 => huge_array(rng),
                _ => {
                    format!("[{}]", (0..items.len().max(1)).map(|_| extreme_number(rng)).collect::<Vec<_>>().join(", "))
                }
            }
        }
        _ => any_value(rng),
    }
}

/// Top-level comma-separated items of an array's inside (nested brackets and strings kept).
fn split_top(inner: &str) -> Vec<&str> {
    let (mut depth, mut in_str, mut start) = (0i32, false, 0usize);
    let mut out = Vec::new();
    let b = inner.as_bytes();
    for (i, &c) in b.iter().enumerate() {
        match c {
            b'"' if i == 0 || b[i - 1] != b'\\' => in_str = !in_str,
            b'[' | b'{' if !in_str => depth += 1,
            b']' | b'}' if !in_str => depth -= 1,
            b',' if !in_str && depth == 0 => {
                out.push(inner[start..i].trim());
                start = i + 1;
            }
            _ => {}
        }
    }
    if !inner[start..].trim().is_empty() {
        out.push(inner[start..].trim());
    }
    out
}

/// What the mutator may splice in: `key = value` lines and string values of every seed.
pub struct Pool {
    /// Single-line entries.
    pub entries: Vec<String>,
    /// String values (as TOML text).
    pub strings: Vec<String>,
    /// Keys.
    pub keys: Vec<String>,
}

impl Pool {
    /// The pool of `docs`.
    pub fn of(docs: &[&str]) -> Pool {
        let mut p = Pool { entries: Vec::new(), strings: Vec::new(), keys: Vec::new() };
        for d in docs {
            p.entries.extend(entries(d));
            for s in slots(d) {
                if s.kind == "string" {
                    p.strings.push(s.text.clone());
                }
                if let Some(k) = &s.key {
                    p.keys.push(d[k.clone()].to_string());
                }
            }
        }
        for v in [&mut p.entries, &mut p.strings, &mut p.keys] {
            v.sort();
            v.dedup();
        }
        p
    }
}

/// Line start and end (after the newline) around byte `at`.
fn line_of(src: &str, at: usize) -> Range<usize> {
    let start = src[..at.min(src.len())].rfind('\n').map_or(0, |i| i + 1);
    let end = src[at.min(src.len())..].find('\n').map_or(src.len(), |i| at + i + 1);
    start..end
}

/// `[table]` and `[[array]]` sections: (header line start, section end).
fn sections(src: &str) -> Vec<Range<usize>> {
    let mut starts = Vec::new();
    let mut pos = 0;
    for line in src.split_inclusive('\n') {
        if line.trim_start().starts_with('[') {
            starts.push(pos);
        }
        pos += line.len();
    }
    let mut out = Vec::new();
    for (i, &s) in starts.iter().enumerate() {
        out.push(s..starts.get(i + 1).copied().unwrap_or(src.len()));
    }
    out
}

/// One mutation of a TOML document; returns the new text and what was done.
pub fn mutate(rng: &mut Pcg64, src: &str, pool: &Pool) -> (Vec<u8>, String) {
    let slots = slots(src);
    let roll = rng.random_range(0..100);
    if slots.is_empty() || roll >= 92 {
        return if rng.random_bool(0.5) {
            mutate_lines(rng, src.as_bytes(), 0)
        } else {
            mutate_bytes(rng, src.as_bytes())
        };
    }
    let slot = &slots[rng.random_range(0..slots.len())];
    let edit = |range: Range<usize>, with: &str| format!("{}{}{}", &src[..range.start], with, &src[range.end..]);
    let out = match roll {
        0..=39 => {
            let v = new_value(rng, slot, &pool.strings);
            (edit(slot.value.clone(), &v), format!("set {} = {}", slot.path, clip(&v)))
        }
        40..=49 => {
            // Delete the entry: its whole line when it is on one, else the key = value text.
            match &slot.key {
                Some(k) => {
                    let line = line_of(src, k.start);
                    let range = if slot.value.end <= line.end { line } else { k.start..slot.value.end };
                    (edit(range, ""), format!("delete {}", slot.path))
                }
                None => (edit(slot.value.clone(), ""), format!("delete element {}", slot.path)),
            }
        }
        50..=55 => match &slot.key {
            Some(k) => {
                let line = line_of(src, k.start);
                let text = src[k.start..slot.value.end].to_string();
                let at = line.end.max(slot.value.end);
                (format!("{}\n{text}\n{}", &src[..at], &src[at..]), format!("duplicate {}", slot.path))
            }
            None => {
                let t = slot.text.clone();
                (edit(slot.value.clone(), &format!("{t}, {t}")), format!("duplicate element {}", slot.path))
            }
        },
        56..=62 => match &slot.key {
            Some(k) if !pool.keys.is_empty() => {
                let new = if rng.random_bool(0.3) {
                    format!("{}_x", &src[k.clone()])
                } else {
                    pool.keys[rng.random_range(0..pool.keys.len())].clone()
                };
                (edit(k.clone(), &new), format!("rename {} to {new}", slot.path))
            }
            _ => {
                let v = any_value(rng);
                (edit(slot.value.clone(), &v), format!("retype {} = {}", slot.path, clip(&v)))
            }
        },
        63..=72 if !pool.entries.is_empty() => {
            // Splice an entry of any seed after this entry's line (into the same table).
            let e = &pool.entries[rng.random_range(0..pool.entries.len())];
            let at = line_of(src, slot.value.end.saturating_sub(1)).end;
            (format!("{}{e}\n{}", &src[..at], &src[at..]), format!("insert after {}: {}", slot.path, clip(e)))
        }
        73..=80 => {
            let secs = sections(src);
            if secs.is_empty() {
                return mutate_lines(rng, src.as_bytes(), 0);
            }
            let s = secs[rng.random_range(0..secs.len())].clone();
            let body = src[s.clone()].to_string();
            match rng.random_range(0..4) {
                0 => (edit(s.clone(), ""), format!("delete section at byte {}", s.start)),
                1 => {
                    let n = if rng.random_bool(0.9) { 2 } else { rng.random_range(3..300) };
                    (edit(s.clone(), &body.repeat(n)), format!("section at byte {} ×{n}", s.start))
                }
                2 => {
                    let t = &secs[rng.random_range(0..secs.len())];
                    let other = src[t.clone()].to_string();
                    (
                        format!("{}{other}\n{}", &src[..s.start], &src[s.start..]),
                        format!("copy section {} before {}", t.start, s.start),
                    )
                }
                _ => {
                    let names = [
                        "[camera]",
                        "[output]",
                        "[integrator]",
                        "[spectra]",
                        "[world]",
                        "[[material]]",
                        "[[shape]]",
                        "[[light]]",
                        "[[medium]]",
                        "[[sensor]]",
                        "[[edit]]",
                        "[x]",
                    ];
                    let h = names[rng.random_range(0..names.len())];
                    let first_nl = body.find('\n').unwrap_or(body.len());
                    (edit(s.start..s.start + first_nl, h), format!("section header at byte {} -> {h}", s.start))
                }
            }
        }
        _ => reserialize(rng, src).unwrap_or_else(|| mutate_lines(rng, src.as_bytes(), 0).into_text()),
    };
    (out.0.into_bytes(), out.1)
}

trait IntoText {
    fn into_text(self) -> (String, String);
}

impl IntoText for (Vec<u8>, String) {
    fn into_text(self) -> (String, String) {
        (String::from_utf8_lossy(&self.0).into_owned(), self.1)
    }
}

/// A step down a TOML value tree.
enum Step {
    Key(String),
    Index(usize),
}

fn at_path<'a>(v: &'a mut toml::Value, path: &[Step]) -> Option<&'a mut toml::Value> {
    match path.split_first() {
        None => Some(v),
        Some((Step::Key(k), rest)) => at_path(v.as_table_mut()?.get_mut(k)?, rest),
        Some((Step::Index(i), rest)) => at_path(v.as_array_mut()?.get_mut(*i)?, rest),
    }
}

/// Parses into a value tree, edits one value (set to an extreme, retyped, removed) and
/// serialises again.
fn reserialize(rng: &mut Pcg64, src: &str) -> Option<(String, String)> {
    let doc: toml::Table = toml::from_str(src).ok()?;
    let mut root = toml::Value::Table(doc);
    // Walk down from the root, choosing at random, to depth 1 to 4.
    let mut path = Vec::new();
    let mut cur = &root;
    for depth in 0..rng.random_range(1..5) {
        let step = match cur {
            toml::Value::Table(t) if !t.is_empty() => Step::Key(t.keys().nth(rng.random_range(0..t.len()))?.clone()),
            toml::Value::Array(a) if !a.is_empty() => Step::Index(rng.random_range(0..a.len())),
            _ => break,
        };
        cur = match &step {
            Step::Key(k) => cur.get(k.as_str())?,
            Step::Index(i) => cur.get(*i)?,
        };
        path.push(step);
        let _ = depth;
    }
    let names: Vec<String> = path
        .iter()
        .map(|s| match s {
            Step::Key(k) => k.clone(),
            Step::Index(i) => format!("[{i}]"),
        })
        .collect();
    let mut what = format!("reserialise, at {}", names.join("."));
    let v = at_path(&mut root, &path)?;
    match rng.random_range(0..4) {
        0 => {
            *v = toml::Value::Float(
                [f64::NAN, f64::INFINITY, -f64::INFINITY, 1e308, 5e-324, -1.0][rng.random_range(0..6)],
            )
        }
        1 => *v = toml::Value::Integer([0, -1, i64::MAX, i64::MIN, 1_000_000_000_000][rng.random_range(0..5)]),
        2 => *v = toml::Value::String(extreme_strings(rng)),
        _ => match &mut *v {
            toml::Value::Table(t) if !t.is_empty() => {
                let k = t.keys().nth(rng.random_range(0..t.len())).cloned()?;
                t.remove(&k);
                what.push_str(&format!(", remove {k}"));
            }
            toml::Value::Array(a) if !a.is_empty() => {
                a.remove(rng.random_range(0..a.len()));
                what.push_str(", remove an element");
            }
            other => *other = toml::Value::Array(vec![]),
        },
    }
    what.push_str(&format!(" ({})", v.type_str()));
    let toml::Value::Table(doc) = root else { return None };
    Some((toml::to_string(&doc).ok()?, what))
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    const DOC: &str = "# c\n[camera]\nwidth = 4 # w\nfov_deg = 40.0\nposition = [0.0, 1.0, 3.0]\n\n[[shape]]\ntype = \"sphere\"\nradius = { a = 1 }\n";

    #[test]
    fn slots_point_at_values() {
        let s = slots(DOC);
        let width = s.iter().find(|s| s.path == "camera.width").expect("width");
        assert_eq!(&DOC[width.value.clone()], "4");
        assert_eq!(&DOC[width.key.clone().unwrap()], "width");
        assert!(s.iter().any(|s| s.path == "camera.position[1]" && s.text == "1.0"));
        assert!(s.iter().any(|s| s.path == "shape[0].type" && s.text == "\"sphere\""));
    }

    #[test]
    fn mutations_are_reproducible() {
        let pool = Pool::of(&[DOC]);
        for k in 0..200u64 {
            let a = mutate(&mut Pcg64::seed_from_u64(k), DOC, &pool);
            let b = mutate(&mut Pcg64::seed_from_u64(k), DOC, &pool);
            assert_eq!(a, b);
        }
    }
}
