//! A participating medium: absorption σ_a(λ) and scattering σ_s(λ) per metre at density 1 (given
//! directly, or as extinction σ_t(λ) and single-scattering albedo ω(λ)), a phase function, and a
//! density field d(x) that scales both; optionally inelastic components ([`Inelastic`]), whose
//! coefficients σ_i(λ) (fluorescent absorption, Raman scattering) add to the extinction:
//! σ_t = σ_a + σ_s + Σ_i σ_i (the albedo σ_s/σ_t is that of elastic scattering only); and,
//! optionally, a refractive-index field n(λ, x) ([`super::index`]) along which light curves.

use super::density::Density;
use super::inelastic::Inelastic;
use super::phase::PhaseFunction;
use crate::spectrum::Spectrum;

/// The share of an atmosphere's least scale height a march step may climb
/// ([`Medium::climb_step`]): the in-scattered light then changes by about e^(1/4) − 1 ≈ 28 %
/// across a step, and a jittered sample per step estimates it with a few % of noise where
/// steps of tens of km (1 % of an Earth-sized scene) left 30 %.
pub const CLIMB_PER_STEP: f64 = 0.25;

/// The medium's coefficients at density 1, as the scene gave them.
#[derive(Clone, Debug)]
pub enum Coefficients {
    /// σ_a(λ) and σ_s(λ), m⁻¹.
    AbsorptionScattering {
        /// Absorption coefficient σ_a(λ), m⁻¹.
        sigma_a: Spectrum,
        /// Scattering coefficient σ_s(λ), m⁻¹.
        sigma_s: Spectrum,
    },
    /// σ_t(λ) (m⁻¹) and ω(λ) = σ_s/σ_t.
    ExtinctionAlbedo {
        /// Extinction coefficient σ_t(λ), m⁻¹.
        sigma_t: Spectrum,
        /// Single-scattering albedo ω(λ) = σ_s/σ_t, in [0, 1].
        albedo: Spectrum,
    },
    /// σ_a(λ), with σ_s(λ) the sum over the components of a mixture phase function.
    AbsorptionMixture {
        /// Absorption coefficient σ_a(λ), m⁻¹.
        sigma_a: Spectrum,
    },
    /// Rayleigh scattering by dry air at the standard density N_s
    /// ([`super::rayleigh_air::N_STANDARD_PER_M3`]): σ_s(λ) = σ(λ) N_s (σ of Bodhaine et al. 1999
    /// or the scene's table), σ_a = 0; the density field carries N/N_s.
    RayleighAir(super::rayleigh_air::CrossSection),
    /// An atmosphere of constituents (air, ozone, aerosols), each with its own profile in height:
    /// σ_t, σ_s, albedo and phase vary with position ([`Medium::at`]); the density field is
    /// uniform and unused. Position-free queries give bounds: σ_t(λ) and σ_s(λ) are the sums of
    /// each constituent's largest.
    Constituents(super::constituents::Constituents),
}

/// A participating medium (see the module docs): coefficients at density 1, phase function,
/// density field, and optionally a refractive-index field and inelastic components.
#[derive(Clone, Debug)]
pub struct Medium {
    /// Unique name from the scene (`[[medium]] name`).
    pub name: String,
    /// σ_a and σ_s at density 1, in the form the scene gave them.
    pub coefficients: Coefficients,
    /// Phase function of elastic scattering, sr⁻¹.
    pub phase: PhaseFunction,
    /// Dimensionless density d(x) multiplying the coefficients.
    pub density: Density,
    /// The medium's refractive index; `None`: n = 1 and straight paths.
    pub index: Option<super::refractive_index::IndexField>,
    /// Fluorescence and Raman components (empty for most media).
    pub inelastic: Inelastic,
}

impl Medium {
    /// Extinction σ_t = σ_a + σ_s + Σ_i σ_i at density 1, m⁻¹.
    pub fn sigma_t(&self, wavelength_nm: f64) -> f64 {
        let elastic = self.sigma_t_without_inelastic(wavelength_nm);
        if self.inelastic.is_empty() { elastic } else { elastic + self.inelastic.sigma(wavelength_nm) }
    }

