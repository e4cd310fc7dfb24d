//! Seed documents the harness makes itself (OBJ meshes, density and field grids, EXR images,
//! GLDF containers) and the mutators of formats that are not TOML: XML, OBJ, grids, EXR, zip.

use crate::text_mut::{clip, extreme_number, mutate_bytes, mutate_lines};
use morgana::field::Lattice;
use morgana::field::grid_file::{self, Encoding, Quantity};
use rand::Rng;
use rand_pcg::Pcg64;
use std::io::Write;

/// Small OBJ meshes: a tetrahedron, a cube of quads with normals and texture coordinates, two
/// objects with groups, negative (relative) indices.
pub fn obj_seeds() -> Vec<(String, Vec<u8>)> {
    let tetra = "# tetrahedron\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    let cube = "o cube\nv -0.5 -0.5 -0.5\nv 0.5 -0.5 -0.5\nv 0.5 0.5 -0.5\nv -0.5 0.5 -0.5\nv -0.5 -0.5 0.5\nv 0.5 -0.5 0.5\nv 0.5 0.5 0.5\nv -0.5 0.5 0.5\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 -1\nvn 0 0 1\nvn 0 -1 0\nvn 0 1 0\nvn -1 0 0\nvn 1 0 0\ns off\nf 1/1/1 4/4/1 3/3/1 2/2/1\nf 5/1/2 6/2/2 7/3/2 8/4/2\nf 1/1/3 2/2/3 6/3/3 5/4/3\nf 4/1/4 8/2/4 7/3/4 3/4/4\nf 1/1/5 5/2/5 8/3/5 4/4/5\nf 2/1/6 3/2/6 7/3/6 6/4/6\n";
    let two = "mtllib none.mtl\no a\ng first\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf -3 -2 -1\no b\ng second\nv 2 0 0\nv 3 0 0\nv 2 1 0\nv 3 1 0\nf 4//  5// 6//\nf 5 7 6\nl 1 2\n";
    vec![("tetra.obj".into(), tetra.into()), ("cube.obj".into(), cube.into()), ("two.obj".into(), two.into())]
}

/// One mutation of an OBJ file: a token, a line or bytes, or an OBJ-specific edit.
pub fn mutate_obj(rng: &mut Pcg64, src: &[u8]) -> (Vec<u8>, String) {
    let text = String::from_utf8_lossy(src).into_owned();
    match rng.random_range(0..10) {
        0 => {
            let line = match rng.random_range(0..7) {
                0 => format!(
                    "f 1 2 {}",
                    ["0", "-100", "999999999999", "4294967297", "18446744073709551617"][rng.random_range(0..5)]
                ),
                1 => format!("v {} {} {}", extreme_number(rng), extreme_number(rng), extreme_number(rng)),
                2 => format!(
                    "f {}",
                    (1..=rng.random_range(1..100_000)).map(|i| (i % 4 + 1).to_string()).collect::<Vec<_>>().join(" ")
                ),
                3 => "f".into(),
                4 => "f 1".into(),
                5 => "f 1/2/3/4 2 3".into(),
                _ => format!("v {}", "1 ".repeat(rng.random_range(0..10))),
            };
            let mut lines: Vec<&str> = text.lines().collect();
            let at = rng.random_range(0..=lines.len());
            lines.insert(at, &line);
            (lines.join("\n").into_bytes(), format!("insert line {}: {}", at + 1, clip(&line)))
        }
        1 => mutate_bytes(rng, src),
        _ => mutate_lines(rng, src, 0),
    }
}

/// A density grid (`.mgrid`): header and f32 data, `n` points per axis.
pub fn mgrid(n: [usize; 3], min: [f64; 3], max: [f64; 3], value: impl Fn(usize) -> f32) -> Vec<u8> {
    let mut out = format!(
        "MORGANA-GRID 1\n{} {} {}\n{} {} {}\n{} {} {}\n",
        n[0], n[1], n[2], min[0], min[1], min[2], max[0], max[1], max[2]
    )
    .into_bytes();
    for i in 0..n[0] * n[1] * n[2] {
        out.extend_from_slice(&value(i).to_le_bytes());
    }
    out
}

/// A lattice file (`.mfield`).
pub fn mfield(quantity: Quantity, dims: [usize; 3], encoding: Encoding, value: impl Fn(usize) -> f64) -> Vec<u8> {
    let values: Vec<f64> = (0..dims[0] * dims[1] * dims[2]).map(value).collect();
    let lattice =
        Lattice::new(dims, [-1.0, 0.0, -1.0].into(), [1.0, 0.5, 1.0].into(), values).expect("a valid lattice");
    grid_file::to_bytes(quantity, &lattice, encoding)
}

