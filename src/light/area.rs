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
    Front,
    Back,
    Both,
}

#[derive(Clone, Debug)]
pub struct AreaLight {
    pub shape: Shape,
    pub side: Side,
    /// Spectral radiance L_e(λ), W m⁻² sr⁻¹ nm⁻¹.
    pub emission: LightSpectrum,
}

impl AreaLight {
    fn sides(&self) -> f64 {
        if self.side == Side::Both { 2.0 } else { 1.0 }
    }

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
        (cos_l > 0.0).then(|| Incident {
            wi,
            dist,
            weight: cos_l * self.shape.area() / dist2,
        })
    }
}
