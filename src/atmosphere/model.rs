//! An atmosphere: a base profile of T(z) and P(z), temperature edits, an Earth to measure height
//! on, a dispersion law and a top. Its refractive index is
//!
//! n(λ, x) = 1 + N(λ, P, T)·s(h),  P = P_base(h),  T = T_base(h) + Σᵢ ΔTᵢ(x),
//!
//! where N = K(λ)·ρ(P, T) is the dispersion law's refractivity at (P, T), Gladstone–Dale with the
//! density its K refers to (Ciddor's real-gas density PM_a/(ZRT), or for Cauchy the ideal gas
//! PM₀/(R*T); see [`AirDispersion::refractivity_grad`]),
//! with h the height of x above the ground and s a C¹ taper that takes n to exactly 1 at the top
//! (s = 1 below top − w, s = 3u² − 2u³ with u = (top − h)/w above, s = 0 at and above the top;
//! w = min(1 km, top/10)). The taper changes n − 1 only where it is below 10⁻⁵ of its sea-level
//! value for the 86 km standard top (3 × 10⁻³ for the 40 km top of Gutierrez et al. 2005), and
//! keeps n and ∇n continuous where paths leave the atmosphere. The gradient is, by the chain rule,
//!
//! ∇T = T′_base ∇h + Σᵢ ∇ΔTᵢ,  ∇P = P′_base ∇h,  ∇n = s (∂N/∂P ∇P + ∂N/∂T ∇T) + N s′ ∇h.
//!
//! [`AirPoint::density_kg_m3`] is the ideal-gas density PM₀/(R*T) of the air (USA76's).
//!
//! Approximation: pressure is the base atmosphere's hydrostatic pressure at the height; the edits
//! change temperature (hence density) but not pressure. For the mirage layers (metres to tens of
//! metres thick) the hydrostatic pressure change a temperature edit would cause is ~10⁻⁴ of P.
//!
//! # References
//! - D. Gutierrez et al. 2005, §5 (USA76 → T(h), P(h) → ideal gas → Gladstone–Dale; edited profiles
//!   for the mirages).

use super::base::BaseProfile;
use super::edit::{Edit, ThinLayer};
use super::{AirDispersion, Earth, gas};
use crate::field::GradientRegion;
use glam::DVec3;

/// An atmosphere (see the module docs for its refractive index).
#[derive(Clone, Debug, PartialEq)]
pub struct Atmosphere {
    /// Label in reports.
    pub name: String,
    /// How height above the ground is measured.
    pub earth: Earth,
    /// Temperature and pressure before the edits.
    pub base: BaseProfile,
    /// Temperature edits; their ΔT add.
    pub edits: Vec<Edit>,
    /// Gladstone–Dale law K(λ) of the air.
    pub dispersion: AirDispersion,
    top_m: f64,
    taper_m: f64,
}

/// The local state of the (edited) air, with gradients.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AirPoint {
    /// Height above the ground, m.
    pub height_m: f64,
    /// Edited temperature T, K.
    pub temperature_k: f64,
    /// ∇T, K m⁻¹.
    pub grad_temperature: DVec3,
    /// Pressure P (the base atmosphere's), Pa.
    pub pressure_pa: f64,
    /// ∇P, Pa m⁻¹.
    pub grad_pressure: DVec3,
    /// Density ρ = P M₀/(R* T), kg m⁻³.
    pub density_kg_m3: f64,
    /// ∇ρ, kg m⁻⁴.
    pub grad_density: DVec3,
}

