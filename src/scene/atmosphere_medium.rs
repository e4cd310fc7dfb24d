//! `[[medium]] type = "atmosphere"`: the air of an atmosphere profile, scattering light.
//!
//! ```toml
//! [[medium]]
//! name = "air"
//! type = "atmosphere"
//! atmosphere = "usa76"     # a built-in atmosphere, or { file = "my_atmosphere.toml" } (default usa76)
//! rayleigh = true          # Rayleigh scattering by dry air, Bodhaine et al. 1999 (default true)
//! co2_ppm = 360            # CO₂ of the cross-section and King factor (default 360, Bodhaine's)
//! refraction = false       # light also curves along the atmosphere's refractive index (default false)
//! ozone_du = 300           # ozone column, Dobson units (default: no ozone)
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
//!
//! With `ozone_du` or `aerosol` the medium is an atmosphere of constituents (air, ozone,
//! aerosols; [`crate::media::constituents`]), built in `atmosphere_constituents.rs`; without
//! them it is the air alone, as before.

use super::raw::RawMedium;
use crate::atmosphere::{Atmosphere, Earth};
use crate::media::density::{AirProfile, Density};
use crate::media::phase::PhaseFunction;
use crate::media::rayleigh_air::{self, BODHAINE_CO2_PPM, N_STANDARD_PER_M3};
use crate::media::refractive_index::IndexField;
use crate::media::{Coefficients, Medium};
use crate::spectrum::Bands;
use crate::validate::present_fields;
use crate::validate::{Ctx, R};
use toml::{Spanned, Value};

const ATMOSPHERE_FIELDS: &[&str] = &["atmosphere", "rayleigh", "co2_ppm", "refraction", "ozone_du", "aerosol"];

/// Rejects atmosphere-only fields on a medium without `type = "atmosphere"`.
pub fn reject_atmosphere_fields(ctx: &Ctx, m: &RawMedium, what: &str) -> R<()> {
    for (name, span) in present_fields!(m; atmosphere, rayleigh, co2_ppm, refraction, ozone_du, aerosol) {
        if let Some(span) = span {
            return Err(ctx.err(&span, format!("{what}: field `{name}` is used only with type = \"atmosphere\"")));
        }
    }
    Ok(())
}

/// `[[medium]] type = "atmosphere"` (see the module docs).
pub fn atmosphere_medium(
    ctx: &Ctx,
    m: &RawMedium,
    kind: &Spanned<String>,
    name: &str,
    bands: &Bands,
    earth: &(Earth, bool),
) -> R<Medium> {
    let what = format!("medium \"{name}\"");
    let present = present_fields!(m; sigma_a, sigma_s, sigma_t, albedo, phase, density, index, inelastic, chl_mg_m3, cdom_a440_per_m, cdom_slope_per_nm, chl_yield, cdom_yield, raman, particle_phase, data_dir, atmosphere, rayleigh, co2_ppm, refraction, ozone_du, aerosol);
    ctx.only(&present, ATMOSPHERE_FIELDS, &format!("{what} (atmosphere)"))?;
    let atmosphere = profile(ctx, m.atmosphere.as_ref(), kind, &what)?;
    let atmosphere = if earth.1 { atmosphere.with_earth(earth.0) } else { atmosphere };
    let co2_ppm = match &m.co2_ppm {
        None => BODHAINE_CO2_PPM,
        Some(c) => ctx.number(c, &format!("{what}: co2_ppm"), 0.0, 10_000.0, false)?,
    };
    let rayleigh = m.rayleigh.as_ref().is_none_or(|r| *r.get_ref());
    let index = m
        .refraction
        .as_ref()
        .is_some_and(|r| *r.get_ref())
        .then(|| IndexField::Atmosphere(Box::new(atmosphere.clone())));
    if m.ozone_du.is_some() || m.aerosol.is_some() {
        let span = m.rayleigh.as_ref().map_or(kind.span(), |r| r.span());
        if rayleigh {
            check_range(ctx, span, &what, bands)?;
        }
        let air = super::atmosphere_constituents::Air { atmosphere: &atmosphere, rayleigh, co2_ppm, kind, bands };
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
    let (coefficients, phase, density) = if rayleigh {
        check_range(ctx, m.rayleigh.as_ref().map_or(kind.span(), |r| r.span()), &what, bands)?;
        let density = AirProfile::new(&atmosphere, atmosphere.earth, N_STANDARD_PER_M3)
            .map_err(|e| ctx.err(&m.atmosphere.as_ref().map_or(kind.span(), |a| a.span()), format!("{what}: {e}")))?;
        let mid_nm = 0.5 * (bands.min_nm + bands.max_nm);
        let rho = rayleigh_air::depolarisation(mid_nm, co2_ppm);
        let phase =
            PhaseFunction::rayleigh_depolarised(rho).map_err(|e| ctx.err(&kind.span(), format!("{what}: {e}")))?;
        (Coefficients::RayleighAir { co2_ppm }, phase, Density::AirProfile(density))
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
