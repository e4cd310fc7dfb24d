//! GLDF (.gldf) reader: the Global Lighting Data Format container.
//!
//! A GLDF file is a zip archive with `product.xml` at its root and its assets in folders named
//! after the first part of their content type: photometry in `ldc/` (`ldc/eulumdat`,
//! `ldc/ies`), spectra in `spectrum/` (`spectrum/text`), images, geometry and documents
//! elsewhere. `product.xml` (root `<Root>`) defines building blocks under
//! `GeneralDefinitions` and puts them together under `ProductDefinitions/Variants`. morgana
//! follows one chain:
//!
//! `Variant` (by `id`) → its `EmitterReference`/`SimpleGeometryReference` `emitterId` →
//! `Emitter` → its first `ChangeableLightEmitter`, `FixedLightEmitter` (GLDF 1.0) or
//! `LightEmitter` (0.9) → `PhotometryReference photometryId` → `Photometry` →
//! `PhotometryFileReference fileId` → `File` (`type="localFileName"`, content type `ldc/…`) →
//! the zip entry `ldc/<name>`, read by morgana's EULUMDAT, IES LM-63 (or, by content, TM-33)
//! reader.
//!
//! The spectrum: the light emitter's `LightSourceReference` (`fixedLightSourceId`,
//! `changeableLightSourceId`), or that of the `Equipment` it references (`EquipmentReference
//! equipmentId`) → the light source's `SpectrumReference spectrumId` → `Spectrum`, either
//! inline (`Intensity wavelength="…"`) or `SpectrumFileReference` to a `spectrum/text` entry of
//! "wavelength intensity" lines. Normalised as [`super::EmissionSpectrum`] says.
//!
//! # Choices
//! - The variant: the first unless one is named (`variant = "…"` in a scene, `--variant` on the
//!   command line); a name not in the file is an error listing the ids.
//! - Of several light emitters in a variant, or several modes of one emitter (emergency
//!   modes, alternative lamps, which GLDF says are interchangeable), the first; a note says so.
//! - Files of `type="url"` are not fetched: a photometry URL is an error, a spectrum URL a note.
//! - Entry names are case-sensitive as the specification says; an entry found only by a
//!   case-insensitive match or in another folder is used with a note.
//!
//! # Limits
//! Each entry is read up to [`MAX_ENTRY_BYTES`] uncompressed, whatever its header claims, so a
//! zip bomb costs at most that much memory; only stored and deflated entries are read.
//!
//! # References
//! - GLDF container specification and XML structure (Files, Photometries, Spectrums,
//!   LightSources, Equipments, Emitters, Variant), gldf.io documentation, public repository
//!   globallightingdata/website (`docs/container/container-specification.md`,
//!   `docs/structure/*.md`); element names checked against the test data of
//!   globallightingdata/gldf.net (`src/Gldf.Net.Tests/TestData/`, GLDF 0.9 and 1.0-rc.3).

use super::format::Format;
use super::xml::{self, child, children};
use super::{EmissionSpectrum, ParseError, Photometry};
use roxmltree::{Document, Node};
use std::io::{Cursor, Read};
use std::path::{Path, PathBuf};
use zip::ZipArchive;

pub const NAME: &str = "GLDF";
pub const EXTENSIONS: &[&str] = &["gldf"];

/// The most bytes read from one zip entry (uncompressed).
pub const MAX_ENTRY_BYTES: u64 = 64 << 20;

/// Prefix of every field this reader names.
const W: &str = "GLDF";

/// A zip archive (local file header or empty-archive signature).
pub fn sniff(bytes: &[u8]) -> bool {
    bytes.starts_with(b"PK\x03\x04") || bytes.starts_with(b"PK\x05\x06")
}

