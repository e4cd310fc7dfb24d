//! `[[light]] type = "luminaire"`: a light from a photometric file.
//!
//! ```toml
//! [[light]]
//! name = "desk lamp"
//! type = "luminaire"
//! file = "../luminaires/office_linear_led.ldt"  # relative to the scene
//! # .ies (LM-63), .ldt (EULUMDAT), .xml (IES TM-33-18/-23) or .gldf; for a GLDF with several
//! # variants, variant = "id" chooses one (else the first)
//! position = [1.0, 2.8, 1.5]   # the photometric centre, m
//! # orientation: nothing (hanging: nadir −Y, C0 +X), or an aim —
//! # direction = [0, -1, 0.2] or look_at = [x, y, z], with optional c0_toward = [1, 0, 0] —
//! # or Euler angles rotation_deg = [about X, then about Y, then about Z] (see luminaire::Placement)
//! cct_k = 4000                 # black-body lamp spectrum; or spectrum = <any emission spectrum>;
//!                              # with neither, the file's own spectrum (TM-33, GLDF) if it has one
//! flux_scale = 1.0             # optional: multiplies the file's intensities (dimming, maintenance)
//! emitter = "point"            # or "opening": photons start over the file's luminous opening
//! ```
//!
//! The level comes from the file (its candela values, in lumens); `power_w` and `scale` are not
//! used. Watts follow from the spectrum (see [`crate::luminaire::per_candela`]): the file's
//! lumens are those of the whole visible spectrum, so a scene whose wavelength range cuts part of
//! it carries only that part's watts, and a note says how much of the luminous flux is inside.
//!
//! The lamp spectrum: the scene's `spectrum` or `cct_k` when given (a note says it overrides a
//! spectrum the file carries), else the file's emission spectrum (TM-33 `SpectralData`, GLDF
//! `Spectrum`; a note names it), else an error asking for one.

use super::raw::RawLight;
use super::spectrum_spec::{SpectrumLibrary, Use};
use crate::light::{Light, LightSpectrum, LuminaireLight};
use crate::luminaire::{self, Opening, Photometry, Placement, WebSampler, luminous_fraction_in, per_candela};
use crate::spectrum::{Bands, Spectrum};
use crate::validate::{Ctx, R};
use std::ops::Range;
use std::sync::Arc;
use toml::Spanned;

/// The fields a luminaire light may have.
pub const FIELDS: &[&str] = &[
    "position",
    "direction",
    "look_at",
    "c0_toward",
    "rotation_deg",
    "file",
    "cct_k",
    "flux_scale",
    "emitter",
    "variant",
];

/// Below this fraction of the lumens inside the scene's wavelength range, a note says so.
const RANGE_NOTE_FRACTION: f64 = 0.99;

pub fn luminaire(
    ctx: &Ctx,
    lib: &SpectrumLibrary,
    l: &RawLight,
    span: &Range<usize>,
    what: &str,
    bands: &Bands,
) -> R<(Light, Vec<String>)> {
    let file = ctx.require(&l.file, "file", span, what)?;
    let photometry = read_file(ctx, file, l.variant.as_ref(), what)?;
    let position = ctx.vec3(ctx.require(&l.position, "position", span, what)?, "position")?;
    let placement = placement(ctx, l, span, what, position)?;
    let (shape, spectrum_note) = lamp_spectrum(ctx, lib, l, span, what, bands, &photometry, file.get_ref())?;
    let per_cd = per_candela(&shape).ok_or_else(|| {
        ctx.err(span, format!("{what}: the lamp spectrum has nothing visible (360–830 nm) to carry lumens"))
    })?;
    let emission = LightSpectrum::new(per_cd, bands.min_nm, bands.max_nm).ok_or_else(|| {
        ctx.err(span, format!("{what}: the lamp spectrum emits nothing within {}–{} nm", bands.min_nm, bands.max_nm))
    })?;
    let flux_scale = match &l.flux_scale {
        Some(v) => ctx.number(v, "flux_scale", 0.0, f64::INFINITY, true)?,
        None => 1.0,
    };
    let tilt_factor = photometry.tilt.as_ref().map_or(1.0, |t| t.factor(placement.tilt_deg()));
    let opening = emitter(ctx, l, what, &photometry)?;
    let mut notes = file_notes(&photometry, what, file.get_ref());
    notes.extend(spectrum_note);
    let fraction = luminous_fraction_in(&shape, bands.min_nm, bands.max_nm);
    if fraction < RANGE_NOTE_FRACTION {
        notes.push(format!(
            "{what}: the scene's {}–{} nm carry {:.1}% of the luminaire's lumens; its watts are those of that part",
            bands.min_nm,
            bands.max_nm,
            100.0 * fraction
        ));
    }
    let web = photometry.web;
    let sampler = WebSampler::new(&web)
        .ok_or_else(|| ctx.err(&file.span(), format!("{what}: the luminaire file's intensities are all zero")))?;
    let light = LuminaireLight {
        web: Arc::new(web),
        sampler: Arc::new(sampler),
        placement,
        opening,
        intensity_scale: flux_scale * tilt_factor,
        emission,
    };
    Ok((Light::Luminaire(light), notes))
}

