//! `ozone_du`, `ozone` and `aerosol` of a `[[medium]] type = "atmosphere"`: the atmosphere of
//! constituents ([`crate::media::constituents`]) — the air (when `rayleigh` is on), ozone and
//! aerosols, each tabulated on the atmosphere's heights.
//!
//! ```toml
//! ozone_du = 300     # ozone column, Dobson units, 0–1000: AFGL mid-latitude summer shape,
//!                    # Bogumil et al. (2003) cross-section at 293 K (see crate::media::ozone)
//! aerosol = { angstrom_beta = 0.05,   # optical depth at 1 µm (or visibility_km, Koschmieder)
//!             angstrom_alpha = 1.3,   # Ångström exponent, 0–4 (default 1.3, Ångström 1929)
//!             scale_height_m = 1200,  # exponential profile, 100–20 000 m
//!             albedo = 0.95,          # single-scattering albedo, 0–1, or a table (below)
//!             g = 0.7 }               # Henyey–Greenstein asymmetry, −1 < g < 1
//! ```
//!
//! Instead of `g`, `phase = { type = "two_term_hg", w = 0.9, g1 = 0.8, g2 = -0.3 }` gives the
//! aerosols a two-term Henyey–Greenstein phase function w HG(g₁) + (1 − w) HG(g₂) (Kattawar
//! 1975), a forward lobe and a backward one; `phase = { type = "hg", g = 0.7 }` is the same as
//! `g = 0.7`.
//!
//! Instead of `ozone_du`, a scene may give its own ozone:
//!
//! ```toml
//! ozone = { profile = "o3.csv",            # CSV altitude_m,number_density_per_cm3, ground to top
//!           interpolation = "log",         # or "linear": how n is read between the levels
//!           cross_section_cm2 = <spectrum>,# σ(λ), cm² (default Bogumil et al. 2003, 293 K)
//!           column_du = 300 }              # scale to this column (alone: the AFGL shape)
//! ```
//!
//! ([`crate::media::ozone::NumberDensityTable`]).
//!
//! `albedo = { wavelength_nm = [400, 550, 700], value = [0.93, 0.91, 0.89] }` gives ω(λ) as a
//! table: at least two samples, wavelengths strictly increasing, values in [0, 1]; linear
//! between the samples and constant beyond the ends ([`crate::media::albedo`]).

use super::atmosphere_medium::Rayleigh;
use super::media::Table;
use super::raw::RawMedium;
use super::spectrum_spec::{SpectrumLibrary, Use};
use crate::atmosphere::Atmosphere;
use crate::atmosphere::Earth;
use crate::error::{Error, Location};
use crate::media::albedo::Albedo;
use crate::media::constituents::{Constituent, Constituents, Extinction};
use crate::media::density::AirProfile;
use crate::media::ozone::{Interpolation, NumberDensityTable};
use crate::media::phase::PhaseFunction;
use crate::media::rayleigh_air::N_STANDARD_PER_M3;
use crate::media::{aerosol, ozone};
use crate::spectrum::{Bands, Spectrum};
use crate::validate::{Ctx, R};
use toml::Spanned;

/// The air the constituents are added to.
pub struct Air<'a> {
    /// The atmosphere's profile, on the scene's Earth.
    pub atmosphere: &'a Atmosphere,
    /// The air's Rayleigh scattering; `None`: the air does not scatter.
    pub rayleigh: Option<&'a Rayleigh>,
    /// The medium's `type` (for spans of messages about the whole medium).
    pub kind: &'a Spanned<String>,
    /// The scene's named spectra (an ozone cross-section may be one).
    pub lib: &'a SpectrumLibrary<'a>,
    /// The scene's wavelengths.
    pub bands: &'a Bands,
}

