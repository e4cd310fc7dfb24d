//! The camera: a pinhole, or an all-sky (fisheye) camera with the equal-area projection.
//!
//! The equal-area (equisolid, Lambert azimuthal) projection puts a direction at angle θ from
//! the optical axis at the distance ρ = R sin(θ/2)/sin(θ_f/2) from the image centre, along its
//! azimuth about the axis, where R is the radius of the image circle (half the smaller image
//! side, pixels) and θ_f half the field (`fov_deg`/2; 90° for the whole hemisphere). The
//! Lambert map (θ, φ) ↦ 2 sin(θ/2)(cos φ, sin φ) preserves area on the unit sphere, so every
//! pixel inside the circle subtends the same solid angle
//!
//! Ω_pixel = 4π sin²(θ_f/2)/(π R²) = 2π (1 − cos θ_f)/(π R²) sr
//!
//! (Snyder, *Map Projections — A Working Manual*, USGS Professional Paper 1395, 1987, §24).
//! Pixels and parts of pixels outside the circle see nothing (radiance 0).

use super::Ray;
use glam::DVec3;
use serde::Serialize;

/// How directions map onto the image (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Projection {
    /// A pinhole: the image plane at distance 1, `fov_deg` the full vertical field.
    Pinhole,
    /// All-sky (fisheye), equal-area: `fov_deg` the full field across the image circle.
    EqualArea,
}

/// A camera at `position` looking at `look_at`; `fov_deg` is the full vertical field of view
/// of a pinhole, or the field across an all-sky camera's image circle. Pixel (0, 0) is the
/// top-left corner of the image; `up` points to the image's top.
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
    /// How directions map onto the image.
    #[serde(skip_serializing_if = "Projection::is_pinhole")]
    pub projection: Projection,
    #[serde(skip)]
    basis: [DVec3; 3],
}

impl Camera {
    /// `up` must not be parallel to the viewing direction (the scene validator checks).
    pub fn new(position: DVec3, look_at: DVec3, up: DVec3, fov_deg: f64, width: usize, height: usize) -> Camera {
        let forward = (look_at - position).normalize();
        let right = forward.cross(up).normalize();
        let true_up = right.cross(forward);
        let projection = Projection::Pinhole;
        Camera { position, look_at, up, fov_deg, width, height, projection, basis: [right, true_up, forward] }
    }

    /// The same camera with the projection `projection`.
    pub fn with_projection(mut self, projection: Projection) -> Camera {
        self.projection = projection;
        self
    }

    /// The ray through image position (x, y) in pixels (continuous: pixel i spans [i, i+1));
    /// `None` outside an all-sky camera's image circle.
    pub fn ray(&self, x: f64, y: f64) -> Option<Ray> {
        let [right, up, forward] = self.basis;
        match self.projection {
            Projection::Pinhole => {
                let tan_half = (0.5 * self.fov_deg.to_radians()).tan();
                let aspect = self.width as f64 / self.height as f64;
                let sx = (2.0 * x / self.width as f64 - 1.0) * tan_half * aspect;
                let sy = (1.0 - 2.0 * y / self.height as f64) * tan_half;
                Some(Ray::new(self.position, (forward + sx * right + sy * up).normalize()))
            }
            Projection::EqualArea => {
                let r_px = 0.5 * self.width.min(self.height) as f64;
                let (dx, dy) = (x - 0.5 * self.width as f64, 0.5 * self.height as f64 - y);
                let rho = (dx * dx + dy * dy).sqrt() / r_px;
                if rho > 1.0 {
                    return None;
                }
                // ρ = sin(θ/2)/sin(θ_f/2): θ = 2 asin(ρ sin(θ_f/2)).
                let theta = 2.0 * (rho * (0.25 * self.fov_deg.to_radians()).sin()).asin();
                let (sin_t, cos_t) = theta.sin_cos();
                let (cx, cy) = if rho > 0.0 { (dx / (rho * r_px), dy / (rho * r_px)) } else { (0.0, 0.0) };
                Some(Ray::new(self.position, (cos_t * forward + sin_t * (cx * right + cy * up)).normalize()))
            }
        }
    }

    /// The solid angle of a pixel inside an all-sky camera's image circle,
    /// 4π sin²(θ_f/2)/(π R²) (module docs); `None` for a pinhole.
    pub fn all_sky_pixel_sr(&self) -> Option<f64> {
        let r_px = 0.5 * self.width.min(self.height) as f64;
        (self.projection == Projection::EqualArea)
            .then(|| 4.0 * (0.25 * self.fov_deg.to_radians()).sin().powi(2) / (r_px * r_px))
    }
}

