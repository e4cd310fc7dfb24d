//! Warps from the unit square. Directions are in a local frame whose z axis is the normal.

use glam::DVec3;
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};

/// Shirley–Chiu concentric map from the unit square to the unit disk (PBRT4 §A.5.1):
/// area-preserving, so the density on the disk is 1/π.
pub fn concentric_disk(u: [f64; 2]) -> [f64; 2] {
    let (a, b) = (2.0 * u[0] - 1.0, 2.0 * u[1] - 1.0);
    if a == 0.0 && b == 0.0 {
        return [0.0, 0.0];
    }
    let (r, theta) = if a.abs() > b.abs() { (a, FRAC_PI_4 * (b / a)) } else { (b, FRAC_PI_2 - FRAC_PI_4 * (a / b)) };
    [r * theta.cos(), r * theta.sin()]
}

/// Cosine-weighted hemisphere about +z by Malley's method: p(ω) = cos θ / π.
pub fn cosine_hemisphere(u: [f64; 2]) -> DVec3 {
    let [x, y] = concentric_disk(u);
    let z = (1.0 - x * x - y * y).max(0.0).sqrt();
    DVec3::new(x, y, z)
}

/// Density of [`cosine_hemisphere`] with respect to solid angle.
pub fn cosine_hemisphere_pdf(cos_theta: f64) -> f64 {
    if cos_theta > 0.0 { cos_theta / PI } else { 0.0 }
}

