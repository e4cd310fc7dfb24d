//! Scenes: TOML → raw records ([`raw`]) → a validated [`Scene`] with its [`EffectPlan`].
//!
//! Loading goes parse, then validate and transform, then build (as Mitsuba 3 does). Every
//! error names the file, line and column, the field, what was wrong and what is allowed.

mod atmosphere_constituents;
mod atmosphere_medium;
mod ground;
mod inelastic;
mod lights;
mod luminaires;
mod materials;
mod media;
mod plan;
pub mod progressive;
pub mod raw;
mod refractive_index;
mod sensors;
mod settings;
mod shapes;
mod sight;
mod spectrum_spec;
pub mod symmetry;
mod tone;
pub mod twilight;

pub use plan::{Decision, EffectPlan};
pub use settings::{
    BUNDLE_MIN_LANES, DirectLighting, HERO_WAVELENGTHS, IntegratorSettings, MAX_PHOTONS, MIN_MARCH_STEP_M, Method,
    OutputSettings, VolumeEstimate, WavelengthSampling, check_photons_override,
};

use crate::atmosphere::Earth;
use crate::error::{Error, Location, Result};
use crate::geometry::Camera;
use crate::geometry::{Aabb, Bvh, Shape};
use crate::light::Light;
use crate::material::Material;
use crate::media::Medium;
use crate::media::density::Density;
use crate::ode::CurvedSettings;
use crate::photon_map::DiscShare;
use crate::raypath::projection::MapInputs;
use crate::spectrum::Bands;
use crate::validate::Ctx;
use crate::world::{Names as WorldNames, Prim, Reach, World};
use glam::DVec3;
use raw::RawScene;
use spectrum_spec::SpectrumLibrary;
use std::path::{Path, PathBuf};

/// The name of the run report every render writes.
pub const REPORT_FILE: &str = "report.json";

/// The longest output file name a scene may ask for, in bytes: file systems allow 255, and the
/// staged temporary name adds a dot, the process id and a counter (see [`crate::atomic`]).
pub const MAX_OUTPUT_NAME_BYTES: usize = 200;

/// The embedded default scene: a spectral Cornell box with a glass and a mirror sphere.
pub const DEFAULT_SCENE: &str = include_str!("default.toml");

/// A validated scene, ready to render: the [`World`] light interacts with and the run
/// description (camera, wavelengths, integrator settings, effect plan, sensors).
pub struct Scene {
    /// Everything light interacts with.
    pub world: World,
    /// The scene file; `None` for the embedded default scene.
    pub file: Option<PathBuf>,
    /// The pinhole camera.
    pub camera: Camera,
    /// The medium the camera sits in.
    pub camera_medium: Option<u32>,
    /// The simulated wavelength bands.
    pub bands: Bands,
    /// How eye paths choose their wavelengths.
    pub sampling: WavelengthSampling,
    /// Validated `[integrator]` settings.
    pub integrator: IntegratorSettings,
    /// Validated `[output]` settings.
    pub output: OutputSettings,
    /// What machinery runs and why, decided once from the scene and the settings.
    pub plan: EffectPlan,
    /// Sensors evaluated after the photon pass (see [`crate::sensor`]).
    pub sensors: Vec<crate::sensor::NamedSensor>,
    /// Things the user should know that do not stop the render (e.g. a luminaire file's stated
    /// flux disagreeing with its table).
    pub warnings: Vec<String>,
}

impl Scene {
    /// What surface photon estimates measure their disc's share on surfaces with: the world,
    /// unless `[integrator] edge_correction = false`.
    pub fn disc_share(&self) -> Option<&dyn DiscShare> {
        self.integrator.edge_correction.then_some(&self.world as &dyn DiscShare)
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
        self.plan = decide_plan(&self.world, &self.camera, &self.integrator, &self.sensors, self.sampling, &self.bands);
    }

    /// Applies a front end's stopping rules (`morgana render`'s flags, the Python package's
    /// keywords) over the scene's `[integrator]` keys, checks that the target names one of its
    /// sensors or a region of its image, and decides the progressive plan again.
    pub fn apply_stopping_rules(&mut self, flags: &progressive::Flags) -> crate::error::Result<()> {
        let p = &mut self.integrator.progressive;
        p.apply(flags)?;
        let names: Vec<String> = self.sensors.iter().map(|s| s.name.clone()).collect();
        p.check_target(&names, self.camera.width, self.camera.height).map_err(|e| {
            let rule =
                flags.target.as_ref().map_or("[integrator] target".to_string(), |t| flags.style.said("target", t));
            crate::error::Error::input(None, format!("{rule} {e}"))
        })?;
        self.plan.progressive_passes = EffectPlan::progressive_decision(&self.integrator);
        Ok(())
    }

