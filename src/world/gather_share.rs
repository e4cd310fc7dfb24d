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
//! is 1 without a probe. Elsewhere it is the fraction of `PROBES` points spread evenly over the disc
//! (a Vogel spiral: point j at radius r √((j + ½)/M), turned by the golden angle each time, the
//! whole spiral turned by an angle hashed from x) at which
//! 1. the straight way from x to the point, lifted `LIFT` r off the tangent plane, meets no
//!    surface that stops light (a wall; glass and index-matched boundaries let photons through),
//!    and
//! 2. a ray down the normal from the lifted point, reaching r below the tangent plane, first
//!    meets (past glass and index-matched boundaries) a diffuse surface facing within 60° of x's
//!    normal, the surfaces the estimate reads photons from.
//!
//! A floor that runs on under a wall (scenes often build rooms that way) is cut at the wall by
//! the first test; a surface that just ends, by the second. With M = 32 points the share of a
//! disc cut by a straight edge is within about 0.06 of the area's at one x; turned by an angle
//! that varies from x to x, the error averages out over an edge (`tests/edge_correction.rs`
//! checks both against the circular segment's area).

use super::World;
use crate::geometry::{Aabb, Frame, Ray};
use crate::photon_map::DiscShare;
use crate::rng::splitmix64;
use glam::DVec3;

/// Points probed over a disc.
const PROBES: usize = 32;

/// How far above the tangent plane the probes travel, as a fraction of the disc's radius: above
/// the sagitta of curved surfaces (r/4 is a sphere's at r = R/2) and below walls.
const LIFT: f64 = 0.25;

/// Photons on surfaces tilted more than this (cosine) from x's normal are not counted by the
/// estimate (the same bound as [`crate::photon_map`]'s surface estimate).
const MIN_NORMAL_COS: f64 = 0.5;

/// Surfaces a probe passes before it gives up and counts its point as off the surface.
const MAX_CROSSINGS: usize = 8;

/// The golden angle π (3 − √5), rad.
const GOLDEN_ANGLE: f64 = 2.399_963_229_728_653;

impl World {
    /// The share (in (0, 1]) of the disc of radius `r` about `x`, in the plane normal to `n`,
    /// that lies on surfaces able to hold photons arriving from `n`'s side (see the module
    /// docs); `x` lies on a surface of the world.
    pub fn gather_share(&self, x: DVec3, n: DVec3, r: f64) -> f64 {
        if r.is_nan() || r <= 0.0 || self.disc_is_clear(x, r) {
            return 1.0;
        }
        let frame = Frame::from_normal(n);
        let turn = spiral_turn(x);
        let inside = (0..PROBES)
            .filter(|&j| {
                let rho = r * ((j as f64 + 0.5) / PROBES as f64).sqrt();
                let (sin, cos) = (turn + j as f64 * GOLDEN_ANGLE).sin_cos();
                self.probe_lands(x, n, frame.to_world(DVec3::new(rho * cos, rho * sin, 0.0)), r)
            })
            .count();
        inside.max(1) as f64 / PROBES as f64
    }

    /// Whether one shape alone comes within `r` of `x` (the one `x` lies on) and the disc lies
    /// on it.
    fn disc_is_clear(&self, x: DVec3, r: f64) -> bool {
        let ball = Aabb { min: x - DVec3::splat(r), max: x + DVec3::splat(r) };
        let sole = self.bvh.sole_shape_touching_box(&self.shapes, &ball);
        sole.is_some_and(|p| self.shapes[p as usize].clearance(x) >= r)
    }

    /// Whether a photon could land at tangent offset `u` from `x` (tests 1 and 2 of the
    /// module docs).
    fn probe_lands(&self, x: DVec3, n: DVec3, u: DVec3, r: f64) -> bool {
        let lift = LIFT * r * n;
        let reach = u.length();
        if reach > 0.0 && self.first_stop(Ray::new(x + lift, u / reach), reach).is_some() {
            return false;
        }
        match self.first_stop(Ray::new(x + lift + u, -n), (LIFT + 1.0) * r) {
            Some((prim, normal)) => {
                self.material_of(prim).is_some_and(|m| m.is_diffuse()) && normal.dot(n).abs() >= MIN_NORMAL_COS
            }
            None => false,
        }
    }

    /// The first primitive along `ray` within `t_max` that stops light (not glass, not an
    /// index-matched boundary), with its normal there.
    fn first_stop(&self, mut ray: Ray, mut t_max: f64) -> Option<(u32, DVec3)> {
        for _ in 0..MAX_CROSSINGS {
            let hit = self.bvh.intersect(&self.shapes, &ray, t_max)?;
            if !self.is_passable(hit.prim) {
                return Some((hit.prim, hit.normal));
            }
            t_max -= hit.t;
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

/// The angle, in [0, 2π), the probe spiral about `x` is turned by: a hash of `x`'s coordinates,
/// so that a straight edge meets the spiral at a different angle at each point along it.
fn spiral_turn(x: DVec3) -> f64 {
    let h = [x.x, x.y, x.z].iter().fold(0u64, |h, c| splitmix64(h ^ c.to_bits()));
    (h >> 11) as f64 / (1u64 << 53) as f64 * std::f64::consts::TAU
}
