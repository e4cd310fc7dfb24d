//! A medium's `index` → an [`IndexField`]: the refractive index light curves along.
//!
//! ```toml
//! index = 1.33                                   # constant n
//! index = { type = "constant", n = 1.33 }
//! index = { type = "air", density_kg_m3 = 1.225, dispersion = "ciddor", co2_ppm = 450 }
//! index = { type = "linear", n0 = 1.0, k_per_m = 1e-3, direction = [0, 1, 0] }   # n = n0 + k x·d
//! index = { type = "exponential", n0 = 1.000293, scale_height_m = 8000 }         # height per [world] earth
//! index = { type = "profile", file = "n_of_h.csv" }          # CSV height_m,n; monotone cubic
//! index = { type = "temperature_grid", file = "plume.mfield", interpolation = "tricubic",
//!           pressure_pa = 101325 }                           # or pressure = "usa76"
//! index = { type = "atmosphere", file = "../atmospheres/hot_road.toml" }  # or name = "usa76"
//!         # (an atmosphere file: USA76 or a table, mirage edits, dispersion, its own Earth — which
//!         #  an explicit [world] earth replaces; see atmospheres/README.md)
//! # any of these (but a number) may add local bumps and allow n < 1:
//! #   bumps = [{ center = [0, 1, 0], radius_m = 0.5, delta_n = 1e-4 }], allow_below_one = false
//! ```
//!
//! Heights are measured by the scene's Earth (`[world] earth = "flat"` with +y up, or
//! `"spherical"` with the centre at (0, −R, 0), R = `earth_radius_m`, default 6 371 km).

use super::media::Table;
use crate::atmosphere::{AirDispersion, Earth};
use crate::error::{Error, Location};
use crate::field::{Bump, Interpolation, grid_file};
use crate::material::Ior;
use crate::media::refractive_index::{
    Constant, Exponential, GridPressure, IndexField, Linear, Profile, Sum, TemperatureGrid,
};
use crate::validate::{Ctx, R};
use glam::DVec3;
use toml::{Spanned, Value};

const KINDS: &str =
    "\"constant\", \"air\", \"linear\", \"exponential\", \"profile\", \"temperature_grid\" or \"atmosphere\"";

