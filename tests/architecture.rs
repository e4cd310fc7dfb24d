//! The library's modules form layers, and every import points down.
//!
//! [`LAYERS`] lists every top-level module of `src/` with its layer and rank. A module may use
//! (by `use crate::…` or an inline `crate::…` path, in code or in its unit tests) only modules of
//! a lower rank. Two exceptions, both stated here: unit tests (`#[cfg(test)]` modules) may use
//! the test harnesses of `testing`, and `lib.rs` and `main.rs` sit above everything. The test
//! reads the source, so it also fails when `lib.rs` declares a module the table does not place.
//! The layering and the reasons for it are in the book (`docs/book/src/architecture.md`).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// (module, layer, rank): a module may import only modules of lower rank.
const LAYERS: &[(&str, &str, u32)] = &[
    // Base: numbers, data and files, knowing nothing of light transport.
    ("error", "base", 0),
    ("rng", "base", 0),
    ("quadrature", "base", 0),
    ("atomic", "base", 0),
    ("timing", "base", 0),
    ("memory", "base", 0),
    ("sampling", "base", 1),
    ("raster", "base", 1),
    ("validate", "base", 1),
    ("spectrum", "base", 2),
    ("geometry", "base", 2),
    ("ode", "base", 2),
    ("testing", "base", 3),
    ("field", "base", 3),
    // Domain: the physics of materials, lights, media, photon maps, sensors and vision.
    ("material", "domain", 10),
    ("luminaire", "domain", 10),
    ("atmosphere", "domain", 10),
    ("tonemap", "domain", 10),
    ("light", "domain", 11),
    ("media", "domain", 12),
    ("photon_map", "domain", 13),
    ("sensor", "domain", 13),
    // What light interacts with, propagation through it (which the scene reader uses to aim
    // beams along curved paths), and the scene reader that builds both with the run description.
    ("world", "world", 20),
    ("raypath", "raypath", 25),
    ("scene", "scene", 30),
    // The passes built on propagation.
    ("photon", "photon", 50),
    ("distributed", "distributed", 60),
    ("render", "render", 70),
    ("output", "output", 80),
    ("cli", "cli", 90),
];

/// The module a unit test may use whatever its own rank.
const TEST_HARNESS: &str = "testing";

fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<_> = std::fs::read_dir(dir).expect("read src").map(|e| e.expect("entry").path()).collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|e| e == "rs") {
            out.push(p);
        }
    }
}

/// The top-level module a file of `src/` belongs to (`None` for lib.rs, main.rs and `bin/`).
fn module_of(file: &Path) -> Option<String> {
    let rel = file.strip_prefix(src()).ok()?;
    let first = rel.components().next()?.as_os_str().to_str()?.to_string();
    match first.as_str() {
        "lib.rs" | "main.rs" | "bin" => None,
        f => Some(f.trim_end_matches(".rs").to_string()),
    }
}

/// The text of a line without its `//` comment (outside string literals).
fn code_part(line: &str) -> &str {
    let mut in_str = false;
    let b = line.as_bytes();
    let mut i = 0;
    while i < b.len() {
        match b[i] {
            b'\\' if in_str => i += 1,
            b'"' => in_str = !in_str,
            b'/' if !in_str && b.get(i + 1) == Some(&b'/') => return &line[..i],
            _ => {}
        }
        i += 1;
    }
    line
}

/// The top-level modules named by the `crate::` paths of a line of code: `crate::a::x` gives
/// `a`, `crate::{a::x, b}` gives `a` and `b`.
fn crate_paths(code: &str) -> Vec<String> {
    let mut found = Vec::new();
    let mut rest = code;
    while let Some(i) = rest.find("crate::") {
        let before_ok = i == 0 || !rest.as_bytes()[i - 1].is_ascii_alphanumeric() && rest.as_bytes()[i - 1] != b'_';
        rest = &rest[i + "crate::".len()..];
        if !before_ok {
            continue;
        }
        if let Some(group) = rest.strip_prefix('{') {
            let mut depth = 0usize;
            let mut start = true;
            for (k, c) in group.char_indices() {
                match c {
                    '{' => depth += 1,
                    '}' if depth == 0 => break,
                    '}' => depth -= 1,
                    ',' if depth == 0 => start = true,
                    c if start && (c.is_alphanumeric() || c == '_') => {
                        let name: String =
                            group[k..].chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
                        found.push(name);
                        start = false;
                    }
                    _ => {}
                }
            }
        } else {
            let name: String = rest.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
            found.push(name);
        }
    }
    found
}

/// One `crate::` import: where it is and what it names.
struct Import {
    file: PathBuf,
    line: usize,
    in_test: bool,
    target: String,
}

