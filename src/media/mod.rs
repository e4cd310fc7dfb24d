//! Participating media: what fills space between surfaces — absorption, scattering, phase
//! functions ([`phase`]), spatial density ([`density`]), free-flight sampling and transmittance
//! ([`tracking`]), refractive-index fields ([`refractive_index`]), inelastic scattering —
//! fluorescence and Raman — ([`inelastic`]), and Rayleigh scattering by air ([`rayleigh_air`]).

pub mod density;
pub mod inelastic;
mod medium;
pub mod ocean;
pub mod phase;
pub mod rayleigh_air;
pub mod refractive_index;
pub mod tracking;

pub use medium::{Coefficients, Medium};
