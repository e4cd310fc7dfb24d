//! Atmosphere physics: the Earth's geometry ([`Earth`]), standard atmospheres ([`usa76`], tabulated
//! profiles), temperature edits for mirages ([`edit`]), and the refractive index of air
//! ([`dispersion`]), combined in [`Atmosphere`]. Atmospheres are data files (`atmospheres/`,
//! loaded by [`load`]) or built in ([`Atmosphere::builtin`]). [`refraction`] traces rays out of
//! one: astronomical refraction.

mod base;
mod builtin;
pub mod dispersion;
pub mod dual;
mod earth;
pub mod edit;
pub mod file;
pub mod gas;
pub mod horizon_ray;
mod model;
pub mod radial_table;
pub mod refraction;
mod table_profile;
pub mod usa76;

pub use base::BaseProfile;
pub use builtin::{BUILTIN_NAMES, resolve};
pub use dispersion::AirDispersion;
pub use earth::{EARTH_RADIUS_M, Earth, MAX_EARTH_RADIUS_M, Sphere};
pub use edit::Edit;
pub use file::load;
pub use model::{AirPoint, Atmosphere};
pub use radial_table::RadialTable;
pub use table_profile::TableProfile;
