//! A directional light: parallel rays of spectral irradiance E(λ) (normal to the beam) from
//! infinitely far away.
//!
//! Photons start on a rectangle perpendicular to the beam, one scene radius upstream of the
//! scene: by default the square around the scene's bounding sphere, so the emitted flux is
//! Φ = A_beam ∫E dλ; a directional light's power is only defined relative to the region it
//! lights, and `report.json` states it. A scene may limit the beam to the rays through a target
//! box (`target_min`, `target_max` — e.g. a window): the rectangle then covers only the box's
//! shadow on the emitting plane, photons are not spent on walls no camera sees, and shadow rays
//! see the light only inside that beam, so both passes simulate the same, limited, light.
//!
//! A light of finite angular size (the sun: angular diameter 0.53°) is a uniformly bright disc
//! of angular radius θ_m: its rays cross the beam plane with the direction density
//! cos θ/(π sin²θ_m) about the axis ([`crate::sampling::cosine_cone`]), and an eye ray looking
//! into the disc sees the radiance L(λ) = E(λ)/(π sin²θ_m), since E = ∫_disc L cos θ dω.

use crate::geometry::Frame;
use glam::DVec3;

use super::{Incident, LightSpectrum};

#[derive(Clone, Debug)]
pub struct DirectionalLight {
    /// Unit direction the light travels in.
    pub dir: DVec3,
    /// Centre and radius of the scene's bounding sphere.
    pub scene_centre: DVec3,
    pub scene_radius: f64,
    /// The beam's cross-section in the frame about `dir`: (s, t) ranges.
    pub beam: [[f64; 2]; 2],
    /// Spectral irradiance normal to the beam, W m⁻² nm⁻¹.
    pub emission: LightSpectrum,
    /// sin θ_m of the disc's angular radius; 0 for a collimated beam.
    pub sin_max: f64,
    /// The box the beam is aimed at, if the scene gave one.
    pub target: Option<crate::geometry::Aabb>,
    /// Where paths curve, the cells of the beam whose light reaches the target (a projection
    /// map, see [`crate::photon::projection`]); `None`: the whole rectangle.
    pub cells: Option<BeamCells>,
}

/// A projection map of a beam: the cells of a regular grid over the beam's cross-section from
/// which light reaches the target, drawn uniformly (each cell has the same area).
#[derive(Clone, Debug, PartialEq)]
pub struct BeamCells {
    /// The grid's corner (s, t) and cell size, m.
    pub origin: [f64; 2],
    pub size: [f64; 2],
    /// The (i, j) indices of the cells that emit.
    pub cells: Vec<[u32; 2]>,
}

impl BeamCells {
    pub fn area(&self) -> f64 {
        self.cells.len() as f64 * self.size[0] * self.size[1]
    }

    /// A uniform point (s, t) on the marked cells.
    fn sample(&self, u: [f64; 2]) -> [f64; 2] {
        let k = self.cells.len() as f64 * u[0];
        let i = (k as usize).min(self.cells.len() - 1);
        let v = k - i as f64;
        let [ci, cj] = self.cells[i];
        [self.origin[0] + (ci as f64 + v) * self.size[0], self.origin[1] + (cj as f64 + u[1]) * self.size[1]]
    }

    fn contains(&self, s: f64, t: f64) -> bool {
        let i = ((s - self.origin[0]) / self.size[0]).floor();
        let j = ((t - self.origin[1]) / self.size[1]).floor();
        i >= 0.0 && j >= 0.0 && self.cells.binary_search(&[i as u32, j as u32]).is_ok()
    }
}

