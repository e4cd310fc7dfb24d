//! A sky: uniform spectral radiance L(λ) arriving from every direction above its horizon
//! (directions ω with ω·up > sin h₀, elevation h₀ = `horizon_deg`, default 0°: the upper
//! hemisphere), from infinitely far away — the light a mirage shows below the horizon, and the
//! diffuse skylight of daytime scenes. On a round Earth a ray that leaves the atmosphere without
//! meeting the ground sees sky even a little below the observer's horizontal plane (refraction
//! bends it down by up to a degree); a negative `horizon_deg` covers those directions.
//!
//! Photons (as for an environment light in PBRT4 §12.5): a direction ω uniform over the sky's
//! cap of solid angle Ω = 2π(1 − sin h₀), then a start point uniform on the disk of radius r that
//! the target sphere (centre c, radius r: the scene's bounding sphere unless the scene names a
//! target box) casts perpendicular to ω, upstream of the whole scene. The flux crossing that disk
//! is L·πr² per unit solid angle, so Φ = Ω·πr²·∫L dλ. Shadow rays see the sky only from inside
//! the target sphere, so both passes simulate the same light.

use crate::geometry::Frame;
use crate::sampling::concentric_disk;
use glam::DVec3;
use std::f64::consts::PI;

use super::{Incident, LightSpectrum};

/// Uniform radiance from every direction above a horizon, at infinity (see the module docs).
#[derive(Clone, Debug)]
pub struct SkyLight {
    /// Unit zenith direction.
    pub up: DVec3,
    /// sin h₀ of the horizon's elevation: the sky covers ω·up > sin h₀.
    pub sin_horizon: f64,
    /// The sphere photons are aimed at.
    pub target_centre: DVec3,
    /// Radius of the target sphere, m.
    pub target_radius: f64,
    /// Distance upstream of the target centre at which photons start (beyond every shape).
    pub start_distance: f64,
    /// Spectral radiance, W m⁻² sr⁻¹ nm⁻¹.
    pub emission: LightSpectrum,
}

impl SkyLight {
    /// The sky's solid angle, sr.
    pub fn solid_angle(&self) -> f64 {
        2.0 * PI * (1.0 - self.sin_horizon)
    }

    /// Φ = Ω π r² ∫ L dλ within the scene's wavelength range, W.
    pub fn power_w(&self) -> f64 {
        self.solid_angle() * PI * self.target_radius * self.target_radius * self.emission.integral()
    }

    /// A direction toward the sky, uniform over its cap.
    fn toward_sky(&self, u: [f64; 2]) -> DVec3 {
        let z = self.sin_horizon + u[0] * (1.0 - self.sin_horizon);
        let r = (1.0 - z * z).max(0.0).sqrt();
        let phi = 2.0 * PI * u[1];
        Frame::from_normal(self.up).to_world(DVec3::new(r * phi.cos(), r * phi.sin(), z))
    }

    /// Start point and direction of travel of a photon.
    pub fn emit(&self, u_dir: [f64; 2], u_disk: [f64; 2]) -> (DVec3, DVec3) {
        let w = -self.toward_sky(u_dir);
        let frame = Frame::from_normal(w);
        let [x, y] = concentric_disk(u_disk);
        let origin = self.target_centre - w * self.start_distance + self.target_radius * (x * frame.s + y * frame.t);
        (origin, w)
    }

    /// One direction toward the sky with weight 1/p = Ω, for points inside the target sphere.
    pub fn incident(&self, p: DVec3, u: [f64; 2]) -> Option<Incident> {
        let inside = (p - self.target_centre).length_squared() <= self.target_radius * self.target_radius;
        inside.then(|| Incident { wi: self.toward_sky(u), dist: f64::INFINITY, weight: self.solid_angle() })
    }

    /// Density of [`SkyLight::incident`]'s directions, per steradian.
    pub fn pdf(&self, toward: DVec3) -> f64 {
        if self.sees(toward) { 1.0 / self.solid_angle() } else { 0.0 }
    }

    /// Whether a ray leaving the scene along `view_dir` sees the sky.
    pub fn sees(&self, view_dir: DVec3) -> bool {
        view_dir.dot(self.up) > self.sin_horizon
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::{Rng, Stream};
    use crate::spectrum::Spectrum;

    fn sky() -> SkyLight {
        let emission = LightSpectrum::new(Spectrum::Constant(1.0), 400.0, 700.0).expect("spectrum");
        SkyLight {
            up: DVec3::Y,
            sin_horizon: 0.0,
            target_centre: DVec3::new(1.0, 2.0, 3.0),
            target_radius: 2.0,
            start_distance: 10.0,
            emission,
        }
    }

    #[test]
    fn photons_start_upstream_and_cross_the_target_disk_going_down() {
        let s = sky();
        let mut rng = Rng::for_task(1, Stream::Test, 0);
        for _ in 0..1000 {
            let (o, w) = s.emit(rng.uniform2(), rng.uniform2());
            assert!(w.y < 0.0 && (w.length() - 1.0).abs() < 1e-12);
            // The ray passes within r of the target centre, after starting 10 m upstream of it.
            let t = (s.target_centre - o).dot(w);
            assert!((t - 10.0).abs() < 1e-9);
            assert!((o + t * w - s.target_centre).length() <= 2.0 + 1e-9);
        }
    }

    #[test]
    fn power_is_two_pi_times_the_disk_times_the_radiance() {
        // ∫ L dλ = 300 over 400–700 nm; Φ = 2π · π·2² · 300.
        assert!((sky().power_w() - 2.0 * PI * PI * 4.0 * 300.0).abs() < 1e-6);
    }

    #[test]
    fn a_sky_reaching_below_the_horizontal_covers_its_cap_uniformly() {
        // Horizon at −30°: Ω = 2π(1 + 1/2) = 3π, and directions reach down to sin h = −1/2.
        let s = SkyLight { sin_horizon: -0.5, ..sky() };
        assert!((s.solid_angle() - 3.0 * PI).abs() < 1e-12);
        let mut rng = Rng::for_task(3, Stream::Test, 0);
        let n = 100_000;
        let below =
            (0..n).filter(|_| s.incident(s.target_centre, rng.uniform2()).is_some_and(|i| i.wi.y < 0.0)).count();
        // The cap's part below the horizontal is 1/3 of it.
        assert!((below as f64 / n as f64 - 1.0 / 3.0).abs() < 0.01, "{below}");
        assert!(s.sees(DVec3::new(1.0, -0.4, 0.0).normalize()) && !s.sees(DVec3::new(1.0, -0.7, 0.0).normalize()));
    }

    #[test]
    fn irradiance_on_an_upward_surface_is_pi_l() {
        // E = ∫ L cos θ dω over the hemisphere = πL: the mean of L·cos θ·weight over samples.
        let s = sky();
        let mut rng = Rng::for_task(2, Stream::Test, 0);
        let n = 200_000;
        let e: f64 =
            (0..n).map(|_| s.incident(s.target_centre, rng.uniform2()).map_or(0.0, |i| i.wi.y * i.weight)).sum::<f64>()
                / n as f64;
        // cos θ is uniform on [0, 1] for uniform hemisphere directions: σ = 2π/√12/√n.
        let se = 2.0 * PI / 12f64.sqrt() / (n as f64).sqrt();
        assert!((e - PI).abs() < 4.0 * se, "E = {e}");
        assert!(s.incident(s.target_centre + DVec3::new(0.0, 3.0, 0.0), [0.5, 0.5]).is_none());
    }
}
