//! report.json: what ran, how long each phase took, how many photons and rays.

use crate::light::Light;
use crate::render::RenderStats;
use crate::scene::{EffectPlan, IntegratorSettings, Scene, WavelengthSampling};
use serde::Serialize;

/// One light as the run simulated it: its power, and for a light at infinity the beam its
/// photons fill (the box's shadow, or the projection map's cells where paths curve).
#[derive(Serialize)]
pub struct LightReport {
    /// The light's name (`[[light]] name`, or a generated one).
    pub name: String,
    /// Its type: "area", "point", "spot", "directional", "sun", "luminaire" or "sky".
    #[serde(rename = "type")]
    pub kind: &'static str,
    /// Power emitted into the scene's wavelength range, W.
    pub power_w: f64,
    /// Cross-section of a directional light's (or the sun's) beam, m².
    pub beam_area_m2: Option<f64>,
    /// Cells of its projection map (`None`: the straight shadow of the target, or the whole scene).
    pub projection_map_cells: Option<usize>,
    /// With a target and no projection map: the fraction of the beam's photons whose straight
    /// paths pass through the target box (its shadow's area over the beam's).
    pub beam_on_target: Option<f64>,
}

impl LightReport {
    fn of(name: &str, light: &Light) -> LightReport {
        let kind = match light {
            Light::Area(_) => "area",
            Light::Point(_) => "point",
            Light::Spot(_) => "spot",
            Light::Directional(d) if d.sin_max > 0.0 => "sun",
            Light::Directional(_) => "directional",
            Light::Luminaire(_) => "luminaire",
            Light::Sky(_) => "sky",
        };
        let (beam_area_m2, projection_map_cells, beam_on_target) = match light {
            Light::Directional(d) => (Some(d.beam_area()), d.cells.as_ref().map(|c| c.cells.len()), d.on_target()),
            _ => (None, None, None),
        };
        LightReport {
            name: name.to_string(),
            kind,
            power_w: light.power_w(),
            beam_area_m2,
            projection_map_cells,
            beam_on_target,
        }
    }
}

/// The simulated wavelength range and its sampling.
#[derive(Serialize)]
pub struct Wavelengths {
    /// Short end, nm.
    pub min_nm: f64,
    /// Long end, nm.
    pub max_nm: f64,
    /// Number of bands.
    pub bands: usize,
    /// How eye paths choose their wavelengths.
    pub sampling: WavelengthSampling,
}

/// The whole of `report.json`.
#[derive(Serialize)]
pub struct Report<'a> {
    /// Version of morgana that rendered.
    pub morgana_version: &'static str,
    /// The scene file, or `<embedded default scene>`.
    pub scene: String,
    /// Random seed.
    pub seed: u64,
    /// Worker threads (of rank 0).
    pub threads: usize,
    /// Image width, pixels.
    pub width: usize,
    /// Image height, pixels.
    pub height: usize,
    /// The wavelength range and its sampling.
    pub wavelengths: Wavelengths,
    /// Units of the spectral EXR's band values.
    pub radiance_units: &'static str,
    /// Units of the RGB values.
    pub rgb_units: &'static str,
    /// The integrator settings used.
    pub integrator: &'a IntegratorSettings,
    /// The effect plan: what ran and why.
    pub effects: &'a EffectPlan,
    /// One entry per light.
    pub lights: Vec<LightReport>,
    /// Notes the scene's validation printed (e.g. a beam no curved path reaches).
    pub warnings: &'a [String],
    /// Wall time of the whole run, s.
    pub total_seconds: f64,
    /// The process's peak resident memory when the report was written (after every output
    /// was staged), bytes; compare `memory.estimated_peak_bytes`.
    pub peak_memory_bytes: Option<u64>,
    /// Timings, photon and ray counts (its fields appear at the top level).
    #[serde(flatten)]
    pub stats: &'a RenderStats,
    /// The files written.
    pub outputs: Vec<String>,
}

impl<'a> Report<'a> {
    /// The report of a render of `scene`: its statistics, worker threads, wall time (s) and
    /// outputs.
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
            lights: scene
                .world
                .lights
                .iter()
                .zip(&scene.world.names.lights)
                .map(|(l, n)| LightReport::of(n, l))
                .collect(),
            warnings: &scene.warnings,
            total_seconds,
            peak_memory_bytes: crate::memory::peak_rss_bytes(),
            stats,
            outputs,
        }
    }
}