/// Reads the container at `path` (its bytes), choosing `variant` or the first.
pub fn read(bytes: &[u8], path: &Path, variant: Option<&str>) -> Result<Photometry, ParseError> {
    let mut zip = Container::open(bytes)?;
    let product = zip.entry("product.xml")?;
    let (text, _) = xml::decode(&product.bytes, "GLDF product.xml")?;
    let doc = xml::parse(&text, "GLDF product.xml").map_err(|e| e.in_file(&inner_path(path, "product.xml")))?;
    let raw = raw(&doc).map_err(|e| e.in_file(&inner_path(path, "product.xml")))?;
    let mut notes: Vec<String> = product.note.into_iter().collect();
    let choice = choose(&raw, variant, &mut notes).map_err(|e| e.in_file(&inner_path(path, "product.xml")))?;
    let file = choice.photometry;
    let entry = zip.entry(&file.entry_name())?;
    notes.extend(entry.note);
    let inner = inner_path(path, &entry.name);
    let format = inner_format(file, &entry.bytes).ok_or_else(|| {
        ParseError::new(
            file.line,
            format!("{W} {} id=\"{}\"", file.path, file.id),
            format!("content type \"{}\" (entry {})", file.content_type, entry.name),
            "a photometry file morgana reads: ldc/eulumdat, ldc/ies (or an IES TM-33 XML file)",
        )
        .in_file(&inner_path(path, "product.xml"))
    })?;
    let mut p = format.read(&entry.bytes, &inner, None).map_err(|e| e.in_file(&inner))?;
    let spectrum = match &choice.spectrum {
        Some(s) => spectrum(s, &raw, &mut zip, path, &mut notes)?,
        None => None,
    };
    let inner_format = std::mem::take(&mut p.format);
    p.format = format!("GLDF{} (variant \"{}\": {inner_format}, {})", raw.version, choice.variant_id, entry.name);
    if p.manufacturer.is_empty() {
        p.manufacturer = raw.manufacturer.clone();
    }
    if !raw.product_name.is_empty() {
        p.luminaire = match choice.variant_name.as_str() {
            "" => raw.product_name.clone(),
            v if v == raw.product_name => raw.product_name.clone(),
            v => format!("{}, {v}", raw.product_name),
        };
    }
    if !raw.product_number.is_empty() {
        p.catalogue = raw.product_number.clone();
    }
    if spectrum.is_some() {
        p.spectrum = spectrum;
    }
    notes.append(&mut p.notes);
    p.notes = notes;
    Ok(p)
}

/// `x.gldf!/ldc/a.ldt`: how errors name a file inside the container.
fn inner_path(path: &Path, entry: &str) -> PathBuf {
    PathBuf::from(format!("{}!/{entry}", path.display()))
}

/// The reader for a photometry entry: by content type, else by its name and content.
fn inner_format(file: &RawFile, bytes: &[u8]) -> Option<Format> {
    match file.content_type.to_ascii_lowercase().as_str() {
        "ldc/eulumdat" | "ldc/ldt" | "ldc/eulum" => Some(Format::Eulumdat),
        "ldc/ies" => Some(Format::Lm63),
        _ => {
            Format::by_extension(Path::new(&file.name)).or_else(|| Format::sniff(bytes)).filter(|f| *f != Format::Gldf)
        }
    }
}

/// The zip archive and the entries read from it.
struct Container<'a> {
    archive: ZipArchive<Cursor<&'a [u8]>>,
}

/// An entry's bytes, its name in the archive, and a note when it was found only loosely.
struct Entry {
    name: String,
    bytes: Vec<u8>,
    note: Option<String>,
}