    /// How curved paths are followed, when the plan follows them (`None`: every path is
    /// straight).
    pub fn curved(&self) -> Option<&CurvedSettings> {
        self.plan.curved_paths.on.then_some(&self.integrator.curved)
    }

    /// The names of the files a render of this scene writes, in the order they are written
    /// (`report.json` last): the spectral EXR, the PNG, the region and pixel CSVs as
    /// `[output]` asks, and each sensor's files.
    pub fn output_file_names(&self) -> Vec<String> {
        let o = &self.output;
        let mut names = Vec::new();
        let mut add = |on: bool, name: String| {
            if on {
                names.push(name);
            }
        };
        add(o.exr, format!("{}.exr", o.name));
        add(o.png, format!("{}.png", o.name));
        add(o.region.is_some(), format!("{}.region.csv", o.name));
        add(o.csv, format!("{}.csv", o.name));
        for s in &self.sensors {
            let stem = format!("{}_{}", o.name, crate::sensor::file_stem(&s.name));
            match s.sensor {
                crate::sensor::Sensor::IlluminancePlane(_) => {
                    add(true, format!("{stem}.csv"));
                    add(true, format!("{stem}.png"));
                }
                crate::sensor::Sensor::SkyRadiance(_) => add(true, format!("{stem}.csv")),
                crate::sensor::Sensor::OceanProfile(_) => {
                    add(true, format!("{stem}.csv"));
                    add(true, format!("{stem}_derived.csv"));
                }
            }
        }
        names.push(REPORT_FILE.to_string());
        names
    }

    /// A short label for messages and reports: the file path or "default scene".
    pub fn label(&self) -> String {
        self.file.as_ref().map_or_else(|| "<embedded default scene>".to_string(), |p| p.display().to_string())
    }
}

/// Loads and validates a scene file.
pub fn load_scene_file(path: &Path) -> Result<Scene> {
    let source = crate::error::read_utf8(path, "scene file")?;
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
    let raw: RawScene = toml::from_str(source).map_err(|e| ctx.toml_error(&e))?;
    build(&ctx, &raw, default_name)
}

/// Validates scene text as [`load_scene_str`] does, with its sun placed at solar zenith angle
/// `zenith_deg` (elevation 90° − zenith, its azimuth kept): the scene must have exactly one
/// `type = "sun"` light, placed by `elevation_deg` and `azimuth_deg` (`morgana render
/// --sun-zenith-deg`).
pub fn load_scene_str_at_sun_zenith(
    source: &str,
    file: &Path,
    dir: &Path,
    default_name: &str,
    zenith_deg: f64,
) -> Result<Scene> {
    let ctx = Ctx::new(file, source, dir);
    let mut raw: RawScene = toml::from_str(source).map_err(|e| ctx.toml_error(&e))?;
    let suns: Vec<usize> = (0..raw.light.len())
        .filter(|&i| raw.light[i].get_ref().kind.as_ref().is_some_and(|k| k.get_ref() == "sun"))
        .collect();
    let [i] = suns[..] else {
        return Err(Error::input(
            None,
            format!(
                "{}: --sun-zenith-deg moves the scene's sun, but the scene has {} [[light]] of type \"sun\"; give it exactly one",
                file.display(),
                suns.len()
            ),
        ));
    };
    let span = raw.light[i].span();
    let light = raw.light[i].get_mut();
    let Some(elevation) = &light.elevation_deg else {
        return Err(ctx.err(
            &span,
            "--sun-zenith-deg: place the sun by elevation_deg and azimuth_deg (not direction), so its azimuth is kept",
        ));
    };
    if !(0.0..=180.0).contains(&zenith_deg) {
        return Err(Error::input(None, format!("--sun-zenith-deg {zenith_deg}: a solar zenith angle is 0 to 180°")));
    }
    light.elevation_deg = Some(toml::Spanned::new(elevation.span(), 90.0 - zenith_deg));
    build(&ctx, &raw, default_name)
}

