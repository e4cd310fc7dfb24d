//! Camera, `[output]` and `[integrator]`: validated settings.

use super::progressive::Progressive;
use super::raw::{RawCamera, RawIntegrator, RawOutput};
use crate::geometry::Aabb;
use crate::geometry::{Camera, Projection};
use crate::ode::CurvedSettings;
use crate::photon_map::Filter;
use crate::spectrum::{Bands, MAX_BANDS};
use crate::tonemap::Exposure;
use crate::tonemap::ToneSettings;
use crate::tonemap::region::Region;
use crate::validate::{Ctx, R};
use serde::Serialize;
use toml::{Spanned, Value};

/// How an eye path chooses its wavelengths.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum WavelengthSampling {
    /// One wavelength per band, jittered within it: the path carries all bands.
    Bands,
    /// Hero-wavelength sampling (Wilkie et al. 2014): 4 stratified wavelengths over the whole
    /// range per path.
    Hero,
}

/// Number of wavelengths a hero-sampled path carries.
pub const HERO_WAVELENGTHS: usize = 4;

/// Where direct light on diffuse surfaces comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum DirectLighting {
    /// Shadow rays to the lights (Jensen; needs straight paths).
    ShadowRays,
    /// Everything from the global photon map (Lucifer; works on curved paths).
    PhotonMap,
}

/// How the volume photon map's light scattered toward the eye is estimated along a medium chord.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum VolumeEstimate {
    /// A k-nearest sphere at every ray-march step (Jensen & Christensen 1998).
    Point,
    /// One query per chord for every photon whose disc the chord crosses (Jarosz, Zwicker &
    /// Jensen 2008): no march steps.
    Beam,
    /// Photon beams: every photon's flight through a medium is kept as a segment blurred into a
    /// thin tube, and a chord gathers the tubes it passes through (Jarosz et al. 2011). Only
    /// when a scene asks for it.
    PhotonBeams,
}

impl VolumeEstimate {
    /// The estimate a scene gets when it names none. The beam estimate where the volume map holds
    /// sharp-edged light (`sharp_light`): where a specular surface can focus light into a
    /// scattering medium, where the map carries the direct light (`direct = "photon_map"`,
    /// which curved paths force), whose edges — a spot's cone, a shadow — are then in it, or
    /// where a spot light shines into the medium (its scattered light stays near its cone).
    /// Each photon's disc holds all of its power, while the point estimate's k-nearest radius,
    /// set by the point being lit, reaches from the dim medium beside such an edge into the
    /// light and makes light (against light tracing, `tests/volume_caustic.rs`: a ball lens's
    /// volume caustic 14 % too bright after 32 passes, a 3° spot read from the map 15.6 %; the
    /// beam estimate within 0.3 %; `searchlight_turbulence`'s multiply scattered light 15 %
    /// above the beam estimate, falling toward it as progressive passes shrink the radii). Not
    /// in air stratified in height (`stratified_air`), whose density weights the point
    /// estimate's sphere, nor where the eye paths' march steps (at most eye samples × the
    /// scattering media's extent over `march_step`) are fewer than the photons emitted
    /// (`!eye_work_dominates`): there the point estimate's few queries are cheap, and the beam
    /// estimate's cost is not repaid — a k-nearest query per stored photon for the radii (20 s
    /// for a one-pixel camera beside ocean sensors), a query per chord of a curved path where a
    /// long march step crosses a thin fog layer once (`sunset_fog`: eye pass 2.7 → 6.6 CPU s,
    /// image mean within 0.2 %). Elsewhere the point estimate.
    pub fn default_for(sharp_light: bool, stratified_air: bool, eye_work_dominates: bool) -> VolumeEstimate {
        if sharp_light && !stratified_air && eye_work_dominates { VolumeEstimate::Beam } else { VolumeEstimate::Point }
    }
}

/// The gather discs of the beam estimate: each photon's radius is that of the sphere holding its
/// `k` nearest photons (at most `max_radius_m`), times `scale` (√sᵢ in progressive pass i).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct BeamRadii {
    /// Nearest photons of the pilot query that sets a photon's radius (the first pass's `volume_k`).
    pub k: usize,
    /// Largest pilot radius, m (the first pass's `volume_max_radius`).
    pub max_radius_m: f64,
    /// Factor on every radius in this pass: 1 in the first, √sᵢ later (2-D kernel shrinkage).
    pub scale: f64,
    /// Factor on every photon beam's tube radius in this pass: 1 in the first, sᵢ later (the
    /// rule r_{i+1} = r_i (i + α)/(i + 1) of progressive photon beams, whose one-pass variance
    /// grows as 1/r).
    pub tube_scale: f64,
}

