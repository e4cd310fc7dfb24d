//! A luminaire described by measured photometry: intensity I_v(ω) in candela from a photometric
//! web ([`crate::luminaire`]), placed in the scene, with a lamp spectrum.
//!
//! Spectral intensity toward ω: I_e(ω, λ) = k · I_v(ω_local) · e(λ), where e(λ) is the spectral
//! intensity of one candela of the lamp's light (W sr⁻¹ nm⁻¹ cd⁻¹, [`crate::luminaire::per_candela`])
//! and k = flux_scale × the LM-63 tilt factor at the installed tilt. So the emitted power within
//! the scene's wavelength range is
//!
//! Φ_e = k Φ_v ∫_{min}^{max} e(λ) dλ,   Φ_v = ∫ I_v dω (the web's own quadrature, lm).
//!
//! Photons start at the photometric centre, or (near field) at a point drawn uniformly over the
//! luminous opening, and leave in a direction drawn with density I_v(ω)/Φ_v. A shadow ray sees
//! the same source: irradiance k I_v(−ω_i) e(λ) / d² from the start point it samples.

use super::{Incident, LightSpectrum};
use crate::luminaire::{Opening, PhotometricWeb, Placement, WebSampler};
use crate::rng::Rng;
use glam::DVec3;
use std::sync::Arc;

/// A luminaire from measured photometry (see the module docs).
#[derive(Clone, Debug)]
pub struct LuminaireLight {
    /// The intensity I_v(C, γ), cd, in the luminaire frame.
    pub web: Arc<PhotometricWeb>,
    /// Draws emission directions with density I_v/Φ_v.
    pub sampler: Arc<WebSampler>,
    /// Where the luminaire frame sits in the scene and which way it points.
    pub placement: Placement,
    /// Where photons start, in the luminaire frame ([`Opening::POINT`] for a point source).
    pub opening: Opening,
    /// k: flux_scale × tilt factor.
    pub intensity_scale: f64,
    /// e(λ): spectral intensity per candela, W sr⁻¹ nm⁻¹ cd⁻¹.
    pub emission: LightSpectrum,
}

impl LuminaireLight {
    /// Luminous intensity toward the scene direction `dir` (unit), cd.
    pub fn intensity_cd(&self, dir: DVec3) -> f64 {
        self.intensity_scale * self.web.intensity(self.placement.to_local(dir))
    }

    /// Luminous flux emitted, lm.
    pub fn flux_lm(&self) -> f64 {
        self.intensity_scale * self.sampler.flux_lm()
    }

    /// Radiant flux within the scene's wavelength range, W.
    pub fn power_w(&self) -> f64 {
        self.flux_lm() * self.emission.integral()
    }

    /// A photon start point in the scene.
    pub fn start(&self, rng: &mut Rng) -> DVec3 {
        if self.opening.is_point() {
            return self.placement.position;
        }
        self.placement.position + self.placement.to_world(self.opening.sample(rng))
    }

    /// Start point, unit direction and (zero) normal of a photon.
    pub fn emit(&self, rng: &mut Rng) -> (DVec3, DVec3, DVec3) {
        let origin = self.start(rng);
        let local = self.sampler.sample(&self.web, [rng.uniform(), rng.uniform(), rng.uniform()]);
        (origin, self.placement.to_world(local), DVec3::ZERO)
    }

    /// Density of emitted directions toward the scene direction `dir`, sr⁻¹.
    pub fn pdf_dir(&self, dir: DVec3) -> f64 {
        self.sampler.pdf(&self.web, self.placement.to_local(dir))
    }

