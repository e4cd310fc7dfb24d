//! Serde structs that mirror the scene TOML exactly. Nothing here is validated; every field that
//! the validator may complain about is `Spanned`, so errors can point at its line and column.
//!
//! Shapes, materials and lights are flat structs with a `type` and the union of all types'
//! fields: the validator rejects a field that the given type does not use, naming the fields it
//! does use (a parameter the scene gives but nobody reads is an error).

use crate::validate::{Exactly, Vec3Raw};
use serde::Deserialize;
use std::collections::BTreeMap;
use toml::Spanned;

/// An optional TOML value that remembers its position in the file, for error messages.
pub type S<T> = Option<Spanned<T>>;

/// The whole scene file: one field per top-level table or array of tables.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawScene {
    /// `[camera]` (required).
    pub camera: Spanned<RawCamera>,
    /// `[output]`: outputs, wavelength range and tone reproduction.
    pub output: Option<Spanned<RawOutput>>,
    /// `[integrator]`: photon counts, estimates, eye samples and ray-equation settings.
    pub integrator: Option<Spanned<RawIntegrator>>,
    /// `[spectra]`: named spectra (`name = <spectrum value>`), referred to by name elsewhere.
    #[serde(default)]
    pub spectra: BTreeMap<String, Spanned<toml::Value>>,
    /// `[[material]]` records.
    #[serde(default)]
    pub material: Vec<Spanned<RawMaterial>>,
    /// `[[shape]]` records.
    #[serde(default)]
    pub shape: Vec<Spanned<RawShape>>,
    /// `[[light]]` records.
    #[serde(default)]
    pub light: Vec<Spanned<RawLight>>,
    /// `[world]`: the medium outside every closed shape and the Earth model.
    pub world: Option<Spanned<RawWorld>>,
    /// `[[medium]]` records.
    #[serde(default)]
    pub medium: Vec<Spanned<RawMedium>>,
    /// `[[sensor]]` records.
    #[serde(default)]
    pub sensor: Vec<Spanned<RawSensor>>,
}

/// `[world]`: what fills space outside every closed shape.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawWorld {
    /// `[world] medium`: name of the `[[medium]]` filling space outside every closed shape, or
    /// `"vacuum"`.
    pub medium: S<String>,
    /// `[world] earth`: `"flat"` or `"spherical"`; how heights of index fields and densities are
    /// measured.
    pub earth: S<String>,
    /// `[world] earth_radius_m`: radius R of the spherical Earth, m (centre at (0, −R, 0)).
    pub earth_radius_m: S<f64>,
}

