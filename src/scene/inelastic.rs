//! Inelastic media in a scene: `[[medium]] type = "ocean"` and the `inelastic = [...]` components
//! any medium may have.
//!
//! ```toml
//! [[medium]]
//! name = "sea"
//! type = "ocean"
//! chl_mg_m3 = 0.5              # chlorophyll a, mg m⁻³ (default 0.1)
//! cdom_a440_per_m = 0.05       # CDOM absorption at 440 nm, m⁻¹ (default 0)
//! cdom_slope_per_nm = 0.014    # its exponential slope S (default 0.014)
//! chl_yield = 0.02             # chlorophyll fluorescence quantum yield (0 = off)
//! cdom_yield = 0.01            # CDOM yield; omit for FA7's own Γ(λ'), 0 = off
//! raman = true                 # Raman scattering by water
//! particle_phase = "petzold"   # or { type = "hg", g = 0.924 }
//! # data_dir = "my_tables"     # optional: a folder of one's own tables; see below
//!
//! [[medium]]
//! name = "dye"
//! sigma_a = 0.05
//! sigma_s = 0.0
//! inelastic = [{ process = "fluorescence", sigma_a = { nm = [300, 400, 460], values = [2, 3, 0] },
//!                yield = 0.9, emission = { type = "gaussian", peak_nm = 520, sigma_nm = 20 },
//!                excitation_nm = [300, 460], accounting = "photon_number", phase = "isotropic" },
//!              { process = "raman", sigma_s = 2.7e-4, band = "walrafen", accounting = "energy" }]
//! ```
//!
//! A component's `sigma_a` (fluorescence) or `sigma_s` (Raman) adds to the medium's extinction.
//! `emission` is `{ type = "gaussian", peak_nm, sigma_nm }` or `{ type = "fa7", file }` (CDOM,
//! Hawes 1992; `file` defaults to morgana's built-in FA7 table, `yield` then defaults to
//! FA7's own Γ). A Raman `band` is "walrafen" or `{ shift_cm = 3357, fwhm_cm = .. }`.
//! `accounting` is "photon_number" (default for fluorescence: energy × λ'/λ) or "energy"
//! (default for Raman); see `src/media/inelastic/component.rs`.
//!
//! The ocean tables are morgana's built-in ones (`src/media/ocean/builtin.rs`, each citing its
//! source) unless the medium names `data_dir`: a folder (relative to the scene file) holding
//! files with the built-in tables' names and layout. A missing folder or file is an error
//! naming it. Nothing is read from outside the binary otherwise (no environment variable).

use super::media::{Table, phase};
use super::raw::RawMedium;
use super::spectrum_spec::{SpectrumLibrary, Use};
use crate::media::inelastic::{
    Accounting, BandTransfer, Component, Fa7, GaussianEmission, Process, RamanShift, Redistribution, Yield,
};
use crate::media::ocean::{self, OceanData, OceanParams, ParticlePhase};
use crate::media::{Medium, phase::PhaseFunction};
use crate::spectrum::Bands;
use crate::validate::present_fields;
use crate::validate::{Ctx, R};
use toml::{Spanned, Value};

const OCEAN_FIELDS: &[&str] = &[
    "chl_mg_m3",
    "cdom_a440_per_m",
    "cdom_slope_per_nm",
    "chl_yield",
    "cdom_yield",
    "raman",
    "particle_phase",
    "data_dir",
    "inelastic",
];

/// Rejects ocean-only fields on a medium without `type = "ocean"`.
pub fn reject_ocean_fields(ctx: &Ctx, m: &RawMedium, what: &str) -> R<()> {
    let present = present_fields!(m; chl_mg_m3, cdom_a440_per_m, cdom_slope_per_nm, chl_yield, cdom_yield, raman, particle_phase, data_dir);
    for (name, span) in present {
        if let Some(span) = span {
            return Err(ctx.err(&span, format!("{what}: field `{name}` is used only with type = \"ocean\"")));
        }
    }
    Ok(())
}

