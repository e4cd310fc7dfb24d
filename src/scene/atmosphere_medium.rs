//! `[[medium]] type = "atmosphere"`: the air of an atmosphere profile, scattering light.
//!
//! ```toml
//! [[medium]]
//! name = "air"
//! type = "atmosphere"
//! atmosphere = "usa76"     # a built-in atmosphere, or { file = "my_atmosphere.toml" } (default usa76)
//! rayleigh = true          # Rayleigh scattering by dry air, Bodhaine et al. 1999 (default true),
//!                          # or { cross_section_cm2 = <tabulated spectrum>, depolarisation = ρ }
//! co2_ppm = 360            # CO₂ of the cross-section and King factor (default 360, Bodhaine's)
//! refraction = false       # light also curves along the atmosphere's refractive index (default false)
//! ozone_du = 300           # ozone column, Dobson units (default: no ozone), or
//!                          # ozone = { profile, interpolation, cross_section_cm2, column_du }
//! aerosol = { angstrom_beta = 0.05, angstrom_alpha = 1.3, scale_height_m = 1200, albedo = 0.95, g = 0.7 }
//!                          # or visibility_km = 23 instead of angstrom_beta (default: no aerosols)
//! ```
//!
//! The scattering coefficient is σ_s(λ, x) = σ(λ) N(h(x)), with σ the Rayleigh cross-section
//! per molecule ([`crate::media::rayleigh_air`]) and N = P N_A/(R* T) the number density of the
//! atmosphere's profile at the height h of x ([`AirProfile`]), from the ground to the
//! atmosphere's top (86 km for USA76). Heights are measured on the `[world] earth` when the scene
//! gives one, else on the atmosphere's own (USA76: the spherical Earth of radius 6371 km centred
//! at (0, −R, 0)). The phase function is Rayleigh's with the depolarisation ratio ρ of Bodhaine's
//! King factor at the middle of the scene's wavelength range (see the book's page "The sky").
//! A `rayleigh` table replaces σ(λ) by the scene's (read as a power law between its samples,
//! [`PowerLawTable`]) and/or ρ by the scene's, as benchmarks give them.
//!
//! With `ozone_du`, `ozone` or `aerosol` the medium is an atmosphere of constituents (air, ozone,
//! aerosols; [`crate::media::constituents`]), built in `atmosphere_constituents.rs`; without
//! them it is the air alone, as before.

use super::raw::RawMedium;
use super::spectrum_spec::{SpectrumLibrary, Use};
use crate::atmosphere::{Atmosphere, Earth};
use crate::media::density::{AirProfile, Density};
use crate::media::phase::PhaseFunction;
use crate::media::rayleigh_air::{self, BODHAINE_CO2_PPM, CrossSection, N_STANDARD_PER_M3};
use crate::media::refractive_index::IndexField;
use crate::media::{Coefficients, Medium};
use crate::spectrum::{Bands, PowerLawTable, Spectrum};
use crate::validate::present_fields;
use crate::validate::{Ctx, R};
use std::ops::Range;
use toml::{Spanned, Value};

const ATMOSPHERE_FIELDS: &[&str] = &["atmosphere", "rayleigh", "co2_ppm", "refraction", "ozone_du", "ozone", "aerosol"];

/// Rejects atmosphere-only fields on a medium without `type = "atmosphere"`.
pub fn reject_atmosphere_fields(ctx: &Ctx, m: &RawMedium, what: &str) -> R<()> {
    for (name, span) in present_fields!(m; atmosphere, rayleigh, co2_ppm, refraction, ozone_du, ozone, aerosol) {
        if let Some(span) = span {
            return Err(ctx.err(&span, format!("{what}: field `{name}` is used only with type = \"atmosphere\"")));
        }
    }
    Ok(())
}

