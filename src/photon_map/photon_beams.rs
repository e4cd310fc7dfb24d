//! Photon beams: each photon's straight flight through a medium kept whole as a segment, blurred
//! into a finite cylinder ("tube"), and the tubes an eye segment passes through.
//!
//! Progressive photon beams (Jarosz, Nowrouzezahrai, Thomas, Sloan & Zwicker 2011) store a
//! photon's flight from one event to the next as a beam b (origin a_b, unit direction d_b,
//! length l_b, power Φ_b) instead of a point at its end. Blurring each beam across itself with
//! the 2-D box kernel 1/(π r_b²) turns it into a tube of radius r_b with flat ends (the planes
//! across it at s = 0 and s = l_b). The radiance an eye segment of length s gathers is then
//!
//! L ≈ Σ_b Φ_b σ_s f(θ_b) T_eye(t_b) · inside_b / (π r_b²),
//!
//! inside_b the length of the eye segment within b's tube and t_b the middle of that part (the
//! caller evaluates it; this file finds the tubes, [`PhotonBeamMap::query`]). It is the
//! track-length estimator of fluence (Σ_b Φ_b × length of b within dV, over dV) smoothed by the
//! tube kernel: the fluence integrated along the eye segment is Σ_b Φ_b |S ∩ T_b| / (π r_b²),
//! whose expectation over beam positions is exact for any radii (each beam's kernel integrates
//! to its length over space; see the test `inside_lengths_measure_beam_length_density`). Unlike
//! the beam × beam estimate with a 1-D blur of Jarosz, Nowrouzezahrai, Sadeghi & Jensen (2011),
//! whose kernel carries 1/sin θ, it has no singularity where the two segments are parallel: then
//! inside_b is the overlap of their axial ranges, at most l_b.
//!
//! The tubes sit in a binary bounding volume hierarchy (split along the longest axis where the
//! surface area heuristic puts it, leaves of at most [`LEAF_BEAMS`] beams, boxes as f32 relative
//! to the map's centre rounded outward, 32 bytes a node); a query descends through the boxes its
//! segment crosses and cuts the segment with each tube of a leaf ([`tube_interval`]). The
//! renderer hands it pieces of the flights a few tube radii long ([`super::pieces`]), whose
//! flat-ended tubes tile their flight's.
//!
//! # References
//! - W. Jarosz, D. Nowrouzezahrai, R. Thomas, P.-P. Sloan and M. Zwicker (2011), "Progressive
//!   photon beams", ACM Transactions on Graphics 30(6), 181.
//! - W. Jarosz, D. Nowrouzezahrai, I. Sadeghi and H. W. Jensen (2011), "A comprehensive theory of
//!   volumetric radiance estimation using photon points and beams", ACM Transactions on Graphics
//!   30(1), 5.

use super::PhotonPath;
use super::beam::crosses;
pub use super::tube::tube_interval;
use super::tube::{interval_in_tube, is_unit, positive};
use crate::geometry::rounding::{gamma, max_abs};
use glam::DVec3;
use rayon::prelude::*;

/// Most beams in a leaf of the hierarchy.
pub const LEAF_BEAMS: usize = 4;

/// Bytes a [`PhotonBeamMap`] holds per beam at most: the beam, its radius, its two indices and
/// a node of the hierarchy (a binary tree over leaves of at least one beam has fewer nodes than
/// twice its beams; the leaves hold about half of them).
pub const BYTES_PER_BEAM: usize = size_of::<PhotonBeam>() + size_of::<f64>() + 2 * size_of::<u32>() + 2 * 32;

/// Deepest traversal stack a query needs: the hierarchy splits by the surface area heuristic for
/// at most [`SAH_LEVELS`] levels, then at the median, so fewer than 2³² beams in leaves of at
/// most 4 reach a leaf after at most 64 + 31 splits, and the stack holds one node per split.
const STACK: usize = 128;

/// Levels of the hierarchy split by the surface area heuristic (each split leaves at least a
/// sixteenth on a side); deeper ones split at the median.
const SAH_LEVELS: usize = 64;

/// One straight flight of a photon through a medium (a whole flight, or one chord of a curved one).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PhotonBeam {
    /// Start, m.
    pub origin: DVec3,
    /// Unit direction of travel.
    pub dir: DVec3,
    /// Length, m (> 0 and finite for a stored beam).
    pub length: f64,
    /// The photon's wavelength, nm.
    pub wavelength_nm: f64,
    /// The photon's power along the flight, W.
    pub power_w: f64,
    /// What it met before this flight.
    pub path: PhotonPath,
    /// Index of the medium it flies through.
    pub medium: u32,
}

impl PhotonBeam {
    /// Its end, m.
    pub fn end(&self) -> DVec3 {
        self.origin + self.length * self.dir
    }

    /// Bytes of a beam on the wire ([`PhotonBeam::to_le_bytes`]): nine f64, the path, the medium.
    pub const BYTES: usize = 9 * 8 + 1 + 4;

    /// The beam as little-endian bytes: origin, direction, length, wavelength and power as f64,
    /// the path as one byte (0 direct, 1 specular, 2 diffuse), the medium as u32. Every bit is
    /// kept: a beam sent between ranks is the beam.
    pub fn to_le_bytes(&self) -> [u8; Self::BYTES] {
        let mut out = [0u8; Self::BYTES];
        let values = [
            self.origin.x,
            self.origin.y,
            self.origin.z,
            self.dir.x,
            self.dir.y,
            self.dir.z,
            self.length,
            self.wavelength_nm,
            self.power_w,
        ];
        for (chunk, v) in out.chunks_exact_mut(8).zip(values) {
            chunk.copy_from_slice(&v.to_le_bytes());
        }
        out[72] = match self.path {
            PhotonPath::Direct => 0,
            PhotonPath::Specular => 1,
            PhotonPath::Diffuse => 2,
        };
        out[73..].copy_from_slice(&self.medium.to_le_bytes());
        out
    }