impl<'a> Container<'a> {
    fn open(bytes: &'a [u8]) -> Result<Container<'a>, ParseError> {
        let archive = ZipArchive::new(Cursor::new(bytes)).map_err(|e| {
            ParseError::whole_file(
                format!("{W} container"),
                format!("a damaged or incomplete zip archive ({e})"),
                "a complete zip archive with product.xml at its root",
            )
        })?;
        Ok(Container { archive })
    }

    fn names(&self) -> Vec<String> {
        self.archive.file_names().filter_map(|n| n.ok()).map(|n| n.into_owned()).collect()
    }

    /// The entry `name`; else one whose name matches ignoring case or folder (with a note).
    fn entry(&mut self, name: &str) -> Result<Entry, ParseError> {
        let names = self.names();
        let file_part = |n: &str| n.rsplit(['/', '\\']).next().unwrap_or(n).to_string();
        let (found, note) = if names.iter().any(|n| n == name) {
            (name.to_string(), None)
        } else if let Some(n) = names.iter().find(|n| n.replace('\\', "/").eq_ignore_ascii_case(name)) {
            (n.clone(), Some(format!("entry {name} is stored as {n} (names are case-sensitive in GLDF)")))
        } else if let Some(n) = names.iter().find(|n| !n.ends_with('/') && file_part(n) == file_part(name)) {
            (n.clone(), Some(format!("entry {name} is stored as {n} (GLDF puts it in the folder of its content type)")))
        } else {
            let shown: Vec<&str> = names.iter().take(12).map(String::as_str).collect();
            let more = if names.len() > 12 { format!(", … ({} entries)", names.len()) } else { String::new() };
            return Err(ParseError::whole_file(
                format!("{W} container entry {name}"),
                format!("no such entry (the archive has: {}{more})", shown.join(", ")),
                if name == "product.xml" {
                    "product.xml at the root of the archive"
                } else {
                    "the file product.xml names"
                },
            ));
        };
        let bytes = self.read(&found)?;
        Ok(Entry { name: found, bytes, note })
    }

    fn read(&mut self, name: &str) -> Result<Vec<u8>, ParseError> {
        let field = format!("{W} container entry {name}");
        let too_big = |n: u64| {
            ParseError::whole_file(
                &field,
                format!("{n} bytes uncompressed"),
                format!("at most {} MiB (morgana's limit for one entry)", MAX_ENTRY_BYTES >> 20),
            )
        };
        let unreadable = |e: &dyn std::fmt::Display| {
            ParseError::whole_file(
                &field,
                format!("an entry that cannot be read ({e})"),
                "a stored or deflated entry intact",
            )
        };
        let file = self.archive.by_name(name).map_err(|e| unreadable(&e))?;
        if file.size() > MAX_ENTRY_BYTES {
            return Err(too_big(file.size()));
        }
        let mut bytes = Vec::with_capacity(file.size() as usize);
        file.take(MAX_ENTRY_BYTES + 1).read_to_end(&mut bytes).map_err(|e| unreadable(&e))?;
        if bytes.len() as u64 > MAX_ENTRY_BYTES {
            return Err(too_big(bytes.len() as u64));
        }
        Ok(bytes)
    }
}

/// `product.xml` as written: the parts morgana follows (see the module docs).
struct Raw {
    version: String,
    manufacturer: String,
    product_name: String,
    product_number: String,
    files: Vec<RawFile>,
    /// Photometry id → PhotometryFileReference fileId.
    photometries: Vec<RawRef>,
    spectra: Vec<RawSpectrum>,
    /// Light source id → SpectrumReference spectrumId.
    light_sources: Vec<RawRef>,
    /// Equipment id → LightSourceReference id.
    equipments: Vec<RawRef>,
    emitters: Vec<RawEmitter>,
    variants: Vec<RawVariant>,
}

#[derive(Debug)]
struct RawFile {
    id: String,
    content_type: String,
    kind: String,
    name: String,
    line: usize,
    path: String,
}

impl RawFile {
    /// Where a local file lies in the container: the folder of its content type.
    fn entry_name(&self) -> String {
        let folder = self.content_type.split('/').next().unwrap_or("");
        format!("{folder}/{}", self.name)
    }
}

/// An element with an id that refers to another by id.
struct RawRef {
    id: String,
    target: Option<String>,
    line: usize,
    path: String,
}

struct RawSpectrum {
    id: String,
    file_id: Option<String>,
    inline: Vec<(f64, f64)>,
    line: usize,
    path: String,
}

struct RawEmitter {
    id: String,
    modes: Vec<RawMode>,
}

/// One light emitter (mode) of an emitter.
struct RawMode {
    kind: String,
    photometry_id: Option<String>,
    light_source_id: Option<String>,
    equipment_id: Option<String>,
    line: usize,
    path: String,
}

struct RawVariant {
    id: String,
    name: String,
    emitter_ids: Vec<(String, usize)>,
    line: usize,
    path: String,
}

fn raw(doc: &Document) -> Result<Raw, ParseError> {
    let root = doc.root_element();
    if root.tag_name().name() != "Root" {
        return Err(ParseError::new(
            xml::line(root),
            format!("{W} product.xml root element"),
            format!("<{}>", root.tag_name().name()),
            "<Root> (a GLDF product.xml)",
        ));
    }
    let header = child(root, "Header");
    let general = xml::require(root, "GeneralDefinitions", W, "the definitions of files, photometries and emitters")?;
    let products = xml::require(root, "ProductDefinitions", W, "the product's variants")?;
    let meta = child(products, "ProductMetaData");
    let section = |name: &str| child(general, name);
    let mut files = Vec::new();
    for f in section("Files").into_iter().flat_map(|s| children(s, "File")) {
        files.push(RawFile {
            id: id(f)?,
            content_type: f.attribute("contentType").unwrap_or("").to_string(),
            kind: f.attribute("type").unwrap_or("").to_string(),
            name: xml::text(f),
            line: xml::line(f),
            path: xml::path(f),
        });
    }
    let refs =
        |section_name: &str, elements: &[&str], reference: &str, attrs: &[&str]| -> Result<Vec<RawRef>, ParseError> {
            let mut out = Vec::new();
            for s in section(section_name).into_iter() {
                for e in s.children().filter(|c| elements.contains(&c.tag_name().name())) {
                    let target = e
                        .descendants()
                        .filter(|d| d.tag_name().name() == reference)
                        .find_map(|d| attrs.iter().find_map(|a| d.attribute(*a)))
                        .map(str::to_string);
                    out.push(RawRef { id: id(e)?, target, line: xml::line(e), path: xml::path(e) });
                }
            }
            Ok(out)
        };
    let photometries = refs("Photometries", &["Photometry"], "PhotometryFileReference", &["fileId"])?;
    let light_sources = refs(
        "LightSources",
        &["ChangeableLightSource", "FixedLightSource", "LightSource"],
        "SpectrumReference",
        &["spectrumId"],
    )?;
    let equipments =
        refs("Equipments", &["Equipment"], "LightSourceReference", &["changeableLightSourceId", "lightSourceId"])?;
    let mut spectra = Vec::new();
    for s in section("Spectrums").into_iter().flat_map(|s| children(s, "Spectrum")) {
        let mut inline = Vec::new();
        for i in children(s, "Intensity") {
            inline.push((
                xml::attr_number(i, "wavelength", W, 0.0, f64::INFINITY)?,
                xml::number(i, W, 0.0, f64::INFINITY)?,
            ));
        }
        spectra.push(RawSpectrum {
            id: id(s)?,
            file_id: child(s, "SpectrumFileReference").and_then(|r| r.attribute("fileId")).map(str::to_string),
            inline,
            line: xml::line(s),
            path: xml::path(s),
        });
    }
    let mut emitters = Vec::new();
    for e in section("Emitters").into_iter().flat_map(|s| children(s, "Emitter")) {
        let modes = e
            .children()
            .filter(|m| ["ChangeableLightEmitter", "FixedLightEmitter", "LightEmitter"].contains(&m.tag_name().name()))
            .map(raw_mode)
            .collect();
        emitters.push(RawEmitter { id: id(e)?, modes });
    }
    let mut variants = Vec::new();
    if let Some(vs) = child(products, "Variants") {
        for v in children(vs, "Variant") {
            let emitter_ids = v
                .descendants()
                .filter(|d| ["EmitterReference", "SimpleGeometryReference"].contains(&d.tag_name().name()))
                .filter_map(|d| d.attribute("emitterId").map(|a| (a.to_string(), xml::line(d))))
                .collect();
            let name = child(v, "Name").or_else(|| child(v, "VariantName")).map(locale).unwrap_or_default();
            variants.push(RawVariant { id: id(v)?, name, emitter_ids, line: xml::line(v), path: xml::path(v) });
        }
    }
    if variants.is_empty() {
        let vs = xml::require(products, "Variants", W, "the product's variants")?;
        xml::require(vs, "Variant", W, "at least one <Variant>")?;
    }
    Ok(Raw {
        version: header.and_then(|h| child(h, "FormatVersion")).map(format_version).unwrap_or_default(),
        manufacturer: header.and_then(|h| xml::child_text(h, "Manufacturer")).unwrap_or_default(),
        product_name: meta
            .and_then(|m| child(m, "Name").or_else(|| child(m, "ProductName")))
            .map(locale)
            .unwrap_or_default(),
        product_number: meta.and_then(|m| child(m, "ProductNumber")).map(locale).unwrap_or_default(),
        files,
        photometries,
        spectra,
        light_sources,
        equipments,
        emitters,
        variants,
    })
}

fn raw_mode(m: Node) -> RawMode {
    let attr_of = |element: &str, attrs: &[&str]| {
        children(m, element).find_map(|c| attrs.iter().find_map(|a| c.attribute(*a))).map(str::to_string)
    };
    RawMode {
        kind: m.tag_name().name().to_string(),
        photometry_id: attr_of("PhotometryReference", &["photometryId"])
            .or_else(|| m.attribute("photometryId").map(str::to_string)),
        light_source_id: attr_of(
            "LightSourceReference",
            &["fixedLightSourceId", "changeableLightSourceId", "lightSourceId"],
        ),
        equipment_id: attr_of("EquipmentReference", &["equipmentId"])
            .or_else(|| m.attribute("equipmentId").map(str::to_string)),
        line: xml::line(m),
        path: xml::path(m),
    }
}

/// The `id` attribute, which every referenced GLDF element has.
fn id(n: Node) -> Result<String, ParseError> {
    n.attribute("id").map(str::to_string).ok_or_else(|| {
        ParseError::new(xml::line(n), format!("{W} {}", xml::path(n)), "no id attribute", "an id=\"…\" attribute")
    })
}

/// The English `Locale` text, else the first.
fn locale(n: Node) -> String {
    let locales: Vec<Node> = children(n, "Locale").collect();
    locales
        .iter()
        .find(|l| l.attribute("language") == Some("en"))
        .or(locales.first())
        .map(|l| xml::text(*l))
        .unwrap_or_else(|| xml::text(n))
}

/// " 1.0" from `major`/`minor` attributes (GLDF 1.0), or " 0.9" from the text (0.9).
fn format_version(n: Node) -> String {
    match (n.attribute("major"), n.attribute("minor")) {
        (Some(a), Some(b)) => format!(" {a}.{b}"),
        _ => {
            let t = xml::text(n);
            if t.is_empty() { t } else { format!(" {}", xml::truncate(&t, 12)) }
        }
    }
}

/// What the chain from the variant leads to.
#[derive(Debug)]
struct Choice<'r> {
    variant_id: String,
    variant_name: String,
    photometry: &'r RawFile,
    /// The spectrum id the light source names.
    spectrum: Option<String>,
}