/// Every `crate::` import of `file`, marking those inside `#[cfg(test)]` items.
fn imports(file: &Path) -> Vec<Import> {
    let text = std::fs::read_to_string(file).expect("read source");
    let mut out = Vec::new();
    let mut test_depth: Option<i64> = None;
    let mut depth: i64 = 0;
    let mut pending_test = false;
    for (n, line) in text.lines().enumerate() {
        let code = code_part(line);
        if code.trim_start().starts_with("#[cfg(test)]") {
            pending_test = true;
        }
        let opens = code.matches('{').count() as i64;
        let closes = code.matches('}').count() as i64;
        if pending_test && opens > 0 && test_depth.is_none() {
            test_depth = Some(depth);
            pending_test = false;
        }
        for target in crate_paths(code) {
            out.push(Import { file: file.to_path_buf(), line: n + 1, in_test: test_depth.is_some(), target });
        }
        depth += opens - closes;
        if test_depth.is_some_and(|d| depth <= d) {
            test_depth = None;
        }
    }
    out
}

fn table() -> BTreeMap<&'static str, (&'static str, u32)> {
    LAYERS.iter().map(|(m, l, r)| (*m, (*l, *r))).collect()
}

#[test]
fn every_import_points_to_a_lower_layer() {
    let layers = table();
    let mut files = Vec::new();
    rust_files(&src(), &mut files);
    let mut violations = Vec::new();
    for file in &files {
        let Some(module) = module_of(file) else { continue };
        let Some(&(layer, rank)) = layers.get(module.as_str()) else {
            violations.push(format!("{}: module `{module}` is not in the LAYERS table", file.display()));
            continue;
        };
        for i in imports(file) {
            if i.target == module || (i.in_test && i.target == TEST_HARNESS) {
                continue;
            }
            match layers.get(i.target.as_str()) {
                Some(&(_, r)) if r < rank => {}
                Some(&(target_layer, r)) => violations.push(format!(
                    "{}:{}: `{module}` ({layer}, rank {rank}) imports `crate::{}` ({target_layer}, rank {r}); imports must point to a lower rank",
                    i.file.strip_prefix(src().parent().unwrap()).unwrap_or(&i.file).display(),
                    i.line,
                    i.target
                )),
                None => violations.push(format!(
                    "{}:{}: `crate::{}` is not a module in the LAYERS table",
                    i.file.display(),
                    i.line,
                    i.target
                )),
            }
        }
    }
    assert!(violations.is_empty(), "{} upward or unknown imports:\n{}", violations.len(), violations.join("\n"));
}

#[test]
fn lib_declares_exactly_the_modules_of_the_table() {
    let lib = std::fs::read_to_string(src().join("lib.rs")).expect("lib.rs");
    let declared: Vec<String> = lib
        .lines()
        .filter_map(|l| l.trim().strip_prefix("pub mod ").or_else(|| l.trim().strip_prefix("mod ")))
        .map(|l| l.trim_end_matches(';').to_string())
        .collect();
    let mut declared_sorted = declared.clone();
    declared_sorted.sort();
    let mut tabled: Vec<String> = LAYERS.iter().map(|(m, _, _)| m.to_string()).collect();
    tabled.sort();
    assert_eq!(declared_sorted, tabled, "lib.rs modules (left) and the LAYERS table (right) differ");
}

#[test]
fn the_import_reader_finds_what_it_must() {
    assert_eq!(crate_paths("use crate::spectrum::Bands;"), vec!["spectrum"]);
    assert_eq!(crate_paths("use crate::{geometry::Ray, media::{Medium, phase}};"), vec!["geometry", "media"]);
    assert_eq!(crate_paths(code_part("let x = crate::ode::Method::Dopri5; // crate::render")), vec!["ode"]);
    assert_eq!(crate_paths(code_part("let x = 1; // crate::render::x")), Vec::<String>::new());
    assert_eq!(crate_paths("foo_crate::bar"), Vec::<String>::new());
    let dir = std::env::temp_dir().join(format!("morgana-arch-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let f = dir.join("x.rs");
    std::fs::write(
        &f,
        "use crate::a::B;\n#[cfg(test)]\nmod tests {\n    use crate::testing::c;\n}\nfn f() { crate::d::e(); }\n",
    )
    .unwrap();
    let found: Vec<(usize, bool, String)> = imports(&f).into_iter().map(|i| (i.line, i.in_test, i.target)).collect();
    std::fs::remove_dir_all(&dir).ok();
    assert_eq!(found, vec![(1, false, "a".to_string()), (4, true, "testing".to_string()), (6, false, "d".to_string())]);
}
