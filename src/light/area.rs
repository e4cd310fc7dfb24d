//! Diffuse area emitters: a quad, disk or sphere radiating L_e(λ) uniformly (Lambertian) from
//! one or both sides.
//!
//! Flux Φ = π A s ∫ L_e(λ) dλ for area A and s emitting sides.

use crate::geometry::{Frame, Shape};
use crate::rng::Rng;
use crate::sampling::cosine_hemisphere;
use glam::DVec3;
use serde::Serialize;

use super::{Incident, LightSpectrum};

/// Which side of the shape emits: the front (along the shape's normal), the back, or both.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Side {
    /// The side the shape's normal points to.
    Front,
    /// The side opposite the normal.
    Back,
    /// Both sides.
    Both,
}

/// A diffuse area emitter (see the module docs).
#[derive(Clone, Debug)]
pub struct AreaLight {
    /// The emitting surface.
    pub shape: Shape,
    /// Which sides emit.
    pub side: Side,
    /// Spectral radiance L_e(λ), W m⁻² sr⁻¹ nm⁻¹.
    pub emission: LightSpectrum,
}

impl AreaLight {
    fn sides(&self) -> f64 {
        if self.side == Side::Both { 2.0 } else { 1.0 }
    }

    /// Φ = π A s ∫ L_e dλ within the scene's wavelength range, W.
    pub fn power_w(&self) -> f64 {
        std::f64::consts::PI * self.shape.area() * self.sides() * self.emission.integral()
    }

    /// Cosine factor of emission toward travel direction `dir` leaving a point with normal `n`:
    /// |cos| on an emitting side, zero otherwise.
    pub fn emitted_cos(&self, n: DVec3, dir: DVec3) -> f64 {
        let c = n.dot(dir);
        match self.side {
            Side::Front if c > 0.0 => c,
            Side::Back if c < 0.0 => -c,
            Side::Both => c.abs(),
            _ => 0.0,
        }
    }

    /// Uniform point, cosine-distributed direction on an emitting side.
    pub fn emit(&self, rng: &mut Rng) -> (DVec3, DVec3, DVec3) {
        let s = self.shape.sample(rng.uniform2());
        let facing = match self.side {
            Side::Front => s.normal,
            Side::Back => -s.normal,
            Side::Both => {
                if rng.uniform() < 0.5 {
                    s.normal
                } else {
                    -s.normal
                }
            }
        };
        let dir = Frame::from_normal(facing).to_world(cosine_hemisphere(rng.uniform2()));
        (s.point, dir, facing)
    }

    /// Uniform-area sample seen from `p`: weight = cos θ_l A / d².
    pub fn incident(&self, p: DVec3, u: [f64; 2]) -> Option<Incident> {
        let s = self.shape.sample(u);
        let d = s.point - p;
        let dist2 = d.length_squared();
        if dist2 <= 0.0 {
            return None;
        }
        let dist = dist2.sqrt();
        let wi = d / dist;
        let cos_l = self.emitted_cos(s.normal, -wi);
        (cos_l > 0.0).then(|| Incident { wi, dist, weight: cos_l * self.shape.area() / dist2 })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Quad;
    use crate::rng::Stream;
    use crate::spectrum::Spectrum;
    use crate::testing::chi2::{chi2_1d, chi2_sphere};

    fn light(side: Side) -> AreaLight {
        AreaLight {
            shape: Shape::Quad(Quad { origin: DVec3::ZERO, u: DVec3::X * 2.0, v: DVec3::Y }),
            side,
            emission: LightSpectrum::new(Spectrum::Constant(1.0), 400.0, 700.0).unwrap(),
        }
    }

    #[test]
    fn emission_is_cosine_distributed_on_the_emitting_sides() {
        for side in [Side::Front, Side::Back, Side::Both] {
            let l = light(side);
            let mut rng = Rng::for_task(41, Stream::Test, side as u64);
            let p = chi2_sphere(
                20,
                16,
                200_000,
                || Some(l.emit(&mut rng).1),
                |w| {
                    let c = l.emitted_cos(DVec3::Z, w);
                    c / std::f64::consts::PI / if side == Side::Both { 2.0 } else { 1.0 }
                },
            );
            assert!(p > 1e-3, "{side:?}: p = {p}");
        }
    }

    #[test]
    fn emission_points_are_uniform_over_the_area() {
        let l = light(Side::Front);
        let mut rng = Rng::for_task(42, Stream::Test, 0);
        let p = chi2_1d((0.0, 2.0), 20, 100_000, || Some(l.emit(&mut rng).0.x), |_| 0.5);
        assert!(p > 1e-3, "p = {p}");
        assert!((l.power_w() - std::f64::consts::PI * 2.0 * 300.0).abs() < 1e-9);
    }

    #[test]
    fn incident_sampling_integrates_to_the_closed_form_irradiance() {
        // Irradiance from a uniform disk of radiance L, radius a, on axis at height h:
        // E = π L a²/(h² + a²) (Modest, Radiative Heat Transfer, view factor of a disk).
        let (a, h) = (0.5, 1.0);
        let l = AreaLight {
            shape: Shape::Disk(crate::geometry::Disk { center: DVec3::ZERO, normal: DVec3::Z, radius: a }),
            side: Side::Front,
            emission: LightSpectrum::new(Spectrum::Constant(1.0), 400.0, 700.0).unwrap(),
        };
        let p = DVec3::new(0.0, 0.0, h);
        let mut rng = Rng::for_task(43, Stream::Test, 0);
        let n = 400_000;
        let mut sum = 0.0;
        for _ in 0..n {
            if let Some(inc) = l.incident(p, rng.uniform2()) {
                sum += inc.weight * (-inc.wi.z).max(0.0);
            }
        }
        let e = sum / n as f64;
        let exact = std::f64::consts::PI * a * a / (h * h + a * a);
        assert!((e / exact - 1.0).abs() < 0.01, "E = {e}, exact {exact}");
    }
}
