//! `[[sensor]]` records → [`NamedSensor`]s.
//!
//! ```toml
//! [[sensor]]
//! name = "desk"                 # names the outputs: <output name>_desk.csv / .png
//! type = "illuminance_plane"
//! origin = [0.5, 0.8, -0.5]     # a corner of the grid, m
//! u = [4.0, 0.0, 0.0]           # edge along the grid's i axis
//! v = [0.0, 0.0, -3.0]          # edge along j; the default normal (u × v) here is +Y (up)
//! resolution = [40, 30]         # points along u and v (cell centres), each at most 4096
//! normal = [0.0, 1.0, 0.0]      # optional: the side measured (any direction)
//! samples = 4                   # optional: estimates averaged per point
//! gather_rays = 64              # optional: rays for indirect light per sample; 0 = direct only
//!
//! [[sensor]]
//! name = "profile"              # writes <output name>_profile.csv and _profile_derived.csv
//! type = "ocean_profile"        # Ed, Eu, Eod, Eou, Lu at depths (src/sensor/ocean_profile.rs)
//! origin = [0.0, 0.0, 0.0]      # a point on the water surface: centre of the measured square
//! u = [100.0, 0.0, 0.0]         # edges of the horizontal square (centred on origin)
//! v = [0.0, 0.0, 100.0]
//! normal = [0.0, 1.0, 0.0]      # optional: up, toward the air (default +Y)
//! depths_m = [1.0, 5.0, 10.0]   # below the surface (at most 4096 depths)
//! slab_m = 0.2                  # optional: thickness of each measuring slab (default 0.1)
//! ior = 1.34                    # optional: water's refractive index for Lw (default 1.34)
//! samples = 64                  # optional: shadow rays per band for Ed(0+)
//!
//! [[sensor]]
//! name = "sky"                  # writes <output name>_sky.csv: radiance per band and direction
//! type = "sky_radiance"         # src/sensor/sky_radiance.rs
//! origin = [0.0, 1.0, 0.0]      # where the radiance is measured, m
//! directions_deg = [[0, 0], [60, 90], [120, 180]]   # [view zenith, azimuth] (0 toward −z, 90 +x)
//! samples = 64                  # optional: estimates per direction and band (default 64)
//! ```

use super::raw::RawSensor;
use super::settings::{DirectLighting, IntegratorSettings};
use crate::sensor::{IlluminancePlane, NamedSensor, OceanProfile, Sensor, SkyRadiance};
use crate::validate::present_fields;
use crate::validate::{Ctx, MAX_LENGTH_M, MIN_LENGTH_M, R};
use glam::DVec3;
use toml::Spanned;

const KINDS: &[&str] = &["illuminance_plane", "ocean_profile", "sky_radiance", "limb"];
const MAX_POINTS: i64 = 4096;

