//! Atmosphere physics: the Earth's geometry ([`Earth`]), standard atmospheres, profile edits and
//! the refractive index of air.

pub mod dispersion;
mod earth;
pub mod gas;
pub mod table;
pub mod usa76;

pub use dispersion::AirDispersion;
pub use earth::{EARTH_RADIUS_M, Earth, Sphere};