impl Atmosphere {
    /// Checks the top (positive, at most the base profile's highest altitude) and that the edited
    /// temperature stays positive (lower bound: the base's minimum below the top plus each edit's
    /// most negative ΔT).
    pub fn new(
        name: impl Into<String>,
        earth: Earth,
        base: BaseProfile,
        edits: Vec<Edit>,
        dispersion: AirDispersion,
        top_m: f64,
    ) -> Result<Atmosphere, String> {
        let max = base.max_altitude_m();
        if !(top_m.is_finite() && top_m > 0.0 && top_m <= max) {
            return Err(format!(
                "top_m = {top_m} is out of range: it must be positive and at most {max} m (the base profile's top)"
            ));
        }
        let a = Atmosphere {
            name: name.into(),
            earth,
            base,
            edits,
            dispersion,
            top_m,
            taper_m: (0.1 * top_m).min(1_000.0),
        };
        let t_min = a.min_temperature_bound();
        if t_min.is_nan() || t_min <= 0.0 {
            return Err(format!(
                "the edits can cool the air to {t_min} K (base minimum {} K plus the most negative ΔT of each edit); temperatures must stay positive",
                a.base.min_temperature_below(top_m)
            ));
        }
        Ok(a)
    }

    /// The U.S. Standard Atmosphere 1976 to 86 km on the standard spherical Earth, Ciddor's
    /// dispersion with 450 µmol/mol CO₂.
    pub fn usa76() -> Atmosphere {
        let d = AirDispersion::ciddor(450.0).unwrap_or(AirDispersion::CauchyBornWolf);
        let top = super::usa76::TOP_GEOMETRIC_M;
        Atmosphere {
            name: "usa76".into(),
            earth: Earth::standard(),
            base: BaseProfile::Usa76,
            edits: Vec::new(),
            dispersion: d,
            top_m: top,
            taper_m: 1_000.0,
        }
    }

    /// The same atmosphere over another Earth (e.g. flat ground for a small scene).
    pub fn with_earth(mut self, earth: Earth) -> Atmosphere {
        self.earth = earth;
        self
    }

    /// The same atmosphere ending at `top_m` (e.g. the 40 km of Gutierrez et al. 2005).
    pub fn with_top(self, top_m: f64) -> Result<Atmosphere, String> {
        Atmosphere::new(self.name, self.earth, self.base, self.edits, self.dispersion, top_m)
    }

    /// Altitude where the atmosphere ends (n = 1 at and above it), m.
    pub fn top_m(&self) -> f64 {
        self.top_m
    }

    /// A lower bound of the edited temperature below the top, K.
    pub fn min_temperature_bound(&self) -> f64 {
        let base = self.base.min_temperature_below(self.top_m);
        base + self.edits.iter().map(|e| e.range_k().0.min(0.0)).sum::<f64>()
    }

    /// Temperature, pressure and density at `p`, with their gradients.
    pub fn air(&self, p: DVec3) -> AirPoint {
        let (h, gh) = self.earth.height_grad(p);
        self.air_at(p, h, gh)
    }

    /// [`Atmosphere::air`] at `p` of height `h` with ∇h = `gh`.
    fn air_at(&self, p: DVec3, h: f64, gh: DVec3) -> AirPoint {
        let s = self.base.state(h);
        let (mut t, mut gt) = (s.temperature_k, s.dt_dz * gh);
        for e in &self.edits {
            let (dt, g) = e.delta(p, h, gh);
            t += dt;
            gt += g;
        }
        let gp = s.dp_dz * gh;
        let rho = gas::density_kg_m3(s.pressure_pa, t);
        let grho = rho * (gp / s.pressure_pa - gt / t);
        AirPoint {
            height_m: h,
            temperature_k: t,
            grad_temperature: gt,
            pressure_pa: s.pressure_pa,
            grad_pressure: gp,
            density_kg_m3: rho,
            grad_density: grho,
        }
    }

    /// n(λ, x) and ∇n (see the module notes). Exactly (1, 0) at and above the top.
    pub fn n_grad(&self, wavelength_nm: f64, p: DVec3) -> (f64, DVec3) {
        let (h, gh) = self.earth.height_grad(p);
        if h >= self.top_m {
            return (1.0, DVec3::ZERO);
        }
        let a = self.air_at(p, h, gh);
        let (s, ds) = self.taper(h);
        let (nr, nr_p, nr_t) = self.dispersion.refractivity_grad(wavelength_nm, a.pressure_pa, a.temperature_k);
        let n = 1.0 + nr * s;
        (n, s * (nr_p * a.grad_pressure + nr_t * a.grad_temperature) + (nr * ds) * gh)
    }

