//! Whether a scene is symmetric about the sun's axis, so that its volume photons may be folded
//! onto one half-plane ([`crate::geometry::AxialFold`]).
//!
//! A round Earth under air stratified in height, lit by one sun, looks the same from every
//! point of a ring about the line through the Earth's centre along the sunlight: the light
//! field is that of a two-dimensional problem (Marchuk et al. 1980, §4, the "spherical
//! one-dimensional" geometry of Monte Carlo sky codes such as MYSTIC; Emde et al. 2010). A
//! photon stored anywhere on a ring then counts at every point of it. Folded, 10⁶ photons over
//! the whole lit hemisphere fill the observer's neighbourhood as densely as if all of them had
//! been aimed at its ring: gather radii fall from hundreds of kilometres to a few, and the
//! estimate in the Earth's shadow at twilight no longer reaches the sunlit air above it.
//!
//! The fold is exact only if nothing breaks the symmetry, so every part is checked: the world's
//! medium and every other medium in use depend on the distance from the Earth's centre alone
//! (coefficients and refractive index); every shape is a sphere about that centre; the only light
//! is one directional light with no target box, whose beam covers the whole atmosphere; and the
//! volume map is read by the point estimate (the beam estimate's discs lie along straight
//! chords, which a fold would bend).
//!
//! By default photons are folded only in twilight — with the sun below the horizon at the
//! camera or a sky sensor — where the unfolded estimate is biased; with the sun above it the
//! sky is horizontally uniform, the unfolded estimate was measured unbiased, and the ring's
//! volume integral would only cost eye-pass time (16 % at noon, 58 % at sunset).
//! `axial_symmetry = true` folds wherever the scene is symmetric, `false` never.

use crate::atmosphere::Earth;
use crate::geometry::{AxialFold, DVec3, Shape};
use crate::light::Light;
use crate::media::density::Density;
use crate::media::{Coefficients, Medium};
use crate::world::World;

use super::{IntegratorSettings, VolumeEstimate};

/// The fold about the sun's axis through the Earth's centre, or why photons are not folded:
/// the scene is not symmetric about it, or (by default) the sun is above the horizon at every
/// one of the `viewpoints` (the camera and the sky sensors, see [`viewpoints`]).
pub fn sun_axis(world: &World, s: &IntegratorSettings, viewpoints: &[DVec3]) -> Result<AxialFold, String> {
    if s.axial_symmetry == Some(false) {
        return Err("axial_symmetry = false".into());
    }
    match s.volume_estimate {
        VolumeEstimate::Beam => return Err("volume_estimate = \"beam\" reads photons along straight chords".into()),
        VolumeEstimate::PhotonBeams => {
            return Err("volume_estimate = \"photon_beams\" keeps each photon's flight as it was".into());
        }
        VolumeEstimate::Point => {}
    }
    let global = world.global_medium.ok_or("no [world] medium")?;
    let air = &world.media[global as usize];
    let (centre, top_radius) =
        shell(air).ok_or_else(|| format!("medium \"{}\" is not stratified over a round Earth", air.name))?;
    for (i, m) in world.media.iter().enumerate() {
        let used = Some(i as u32) == world.global_medium
            || world.prims.iter().any(|p| p.interior == Some(i as u32) || p.exterior == Some(i as u32));
        if used && !radial_about(m, centre) {
            return Err(format!("medium \"{}\" is not symmetric about the Earth's centre", m.name));
        }
    }
    if let Some(i) = world.shapes.iter().position(|s| !sphere_about(s, centre)) {
        return Err(format!("shape {} is not a sphere about the Earth's centre", i + 1));
    }
    let [Light::Directional(sun)] = world.lights.as_slice() else {
        return Err("the scene's lights are not one directional light".into());
    };
    if sun.target.is_some() {
        return Err(format!("light \"{}\" aims at a target box", world.names.lights[0]));
    }
    if !covers(sun, centre, top_radius) {
        return Err(format!("light \"{}\"'s beam does not cover the whole atmosphere", world.names.lights[0]));
    }
    let below = |p: &DVec3| sun.dir.dot(*p - centre) > 0.0;
    if s.axial_symmetry.is_none() && !viewpoints.iter().any(below) {
        return Err("the sun is above the horizon at the camera and every sky sensor (folding pays in twilight; axial_symmetry = true folds here too)".into());
    }
    AxialFold::new(centre, -sun.dir).ok_or_else(|| "the light has no direction".into())
}

