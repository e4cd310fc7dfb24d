//! # morgana
//!
//! A spectral light-transport simulator for media that bend and re-colour light. Photons and eye
//! rays travel through one propagation interface ([`raypath`]); a photon carries one wavelength,
//! an eye path carries all bands until something on it depends on wavelength. What a scene needs
//! is decided once, in the [`scene::EffectPlan`], and every integrator reads that plan.
//!
//! Entry points: [`scene::load_scene_file`] / [`scene::load_scene_str`] build a validated
//! [`scene::Scene`]; [`render::render`] runs the photon passes and the eye pass;
//! [`output::write_outputs`] writes the spectral EXR, PNG preview and `report.json`.
//!
//! Units are SI (metres, seconds, watts); spectral quantities are per nanometre, and names carry
//! units where they could be doubted (`wavelength_nm`, `power_w`).

#![warn(missing_docs)]

pub mod atmosphere;
pub mod atomic;
pub mod cli;
pub mod distributed;
pub mod error;
pub mod field;
pub mod geometry;
pub mod light;
pub mod luminaire;
pub mod material;
pub mod media;
pub mod memory;
pub mod ode;
pub mod output;
pub mod photon;
pub mod photon_map;
pub mod quadrature;
pub mod raster;
pub mod raypath;
pub mod render;
pub mod rng;
pub mod sampling;
pub mod scene;
pub mod sensor;
pub mod spectrum;
pub mod testing;
pub mod timing;
pub mod tonemap;
pub mod validate;
pub mod world;
