//! Evaluating a [`SkyRadiance`] sensor: each direction's radiance by the eye pass the scene
//! uses (photon map or path tracer), as a camera ray from the sensor's position would read it
//! (see [`crate::sensor::sky_radiance`]).

use super::super::Lanes;
use super::super::eye::{EyeTracer, Scratch};
use super::super::path::PathTracer;
use crate::raypath::RayState;
use crate::rng::{Rng, Stream};
use crate::scene::{Method, Scene};
use crate::sensor::{Reading, SkyRadiance};
use rayon::prelude::*;

/// Measures every direction; sensor `index` and the pass's `seed` seed its random streams.
pub fn evaluate(
    sensor: &SkyRadiance,
    (scene, seed): (&Scene, u64),
    tracer: &EyeTracer,
    name: &str,
    index: u64,
) -> Reading {
    let path = (scene.integrator.method == Method::Path).then(|| PathTracer::new(scene));
    let n = sensor.directions_deg.len();
    let bands = scene.bands.count;
    let per_direction: Vec<Vec<f64>> = (0..n)
        .into_par_iter()
        .map_init(Scratch::default, |sc, k| {
            let mut rng = Rng::for_task(seed, Stream::Sensor, (index << 40) | k as u64);
            band_means(sensor, scene, (tracer, path.as_ref()), k, &mut rng, sc)
        })
        .collect();
    let mut columns = vec![
        ("L_mean".to_string(), per_direction.iter().map(|l| l.iter().sum::<f64>() / bands as f64).collect()),
        ("view_zenith_deg".to_string(), sensor.directions_deg.iter().map(|d| d[0]).collect()),
        ("view_azimuth_deg".to_string(), sensor.directions_deg.iter().map(|d| d[1]).collect()),
    ];
    if let Some(limb) = &sensor.limb {
        columns.push(("tangent_height_m".to_string(), limb.iter().map(|(h, _)| *h).collect()));
    }
    for b in 0..bands {
        let (lo, hi) = scene.bands.edges_nm(b);
        columns.push((format!("L_{lo}_{hi}nm"), per_direction.iter().map(|l| l[b]).collect()));
    }
    Reading {
        name: name.to_string(),
        quantity: "radiance".to_string(),
        unit: "W m-2 sr-1 nm-1".to_string(),
        nx: n,
        ny: 1,
        points: match &sensor.limb {
            Some(limb) => limb.iter().map(|(_, t)| *t).collect(),
            None => sensor.origins.clone(),
        },
        columns,
    }
}

/// The mean radiance per band over the sensor's samples, looking along direction `k`.
fn band_means(
    sensor: &SkyRadiance,
    scene: &Scene,
    (tracer, path): (&EyeTracer, Option<&PathTracer>),
    k: usize,
    rng: &mut Rng,
    sc: &mut Scratch,
) -> Vec<f64> {
    let position = sensor.origins[k];
    let medium = scene.world.medium_at(position);
    let state = RayState { position, dir: sensor.direction(k), wavelength_nm: None, medium };
    let mut acc = vec![0.0; scene.bands.count];
    let weight = Lanes::film_weight(&scene.bands, scene.sampling) / sensor.samples as f64;
    for s in 0..sensor.samples {
        // The wavelength jitter stratified over the samples.
        let u = (s as f64 + rng.uniform()) / sensor.samples as f64;
        let lanes = Lanes::new(&scene.bands, scene.sampling, u);
        let l = match path {
            Some(p) => p.camera_radiance(&state, &lanes, None, rng, &mut sc.rays),
            None => tracer.camera_radiance(&state, &lanes, None, rng, sc),
        };
        for i in 0..lanes.len {
            acc[lanes.band[i] as usize] += weight * l[i];
        }
    }
    acc
}
