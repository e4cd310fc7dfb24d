//! Aiming caustic photons at specular objects (Jensen's projection maps, done analytically).
//!
//! Each specular material's primitives are bounded by one sphere (the sphere itself when the
//! material is on a single sphere). A caustic photon's direction
//! (or, for a directional light, its start point) is drawn from an equal-weight mixture of
//! "uniform within the cone (disk) that sphere subtends", and its power is multiplied by
//! p_light / p_mixture, so the estimator stays unbiased for every path that reaches a specular
//! surface first — and no path that does is impossible to sample, because each sphere contains
//! its objects.

use crate::geometry::{Aabb, Frame, Shape};
use crate::light::{Emission, Light, Side};
use crate::rng::Rng;
use crate::sampling::{
    concentric_disk, cosine_hemisphere_pdf, uniform_cone, uniform_cone_pdf, uniform_sphere, uniform_sphere_pdf,
};
use crate::world::World;
use glam::DVec3;

/// Bounding spheres of the scene's specular objects.
pub struct CausticTargets {
    spheres: Vec<(DVec3, f64)>,
}

impl CausticTargets {
    /// `None` when the scene has no specular surface.
    pub fn new(world: &World) -> Option<CausticTargets> {
        let mut spheres = Vec::new();
        for (m, material) in world.materials.iter().enumerate() {
            if !material.is_specular() {
                continue;
            }
            let shapes: Vec<&Shape> = world
                .prims
                .iter()
                .zip(&world.shapes)
                .filter(|(p, _)| p.material == Some(m as u32))
                .map(|(_, s)| s)
                .collect();
            // One sphere bounds the material's shapes: the shape itself for a lone sphere, else the
            // sphere around their bounding box; a small margin keeps surfaces on it from being
            // missed by rounding.
            let (centre, radius) = match shapes.as_slice() {
                [] => continue,
                [Shape::Sphere(s)] => (s.center, s.radius),
                _ => {
                    let b = shapes.iter().fold(Aabb::EMPTY, |b, s| b.union(s.bounds()));
                    (b.centre(), 0.5 * b.diagonal().length())
                }
            };
            spheres.push((centre, radius * (1.0 + 1e-6) + 1e-9));
        }
        (!spheres.is_empty()).then_some(CausticTargets { spheres })
    }

    /// A photon from `light` aimed at the targets, and the factor p_light/p_mixture for its power
    /// (zero when the light emits nothing in the chosen direction).
    pub fn emit(&self, light: &Light, rng: &mut Rng) -> (Emission, f64) {
        let (wavelength_nm, _) = light.spectrum().sampler.sample(rng.uniform());
        match light {
            Light::Directional(d) => self.emit_directional(d, wavelength_nm, rng),
            // The sky's photons are not aimed: emitted as the light emits them (weight 1), the
            // few that reach a specular object first make its caustics, unbiased.
            Light::Sky(_) => {
                let mut e = light.emit(rng);
                e.wavelength_nm = wavelength_nm;
                (e, 1.0)
            }
            _ => {
                let (origin, normal, p_light) = start(light, rng);
                let j = rng.below(self.spheres.len() as u64) as usize;
                let dir = self.sample_toward(origin, j, rng.uniform2());
                let p_mix = self.pdf_toward(origin, dir);
                let factor = if p_mix > 0.0 { p_light(dir) / p_mix } else { 0.0 };
                (Emission { origin, dir, wavelength_nm, normal }, factor)
            }
        }
    }

    fn sample_toward(&self, origin: DVec3, j: usize, u: [f64; 2]) -> DVec3 {
        let (c, r) = self.spheres[j];
        let d = c - origin;
        let dist2 = d.length_squared();
        if dist2 <= r * r {
            return uniform_sphere(u);
        }
        let cos_max = (1.0 - r * r / dist2).max(0.0).sqrt();
        Frame::from_normal(d / dist2.sqrt()).to_world(uniform_cone(u, cos_max))
    }