/// The light-transport algorithm.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Method {
    /// Photon mapping (Jensen; Jensen & Christensen; Gutierrez et al.).
    PhotonMap,
    /// Unbiased volumetric path tracing: the reference estimator.
    Path,
}

/// The wavelengths a scene may simulate, nm: from the vacuum ultraviolet to the far infrared.
pub const MIN_WAVELENGTH_NM: f64 = 1.0;
/// See [`MIN_WAVELENGTH_NM`].
pub const MAX_WAVELENGTH_NM: f64 = 100_000.0;

/// The most photons a map may emit (2⁴⁰), in a scene file and on the command line alike.
pub const MAX_PHOTONS: u64 = 1 << 40;

/// Checks a `--photons` override: 1 to [`MAX_PHOTONS`] (a scene switches a map off with
/// `photons = 0` in `[integrator]`, not from the command line).
pub fn check_photons_override(n: u64) -> crate::error::Result<()> {
    if (1..=MAX_PHOTONS).contains(&n) {
        return Ok(());
    }
    Err(crate::error::Error::input(
        None,
        format!(
            "--photons {n} is out of range: it must be between 1 and {MAX_PHOTONS} (2^40) photons per map; to switch a map off set photons = 0 or caustic_photons = 0 in [integrator]"
        ),
    ))
}

/// The smallest `march_step` a scene may give, m (0.1 mm): a step of 1e-300 m made a render of
/// 4 × 4 pixels march for ever (found by morgana-fuzz).
pub const MIN_MARCH_STEP_M: f64 = 1e-4;

/// Validated `[integrator]`: photon counts, density estimates, eye sampling and curved-path
/// stepping.
#[derive(Clone, Debug, Serialize)]
pub struct IntegratorSettings {
    /// Photon mapping or the reference path tracer.
    pub method: Method,
    /// Photons emitted for the global map.
    pub photons: u64,
    /// Photons emitted for the caustic map.
    pub caustic_photons: u64,
    /// Nearest photons per global-map estimate.
    pub k: usize,
    /// Largest gather radius of the global map, m.
    pub max_radius_m: f64,
    /// Nearest photons per caustic-map estimate.
    pub caustic_k: usize,
    /// Largest gather radius of the caustic map, m.
    pub caustic_max_radius_m: f64,
    /// Nearest photons per volume estimate.
    pub volume_k: usize,
    /// Largest gather radius of the volume map, m.
    pub volume_max_radius_m: f64,
    /// Largest ray-marching step in media, m (steps shrink where photons are dense); at least
    /// [`MIN_MARCH_STEP_M`].
    pub march_step_m: f64,
    /// The volume map's estimate along eye rays.
    pub volume_estimate: VolumeEstimate,
    /// The beam estimate's gather discs.
    pub beam: BeamRadii,
    /// Where direct light on diffuse surfaces comes from.
    pub direct: DirectLighting,
    /// Gather indirect light with rays into the global map at the first diffuse hit.
    pub final_gather: bool,
    /// Camera paths through an absorbing medium that bends each wavelength differently follow
    /// four guide wavelengths and interpolate the others where a check allows
    /// (`render::eye` bundles); `false` traces every wavelength.
    pub dispersion_bundles: bool,
    /// Fold volume photons about the sun's axis through the Earth's centre where the scene is
    /// symmetric about it ([`crate::scene::symmetry`]): `Some(true)` wherever it is,
    /// `Some(false)` never, `None` (the default) where the sun is also below the horizon at the
    /// camera or a sky sensor — twilight, where the unfolded map is biased.
    pub axial_symmetry: Option<bool>,
    /// Surface photon estimates divide by the part of their disc that lies on surfaces able to
    /// hold photons ([`crate::world::World::gather_share`]) rather than by the whole disc.
    pub edge_correction: bool,
    /// Final-gather rays per shading point.
    pub gather_rays: usize,
    /// Eye samples per pixel.
    pub spp: usize,
    /// Largest number of specular bounces of an eye path.
    pub max_depth: usize,
    /// Random seed of the whole run.
    pub seed: u64,
    /// Kernel of the photon density estimates.
    pub filter: Filter,
    /// How curved paths are stepped where a medium's index varies.
    pub curved: CurvedSettings,
    /// Progressive passes and the rules that stop them.
    pub progressive: Progressive,
}

