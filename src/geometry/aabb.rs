//! Axis-aligned boxes.

use glam::DVec3;

/// An axis-aligned box, m; empty when `min` exceeds `max` on some axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// Lower corner, m.
    pub min: DVec3,
    /// Upper corner, m.
    pub max: DVec3,
}

impl Aabb {
    /// The empty box: the identity of [`Aabb::union`].
    pub const EMPTY: Aabb = Aabb { min: DVec3::splat(f64::INFINITY), max: DVec3::splat(f64::NEG_INFINITY) };
    /// The smallest box holding both.
    pub fn union(self, o: Aabb) -> Aabb {
        Aabb { min: self.min.min(o.min), max: self.max.max(o.max) }
    }
    /// The smallest box holding this one and `p`.
    pub fn include(self, p: DVec3) -> Aabb {
        Aabb { min: self.min.min(p), max: self.max.max(p) }
    }
    /// Centre, m.
    pub fn centre(&self) -> DVec3 {
        0.5 * (self.min + self.max)
    }
    /// `max − min`, m.
    pub fn diagonal(&self) -> DVec3 {
        self.max - self.min
    }
    /// True when the box holds no point.
    pub fn is_empty(&self) -> bool {
        self.min.x > self.max.x || self.min.y > self.max.y || self.min.z > self.max.z
    }
    /// Surface area 2(dx dy + dy dz + dz dx); zero for an empty box.
    pub fn surface_area(&self) -> f64 {
        if self.is_empty() {
            return 0.0;
        }
        let d = self.diagonal();
        2.0 * (d.x * d.y + d.y * d.z + d.z * d.x)
    }
    /// The box grown by `pad` on every side and then by one ulp outward, so that it still
    /// contains what it contained before rounding.
    pub fn padded(self, pad: f64) -> Aabb {
        let down = |v: DVec3| DVec3::new(v.x.next_down(), v.y.next_down(), v.z.next_down());
        let up = |v: DVec3| DVec3::new(v.x.next_up(), v.y.next_up(), v.z.next_up());
        Aabb { min: down(self.min - DVec3::splat(pad)), max: up(self.max + DVec3::splat(pad)) }
    }
    /// The largest coordinate magnitude in the box.
    pub fn max_abs(&self) -> f64 {
        self.min.abs().max(self.max.abs()).max_element()
    }
    /// Whether `p` lies in the closed box.
    pub fn contains(&self, p: DVec3) -> bool {
        p.cmpge(self.min).all() && p.cmple(self.max).all()
    }
}