/// Where the ocean tables come from (see the module documentation).
pub fn data_dir(ctx: &Ctx, given: Option<&Spanned<String>>, what: &str) -> R<OceanData> {
    let Some(d) = given else { return Ok(OceanData::BuiltIn) };
    let dir = ctx.path(d);
    if !dir.is_dir() {
        return Err(ctx.err(
            &d.span(),
            format!(
                "{what}: data_dir \"{}\" is not a folder (resolved to {}); remove data_dir to use morgana's built-in ocean tables",
                d.get_ref(),
                dir.display()
            ),
        ));
    }
    Ok(OceanData::Folder(dir))
}

/// `[[medium]] type = "ocean"`.
pub fn ocean_medium(ctx: &Ctx, m: &RawMedium, kind: &Spanned<String>, name: &str, bands: &Bands) -> R<Medium> {
    let what = format!("medium \"{name}\"");
    let present = present_fields!(m; sigma_a, sigma_s, sigma_t, albedo, phase, density, chl_mg_m3, cdom_a440_per_m, cdom_slope_per_nm, chl_yield, cdom_yield, raman, particle_phase, data_dir, inelastic, atmosphere, rayleigh, co2_ppm, refraction, ozone_du, ozone, aerosol);
    ctx.only(&present, OCEAN_FIELDS, &format!("{what} (ocean)"))?;
    let span = kind.span();
    let data = data_dir(ctx, m.data_dir.as_ref(), &what)?;
    let mut p = OceanParams::new(data);
    let num = |v: &Option<Spanned<f64>>, field: &str, default: f64, hi: f64| -> R<f64> {
        v.as_ref().map_or(Ok(default), |x| ctx.number(x, &format!("{what}: {field}"), 0.0, hi, false))
    };
    p.chl_mg_m3 = num(&m.chl_mg_m3, "chl_mg_m3", p.chl_mg_m3, 1e3)?;
    p.cdom_a440_per_m = num(&m.cdom_a440_per_m, "cdom_a440_per_m", 0.0, 1e3)?;
    p.cdom_slope_per_nm = num(&m.cdom_slope_per_nm, "cdom_slope_per_nm", p.cdom_slope_per_nm, 1.0)?;
    p.chl_yield = num(&m.chl_yield, "chl_yield", p.chl_yield, 1.0)?;
    p.cdom_yield = match &m.cdom_yield {
        None => None,
        Some(y) => Some(ctx.number(y, &format!("{what}: cdom_yield"), 0.0, 1.0, false)?),
    };
    p.raman = m.raman.as_ref().is_none_or(|r| *r.get_ref());
    if let Some(pp) = &m.particle_phase {
        p.particle_phase = particle_phase(ctx, pp, &what)?;
    }
    ocean::sea_water(name, &p, (bands.min_nm, bands.max_nm)).map_err(|e| ctx.err(&span, format!("{what}: {e}")))
}

fn particle_phase(ctx: &Ctx, v: &Spanned<Value>, what: &str) -> R<ParticlePhase> {
    let span = v.span();
    match v.get_ref() {
        Value::String(s) if s == "petzold" => Ok(ParticlePhase::Petzold),
        Value::Table(_) => {
            let t = Table::new(ctx, v, format!("{what}: particle_phase"), &["type", "g"])?;
            match t.t.get("type").and_then(Value::as_str) {
                Some("hg") => Ok(ParticlePhase::HenyeyGreenstein(t.num("g", Some(0.924))?)),
                _ => Err(ctx.err(&span, format!("{what}: particle_phase table needs type = \"hg\" (and g)"))),
            }
        }
        _ => {
            Err(ctx.err(&span, format!("{what}: particle_phase must be \"petzold\" or {{ type = \"hg\", g = 0.924 }}")))
        }
    }
}

