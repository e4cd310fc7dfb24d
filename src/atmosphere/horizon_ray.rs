//! A ray near the horizon through the U.S. Standard Atmosphere 1976, with its end found without
//! integrating the ray equation: the second test ray of `morgana accuracy` (issue 18), beside
//! the paper's linear field ([`crate::ode::accuracy`]).
//!
//! The ray starts at height h₀ above the standard spherical Earth (radius R, r₀ = R + h₀) at
//! elevation e₀ > 0 and is followed for arc length L. In air whose n depends on the distance r
//! from the Earth's centre alone, the path lies in a plane and keeps Bouguer's invariant
//! n(r)·r·cos e = c = n₀·r₀·cos e₀ (e the elevation above the local horizontal; Born & Wolf,
//! *Principles of Optics*, §3.2.1). With D(r) = √(n²r² − c²), along a rising ray
//!
//! ```text
//!     ds/dr = n r / D,        dθ/dr = c / (r D),
//! ```
//!
//! θ the angle at the Earth's centre from the start. Below the tropopause (11 km, where dT/dh
//! jumps) n(r) is smooth, so both integrals over x = r − r₀ ∈ [0, Δh] converge fast under the
//! composite 16-point Gauss–Legendre rule; Δh at s = L is found by Newton's method on
//! s(Δh) = L. The end, in the frame of the start (x forward, y up, the centre at (0, −r₀, 0)):
//! (r sin θ, Δh cos θ − 2 r₀ sin²(θ/2)) — written so that no 6 371 km coordinates cancel.
//!
//! D is formed as √((nr − c)(nr + c)) with nr − c = K·(q(h) − q(h₀))·r + n₀·x + 2 n₀ r₀ sin²(e₀/2)
//! (n − 1 = K·q(h), [`super::Atmosphere::reduced_refractivity`]): every term is found to its
//! own relative precision, and nr − c ≥ 2 n₀ r₀ sin²(e₀/2) stays far from zero for e₀ ≥ 0.1°.
//! The field the integrators follow is the same n = 1 + K·q(h) with ∇n = K·q′(h)·r̂.

use super::{Atmosphere, EARTH_RADIUS_M, Earth};
use crate::ode::accuracy::TestRay;
use glam::DVec3;

/// Panels of the composite 16-point rule over [0, Δh].
const PANELS: usize = 64;
/// Lowest and highest start elevation, degrees.
pub const ELEVATION_DEG: (f64, f64) = (0.1, 10.0);
/// Highest start height, m.
pub const MAX_HEIGHT_M: f64 = 5_000.0;
/// The ray must end below this height (the tropopause of USA76, where dT/dh jumps), m.
pub const MAX_END_HEIGHT_M: f64 = 11_000.0;

/// The test ray (module notes).
#[derive(Clone, Debug)]
pub struct HorizonRay {
    air: Atmosphere,
    /// The standard Earth in the frame of the start (its centre at (0, −r₀, 0)).
    earth: Earth,
    /// Gladstone–Dale factor K(λ), m³ kg⁻¹.
    k: f64,
    h0: f64,
    r0: f64,
    e0: f64,
    n0: f64,
    q0: f64,
    /// Bouguer's invariant c = n₀ r₀ cos e₀, m.
    c: f64,
    /// n₀ r₀ − c = 2 n₀ r₀ sin²(e₀/2), m: the part of nr − c at the start.
    gap0: f64,
    wavelength_nm: f64,
    length_m: f64,
    end: DVec3,
    end_height_m: f64,
}

impl HorizonRay {
    /// The ray from `height_m` at `elevation_deg` at `wavelength_nm`, followed for `length_m`;
    /// an error naming the option when a value is out of range or the ray would cross the
    /// tropopause.
    pub fn new(height_m: f64, elevation_deg: f64, wavelength_nm: f64, length_m: f64) -> Result<HorizonRay, String> {
        if !(0.0..=MAX_HEIGHT_M).contains(&height_m) {
            return Err(format!("--height-m: found {height_m}; expected 0 to {MAX_HEIGHT_M} m"));
        }
        if !(ELEVATION_DEG.0..=ELEVATION_DEG.1).contains(&elevation_deg) {
            return Err(format!(
                "--elevation-deg: found {elevation_deg}; expected {} to {} degrees (a rising ray near the horizon)",
                ELEVATION_DEG.0, ELEVATION_DEG.1
            ));
        }
        let air = Atmosphere::usa76();
        if !wavelength_nm.is_finite() {
            return Err(format!("--wavelength-nm: found {wavelength_nm}; expected a wavelength in nm"));
        }
        air.dispersion.check_range((wavelength_nm, wavelength_nm)).map_err(|e| format!("--wavelength-nm: {e}"))?;
        if !(1.0..=1e6).contains(&length_m) {
            return Err(format!("--length-m: found {length_m}; expected a path length of 1 m to 1e6 m"));
        }
        let k = air.dispersion.gladstone_dale_m3_per_kg(wavelength_nm);
        let q0 = air.reduced_refractivity(height_m).0;
        let (r0, e0) = (EARTH_RADIUS_M + height_m, elevation_deg.to_radians());
        let n0 = 1.0 + k * q0;
        let earth = Earth::spherical(DVec3::new(0.0, -r0, 0.0), EARTH_RADIUS_M)?;
        let half = (0.5 * e0).sin();
        let mut ray = HorizonRay {
            air,
            earth,
            k,
            h0: height_m,
            r0,
            e0,
            n0,
            q0,
            c: n0 * r0 * e0.cos(),
            gap0: 2.0 * n0 * r0 * half * half,
            wavelength_nm,
            length_m,
            end: DVec3::ZERO,
            end_height_m: 0.0,
        };
        let dh = ray.rise_at(length_m)?;
        ray.end_height_m = height_m + dh;
        ray.end = ray.point(dh, ray.integrals(dh).1);
        Ok(ray)
    }

