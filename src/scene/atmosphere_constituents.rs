//! `ozone_du` and `aerosol` of a `[[medium]] type = "atmosphere"`: the atmosphere of
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
//! `albedo = { wavelength_nm = [400, 550, 700], value = [0.93, 0.91, 0.89] }` gives ω(λ) as a
//! table: at least two samples, wavelengths strictly increasing, values in [0, 1]; linear
//! between the samples and constant beyond the ends ([`crate::media::albedo`]).

use super::media::Table;
use super::raw::RawMedium;
use crate::atmosphere::Atmosphere;
use crate::media::albedo::Albedo;
use crate::media::constituents::{Constituent, Constituents, Extinction};
use crate::media::density::AirProfile;
use crate::media::phase::PhaseFunction;
use crate::media::rayleigh_air::{self, N_STANDARD_PER_M3};
use crate::media::{aerosol, ozone};
use crate::spectrum::Bands;
use crate::validate::{Ctx, R};
use toml::Spanned;

/// The air the constituents are added to.
pub struct Air<'a> {
    /// The atmosphere's profile, on the scene's Earth.
    pub atmosphere: &'a Atmosphere,
    /// Whether the air scatters (Rayleigh).
    pub rayleigh: bool,
    /// CO₂ of the Rayleigh cross-section, ppm.
    pub co2_ppm: f64,
    /// The medium's `type` (for spans of messages about the whole medium).
    pub kind: &'a Spanned<String>,
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
    if air.rayleigh {
        let mid_nm = 0.5 * (air.bands.min_nm + air.bands.max_nm);
        let rho = rayleigh_air::depolarisation(mid_nm, air.co2_ppm);
        let phase =
            PhaseFunction::rayleigh_depolarised(rho).map_err(|e| ctx.err(&air.kind.span(), format!("{what}: {e}")))?;
        list.push(Constituent {
            name: "air",
            extinction: Extinction::Rayleigh { co2_ppm: air.co2_ppm },
            albedo: Albedo::Constant(1.0),
            phase,
            profile: air_profile.clone(),
        });
    }
    if let Some(du) = &m.ozone_du {
        let du = ctx.number(du, &format!("{what}: ozone_du (Dobson units)"), 0.0, 1000.0, false)?;
        list.push(Constituent {
            name: "ozone",
            extinction: Extinction::CrossSection(ozone::cross_section_m2()),
            albedo: Albedo::Constant(0.0),
            phase: PhaseFunction::isotropic(),
            profile: AirProfile::from_heights(earth, top_m, ozone::profile(du, top_m)),
        });
    }
    if let Some(v) = &m.aerosol {
        let rayleigh_550 = if air.rayleigh {
            rayleigh_air::cross_section_m2(550.0, air.co2_ppm) * N_STANDARD_PER_M3 * air_profile.at_height(0.0)
        } else {
            0.0
        };
        list.push(aerosols(ctx, v, &format!("{what}: aerosol"), (earth, top_m), rayleigh_550)?);
    }
    let phase = list.iter().find(|c| c.albedo.scatters()).map_or(PhaseFunction::isotropic(), |c| c.phase.clone());
    let constituents = Constituents::new(list).map_err(|e| ctx.err(&air.kind.span(), format!("{what}: {e}")))?;
    Ok((constituents, phase))
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
    let (ctx, span) = (t.ctx, &t.span);
    let awhat = format!("{what}: albedo");
    let Some(v) = t.t.get("albedo") else { return Err(ctx.err(span, format!("{what}: missing `albedo`"))) };
    let v = Spanned::new(span.clone(), v.clone());
    let table = Table::new(ctx, &v, awhat.clone(), &["wavelength_nm", "value"])?;
    let list = |key: &str| -> R<Vec<f64>> {
        let Some(x) = table.t.get(key) else {
            return Err(ctx.err(
                span,
                format!(
                    "{awhat}: missing `{key}`; give albedo = {{ wavelength_nm = [400, 700], value = [0.95, 0.9] }}"
                ),
            ));
        };
        let numbers: Option<Vec<f64>> = x
            .as_array()
            .and_then(|a| a.iter().map(|x| x.as_float().or_else(|| x.as_integer().map(|i| i as f64))).collect());
        numbers.ok_or_else(|| ctx.err(span, format!("{awhat}: `{key}` must be an array of numbers")))
    };
    let (nm, value) = (list("wavelength_nm")?, list("value")?);
    Albedo::spectral(nm, value).map_err(|e| ctx.err(span, format!("{awhat}: {e}")))
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
