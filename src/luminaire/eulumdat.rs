//! EULUMDAT (.ldt) reader.
//!
//! The format is a fixed sequence of lines (Stockmar 1990, 1998):
//!
//! | field | content |
//! |---|---|
//! | 1 | company identification |
//! | 2 | Ityp: 0 point source without symmetry, 1 symmetric about the vertical axis, 2 linear, 3 other |
//! | 3 | Isym: 0 none, 1 about the vertical axis, 2 about C0–C180, 3 about C90–C270, 4 about both |
//! | 4, 5 | Mc, number of C-planes in 0–360°; Dc, their spacing (0: uneven) |
//! | 6, 7 | Ng, number of intensities per C-plane; Dg, their spacing (0: uneven) |
//! | 8–12 | measurement report number, luminaire name, luminaire number, file name, date/user |
//! | 13–15 | luminaire length (or diameter), width (0: circular), height, mm |
//! | 16–21 | luminous area length (or diameter), width (0: circular), heights at C0, C90, C180, C270, mm |
//! | 22–25 | DFF (downward flux fraction, %), LORL (light output ratio, %), conversion factor for intensities, tilt during measurement (°) |
//! | 26 | n, number of standard lamp sets; then per set: 26a number of lamps (negative: absolute photometry), 26b type, 26c total flux (lm), 26d colour temperature, 26e colour rendering, 26f wattage including ballast (W) |
//! | 27 | direct ratios for room indices k = 0.6 … 5 (10 values) |
//! | 28, 29 | the Mc C-angles and the Ng γ-angles, degrees |
//! | 30 | intensities, cd per 1000 lm of lamp flux, plane by plane for the planes Isym stores |
//!
//! Isym decides which planes are stored (1-based indices into the C-angles, Mc1…Mc2): Isym 0 all;
//! 1 one plane; 2 C0–C180 (1 … Mc/2 + 1); 3 C270 through C0 to C90 (3Mc/4 + 1 … 3Mc/4 + Mc/2 + 1,
//! wrapping past Mc); 4 C0–C90 (1 … Mc/4 + 1). [`super::symmetry`] expands them.
//!
//! Intensity in cd = value × conversion factor × (flux of the first lamp set)/1000. Further lamp
//! sets are alternative equipments the file also describes; they are listed, not added. The
//! luminaire flux the file states is LORL/100 × that lamp flux.
//!
//! Tolerated, because real files do it: a blank line before field 1, decimal commas, values
//! beyond the intensity table (ignored with a note), and more than one value on a line from
//! field 27 on.
//!
//! # References
//! - A. Stockmar (1990), "EULUMDAT — ein Leuchtendatenformat für den europäischen
//!   Beleuchtungsplaner", Tagungsband Licht '90; and the EULUMDAT/2 description (1998), LCI.

use super::opening::Opening;
use super::symmetry::{self, Plane, Symmetry};
use super::text::{SourceText, Tokens, parse_number, range_text};
use super::web::{PhotometricWeb, WebAxes};
use super::{LampSet, ParseError, PhotometricType, Photometry, Reader};
use std::path::Path;

pub const READER: Reader = Reader { name: "EULUMDAT", extensions: &["ldt", "eul"], sniff, read, implemented: true };

/// Lines 2–4 after an optional leading blank line are Ityp, Isym and Mc.
fn sniff(src: &SourceText) -> bool {
    let o = leading_blank_offset(src);
    let int = |n: usize, lo: f64, hi: f64| {
        src.line(n + o).and_then(parse_number).is_some_and(|x| x.fract() == 0.0 && (lo..=hi).contains(&x))
    };
    int(2, 0.0, 3.0) && int(3, 0.0, 4.0) && int(4, 1.0, 3600.0)
}

/// 1 when the file starts with a blank line that is not the company field (line 2 is then not
/// Ityp but line 3 is).
fn leading_blank_offset(src: &SourceText) -> usize {
    let is_int = |n: usize| src.line(n).and_then(parse_number).is_some_and(|x| x.fract() == 0.0);
    let blank_first = src.line(1).is_some_and(|l| l.trim().is_empty());
    usize::from(blank_first && !is_int(2) && is_int(3))
}