    /// The beam [`PhotonBeam::to_le_bytes`] wrote (`bytes` at least [`PhotonBeam::BYTES`] long);
    /// a path byte above 2 reads as diffuse.
    pub fn from_le_bytes(bytes: &[u8]) -> PhotonBeam {
        let f = |i: usize| {
            let mut b = [0u8; 8];
            b.copy_from_slice(&bytes[8 * i..8 * i + 8]);
            f64::from_le_bytes(b)
        };
        let mut m = [0u8; 4];
        m.copy_from_slice(&bytes[73..77]);
        PhotonBeam {
            origin: DVec3::new(f(0), f(1), f(2)),
            dir: DVec3::new(f(3), f(4), f(5)),
            length: f(6),
            wavelength_nm: f(7),
            power_w: f(8),
            path: match bytes[72] {
                0 => PhotonPath::Direct,
                1 => PhotonPath::Specular,
                _ => PhotonPath::Diffuse,
            },
            medium: u32::from_le_bytes(m),
        }
    }
}

/// A beam whose tube an eye segment passes through.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TubeHit {
    /// The beam (index into the map's beams, in the order given to [`PhotonBeamMap::new`]).
    pub index: u32,
    /// Middle of the part of the eye segment inside the tube, m from the segment's start.
    pub t: f64,
    /// Length of that part, m (> 0).
    pub inside_m: f64,
    /// The tube's squared radius, m².
    pub r2: f64,
}

/// A node of the hierarchy: 32 bytes.
#[derive(Clone, Copy, Debug)]
struct Node {
    /// Bounds of its tubes relative to the map's centre (min xyz, max xyz), rounded outward.
    bounds: [f32; 6],
    /// A leaf: the stored position of its first beam. Otherwise: its second child (the
    /// first child is the next node).
    first: u32,
    /// A leaf: how many beams it holds (≥ 1). Otherwise 0.
    count: u32,
}

/// Photon beams with their tube radii and a bounding volume hierarchy over the tubes.
///
/// The beams are stored in the hierarchy's leaf order (those that can never be hit last), so a
/// leaf's beams are consecutive in memory and leaves near in the tree are near in memory; `index`
/// and `slot` translate between that order and the order given.
#[derive(Clone, Debug)]
pub struct PhotonBeamMap {
    /// The beams, leaf by leaf.
    beams: Vec<PhotonBeam>,
    /// Tube radius of each, m.
    radii: Vec<f64>,
    /// Each stored beam's index in the order given.
    index: Vec<u32>,
    /// Where the beam of each given index is stored.
    slot: Vec<u32>,
    /// The point node bounds are relative to, m.
    centre: DVec3,
    /// The hierarchy, depth first (root first; empty when no beam can be hit).
    nodes: Vec<Node>,
}

impl PhotonBeamMap {
    /// Beams with their tube radii (one per beam, m, > 0), and the hierarchy over them (built
    /// sequentially after computing the tubes' boxes in parallel; the result does not depend on
    /// the thread count).
    ///
    /// Beams with non-finite or non-positive length or radius, a non-finite origin, or a
    /// direction that is not a unit vector (squared length within 10⁻⁶ of 1) are kept but never
    /// hit.
    ///
    /// # Panics
    /// If `radii` does not hold one radius per beam, or there are 2³² beams or more.
    pub fn new(mut beams: Vec<PhotonBeam>, mut radii: Vec<f64>) -> PhotonBeamMap {
        assert_eq!(beams.len(), radii.len(), "one tube radius per photon beam");
        assert!(u32::try_from(beams.len()).is_ok(), "fewer than 2^32 photon beams");
        let (hit, never): (Vec<u32>, Vec<u32>) =
            (0..beams.len() as u32).partition(|&i| hittable(&beams[i as usize], radii[i as usize]));
        let centre = centre_of(&beams, &radii, &hit);
        let mut items: Vec<Item> = hit
            .par_iter()
            .map(|&i| Item { bounds: tube_box(&beams[i as usize], radii[i as usize], centre), index: i })
            .collect();
        let mut nodes = Vec::with_capacity(items.len().div_ceil(LEAF_BEAMS) * 2);
        if !items.is_empty() {
            let depth = build(&mut items, 0, &mut nodes, 0);
            assert!(depth < STACK, "hierarchy depth {depth} within the query stack");
        }
        let index: Vec<u32> = items.iter().map(|item| item.index).chain(never).collect();
        let mut slot = vec![0u32; index.len()];
        for (k, &i) in index.iter().enumerate() {
            slot[i as usize] = k as u32;
        }
        gather(&mut beams, &index);
        gather(&mut radii, &index);
        PhotonBeamMap { beams, radii, index, slot, centre, nodes }
    }

    /// Number of beams (including those that are never hit).
    pub fn len(&self) -> usize {
        self.beams.len()
    }

    /// Whether the map holds no beam.
    pub fn is_empty(&self) -> bool {
        self.beams.is_empty()
    }

