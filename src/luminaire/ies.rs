//! IES LM-63 (.ies) reader: the 1986, 1991, 1995, 2002 and 2019 editions.
//!
//! Layout (LM-63-2002 §5; LM-63-2019 §5):
//! 1. A version line — `IESNA91`, `IESNA:LM-63-1995`, `IESNA:LM-63-2002`, `IES:LM-63-2019` — absent
//!    in LM-63-1986 files, whose first lines are free labels.
//! 2. Keyword lines `[KEYWORD] text` (`[MORE]` continues the previous one).
//! 3. `TILT=NONE`, `TILT=INCLUDE` (the tilt block follows) or `TILT=<file>` (the tilt block is in
//!    that file, beside this one); see [`super::Tilt`].
//! 4. Numbers, separated by spaces, tabs, commas or line ends, wrapping freely:
//!    number of lamps, lumens per lamp (−1: absolute photometry), candela multiplier, number of
//!    vertical angles, number of horizontal angles, photometric type (1 = C, 2 = B, 3 = A), units
//!    (1 feet, 2 metres), width, length, height of the luminous opening;
//!    ballast factor, ballast-lamp photometric factor (1986–1995; "future use" in 2002, "file
//!    generation type" in 2019), input watts;
//!    the vertical angles, the horizontal angles, then the candela values, all vertical angles of
//!    the first horizontal angle first.
//!
//! Intensity in cd = value × candela multiplier × ballast factor (× the ballast-lamp photometric
//! factor in editions before 2002, where it is defined). For relative photometry the values
//! already refer to the rated lamp lumens; the file states no luminaire flux, so its web's flux
//! over the lamp flux is the luminaire's efficiency.
//!
//! Horizontal angles and symmetry, type C: one angle — rotational; 0–90° — quadrant; 0–180° —
//! about C0–C180; 90–270° — about C90–C270; 0 to more than 180° — none (360° repeats 0°). Types
//! A and B: 0–90° — symmetric about H = 0; −90–90° (or any other span) — none.
//!
//! Values after the candela table are ignored with a note, as are blank lines before the first.
//!
//! # References
//! - ANSI/IESNA LM-63-1995, LM-63-2002 (R2008), ANSI/IES LM-63-2019, *Standard File Format for
//!   the Electronic Transfer of Photometric Data and Related Information*.

use super::opening::Opening;
use super::planes::{type_c_symmetry, web_from_planes};
use super::symmetry::{Plane, Symmetry};
use super::text::{SourceText, Tokens};
use super::tilt::Tilt;
use super::web::PhotometricWeb;
use super::{LampSet, ParseError, PhotometricType, Photometry, Reader};
use std::path::Path;

pub const READER: Reader = Reader { name: "IES LM-63", extensions: &["ies"], sniff, read, implemented: true };

/// Starts with an IESNA/IES version line, or has a `TILT=` line.
fn sniff(src: &SourceText) -> bool {
    let first = src.lines.iter().find(|l| !l.trim().is_empty()).map(|l| l.trim().to_ascii_uppercase());
    first.is_some_and(|l| l.starts_with("IESNA") || l.starts_with("IES:"))
        || src.lines.iter().any(|l| l.trim_start().to_ascii_uppercase().starts_with("TILT="))
}

/// The LM-63 edition a file declares.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Edition {
    E1986,
    E1991,
    E1995,
    E2002,
    E2019,
}

impl Edition {
    fn name(self) -> &'static str {
        match self {
            Edition::E1986 => "IES LM-63-1986",
            Edition::E1991 => "IES LM-63-1991",
            Edition::E1995 => "IES LM-63-1995",
            Edition::E2002 => "IES LM-63-2002",
            Edition::E2019 => "IES LM-63-2019",
        }
    }

    /// The edition a first line declares (spaces ignored), `None` for a 1986 label line.
    fn of(line: &str) -> Option<Edition> {
        let t: String = line.chars().filter(|c| !c.is_whitespace()).collect::<String>().to_ascii_uppercase();
        if t.starts_with("IESNA91") {
            Some(Edition::E1991)
        } else if t.starts_with("IESNA:LM-63-1995") {
            Some(Edition::E1995)
        } else if t.starts_with("IES:LM-63-2019") || t.starts_with("IESNA:LM-63-2019") {
            Some(Edition::E2019)
        } else if t.starts_with("IESNA") || t.starts_with("IES:") {
            Some(Edition::E2002)
        } else {
            None
        }
    }
}

