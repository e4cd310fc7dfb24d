//! A rough dielectric interface: Beckmann facets, each a smooth Fresnel boundary — a
//! wind-roughened sea (Cox–Munk) or frosted glass.
//!
//! A path arriving along d (ω_i = −d) picks a facet normal m with density D(m)|m·n|, then
//! reflects about m with probability F(ω_i·m) or refracts through it otherwise (Walter et al.
//! 2007 §5.3). The throughput factor of either branch is
//!
//! ```text
//!     w = |ω_i·m| G₁(ω_i, m) G₁(ω_o, m) / (|ω_i·n| |m·n|)        (Walter et al. 2007 eq. 41)
//! ```
//!
//! which is f·|ω_o·n|/p for their BSDF
//!
//! ```text
//!     f_r = F(ω_i·h_r) G D(h_r) / (4 |ω_i·n| |ω_o·n|),                         h_r ∝ ω_i + ω_o
//!     f_t = |ω_i·h_t| |ω_o·h_t| η_o² (1 − F) G D(h_t) / (|ω_i·n| |ω_o·n| (η_i ω_i·h_t + η_o ω_o·h_t)²),
//!                                                                               h_t ∝ −(η_i ω_i + η_o ω_o)
//! ```
//!
//! (eqs. 20–21, [`RoughDielectric::eval`]). As α → 0 this is the smooth [`super::Dielectric`]:
//! reflection with probability F, weight 1. Facets the path cannot see, and directions that
//! leave on the wrong side, carry weight 0 (light lost to shadowing; G also removes the light a
//! single-scattering model cannot follow, a few per cent at grazing angles).
//!
//! # References
//! B. Walter, S. R. Marschner, H. Li, K. E. Torrance, "Microfacet models for refraction through
//! rough surfaces", EGSR 2007.

use super::beckmann::Beckmann;
use super::{Ior, SpecularSample, fresnel_dielectric, reflect, refract};
use glam::DVec3;

/// A rough dielectric interface (see the module docs).
#[derive(Clone, Debug)]
pub struct RoughDielectric {
    /// Refractive index n(λ) of the body behind the normal.
    pub ior: Ior,
    /// Facet normal distribution.
    pub facets: Beckmann,
}

impl RoughDielectric {
    /// A direction leaving the surface for a path arriving along `dir` at mean normal `n`, with
    /// a medium of index `n_outside` on the front side; `u[0]` chooses the Fresnel branch,
    /// `u[1..3]` the facet.
    pub fn sample_in(&self, dir: DVec3, n: DVec3, wavelength_nm: f64, u: [f64; 3], n_outside: f64) -> SpecularSample {
        let (ns, eta) = self.side(dir, n, wavelength_nm, n_outside);
        let wi = -dir;
        let m = self.facets.sample(ns, u[1], u[2]);
        let cos_im = wi.dot(m);
        let lost = SpecularSample { dir: reflect(dir, ns), weight: 0.0, transmitted: false };
        if cos_im <= 0.0 {
            return lost;
        }
        let f = fresnel_dielectric(cos_im, eta);
        let (out, transmitted) = match refract(dir, m, eta) {
            Some(t) if u[0] >= f => (t, true),
            _ => (reflect(dir, m), false),
        };
        let below = out.dot(ns) < 0.0;
        if below != transmitted {
            return lost;
        }
        let g = self.facets.g1(wi, m, ns) * self.facets.g1(out, m, ns);
        SpecularSample { dir: out, weight: cos_im * g / (wi.dot(ns) * m.dot(ns)), transmitted }
    }

