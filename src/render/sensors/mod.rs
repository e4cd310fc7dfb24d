//! Evaluating the scene's sensors after the photon pass, against the same photon maps as the eye
//! pass (the sensors themselves are defined in [`crate::sensor`]).

mod illuminance_plane;
mod ocean_profile;

use super::eye::EyeTracer;
use super::photon_pass::Maps;
use crate::scene::Scene;
use crate::sensor::{ProfileReading, Reading, Sensor};

/// Evaluates every sensor of the scene against the photon maps.
pub fn evaluate_all(scene: &Scene, maps: &Maps) -> Vec<Reading> {
    let tracer = EyeTracer::new(scene, maps);
    scene
        .sensors
        .iter()
        .enumerate()
        .filter_map(|(i, s)| match &s.sensor {
            Sensor::IlluminancePlane(p) => Some(illuminance_plane::evaluate(p, scene, &tracer, &s.name, i as u64)),
            Sensor::OceanProfile(_) => None,
        })
        .collect()
}

/// Evaluates every ocean profile sensor of the scene against the volume map.
pub fn evaluate_profiles(scene: &Scene, maps: &Maps) -> Vec<ProfileReading> {
    scene
        .sensors
        .iter()
        .enumerate()
        .filter_map(|(i, s)| match &s.sensor {
            Sensor::OceanProfile(p) => Some(ocean_profile::evaluate(p, scene, maps, &s.name, i as u64)),
            Sensor::IlluminancePlane(_) => None,
        })
        .collect()
}
