//! `[[light]]` records → [`Light`]s.
//!
//! Each light has a `spectrum` and exactly one way to set its absolute level:
//! - `power_w`: radiant flux within the scene's wavelength range; the spectrum gives the shape.
//! - `scale`: the spectrum times `scale` is the absolute spectral radiance (area,
//!   W m⁻² sr⁻¹ nm⁻¹), intensity (point, spot: W sr⁻¹ nm⁻¹) or irradiance normal to the beam
//!   (directional: W m⁻² nm⁻¹).
//! - `irradiance_w_m2` (directional and sun): irradiance normal to the beam within the range.
//!
//! A `sun` is a directional light of angular diameter `angular_diameter_deg` (default 0.533°),
//! with the extraterrestrial solar spectrum (`spectrum = "solar"`, `scale = 1`) unless given,
//! placed by `direction` (of travel) or by `elevation_deg` and `azimuth_deg`: the direction
//! *toward* the sun is (sin A cos e, sin e, −cos A cos e) in the scene frame (+y up), so azimuth
//! 0° is straight ahead of a camera looking along −z and 90° is toward +x. A `directional` light
//! may also be given an `angular_diameter_deg`.
//!
//! A `sky` is uniform radiance (`spectrum` × `scale`, W m⁻² sr⁻¹ nm⁻¹) from every direction above
//! its horizon — elevation `horizon_deg` above the plane normal to `up` (defaults 0° and +y; a
//! round-Earth scene sets it a few degrees negative, since rays that leave the atmosphere bend
//! below the horizontal) — with photons aimed at the bounding sphere of
//! `target_min`/`target_max` (default: of the whole scene).

use super::raw::RawLight;
use super::spectrum_spec::{SpectrumLibrary, Use};
use crate::geometry::{Aabb, Disk, Quad, Shape, Sphere};
use crate::light::{
    AreaLight, DirectionalLight, Light, LightSpectrum, LimbDarkening, PointLight, Side, SkyLight, SpotLight,
};
use crate::spectrum::Bands;
use crate::validate::present_fields;
use crate::validate::{Ctx, MAX_LENGTH_M, MIN_LENGTH_M, R};
use toml::Spanned;

pub struct NamedLight {
    pub name: String,
    pub light: Light,
    /// For an area light: the material its surface reflects with (none: black).
    pub material: Option<Spanned<String>>,
    /// Warnings for the user (a luminaire file's quirks, lumens outside the wavelength range).
    pub notes: Vec<String>,
}

const KINDS: &[&str] = &["area", "point", "spot", "directional", "sun", "sky", "luminaire"];

/// The sun's mean angular diameter seen from the Earth, degrees (see
/// [`crate::spectrum::solar::ANGULAR_DIAMETER_DEG`]).
pub const SUN_ANGULAR_DIAMETER_DEG: f64 = crate::spectrum::solar::ANGULAR_DIAMETER_DEG;

/// The largest power of one light, W: 10²⁷ W, above the sun's luminosity (3.8 × 10²⁶ W). A light
/// of 10³⁰⁸ W was accepted before and its radiance overflowed to NaN pixels.
pub const MAX_LIGHT_POWER_W: f64 = 1e27;