/// `[[medium]]`: a participating medium; plain coefficients, `type = "ocean"`,
/// `type = "atmosphere"`, or coefficients with `inelastic`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawMedium {
    /// `[[medium]] name`: unique name that shapes and `[world]` refer to.
    pub name: S<String>,
    /// `[[medium]] sigma_a`: absorption coefficient at density 1, m⁻¹ (a spectrum value).
    pub sigma_a: S<toml::Value>,
    /// `[[medium]] sigma_s`: scattering coefficient at density 1, m⁻¹ (a spectrum value).
    pub sigma_s: S<toml::Value>,
    /// `[[medium]] sigma_t`: extinction coefficient at density 1, m⁻¹ (a spectrum value; with
    /// `albedo`).
    pub sigma_t: S<toml::Value>,
    /// `[[medium]] albedo`: single-scattering albedo σ_s/σ_t (a spectrum value in [0, 1]; with
    /// `sigma_t`).
    pub albedo: S<toml::Value>,
    /// `[[medium]] phase`: phase function, a name or a table with `type`.
    pub phase: S<toml::Value>,
    /// `[[medium]] density`: spatial density multiplying the coefficients, a table with `type`.
    pub density: S<toml::Value>,
    /// `[[medium]] index`: refractive-index field light curves along, a number or a table with
    /// `type`.
    pub index: S<toml::Value>,
    /// `type = "ocean"` builds sea water from the fields below (src/scene/inelastic.rs);
    /// `type = "atmosphere"` scattering air (src/scene/atmosphere_medium.rs).
    #[serde(rename = "type")]
    pub kind: S<String>,
    /// `[[medium]] chl_mg_m3` (ocean): chlorophyll-a concentration, mg m⁻³.
    pub chl_mg_m3: S<f64>,
    /// `[[medium]] cdom_a440_per_m` (ocean): CDOM absorption at 440 nm, m⁻¹.
    pub cdom_a440_per_m: S<f64>,
    /// `[[medium]] cdom_slope_per_nm` (ocean): spectral slope of CDOM absorption, nm⁻¹.
    pub cdom_slope_per_nm: S<f64>,
    /// `[[medium]] chl_yield` (ocean): chlorophyll fluorescence quantum yield (0 = off).
    pub chl_yield: S<f64>,
    /// `[[medium]] cdom_yield` (ocean): CDOM fluorescence quantum yield (omitted: FA7's own Γ(λ′);
    /// 0 = off).
    pub cdom_yield: S<f64>,
    /// `[[medium]] raman` (ocean): whether water Raman scattering is on.
    pub raman: S<bool>,
    /// `[[medium]] particle_phase` (ocean): phase function of the particles (`"petzold"` or a
    /// table).
    pub particle_phase: S<toml::Value>,
    /// `[[medium]] data_dir` (ocean): folder of tables replacing the built-in ones, relative to the
    /// scene file.
    pub data_dir: S<String>,
    /// Inelastic components of any medium: an array of tables.
    pub inelastic: S<toml::Value>,
    /// `[[medium]] atmosphere` (atmosphere): the air's profile, a built-in name or `{ file }`.
    pub atmosphere: S<toml::Value>,
    /// `[[medium]] rayleigh` (atmosphere): whether the air scatters (Rayleigh, Bodhaine et al. 1999),
    /// or a table `{ cross_section_cm2 = { wavelength_nm, value }, depolarisation }`.
    pub rayleigh: S<toml::Value>,
    /// `[[medium]] co2_ppm` (atmosphere): CO₂ of the air's Rayleigh cross-section, ppm by volume.
    pub co2_ppm: S<f64>,
    /// `[[medium]] refraction` (atmosphere): whether light curves along the air's refractive index.
    pub refraction: S<bool>,
    /// `[[medium]] ozone_du` (atmosphere): the ozone column in Dobson units (AFGL mid-latitude
    /// summer profile, Bogumil et al. 2003 cross-section).
    pub ozone_du: S<f64>,
    /// `[[medium]] ozone` (atmosphere): ozone from a profile file, a cross-section and/or a
    /// column: `{ profile = "o3.csv", cross_section_cm2 = <spectrum>, column_du = 300 }`.
    pub ozone: S<toml::Value>,
    /// `[[medium]] aerosol` (atmosphere): a table of Ångström α and β (or a visibility), scale
    /// height, single-scattering albedo and Henyey–Greenstein g.
    pub aerosol: S<toml::Value>,
}

/// `[camera]`: a pinhole or all-sky camera.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawCamera {
    /// `[camera] position`: eye point, m.
    pub position: S<Vec3Raw>,
    /// `[camera] look_at`: a point on the optical axis, m.
    pub look_at: S<Vec3Raw>,
    /// `[camera] up`: up direction (need not be unit or orthogonal to the view).
    pub up: S<Vec3Raw>,
    /// `[camera] fov_deg`: full vertical field of view, degrees.
    pub fov_deg: S<f64>,
    /// `[camera] width`: image width, pixels.
    pub width: S<i64>,
    /// `[camera] height`: image height, pixels.
    pub height: S<i64>,
    /// `[camera] projection`: `"pinhole"` (default) or `"equal_area"` (an all-sky fisheye).
    pub projection: S<String>,
}

