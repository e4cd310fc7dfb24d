//! Radiance arriving at a point from listed directions of the sky, per band: the quantity sky
//! radiometers, all-sky cameras and radiative-transfer benchmarks report.
//!
//! A direction is given by its view zenith angle θ (0° straight up along +y, 90° the horizon,
//! above 90° looking down) and azimuth φ in the scene's compass (0° toward −z, 90° toward +x, as
//! a sun's `azimuth_deg`): the sensor looks along
//!
//! d = (sin θ sin φ, cos θ, −sin θ cos φ)
//!
//! and reads the radiance L(λ) travelling toward it along −d, as a camera pixel would (the same
//! eye pass, photon map or path tracer, and the same wavelength sampling, `bands` or `hero`).
//! Each band's value is the mean of `samples` estimates whose wavelength jitter is stratified
//! over the samples, so it estimates the band average (1/Δλ)∫_b L dλ, W m⁻² sr⁻¹ nm⁻¹.
//!
//! The reading has one point per direction (nx = the number of directions, ny = 1). Columns:
//! `L_mean` (the mean over the bands), `view_zenith_deg`, `view_azimuth_deg`, then
//! `L_<lo>_<hi>nm` per band.

use glam::DVec3;

/// Radiance at a point from listed directions (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct SkyRadiance {
    /// Where the radiance is measured, m.
    pub position: DVec3,
    /// (view zenith, view azimuth) pairs, degrees.
    pub directions_deg: Vec<[f64; 2]>,
    /// Estimates averaged per direction and band.
    pub samples: usize,
}

impl SkyRadiance {
    /// The unit vector the sensor looks along for direction `k`.
    pub fn direction(&self, k: usize) -> DVec3 {
        view_direction(self.directions_deg[k][0], self.directions_deg[k][1])
    }
}

/// d = (sin θ sin φ, cos θ, −sin θ cos φ) for view zenith θ and azimuth φ in degrees.
pub fn view_direction(zenith_deg: f64, azimuth_deg: f64) -> DVec3 {
    let (t, p) = (zenith_deg.to_radians(), azimuth_deg.to_radians());
    DVec3::new(t.sin() * p.sin(), t.cos(), -t.sin() * p.cos())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn directions_follow_the_suns_compass() {
        let close = |a: DVec3, b: DVec3| (a - b).length() < 1e-15;
        assert!(close(view_direction(0.0, 123.0), DVec3::Y));
        assert!(close(view_direction(90.0, 0.0), -DVec3::Z));
        assert!(close(view_direction(90.0, 90.0), DVec3::X));
        assert!(close(view_direction(180.0, 0.0), -DVec3::Y));
        assert!((view_direction(37.0, 211.0).length() - 1.0).abs() < 1e-15);
    }
}