/// Where the scene's light is looked at from: the camera and every sky-radiance sensor.
pub fn viewpoints(camera: &crate::geometry::Camera, sensors: &[crate::sensor::NamedSensor]) -> Vec<DVec3> {
    let sky = sensors.iter().flat_map(|n| match &n.sensor {
        crate::sensor::Sensor::SkyRadiance(s) => s.origins.clone(),
        _ => Vec::new(),
    });
    std::iter::once(camera.position).chain(sky).collect()
}

/// The fold the photon pass applies to `scene`'s volume map, or why there is none.
pub fn scene_fold(scene: &super::Scene) -> Result<AxialFold, String> {
    sun_axis(&scene.world, &scene.integrator, &viewpoints(&scene.camera, &scene.sensors))
}

/// What the effect plan says of the fold under the volume map: that photons are folded, or —
/// for a scene over a round Earth that is not symmetric — why not; nothing for other scenes.
pub fn plan_words(world: &World, s: &IntegratorSettings, viewpoints: &[DVec3]) -> Option<String> {
    let air = world.media.get(world.global_medium? as usize)?;
    shell(air)?;
    let why = match s.axial_symmetry {
        Some(true) => "axial_symmetry = true",
        _ => "the sun is below the horizon where the scene is looked at from, where the unfolded map is biased",
    };
    Some(match sun_axis(world, s, viewpoints) {
        Ok(_) => format!(
            "; the scene is symmetric about the sun's axis through the Earth's centre, so volume photons are folded onto one half-plane about it and each estimate gathers a ring ({why})"
        ),
        Err(why) => format!("; not folded about the sun's axis: {why}"),
    })
}

/// The Earth's centre and the distance from it of the top of `m`'s air, if `m` is stratified in
/// height over a round Earth.
fn shell(m: &Medium) -> Option<(DVec3, f64)> {
    let (earth, top) = match (&m.coefficients, &m.density) {
        (Coefficients::Constituents(c), Density::Uniform) => {
            let p = &c.list().first()?.profile;
            (p.earth(), p.top_m())
        }
        (_, Density::AirProfile(p)) => (p.earth(), p.top_m()),
        _ => return None,
    };
    match earth {
        Earth::Spherical(s) => Some((s.centre, s.radius_m + top)),
        Earth::Flat { .. } => None,
    }
}

/// Whether `m`'s coefficients and refractive index depend on the distance from `centre` alone.
fn radial_about(m: &Medium, centre: DVec3) -> bool {
    let same = |e: &Earth| matches!(e, Earth::Spherical(s) if s.centre == centre);
    let coefficients = match (&m.coefficients, &m.density) {
        (Coefficients::Constituents(c), Density::Uniform) => c.list().iter().all(|k| same(k.profile.earth())),
        (Coefficients::Constituents(_), _) => false,
        (_, Density::AirProfile(p)) => same(p.earth()),
        _ => false,
    };
    let index = match &m.index {
        None => true,
        Some(f) if f.is_uniform() => true,
        Some(f) => f.radial_centre() == Some(centre),
    };
    coefficients && index
}

/// Whether `shape` is a sphere centred on `centre` (to a millionth of its radius).
fn sphere_about(shape: &Shape, centre: DVec3) -> bool {
    matches!(shape, Shape::Sphere(s) if (s.center - centre).length() <= 1e-6 * s.radius)
}

/// Whether the beam of `sun` covers the disc of radius `top_radius` about the axis through
/// `centre`, widened by the disc's angular radius over the beam's length (photons from the sun's
/// edge start off the axis so as to cross it at the scene's centre). A beam with a projection
/// map has a target box, refused before.
fn covers(sun: &crate::light::DirectionalLight, centre: DVec3, top_radius: f64) -> bool {
    let d = centre - sun.scene_centre;
    let (cs, ct) = (d.dot(sun.frame.s), d.dot(sun.frame.t));
    let reach = top_radius * 1.001 + sun.sin_max * 4.0 * sun.scene_radius;
    let [[s0, s1], [t0, t1]] = sun.beam;
    s0 <= cs - reach && cs + reach <= s1 && t0 <= ct - reach && ct + reach <= t1
}
