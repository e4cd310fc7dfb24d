//! Wavelengths, spectra and colour.
//!
//! Wavelengths are in nanometres. A [`Spectrum`] is a function of wavelength whose unit depends on
//! its use (reflectance: none; light: spectral radiance, intensity or irradiance per nm).
//! [`Bands`] is the scene's wavelength sampling of the output. Colour conversion goes
//! spectrum → CIE 1931 XYZ → linear sRGB (D65), see [`colour`].

mod bands;
mod blackbody;
pub mod cie;
pub mod cie_data;
pub mod colour;
pub mod exr;
mod image;
mod power_law;
mod rgb_sigmoid;
mod sampler;
pub mod solar;
mod solar_data;
pub mod table;
mod tabulated;

pub use bands::{BandValues, Bands, MAX_BANDS};
pub use blackbody::planck_radiance;
pub use image::SpectralImage;
pub use power_law::PowerLawTable;
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
    Blackbody {
        /// Temperature T, K.
        temperature_k: f64,
    },
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integrals_are_exact_or_within_the_stated_accuracy() {
        assert_eq!(Spectrum::Constant(2.0).integral(400.0, 500.0), 200.0);
        let t = Tabulated::new(vec![400.0, 500.0], vec![0.0, 1.0]).unwrap();
        assert!((Spectrum::Tabulated(t).scaled(4.0).integral(0.0, 1000.0) - 200.0).abs() < 1e-12);
        // s = S(aλ + b) has the antiderivative λ/2 + √(1 + (aλ + b)²) / (2a).
        let (a, b) = (0.02, -11.0);
        let s = Spectrum::RgbReflectance(RgbSigmoid { coefficients: [0.0, a, b] });
        let anti = |l: f64| l / 2.0 + (1.0 + (a * l + b).powi(2)).sqrt() / (2.0 * a);
        let want = anti(830.0) - anti(360.0);
        let got = s.integral(360.0, 830.0);
        assert!(((got - want) / want).abs() < 1e-9, "{got} vs {want}");
        assert!((s.integral(830.0, 360.0) + want).abs() < 1e-9 * want);
        assert_eq!(s.integral(500.0, 500.0), 0.0);
    }

    #[test]
    fn constant_and_scaled_spectra_report_constancy() {
        assert!(Spectrum::Constant(1.0).scaled(3.0).is_constant());
        assert!(!Spectrum::Blackbody { temperature_k: 3000.0 }.is_constant());
        assert_eq!(Spectrum::Constant(2.0).scaled(3.0).eval(123.0), 6.0);
        assert!(named_illuminant("E").unwrap().is_constant());
    }
}
