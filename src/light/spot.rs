//! A spotlight: intensity I(θ) = I₀(λ) S(cos θ) about an axis, where the falloff S is 1 inside
//! the cone of half-angle θ_start, 0 outside θ_total, and the smoothstep 3t² − 2t³ of
//! t = (cos θ − cos θ_total)/(cos θ_start − cos θ_total) in between (PBRT4 §12.1.2).
//!
//! Flux Φ = 2π ∫I₀ dλ · [(1 − cos θ_start) + (cos θ_start − cos θ_total)/2], since ∫₀¹ S dt = 1/2.

use crate::geometry::Frame;
use crate::sampling::uniform_cone;
use glam::DVec3;
use std::f64::consts::PI;

use super::{Incident, LightSpectrum};

/// A spotlight (see the module docs).
#[derive(Clone, Debug)]
pub struct SpotLight {
    /// Position, m.
    pub position: DVec3,
    /// Unit axis of the cone.
    pub axis: DVec3,
    /// cos θ_total: no light beyond this half-angle.
    pub cos_total: f64,
    /// cos θ_start: full intensity within this half-angle.
    pub cos_start: f64,
    /// On-axis spectral intensity I₀(λ), W sr⁻¹ nm⁻¹.
    pub emission: LightSpectrum,
}

impl SpotLight {
    /// The falloff S(cos θ).
    pub fn falloff(&self, cos_theta: f64) -> f64 {
        if cos_theta >= self.cos_start {
            return 1.0;
        }
        if cos_theta <= self.cos_total {
            return 0.0;
        }
        let t = (cos_theta - self.cos_total) / (self.cos_start - self.cos_total);
        t * t * (3.0 - 2.0 * t)
    }

    /// Solid-angle integral of the falloff, sr.
    pub fn falloff_solid_angle(&self) -> f64 {
        2.0 * PI * ((1.0 - self.cos_start) + 0.5 * (self.cos_start - self.cos_total))
    }

    /// Φ = Ω_S ∫ I₀ dλ within the scene's wavelength range, W.
    pub fn power_w(&self) -> f64 {
        self.falloff_solid_angle() * self.emission.integral()
    }

    /// A direction with density S(cos θ)/Ω_S: the inner cone with probability
    /// (1 − cos θ_start)/(Ω_S/2π), uniformly; otherwise the falloff ring, with cos θ drawn from
    /// the density ∝ S by inverting its CDF F(t) = 2t³ − t⁴.
    pub fn emit_dir(&self, u_choice: f64, u: [f64; 2]) -> DVec3 {
        let inner = 2.0 * PI * (1.0 - self.cos_start) / self.falloff_solid_angle();
        let local = if u_choice < inner {
            uniform_cone(u, self.cos_start)
        } else {
            let t = invert_ring_cdf(u[0]);
            let cos_theta = self.cos_total + t * (self.cos_start - self.cos_total);
            let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
            let phi = 2.0 * PI * u[1];
            DVec3::new(sin_theta * phi.cos(), sin_theta * phi.sin(), cos_theta)
        };
        Frame::from_normal(self.axis).to_world(local)
    }

    /// Irradiance I₀ S(cos θ)/d², so weight = S/d².
    pub fn incident(&self, p: DVec3) -> Option<Incident> {
        let d = self.position - p;
        let dist2 = d.length_squared();
        if dist2 <= 0.0 {
            return None;
        }
        let dist = dist2.sqrt();
        let wi = d / dist;
        let s = self.falloff(-wi.dot(self.axis));
        (s > 0.0).then(|| Incident { wi, dist, weight: s / dist2 })
    }
}

/// Solves 2t³ − t⁴ = u for t in [0, 1] by Newton's method safeguarded with bisection.
fn invert_ring_cdf(u: f64) -> f64 {
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    let mut t = u.cbrt().clamp(0.0, 1.0);
    for _ in 0..60 {
        let f = 2.0 * t * t * t - t * t * t * t - u;
        if f > 0.0 {
            hi = t
        } else {
            lo = t
        }
        let df = 6.0 * t * t - 4.0 * t * t * t;
        let next = if df > 0.0 { t - f / df } else { 0.5 * (lo + hi) };
        t = if next > lo && next < hi { next } else { 0.5 * (lo + hi) };
        if hi - lo < 1e-14 {
            break;
        }
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::{Rng, Stream};
    use crate::spectrum::Spectrum;
    use crate::testing::chi2::chi2_sphere;

    fn spot() -> SpotLight {
        SpotLight {
            position: DVec3::ZERO,
            axis: DVec3::Z,
            cos_total: 35f64.to_radians().cos(),
            cos_start: 20f64.to_radians().cos(),
            emission: LightSpectrum::new(Spectrum::Constant(1.0), 400.0, 700.0).unwrap(),
        }
    }

    #[test]
    fn emitted_directions_follow_the_falloff() {
        let s = spot();
        let mut rng = Rng::for_task(21, Stream::Test, 0);
        let p = chi2_sphere(
            200,
            8,
            300_000,
            || Some(s.emit_dir(rng.uniform(), rng.uniform2())),
            |w| s.falloff(w.z) / s.falloff_solid_angle(),
        );
        assert!(p > 1e-3, "p = {p}");
    }

    #[test]
    fn ring_cdf_inverts() {
        for i in 0..=100 {
            let u = i as f64 / 100.0;
            let t = invert_ring_cdf(u);
            assert!((2.0 * t.powi(3) - t.powi(4) - u).abs() < 1e-12, "u = {u}, t = {t}");
        }
    }

    #[test]
    fn power_is_the_integral_of_intensity() {
        // Numerical ∫ S(cos θ) dω = 2π ∫ S(z) dz by Simpson, independent of the closed form.
        let s = spot();
        let f = |z: f64| s.falloff(z);
        let numeric = 2.0 * PI * crate::quadrature::simpson(&f, s.cos_total, 1.0, 20_000);
        assert!((numeric - s.falloff_solid_angle()).abs() < 1e-8);
        assert!((s.power_w() - numeric * 300.0).abs() < 1e-5);
    }
}