/// `inelastic = [ {...}, ... ]`.
pub fn components(
    ctx: &Ctx,
    lib: &SpectrumLibrary,
    v: &Spanned<Value>,
    what: &str,
    range: (f64, f64),
) -> R<Vec<Component>> {
    let span = v.span();
    let Some(list) = v.get_ref().as_array() else {
        return Err(ctx.err(&span, format!("{what}: inelastic must be an array of tables")));
    };
    list.iter()
        .enumerate()
        .map(|(i, c)| {
            component(ctx, lib, &Spanned::new(span.clone(), c.clone()), &format!("{what}: inelastic #{}", i + 1), range)
        })
        .collect()
}

const COMPONENT_KEYS: &[&str] =
    &["process", "name", "sigma_a", "sigma_s", "yield", "emission", "band", "excitation_nm", "accounting", "phase"];

fn component(ctx: &Ctx, lib: &SpectrumLibrary, v: &Spanned<Value>, what: &str, range: (f64, f64)) -> R<Component> {
    let span = v.span();
    let t = Table::new(ctx, v, what.to_string(), COMPONENT_KEYS)?;
    let get = |k: &str| t.t.get(k).map(|x| Spanned::new(span.clone(), x.clone()));
    let process = match t.t.get("process").and_then(Value::as_str) {
        Some("fluorescence") => Process::Fluorescence,
        Some("raman") => Process::Raman,
        _ => return Err(ctx.err(&span, format!("{what}: process must be \"fluorescence\" or \"raman\""))),
    };
    let (coef_key, wrong) = match process {
        Process::Fluorescence => ("sigma_a", ["sigma_s", "band"]),
        Process::Raman => ("sigma_s", ["sigma_a", "emission"]),
    };
    if let Some(k) = wrong.iter().find(|k| t.t.contains_key(**k)) {
        return Err(ctx.err(&span, format!("{what}: `{k}` is not used by process {process:?}")));
    }
    let coef = get(coef_key).ok_or_else(|| ctx.err(&span, format!("{what}: missing `{coef_key}` (m⁻¹)")))?;
    let coefficient = lib.parse(ctx, &coef, &format!("{what}: {coef_key}"), Use::Emission, range)?;
    let redistribution = match process {
        Process::Fluorescence => emission(ctx, &t, get("emission"), what)?,
        Process::Raman => raman_band(ctx, get("band"), what)?,
    };
    let quantum_yield = match (t.t.get("yield"), &redistribution) {
        (None, Redistribution::Fa7(_)) => Yield::FromRedistribution,
        (None, _) if process == Process::Raman => Yield::Constant(1.0),
        (None, _) => return Err(ctx.err(&span, format!("{what}: missing `yield` (the quantum yield Φ, 0 to 1)"))),
        (Some(_), _) => {
            let y = t.num("yield", None)?;
            if !(0.0..=1.0).contains(&y) {
                return Err(ctx.err(&span, format!("{what}: yield = {y} must be between 0 and 1")));
            }
            Yield::Constant(y)
        }
    };
    let excitation_nm = match t.t.get("excitation_nm").and_then(Value::as_array) {
        None if t.t.contains_key("excitation_nm") => {
            return Err(ctx.err(&span, format!("{what}: excitation_nm must be [min, max] in nm")));
        }
        None => match &redistribution {
            Redistribution::Fa7(f) => f.excitation_nm(),
            _ => (0.0, f64::INFINITY),
        },
        Some(a) => {
            let x: Vec<f64> =
                a.iter().filter_map(|v| v.as_float().or_else(|| v.as_integer().map(|i| i as f64))).collect();
            match x.as_slice() {
                [lo, hi] if lo < hi && lo.is_finite() && hi.is_finite() => (*lo, *hi),
                _ => {
                    return Err(ctx.err(&span, format!("{what}: excitation_nm must be [min, max] with min < max (nm)")));
                }
            }
        }
    };
    let accounting = match t.t.get("accounting").and_then(Value::as_str) {
        None if t.t.contains_key("accounting") => None,
        None => Some(if process == Process::Raman { Accounting::Energy } else { Accounting::PhotonNumber }),
        Some("photon_number") => Some(Accounting::PhotonNumber),
        Some("energy") => Some(Accounting::Energy),
        Some(_) => None,
    }
    .ok_or_else(|| ctx.err(&span, format!("{what}: accounting must be \"photon_number\" or \"energy\"")))?;
    let phase = match get("phase") {
        Some(p) => phase(ctx, lib, &p, what, range)?,
        None if process == Process::Raman => PhaseFunction::raman(),
        None => PhaseFunction::isotropic(),
    };
    let name = t.t.get("name").and_then(Value::as_str).map_or_else(
        || match process {
            Process::Fluorescence => "fluorescence".to_string(),
            Process::Raman => "Raman".to_string(),
        },
        str::to_string,
    );
    Ok(Component { name, process, coefficient, quantum_yield, excitation_nm, redistribution, phase, accounting })
}