    /// The luminaire seen from `p`: irradiance weight k I_v / d² toward a start point drawn from
    /// `u` (the opening uses a third uniform taken from the low bits of `u[0]`).
    pub fn incident(&self, p: DVec3, u: [f64; 2]) -> Option<Incident> {
        let origin = if self.opening.is_point() {
            self.placement.position
        } else {
            let u2 = (u[0] * 65536.0).fract();
            self.placement.position + self.placement.to_world(self.opening.sample_u([u[0], u[1], u2]))
        };
        let d = origin - p;
        let dist2 = d.length_squared();
        if dist2 <= 0.0 {
            return None;
        }
        let dist = dist2.sqrt();
        let wi = d / dist;
        let i = self.intensity_cd(-wi);
        (i > 0.0).then(|| Incident { wi, dist, weight: i / dist2 })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::luminaire::WebAxes;
    use crate::rng::Stream;
    use crate::spectrum::Spectrum;
    use crate::testing::chi2::chi2_sphere;

    /// I_v = 100 cd · (1 + cos C sin γ) below the horizon, hanging at height 2 m.
    fn light(opening: Opening) -> LuminaireLight {
        let c: Vec<f64> = (0..36).map(|i| 10.0 * i as f64).collect();
        let g: Vec<f64> = (0..=18).map(|j| 5.0 * j as f64).collect();
        let cd = c
            .iter()
            .flat_map(|ci| g.iter().map(move |gj| 100.0 * (1.0 + ci.to_radians().cos() * gj.to_radians().sin())))
            .collect();
        let web = PhotometricWeb::new(WebAxes::TYPE_C, c, true, g, cd).unwrap();
        let sampler = WebSampler::new(&web).unwrap();
        let per_cd = crate::luminaire::per_candela(&Spectrum::Constant(1.0)).unwrap();
        LuminaireLight {
            web: Arc::new(web),
            sampler: Arc::new(sampler),
            placement: Placement::hanging(DVec3::new(0.0, 2.0, 0.0)),
            opening,
            intensity_scale: 2.0,
            emission: LightSpectrum::new(per_cd, 380.0, 780.0).unwrap(),
        }
    }

    #[test]
    fn intensity_follows_the_placement() {
        let l = light(Opening::POINT);
        // Straight down is γ = 0: 2 × 100 cd. Toward +X at 45° below the horizon is C0, γ = 45°.
        assert!((l.intensity_cd(DVec3::NEG_Y) - 200.0).abs() < 1e-9);
        let d = DVec3::new(1.0, -1.0, 0.0).normalize();
        let want = 200.0 * (1.0 + 45f64.to_radians().sin());
        // The web interpolates linearly in cos γ between 5° nodes; sin γ is smooth, so within 1e-3.
        assert!((l.intensity_cd(d) / want - 1.0).abs() < 1e-3);
        assert_eq!(l.intensity_cd(DVec3::Y), 0.0);
        // C90 is −Z in the scene: there cos C = 0.
        assert!((l.intensity_cd(DVec3::new(0.0, -1.0, -1.0).normalize()) - 200.0).abs() < 1e-9);
    }

    #[test]
    fn power_is_flux_times_watts_per_lumen_in_range() {
        let l = light(Opening::POINT);
        // The cos C term integrates to zero over C: Φ_v = 2 × 100 × 2π sr (the lower hemisphere).
        let flux = 2.0 * 100.0 * 2.0 * std::f64::consts::PI;
        assert!((l.flux_lm() / flux - 1.0).abs() < 1e-12);
        assert!((l.power_w() - flux * l.emission.integral()).abs() < 1e-12);
    }

    #[test]
    fn emitted_directions_follow_the_intensity_in_the_scene() {
        let l = light(Opening::POINT);
        let mut rng = Rng::for_task(9, Stream::Test, 0);
        let p = chi2_sphere(40, 36, 300_000, || Some(l.emit(&mut rng).1), |w| l.intensity_cd(w) / l.flux_lm());
        assert!(p > 1e-3, "p = {p}");
        assert!((l.pdf_dir(DVec3::NEG_Y) - l.intensity_cd(DVec3::NEG_Y) / l.flux_lm()).abs() < 1e-12);
    }

    #[test]
    fn the_opening_spreads_start_points_and_shadow_samples() {
        let l = light(Opening::from_lm63(0.2, 0.4, 0.0).0);
        let mut rng = Rng::for_task(10, Stream::Test, 0);
        for _ in 0..1000 {
            let o = l.start(&mut rng) - l.placement.position;
            // Length 0.4 along C0 = +X, width 0.2 along C90 = −Z, in the plane y = 2.
            assert!(o.x.abs() <= 0.2 && o.z.abs() <= 0.1 && o.y == 0.0, "{o}");
            let inc = l.incident(DVec3::ZERO, rng.uniform2()).unwrap();
            let hit = inc.wi * inc.dist;
            assert!((hit.y - 2.0).abs() < 1e-12 && hit.x.abs() <= 0.2 && hit.z.abs() <= 0.1);
        }
        assert!(l.incident(DVec3::new(0.0, 3.0, 0.0), [0.5, 0.5]).is_none(), "nothing goes up");
    }
}
