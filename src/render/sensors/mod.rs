//! Evaluating the scene's sensors after the photon pass, against the same photon maps as the eye
//! pass (the sensors themselves are defined in [`crate::sensor`]).

mod illuminance_plane;
mod ocean_profile;
pub mod sky_radiance;

use super::eye::EyeTracer;
use super::photon_pass::Maps;
use crate::scene::{IntegratorSettings, Scene};
use crate::sensor::{ProfileReading, Reading, Sensor};

/// Evaluates every sensor of the scene against the photon maps, with the estimate settings and
/// seed `s` (the scene's own, or a progressive pass's).
pub fn evaluate_all(scene: &Scene, s: &IntegratorSettings, maps: &Maps) -> Vec<Reading> {
    let tracer = EyeTracer::new(scene, s, maps);
    let seed = s.seed;
    scene
        .sensors
        .iter()
        .enumerate()
        .filter_map(|(i, s)| match &s.sensor {
            Sensor::IlluminancePlane(p) => {
                Some(illuminance_plane::evaluate(p, (scene, seed), &tracer, &s.name, i as u64))
            }
            Sensor::SkyRadiance(r) => Some(sky_radiance::evaluate(r, (scene, seed), &tracer, &s.name, i as u64)),
            Sensor::OceanProfile(_) => None,
        })
        .collect()
}

/// Evaluates every ocean profile sensor of the scene against the volume map, with the random
/// streams of `seed`.
pub fn evaluate_profiles(scene: &Scene, seed: u64, maps: &Maps) -> Vec<ProfileReading> {
    scene
        .sensors
        .iter()
        .enumerate()
        .filter_map(|(i, s)| match &s.sensor {
            Sensor::OceanProfile(p) => Some(ocean_profile::evaluate(p, (scene, seed), maps, &s.name, i as u64)),
            Sensor::IlluminancePlane(_) | Sensor::SkyRadiance(_) => None,
        })
        .collect()
}