impl IntegratorSettings {
    /// The settings of progressive pass `pass` (0-based): the seed of that pass and the gather
    /// parameters shrunk by Knaus & Zwicker's schedule (see [`crate::photon_map::progressive`]);
    /// pass 0 is these settings unchanged.
    pub fn for_pass(&self, pass: u32) -> IntegratorSettings {
        use crate::photon_map::progressive::{k, measure_ratio, surface_radius, volume_radius};
        let a = self.progressive.alpha;
        IntegratorSettings {
            seed: crate::rng::pass_seed(self.seed, pass),
            k: k(self.k, pass, a),
            max_radius_m: surface_radius(self.max_radius_m, pass, a),
            caustic_k: k(self.caustic_k, pass, a),
            caustic_max_radius_m: surface_radius(self.caustic_max_radius_m, pass, a),
            volume_k: k(self.volume_k, pass, a),
            volume_max_radius_m: volume_radius(self.volume_max_radius_m, pass, a),
            beam: BeamRadii {
                scale: self.beam.scale * measure_ratio(pass, a).sqrt(),
                tube_scale: self.beam.tube_scale * measure_ratio(pass, a),
                ..self.beam
            },
            ..self.clone()
        }
    }
}

/// Validated `[output]`: which files are written and how the PNG is made.
#[derive(Clone, Debug, Serialize)]
pub struct OutputSettings {
    /// File stem of the outputs.
    pub name: String,
    /// Write the spectral EXR.
    pub exr: bool,
    /// Write the PNG preview.
    pub png: bool,
    /// Write one CSV row per pixel (x, y, radiance per band).
    pub csv: bool,
    /// Exposure of the PNG preview.
    #[serde(skip)]
    pub exposure: Exposure,
    /// How the PNG is made; `None`: the exposure preview.
    #[serde(skip)]
    pub tone: Option<ToneSettings>,
    /// Pixels whose luminance goes to `NAME.region.csv`.
    #[serde(skip)]
    pub region: Option<Region>,
}

pub fn camera(ctx: &Ctx, c: &Spanned<RawCamera>) -> R<Camera> {
    let span = c.span();
    let c = c.get_ref();
    let what = "[camera]";
    let position = ctx.vec3(ctx.require(&c.position, "position", &span, what)?, "camera position")?;
    let look_at = ctx.vec3(ctx.require(&c.look_at, "look_at", &span, what)?, "camera look_at")?;
    let up = match &c.up {
        Some(u) => ctx.direction(u, "camera up")?,
        None => glam::DVec3::Y,
    };
    let projection = match &c.projection {
        None => Projection::Pinhole,
        Some(p) => match ctx.choice(p, "[camera] projection", &["pinhole", "equal_area"])? {
            "equal_area" => Projection::EqualArea,
            _ => Projection::Pinhole,
        },
    };
    // A pinhole sees less than a half-space; the equal-area image circle up to the whole sphere.
    let fov_v = ctx.require(&c.fov_deg, "fov_deg", &span, what)?;
    let fov = match projection {
        Projection::Pinhole => ctx.number(fov_v, "fov_deg", 0.0, 180.0, true)?,
        Projection::EqualArea => ctx.number_above(fov_v, "fov_deg", 0.0, 360.0)?,
    };
    let width = ctx.integer(ctx.require(&c.width, "width", &span, what)?, "width", 1, 16384)? as usize;
    let height = ctx.integer(ctx.require(&c.height, "height", &span, what)?, "height", 1, 16384)? as usize;
    let forward = look_at - position;
    if forward.length_squared() == 0.0 {
        return Err(ctx.err(&span, "[camera]: look_at equals position; the camera needs a viewing direction"));
    }
    if forward.normalize().cross(up).length() < 1e-9 {
        let hint = match projection {
            Projection::EqualArea => " (looking up, up = [0, 0, -1] puts azimuth 0°, toward −z, at the image's top)",
            Projection::Pinhole => "",
        };
        return Err(
            ctx.err(&span, format!("[camera]: up is parallel to the viewing direction; choose another up{hint}"))
        );
    }
    Ok(Camera::new(position, look_at, up, fov, width, height).with_projection(projection))
}