/// `[output]`: what is written, over which wavelengths, and how the PNG is tone-mapped.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawOutput {
    /// `[output] name`: file stem of the outputs.
    pub name: S<String>,
    /// `[output] bands`: number of equal wavelength bands over [`min_nm`, `max_nm`].
    pub bands: S<i64>,
    /// `[output] min_nm`: short end of the simulated wavelength range, nm.
    pub min_nm: S<f64>,
    /// `[output] max_nm`: long end of the simulated wavelength range, nm.
    pub max_nm: S<f64>,
    /// `[output] sampling`: `"bands"` (one jittered wavelength per band) or `"hero"` (4 stratified
    /// per path).
    pub sampling: S<String>,
    /// `[output] exr`: write the spectral EXR.
    pub exr: S<bool>,
    /// `[output] png`: write the PNG preview.
    pub png: S<bool>,
    /// `[output] csv`: write one CSV row per pixel (x, y, radiance per band).
    pub csv: S<bool>,
    /// `[output] exposure`: PNG exposure, `"auto"` or stops (EV).
    pub exposure: S<toml::Value>,
    /// `[output] tonemap`: tone-reproduction operator of the PNG (`exposure`, `reinhard`,
    /// `ward_histogram`, `pattanaik`).
    pub tonemap: S<String>,
    /// `[output] adapt_to`: scene white for chromatic adaptation, a name or an [x, y] chromaticity.
    pub adapt_to: S<toml::Value>,
    /// `[output] cat`: chromatic adaptation transform (`von_kries`, `bradford`, `cat16`).
    pub cat: S<String>,
    /// `[output] adaptation_degree`: degree of chromatic adaptation D, 0 to 1.
    pub adaptation_degree: S<f64>,
    /// `[output] adaptation_time_s`: time since the adaptation luminance changed, s (Pattanaik
    /// only).
    pub adaptation_time_s: S<f64>,
    /// `[output] adapt_from_cd_m2`: luminance the eye was adapted to before, cd m⁻² (Pattanaik
    /// only).
    pub adapt_from_cd_m2: S<f64>,
    /// `[output] scotopic`: rod vision, `auto`, `on` or `off`.
    pub scotopic: S<String>,
    /// `[output] false_colour`: write luminance on a log scale with a legend instead of a picture.
    pub false_colour: S<bool>,
    /// `[output] region`: pixel rectangle [x0, y0, x1, y1] (x1, y1 exclusive) written to
    /// `NAME.region.csv`.
    pub region: S<Exactly<i64, 4>>,
}

/// `[integrator]`: how light is simulated.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawIntegrator {
    /// `[integrator] method`: `"photon_map"` or `"path"` (the unbiased volumetric path tracer).
    pub method: S<String>,
    /// `[integrator] photons`: photons emitted for the global and volume maps.
    pub photons: S<i64>,
    /// `[integrator] caustic_photons`: photons emitted for the caustic map.
    pub caustic_photons: S<i64>,
    /// `[integrator] k`: nearest photons per global-map estimate.
    pub k: S<i64>,
    /// `[integrator] max_radius`: largest gather radius of the global map, m.
    pub max_radius: S<f64>,
    /// `[integrator] caustic_k`: nearest photons per caustic-map estimate.
    pub caustic_k: S<i64>,
    /// `[integrator] caustic_max_radius`: largest gather radius of the caustic map, m.
    pub caustic_max_radius: S<f64>,
    /// `[integrator] volume_k`: nearest photons per volume-map estimate.
    pub volume_k: S<i64>,
    /// `[integrator] volume_max_radius`: largest gather radius of the volume map, m.
    pub volume_max_radius: S<f64>,
    /// `[integrator] march_step`: largest ray-marching step in media, m.
    pub march_step: S<f64>,
    /// `[integrator] volume_estimate`: `"point"`, `"beam"` or `"photon_beams"`: how the volume
    /// map is read along eye rays.
    pub volume_estimate: S<String>,
    /// `[integrator] direct`: `"shadow_rays"` or `"photon_map"`: how direct light on diffuse
    /// surfaces is found.
    pub direct: S<String>,
    /// `[integrator] final_gather`: gather indirect light with rays into the global map.
    pub final_gather: S<bool>,
    /// `[integrator] dispersion_bundles`: interpolate the paths of a camera path's wavelengths
    /// through an absorbing, dispersive medium from four guides where a check allows.
    pub dispersion_bundles: S<bool>,
    /// `[integrator] axial_symmetry`: fold volume photons about the sun's axis where the scene
    /// is symmetric about it.
    pub axial_symmetry: S<bool>,
    /// `[integrator] edge_correction`: surface photon estimates divide by the part of their
    /// disc that lies on surfaces able to hold photons.
    pub edge_correction: S<bool>,
    /// `[integrator] gather_rays`: final-gather rays per shading point.
    pub gather_rays: S<i64>,
    /// `[integrator] spp`: eye samples per pixel.
    pub spp: S<i64>,
    /// `[integrator] max_depth`: specular bounces of an eye path.
    pub max_depth: S<i64>,
    /// `[integrator] seed`: random seed.
    pub seed: S<i64>,
    /// `[integrator] filter`: density-estimate kernel, `"cone"`, `"epanechnikov"` or `"box"`.
    pub filter: S<String>,
    /// `[integrator] cone_k`: Jensen's cone-filter constant k (≥ 1).
    pub cone_k: S<f64>,
    /// `[integrator] ode`: integrator of the ray equation, `"dopri5"`, `"rk4"` or `"euler"`.
    pub ode: S<String>,
    /// `[integrator] ode_rtol`: Dormand–Prince relative tolerance.
    pub ode_rtol: S<f64>,
    /// `[integrator] ode_atol`: Dormand–Prince absolute tolerance.
    pub ode_atol: S<f64>,
    /// `[integrator] ode_step_m`: fixed step of `rk4` / `euler`, m.
    pub ode_step_m: S<f64>,
    /// `[integrator] ode_max_step_m`: longest step Dormand–Prince may take, m.
    pub ode_max_step_m: S<f64>,
    /// `[integrator] arc_tolerance_m`: how far a chord may stray from the curved path, m.
    pub arc_tolerance_m: S<f64>,
    /// `[integrator] passes`: progressive photon-mapping passes to run.
    pub passes: S<i64>,
    /// `[integrator] time`: wall-clock budget of the whole run, e.g. `"90s"` or a number of seconds.
    pub time: S<toml::Value>,
    /// `[integrator] target_rel_error`: stop when the relative standard error falls below this.
    pub target_rel_error: S<f64>,
    /// `[integrator] target`: what `target_rel_error` is measured on: `"image"`, `"pixels"`, a
    /// sensor's name or a pixel region `"x0,y0,x1,y1"`.
    pub target: S<String>,
    /// `[integrator] alpha`: how fast progressive gather radii shrink (Knaus & Zwicker's α).
    pub alpha: S<f64>,
    /// `[integrator] adaptive`: from the second progressive pass on, spend each pass's eye
    /// samples where the pixels' samples spread most.
    pub adaptive: S<bool>,
}

