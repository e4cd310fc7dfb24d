//! `[[medium]]` records → [`Medium`]s.
//!
//! ```toml
//! [[medium]]
//! name = "fog"
//! sigma_a = 0.1          # m⁻¹ at density 1 (any spectrum), with sigma_s; or sigma_t with albedo
//! sigma_s = 0.4
//! phase = "isotropic"    # "rayleigh", "pure_water", "raman", "petzold" (built-in Mobley et al.
//!                        # 1993 Table 2, src/media/ocean/data/), or { type = "hg", g = 0.8 },
//!                        # { type = "schlick", k = 0.5 }, { type = "two_term_hg", w, g1, g2 },
//!                        # { type = "tabulated", file = "petzold.csv" }, or
//!                        # { type = "mixture", components = [{ sigma_s = .., phase = .. }, ..] }
//!                        # (then give sigma_a only: σ_s is the components' sum)
//! density = { type = "exponential", scale_height_m = 2.0, reference_m = 0.0, up = [0, 1, 0] }
//!         # or { type = "exponential", scale_height_m = 8000, earth = "scene" }: in height above
//!         #    the [world] earth (a sphere: the barometric air of a round-Earth scene)
//!         # or { type = "grid", file = "smoke.mgrid" }
//!         # or { type = "fbm", base = 0.5, amplitude = 0.5, frequency_per_m = 2.0, octaves = 5, seed = 1 }
//! index = { type = "linear", n0 = 1.0, k_per_m = 1e-3, direction = [0, 1, 0] }
//!         # the refractive index light curves along: see `super::index` for every field
//! ```
//!
//! A medium may be clear (`sigma_a = 0`, `sigma_s = 0`) and only bend light.

use super::raw::RawMedium;
use super::spectrum_spec::{SpectrumLibrary, Use};
use crate::atmosphere::Earth;
use crate::media::density::{Density, ExponentialHeight, Fbm, Grid3D, SphericalExponential};
use crate::media::phase::{MixtureComponent, PhaseFunction};
use crate::media::{Coefficients, Medium};
use crate::spectrum::Bands;
use crate::validate::present_fields;
use crate::validate::{Ctx, MAX_LENGTH_M, R};
use glam::DVec3;
use std::ops::Range;
use toml::{Spanned, Value};

pub fn medium(
    ctx: &Ctx,
    lib: &SpectrumLibrary,
    rec: &Spanned<RawMedium>,
    index: usize,
    bands: &Bands,
    earth: &(Earth, bool),
) -> R<Medium> {
    let span = rec.span();
    let m = rec.get_ref();
    let name = ctx.require(&m.name, "name", &span, &format!("medium #{}", index + 1))?.get_ref().clone();
    let what = format!("medium \"{name}\"");
    let range = (bands.min_nm, bands.max_nm);
    let mut medium = match &m.kind {
        Some(kind) => match ctx.choice(kind, &format!("{what}: type"), &["ocean", "atmosphere"])? {
            "ocean" => super::inelastic::ocean_medium(ctx, m, kind, &name, bands)?,
            _ => super::atmosphere_medium::atmosphere_medium(ctx, lib, m, kind, &name, bands, earth)?,
        },
        None => {
            super::inelastic::reject_ocean_fields(ctx, m, &what)?;
            super::atmosphere_medium::reject_atmosphere_fields(ctx, m, &what)?;
            elastic(ctx, lib, m, &span, name, &what, range, &earth.0)?
        }
    };
    if let Some(v) = &m.inelastic {
        let extra = super::inelastic::components(ctx, lib, v, &what, range)?;
        medium.inelastic.components.extend(extra);
    }
    super::inelastic::finish(&mut medium, bands);
    if let Some(v) = &m.index {
        medium.index = Some(super::refractive_index::field(ctx, v, &what, &earth.0, earth.1, range)?);
    }
    Ok(medium)
}