/// The field a medium's `index` value describes, checked over the scene's wavelengths.
///
/// `earth` is the scene's Earth; `explicit_earth` says whether `[world]` gave it (then it also
/// replaces an atmosphere file's own).
pub fn field(
    ctx: &Ctx,
    v: &Spanned<Value>,
    what: &str,
    earth: &Earth,
    explicit_earth: bool,
    range_nm: (f64, f64),
) -> R<IndexField> {
    let span = v.span();
    let iwhat = format!("{what}: index");
    if let Some(n) = v.get_ref().as_float().or_else(|| v.get_ref().as_integer().map(|i| i as f64)) {
        let f = IndexField::Constant(Constant::Ior(Ior::Constant { n }));
        return check(ctx, &span, &iwhat, f, false, range_nm, None);
    }
    let Value::Table(t) = v.get_ref() else {
        return Err(ctx.err(&span, format!("{iwhat}: expected a number or a table with type = {KINDS}")));
    };
    let kind = t.get("type").and_then(Value::as_str).unwrap_or("");
    let common = ["type", "bumps", "allow_below_one"];
    let keys = |own: &[&'static str]| -> Vec<&'static str> { common.iter().chain(own).copied().collect() };
    let base = match kind {
        "constant" => {
            let t = Table::new(ctx, v, iwhat.clone(), &keys(&["n"]))?;
            IndexField::Constant(Constant::Ior(Ior::Constant { n: t.positive("n", None)? }))
        }
        "air" => {
            let t = Table::new(ctx, v, iwhat.clone(), &keys(&["density_kg_m3", "dispersion", "co2_ppm"]))?;
            let dispersion = dispersion(&t)?;
            let density_kg_m3 = t.num("density_kg_m3", None)?;
            if density_kg_m3 < 0.0 {
                return Err(ctx.err(&span, format!("{iwhat}: density_kg_m3 = {density_kg_m3} must not be negative")));
            }
            IndexField::Constant(Constant::Air { dispersion, density_kg_m3 })
        }
        "linear" => {
            let t = Table::new(ctx, v, iwhat.clone(), &keys(&["n0", "k_per_m", "direction"]))?;
            let l = Linear::new(t.positive("n0", None)?, t.num("k_per_m", None)?, t.vec3("direction", DVec3::Y)?);
            IndexField::Linear(l.map_err(|e| ctx.err(&span, format!("{iwhat}: {e}")))?)
        }
        "exponential" => {
            let t = Table::new(ctx, v, iwhat.clone(), &keys(&["n0", "scale_height_m"]))?;
            let e = Exponential::new(t.positive("n0", None)?, t.positive("scale_height_m", None)?, *earth);
            IndexField::Exponential(e.map_err(|e| ctx.err(&span, format!("{iwhat}: {e}")))?)
        }
        "profile" => {
            let t = Table::new(ctx, v, iwhat.clone(), &keys(&["file"]))?;
            let path = ctx.dir.join(file_key(&t)?);
            let text = std::fs::read_to_string(&path)
                .map_err(|e| Error::input(Some(Location::file(&path)), format!("{iwhat}: cannot read profile: {e}")))?;
            let p = Profile::from_csv(&text, *earth).map_err(|(line, e)| {
                Error::input(
                    Some(Location { file: path.clone(), line: Some(line), column: None }),
                    format!("{iwhat}: {e}"),
                )
            })?;
            IndexField::Profile(p)
        }
        "temperature_grid" => temperature_grid(ctx, v, &iwhat, earth, &keys)?,
        "atmosphere" => {
            let t = Table::new(ctx, v, iwhat.clone(), &keys(&["file", "name"]))?;
            let (file, name) = (t.t.get("file").and_then(Value::as_str), t.t.get("name").and_then(Value::as_str));
            let a = atmosphere(ctx, &span, file, name, &iwhat)?;
            let a = if explicit_earth { a.with_earth(*earth) } else { a };
            IndexField::Atmosphere(Box::new(a))
        }
        _ => return Err(ctx.err(&span, format!("{iwhat}: type must be {KINDS}"))),
    };
    let field = with_bumps(ctx, v, &iwhat, base)?;
    check(ctx, &span, &iwhat, field, allow_below_one(ctx, v, &iwhat)?, range_nm, None)
}

/// The atmosphere a `file` (an atmosphere TOML, relative to the scene) or a built-in `name`
/// gives; exactly one of them.
pub(super) fn atmosphere(
    ctx: &Ctx,
    span: &std::ops::Range<usize>,
    file: Option<&str>,
    name: Option<&str>,
    what: &str,
) -> R<crate::atmosphere::Atmosphere> {
    match (file, name) {
        (Some(f), None) => {
            // A file that cannot be read is this field's error; an error inside a file that can is
            // located in that file.
            let path = ctx.dir.join(f);
            if let Err(e) = std::fs::metadata(&path) {
                return Err(ctx.err(span, format!("{what}: cannot read the atmosphere file {}: {e}", path.display())));
            }
            crate::atmosphere::load(&path).map_err(|e| ctx.in_named_file(e, span, what, "atmosphere"))
        }
        (None, Some(n)) => crate::atmosphere::Atmosphere::builtin(n).map_err(|e| ctx.err(span, format!("{what}: {e}"))),
        _ => Err(ctx.err(
            span,
            format!(
                "{what}: give file (an atmosphere TOML) or name (built-in: {})",
                crate::atmosphere::BUILTIN_NAMES.join(", ")
            ),
        )),
    }
}

/// The `allow_below_one` flag of an `index` table (false when absent).
fn allow_below_one(ctx: &Ctx, v: &Spanned<Value>, iwhat: &str) -> R<bool> {
    match v.get_ref().get("allow_below_one") {
        None => Ok(false),
        Some(Value::Boolean(b)) => Ok(*b),
        Some(_) => Err(ctx.err(&v.span(), format!("{iwhat}: allow_below_one must be true or false"))),
    }
}

/// Checks a medium's field over the box the scene's light can reach (known once the geometry is
/// built): n must stay positive, and at least 1 unless the scene allows less.
pub fn check_over(
    ctx: &Ctx,
    v: &Spanned<Value>,
    what: &str,
    f: &IndexField,
    range_nm: (f64, f64),
    domain: &crate::geometry::Aabb,
) -> R<()> {
    let iwhat = format!("{what}: index");
    let allow = if v.get_ref().is_table() { allow_below_one(ctx, v, &iwhat)? } else { false };
    check(ctx, &v.span(), &iwhat, f.clone(), allow, range_nm, Some(domain)).map(|_| ())
}

fn file_key<'a>(t: &'a Table) -> R<&'a str> {
    t.t.get("file").and_then(Value::as_str).ok_or_else(|| t.ctx.err(&t.span, format!("{}: missing `file`", t.what)))
}

/// `dispersion = "ciddor"` (default, with `co2_ppm`, default 450) or `"cauchy_born_wolf"`.
fn dispersion(t: &Table) -> R<AirDispersion> {
    let name = match t.t.get("dispersion") {
        None => "ciddor",
        Some(v) => v.as_str().unwrap_or(""),
    };
    match name {
        "ciddor" => AirDispersion::ciddor(t.num("co2_ppm", Some(450.0))?)
            .map_err(|e| t.ctx.err(&t.span, format!("{}: {e}", t.what))),
        "cauchy_born_wolf" if t.t.contains_key("co2_ppm") => {
            Err(t.ctx.err(&t.span, format!("{}: co2_ppm is only used by dispersion = \"ciddor\"", t.what)))
        }
        "cauchy_born_wolf" => Ok(AirDispersion::CauchyBornWolf),
        other => Err(t.ctx.err(
            &t.span,
            format!("{}: dispersion \"{other}\" is not known; use \"ciddor\" or \"cauchy_born_wolf\"", t.what),
        )),
    }
}

