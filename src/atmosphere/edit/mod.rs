//! Temperature edits of a base atmosphere, the profiles a mirage needs: T = T_base + Σᵢ ΔTᵢ(x).
//!
//! Pressure stays that of the base atmosphere (an edit heats or cools air in place without
//! changing the hydrostatic column above it); density follows from the ideal gas at the local
//! pressure and the edited temperature. Every edit gives ΔT and ∇ΔT in closed form.

mod bubble;
mod grid;
mod hot_surface;
mod inversion;
mod offset;

pub use bubble::Bubble;
pub use grid::GridEdit;
pub use hot_surface::HotSurface;
pub use inversion::Inversion;
pub use offset::Offset;

use glam::DVec3;

/// One temperature edit of a base atmosphere; ΔT in K.
#[derive(Clone, Debug, PartialEq)]
pub enum Edit {
    /// T += ΔT everywhere.
    Offset(Offset),
    /// T += ΔT·exp(−z/z₀): air heated by the ground (a hot road).
    HotSurface(HotSurface),
    /// T += ΔT/(1 + exp(−(z − h)/w)): a temperature inversion.
    Inversion(Inversion),
    /// T += ΔT·(1 − r²/R²)³ within a ball: a warm (or cold) bubble.
    Bubble(Bubble),
    /// T += ΔT(x) from a lattice file (zero outside it).
    Grid(GridEdit),
}

impl Edit {
    /// ΔT and ∇ΔT at `p`, whose height is `h` with gradient `gh`.
    pub fn delta(&self, p: DVec3, h: f64, gh: DVec3) -> (f64, DVec3) {
        match self {
            Edit::Offset(e) => (e.dt_k, DVec3::ZERO),
            Edit::HotSurface(e) => e.delta(h, gh),
            Edit::Inversion(e) => e.delta(h, gh),
            Edit::Bubble(e) => e.delta(p),
            Edit::Grid(e) => e.delta(p),
        }
    }

    /// Whether ΔT depends on height alone (so an atmosphere keeps the symmetry of its Earth).
    pub fn is_height_only(&self) -> bool {
        match self {
            Edit::Offset(_) | Edit::HotSurface(_) | Edit::Inversion(_) => true,
            Edit::Bubble(_) | Edit::Grid(_) => false,
        }
    }

    /// The height where ∇ΔT jumps, if the edit has one: a hot surface is held at ΔT below the
    /// ground, so its gradient −ΔT/z₀ drops to 0 at h = 0 (the others are smooth, or do not
    /// depend on height alone).
    pub fn kink_height_m(&self) -> Option<f64> {
        match self {
            Edit::HotSurface(_) => Some(0.0),
            Edit::Offset(_) | Edit::Inversion(_) | Edit::Bubble(_) | Edit::Grid(_) => None,
        }
    }

    /// The edit's thin layer, if it has one, which curved paths' steps approach as they
    /// approach a hot road's ground (`crate::ode::kink`, "Approaching a layer"): an inversion's
    /// ([`Inversion::thin_layer`]). None for the others (a hot surface's layer ends on its
    /// ground kink; an offset has none; a bubble or grid does not depend on height alone).
    pub fn thin_layer(&self) -> Option<ThinLayer> {
        match self {
            Edit::Inversion(e) => Some(e.thin_layer()),
            Edit::Offset(_) | Edit::HotSurface(_) | Edit::Bubble(_) | Edit::Grid(_) => None,
        }
    }

    /// The smallest and largest ΔT the edit can add, K.
    pub fn range_k(&self) -> (f64, f64) {
        match self {
            Edit::Offset(e) => (e.dt_k, e.dt_k),
            Edit::HotSurface(e) => span(e.dt_k),
            Edit::Inversion(e) => span(e.dt_k),
            Edit::Bubble(e) => span(e.dt_k),
            Edit::Grid(e) => e.range_k(),
        }
    }
}

/// A thin layer of air: the height where its temperature gradient peaks and the depth over
/// which the gradient's envelope falls e-fold on either side.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ThinLayer {
    /// Height of the peak, m.
    pub height_m: f64,
    /// e-folding depth of the envelope, m.
    pub scale_m: f64,
}

/// [min(0, x), max(0, x)].
fn span(x: f64) -> (f64, f64) {
    (x.min(0.0), x.max(0.0))
}
