//! IES TM-33 (.xml) reader: TM-33-18 (root `<IESTM33>`) and TM-33-23 (root `<IESTM33-22>`).
//!
//! TM-33 is XML. The parts morgana reads, by element path (the same in both editions unless
//! said):
//!
//! - `Header/Manufacturer`, `Header/CatalogNumber`, `Header/Description` — maker, catalogue
//!   number, luminaire name.
//! - `Equipment/Gonioradiometer/Type` — `CIE_A`/`IES_A`, `CIE_B`/`IES_B`, `CIE_C`/`IES_C`
//!   (`CUSTOM` is refused); absent means type C. Types A and B use the LM-63 angle conventions
//!   of [`super::web`] whichever body names them.
//! - `Emitter` (one or more): `Quantity`, `Description`, `RatedLumens`, `InputWattage`,
//!   `BallastFactor`, `ColorTemperature/FixedCCT`, `ColorRendering` (`CIE_CRI/Ra` or `Ra`).
//! - `Emitter/LuminousData/LuminousIntensity`: `AbsolutePhotometry` (required in -18,
//!   optional in -23), `Symm` and `Multiplier` (-23 only), `NumberMeasured`, `NumberHorz`,
//!   `NumberVert`, and `IntData h="…" v="…"` elements, one per (horizontal, vertical) angle
//!   pair, in any order. For type C, h is the plane angle C and v the polar angle γ from the
//!   nadir; for types A and B, h and v are the LM-63 horizontal and vertical angles.
//!   `Emitter/LuminousData/LuminousFlux` is the flux the file states.
//! - `Emitter/SpectralData/EmitterSpectral`: `NumberWavelength`, `Multiplier` (-23), `Quantum`
//!   (-23) and `PwrData w="…"` (wavelength in nm): the emission spectrum
//!   ([`super::EmissionSpectrum`]).
//! - `Emitter/EmissionAreas/BottomFace/BottomArea` (`Length`, `Width`, `LengthOffset`,
//!   `WidthOffset`, `Circular`), in metres: one centred downward area becomes the luminous
//!   opening; anything else is noted and the light starts at the photometric centre.
//!
//! # How morgana reads them
//! - Intensity in cd = `IntData` × `Multiplier` (1 when absent). The IntData must fill the
//!   grid: exactly `NumberHorz` distinct h, `NumberVert` distinct v, each pair once, so
//!   NumberHorz × NumberVert values (`NumberMeasured` differing from that gets a note).
//! - Symmetry: TM-33-18 has no `Symm`; as in LM-63 the stored planes say it (type C: one plane —
//!   rotational; 0–90° — quadrant; 0–180° — about C0–C180; 90–270° or −90–90° — about
//!   C90–C270; 0° to beyond 180° — none). A TM-33-23 `Symm` (`Symm_None`, `Symm_Bi_0`,
//!   `Symm_Bi_90`, `Symm_Quad`, `Symm_Full`) must agree with the planes; `Symm_Arbitrary`
//!   leaves it to the planes, with a note.
//! - Relative photometry (`AbsolutePhotometry` false) is taken as in LM-63: the values are
//!   candela for the emitter's `RatedLumens`, which is reported as the lamp flux (the emitter's
//!   total; morgana does not multiply it by `Quantity`). A missing `AbsolutePhotometry` is
//!   read as relative when `RatedLumens` is given, else absolute, with a note.
//! - `BallastFactor` is reported, not applied (a note says so when it is not 1): TM-33 does
//!   not say whether writers fold it into the values; `flux_scale` applies one.
//! - Of several emitters with luminous intensity the first is used (a note names the others);
//!   of several `EmitterSpectral` the first. A spectrum in photon units (`Quantum` ≠ 0) is not
//!   converted: it is left out with a note. Radiant, photon, illuminance and angular colour
//!   data, tilt angles and custom data are not read.
//!
//! # References
//! - ANSI/IES TM-33-18, *Standard Format for the Electronic Transfer of Luminaire Optical
//!   Data* (IES, 2018), and ANSI/IES TM-33-23 (schema root `IESTM33-22`, version 1.1). Element
//!   names and nesting were taken from the schemas as extracted from the two standards in the
//!   public repository holg/eulumdat-rs (`docs/atla-s001-raw.xsd`, root `IESTM33`, and
//!   `docs/tm-33-23-extracted.xsd`, root `IESTM33-22`), and checked against DesignLights
//!   Consortium's public *TM-33 Required Elements (Horticultural)* example
//!   (`docs/TM33-DLC-Required_Elements_Hort_01032022.xml` in the same repository), which also
//!   states that TM-33 dimensions are in metres.
//! - I. Ashdown, "Rethinking the Photometric Data File Format", LED professional (2019).