fn temperature_grid(
    ctx: &Ctx,
    v: &Spanned<Value>,
    iwhat: &str,
    earth: &Earth,
    keys: &dyn Fn(&[&'static str]) -> Vec<&'static str>,
) -> R<IndexField> {
    let own = ["file", "interpolation", "pressure_pa", "pressure", "dispersion", "co2_ppm"];
    let t = Table::new(ctx, v, iwhat.to_string(), &keys(&own))?;
    let span = v.span();
    let interpolation = match t.t.get("interpolation").map(|v| v.as_str().unwrap_or("")) {
        None | Some("tricubic") => Interpolation::Tricubic,
        Some("trilinear") => Interpolation::Trilinear,
        Some(other) => {
            return Err(
                ctx.err(&span, format!("{iwhat}: interpolation \"{other}\": use \"trilinear\" or \"tricubic\""))
            );
        }
    };
    let pressure = match (t.t.get("pressure_pa"), t.t.get("pressure").map(|v| v.as_str().unwrap_or(""))) {
        (Some(_), None) => GridPressure::Constant { pressure_pa: t.positive("pressure_pa", None)? },
        (None, Some("usa76")) => GridPressure::Usa76 { earth: *earth },
        _ => {
            return Err(ctx.err(&span, format!("{iwhat}: give pressure_pa (Pa), or pressure = \"usa76\"")));
        }
    };
    let path = ctx.dir.join(file_key(&t)?);
    let (quantity, lattice) = grid_file::read(&path).map_err(|e| ctx.in_named_file(e, &span, iwhat, "grid"))?;
    if quantity != grid_file::Quantity::TemperatureK {
        return Err(Error::input(
            Some(Location { file: path.clone(), line: Some(2), column: None }),
            format!("{iwhat}: the file holds {}, a temperature grid needs temperature_k", quantity.name()),
        ));
    }
    // The overshoot depends on the scene's choice of interpolation as much as on the data: the
    // scene's index table is the place to fix it.
    let g = TemperatureGrid::new(lattice, interpolation, pressure, dispersion(&t)?).map_err(|e| {
        ctx.err(
            &span,
            format!(
                "{iwhat} ({}): {e}; use interpolation = \"trilinear\" or raise the lowest temperatures",
                path.display()
            ),
        )
    })?;
    Ok(IndexField::TemperatureGrid(Box::new(g)))
}

/// `bumps = [{ center, radius_m, delta_n }, ...]` on top of `base`.
fn with_bumps(ctx: &Ctx, v: &Spanned<Value>, iwhat: &str, base: IndexField) -> R<IndexField> {
    let span = v.span();
    let Some(list) = v.get_ref().get("bumps") else { return Ok(base) };
    let Some(list) = list.as_array() else {
        return Err(ctx.err(&span, format!("{iwhat}: bumps must be an array of {{ center, radius_m, delta_n }}")));
    };
    let mut bumps = Vec::new();
    for (i, b) in list.iter().enumerate() {
        let b = Spanned::new(span.clone(), b.clone());
        let bwhat = format!("{iwhat}: bump #{}", i + 1);
        let t = Table::new(ctx, &b, bwhat.clone(), &["center", "radius_m", "delta_n"])?;
        if !t.t.contains_key("center") {
            return Err(ctx.err(&span, format!("{bwhat}: missing `center`")));
        }
        let bump = Bump::new(t.vec3("center", DVec3::ZERO)?, t.positive("radius_m", None)?, t.num("delta_n", None)?);
        bumps.push(bump.map_err(|e| ctx.err(&span, format!("{bwhat}: {e}")))?);
    }
    Ok(IndexField::Sum(Sum { base: Box::new(base), bumps }))
}

/// n must be positive over the scene's wavelengths in `domain` (a point, the origin, before the
/// geometry is known), and not below 1 unless allowed.
fn check(
    ctx: &Ctx,
    span: &std::ops::Range<usize>,
    iwhat: &str,
    f: IndexField,
    allow_below_one: bool,
    range_nm: (f64, f64),
    domain: Option<&crate::geometry::Aabb>,
) -> R<IndexField> {
    let origin = crate::geometry::Aabb { min: DVec3::ZERO, max: DVec3::ZERO };
    f.validate(domain.unwrap_or(&origin), range_nm, allow_below_one).map_err(|e| {
        let fix = if allow_below_one { "" } else { " (set allow_below_one = true if that is intended)" };
        ctx.err(span, format!("{iwhat}: {e}{fix}"))
    })?;
    Ok(f)
}