enum TiltSpec {
    None,
    Include,
    File(String),
}

/// Everything before the numbers.
struct Header {
    edition: Edition,
    keywords: Vec<(String, String)>,
    tilt: TiltSpec,
    tilt_line: usize,
}

impl Header {
    fn keyword(&self, k: &str) -> Option<&str> {
        self.keywords.iter().find(|(key, _)| key == k).map(|(_, v)| v.as_str())
    }
}

fn header(src: &SourceText, notes: &mut Vec<String>) -> Result<Header, ParseError> {
    let start = src.lines.iter().position(|l| !l.trim().is_empty()).unwrap_or(src.lines.len());
    if start > 0 {
        notes.push(format!("{start} blank line(s) before the first line were skipped"));
    }
    let first = src.lines.get(start).map_or("", String::as_str);
    let edition = Edition::of(first);
    if edition == Some(Edition::E2002) && !first.contains("2002") {
        notes.push(format!("unknown version line \"{}\", read as LM-63-2002", first.trim()));
    }
    let mut keywords: Vec<(String, String)> = Vec::new();
    let body = start + usize::from(edition.is_some());
    for (i, line) in src.lines.iter().enumerate().skip(body) {
        let t = line.trim();
        if t.to_ascii_uppercase().starts_with("TILT") && t.contains('=') {
            let value = t.split_once('=').map_or("", |(_, v)| v.trim());
            let tilt = match value.to_ascii_uppercase().as_str() {
                "NONE" => TiltSpec::None,
                "INCLUDE" => TiltSpec::Include,
                _ => TiltSpec::File(value.to_string()),
            };
            return Ok(Header { edition: edition.unwrap_or(Edition::E1986), keywords, tilt, tilt_line: i + 1 });
        }
        add_keyword(&mut keywords, t);
    }
    Err(ParseError::new(
        src.lines.len() + 1,
        "LM-63 TILT line",
        "the end of the file with no line starting \"TILT=\"",
        "TILT=NONE, TILT=INCLUDE or TILT=<file> after the keyword lines",
    ))
}

/// `[KEY] text` starts a keyword; `[MORE] text` continues the last one; other lines are labels.
fn add_keyword(keywords: &mut Vec<(String, String)>, line: &str) {
    let Some(rest) = line.strip_prefix('[') else {
        return;
    };
    let Some((key, text)) = rest.split_once(']') else {
        return;
    };
    let (key, text) = (key.trim().to_ascii_uppercase(), text.trim().to_string());
    match (key.as_str(), keywords.last_mut()) {
        ("MORE", Some((_, prev))) => {
            prev.push(' ');
            prev.push_str(&text);
        }
        _ => keywords.push((key, text)),
    }
}

/// The two lines of numbers after the tilt block.
struct Params {
    lamps: i64,
    lumens: f64,
    multiplier: f64,
    nv: usize,
    nh: usize,
    ptype: PhotometricType,
    metres_per_unit: f64,
    dims: [f64; 3],
    ballast: f64,
    factor2: f64,
    watts: f64,
}