/// `[[medium]] type = "atmosphere"` (see the module docs).
pub fn atmosphere_medium(
    ctx: &Ctx,
    lib: &SpectrumLibrary,
    m: &RawMedium,
    kind: &Spanned<String>,
    name: &str,
    bands: &Bands,
    earth: &(Earth, bool),
) -> R<Medium> {
    let what = format!("medium \"{name}\"");
    let present = present_fields!(m; sigma_a, sigma_s, sigma_t, albedo, phase, density, index, inelastic, chl_mg_m3, cdom_a440_per_m, cdom_slope_per_nm, chl_yield, cdom_yield, raman, particle_phase, data_dir, atmosphere, rayleigh, co2_ppm, refraction, ozone_du, ozone, aerosol);
    ctx.only(&present, ATMOSPHERE_FIELDS, &format!("{what} (atmosphere)"))?;
    let atmosphere = profile(ctx, m.atmosphere.as_ref(), kind, &what)?;
    let atmosphere = if earth.1 { atmosphere.with_earth(earth.0) } else { atmosphere };
    let co2_ppm = match &m.co2_ppm {
        None => BODHAINE_CO2_PPM,
        Some(c) => ctx.number(c, &format!("{what}: co2_ppm"), 0.0, 10_000.0, false)?,
    };
    let rayleigh = rayleigh(ctx, lib, m, kind, &what, co2_ppm, bands)?;
    let index = m
        .refraction
        .as_ref()
        .is_some_and(|r| *r.get_ref())
        .then(|| IndexField::Atmosphere(Box::new(atmosphere.clone())));
    if m.ozone_du.is_some() || m.ozone.is_some() || m.aerosol.is_some() {
        let air = super::atmosphere_constituents::Air {
            atmosphere: &atmosphere,
            rayleigh: rayleigh.as_ref(),
            kind,
            lib,
            bands,
        };
        let (constituents, phase) = super::atmosphere_constituents::constituents(ctx, m, &air, &what)?;
        return Ok(Medium {
            name: name.to_string(),
            coefficients: Coefficients::Constituents(constituents),
            phase,
            density: Density::Uniform,
            index,
            inelastic: crate::media::inelastic::Inelastic::none(),
        });
    }
    let (coefficients, phase, density) = if let Some(rayleigh) = rayleigh {
        let density = AirProfile::new(&atmosphere, atmosphere.earth, N_STANDARD_PER_M3)
            .map_err(|e| ctx.err(&m.atmosphere.as_ref().map_or(kind.span(), |a| a.span()), format!("{what}: {e}")))?;
        let phase = PhaseFunction::rayleigh_depolarised(rayleigh.depolarisation)
            .map_err(|e| ctx.err(&kind.span(), format!("{what}: {e}")))?;
        (Coefficients::RayleighAir(rayleigh.cross_section), phase, Density::AirProfile(density))
    } else {
        let zero = crate::spectrum::Spectrum::Constant(0.0);
        (
            Coefficients::AbsorptionScattering { sigma_a: zero.clone(), sigma_s: zero },
            PhaseFunction::isotropic(),
            Density::Uniform,
        )
    };
    Ok(Medium {
        name: name.to_string(),
        coefficients,
        phase,
        density,
        index,
        inelastic: crate::media::inelastic::Inelastic::none(),
    })
}

/// `atmosphere = "usa76"` (a built-in name) or `{ file = "…" }` / `{ name = "…" }`; default usa76.
fn profile(ctx: &Ctx, v: Option<&Spanned<Value>>, kind: &Spanned<String>, what: &str) -> R<Atmosphere> {
    let awhat = format!("{what}: atmosphere");
    let Some(v) = v else { return super::refractive_index::atmosphere(ctx, &kind.span(), None, Some("usa76"), &awhat) };
    let span = v.span();
    match v.get_ref() {
        Value::String(n) => super::refractive_index::atmosphere(ctx, &span, None, Some(n), &awhat),
        Value::Table(_) => {
            let t = super::media::Table::new(ctx, v, awhat.clone(), &["file", "name"])?;
            let (file, name) = (t.t.get("file").and_then(Value::as_str), t.t.get("name").and_then(Value::as_str));
            super::refractive_index::atmosphere(ctx, &span, file, name, &awhat)
        }
        _ => {
            Err(ctx
                .err(&span, format!("{awhat}: give a built-in name (\"usa76\") or {{ file = \"atmosphere.toml\" }}")))
        }
    }
}

/// The air's Rayleigh scattering as a scene asks for it.
pub struct Rayleigh {
    /// σ(λ) per molecule.
    pub cross_section: CrossSection,
    /// The depolarisation ratio ρ of the phase function.
    pub depolarisation: f64,
}

/// `rayleigh = true | false | { cross_section_cm2 = <tabulated spectrum>, depolarisation = ρ }`
/// (default true); `None` where the air does not scatter.
fn rayleigh(
    ctx: &Ctx,
    lib: &SpectrumLibrary,
    m: &RawMedium,
    kind: &Spanned<String>,
    what: &str,
    co2_ppm: f64,
    bands: &Bands,
) -> R<Option<Rayleigh>> {
    let Some(v) = &m.rayleigh else { return bodhaine(ctx, kind.span(), what, co2_ppm, bands).map(Some) };
    match v.get_ref() {
        Value::Boolean(false) => Ok(None),
        Value::Boolean(true) => bodhaine(ctx, v.span(), what, co2_ppm, bands).map(Some),
        Value::Table(_) => rayleigh_table(ctx, lib, m, v, what, co2_ppm, bands).map(Some),
        _ => Err(ctx.err(
            &v.span(),
            format!("{what}: rayleigh: give true, false or {{ cross_section_cm2 = {{ nm = [...], values = [...] }}, depolarisation = ρ }}"),
        )),
    }
}

/// Bodhaine's σ(λ) and the depolarisation of his King factor at the middle of the scene's
/// wavelengths, which must lie where they are known.
fn bodhaine(ctx: &Ctx, span: Range<usize>, what: &str, co2_ppm: f64, bands: &Bands) -> R<Rayleigh> {
    check_range(ctx, span, what, bands)?;
    let depolarisation = rayleigh_air::depolarisation(0.5 * (bands.min_nm + bands.max_nm), co2_ppm);
    Ok(Rayleigh { cross_section: CrossSection::Bodhaine { co2_ppm }, depolarisation })
}

