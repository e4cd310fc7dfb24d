//! Refractive-index fields n(λ, x) and their gradients ∇n(λ, x), which bend light along Fermat's
//! ray equation d/ds(n dr/ds) = ∇n (Gutierrez et al. 2005, Eq. 7).
//!
//! [`IndexField`] is a closed set of fields, one file each; every field gives its gradient in
//! closed form (tests compare each with central differences). [`GradientRegion`] tells the
//! propagator where ∇n can be non-zero, so paths outside it stay straight.
//!
//! # References
//! - D. Gutierrez, F. J. Serón, A. Muñoz & O. Anson 2005, "Non-linear volume photon mapping",
//!   Eurographics Symposium on Rendering, §2.3 and §5.

mod constant;
mod exponential;
mod linear;
mod profile;
mod sum;
mod temperature_grid;

pub use constant::Constant;
pub use exponential::Exponential;
pub use linear::Linear;
pub use profile::Profile;
pub use sum::Sum;
pub use temperature_grid::{GridPressure, TemperatureGrid};

use crate::atmosphere::Earth;
use crate::field::GradientRegion;
use crate::geometry::Aabb;
use glam::DVec3;

/// A refractive-index field.
#[derive(Clone, Debug)]
pub enum IndexField {
    /// The same n(λ) everywhere (∇n ≡ 0).
    Constant(Constant),
    /// n = n₀ + k·(x·d̂).
    Linear(Linear),
    /// n = 1 + (n₀ − 1)·exp(−h/H).
    Exponential(Exponential),
    /// A tabulated n(h).
    Profile(Profile),
    /// Air with a 3-D temperature lattice.
    TemperatureGrid(Box<TemperatureGrid>),
    /// A standard or edited atmosphere.
    Atmosphere(Box<crate::atmosphere::Atmosphere>),
    /// A base field plus local bumps.
    Sum(Sum),
}

impl IndexField {
    /// n(λ, x).
    pub fn n(&self, wavelength_nm: f64, p: DVec3) -> f64 {
        match self {
            IndexField::Constant(c) => c.n(wavelength_nm),
            _ => self.n_grad(wavelength_nm, p).0,
        }
    }

    /// (n, ∇n) at (λ, x), the gradient in closed form.
    pub fn n_grad(&self, wavelength_nm: f64, p: DVec3) -> (f64, DVec3) {
        match self {
            IndexField::Constant(c) => (c.n(wavelength_nm), DVec3::ZERO),
            IndexField::Linear(l) => l.n_grad(p),
            IndexField::Exponential(e) => e.n_grad(p),
            IndexField::Profile(f) => f.n_grad(p),
            IndexField::TemperatureGrid(g) => g.n_grad(wavelength_nm, p),
            IndexField::Atmosphere(a) => a.n_grad(wavelength_nm, p),
            IndexField::Sum(s) => s.n_grad(wavelength_nm, p),
        }
    }

    /// True when ∇n ≡ 0 everywhere (no ODE needs to run).
    pub fn is_uniform(&self) -> bool {
        matches!(self.gradient_region(), GradientRegion::Nowhere)
    }

    /// True when n depends on wavelength.
    pub fn is_dispersive(&self) -> bool {
        match self {
            IndexField::Constant(c) => c.is_dispersive(),
            IndexField::Linear(_) | IndexField::Exponential(_) | IndexField::Profile(_) => false,
            IndexField::TemperatureGrid(_) | IndexField::Atmosphere(_) => true,
            IndexField::Sum(s) => s.base.is_dispersive(),
        }
    }

    /// Where ∇n can be non-zero; outside it n is constant and paths are straight, and n is
    /// continuous across its boundary. Built on each call (a `Sum` allocates its union): ask once
    /// per scene, not per step.
    pub fn gradient_region(&self) -> GradientRegion {
        match self {
            IndexField::Constant(_) => GradientRegion::Nowhere,
            IndexField::Linear(l) if l.k_per_m == 0.0 => GradientRegion::Nowhere,
            IndexField::Exponential(e) if e.n0 == 1.0 => GradientRegion::Nowhere,
            IndexField::Linear(_) => GradientRegion::Everywhere,
            IndexField::Exponential(e) => height_band(&e.earth, (0.0, f64::INFINITY)),
            IndexField::Profile(f) => height_band(&f.earth, f.height_range()),
            IndexField::TemperatureGrid(g) => g.gradient_region(),
            IndexField::Atmosphere(a) => a.gradient_region(),
            IndexField::Sum(s) => s.bumps.iter().fold(s.base.gradient_region(), |r, b| {
                r.union(GradientRegion::Shell { centre: b.centre, r_min: 0.0, r_max: b.radius_m })
            }),
        }
    }

