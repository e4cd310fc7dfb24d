//! report.json: what ran, how long each phase took, how many photons and rays.

use crate::render::RenderStats;
use crate::scene::{EffectPlan, IntegratorSettings, Scene, WavelengthSampling};
use serde::Serialize;

#[derive(Serialize)]
pub struct Wavelengths {
    pub min_nm: f64,
    pub max_nm: f64,
    pub bands: usize,
    pub sampling: WavelengthSampling,
}

#[derive(Serialize)]
pub struct Report<'a> {
    pub morgana_version: &'static str,
    pub scene: String,
    pub seed: u64,
    pub threads: usize,
    pub width: usize,
    pub height: usize,
    pub wavelengths: Wavelengths,
    pub radiance_units: &'static str,
    pub rgb_units: &'static str,
    pub integrator: &'a IntegratorSettings,
    pub effects: &'a EffectPlan,
    pub total_seconds: f64,
    #[serde(flatten)]
    pub stats: &'a RenderStats,
    pub outputs: Vec<String>,
}

impl<'a> Report<'a> {
    pub fn new(
        scene: &'a Scene,
        stats: &'a RenderStats,
        threads: usize,
        total_seconds: f64,
        outputs: Vec<String>,
    ) -> Report<'a> {
        Report {
            morgana_version: env!("CARGO_PKG_VERSION"),
            scene: scene.label(),
            seed: scene.integrator.seed,
            threads,
            width: scene.camera.width,
            height: scene.camera.height,
            wavelengths: Wavelengths {
                min_nm: scene.bands.min_nm,
                max_nm: scene.bands.max_nm,
                bands: scene.bands.count,
                sampling: scene.sampling,
            },
            radiance_units: "W m^-2 sr^-1 nm^-1 (band averages)",
            rgb_units: "linear sRGB (D65), Y in cd m^-2",
            integrator: &scene.integrator,
            effects: &scene.plan,
            total_seconds,
            stats,
            outputs,
        }
    }
}
