//! Atmosphere files: TOML → [`RawAtmosphere`] (serde, unknown keys rejected, every value
//! spanned) → a validated [`Atmosphere`], through the validation context scenes use
//! ([`crate::validate`]). Errors name the file, line and column, the field, what was found and
//! what is allowed. The keys are documented in `atmospheres/README.md`.

use super::edit::{Bubble, Edit, GridEdit, HotSurface, Inversion, Offset};
use super::{AirDispersion, Atmosphere, BaseProfile, EARTH_RADIUS_M, Earth, MAX_EARTH_RADIUS_M, TableProfile, usa76};
use crate::error::{Error, Location, Result};
use crate::field::Interpolation;
use crate::field::grid_file::{self, Quantity};
use crate::validate::{Ctx, Vec3Raw};
use glam::DVec3;
use serde::Deserialize;
use std::ops::Range;
use std::path::{Path, PathBuf};
use toml::Spanned;

type S<T> = Option<Spanned<T>>;

/// The atmosphere TOML exactly as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawAtmosphere {
    /// `name`: label in reports (default: the file stem).
    pub name: S<String>,
    /// `base`: the base atmosphere, `"usa76"`.
    pub base: S<String>,
    /// `profile`: instead of `base`, a CSV table `altitude_m,temperature_k,pressure_pa`, relative
    /// to the file.
    pub profile: S<String>,
    /// `dispersion`: K(λ) of air, `"ciddor"` or `"cauchy_born_wolf"`.
    pub dispersion: S<String>,
    /// `co2_ppm`: CO₂ mole fraction, µmol/mol (Ciddor only).
    pub co2_ppm: S<f64>,
    /// `top_m`: altitude where the atmosphere ends, m.
    pub top_m: S<f64>,
    /// `earth`: `"spherical"` or `"flat"`, how height is measured.
    pub earth: S<String>,
    /// `earth_radius_m`: sphere radius, m (spherical only).
    pub earth_radius_m: S<f64>,
    /// `[[edit]]`: temperature edits, applied in order (they add).
    #[serde(default)]
    pub edit: Vec<Spanned<RawEdit>>,
}

/// One `[[edit]]` table: a `type` and the union of all types' keys.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawEdit {
    /// `[[edit]] type`: `offset`, `hot_surface`, `inversion`, `bubble` or `grid`.
    #[serde(rename = "type")]
    pub kind: S<String>,
    /// `[[edit]] dT_k`: temperature change ΔT, K.
    #[serde(rename = "dT_k")]
    pub dt_k: S<f64>,
    /// `[[edit]] z0_m`: e-folding height of a hot surface, m.
    pub z0_m: S<f64>,
    /// `[[edit]] height_m`: height of an inversion's midpoint, m.
    pub height_m: S<f64>,
    /// `[[edit]] thickness_m`: thickness parameter w of an inversion, m.
    pub thickness_m: S<f64>,
    /// `[[edit]] centre`: centre of a bubble, m.
    pub centre: S<Vec3Raw>,
    /// `[[edit]] radius_m`: radius of a bubble, m.
    pub radius_m: S<f64>,
    /// `[[edit]] file`: lattice file of a grid edit (quantity `delta_temperature_k`), relative to
    /// the file.
    pub file: S<String>,
    /// `[[edit]] interpolation`: `"tricubic"` or `"trilinear"` (grid edits).
    pub interpolation: S<String>,
}

/// Where relative file names in an atmosphere file are found.
pub enum Files<'a> {
    /// On disk, relative to this directory.
    Dir(PathBuf),
    /// Embedded texts by name (the built-in atmospheres).
    Embedded(&'a [(&'a str, &'a str)]),
}

/// Loads and validates an atmosphere file.
pub fn load(path: &Path) -> Result<Atmosphere> {
    let source = crate::error::read_utf8(path, "atmosphere file")?;
    let dir = path.parent().map_or_else(|| PathBuf::from("."), Path::to_path_buf);
    load_str(&source, path, &Files::Dir(dir))
}

/// Validates atmosphere TOML; `file` names it in errors and is the default `name` (its stem).
pub fn load_str(source: &str, file: &Path, files: &Files) -> Result<Atmosphere> {
    let dir = match files {
        Files::Dir(d) => d.clone(),
        Files::Embedded(_) => PathBuf::from("."),
    };
    let ctx = Ctx::new(file, source, &dir);
    let raw: RawAtmosphere = toml::from_str(source).map_err(|e| ctx.toml_error(&e))?;
    build(&ctx, files, &raw)
}

const TYPES: &[&str] = &["offset", "hot_surface", "inversion", "bubble", "grid"];