    /// The centre about which n is spherically symmetric, if it is (n depends only on the
    /// distance from it: a height profile over a spherical Earth). Light in such a field moves in
    /// a plane through the centre, round it always the same way (the angular momentum
    /// n·r × dr/ds is conserved: Born & Wolf, *Principles of Optics*, §3.2.1, Bouguer's formula).
    pub fn radial_centre(&self) -> Option<DVec3> {
        let centre = |e: &Earth| match e {
            Earth::Spherical(s) => Some(s.centre),
            Earth::Flat { .. } => None,
        };
        match self {
            IndexField::Exponential(e) => centre(&e.earth),
            IndexField::Profile(f) => centre(&f.earth),
            IndexField::Atmosphere(a) => a.radial_centre(),
            IndexField::Constant(_) | IndexField::Linear(_) | IndexField::TemperatureGrid(_) | IndexField::Sum(_) => {
                None
            }
        }
    }

    /// For a field with a [`IndexField::radial_centre`]: the distances from the centre where ∇n
    /// is not smooth (a standard atmosphere's layer boundaries), ascending, m — where an
    /// integrator step should end rather than straddle. Empty for other fields.
    pub fn kink_radii_m(&self) -> Vec<f64> {
        match self {
            IndexField::Atmosphere(a) => match (&a.earth, a.radial_centre()) {
                (Earth::Spherical(s), Some(_)) => a.kink_heights_m().iter().map(|h| s.radius_m + h).collect(),
                _ => Vec::new(),
            },
            _ => Vec::new(),
        }
    }

    /// For a field with a [`IndexField::radial_centre`]: its thin layers (an inversion's) as
    /// (distance from the centre of the layer's peak, e-folding depth of its envelope), m,
    /// ascending — which curved paths' steps approach rather than dive into. Empty for other
    /// fields.
    pub fn thin_layer_radii_m(&self) -> Vec<(f64, f64)> {
        match self {
            IndexField::Atmosphere(a) => match (&a.earth, a.radial_centre()) {
                (Earth::Spherical(s), Some(_)) => {
                    a.thin_layers().iter().map(|l| (s.radius_m + l.height_m, l.scale_m)).collect()
                }
                _ => Vec::new(),
            },
            _ => Vec::new(),
        }
    }

    /// A lower bound of n over `domain` and the wavelength range `[min_nm, max_nm]` (NaN when the
    /// field produces NaN there).
    pub fn min_n_bound(&self, domain: &Aabb, wavelength_range_nm: (f64, f64)) -> f64 {
        match self {
            IndexField::Constant(c) => c.min_n(wavelength_range_nm),
            IndexField::Linear(l) => l.min_over(domain),
            IndexField::Exponential(e) => e.min_n(),
            IndexField::Profile(f) => f.min_n(),
            // K(λ) > 0 and ρ > 0 in the air laws' range (checked by `validate`).
            IndexField::TemperatureGrid(_) | IndexField::Atmosphere(_) => 1.0,
            IndexField::Sum(s) => s.base.min_n_bound(domain, wavelength_range_nm) + s.min_n_added(),
        }
    }

    /// Checks n over `domain` and the wavelength range: n ≤ 0 (or NaN) is always an error; n < 1
    /// is an error unless `allow_below_one` (a scene may allow it explicitly, e.g. for plasma).
    pub fn validate(
        &self,
        domain: &Aabb,
        wavelength_range_nm: (f64, f64),
        allow_below_one: bool,
    ) -> Result<(), String> {
        self.check_range(wavelength_range_nm)?;
        let m = self.min_n_bound(domain, wavelength_range_nm);
        let (lo, hi) = wavelength_range_nm;
        if m.is_nan() || m <= 0.0 {
            return Err(format!(
                "refractive index can reach {m} in the scene's box {} – {} at {lo}–{hi} nm; it must be positive everywhere",
                domain.min, domain.max
            ));
        }
        if m < 1.0 && !allow_below_one {
            return Err(format!(
                "refractive index can drop to {m} (below 1) in the scene's box {} – {} at {lo}–{hi} nm; \
                 n < 1 is only accepted when the scene allows it explicitly",
                domain.min, domain.max
            ));
        }
        Ok(())
    }
}

impl IndexField {
    /// Fields made of air must be asked at wavelengths where the air law is defined.
    fn check_range(&self, range_nm: (f64, f64)) -> Result<(), String> {
        match self {
            IndexField::Constant(c) => c.check_range(range_nm),
            IndexField::Linear(_) | IndexField::Exponential(_) | IndexField::Profile(_) => Ok(()),
            IndexField::TemperatureGrid(g) => g.dispersion.check_range(range_nm),
            IndexField::Atmosphere(a) => a.dispersion.check_range(range_nm),
            IndexField::Sum(s) => s.base.check_range(range_nm),
        }
    }
}

/// The region h_min ≤ h ≤ h_max of an Earth's height.
fn height_band(earth: &crate::atmosphere::Earth, (h_min, h_max): (f64, f64)) -> GradientRegion {
    match earth {
        crate::atmosphere::Earth::Flat { up } => GradientRegion::Slab { up: *up, h_min, h_max },
        crate::atmosphere::Earth::Spherical(s) => {
            GradientRegion::Shell { centre: s.centre, r_min: (s.radius_m + h_min).max(0.0), r_max: s.radius_m + h_max }
        }
    }
}