fn emission(ctx: &Ctx, owner: &Table, v: Option<Spanned<Value>>, what: &str) -> R<Redistribution> {
    let span = owner.span.clone();
    let Some(v) = v else { return Err(ctx.err(&span, format!("{what}: fluorescence needs `emission`"))) };
    let ewhat = format!("{what}: emission");
    let kind = v.get_ref().get("type").and_then(Value::as_str).unwrap_or("").to_string();
    match kind.as_str() {
        "gaussian" => {
            let t = Table::new(ctx, &v, ewhat.clone(), &["type", "peak_nm", "sigma_nm"])?;
            GaussianEmission::new(t.num("peak_nm", None)?, t.num("sigma_nm", None)?)
                .map(Redistribution::Gaussian)
                .map_err(|e| ctx.err(&span, format!("{ewhat}: {e}")))
        }
        "fa7" => {
            let t = Table::new(ctx, &v, ewhat.clone(), &["type", "file"])?;
            let fa7 = match t.t.get("file").and_then(Value::as_str) {
                Some(f) => Fa7::from_csv(&ctx.dir.join(f)),
                None => OceanData::BuiltIn.fa7(),
            };
            fa7.map(|f| Redistribution::Fa7(Box::new(f))).map_err(|e| ctx.err(&span, format!("{ewhat}: {e}")))
        }
        _ => Err(ctx.err(&span, format!("{ewhat}: needs type = \"gaussian\" (peak_nm, sigma_nm) or \"fa7\" (file)"))),
    }
}

fn raman_band(ctx: &Ctx, v: Option<Spanned<Value>>, what: &str) -> R<Redistribution> {
    let Some(v) = v else { return Ok(Redistribution::Raman(RamanShift::walrafen())) };
    let span = v.span();
    match v.get_ref() {
        Value::String(s) if s == "walrafen" => Ok(Redistribution::Raman(RamanShift::walrafen())),
        Value::Table(_) => {
            let t = Table::new(ctx, &v, format!("{what}: band"), &["shift_cm", "fwhm_cm"])?;
            RamanShift::single(t.num("shift_cm", Some(3357.0))?, t.positive("fwhm_cm", None)?)
                .map(Redistribution::Raman)
                .map_err(|e| ctx.err(&span, format!("{what}: {e}")))
        }
        _ => Err(ctx.err(&span, format!("{what}: band must be \"walrafen\" or {{ shift_cm = 3357, fwhm_cm = .. }}"))),
    }
}

/// Builds the volume-map band table of a medium with inelastic components.
pub fn finish(m: &mut Medium, bands: &Bands) {
    if m.inelastic.is_empty() {
        return;
    }
    let t = BandTransfer::new(&m.inelastic, &|l| m.sigma_t(l), bands);
    m.inelastic.transfer = Some(t);
}