use super::opening::Opening;
use super::planes::{type_c_symmetry, web_from_planes};
use super::symmetry::{Plane, Symmetry};
use super::xml::{self, child, child_number, child_text, children};
use super::{EmissionSpectrum, LampSet, ParseError, PhotometricType, Photometry};
use roxmltree::{Document, Node};
use std::path::Path;

pub const NAME: &str = "IES TM-33";
pub const EXTENSIONS: &[&str] = &["xml"];

/// Prefix of every field this reader names.
const W: &str = "TM-33";

/// An XML document whose root is `<IESTM33` or `<IESTM33-22` (within its first 64 KiB).
pub fn sniff(bytes: &[u8]) -> bool {
    let head = String::from_utf8_lossy(&bytes[..bytes.len().min(65_536)]);
    head.trim_start_matches('\u{feff}').trim_start().starts_with('<') && head.contains("<IESTM33")
}

/// The TM-33 edition, from the root element.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Edition {
    /// Root `<IESTM33>`.
    Tm33_18,
    /// Root `<IESTM33-22>`.
    Tm33_23,
}

impl Edition {
    fn of_root(name: &str) -> Option<Edition> {
        match name {
            "IESTM33" => Some(Edition::Tm33_18),
            "IESTM33-22" => Some(Edition::Tm33_23),
            _ => None,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Edition::Tm33_18 => "IES TM-33-18",
            Edition::Tm33_23 => "IES TM-33-23",
        }
    }
}

/// The file as written: what the reader takes from it, before any check across elements.
struct Raw {
    edition: Edition,
    manufacturer: String,
    catalogue: String,
    description: String,
    gonio_type: Option<(String, usize, String)>,
    emitters: Vec<RawEmitter>,
}

struct RawEmitter {
    quantity: Option<f64>,
    description: String,
    rated_lumens: Option<f64>,
    input_watts: Option<f64>,
    ballast_factor: Option<f64>,
    cct: String,
    ra: String,
    intensity: Option<RawIntensity>,
    luminous_flux: Option<f64>,
    spectra: Vec<RawSpectrum>,
    opening: RawOpening,
    other_data: Vec<&'static str>,
}

struct RawIntensity {
    line: usize,
    path: String,
    absolute: Option<bool>,
    symm: Option<(String, usize)>,
    multiplier: Option<f64>,
    number_measured: Option<i64>,
    nh: usize,
    nv: usize,
    values: Vec<IntValue>,
}

struct IntValue {
    h: f64,
    v: f64,
    cd: f64,
    line: usize,
}

struct RawSpectrum {
    line: usize,
    path: String,
    multiplier: f64,
    quantum: bool,
    samples: Vec<(f64, f64)>,
}

/// `EmissionAreas`: the single centred bottom area as (length, width, circular), if that is
/// all there is, else how many areas there are.
enum RawOpening {
    None,
    Bottom { length_m: f64, width_m: f64, circular: bool },
    Other(String),
}

pub fn read(bytes: &[u8], _path: &Path) -> Result<Photometry, ParseError> {
    let (text, encoding) = xml::decode(bytes, W)?;
    let doc = xml::parse(&text, W)?;
    let raw = raw(&doc)?;
    validate(raw, encoding)
}

fn raw(doc: &Document) -> Result<Raw, ParseError> {
    let root = doc.root_element();
    let edition = Edition::of_root(root.tag_name().name()).ok_or_else(|| {
        let hint =
            if root.tag_name().name() == "Root" { " (this looks like a GLDF product.xml: give the .gldf)" } else { "" };
        ParseError::new(
            xml::line(root),
            format!("{W} root element"),
            format!("<{}>{hint}", root.tag_name().name()),
            "<IESTM33> (TM-33-18) or <IESTM33-22> (TM-33-23)",
        )
    })?;
    let header = child(root, "Header");
    let head = |name: &str| header.and_then(|h| child_text(h, name)).unwrap_or_default();
    let gonio_type = child(root, "Equipment")
        .and_then(|e| child(e, "Gonioradiometer"))
        .and_then(|g| child(g, "Type"))
        .map(|t| (xml::text(t), xml::line(t), xml::path(t)));
    let mut emitters = Vec::new();
    for e in children(root, "Emitter") {
        emitters.push(raw_emitter(e)?);
    }
    if emitters.is_empty() {
        xml::require(root, "Emitter", W, "at least one <Emitter> with the luminous data")?;
    }
    Ok(Raw {
        edition,
        manufacturer: head("Manufacturer"),
        catalogue: head("CatalogNumber"),
        description: head("Description"),
        gonio_type,
        emitters,
    })
}

