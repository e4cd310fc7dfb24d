//! Evaluating a [`SkyRadiance`] sensor: each direction's radiance by the eye pass the scene
//! uses (photon map or path tracer), as a camera ray from the sensor's position would read it
//! (see [`crate::sensor::sky_radiance`]).
//!
//! A direction's samples are split into chunks of [`CHUNK`], each drawing from its own stream,
//! and the chunks run in parallel: one direction read with 10⁷ path-traced samples (the zenith
//! through twilight) uses every thread. The chunks are fixed by the sample count, not by the
//! threads, and summed in order, so a seed gives the same reading on any number of threads; a
//! direction of at most [`CHUNK`] samples draws exactly what it drew before the split.

use super::super::Lanes;
use super::super::eye::{EyeTracer, Scratch};
use super::super::path::PathTracer;
use crate::raypath::RayState;
use crate::rng::{Rng, Stream, splitmix64};
use crate::scene::{Method, Scene};
use crate::sensor::{Reading, SkyRadiance};
use rayon::prelude::*;

/// Samples per chunk of one direction.
pub const CHUNK: usize = 65_536;

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
    let chunks = sensor.samples.div_ceil(CHUNK).max(1);
    let weight = Lanes::film_weight(&scene.bands, scene.sampling) / sensor.samples as f64;
    let per_chunk: Vec<Vec<f64>> = (0..n * chunks)
        .into_par_iter()
        .map_init(Scratch::default, |sc, task| {
            let (k, chunk) = (task / chunks, task % chunks);
            let mut rng = chunk_rng(seed, index, k, chunk);
            let samples = chunk * CHUNK..sensor.samples.min((chunk + 1) * CHUNK);
            band_sums(sensor, scene, (tracer, path.as_ref()), (k, samples, weight), &mut rng, sc)
        })
        .collect();
    let per_direction: Vec<Vec<f64>> = per_chunk
        .chunks(chunks)
        .map(|sums| (0..bands).map(|b| sums.iter().map(|s| s[b]).sum::<f64>()).collect())
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

/// The random stream of chunk `chunk` of direction `k` of sensor `index`: the first chunk's is
/// the stream the whole direction drew from before directions were split, the others' are
/// seeded by a hash of (seed, chunk).
fn chunk_rng(seed: u64, index: u64, k: usize, chunk: usize) -> Rng {
    let task = (index << 40) | k as u64;
    match chunk {
        0 => Rng::for_task(seed, Stream::Sensor, task),
        c => Rng::for_task(splitmix64(seed ^ splitmix64(c as u64)), Stream::SensorChunk, task),
    }
}

/// The sums per band of `weight` × the sensor's samples `samples` (indices among all the
/// direction's samples, over which the wavelength jitter is stratified), looking along
/// direction `k`.
fn band_sums(
    sensor: &SkyRadiance,
    scene: &Scene,
    (tracer, path): (&EyeTracer, Option<&PathTracer>),
    (k, samples, weight): (usize, std::ops::Range<usize>, f64),
    rng: &mut Rng,
    sc: &mut Scratch,
) -> Vec<f64> {
    let position = sensor.origins[k];
    let medium = scene.world.medium_at(position);
    let state = RayState { position, dir: sensor.direction(k), wavelength_nm: None, medium };
    let mut acc = vec![0.0; scene.bands.count];
    for s in samples {
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