/// The constituents of medium `m` and the phase function for position-free callers (the first
/// scatterer's, else isotropic).
pub fn constituents(ctx: &Ctx, m: &RawMedium, air: &Air, what: &str) -> R<(Constituents, PhaseFunction)> {
    let atmosphere = air.atmosphere;
    let (earth, top_m) = (atmosphere.earth, atmosphere.top_m());
    let air_profile = AirProfile::new(atmosphere, earth, N_STANDARD_PER_M3)
        .map_err(|e| ctx.err(&m.atmosphere.as_ref().map_or(air.kind.span(), |a| a.span()), format!("{what}: {e}")))?;
    let mut list = Vec::new();
    if let Some(rayleigh) = air.rayleigh {
        let phase = PhaseFunction::rayleigh_depolarised(rayleigh.depolarisation)
            .map_err(|e| ctx.err(&air.kind.span(), format!("{what}: {e}")))?;
        list.push(Constituent {
            name: "air",
            extinction: Extinction::Rayleigh(rayleigh.cross_section.clone()),
            albedo: Albedo::Constant(1.0),
            phase,
            profile: air_profile.clone(),
        });
    }
    match (&m.ozone_du, &m.ozone) {
        (Some(du), None) => {
            let du = ctx.number(du, &format!("{what}: ozone_du (Dobson units)"), 0.0, 1000.0, false)?;
            list.push(ozone_constituent(
                ozone::cross_section_m2(),
                AirProfile::from_heights(earth, top_m, ozone::profile(du, top_m)),
            ));
        }
        (None, Some(v)) => list.push(ozone_table(ctx, v, air, what, (earth, top_m))?),
        (Some(du), Some(_)) => {
            return Err(ctx.err(
                &du.span(),
                format!("{what}: give ozone_du (the AFGL profile's column) or ozone = {{ ... }}, not both"),
            ));
        }
        (None, None) => {}
    }
    if let Some(v) = &m.aerosol {
        let rayleigh_550 = if let Some(rayleigh) = air.rayleigh {
            rayleigh.cross_section.at_standard_density(550.0) * air_profile.at_height(0.0)
        } else {
            0.0
        };
        list.push(aerosols(ctx, v, &format!("{what}: aerosol"), (earth, top_m), rayleigh_550)?);
    }
    let phase = list.iter().find(|c| c.albedo.scatters()).map_or(PhaseFunction::isotropic(), |c| c.phase.clone());
    let constituents = Constituents::new(list).map_err(|e| ctx.err(&air.kind.span(), format!("{what}: {e}")))?;
    Ok((constituents, phase))
}

/// Ozone of this cross-section (m², per molecule) and number density (m⁻³): it only absorbs.
fn ozone_constituent(cross_section_m2: Spectrum, profile: AirProfile) -> Constituent {
    Constituent {
        name: "ozone",
        extinction: Extinction::CrossSection(cross_section_m2),
        albedo: Albedo::Constant(0.0),
        phase: PhaseFunction::isotropic(),
        profile,
    }
}

/// `ozone = { profile = "o3.csv", cross_section_cm2 = <spectrum>, column_du = D }` (see the
/// module docs).
fn ozone_table(
    ctx: &Ctx,
    v: &Spanned<toml::Value>,
    air: &Air,
    what: &str,
    (earth, top_m): (Earth, f64),
) -> R<Constituent> {
    let owhat = format!("{what}: ozone");
    let t = Table::new(ctx, v, owhat.clone(), &["profile", "interpolation", "cross_section_cm2", "column_du"])?;
    let cross_section = match t.t.get("cross_section_cm2") {
        None => ozone::cross_section_m2(),
        Some(x) => {
            let range = (air.bands.min_nm, air.bands.max_nm);
            let xwhat = format!("{owhat}: cross_section_cm2");
            let cm2 = air.lib.parse(ctx, &Spanned::new(v.span(), x.clone()), &xwhat, Use::Emission, range)?;
            Spectrum::Scaled(1e-4, Box::new(cm2))
        }
    };
    let (density, levels) = ozone_density(&t, top_m)?;
    let profile = AirProfile::from_heights(earth, top_m, density);
    // A profile file's levels break its slope: no column table may stand for it.
    let profile = if levels { profile.with_slope_breaks() } else { profile };
    Ok(ozone_constituent(cross_section, profile))
}

/// A number density, m⁻³ at a height in m.
type NumberDensity = Box<dyn Fn(f64) -> f64>;

