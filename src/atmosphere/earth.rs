//! Where "height" is measured from: flat ground or a spherical Earth.
//!
//! # Scene frame
//! Scenes are +y up with the ground at y = 0 under the origin. A flat Earth is the plane through
//! the origin normal to `up` (default +y), so h(p) = p·up. The default spherical Earth has radius
//! 6371 km (the mean radius of IUGG/WGS-84; Gutierrez et al. 2005 §5 use the same) and its centre
//! at (0, −R, 0), so the ground at the origin is at y = 0 and h(p) = |p − c| − R.
//!
//! # Precision
//! Near the ground, |p − c| − R loses the digits of h in the subtraction of two numbers of size R
//! (about 1e-9 m in f64). [`Sphere`] instead measures from the ground point g = c + R·û under the
//! origin: with q = p − g, |p − c|² − R² = |q|² + 2R q·û, so
//! h = (|q|² + 2R q·û) / (|p − c| + R) keeps the relative precision of h at any height.

use glam::DVec3;

/// Mean Earth radius, m.
pub const EARTH_RADIUS_M: f64 = 6_371_000.0;

/// The largest sphere radius accepted, m: 10⁶ km (the Sun's radius is 6.96 × 10⁵ km). Beyond
/// it the squared distances of h = |p − centre| − R lose every digit of a metre and then
/// overflow (R = 10³⁰⁸ gave NaN temperatures); `earth = "flat"` is the infinite radius.
pub const MAX_EARTH_RADIUS_M: f64 = 1e9;

/// A sphere measured from its surface point under the scene origin (see the module notes).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere {
    /// Centre c of the sphere, m.
    pub centre: DVec3,
    /// Radius R, m.
    pub radius_m: f64,
    /// Unit vector from the centre towards the scene origin (+y when the centre is the origin).
    up: DVec3,
    /// The surface point c + R·up.
    ground: DVec3,
}

/// The geometry heights are measured in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Earth {
    /// Flat ground through the origin: h = p·up (up is a unit vector).
    Flat {
        /// Unit normal of the ground plane, pointing up.
        up: DVec3,
    },
    /// A sphere: h = |p − centre| − radius.
    Spherical(Sphere),
}

impl Earth {
    /// Flat ground through the origin normal to `up` (normalised; must be finite and non-zero).
    pub fn flat(up: DVec3) -> Result<Earth, String> {
        if !up.is_finite() || up.length_squared() == 0.0 {
            return Err(format!("flat Earth: up = {up} must be a finite non-zero vector"));
        }
        Ok(Earth::Flat { up: up.normalize() })
    }

    /// Flat ground y = 0, +y up.
    pub fn flat_y() -> Earth {
        Earth::Flat { up: DVec3::Y }
    }

    /// A sphere of `radius_m` (finite, > 0) centred at `centre`.
    pub fn spherical(centre: DVec3, radius_m: f64) -> Result<Earth, String> {
        if !(radius_m > 0.0 && radius_m <= MAX_EARTH_RADIUS_M) {
            return Err(format!(
                "spherical Earth: radius {radius_m} m must be positive and at most {MAX_EARTH_RADIUS_M:e} m (use earth = \"flat\" for a flat one)"
            ));
        }
        if !centre.is_finite() {
            return Err(format!("spherical Earth: centre {centre} must be finite"));
        }
        let up = (-centre).try_normalize().unwrap_or(DVec3::Y);
        Ok(Earth::Spherical(Sphere { centre, radius_m, up, ground: centre + radius_m * up }))
    }

    /// The scene-frame Earth of radius `radius_m`: centre (0, −R, 0), ground at y = 0.
    pub fn spherical_y(radius_m: f64) -> Result<Earth, String> {
        Earth::spherical(DVec3::new(0.0, -radius_m, 0.0), radius_m)
    }

    /// The default Earth of morgana's atmospheres: R = 6371 km, centre (0, −R, 0).
    pub fn standard() -> Earth {
        let r = EARTH_RADIUS_M;
        let up = DVec3::Y;
        Earth::Spherical(Sphere { centre: DVec3::new(0.0, -r, 0.0), radius_m: r, up, ground: DVec3::ZERO })
    }

    /// Height above the ground, m.
    pub fn height(&self, p: DVec3) -> f64 {
        self.height_grad(p).0
    }

    /// Height and its gradient ∇h (a unit vector: `up`, or the radial direction).
    pub fn height_grad(&self, p: DVec3) -> (f64, DVec3) {
        match self {
            Earth::Flat { up } => (p.dot(*up), *up),
            Earth::Spherical(s) => s.height_grad(p),
        }
    }
}

impl Sphere {
    fn height_grad(&self, p: DVec3) -> (f64, DVec3) {
        let q = p - self.ground;
        let d = q + self.radius_m * self.up;
        let r = d.length();
        if r == 0.0 {
            return (-self.radius_m, self.up);
        }
        let excess = q.length_squared() + 2.0 * self.radius_m * q.dot(self.up);
        (excess / (r + self.radius_m), d / r)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flat_height_is_the_projection_on_up() {
        let e = Earth::flat(DVec3::new(0.0, 2.0, 0.0)).unwrap();
        assert_eq!(e.height_grad(DVec3::new(3.0, 4.5, -1.0)), (4.5, DVec3::Y));
        assert!(Earth::flat(DVec3::ZERO).is_err());
    }

    #[test]
    fn spherical_height_is_precise_near_the_ground_and_far_away() {
        let e = Earth::standard();
        // A point 1 mm up and 10 km along the ground: with a = R + 1e-3 and u = x²/a²,
        // h = √(a² + x²) − R = 1e-3 + a(u/2 − u²/8 + u³/16 − …), the next term ~1e-11 m.
        let x = 10_000.0_f64;
        let r = EARTH_RADIUS_M;
        let (h, g) = e.height_grad(DVec3::new(x, 1e-3, 0.0));
        let want = ((r + 1e-3) * (r + 1e-3) + x * x).sqrt() - r;
        let a = r + 1e-3;
        let u = x * x / (a * a);
        let series = 1e-3 + a * (u / 2.0 - u * u / 8.0 + u * u * u / 16.0);
        assert!((h - series).abs() < 1e-9, "h = {h}, series {series}");
        assert!((h - want).abs() < 1e-6, "h = {h}, direct {want}");
        assert!((g.length() - 1.0).abs() < 1e-15);
        // Height of the origin is exactly zero; the gradient there is +y.
        assert_eq!(e.height_grad(DVec3::ZERO), (0.0, DVec3::Y));
        // The centre itself is finite.
        let (hc, gc) = e.height_grad(DVec3::new(0.0, -r, 0.0));
        assert_eq!(hc, -r);
        assert!(gc.is_finite());
        // 100 km up.
        assert!((e.height(DVec3::new(0.0, 1e5, 0.0)) - 1e5).abs() < 1e-9);
    }

    #[test]
    fn spherical_constructor_checks_its_inputs() {
        assert!(Earth::spherical(DVec3::ZERO, -1.0).is_err());
        assert!(Earth::spherical(DVec3::NAN, 1.0).is_err());
        let e = Earth::spherical(DVec3::ZERO, 2.0).unwrap();
        assert!((e.height(DVec3::new(0.0, 0.0, 3.0)) - 1.0).abs() < 1e-15);
        assert_eq!(Earth::spherical_y(EARTH_RADIUS_M).unwrap(), Earth::standard());
    }
}