impl DirectionalLight {
    /// A light covering the scene's bounding sphere, or only the beam through `target`.
    pub fn new(
        dir: DVec3,
        scene_centre: DVec3,
        scene_radius: f64,
        target: Option<(DVec3, DVec3)>,
        emission: LightSpectrum,
    ) -> DirectionalLight {
        let frame = Frame::from_normal(dir);
        let beam = match target {
            None => [[-scene_radius, scene_radius], [-scene_radius, scene_radius]],
            Some((lo, hi)) => {
                let mut b = [[f64::INFINITY, f64::NEG_INFINITY], [f64::INFINITY, f64::NEG_INFINITY]];
                for i in 0..8 {
                    let c = DVec3::new(
                        if i & 1 == 0 { lo.x } else { hi.x },
                        if i & 2 == 0 { lo.y } else { hi.y },
                        if i & 4 == 0 { lo.z } else { hi.z },
                    );
                    let (s, t) = ((c - scene_centre).dot(frame.s), (c - scene_centre).dot(frame.t));
                    b = [[b[0][0].min(s), b[0][1].max(s)], [b[1][0].min(t), b[1][1].max(t)]];
                }
                b
            }
        };
        let target = target.map(|(min, max)| crate::geometry::Aabb { min, max });
        DirectionalLight { dir, scene_centre, scene_radius, beam, emission, sin_max: 0.0, target, cells: None }
    }

    /// The same light as a uniformly bright disc of angular diameter `diameter_deg`.
    pub fn with_angular_diameter(mut self, diameter_deg: f64) -> DirectionalLight {
        self.sin_max = (0.5 * diameter_deg).to_radians().sin();
        self
    }

    /// A direction of travel: the axis for a collimated beam, else cosine-distributed within the
    /// disc's cone about it.
    pub fn sample_dir(&self, u: [f64; 2]) -> DVec3 {
        if self.sin_max == 0.0 {
            return self.dir;
        }
        Frame::from_normal(self.dir).to_world(crate::sampling::cosine_cone(u, self.sin_max)).normalize()
    }

    /// The factor L/E seen by an eye ray travelling along `view_dir`: 1/(π sin²θ_m) inside the
    /// disc, 0 outside it and for a collimated beam (which no ray can hit).
    pub fn radiance_factor(&self, view_dir: DVec3) -> f64 {
        let cos_max = (1.0 - self.sin_max * self.sin_max).sqrt();
        if self.sin_max > 0.0 && -view_dir.dot(self.dir) >= cos_max {
            1.0 / (std::f64::consts::PI * self.sin_max * self.sin_max)
        } else {
            0.0
        }
    }

    /// Area of the beam's cross-section (of its projection map's cells, when it has one), m².
    pub fn beam_area(&self) -> f64 {
        match &self.cells {
            Some(c) => c.area(),
            None => (self.beam[0][1] - self.beam[0][0]) * (self.beam[1][1] - self.beam[1][0]),
        }
    }

    /// The point of the emitting plane at beam coordinates (s, t).
    pub fn plane_point(&self, s: f64, t: f64) -> DVec3 {
        let frame = Frame::from_normal(self.dir);
        self.scene_centre - self.dir * (1.001 * self.scene_radius) + s * frame.s + t * frame.t
    }

    pub fn power_w(&self) -> f64 {
        self.beam_area() * self.emission.integral()
    }

    /// A uniform point on the beam's cross-section (or its projection map's cells), upstream of
    /// the scene.
    pub fn emit_origin(&self, u: [f64; 2]) -> DVec3 {
        let [s, t] = match &self.cells {
            Some(c) => c.sample(u),
            None => [
                self.beam[0][0] + u[0] * (self.beam[0][1] - self.beam[0][0]),
                self.beam[1][0] + u[1] * (self.beam[1][1] - self.beam[1][0]),
            ],
        };
        self.plane_point(s, t)
    }

    /// Whether the beam passes through `p` (along straight rays: used by shadow rays, which
    /// only run where paths are straight).
    pub fn lights(&self, p: DVec3) -> bool {
        let frame = Frame::from_normal(self.dir);
        let (s, t) = ((p - self.scene_centre).dot(frame.s), (p - self.scene_centre).dot(frame.t));
        let in_rect =
            (self.beam[0][0]..=self.beam[0][1]).contains(&s) && (self.beam[1][0]..=self.beam[1][1]).contains(&t);
        in_rect && self.cells.as_ref().is_none_or(|c| c.contains(s, t))
    }

    /// Irradiance normal to the beam is E, so weight = 1 toward −dir (or toward a direction
    /// sampled in the disc, whose cosine density makes the weight 1 again) at infinite distance.
    pub fn incident(&self, p: DVec3, u: [f64; 2]) -> Option<Incident> {
        self.lights(p).then(|| Incident { wi: -self.sample_dir(u), dist: f64::INFINITY, weight: 1.0 })
    }
}
