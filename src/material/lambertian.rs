//! Lambertian (ideal diffuse) reflection: f_r = ρ(λ)/π on the side the light arrives from.

use crate::geometry::Frame;
use crate::sampling::cosine_hemisphere;
use crate::spectrum::Spectrum;
use glam::DVec3;

/// Ideal diffuse reflection (see the module docs).
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::{Rng, Stream};
    use crate::sampling::cosine_hemisphere_pdf;
    use crate::testing::chi2::chi2_sphere;

    #[test]
    fn sampled_directions_are_cosine_distributed_on_the_arrival_side() {
        let n = DVec3::new(0.3, -0.5, 0.8).normalize();
        // Arriving from the back side: directions leave on the side opposite n.
        let dir = n;
        let frame = Frame::from_normal(-n);
        let mut rng = Rng::for_task(31, Stream::Test, 0);
        let p = chi2_sphere(
            20,
            20,
            200_000,
            || Some(frame.to_local(Lambertian::sample(dir, n, rng.uniform2()))),
            |w| cosine_hemisphere_pdf(w.z),
        );
        assert!(p > 1e-3, "p = {p}");
    }
}
