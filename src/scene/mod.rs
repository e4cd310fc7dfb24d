//! Scenes: TOML → raw records ([`raw`]) → a validated [`Scene`] with its [`EffectPlan`].
//!
//! Loading goes parse, then validate and transform, then build (as Mitsuba 3 does). Every
//! error names the file, line and column, the field, what was wrong and what is allowed.

mod context;
mod lights;
mod luminaires;
mod materials;
mod plan;
pub mod raw;
mod sensors;
mod settings;
mod shapes;
mod spectrum_spec;

pub use plan::{Decision, EffectPlan};
pub use settings::{DirectLighting, Filter, HERO_WAVELENGTHS, IntegratorSettings, OutputSettings, WavelengthSampling};
pub use spectrum_spec::parse_two_column_csv;

use crate::error::{Error, Location, Result};
use crate::geometry::{Aabb, Bvh, Shape};
use crate::light::{AreaLight, Light};
use crate::material::Material;
use crate::render::Camera;
use crate::spectrum::Bands;
use context::Ctx;
use raw::RawScene;
use spectrum_spec::SpectrumLibrary;
use std::path::{Path, PathBuf};

/// The embedded default scene: a spectral Cornell box with a glass and a mirror sphere.
pub const DEFAULT_SCENE: &str = include_str!("default.toml");

/// What a shape in the BVH is: its material (none for an emitter with no reflectance) and the
/// light it emits as, if any.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Prim {
    pub material: Option<u32>,
    pub light: Option<u32>,
}

/// A validated scene, ready to render.
pub struct Scene {
    /// The scene file; `None` for the embedded default scene.
    pub file: Option<PathBuf>,
    pub camera: Camera,
    pub bands: Bands,
    pub sampling: WavelengthSampling,
    pub material_names: Vec<String>,
    pub materials: Vec<Material>,
    pub shapes: Vec<Shape>,
    pub prims: Vec<Prim>,
    pub light_names: Vec<String>,
    pub lights: Vec<Light>,
    pub bvh: Bvh,
    pub bounds: Aabb,
    pub integrator: IntegratorSettings,
    pub output: OutputSettings,
    pub plan: EffectPlan,
    /// Sensors evaluated after the photon pass (see [`crate::sensor`]).
    pub sensors: Vec<crate::sensor::NamedSensor>,
    /// Things the user should know that do not stop the render (e.g. a luminaire file's stated
    /// flux disagreeing with its table).
    pub warnings: Vec<String>,
}

impl Scene {
    /// The material of primitive `prim`, if it has one.
    pub fn material_of(&self, prim: u32) -> Option<&Material> {
        self.prims[prim as usize].material.map(|m| &self.materials[m as usize])
    }

    /// The area light that primitive `prim` emits as, if any.
    pub fn area_light_of(&self, prim: u32) -> Option<&AreaLight> {
        match self.prims[prim as usize].light.map(|l| &self.lights[l as usize]) {
            Some(Light::Area(a)) => Some(a),
            _ => None,
        }
    }

    /// Overrides the photon counts (both maps) and the seed, and decides the plan again.
    pub fn apply_overrides(&mut self, photons: Option<u64>, seed: Option<u64>) {
        if let Some(n) = photons {
            self.integrator.photons = n;
            self.integrator.caustic_photons = n;
        }
        if let Some(s) = seed {
            self.integrator.seed = s;
        }
        self.plan = decide_plan(
            &self.materials,
            &self.material_names,
            &self.prims,
            &self.integrator,
            self.sampling,
            self.bands.count,
        );
    }

    /// A short label for messages and reports: the file path or "default scene".
    pub fn label(&self) -> String {
        self.file.as_ref().map_or_else(|| "<embedded default scene>".to_string(), |p| p.display().to_string())
    }
}

/// Loads and validates a scene file.
pub fn load_scene_file(path: &Path) -> Result<Scene> {
    let source = std::fs::read_to_string(path)
        .map_err(|e| Error::input(Some(Location::file(path)), format!("cannot read scene file: {e}")))?;
    let dir = path.parent().map_or_else(|| PathBuf::from("."), Path::to_path_buf);
    let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("scene").to_string();
    let mut scene = load_scene_str(&source, path, &dir, &stem)?;
    scene.file = Some(path.to_path_buf());
    Ok(scene)
}

/// The embedded default scene.
pub fn default_scene() -> Result<Scene> {
    load_scene_str(DEFAULT_SCENE, Path::new("<embedded default scene>"), Path::new("."), "default")
}

/// Validates scene text. `file` names it in errors, `dir` resolves relative paths, and
/// `default_name` is the output stem when `[output] name` is absent.
pub fn load_scene_str(source: &str, file: &Path, dir: &Path, default_name: &str) -> Result<Scene> {
    let ctx = Ctx::new(file, source, dir);
    let raw: RawScene = toml::from_str(source).map_err(|e| toml_error(&ctx, &e))?;
    build(&ctx, &raw, default_name)
}

