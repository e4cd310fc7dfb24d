//! Fields sampled and interpolated in space: the building blocks of refractive-index fields and
//! atmospheres, independent of what quantity they hold.
//!
//! - [`Lattice`]: a scalar on a regular 3-D lattice, trilinear or tricubic (Catmull–Rom), with its
//!   gradient in closed form; [`grid_file`] reads and writes lattices as files.
//! - [`MonotoneCubic`]: a monotone piecewise-cubic interpolant of a 1-D table (Fritsch–Carlson).
//! - [`Bump`]: a smooth, compactly supported bump.
//! - [`GradientRegion`]: where a field's gradient can be non-zero, so that paths outside it stay
//!   straight.

mod bump;
pub mod grid_file;
mod lattice;
mod monotone_cubic;
mod region;

pub use bump::Bump;
pub use lattice::{Beyond, Interpolation, Lattice, MAX_LATTICE_POINTS, catmull_rom_overshoot};
pub use monotone_cubic::MonotoneCubic;
pub use region::GradientRegion;