fn raw_emitter(e: Node) -> Result<RawEmitter, ParseError> {
    let ra = child(e, "ColorRendering")
        .and_then(|c| child(c, "CIE_CRI").and_then(|k| child_text(k, "Ra")).or_else(|| child_text(c, "Ra")))
        .map_or(String::new(), |r| format!("Ra {r}"));
    let cct = child(e, "ColorTemperature")
        .and_then(|c| child_text(c, "FixedCCT"))
        .map_or(String::new(), |t| format!("{t} K"));
    let luminous = child(e, "LuminousData");
    let intensity = luminous.and_then(|l| child(l, "LuminousIntensity")).map(raw_intensity).transpose()?;
    let luminous_flux = luminous.map(|l| child_number(l, "LuminousFlux", W, 0.0, f64::INFINITY)).transpose()?.flatten();
    let mut spectra = Vec::new();
    if let Some(sd) = child(e, "SpectralData") {
        for s in children(sd, "EmitterSpectral") {
            spectra.push(raw_spectrum(s)?);
        }
    }
    let other_data = ["RadiantData", "PhotonData", "IllumData", "IrradData", "AngularColor"]
        .into_iter()
        .filter(|n| child(e, n).is_some())
        .collect();
    Ok(RawEmitter {
        quantity: child_number(e, "Quantity", W, f64::NEG_INFINITY, f64::INFINITY)?,
        description: child_text(e, "Description").unwrap_or_default(),
        rated_lumens: child_number(e, "RatedLumens", W, 0.0, f64::INFINITY)?,
        input_watts: child_number(e, "InputWattage", W, 0.0, f64::INFINITY)?,
        ballast_factor: child_number(e, "BallastFactor", W, 0.0, f64::INFINITY)?,
        cct,
        ra,
        intensity,
        luminous_flux,
        spectra,
        opening: raw_opening(e)?,
        other_data,
    })
}

fn raw_intensity(n: Node) -> Result<RawIntensity, ParseError> {
    let count = |name: &str, lo: i64, what: &str| -> Result<usize, ParseError> {
        let c = xml::require(n, name, W, what)?;
        Ok(xml::integer(c, W, lo, 3601)? as usize)
    };
    let nh = count("NumberHorz", 1, "the number of horizontal angles (planes), 1 to 3601")?;
    let nv = count("NumberVert", 2, "the number of vertical angles, 2 to 3601")?;
    let multiplier =
        child(n, "Multiplier").map(|m| xml::number(m, W, f64::MIN_POSITIVE, super::MAX_MULTIPLIER)).transpose()?;
    let mut values = Vec::with_capacity((nh * nv).min(1 << 20));
    for d in children(n, "IntData") {
        values.push(IntValue {
            h: xml::attr_number(d, "h", W, -180.0, 360.0)?,
            v: xml::attr_number(d, "v", W, -90.0, 180.0)?,
            cd: xml::number(d, W, 0.0, super::MAX_TABLE_VALUE)?,
            line: xml::line(d),
        });
    }
    Ok(RawIntensity {
        line: xml::line(n),
        path: xml::path(n),
        absolute: child(n, "AbsolutePhotometry").map(|a| xml::boolean(a, W)).transpose()?,
        symm: child(n, "Symm").map(|s| (xml::text(s), xml::line(s))),
        multiplier,
        number_measured: child(n, "NumberMeasured").map(|m| xml::integer(m, W, 0, i64::MAX)).transpose()?,
        nh,
        nv,
        values,
    })
}

fn raw_spectrum(s: Node) -> Result<RawSpectrum, ParseError> {
    let number = xml::integer(xml::require(s, "NumberWavelength", W, "the number of PwrData values")?, W, 2, 100_000)?;
    let multiplier =
        child(s, "Multiplier").map(|m| xml::number(m, W, 0.0, super::MAX_MULTIPLIER)).transpose()?.unwrap_or(1.0);
    let quantum =
        child(s, "Quantum").map(|q| xml::number(q, W, 0.0, f64::INFINITY)).transpose()?.is_some_and(|q| q != 0.0);
    let mut samples = Vec::new();
    for p in children(s, "PwrData") {
        samples.push((xml::attr_number(p, "w", W, 0.0, f64::INFINITY)?, xml::number(p, W, 0.0, f64::INFINITY)?));
    }
    if samples.len() != number as usize {
        return Err(ParseError::new(
            xml::line(s),
            format!("{W} {}/PwrData", xml::path(s)),
            format!("{} PwrData values", samples.len()),
            format!("NumberWavelength = {number} values"),
        ));
    }
    Ok(RawSpectrum { line: xml::line(s), path: xml::path(s), multiplier, quantum, samples })
}