impl Projection {
    /// True for the pinhole (the default, left out of serialised settings).
    pub fn is_pinhole(&self) -> bool {
        *self == Projection::Pinhole
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centre_and_edges_follow_the_field_of_view() {
        let c = Camera::new(DVec3::ZERO, DVec3::new(0.0, 0.0, -1.0), DVec3::Y, 60.0, 200, 100);
        let centre = c.ray(100.0, 50.0).expect("pinhole").dir;
        assert!((centre - DVec3::new(0.0, 0.0, -1.0)).length() < 1e-12);
        // Top edge is 30° above the axis; right edge at atan(2 tan 30°) to the right.
        let top = c.ray(100.0, 0.0).expect("pinhole").dir;
        assert!((top.y.atan2(-top.z).to_degrees() - 30.0).abs() < 1e-9);
        let right = c.ray(200.0, 50.0).expect("pinhole").dir;
        let expect = (2.0 * 30f64.to_radians().tan()).atan().to_degrees();
        assert!((right.x.atan2(-right.z).to_degrees() - expect).abs() < 1e-9);
    }

    /// Solid angle of the spherical quadrilateral a, b, c, d (in order) on the unit sphere: two
    /// triangles by Van Oosterom & Strackee's formula (IEEE Trans. Biomed. Eng. 30, 125, 1983):
    /// tan(Ω/2) = a·(b × c)/(1 + a·b + b·c + c·a).
    fn quad_sr(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> f64 {
        let tri =
            |a: DVec3, b: DVec3, c: DVec3| 2.0 * a.dot(b.cross(c)).abs().atan2(1.0 + a.dot(b) + b.dot(c) + c.dot(a));
        tri(a, b, c) + tri(a, c, d)
    }

    /// An all-sky camera at the origin looking up, azimuth 0° (−z) at the image's top.
    fn all_sky(fov_deg: f64, n: usize) -> Camera {
        Camera::new(DVec3::ZERO, DVec3::Y, DVec3::new(0.0, 0.0, -1.0), fov_deg, n, n)
            .with_projection(Projection::EqualArea)
    }

    #[test]
    fn every_all_sky_pixel_subtends_the_same_solid_angle() {
        // Each pixel's solid angle, summed over 24 × 24 sub-squares whose corners are mapped to
        // the sphere (spherical quadrilaterals), against 4π sin²(θ_f/2)/(π R²): at the centre,
        // half-way out and at the circle's edge (the last pixel wholly inside), for the
        // hemisphere and a 120° field, to 1e-6 (the sub-squares' curved edges).
        for fov in [180.0, 120.0] {
            let n = 64;
            let c = all_sky(fov, n);
            let want = c.all_sky_pixel_sr().expect("all-sky");
            assert!(
                (want * std::f64::consts::PI * 32.0 * 32.0
                    - 2.0 * std::f64::consts::PI * (1.0 - (0.5 * fov).to_radians().cos()))
                .abs()
                    < 1e-12
            );
            for (px, py) in [(32, 32), (48, 20), (52, 12), (62, 32)] {
                let k = 24;
                let dir = |x: f64, y: f64| c.ray(x, y).expect("inside the circle").dir;
                let mut sr = 0.0;
                for j in 0..k {
                    for i in 0..k {
                        let (x0, y0) = (px as f64 + i as f64 / k as f64, py as f64 + j as f64 / k as f64);
                        let h = 1.0 / k as f64;
                        sr += quad_sr(dir(x0, y0), dir(x0 + h, y0), dir(x0 + h, y0 + h), dir(x0, y0 + h));
                    }
                }
                assert!((sr / want - 1.0).abs() < 1e-6, "fov {fov}°, pixel ({px}, {py}): {sr} sr, want {want}");
            }
        }
    }

    #[test]
    fn the_all_sky_image_is_centred_on_the_zenith_with_azimuth_zero_at_the_top() {
        let c = all_sky(180.0, 100);
        let ray = |x: f64, y: f64| c.ray(x, y).expect("inside").dir;
        assert!((ray(50.0, 50.0) - DVec3::Y).length() < 1e-12, "centre: zenith");
        // The top of the circle is the horizon toward azimuth 0° (−z); looking up from below,
        // azimuth 90° (+x) is on the left, 270° (−x) on the right.
        assert!((ray(50.0, 0.0) - DVec3::new(0.0, 0.0, -1.0)).length() < 1e-12);
        assert!((ray(0.0, 50.0) - DVec3::X).length() < 1e-12);
        assert!((ray(100.0, 50.0) + DVec3::X).length() < 1e-12);
        // Zenith angle 60° lies at ρ = sin 30°/sin 45° of the radius.
        let rho = 50.0 * 30f64.to_radians().sin() / 45f64.to_radians().sin();
        assert!((ray(50.0, 50.0 - rho).y - 0.5).abs() < 1e-12);
        assert!(c.ray(2.0, 2.0).is_none(), "outside the circle");
    }
}