fn choose<'r>(raw: &'r Raw, variant: Option<&str>, notes: &mut Vec<String>) -> Result<Choice<'r>, ParseError> {
    let ids: Vec<&str> = raw.variants.iter().map(|v| v.id.as_str()).collect();
    let v = match variant {
        Some(name) => raw.variants.iter().find(|v| v.id == name).ok_or_else(|| {
            ParseError::whole_file(
                format!("{W} variant"),
                format!("\"{name}\", which the file does not define"),
                format!("one of its variant ids: {}", ids.join(", ")),
            )
        })?,
        None => {
            if ids.len() > 1 {
                notes.push(format!(
                    "{} variants ({}); the first is used (name another with variant)",
                    ids.len(),
                    ids.join(", ")
                ));
            }
            &raw.variants[0]
        }
    };
    let mut light = Vec::new();
    for (eid, line) in &v.emitter_ids {
        let e = raw.emitters.iter().find(|e| &e.id == eid).ok_or_else(|| {
            ParseError::new(
                *line,
                format!("{W} {} id=\"{}\" emitterId", v.path, v.id),
                format!("\"{eid}\""),
                "the id of an Emitter",
            )
        })?;
        if !e.modes.is_empty() && !light.iter().any(|l: &&RawEmitter| l.id == e.id) {
            light.push(e);
        }
    }
    let Some(e) = light.first() else {
        return Err(ParseError::new(
            v.line,
            format!("{W} {} id=\"{}\"", v.path, v.id),
            "no EmitterReference to an emitter with light (ChangeableLightEmitter, FixedLightEmitter)",
            "a variant that emits light",
        ));
    };
    if light.len() > 1 {
        let others: Vec<&str> = light[1..].iter().map(|l| l.id.as_str()).collect();
        notes.push(format!(
            "variant \"{}\" has {} light emitters; morgana uses the first, \"{}\" (not {})",
            v.id,
            light.len(),
            e.id,
            others.join(", ")
        ));
    }
    if e.modes.len() > 1 {
        notes.push(format!(
            "emitter \"{}\" has {} interchangeable light emitters (modes); the first, a {}, is used",
            e.id,
            e.modes.len(),
            e.modes[0].kind
        ));
    }
    let mode = &e.modes[0];
    let pid = mode.photometry_id.as_ref().ok_or_else(|| {
        ParseError::new(
            mode.line,
            format!("{W} {}", mode.path),
            "no PhotometryReference",
            "a PhotometryReference photometryId",
        )
    })?;
    let photometry = find(&raw.photometries, pid, mode.line, &mode.path, "photometryId", "Photometry")?;
    let fid = photometry.target.as_ref().ok_or_else(|| {
        ParseError::new(
            photometry.line,
            format!("{W} {} id=\"{}\"", photometry.path, photometry.id),
            "no PhotometryFileReference",
            "a PhotometryFileReference fileId (morgana reads photometry files, not descriptive photometry)",
        )
    })?;
    let file = raw.files.iter().find(|f| &f.id == fid).ok_or_else(|| {
        ParseError::new(
            photometry.line,
            format!("{W} {} id=\"{}\" PhotometryFileReference", photometry.path, photometry.id),
            format!("fileId \"{fid}\""),
            "the id of a File",
        )
    })?;
    if file.kind != "localFileName" {
        return Err(ParseError::new(
            file.line,
            format!("{W} {} id=\"{}\"", file.path, file.id),
            format!("type=\"{}\" ({})", file.kind, xml::truncate(&file.name, 60)),
            "type=\"localFileName\": a photometry file inside the container (morgana does not download)",
        ));
    }
    let light_source = match (&mode.light_source_id, &mode.equipment_id) {
        (Some(l), _) => Some(l.clone()),
        (None, Some(q)) => find(&raw.equipments, q, mode.line, &mode.path, "equipmentId", "Equipment")?.target.clone(),
        (None, None) => None,
    };
    let spectrum = match light_source {
        Some(l) => {
            find(&raw.light_sources, &l, mode.line, &mode.path, "light source id", "light source")?.target.clone()
        }
        None => None,
    };
    Ok(Choice { variant_id: v.id.clone(), variant_name: v.name.clone(), photometry: file, spectrum })
}