    /// σ_a + σ_s as the coefficients give them, without the inelastic components, m⁻¹.
    pub fn sigma_t_without_inelastic(&self, wavelength_nm: f64) -> f64 {
        match &self.coefficients {
            Coefficients::AbsorptionScattering { sigma_a, sigma_s } => {
                sigma_a.eval(wavelength_nm) + sigma_s.eval(wavelength_nm)
            }
            Coefficients::ExtinctionAlbedo { sigma_t, .. } => sigma_t.eval(wavelength_nm),
            Coefficients::AbsorptionMixture { sigma_a } => sigma_a.eval(wavelength_nm) + self.sigma_s(wavelength_nm),
            Coefficients::RayleighAir(_) => self.sigma_s(wavelength_nm),
            Coefficients::Constituents(c) => c.sigma_t_bound(wavelength_nm),
        }
    }

    /// Scattering σ_s at density 1, m⁻¹.
    pub fn sigma_s(&self, wavelength_nm: f64) -> f64 {
        match &self.coefficients {
            Coefficients::AbsorptionScattering { sigma_s, .. } => sigma_s.eval(wavelength_nm),
            Coefficients::ExtinctionAlbedo { sigma_t, albedo } => {
                sigma_t.eval(wavelength_nm) * albedo.eval(wavelength_nm)
            }
            Coefficients::AbsorptionMixture { .. } => match &self.phase {
                PhaseFunction::Mixture(m) => m.total_sigma_s(wavelength_nm),
                _ => 0.0,
            },
            Coefficients::RayleighAir(sigma) => sigma.at_standard_density(wavelength_nm),
            Coefficients::Constituents(c) => {
                let bound =
                    c.list().iter().map(|k| k.albedo.at(wavelength_nm) * k.profile.bound_from(f64::NEG_INFINITY));
                let mut w = [0.0; super::constituents::MAX_CONSTITUENTS];
                w.iter_mut().zip(bound).for_each(|(w, b)| *w = b);
                super::constituents::Constituents::dot(&c.extinction(wavelength_nm), &w)
            }
        }
    }

    /// Single-scattering albedo σ_s/σ_t (0 where σ_t = 0); independent of density.
    pub fn albedo(&self, wavelength_nm: f64) -> f64 {
        match &self.coefficients {
            Coefficients::ExtinctionAlbedo { albedo, .. } if self.inelastic.is_empty() => albedo.eval(wavelength_nm),
            // Air that only scatters: σ_t is σ_s, the same positive number (the Rayleigh cross
            // section at any wavelength), so σ_s/σ_t is exactly 1 —
            // without the cross section twice per photon of every volume estimate.
            Coefficients::RayleighAir(_) if self.inelastic.is_empty() => 1.0,
            Coefficients::ExtinctionAlbedo { .. }
            | Coefficients::AbsorptionScattering { .. }
            | Coefficients::AbsorptionMixture { .. }
            | Coefficients::RayleighAir(_)
            | Coefficients::Constituents(_) => {
                let t = self.sigma_t(wavelength_nm);
                if t > 0.0 { self.sigma_s(wavelength_nm) / t } else { 0.0 }
            }
        }
    }

    /// Builds the tables of columns to the top of an atmosphere over a spherical Earth
    /// ([`super::density::ColumnTable`]) that are not built yet, so that a render pays for them
    /// once, up front, rather than in its first shadow ray; whether it built any. Other media
    /// have none and cost nothing.
    pub fn build_column_tables(&self) -> bool {
        let mut built = false;
        if let Density::AirProfile(a) = &self.density {
            built |= a.build_column_table();
        }
        if let Coefficients::Constituents(c) = &self.coefficients {
            for k in c.list() {
                built |= k.profile.build_column_table();
            }
        }
        built
    }

    /// The part [a, b] of [0, t_max] of the ray `o + t·dir` outside which the medium is empty
    /// (σ_t = 0: an atmosphere above its top), or `None` where it is empty all along; [0, t_max]
    /// for media that fill their region. A march need only cover it.
    pub fn support(&self, o: glam::DVec3, dir: glam::DVec3, t_max: f64) -> Option<(f64, f64)> {
        match &self.coefficients {
            Coefficients::Constituents(c) => c.support(o, dir, t_max),
            _ => self.density.support(o, dir, t_max),
        }
    }

