//! Evaluating an [`IlluminancePlane`] sensor: direct light by shadow rays, indirect light by
//! gather rays into the global photon map (see [`crate::sensor::illuminance_plane`]).

use super::super::Lanes;
use super::super::direct::{ShadowOrigin, sample_lights};
use super::super::eye::{EyeTracer, Scratch};
use crate::geometry::{Frame, Hit};
use crate::light::{Incident, Light};
use crate::raypath::{Propagator, RayState};
use crate::rng::{Rng, Stream};
use crate::sampling::cosine_hemisphere;
use crate::scene::{Scene, WavelengthSampling};
use crate::sensor::{IlluminancePlane, Reading};
use crate::spectrum::BandValues;
use crate::spectrum::cie::cmf_1931;
use crate::spectrum::colour::K_M;
use glam::DVec3;
use rayon::prelude::*;
use std::f64::consts::PI;

/// Measures every point; sensor `index` and the pass's `seed` seed its random streams.
pub fn evaluate(
    plane: &IlluminancePlane,
    (scene, seed): (&Scene, u64),
    tracer: &EyeTracer,
    name: &str,
    index: u64,
) -> Reading {
    let n = plane.nx * plane.ny;
    let values: Vec<(f64, f64)> = (0..n)
        .into_par_iter()
        .map_init(Scratch::default, |sc, k| {
            let task = (index << 40) | k as u64;
            let mut rng = Rng::for_task(seed, Stream::Sensor, task);
            at(plane, scene, tracer, plane.point(k % plane.nx, k / plane.nx), &mut rng, sc)
        })
        .collect();
    let points = (0..n).map(|k| plane.point(k % plane.nx, k / plane.nx)).collect();
    let direct: Vec<f64> = values.iter().map(|v| v.0).collect();
    let indirect: Vec<f64> = values.iter().map(|v| v.1).collect();
    let total = direct.iter().zip(&indirect).map(|(a, b)| a + b).collect();
    Reading {
        name: name.to_string(),
        quantity: "illuminance".into(),
        unit: "lx".into(),
        nx: plane.nx,
        ny: plane.ny,
        points,
        columns: vec![("E_lx".into(), total), ("E_direct_lx".into(), direct), ("E_indirect_lx".into(), indirect)],
    }
}

/// Direct and indirect illuminance at `p`, lx.
fn at(
    plane: &IlluminancePlane,
    scene: &Scene,
    tracer: &EyeTracer,
    p: DVec3,
    rng: &mut Rng,
    sc: &mut Scratch,
) -> (f64, f64) {
    let (mut direct, mut indirect) = (0.0, 0.0);
    let prop = Propagator::new(&scene.world, scene.curved());
    let here = Hit { t: 0.0, point: p, normal: plane.normal, prim: u32::MAX };
    let medium = scene.world.medium_at(crate::geometry::spawn_origin(p, plane.normal, plane.normal));
    let frame = Frame::from_normal(plane.normal);
    for _ in 0..plane.samples {
        let lanes = Lanes::new(&scene.bands, WavelengthSampling::Bands, rng.uniform());
        // K_m ȳ(λ) Δλ per lane, divided among the samples: lux per W m⁻² nm⁻¹.
        let w = scene.bands.width_nm() * K_M / plane.samples as f64;
        let lux: Vec<f64> = lanes.nm[..lanes.len].iter().map(|l| w * cmf_1931(*l)[1]).collect();
        let nm = &lanes.nm[..lanes.len];
        let at = ShadowOrigin { p, from: Some(&here), medium, wavelengths_nm: nm, light_u: None };
        let mut add = |light: &Light, inc: &Incident, cos: f64, tr: &BandValues| {
            let s = &light.spectrum().spectrum;
            for ((l, y), t) in nm.iter().zip(&lux).zip(tr) {
                direct += y * s.eval(*l) * inc.weight * light.disc_factor(inc, *l) * cos * t;
            }
        };
        let cos = |_: &Light, inc: &Incident| inc.wi.dot(plane.normal);
        sample_lights(&prop, &scene.world.lights, &at, rng, &mut 0, &cos, &mut add);
        for _ in 0..plane.gather_rays {
            let d = frame.to_world(cosine_hemisphere(rng.uniform2()));
            let state = RayState {
                position: crate::geometry::spawn_origin(p, plane.normal, d),
                dir: d,
                wavelength_nm: None,
                medium,
            };
            let l = tracer.gather_radiance(&state, &lanes, rng, sc);
            for (l, y) in l[..lanes.len].iter().zip(&lux) {
                indirect += y * PI * l / plane.gather_rays as f64;
            }
        }
    }
    (direct, indirect)
}
