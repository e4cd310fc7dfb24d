//! Participating media: what fills space between surfaces — absorption, scattering, phase
//! functions ([`phase`]), spatial density ([`density`]), free-flight sampling and transmittance
//! ([`tracking`]), and refractive-index fields ([`index`]).

pub mod density;
pub mod index;
mod medium;
pub mod phase;
pub mod tracking;

pub use medium::{Coefficients, Medium};