fn field(number: &str, name: &str) -> String {
    format!("EULUMDAT field {number} ({name})")
}

/// Reads the fixed one-value-per-line fields 1–26.
struct Lines<'a> {
    src: &'a SourceText,
    next: usize,
}

impl Lines<'_> {
    fn take(&mut self, field: &str) -> Result<(String, usize), ParseError> {
        let n = self.next;
        self.next += 1;
        match self.src.line(n) {
            Some(l) => Ok((l.trim().to_string(), n)),
            None => Err(ParseError::new(n, field, "the end of the file", "a line for this field")),
        }
    }

    fn text(&mut self, field: &str) -> Result<String, ParseError> {
        Ok(self.take(field)?.0)
    }

    fn number(&mut self, field: &str, lo: f64, hi: f64) -> Result<(f64, usize), ParseError> {
        let (s, n) = self.take(field)?;
        let expected = range_text(lo, hi, false);
        match parse_number(&s) {
            Some(x) if (lo..=hi).contains(&x) => Ok((x, n)),
            Some(x) => Err(ParseError::new(n, field, x.to_string(), expected)),
            None => Err(ParseError::new(n, field, format!("\"{s}\""), expected)),
        }
    }

    fn integer(&mut self, field: &str, lo: i64, hi: i64) -> Result<(i64, usize), ParseError> {
        let (s, n) = self.take(field)?;
        let expected = format!("an integer from {lo} to {hi}");
        match parse_number(&s) {
            Some(x) if x.fract() == 0.0 && (lo as f64..=hi as f64).contains(&x) => Ok((x as i64, n)),
            _ => Err(ParseError::new(n, field, format!("\"{s}\""), expected)),
        }
    }
}

/// Fields 1–25.
struct Header {
    company: String,
    isym: i64,
    mc: usize,
    ng: usize,
    dg: f64,
    name: String,
    number: String,
    area_mm: [f64; 6],
    dff: f64,
    lorl: f64,
    conversion: f64,
    tilt_deg: f64,
}

fn header(l: &mut Lines) -> Result<Header, ParseError> {
    let company = l.text(&field("1", "company identification"))?;
    l.integer(&field("2", "Ityp, type indicator"), 0, 3)?;
    let (isym, _) = l.integer(&field("3", "Isym, symmetry indicator"), 0, 4)?;
    let (mc, mc_line) = l.integer(&field("4", "Mc, number of C-planes between 0 and 360°"), 1, 3600)?;
    check_mc(isym, mc, mc_line)?;
    l.number(&field("5", "Dc, distance between C-planes"), 0.0, 360.0)?;
    let (ng, _) = l.integer(&field("6", "Ng, number of luminous intensities in each C-plane"), 2, 3601)?;
    let (dg, _) = l.number(&field("7", "Dg, distance between luminous intensities per C-plane"), 0.0, 180.0)?;
    l.text(&field("8", "measurement report number"))?;
    let name = l.text(&field("9", "luminaire name"))?;
    let number = l.text(&field("10", "luminaire number"))?;
    l.text(&field("11", "file name"))?;
    l.text(&field("12", "date/user"))?;
    for (f, name) in [
        ("13", "length/diameter of luminaire, mm"),
        ("14", "width of luminaire, mm"),
        ("15", "height of luminaire, mm"),
    ] {
        l.number(&field(f, name), 0.0, f64::INFINITY)?;
    }
    let mut area_mm = [0.0; 6];
    let names = [
        ("16", "length/diameter of luminous area, mm"),
        ("17", "width of luminous area, mm"),
        ("18", "height of luminous area C0-plane, mm"),
        ("19", "height of luminous area C90-plane, mm"),
        ("20", "height of luminous area C180-plane, mm"),
        ("21", "height of luminous area C270-plane, mm"),
    ];
    for (a, (f, name)) in area_mm.iter_mut().zip(names) {
        *a = l.number(&field(f, name), 0.0, f64::INFINITY)?.0;
    }
    let (dff, _) = l.number(&field("22", "DFF, downward flux fraction, %"), 0.0, 100.0)?;
    let (lorl, _) = l.number(&field("23", "LORL, light output ratio luminaire, %"), 0.0, 100.0)?;
    let (conversion, _) =
        l.number(&field("24", "conversion factor for luminous intensities"), 0.0, super::MAX_MULTIPLIER)?;
    let (tilt_deg, _) = l.number(&field("25", "tilt of luminaire during measurement, °"), -180.0, 180.0)?;
    Ok(Header {
        company,
        isym,
        mc: mc as usize,
        ng: ng as usize,
        dg,
        name,
        number,
        area_mm,
        dff,
        lorl,
        conversion,
        tilt_deg,
    })
}