/// The number density of an `ozone` table `t`: its profile file's, or AFGL's shape, scaled to
/// `column_du` when it is given; and whether it is a profile file's.
fn ozone_density(t: &Table, top_m: f64) -> R<(NumberDensity, bool)> {
    let column_du = match t.t.contains_key("column_du") {
        true => Some(in_range_number(t, "column_du", 0.0, 1000.0)?),
        false => None,
    };
    let Some(file) = t.t.get("profile") else {
        if t.t.contains_key("interpolation") {
            let e = format!("{}: interpolation reads a profile file's levels: give profile, or remove it", t.what);
            return Err(t.ctx.err(&t.span, e));
        }
        let Some(du) = column_du else {
            let e = format!(
                "{}: give a profile file, a column_du (Dobson units, the AFGL profile's shape), or both",
                t.what
            );
            return Err(t.ctx.err(&t.span, e));
        };
        return Ok((Box::new(ozone::profile(du, top_m)), false));
    };
    let table = ozone_profile_file(t, file, top_m)?;
    let Some(du) = column_du else { return Ok((Box::new(move |h| table.at(h)), true)) };
    let column = ozone::column_per_m2(top_m, |h| table.at(h));
    if column <= 0.0 {
        let e =
            format!("{}: the profile holds no ozone below the top, so it cannot be scaled to column_du = {du}", t.what);
        return Err(t.ctx.err(&t.span, e));
    }
    let scale = du * ozone::MOLECULES_PER_M2_PER_DU / column;
    Ok((Box::new(move |h| scale * table.at(h)), true))
}

/// `key` of `t` as a number in [lo, hi].
fn in_range_number(t: &Table, key: &str, lo: f64, hi: f64) -> R<f64> {
    let x = t.num(key, None)?;
    if (lo..=hi).contains(&x) {
        return Ok(x);
    }
    Err(t.ctx.err(&t.span, format!("{}: {key} = {x} is out of range [{lo}, {hi}]", t.what)))
}

/// The ozone `profile` file (relative to the scene), which must span the ground to the top.
fn ozone_profile_file(t: &Table, file: &toml::Value, top_m: f64) -> R<NumberDensityTable> {
    let Some(file) = file.as_str() else {
        return Err(t.ctx.err(&t.span, format!("{}: profile must be a file name", t.what)));
    };
    let interpolation = match t.t.get("interpolation").map(|i| i.as_str()) {
        None | Some(Some("log")) => Interpolation::Log,
        Some(Some("linear")) => Interpolation::Linear,
        Some(_) => {
            return Err(t.ctx.err(
                &t.span,
                format!(
                    "{}: interpolation must be \"log\" (ln n linear between levels, the default) or \"linear\"",
                    t.what
                ),
            ));
        }
    };
    let path = t.ctx.dir.join(file);
    let text = std::fs::read_to_string(&path).map_err(|e| {
        Error::input(Some(Location::file(&path)), format!("{}: cannot read the ozone profile: {e}", t.what))
    })?;
    let table = NumberDensityTable::from_csv(&text).map_err(|(line, e)| {
        Error::input(
            Some(Location { file: path.clone(), line: Some(line), column: None }),
            format!("{}: profile: {e}", t.what),
        )
    })?;
    let table = table.with_interpolation(interpolation);
    let (lo, hi) = table.altitude_range();
    if lo > 0.0 || hi < top_m {
        return Err(Error::input(
            Some(Location::file(&path)),
            format!("{}: the profile covers {lo} to {hi} m and the atmosphere spans 0 to {top_m} m: extend it", t.what),
        ));
    }
    Ok(table)
}