    /// Beam `i` (in the order given to [`PhotonBeamMap::new`]).
    pub fn beam(&self, i: u32) -> &PhotonBeam {
        &self.beams[self.slot[i as usize] as usize]
    }

    /// Tube radius of beam `i`, m.
    pub fn radius(&self, i: u32) -> f64 {
        self.radii[self.slot[i as usize] as usize]
    }

    /// Bytes held (by capacity).
    pub fn memory_bytes(&self) -> usize {
        size_of::<Self>()
            + self.beams.capacity() * size_of::<PhotonBeam>()
            + self.radii.capacity() * size_of::<f64>()
            + self.nodes.capacity() * size_of::<Node>()
            + (self.index.capacity() + self.slot.capacity()) * size_of::<u32>()
    }

    /// Total length of the beams, m (of those whose length is finite and positive).
    pub fn total_length_m(&self) -> f64 {
        self.beams.iter().map(|b| b.length).filter(|&l| positive(l)).sum()
    }

    /// Every beam whose tube the segment from `o` along unit `dir` of length `length` passes
    /// through, into `hits` (cleared first), sorted by `t` then `index`; each with the part of the
    /// segment inside the tube ([`tube_interval`]). A segment with a non-finite or non-positive
    /// length, a non-finite point, or a direction that is not a unit vector (squared length
    /// within 10⁻⁶ of 1) finds none.
    ///
    /// Stack-based descent through the nodes whose box the segment crosses (slab test in f64,
    /// relative to the map's centre).
    pub fn query(&self, o: DVec3, dir: DVec3, length: f64, hits: &mut Vec<TubeHit>) {
        hits.clear();
        if !(positive(length) && o.is_finite() && is_unit(dir)) || self.nodes.is_empty() {
            return;
        }
        let rel = o - self.centre;
        let inv = dir.recip();
        let mut stack = [0u32; STACK];
        let mut sp = 0;
        let mut n = 0u32;
        loop {
            let node = &self.nodes[n as usize];
            if crosses(&node.bounds, rel, inv, length) {
                if node.count == 0 {
                    stack[sp] = node.first;
                    sp += 1;
                    n += 1;
                    continue;
                }
                self.leaf(node, o, dir, length, hits);
            }
            if sp == 0 {
                break;
            }
            sp -= 1;
            n = stack[sp];
        }
        hits.sort_unstable_by(|a, b| a.t.total_cmp(&b.t).then(a.index.cmp(&b.index)));
    }

    /// The tubes of leaf `node` the segment passes through, onto `hits`.
    fn leaf(&self, node: &Node, o: DVec3, dir: DVec3, length: f64, hits: &mut Vec<TubeHit>) {
        let first = node.first as usize;
        for k in first..first + node.count as usize {
            let (b, r) = (&self.beams[k], self.radii[k]);
            if let Some((t0, t1)) = interval_in_tube(o, dir, length, b.origin, b.dir, b.length, r) {
                hits.push(TubeHit { index: self.index[k], t: 0.5 * (t0 + t1), inside_m: t1 - t0, r2: r * r });
            }
        }
    }
}

/// Reorders `v` in place so that its k-th element is the one that was at `from[k]` (`from` a
/// permutation of 0..v.len()), by following the permutation's cycles.
fn gather<T: Copy>(v: &mut [T], from: &[u32]) {
    let mut done = vec![false; v.len()];
    for start in 0..v.len() {
        if done[start] {
            continue;
        }
        let first = v[start];
        let mut k = start;
        loop {
            done[k] = true;
            let src = from[k] as usize;
            if src == start {
                v[k] = first;
                break;
            }
            v[k] = v[src];
            k = src;
        }
    }
}

/// Whether beam `b` with tube radius `r` can be hit.
fn hittable(b: &PhotonBeam, r: f64) -> bool {
    positive(b.length) && positive(r) && b.origin.is_finite() && is_unit(b.dir)
}

/// The bounding box of no tube: every slab test fails.
const EMPTY: [f32; 6] =
    [f32::INFINITY, f32::INFINITY, f32::INFINITY, f32::NEG_INFINITY, f32::NEG_INFINITY, f32::NEG_INFINITY];

/// The centre of the box around the listed beams' tubes (exact min and max, so it does not
/// depend on the thread count); zero when none is listed.
fn centre_of(beams: &[PhotonBeam], radii: &[f64], order: &[u32]) -> DVec3 {
    let empty = || (DVec3::INFINITY, DVec3::NEG_INFINITY);
    let (lo, hi) = order
        .par_iter()
        .map(|&i| segment_box(&beams[i as usize], radii[i as usize], 0.0))
        .fold(empty, |(lo, hi), (a, b)| (lo.min(a), hi.max(b)))
        .reduce(empty, |(l0, h0), (l1, h1)| (l0.min(l1), h0.max(h1)));
    if order.is_empty() { DVec3::ZERO } else { 0.5 * (lo + hi) }
}

/// The box around beam `b`'s segment, inflated by `r` and `pad` on every axis.
fn segment_box(b: &PhotonBeam, r: f64, pad: f64) -> (DVec3, DVec3) {
    let (p, q) = (b.origin, b.end());
    (p.min(q) - (r + pad), p.max(q) + (r + pad))
}