/// Isym 2 needs an even Mc; Isym 3 and 4 a multiple of 4 (Mc1 and Mc2 must be whole planes).
fn check_mc(isym: i64, mc: i64, line: usize) -> Result<(), ParseError> {
    let need = match isym {
        2 => 2,
        3 | 4 => 4,
        _ => 1,
    };
    if mc % need != 0 {
        return Err(ParseError::new(
            line,
            field("4", "Mc, number of C-planes between 0 and 360°"),
            mc.to_string(),
            format!("a multiple of {need} for Isym {isym}"),
        ));
    }
    Ok(())
}

/// Field 26 and the n sets of 26a–26f.
fn lamp_sets(l: &mut Lines) -> Result<Vec<LampSet>, ParseError> {
    let (n, _) = l.integer(&field("26", "n, number of standard sets of lamps"), 1, 50)?;
    let mut sets = Vec::new();
    for s in 1..=n {
        let f = |c: &str, name: &str| field(&format!("26{c}"), &format!("{name}, lamp set {s}"));
        let (count, line) = l.integer(&f("a", "number of lamps"), -10_000, 10_000)?;
        if count == 0 {
            return Err(ParseError::new(
                line,
                f("a", "number of lamps"),
                "0",
                "a non-zero integer (negative: absolute photometry)",
            ));
        }
        let description = l.text(&f("b", "type of lamps"))?;
        let (flux, line) = l.number(&f("c", "total luminous flux of lamps, lm"), 0.0, f64::INFINITY)?;
        if flux <= 0.0 {
            return Err(ParseError::new(line, f("c", "total luminous flux of lamps, lm"), "0", "a positive flux"));
        }
        let colour_temperature = l.text(&f("d", "colour temperature"))?;
        let colour_rendering = l.text(&f("e", "colour rendering index"))?;
        let (w, line) = l.take(&f("f", "wattage including ballast, W"))?;
        let watts = match (w.is_empty(), parse_number(&w)) {
            (true, _) => None,
            (false, Some(x)) if x >= 0.0 => Some(x),
            _ => {
                return Err(ParseError::new(
                    line,
                    f("f", "wattage including ballast, W"),
                    format!("\"{w}\""),
                    "a number ≥ 0",
                ));
            }
        };
        sets.push(LampSet { count, description, flux_lm: Some(flux), colour_temperature, colour_rendering, watts });
    }
    Ok(sets)
}

/// `n` strictly ascending angles within [lo, hi] (field 28 or 29).
fn angles(tok: &mut Tokens, n: usize, f: &str, name: &str, lo: f64, hi: f64) -> Result<Vec<f64>, ParseError> {
    let mut v: Vec<f64> = Vec::with_capacity(n.min(4096));
    for i in 0..n {
        let what = field(f, &format!("{name}, value {} of {n}", i + 1));
        let (a, line) = tok.number_in(&what, lo, hi)?;
        if let Some(prev) = v.last()
            && a <= *prev
        {
            return Err(ParseError::new(line, what, a.to_string(), format!("an angle above {prev}° (ascending)")));
        }
        v.push(a);
    }
    Ok(v)
}

/// 1-based C-angle indices of the stored planes, wrapped into 0..Mc (0-based).
fn stored_plane_indices(isym: i64, mc: usize) -> Vec<usize> {
    match isym {
        1 => vec![0],
        2 => (0..=mc / 2).collect(),
        3 => (0..=mc / 2).map(|k| (3 * mc / 4 + k) % mc).collect(),
        4 => (0..=mc / 4).collect(),
        _ => (0..mc).collect(),
    }
}