/// A medium given by its coefficients, phase function and density.
#[allow(clippy::too_many_arguments)]
fn elastic(
    ctx: &Ctx,
    lib: &SpectrumLibrary,
    m: &RawMedium,
    span: &Range<usize>,
    name: String,
    what: &str,
    range: (f64, f64),
    earth: &Earth,
) -> R<Medium> {
    let what = what.to_string();
    let spec = |v: &Spanned<Value>, field: &str, use_: Use| lib.parse(ctx, v, &format!("{what}: {field}"), use_, range);
    let phase = match &m.phase {
        None => PhaseFunction::isotropic(),
        Some(p) => phase(ctx, lib, p, &what, range)?,
    };
    let span = span.clone();
    let is_mixture = matches!(phase, PhaseFunction::Mixture(_));
    let coefficients = match (&m.sigma_a, &m.sigma_s, &m.sigma_t, &m.albedo) {
        (Some(a), None, None, None) if is_mixture => {
            Coefficients::AbsorptionMixture { sigma_a: spec(a, "sigma_a", Use::Emission)? }
        }
        (Some(a), Some(s), None, None) if !is_mixture => Coefficients::AbsorptionScattering {
            sigma_a: spec(a, "sigma_a", Use::Emission)?,
            sigma_s: spec(s, "sigma_s", Use::Emission)?,
        },
        (None, None, Some(t), Some(w)) if !is_mixture => Coefficients::ExtinctionAlbedo {
            sigma_t: spec(t, "sigma_t", Use::Emission)?,
            albedo: spec(w, "albedo", Use::Reflectance)?,
        },
        _ => {
            let present = present_fields!(m; sigma_a, sigma_s, sigma_t, albedo);
            let at = present.iter().find_map(|(_, s)| s.clone()).unwrap_or(span.clone());
            let need = if is_mixture {
                "with a mixture phase function give sigma_a only: σ_s is the sum of the components' sigma_s"
            } else {
                "give either sigma_a and sigma_s, or sigma_t and albedo (coefficients in m⁻¹)"
            };
            return Err(ctx.err(&at, format!("{what}: {need}")));
        }
    };
    let density = match &m.density {
        None => Density::Uniform,
        Some(d) => density(ctx, d, &what, earth)?,
    };
    Ok(Medium {
        name,
        coefficients,
        phase,
        density,
        index: None,
        inelastic: crate::media::inelastic::Inelastic::none(),
    })
}

/// A string names a parameter-free phase function ("isotropic", "rayleigh", "pure_water",
/// "raman", "petzold": the built-in average-particle table); a table has `type` — "hg" (g), "schlick" (k, or g), "two_term_hg" (w, g1, g2),
/// "tabulated" (file: CSV of angle_deg, value), "mixture" (components = [{ sigma_s, phase }]).
pub(super) fn phase(
    ctx: &Ctx,
    lib: &SpectrumLibrary,
    v: &Spanned<Value>,
    what: &str,
    range: (f64, f64),
) -> R<PhaseFunction> {
    let span = v.span();
    let named = ["isotropic", "rayleigh", "pure_water", "raman", "petzold"];
    let kind = match v.get_ref() {
        Value::String(s) => {
            return match s.as_str() {
                "isotropic" => Ok(PhaseFunction::isotropic()),
                "rayleigh" => Ok(PhaseFunction::rayleigh()),
                "pure_water" => Ok(PhaseFunction::pure_water()),
                "raman" => Ok(PhaseFunction::raman()),
                "petzold" => Ok(crate::media::ocean::builtin::petzold()),
                other => Err(ctx.err(
                    &span,
                    format!(
                        "{what}: phase \"{other}\" is not known; allowed names: {}, or a table with type",
                        named.join(", ")
                    ),
                )),
            };
        }
        Value::Table(t) => t.get("type").and_then(Value::as_str).unwrap_or(""),
        _ => "",
    };
    let pwhat = format!("{what}: phase");
    let wrap = |r: Result<PhaseFunction, String>| r.map_err(|e| ctx.err(&span, format!("{pwhat}: {e}")));
    match kind {
        "hg" => {
            let t = Table::new(ctx, v, pwhat.clone(), &["type", "g"])?;
            wrap(PhaseFunction::henyey_greenstein(t.num("g", None)?))
        }
        "schlick" => {
            let t = Table::new(ctx, v, pwhat.clone(), &["type", "k", "g"])?;
            match (t.t.contains_key("k"), t.t.contains_key("g")) {
                (true, false) => wrap(PhaseFunction::schlick(t.num("k", None)?)),
                (false, true) => wrap(PhaseFunction::schlick_from_g(t.num("g", None)?)),
                _ => Err(ctx.err(&span, format!("{pwhat}: schlick needs exactly one of k or g"))),
            }
        }
        "two_term_hg" => {
            let t = Table::new(ctx, v, pwhat.clone(), &["type", "w", "g1", "g2"])?;
            wrap(PhaseFunction::two_term_hg(t.num("w", None)?, t.num("g1", None)?, t.num("g2", None)?))
        }
        "tabulated" => {
            let t = Table::new(ctx, v, pwhat.clone(), &["type", "file"])?;
            let file = t.t.get("file").and_then(Value::as_str).ok_or_else(|| ctx.err(&span, format!("{pwhat}: tabulated needs `file`")))?;
            wrap(PhaseFunction::tabulated_csv(&ctx.dir.join(file)))
        }
        "mixture" => mixture(ctx, lib, v, &pwhat, range),
        _ => Err(ctx.err(
            &span,
            format!("{pwhat}: expected a name ({}) or a table with type = \"hg\", \"schlick\", \"two_term_hg\", \"tabulated\" or \"mixture\"", named.join(", ")),
        )),
    }
}