    /// The BSDF f(ω_i → ω_o) for a path arriving along `dir` and leaving along `out` (Walter et
    /// al. 2007 eqs. 20–21), per steradian of `out`.
    pub fn eval(&self, dir: DVec3, out: DVec3, n: DVec3, wavelength_nm: f64, n_outside: f64) -> f64 {
        let (ns, eta) = self.side(dir, n, wavelength_nm, n_outside);
        let wi = -dir;
        let (cos_i, cos_o) = (wi.dot(ns), out.dot(ns));
        if cos_i <= 0.0 || cos_o == 0.0 {
            return 0.0;
        }
        let reflected = cos_o > 0.0;
        let h = if reflected { wi + out } else { -(wi + out * eta) };
        let Some(h) = h.try_normalize() else { return 0.0 };
        let h = if h.dot(ns) < 0.0 { -h } else { h };
        let (ih, oh) = (wi.dot(h), out.dot(h));
        if ih <= 0.0 {
            return 0.0;
        }
        let f = fresnel_dielectric(ih, eta);
        let g = self.facets.g1(wi, h, ns) * self.facets.g1(out, h, ns);
        let d = self.facets.d(h.dot(ns));
        if reflected {
            f * g * d / (4.0 * cos_i * cos_o)
        } else {
            let denom = ih + eta * oh;
            (ih * oh).abs() * eta * eta * (1.0 - f) * g * d / (cos_i * cos_o.abs() * denom * denom)
        }
    }