fn build(ctx: &Ctx, files: &Files, raw: &RawAtmosphere) -> Result<Atmosphere> {
    let base = base_profile(ctx, files, raw)?;
    let dispersion = dispersion(ctx, raw)?;
    let earth = earth(ctx, raw)?;
    let max = base.max_altitude_m();
    let top_m = match &raw.top_m {
        Some(t) => ctx.number_above(t, "top_m", 0.0, max)?,
        None => max.min(usa76::TOP_GEOMETRIC_M),
    };
    let edits = raw.edit.iter().map(|e| edit(ctx, files, e)).collect::<Result<Vec<_>>>()?;
    let name = raw.name.as_ref().map_or_else(
        || ctx.file.file_stem().and_then(|s| s.to_str()).unwrap_or("atmosphere").to_string(),
        |n| n.get_ref().clone(),
    );
    // A temperature that can go negative is the coldest edit's doing: its line is the place.
    let coldest = edits.iter().enumerate().min_by(|a, b| a.1.range_k().0.total_cmp(&b.1.range_k().0)).map(|(i, _)| i);
    let span = match coldest.map(|i| &raw.edit[i]) {
        Some(e) => {
            let r = e.get_ref();
            r.dt_k
                .as_ref()
                .map(Spanned::span)
                .or_else(|| r.kind.as_ref().map(Spanned::span))
                .unwrap_or_else(|| e.span())
        }
        None => raw.top_m.as_ref().map_or(0..0, Spanned::span),
    };
    Atmosphere::new(name, earth, base, edits, dispersion, top_m).map_err(|e| ctx.err(&span, e))
}

fn base_profile(ctx: &Ctx, files: &Files, raw: &RawAtmosphere) -> Result<BaseProfile> {
    match (&raw.base, &raw.profile) {
        (Some(b), Some(_)) => Err(ctx.err(&b.span(), "give either `base` or `profile`, not both")),
        (Some(b), None) => {
            ctx.choice(b, "base", &["usa76"])?;
            Ok(BaseProfile::Usa76)
        }
        (None, Some(p)) => {
            let (label, text) = read_text(ctx, files, p, "profile")?;
            let table = TableProfile::from_csv(&text).map_err(|(line, msg)| {
                Error::input(Some(Location { file: label, line: Some(line), column: None }), format!("profile: {msg}"))
            })?;
            Ok(BaseProfile::Table(table))
        }
        (None, None) => Ok(BaseProfile::Usa76),
    }
}

fn dispersion(ctx: &Ctx, raw: &RawAtmosphere) -> Result<AirDispersion> {
    let kind = match &raw.dispersion {
        Some(d) => ctx.choice(d, "dispersion", &["ciddor", "cauchy_born_wolf"])?,
        None => "ciddor",
    };
    match (kind, &raw.co2_ppm) {
        ("ciddor", co2) => {
            let ppm = co2.as_ref().map_or(Ok(450.0), |c| ctx.number(c, "co2_ppm", 0.0, 2000.0, false))?;
            AirDispersion::ciddor(ppm).map_err(|e| ctx.err(&(0..0), e))
        }
        (_, Some(c)) => Err(ctx.err(&c.span(), "co2_ppm is only used with dispersion = \"ciddor\"")),
        _ => Ok(AirDispersion::CauchyBornWolf),
    }
}

fn earth(ctx: &Ctx, raw: &RawAtmosphere) -> Result<Earth> {
    let kind = match &raw.earth {
        Some(e) => ctx.choice(e, "earth", &["spherical", "flat"])?,
        None => "spherical",
    };
    match (kind, &raw.earth_radius_m) {
        ("spherical", r) => {
            let radius = r
                .as_ref()
                .map_or(Ok(EARTH_RADIUS_M), |r| ctx.number_above(r, "earth_radius_m", 0.0, MAX_EARTH_RADIUS_M))?;
            Earth::spherical_y(radius).map_err(|e| ctx.err(&(0..0), e))
        }
        (_, Some(r)) => Err(ctx.err(&r.span(), "earth_radius_m is only used with earth = \"spherical\"")),
        _ => Ok(Earth::flat_y()),
    }
}