/// The box of beam `b`'s tube relative to `centre` in f32, rounded outward. The tube lies within
/// its segment's box inflated by r on every axis; a further pad of γ₁₆ times the coordinates'
/// size covers the rounding of the box and of a query's slab test.
fn tube_box(b: &PhotonBeam, r: f64, centre: DVec3) -> [f32; 6] {
    let pad = gamma(16) * (max_abs(b.origin) + max_abs(b.end()) + max_abs(centre) + r);
    let (lo, hi) = segment_box(b, r, pad);
    let (lo, hi) = (lo - centre, hi - centre);
    [down(lo.x), down(lo.y), down(lo.z), up(hi.x), up(hi.y), up(hi.z)]
}

/// The largest f32 at most `x`.
fn down(x: f64) -> f32 {
    let f = x as f32;
    if f64::from(f) > x { f.next_down() } else { f }
}

/// The smallest f32 at least `x`.
fn up(x: f64) -> f32 {
    let f = x as f32;
    if f64::from(f) < x { f.next_up() } else { f }
}

/// A beam's tube box while the hierarchy is built: the build permutes these in place, so each
/// pass over a node's beams reads consecutive memory.
#[derive(Clone, Copy, Debug)]
struct Item {
    /// [`tube_box`] of the beam.
    bounds: [f32; 6],
    /// The beam's index.
    index: u32,
}

/// Builds the subtree over `items` (whose first is at `offset` in the map's stored order) onto
/// `nodes`, depth first; returns its depth (1 for a leaf).
///
/// Sorts the items by centroid along the longest axis of the node's box (ties fall to the beam
/// index, so each split is one definite partition, and the build, sequential, involves no thread
/// count) and splits where [`sah_split`] puts it, at the median from [`SAH_LEVELS`] down (`level`
/// is this node's depth, 0 at the root).
fn build(items: &mut [Item], offset: usize, nodes: &mut Vec<Node>, level: usize) -> usize {
    let bounds = union(items);
    let at = nodes.len();
    nodes.push(Node { bounds, first: offset as u32, count: items.len() as u32 });
    if items.len() <= LEAF_BEAMS {
        return 1;
    }
    let axis = longest_axis(&bounds);
    let key = |i: &Item| i.bounds[axis] + i.bounds[axis + 3];
    items.sort_unstable_by(|i, j| key(i).total_cmp(&key(j)).then(i.index.cmp(&j.index)));
    let mid = if level < SAH_LEVELS { sah_split(items) } else { items.len() / 2 };
    let (left, right) = items.split_at_mut(mid);
    let dl = build(left, offset, nodes, level + 1);
    let second = nodes.len() as u32;
    let dr = build(right, offset + mid, nodes, level + 1);
    nodes[at].first = second;
    nodes[at].count = 0;
    1 + dl.max(dr)
}

/// Where to split `items`, sorted along an axis: the cut that minimises the surface area
/// heuristic Σ area(box of a side) × count(side) (MacDonald & Booth 1990), tried at 16 evenly
/// spaced ranks; tubes of very different radii then fall into different subtrees, so a thin
/// tube's query does not descend into boxes swollen by fat ones.
fn sah_split(items: &[Item]) -> usize {
    const CUTS: usize = 16;
    let n = items.len();
    let rank = |k: usize| n * k / CUTS;
    // The boxes of the 16 runs between the ranks, then of every prefix and suffix of runs.
    let runs: Vec<[f32; 6]> = (0..CUTS).map(|k| union(&items[rank(k)..rank(k + 1)])).collect();
    let join = |u: &[f32; 6], b: &[f32; 6]| -> [f32; 6] {
        std::array::from_fn(|a| if a < 3 { u[a].min(b[a]) } else { u[a].max(b[a]) })
    };
    let mut before = vec![EMPTY; CUTS + 1];
    let mut after = vec![EMPTY; CUTS + 1];
    for k in 0..CUTS {
        before[k + 1] = join(&before[k], &runs[k]);
        after[CUTS - 1 - k] = join(&after[CUTS - k], &runs[CUTS - 1 - k]);
    }
    let mut best = (f64::INFINITY, n / 2);
    for k in 1..CUTS {
        let mid = rank(k);
        if mid == 0 || mid >= n {
            continue;
        }
        let cost = area(&before[k]) * mid as f64 + area(&after[k]) * (n - mid) as f64;
        if cost < best.0 {
            best = (cost, mid);
        }
    }
    best.1
}

/// Half the surface area of box `b`.
fn area(b: &[f32; 6]) -> f64 {
    let e: [f64; 3] = std::array::from_fn(|a| (f64::from(b[a + 3]) - f64::from(b[a])).max(0.0));
    e[0] * e[1] + e[1] * e[2] + e[2] * e[0]
}

/// The box around the boxes of `items` (exact: min and max of f32).
fn union(items: &[Item]) -> [f32; 6] {
    items.iter().fold(EMPTY, |u, item| {
        let b = &item.bounds;
        std::array::from_fn(|a| if a < 3 { u[a].min(b[a]) } else { u[a].max(b[a]) })
    })
}

