//! Serde structs that mirror the scene TOML exactly. Nothing here is validated; every field that
//! the validator may complain about is `Spanned`, so errors can point at its line and column.
//!
//! Shapes, materials and lights are flat structs with a `type` and the union of all types'
//! fields: the validator rejects a field that the given type does not use, naming the fields it
//! does use (a parameter the scene gives but nobody reads is an error).

use serde::Deserialize;
use std::collections::BTreeMap;
use toml::Spanned;

pub type S<T> = Option<Spanned<T>>;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawScene {
    pub camera: Spanned<RawCamera>,
    pub output: Option<Spanned<RawOutput>>,
    pub integrator: Option<Spanned<RawIntegrator>>,
    #[serde(default)]
    pub spectra: BTreeMap<String, Spanned<toml::Value>>,
    #[serde(default)]
    pub material: Vec<Spanned<RawMaterial>>,
    #[serde(default)]
    pub shape: Vec<Spanned<RawShape>>,
    #[serde(default)]
    pub light: Vec<Spanned<RawLight>>,
    pub world: Option<Spanned<RawWorld>>,
    #[serde(default)]
    pub medium: Vec<Spanned<RawMedium>>,
    #[serde(default)]
    pub sensor: Vec<Spanned<RawSensor>>,
}

/// `[world]`: what fills space outside every closed shape.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawWorld {
    pub medium: S<String>,
    pub earth: S<String>,
    pub earth_radius_m: S<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawMedium {
    pub name: S<String>,
    pub sigma_a: S<toml::Value>,
    pub sigma_s: S<toml::Value>,
    pub sigma_t: S<toml::Value>,
    pub albedo: S<toml::Value>,
    pub phase: S<toml::Value>,
    pub density: S<toml::Value>,
    pub index: S<toml::Value>,
    /// `type = "ocean"` builds sea water from the fields below (src/scene/inelastic.rs).
    #[serde(rename = "type")]
    pub kind: S<String>,
    pub chl_mg_m3: S<f64>,
    pub cdom_a440_per_m: S<f64>,
    pub cdom_slope_per_nm: S<f64>,
    pub chl_yield: S<f64>,
    pub cdom_yield: S<f64>,
    pub raman: S<bool>,
    pub particle_phase: S<toml::Value>,
    pub data_dir: S<String>,
    /// Inelastic components of any medium: an array of tables.
    pub inelastic: S<toml::Value>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawCamera {
    pub position: S<[f64; 3]>,
    pub look_at: S<[f64; 3]>,
    pub up: S<[f64; 3]>,
    pub fov_deg: S<f64>,
    pub width: S<i64>,
    pub height: S<i64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawOutput {
    pub name: S<String>,
    pub bands: S<i64>,
    pub min_nm: S<f64>,
    pub max_nm: S<f64>,
    pub sampling: S<String>,
    pub exr: S<bool>,
    pub png: S<bool>,
    pub csv: S<bool>,
    pub exposure: S<toml::Value>,
    pub tonemap: S<String>,
    pub adapt_to: S<toml::Value>,
    pub cat: S<String>,
    pub adaptation_degree: S<f64>,
    pub adaptation_time_s: S<f64>,
    pub adapt_from_cd_m2: S<f64>,
    pub scotopic: S<String>,
    pub false_colour: S<bool>,
    pub region: S<[i64; 4]>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawIntegrator {
    pub method: S<String>,
    pub photons: S<i64>,
    pub caustic_photons: S<i64>,
    pub k: S<i64>,
    pub max_radius: S<f64>,
    pub caustic_k: S<i64>,
    pub caustic_max_radius: S<f64>,
    pub volume_k: S<i64>,
    pub volume_max_radius: S<f64>,
    pub march_step: S<f64>,
    pub direct: S<String>,
    pub final_gather: S<bool>,
    pub gather_rays: S<i64>,
    pub spp: S<i64>,
    pub max_depth: S<i64>,
    pub seed: S<i64>,
    pub filter: S<String>,
    pub cone_k: S<f64>,
    pub ode: S<String>,
    pub ode_rtol: S<f64>,
    pub ode_atol: S<f64>,
    pub ode_step_m: S<f64>,
    pub ode_max_step_m: S<f64>,
    pub arc_tolerance_m: S<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawMaterial {
    pub name: S<String>,
    #[serde(rename = "type")]
    pub kind: S<String>,
    pub reflectance: S<toml::Value>,
    pub ior: S<toml::Value>,
    pub ior_model: S<String>,
    pub a: S<f64>,
    pub b_um2: S<f64>,
    pub c_um4: S<f64>,
    pub sellmeier_b: S<[f64; 3]>,
    pub sellmeier_c_um2: S<[f64; 3]>,
    pub wind_speed_m_s: S<f64>,
    pub rms_slope: S<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawShape {
    pub name: S<String>,
    #[serde(rename = "type")]
    pub kind: S<String>,
    pub material: S<String>,
    pub interior: S<String>,
    pub exterior: S<String>,
    pub center: S<[f64; 3]>,
    pub radius: S<f64>,
    pub normal: S<[f64; 3]>,
    pub origin: S<[f64; 3]>,
    pub u: S<[f64; 3]>,
    pub v: S<[f64; 3]>,
    pub min: S<[f64; 3]>,
    pub max: S<[f64; 3]>,
    pub vertices: S<Vec<[f64; 3]>>,
    pub file: S<String>,
    pub scale: S<f64>,
    pub translate: S<[f64; 3]>,
    pub rotate_y_deg: S<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawLight {
    pub name: S<String>,
    #[serde(rename = "type")]
    pub kind: S<String>,
    pub spectrum: S<toml::Value>,
    pub power_w: S<f64>,
    pub scale: S<f64>,
    pub irradiance_w_m2: S<f64>,
    pub shape: S<String>,
    pub side: S<String>,
    pub material: S<String>,
    pub center: S<[f64; 3]>,
    pub radius: S<f64>,
    pub normal: S<[f64; 3]>,
    pub origin: S<[f64; 3]>,
    pub u: S<[f64; 3]>,
    pub v: S<[f64; 3]>,
    pub position: S<[f64; 3]>,
    pub direction: S<[f64; 3]>,
    pub look_at: S<[f64; 3]>,
    pub cone_deg: S<f64>,
    pub falloff_start_deg: S<f64>,
    pub target_min: S<[f64; 3]>,
    pub target_max: S<[f64; 3]>,
    pub file: S<String>,
    pub cct_k: S<f64>,
    pub flux_scale: S<f64>,
    pub c0_toward: S<[f64; 3]>,
    pub rotation_deg: S<[f64; 3]>,
    pub emitter: S<String>,
    /// `type = "luminaire"` with a GLDF file: the variant id.
    pub variant: S<String>,
    pub elevation_deg: S<f64>,
    pub azimuth_deg: S<f64>,
    pub angular_diameter_deg: S<f64>,
    pub up: S<[f64; 3]>,
    pub horizon_deg: S<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawSensor {
    pub name: S<String>,
    #[serde(rename = "type")]
    pub kind: S<String>,
    pub origin: S<[f64; 3]>,
    pub u: S<[f64; 3]>,
    pub v: S<[f64; 3]>,
    pub normal: S<[f64; 3]>,
    pub resolution: S<[i64; 2]>,
    pub samples: S<i64>,
    pub gather_rays: S<i64>,
    /// `type = "ocean_profile"` only.
    pub depths_m: S<Vec<f64>>,
    pub slab_m: S<f64>,
    pub ior: S<f64>,
}