fn edit(ctx: &Ctx, files: &Files, e: &Spanned<RawEdit>) -> Result<Edit> {
    let span = e.span();
    let r = e.get_ref();
    let kind = ctx.choice(ctx.require(&r.kind, "type", &span, "edit")?, "edit type", TYPES)?;
    let what = format!("edit \"{kind}\"");
    let present = [
        ("dT_k", r.dt_k.as_ref().map(|v| v.span())),
        ("z0_m", r.z0_m.as_ref().map(|v| v.span())),
        ("height_m", r.height_m.as_ref().map(|v| v.span())),
        ("thickness_m", r.thickness_m.as_ref().map(|v| v.span())),
        ("centre", r.centre.as_ref().map(|v| v.span())),
        ("radius_m", r.radius_m.as_ref().map(|v| v.span())),
        ("file", r.file.as_ref().map(|v| v.span())),
        ("interpolation", r.interpolation.as_ref().map(|v| v.span())),
    ];
    let allowed: &[&str] = match kind {
        "offset" => &["dT_k"],
        "hot_surface" => &["dT_k", "z0_m"],
        "inversion" => &["dT_k", "height_m", "thickness_m"],
        "bubble" => &["dT_k", "centre", "radius_m"],
        _ => &["file", "interpolation"],
    };
    ctx.only(&present, allowed, &what)?;
    let dt = |ctx: &Ctx| ctx.number(ctx.require(&r.dt_k, "dT_k", &span, &what)?, "dT_k", -500.0, 500.0, false);
    let positive = |ctx: &Ctx, v: &S<f64>, key: &str| {
        ctx.number_above(ctx.require(v, key, &span, &what)?, key, 0.0, f64::INFINITY)
    };
    let edit = match kind {
        "offset" => Edit::Offset(Offset { dt_k: dt(ctx)? }),
        "hot_surface" => {
            Edit::HotSurface(HotSurface::new(dt(ctx)?, positive(ctx, &r.z0_m, "z0_m")?).map_err(|m| ctx.err(&span, m))?)
        }
        "inversion" => {
            let h = ctx.number(ctx.require(&r.height_m, "height_m", &span, &what)?, "height_m", -1e4, 1e5, false)?;
            let w = positive(ctx, &r.thickness_m, "thickness_m")?;
            Edit::Inversion(Inversion::new(dt(ctx)?, h, w).map_err(|m| ctx.err(&span, m))?)
        }
        "bubble" => {
            let c = ctx.require(&r.centre, "centre", &span, &what)?;
            let centre = DVec3::from_array(c.get_ref().0);
            if !centre.is_finite() {
                return Err(ctx.err(&c.span(), format!("centre = {centre} must have three finite numbers (m)")));
            }
            let radius = positive(ctx, &r.radius_m, "radius_m")?;
            Edit::Bubble(Bubble::new(centre, radius, dt(ctx)?).map_err(|m| ctx.err(&span, m))?)
        }
        _ => grid_edit(ctx, files, r, &span, &what)?,
    };
    Ok(edit)
}

fn grid_edit(ctx: &Ctx, files: &Files, r: &RawEdit, span: &Range<usize>, what: &str) -> Result<Edit> {
    let f = ctx.require(&r.file, "file", span, what)?;
    let interpolation = match &r.interpolation {
        Some(i) => match ctx.choice(i, "interpolation", &["trilinear", "tricubic"])? {
            "trilinear" => Interpolation::Trilinear,
            _ => Interpolation::Tricubic,
        },
        None => Interpolation::Tricubic,
    };
    let Files::Dir(dir) = files else {
        return Err(ctx.err(&f.span(), "grid edits need a file on disk; built-in atmospheres have none"));
    };
    let path = resolve(dir, f.get_ref());
    let (quantity, lattice) = grid_file::read(&path)?;
    if quantity != Quantity::DeltaTemperatureK {
        return Err(ctx.err(
            &f.span(),
            format!(
                "{}: a grid edit needs quantity delta_temperature_k, the file holds {}",
                path.display(),
                quantity.name()
            ),
        ));
    }
    let edit =
        GridEdit::new(lattice, interpolation).map_err(|m| ctx.err(&f.span(), format!("{}: {m}", path.display())))?;
    Ok(Edit::Grid(edit))
}

fn resolve(dir: &Path, name: &str) -> PathBuf {
    let p = Path::new(name);
    if p.is_absolute() { p.to_path_buf() } else { dir.join(p) }
}

/// The text of a file named by the atmosphere, and the path or label to cite in errors.
fn read_text(ctx: &Ctx, files: &Files, v: &Spanned<String>, what: &str) -> Result<(PathBuf, String)> {
    match files {
        Files::Dir(dir) => {
            let path = resolve(dir, v.get_ref());
            std::fs::read_to_string(&path)
                .map(|t| (path.clone(), t))
                .map_err(|e| ctx.err(&v.span(), format!("{what}: cannot read {}: {e}", path.display())))
        }
        Files::Embedded(list) => list
            .iter()
            .find(|(n, _)| *n == v.get_ref())
            .map(|(n, t)| (PathBuf::from(format!("<built-in {n}>")), t.to_string()))
            .ok_or_else(|| ctx.err(&v.span(), format!("{what}: no built-in file \"{}\"", v.get_ref()))),
    }
}
