//! Lambertian (ideal diffuse) reflection: f_r = ρ(λ)/π on the side the light arrives from.

use crate::geometry::Frame;
use crate::sampling::cosine_hemisphere;
use crate::spectrum::Spectrum;
use glam::DVec3;

#[derive(Clone, Debug)]
pub struct Lambertian {
    /// Reflectance ρ(λ) in [0, 1].
    pub reflectance: Spectrum,
}

impl Lambertian {
    /// A cosine-distributed direction (p = cos θ/π) leaving the surface on the side the path
    /// arrived from, for a path arriving along `dir` at normal `n`. With this sampling the
    /// throughput factor f_r cos θ / p equals ρ.
    pub fn sample(dir: DVec3, n: DVec3, u: [f64; 2]) -> DVec3 {
        let side = if dir.dot(n) < 0.0 { n } else { -n };
        Frame::from_normal(side).to_world(cosine_hemisphere(u))
    }
}
