//! Participating media: what fills space between surfaces — absorption, scattering, phase
//! functions ([`phase`]) and refractive-index fields ([`index`]).

pub mod index;
pub mod phase;