fn find<'r>(
    list: &'r [RawRef],
    id: &str,
    line: usize,
    path: &str,
    attr: &str,
    what: &str,
) -> Result<&'r RawRef, ParseError> {
    list.iter().find(|r| r.id == id).ok_or_else(|| {
        ParseError::new(line, format!("{W} {path} {attr}"), format!("\"{id}\""), format!("the id of a {what}"))
    })
}

/// The spectrum `id`: inline, or from its `spectrum/text` entry.
fn spectrum(
    id: &str,
    raw: &Raw,
    zip: &mut Container,
    path: &Path,
    notes: &mut Vec<String>,
) -> Result<Option<EmissionSpectrum>, ParseError> {
    let product = inner_path(path, "product.xml");
    let s = raw.spectra.iter().find(|s| s.id == id).ok_or_else(|| {
        ParseError::whole_file(format!("{W} SpectrumReference spectrumId"), format!("\"{id}\""), "the id of a Spectrum")
            .in_file(&product)
    })?;
    let field = format!("{W} {} id=\"{}\"", s.path, s.id);
    if !s.inline.is_empty() {
        return EmissionSpectrum::new(s.inline.clone(), format!("GLDF Spectrum \"{id}\"")).map(Some).map_err(|why| {
            ParseError::new(s.line, field, why, "a relative spectral power distribution").in_file(&product)
        });
    }
    let Some(fid) = &s.file_id else {
        notes.push(format!("GLDF Spectrum \"{id}\" has no Intensity values or file; no emission spectrum"));
        return Ok(None);
    };
    let file = raw.files.iter().find(|f| &f.id == fid).ok_or_else(|| {
        ParseError::new(
            s.line,
            format!("{field} SpectrumFileReference"),
            format!("fileId \"{fid}\""),
            "the id of a File",
        )
        .in_file(&product)
    })?;
    if file.kind != "localFileName" {
        notes.push(format!(
            "GLDF Spectrum \"{id}\" is a {} file ({}), not read",
            file.kind,
            xml::truncate(&file.name, 60)
        ));
        return Ok(None);
    }
    let entry = zip.entry(&file.entry_name())?;
    notes.extend(entry.note);
    let inner = inner_path(path, &entry.name);
    let samples = spectrum_text(&entry.bytes).map_err(|e| e.in_file(&inner))?;
    EmissionSpectrum::new(samples, format!("GLDF Spectrum \"{id}\" ({})", entry.name)).map(Some).map_err(|why| {
        ParseError::whole_file("GLDF spectrum file", why, "a relative spectral power distribution").in_file(&inner)
    })
}