/// `rayleigh = { cross_section_cm2, depolarisation }`: the scene's σ(λ) and/or ρ, Bodhaine's
/// for the one not given.
fn rayleigh_table(
    ctx: &Ctx,
    lib: &SpectrumLibrary,
    m: &RawMedium,
    v: &Spanned<Value>,
    what: &str,
    co2_ppm: f64,
    bands: &Bands,
) -> R<Rayleigh> {
    let rwhat = format!("{what}: rayleigh");
    let t = super::media::Table::new(ctx, v, rwhat.clone(), &["cross_section_cm2", "depolarisation"])?;
    let (given_sigma, given_rho) = (t.t.contains_key("cross_section_cm2"), t.t.contains_key("depolarisation"));
    let cross_section = match given_sigma {
        true => cross_section_table(&t, lib, bands)?,
        false => {
            check_range(ctx, v.span(), what, bands)?;
            CrossSection::Bodhaine { co2_ppm }
        }
    };
    let mid_nm = 0.5 * (bands.min_nm + bands.max_nm);
    let (lo, hi) = rayleigh_air::RANGE_NM;
    let depolarisation = match given_rho {
        true => t.num("depolarisation", None)?,
        false if (lo..=hi).contains(&mid_nm) => rayleigh_air::depolarisation(mid_nm, co2_ppm),
        false => {
            let e = format!(
                "{rwhat}: give `depolarisation`: its default, from Bodhaine's King factor, is known from {lo} to {hi} nm and the scene's wavelengths centre on {mid_nm} nm"
            );
            return Err(ctx.err(&v.span(), e));
        }
    };
    if !(0.0..=0.5).contains(&depolarisation) {
        let e = format!("{rwhat}: depolarisation = {depolarisation} must lie in [0, 0.5] (air: about 0.03)");
        return Err(ctx.err(&v.span(), e));
    }
    if let (Some(c), true, true) = (&m.co2_ppm, given_sigma, given_rho) {
        let e = format!(
            "{what}: co2_ppm changes nothing when rayleigh gives both cross_section_cm2 and depolarisation: remove it"
        );
        return Err(ctx.err(&c.span(), e));
    }
    Ok(Rayleigh { cross_section, depolarisation })
}

/// `cross_section_cm2` of the `rayleigh` table `t`: a tabulated spectrum (`{ nm = [...],
/// values = [...] }`, `{ file = "..." }` or a `[spectra]` name) of σ(λ) in cm² per molecule,
/// covering the scene's wavelengths, read as a power law between its samples.
fn cross_section_table(t: &super::media::Table, lib: &SpectrumLibrary, bands: &Bands) -> R<CrossSection> {
    let what = format!("{}: cross_section_cm2", t.what);
    let Some(v) = t.t.get("cross_section_cm2") else { return Err(t.ctx.err(&t.span, format!("{what}: missing"))) };
    let spectrum =
        lib.parse(t.ctx, &Spanned::new(t.span.clone(), v.clone()), &what, Use::Emission, (bands.min_nm, bands.max_nm))?;
    let samples = |s: &Spectrum, k: f64| match s {
        Spectrum::Tabulated(tab) => {
            Some((tab.samples().0.to_vec(), tab.samples().1.iter().map(|y| y * k).collect::<Vec<f64>>()))
        }
        _ => None,
    };
    let table = match &spectrum {
        Spectrum::Scaled(k, s) => samples(s, *k),
        s => samples(s, 1.0),
    };
    let Some((nm, cm2)) = table else {
        return Err(t.ctx.err(&t.span, format!("{what}: give a table, {{ nm = [...], values = [...] }} or {{ file = \"sigma.csv\" }}: it is read as a power law between its samples")));
    };
    let m2: Vec<f64> = cm2.iter().map(|c| c * 1e-4).collect();
    PowerLawTable::new(&nm, &m2).map(CrossSection::Table).map_err(|e| t.ctx.err(&t.span, format!("{what}: {e}")))
}

/// The scene's wavelengths must lie where the refractive-index formula of the cross-section holds.
fn check_range(ctx: &Ctx, span: std::ops::Range<usize>, what: &str, bands: &Bands) -> R<()> {
    let (lo, hi) = rayleigh_air::RANGE_NM;
    if bands.min_nm >= lo && bands.max_nm <= hi {
        return Ok(());
    }
    Err(ctx.err(
        &span,
        format!(
            "{what}: Rayleigh scattering of air is known from {lo} to {hi} nm (Peck & Reeder's refractive index); \
             the scene simulates {} to {} nm: narrow [output] min_nm and max_nm",
            bands.min_nm, bands.max_nm
        ),
    ))
}
