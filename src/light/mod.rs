//! Light sources: one file each, dispatched by a closed enum.
//!
//! Every light holds an absolute spectrum — spectral radiance (area), spectral intensity (point,
//! spot) or spectral irradiance normal to the beam (directional), all per nm; a luminaire holds
//! the spectral intensity of one candela and scales it by its photometric web — and a sampler
//! that draws photon wavelengths in proportion to its emitted spectral power.
//!
//! Two queries serve the two passes: [`Light::emit`] starts a photon (power is assigned by the
//! caller: total power / photons emitted), [`Light::incident`] samples the light as seen from a
//! point for shadow rays. The spectral contribution of an incident sample at λ is
//! `spectrum(λ) · weight`, where `weight` already divides by the sampling density.

mod area;
mod directional;
mod limb_darkening;
mod luminaire;
mod point;
mod sky;
mod spot;

pub use area::{AreaLight, Side};
pub use directional::{BeamCells, DirectionalLight};
pub use limb_darkening::{DISK_TABLE_CELLS, DiskTable, LimbDarkening, NECKEL_LABS_1994};
pub use luminaire::LuminaireLight;
pub use point::PointLight;
pub use sky::SkyLight;
pub use spot::SpotLight;

use crate::rng::Rng;
use crate::spectrum::{Spectrum, SpectrumSampler};
use glam::DVec3;

/// A light's spectrum and the sampler of its photon wavelengths.
#[derive(Clone, Debug)]
pub struct LightSpectrum {
    /// Absolute spectral quantity per nm (see the module docs for the unit per light type).
    pub spectrum: Spectrum,
    /// Draws wavelengths ∝ `spectrum` over the scene's range.
    pub sampler: SpectrumSampler,
}

impl LightSpectrum {
    /// `None` when the spectrum has no positive power within [min_nm, max_nm].
    pub fn new(spectrum: Spectrum, min_nm: f64, max_nm: f64) -> Option<LightSpectrum> {
        let sampler = SpectrumSampler::new(&spectrum, min_nm, max_nm)?;
        Some(LightSpectrum { spectrum, sampler })
    }

    /// ∫ spectrum dλ over the scene's range.
    pub fn integral(&self) -> f64 {
        self.sampler.integral()
    }
}

/// A light source, one variant per kind (see the module docs).
#[derive(Clone, Debug)]
pub enum Light {
    /// A diffuse emitting quad, disk or sphere.
    Area(AreaLight),
    /// An isotropic point.
    Point(PointLight),
    /// A point with a cone and smooth falloff.
    Spot(SpotLight),
    /// Parallel light (directional or sun), possibly of finite angular size.
    Directional(DirectionalLight),
    /// Measured photometry (IES LM-63, EULUMDAT); spectrum per candela.
    Luminaire(LuminaireLight),
    /// Uniform radiance from every direction above its horizon, at infinity.
    Sky(SkyLight),
}

/// Where a photon starts: origin, unit direction, wavelength.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Emission {
    /// Start point, m.
    pub origin: DVec3,
    /// Unit direction of travel.
    pub dir: DVec3,
    /// Wavelength, nm.
    pub wavelength_nm: f64,
    /// Unit normal of the emitting surface at `origin` (zero for point-like lights).
    pub normal: DVec3,
}

/// A light sampled from a receiving point: unit direction toward the light, distance
/// (infinite for directional lights), and the factor that turns the light's spectrum into
/// incident radiance divided by the sampling density.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Incident {
    /// Unit direction from the receiving point toward the light.
    pub wi: DVec3,
    /// Distance to the sampled point of the light, m (infinite for lights at infinity).
    pub dist: f64,
    /// Incident radiance per unit of the light's spectrum, divided by the sampling density.
    pub weight: f64,
}

impl Light {
    /// The light's absolute spectrum (radiance, intensity or irradiance by kind; see the module
    /// docs).
    pub fn spectrum(&self) -> &LightSpectrum {
        match self {
            Light::Area(l) => &l.emission,
            Light::Point(l) => &l.emission,
            Light::Spot(l) => &l.emission,
            Light::Directional(l) => &l.emission,
            Light::Luminaire(l) => &l.emission,
            Light::Sky(l) => &l.emission,
        }
    }