pub fn light(
    ctx: &Ctx,
    lib: &SpectrumLibrary,
    rec: &Spanned<RawLight>,
    index: usize,
    bands: &Bands,
    bounds: &Aabb,
) -> R<NamedLight> {
    let span = rec.span();
    let l = rec.get_ref();
    let name = l.name.as_ref().map_or_else(|| format!("light #{}", index + 1), |n| n.get_ref().clone());
    let owner = format!("light \"{name}\"");
    let kind = ctx.choice(ctx.require(&l.kind, "type", &span, &owner)?, &format!("{owner}: type"), KINDS)?;
    let what = format!("{owner} ({kind})");
    let present = present_fields!(l; power_w, scale, irradiance_w_m2, shape, side, material, center, radius, normal, origin, u, v, position, direction, look_at, cone_deg, falloff_start_deg, target_min, target_max, file, cct_k, flux_scale, c0_toward, rotation_deg, emitter, variant, elevation_deg, azimuth_deg, angular_diameter_deg, limb_darkening, up, horizon_deg);
    let allowed: &[&str] = match kind {
        "area" => &["power_w", "scale", "shape", "side", "material", "center", "radius", "normal", "origin", "u", "v"],
        "point" => &["power_w", "scale", "position"],
        "spot" => &["power_w", "scale", "position", "direction", "look_at", "cone_deg", "falloff_start_deg"],
        "luminaire" => super::luminaires::FIELDS,
        "sun" => &[
            "scale",
            "irradiance_w_m2",
            "direction",
            "elevation_deg",
            "azimuth_deg",
            "angular_diameter_deg",
            "limb_darkening",
            "target_min",
            "target_max",
        ],
        "sky" => &["scale", "up", "horizon_deg", "target_min", "target_max"],
        _ => &[
            "scale",
            "irradiance_w_m2",
            "direction",
            "angular_diameter_deg",
            "limb_darkening",
            "target_min",
            "target_max",
        ],
    };
    ctx.only(&present, allowed, &what)?;
    if kind == "luminaire" {
        let (light, notes) = super::luminaires::luminaire(ctx, lib, l, &span, &what, bands)?;
        return Ok(NamedLight { name, light, material: None, notes });
    }
    let solar = Spanned::new(span.clone(), toml::Value::String("solar".into()));
    let spec = match (&l.spectrum, kind) {
        (None, "sun") => &solar,
        _ => ctx.require(&l.spectrum, "spectrum", &span, &what)?,
    };
    let shape_spectrum =
        lib.parse(ctx, spec, &format!("{what}: spectrum"), Use::Emission, (bands.min_nm, bands.max_nm))?;
    let emission = LightSpectrum::new(shape_spectrum, bands.min_nm, bands.max_nm).ok_or_else(|| {
        ctx.err(&spec.span(), format!("{what}: the spectrum emits nothing within {}–{} nm", bands.min_nm, bands.max_nm))
    })?;
    let mut light = match kind {
        "area" => Light::Area(area(ctx, l, &span, &what, emission)?),
        "point" => {
            let position = ctx.vec3(ctx.require(&l.position, "position", &span, &what)?, "position")?;
            Light::Point(PointLight { position, emission })
        }
        "spot" => Light::Spot(spot(ctx, l, &span, &what, emission)?),
        "sky" => Light::Sky(sky(ctx, l, &span, &what, emission, bounds)?),
        _ => {
            let dir = beam_direction(ctx, l, &span, &what, kind == "sun")?;
            if bounds.is_empty() {
                return Err(ctx.err(
                    &span,
                    format!("{what}: a directional light needs geometry to light; the scene has no shapes"),
                ));
            }
            let scene_radius = (0.5 * bounds.diagonal().length()).max(1e-6);
            let target = target_box(ctx, l, &span, &what)?;
            let diameter = match (&l.angular_diameter_deg, kind) {
                (Some(d), _) => ctx.number(d, "angular_diameter_deg", 0.0, 10.0, false)?,
                (None, "sun") => SUN_ANGULAR_DIAMETER_DEG,
                (None, _) => 0.0,
            };
            let limb = limb_darkening(ctx, l, &what, diameter, bands)?;
            let beam = DirectionalLight::new(dir, bounds.centre(), scene_radius, target, emission);
            Light::Directional(
                beam.with_angular_diameter(diameter).with_limb_darkening(limb, 0.5 * (bands.min_nm + bands.max_nm)),
            )
        }
    };
    set_level(ctx, l, &span, &what, &mut light, bands)?;
    Ok(NamedLight { name, light, material: l.material.clone(), notes: Vec::new() })
}

/// `limb_darkening`: the law of a disc's radiance across it (default none, a uniform disc);
/// a law needs a disc (`angular_diameter_deg` > 0) and must cover the scene's wavelengths.
fn limb_darkening(ctx: &Ctx, l: &RawLight, what: &str, diameter_deg: f64, bands: &Bands) -> R<LimbDarkening> {
    let Some(given) = &l.limb_darkening else { return Ok(LimbDarkening::Uniform) };
    let law = match ctx.choice(given, &format!("{what}: limb_darkening"), &["none", "neckel_labs_1994"])? {
        "neckel_labs_1994" => LimbDarkening::NeckelLabs1994,
        _ => LimbDarkening::Uniform,
    };
    if law != LimbDarkening::Uniform && diameter_deg <= 0.0 {
        return Err(ctx.err(
            &given.span(),
            format!("{what}: limb_darkening needs a disc; set angular_diameter_deg > 0 (the sun's is 0.533)"),
        ));
    }
    let (lo, hi) = law.range_nm();
    if bands.min_nm < lo || bands.max_nm > hi {
        return Err(ctx.err(
            &given.span(),
            format!(
                "{what}: limb_darkening = \"{}\" is tabulated for {lo}–{hi} nm, but the scene simulates {}–{} nm; \
                 narrow [output] min_nm/max_nm to that range or use limb_darkening = \"none\"",
                law.name(),
                bands.min_nm,
                bands.max_nm
            ),
        ));
    }
    Ok(law)
}