fn toml_error(ctx: &Ctx, e: &toml::de::Error) -> Error {
    let message = e.message().trim().to_string();
    let Some(span) = e.span() else {
        return Error::input(Some(Location::file(&ctx.file)), message);
    };
    let loc = ctx.loc(&span);
    // Name the key written on the offending line, since serde's type errors do not.
    let line = loc.line.and_then(|l| ctx.source.lines().nth(l - 1)).unwrap_or("");
    let key = line.split_once('=').map(|(k, _)| k.trim()).filter(|k| !k.is_empty() && !k.starts_with('['));
    let message = match key {
        Some(k) if !message.contains(&format!("`{k}`")) => format!("field `{k}`: {message}"),
        _ => message,
    };
    Error::input(Some(loc), message)
}

fn build(ctx: &Ctx, raw: &RawScene, default_name: &str) -> Result<Scene> {
    let camera = settings::camera(ctx, &raw.camera)?;
    let (output, bands, sampling) = settings::output(ctx, raw.output.as_ref(), default_name)?;
    let lib = SpectrumLibrary { named: &raw.spectra };
    let mut material_names: Vec<String> = Vec::new();
    let mut materials = Vec::new();
    for (i, rec) in raw.material.iter().enumerate() {
        let m = materials::material(ctx, &lib, rec, i, &bands)?;
        if material_names.contains(&m.name) {
            return Err(ctx.err(&rec.span(), format!("material \"{}\" is defined twice; names must be unique", m.name)));
        }
        material_names.push(m.name);
        materials.push(m.material);
    }
    let mut shapes = Vec::new();
    let mut prims = Vec::new();
    for (i, rec) in raw.shape.iter().enumerate() {
        let group = shapes::shape(ctx, rec, i)?;
        let m = material_index(ctx, &material_names, &group.material, &group.name)?;
        for s in &group.shapes {
            s.check().map_err(|e| ctx.err(&rec.span(), format!("{}: {e}", group.name)))?;
        }
        for s in group.shapes {
            shapes.push(s);
            prims.push(Prim { material: Some(m), light: None });
        }
    }
    let geometry_bounds = shapes.iter().fold(Aabb::EMPTY, |b, s| b.union(s.bounds()));
    let mut lights = Vec::new();
    let mut light_names = Vec::new();
    let mut warnings = Vec::new();
    for (i, rec) in raw.light.iter().enumerate() {
        let l = lights::light(ctx, &lib, rec, i, &bands, &geometry_bounds)?;
        if let Light::Area(a) = &l.light {
            let material = match &l.material {
                None => None,
                Some(m) => Some(material_index(ctx, &material_names, m, &format!("light \"{}\"", l.name))?),
            };
            shapes.push(a.shape.clone());
            prims.push(Prim { material, light: Some(i as u32) });
        }
        warnings.extend(l.notes);
        light_names.push(l.name);
        lights.push(l.light);
    }
    if lights.is_empty() {
        return Err(Error::input(
            Some(Location::file(&ctx.file)),
            "the scene has no [[light]]: nothing would be lit; add at least one light",
        ));
    }
    let bounds = shapes.iter().fold(Aabb::EMPTY, |b, s| b.union(s.bounds()));
    let integrator = settings::integrator(ctx, raw.integrator.as_ref(), &bounds)?;
    let sensors = sensors::sensors(ctx, &raw.sensor, &integrator)?;
    let plan = decide_plan(&materials, &material_names, &prims, &integrator, sampling, bands.count);
    let bvh = Bvh::build(&shapes);
    Ok(Scene {
        file: None,
        camera,
        bands,
        sampling,
        material_names,
        materials,
        shapes,
        prims,
        light_names,
        lights,
        bvh,
        bounds,
        integrator,
        output,
        plan,
        sensors,
        warnings,
    })
}

fn decide_plan(
    materials: &[Material],
    names: &[String],
    prims: &[Prim],
    integrator: &IntegratorSettings,
    sampling: WavelengthSampling,
    bands: usize,
) -> EffectPlan {
    let used: Vec<(&str, &Material)> = (0..materials.len())
        .filter(|m| prims.iter().any(|p| p.material == Some(*m as u32)))
        .map(|m| (names[m].as_str(), &materials[m]))
        .collect();
    let facts = plan::SceneFacts { used_materials: used, sampling, bands };
    EffectPlan::decide(&facts, integrator)
}

/// Index of the material a record refers to, or an error at the reference.
fn material_index(ctx: &Ctx, names: &[String], name: &toml::Spanned<String>, owner: &str) -> Result<u32> {
    names.iter().position(|n| n == name.get_ref()).map(|i| i as u32).ok_or_else(|| {
        ctx.err(&name.span(), format!("{owner}: no material named \"{}\"; defined: {}", name.get_ref(), list(names)))
    })
}

fn list(names: &[String]) -> String {
    if names.is_empty() { "none".to_string() } else { names.join(", ") }
}