fn raw_opening(e: Node) -> Result<RawOpening, ParseError> {
    let Some(areas) = child(e, "EmissionAreas") else {
        return Ok(RawOpening::None);
    };
    let faces: Vec<Node> = areas.children().filter(Node::is_element).collect();
    let bottom: Vec<Node> = child(areas, "BottomFace").map(|b| children(b, "BottomArea").collect()).unwrap_or_default();
    if faces.len() != 1 || bottom.len() != 1 {
        let names: Vec<&str> = faces.iter().map(|f| f.tag_name().name()).collect();
        return Ok(RawOpening::Other(format!("{} ({} bottom areas)", names.join(", "), bottom.len())));
    }
    let a = bottom[0];
    let num = |name: &str| -> Result<f64, ParseError> {
        xml::number(xml::require(a, name, W, "a length in metres")?, W, -super::MAX_OPENING, super::MAX_OPENING)
    };
    let (length_m, width_m) = (num("Length")?, num("Width")?);
    let offsets = child_number(a, "LengthOffset", W, f64::NEG_INFINITY, f64::INFINITY)?.unwrap_or(0.0).abs()
        + child_number(a, "WidthOffset", W, f64::NEG_INFINITY, f64::INFINITY)?.unwrap_or(0.0).abs();
    if offsets > 0.0 || length_m < 0.0 || width_m < 0.0 {
        return Ok(RawOpening::Other("a BottomArea off the centre".into()));
    }
    let circular = child(a, "Circular").map(|c| xml::boolean(c, W)).transpose()?.unwrap_or(false);
    Ok(RawOpening::Bottom { length_m, width_m, circular })
}

fn validate(raw: Raw, encoding: &'static str) -> Result<Photometry, ParseError> {
    let mut notes = Vec::new();
    let ptype = photometric_type(&raw)?;
    let with_intensity: Vec<usize> = (0..raw.emitters.len()).filter(|i| raw.emitters[*i].intensity.is_some()).collect();
    let Some(&k) = with_intensity.first() else {
        let other: Vec<&str> = raw.emitters.iter().flat_map(|e| e.other_data.iter().copied()).collect();
        let found = if other.is_empty() {
            "no Emitter with LuminousData/LuminousIntensity".to_string()
        } else {
            format!("no Emitter with LuminousData/LuminousIntensity (the file has {})", other.join(", "))
        };
        return Err(ParseError::whole_file(
            format!("{W} Emitter/LuminousData/LuminousIntensity"),
            found,
            "luminous intensity data: morgana reads luminous photometry",
        ));
    };
    if with_intensity.len() > 1 {
        notes.push(format!(
            "{} emitters carry luminous intensity; morgana uses the first (emitter {}, \"{}\")",
            with_intensity.len(),
            k + 1,
            raw.emitters[k].description
        ));
    }
    let e = &raw.emitters[k];
    let Some(intensity) = &e.intensity else {
        return Err(ParseError::whole_file(format!("{W} Emitter/LuminousData"), "nothing", "luminous intensity"));
    };
    let (symmetry, web) = intensity_web(intensity, ptype, &mut notes)?;
    let absolute = match intensity.absolute {
        Some(a) => a,
        None => {
            let a = e.rated_lumens.is_none();
            let how = if a { "absolute (no RatedLumens)" } else { "relative to RatedLumens" };
            notes.push(format!("no AbsolutePhotometry element; the intensities are read as {how}"));
            a
        }
    };
    if !absolute && e.rated_lumens.is_none() {
        notes.push("relative photometry without RatedLumens: the lamp flux is not known".to_string());
    }
    if let Some(b) = e.ballast_factor.filter(|b| (*b - 1.0).abs() > 1e-12) {
        notes.push(format!("BallastFactor {b} is not applied to the intensities (use flux_scale to apply it)"));
    }
    if let Some(m) = intensity.number_measured.filter(|m| *m as usize != intensity.values.len()) {
        notes.push(format!("NumberMeasured is {m} but the file has {} IntData values", intensity.values.len()));
    }
    if !e.other_data.is_empty() {
        notes.push(format!("{} not read (morgana reads luminous intensity)", e.other_data.join(", ")));
    }
    let spectrum = emitter_spectrum(e, k, &mut notes)?;
    let opening = match &e.opening {
        RawOpening::None => Opening::POINT,
        RawOpening::Bottom { length_m, width_m, circular } => {
            let sign = if *circular { -1.0 } else { 1.0 };
            let width = if *circular && *width_m == 0.0 { *length_m } else { *width_m };
            let (o, note) = Opening::from_lm63(sign * width, sign * length_m, 0.0);
            notes.extend(note);
            o
        }
        RawOpening::Other(what) => {
            notes.push(format!("EmissionAreas {what} are not modelled; the luminous opening is a point"));
            Opening::POINT
        }
    };
    let lamp_flux = if absolute { None } else { e.rated_lumens };
    let count = match e.quantity {
        Some(q) if q.fract() == 0.0 && (1.0..=1e6).contains(&q) => q as i64,
        Some(q) => {
            notes.push(format!("Quantity {q} is not a count of emitters; read as 1"));
            1
        }
        None => 1,
    };
    let lamp = LampSet {
        count,
        description: e.description.clone(),
        flux_lm: lamp_flux,
        colour_temperature: e.cct.clone(),
        colour_rendering: e.ra.clone(),
        watts: e.input_watts,
    };
    let luminaire = if raw.description.is_empty() { e.description.clone() } else { raw.description.clone() };
    Ok(Photometry {
        format: raw.edition.name().to_string(),
        encoding,
        manufacturer: raw.manufacturer,
        luminaire,
        catalogue: raw.catalogue,
        lamps: vec![lamp],
        lamp_flux_lm: lamp_flux,
        stated_flux_lm: e.luminous_flux,
        absolute,
        photometric_type: ptype,
        symmetry,
        stored_grid: (intensity.nh, intensity.nv),
        opening,
        input_watts: e.input_watts,
        tilt: None,
        dff_percent: None,
        lorl_percent: None,
        measurement_tilt_deg: None,
        web,
        notes,
        spectrum,
    })
}

