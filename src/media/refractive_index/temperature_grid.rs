//! Air whose temperature is given on a 3-D lattice: the dispersion law's refractivity at the
//! local pressure and temperature, Gladstone–Dale n = 1 + K(λ)ρ(P, T) (ρ the density K refers
//! to: the ideal gas PM₀/(R*T) for Cauchy, Ciddor's real gas; see
//! [`AirDispersion::refractivity_grad`]). At constant pressure this is Stam & Languenou's
//! n = 1 + (T₀/T)(n₀ − 1) (up to Ciddor's compressibility), which Gutierrez et al. 2005 use for
//! their heat-shimmer image (Fig. 6).
//!
//! ∇n = ∂N/∂P ∇P + ∂N/∂T ∇T (N = n − 1).
//!
//! Outside the lattice the temperature of the nearest face holds ([`Beyond::Clamp`]), so n is
//! continuous everywhere; at constant pressure with a uniform face temperature the gradient
//! region is the lattice box.
//!
//! # References
//! - J. Stam & E. Languenou 1996, "Ray tracing in non-constant media", Eurographics Rendering
//!   Workshop, 225–234.

use crate::atmosphere::{AirDispersion, Earth, usa76};
use crate::field::{Beyond, GradientRegion, Interpolation, Lattice, catmull_rom_overshoot};
use glam::DVec3;

/// The pressure the grid's air is at.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum GridPressure {
    /// The same pressure everywhere, Pa.
    Constant {
        /// Pressure P, Pa.
        pressure_pa: f64,
    },
    /// The USA76 hydrostatic pressure at the point's height (the grid's temperature does not
    /// change it: pressure from the standard, temperature from the grid).
    Usa76 {
        /// Where heights are measured from (flat or spherical Earth).
        earth: Earth,
    },
}

/// Air whose temperature (K) is given on a lattice (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct TemperatureGrid {
    lattice: Lattice,
    /// How the temperature is interpolated between lattice points.
    pub interpolation: Interpolation,
    /// Where the pressure comes from.
    pub pressure: GridPressure,
    /// Gladstone–Dale law K(λ) of the air.
    pub dispersion: AirDispersion,
    uniform_faces: bool,
}

impl TemperatureGrid {
    /// Temperatures must be positive, including the lowest value Catmull–Rom can overshoot to
    /// (see [`catmull_rom_overshoot`]); a constant pressure must be positive and finite.
    pub fn new(
        lattice: Lattice,
        interpolation: Interpolation,
        pressure: GridPressure,
        dispersion: AirDispersion,
    ) -> Result<TemperatureGrid, String> {
        let lowest = lattice.value_range().0 - catmull_rom_overshoot(&lattice, interpolation);
        if lowest <= 0.0 {
            return Err(format!(
                "temperature grid: {} interpolation can reach {lowest} K; temperatures must stay positive",
                interpolation.name()
            ));
        }
        if let GridPressure::Constant { pressure_pa } = pressure
            && !(pressure_pa.is_finite() && pressure_pa > 0.0)
        {
            return Err(format!("temperature grid: pressure {pressure_pa} Pa must be finite and positive"));
        }
        let (lo, hi) = lattice.face_range();
        let uniform_faces = hi - lo <= 1e-12 * hi.abs();
        Ok(TemperatureGrid { lattice, interpolation, pressure, dispersion, uniform_faces })
    }

    /// Reads a lattice file of quantity `temperature_k` (see [`crate::field::grid_file`]); errors name
    /// the file.
    pub fn load(
        path: &std::path::Path,
        interpolation: Interpolation,
        pressure: GridPressure,
        dispersion: AirDispersion,
    ) -> crate::error::Result<TemperatureGrid> {
        use crate::error::{Error, Location};
        let (quantity, lattice) = crate::field::grid_file::read(path)?;
        let at = || Some(Location::file(path));
        if quantity != crate::field::grid_file::Quantity::TemperatureK {
            return Err(Error::input(
                at(),
                format!("a temperature grid needs quantity temperature_k, the file holds {}", quantity.name()),
            ));
        }
        TemperatureGrid::new(lattice, interpolation, pressure, dispersion).map_err(|e| Error::input(at(), e))
    }

    /// The temperature lattice, K.
    pub fn lattice(&self) -> &Lattice {
        &self.lattice
    }

    /// Temperature (K) and its gradient at `p`.
    pub fn temperature_grad(&self, p: DVec3) -> (f64, DVec3) {
        self.lattice.value_grad(p, self.interpolation, Beyond::Clamp)
    }

    /// n and ∇n at `p` (m) for wavelength `wavelength_nm`.
    pub fn n_grad(&self, wavelength_nm: f64, p: DVec3) -> (f64, DVec3) {
        let (t, gt) = self.temperature_grad(p);
        let (pr, gp) = match self.pressure {
            GridPressure::Constant { pressure_pa } => (pressure_pa, DVec3::ZERO),
            GridPressure::Usa76 { earth } => {
                let (h, gh) = earth.height_grad(p);
                let s = usa76::at_geometric(h);
                (s.pressure_pa, s.dp_dz * gh)
            }
        };
        let (nr, nr_p, nr_t) = self.dispersion.refractivity_grad(wavelength_nm, pr, t);
        (1.0 + nr, nr_p * gp + nr_t * gt)
    }

    /// Where ∇n can be non-zero: the lattice box at constant pressure with uniform face
    /// temperatures, everywhere otherwise.
    pub fn gradient_region(&self) -> GradientRegion {
        match self.pressure {
            GridPressure::Constant { .. } if self.uniform_faces => GradientRegion::Box(self.lattice.bounds()),
            _ => GradientRegion::Everywhere,
        }
    }
}