/// Every sensor key the record gives, with its span (each type accepts some of them).
fn present(s: &RawSensor) -> [(&'static str, Option<std::ops::Range<usize>>); 13] {
    present_fields!(s; origin, u, v, normal, resolution, samples, gather_rays, depths_m, slab_m, ior, directions_deg, tangent_heights_m, azimuth_deg)
}

/// The world's air for limb sensors: the Earth's centre and radius and the atmosphere's top, m
/// (`None` unless the world medium is an atmosphere over a spherical Earth).
pub type LimbAir = Option<(DVec3, f64, f64)>;

pub fn sensors(
    ctx: &Ctx,
    raw: &[Spanned<RawSensor>],
    integrator: &IntegratorSettings,
    air: LimbAir,
) -> R<Vec<NamedSensor>> {
    let mut out: Vec<NamedSensor> = Vec::new();
    for (i, rec) in raw.iter().enumerate() {
        let s = sensor(ctx, rec, i, integrator, air)?;
        if out.iter().any(|o| o.name == s.name) {
            return Err(ctx.err(&rec.span(), format!("sensor \"{}\" is defined twice; names must be unique", s.name)));
        }
        out.push(s);
    }
    Ok(out)
}

fn sensor(
    ctx: &Ctx,
    rec: &Spanned<RawSensor>,
    index: usize,
    integrator: &IntegratorSettings,
    air: LimbAir,
) -> R<NamedSensor> {
    let span = rec.span();
    let s = rec.get_ref();
    let name = s.name.as_ref().map_or_else(|| format!("sensor{}", index + 1), |n| n.get_ref().clone());
    let what = format!("sensor \"{name}\"");
    let kind = ctx.choice(ctx.require(&s.kind, "type", &span, &what)?, &format!("{what}: type"), KINDS)?;
    if kind == "ocean_profile" {
        return profile(ctx, rec, name, &what, integrator);
    }
    if kind == "sky_radiance" {
        return sky_radiance(ctx, rec, name, &what);
    }
    if kind == "limb" {
        return limb(ctx, rec, name, &what, air);
    }
    let present = present(s);
    ctx.only(&present, &["origin", "u", "v", "normal", "resolution", "samples", "gather_rays"], &what)?;
    let origin = ctx.vec3(ctx.require(&s.origin, "origin", &span, &what)?, "origin")?;
    let u = ctx.vec3(ctx.require(&s.u, "u", &span, &what)?, "u")?;
    let v = ctx.vec3(ctx.require(&s.v, "v", &span, &what)?, "v")?;
    let cross = u.cross(v);
    if cross.length() < MIN_LENGTH_M * MIN_LENGTH_M {
        return Err(
            ctx.err(&span, format!("{what}: u and v are parallel or zero; the grid has no area (below 1e-18 m²)"))
        );
    }
    let normal = match &s.normal {
        Some(n) => ctx.direction(n, "normal")?,
        None => cross.normalize(),
    };
    let res = ctx.require(&s.resolution, "resolution", &span, &what)?;
    let [nx, ny] = res.get_ref().0;
    if !(1..=MAX_POINTS).contains(&nx) || !(1..=MAX_POINTS).contains(&ny) {
        return Err(ctx.err(
            &res.span(),
            format!("{what}: resolution = [{nx}, {ny}] is out of range: each must be from 1 to {MAX_POINTS}"),
        ));
    }
    let samples = s.samples.as_ref().map_or(Ok(4), |x| ctx.integer(x, "samples", 1, 4096))? as usize;
    let gather_rays = s.gather_rays.as_ref().map_or(Ok(64), |x| ctx.integer(x, "gather_rays", 0, 65536))? as usize;
    let map_holds_direct = integrator.final_gather || integrator.direct == DirectLighting::PhotonMap;
    if gather_rays > 0 && !map_holds_direct {
        return Err(ctx.err(
            &span,
            format!(
                "{what}: indirect light needs a global photon map that holds first-bounce photons, but final_gather = false with direct = \"shadow_rays\" stores only later bounces; set final_gather = true or direct = \"photon_map\" in [integrator], or gather_rays = 0 to measure direct light only"
            ),
        ));
    }
    let plane = IlluminancePlane { origin, u, v, normal, nx: nx as usize, ny: ny as usize, samples, gather_rays };
    Ok(NamedSensor { name, sensor: Sensor::IlluminancePlane(plane) })
}

/// `type = "ocean_profile"`.
fn profile(
    ctx: &Ctx,
    rec: &Spanned<RawSensor>,
    name: String,
    what: &str,
    integrator: &IntegratorSettings,
) -> R<NamedSensor> {
    let span = rec.span();
    let s = rec.get_ref();
    let present = present(s);
    ctx.only(&present, &["origin", "u", "v", "normal", "samples", "depths_m", "slab_m", "ior"], what)?;
    if integrator.photons == 0 {
        return Err(ctx.err(
            &span,
            format!("{what}: an ocean profile reads the volume photon map; set [integrator] photons > 0"),
        ));
    }
    let origin = ctx.vec3(ctx.require(&s.origin, "origin", &span, what)?, "origin")?;
    let u = ctx.vec3(ctx.require(&s.u, "u", &span, what)?, "u")?;
    let v = ctx.vec3(ctx.require(&s.v, "v", &span, what)?, "v")?;
    if u.cross(v).length() < MIN_LENGTH_M * MIN_LENGTH_M {
        return Err(
            ctx.err(&span, format!("{what}: u and v are parallel or zero; the square has no area (below 1e-18 m²)"))
        );
    }
    let up = match &s.normal {
        Some(n) => ctx.direction(n, "normal")?,
        None => glam::DVec3::Y,
    };
    let d = ctx.require(&s.depths_m, "depths_m", &span, what)?;
    let depths_m = d.get_ref().clone();
    if depths_m.is_empty() || depths_m.iter().any(|z| !(z.is_finite() && *z >= 0.0)) {
        return Err(ctx.err(&d.span(), format!("{what}: depths_m must be a non-empty list of depths ≥ 0 (m)")));
    }
    if depths_m.len() > MAX_POINTS as usize {
        return Err(ctx.err(
            &d.span(),
            format!("{what}: depths_m lists {} depths; at most {MAX_POINTS} (every stored photon is tallied at every depth)", depths_m.len()),
        ));
    }
    let slab_m = s.slab_m.as_ref().map_or(Ok(0.1), |x| ctx.number(x, "slab_m", MIN_LENGTH_M, MAX_LENGTH_M, false))?;
    let ior = s.ior.as_ref().map_or(Ok(1.34), |x| ctx.number(x, "ior", 1.0, 3.0, false))?;
    let samples = s.samples.as_ref().map_or(Ok(64), |x| ctx.integer(x, "samples", 1, 1 << 20))? as usize;
    let p = OceanProfile { origin, u, v, up, depths_m, slab_m, ior, samples };
    Ok(NamedSensor { name, sensor: Sensor::OceanProfile(p) })
}

/// `type = "sky_radiance"`: a position and [view zenith, view azimuth] pairs in degrees (zenith 0
/// to 180, azimuth −360 to 360).
fn sky_radiance(ctx: &Ctx, rec: &Spanned<RawSensor>, name: String, what: &str) -> R<NamedSensor> {
    let span = rec.span();
    let s = rec.get_ref();
    let present = present(s);
    ctx.only(&present, &["origin", "directions_deg", "samples"], what)?;
    let position = ctx.vec3(ctx.require(&s.origin, "origin", &span, what)?, "origin")?;
    let d = ctx.require(&s.directions_deg, "directions_deg", &span, what)?;
    let directions_deg: Vec<[f64; 2]> = d.get_ref().iter().map(|x| x.0).collect();
    if directions_deg.is_empty() || directions_deg.len() > MAX_POINTS as usize {
        return Err(
            ctx.err(&d.span(), format!("{what}: directions_deg must list 1 to {MAX_POINTS} [zenith, azimuth] pairs"))
        );
    }
    if let Some([z, a]) = directions_deg
        .iter()
        .find(|[z, a]| !(z.is_finite() && (0.0..=180.0).contains(z) && a.is_finite() && (-360.0..=360.0).contains(a)))
    {
        return Err(ctx.err(
            &d.span(),
            format!("{what}: direction [{z}, {a}] is out of range: view zenith 0 to 180°, azimuth −360 to 360°"),
        ));
    }
    let samples = s.samples.as_ref().map_or(Ok(64), |x| ctx.integer(x, "samples", 1, 1 << 20))? as usize;
    Ok(NamedSensor { name, sensor: Sensor::SkyRadiance(SkyRadiance::at_point(position, directions_deg, samples)) })
}

/// A limb's lines of sight hardly climb near their tangent points, where the default march
/// steps (bounded by a quarter of the least scale height's climb and a quarter of the mean free
/// path) grow to ~100 km: on the limb benchmark of Zawada et al. they left ±0.1 % of noise at
/// 8192 samples where 1 km steps leave < 0.01 % at 256. A note when a scene with a limb sensor
/// keeps the default step and it is longer than 1 km.
pub fn limb_march_note(sensors: &[NamedSensor], march_step_m: f64, given: bool) -> Option<String> {
    let limb = sensors.iter().find(|s| matches!(&s.sensor, Sensor::SkyRadiance(sky) if sky.limb.is_some()))?;
    (!given && march_step_m > 1000.0).then(|| {
        format!(
            "sensor \"{}\": a limb's lines of sight are marched in the default steps of up to {:.0} km; [integrator] march_step = 1000 gives noise below 0.01 % at 256 samples (the book's The sky, Limb sensor)",
            limb.name,
            march_step_m * 1e-3
        )
    })
}

/// `type = "limb"`: tangent heights (m, from the ground to below the atmosphere's top) and the
/// azimuth the lines of sight look toward, in the world's air over a spherical Earth
/// ([`SkyRadiance::limb`]).
fn limb(ctx: &Ctx, rec: &Spanned<RawSensor>, name: String, what: &str, air: LimbAir) -> R<NamedSensor> {
    let span = rec.span();
    let s = rec.get_ref();
    let present = present(s);
    ctx.only(&present, &["tangent_heights_m", "azimuth_deg", "samples"], what)?;
    let Some((centre, radius_m, top_m)) = air else {
        return Err(ctx.err(&span, format!("{what}: a limb needs the world's air to be an atmosphere over a round Earth: [world] medium = an atmosphere medium, earth = \"spherical\"")));
    };
    let h = ctx.require(&s.tangent_heights_m, "tangent_heights_m", &span, what)?;
    let heights = h.get_ref();
    if heights.is_empty() || heights.len() > MAX_POINTS as usize {
        return Err(ctx.err(&h.span(), format!("{what}: tangent_heights_m must list 1 to {MAX_POINTS} heights (m)")));
    }
    if let Some(x) = heights.iter().find(|x| !(x.is_finite() && (0.0..top_m).contains(*x))) {
        return Err(ctx.err(&h.span(), format!("{what}: tangent height {x} m is out of range: from the ground (0) to below the atmosphere's top ({top_m} m)")));
    }
    let azimuth_deg = match &s.azimuth_deg {
        None => 0.0,
        Some(a) => ctx.number(a, "azimuth_deg", -360.0, 360.0, false)?,
    };
    let samples = s.samples.as_ref().map_or(Ok(64), |x| ctx.integer(x, "samples", 1, 1 << 20))? as usize;
    let sky = SkyRadiance::limb((centre, radius_m, top_m), heights, azimuth_deg, samples);
    Ok(NamedSensor { name, sensor: Sensor::SkyRadiance(sky) })
}