fn symmetry_of(isym: i64) -> Symmetry {
    match isym {
        1 => Symmetry::Rotational,
        2 => Symmetry::C0C180,
        3 => Symmetry::C90C270,
        4 => Symmetry::Quadrant,
        _ => Symmetry::None,
    }
}

/// Field 30: the stored planes' intensities, cd/klm.
fn intensities(tok: &mut Tokens, h: &Header, c: &[f64], g: &[f64]) -> Result<Vec<Plane>, ParseError> {
    let mut planes = Vec::new();
    for i in stored_plane_indices(h.isym, h.mc) {
        let mut values = Vec::with_capacity(h.ng);
        for gj in g {
            let what = field("30", &format!("luminous intensity at C{}° γ{gj}°, cd/1000 lm", c[i]));
            values.push(tok.number_in(&what, 0.0, super::MAX_TABLE_VALUE)?.0);
        }
        planes.push((c[i], values));
    }
    Ok(planes)
}

pub fn read(src: &SourceText, _path: &Path) -> Result<Photometry, ParseError> {
    let mut notes = Vec::new();
    let offset = leading_blank_offset(src);
    if offset > 0 {
        notes.push("a blank line before the company identification was skipped".to_string());
    }
    let mut l = Lines { src, next: 1 + offset };
    let h = header(&mut l)?;
    let lamps = lamp_sets(&mut l)?;
    let mut tok = Tokens::new(src, l.next, false);
    for k in 1..=10 {
        tok.number_in(&field("27", &format!("direct ratio {k} of 10")), 0.0, f64::INFINITY)?;
    }
    let c = angles(&mut tok, h.mc, "28", "C-angle", 0.0, 360.0)?;
    let g = angles(&mut tok, h.ng, "29", "γ-angle", 0.0, 180.0)?;
    if h.dg > 0.0 && g.iter().enumerate().any(|(i, x)| (x - g[0] - i as f64 * h.dg).abs() > 1e-6) {
        notes.push(format!("Dg = {} but the γ-angles are not evenly spaced by it; the listed angles are used", h.dg));
    }
    let table_line = tok.rest().1.unwrap_or(l.next);
    let stored = intensities(&mut tok, &h, &c, &g)?;
    let (left, first) = tok.rest();
    if let Some(line) = first {
        notes.push(format!("{left} values after the intensity table (from line {line}) were ignored"));
    }
    let lamp_flux = lamps[0].flux_lm.unwrap_or(0.0);
    let symmetry = symmetry_of(h.isym);
    let stored_grid = (stored.len(), g.len());
    let web = build_web(stored, symmetry, g, h.conversion * lamp_flux / 1000.0, table_line, &mut notes)?;
    Ok(Photometry {
        format: "EULUMDAT".into(),
        encoding: src.encoding,
        manufacturer: h.company,
        luminaire: h.name,
        catalogue: h.number,
        absolute: lamps[0].count < 0,
        input_watts: lamps[0].watts,
        lamp_flux_lm: Some(lamp_flux),
        stated_flux_lm: Some(h.lorl / 100.0 * lamp_flux),
        lamps,
        photometric_type: PhotometricType::C,
        symmetry,
        stored_grid,
        opening: Opening::from_eulumdat(
            h.area_mm[0],
            h.area_mm[1],
            [h.area_mm[2], h.area_mm[3], h.area_mm[4], h.area_mm[5]],
        ),
        tilt: None,
        dff_percent: Some(h.dff),
        lorl_percent: Some(h.lorl),
        measurement_tilt_deg: Some(h.tilt_deg),
        web,
        notes,
        spectrum: None,
    })
}

