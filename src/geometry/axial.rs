//! Folding space about an axis: the rotation that carries a point into one reference half-plane.
//!
//! Where a scene does not change under rotation about an axis — a round Earth, an atmosphere
//! stratified in height above it, and the sun as its only light, about the line through the
//! Earth's centre along the sunlight — so does the light in it: L(R_φ x, R_φ ω) = L(x, ω) for
//! every rotation R_φ about that axis. A point x then stands for its whole ring, and a photon
//! stored anywhere on the ring tells as much about x as one stored beside it. Folding maps x to
//! the point of its ring in the half-plane spanned by the axis `a` and a reference direction
//! `e₁` ⊥ `a`:
//!
//! x − c = z a + ρ (cos φ e₁ + sin φ e₂),   fold(x) = c + z a + ρ e₁,
//!
//! with e₂ = a × e₁, ρ ≥ 0, and a direction ω at x is carried by the same rotation, R_{−φ}. The
//! rotation keeps every distance and angle, so a photon's direction folded with its own point
//! and a query's folded with its own meet at the angle they meet at when the photon's ring is
//! turned to the query. On the axis (ρ = 0) φ is taken as 0.

use glam::DVec3;

/// The fold about an axis through `centre` along the unit vector `axis` (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AxialFold {
    /// A point of the axis (the Earth's centre), m.
    pub centre: DVec3,
    /// Unit vector along the axis (toward the sun).
    pub axis: DVec3,
    /// The reference direction e₁ ⊥ axis: folded points have ρ along it.
    e1: DVec3,
    /// e₂ = axis × e₁.
    e2: DVec3,
}

impl AxialFold {
    /// The fold about the line through `centre` along `axis` (normalised here; `None` if it is
    /// zero or not finite).
    pub fn new(centre: DVec3, axis: DVec3) -> Option<AxialFold> {
        let axis = axis.try_normalize()?;
        let frame = super::Frame::from_normal(axis);
        Some(AxialFold { centre, axis, e1: frame.s, e2: axis.cross(frame.s) })
    }

    /// (z, ρ): the position of `x` along the axis and its distance from it, m.
    pub fn coordinates(&self, x: DVec3) -> (f64, f64) {
        let d = x - self.centre;
        let z = d.dot(self.axis);
        (z, d.dot(self.e1).hypot(d.dot(self.e2)))
    }

    /// cos φ and sin φ of `x`'s azimuth about the axis from e₁ (1, 0 on the axis).
    fn azimuth(&self, x: DVec3) -> (f64, f64) {
        let d = x - self.centre;
        let (u, v) = (d.dot(self.e1), d.dot(self.e2));
        let rho = u.hypot(v);
        if rho > 0.0 { (u / rho, v / rho) } else { (1.0, 0.0) }
    }

    /// `x` turned about the axis into the reference half-plane.
    pub fn point(&self, x: DVec3) -> DVec3 {
        let (z, rho) = self.coordinates(x);
        self.centre + z * self.axis + rho * self.e1
    }

    /// The direction `w` at `x`, turned with `x` into the reference half-plane.
    pub fn direction(&self, x: DVec3, w: DVec3) -> DVec3 {
        let (c, s) = self.azimuth(x);
        let (a, u, v) = (w.dot(self.axis), w.dot(self.e1), w.dot(self.e2));
        // R_{−φ}: (u, v) → (u cos φ + v sin φ, −u sin φ + v cos φ).
        a * self.axis + (u * c + v * s) * self.e1 + (v * c - u * s) * self.e2
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::{Rng, Stream};
    use crate::sampling::uniform_sphere;

    fn fold() -> AxialFold {
        AxialFold::new(DVec3::new(1.0, -6_371_000.0, 2.0), DVec3::new(0.3, 0.5, -0.8)).expect("an axis")
    }

    #[test]
    fn folding_keeps_distances_to_the_axis_and_angles_between_directions() {
        let f = fold();
        let mut rng = Rng::for_task(7, Stream::Test, 0);
        for _ in 0..1000 {
            let x = f.centre + 7e6 * uniform_sphere(rng.uniform2()) * rng.uniform();
            let (w1, w2) = (uniform_sphere(rng.uniform2()), uniform_sphere(rng.uniform2()));
            let y = f.point(x);
            assert!(((y - f.centre).length() / (x - f.centre).length() - 1.0).abs() < 1e-12);
            let (zx, rx) = f.coordinates(x);
            let (zy, ry) = f.coordinates(y);
            assert!((zx - zy).abs() < 1e-6 && (rx - ry).abs() < 1e-6);
            assert!((y - f.centre).dot(f.e2).abs() < 1e-6, "folded points lie in the half-plane");
            assert!((y - f.centre).dot(f.e1) >= -1e-6);
            let (v1, v2) = (f.direction(x, w1), f.direction(x, w2));
            assert!((v1.dot(v2) - w1.dot(w2)).abs() < 1e-12, "angles between directions are kept");
            assert!((v1.dot(f.axis) - w1.dot(f.axis)).abs() < 1e-12);
            // The radial direction at x (away from the axis) folds to e₁.
            let radial = (x - f.centre - zx * f.axis) / rx;
            assert!((f.direction(x, radial) - f.e1).length() < 1e-9);
        }
    }

    #[test]
    fn a_point_already_in_the_half_plane_stays_put() {
        let f = fold();
        let x = f.centre + 3e6 * f.axis + 5e6 * f.e1;
        assert!((f.point(x) - x).length() < 1e-6);
        let w = DVec3::new(0.6, 0.0, 0.8);
        assert!((f.direction(x, w) - w).length() < 1e-12);
    }

    #[test]
    fn points_on_the_axis_fold_to_themselves() {
        let f = fold();
        let x = f.centre - 2e6 * f.axis;
        assert!(f.coordinates(x).1 < 1e-6);
        assert!((f.point(x) - x).length() < 1e-6);
        assert!(AxialFold::new(DVec3::ZERO, DVec3::ZERO).is_none());
    }
}
