//! A smooth dielectric interface (glass, water) with a wavelength-dependent index.

use super::{Ior, SpecularSample, fresnel_dielectric, reflect, refract};
use glam::DVec3;

/// Smooth boundary between the outside (the front side of the normal: index 1, or the local n of
/// the medium there) and a body of index n(λ) (the back side).
#[derive(Clone, Debug)]
pub struct Dielectric {
    /// Refractive index n(λ) of the body.
    pub ior: Ior,
}

impl Dielectric {
    /// Chooses reflection with probability F (the Fresnel reflectance) and refraction otherwise,
    /// so power is carried unchanged (weight 1): the analog choice for photons and an
    /// unbiased one for eye paths.
    pub fn sample(&self, dir: DVec3, n: DVec3, wavelength_nm: f64, u: f64) -> SpecularSample {
        self.sample_in(dir, n, wavelength_nm, u, 1.0)
    }

    /// [`Dielectric::sample`] with a medium of index `n_outside` on the front side.
    pub fn sample_in(&self, dir: DVec3, n: DVec3, wavelength_nm: f64, u: f64, n_outside: f64) -> SpecularSample {
        let n_body = self.ior.eval(wavelength_nm) / n_outside;
        fresnel_sample(dir, n, n_body, u)
    }

    /// Fresnel reflectance for a path arriving along `dir` at normal `n`.
    pub fn reflectance(&self, dir: DVec3, n: DVec3, wavelength_nm: f64) -> f64 {
        let n_body = self.ior.eval(wavelength_nm);
        let eta = if dir.dot(n) < 0.0 { n_body } else { 1.0 / n_body };
        fresnel_dielectric(dir.dot(n).abs(), eta)
    }
}

/// Reflection with probability F or refraction, at a boundary whose back side has index
/// `n_back` relative to the front side (weight 1): the analog choice for photons, unbiased for
/// eye paths. Total internal reflection reflects.
pub fn fresnel_sample(dir: DVec3, n: DVec3, n_back: f64, u: f64) -> SpecularSample {
    {
        let n_body = n_back;
        let entering = dir.dot(n) < 0.0;
        let eta = if entering { n_body } else { 1.0 / n_body };
        let cos_i = dir.dot(n).abs();
        let f = fresnel_dielectric(cos_i, eta);
        if u < f {
            return SpecularSample { dir: reflect(dir, n), weight: 1.0, transmitted: false };
        }
        match refract(dir, n, eta) {
            Some(t) => SpecularSample { dir: t, weight: 1.0, transmitted: true },
            None => SpecularSample { dir: reflect(dir, n), weight: 1.0, transmitted: false },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reflection_probability_is_the_fresnel_reflectance() {
        let d = Dielectric { ior: Ior::Constant { n: 1.5 } };
        let dir = DVec3::new(0.5, 0.0, -(0.75f64).sqrt());
        let f = d.reflectance(dir, DVec3::Z, 550.0);
        let n = 100_000;
        let reflected =
            (0..n).filter(|i| !d.sample(dir, DVec3::Z, 550.0, (*i as f64 + 0.5) / n as f64).transmitted).count();
        assert!((reflected as f64 / n as f64 - f).abs() < 2.0 / n as f64);
    }
}