fn params(tok: &mut Tokens) -> Result<Params, ParseError> {
    let (lamps, _) = tok.integer_in("LM-63 number of lamps", 1, 10_000)?;
    let (lumens, line) = tok.number("LM-63 lumens per lamp", "a positive number, or -1 for absolute photometry")?;
    if !(lumens > 0.0 || lumens == -1.0) {
        return Err(ParseError::new(
            line,
            "LM-63 lumens per lamp",
            lumens.to_string(),
            "a positive number, or -1 for absolute photometry",
        ));
    }
    let (multiplier, line) = tok.number_in("LM-63 candela multiplier", 0.0, super::MAX_MULTIPLIER)?;
    positive(multiplier, line, "LM-63 candela multiplier")?;
    let (nv, _) = tok.integer_in("LM-63 number of vertical angles", 2, 3601)?;
    let (nh, _) = tok.integer_in("LM-63 number of horizontal angles", 1, 3601)?;
    let (t, _) = tok.integer_in("LM-63 photometric type (1 = C, 2 = B, 3 = A)", 1, 3)?;
    let ptype = [PhotometricType::C, PhotometricType::B, PhotometricType::A][t as usize - 1];
    let (units, _) = tok.integer_in("LM-63 units type (1 = feet, 2 = metres)", 1, 2)?;
    let mut dims = [0.0; 3];
    for (d, name) in dims.iter_mut().zip(["width", "length", "height"]) {
        *d = tok.number_in(&format!("LM-63 luminous opening {name}"), -super::MAX_OPENING, super::MAX_OPENING)?.0;
    }
    let (ballast, line) = tok.number_in("LM-63 ballast factor", 0.0, f64::INFINITY)?;
    positive(ballast, line, "LM-63 ballast factor")?;
    let (factor2, _) =
        tok.number("LM-63 ballast-lamp photometric factor / future use / file generation type", "a number")?;
    let (watts, _) = tok.number_in("LM-63 input watts", 0.0, f64::INFINITY)?;
    let metres_per_unit = if units == 1 { 0.3048 } else { 1.0 };
    Ok(Params {
        lamps,
        lumens,
        multiplier,
        nv: nv as usize,
        nh: nh as usize,
        ptype,
        metres_per_unit,
        dims,
        ballast,
        factor2,
        watts,
    })
}

fn positive(x: f64, line: usize, field: &str) -> Result<(), ParseError> {
    if x > 0.0 { Ok(()) } else { Err(ParseError::new(line, field, x.to_string(), "a number > 0")) }
}

/// `n` strictly ascending angles within [lo, hi].
/// The `n` ascending angles of a list, and the line of its last one (0 for an empty list).
fn angle_list(tok: &mut Tokens, n: usize, which: &str, lo: f64, hi: f64) -> Result<(Vec<f64>, usize), ParseError> {
    let mut v: Vec<f64> = Vec::with_capacity(n);
    let mut last_line = 0;
    for i in 0..n {
        let field = format!("LM-63 {which} angle {} of {n}", i + 1);
        let (a, line) = tok.number_in(&field, lo, hi)?;
        last_line = line;
        if let Some(prev) = v.last()
            && a <= *prev
        {
            return Err(ParseError::new(line, field, a.to_string(), format!("an angle above {prev}° (ascending)")));
        }
        v.push(a);
    }
    Ok((v, last_line))
}

/// The candela table: one plane per horizontal angle.
fn table(tok: &mut Tokens, h: &[f64], v: &[f64]) -> Result<Vec<Plane>, ParseError> {
    let mut planes = Vec::with_capacity(h.len());
    for hi in h {
        let mut row = Vec::with_capacity(v.len());
        for vj in v {
            let field = format!("LM-63 candela value at horizontal angle {hi}°, vertical angle {vj}°");
            row.push(tok.number_in(&field, 0.0, super::MAX_TABLE_VALUE)?.0);
        }
        planes.push((*hi, row));
    }
    Ok(planes)
}