/// Grid seeds: (name, bytes); the name's extension says which scene context reads it.
pub fn grid_seeds() -> Vec<(String, Vec<u8>)> {
    vec![
        ("density.mgrid".into(), mgrid([4, 3, 5], [-1.0, 0.0, -1.0], [1.0, 1.0, 1.0], |i| (i % 7) as f32 * 0.1)),
        ("density.mgrid".into(), mgrid([2, 2, 2], [-0.5, -0.5, -0.5], [0.5, 0.5, 0.5], |_| 1.0)),
        (
            "temperature.mfield".into(),
            mfield(Quantity::TemperatureK, [3, 4, 3], Encoding::Ascii, |i| 280.0 + i as f64 * 0.5),
        ),
        ("temperature.mfield".into(), mfield(Quantity::TemperatureK, [2, 3, 2], Encoding::F64Le, |i| 300.0 - i as f64)),
        (
            "delta.mfield".into(),
            mfield(Quantity::DeltaTemperatureK, [3, 3, 3], Encoding::Ascii, |i| (i as f64 - 13.0) * 0.2),
        ),
        ("delta.mfield".into(), mfield(Quantity::DeltaTemperatureK, [2, 2, 4], Encoding::F64Le, |i| i as f64 * 0.1)),
    ]
}

/// One mutation of a grid file: a header token or line, the data as bytes, or an extreme
/// value written into the data.
pub fn mutate_grid(rng: &mut Pcg64, src: &[u8], header_lines: usize) -> (Vec<u8>, String) {
    let header_end =
        src.iter().enumerate().filter(|(_, b)| **b == b'\n').nth(header_lines - 1).map_or(src.len(), |(i, _)| i + 1);
    match rng.random_range(0..10) {
        0..=4 => {
            let (mut h, what) = mutate_lines(rng, &src[..header_end], header_lines);
            if !h.ends_with(b"\n") {
                h.push(b'\n');
            }
            h.extend_from_slice(&src[header_end..]);
            (h, format!("header: {what}"))
        }
        5 | 6 => {
            let data = &src[header_end..];
            let ascii = data.iter().all(|b| b.is_ascii());
            let mut out = src[..header_end].to_vec();
            if ascii && !data.is_empty() {
                let (d, what) = mutate_lines(rng, data, 0);
                out.extend(d);
                (out, format!("data: {what}"))
            } else {
                let width = if src.starts_with(b"MORGANA-GRID") { 4 } else { 8 };
                let mut d = data.to_vec();
                let k = if d.len() >= width { rng.random_range(0..d.len() / width) * width } else { 0 };
                let bytes: Vec<u8> = if width == 4 {
                    [f32::NAN, f32::INFINITY, -1.0, f32::MAX, 1e-45][rng.random_range(0..5)].to_le_bytes().to_vec()
                } else {
                    [f64::NAN, f64::NEG_INFINITY, -300.0, f64::MAX, 5e-324][rng.random_range(0..5)]
                        .to_le_bytes()
                        .to_vec()
                };
                for (j, b) in bytes.iter().enumerate() {
                    if let Some(x) = d.get_mut(k + j) {
                        *x = *b;
                    }
                }
                out.extend(d);
                (out, format!("data value {} set to an extreme", k / width))
            }
        }
        _ => mutate_bytes(rng, src),
    }
}

