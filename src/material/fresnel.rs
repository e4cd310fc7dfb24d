//! Reflection, refraction and the Fresnel equations for dielectrics.
//!
//! # References
//! Born & Wolf, *Principles of Optics*, 7th ed., §1.5; PBRT4 §9.3.

use glam::DVec3;

/// Mirror reflection of travel direction `dir` about normal `n` (either orientation).
pub fn reflect(dir: DVec3, n: DVec3) -> DVec3 {
    dir - 2.0 * dir.dot(n) * n
}

/// Refraction of travel direction `dir` through a surface with normal `n` (either orientation)
/// for relative index `eta = n_transmitted / n_incident`. `None` on total internal reflection.
///
/// Snell: n_i sin θ_i = n_t sin θ_t; ω_t = d/η + (cos θ_i/η − cos θ_t) n̂, with n̂ facing the
/// incident side.
pub fn refract(dir: DVec3, n: DVec3, eta: f64) -> Option<DVec3> {
    let n = if dir.dot(n) < 0.0 { n } else { -n };
    let cos_i = -dir.dot(n);
    let sin2_t = (1.0 - cos_i * cos_i).max(0.0) / (eta * eta);
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some((dir / eta + (cos_i / eta - cos_t) * n).normalize())
}

/// Unpolarised Fresnel reflectance at a dielectric interface, for the cosine of the incidence
/// angle `cos_i` ≥ 0 and relative index `eta = n_t / n_i`: F = (r_s² + r_p²)/2 with
/// r_s = (η_i cos θ_i − η_t cos θ_t)/(η_i cos θ_i + η_t cos θ_t) and
/// r_p = (η_t cos θ_i − η_i cos θ_t)/(η_t cos θ_i + η_i cos θ_t). Returns 1 on total internal
/// reflection.
pub fn fresnel_dielectric(cos_i: f64, eta: f64) -> f64 {
    let cos_i = cos_i.clamp(0.0, 1.0);
    let sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
    if sin2_t >= 1.0 {
        return 1.0;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    let r_s = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    let r_p = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    0.5 * (r_s * r_s + r_p * r_p)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normal_incidence_reflectance_is_the_closed_form() {
        // F(0) = ((η − 1)/(η + 1))², 0.04 for η = 1.5.
        assert!((fresnel_dielectric(1.0, 1.5) - 0.04).abs() < 1e-12);
        assert!((fresnel_dielectric(1.0, 1.0 / 1.5) - 0.04).abs() < 1e-12);
        assert!((fresnel_dielectric(0.0, 1.5) - 1.0).abs() < 1e-12, "grazing incidence reflects all");
    }

    #[test]
    fn brewster_angle_has_no_p_reflection() {
        // At tan θ_B = η, r_p = 0 so F = r_s²/2 = ((cos θ_i − η cos θ_t)/(cos θ_i + η cos θ_t))²/2.
        let eta: f64 = 1.5;
        let theta_b = eta.atan();
        let (ci, ct) = (theta_b.cos(), (1.0 - (theta_b.sin() / eta).powi(2)).sqrt());
        let rs = (ci - eta * ct) / (ci + eta * ct);
        assert!((fresnel_dielectric(ci, eta) - 0.5 * rs * rs).abs() < 1e-12);
    }

    #[test]
    fn snell_law_and_total_internal_reflection() {
        let n = DVec3::Z;
        let theta_i: f64 = 0.6;
        let d = DVec3::new(theta_i.sin(), 0.0, -theta_i.cos());
        let t = refract(d, n, 1.5).expect("no TIR entering glass");
        assert!((t.x - theta_i.sin() / 1.5).abs() < 1e-12, "n_i sin θ_i = n_t sin θ_t");
        assert!(t.z < 0.0 && (t.length() - 1.0).abs() < 1e-12);
        // Leaving glass beyond the critical angle asin(1/1.5) = 41.8°.
        let d = DVec3::new(0.8f64.sin(), 0.0, 0.8f64.cos());
        assert!(refract(d, n, 1.0 / 1.5).is_none());
        assert!((fresnel_dielectric(0.8f64.cos(), 1.0 / 1.5) - 1.0).abs() < 1e-15);
        let r = reflect(DVec3::new(1.0, 0.0, -1.0).normalize(), n);
        assert!((r - DVec3::new(1.0, 0.0, 1.0).normalize()).length() < 1e-15);
    }
}