/// The axis along which box `b` is longest (the first of equals).
fn longest_axis(b: &[f32; 6]) -> usize {
    let extent = |a: usize| f64::from(b[a + 3]) - f64::from(b[a]);
    (1..3).fold(0, |best, a| if extent(a) > extent(best) { a } else { best })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::{Rng, Stream};
    use std::f64::consts::PI;

    /// A direction uniform on the sphere.
    fn isotropic(rng: &mut Rng) -> DVec3 {
        let z = 2.0 * rng.uniform() - 1.0;
        let phi = 2.0 * PI * rng.uniform();
        let s = (1.0 - z * z).max(0.0).sqrt();
        DVec3::new(s * phi.cos(), s * phi.sin(), z)
    }

    /// A point uniform in the box [lo, hi]³.
    fn in_cube(rng: &mut Rng, lo: f64, hi: f64) -> DVec3 {
        DVec3::new(rng.uniform(), rng.uniform(), rng.uniform()) * (hi - lo) + lo
    }

    /// A unit vector perpendicular to unit `d`.
    fn across(rng: &mut Rng, d: DVec3) -> DVec3 {
        d.cross(isotropic(rng)).normalize()
    }

    fn beam(origin: DVec3, dir: DVec3, length: f64) -> PhotonBeam {
        PhotonBeam { origin, dir, length, wavelength_nm: 550.0, power_w: 1.0, path: PhotonPath::Diffuse, medium: 0 }
    }

    /// A segment/tube pair (o, dir, length, a, d, l, r) of one of six kinds, by `kind`.
    #[allow(clippy::type_complexity)]
    fn pair(rng: &mut Rng, kind: u64) -> (DVec3, DVec3, f64, DVec3, DVec3, f64, f64) {
        let a = in_cube(rng, 0.0, 1.0);
        let mut d = isotropic(rng);
        let l = 0.05 + 0.5 * rng.uniform();
        let r = 0.01 + 0.2 * rng.uniform();
        let length = 0.05 + rng.uniform();
        let sign = if rng.uniform() < 0.5 { -1.0 } else { 1.0 };
        let axis = [DVec3::X, DVec3::Y, DVec3::Z][rng.below(3) as usize];
        let near = a + d * l * (1.4 * rng.uniform() - 0.2);
        let off = 1.5 * r * rng.uniform();
        let (o, dir) = match kind {
            // Exactly parallel (or antiparallel).
            1 => (a + d * l * (3.0 * rng.uniform() - 1.0) + across(rng, d) * off, sign * d),
            // Exactly perpendicular: an axis-aligned tube, a segment in the plane across it.
            2 => {
                d = sign * axis;
                let dir = across(rng, d);
                let dir = (dir - dir.dot(d) * d).normalize();
                let x = a + d * l * (1.4 * rng.uniform() - 0.2) + isotropic(rng) * off;
                (x - dir * length * rng.uniform(), dir)
            }
            // Starting inside the tube.
            3 => (a + d * l * rng.uniform() + across(rng, d) * 0.95 * r * rng.uniform(), isotropic(rng)),
            // Axis-aligned and parallel.
            4 => {
                d = sign * axis;
                (a + d * l * (3.0 * rng.uniform() - 1.0) + across(rng, d) * off, axis)
            }
            // Nearly parallel.
            5 => {
                let dir = (d + isotropic(rng) * 1e-9).normalize();
                (a + d * l * (3.0 * rng.uniform() - 1.0) + across(rng, d) * off, sign * dir)
            }
            // General: a segment passing near a point near the tube.
            _ => {
                let dir = isotropic(rng);
                (near + isotropic(rng) * off - dir * length * rng.uniform(), dir)
            }
        };
        (o, dir, length, a, d, l, r)
    }

    /// Whether x is inside (Some(true)), outside (Some(false)) the tube by more than `margin`,
    /// or within `margin` of its surface (None), by its axial coordinate and distance to the axis.
    fn side(x: DVec3, a: DVec3, d: DVec3, l: f64, r: f64, margin: f64) -> Option<bool> {
        let v = x - a;
        let s = v.dot(d);
        let dist = (v - s * d).length();
        if s > margin && s < l - margin && dist < r - margin {
            Some(true)
        } else if s < -margin || s > l + margin || dist > r + margin {
            Some(false)
        } else {
            None
        }
    }

    #[test]
    fn tube_intervals_hold_the_samples_inside_the_tube() {
        let mut rng = Rng::for_task(11, Stream::Test, 0);
        let samples = 2000;
        let (mut entered, mut inside, mut outside) = (0, 0, 0);
        for k in 0..3000 {
            let (o, dir, length, a, d, l, r) = pair(&mut rng, k % 6);
            let found = tube_interval(o, dir, length, a, d, l, r);
            if let Some((t0, t1)) = found {
                assert!(0.0 <= t0 && t0 < t1 && t1 <= length, "case {k}: [{t0}, {t1}] within [0, {length}]");
                entered += 1;
            }
            let h = length / samples as f64;
            for j in 0..samples {
                let t = (j as f64 + 0.5) * h;
                match (side(o + t * dir, a, d, l, r, 1e-9), found) {
                    (Some(true), Some((t0, t1))) => {
                        assert!(t >= t0 - h && t <= t1 + h, "case {k}: inside point t = {t} beyond [{t0}, {t1}]");
                        inside += 1;
                    }
                    (Some(true), None) => panic!("case {k}: point t = {t} inside a tube the segment misses"),
                    (Some(false), Some((t0, t1))) => {
                        assert!(t <= t0 + h || t >= t1 - h, "case {k}: outside point t = {t} within [{t0}, {t1}]");
                        outside += 1;
                    }
                    _ => outside += 1,
                }
            }
        }
        eprintln!("{entered} of 3000 segments entered their tube; {inside} samples inside, {outside} outside");
        assert!(entered > 1000 && inside > 100_000 && outside > 100_000);
    }

    /// Every hit, by cutting the segment with each tube.
    fn brute(map: &PhotonBeamMap, o: DVec3, dir: DVec3, length: f64) -> Vec<TubeHit> {
        let mut hits: Vec<TubeHit> = (0..map.len() as u32)
            .filter_map(|i| {
                let (b, r) = (map.beam(i), map.radius(i));
                let (t0, t1) = tube_interval(o, dir, length, b.origin, b.dir, b.length, r)?;
                Some(TubeHit { index: i, t: 0.5 * (t0 + t1), inside_m: t1 - t0, r2: r * r })
            })
            .collect();
        hits.sort_by(|a, b| a.t.total_cmp(&b.t).then(a.index.cmp(&b.index)));
        hits
    }

    /// `n` beams starting in the unit cube, with radii.
    fn random_beams(n: usize, seed: u64) -> (Vec<PhotonBeam>, Vec<f64>) {
        let mut rng = Rng::for_task(seed, Stream::Test, 0);
        let beams: Vec<PhotonBeam> = (0..n)
            .map(|_| beam(in_cube(&mut rng, 0.0, 1.0), isotropic(&mut rng), 0.02 + 0.3 * rng.uniform()))
            .collect();
        let radii = (0..n).map(|_| 0.005 + 0.045 * rng.uniform()).collect();
        (beams, radii)
    }

    #[test]
    fn queries_find_what_testing_every_beam_finds() {
        let (beams, radii) = random_beams(20_000, 21);
        let map = PhotonBeamMap::new(beams.clone(), radii.clone());
        let given = |i: usize| *map.beam(i as u32) == beams[i] && map.radius(i as u32) == radii[i];
        assert!((0..beams.len()).all(given), "beams and radii read back by the index given");
        let mut rng = Rng::for_task(22, Stream::Test, 1);
        let axes = [DVec3::X, DVec3::Y, DVec3::Z, -DVec3::X, -DVec3::Y, -DVec3::Z];
        let (mut hits, mut total) = (Vec::new(), 0);
        for q in 0..300 {
            let o = in_cube(&mut rng, -0.1, 1.1);
            let dir = if q % 3 == 0 { axes[rng.below(6) as usize] } else { isotropic(&mut rng) };
            let length = 0.1 + 1.4 * rng.uniform();
            map.query(o, dir, length, &mut hits);
            assert_eq!(hits, brute(&map, o, dir, length), "query {q}");
            assert!(hits.windows(2).all(|w| w[0].t <= w[1].t));
            total += hits.len();
        }
        eprintln!("300 queries found {total} tubes; map holds {} bytes", map.memory_bytes());
        assert!(total > 1000);
    }

    /// The sizes the memory model (`render::memory`) states: a beam 80 bytes, a node 32, at most
    /// 160 per beam of a built map; a built map holds no more than that per beam.
    #[test]
    fn a_map_holds_at_most_its_stated_bytes_per_beam() {
        assert_eq!((size_of::<PhotonBeam>(), size_of::<Node>(), BYTES_PER_BEAM), (80, 32, 160));
        let mut rng = Rng::for_task(33, Stream::Test, 0);
        for n in [1usize, 5, 1000, 20_000] {
            let beams: Vec<PhotonBeam> = (0..n)
                .map(|_| PhotonBeam {
                    origin: DVec3::new(rng.uniform(), rng.uniform(), rng.uniform()),
                    dir: DVec3::new(rng.uniform() - 0.5, rng.uniform() - 0.5, 1.0).normalize(),
                    length: 0.1,
                    wavelength_nm: 550.0,
                    power_w: 1.0,
                    path: PhotonPath::Diffuse,
                    medium: 0,
                })
                .collect();
            let map = PhotonBeamMap::new(beams, vec![0.01; n]);
            let held = map.memory_bytes() - size_of::<PhotonBeamMap>();
            assert!(held <= n * BYTES_PER_BEAM, "{n} beams hold {held} bytes");
        }
    }

    /// A beam sent between ranks comes back bit for bit, every path and the largest medium index.
    #[test]
    fn beams_cross_the_wire_bit_for_bit() {
        let mut rng = Rng::for_task(31, Stream::Test, 0);
        for (i, path) in [PhotonPath::Direct, PhotonPath::Specular, PhotonPath::Diffuse].into_iter().enumerate() {
            let b = PhotonBeam {
                origin: DVec3::new(rng.uniform(), -6.4e6 * rng.uniform(), 1e-300),
                dir: DVec3::new(rng.uniform(), rng.uniform(), rng.uniform()).normalize(),
                length: rng.uniform(),
                wavelength_nm: 400.0 + 300.0 * rng.uniform(),
                power_w: 1e-9 * rng.uniform(),
                path,
                medium: [0, 7, u32::MAX][i],
            };
            let back = PhotonBeam::from_le_bytes(&b.to_le_bytes());
            let bits = |b: &PhotonBeam| {
                [b.origin.x, b.origin.y, b.origin.z, b.dir.x, b.dir.y, b.dir.z, b.length, b.wavelength_nm, b.power_w]
                    .map(f64::to_bits)
            };
            assert_eq!(bits(&back), bits(&b));
            assert_eq!((back.path, back.medium), (b.path, b.medium));
        }
    }

    #[test]
    fn degenerate_segments_and_empty_maps_find_nothing() {
        let (beams, radii) = random_beams(2_000, 31);
        let map = PhotonBeamMap::new(beams, radii);
        let mut hits = vec![TubeHit { index: 0, t: 0.0, inside_m: 1.0, r2: 1.0 }];
        let o = DVec3::splat(0.5);
        map.query(o, DVec3::X, 1.0, &mut hits);
        assert!(!hits.is_empty(), "a segment through the middle finds tubes");
        for length in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            map.query(o, DVec3::X, length, &mut hits);
            assert!(hits.is_empty(), "length {length}");
        }
        for (o, dir) in [(DVec3::NAN, DVec3::X), (o, DVec3::NAN), (o, DVec3::ZERO), (DVec3::INFINITY, DVec3::X)] {
            map.query(o, dir, 1.0, &mut hits);
            assert!(hits.is_empty(), "point {o}, direction {dir}");
        }
        let empty = PhotonBeamMap::new(Vec::new(), Vec::new());
        empty.query(o, DVec3::X, 1.0, &mut hits);
        assert!(hits.is_empty() && empty.is_empty() && empty.total_length_m() == 0.0);
        // Beams that can never be hit: bad lengths, radii, origins, directions.
        let b = beam(DVec3::new(0.0, 0.5, 0.5), DVec3::X, 1.0);
        let bad = vec![
            PhotonBeam { length: f64::NAN, ..b },
            PhotonBeam { length: 0.0, ..b },
            PhotonBeam { length: f64::INFINITY, ..b },
            b,
            b,
            PhotonBeam { origin: DVec3::NAN, ..b },
            PhotonBeam { dir: DVec3::ZERO, ..b },
        ];
        let radii = vec![0.1, 0.1, 0.1, 0.0, f64::NAN, 0.1, 0.1];
        let never = PhotonBeamMap::new(bad.clone(), radii.clone());
        for (i, (b, r)) in bad.iter().zip(&radii).enumerate() {
            let i = i as u32;
            assert!(never.beam(i).length.total_cmp(&b.length).is_eq() && never.radius(i).total_cmp(r).is_eq());
        }
        never.query(DVec3::new(0.5, 0.0, 0.5), DVec3::Y, 1.0, &mut hits);
        assert!(hits.is_empty() && never.len() == 7);
        assert_eq!(never.total_length_m(), 4.0, "lengths that are finite and positive");
    }

    /// Beams of length `lb` with origins uniform in [−1, 1]³ and isotropic directions.
    fn uniform_beams(n: usize, lb: f64, rng: &mut Rng) -> Vec<PhotonBeam> {
        (0..n).map(|_| beam(in_cube(rng, -1.0, 1.0), isotropic(rng), lb)).collect()
    }

    /// The tubes measure beam length density: the property the estimator relies on.
    ///
    /// Σ_b inside_b = ∫₀ˢ Σ_b 1[x(t) ∈ T_b] dt. With N beams whose origins are uniform in a box of
    /// volume V (directions drawn independently of position, here isotropic), a point x lies in
    /// beam b's tube T_b with probability |T_b|/V = π r² l_b/V whenever every translate of T_b
    /// that contains x starts inside the box (x at least l_b + r from its walls). So
    /// E[Σ_b 1[x ∈ T_b]] = π r² N l_b/V = π r² λ_L (Campbell's theorem), and
    /// E[Σ_b inside_b/(π r²)] = λ_L s for a segment of length s: the kernel spreads each beam's
    /// length over its tube without loss, for any radius and direction distribution.
    ///
    /// Queries sharing a map are correlated (they read the same beams), so the standard error is
    /// taken from the means of independent batches, each with its own map.
    #[test]
    fn inside_lengths_measure_beam_length_density() {
        let (n, lb, r, s) = (200_000, 0.2, 0.02, 0.5);
        let (batches, per_batch) = (20, 100);
        let lambda = n as f64 * lb / 8.0;
        let mut rng = Rng::for_task(41, Stream::Test, 0);
        let (mut means, mut all) = (Vec::new(), Vec::new());
        let mut hits = Vec::new();
        for _ in 0..batches {
            let map = PhotonBeamMap::new(uniform_beams(n, lb, &mut rng), vec![r; n]);
            let mut sum = 0.0;
            for _ in 0..per_batch {
                let dir = isotropic(&mut rng);
                let centre = in_cube(&mut rng, -0.5, 0.5);
                map.query(centre - 0.5 * s * dir, dir, s, &mut hits);
                let x = hits.iter().map(|h| h.inside_m).sum::<f64>() / (PI * r * r);
                all.push(x);
                sum += x;
            }
            means.push(sum / per_batch as f64);
        }
        let (mean, se) = mean_and_error(&means);
        let (_, naive) = mean_and_error(&all);
        let expected = lambda * s;
        eprintln!(
            "λ_L s = {expected}; mean Σ inside/(π r²) = {mean:.2} ± {se:.2} (batch means; {naive:.2} \
             treating the {} queries as independent), ratio {:.5}",
            all.len(),
            mean / expected
        );
        assert!((mean - expected).abs() < 3.0 * se, "within 3 standard errors");
        assert!((mean - expected).abs() < 0.02 * expected, "within 2 %");
    }

    /// Mean and standard error of the mean.
    fn mean_and_error(x: &[f64]) -> (f64, f64) {
        let n = x.len() as f64;
        let mean = x.iter().sum::<f64>() / n;
        let var = x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
        (mean, (var / n).sqrt())
    }

    /// A segment parallel to a beam and within its tube is inside along the overlap of the two
    /// axial ranges: [max(s₀, 0), min(s₀ + s, l)] for a segment starting at axial s₀ along d
    /// (and [max(s₀ − s, 0), min(s₀, l)] against it), at laboratory and planetary scale.
    #[test]
    fn parallel_segments_are_inside_along_the_overlap() {
        let mut rng = Rng::for_task(51, Stream::Test, 0);
        let (l, r) = (0.8, 0.05);
        let mut hits = Vec::new();
        let mut overlapping = 0;
        for (k, base) in [DVec3::new(0.3, 0.2, 0.1), DVec3::new(6.371e6, -1.2e3, 2.5e4)].into_iter().enumerate() {
            let d = DVec3::new(1.0, 2.0, 3.0).normalize();
            let map = PhotonBeamMap::new(vec![beam(base, d, l)], vec![r]);
            let tolerance = if k == 0 { 1e-12 } else { 1e-6 };
            for _ in 0..200 {
                let (s0, s, sign) = (2.0 * rng.uniform() - 0.5, 0.05 + rng.uniform(), rng.uniform() < 0.5);
                let o = base + s0 * d + across(&mut rng, d) * 0.99 * r * rng.uniform();
                let (dir, lo, hi) = if sign { (d, s0, s0 + s) } else { (-d, s0 - s, s0) };
                let (a0, a1) = (lo.max(0.0), hi.min(l));
                map.query(o, dir, s, &mut hits);
                if a1 - a0 <= tolerance {
                    assert!(hits.is_empty() || hits[0].inside_m <= tolerance, "no overlap: {hits:?}");
                    continue;
                }
                overlapping += 1;
                let t = if sign { 0.5 * (a0 + a1) - s0 } else { s0 - 0.5 * (a0 + a1) };
                assert_eq!(hits.len(), 1, "s0 = {s0}, s = {s}");
                assert!((hits[0].inside_m - (a1 - a0)).abs() < tolerance, "{:?} against {}", hits[0], a1 - a0);
                assert!((hits[0].t - t).abs() < tolerance, "{:?} against t = {t}", hits[0]);
            }
        }
        assert!(overlapping > 200);
    }

    /// Far from the origin, nearly parallel segments give the interval they give near it, finite.
    #[test]
    fn planetary_coordinates_and_near_parallel_segments_stay_finite() {
        let mut rng = Rng::for_task(61, Stream::Test, 0);
        let shift = DVec3::new(6.371e6, 3.0e5, -2.0e5);
        let mut compared = 0;
        for k in 0..2000 {
            let d = isotropic(&mut rng);
            let (l, r, length) = (1e4 * (0.1 + rng.uniform()), 50.0 * (0.1 + rng.uniform()), 2e4 * rng.uniform() + 1.0);
            let tilt = 10f64.powf(-16.0 + 12.0 * rng.uniform());
            let dir = (d + across(&mut rng, d) * tilt).normalize();
            let dir = if k % 2 == 0 { dir } else { -dir };
            let o = d * l * (1.4 * rng.uniform() - 0.2) + across(&mut rng, d) * 1.2 * r * rng.uniform();
            let near = tube_interval(o, dir, length, DVec3::ZERO, d, l, r);
            let far = tube_interval(o + shift, dir, length, shift, d, l, r);
            for (t0, t1) in near.iter().chain(far.iter()) {
                assert!(t0.is_finite() && t1.is_finite() && 0.0 <= *t0 && t0 < t1 && *t1 <= length);
            }
            // o − a carries ~10⁻⁹ m of rounding at this scale, which moves a root where the
            // segment crosses the tube's side by that much over sin θ.
            let tolerance = 1e-9 * length + 1e-8 / dir.cross(d).length();
            if let (Some(a), Some(b)) = (near, far) {
                let close = (a.0 - b.0).abs() < tolerance && (a.1 - b.1).abs() < tolerance;
                assert!(close, "case {k}: {a:?} against {b:?}");
                compared += 1;
            }
        }
        assert!(compared > 500, "{compared} intervals compared");
    }

    /// Build time of the hierarchy over 10⁶ beams (run with `--ignored --nocapture` in release).
    #[test]
    #[ignore]
    fn builds_a_million_beams_quickly() {
        let mut rng = Rng::for_task(71, Stream::Test, 0);
        let n = 1_000_000;
        let beams = uniform_beams(n, 0.1, &mut rng);
        let radii = vec![0.01; n];
        let start = std::time::Instant::now();
        let map = PhotonBeamMap::new(beams, radii);
        let build = start.elapsed();
        let mut hits = Vec::new();
        let start = std::time::Instant::now();
        let mut found = 0;
        for _ in 0..10_000 {
            let dir = isotropic(&mut rng);
            map.query(in_cube(&mut rng, -0.8, 0.8), dir, 0.2, &mut hits);
            found += hits.len();
        }
        let query = start.elapsed() / 10_000;
        let (mut boxed, mut tested) = (0, 0);
        for _ in 0..100 {
            let (dir, o) = (isotropic(&mut rng), in_cube(&mut rng, -0.8, 0.8));
            let (inv, rel) = (dir.recip(), o - map.centre);
            let own = |i: &u32| crosses(&tube_box(map.beam(*i), map.radius(*i), map.centre), rel, inv, 0.2);
            boxed += map.index[..map.len()].iter().filter(|i| own(i)).count();
            tested += map.nodes.iter().filter(|n| n.count > 0 && crosses(&n.bounds, rel, inv, 0.2)).count();
        }
        eprintln!(
            "10^6 beams: build {build:?}, {} nodes, {} MB; query {query:?} ({} hits each; the segment \
             crosses {} beams' own boxes and at most {} leaves)",
            map.nodes.len(),
            map.memory_bytes() / 1_000_000,
            found / 10_000,
            boxed / 100,
            tested / 100
        );
        assert!(build.as_secs_f64() < 5.0);
    }
}