fn build(ctx: &Ctx, raw: &RawScene, default_name: &str) -> Result<Scene> {
    let camera = settings::camera(ctx, &raw.camera)?;
    let (output, bands, sampling) = settings::output(ctx, raw.output.as_ref(), default_name, &camera)?;
    let lib = SpectrumLibrary { named: &raw.spectra };
    let (material_names, materials) = build_materials(ctx, &lib, raw, &bands)?;
    let earth = build_earth(ctx, raw)?;
    let (medium_names, media, global_medium) = build_media(ctx, &lib, raw, &bands, &earth)?;
    let names = Names { materials: &material_names, media: &medium_names };
    let (mut shapes, mut prims, mut prim_names) = build_shapes(ctx, raw, &names, &materials, global_medium)?;
    let geometry_bounds = shapes.iter().fold(Aabb::EMPTY, |b, s| b.union(s.bounds()));
    let mut lights = Vec::new();
    let mut light_names = Vec::new();
    let mut warnings = Vec::new();
    for (i, rec) in raw.light.iter().enumerate() {
        let l = lights::light(ctx, &lib, rec, i, &bands, &geometry_bounds)?;
        let power = l.light.power_w();
        if !(power.is_finite() && power >= 0.0) {
            return Err(ctx.err(
                &rec.span(),
                format!(
                    "light \"{}\": its power over the scene's wavelengths is {power} W; give a finite emission and a light of non-zero size",
                    l.name
                ),
            ));
        }
        if let Light::Area(a) = &l.light {
            let material = match &l.material {
                None => None,
                Some(m) => Some(names.index(ctx, Kind::Material, m, &format!("light \"{}\"", l.name))?),
            };
            shapes.push(a.shape.clone());
            prims.push(Prim { material, light: Some(i as u32), interior: global_medium, exterior: global_medium });
            prim_names.push(format!("light \"{}\"", l.name));
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
    let mut integrator = settings::integrator(ctx, raw.integrator.as_ref(), &bounds)?;
    check_index_fields(ctx, raw, &media, &bands, &bounds.include(camera.position))?;
    check_tracking_work(ctx, raw, &media, &bands, &bounds.include(camera.position))?;
    curved_integrator(ctx, raw, &media, &mut integrator)?;
    let sensors = sensors::sensors(ctx, &raw.sensor, &integrator, limb_air(&media, global_medium))?;
    let march_given = raw.integrator.as_ref().is_some_and(|i| i.get_ref().march_step.is_some());
    warnings.extend(sensors::limb_march_note(&sensors, integrator.march_step_m, march_given));
    check_target(ctx, raw, &integrator, &sensors, &camera)?;
    let bvh = Bvh::build(&shapes);
    let reach = Reach::around(&bounds.include(camera.position));
    let names = WorldNames { materials: material_names, media: medium_names, prims: prim_names, lights: light_names };
    let mut world = World {
        materials,
        media,
        global_medium,
        shapes,
        prims,
        lights,
        light_media: Vec::new(),
        bvh,
        bounds,
        reach,
        names,
    };
    world.light_media = world.lights.iter().map(|l| world.medium_at(l.representative_point())).collect();
    ground::check_ground_closes_the_air(ctx, raw, &world)?;
    check_march_work(ctx, raw, &world, &integrator)?;
    default_volume_estimate(raw, &world, &camera, &mut integrator);
    let plan = decide_plan(&world, &camera, &integrator, &sensors, sampling, &bands);
    let camera_medium = world.medium_at(camera.position);
    let mut scene = Scene {
        world,
        file: None,
        camera,
        camera_medium,
        bands,
        sampling,
        integrator,
        output,
        plan,
        sensors,
        warnings,
    };
    check_output_names(ctx, raw, &scene)?;
    aim_beams(&mut scene);
    Ok(scene)
}

/// `[integrator] target` must name a sensor of the scene or a region inside the image.
fn check_target(
    ctx: &Ctx,
    raw: &RawScene,
    s: &IntegratorSettings,
    sensors: &[crate::sensor::NamedSensor],
    camera: &Camera,
) -> Result<()> {
    let names: Vec<String> = sensors.iter().map(|s| s.name.clone()).collect();
    s.progressive.check_target(&names, camera.width, camera.height).map_err(|e| {
        let span = raw.integrator.as_ref().and_then(|i| i.get_ref().target.as_ref()).map_or(0..0, |t| t.span());
        ctx.err(&span, format!("[integrator] target {e}"))
    })
}

/// Every file a render would write must have a name the file system takes (at most
/// [`MAX_OUTPUT_NAME_BYTES`]); the error points at `[output] name` (or the scene, when the name
/// came from the file's own).
fn check_output_names(ctx: &Ctx, raw: &RawScene, scene: &Scene) -> Result<()> {
    let Some(long) = scene.output_file_names().into_iter().find(|n| n.len() > MAX_OUTPUT_NAME_BYTES) else {
        return Ok(());
    };
    let span = raw.output.as_ref().and_then(|o| o.get_ref().name.as_ref()).map_or(0..0, |n| n.span());
    Err(ctx.err(
        &span,
        format!(
            "[output] name: the output file \"{long}\" would be {} bytes long; file names are limited to {MAX_OUTPUT_NAME_BYTES} bytes here (shorten name or the sensor names)",
            long.len()
        ),
    ))
}

/// Where paths curve, lights at infinity aimed at a target get a projection map (see
/// [`crate::raypath::projection`]), so their photons reach the target along bent paths. Lights
/// of the same geometry (direction, beam, disc, target, medium: the map does not depend on the
/// spectrum) share one map, traced once.
fn aim_beams(scene: &mut Scene) {
    let Some(curved) = scene.curved() else { return };
    let world = &scene.world;
    let mut traced: Vec<(MapInputs, Option<crate::light::BeamCells>)> = Vec::new();
    let mut maps: Vec<(usize, Option<crate::light::BeamCells>)> = Vec::new();
    for (i, l) in world.lights.iter().enumerate() {
        let Light::Directional(d) = l else { continue };
        if d.target.is_none() {
            continue;
        }
        let key = MapInputs::of(d, world.light_media[i]);
        let cells = match traced.iter().find(|(k, _)| *k == key) {
            Some((_, cells)) => cells.clone(),
            None => {
                let cells = crate::raypath::projection::build(world, curved, d, world.light_media[i]);
                traced.push((key, cells.clone()));
                cells
            }
        };
        maps.push((i, cells));
    }
    for (i, cells) in maps {
        let name = scene.world.names.lights[i].clone();
        if let Light::Directional(d) = &mut scene.world.lights[i] {
            match cells {
                Some(c) => d.cells = Some(Box::new(c)),
                None => scene.warnings.push(format!(
                    "light \"{name}\": no curved path from the beam reaches its target box; its photons start on the box's straight shadow"
                )),
            }
        }
    }
}

fn build_materials(
    ctx: &Ctx,
    lib: &SpectrumLibrary,
    raw: &RawScene,
    bands: &Bands,
) -> Result<(Vec<String>, Vec<Material>)> {
    let (mut names, mut materials) = (Vec::new(), Vec::new());
    for (i, rec) in raw.material.iter().enumerate() {
        let m = materials::material(ctx, lib, rec, i, bands)?;
        if names.contains(&m.name) {
            return Err(ctx.err(&rec.span(), format!("material \"{}\" is defined twice; names must be unique", m.name)));
        }
        names.push(m.name);
        materials.push(m.material);
    }
    Ok((names, materials))
}

/// The world medium's Earth (centre, radius) and top when it is an atmosphere over a sphere
/// centred below the origin, (0, −R, 0), as every scene's round Earth is.
fn limb_air(media: &[crate::media::Medium], global_medium: Option<u32>) -> sensors::LimbAir {
    let m = &media[global_medium? as usize];
    match (m.earth()?, m.top_m()?) {
        (Earth::Spherical(s), top) if s.centre == glam::DVec3::new(0.0, -s.radius_m, 0.0) => {
            Some((s.centre, s.radius_m, top))
        }
        _ => None,
    }
}

/// The media, their names and the medium filling the world (`[world] medium`), if any.
fn build_media(
    ctx: &Ctx,
    lib: &SpectrumLibrary,
    raw: &RawScene,
    bands: &Bands,
    earth: &(Earth, bool),
) -> Result<(Vec<String>, Vec<Medium>, Option<u32>)> {
    let (mut names, mut list) = (Vec::new(), Vec::new());
    for (i, rec) in raw.medium.iter().enumerate() {
        let m = media::medium(ctx, lib, rec, i, bands, earth)?;
        if names.contains(&m.name) || m.name == VACUUM {
            return Err(
                ctx.err(&rec.span(), format!("medium \"{}\": names must be unique and not \"{VACUUM}\"", m.name))
            );
        }
        names.push(m.name.clone());
        list.push(m);
    }
    let names_ref = Names { materials: &[], media: &names };
    let global = match raw.world.as_ref().and_then(|w| w.get_ref().medium.as_ref()) {
        None => None,
        Some(m) => names_ref.medium(ctx, m, "[world] medium")?,
    };
    Ok((names, list, global))
}

/// `[world] earth`: "flat" (default; ground y = 0, +y up) or "spherical" (centre (0, −R, 0),
/// R = `earth_radius_m`, default 6 371 km): how the heights of index fields are measured; and
/// whether the scene gave it (an atmosphere file otherwise keeps its own Earth).
fn build_earth(ctx: &Ctx, raw: &RawScene) -> Result<(Earth, bool)> {
    let Some(w) = raw.world.as_ref() else { return Ok((Earth::flat_y(), false)) };
    let w = w.get_ref();
    let explicit = w.earth.is_some();
    let kind = match &w.earth {
        None => "flat",
        Some(e) => ctx.choice(e, "[world] earth", &["flat", "spherical"])?,
    };
    match (kind, &w.earth_radius_m) {
        ("flat", Some(r)) => Err(ctx.err(&r.span(), "[world] earth_radius_m is only used with earth = \"spherical\"")),
        ("flat", None) => Ok((Earth::flat_y(), explicit)),
        (_, r) => {
            let radius = match r {
                None => crate::atmosphere::EARTH_RADIUS_M,
                Some(r) => ctx.number(r, "[world] earth_radius_m", 0.0, crate::atmosphere::MAX_EARTH_RADIUS_M, true)?,
            };
            let earth =
                Earth::spherical_y(radius).map_err(|e| ctx.err(&w.earth.as_ref().map_or(0..0, |e| e.span()), e))?;
            Ok((earth, explicit))
        }
    }
}

/// The largest majorant optical depth a heterogeneous medium may present across the scene: the
/// expected number of tentative collisions ratio tracking draws for one transmittance.
pub const MAX_MAJORANT_OPTICAL_DEPTH: f64 = 1e6;

/// A medium without a closed-form optical depth (fBm, grid) is tracked by sampling tentative
/// collisions at its majorant rate, so one transmittance costs about σ̄·L samples: refuse one
/// whose majorant σ_t,max × density bound over the longest chord (the world sphere's diameter,
/// or the grid's diagonal) exceeds [`MAX_MAJORANT_OPTICAL_DEPTH`] — the fuzzer found σ_t = 10¹²
/// m⁻¹ in turbulence turn a 4 × 4 render into hours.
fn check_tracking_work(ctx: &Ctx, raw: &RawScene, media: &[Medium], bands: &Bands, bounds: &Aabb) -> Result<()> {
    let world = 2.0 * bounds.diagonal().length().max(2e-3);
    for (rec, m) in raw.medium.iter().zip(media) {
        let (bound, chord) = match &m.density {
            Density::Fbm(f) => (f.bound(), world),
            Density::Grid(g) => (g.max_value(), (g.max - g.min).length().min(world)),
            _ => continue,
        };
        let steps = ((bands.max_nm - bands.min_nm).ceil() as usize).max(1);
        let sigma_max = (0..=steps)
            .map(|i| m.sigma_t(bands.min_nm + (bands.max_nm - bands.min_nm) * i as f64 / steps as f64))
            .fold(0.0f64, f64::max);
        let depth = sigma_max * bound * chord;
        if depth.is_nan() || depth > MAX_MAJORANT_OPTICAL_DEPTH {
            return Err(ctx.err(
                &rec.span(),
                format!(
                    "medium \"{}\": σ_t up to {sigma_max:e} m⁻¹ × density bound {bound:e} over {chord:.3e} m is a majorant optical depth of {depth:e}, above {MAX_MAJORANT_OPTICAL_DEPTH:e}: one transmittance would take about that many samples. Lower sigma_t or the density, or make the medium homogeneous (its transmittance is exact)",
                    m.name
                ),
            ));
        }
    }
    Ok(())
}

/// The most steps `march_step` may ask of one camera ray across the extent of a scattering
/// medium. The step only halves from there (at most 16-fold, where the in-scattered light changes
/// fast), and each step reads the volume estimate or casts shadow rays: 10⁵ steps take about a
/// second of CPU per pixel sample.
pub const MAX_MARCH_STEPS_ACROSS: f64 = 1e5;

/// Refuses a `march_step` that would march a camera ray through more than
/// [`MAX_MARCH_STEPS_ACROSS`] steps across a scattering medium. The medium's extent is the world
/// sphere's diameter for the world medium (geometry and camera), the diagonal of the shapes
/// bounding it otherwise; a path, curved or not, crosses it a few times at most. The render
/// fuzzer found a 2 × 10⁹ m glass block marched in 5 mm steps, the sunset sky's air in 0.25 m
/// steps across its 4.4 × 10⁷ m world, and a camera 10¹² m from that sky, which the default
/// step (1 % of the geometry's diagonal) crossed in 10⁷ steps. The error names `march_step`'s
/// line when the scene gives it, else the camera's position.
fn check_march_work(ctx: &Ctx, raw: &RawScene, world: &World, integrator: &IntegratorSettings) -> Result<()> {
    if integrator.method != Method::PhotonMap {
        return Ok(());
    }
    let step = integrator.march_step_m;
    for (id, m) in world.media.iter().enumerate().filter(|(_, m)| m.scatters()) {
        let extent = medium_extent(world, id);
        let whose = if world.global_medium == Some(id as u32) {
            "the world sphere's diameter: it is the world medium"
        } else {
            "its shapes' extent"
        };
        if !extent.is_finite() || extent / step <= MAX_MARCH_STEPS_ACROSS {
            continue;
        }
        let given = raw.integrator.as_ref().and_then(|i| i.get_ref().march_step.as_ref());
        let camera = raw.camera.get_ref().position.as_ref().map_or(raw.camera.span(), |p| p.span());
        let (span, what) = match given {
            Some(g) => (g.span(), format!("march_step = {step} m")),
            None => (
                camera,
                format!("the default march_step ({step:.3e} m, 1 % of the geometry's diagonal) with the camera here"),
            ),
        };
        return Err(ctx.err(
            &span,
            format!(
                "{what} would cross medium \"{}\" ({extent:.3e} m, {whose}) in {:.2e} steps, more than {MAX_MARCH_STEPS_ACROSS:e} per camera ray; use march_step ≥ {:.3e} m, or give the medium a smaller extent (a shape's interior)",
                m.name,
                extent / step,
                extent / MAX_MARCH_STEPS_ACROSS
            ),
        ));
    }
    Ok(())
}

/// How far a camera ray can march through medium `id`: the world sphere's diameter for the
/// world medium, the diagonal of the shapes bounding it otherwise. A medium no shape bounds
/// (named but unused) is never marched: its empty box gives an infinite diagonal.
fn medium_extent(world: &World, id: usize) -> f64 {
    let id = Some(id as u32);
    if world.global_medium == id {
        return 2.0 * world.reach.radius;
    }
    let bounding = world.shapes.iter().zip(&world.prims).filter(|(_, p)| p.interior == id || p.exterior == id);
    bounding.fold(Aabb::EMPTY, |b, (s, _)| b.union(s.bounds())).diagonal().length()
}

/// Every index field must keep n positive (and ≥ 1 unless allowed) over the box the scene's
/// light can reach: its geometry and camera, doubled as the world sphere is.
fn check_index_fields(ctx: &Ctx, raw: &RawScene, media: &[Medium], bands: &Bands, bounds: &Aabb) -> Result<()> {
    let c = bounds.centre();
    let r = bounds.diagonal().length().max(2e-3);
    let world = Aabb { min: c - DVec3::splat(r), max: c + DVec3::splat(r) };
    for (rec, m) in raw.medium.iter().zip(media) {
        if let (Some(v), Some(f)) = (&rec.get_ref().index, &m.index) {
            refractive_index::check_over(
                ctx,
                v,
                &format!("medium \"{}\"", m.name),
                f,
                (bands.min_nm, bands.max_nm),
                &world,
            )?;
        }
    }
    Ok(())
}

/// Where light curves, shadow rays cannot follow it (Gutierrez et al. 2005, §3): direct light
/// comes from the photon maps, and the path tracer (whose next-event estimation needs straight
/// shadow rays) is not available. A scene that asks for either explicitly gets an error.
fn curved_integrator(ctx: &Ctx, raw: &RawScene, media: &[Medium], s: &mut IntegratorSettings) -> Result<()> {
    let Some(m) = media.iter().find(|m| m.bends_light()) else { return Ok(()) };
    let r = raw.integrator.as_ref().map(|i| i.get_ref());
    let why = format!("medium \"{}\" bends light, and shadow rays cannot follow curved paths", m.name);
    if s.method == Method::Path {
        let at = r.and_then(|r| r.method.as_ref()).map_or(0..0, |m| m.span());
        return Err(ctx.err(
            &at,
            format!(
                "[integrator] method = \"path\": {why} (next-event estimation needs them); use method = \"photon_map\""
            ),
        ));
    }
    if let Some(d) = r.and_then(|r| r.direct.as_ref()).filter(|_| s.direct == DirectLighting::ShadowRays) {
        return Err(
            ctx.err(&d.span(), format!("[integrator] direct = \"shadow_rays\": {why}; use direct = \"photon_map\""))
        );
    }
    if let Some(fg) = r.and_then(|r| r.final_gather.as_ref()).filter(|f| *f.get_ref()) {
        return Err(ctx.err(
            &fg.span(),
            format!("[integrator] final_gather = true: {why}; direct light comes from the photon map"),
        ));
    }
    s.direct = DirectLighting::PhotonMap;
    s.final_gather = false;
    Ok(())
}

/// How eye rays read the volume map when `[integrator] volume_estimate` is not given
/// ([`VolumeEstimate::default_for`]), from what the scene holds.
fn default_volume_estimate(raw: &RawScene, world: &World, camera: &Camera, s: &mut IntegratorSettings) {
    if raw.integrator.as_ref().is_some_and(|i| i.get_ref().volume_estimate.is_some()) {
        return;
    }
    let specular = world.prims.iter().filter_map(|p| p.material).any(|m| world.materials[m as usize].is_specular());
    let map_direct = s.direct == DirectLighting::PhotonMap;
    // A spot's cone edge: the light it scatters into the map stays in a narrow cone.
    let spot = world.lights.iter().any(|l| matches!(l, Light::Spot(_)));
    let stratified = world.media.iter().any(Medium::stratified_air);
    // March steps the point estimate would query along eye paths, at most: a chord across each
    // scattering medium in steps of `march_step` for each eye sample.
    let extent: f64 = (0..world.media.len())
        .filter(|&id| world.media[id].scatters())
        .map(|id| medium_extent(world, id))
        .filter(|e| e.is_finite())
        .sum();
    let eye_queries = (camera.width * camera.height * s.spp) as f64 * extent / s.march_step_m;
    s.volume_estimate =
        VolumeEstimate::default_for(specular || map_direct || spot, stratified, eye_queries >= s.photons as f64);
}

/// Shapes and their primitives' materials and media (see [`Prim`] for the defaults).
fn build_shapes(
    ctx: &Ctx,
    raw: &RawScene,
    names: &Names,
    materials: &[Material],
    global: Option<u32>,
) -> Result<(Vec<Shape>, Vec<Prim>, Vec<String>)> {
    let (mut shapes, mut prims, mut labels) = (Vec::new(), Vec::new(), Vec::new());
    for (i, rec) in raw.shape.iter().enumerate() {
        let group = shapes::shape(ctx, rec, i)?;
        let material = match &group.material {
            Some(m) => Some(names.index(ctx, Kind::Material, m, &group.name)?),
            None => None,
        };
        let s = rec.get_ref();
        let interior = match &s.interior {
            Some(m) => names.medium(ctx, m, &group.name)?,
            None => match material.map(|m| &materials[m as usize]) {
                None => {
                    return Err(ctx.err(
                        &rec.span(),
                        format!("{}: give a material, or an interior medium for an index-matched boundary", group.name),
                    ));
                }
                Some(m) if m.is_refractive() => None,
                Some(_) => global,
            },
        };
        let exterior = match &s.exterior {
            Some(m) => names.medium(ctx, m, &group.name)?,
            None => global,
        };
        for shape in &group.shapes {
            shape.check().map_err(|e| ctx.err(&rec.span(), format!("{}: {e}", group.name)))?;
        }
        for shape in group.shapes {
            shapes.push(shape);
            prims.push(Prim { material, light: None, interior, exterior });
            labels.push(group.name.clone());
        }
    }
    Ok((shapes, prims, labels))
}

/// The reserved medium name for empty space.
pub const VACUUM: &str = "vacuum";

#[derive(Clone, Copy)]
enum Kind {
    Material,
    Medium,
}

/// Name lists for resolving references.
struct Names<'a> {
    materials: &'a [String],
    media: &'a [String],
}

impl Names<'_> {
    /// Index of the material or medium a record refers to, or an error at the reference.
    fn index(&self, ctx: &Ctx, kind: Kind, name: &toml::Spanned<String>, owner: &str) -> Result<u32> {
        let (list, word) = match kind {
            Kind::Material => (self.materials, "material"),
            Kind::Medium => (self.media, "medium"),
        };
        list.iter().position(|n| n == name.get_ref()).map(|i| i as u32).ok_or_else(|| {
            ctx.err(
                &name.span(),
                format!("{owner}: no {word} named \"{}\"; defined: {}", name.get_ref(), list_names(list)),
            )
        })
    }

    /// A medium reference: `None` for "vacuum".
    fn medium(&self, ctx: &Ctx, name: &toml::Spanned<String>, owner: &str) -> Result<Option<u32>> {
        if name.get_ref() == VACUUM {
            return Ok(None);
        }
        self.index(ctx, Kind::Medium, name, owner).map(Some)
    }
}

