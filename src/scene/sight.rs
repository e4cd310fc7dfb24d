//! The lowest line of sight of a scene: how close to the horizon (the plane y = const, +y up)
//! its camera, its sensors and its lights look. The effect plan reads it to say whether an
//! atmosphere's bending matters ([`crate::media::bending`]).

use crate::geometry::{Camera, Projection};
use crate::light::Light;
use crate::sensor::{NamedSensor, Sensor};

/// Points sampled along each edge of a pinhole camera's image.
const EDGE_SAMPLES: usize = 9;

/// The lowest elevation, degrees, of any direction the scene measures light along or receives
/// it from: the camera's field (a pinhole's image edges, sampled; an all-sky camera's rim), the
/// `sky_radiance` sensors' directions, and the directional lights' (suns') directions. Sensors
/// that gather from a hemisphere and lights that shine in every direction give −90°.
pub fn lowest_elevation_deg(camera: &Camera, sensors: &[NamedSensor], lights: &[Light]) -> f64 {
    let elevation = |y: f64| y.clamp(-1.0, 1.0).asin().to_degrees();
    let camera_low = match camera.projection {
        Projection::Pinhole => edge_points(camera.width as f64, camera.height as f64)
            .filter_map(|(x, y)| camera.ray(x, y))
            .map(|r| elevation(r.dir.y))
            .fold(90.0, f64::min),
        Projection::EqualArea => {
            let axis = (camera.look_at - camera.position).normalize();
            elevation(axis.y) - 0.5 * camera.fov_deg
        }
    };
    let sensors_low = sensors.iter().map(|s| match &s.sensor {
        Sensor::SkyRadiance(sky) => {
            (0..sky.directions_deg.len()).map(|k| elevation(sky.direction(k).y)).fold(90.0, f64::min)
        }
        Sensor::IlluminancePlane(_) | Sensor::OceanProfile(_) => -90.0,
    });
    let lights_low = lights.iter().map(|l| match l {
        Light::Directional(d) => elevation(-d.dir.y),
        Light::Sky(_) => 0.0,
        Light::Area(_) | Light::Point(_) | Light::Spot(_) | Light::Luminaire(_) => -90.0,
    });
    sensors_low.chain(lights_low).fold(camera_low, f64::min)
}

/// Image positions along the four edges of a `w` × `h` image, corners included.
fn edge_points(w: f64, h: f64) -> impl Iterator<Item = (f64, f64)> {
    (0..EDGE_SAMPLES).flat_map(move |i| {
        let f = i as f64 / (EDGE_SAMPLES - 1) as f64;
        [(f * w, 0.0), (f * w, h), (0.0, f * h), (w, f * h)]
    })
}