/// `[[material]]`: a surface material; the union of every type's keys.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawMaterial {
    /// `[[material]] name`: unique name that shapes and area lights refer to.
    pub name: S<String>,
    /// `[[material]] type`: `lambertian`, `mirror`, `dielectric` or `rough_dielectric`.
    #[serde(rename = "type")]
    pub kind: S<String>,
    /// `[[material]] reflectance`: reflectance spectrum in [0, 1] (lambertian, mirror).
    pub reflectance: S<toml::Value>,
    /// `[[material]] ior`: refractive index, a number or a catalogue name (dielectrics).
    pub ior: S<toml::Value>,
    /// `[[material]] ior_model`: dispersion law, `constant`, `cauchy` or `sellmeier` (dielectrics).
    pub ior_model: S<String>,
    /// `[[material]] a`: Cauchy constant term, n = a + b/λ² + c/λ⁴ with λ in μm.
    pub a: S<f64>,
    /// `[[material]] b_um2`: Cauchy b, μm².
    pub b_um2: S<f64>,
    /// `[[material]] c_um4`: Cauchy c, μm⁴.
    pub c_um4: S<f64>,
    /// `[[material]] sellmeier_b`: Sellmeier coefficients B₁..B₃ (dimensionless).
    pub sellmeier_b: S<Vec3Raw>,
    /// `[[material]] sellmeier_c_um2`: Sellmeier coefficients C₁..C₃, μm².
    pub sellmeier_c_um2: S<Vec3Raw>,
    /// `[[material]] wind_speed_m_s` (rough_dielectric): wind speed of the Cox–Munk sea, m s⁻¹.
    pub wind_speed_m_s: S<f64>,
    /// `[[material]] rms_slope` (rough_dielectric): Beckmann RMS slope α.
    pub rms_slope: S<f64>,
}