fn photometric_type(raw: &Raw) -> Result<PhotometricType, ParseError> {
    let Some((t, line, path)) = &raw.gonio_type else {
        return Ok(PhotometricType::C);
    };
    let norm: String = t.chars().filter(|c| !c.is_whitespace()).collect::<String>().to_ascii_uppercase();
    match norm.as_str() {
        "CIE_A" | "IES_A" => Ok(PhotometricType::A),
        "CIE_B" | "IES_B" => Ok(PhotometricType::B),
        "CIE_C" | "IES_C" => Ok(PhotometricType::C),
        _ => Err(ParseError::new(
            *line,
            format!("{W} {path}"),
            format!("\"{}\"", xml::truncate(t, 40)),
            "CIE_A, CIE_B, CIE_C, IES_A, IES_B or IES_C (morgana cannot read CUSTOM angles)",
        )),
    }
}

/// The grid of IntData as planes, its symmetry and the web.
fn intensity_web(
    r: &RawIntensity,
    ptype: PhotometricType,
    notes: &mut Vec<String>,
) -> Result<(Symmetry, super::PhotometricWeb), ParseError> {
    let data_field = format!("{W} {}/IntData", r.path);
    if r.values.len() != r.nh * r.nv {
        return Err(ParseError::new(
            r.line,
            data_field,
            format!("{} IntData values", r.values.len()),
            format!("NumberHorz × NumberVert = {} × {} = {} values", r.nh, r.nv, r.nh * r.nv),
        ));
    }
    let hs = distinct(r.values.iter().map(|d| d.h));
    let vs = distinct(r.values.iter().map(|d| d.v));
    for (angles, n, name, which) in [(&hs, r.nh, "NumberHorz", "h"), (&vs, r.nv, "NumberVert", "v")] {
        if angles.len() != n {
            return Err(ParseError::new(
                r.line,
                format!("{W} {}/{name}", r.path),
                n.to_string(),
                format!("the number of distinct {which} angles in the IntData, {}", angles.len()),
            ));
        }
    }
    let (vlo, vhi) = if ptype == PhotometricType::C { (0.0, 180.0) } else { (-90.0, 90.0) };
    if let Some(d) = r.values.iter().find(|d| d.v < vlo || d.v > vhi) {
        return Err(ParseError::new(
            d.line,
            format!("{data_field} attribute v"),
            d.v.to_string(),
            format!("an angle from {vlo} to {vhi}°"),
        ));
    }
    let mut grid: Vec<Option<f64>> = vec![None; r.nh * r.nv];
    for d in &r.values {
        // `+ 0.0` makes −0 equal 0, as in `distinct` (total_cmp orders them apart; the fuzzer
        // wrote "-0.0").
        let find = |grid: &[f64], a: f64| grid.binary_search_by(|x| x.total_cmp(&(a + 0.0)));
        let (Ok(i), Ok(j)) = (find(&hs, d.h), find(&vs, d.v)) else {
            return Err(ParseError::new(
                d.line,
                &data_field,
                format!("the angle pair ({}°, {}°), not in the grid", d.h, d.v),
                "a full grid",
            ));
        };
        if grid[i * r.nv + j].replace(d.cd).is_some() {
            return Err(ParseError::new(
                d.line,
                &data_field,
                format!("h = {}°, v = {}° a second time", d.h, d.v),
                "each (h, v) pair once",
            ));
        }
    }
    let planes: Vec<Plane> = hs
        .iter()
        .enumerate()
        .map(|(i, h)| (*h, (0..r.nv).map(|j| grid[i * r.nv + j].unwrap_or(0.0)).collect()))
        .collect();
    let symmetry = symmetry_of(r, ptype, &hs, notes)?;
    let web = web_from_planes(ptype, symmetry, planes, vs, r.multiplier.unwrap_or(1.0), &data_field, notes)?;
    Ok((symmetry, web))
}