/// One mutation of an XML document: an element's text, an attribute value, a tag name, a
/// line, bytes, or an entity-expansion or deeply nested prologue.
pub fn mutate_xml(rng: &mut Pcg64, src: &[u8]) -> (Vec<u8>, String) {
    let text = String::from_utf8_lossy(src).into_owned();
    let r = rng.random_range(0..20);
    // Element texts: `>text</`.
    let texts: Vec<(usize, usize)> = text
        .match_indices("</")
        .filter_map(|(end, _)| {
            let start = text[..end].rfind('>')? + 1;
            (start < end && !text[start..end].contains('<')).then_some((start, end))
        })
        .collect();
    let attrs: Vec<(usize, usize)> = text
        .match_indices("=\"")
        .filter_map(|(i, _)| {
            let s = i + 2;
            let e = s + text[s..].find('"')?;
            Some((s, e))
        })
        .collect();
    match r {
        0..=6 if !texts.is_empty() => {
            let (s, e) = texts[rng.random_range(0..texts.len())];
            let new = crate::text_mut::replace_token(rng, text[s..e].trim());
            let new = new.replace('<', "&lt;").replace('&', "&amp;");
            (
                format!("{}{}{}", &text[..s], new, &text[e..]).into_bytes(),
                format!("element text {:?} -> {:?}", clip(&text[s..e]), clip(&new)),
            )
        }
        7..=9 if !attrs.is_empty() => {
            let (s, e) = attrs[rng.random_range(0..attrs.len())];
            let new = crate::text_mut::replace_token(rng, &text[s..e]).replace(['<', '&', '"'], "");
            (
                format!("{}{}{}", &text[..s], new, &text[e..]).into_bytes(),
                format!("attribute {:?} -> {:?}", clip(&text[s..e]), clip(&new)),
            )
        }
        10 if !texts.is_empty() => {
            // Delete an element written on one line.
            let (s, _) = texts[rng.random_range(0..texts.len())];
            let line_start = text[..s].rfind('\n').map_or(0, |i| i + 1);
            let line_end = text[s..].find('\n').map_or(text.len(), |i| s + i + 1);
            (
                format!("{}{}", &text[..line_start], &text[line_end..]).into_bytes(),
                format!("delete element line at byte {line_start}"),
            )
        }
        11 => {
            let lol = "<!DOCTYPE r [<!ENTITY a \"aaaaaaaaaa\"><!ENTITY b \"&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;\"><!ENTITY c \"&b;&b;&b;&b;&b;&b;&b;&b;&b;&b;\"><!ENTITY d \"&c;&c;&c;&c;&c;&c;&c;&c;&c;&c;\"><!ENTITY e \"&d;&d;&d;&d;&d;&d;&d;&d;&d;&d;\"><!ENTITY f \"&e;&e;&e;&e;&e;&e;&e;&e;&e;&e;\">]>";
            let at = text.find("?>").map_or(0, |i| i + 2);
            let body = text[at..].replacen("</Manufacturer>", "&f;</Manufacturer>", 1);
            (format!("{}{lol}{body}", &text[..at]).into_bytes(), "entity expansion (billion laughs)".into())
        }
        12 => {
            let d = [100, 10_000, 200_000][rng.random_range(0..3)];
            let at = text.rfind("</").unwrap_or(text.len());
            let nest = format!("{}{}", "<x>".repeat(d), "</x>".repeat(d));
            (format!("{}{nest}{}", &text[..at], &text[at..]).into_bytes(), format!("{d} nested elements"))
        }
        13 | 14 => mutate_bytes(rng, src),
        _ => mutate_lines(rng, src, 0),
    }
}

/// A deflated zip of `entries`.
pub fn zip_of(entries: &[(String, Vec<u8>)]) -> Vec<u8> {
    let mut w = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let options = zip::write::SimpleFileOptions::default().compression_method(zip::CompressionMethod::Deflated);
    for (name, content) in entries {
        // The zip writer refuses a second entry of one name: it is left out.
        if w.start_file(name.as_str(), options).is_ok() {
            let _ = w.write_all(content);
        }
    }
    w.finish().map(|c| c.into_inner()).unwrap_or_default()
}

/// The entries of this project's test GLDF container.
pub fn gldf_entries(product: &[u8], ldt: &[u8], ies: &[u8], spectrum: &[u8]) -> Vec<(String, Vec<u8>)> {
    vec![
        ("product.xml".into(), product.to_vec()),
        ("ldc/quad_downlight.ldt".into(), ldt.to_vec()),
        ("ldc/quad_downlight.ies".into(), ies.to_vec()),
        ("spectrum/quad_downlight_spectrum.txt".into(), spectrum.to_vec()),
    ]
}

/// One mutation of a GLDF container: one entry mutated (as XML or text), an entry removed,
/// renamed or duplicated, or the zip's bytes.
pub fn mutate_gldf(rng: &mut Pcg64, entries: &mut Vec<(String, Vec<u8>)>) -> Option<String> {
    match rng.random_range(0..10) {
        0..=5 => {
            let i = rng.random_range(0..entries.len());
            let (m, what) = if entries[i].0.ends_with(".xml") {
                mutate_xml(rng, &entries[i].1)
            } else {
                mutate_lines(rng, &entries[i].1, 40)
            };
            entries[i].1 = m;
            Some(format!("entry {}: {what}", entries[i].0))
        }
        6 => {
            let i = rng.random_range(0..entries.len());
            let name = entries.remove(i).0;
            Some(format!("remove entry {name}"))
        }
        7 => {
            let i = rng.random_range(0..entries.len());
            let new = ["", "/", "../x", "PRODUCT.XML", "ldc/", "a\\b"][rng.random_range(0..6)].to_string();
            let old = std::mem::replace(&mut entries[i].0, new.clone());
            Some(format!("rename entry {old} to {new:?}"))
        }
        8 => {
            let i = rng.random_range(0..entries.len());
            let e = entries[i].clone();
            // At most 4 MB: a copy of a copy must not grow without bound.
            let times = rng.random_range(2..2000).min((4 << 20) / e.1.len().max(1)).max(1);
            entries.push(("big/".to_string() + &e.0, e.1.repeat(times)));
            Some(format!("add a large copy of {}", e.0))
        }
        _ => None, // byte mutation of the zip, done by the caller
    }
}

