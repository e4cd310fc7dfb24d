//! Atmosphere physics: the Earth's geometry ([`Earth`]), standard atmospheres, profile edits and
//! the refractive index of air.

mod base;
pub mod dispersion;
mod earth;
pub mod edit;
pub mod gas;
mod model;
pub mod table;
mod table_profile;
pub mod usa76;

pub use base::BaseProfile;
pub use dispersion::AirDispersion;
pub use earth::{EARTH_RADIUS_M, Earth, Sphere};
pub use edit::Edit;
pub use model::{AirPoint, Atmosphere};
pub use table_profile::TableProfile;
