//! A pinhole camera.

use super::Ray;
use glam::DVec3;
use serde::Serialize;

/// A pinhole at `position` looking at `look_at`; `fov_deg` is the full vertical field of view.
/// Pixel (0, 0) is the top-left corner of the image.
#[derive(Clone, Debug, Serialize)]
pub struct Camera {
    /// Eye point (the pinhole), m.
    pub position: DVec3,
    /// A point on the optical axis, m.
    pub look_at: DVec3,
    /// Up direction as given; the image's vertical is its part orthogonal to the view.
    pub up: DVec3,
    /// Full vertical field of view, degrees.
    pub fov_deg: f64,
    /// Image width, pixels.
    pub width: usize,
    /// Image height, pixels.
    pub height: usize,
    #[serde(skip)]
    basis: [DVec3; 3],
}

impl Camera {
    /// `up` must not be parallel to the viewing direction (the scene validator checks).
    pub fn new(position: DVec3, look_at: DVec3, up: DVec3, fov_deg: f64, width: usize, height: usize) -> Camera {
        let forward = (look_at - position).normalize();
        let right = forward.cross(up).normalize();
        let true_up = right.cross(forward);
        Camera { position, look_at, up, fov_deg, width, height, basis: [right, true_up, forward] }
    }

    /// The ray through image position (x, y) in pixels (continuous: pixel i spans [i, i+1)).
    pub fn ray(&self, x: f64, y: f64) -> Ray {
        let tan_half = (0.5 * self.fov_deg.to_radians()).tan();
        let aspect = self.width as f64 / self.height as f64;
        let sx = (2.0 * x / self.width as f64 - 1.0) * tan_half * aspect;
        let sy = (1.0 - 2.0 * y / self.height as f64) * tan_half;
        let [right, up, forward] = self.basis;
        Ray::new(self.position, (forward + sx * right + sy * up).normalize())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centre_and_edges_follow_the_field_of_view() {
        let c = Camera::new(DVec3::ZERO, DVec3::new(0.0, 0.0, -1.0), DVec3::Y, 60.0, 200, 100);
        let centre = c.ray(100.0, 50.0).dir;
        assert!((centre - DVec3::new(0.0, 0.0, -1.0)).length() < 1e-12);
        // Top edge is 30° above the axis; right edge at atan(2 tan 30°) to the right.
        let top = c.ray(100.0, 0.0).dir;
        assert!((top.y.atan2(-top.z).to_degrees() - 30.0).abs() < 1e-9);
        let right = c.ray(200.0, 50.0).dir;
        let expect = (2.0 * 30f64.to_radians().tan()).atan().to_degrees();
        assert!((right.x.atan2(-right.z).to_degrees() - expect).abs() < 1e-9);
    }
}