/// `aerosol = { … }` (see the module docs); `rayleigh_550` is the air's extinction at 550 nm at
/// the ground, which a visibility's extinction includes.
fn aerosols(
    ctx: &Ctx,
    v: &Spanned<toml::Value>,
    what: &str,
    (earth, top_m): (crate::atmosphere::Earth, f64),
    rayleigh_550: f64,
) -> R<Constituent> {
    const KEYS: &[&str] =
        &["angstrom_alpha", "angstrom_beta", "visibility_km", "scale_height_m", "albedo", "g", "phase"];
    let t = Table::new(ctx, v, what.to_string(), KEYS)?;
    let span = v.span();
    let in_range = |key: &str, x: f64, lo: f64, hi: f64, open: bool| -> R<f64> {
        let ok = if open { x > lo && x < hi } else { x >= lo && x <= hi };
        if ok {
            return Ok(x);
        }
        let (l, r) = if open { ("(", ")") } else { ("[", "]") };
        Err(ctx.err(&span, format!("{what}: {key} = {x} is out of range: give a value in {l}{lo}, {hi}{r}")))
    };
    let alpha = in_range("angstrom_alpha", t.num("angstrom_alpha", Some(1.3))?, 0.0, 4.0, false)?;
    let scale_height_m = in_range("scale_height_m", t.num("scale_height_m", None)?, 100.0, 20_000.0, false)?;
    let albedo = match t.t.get("albedo") {
        Some(toml::Value::Table(_)) => albedo_table(&t, what)?,
        Some(toml::Value::Float(_) | toml::Value::Integer(_)) | None => {
            Albedo::Constant(in_range("albedo", t.num("albedo", None)?, 0.0, 1.0, false)?)
        }
        Some(other) => {
            return Err(ctx.err(
                &span,
                format!(
                    "{what}: albedo must be a number in [0, 1] or a table {{ wavelength_nm = [...], value = [...] }}, not {}",
                    other.type_str()
                ),
            ));
        }
    };
    let beta = match (t.t.contains_key("angstrom_beta"), t.t.contains_key("visibility_km")) {
        (true, false) => in_range("angstrom_beta", t.num("angstrom_beta", None)?, 0.0, 10.0, false)?,
        (false, true) => {
            let km = in_range("visibility_km", t.num("visibility_km", None)?, 0.01, 1000.0, false)?;
            aerosol::beta_from_visibility(km * 1e3, rayleigh_550, alpha, scale_height_m, top_m).ok_or_else(|| {
                ctx.err(
                    &span,
                    format!(
                        "{what}: visibility_km = {km}: the air alone limits the visibility to {:.0} km (Koschmieder, 3.912/σ at 550 nm); give a shorter visibility",
                        aerosol::KOSCHMIEDER / rayleigh_550 * 1e-3
                    ),
                )
            })?
        }
        _ => {
            return Err(ctx.err(
                &span,
                format!("{what}: give either angstrom_beta (optical depth at 1 µm) or visibility_km (Koschmieder), not both or neither"),
            ));
        }
    };
    let phase = match (t.t.get("g"), t.t.get("phase")) {
        (Some(_), None) => {
            let g = in_range("g", t.num("g", None)?, -1.0, 1.0, true)?;
            PhaseFunction::henyey_greenstein(g).map_err(|e| ctx.err(&span, format!("{what}: {e}")))?
        }
        (None, Some(p)) => aerosol_phase(ctx, &Spanned::new(span.clone(), p.clone()), what)?,
        _ => {
            return Err(ctx.err(
                &span,
                format!("{what}: give either g (Henyey–Greenstein asymmetry) or phase = {{ type = \"two_term_hg\", w, g1, g2 }}, not both or neither"),
            ));
        }
    };
    Ok(Constituent {
        name: "aerosol",
        extinction: Extinction::Angstrom { alpha, beta },
        albedo,
        phase,
        profile: AirProfile::from_heights(earth, top_m, aerosol::profile(scale_height_m, top_m)),
    })
}

/// `albedo = { wavelength_nm = [...], value = [...] }` of the aerosol table `t`: ω(λ) linear
/// between the samples, constant beyond the ends ([`Albedo::spectral`]).
fn albedo_table(t: &Table, what: &str) -> R<Albedo> {
    let (nm, value) = t.wavelength_table("albedo", "{ wavelength_nm = [400, 700], value = [0.95, 0.9] }")?;
    Albedo::spectral(nm, value).map_err(|e| t.ctx.err(&t.span, format!("{what}: albedo: {e}")))
}

/// An aerosol's `phase`: `{ type = "hg", g }` or `{ type = "two_term_hg", w, g1, g2 }`.
fn aerosol_phase(ctx: &Ctx, v: &Spanned<toml::Value>, what: &str) -> R<PhaseFunction> {
    let pwhat = format!("{what}: phase");
    let kind = v.get_ref().get("type").and_then(toml::Value::as_str).unwrap_or("");
    let built = match kind {
        "hg" => {
            let t = Table::new(ctx, v, pwhat.clone(), &["type", "g"])?;
            PhaseFunction::henyey_greenstein(t.num("g", None)?)
        }
        "two_term_hg" => {
            let t = Table::new(ctx, v, pwhat.clone(), &["type", "w", "g1", "g2"])?;
            PhaseFunction::two_term_hg(t.num("w", None)?, t.num("g1", None)?, t.num("g2", None)?)
        }
        _ => {
            return Err(ctx.err(
                &v.span(),
                format!("{pwhat}: expected a table with type = \"hg\" (g) or \"two_term_hg\" (w, g1, g2)"),
            ));
        }
    };
    built.map_err(|e| ctx.err(&v.span(), format!("{pwhat}: {e}")))
}
