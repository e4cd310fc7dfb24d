//! Wavelengths, spectra and colour.
//!
//! Wavelengths are in nanometres. A [`Spectrum`] is a function of wavelength whose unit depends on
//! its use (reflectance: none; light: spectral radiance, intensity or irradiance per nm).
//! [`Bands`] is the scene's wavelength sampling of the output. Colour conversion goes
//! spectrum → CIE 1931 XYZ → linear sRGB (D65), see [`colour`].

mod bands;
mod blackbody;
pub mod check;
pub mod cie;
pub mod cie_data;
pub mod colour;
mod rgb_sigmoid;
mod sampler;
mod tabulated;

pub use bands::{Bands, MAX_BANDS};
pub use blackbody::planck_radiance;
pub use rgb_sigmoid::RgbSigmoid;
pub use sampler::SpectrumSampler;
pub use tabulated::Tabulated;

/// A function of wavelength.
#[derive(Clone, Debug)]
pub enum Spectrum {
    /// The same value at every wavelength.
    Constant(f64),
    /// Piecewise linear through samples; zero outside the sampled range.
    Tabulated(Tabulated),
    /// Planck's spectral radiance of a black body at `temperature_k`, in W m⁻² sr⁻¹ nm⁻¹.
    Blackbody { temperature_k: f64 },
    /// A smooth reflectance in [0, 1] whose sRGB albedo is the given one (Jakob & Hanika 2019).
    RgbReflectance(RgbSigmoid),
    /// `scale` times another spectrum.
    Scaled(f64, Box<Spectrum>),
}

impl Spectrum {
    /// Value at `wavelength_nm`.
    pub fn eval(&self, wavelength_nm: f64) -> f64 {
        match self {
            Spectrum::Constant(c) => *c,
            Spectrum::Tabulated(t) => t.eval(wavelength_nm),
            Spectrum::Blackbody { temperature_k } => planck_radiance(*temperature_k, wavelength_nm),
            Spectrum::RgbReflectance(s) => s.eval(wavelength_nm),
            Spectrum::Scaled(k, s) => k * s.eval(wavelength_nm),
        }
    }

    /// ∫ s(λ) dλ over [min_nm, max_nm] (exact for tabulated and constant spectra).
    pub fn integral(&self, min_nm: f64, max_nm: f64) -> f64 {
        match self {
            Spectrum::Constant(c) => c * (max_nm - min_nm),
            Spectrum::Tabulated(t) => t.integral(min_nm, max_nm),
            Spectrum::Scaled(k, s) => k * s.integral(min_nm, max_nm),
            _ => sampler::integrate_smooth(self, min_nm, max_nm),
        }
    }

    /// True when the value does not depend on wavelength.
    pub fn is_constant(&self) -> bool {
        match self {
            Spectrum::Constant(_) => true,
            Spectrum::Scaled(_, s) => s.is_constant(),
            _ => false,
        }
    }

    /// `k` times this spectrum.
    pub fn scaled(self, k: f64) -> Spectrum {
        Spectrum::Scaled(k, Box::new(self))
    }
}

/// A CIE standard illuminant by name ("D65", "A", "E"), as a relative spectral power
/// distribution normalised to 100 at 560 nm (CIE 15:2018 convention).
pub fn named_illuminant(name: &str) -> Option<Spectrum> {
    cie::illuminant(name)
}
