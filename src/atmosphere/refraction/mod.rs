//! Astronomical refraction: how much the atmosphere lifts a star seen at a given apparent
//! altitude, by tracing the ray from the observer out of the atmosphere.
//!
//! # Method
//! The observer stands at height h₀ above the spherical Earth of the atmosphere (centre c,
//! radius R; the scene frame puts c at (0, −R, 0), so the observer is at (0, h₀, 0)). A ray
//! leaves at apparent altitude a above the observer's horizontal plane and follows Fermat's ray
//! equation d/ds(n dr/ds) = ∇n through the atmosphere's n(λ, x), integrated by Dormand–Prince
//! RK5(4)7M ([`crate::ode`]) with a tight tolerance (rtol = atol = 10⁻¹², converged:
//! tests/refraction.rs). Above the atmosphere's top n ≡ 1 and the path is straight, so the
//! direction d on leaving is the star's true direction; the *true altitude* is its angle above
//! the observer's horizontal plane, t = atan2(d·û, |d − (d·û)û|) (û the observer's vertical),
//! and the refraction is R = a − t. A star at infinity has no parallax, so the observer's
//! position does not enter t.
//!
//! A ray can also end below the ground (h < 0: it "hits the ground", no refraction), or be
//! *trapped*: it turned from climbing to descending inside the atmosphere (ducting, a
//! gradient of n steeper than the Earth's curvature) — in an atmosphere whose n depends only on
//! height such a ray can never escape (Bouguer's invariant n·r·cos e would have to exceed its
//! value at the turning point) — and then met the ground, or is still aloft after
//! [`Settings::max_path_m`].
//!
//! [`formulas`] holds the classical formulas the traced values are compared with (Bennett 1982,
//! Saemundsson 1986, their pressure–temperature factor); [`sun`] the apparent shape of the sun
//! near the horizon; [`report`] the table and CSV of `morgana refraction`. [`terrestrial`] is
//! the other question refraction answers, for targets on the Earth: where a ray from the
//! observer is at a given distance along the ground, by quadrature of Bouguer's invariant
//! ([`terrestrial_table`]: `morgana refraction --ground-distances-km`).
//!
//! # References
//! - W. M. Smart, *Textbook on Spherical Astronomy*, 6th ed. (rev. R. M. Green), Cambridge 1977,
//!   ch. III (the refraction integral, Laplace's series).
//! - A. T. Young 2004, "Sunset science. IV. Low-altitude refraction", Astron. J. 127:3622.

pub mod formulas;
pub mod model;
pub mod model_table;
pub mod model_trace;
pub mod quadrature;
pub mod refractor;
pub mod report;
pub mod sight;
pub mod sun;
pub mod terrestrial;
pub mod terrestrial_table;
mod trace;

pub use trace::{Outcome, Settings, Trace, Tracer};

/// Writes `text` to the CSV file `path` atomically (the `--csv` option of `morgana refraction`).
fn write_csv(path: &std::path::Path, text: &str) -> crate::error::Result<()> {
    use crate::error::Error;
    let staged =
        crate::atomic::Staged::new(path).map_err(|e| Error::input(None, format!("--csv {}: {e}", path.display())))?;
    let fail = |e: std::io::Error| Error::internal(format!("cannot write {}: {e}", path.display()));
    std::fs::write(&staged.temp, text).map_err(fail)?;
    staged.commit().map_err(fail)
}

/// Arcseconds per radian (648000/π).
pub const ARCSEC_PER_RAD: f64 = 648_000.0 / std::f64::consts::PI;
