//! Atmosphere physics: the Earth's geometry ([`Earth`]), standard atmospheres, profile edits and
//! the refractive index of air.

mod earth;
pub mod table;

pub use earth::{EARTH_RADIUS_M, Earth, Sphere};
