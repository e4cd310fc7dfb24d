//! Surface materials: one file each, dispatched by a closed enum.
//!
//! Directions follow the convention of the photon tracer and the eye tracer alike: `dir` is the
//! direction of travel arriving at the surface, `n` the shape's front-side geometric normal (in
//! either orientation relative to `dir`). Sampling returns the direction of travel leaving it.

mod beckmann;
mod dielectric;
mod fresnel;
mod ior;
mod lambertian;
mod mirror;
mod rough_dielectric;

pub use beckmann::{Beckmann, COX_MUNK_MAX_WIND_M_S};
pub use dielectric::{Dielectric, fresnel_sample};
pub use fresnel::{fresnel_dielectric, reflect, refract};
pub use ior::{GLASS_NAMES, Ior, named_glass};
pub use lambertian::Lambertian;
pub use mirror::Mirror;
pub use rough_dielectric::RoughDielectric;

use crate::rng::Rng;
use glam::DVec3;

/// A surface's scattering.
#[derive(Clone, Debug)]
pub enum Material {
    /// Ideal diffuse reflection.
    Lambertian(Lambertian),
    /// Perfect specular reflection.
    Mirror(Mirror),
    /// Smooth dielectric interface: Fresnel reflection and refraction.
    Dielectric(Dielectric),
    /// Rough dielectric interface: Beckmann microfacets (a wind-roughened sea, frosted glass).
    RoughDielectric(RoughDielectric),
}

/// A specular direction chosen at a surface and the factor it multiplies the carried power or
/// throughput by at `wavelength_nm`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpecularSample {
    /// Unit direction of travel leaving the surface.
    pub dir: DVec3,
    /// Factor to multiply the path throughput by.
    pub weight: f64,
    /// True when the direction passes through the surface (refraction).
    pub transmitted: bool,
}

impl Material {
    /// Diffuse materials hold photons and are lit by radiance estimates and shadow rays.
    pub fn is_diffuse(&self) -> bool {
        matches!(self, Material::Lambertian(_))
    }

    /// Specular materials (mirrors, glass) redirect light into one direction per wavelength.
    pub fn is_specular(&self) -> bool {
        !self.is_diffuse()
    }

    /// True when the outgoing direction depends on wavelength (dispersive refraction): an eye
    /// path carrying several wavelengths must split here.
    pub fn is_dispersive(&self) -> bool {
        match self {
            Material::Dielectric(d) => d.ior.is_dispersive(),
            Material::RoughDielectric(d) => d.ior.is_dispersive(),
            _ => false,
        }
    }

    /// Glass-like boundaries a path passes through when it is not reflected.
    pub fn is_refractive(&self) -> bool {
        matches!(self, Material::Dielectric(_) | Material::RoughDielectric(_))
    }

    /// The random numbers [`Material::sample_specular_in`] uses: `u[0]` chooses between
    /// reflection and refraction; rough surfaces also draw a facet from `u[1..3]` (smooth ones
    /// draw nothing more, so their random sequence is unchanged).
    pub fn specular_u(&self, rng: &mut Rng) -> [f64; 3] {
        let u0 = rng.uniform();
        match self {
            Material::RoughDielectric(_) => {
                let [u1, u2] = rng.uniform2();
                [u0, u1, u2]
            }
            _ => [u0, 0.5, 0.5],
        }
    }

    /// The specular direction for a path arriving along `dir` at a surface with normal `n`, at
    /// `wavelength_nm`, using `u` (see [`Material::specular_u`]); `None` for diffuse materials.
    /// A zero weight means the path ends there (a rough surface's shadowed facets).
    pub fn sample_specular(&self, dir: DVec3, n: DVec3, wavelength_nm: f64, u: [f64; 3]) -> Option<SpecularSample> {
        self.sample_specular_in(dir, n, wavelength_nm, u, 1.0)
    }

    /// [`Material::sample_specular`] with a medium of index `n_outside` on the front side of the
    /// normal (the local n of the exterior medium: air is 1.0003, not 1).
    pub fn sample_specular_in(
        &self,
        dir: DVec3,
        n: DVec3,
        wavelength_nm: f64,
        u: [f64; 3],
        n_outside: f64,
    ) -> Option<SpecularSample> {
        match self {
            Material::Lambertian(_) => None,
            Material::Mirror(m) => Some(m.sample(dir, n, wavelength_nm)),
            Material::Dielectric(d) => Some(d.sample_in(dir, n, wavelength_nm, u[0], n_outside)),
            Material::RoughDielectric(d) => Some(d.sample_in(dir, n, wavelength_nm, u, n_outside)),
        }
    }

    /// η = n_far/n_near for a path arriving along `dir` at a surface with normal `n` that is
    /// transmitted: the index of the side it enters over the index of the side it leaves (1 for
    /// materials that do not refract). Radiance carried across such a boundary scales by
    /// 1/η² (L/n² is conserved along a ray; Veach 1997, §5.2); power does not.
    pub fn transmitted_index_ratio(&self, dir: DVec3, n: DVec3, wavelength_nm: f64, n_outside: f64) -> f64 {
        let body = match self {
            Material::Dielectric(d) => d.ior.eval(wavelength_nm),
            Material::RoughDielectric(d) => d.ior.eval(wavelength_nm),
            Material::Lambertian(_) | Material::Mirror(_) => return 1.0,
        };
        let relative = body / n_outside;
        if dir.dot(n) < 0.0 { relative } else { 1.0 / relative }
    }

    /// Diffuse reflectance ρ(λ) (the BRDF is ρ/π); zero for specular materials.
    pub fn diffuse_reflectance(&self, wavelength_nm: f64) -> f64 {
        match self {
            Material::Lambertian(l) => l.reflectance.eval(wavelength_nm),
            _ => 0.0,
        }
    }
}
