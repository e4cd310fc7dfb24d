//! Cheap escape for paths trapped in a duct, past everything they could meet.
//!
//! In a field that depends only on the distance from a centre C (a height profile over a spherical
//! Earth: [`IndexField::radial_centre`]) the ray equation conserves the angular momentum
//! L = n·(r − C) × dr/ds (Born & Wolf, *Principles of Optics*, §3.2.1: Bouguer's formula
//! n·r·sin z = const is its magnitude). So a path stays in the plane through C normal to L and
//! turns about C always the same way, and its distance r from C obeys a one-dimensional motion:
//! between two turning points (where dr/ds changes sign) it repeats the same r(φ) for ever.
//!
//! The scene's finite geometry — every shape but the spheres centred on C (the ground or sea,
//! which share the field's symmetry) — lies in a cone about C of half-angle α around the axis
//! `a` (through the centre of its bounding box). A path outside that cone whose angle about C
//! grows away from `a` (its tangential direction t = ℓ̂ × û has t·a < 0, with û the unit vector
//! from C, ℓ̂ = û × d̂ the plane normal) cannot reach the cone again before turning half round
//! the planet. If such a path then passes a lower and an upper turning point without meeting a
//! surface, it has completed one period of its radial motion with no concentric sphere in its
//! range, and will repeat it until it has circled the Earth: it is trapped in a duct, and is
//! taken to escape there (along its current direction) instead of being followed round the
//! planet (issue 15: a ray trapped under a mirage's inversion circled the Earth twice, tens of
//! thousands of integrator steps, before it met a surface again).
//!
//! The test costs a few dot products per step and needs no knowledge of the profile.

use crate::geometry::Shape;
use crate::media::refractive_index::IndexField;
use crate::world::World;
use glam::DVec3;

/// Largest half-angle of the cone of finite geometry for which the test is used: beyond it the
/// half-turn argument leaves too little room to be worth it.
const MAX_HALF_ANGLE_RAD: f64 = 1.0;

/// The cone about a radial field's centre that holds the finite geometry.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FarCone {
    /// The field's centre, m.
    pub centre: DVec3,
    /// Unit axis of the cone.
    pub axis: DVec3,
    /// cos α, α the half-angle (with a margin).
    pub cos_half_angle: f64,
}

impl FarCone {
    /// The cone for a medium with index field `field` in `world`: `None` unless the field is
    /// radial and the finite geometry fits a cone of half-angle at most 1 rad about its centre
    /// (or there is no finite geometry at all: then nothing but the concentric spheres can be met,
    /// and the cone is empty, cos α = 2).
    pub fn new(world: &World, field: &IndexField) -> Option<FarCone> {
        let centre = field.radial_centre()?;
        let concentric = |s: &Shape| match s {
            Shape::Sphere(sp) => (sp.center - centre).length() <= 1e-9 * sp.radius.max(1.0),
            _ => false,
        };
        let corners: Vec<DVec3> = world
            .shapes
            .iter()
            .filter(|s| !concentric(s))
            .flat_map(|s| {
                let b = s.bounds();
                (0..8).map(move |i| {
                    DVec3::new(
                        if i & 1 == 0 { b.min.x } else { b.max.x },
                        if i & 2 == 0 { b.min.y } else { b.max.y },
                        if i & 4 == 0 { b.min.z } else { b.max.z },
                    )
                })
            })
            .collect();
        if corners.is_empty() {
            return Some(FarCone { centre, axis: DVec3::Y, cos_half_angle: 2.0 });
        }
        let mid = corners.iter().fold(DVec3::ZERO, |s, c| s + *c) / corners.len() as f64;
        let axis = (mid - centre).try_normalize()?;
        let mut cos_min = 1.0_f64;
        for c in &corners {
            let u = (*c - centre).try_normalize()?;
            cos_min = cos_min.min(u.dot(axis));
        }
        let alpha = cos_min.clamp(-1.0, 1.0).acos() * 1.01 + 1e-6;
        (alpha <= MAX_HALF_ANGLE_RAD).then_some(FarCone { centre, axis, cos_half_angle: alpha.cos() })
    }