/// `[[shape]]`: a surface; the union of every type's keys.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawShape {
    /// `[[shape]] name`: optional name used in messages and by `morgana trace`.
    pub name: S<String>,
    /// `[[shape]] type`: `sphere`, `quad`, `box`, `disk`, `triangle` or `mesh`.
    #[serde(rename = "type")]
    pub kind: S<String>,
    /// `[[shape]] material`: material name (omitted: an index-matched boundary, needs `interior`).
    pub material: S<String>,
    /// `[[shape]] interior`: medium inside (behind the normal), a `[[medium]]` name or `"vacuum"`.
    pub interior: S<String>,
    /// `[[shape]] exterior`: medium outside (in front of the normal).
    pub exterior: S<String>,
    /// `[[shape]] center`: centre of a sphere or disk, m.
    pub center: S<Vec3Raw>,
    /// `[[shape]] radius`: radius of a sphere or disk, m.
    pub radius: S<f64>,
    /// `[[shape]] normal`: normal of a disk.
    pub normal: S<Vec3Raw>,
    /// `[[shape]] origin`: corner of a quad, m.
    pub origin: S<Vec3Raw>,
    /// `[[shape]] u`: first edge of a quad, m (the normal is u × v).
    pub u: S<Vec3Raw>,
    /// `[[shape]] v`: second edge of a quad, m.
    pub v: S<Vec3Raw>,
    /// `[[shape]] min`: lower corner of a box, m.
    pub min: S<Vec3Raw>,
    /// `[[shape]] max`: upper corner of a box, m.
    pub max: S<Vec3Raw>,
    /// `[[shape]] vertices`: the three corners of a triangle, m, counter-clockwise seen from the
    /// front.
    pub vertices: S<Vec<Vec3Raw>>,
    /// `[[shape]] file`: OBJ file of a mesh, relative to the scene file.
    pub file: S<String>,
    /// `[[shape]] scale`: uniform scale of a mesh, applied first.
    pub scale: S<f64>,
    /// `[[shape]] translate`: translation of a mesh, m, applied last.
    pub translate: S<Vec3Raw>,
    /// `[[shape]] rotate_y_deg`: rotation of a mesh about +y, degrees, applied after scaling.
    pub rotate_y_deg: S<f64>,
}

/// `[[light]]`: a light source; the union of every type's keys.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawLight {
    /// `[[light]] name`: optional label in messages and reports.
    pub name: S<String>,
    /// `[[light]] type`: `area`, `point`, `spot`, `directional`, `sun`, `sky` or `luminaire`.
    #[serde(rename = "type")]
    pub kind: S<String>,
    /// `[[light]] spectrum`: emission spectrum (shape, or absolute with `scale`).
    pub spectrum: S<toml::Value>,
    /// `[[light]] power_w`: radiant flux within the scene's wavelength range, W.
    pub power_w: S<f64>,
    /// `[[light]] scale`: multiplier making `spectrum` absolute (radiance, intensity or irradiance
    /// by type).
    pub scale: S<f64>,
    /// `[[light]] irradiance_w_m2` (directional, sun): irradiance normal to the beam within the
    /// wavelength range, W m⁻².
    pub irradiance_w_m2: S<f64>,
    /// `[[light]] shape`: emitting shape of an area light, `quad`, `disk` or `sphere`.
    pub shape: S<String>,
    /// `[[light]] side`: emitting side of an area light, `front`, `back` or `both`.
    pub side: S<String>,
    /// `[[light]] material`: material of an area light's surface (default black).
    pub material: S<String>,
    /// `[[light]] center`: centre of an area light's disk or sphere, m.
    pub center: S<Vec3Raw>,
    /// `[[light]] radius`: radius of an area light's disk or sphere, m.
    pub radius: S<f64>,
    /// `[[light]] normal`: normal of an area light's disk.
    pub normal: S<Vec3Raw>,
    /// `[[light]] origin`: corner of an area light's quad, m.
    pub origin: S<Vec3Raw>,
    /// `[[light]] u`: first edge of an area light's quad, m.
    pub u: S<Vec3Raw>,
    /// `[[light]] v`: second edge of an area light's quad, m.
    pub v: S<Vec3Raw>,
    /// `[[light]] position`: position of a point light, spot or luminaire's photometric centre, m.
    pub position: S<Vec3Raw>,
    /// `[[light]] direction`: direction of travel of a directional light or sun; the axis of a
    /// spot; a luminaire's nadir.
    pub direction: S<Vec3Raw>,
    /// `[[light]] look_at`: point the spot or luminaire aims at, m (instead of `direction`).
    pub look_at: S<Vec3Raw>,
    /// `[[light]] cone_deg`: half-angle of a spot's cone, degrees.
    pub cone_deg: S<f64>,
    /// `[[light]] falloff_start_deg`: half-angle where a spot's falloff begins, degrees.
    pub falloff_start_deg: S<f64>,
    /// `[[light]] target_min`: lower corner of the box a directional light or sun or sky aims its
    /// photons at, m.
    pub target_min: S<Vec3Raw>,
    /// `[[light]] target_max`: upper corner of that target box, m.
    pub target_max: S<Vec3Raw>,
    /// `[[light]] file`: photometric file of a luminaire (IES, EULUMDAT, ...), relative to the
    /// scene file.
    pub file: S<String>,
    /// `[[light]] cct_k`: colour temperature of a luminaire's black-body spectrum, K.
    pub cct_k: S<f64>,
    /// `[[light]] flux_scale`: multiplier of a luminaire file's intensities.
    pub flux_scale: S<f64>,
    /// `[[light]] c0_toward`: direction the luminaire's C0 half-plane points toward.
    pub c0_toward: S<Vec3Raw>,
    /// `[[light]] rotation_deg`: a luminaire's Euler angles about the fixed X, then Y, then Z axes,
    /// degrees.
    pub rotation_deg: S<Vec3Raw>,
    /// `[[light]] emitter`: where a luminaire's photons start, `"point"` or `"opening"`.
    pub emitter: S<String>,
    /// `type = "luminaire"` with a GLDF file: the variant id.
    pub variant: S<String>,
    /// `[[light]] elevation_deg`: sun elevation above the horizontal, degrees.
    pub elevation_deg: S<f64>,
    /// `[[light]] azimuth_deg`: sun azimuth, degrees (0 toward −z, 90 toward +x).
    pub azimuth_deg: S<f64>,
    /// `[[light]] angular_diameter_deg`: apparent diameter of a directional light or the sun's
    /// disk, degrees.
    pub angular_diameter_deg: S<f64>,
    /// `[[light]] limb_darkening`: how a sun's or a directional disc's radiance falls toward its
    /// edge, `"none"` (uniform) or `"neckel_labs_1994"`.
    pub limb_darkening: S<String>,
    /// `[[light]] up`: zenith direction of a sky.
    pub up: S<Vec3Raw>,
    /// `[[light]] horizon_deg`: elevation of a sky's lower edge above the plane normal to `up`,
    /// degrees.
    pub horizon_deg: S<f64>,
}