/// `target_min`/`target_max`: the box a light at infinity aims its photons at, if given.
fn target_box(
    ctx: &Ctx,
    l: &RawLight,
    span: &std::ops::Range<usize>,
    what: &str,
) -> R<Option<(glam::DVec3, glam::DVec3)>> {
    match (&l.target_min, &l.target_max) {
        (None, None) => Ok(None),
        (Some(a), Some(b)) => {
            let (lo, hi) = (ctx.vec3(a, "target_min")?, ctx.vec3(b, "target_max")?);
            if !hi.cmpge(lo).all() {
                return Err(ctx
                    .err(&b.span(), format!("{what}: target_max {hi} must not be below target_min {lo} on any axis")));
            }
            Ok(Some((lo, hi)))
        }
        _ => Err(ctx.err(span, format!("{what}: give both target_min and target_max, or neither"))),
    }
}

fn sky(
    ctx: &Ctx,
    l: &RawLight,
    span: &std::ops::Range<usize>,
    what: &str,
    emission: LightSpectrum,
    bounds: &Aabb,
) -> R<SkyLight> {
    if bounds.is_empty() {
        return Err(ctx.err(span, format!("{what}: a sky needs geometry to light; the scene has no shapes")));
    }
    let up = match &l.up {
        Some(u) => ctx.direction(u, "up")?,
        None => glam::DVec3::Y,
    };
    let scene_centre = bounds.centre();
    let scene_radius = (0.5 * bounds.diagonal().length()).max(1e-6);
    let (target_centre, target_radius) = match target_box(ctx, l, span, what)? {
        None => (scene_centre, scene_radius),
        Some((lo, hi)) => (0.5 * (lo + hi), (0.5 * (hi - lo).length()).max(1e-9)),
    };
    let start_distance = 1.001 * ((target_centre - scene_centre).length() + scene_radius);
    let horizon = match &l.horizon_deg {
        None => 0.0,
        Some(h) => ctx.number(h, "horizon_deg", -90.0, 90.0, true)?,
    };
    Ok(SkyLight { up, sin_horizon: horizon.to_radians().sin(), target_centre, target_radius, start_distance, emission })
}

/// The direction of travel of a directional light or sun: `direction`, or (sun only) the
/// direction away from the sun at `elevation_deg`, `azimuth_deg` (see the module docs).
fn beam_direction(ctx: &Ctx, l: &RawLight, span: &std::ops::Range<usize>, what: &str, sun: bool) -> R<glam::DVec3> {
    match (&l.direction, &l.elevation_deg, &l.azimuth_deg) {
        (Some(d), None, None) => ctx.direction(d, "direction"),
        (None, Some(e), Some(a)) if sun => {
            let e = ctx.number(e, "elevation_deg", -90.0, 90.0, false)?.to_radians();
            let a = ctx.number(a, "azimuth_deg", -360.0, 360.0, false)?.to_radians();
            let toward = glam::DVec3::new(a.sin() * e.cos(), e.sin(), -a.cos() * e.cos());
            Ok(-toward)
        }
        _ if sun => {
            Err(ctx
                .err(span, format!("{what}: give either direction (of travel) or both elevation_deg and azimuth_deg")))
        }
        _ => ctx.direction(ctx.require(&l.direction, "direction", span, what)?, "direction"),
    }
}

/// Scales the light's spectrum to the absolute level the record asks for: k = scale, or
/// k = power_w / Φ₁ where Φ₁ is the flux at unit scale, or k = irradiance_w_m2 / ∫spectrum.
fn set_level(
    ctx: &Ctx,
    l: &RawLight,
    span: &std::ops::Range<usize>,
    what: &str,
    light: &mut Light,
    bands: &Bands,
) -> R<()> {
    let given: Vec<&Spanned<f64>> = [&l.power_w, &l.scale, &l.irradiance_w_m2].into_iter().flatten().collect();
    if given.is_empty() && l.spectrum.is_none() && matches!(light, Light::Directional(d) if d.sin_max > 0.0) {
        // A sun with its default spectrum: the solar irradiance itself, scale 1.
        return Ok(());
    }
    if given.len() != 1 {
        let options = match light {
            Light::Directional(_) => "irradiance_w_m2 or scale",
            Light::Sky(_) => "scale (the sky's radiance is spectrum × scale)",
            _ => "power_w or scale",
        };
        return Err(ctx.err(span, format!("{what}: give exactly one of {options} to set the light's level")));
    }
    let v = given[0];
    let x = ctx.number(v, "light level", 0.0, f64::INFINITY, true)?;
    let k = if l.scale.is_some() {
        x
    } else if l.irradiance_w_m2.is_some() {
        x / light.spectrum().integral()
    } else {
        x / light.power_w()
    };
    let emission = emission_mut(light);
    let scaled = LightSpectrum::new(emission.spectrum.clone().scaled(k), bands.min_nm, bands.max_nm)
        .ok_or_else(|| ctx.err(&v.span(), format!("{what}: level {x} gives no emission")))?;
    *emission = scaled;
    let power = light.power_w();
    if !(power > 0.0 && power <= MAX_LIGHT_POWER_W) {
        return Err(ctx.err(
            &v.span(),
            format!("{what}: the light's power {power} W is not a positive number of at most {MAX_LIGHT_POWER_W:e} W"),
        ));
    }
    Ok(())
}