/// Expands the stored planes to the full circle and scales cd/klm to cd.
fn build_web(
    stored: Vec<Plane>,
    symmetry: Symmetry,
    g: Vec<f64>,
    cd_per_value: f64,
    table_line: usize,
    notes: &mut Vec<String>,
) -> Result<PhotometricWeb, ParseError> {
    let mut planes = symmetry::expand(stored, symmetry);
    let before = planes.len();
    planes.dedup_by(|b, a| (a.0 - b.0).abs() < 1e-9);
    if planes.len() < before {
        notes.push("a C-plane listed twice (C0 and C360) was used once".to_string());
    }
    let c: Vec<f64> = planes.iter().map(|p| p.0).collect();
    let cd: Vec<f64> = planes.into_iter().flat_map(|p| p.1).map(|v| v * cd_per_value).collect();
    let web = PhotometricWeb::new(WebAxes::TYPE_C, c, true, g, cd)
        .map_err(|e| {
            ParseError::new(
                table_line,
                "EULUMDAT intensity table (field 30)",
                e,
                "a valid photometric web (the values in cd/klm times the lamp flux, field 26c, and the conversion factor, field 22)",
            )
        })?;
    if let Some(n) = web.pole_note() {
        notes.push(n.to_string());
    }
    Ok(web)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small EULUMDAT file: `isym`, Mc C-planes at 360/Mc spacing, γ = 0, 45, 90, and each
    /// stored plane's intensities [100, 50 + C, C/10] cd/klm; one lamp set of 2000 lm, LORL 80.
    pub fn small(isym: i64, mc: usize) -> String {
        let mut s = String::from("ACME\n1\n");
        s += &format!(
            "{isym}\n{mc}\n{}\n3\n45\nR1\nLamp\nNo1\nf.ldt\n2024\n100\n100\n50\n80\n0\n0\n0\n0\n0\n",
            360.0 / mc as f64
        );
        s += "100\n80\n1.0\n0\n1\n2\nLED\n2000\n3000 K\n80\n20\n";
        s += &"0.5\n".repeat(10);
        for i in 0..mc {
            s += &format!("{}\n", 360.0 * i as f64 / mc as f64);
        }
        s += "0\n45\n90\n";
        for i in stored_plane_indices(isym, mc) {
            let c = 360.0 * i as f64 / mc as f64;
            s += &format!("100\n{}\n{}\n", 50.0 + c, c / 10.0);
        }
        s
    }

    fn read_str(s: &str) -> Result<Photometry, ParseError> {
        read(&SourceText::decode(s.as_bytes()), Path::new("t.ldt"))
    }

    #[test]
    fn header_facts_and_scaling() {
        let p = read_str(&small(0, 4)).unwrap();
        assert_eq!(p.manufacturer, "ACME");
        assert_eq!(p.luminaire, "Lamp");
        assert_eq!(p.catalogue, "No1");
        assert_eq!(p.lamps.len(), 1);
        assert_eq!(p.lamps[0].count, 2);
        assert_eq!(p.lamp_flux_lm, Some(2000.0));
        assert_eq!(p.stated_flux_lm, Some(1600.0));
        assert_eq!(p.stored_grid, (4, 3));
        assert_eq!(p.symmetry, Symmetry::None);
        // 140 cd/klm at C90 γ45 × 2000 lm / 1000.
        assert!((p.web.intensity_at(90.0, 45.0) - 280.0).abs() < 1e-9);
        assert_eq!(p.opening, Opening::from_eulumdat(80.0, 0.0, [0.0; 4]));
        assert!(p.notes.is_empty(), "{:?}", p.notes);
    }

    #[test]
    fn isym_3_planes_run_from_c270_through_c0_and_mirror_about_c90() {
        // Mc = 8 (45° apart): stored C270, C315, C0, C45, C90.
        let p = read_str(&small(3, 8)).unwrap();
        assert_eq!(p.stored_grid, (5, 3));
        assert_eq!(p.web.c_deg(), &[0.0, 45.0, 90.0, 135.0, 180.0, 225.0, 270.0, 315.0]);
        let at = |c: f64| p.web.intensity_at(c, 45.0) / 2.0 - 50.0;
        // C135 mirrors C45, C180 mirrors C0, C225 mirrors C315 (= −45°).
        assert!((at(135.0) - 45.0).abs() < 1e-9);
        assert!((at(180.0) - 0.0).abs() < 1e-9);
        assert!((at(225.0) - 315.0).abs() < 1e-9);
        assert!((at(270.0) - 270.0).abs() < 1e-9);
    }

    #[test]
    fn isym_1_2_4_expand_to_the_full_circle() {
        let p = read_str(&small(1, 4)).unwrap();
        assert_eq!(p.web.c_deg(), &[0.0]);
        assert!((p.web.intensity_at(123.0, 45.0) - 100.0).abs() < 1e-9);
        let p = read_str(&small(2, 4)).unwrap();
        assert_eq!(p.stored_grid.0, 3);
        assert!((p.web.intensity_at(270.0, 45.0) - p.web.intensity_at(90.0, 45.0)).abs() < 1e-9);
        let p = read_str(&small(4, 8)).unwrap();
        assert_eq!(p.stored_grid.0, 3);
        assert!((p.web.intensity_at(315.0, 45.0) / 2.0 - 95.0).abs() < 1e-9, "C315 mirrors C45");
    }

    #[test]
    fn tolerates_a_leading_blank_line_junk_crlf_latin1_and_decimal_commas() {
        let mut s = format!("\n{}", small(0, 4)).replace("\n80\n1.0\n", "\n80\n1,0\n");
        s = s.replace("ACME", "Leuchten f\u{fc}r B\u{fc}ro");
        s += "end of data\n\n";
        let bytes: Vec<u8> = s.replace('\n', "\r\n").chars().map(|c| c as u32 as u8).collect();
        let p = read(&SourceText::decode(&bytes), Path::new("t.ldt")).unwrap();
        assert_eq!(p.manufacturer, "Leuchten für Büro");
        assert_eq!(p.encoding, "Latin-1");
        assert_eq!(p.notes.len(), 2, "{:?}", p.notes);
        assert!((p.web.intensity_at(0.0, 45.0) - 100.0).abs() < 1e-9);
    }

    #[test]
    fn uneven_gamma_angles_with_dg_zero() {
        let s = small(0, 4).replace("\n45\nR1", "\n0\nR1").replace("0\n45\n90\n", "0\n10\n90\n");
        let p = read_str(&s).unwrap();
        assert_eq!(p.web.gamma_deg(), &[0.0, 10.0, 90.0]);
        assert!(p.notes.is_empty());
    }

    #[test]
    fn errors_name_line_field_found_and_expected() {
        let e = read_str(&small(0, 4).replacen("\n0\n4\n", "\n0\nfour\n", 1)).unwrap_err();
        assert_eq!(e.line, Some(4));
        assert!(e.field.contains("Mc"), "{e}");
        assert_eq!(e.found, "\"four\"");
        let e = read_str(&small(0, 4).replacen("\n1\n0\n4\n", "\n1\n7\n4\n", 1)).unwrap_err();
        assert!(e.field.contains("Isym") && e.expected == "an integer from 0 to 4", "{e}");
        let e = read_str(&small(4, 8).replacen("\n4\n8\n", "\n4\n6\n", 1)).unwrap_err();
        assert!(e.expected.contains("multiple of 4"), "{e}");
        let full = small(0, 4);
        let cut: String = full.lines().take(full.lines().count() - 2).map(|l| format!("{l}\n")).collect();
        let e = read_str(&cut).unwrap_err();
        assert_eq!(e.found, "the end of the file");
        assert!(e.field.contains("field 30"), "{e}");
        let e = read_str(&full.replace("\n140\n", "\n-140\n")).unwrap_err();
        assert!(e.field.contains("field 30") && e.field.contains("C90° γ45°"), "{e}");
        assert_eq!(e.found, "-140");
        // A lamp flux that makes the table's flux overflow: the table's first line (line 50 of
        // this file) and the fields that scale it (the fuzzer found it without a line).
        let huge = full.replacen("\nLED\n2000\n", "\nLED\n1e308\n", 1).replacen("\n80\n1.0\n", "\n80\n1e6\n", 1);
        assert_ne!(huge, full);
        let e = read_str(&huge).unwrap_err();
        assert_eq!(e.line, Some(50), "{e}");
        assert!(e.field.contains("field 30") && e.expected.contains("26c"), "{e}");
    }

    #[test]
    fn sniffing_recognises_the_layout() {
        assert!(sniff(&SourceText::decode(small(2, 4).as_bytes())));
        assert!(sniff(&SourceText::decode(format!("\n{}", small(2, 4)).as_bytes())));
        assert!(!sniff(&SourceText::decode(b"IESNA:LM-63-2002\n[TEST] x\nTILT=NONE\n")));
    }
}
