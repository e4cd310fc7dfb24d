//! The warning a run gives when its volume photon map would read the sky in the Earth's
//! shadow, where the estimate is known to be biased (issue 19; the book's The sky, "Not yet").
//!
//! In twilight the observer's air is in the Earth's shadow and holds few photons: the k nearest
//! are found only within hundreds of kilometres, a sphere that reaches the sunlit air above the
//! shadow. The density-weighted gather volume corrects for the air's density across it, not for
//! the light's, so the estimate is too high: on `examples/sky_twilight.toml` at solar zenith 96°
//! it read 25–50 times the path tracer's zenith radiance.

use super::Scene;
use crate::atmosphere::Earth;
use crate::light::Light;

/// A warning when the plan reads a volume photon map, the camera sits in a scattering
/// atmosphere over a round Earth, and a directional light (the sun) is below the camera's
/// horizon; `None` otherwise.
pub fn warning(scene: &Scene) -> Option<String> {
    if !scene.plan.volume_map.on {
        return None;
    }
    let air = &scene.world.media[scene.camera_medium? as usize];
    let earth = air.earth().filter(|e| matches!(e, Earth::Spherical(_)) && air.scatters())?;
    let (_, up) = earth.height_grad(scene.camera.position);
    let below = scene.world.lights.iter().position(|l| matches!(l, Light::Directional(d) if d.dir.dot(up) > 0.0))?;
    Some(format!(
        "light \"{}\" is below the horizon at the camera: in the Earth's shadow the volume photon map's estimate is biased high (25–50× the path tracer's zenith radiance at solar zenith 96°, see the book's The sky, \"Not yet\"); for twilight use photons = 0 (single scattering) or method = \"path\"",
        scene.world.names.lights[below]
    ))
}
