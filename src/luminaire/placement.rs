//! Where a luminaire hangs and which way it points: its frame in the scene.
//!
//! Scenes are Y-up. The luminaire frame (x = C0 = length, y = C90, z = up, nadir −z; see
//! [`super`]) is placed by one of:
//! - nothing: hanging straight down — nadir = −Y, C0 = +X, C90 = −Z;
//! - an aim: the nadir points along `direction` (or toward `look_at`), and C0 lies along the part
//!   of `c0_toward` (default +X; +Z if the nadir is along ±X) perpendicular to the nadir;
//! - Euler angles `rotation_deg = [a, b, c]`: the hanging luminaire turned by a° about the scene's
//!   X axis, then b° about Y, then c° about Z (right-handed, fixed axes: R = R_z(c) R_y(b) R_x(a)).
//!   A street light tilted 10° toward +Z: `rotation_deg = [10, 0, 0]`.

use glam::{DMat3, DVec3};

/// The luminaire frame in the scene: its origin (the photometric centre) and unit axes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement {
    /// The photometric centre, m.
    pub position: DVec3,
    /// C0 (length axis).
    pub x: DVec3,
    /// C90.
    pub y: DVec3,
    /// Up; the nadir is −z.
    pub z: DVec3,
}

impl Placement {
    /// Hanging straight down: nadir −Y, C0 +X, C90 −Z.
    pub fn hanging(position: DVec3) -> Placement {
        Placement { position, x: DVec3::X, y: DVec3::NEG_Z, z: DVec3::Y }
    }

    /// Nadir along the unit vector `nadir`; C0 toward `c0_toward` (see the module docs). Errs when
    /// a given `c0_toward` is parallel to the nadir.
    pub fn aimed(position: DVec3, nadir: DVec3, c0_toward: Option<DVec3>) -> Result<Placement, String> {
        let n = nadir.normalize();
        let hint = c0_toward.unwrap_or(if n.x.abs() > 0.999 { DVec3::Z } else { DVec3::X });
        let x = hint - hint.dot(n) * n;
        if x.length() < 1e-6 * hint.length().max(1e-300) {
            return Err(format!("c0_toward {hint:?} is parallel to the aim {n:?}; C0 must point across the nadir"));
        }
        let x = x.normalize();
        let z = -n;
        Ok(Placement { position, x, y: z.cross(x), z })
    }

    /// The hanging luminaire turned by Euler angles in degrees (module docs).
    pub fn rotated(position: DVec3, rotation_deg: [f64; 3]) -> Placement {
        let [a, b, c] = rotation_deg.map(f64::to_radians);
        let r = DMat3::from_rotation_z(c) * DMat3::from_rotation_y(b) * DMat3::from_rotation_x(a);
        let h = Placement::hanging(position);
        Placement { position, x: r * h.x, y: r * h.y, z: r * h.z }
    }

    /// A direction or offset from the luminaire frame to the scene frame.
    pub fn to_world(&self, local: DVec3) -> DVec3 {
        local.x * self.x + local.y * self.y + local.z * self.z
    }

    /// A direction or offset from the scene frame to the luminaire frame.
    pub fn to_local(&self, world: DVec3) -> DVec3 {
        DVec3::new(world.dot(self.x), world.dot(self.y), world.dot(self.z))
    }

    /// Angle between the luminaire's nadir and the scene's straight down (−Y), degrees: the tilt
    /// at which LM-63 tilt factors are read.
    pub fn tilt_deg(&self) -> f64 {
        (-self.z).dot(DVec3::NEG_Y).clamp(-1.0, 1.0).acos().to_degrees()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn orthonormal_right_handed(p: &Placement) -> bool {
        let ok = |a: DVec3, b: DVec3| a.dot(b).abs() < 1e-12;
        ok(p.x, p.y) && ok(p.y, p.z) && ok(p.x, p.z) && (p.x.cross(p.y) - p.z).length() < 1e-12
    }

    #[test]
    fn hanging_points_down_with_c0_along_x() {
        let p = Placement::hanging(DVec3::new(1.0, 3.0, 0.0));
        assert!(orthonormal_right_handed(&p));
        assert_eq!(p.to_world(DVec3::NEG_Z), DVec3::NEG_Y);
        assert_eq!(p.tilt_deg(), 0.0);
        assert_eq!(p.to_local(p.to_world(DVec3::new(0.1, 0.2, 0.3))), DVec3::new(0.1, 0.2, 0.3));
    }

    #[test]
    fn aiming_sets_the_nadir_and_keeps_c0_across_it() {
        let n = DVec3::new(1.0, -1.0, 0.0).normalize();
        let p = Placement::aimed(DVec3::ZERO, n, None).unwrap();
        assert!(orthonormal_right_handed(&p));
        assert!((p.to_world(DVec3::NEG_Z) - n).length() < 1e-12);
        assert!((p.tilt_deg() - 45.0).abs() < 1e-9);
        let p = Placement::aimed(DVec3::ZERO, DVec3::NEG_Y, Some(DVec3::Z)).unwrap();
        assert!((p.x - DVec3::Z).length() < 1e-12);
        assert!(Placement::aimed(DVec3::ZERO, DVec3::NEG_Y, Some(DVec3::Y)).is_err());
        assert!(orthonormal_right_handed(&Placement::aimed(DVec3::ZERO, DVec3::X, None).unwrap()));
    }

    #[test]
    fn euler_angles_turn_about_fixed_scene_axes_in_order() {
        // 90° about X turns the nadir (−Y) to −Z... right-handed: R_x(90°) maps −Y to −Z.
        let p = Placement::rotated(DVec3::ZERO, [90.0, 0.0, 0.0]);
        assert!((p.to_world(DVec3::NEG_Z) - DVec3::NEG_Z).length() < 1e-12);
        // Then 90° about Y maps −Z to −X.
        let p = Placement::rotated(DVec3::ZERO, [90.0, 90.0, 0.0]);
        assert!((p.to_world(DVec3::NEG_Z) - DVec3::NEG_X).length() < 1e-12);
        assert!(orthonormal_right_handed(&p));
        // A pure turn about Y spins C0 in the floor plane without tilting.
        let p = Placement::rotated(DVec3::ZERO, [0.0, 90.0, 0.0]);
        assert!((p.x - DVec3::NEG_Z).length() < 1e-12 && p.tilt_deg() < 1e-9);
    }
}