    /// For an atmosphere whose edits depend on height alone: q(h) and dq/dh with
    /// n − 1 = K(λ)·q(h), K the dispersion law's Gladstone–Dale factor
    /// ([`AirDispersion::gladstone_dale_m3_per_kg`]) and q the density it refers to times the
    /// taper ([`AirDispersion::density_grad`]); (0, 0) at and above the top. What
    /// [`super::RadialTable`] tabulates.
    pub fn reduced_refractivity(&self, h: f64) -> (f64, f64) {
        if h >= self.top_m {
            return (0.0, 0.0);
        }
        let a = self.air_at(DVec3::ZERO, h, DVec3::Y);
        let (s, ds) = self.taper(h);
        let (d, d_p, d_t) = self.dispersion.density_grad(a.pressure_pa, a.temperature_k);
        (d * s, s * (d_p * a.grad_pressure.y + d_t * a.grad_temperature.y) + d * ds)
    }

    /// The taper s(h) and ds/dh.
    fn taper(&self, h: f64) -> (f64, f64) {
        let u = (self.top_m - h) / self.taper_m;
        if u >= 1.0 {
            return (1.0, 0.0);
        }
        let u = u.max(0.0);
        (u * u * (3.0 - 2.0 * u), -6.0 * u * (1.0 - u) / self.taper_m)
    }

    /// The centre about which n is spherically symmetric (n depends only on the distance from
    /// it): the Earth's centre when the Earth is spherical and every edit depends on height
    /// alone; `None` otherwise.
    pub fn radial_centre(&self) -> Option<DVec3> {
        match &self.earth {
            Earth::Spherical(s) if self.edits.iter().all(|e| e.is_height_only()) => Some(s.centre),
            _ => None,
        }
    }

    /// Heights below the top where ∇n is not smooth, ascending, m: the base profile's kinks, the
    /// edits' (a hot surface's ground) and the start of the taper (where d²n/dh² jumps).
    pub fn kink_heights_m(&self) -> Vec<f64> {
        let mut k = self.base.kink_heights_m();
        k.extend(self.edits.iter().filter_map(Edit::kink_height_m));
        k.push(self.top_m - self.taper_m);
        k.retain(|h| *h < self.top_m);
        k.sort_by(f64::total_cmp);
        k
    }

    /// The thin layers of the edits below the top (an inversion's), ascending, which curved
    /// paths' steps approach ([`Edit::thin_layer`]).
    pub fn thin_layers(&self) -> Vec<ThinLayer> {
        let mut layers: Vec<ThinLayer> =
            self.edits.iter().filter_map(Edit::thin_layer).filter(|l| l.height_m < self.top_m).collect();
        layers.sort_by(|a, b| a.height_m.total_cmp(&b.height_m));
        layers
    }

    /// Heights below the top between which n is analytic, ascending, m: [`Self::kink_heights_m`]
    /// and a table profile's every row (for quadratures over height).
    pub fn smooth_piece_ends_m(&self) -> Vec<f64> {
        let mut k = self.kink_heights_m();
        k.extend(self.base.smooth_piece_ends_m());
        k.retain(|h| *h < self.top_m);
        k.sort_by(f64::total_cmp);
        k.dedup();
        k
    }

    /// Everything below the top: the ball of radius R + top (spherical Earth) or the half-space
    /// h ≤ top (flat Earth).
    pub fn gradient_region(&self) -> GradientRegion {
        match &self.earth {
            Earth::Flat { up } => GradientRegion::Slab { up: *up, h_min: f64::NEG_INFINITY, h_max: self.top_m },
            Earth::Spherical(s) => {
                GradientRegion::Shell { centre: s.centre, r_min: 0.0, r_max: s.radius_m + self.top_m }
            }
        }
    }
}
