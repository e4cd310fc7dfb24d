//! Leaving a surface: where a new ray starts so that it does not hit the surface it leaves.
//!
//! A computed hit point is only within rounding error of the surface, on either side. A ray
//! spawned from it could therefore find the same surface again at t ≈ 0 ("surface acne"). Following
//! pbrt-v4 §6.8.6 (Pharr, Jakob & Humphreys 2023), the origin is pushed along the normal, to the
//! side the ray leaves towards, by a bound δ on that error, and each coordinate is then rounded
//! away from the surface so that the offset survives the addition:
//!
//! ```text
//! δ = K ε S,   o' = p ± δ n   (sign of n·ω),   K = SPAWN_ERROR_FACTOR,  ε = 2⁻⁵³
//! ```
//!
//! S is the magnitude (∞-norm) of the coordinates the intersection arithmetic works with: at
//! least |p|, and for a shape also its own defining coordinates ([`crate::geometry::Shape::spawn_origin`]).
//! The latter matters when a shape is defined far from the origin but hit near it: the Earth
//! (radius 6.371e6 m, centre (0, −6.371e6, 0)) is hit at |p| ≈ 1 m, but its intersection rounds
//! at the scale of 6.4e6 m, about 1e-9 m; there δ ≈ 1.8e-7 m.
//!
//! The caller spawns from o' and queries hits with t in (0, t_max). Each shape also refuses hits
//! whose t is within its own rounding error of zero, so the offset is a second line of defence.

use super::rounding::{UNIT_ROUNDOFF, max_abs};
use glam::DVec3;

/// K in δ = K ε S. The error of a reprojected hit point is a few ε S, and a shape's own test
/// refuses hits closer than about 40 ε S (the sphere's tangent tolerance of 16 ε r included); K
/// leaves a margin above both.
pub const SPAWN_ERROR_FACTOR: f64 = 128.0;

/// The origin of a ray leaving the surface point `p` (unit normal `n`) in direction `dir`, for a
/// surface whose intersection arithmetic rounds at the coordinate scale `scale` (metres).
pub fn offset_origin(p: DVec3, n: DVec3, dir: DVec3, scale: f64) -> DVec3 {
    let delta = SPAWN_ERROR_FACTOR * UNIT_ROUNDOFF * scale.max(max_abs(p));
    let offset = if n.dot(dir) < 0.0 { -delta * n } else { delta * n };
    let o = p + offset;
    DVec3::new(round_away(o.x, offset.x), round_away(o.y, offset.y), round_away(o.z, offset.z))
}

/// `x` moved one ulp further in the direction of `offset`, so that rounding of p + offset cannot
/// take the point back towards the surface.
fn round_away(x: f64, offset: f64) -> f64 {
    if offset > 0.0 {
        x.next_up()
    } else if offset < 0.0 {
        x.next_down()
    } else {
        x
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn offset_is_on_the_side_of_the_direction_and_scales_with_p() {
        let n = DVec3::Y;
        let p = DVec3::new(3.0, 0.0, -4.0);
        let up = offset_origin(p, n, DVec3::new(0.3, 0.5, 0.0), 0.0);
        let down = offset_origin(p, n, DVec3::new(0.3, -0.5, 0.0), 0.0);
        let delta = SPAWN_ERROR_FACTOR * UNIT_ROUNDOFF * 4.0;
        assert!(up.y >= delta && up.y < 2.0 * delta, "{up}");
        assert!(down.y <= -delta && down.y > -2.0 * delta, "{down}");
        assert_eq!((up.x, up.z), (p.x, p.z));
        let far = offset_origin(p, n, n, 1e6);
        assert!(far.y >= SPAWN_ERROR_FACTOR * UNIT_ROUNDOFF * 1e6, "{far}");
    }
}