fn distinct(xs: impl Iterator<Item = f64>) -> Vec<f64> {
    let mut v: Vec<f64> = xs.map(|x| x + 0.0).collect();
    v.sort_by(f64::total_cmp);
    v.dedup();
    v
}

/// The symmetry the planes imply, checked against a TM-33-23 `Symm`.
fn symmetry_of(
    r: &RawIntensity,
    ptype: PhotometricType,
    hs: &[f64],
    notes: &mut Vec<String>,
) -> Result<Symmetry, ParseError> {
    let implied = match ptype {
        PhotometricType::C => type_c_symmetry(hs).map_err(|found| {
            ParseError::new(
                r.line,
                format!("{W} {}/IntData horizontal angles (type C)", r.path),
                found,
                "one plane (rotational), 0–90°, 0–180°, 90–270° or −90–90°, or 0° to beyond 180°",
            )
        })?,
        _ if hs[0] >= 0.0 => Symmetry::Lateral,
        _ => Symmetry::None,
    };
    let Some((text, line)) = &r.symm else {
        return Ok(implied);
    };
    let norm: String = text.chars().filter(|c| !c.is_whitespace()).collect::<String>().to_ascii_uppercase();
    let declared = match norm.as_str() {
        "SYMM_NONE" => Symmetry::None,
        "SYMM_BI_0" => Symmetry::C0C180,
        "SYMM_BI_90" => Symmetry::C90C270,
        "SYMM_QUAD" => Symmetry::Quadrant,
        "SYMM_FULL" => Symmetry::Rotational,
        "SYMM_ARBITRARY" => {
            notes.push(format!("Symm_Arbitrary: the symmetry is taken from the planes ({implied})"));
            return Ok(implied);
        }
        _ => {
            return Err(ParseError::new(
                *line,
                format!("{W} {}/Symm", r.path),
                format!("\"{}\"", xml::truncate(text, 40)),
                "Symm_None, Symm_Bi_0, Symm_Bi_90, Symm_Quad, Symm_Full or Symm_Arbitrary",
            ));
        }
    };
    if ptype != PhotometricType::C {
        notes.push(format!("Symm {text} with type {ptype:?} angles: the horizontal angles decide ({implied})"));
        return Ok(implied);
    }
    if declared != implied {
        return Err(ParseError::new(
            *line,
            format!("{W} {}/Symm", r.path),
            format!("{text}, but the planes run {}–{}° ({implied})", hs[0], hs[hs.len() - 1]),
            format!("planes that match it ({})", planes_for(declared)),
        ));
    }
    Ok(declared)
}

fn planes_for(s: Symmetry) -> &'static str {
    match s {
        Symmetry::None => "0° to beyond 180°",
        Symmetry::C0C180 => "0–180°",
        Symmetry::C90C270 => "90–270° or −90–90°",
        Symmetry::Quadrant => "0–90°",
        Symmetry::Rotational => "a single plane",
        Symmetry::Lateral => "0–90° (types A, B)",
    }
}