    fn pdf_toward(&self, origin: DVec3, dir: DVec3) -> f64 {
        let sum: f64 = self
            .spheres
            .iter()
            .map(|&(c, r)| {
                let d = c - origin;
                let dist2 = d.length_squared();
                if dist2 <= r * r {
                    return uniform_sphere_pdf();
                }
                let cos_max = (1.0 - r * r / dist2).max(0.0).sqrt();
                if dir.dot(d) / dist2.sqrt() >= cos_max { uniform_cone_pdf(cos_max) } else { 0.0 }
            })
            .sum();
        sum / self.spheres.len() as f64
    }

    /// Directional light: the direction drawn as the light draws it, then start points drawn
    /// uniformly on disks covering the shadows the spheres cast along that direction on the
    /// emitting plane (radius r/cos α for a direction α off the axis; area density 1/(π r'²)
    /// each), against the light's uniform 1/A_beam.
    fn emit_directional(
        &self,
        d: &crate::light::DirectionalLight,
        wavelength_nm: f64,
        rng: &mut Rng,
    ) -> (Emission, f64) {
        let frame = Frame::from_normal(d.dir);
        let plane_centre = d.scene_centre - d.dir * (1.001 * d.scene_radius);
        let dir = d.sample_photon_dir(rng.uniform2(), wavelength_nm);
        let cos_a = dir.dot(d.dir);
        // The point of the emitting plane from which `dir` leads through c.
        let project = |c: DVec3| c - dir * ((c - plane_centre).dot(d.dir) / cos_a);
        let j = rng.below(self.spheres.len() as u64) as usize;
        let (c, r) = self.spheres[j];
        let [x, y] = concentric_disk(rng.uniform2());
        let origin = project(c) + (r / cos_a) * (x * frame.s + y * frame.t);
        let inside_light = d.lights(origin);
        let p_mix: f64 = self
            .spheres
            .iter()
            .map(|&(c, r)| {
                let rr = r / cos_a;
                if (origin - project(c)).length_squared() <= rr * rr {
                    1.0 / (std::f64::consts::PI * rr * rr)
                } else {
                    0.0
                }
            })
            .sum::<f64>()
            / self.spheres.len() as f64;
        let p_light = 1.0 / d.beam_area();
        let factor = if inside_light && p_mix > 0.0 { p_light / p_mix } else { 0.0 };
        (Emission { origin, dir, wavelength_nm, normal: d.dir }, factor)
    }
}

/// A start point on the light, its facing normal (zero for point lights), and the light's own
/// direction density there.
fn start<'a>(light: &'a Light, rng: &mut Rng) -> (DVec3, DVec3, Box<dyn Fn(DVec3) -> f64 + 'a>) {
    match light {
        Light::Area(a) => {
            let s = a.shape.sample(rng.uniform2());
            // Density of the light's own emission at this point: cos θ/π on one emitting side, or
            // |cos θ|/(2π) over both.
            let (n, both) = match a.side {
                Side::Front => (s.normal, false),
                Side::Back => (-s.normal, false),
                Side::Both => (s.normal, true),
            };
            let p = move |w: DVec3| {
                if both { 0.5 * cosine_hemisphere_pdf(w.dot(n).abs()) } else { cosine_hemisphere_pdf(w.dot(n)) }
            };
            (s.point, n, Box::new(p))
        }
        Light::Point(p) => (p.position, DVec3::ZERO, Box::new(|_| uniform_sphere_pdf())),
        Light::Spot(s) => {
            (s.position, DVec3::ZERO, Box::new(move |w: DVec3| s.falloff(w.dot(s.axis)) / s.falloff_solid_angle()))
        }
        Light::Luminaire(l) => (l.start(rng), DVec3::ZERO, Box::new(move |w: DVec3| l.pdf_dir(w))),
        Light::Directional(_) | Light::Sky(_) => unreachable!("lights at infinity are emitted by CausticTargets::emit"),
    }
}