fn read_tilt(h: &Header, tok: &mut Tokens, path: &Path) -> Result<Option<Tilt>, ParseError> {
    match &h.tilt {
        TiltSpec::None => Ok(None),
        TiltSpec::Include => Tilt::read(tok, "INCLUDE").map(Some),
        TiltSpec::File(name) => {
            let tilt_path = path.parent().unwrap_or(Path::new(".")).join(name);
            let bytes = std::fs::read(&tilt_path).map_err(|e| {
                ParseError::new(
                    h.tilt_line,
                    "LM-63 TILT=<file>",
                    format!("\"{name}\", which cannot be read ({e})"),
                    "a tilt file beside the IES file, or TILT=NONE or TILT=INCLUDE",
                )
            })?;
            let src = SourceText::decode(&bytes);
            Tilt::read(&mut Tokens::new(&src, 1, true), name).map(Some).map_err(|e| e.in_file(&tilt_path))
        }
    }
}

pub fn read(src: &SourceText, path: &Path) -> Result<Photometry, ParseError> {
    let mut notes = Vec::new();
    let h = header(src, &mut notes)?;
    let mut tok = Tokens::new(src, h.tilt_line + 1, true);
    let tilt = read_tilt(&h, &mut tok, path)?;
    let p = params(&mut tok)?;
    let (vlo, vhi, hlo, hhi) = match p.ptype {
        PhotometricType::C => (0.0, 180.0, 0.0, 360.0),
        _ => (-90.0, 90.0, -180.0, 180.0),
    };
    let (v, _) = angle_list(&mut tok, p.nv, "vertical", vlo, vhi)?;
    let (hz, hz_line) = angle_list(&mut tok, p.nh, "horizontal", hlo, hhi)?;
    let planes = table(&mut tok, &hz, &v)?;
    let (left, first) = tok.rest();
    if let Some(line) = first {
        notes.push(format!("{left} values after the candela table (from line {line}) were ignored"));
    }
    let mut scale = p.multiplier * p.ballast;
    if matches!(h.edition, Edition::E1986 | Edition::E1991 | Edition::E1995) {
        scale *= p.factor2;
    }
    let (symmetry, web) = build_web(p.ptype, planes, v, scale, hz_line, &mut notes)?;
    Ok(photometry(src, &h, &p, symmetry, web, tilt, notes))
}

fn photometry(
    src: &SourceText,
    h: &Header,
    p: &Params,
    symmetry: Symmetry,
    web: PhotometricWeb,
    tilt: Option<Tilt>,
    mut notes: Vec<String>,
) -> Photometry {
    let absolute = p.lumens < 0.0;
    let lamp_flux = (!absolute).then_some(p.lamps as f64 * p.lumens);
    let [w, l, ht] = p.dims.map(|d| d * p.metres_per_unit);
    let (opening, note) = Opening::from_lm63(w, l, ht);
    notes.extend(note);
    let text = |k: &str| h.keyword(k).unwrap_or("").to_string();
    let lamp = LampSet {
        count: p.lamps,
        description: h.keyword("LAMP").or(h.keyword("LAMPCAT")).unwrap_or("").to_string(),
        flux_lm: lamp_flux,
        colour_temperature: h.keyword("_TEMPCOLOR").or(h.keyword("COLORTEMP")).unwrap_or("").to_string(),
        colour_rendering: h.keyword("_CRI").unwrap_or("").to_string(),
        watts: Some(p.watts),
    };
    Photometry {
        format: h.edition.name().to_string(),
        encoding: src.encoding,
        manufacturer: text("MANUFAC"),
        luminaire: h.keyword("LUMINAIRE").or(h.keyword("LUMCAT")).unwrap_or("").to_string(),
        catalogue: text("LUMCAT"),
        lamps: vec![lamp],
        lamp_flux_lm: lamp_flux,
        stated_flux_lm: None,
        absolute,
        photometric_type: p.ptype,
        symmetry,
        stored_grid: (p.nh, p.nv),
        opening,
        input_watts: Some(p.watts),
        tilt,
        dff_percent: None,
        lorl_percent: None,
        measurement_tilt_deg: None,
        web,
        notes,
        spectrum: None,
    }
}

