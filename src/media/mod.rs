//! Participating media: what fills space between surfaces — absorption, scattering, phase
//! functions ([`phase`]), spatial density ([`density`]), free-flight sampling and transmittance
//! ([`tracking`]), refractive-index fields ([`refractive_index`]), and inelastic scattering —
//! fluorescence and Raman — ([`inelastic`]).

pub mod density;
pub mod inelastic;
mod medium;
pub mod ocean;
pub mod phase;
pub mod refractive_index;
pub mod tracking;

pub use medium::{Coefficients, Medium};