/// Uniform direction on the unit sphere: p(ω) = 1/(4π).
pub fn uniform_sphere(u: [f64; 2]) -> DVec3 {
    let z = 1.0 - 2.0 * u[0];
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = 2.0 * PI * u[1];
    DVec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// Density of [`uniform_sphere`].
pub fn uniform_sphere_pdf() -> f64 {
    1.0 / (4.0 * PI)
}

/// Uniform direction in the cone about +z with cos θ ≥ `cos_max`: p(ω) = 1/(2π(1 − cos_max)).
pub fn uniform_cone(u: [f64; 2], cos_max: f64) -> DVec3 {
    let cos_theta = (1.0 - u[0]) + u[0] * cos_max;
    let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
    let phi = 2.0 * PI * u[1];
    DVec3::new(sin_theta * phi.cos(), sin_theta * phi.sin(), cos_theta)
}

/// Density of [`uniform_cone`] for directions inside the cone.
pub fn uniform_cone_pdf(cos_max: f64) -> f64 {
    1.0 / (2.0 * PI * (1.0 - cos_max))
}

/// Cosine-weighted direction within the cone about +z with sin θ ≤ `sin_max` (a cosine-weighted
/// hemisphere restricted to the cone, by Malley's method on the disk of radius `sin_max`):
/// p(ω) = cos θ / (π sin²θ_max). This is the direction density of the light crossing a plane
/// normal to +z from a uniformly bright disc (the sun) of angular radius θ_max.
pub fn cosine_cone(u: [f64; 2], sin_max: f64) -> DVec3 {
    let [x, y] = concentric_disk(u);
    let (x, y) = (x * sin_max, y * sin_max);
    DVec3::new(x, y, (1.0 - x * x - y * y).max(0.0).sqrt())
}

/// Density of [`cosine_cone`] for a direction with cosine `cos_theta` about +z.
pub fn cosine_cone_pdf(cos_theta: f64, sin_max: f64) -> f64 {
    let cos_max = (1.0 - sin_max * sin_max).max(0.0).sqrt();
    if cos_theta >= cos_max && sin_max > 0.0 { cos_theta / (PI * sin_max * sin_max) } else { 0.0 }
}

/// Uniform barycentric coordinates (b0, b1, b2) on a triangle (Heitz 2019, "A Low-Distortion Map
/// Between Triangle and Square"); the area density is 1/area.
pub fn uniform_triangle(u: [f64; 2]) -> [f64; 3] {
    let (b0, b1) = if u[0] < u[1] {
        let b0 = u[0] / 2.0;
        (b0, u[1] - b0)
    } else {
        let b1 = u[1] / 2.0;
        (u[0] - b1, b1)
    };
    [b0, b1, 1.0 - b0 - b1]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::{Rng, Stream};
    use crate::testing::chi2::{chi2_1d, chi2_sphere};

    #[test]
    fn uniform_cone_chi_square() {
        let cos_max = 0.8f64;
        let mut rng = Rng::for_task(11, Stream::Test, 0);
        let p = chi2_sphere(
            40,
            16,
            200_000,
            || Some(uniform_cone(rng.uniform2(), cos_max)),
            |w| {
                if w.z >= cos_max { uniform_cone_pdf(cos_max) } else { 0.0 }
            },
        );
        assert!(p > 1e-3, "p = {p}");
    }

    #[test]
    fn cosine_cone_chi_square() {
        // A wide cone, so the sphere's bins resolve it; the density has no scale of its own.
        let sin_max = 0.6f64;
        let mut rng = Rng::for_task(16, Stream::Test, 0);
        let p = chi2_sphere(
            40,
            16,
            200_000,
            || Some(cosine_cone(rng.uniform2(), sin_max)),
            |w| cosine_cone_pdf(w.z, sin_max),
        );
        assert!(p > 1e-3, "p = {p}");
    }

    #[test]
    fn cosine_cone_pdf_integrates_to_one_over_a_narrow_cone() {
        // ∫ cos θ / (π sin²θm) dω over the cone = 2π ∫ cos θ sin θ dθ / (π sin²θm) = 1, for the
        // sun's 0.265° radius too: midpoint rule in θ.
        let sin_max = 0.265f64.to_radians().sin();
        let theta_max = sin_max.asin();
        let n = 10_000;
        let dtheta = theta_max / n as f64;
        let total: f64 = (0..n)
            .map(|i| {
                let t = (i as f64 + 0.5) * dtheta;
                2.0 * PI * t.sin() * cosine_cone_pdf(t.cos(), sin_max) * dtheta
            })
            .sum();
        assert!((total - 1.0).abs() < 1e-6, "integral {total}");
    }

    #[test]
    fn concentric_disk_is_uniform_in_radius_squared_and_angle() {
        // Uniform on the disk <=> r² ~ U(0,1) and φ ~ U(0, 2π) independently.
        let mut rng = Rng::for_task(12, Stream::Test, 0);
        let p_r = chi2_1d(
            (0.0, 1.0),
            40,
            100_000,
            || {
                let [x, y] = concentric_disk(rng.uniform2());
                Some(x * x + y * y)
            },
            |_| 1.0,
        );
        assert!(p_r > 1e-3, "p = {p_r}");
        let mut rng = Rng::for_task(13, Stream::Test, 0);
        let p_phi = chi2_1d(
            (0.0, 2.0 * PI),
            40,
            100_000,
            || {
                let [x, y] = concentric_disk(rng.uniform2());
                Some(y.atan2(x).rem_euclid(2.0 * PI))
            },
            |_| 1.0 / (2.0 * PI),
        );
        assert!(p_phi > 1e-3, "p = {p_phi}");
    }

    #[test]
    fn triangle_barycentrics_are_uniform() {
        // For a uniform point on a triangle, each barycentric b has density 2(1 − b).
        let mut rng = Rng::for_task(14, Stream::Test, 0);
        let p = chi2_1d((0.0, 1.0), 40, 100_000, || Some(uniform_triangle(rng.uniform2())[0]), |b| 2.0 * (1.0 - b));
        assert!(p > 1e-3, "p = {p}");
        let mut rng = Rng::for_task(15, Stream::Test, 0);
        let p = chi2_1d((0.0, 1.0), 40, 100_000, || Some(uniform_triangle(rng.uniform2())[2]), |b| 2.0 * (1.0 - b));
        assert!(p > 1e-3, "p = {p}");
    }
}