fn build_web(
    ptype: PhotometricType,
    planes: Vec<Plane>,
    v: Vec<f64>,
    scale: f64,
    horizontal_line: usize,
    notes: &mut Vec<String>,
) -> Result<(Symmetry, PhotometricWeb), ParseError> {
    let symmetry = match ptype {
        PhotometricType::C => type_c_symmetry(&planes.iter().map(|p| p.0).collect::<Vec<_>>()).map_err(|found| {
            ParseError::new(
                horizontal_line,
                "LM-63 horizontal angles (type C)",
                found,
                "last 0° (rotational), 0–90°, 0–180°, 90–270°, or 0° to more than 180°",
            )
        })?,
        _ if planes[0].0 >= 0.0 => Symmetry::Lateral,
        _ => Symmetry::None,
    };
    let web = web_from_planes(ptype, symmetry, planes, v, scale, "LM-63 candela table", notes)?;
    Ok((symmetry, web))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The LM-63-2002 worked example (spec Annex), with a chosen first line and TILT.
    fn example(first: &str, tilt: &str) -> String {
        format!(
            "{first}[TEST] ABC1234\n[MANUFAC] Aardvark lighting Inc.\n[LUMCAT] SKYVIEW 123-XYZ-abs-400\n\
             [LUMINAIRE] Wide beam flood\n[MORE] to be used without tilt\n[LAMP] 400 Watt Metal Halide\n{tilt}\
             1 50000 1 5 3 1 1 .5 .6 0\n1.0 1.0 495\n0 22.5 45 67.5 90\n0 45 90\n\
             100000 50000 25000 10000 5000\n100000 35000 16000 8000 3000\n100000 20000 10000 5000 1000\n"
        )
    }

    const INCLUDE: &str = "TILT=INCLUDE\n1\n13\n0 15 30 45 60 75 90 105 120 135 150 165 180\n1.0 .95 .94 .90 .88 .87 .98 .87 .88 .90 .94 .95 1.0\n";

    fn read_str(s: &str) -> Result<Photometry, ParseError> {
        read(&SourceText::decode(s.as_bytes()), Path::new("t.ies"))
    }

    #[test]
    fn every_edition_is_recognised() {
        for (first, name) in [
            ("", "IES LM-63-1986"),
            ("Some label line\n", "IES LM-63-1986"),
            ("IESNA91\n", "IES LM-63-1991"),
            ("IESNA:LM-63-1995\n", "IES LM-63-1995"),
            ("IESNA: LM-63-2002 \n", "IES LM-63-2002"),
            ("IES:LM-63-2019\n", "IES LM-63-2019"),
        ] {
            let p = read_str(&example(first, "TILT=NONE\n")).unwrap();
            assert_eq!(p.format, name);
        }
    }

    #[test]
    fn header_facts_keywords_tilt_and_symmetry() {
        let p = read_str(&example("IESNA:LM-63-2002\n", INCLUDE)).unwrap();
        assert_eq!(p.manufacturer, "Aardvark lighting Inc.");
        assert_eq!(p.luminaire, "Wide beam flood to be used without tilt");
        assert_eq!(p.lamps[0].count, 1);
        assert_eq!(p.lamp_flux_lm, Some(50000.0));
        assert!(!p.absolute);
        assert_eq!(p.symmetry, Symmetry::Quadrant);
        assert_eq!(p.stored_grid, (3, 5));
        assert_eq!(p.tilt.as_ref().map(|t| t.angles_deg.len()), Some(13));
        // Feet to metres: 0.5 ft × 0.6 ft rectangle.
        assert!((p.opening.size_m.y - 0.1524).abs() < 1e-12 && (p.opening.size_m.x - 0.18288).abs() < 1e-12);
        // Quadrant symmetry: C135 mirrors C45, C270 mirrors C90.
        assert_eq!(p.web.intensity_at(135.0, 22.5), 35000.0);
        assert_eq!(p.web.intensity_at(270.0, 45.0), 10000.0);
        assert_eq!(p.web.intensity_at(0.0, 100.0), 0.0);
    }

    #[test]
    fn values_wrap_freely_and_commas_separate() {
        let s = example("IESNA:LM-63-2002\n", "TILT=NONE\n")
            .replace("1 50000 1 5 3 1 1 .5 .6 0\n", "1,50000\n1 5\n3 1 1\n.5,.6,0 ");
        let p = read_str(&s).unwrap();
        assert_eq!(p.web.intensity_at(90.0, 90.0), 1000.0);
    }

    #[test]
    fn absolute_photometry_ballast_factor_and_junk() {
        let s = example("IESNA:LM-63-2002\n", "TILT=NONE\n")
            .replace("1 50000 1 5 3", "1 -1 2 5 3")
            .replace("1.0 1.0 495", "0.5 1.0 495")
            + "junk 1 2 3\n";
        let p = read_str(&s).unwrap();
        assert!(p.absolute);
        assert_eq!(p.lamp_flux_lm, None);
        // Candela multiplier 2 × ballast factor 0.5.
        assert_eq!(p.web.intensity_at(0.0, 0.0), 100000.0);
        assert_eq!(p.notes.len(), 1, "{:?}", p.notes);
    }

    #[test]
    fn type_b_maps_h_and_v_about_the_transverse_axis() {
        // Type B, laterally symmetric (H 0–90): I = 1000 + 10 H + V.
        let mut s = String::from("IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 3 3 2 2 0 0 0\n1 1 0\n-90 0 90\n0 45 90\n");
        for h in [0.0, 45.0, 90.0] {
            for v in [-90.0, 0.0, 90.0] {
                s += &format!("{} ", 1000.0 + 10.0 * h + v);
            }
            s += "\n";
        }
        let p = read_str(&s).unwrap();
        assert_eq!(p.symmetry, Symmetry::Lateral);
        assert_eq!(p.photometric_type, PhotometricType::B);
        let at = |d: glam::DVec3| p.web.intensity(d.normalize());
        // H = V = 0 is nadir; H = 45 turns toward +x; H = −45 mirrors it; V = 90 is +y.
        assert!((at(glam::DVec3::NEG_Z) - 1000.0).abs() < 1e-9);
        assert!((at(glam::DVec3::new(1.0, 0.0, -1.0)) - 1450.0).abs() < 1e-9);
        assert!((at(glam::DVec3::new(-1.0, 0.0, -1.0)) - 1450.0).abs() < 1e-9);
        assert!((at(glam::DVec3::Y) - 1090.0).abs() < 1e-9);
        // Nothing toward the back (|H| > 90°).
        assert_eq!(at(glam::DVec3::new(0.0, 0.3, 1.0)), 0.0);
    }

    #[test]
    fn type_a_has_elevation_angles_and_clockwise_h() {
        let s = "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 3 3 3 2 0 0 0\n1 1 0\n-90 0 90\n-90 0 90\n\
                 1 2 3\n4 5 6\n7 8 9\n";
        let p = read_str(s).unwrap();
        assert_eq!(p.symmetry, Symmetry::None);
        // H = 0, V = 0 is horizontal along +x; V = −90 is nadir; H = 90 (clockwise from above) is −y.
        assert!((p.web.intensity(glam::DVec3::X) - 5.0).abs() < 1e-9);
        assert!((p.web.intensity(glam::DVec3::NEG_Y) - 8.0).abs() < 1e-9);
        // Interpolation is linear in cos γ: halfway in angle (γ = 135°) is 1/√2 of the way.
        let up = glam::DVec3::new(0.0, -1.0, 1.0).normalize();
        assert!((p.web.intensity(up) - (8.0 + 0.5f64.sqrt())).abs() < 1e-9);
    }

    #[test]
    fn full_circle_type_c_drops_the_repeated_360_plane() {
        let s = "IESNA:LM-63-2002\nTILT=NONE\n1 1000 1 2 5 1 2 0 0 0\n1 1 10\n0 90\n0 90 180 270 360\n\
                 10 1\n20 2\n30 3\n40 4\n10 1\n";
        let p = read_str(s).unwrap();
        assert_eq!(p.symmetry, Symmetry::None);
        assert_eq!(p.web.c_deg(), &[0.0, 90.0, 180.0, 270.0]);
        assert!((p.web.intensity_at(315.0, 90.0) - 2.5).abs() < 1e-9);
    }

    #[test]
    fn tilt_from_a_file_and_a_missing_tilt_file() {
        let dir = std::env::temp_dir().join(format!("morgana-ies-tilt-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("lamp.tlt"), "1\n2\n0 90\n1 0.5\n").unwrap();
        let text = example("IESNA:LM-63-2002\n", "TILT=lamp.tlt\n");
        let p = read(&SourceText::decode(text.as_bytes()), &dir.join("a.ies")).unwrap();
        assert_eq!(p.tilt.unwrap().factor(45.0), 0.75);
        let text = example("IESNA:LM-63-2002\n", "TILT=missing.tlt\n");
        let e = read(&SourceText::decode(text.as_bytes()), &dir.join("a.ies")).unwrap_err();
        assert_eq!(e.line, Some(8));
        assert!(e.found.contains("missing.tlt"), "{e}");
        std::fs::write(dir.join("bad.tlt"), "1\n2\n0 x\n").unwrap();
        let text = example("IESNA:LM-63-2002\n", "TILT=bad.tlt\n");
        let e = read(&SourceText::decode(text.as_bytes()), &dir.join("a.ies")).unwrap_err();
        assert_eq!(e.file, Some(dir.join("bad.tlt")));
        assert_eq!(e.line, Some(3));
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn errors_name_line_field_found_and_expected() {
        let base = example("IESNA:LM-63-2002\n", "TILT=NONE\n");
        let e = read_str(&base.replace("1 50000 1 5 3 1 1", "1 50000 1 5 3 7 1")).unwrap_err();
        assert_eq!(e.line, Some(9));
        assert!(e.field.contains("photometric type") && e.found == "7" && e.expected == "an integer from 1 to 3");
        let e = read_str(&base.replace("100000 35000", "100000 3500O")).unwrap_err();
        assert_eq!(e.line, Some(14));
        assert!(e.field.contains("horizontal angle 45°, vertical angle 22.5°"), "{e}");
        assert_eq!(e.found, "\"3500O\"");
        let e = read_str(&base.replace("0 22.5 45 67.5 90", "0 22.5 45 40 90")).unwrap_err();
        assert!(e.expected.contains("ascending"), "{e}");
        let e = read_str(&base.replace("0 45 90\n", "0 45 120\n")).unwrap_err();
        assert!(e.field.contains("horizontal angles") && e.found == "first 0°, last 120°", "{e}");
        // The line of the list's last angle (the fuzzer found this error without a line).
        assert_eq!(e.line, Some(12), "{e}");
        // An opening of 1.8e308 ft printed as "inf × 300 mm" (the fuzzer): at most 10^4 units.
        let e = read_str(&base.replace("1 1 .5 .6 0", "1 1 .5 1.7976931348623157e308 0")).unwrap_err();
        assert_eq!(e.line, Some(9), "{e}");
        assert!(e.field.contains("luminous opening length") && e.expected.contains("10000"), "{e}");
        let e = read_str(&base.replace("TILT=NONE\n", "")).unwrap_err();
        assert!(e.field.contains("TILT"), "{e}");
        let e = read_str(&base.replace("1 50000", "1 0")).unwrap_err();
        assert!(e.field.contains("lumens per lamp"), "{e}");
        let cut: String = base.lines().take(13).map(|l| format!("{l}\n")).collect();
        assert_eq!(read_str(&cut).unwrap_err().found, "the end of the file");
    }

    #[test]
    fn sniffing() {
        assert!(sniff(&SourceText::decode(example("", "TILT=NONE\n").as_bytes())));
        assert!(sniff(&SourceText::decode(b"\n\nIESNA:LM-63-2002\n")));
        assert!(!sniff(&SourceText::decode(b"ACME\n1\n2\n")));
    }
}
