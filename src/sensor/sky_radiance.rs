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
//!
//! # Limb views
//! A limb sounder sees the air edge-on from outside the atmosphere. `type = "limb"` lists the
//! heights of the tangent points, which lie on the vertical above the scene origin (so a sun's
//! `elevation_deg` and `azimuth_deg` are its elevation and azimuth at every tangent point), and
//! the azimuth φ the horizontal lines of sight look toward. Line k looks along
//! d = (sin φ, 0, −cos φ) through T_k = C + (R + h_k) ŷ (C and R the Earth's centre and radius)
//! from O_k = T_k − D_k d, 1 km above the atmosphere's top: D_k = √((R + top + 1 km)² −
//! (R + h_k)²). Nothing lies above the top, so where on its line the observer is does not change
//! the radiance. The reading's points are the tangent points, and a `tangent_height_m` column
//! follows `view_azimuth_deg`.

use glam::DVec3;

/// Radiance at a point from listed directions, or along a limb's lines of sight (see the module
/// docs).
#[derive(Clone, Debug, PartialEq)]
pub struct SkyRadiance {
    /// Where the radiance of each direction is measured, m.
    pub origins: Vec<DVec3>,
    /// (view zenith, view azimuth) pairs, degrees.
    pub directions_deg: Vec<[f64; 2]>,
    /// Estimates averaged per direction and band.
    pub samples: usize,
    /// A limb's (tangent height m, tangent point) per direction; `None` for a point's sky.
    pub limb: Option<Vec<(f64, DVec3)>>,
}

impl SkyRadiance {
    /// The sky seen from `position` in `directions_deg`.
    pub fn at_point(position: DVec3, directions_deg: Vec<[f64; 2]>, samples: usize) -> SkyRadiance {
        SkyRadiance { origins: vec![position; directions_deg.len()], directions_deg, samples, limb: None }
    }

    /// The limb of an atmosphere of top `top_m` over the sphere of `centre` = (0, −R, 0) and
    /// `radius_m` = R (the scene origin on its surface, +y up there): horizontal lines of sight toward `azimuth_deg`
    /// through the tangent points at `tangent_heights_m` above the origin (see the module docs).
    pub fn limb(
        (centre, radius_m, top_m): (DVec3, f64, f64),
        tangent_heights_m: &[f64],
        azimuth_deg: f64,
        samples: usize,
    ) -> SkyRadiance {
        let p = azimuth_deg.to_radians();
        let d = DVec3::new(p.sin(), 0.0, -p.cos());
        let observer_r = radius_m + top_m + 1000.0;
        let tangents: Vec<(f64, DVec3)> =
            tangent_heights_m.iter().map(|h| (*h, centre + (radius_m + h) * DVec3::Y)).collect();
        let origins = tangents
            .iter()
            .map(|(h, t)| *t - (observer_r * observer_r - (radius_m + h) * (radius_m + h)).sqrt() * d)
            .collect();
        let directions_deg = vec![[90.0, azimuth_deg]; tangent_heights_m.len()];
        SkyRadiance { origins, directions_deg, samples, limb: Some(tangents) }
    }

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
    fn a_limbs_lines_of_sight_graze_their_tangent_points_from_above_the_top() {
        let (r, top) = (6_371_000.0, 100_000.0);
        let centre = DVec3::new(0.0, -r, 0.0);
        let heights = [0.0, 500.0, 30_500.0, 99_000.0];
        for azimuth in [0.0, 30.0, 135.0, -90.0] {
            let s = SkyRadiance::limb((centre, r, top), &heights, azimuth, 8);
            let limb = s.limb.as_ref().unwrap();
            for (k, h) in heights.iter().enumerate() {
                let (o, d, t) = (s.origins[k], s.direction(k), limb[k].1);
                assert_eq!(limb[k].0, *h);
                assert!(((t - centre).length() - (r + h)).abs() < 1e-6 && (t.x, t.z) == (0.0, 0.0));
                assert!(((o - centre).length() - (r + top + 1000.0)).abs() < 1e-6, "the observer 1 km above the top");
                // The line through o along d passes through t, where it is horizontal.
                let along = (t - o).dot(d);
                assert!(along > 0.0 && (o + along * d - t).length() < 1e-6);
                assert!(d.dot(t - centre).abs() < 1e-6 * (r + h), "horizontal at the tangent point");
                let expected = view_direction(90.0, azimuth);
                assert!((d - expected).length() < 1e-12 && s.directions_deg[k] == [90.0, azimuth]);
            }
        }
    }

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