/// Output settings and the wavelength sampling.
pub fn output(
    ctx: &Ctx,
    o: Option<&Spanned<RawOutput>>,
    default_name: &str,
    camera: &Camera,
) -> R<(OutputSettings, Bands, WavelengthSampling)> {
    let Some(o) = o else {
        let bands = Bands::new(380.0, 780.0, 16).map_err(crate::error::Error::internal)?;
        let out = OutputSettings {
            name: default_name.into(),
            exr: true,
            png: true,
            csv: false,
            exposure: Exposure::Auto,
            tone: None,
            region: None,
        };
        return Ok((out, bands, WavelengthSampling::Bands));
    };
    let span = o.span();
    let o = o.get_ref();
    let nm = |v: &Spanned<f64>, what: &str| ctx.number(v, what, MIN_WAVELENGTH_NM, MAX_WAVELENGTH_NM, false);
    let min_nm = o.min_nm.as_ref().map_or(Ok(380.0), |v| nm(v, "min_nm"))?;
    let max_nm = o.max_nm.as_ref().map_or(Ok(780.0), |v| nm(v, "max_nm"))?;
    let count = o.bands.as_ref().map_or(Ok(16), |v| ctx.integer(v, "bands", 1, MAX_BANDS as i64))? as usize;
    let bands = Bands::new(min_nm, max_nm, count).map_err(|e| ctx.err(&span, format!("[output]: {e}")))?;
    let sampling = match &o.sampling {
        None => WavelengthSampling::Bands,
        Some(s) => match ctx.choice(s, "sampling", &["bands", "hero"])? {
            "hero" => WavelengthSampling::Hero,
            _ => WavelengthSampling::Bands,
        },
    };
    let name = match &o.name {
        None => default_name.to_string(),
        Some(n) => valid_name(ctx, n)?,
    };
    let exposure = match &o.exposure {
        None => Exposure::Auto,
        Some(e) => exposure(ctx, e)?,
    };
    let flag = |f: &Option<Spanned<bool>>, d: bool| f.as_ref().map_or(d, |v| *v.get_ref());
    let (tone, region) = super::tone::tone(ctx, o, exposure, camera)?;
    let out = OutputSettings {
        name,
        exr: flag(&o.exr, true),
        png: flag(&o.png, true),
        csv: flag(&o.csv, false),
        exposure,
        tone,
        region,
    };
    Ok((out, bands, sampling))
}

fn valid_name(ctx: &Ctx, n: &Spanned<String>) -> R<String> {
    let s = n.get_ref();
    let ok = !s.is_empty() && s.chars().all(|c| c.is_ascii_alphanumeric() || "-_.".contains(c)) && !s.starts_with('.');
    if ok {
        Ok(s.clone())
    } else {
        Err(ctx
            .err(&n.span(), format!("[output] name \"{s}\" must be a plain file stem: letters, digits, '-', '_', '.'")))
    }
}

fn exposure(ctx: &Ctx, e: &Spanned<Value>) -> R<Exposure> {
    match e.get_ref() {
        Value::String(s) if s == "auto" => Ok(Exposure::Auto),
        Value::Float(x) if x.is_finite() => Ok(Exposure::Ev(*x)),
        Value::Integer(i) => Ok(Exposure::Ev(*i as f64)),
        _ => Err(ctx.err(&e.span(), "[output] exposure must be \"auto\" or a number of stops (EV)")),
    }
}

