//! Illuminance on a grid of points on a plane (a lighting engineer's calculation surface: the
//! desk plane, a road, a wall).
//!
//! The grid spans origin + s u + t v for s, t ∈ [0, 1] with points at the centres of nx × ny
//! cells; it measures on the side of the unit normal n (default (u × v)/|u × v|). The plane is
//! virtual — it blocks no light — and need not lie on a surface. At each point
//!
//! E_v = K_m ∫ E_e(λ) ȳ(λ) dλ,  E_e(λ) = E_direct(λ) + E_indirect(λ)
//!
//! - E_direct = Σ_lights S(λ) · weight · cos θ, by one shadow ray per light and sample (exact for
//!   point-like lights; a luminaire emitting from its opening is averaged over its samples);
//! - E_indirect = π · mean L(λ) over cosine-distributed gather rays, L being what a gather ray of
//!   the eye pass reads from the global photon map where it meets a diffuse surface (so light
//!   reflected at least once; caustics through glass reach it along those rays).
//!
//! The lux integral runs over the scene's wavelength range only, by stratified sampling: each
//! sample takes one wavelength per band (jittered within it, as eye paths do), so
//! E_v ≈ K_m Σ_b E_e(λ_b) ȳ(λ_b) Δλ_b, an unbiased estimate. Columns: `E_lx`, `E_direct_lx`,
//! `E_indirect_lx`.

use super::Reading;
use crate::geometry::{Frame, Hit};
use crate::raypath::{Propagator, RayState};
use crate::render::Lanes;
use crate::render::eye::{EyeTracer, Scratch};
use crate::rng::{Rng, Stream};
use crate::sampling::cosine_hemisphere;
use crate::scene::{Scene, WavelengthSampling};
use crate::spectrum::cie::cmf_1931;
use crate::spectrum::colour::K_M;
use glam::DVec3;
use rayon::prelude::*;
use std::f64::consts::PI;

#[derive(Clone, Debug, PartialEq)]
pub struct IlluminancePlane {
    pub origin: DVec3,
    pub u: DVec3,
    pub v: DVec3,
    /// Unit normal of the measuring side.
    pub normal: DVec3,
    pub nx: usize,
    pub ny: usize,
    /// Estimates averaged per point.
    pub samples: usize,
    /// Gather rays per sample for indirect light (0: direct light only).
    pub gather_rays: usize,
}

impl IlluminancePlane {
    /// The centre of cell (i, j).
    pub fn point(&self, i: usize, j: usize) -> DVec3 {
        self.origin + (i as f64 + 0.5) / self.nx as f64 * self.u + (j as f64 + 0.5) / self.ny as f64 * self.v
    }

    /// Measures every point; sensor `index` seeds its random streams.
    pub fn evaluate(&self, scene: &Scene, tracer: &EyeTracer, name: &str, index: u64) -> Reading {
        let n = self.nx * self.ny;
        let values: Vec<(f64, f64)> = (0..n)
            .into_par_iter()
            .map_init(Scratch::default, |sc, k| {
                let task = (index << 40) | k as u64;
                let mut rng = Rng::for_task(scene.integrator.seed, Stream::Sensor, task);
                self.at(scene, tracer, self.point(k % self.nx, k / self.nx), &mut rng, sc)
            })
            .collect();
        let points = (0..n).map(|k| self.point(k % self.nx, k / self.nx)).collect();
        let direct: Vec<f64> = values.iter().map(|v| v.0).collect();
        let indirect: Vec<f64> = values.iter().map(|v| v.1).collect();
        let total = direct.iter().zip(&indirect).map(|(a, b)| a + b).collect();
        Reading {
            name: name.to_string(),
            quantity: "illuminance",
            unit: "lx",
            nx: self.nx,
            ny: self.ny,
            points,
            columns: vec![("E_lx".into(), total), ("E_direct_lx".into(), direct), ("E_indirect_lx".into(), indirect)],
        }
    }

    /// Direct and indirect illuminance at `p`, lx.
    fn at(&self, scene: &Scene, tracer: &EyeTracer, p: DVec3, rng: &mut Rng, sc: &mut Scratch) -> (f64, f64) {
        let (mut direct, mut indirect) = (0.0, 0.0);
        let prop = Propagator::new(scene);
        let here = Hit { t: 0.0, point: p, normal: self.normal, prim: u32::MAX };
        let medium = scene.medium_at(crate::geometry::spawn_origin(p, self.normal, self.normal));
        let frame = Frame::from_normal(self.normal);
        for _ in 0..self.samples {
            let lanes = Lanes::new(&scene.bands, WavelengthSampling::Bands, rng.uniform());
            // K_m ȳ(λ) Δλ per lane, divided among the samples: lux per W m⁻² nm⁻¹.
            let w = scene.bands.width_nm() * K_M / self.samples as f64;
            let lux: Vec<f64> = lanes.nm[..lanes.len].iter().map(|l| w * cmf_1931(*l)[1]).collect();
            for light in &scene.lights {
                let Some(inc) = light.incident(p, rng.uniform2()) else { continue };
                let cos = inc.wi.dot(self.normal);
                if cos <= 0.0 {
                    continue;
                }
                let nm = &lanes.nm[..lanes.len];
                let Some(tr) = prop.shadow(p, Some(&here), inc.wi, inc.dist, medium, nm, rng) else { continue };
                let s = &light.spectrum().spectrum;
                for ((l, y), t) in nm.iter().zip(&lux).zip(&tr) {
                    direct += y * s.eval(*l) * inc.weight * cos * t;
                }
            }
            for _ in 0..self.gather_rays {
                let d = frame.to_world(cosine_hemisphere(rng.uniform2()));
                let state = RayState {
                    position: crate::geometry::spawn_origin(p, self.normal, d),
                    dir: d,
                    wavelength_nm: None,
                    medium,
                };
                let l = tracer.gather_radiance(&state, &lanes, rng, sc);
                for (l, y) in l[..lanes.len].iter().zip(&lux) {
                    indirect += y * PI * l / self.gather_rays as f64;
                }
            }
        }
        (direct, indirect)
    }
}