/// `[[sensor]]`: a virtual instrument; the union of every type's keys.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawSensor {
    /// `[[sensor]] name`: names the outputs `NAME_<sensor>.*`.
    pub name: S<String>,
    /// `[[sensor]] type`: `illuminance_plane` or `ocean_profile`.
    #[serde(rename = "type")]
    pub kind: S<String>,
    /// `[[sensor]] origin`: a corner of the plane's grid, or the centre of the profile's square on
    /// the water surface, m.
    pub origin: S<Vec3Raw>,
    /// `[[sensor]] u`: first edge of the grid or square, m.
    pub u: S<Vec3Raw>,
    /// `[[sensor]] v`: second edge of the grid or square, m.
    pub v: S<Vec3Raw>,
    /// `[[sensor]] normal`: the side measured (plane), or up toward the air (profile).
    pub normal: S<Vec3Raw>,
    /// `[[sensor]] resolution`: grid points [nu, nv] of an illuminance plane.
    pub resolution: S<Exactly<i64, 2>>,
    /// `[[sensor]] samples`: estimates averaged per point (plane), or shadow rays per band for
    /// Ed(0+) (profile).
    pub samples: S<i64>,
    /// `[[sensor]] gather_rays`: rays for indirect light per sample of an illuminance plane (0:
    /// direct only).
    pub gather_rays: S<i64>,
    /// `type = "ocean_profile"` only.
    pub depths_m: S<Vec<f64>>,
    /// `type = "sky_radiance"` only: [view zenith, view azimuth] pairs, degrees.
    pub directions_deg: S<Vec<Exactly<f64, 2>>>,
    /// `[[sensor]] slab_m`: thickness of each measuring slab of an ocean profile, m.
    pub slab_m: S<f64>,
    /// `[[sensor]] ior`: water's refractive index used for the water-leaving radiance Lw.
    pub ior: S<f64>,
    /// `tangent_heights_m` (limb): heights of the lines of sight's tangent points above the
    /// ground, m.
    pub tangent_heights_m: S<Vec<f64>>,
    /// `azimuth_deg` (limb): the azimuth the lines of sight look toward, degrees.
    pub azimuth_deg: S<f64>,
}