/// Integrator settings; automatic radii are fractions of the scene's bounding diagonal.
pub fn integrator(ctx: &Ctx, i: Option<&Spanned<RawIntegrator>>, bounds: &Aabb) -> R<IntegratorSettings> {
    let diag = bounds.diagonal().length().max(1e-9);
    let mut s = IntegratorSettings {
        method: Method::PhotonMap,
        photons: 200_000,
        caustic_photons: 200_000,
        k: 100,
        max_radius_m: 0.05 * diag,
        caustic_k: 50,
        caustic_max_radius_m: 0.01 * diag,
        volume_k: 100,
        volume_max_radius_m: 0.05 * diag,
        march_step_m: 0.01 * diag,
        volume_estimate: VolumeEstimate::Point,
        beam: BeamRadii { k: 100, max_radius_m: 0.05 * diag, scale: 1.0, tube_scale: 1.0 },
        direct: DirectLighting::ShadowRays,
        final_gather: true,
        dispersion_bundles: true,
        axial_symmetry: None,
        edge_correction: true,
        gather_rays: 64,
        spp: 16,
        max_depth: 10,
        seed: 1,
        filter: Filter::Cone { k: 1.1 },
        curved: CurvedSettings::default(),
        progressive: Progressive::default(),
    };
    let Some(i) = i else { return Ok(s) };
    let r = i.get_ref();
    let int = |v: &Option<Spanned<i64>>, name: &str, lo: i64, hi: i64, d: i64| -> R<i64> {
        v.as_ref().map_or(Ok(d), |v| ctx.integer(v, name, lo, hi))
    };
    if let Some(m) = &r.method {
        s.method = match ctx.choice(m, "method", &["photon_map", "path"])? {
            "path" => Method::Path,
            _ => Method::PhotonMap,
        };
    }
    s.photons = int(&r.photons, "photons", 0, MAX_PHOTONS as i64, s.photons as i64)? as u64;
    s.caustic_photons =
        int(&r.caustic_photons, "caustic_photons", 0, MAX_PHOTONS as i64, s.caustic_photons as i64)? as u64;
    s.k = int(&r.k, "k", 1, 100_000, s.k as i64)? as usize;
    s.caustic_k = int(&r.caustic_k, "caustic_k", 1, 100_000, s.caustic_k as i64)? as usize;
    s.volume_k = int(&r.volume_k, "volume_k", 1, 100_000, s.volume_k as i64)? as usize;
    if let Some(v) = &r.volume_max_radius {
        s.volume_max_radius_m = ctx.number(v, "volume_max_radius", 0.0, f64::INFINITY, true)?;
    }
    if let Some(v) = &r.march_step {
        s.march_step_m = ctx.number(v, "march_step", MIN_MARCH_STEP_M, f64::INFINITY, false)?;
    }
    if let Some(v) = &r.volume_estimate {
        s.volume_estimate = match ctx.choice(v, "volume_estimate", &["point", "beam", "photon_beams"])? {
            "beam" => VolumeEstimate::Beam,
            "photon_beams" => VolumeEstimate::PhotonBeams,
            _ => VolumeEstimate::Point,
        };
    }
    s.beam = BeamRadii { k: s.volume_k, max_radius_m: s.volume_max_radius_m, scale: 1.0, tube_scale: 1.0 };
    s.gather_rays = int(&r.gather_rays, "gather_rays", 1, 1 << 20, s.gather_rays as i64)? as usize;
    s.spp = int(&r.spp, "spp", 1, 1 << 20, s.spp as i64)? as usize;
    s.max_depth = int(&r.max_depth, "max_depth", 1, 1000, s.max_depth as i64)? as usize;
    s.seed = int(&r.seed, "seed", 0, i64::MAX, s.seed as i64)? as u64;
    if let Some(v) = &r.max_radius {
        s.max_radius_m = ctx.number(v, "max_radius", 0.0, f64::INFINITY, true)?;
    }
    if let Some(v) = &r.caustic_max_radius {
        s.caustic_max_radius_m = ctx.number(v, "caustic_max_radius", 0.0, f64::INFINITY, true)?;
    }
    if let Some(d) = &r.direct {
        s.direct = match ctx.choice(d, "direct", &["shadow_rays", "photon_map"])? {
            "photon_map" => DirectLighting::PhotonMap,
            _ => DirectLighting::ShadowRays,
        };
    }
    s.final_gather = match (&r.final_gather, s.direct) {
        (Some(fg), DirectLighting::PhotonMap) if *fg.get_ref() => {
            return Err(ctx.err(
                &fg.span(),
                "[integrator]: final_gather = true needs direct = \"shadow_rays\"; with direct = \"photon_map\" the global map is visualised directly",
            ));
        }
        (Some(fg), _) => *fg.get_ref(),
        (None, DirectLighting::PhotonMap) => false,
        (None, DirectLighting::ShadowRays) => true,
    };
    s.dispersion_bundles = r.dispersion_bundles.as_ref().is_none_or(|b| *b.get_ref());
    s.axial_symmetry = r.axial_symmetry.as_ref().map(|b| *b.get_ref());
    s.edge_correction = r.edge_correction.as_ref().is_none_or(|b| *b.get_ref());
    s.filter = filter(ctx, r)?;
    s.curved = curved(ctx, r)?;
    s.progressive = super::progressive::progressive(ctx, r)?;
    Ok(s)
}

/// Fewest wavelength lanes for which a camera path is followed as a dispersion bundle (four
/// guides must leave lanes to interpolate).
pub const BUNDLE_MIN_LANES: usize = 8;