/// A spectral EXR as morgana writes it, `w`×`h` pixels of `bands` bands over `min_nm`–`max_nm`,
/// one sample set to `poison` (or none).
pub fn spectral_exr(
    path: &std::path::Path,
    w: usize,
    h: usize,
    bands: usize,
    range: (f64, f64),
    poison: Option<(usize, f32)>,
) -> Result<(), String> {
    let bands = morgana::spectrum::Bands::new(range.0, range.1, bands)?;
    let mut data: Vec<f32> = (0..w * h * bands.count).map(|i| 0.05 + (i % 11) as f32 * 0.01).collect();
    if let Some((i, v)) = poison {
        let k = i % data.len().max(1);
        data[k] = v;
    }
    let rgb = vec![0.1; w * h * 3];
    let image = morgana::spectrum::SpectralImage { width: w, height: h, bands, data, rgb };
    morgana::spectrum::exr::write_spectral_exr(path, &image).map_err(|e| e.to_string())
}

/// An RGB (or luminance-only) EXR written with the `exr` crate.
pub fn rgb_exr(
    path: &std::path::Path,
    w: usize,
    h: usize,
    poison: Option<f32>,
    luminance_only: bool,
) -> Result<(), String> {
    use exr::prelude::*;
    let v = move |x: usize, y: usize| {
        if (x, y) == (w / 2, h / 2) { poison.unwrap_or(0.4) } else { 0.1 + 0.01 * (x + y) as f32 }
    };
    if luminance_only {
        let ch = AnyChannel::new("Y", FlatSamples::F32((0..w * h).map(|i| v(i % w, i / w)).collect()));
        let layer = Layer::new(
            (w, h),
            LayerAttributes::named("l"),
            Encoding::FAST_LOSSLESS,
            AnyChannels::sort(SmallVec::from_vec(vec![ch])),
        );
        Image::from_layer(layer).write().to_file(path).map_err(|e| e.to_string())
    } else {
        write_rgb_file(path, w, h, |x, y| (v(x, y), 0.2f32, 0.3f32)).map_err(|e| e.to_string())
    }
}

/// Offsets of header attribute values of an EXR (after the magic and version): (name, value
/// offset, value size).
pub fn exr_attributes(b: &[u8]) -> Vec<(String, usize, usize)> {
    let mut out = Vec::new();
    let mut i = 8;
    let cstr = |i: usize| -> Option<(String, usize)> {
        let end = i + b.get(i..)?.iter().position(|&c| c == 0)?;
        Some((String::from_utf8_lossy(&b[i..end]).into_owned(), end + 1))
    };
    while let Some((name, j)) = cstr(i) {
        if name.is_empty() {
            break;
        }
        let Some((_ty, k)) = cstr(j) else { break };
        let Some(size) = b.get(k..k + 4).map(|s| i32::from_le_bytes([s[0], s[1], s[2], s[3]])) else { break };
        if size < 0 || k + 4 + size as usize > b.len() {
            break;
        }
        out.push((name, k + 4, size as usize));
        i = k + 4 + size as usize;
    }
    out
}

/// One mutation of an EXR: an attribute's value (4-byte integers set to extremes, or its
/// bytes), a channel name, or bytes anywhere.
pub fn mutate_exr(rng: &mut Pcg64, src: &[u8]) -> (Vec<u8>, String) {
    let attrs = exr_attributes(src);
    let mut b = src.to_vec();
    if attrs.is_empty() || rng.random_bool(0.3) {
        return mutate_bytes(rng, src);
    }
    let (name, at, size) = attrs[rng.random_range(0..attrs.len())].clone();
    if name == "channels" && rng.random_bool(0.5) {
        // Rewrite a digit or letter of a channel name.
        let digits: Vec<usize> = (at..at + size).filter(|&k| b[k].is_ascii_alphanumeric()).collect();
        if !digits.is_empty() {
            let k = digits[rng.random_range(0..digits.len())];
            let c = b"0123456789.,nmSXYZRGBx"[rng.random_range(0..22)];
            b[k] = c;
            return (b, format!("channels: byte {} -> {:?}", k - at, c as char));
        }
    }
    if size >= 4 && rng.random_bool(0.6) {
        let k = at + 4 * rng.random_range(0..size / 4);
        let v: i32 = [0, -1, 1, i32::MAX, i32::MIN, 1 << 20, 65_535, 100_000][rng.random_range(0..8)];
        b[k..k + 4].copy_from_slice(&v.to_le_bytes());
        return (b, format!("attribute {name}: int at +{} = {v}", k - at));
    }
    if size > 0 {
        let k = at + rng.random_range(0..size);
        b[k] = rng.random();
        return (b, format!("attribute {name}: byte +{} randomised", k - at));
    }
    mutate_bytes(rng, src)
}
