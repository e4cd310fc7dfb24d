//! The part of a segment inside a finite cylinder: the geometry of a photon beam's tube
//! ([`super::photon_beams`]), where an eye segment's gather meets a beam.

use glam::DVec3;

/// How far a direction's squared length may be from 1 and still count as a unit vector.
const UNIT_TOLERANCE: f64 = 1e-6;

/// Below this squared drift across the tube over the part of the segment in the slab, relative
/// to r², the segment is taken as parallel to the tube (a drift of 10⁻⁶ r).
const PARALLEL_DRIFT2: f64 = 1e-12;

/// The part [t0, t1] (0 ≤ t0 < t1 ≤ length) of the segment o + t·dir, 0 ≤ t ≤ length, that lies
/// inside the finite cylinder of radius r around the segment a + s·d, 0 ≤ s ≤ l (unit d; flat
/// ends: the planes s = 0 and s = l), or `None` if it does not enter it.
///
/// The cylinder is convex, so the part is one interval: the intersection of [0, length] with
///
/// - the slab 0 ≤ (o + t dir − a)·d ≤ l: with p = o − a, s(t) = p·d + t (dir·d);
/// - the infinite cylinder |w⊥(t)|² ≤ r², w⊥(t) = (p + t dir) × d the part of o + t dir − a
///   perpendicular to d: the quadratic A t² + 2B t + C ≤ 0 with A = |dir × d|² (= sin²θ),
///   B = (p × d)·(dir × d), C = |p × d|² − r². Its roots are q/A and C/q with
///   q = −(B + sgn(B) √(B² − AC)) (the form without cancellation; Press et al., *Numerical
///   Recipes* 3rd ed. §5.6).
///
/// Cross products keep sin θ accurate for near-parallel segments (dir − (dir·d) d would lose it
/// to cancellation). Where the segment drifts across the tube by less than 10⁻⁶ r over its part
/// in the slab (A·(half that part)² ≤ 10⁻¹² r²), it is taken as parallel: inside over the whole
/// part if the distance at its middle is below r, else nowhere. Everything is computed relative
/// to the tube's start, so coordinates at planetary scale (≈ 6.4·10⁶ m) lose nothing but the
/// rounding of o − a. No NaN or infinity escapes: non-finite inputs, non-positive lengths or
/// radius, or directions that are not unit vectors (squared length within 10⁻⁶ of 1) give `None`,
/// and an interval of zero length is no intersection.
pub fn tube_interval(o: DVec3, dir: DVec3, length: f64, a: DVec3, d: DVec3, l: f64, r: f64) -> Option<(f64, f64)> {
    if !(positive(length) && positive(l) && positive(r) && o.is_finite() && a.is_finite() && is_unit(dir) && is_unit(d))
    {
        return None;
    }
    interval_in_tube(o, dir, length, a, d, l, r)
}

/// [`tube_interval`] for inputs known to be valid (finite, positive lengths and radius, unit
/// directions): what a query tests for each beam of a leaf, whose beams were checked when the
/// map was built and whose segment was checked once.
#[inline]
pub(super) fn interval_in_tube(
    o: DVec3,
    dir: DVec3,
    length: f64,
    a: DVec3,
    d: DVec3,
    l: f64,
    r: f64,
) -> Option<(f64, f64)> {
    let p = o - a;
    let (lo, hi) = slab(p.dot(d), dir.dot(d), l, length)?;
    let (c0, c1) = cylinder(p, dir, d, r, lo, hi)?;
    let (t0, t1) = (lo.max(c0), hi.min(c1));
    (t0 < t1).then_some((t0, t1))
}

/// The t in [0, `length`] where the axial coordinate s0 + c·t lies in [0, l], if any.
fn slab(s0: f64, c: f64, l: f64, length: f64) -> Option<(f64, f64)> {
    if c == 0.0 {
        return (0.0..=l).contains(&s0).then_some((0.0, length));
    }
    let (ta, tb) = (-s0 / c, (l - s0) / c);
    let (lo, hi) = (ta.min(tb).max(0.0), ta.max(tb).min(length));
    (lo < hi).then_some((lo, hi))
}

/// The t where p + t·dir lies within `r` of the line through the origin along `d`, as an
/// interval (possibly reaching beyond [lo, hi], the part of the segment in the slab), if any.
fn cylinder(p: DVec3, dir: DVec3, d: DVec3, r: f64, lo: f64, hi: f64) -> Option<(f64, f64)> {
    let r2 = r * r;
    let (m, n) = (p.cross(d), dir.cross(d));
    let a = n.length_squared();
    let half = 0.5 * (hi - lo);
    if a * half * half <= PARALLEL_DRIFT2 * r2 {
        let mid = (p + (lo + half) * dir).cross(d);
        return (mid.length_squared() < r2).then_some((lo, hi));
    }
    let (b, c) = (m.dot(n), m.length_squared() - r2);
    let disc = b * b - a * c;
    if disc.is_nan() || disc <= 0.0 {
        return None;
    }
    let q = -(b + disc.sqrt().copysign(b));
    let (ra, rb) = (q / a, c / q);
    Some((ra.min(rb), ra.max(rb)))
}

/// Whether `x` is finite and positive.
pub(super) fn positive(x: f64) -> bool {
    x > 0.0 && x.is_finite()
}

/// Whether `v` is a unit vector to within [`UNIT_TOLERANCE`] (false for any non-finite `v`).
pub(super) fn is_unit(v: DVec3) -> bool {
    (v.length_squared() - 1.0).abs() <= UNIT_TOLERANCE
}
