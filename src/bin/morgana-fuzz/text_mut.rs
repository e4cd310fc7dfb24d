//! Mutations of any document as text (lines and whitespace-separated tokens) or as bytes, and
//! the extreme values every mutator draws from.

use rand::Rng;
use rand_pcg::Pcg64;

/// Numbers that break readers: zero, signs, NaN and infinities, the largest and smallest
/// doubles, a subnormal, 2^63 and its neighbours, huge counts (10^12) and counts just past
/// 32-bit limits.
pub const EXTREME_NUMBERS: &[&str] = &[
    "0",
    "-0",
    "-1",
    "1",
    "2",
    "nan",
    "inf",
    "-inf",
    "+inf",
    "1e308",
    "-1e308",
    "1.7976931348623157e308",
    "5e-324",
    "2.2250738585072014e-308",
    "1e-300",
    "9223372036854775807",
    "9223372036854775808",
    "-9223372036854775808",
    "18446744073709551615",
    "18446744073709551616",
    "1000000000000",
    "4294967296",
    "2147483648",
    "65536",
    "1e9",
    "1e12",
    "0.5",
    "-0.5",
    "360",
    "-360",
    "180",
    "1e-9",
    "3",
    "100000",
];

/// Strings that break readers: empty, blank, very long, paths out of the case, control and
/// non-ASCII characters, format syntax.
pub fn extreme_strings(rng: &mut Pcg64) -> String {
    match rng.random_range(0..14) {
        0 => String::new(),
        1 => " ".into(),
        2 => "x".repeat(100_000),
        3 => "../../../../nonexistent/file".into(),
        4 => "/".into(),
        5 => ".".into(),
        6 => "\u{0}".into(),
        7 => "é日本\u{202e}".into(),
        8 => "a,b,c".into(),
        9 => "[".into(),
        10 => "\"".into(),
        11 => "1e308".into(),
        12 => "nan".into(),
        _ => "😀".repeat(rng.random_range(1..300)),
    }
}

/// One extreme number, as text.
pub fn extreme_number(rng: &mut Pcg64) -> String {
    EXTREME_NUMBERS[rng.random_range(0..EXTREME_NUMBERS.len())].to_string()
}

/// A number near `x`: scaled by a power of ten, negated, nudged, or an extreme.
pub fn related_number(rng: &mut Pcg64, x: f64) -> String {
    match rng.random_range(0..6) {
        0 => format!("{:?}", x * 10f64.powi(rng.random_range(-12..=12))),
        1 => format!("{:?}", -x),
        2 => format!("{:?}", x + 1.0),
        3 => format!("{:?}", x * (1.0 + 1e-9)),
        _ => extreme_number(rng),
    }
}

/// A token to put where a token was: a number related to it, an extreme, junk.
pub fn replace_token(rng: &mut Pcg64, token: &str) -> String {
    if let Ok(x) = token.parse::<f64>()
        && rng.random_bool(0.5)
    {
        return related_number(rng, x);
    }
    match rng.random_range(0..8) {
        0 => "x".into(),
        1 => String::new(),
        2 => "3.5.6".into(),
        3 => "1,5".into(),
        4 => token.repeat(rng.random_range(2..50)),
        5 => extreme_strings(rng),
        _ => extreme_number(rng),
    }
}

fn pick(rng: &mut Pcg64, n: usize) -> usize {
    if n == 0 { 0 } else { rng.random_range(0..n) }
}

/// One mutation of a text document, line- or token-wise; `what` says which.
pub fn mutate_lines(rng: &mut Pcg64, src: &[u8], favour_first: usize) -> (Vec<u8>, String) {
    let text = String::from_utf8_lossy(src).into_owned();
    let ends_nl = text.ends_with('\n');
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    if lines.is_empty() {
        return mutate_bytes(rng, src);
    }
    let n = lines.len();
    let i = if favour_first > 0 && rng.random_bool(0.5) { pick(rng, n.min(favour_first)) } else { pick(rng, n) };
    let what = match rng.random_range(0..10) {
        0 => {
            lines.remove(i);
            format!("delete line {}", i + 1)
        }
        1 => {
            let copies = if rng.random_bool(0.9) { 1 } else { rng.random_range(2..2000) };
            for _ in 0..copies {
                lines.insert(i, lines[i].clone());
            }
            format!("duplicate line {} ×{copies}", i + 1)
        }
        2 => {
            let j = pick(rng, n);
            lines.swap(i, j);
            format!("swap lines {} and {}", i + 1, j + 1)
        }
        3 => {
            let long = lines[i].repeat(rng.random_range(2..5000).min(200_000 / (lines[i].len() + 1) + 2));
            lines[i] = long;
            format!("repeat line {} within itself", i + 1)
        }
        _ => {
            let mut tokens: Vec<String> = lines[i].split_whitespace().map(str::to_string).collect();
            if tokens.is_empty() {
                lines[i] = replace_token(rng, "");
                format!("fill blank line {}", i + 1)
            } else {
                let k = pick(rng, tokens.len());
                let new = replace_token(rng, &tokens[k]);
                let what = format!("line {} token {}: {:?} -> {:?}", i + 1, k + 1, tokens[k], clip(&new));
                tokens[k] = new;
                lines[i] = tokens.join(" ");
                what
            }
        }
    };
    let mut out = lines.join("\n");
    if ends_nl {
        out.push('\n');
    }
    (out.into_bytes(), what)
}

/// One mutation of bytes: truncation, flipped bits, inserted or overwritten random bytes, a
/// deleted run, invalid UTF-8, CRLF, a BOM.
pub fn mutate_bytes(rng: &mut Pcg64, src: &[u8]) -> (Vec<u8>, String) {
    let mut b = src.to_vec();
    let at = pick(rng, b.len() + 1);
    let what = match rng.random_range(0..9) {
        0 => {
            b.truncate(at);
            format!("truncate at byte {at}")
        }
        1 | 2 => {
            let flips = rng.random_range(1..4);
            for _ in 0..flips {
                if !b.is_empty() {
                    let k = pick(rng, b.len());
                    b[k] ^= 1 << rng.random_range(0..8);
                }
            }
            format!("flip {flips} bits near byte {at}")
        }
        3 => {
            let n = rng.random_range(1..16);
            for _ in 0..n {
                b.insert(at.min(b.len()), rng.random());
            }
            format!("insert {n} random bytes at {at}")
        }
        4 => {
            let n = rng.random_range(1..9);
            for k in at..(at + n).min(b.len()) {
                b[k] = rng.random();
            }
            format!("overwrite {n} bytes at {at}")
        }
        5 => {
            let n = rng.random_range(1..64).min(b.len() - at.min(b.len()));
            b.drain(at..at + n);
            format!("delete {n} bytes at {at}")
        }
        6 => {
            b.insert(at.min(b.len()), [0xFF, 0xC3, 0x80][rng.random_range(0..3)]);
            format!("invalid UTF-8 byte at {at}")
        }
        7 => {
            let t = String::from_utf8_lossy(&b).replace('\n', "\r\n");
            b = t.into_bytes();
            "CRLF line ends".into()
        }
        _ => {
            let mut v = vec![0xEF, 0xBB, 0xBF];
            v.extend_from_slice(&b);
            b = v;
            "BOM prefix".into()
        }
    };
    (b, what)
}

/// A short printable form of a mutation's new text.
pub fn clip(s: &str) -> String {
    if s.chars().count() > 40 {
        format!("{}…({} chars)", s.chars().take(30).collect::<String>(), s.len())
    } else {
        s.to_string()
    }
}