    /// Whether a path at `p` going along unit `dir` is outside the cone and turning away from it:
    /// with q = p − C, q·axis < cos α·|q|, and the angular motion (q × d) × q points away from
    /// the axis. (Neither vector needs normalising for the signs: one square root per call, not
    /// two and two divisions; it is called after every integrator step.)
    pub fn receding(&self, p: DVec3, dir: DVec3) -> bool {
        let q = p - self.centre;
        let len = q.length();
        if !(len > 0.0 && len.is_finite()) || q.dot(self.axis) >= self.cos_half_angle * len {
            return false;
        }
        let l = q.cross(dir);
        let l2 = l.length_squared();
        if !(l2 > 0.0 && l2.is_finite()) {
            return false;
        }
        l.cross(q).dot(self.axis) < 0.0
    }

    /// The sign of dr/ds at `p` going along `dir`: whether the path climbs away from the centre.
    pub fn climbing(&self, p: DVec3, dir: DVec3) -> bool {
        (p - self.centre).dot(dir) > 0.0
    }
}

/// Watches a path for one full period of its radial motion while it recedes from the cone.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TrapWatch {
    /// Whether the path climbed at the last observation (`None`: not receding then).
    climbing: Option<bool>,
    /// Turning points seen since the path last started to recede: a lower one (descending to
    /// climbing) and an upper one (climbing to descending).
    lower: bool,
    upper: bool,
}

impl TrapWatch {
    /// Observes the path at `p` going along `dir` (at the end of an integrator step); true when
    /// it is trapped: receding, with a lower and an upper turning point seen while receding.
    pub fn observe(&mut self, cone: &FarCone, p: DVec3, dir: DVec3) -> bool {
        if !cone.receding(p, dir) {
            *self = TrapWatch::default();
            return false;
        }
        let now = cone.climbing(p, dir);
        match self.climbing {
            Some(false) if now => self.lower = true,
            Some(true) if !now => self.upper = true,
            _ => {}
        }
        self.climbing = Some(now);
        self.lower && self.upper
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cone() -> FarCone {
        // Geometry straight up the +y axis from a centre at the origin, within 0.1 rad.
        FarCone { centre: DVec3::ZERO, axis: DVec3::Y, cos_half_angle: 0.1f64.cos() }
    }

    #[test]
    fn receding_means_outside_and_turning_away() {
        let c = cone();
        let p = DVec3::new(0.5f64.sin(), 0.5f64.cos(), 0.0);
        // Tangential motion away from the axis (toward +x, angle from +y grows).
        let away = DVec3::new(0.5f64.cos(), -(0.5f64.sin()), 0.0);
        assert!(c.receding(p, away));
        assert!(!c.receding(p, -away));
        // Inside the cone nothing recedes.
        assert!(!c.receding(DVec3::new(0.01, 1.0, 0.0), away));
        // A radial path has no angular motion.
        assert!(!c.receding(p, p.normalize()));
    }

    #[test]
    fn a_full_radial_period_while_receding_is_a_trap() {
        let c = cone();
        let mut w = TrapWatch::default();
        let at = |phi: f64, up: f64| {
            let u = DVec3::new(phi.sin(), phi.cos(), 0.0);
            let t = DVec3::new(phi.cos(), -phi.sin(), 0.0);
            (u, (t + up * u).normalize())
        };
        let (p, d) = at(0.5, -0.01);
        assert!(!w.observe(&c, p, d));
        let (p, d) = at(0.6, 0.01); // lower turning point passed
        assert!(!w.observe(&c, p, d));
        let (p, d) = at(0.7, 0.02);
        assert!(!w.observe(&c, p, d));
        let (p, d) = at(0.8, -0.01); // upper turning point passed
        assert!(w.observe(&c, p, d));
        // Back inside the cone the watch starts over.
        let (p, d) = at(0.05, -0.01);
        assert!(!w.observe(&c, p, d));
        assert_eq!(w, TrapWatch::default());
    }
}
