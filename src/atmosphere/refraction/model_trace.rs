//! The ray trace through a [`ModelAtmosphere`]: the test oracle of the quadrature
//! ([`super::quadrature`]) and `morgana refraction --method trace`.
//!
//! The ray leaves the observer (at r₀ on the y axis, the Earth's centre at the origin) at
//! apparent zenith distance z₀ and follows Fermat's ray equation d/ds(n dr/ds) = ∇n,
//! ∇n = (dn/dr) r̂, by Dormand–Prince RK5(4)7M ([`crate::ode`], rtol = atol = 10⁻¹²). No step
//! straddles the tropopause, where dn/dr jumps, or the top: a step is limited to the straight
//! distance to the next of these spheres, and within 1 μm of one the path is on it. At the top
//! r_s the ray has turned by the central angle φ_s and leaves at zenith distance z_s in n_s; in
//! vacuum its direction makes z_v = asin(n_s sin z_s) with the vertical there (Snell), so the
//! star's true zenith distance at the observer is φ_s + z_v and the refraction is
//! R = φ_s + z_v − z₀. A ray that turns down (ducting) or meets the ground is refused.

use super::model::ModelAtmosphere;
use crate::ode::{Integrator, Method, OdeState};
use glam::DVec3;

/// A path within this distance of a sphere is on it, m.
const ON_SPHERE_M: f64 = 1e-6;
/// Steps after which a path is given up.
const MAX_STEPS: usize = 1_000_000;

/// The traced refraction at apparent zenith distance `zenith_rad` (0 … π/2), rad, and the
/// integrator's accepted steps.
pub fn traced_refraction(m: &ModelAtmosphere, zenith_rad: f64) -> Result<(f64, u64), String> {
    let field = |p: DVec3| {
        let r = p.length();
        let (n, dndr) = m.n_dndr(r);
        (n, dndr / r * p)
    };
    let method =
        Method::DormandPrince { rtol: 1e-12, atol: 1e-12, pi: true, h0: None, h_min: 0.0, h_max: f64::INFINITY };
    let mut ode = Integrator::new(method).map_err(|e| e.to_string())?;
    let start = DVec3::new(0.0, m.r_obs_m, 0.0);
    let dir = DVec3::new(zenith_rad.sin(), zenith_rad.cos(), 0.0);
    let mut state = OdeState::launch(&field, start, dir).map_err(|e| e.to_string())?;
    for _ in 0..MAX_STEPS {
        let p = state.y.r;
        let r = p.length();
        let d = state.y.direction();
        if r >= m.r_top_m - ON_SPHERE_M {
            let z_s = angle_between(d, p);
            let n_s = m.n_rdndr(m.layer_of(m.r_top_m - 1.0), m.r_top_m).0;
            let z_v = (n_s * z_s.sin()).min(1.0).asin();
            return Ok((angle_between(start, p) + z_v - zenith_rad, ode.counters().accepted));
        }
        if d.dot(p) < 0.0 || r < m.r_obs_m - 1.0 {
            return Err(format!(
                "the ray at zenith distance {} deg turns down: no refraction",
                zenith_rad.to_degrees()
            ));
        }
        let next = if r < m.r_tropopause_m - ON_SPHERE_M { m.r_tropopause_m } else { m.r_top_m };
        let h_limit = distance_to_sphere(p, d, next).max(ON_SPHERE_M * 2.0);
        ode.step(&field, &mut state, h_limit).map_err(|e| e.to_string())?;
    }
    Err("the ray trace did not reach the top".into())
}

/// The angle between `a` and `b`, rad.
fn angle_between(a: DVec3, b: DVec3) -> f64 {
    a.cross(b).length().atan2(a.dot(b))
}

/// The distance along unit `d` from `p` (inside) to the sphere of radius `radius` about the
/// origin: t with |p + t d| = radius, t = −p·d + √((p·d)² − (|p|² − radius²)).
fn distance_to_sphere(p: DVec3, d: DVec3, radius: f64) -> f64 {
    let b = p.dot(d);
    let c = (p.length() - radius) * (p.length() + radius);
    -b + (b * b - c).max(0.0).sqrt()
}