/// `{ type = "mixture", components = [{ sigma_s = <spectrum>, phase = <phase> }, ...] }`: the
/// phase functions weighted by each component's σ_s(λ), which also make up the medium's σ_s.
fn mixture(ctx: &Ctx, lib: &SpectrumLibrary, v: &Spanned<Value>, what: &str, range: (f64, f64)) -> R<PhaseFunction> {
    let span = v.span();
    let t = Table::new(ctx, v, what.to_string(), &["type", "components"])?;
    let list = t.t.get("components").and_then(Value::as_array).filter(|a| !a.is_empty());
    let list = list.ok_or_else(|| {
        ctx.err(&span, format!("{what}: mixture needs `components`, a non-empty array of {{ sigma_s, phase }}"))
    })?;
    let mut components = Vec::new();
    for (i, c) in list.iter().enumerate() {
        let cwhat = format!("{what} component #{}", i + 1);
        let c = Spanned::new(span.clone(), c.clone());
        let ct = Table::new(ctx, &c, cwhat.clone(), &["sigma_s", "phase"])?;
        let (Some(s), Some(p)) = (ct.t.get("sigma_s"), ct.t.get("phase")) else {
            return Err(ctx.err(&span, format!("{cwhat}: needs sigma_s and phase")));
        };
        let sigma_s =
            lib.parse(ctx, &Spanned::new(span.clone(), s.clone()), &format!("{cwhat}: sigma_s"), Use::Emission, range)?;
        let phase = phase(ctx, lib, &Spanned::new(span.clone(), p.clone()), &cwhat, range)?;
        components.push(MixtureComponent::new(sigma_s, phase));
    }
    PhaseFunction::mixture(components).map_err(|e| ctx.err(&span, format!("{what}: {e}")))
}

/// Reads the keys of a table value, rejecting unknown ones.
pub(super) struct Table<'a> {
    pub ctx: &'a Ctx<'a>,
    pub span: Range<usize>,
    pub t: &'a toml::Table,
    pub what: String,
}