    /// Height of the end above the ground, m.
    pub fn end_height_m(&self) -> f64 {
        self.end_height_m
    }

    /// ds/dx and dθ/dx at x = r − r₀ (module notes).
    fn slopes(&self, x: f64) -> [f64; 2] {
        let r = self.r0 + x;
        let q = self.air.reduced_refractivity(self.h0 + x).0;
        let n = 1.0 + self.k * q;
        let below = self.k * (q - self.q0) * r + self.n0 * x + self.gap0;
        let d = (below * (n * r + self.c)).sqrt();
        [n * r / d, self.c / (r * d)]
    }

    /// (s, θ) at x = Δh.
    fn integrals(&self, dh: f64) -> (f64, f64) {
        let mut sums = [0.0; 2];
        let w = dh / PANELS as f64;
        for i in 0..PANELS {
            let a = i as f64 * w;
            crate::quadrature::gauss_legendre_panel_many(
                &mut |x, v| v.copy_from_slice(&self.slopes(x)),
                a,
                a + w,
                &mut sums,
            );
        }
        (sums[0], sums[1])
    }

    /// The rise Δh where the arc length is `s`, by Newton's method on s(Δh) = `s`.
    fn rise_at(&self, s: f64) -> Result<f64, String> {
        let mut dh = s * self.e0.sin() + s * s / (2.0 * self.r0);
        for _ in 0..50 {
            if self.h0 + dh >= MAX_END_HEIGHT_M {
                return Err(format!(
                    "--length-m {}: the ray would climb past the tropopause ({MAX_END_HEIGHT_M} m), where dT/dh jumps; use a shorter length or a lower elevation",
                    self.length_m
                ));
            }
            let step = (self.integrals(dh).0 - s) / self.slopes(dh)[0];
            dh -= step;
            if step.abs() <= 1e-14 * dh.abs().max(1.0) {
                return Ok(dh);
            }
        }
        Ok(dh)
    }

    /// The point at rise `dh` and central angle `theta`, in the frame of the start.
    fn point(&self, dh: f64, theta: f64) -> DVec3 {
        let half = (0.5 * theta).sin();
        DVec3::new((self.r0 + dh) * theta.sin(), dh * theta.cos() - 2.0 * self.r0 * half * half, 0.0)
    }
}

impl TestRay for HorizonRay {
    #[inline]
    fn n_grad(&self, p: DVec3) -> (f64, DVec3) {
        let (h, up) = self.earth.height_grad(p);
        let (q, dq) = self.air.reduced_refractivity(h);
        (1.0 + self.k * q, up * (self.k * dq))
    }
    fn start(&self) -> (DVec3, DVec3) {
        (DVec3::ZERO, DVec3::new(self.e0.cos(), self.e0.sin(), 0.0))
    }
    fn length_m(&self) -> f64 {
        self.length_m
    }
    fn end(&self) -> DVec3 {
        self.end
    }
    fn scale_m(&self) -> f64 {
        self.length_m
    }
    fn describe(&self) -> String {
        format!(
            "ray through USA76 air (Ciddor, {} nm) from {} m at +{}°, arc length {} m, ending {:.3} m up; endpoint from Bouguer's invariant by quadrature ({:.6}, {:.6}) m",
            self.wavelength_nm,
            self.h0,
            self.e0.to_degrees(),
            self.length_m,
            self.end_height_m,
            self.end.x,
            self.end.y
        )
    }
    fn title(&self) -> String {
        format!(
            "RAY IN USA76 AIR FROM {} M AT {} DEG, ARC LENGTH {} M: ERROR VS BOUGUER QUADRATURE",
            self.h0,
            self.e0.to_degrees(),
            self.length_m
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_quadrature_has_converged_and_the_end_keeps_its_length() {
        let ray = HorizonRay::new(10.0, 0.5, 550.0, 100_000.0).unwrap();
        let dh = ray.end_height_m - ray.h0;
        let (s, theta) = ray.integrals(dh);
        assert!((s - 100_000.0).abs() < 1e-9, "{s}");
        // Twice the panels: the same s and θ to rounding.
        let twice = |f: usize| {
            let mut sums = [0.0; 2];
            let w = dh / (f * PANELS) as f64;
            for i in 0..f * PANELS {
                let a = i as f64 * w;
                crate::quadrature::gauss_legendre_panel_many(
                    &mut |x, v| v.copy_from_slice(&ray.slopes(x)),
                    a,
                    a + w,
                    &mut sums,
                );
            }
            sums
        };
        let fine = twice(2);
        assert!((fine[0] - s).abs() < 1e-9 && (fine[1] - theta).abs() * EARTH_RADIUS_M < 1e-9, "{fine:?}");
        // A ray climbing 0.5° for 100 km rises by about L sin e + L²/2R less the refraction.
        assert!((800.0..1700.0).contains(&dh), "{dh}");
        assert!(ray.n_grad(DVec3::ZERO).0 == ray.n0);
    }

    #[test]
    fn bad_options_name_themselves() {
        assert!(HorizonRay::new(-1.0, 0.5, 550.0, 1e5).unwrap_err().contains("--height-m"));
        assert!(HorizonRay::new(10.0, 0.0, 550.0, 1e5).unwrap_err().contains("--elevation-deg"));
        assert!(HorizonRay::new(10.0, 0.5, 100.0, 1e5).unwrap_err().contains("--wavelength-nm"));
        assert!(HorizonRay::new(10.0, 5.0, 550.0, 1e6).unwrap_err().contains("tropopause"));
    }
}