    /// The mean normal on the arrival side, and η = n_transmitted/n_incident.
    fn side(&self, dir: DVec3, n: DVec3, wavelength_nm: f64, n_outside: f64) -> (DVec3, f64) {
        let n_body = self.ior.eval(wavelength_nm) / n_outside;
        if dir.dot(n) < 0.0 { (n, n_body) } else { (-n, 1.0 / n_body) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Frame;
    use crate::quadrature::gauss_legendre;
    use crate::rng::{Rng, Stream};
    use crate::testing::chi2::chi2_sphere;
    use std::f64::consts::PI;

    fn water(alpha: f64) -> RoughDielectric {
        RoughDielectric { ior: Ior::Constant { n: 1.333 }, facets: Beckmann { alpha } }
    }

    fn arriving(theta_deg: f64, from_inside: bool) -> DVec3 {
        let t = theta_deg.to_radians();
        let d = DVec3::new(t.sin(), 0.0, -t.cos());
        if from_inside { -d * DVec3::new(-1.0, 1.0, 1.0) } else { d }
    }

    /// ∫ f |ω_o·n| dω_o over the hemisphere on the side `sign` (+1 reflection), by product
    /// Gauss–Legendre in (cos θ_o, φ_o) — from the BSDF alone.
    fn quadrature(s: &RoughDielectric, dir: DVec3, sign: f64) -> f64 {
        let f = |mu: f64| {
            let r = (1.0 - mu * mu).max(0.0).sqrt();
            gauss_legendre(
                &|phi: f64| {
                    let o = DVec3::new(r * phi.cos(), r * phi.sin(), sign * mu);
                    s.eval(dir, o, DVec3::Z, 550.0, 1.0) * mu
                },
                0.0,
                2.0 * PI,
                24,
            )
        };
        gauss_legendre(&f, 0.0, 1.0, 64)
    }

    /// Monte Carlo means of the weight into reflection and transmission, with standard errors.
    fn sampled(s: &RoughDielectric, dir: DVec3, n: usize) -> [(f64, f64); 2] {
        let mut rng = Rng::for_task(17, Stream::Test, 0);
        let mut acc = [[0.0; 2]; 2];
        for _ in 0..n {
            let u = [rng.uniform(), rng.uniform(), rng.uniform()];
            let x = s.sample_in(dir, DVec3::Z, 550.0, u, 1.0);
            let k = x.transmitted as usize;
            acc[k][0] += x.weight;
            acc[k][1] += x.weight * x.weight;
        }
        acc.map(|[s1, s2]| {
            let mean = s1 / n as f64;
            (mean, ((s2 / n as f64 - mean * mean) / n as f64).sqrt())
        })
    }

    #[test]
    fn sampled_weights_integrate_the_bsdf() {
        // E[w; reflected] = ∫ f_r cos θ_o dω_o and E[w; transmitted] = ∫ f_t |cos θ_o| dω_o,
        // with the integrals from Walter's eqs. 20–21 by quadrature: checks the sampler, its
        // weight and the BSDF against each other, from air and from inside the water.
        for (alpha, theta, inside) in [(0.17, 0.0, false), (0.17, 60.0, false), (0.3, 75.0, false), (0.17, 30.0, true)]
        {
            let s = water(alpha);
            let dir = arriving(theta, inside);
            let [(r, r_se), (t, t_se)] = sampled(&s, dir, 400_000);
            // Reflection stays on the arrival side: above for a path coming down from the air.
            let up = if dir.z < 0.0 { 1.0 } else { -1.0 };
            let (rq, tq) = (quadrature(&s, dir, up), quadrature(&s, dir, -up));
            let case = format!("α = {alpha}, θ = {theta}°, inside = {inside}");
            assert!((r - rq).abs() < 4.0 * r_se + 1e-4, "{case}: R {r} ± {r_se} vs {rq}");
            assert!((t - tq).abs() < 4.0 * t_se + 1e-4, "{case}: T {t} ± {t_se} vs {tq}");
            assert!(r + t <= 1.0 + 4.0 * (r_se + t_se), "{case}: no energy gained ({})", r + t);
        }
    }

    #[test]
    fn a_nearly_smooth_surface_is_the_smooth_dielectric() {
        // α → 0: reflection with probability F(θ) and weight 1, in the mirror direction.
        let s = water(1e-5);
        let dir = arriving(50.0, false);
        let f = fresnel_dielectric(50f64.to_radians().cos(), 1.333);
        let [(r, _), (t, _)] = sampled(&s, dir, 100_000);
        assert!((r - f).abs() < 0.005 && (t - (1.0 - f)).abs() < 0.005, "R {r}, T {t}, F {f}");
        let x = s.sample_in(dir, DVec3::Z, 550.0, [0.0, 0.3, 0.6], 1.0);
        assert!((x.dir - reflect(dir, DVec3::Z)).length() < 1e-4);
    }

    #[test]
    fn sampled_directions_follow_the_sampling_density() {
        // The density of ω_o implied by the sampler: facet density D|m·n| times the Fresnel
        // choice, carried to ω_o by the Jacobians 1/(4|ω_o·h|) (reflection) and
        // η²|ω_o·h|/(ω_i·h + η ω_o·h)² (refraction), Walter et al. eqs. 14 and 17.
        let s = water(0.25);
        let dir = arriving(40.0, false);
        let wi = -dir;
        let eta = 1.333;
        let pdf = |o: DVec3| {
            let (h, jac) = if o.z > 0.0 {
                let h = (wi + o).normalize();
                (h, 1.0 / (4.0 * o.dot(h).abs()))
            } else {
                let h = -(wi + o * eta).normalize();
                let h = if h.z < 0.0 { -h } else { h };
                let den = wi.dot(h) + eta * o.dot(h);
                (h, eta * eta * o.dot(h).abs() / (den * den))
            };
            if wi.dot(h) <= 0.0 {
                return 0.0;
            }
            let f = fresnel_dielectric(wi.dot(h), eta);
            let branch = if o.z > 0.0 { f } else { 1.0 - f };
            s.facets.d(h.z) * h.z * branch * jac
        };
        let mut rng = Rng::for_task(23, Stream::Test, 0);
        let frame = Frame::from_normal(DVec3::Z);
        let p = chi2_sphere(
            24,
            24,
            300_000,
            || {
                let u = [rng.uniform(), rng.uniform(), rng.uniform()];
                // Lost samples (facets the path cannot see, directions on the wrong side) are
                // the mass the density leaves out.
                let x = s.sample_in(dir, DVec3::Z, 550.0, u, 1.0);
                (x.weight > 0.0).then(|| frame.to_local(x.dir))
            },
            pdf,
        );
        assert!(p > 1e-3, "p = {p}");
    }
}