/// The first `EmitterSpectral` of the emitter, as an emission spectrum.
fn emitter_spectrum(e: &RawEmitter, k: usize, notes: &mut Vec<String>) -> Result<Option<EmissionSpectrum>, ParseError> {
    let Some(s) = e.spectra.first() else {
        return Ok(None);
    };
    if e.spectra.len() > 1 {
        notes.push(format!("{} EmitterSpectral elements; the first is the emission spectrum", e.spectra.len()));
    }
    if s.quantum {
        notes.push("the EmitterSpectral is in photon units (Quantum); morgana does not convert it, so the file gives no emission spectrum".into());
        return Ok(None);
    }
    let samples = s.samples.iter().map(|(w, v)| (*w, v * s.multiplier)).collect();
    EmissionSpectrum::new(samples, format!("TM-33 Emitter {}, EmitterSpectral 1", k + 1)).map(Some).map_err(|why| {
        ParseError::new(s.line, format!("{W} {}/PwrData", s.path), why, "a relative spectral power distribution")
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A TM-33-23 file: type C, planes `h`, polar angles 0, 45, 90, I = 100 + v + h v / 90.
    fn tm33_23(h: &[f64], symm: &str, extra: &str) -> String {
        let mut s = String::from(
            "<?xml version=\"1.0\"?>\n<IESTM33-22>\n<Version>1.1</Version>\n<Header><Manufacturer>ACME</Manufacturer>",
        );
        s +=
            "<Description>Test</Description></Header>\n<Emitter>\n<Quantity>1</Quantity><Description>LED</Description>";
        s += &format!("<InputWattage>10</InputWattage>{extra}\n<LuminousData><LuminousIntensity>\n");
        s += &format!("<AbsolutePhotometry>true</AbsolutePhotometry>{symm}<Multiplier>2</Multiplier>\n");
        s += &format!(
            "<NumberMeasured>{}</NumberMeasured><NumberHorz>{}</NumberHorz><NumberVert>3</NumberVert>\n",
            3 * h.len(),
            h.len()
        );
        for hi in h {
            for v in [0.0, 45.0, 90.0] {
                s += &format!("<IntData h=\"{hi}\" v=\"{v}\">{}</IntData>\n", 100.0 + v + hi * v / 90.0);
            }
        }
        s + "</LuminousIntensity><LuminousFlux>123</LuminousFlux></LuminousData>\n</Emitter>\n</IESTM33-22>\n"
    }

    fn read_str(s: &str) -> Result<Photometry, ParseError> {
        read(s.as_bytes(), Path::new("t.xml"))
    }

    #[test]
    fn reads_a_quadrant_symmetric_tm33_23_file() {
        let p = read_str(&tm33_23(&[0.0, 45.0, 90.0], "<Symm>Symm_Quad</Symm>", "")).unwrap();
        assert_eq!(p.format, "IES TM-33-23");
        assert_eq!((p.manufacturer.as_str(), p.luminaire.as_str()), ("ACME", "Test"));
        assert_eq!(p.symmetry, Symmetry::Quadrant);
        assert_eq!(p.stored_grid, (3, 3));
        assert!(p.absolute);
        assert_eq!(p.stated_flux_lm, Some(123.0));
        // Multiplier 2: C45 γ45 is 2 × 167.5; C135 mirrors C45.
        assert_eq!(p.web.intensity_at(45.0, 45.0), 335.0);
        assert_eq!(p.web.intensity_at(135.0, 45.0), 335.0);
        assert!(p.notes.is_empty(), "{:?}", p.notes);
    }

    #[test]
    fn intdata_may_come_in_any_order() {
        let a = read_str(&tm33_23(&[0.0, 90.0, 180.0], "", "")).unwrap();
        let text = tm33_23(&[0.0, 90.0, 180.0], "", "");
        let mut lines: Vec<&str> = text.lines().collect();
        let first = lines.iter().position(|l| l.starts_with("<IntData")).unwrap();
        lines[first..first + 9].reverse();
        let b = read_str(&lines.join("\n")).unwrap();
        assert_eq!(a.web, b.web);
        assert_eq!(b.symmetry, Symmetry::C0C180);
    }

    #[test]
    fn symm_must_agree_with_the_planes() {
        let e = read_str(&tm33_23(&[0.0, 90.0, 180.0], "<Symm>Symm_Quad</Symm>", "")).unwrap_err();
        assert!(e.field.ends_with("LuminousIntensity/Symm") && e.expected.contains("0–90°"), "{e}");
        let e = read_str(&tm33_23(&[0.0, 90.0], "<Symm>Symm_Sideways</Symm>", "")).unwrap_err();
        assert!(e.expected.contains("Symm_Bi_90"), "{e}");
        let p = read_str(&tm33_23(&[0.0, 90.0], "<Symm>Symm _ Arbitrary</Symm>", "")).unwrap();
        assert_eq!(p.symmetry, Symmetry::Quadrant);
        assert_eq!(p.notes.len(), 1);
    }

    #[test]
    fn an_opening_of_1e308_metres_is_refused() {
        // The fuzzer: a BottomArea Length of 1e308 m printed as "600 × inf mm".
        let area = "<EmissionAreas><BottomFace><NumberBottom>1</NumberBottom><BottomArea><Length>LEN</Length>\
                    <Width>0.3</Width></BottomArea></BottomFace></EmissionAreas>";
        read_str(&tm33_23(&[0.0], "", &area.replace("LEN", "0.6"))).unwrap();
        let e = read_str(&tm33_23(&[0.0], "", &area.replace("LEN", "1e308"))).unwrap_err();
        assert!(e.field.contains("Length") && e.expected.contains("10000"), "{e}");
        assert!(e.line.is_some(), "{e}");
    }

    #[test]
    fn minus_zero_is_the_angle_zero() {
        // The fuzzer's luminaire target: v="-0.0" in one IntData was "an angle not in the grid"
        // (total_cmp orders −0 before 0), a refusal without a line. (Every pair of distinct
        // angles is now on the grid, so that refusal is left for NaN angles, with their line.)
        let good = tm33_23(&[0.0, 90.0], "", "");
        let minus = good.replacen("<IntData h=\"90\" v=\"0\">", "<IntData h=\"90\" v=\"-0.0\">", 1);
        assert_ne!(minus, good);
        assert_eq!(read_str(&minus).unwrap().web, read_str(&good).unwrap().web);
    }

    #[test]
    fn errors_name_the_element_and_line() {
        let good = tm33_23(&[0.0, 90.0], "", "");
        let e = read_str(&good.replace("<NumberHorz>2</NumberHorz>", "")).unwrap_err();
        assert_eq!(
            e.to_string(),
            "7: TM-33 IESTM33-22/Emitter/LuminousData/LuminousIntensity/NumberHorz: found no <NumberHorz> in <LuminousIntensity>, expected the number of horizontal angles (planes), 1 to 3601"
        );
        let e = read_str(&good.replace("<IntData h=\"90\" v=\"45\">190</IntData>\n", "")).unwrap_err();
        assert_eq!(
            (e.found.as_str(), e.expected.as_str()),
            ("5 IntData values", "NumberHorz × NumberVert = 2 × 3 = 6 values")
        );
        let e = read_str(&good.replace(">280<", ">2x0<")).unwrap_err();
        assert_eq!((e.line, e.found.as_str()), (Some(15), "\"2x0\""));
        let e = read_str(&good.replace("v=\"45\">190", "v=\"0\">190")).unwrap_err();
        assert!(e.found.contains("a second time") || e.field.contains("NumberVert"), "{e}");
        let e = read_str(&good.replace("</LuminousIntensity>", "")).unwrap_err();
        assert!(e.field.starts_with("TM-33 XML"), "{e}");
        let e = read_str("<IESTM33><Header/></IESTM33>").unwrap_err();
        assert!(e.field.ends_with("IESTM33/Emitter"), "{e}");
        let e = read_str("<Root/>").unwrap_err();
        assert!(e.found.contains("GLDF"), "{e}");
        let e = read_str(&good.replace(
            "<Header>",
            "<Equipment><Gonioradiometer><Type>CUSTOM</Type></Gonioradiometer></Equipment><Header>",
        ))
        .unwrap_err();
        assert!(e.expected.contains("CUSTOM"), "{e}");
    }

    #[test]
    fn a_spectrum_and_an_opening() {
        let extra = "<SpectralData><EmitterSpectral><NumberWavelength>3</NumberWavelength><Multiplier>4</Multiplier>\
                     <PwrData w=\"500\">0.5</PwrData><PwrData w=\"400\">0.25</PwrData><PwrData w=\"600\">0.125</PwrData>\
                     </EmitterSpectral></SpectralData><EmissionAreas><BottomFace><NumberBottom>1</NumberBottom><BottomArea>\
                     <Length>0.2</Length><Width>0.1</Width><LengthOffset>0</LengthOffset><WidthOffset>0</WidthOffset>\
                     </BottomArea></BottomFace></EmissionAreas>";
        let p = read_str(&tm33_23(&[0.0], "", extra)).unwrap();
        let s = p.spectrum.unwrap();
        assert_eq!(s.samples(), (&[400.0, 500.0, 600.0][..], &[0.5, 1.0, 0.25][..]));
        assert_eq!(p.opening, Opening::from_lm63(0.1, 0.2, 0.0).0);
        let bad = extra.replace("<NumberWavelength>3", "<NumberWavelength>4");
        let e = read_str(&tm33_23(&[0.0], "", &bad)).unwrap_err();
        assert_eq!((e.found.as_str(), e.expected.as_str()), ("3 PwrData values", "NumberWavelength = 4 values"));
    }

    #[test]
    fn sniffing() {
        assert!(sniff(b"<?xml version=\"1.0\"?>\n<!-- x -->\n<IESTM33-22>"));
        assert!(sniff(b"\xEF\xBB\xBF<IESTM33>"));
        assert!(!sniff(b"<Root/>"));
        assert!(!sniff(b"IESNA:LM-63-2002\n<IESTM33"));
    }
}