/// A `spectrum/text` file: one "wavelength intensity" pair per line (GLDF: separated by one
/// space or tab; any run of spaces, tabs, or a comma or semicolon is accepted).
fn spectrum_text(bytes: &[u8]) -> Result<Vec<(f64, f64)>, ParseError> {
    let src = super::text::SourceText::decode(bytes);
    let mut out = Vec::new();
    for (i, l) in src.lines.iter().enumerate() {
        let t = l.trim();
        if t.is_empty() || t.starts_with('#') {
            continue;
        }
        let cols: Vec<&str> =
            t.split(|c: char| c.is_whitespace() || c == ';' || c == ',').filter(|c| !c.is_empty()).collect();
        let nums: Vec<f64> = cols.iter().filter_map(|c| super::text::parse_number(c)).collect();
        if cols.len() != 2 || nums.len() != 2 {
            return Err(ParseError::new(
                i + 1,
                "GLDF spectrum file line",
                format!("\"{}\"", xml::truncate(t, 40)),
                "a wavelength (nm) and an intensity",
            ));
        }
        out.push((nums[0], nums[1]));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spectrum_text_lines() {
        assert_eq!(
            spectrum_text(b"380 0.1\n385\t0.2\n\n390  0.3\n").unwrap(),
            vec![(380.0, 0.1), (385.0, 0.2), (390.0, 0.3)]
        );
        let e = spectrum_text(b"380 0.1\n385 x\n").unwrap_err();
        assert_eq!((e.line, e.found.as_str()), (Some(2), "\"385 x\""));
    }

    /// A GLDF 0.9 product: `LightEmitter photometryId`, a `SimpleGeometryReference emitterId`
    /// after a sensor emitter, and a URL file.
    const V09: &str = r#"<Root><Header><Manufacturer>DIAL</Manufacturer><FormatVersion>0.9</FormatVersion></Header>
<GeneralDefinitions><Files>
<File id="ldt" contentType="ldc/eulumdat" type="localFileName">a.ldt</File>
<File id="web" contentType="ldc/ies" type="url">https://example.org/a.ies</File>
</Files><Photometries>
<Photometry id="p"><PhotometryFileReference fileId="ldt"/></Photometry>
<Photometry id="q"><PhotometryFileReference fileId="web"/></Photometry>
</Photometries><Emitters>
<Emitter id="sensor"><Sensor sensorId="s"/></Emitter>
<Emitter id="e"><LightEmitter photometryId="p"/><LightEmitter photometryId="q"/></Emitter>
<Emitter id="u"><LightEmitter photometryId="q"/></Emitter>
</Emitters></GeneralDefinitions>
<ProductDefinitions><Variants>
<Variant id="v1"><EmitterReference emitterId="sensor"/><SimpleGeometryReference geometryId="g" emitterId="e"/></Variant>
<Variant id="v2"><EmitterReference emitterId="u"/></Variant>
</Variants></ProductDefinitions></Root>"#;

    #[test]
    fn gldf_0_9_chains_and_a_url_photometry() {
        let doc = xml::parse(V09, "GLDF").unwrap();
        let raw = raw(&doc).unwrap();
        assert_eq!(raw.version, " 0.9");
        let mut notes = Vec::new();
        let c = choose(&raw, None, &mut notes).unwrap();
        assert_eq!((c.variant_id.as_str(), c.photometry.entry_name().as_str()), ("v1", "ldc/a.ldt"));
        assert!(
            notes.iter().any(|n| n.contains("2 variants")) && notes.iter().any(|n| n.contains("2 interchangeable"))
        );
        let e = choose(&raw, Some("v2"), &mut notes).unwrap_err();
        assert!(e.found.contains("type=\"url\"") && e.expected.contains("localFileName"), "{e}");
        assert_eq!(e.line, Some(4));
    }

    #[test]
    fn sniffing() {
        assert!(sniff(b"PK\x03\x04rest"));
        assert!(!sniff(b"<Root/>"));
    }
}