impl<'a> Table<'a> {
    pub fn new(ctx: &'a Ctx<'a>, v: &'a Spanned<Value>, what: String, allowed: &[&str]) -> R<Table<'a>> {
        let span = v.span();
        let Value::Table(t) = v.get_ref() else { return Err(ctx.err(&span, format!("{what}: expected a table"))) };
        if let Some(k) = t.keys().find(|k| !allowed.contains(&k.as_str())) {
            return Err(ctx.err(&span, format!("{what}: unknown key `{k}`; allowed: {}", allowed.join(", "))));
        }
        Ok(Table { ctx, span, t, what })
    }

    pub fn num(&self, key: &str, default: Option<f64>) -> R<f64> {
        match self.t.get(key) {
            None => default.ok_or_else(|| self.ctx.err(&self.span, format!("{}: missing `{key}`", self.what))),
            Some(v) => v
                .as_float()
                .or_else(|| v.as_integer().map(|i| i as f64))
                .filter(|x| x.is_finite())
                .ok_or_else(|| self.ctx.err(&self.span, format!("{}: `{key}` must be a finite number", self.what))),
        }
    }

    pub fn positive(&self, key: &str, default: Option<f64>) -> R<f64> {
        let x = self.num(key, default)?;
        if x > 0.0 {
            Ok(x)
        } else {
            Err(self.ctx.err(&self.span, format!("{}: {key} = {x} must be greater than 0", self.what)))
        }
    }

    /// `key = { wavelength_nm = [...], value = [...] }`: the two arrays as written (their
    /// lengths and order are the caller's to check); `example` shows a whole table in messages.
    pub fn wavelength_table(&self, key: &str, example: &str) -> R<(Vec<f64>, Vec<f64>)> {
        let (ctx, span) = (self.ctx, &self.span);
        let what = format!("{}: {key}", self.what);
        let Some(v) = self.t.get(key) else { return Err(ctx.err(span, format!("{}: missing `{key}`", self.what))) };
        let v = Spanned::new(span.clone(), v.clone());
        let table = Table::new(ctx, &v, what.clone(), &["wavelength_nm", "value"])?;
        let list = |k: &str| -> R<Vec<f64>> {
            let Some(x) = table.t.get(k) else {
                return Err(ctx.err(span, format!("{what}: missing `{k}`; give {key} = {example}")));
            };
            let numbers: Option<Vec<f64>> = x
                .as_array()
                .and_then(|a| a.iter().map(|x| x.as_float().or_else(|| x.as_integer().map(|i| i as f64))).collect());
            numbers.ok_or_else(|| ctx.err(span, format!("{what}: `{k}` must be an array of numbers")))
        };
        Ok((list("wavelength_nm")?, list("value")?))
    }

    pub fn vec3(&self, key: &str, default: DVec3) -> R<DVec3> {
        let Some(v) = self.t.get(key) else { return Ok(default) };
        let a: Option<Vec<f64>> = v
            .as_array()
            .map(|a| a.iter().filter_map(|x| x.as_float().or_else(|| x.as_integer().map(|i| i as f64))).collect());
        match a {
            Some(a) if a.len() == 3 && a.iter().all(|x| x.abs() <= MAX_LENGTH_M) => Ok(DVec3::new(a[0], a[1], a[2])),
            _ => Err(self.ctx.err(
                &self.span,
                format!("{}: `{key}` must be three finite numbers within ±{MAX_LENGTH_M:e}", self.what),
            )),
        }
    }
}

fn density(ctx: &Ctx, v: &Spanned<Value>, what: &str, earth: &Earth) -> R<Density> {
    let span = v.span();
    let kind = match v.get_ref() {
        Value::Table(t) => t.get("type").and_then(Value::as_str).unwrap_or(""),
        _ => "",
    };
    let dwhat = format!("{what}: density");
    match kind {
        "exponential" if v.get_ref().get("earth").is_some() => {
            let t = Table::new(ctx, v, dwhat, &["type", "scale_height_m", "reference_m", "earth"])?;
            if v.get_ref().get("earth").and_then(Value::as_str) != Some("scene") {
                return Err(
                    ctx.err(&span, format!("{what}: density earth must be \"scene\" (heights above [world] earth)"))
                );
            }
            let (reference_m, scale_height_m) = (t.num("reference_m", Some(0.0))?, t.positive("scale_height_m", None)?);
            Ok(match earth {
                Earth::Flat { up } => {
                    Density::ExponentialHeight(ExponentialHeight { up: *up, reference_m, scale_height_m })
                }
                Earth::Spherical(s) => Density::SphericalExponential(SphericalExponential {
                    centre: s.centre,
                    radius_m: s.radius_m,
                    reference_m,
                    scale_height_m,
                }),
            })
        }
        "exponential" => {
            let t = Table::new(ctx, v, dwhat, &["type", "scale_height_m", "reference_m", "up"])?;
            let up = t.vec3("up", DVec3::Y)?;
            if up.length_squared() == 0.0 {
                return Err(ctx.err(&span, format!("{what}: density up must not be zero")));
            }
            Ok(Density::ExponentialHeight(ExponentialHeight {
                up: up.normalize(),
                reference_m: t.num("reference_m", Some(0.0))?,
                scale_height_m: t.positive("scale_height_m", None)?,
            }))
        }
        "grid" => {
            let t = Table::new(ctx, v, dwhat, &["type", "file"])?;
            let file =
                t.t.get("file")
                    .and_then(Value::as_str)
                    .ok_or_else(|| ctx.err(&span, format!("{what}: grid density needs `file`")))?;
            let path = ctx.dir.join(file);
            Grid3D::read(&path).map(Density::Grid).map_err(|(line, e)| {
                crate::error::Error::input(
                    Some(crate::error::Location { file: path.clone(), line, column: None }),
                    format!("{what}: {e}"),
                )
            })
        }
        "fbm" => {
            let t = Table::new(ctx, v, dwhat, &["type", "base", "amplitude", "frequency_per_m", "octaves", "seed"])?;
            let octaves = t.num("octaves", Some(5.0))?;
            if !(octaves.fract() == 0.0 && (1.0..=16.0).contains(&octaves)) {
                return Err(ctx.err(&span, format!("{what}: fbm octaves = {octaves} must be an integer from 1 to 16")));
            }
            let seed = t.num("seed", Some(1.0))?;
            if !(seed.fract() == 0.0 && seed >= 0.0) {
                return Err(ctx.err(&span, format!("{what}: fbm seed must be a non-negative integer")));
            }
            Ok(Density::Fbm(Box::new(Fbm::new(
                t.num("base", Some(0.5))?,
                t.num("amplitude", Some(0.5))?,
                t.positive("frequency_per_m", None)?,
                octaves as u32,
                seed as u64,
            ))))
        }
        _ => Err(
            ctx.err(&span, format!("{what}: density must be a table with type = \"exponential\", \"grid\" or \"fbm\""))
        ),
    }
}