fn decide_plan(
    world: &World,
    camera: &Camera,
    integrator: &IntegratorSettings,
    sensors: &[crate::sensor::NamedSensor],
    sampling: WavelengthSampling,
    bands: &Bands,
) -> EffectPlan {
    let used: Vec<(&str, &Material)> = (0..world.materials.len())
        .filter(|m| world.prims.iter().any(|p| p.material == Some(*m as u32)))
        .map(|m| (world.names.materials[m].as_str(), &world.materials[m]))
        .collect();
    let used_media: Vec<&Medium> = (0..world.media.len())
        .filter(|m| {
            let m = Some(*m as u32);
            world.global_medium == m || world.prims.iter().any(|p| p.interior == m || p.exterior == m)
        })
        .map(|m| &world.media[m])
        .collect();
    let facts = plan::SceneFacts {
        used_materials: used,
        used_media,
        sampling,
        bands: bands.count,
        min_nm: bands.min_nm,
        photon_sensors: !sensors.is_empty(),
        lowest_sight_deg: sight::lowest_elevation_deg(camera, sensors, &world.lights),
        axial_words: symmetry::plan_words(world, integrator, &symmetry::viewpoints(camera, sensors)),
    };
    let mut plan = EffectPlan::decide(&facts, integrator);
    if plan.curved_paths.on && integrator.method == Method::PhotonMap && sensors.is_empty() {
        let shell = (0..world.media.len() as u32)
            .find_map(|i| crate::raypath::shell::LayeredShell::candidate(world, i).map(|h| (i, h)));
        if let Some((i, (low, top, open))) = shell {
            let name = &world.media[i as usize].name;
            let entry = if open {
                format!("come down to the top of \"{name}\"'s atmosphere (straight, from above, where n = 1)")
            } else {
                format!("enter \"{name}\" through its top going down")
            };
            plan.curved_paths.why += &format!(
                "; photons that {entry} cross it from {top:.0} m to {low:.0} m above the ground in one move each, by \
                 Bouguer's invariant (where its table reaches the integrator's rtol; report.json counts the crossings as \
                 shell_descents)"
            );
            let photons_too =
                if open && world.media[i as usize].is_clear() { " (and photons: its air is clear)" } else { "" };
            plan.curved_paths.why += &format!(
                ", and eye paths{photons_too} that climb out of it leave it the same way (report.json: \
                 eye_curved.shell_ascents, maps[].stats.curved.shell_ascents)"
            );
        }
    }
    plan
}

fn list_names(names: &[String]) -> String {
    if names.is_empty() { "none".to_string() } else { names.join(", ") }
}
