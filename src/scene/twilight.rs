//! The warning a run gives when its volume photon map would read the sky in the Earth's
//! shadow, where the estimate is known to be biased (issue 19; the book's The sky, "Not yet").
//!
//! In twilight the observer's air is in the Earth's shadow and holds few photons: the k nearest
//! are found only within hundreds of kilometres, a sphere that reaches the sunlit air above the
//! shadow. The density-weighted gather volume corrects for the air's density across it, not for
//! the light's, so the estimate is too high: on `examples/sky_twilight.toml` at solar zenith 96°
//! it read 25–50 times the path tracer's zenith radiance. Folded about the sun's axis
//! ([`super::symmetry`]) every photon of the observer's ring counts and the bias falls with the
//! photon count — within the noise of the path tracer at 92–94° with 2 × 10⁶ photons — but
//! deeper in the shadow photons stay scarce and the light across the gather disc varies
//! steeply: at 96° in 445–455 nm air (vertical optical depth 0.2) 10⁶ photons read twice the
//! path tracer, 10⁷ within 5 %; at 351 nm in the air of Zawada et al. (optical depth 0.62) 10⁷
//! photons read 1.4–1.7× the path tracer (two seeds) and 3 × 10⁷ still 1.1–1.5× (the book's The sky,
//! "Multiple scattering through twilight against SASKTRAN2"). So a folded map is warned about
//! whenever the sun is more than [`FOLDED_DEPTH_DEG`] below the horizon, whatever its photons.

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
    let name = &scene.world.names.lights[below];
    match super::symmetry::scene_fold(scene) {
        Err(why) => Some(format!(
            "light \"{name}\" is below the horizon at the camera: in the Earth's shadow the volume photon map's estimate is biased high (25–50× the path tracer's zenith radiance at solar zenith 96°, see the book's The sky, twilight), and its photons cannot be folded about the sun's axis ({why}); for twilight use photons = 0 (single scattering) or method = \"path\""
        )),
        Ok(_) => {
            let Light::Directional(d) = &scene.world.lights[below] else { return None };
            let depth_deg = d.dir.dot(up).asin().to_degrees();
            (depth_deg > FOLDED_DEPTH_DEG).then(|| format!(
                "light \"{name}\" is {depth_deg:.1}° below the horizon at the camera: deep in the Earth's shadow even the folded volume photon map finds few photons and can read high (at solar zenith 96°: twice the path tracer's zenith radiance with 10⁶ photons and within 5 % with 10⁷ at 450 nm, but 1.1–1.5× with 3 × 10⁷ at 351 nm, see the book's The sky, twilight); check it with method = \"path\" (seconds for a sky sensor's zenith)"
            ))
        }
    }
}

/// How far below the horizon (degrees) the sun may be before a folded map is warned about.
pub const FOLDED_DEPTH_DEG: f64 = 3.0;
