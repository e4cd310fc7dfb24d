//! Participating media: what fills space between surfaces — absorption, scattering, phase
//! functions ([`phase`]), spatial density ([`density`]), free-flight sampling and transmittance
//! ([`tracking`]), refractive-index fields ([`refractive_index`]), inelastic scattering —
//! fluorescence and Raman — ([`inelastic`]), Rayleigh scattering by air ([`rayleigh_air`]),
//! ozone ([`ozone`]) and aerosols ([`aerosol`]) as constituents of an atmosphere
//! ([`constituents`]) with their single-scattering albedos ([`albedo`]), where an atmosphere's bending is negligible ([`bending`]), and a medium at
//! one point ([`MediumAt`]).

pub mod aerosol;
pub mod albedo;
pub mod bending;
pub mod constituents;
pub mod density;
pub mod inelastic;
mod local;
mod medium;
pub mod ocean;
pub mod ozone;
pub mod phase;
pub mod rayleigh_air;
pub mod refractive_index;
pub mod tracking;

pub use local::MediumAt;
pub use medium::{CLIMB_PER_STEP, Coefficients, Medium};
