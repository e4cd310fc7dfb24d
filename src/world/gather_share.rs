//! How much of a surface photon estimate's disc lies on surfaces that can hold photons.
//!
//! A surface radiance estimate sums the photons within r of x on surfaces facing like x's and
//! divides by the area they could have landed on. Jensen (2001, §7.2) takes that area as π r²,
//! the disc about x in its tangent plane. Where the disc reaches past the surface — into the
//! wall at a room's floor, over a table's edge, under a box standing on the floor — no photon
//! can land on the part beyond, and the estimate is too dark by that part's share: half at a
//! straight edge, three quarters in a corner. The bias shrinks with r (progressive passes shrink
//! it), but at the radii a k-nearest estimate finds it darkens every edge of a room.
//!
//! [`World::gather_share`] measures the share of the disc that does lie on such surfaces, and the
//! estimate divides by π r² times it. Where only one surface comes within r of x (by the BVH's
//! boxes) and it extends a distance r about x ([`crate::geometry::Shape::clearance`]), the share
//! is 1 without a probe. Elsewhere it is the fraction of 32 points spread evenly over the disc —
//! on 8 spokes at 4 radii r √((k + v)/4), k = 0..3, each ring holding a quarter of the disc's
//! area, the spokes turned and v ∈ [0, 1) chosen by hashes of x — at which
//! 1. the straight way from x to the point, lifted `LIFT` r off the tangent plane, meets no
//!    surface that stops light (a wall; glass and index-matched boundaries let photons through),
//!    and
//! 2. a ray down the normal from the lifted point, reaching r below the tangent plane, first
//!    meets (past glass and index-matched boundaries) a diffuse surface facing within 60° of x's
//!    normal, the surfaces the estimate reads photons from.
//!
//! A floor that runs on under a wall (scenes often build rooms that way) is cut at the wall by
//! the first test; a surface that just ends, by the second. One ray along each spoke serves the
//! first test for its four points, so a disc costs at most 8 + 32 ray casts. At one x the share
//! of a disc cut by a straight edge is within about 0.15 of the area's; turned and moved from x
//! to x, the error averages out over an edge, to within 0.003 (`tests/edge_correction.rs`
//! checks both against the circular segment's area).

use super::World;
use crate::geometry::{Aabb, Frame, Ray};
use crate::photon_map::DiscShare;
use crate::rng::splitmix64;
use glam::DVec3;
use std::f64::consts::TAU;

/// Directions (spokes) and rings of the points probed over a disc: 8 × 4 points.
const SPOKES: usize = 8;
const RINGS: usize = 4;

/// How far above the tangent plane the probes travel, as a fraction of the disc's radius: above
/// the sagitta of curved surfaces (r/4 is a sphere's at r = R/2) and below walls.
const LIFT: f64 = 0.25;

/// Photons on surfaces tilted more than this (cosine) from x's normal are not counted by the
/// estimate (the same bound as [`crate::photon_map`]'s surface estimate).
const MIN_NORMAL_COS: f64 = 0.5;

/// Surfaces a probe passes before it gives up and counts its point as off the surface.
const MAX_CROSSINGS: usize = 8;

impl World {
    /// The share (in (0, 1]) of the disc of radius `r` about `x`, in the plane normal to `n`,
    /// that lies on surfaces able to hold photons arriving from `n`'s side (see the module
    /// docs); `x` lies on a surface of the world.
    pub fn gather_share(&self, x: DVec3, n: DVec3, r: f64) -> f64 {
        if r.is_nan() || r <= 0.0 || self.disc_is_clear(x, r) {
            return 1.0;
        }
        let frame = Frame::from_normal(n);
        let (turn, v) = spoke_turn(x);
        let lift = LIFT * r * n;
        let ring = |k: usize| r * ((k as f64 + v) / RINGS as f64).sqrt();
        let mut inside = 0;
        for a in 0..SPOKES {
            let (sin, cos) = (turn + a as f64 * TAU / SPOKES as f64).sin_cos();
            let along = frame.to_world(DVec3::new(cos, sin, 0.0));
            // One ray along the spoke: the rings beyond the first wall it meets are cut off.
            let open = self.first_stop(Ray::new(x + lift, along), ring(RINGS - 1)).map_or(f64::INFINITY, |s| s.2);
            inside +=
                (0..RINGS).take_while(|&k| ring(k) < open).filter(|&k| self.lands(x + ring(k) * along, n, r)).count();
        }
        inside.max(1) as f64 / (SPOKES * RINGS) as f64
    }

    /// Whether one shape alone comes within `r` of `x` (the one `x` lies on) and the disc lies
    /// on it.
    fn disc_is_clear(&self, x: DVec3, r: f64) -> bool {
        let ball = Aabb { min: x - DVec3::splat(r), max: x + DVec3::splat(r) };
        let sole = self.bvh.sole_shape_touching_box(&self.shapes, &ball);
        sole.is_some_and(|p| self.shapes[p as usize].clearance(x) >= r)
    }

    /// Test 2 of the module docs at tangent-plane point `p` (x's disc of radius `r`, normal `n`):
    /// whether a ray down from `p` lifted meets a diffuse surface facing like x's first.
    fn lands(&self, p: DVec3, n: DVec3, r: f64) -> bool {
        match self.first_stop(Ray::new(p + LIFT * r * n, -n), (LIFT + 1.0) * r) {
            Some((prim, normal, _)) => {
                self.material_of(prim).is_some_and(|m| m.is_diffuse()) && normal.dot(n).abs() >= MIN_NORMAL_COS
            }
            None => false,
        }
    }

    /// The first primitive along `ray` within `t_max` that stops light (not glass, not an
    /// index-matched boundary), with its normal there and its distance along the ray.
    fn first_stop(&self, mut ray: Ray, t_max: f64) -> Option<(u32, DVec3, f64)> {
        let start = ray.origin;
        let mut left = t_max;
        for _ in 0..MAX_CROSSINGS {
            let hit = self.bvh.intersect(&self.shapes, &ray, left)?;
            if !self.is_passable(hit.prim) {
                return Some((hit.prim, hit.normal, (hit.point - start).length()));
            }
            left = t_max - (hit.point - start).length();
            ray = Ray::new(hit.spawn_origin(&self.shapes, ray.dir), ray.dir);
        }
        None
    }
}

impl DiscShare for World {
    fn disc_share(&self, x: DVec3, n: DVec3, r: f64) -> f64 {
        self.gather_share(x, n, r)
    }
}

/// The angle, in [0, 2π), the probes' spokes about `x` are turned by, and where in its share of
/// the disc's area each ring lies, in [0, 1): hashes of `x`'s coordinates, so that a straight
/// edge meets the probes at a different angle and radius at each point along it (the share's
/// mean along an edge is then the area's).
fn spoke_turn(x: DVec3) -> (f64, f64) {
    let h = [x.x, x.y, x.z].iter().fold(0u64, |h, c| splitmix64(h ^ c.to_bits()));
    let unit = |bits: u64| (bits >> 11) as f64 / (1u64 << 53) as f64;
    (unit(h) * TAU, unit(splitmix64(h)))
}
