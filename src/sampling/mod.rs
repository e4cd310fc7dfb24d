//! Sample warps (uniform square to directions and points), discrete distributions, and the
//! scrambled low-discrepancy points of a pixel's eye samples.
//!
//! Each warp returns the sample and states its density; `src/testing/chi2.rs` checks every one of
//! them against that density. Formulas follow Pharr, Jakob & Humphreys, *Physically Based
//! Rendering*, 4th ed. (2023), §A.5 and §13.6 (PBRT4).

mod discrete;
mod sobol;
mod warp;

pub use discrete::Discrete1D;
pub use sobol::{ScrambledSobol2, digital_shift};
pub use warp::{
    concentric_disk, cosine_cone, cosine_cone_pdf, cosine_hemisphere, cosine_hemisphere_pdf, uniform_cone,
    uniform_cone_pdf, uniform_sphere, uniform_sphere_pdf, uniform_triangle,
};