    /// The longest march step from `x` along the unit vector `dir` that climbs at most
    /// [`CLIMB_PER_STEP`] of the least scale height of an atmosphere's profiles
    /// ([`super::density::AirProfile::least_scale_height_m`]), m: 1.5 km straight up through
    /// USA76's air, 300 m through a 1.2 km haze, unbounded along the level. Infinite for media
    /// that are not an atmosphere's.
    pub fn climb_step(&self, x: glam::DVec3, dir: glam::DVec3) -> f64 {
        let scale = match (&self.coefficients, &self.density) {
            (Coefficients::Constituents(c), _) => {
                c.list().iter().map(|k| k.profile.least_scale_height_m()).fold(f64::INFINITY, f64::min)
            }
            (_, Density::AirProfile(a)) => a.least_scale_height_m(),
            _ => return f64::INFINITY,
        };
        let Some(earth) = self.earth() else { return f64::INFINITY };
        let (_, up) = earth.height_grad(x);
        CLIMB_PER_STEP * scale / dir.dot(up).abs()
    }

    /// The top of an atmosphere's air, m above its Earth (`None` for other media).
    pub fn top_m(&self) -> Option<f64> {
        match (&self.coefficients, &self.density) {
            (Coefficients::Constituents(c), _) => Some(c.list()[0].profile.top_m()),
            (_, Density::AirProfile(a)) => Some(a.top_m()),
            _ => None,
        }
    }

    /// The Earth an atmosphere's profiles are heights above (`None` for other media).
    pub fn earth(&self) -> Option<&crate::atmosphere::Earth> {
        match (&self.coefficients, &self.density) {
            (Coefficients::Constituents(c), _) => Some(c.list()[0].profile.earth()),
            (_, Density::AirProfile(a)) => Some(a.earth()),
            _ => None,
        }
    }

    /// True when the density is uniform (d ≡ 1) and the coefficients do not vary in space.
    pub fn is_homogeneous(&self) -> bool {
        self.density.is_uniform() && !matches!(self.coefficients, Coefficients::Constituents(_))
    }

    /// True when the medium neither absorbs nor scatters at any wavelength (σ_t ≡ 0 as given,
    /// and no inelastic component): clear air that only bends light.
    pub fn is_clear(&self) -> bool {
        if !self.inelastic.is_empty() {
            return false;
        }
        match &self.coefficients {
            Coefficients::AbsorptionScattering { sigma_a, sigma_s } => zero(sigma_a) && zero(sigma_s),
            Coefficients::ExtinctionAlbedo { sigma_t, .. } => zero(sigma_t),
            Coefficients::AbsorptionMixture { .. } | Coefficients::RayleighAir(_) => false,
            Coefficients::Constituents(_) => false,
        }
    }

    /// True when the medium scatters light somewhere (elastically or by an inelastic
    /// component): only then is there in-scattered light to estimate, and photons to store.
    pub fn scatters(&self) -> bool {
        if !self.inelastic.is_empty() {
            return true;
        }
        match &self.coefficients {
            Coefficients::AbsorptionScattering { sigma_s, .. } => !zero(sigma_s),
            Coefficients::ExtinctionAlbedo { sigma_t, albedo } => !zero(sigma_t) && !zero(albedo),
            Coefficients::AbsorptionMixture { .. } | Coefficients::RayleighAir(_) => true,
            Coefficients::Constituents(c) => c.scatterers() > 0,
        }
    }

    /// Whether photons interacting here are stored in the volume map: where the medium scatters
    /// (there is in-scattered light to estimate), and in any participating medium when the
    /// scene's sensors count photons at every interaction (`photon_sensors`).
    pub fn keeps_photons(&self, photon_sensors: bool) -> bool {
        self.scatters() || (photon_sensors && !self.is_clear())
    }

    /// True for air stratified in height (an atmosphere's constituents, or a density read from
    /// an atmosphere profile): the point estimate then weights its sphere by the air's density
    /// ([`crate::photon_map::stratified`]), which the beam estimate's discs do not.
    pub fn stratified_air(&self) -> bool {
        matches!(self.coefficients, Coefficients::Constituents(_)) || matches!(self.density, Density::AirProfile(_))
    }

    /// True when light curves in this medium (its index field has a gradient somewhere).
    pub fn bends_light(&self) -> bool {
        self.index.as_ref().is_some_and(|f| !f.is_uniform())
    }
}

/// A spectrum given as the constant 0 (the only way a coefficient is known to vanish everywhere).
fn zero(s: &crate::spectrum::Spectrum) -> bool {
    matches!(s, crate::spectrum::Spectrum::Constant(v) if *v == 0.0)
}
