//! Rendering: the photon pass ([`maps`]), then the eye pass ([`eye`]) over the pixels.
//!
//! Pixels are independent tasks with their own random streams derived from (seed, pixel), and
//! each pixel's samples are summed in a fixed order, so the image is identical for any number
//! of threads.

mod camera;
pub mod eye;
mod lanes;
pub mod maps;
mod path;
mod progress;
pub mod stats;

pub use camera::Camera;
pub use lanes::Lanes;
pub use stats::{MapReport, PhaseTime, Phases, RayCounts, RenderStats};

use crate::output::SpectralImage;
use crate::raypath::RayState;
use crate::rng::{Rng, Stream};
use crate::scene::{Method, Scene};
use crate::spectrum::colour::BandsToColour;
use eye::{EyeTracer, Scratch};
use rayon::prelude::*;
use std::time::Instant;

/// How to run a render.
#[derive(Clone, Debug, Default)]
pub struct RenderOptions {
    /// Hide progress bars.
    pub quiet: bool,
}

/// A finished render.
pub struct Rendered {
    pub image: SpectralImage,
    pub stats: RenderStats,
    /// What the scene's sensors measured.
    pub sensors: Vec<crate::sensor::Reading>,
    /// What the scene's ocean profile sensors measured.
    pub profiles: Vec<crate::sensor::ProfileReading>,
}

/// Renders `scene` on the current rayon thread pool.
pub fn render(scene: &Scene, opts: &RenderOptions) -> Rendered {
    let mut stats = RenderStats::default();
    let maps = maps::build(scene, opts.quiet, &mut stats.phases, &mut stats.maps);
    if let Some(c) = &maps.irradiance {
        stats.irradiance_points = c.len() as u64;
        stats.irradiance_memory_bytes = c.memory_bytes() as u64;
    }
    let t = Instant::now();
    let (data, rays, curved) = eye_pass(scene, &maps, opts.quiet);
    stats.rays = rays;
    stats.eye_curved = curved;
    stats.phases.add("eye pass", t);
    let t = Instant::now();
    let image = to_image(scene, data);
    stats.phases.add("colour conversion", t);
    let t = Instant::now();
    let sensors = crate::sensor::evaluate_all(scene, &maps);
    let profiles = crate::sensor::evaluate_profiles(scene, &maps);
    if !sensors.is_empty() || !profiles.is_empty() {
        stats.phases.add("sensors", t);
    }
    Rendered { image, stats, sensors, profiles }
}

/// Per-pixel band averages (row-major, `bands.count` per pixel), the rays traced and the
/// integrator work along curved eye paths.
fn eye_pass(scene: &Scene, maps: &maps::Maps, quiet: bool) -> (Vec<f32>, RayCounts, crate::raypath::CurvedWorkTotals) {
    let (w, h) = (scene.camera.width, scene.camera.height);
    let nb = scene.bands.count;
    let tracer = Tracer::new(scene, maps);
    let pb = progress::bar(quiet, h as u64, "eye pass");
    let rows: Vec<(Vec<f32>, RayCounts)> = (0..h)
        .into_par_iter()
        .map_init(Scratch::default, |sc, y| {
            let before = sc.rays;
            let mut row = vec![0f32; w * nb];
            for x in 0..w {
                let px = pixel(scene, &tracer, x, y, sc);
                for b in 0..nb {
                    row[x * nb + b] = px[b] as f32;
                }
            }
            pb.inc(1);
            let mut rays = sc.rays;
            rays.eye -= before.eye;
            rays.shadow -= before.shadow;
            rays.gather -= before.gather;
            (row, rays)
        })
        .collect();
    pb.finish_and_clear();
    let mut data = Vec::with_capacity(w * h * nb);
    let mut rays = RayCounts::default();
    for (row, r) in rows {
        data.extend(row);
        rays.add(&r);
    }
    let curved = match &tracer {
        Tracer::PhotonMap(t) => t.curved_work(),
        Tracer::Path(t) => t.curved_work(),
    };
    (data, rays, curved)
}

/// The eye-pass algorithm the scene asks for.
enum Tracer<'a> {
    PhotonMap(Box<EyeTracer<'a>>),
    Path(path::PathTracer<'a>),
}

impl<'a> Tracer<'a> {
    fn new(scene: &'a Scene, maps: &'a maps::Maps) -> Tracer<'a> {
        match scene.integrator.method {
            Method::PhotonMap => Tracer::PhotonMap(Box::new(EyeTracer::new(scene, maps))),
            Method::Path => Tracer::Path(path::PathTracer::new(scene)),
        }
    }
}

/// The band averages of one pixel: the mean over `spp` jittered samples.
fn pixel(scene: &Scene, tracer: &Tracer, x: usize, y: usize, sc: &mut Scratch) -> [f64; crate::spectrum::MAX_BANDS] {
    let s = &scene.integrator;
    let mut rng = Rng::for_task(s.seed, Stream::Eye, (y * scene.camera.width + x) as u64);
    let weight = Lanes::film_weight(&scene.bands, scene.sampling) / s.spp as f64;
    let mut acc = [0.0; crate::spectrum::MAX_BANDS];
    for _ in 0..s.spp {
        let [jx, jy] = rng.uniform2();
        let ray = scene.camera.ray(x as f64 + jx, y as f64 + jy);
        let lanes = Lanes::new(&scene.bands, scene.sampling, rng.uniform());
        let state = RayState { position: ray.origin, dir: ray.dir, wavelength_nm: None, medium: scene.camera_medium };
        let l = match tracer {
            Tracer::PhotonMap(t) => t.camera_radiance(&state, &lanes, &mut rng, sc),
            Tracer::Path(t) => t.camera_radiance(&state, &lanes, &mut rng, &mut sc.rays),
        };
        for i in 0..lanes.len {
            acc[lanes.band[i] as usize] += weight * l[i];
        }
    }
    acc
}

fn to_image(scene: &Scene, data: Vec<f32>) -> SpectralImage {
    let nb = scene.bands.count;
    let conv = BandsToColour::new(&scene.bands);
    let rgb: Vec<f32> = data
        .par_chunks(nb)
        .flat_map_iter(|px| {
            let v: Vec<f64> = px.iter().map(|x| *x as f64).collect();
            conv.linear_srgb(&v).map(|c| c as f32)
        })
        .collect();
    SpectralImage { width: scene.camera.width, height: scene.camera.height, bands: scene.bands, data, rgb }
}