/// The smallest `arc_tolerance_m`, m.
pub const MIN_ARC_TOLERANCE_M: f64 = 1e-6;

/// `ode`, `ode_rtol`, `ode_atol`, `ode_step_m`, `ode_max_step_m`, `arc_tolerance_m`.
fn curved(ctx: &Ctx, r: &RawIntegrator) -> R<CurvedSettings> {
    use crate::ode::Method as Ode;
    let mut c = CurvedSettings::default();
    let positive = |v: &Option<Spanned<f64>>, name: &str, d: f64| -> R<f64> {
        v.as_ref().map_or(Ok(d), |v| ctx.number(v, name, 0.0, f64::INFINITY, true))
    };
    c.ode = match &r.ode {
        None => "dopri5",
        Some(o) => match ctx.choice(o, "ode", &["dopri5", "rk4", "euler"])? {
            "rk4" => "rk4",
            "euler" => "euler",
            _ => "dopri5",
        },
    };
    c.rtol = positive(&r.ode_rtol, "ode_rtol", c.rtol)?;
    c.atol = positive(&r.ode_atol, "ode_atol", c.atol)?;
    c.step_m = positive(&r.ode_step_m, "ode_step_m", c.step_m)?;
    c.max_step_m = match &r.ode_max_step_m {
        None => f64::INFINITY,
        Some(v) => ctx.number(v, "ode_max_step_m", 0.0, f64::INFINITY, true)?,
    };
    // At least 1 µm: the chords per path grow as 1/√tolerance, and the fuzzer found
    // arc_tolerance_m = 1e-11 on the fog sunset past a minute of `morgana check`.
    c.arc_tolerance_m = match &r.arc_tolerance_m {
        None => c.arc_tolerance_m,
        Some(v) => ctx.number(v, "arc_tolerance_m", MIN_ARC_TOLERANCE_M, f64::INFINITY, false)?,
    };
    let fixed_only = [(&r.ode_step_m, "ode_step_m")];
    let adaptive_only = [(&r.ode_rtol, "ode_rtol"), (&r.ode_atol, "ode_atol")];
    let unused: &[(&Option<Spanned<f64>>, &str)] = if c.ode == "dopri5" { &fixed_only } else { &adaptive_only };
    if let Some((Some(v), name)) = unused.iter().find(|(v, _)| v.is_some()) {
        return Err(ctx.err(&v.span(), format!("[integrator]: {name} is not used by ode = \"{}\"", c.ode)));
    }
    c.method = match c.ode {
        "rk4" => Ode::Rk4 { h_m: c.step_m },
        "euler" => Ode::Euler { h_m: c.step_m },
        _ => Ode::DormandPrince { rtol: c.rtol, atol: c.atol, pi: true, h0: None, h_min: 0.0, h_max: c.max_step_m },
    };
    c.method.validate().map_err(|e| {
        let at = r.ode.as_ref().map_or(0..0, |o| o.span());
        ctx.err(&at, format!("[integrator]: {e}"))
    })?;
    Ok(c)
}

fn filter(ctx: &Ctx, r: &RawIntegrator) -> R<Filter> {
    let kind = match &r.filter {
        None => "cone",
        Some(f) => ctx.choice(f, "filter", &["cone", "epanechnikov", "box"])?,
    };
    match (kind, &r.cone_k) {
        ("cone", None) => Ok(Filter::Cone { k: 1.1 }),
        ("cone", Some(k)) => Ok(Filter::Cone { k: ctx.number(k, "cone_k", 1.0, f64::INFINITY, false)? }),
        (_, Some(k)) => {
            Err(ctx.err(&k.span(), format!("[integrator]: cone_k is only used with filter = \"cone\", not \"{kind}\"")))
        }
        ("epanechnikov", None) => Ok(Filter::Epanechnikov),
        _ => Ok(Filter::Box),
    }
}

#[cfg(test)]
mod tests {
    use super::VolumeEstimate;

    /// The beam estimate only where the map holds sharp-edged light in a medium that is not
    /// stratified air and the eye's march steps outnumber the photons.
    #[test]
    fn the_default_volume_estimate_follows_the_scene() {
        assert_eq!(VolumeEstimate::default_for(true, false, true), VolumeEstimate::Beam);
        for (sharp, stratified, eye) in [(false, false, true), (true, true, true), (true, false, false)] {
            assert_eq!(VolumeEstimate::default_for(sharp, stratified, eye), VolumeEstimate::Point);
        }
    }
}