fn emission_mut(light: &mut Light) -> &mut LightSpectrum {
    match light {
        Light::Area(l) => &mut l.emission,
        Light::Point(l) => &mut l.emission,
        Light::Spot(l) => &mut l.emission,
        Light::Directional(l) => &mut l.emission,
        Light::Luminaire(l) => &mut l.emission,
        Light::Sky(l) => &mut l.emission,
    }
}

fn area(ctx: &Ctx, l: &RawLight, span: &std::ops::Range<usize>, what: &str, emission: LightSpectrum) -> R<AreaLight> {
    let shape_kind = ctx.choice(
        ctx.require(&l.shape, "shape", span, what)?,
        &format!("{what}: shape"),
        &["quad", "disk", "sphere"],
    )?;
    let fields = present_fields!(l; center, radius, normal, origin, u, v);
    let shape = match shape_kind {
        "quad" => {
            ctx.only(&fields, &["origin", "u", "v"], &format!("{what} with shape \"quad\""))?;
            let origin = ctx.vec3(ctx.require(&l.origin, "origin", span, what)?, "origin")?;
            let u = ctx.vec3(ctx.require(&l.u, "u", span, what)?, "u")?;
            let v = ctx.vec3(ctx.require(&l.v, "v", span, what)?, "v")?;
            if u.cross(v).length() < MIN_LENGTH_M * MIN_LENGTH_M {
                return Err(ctx.err(
                    span,
                    format!("{what}: edges u and v are parallel or zero; the light has no area (below 1e-18 m²)"),
                ));
            }
            Shape::Quad(Quad { origin, u, v })
        }
        "disk" => {
            ctx.only(&fields, &["center", "radius", "normal"], &format!("{what} with shape \"disk\""))?;
            let center = ctx.vec3(ctx.require(&l.center, "center", span, what)?, "center")?;
            let radius =
                ctx.number(ctx.require(&l.radius, "radius", span, what)?, "radius", MIN_LENGTH_M, MAX_LENGTH_M, false)?;
            let normal = ctx.direction(ctx.require(&l.normal, "normal", span, what)?, "normal")?;
            Shape::Disk(Disk { center, normal, radius })
        }
        _ => {
            ctx.only(&fields, &["center", "radius"], &format!("{what} with shape \"sphere\""))?;
            let center = ctx.vec3(ctx.require(&l.center, "center", span, what)?, "center")?;
            let radius =
                ctx.number(ctx.require(&l.radius, "radius", span, what)?, "radius", MIN_LENGTH_M, MAX_LENGTH_M, false)?;
            Shape::Sphere(Sphere { center, radius })
        }
    };
    let side = match &l.side {
        None => Side::Front,
        Some(s) => match ctx.choice(s, &format!("{what}: side"), &["front", "back", "both"])? {
            "back" => Side::Back,
            "both" => Side::Both,
            _ => Side::Front,
        },
    };
    Ok(AreaLight { shape, side, emission })
}

fn spot(ctx: &Ctx, l: &RawLight, span: &std::ops::Range<usize>, what: &str, emission: LightSpectrum) -> R<SpotLight> {
    let position = ctx.vec3(ctx.require(&l.position, "position", span, what)?, "position")?;
    let axis = match (&l.direction, &l.look_at) {
        (Some(d), None) => ctx.direction(d, "direction")?,
        (None, Some(t)) => {
            let target = ctx.vec3(t, "look_at")?;
            let d = target - position;
            if d.length_squared() == 0.0 {
                return Err(ctx.err(&t.span(), format!("{what}: look_at equals position")));
            }
            d.normalize()
        }
        _ => {
            return Err(ctx.err(span, format!("{what}: give exactly one of direction or look_at")));
        }
    };
    let cone = ctx.number(ctx.require(&l.cone_deg, "cone_deg", span, what)?, "cone_deg", 0.0, 180.0, true)?;
    let start = match &l.falloff_start_deg {
        None => cone,
        Some(v) => ctx.number(v, "falloff_start_deg", 0.0, cone, false)?,
    };
    Ok(SpotLight { position, axis, cos_total: cone.to_radians().cos(), cos_start: start.to_radians().cos(), emission })
}