    /// Radiant flux emitted within the scene's wavelength range, W.
    pub fn power_w(&self) -> f64 {
        match self {
            Light::Area(l) => l.power_w(),
            Light::Point(l) => l.power_w(),
            Light::Spot(l) => l.power_w(),
            Light::Directional(l) => l.power_w(),
            Light::Luminaire(l) => l.power_w(),
            Light::Sky(l) => l.power_w(),
        }
    }

    /// Starts a photon: position and direction distributed as the emitted power, wavelength
    /// drawn from the emitted spectrum.
    pub fn emit(&self, rng: &mut Rng) -> Emission {
        let (wavelength_nm, _) = self.spectrum().sampler.sample(rng.uniform());
        let (origin, dir, normal) = match self {
            Light::Area(l) => l.emit(rng),
            Light::Point(l) => (l.position, l.emit_dir(rng.uniform2()), DVec3::ZERO),
            Light::Spot(l) => (l.position, l.emit_dir(rng.uniform(), rng.uniform2()), DVec3::ZERO),
            Light::Directional(l) => {
                let (o, d) = l.emit(rng.uniform2(), rng.uniform2(), wavelength_nm);
                (o, d, l.dir)
            }
            Light::Luminaire(l) => l.emit(rng),
            Light::Sky(l) => {
                let (o, d) = l.emit(rng.uniform2(), rng.uniform2());
                (o, d, DVec3::ZERO)
            }
        };
        Emission { origin, dir, wavelength_nm, normal }
    }

    /// True for lights no path is counted as hitting (point, spot, directional — the sun's
    /// small disc too): they are reached only by sampling them. Area lights and the sky are
    /// both hit and sampled, and the two strategies are combined by MIS.
    pub fn is_delta(&self) -> bool {
        !matches!(self, Light::Area(_) | Light::Sky(_))
    }

    /// A point a photon from this light starts from (for finding the medium it starts in): the
    /// centre of an area light just off its emitting side, the position of a point-like light,
    /// and a point beyond the scene for a directional light.
    pub fn representative_point(&self) -> DVec3 {
        match self {
            Light::Area(a) => {
                let s = a.shape.sample([0.5, 0.5]);
                let n = if a.side == Side::Back { -s.normal } else { s.normal };
                s.point + n * (1e-6 * (1.0 + s.point.abs().max_element()))
            }
            Light::Point(p) => p.position,
            Light::Spot(s) => s.position,
            Light::Directional(d) => d.scene_centre - d.dir * (2.0 * d.scene_radius),
            Light::Luminaire(l) => l.placement.position,
            Light::Sky(l) => l.target_centre + l.up * l.start_distance,
        }
    }

    /// Spectral radiance at `wavelength_nm` seen by a ray that leaves the scene travelling along
    /// `view_dir` (a light at infinity: the sun's disc); zero for lights a ray cannot escape to.
    pub fn escape_radiance(&self, view_dir: DVec3, wavelength_nm: f64) -> f64 {
        match self {
            Light::Directional(l) => {
                let k = l.radiance_factor(view_dir, wavelength_nm);
                if k > 0.0 { k * l.emission.spectrum.eval(wavelength_nm) } else { 0.0 }
            }
            Light::Sky(l) if l.sees(view_dir) => l.emission.spectrum.eval(wavelength_nm),
            _ => 0.0,
        }
    }

    /// The factor an incident sample's `spectrum(λ) · weight` takes at `wavelength_nm` beyond
    /// its weight: the limb-darkened sun's P/F toward `inc.wi`, exactly 1 for every other light.
    pub fn disc_factor(&self, inc: &Incident, wavelength_nm: f64) -> f64 {
        match self {
            Light::Directional(l) => l.disc_factor(inc.wi, wavelength_nm),
            _ => 1.0,
        }
    }

    /// Samples the light as seen from `p`; `None` when it sends nothing toward `p`.
    pub fn incident(&self, p: DVec3, u: [f64; 2]) -> Option<Incident> {
        match self {
            Light::Area(l) => l.incident(p, u),
            Light::Point(l) => l.incident(p),
            Light::Spot(l) => l.incident(p),
            Light::Directional(l) => l.incident(p, u),
            Light::Luminaire(l) => l.incident(p, u),
            Light::Sky(l) => l.incident(p, u),
        }
    }
}