/// Reads the file; a missing file is an error at the scene's `file` line, a malformed one at the
/// luminaire file's line (naming the light and the scene line).
fn read_file(ctx: &Ctx, file: &Spanned<String>, variant: Option<&Spanned<String>>, what: &str) -> R<Photometry> {
    let path = ctx.path(file);
    if !path.is_file() {
        return Err(ctx.err(
            &file.span(),
            format!(
                "{what}: luminaire file {} does not exist (relative paths start at the scene file's folder)",
                path.display()
            ),
        ));
    }
    luminaire::load_file_variant(&path, variant.map(|v| v.get_ref().as_str()))
        .map_err(|e| ctx.in_named_file(e, &file.span(), what, "luminaire"))
}

fn placement(ctx: &Ctx, l: &RawLight, span: &Range<usize>, what: &str, position: glam::DVec3) -> R<Placement> {
    let c0 = l.c0_toward.as_ref().map(|v| ctx.direction(v, "c0_toward")).transpose()?;
    let nadir = match (&l.direction, &l.look_at) {
        (Some(_), Some(_)) => return Err(ctx.err(span, format!("{what}: give direction or look_at, not both"))),
        (Some(d), None) => Some(ctx.direction(d, "direction")?),
        (None, Some(t)) => {
            let d = ctx.vec3(t, "look_at")? - position;
            if d.length_squared() == 0.0 {
                return Err(ctx.err(&t.span(), format!("{what}: look_at equals position")));
            }
            Some(d.normalize())
        }
        (None, None) => None,
    };
    match (nadir, &l.rotation_deg) {
        (Some(_), Some(r)) => Err(ctx.err(
            &r.span(),
            format!("{what}: give an aim (direction or look_at, with c0_toward) or rotation_deg, not both"),
        )),
        (Some(n), None) => Placement::aimed(position, n, c0).map_err(|e| ctx.err(span, format!("{what}: {e}"))),
        (None, r) => {
            if let Some(c) = &l.c0_toward {
                return Err(ctx.err(&c.span(), format!("{what}: c0_toward needs an aim (direction or look_at)")));
            }
            let angles = match r {
                Some(r) => ctx.vec3(r, "rotation_deg")?.to_array(),
                None => [0.0; 3],
            };
            Ok(Placement::rotated(position, angles))
        }
    }
}

/// The lamp's relative spectrum: `spectrum` or `cct_k` (a black body), at most one, else the
/// file's own; with a note saying which when the file has one.
#[allow(clippy::too_many_arguments)]
fn lamp_spectrum(
    ctx: &Ctx,
    lib: &SpectrumLibrary,
    l: &RawLight,
    span: &Range<usize>,
    what: &str,
    bands: &Bands,
    p: &Photometry,
    file: &str,
) -> R<(Spectrum, Option<String>)> {
    let overrides = |key: &str| {
        p.spectrum
            .as_ref()
            .map(|s| format!("{what}: the scene's {key} overrides the spectrum in {file} ({})", s.describe()))
    };
    match (&l.spectrum, &l.cct_k, &p.spectrum) {
        (Some(s), None, _) => {
            let s = lib.parse(ctx, s, &format!("{what}: spectrum"), Use::Emission, (bands.min_nm, bands.max_nm))?;
            Ok((s, overrides("spectrum")))
        }
        (None, Some(t), _) => {
            let temperature_k = ctx.number(t, "cct_k", 0.0, 1.0e6, true)?;
            Ok((Spectrum::Blackbody { temperature_k }, overrides("cct_k")))
        }
        (None, None, Some(s)) => {
            let (lo, hi) = s.domain_nm();
            let cut = if lo > bands.min_nm || hi < bands.max_nm {
                format!("; it spans {lo}–{hi} nm, so the scene's {}–{} nm get no light outside that", bands.min_nm, bands.max_nm)
            } else {
                String::new()
            };
            Ok((s.spectrum(), Some(format!("{what}: emission spectrum from {file}: {}{cut}", s.describe()))))
        }
        (Some(_), Some(_), _) => Err(ctx.err(span, format!("{what}: give spectrum or cct_k for the lamp's colour, not both"))),
        (None, None, None) => Err(ctx.err(
            span,
            format!(
                "{what}: give exactly one of spectrum or cct_k (a black body of that temperature) for the lamp's colour; the luminaire file carries no spectrum"
            ),
        )),
    }
}

/// Where photons start: the photometric centre, or the file's luminous opening.
fn emitter(ctx: &Ctx, l: &RawLight, what: &str, p: &Photometry) -> R<Opening> {
    let Some(e) = &l.emitter else {
        return Ok(Opening::POINT);
    };
    match ctx.choice(e, &format!("{what}: emitter"), &["point", "opening"])? {
        "opening" if p.opening.is_point() => Err(ctx.err(
            &e.span(),
            format!("{what}: emitter = \"opening\" but the file gives no luminous opening (all dimensions 0)"),
        )),
        "opening" => Ok(p.opening),
        _ => Ok(Opening::POINT),
    }
}

/// Notes about the file: what its reader tolerated, and a stated flux its table disagrees with.
fn file_notes(p: &Photometry, what: &str, file: &str) -> Vec<String> {
    let mut notes: Vec<String> = p.notes.iter().map(|n| format!("{what}: {file}: {n}")).collect();
    if let (Some(m), Some(stated)) = (p.flux_mismatch(), p.stated_flux_lm)
        && m.abs() > 0.01
    {
        notes.push(format!(
            "{what}: {file}: the intensity table integrates to {:.1} lm but the file states {stated:.1} lm ({:+.1}%); photons carry the table's flux",
            p.flux_lm(),
            100.0 * m
        ));
    }
    notes
}
