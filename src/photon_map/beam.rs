//! The beam radiance estimate: the light a volume photon map scatters toward the eye along a
//! whole segment, from one query (Jarosz, Zwicker & Jensen 2008).
//!
//! Each photon p carries a gather disc of radius r_p facing the segment. Integrating the point
//! estimate's 3-D kernel along the segment turns it into a 2-D kernel across it, so the radiance
//! scattered toward the eye along a segment of direction ω (the eye looks along −ω... the light
//! travels along ω = `wo`) is
//!
//! ∫₀ˢ T(0→t) σ_s L_i(x(t), ω) dt ≈ Σ_p T(0→t_p) K(d_p, r_p) α(λ_p) f(λ_p; ω_p·ω) ΔΦ_p / Δλ_b
//!
//! (JZJ08 Eq. 14 with the albedo of Jensen & Christensen 1998 §4.3, since photons are stored at
//! every interaction), summed over the photons whose projection t_p onto the segment lies in
//! [0, s] at a distance d_p < r_p from it; K = 1/(π r_p²) is the box kernel. There are no march
//! steps, so no step bias: the transmittance is evaluated at each photon's own projection.
//!
//! The radii: as JZJ08 §5 does, each photon's r_p is the radius of the sphere around it that
//! holds its k nearest other photons (a pilot k-nearest query; at most a cap), times a factor
//! for progressive passes (√sᵢ: the 2-D rule r²ᵢ₊₁ = r²ᵢ (i + α)/(i + 1) of Knaus & Zwicker 2011
//! and Jarosz et al. 2011). A photon whose pilot radius is 0 (a duplicate position) gets the cap.
//! With a radius per photon the estimate is a variable-kernel ("scatter") density estimate: each
//! photon's kernel integrates to one over the plane across the segment, so power is conserved
//! for any radii.
//!
//! Where a segment ends on a surface (a wall, the glass the eye ray met), its tube of discs ends
//! on the surface's tangent plane instead of on the plane across it ([`SegmentEnds`]): the plane
//! across it leaves out the medium's photons in front of a wall met obliquely, beyond the
//! segment's end, and takes in the wedge behind it, which holds none — a deficit of
//! 2 r tan θ/(3π s) of a segment of length s met at θ (see [`BeamMap::query`]).
//!
//! The query: the kd-tree's leaves own consecutive runs of photons, so a complete binary tree
//! over the leaves, each node holding the bounding box of its photons' spheres, is a bounding
//! volume hierarchy of the discs (24 bytes per node, about 1.5 bytes per photon). A segment
//! descends into the nodes whose box it crosses (slab test) and tests the photons of each leaf.
//!
//! # References
//! - W. Jarosz, M. Zwicker and H. W. Jensen (2008), "The beam radiance estimate for volumetric
//!   photon mapping", Computer Graphics Forum 27(2) (Eurographics), 557–566.
//! - W. Jarosz, D. Nowrouzezahrai, R. Thomas, P.-P. Sloan and M. Zwicker (2011), "Progressive
//!   photon beams", ACM Transactions on Graphics 30(6), 181.
//! - H. W. Jensen and P. H. Christensen (1998), "Efficient simulation of light transport in
//!   scenes with participating media using photon maps", SIGGRAPH 98
//!   (`shared/papers/`).

use super::{KdPoint, Neighbours, Paths, PhotonMap, ScatterRows, Wall, Walls};
use crate::media::Medium;
use crate::spectrum::{BandValues, Bands, MAX_BANDS};
use glam::DVec3;
use rayon::prelude::*;
use std::f64::consts::PI;
use std::sync::Arc;

/// The bounding box of no photon: every slab test fails.
const EMPTY: [f32; 6] =
    [f32::INFINITY, f32::INFINITY, f32::INFINITY, f32::NEG_INFINITY, f32::NEG_INFINITY, f32::NEG_INFINITY];

/// A photon whose disc a segment crosses.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BeamHit {
    /// The photon (index into [`PhotonMap::photons`]).
    pub index: u32,
    /// Its projection onto the segment, m from the segment's start.
    pub t: f64,
    /// Its squared distance from the segment's line, m².
    pub d2: f64,
    /// Its squared disc radius, m².
    pub r2: f64,
}

/// The surfaces a segment starts and ends on, whose planes bound its tube of discs there
/// (see [`BeamMap::query`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SegmentEnds {
    /// Normal (either orientation) of the surface the segment starts on, if it does.
    pub start: Option<DVec3>,
    /// Normal (either orientation) of the surface the segment ends on, if it does.
    pub end: Option<DVec3>,
}

impl SegmentEnds {
    /// The planes of the surfaces the segment from `o` along unit `dir` of length `length`
    /// starts and ends on, as [`Wall`]s facing the segment (a surface containing the segment's
    /// direction bounds nothing along it and is left out).
    pub fn walls(&self, o: DVec3, dir: DVec3, length: f64) -> Walls {
        let wall = |n: Option<DVec3>, point: DVec3, toward: DVec3| {
            facing(n?, toward, 0.0).map(|normal| Wall { point, normal })
        };
        Walls { ends: [wall(self.start, o, dir), wall(self.end, o + length * dir, -dir)] }
    }
}

/// An end surface met at a cosine below this (beyond 84°) keeps the plane across the segment:
/// the tube's oblique end would reach 10 disc radii along it.
const MIN_END_COS: f64 = 0.1;

/// The gather discs of a volume photon map and a bounding volume hierarchy over them.
#[derive(Clone, Debug)]
pub struct BeamMap {
    /// Disc radius of each photon, m, in tree order.
    radii: Vec<f32>,
    /// The largest of them, m.
    max_radius: f64,
    /// Sphere bounds per node of the complete binary tree over the kd-tree's leaves, in heap
    /// order (root 1, children 2i and 2i + 1, leaf j at 2^depth + j): min xyz, max xyz in the
    /// map's frame.
    boxes: Vec<[f32; 6]>,
    depth: u32,
}

impl BeamMap {
    /// The discs of `map`'s photons: radius of the sphere holding each photon's `k` nearest
    /// other photons, at most `max_radius` (and `max_radius` when fewer are within it or the
    /// radius is 0), times `scale`. Computed in parallel; the result does not depend on the
    /// thread count.
    pub fn build(map: &PhotonMap, k: usize, max_radius: f64, scale: f64) -> BeamMap {
        let tree = map.tree();
        let max_d2 = (max_radius * max_radius) as f32;
        let radii = tree
            .items()
            .par_iter()
            .map_init(Neighbours::default, |nb, p| {
                tree.knn(p.position(), k + 1, max_d2, nb);
                let r = if nb.len() < k + 1 { max_radius } else { f64::from(nb.max_dist2()).sqrt() };
                let r = if r > 0.0 { r } else { max_radius };
                (r * scale) as f32
            })
            .collect();
        Self::from_radii(map, radii)
    }

    /// The discs of radii `radii` (m, in the map's tree order, one per photon).
    ///
    /// # Panics
    /// If `radii` does not hold one radius per photon.
    pub fn from_radii(map: &PhotonMap, radii: Vec<f32>) -> BeamMap {
        assert_eq!(radii.len(), map.len(), "one radius per photon");
        let tree = map.tree();
        let depth = tree.depth();
        let leaves = 1usize << depth;
        let mut boxes = vec![EMPTY; 2 * leaves];
        for j in 0..leaves {
            let mut b = EMPTY;
            for i in tree.leaf_range(j) {
                let p = tree.items()[i].position();
                let r = radii[i];
                for a in 0..3 {
                    b[a] = b[a].min(p[a] - r);
                    b[a + 3] = b[a + 3].max(p[a] + r);
                }
            }
            boxes[leaves + j] = b;
        }
        for n in (1..leaves).rev() {
            let (l, r) = (boxes[2 * n], boxes[2 * n + 1]);
            boxes[n] = std::array::from_fn(|a| if a < 3 { l[a].min(r[a]) } else { l[a].max(r[a]) });
        }
        let max_radius = radii.iter().fold(0.0f64, |m, r| m.max(f64::from(*r)));
        BeamMap { radii, boxes, max_radius, depth }
    }

    /// Disc radius of photon `i`, m.
    pub fn radius(&self, i: u32) -> f64 {
        f64::from(self.radii[i as usize])
    }

    /// Bytes held (radii and boxes, by capacity).
    pub fn memory_bytes(&self) -> usize {
        size_of::<Self>() + self.radii.capacity() * size_of::<f32>() + self.boxes.capacity() * size_of::<[f32; 6]>()
    }

    /// The photons of `map` (the map these discs were built for) whose disc the segment from
    /// `o` along unit `dir` of length `length` crosses, into `hits`, sorted by `t`. A segment
    /// with a non-finite or non-positive length, or a non-finite point, finds none.
    ///
    /// The tube of discs ends, at each end of the segment that lies on a surface (`ends`), on
    /// that surface's tangent plane rather than on the plane across the segment: a photon
    /// counts if it lies within its radius of the segment's line and between the two end
    /// planes. Where a segment meets a wall at an angle θ, the plane across it leaves out the
    /// wedge of the tube beyond its end that still lies in the medium and takes in the one
    /// before its end that lies behind the wall, where no photon is: a share 2 r tan θ/(3π s) of
    /// a tube of length s too little light (the first moment of a half disc, 2r³/3, times
    /// tan θ over π r² s). Between the tangent planes each line along the tube is s long on
    /// average over the disc (Cavalieri), so the tube holds π r² s of medium and the estimate
    /// has no such bias for a planar boundary. Such a photon's `t` is its projection clamped
    /// onto [0, `length`] (where its transmittance is read).
    pub fn query(
        &self,
        map: &PhotonMap,
        o: DVec3,
        dir: DVec3,
        length: f64,
        ends: SegmentEnds,
        hits: &mut Vec<BeamHit>,
    ) {
        hits.clear();
        let rel = o - map.origin();
        if !(length > 0.0 && length.is_finite() && rel.is_finite() && dir.is_finite()) || map.is_empty() {
            return;
        }
        // Each end plane's normal, pointing into the segment's side of it.
        let start = ends.start.and_then(|n| facing(n, dir, MIN_END_COS));
        let end = ends.end.and_then(|n| facing(n, -dir, MIN_END_COS));
        let reach = |m: Option<DVec3>| {
            m.map_or(0.0, |m| {
                let c = m.dot(dir).abs();
                self.max_radius * (1.0 - c * c).sqrt() / c
            })
        };
        let (t0, t1) = (-reach(start), length + reach(end));
        let tree = map.tree();
        let inv = dir.recip();
        let leaves = 1usize << self.depth;
        let mut stack = [0usize; 64];
        let mut sp = 1;
        stack[0] = 1;
        while sp > 0 {
            sp -= 1;
            let n = stack[sp];
            if !crosses(&self.boxes[n], rel + t0 * dir, inv, t1 - t0) {
                continue;
            }
            if n >= leaves {
                for i in tree.leaf_range(n - leaves) {
                    let [x, y, z] = tree.items()[i].position();
                    let v = DVec3::new(f64::from(x), f64::from(y), f64::from(z)) - rel;
                    let t = v.dot(dir);
                    let r = f64::from(self.radii[i]);
                    let d2 = (v - t * dir).length_squared();
                    let after_start = start.map_or(t >= 0.0, |m| v.dot(m) >= 0.0);
                    let before_end = end.map_or(t <= length, |m| (v - length * dir).dot(m) > 0.0);
                    if d2 < r * r && after_start && before_end {
                        hits.push(BeamHit { index: i as u32, t: t.clamp(0.0, length), d2, r2: r * r });
                    }
                }
            } else {
                stack[sp] = 2 * n + 1;
                stack[sp + 1] = 2 * n;
                sp += 2;
            }
        }
        hits.sort_unstable_by(|a, b| a.t.total_cmp(&b.t).then(a.index.cmp(&b.index)));
    }
}

/// The unit normal `n` turned to face along `d` (n·d > 0), or `None` for a surface met at a
/// cosine below `min_cos` (the beam's tube: [`MIN_END_COS`]), one containing `d`, or a normal
/// that is not finite and non-zero.
fn facing(n: DVec3, d: DVec3, min_cos: f64) -> Option<DVec3> {
    let n = n.try_normalize()?;
    let c = n.dot(d);
    (c != 0.0 && c.abs() >= min_cos).then(|| if c > 0.0 { n } else { -n })
}

/// Whether the segment `o + t·d`, 0 ≤ t ≤ `length` (`inv` = 1/d per axis), meets the box `b`
/// (slab test; NaN from 0·∞ on a face is ignored by `max`/`min`; an empty box, min > max, meets
/// nothing). The hierarchies of discs and of photon beams' tubes both descend by it.
#[inline]
pub(super) fn crosses(b: &[f32; 6], o: DVec3, inv: DVec3, length: f64) -> bool {
    let (mut t0, mut t1) = (0.0f64, length);
    for a in 0..3 {
        let ta = (f64::from(b[a]) - o[a]) * inv[a];
        let tb = (f64::from(b[a + 3]) - o[a]) * inv[a];
        t0 = t0.max(ta.min(tb));
        t1 = t1.min(ta.max(tb));
    }
    t0 <= t1 && b[0] <= b[3]
}

/// An estimate of the light a medium scatters toward the eye along a whole chord from one query:
/// the beam estimate's discs ([`BeamEstimator`]) or photon beams' tubes
/// ([`super::TubeEstimator`]).
pub trait ChordEstimate {
    /// What a query finds: one photon or beam and where along the chord it scatters.
    type Hit;

    /// Everything the chord from `o` along unit `dir` of length `length` (starting and ending
    /// on the surfaces `ends`) gathers, into `hits` (cleared first), sorted by [`Self::t`].
    fn gather(&self, o: DVec3, dir: DVec3, length: f64, ends: SegmentEnds, hits: &mut Vec<Self::Hit>);

    /// Where along the chord `hit` scatters its light (where its transmittance is read), m.
    fn t(hit: &Self::Hit) -> f64;

    /// Calls `add(band, L)` with the radiance (W m⁻² sr⁻¹ nm⁻¹) `hit` scatters toward travel
    /// direction `wo` into each band, before the transmittance from the chord's start; `x` is
    /// the chord's point at [`Self::t`], in medium `(id, medium)`. `tmp` is scratch.
    fn radiance(
        &self,
        hit: &Self::Hit,
        x: DVec3,
        wo: DVec3,
        medium: (u32, &Medium),
        tmp: &mut BandValues,
        add: &mut impl FnMut(usize, f64),
    );
}

impl ChordEstimate for BeamEstimator<'_> {
    type Hit = BeamHit;

    fn gather(&self, o: DVec3, dir: DVec3, length: f64, ends: SegmentEnds, hits: &mut Vec<BeamHit>) {
        BeamEstimator::gather(self, o, dir, length, ends, hits);
    }

    fn t(hit: &BeamHit) -> f64 {
        hit.t
    }

    fn radiance(
        &self,
        hit: &BeamHit,
        _x: DVec3,
        wo: DVec3,
        medium: (u32, &Medium),
        tmp: &mut BandValues,
        add: &mut impl FnMut(usize, f64),
    ) {
        self.photon(hit, wo, medium, tmp, add);
    }
}

/// The beam estimate on one volume map with fixed discs.
pub struct BeamEstimator<'a> {
    /// The photon map read.
    pub map: &'a PhotonMap,
    /// Its photons' discs.
    pub discs: &'a BeamMap,
    /// The bands estimates are binned into.
    pub bands: Bands,
    /// Which photons count for elastic scattering (inelastic re-emission counts every photon).
    pub paths: Paths,
    /// The photons' albedo and phase weights per medium ([`ScatterRows`]; `None`: computed
    /// per photon read).
    pub scatter_rows: Option<Arc<ScatterRows>>,
}

impl BeamEstimator<'_> {
    /// The photons whose disc the segment crosses, sorted by their projection (see
    /// [`BeamMap::query`]).
    pub fn gather(&self, o: DVec3, dir: DVec3, length: f64, ends: SegmentEnds, hits: &mut Vec<BeamHit>) {
        self.discs.query(self.map, o, dir, length, ends, hits);
    }

    /// Calls `add(band, L)` with the radiance (W m⁻² sr⁻¹ nm⁻¹) photon `hit` scatters toward
    /// travel direction `wo` into each band, before the transmittance from the segment's start:
    /// K α(λ_p) f(λ_p; ω_p·ω) ΔΦ_p / Δλ_b elastically, and Σ_i p_i T_i(λ_p, b) K ΔΦ_p / Δλ_b from a
    /// medium's inelastic components (every photon, as in the point estimate). `tmp` is scratch.
    pub fn photon(
        &self,
        hit: &BeamHit,
        wo: DVec3,
        (id, medium): (u32, &Medium),
        tmp: &mut BandValues,
        add: &mut impl FnMut(usize, f64),
    ) {
        if hit.r2.is_nan() || hit.r2 <= 0.0 {
            return;
        }
        let p = self.map.record(hit.index);
        let kernel = 1.0 / (PI * hit.r2 * self.bands.width_nm());
        let l = p.wavelength_nm;
        let cos = p.dir.dot(wo);
        add_reemitted(medium, self.bands, (l, cos, p.power_w), kernel, tmp, add);
        if !self.paths.accepts(p.path) {
            return;
        }
        if let Some(b) = self.bands.index_of(l) {
            let rows = self.scatter_rows.as_ref().and_then(|r| r.rows(self.map, id, medium));
            add(b, super::scatter_rows::scattered(rows, medium, hit.index, &p, cos) * p.power_w * kernel);
        }
    }
}

/// Calls `add(band, L)` with what `medium`'s inelastic components re-emit into each of `bands`
/// from a photon (or a beam's collisions) of wavelength, cosine to the eye and power
/// `(λ, cos, power_w)`: Σ_i p_i T_i(λ, b) ΔΦ times `kernel`. Nothing where the medium has none.
/// `tmp` is scratch.
pub(super) fn add_reemitted(
    medium: &Medium,
    bands: Bands,
    (l, cos, power_w): (f64, f64, f64),
    kernel: f64,
    tmp: &mut BandValues,
    add: &mut impl FnMut(usize, f64),
) {
    let Some(t) = &medium.inelastic.transfer else { return };
    tmp[..bands.count].iter_mut().for_each(|v| *v = 0.0);
    t.add_photon(&medium.inelastic, tmp, l, cos, power_w);
    for (b, v) in tmp.iter().enumerate().take(bands.count.min(MAX_BANDS)) {
        if *v != 0.0 {
            add(b, v * kernel);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::photon_map::{PhotonPath, PhotonRecord};
    use crate::rng::{Rng, Stream};

    fn records(n: usize, seed: u64) -> Vec<PhotonRecord> {
        let mut rng = Rng::for_task(seed, Stream::Test, 0);
        (0..n)
            .map(|_| PhotonRecord {
                position: DVec3::new(rng.uniform(), rng.uniform(), 2.0 * rng.uniform()),
                dir: DVec3::Z,
                normal: DVec3::ZERO,
                wavelength_nm: 550.0,
                power_w: 1.0,
                path: PhotonPath::Direct,
            })
            .collect()
    }

    /// Every photon whose disc the segment crosses, by testing each one (f64 throughout).
    fn brute(map: &PhotonMap, beam: &BeamMap, o: DVec3, d: DVec3, len: f64) -> Vec<u32> {
        (0..map.len() as u32)
            .filter(|&i| {
                let v = map.record(i).position - o;
                let t = v.dot(d);
                let r = beam.radius(i);
                (0.0..=len).contains(&t) && (v - t * d).length_squared() < r * r
            })
            .collect()
    }

    #[test]
    fn queries_find_what_testing_every_photon_finds() {
        let map = PhotonMap::build(&records(20_000, 3));
        let mut rng = Rng::for_task(4, Stream::Test, 1);
        let radii: Vec<f32> = (0..map.len()).map(|_| (0.01 + 0.05 * rng.uniform()) as f32).collect();
        let beam = BeamMap::from_radii(&map, radii);
        let mut hits = Vec::new();
        let mut found = 0;
        for q in 0..200 {
            let o = DVec3::new(rng.uniform(), rng.uniform(), 2.0 * rng.uniform()) * 1.2 - 0.1;
            // Axis-parallel directions too (infinite reciprocals in the slab test).
            let d = match q % 4 {
                0 => DVec3::X,
                1 => DVec3::new(0.0, -1.0, 0.0),
                _ => (DVec3::new(rng.uniform(), rng.uniform(), rng.uniform()) - 0.5).normalize(),
            };
            let len = 1.5 * rng.uniform();
            beam.query(&map, o, d, len, SegmentEnds::default(), &mut hits);
            assert!(hits.windows(2).all(|w| w[0].t <= w[1].t));
            let mut got: Vec<u32> = hits.iter().map(|h| h.index).collect();
            got.sort_unstable();
            let want = brute(&map, &beam, o, d, len);
            // Positions are stored as f32: a photon on a disc's rim may fall either way.
            let missing = want.iter().filter(|i| !got.contains(i)).count();
            let extra = got.iter().filter(|i| !want.contains(i)).count();
            assert!(missing + extra <= 1, "query {q}: {missing} missing, {extra} extra of {}", want.len());
            found += want.len();
        }
        assert!(found > 1000, "the queries must find photons: {found}");
    }

    #[test]
    fn degenerate_segments_find_nothing() {
        let map = PhotonMap::build(&records(1000, 5));
        let beam = BeamMap::build(&map, 10, 0.2, 1.0);
        let mut hits = vec![BeamHit { index: 0, t: 0.0, d2: 0.0, r2: 0.0 }];
        for len in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            beam.query(&map, DVec3::splat(0.5), DVec3::X, len, SegmentEnds::default(), &mut hits);
            assert!(hits.is_empty(), "length {len}");
        }
        beam.query(&map, DVec3::NAN, DVec3::X, 1.0, SegmentEnds::default(), &mut hits);
        assert!(hits.is_empty());
    }

    /// The pilot radius of a photon in a uniform Poisson field of density ρ holding its k
    /// nearest others: (4/3)π r³ ρ ≈ k, so the mean of r³ over interior photons is near
    /// 3k/(4πρ) (the k-th nearest of a Poisson process: E[V] = k/ρ exactly).
    #[test]
    fn pilot_radii_follow_the_photon_density() {
        let n = 40_000;
        let map = PhotonMap::build(&records(n, 6));
        let k = 20;
        let beam = BeamMap::build(&map, k, 1.0, 1.0);
        let rho = n as f64 / 2.0;
        let inner: Vec<f64> = (0..map.len() as u32)
            .filter(|&i| {
                let p = map.record(i).position;
                p.min_element() > 0.2 && p.x < 0.8 && p.y < 0.8 && p.z < 1.8
            })
            .map(|i| beam.radius(i).powi(3) * 4.0 / 3.0 * PI * rho)
            .collect();
        let mean = inner.iter().sum::<f64>() / inner.len() as f64;
        assert!((mean / k as f64 - 1.0).abs() < 0.03, "mean k-ball volume × ρ = {mean}");
        let half = BeamMap::build(&map, k, 1.0, 0.5);
        assert!((half.radius(7) - 0.5 * beam.radius(7)).abs() < 1e-6);
    }

    /// Photons of a uniform field of density 8·10⁵ m⁻³ filling the cube [0, 1]³ (the medium; no
    /// photon outside it), with discs of radius `R_CUBE`.
    fn cube_of_photons() -> (PhotonMap, BeamMap) {
        let inside: Vec<PhotonRecord> = records(1_600_000, 9).into_iter().filter(|p| p.position.z < 1.0).collect();
        let map = PhotonMap::build(&inside);
        let beam = BeamMap::from_radii(&map, vec![R_CUBE as f32; map.len()]);
        (map, beam)
    }

    const R_CUBE: f64 = 0.08;

    /// The photons a segment's tube holds over π r² s ρ (what a tube of length s wholly inside
    /// the medium holds on average), averaged over 400 segments of length 0.3 m at 60° to the
    /// cube's top face z = 1 (ending on it: `at_end`) or to its bottom face z = 0 (starting on
    /// it), read with or without their end plane.
    fn tube_fill(at_end: bool, planes: bool) -> f64 {
        let (map, beam) = cube_of_photons();
        let rho = map.len() as f64;
        let theta = 60f64.to_radians();
        let (s, mut rng, mut hits) = (0.3, Rng::for_task(10, Stream::Test, 2), Vec::new());
        let mut sum = 0.0;
        for _ in 0..400 {
            let foot = DVec3::new(0.45 + 0.3 * rng.uniform(), 0.3 + 0.4 * rng.uniform(), 0.0);
            let (o, d, ends) = if at_end {
                let d = DVec3::new(theta.sin(), 0.0, theta.cos());
                (foot + DVec3::Z - s * d, d, SegmentEnds { start: None, end: Some(DVec3::Z) })
            } else {
                let d = DVec3::new(theta.sin(), 0.0, theta.cos());
                (foot - 0.3 * DVec3::X, d, SegmentEnds { start: Some(DVec3::NEG_Z), end: None })
            };
            beam.query(&map, o, d, s, if planes { ends } else { SegmentEnds::default() }, &mut hits);
            assert!(hits.iter().all(|h| (0.0..=s).contains(&h.t)), "projections clamped onto the segment");
            sum += hits.len() as f64 / (PI * R_CUBE * R_CUBE * s * rho);
        }
        sum / 400.0
    }

    /// A tube cut by the plane across its end where the segment meets a wall at θ = 60° holds
    /// 1 − 2 r tan θ/(3π s) = 0.902 of the medium it should (the wedge behind the wall, empty,
    /// is in; the one in front, beyond the end, is out); cut by the wall's own plane, all of it
    /// (Cavalieri). Both at the end and at the start of a segment; the average over 400 tubes
    /// holding ~4 800 photons each is within about 0.5 % (the tubes overlap: they share ~50 000
    /// photons).
    #[test]
    fn a_tube_ending_on_a_wall_holds_the_medium_in_front_of_it() {
        let plain = 1.0 - 2.0 * R_CUBE * 60f64.to_radians().tan() / (3.0 * PI * 0.3);
        for at_end in [true, false] {
            let (with, without) = (tube_fill(at_end, true), tube_fill(at_end, false));
            eprintln!("at_end {at_end}: with the wall's plane {with:.4}, across the segment {without:.4} ({plain:.4})");
            assert!((with - 1.0).abs() < 0.02, "with the wall's plane: {with}");
            assert!((without - plain).abs() < 0.02, "across the segment: {without}, expected {plain}");
        }
    }

    /// A boundary inside the medium (the same photons on both sides, say an index-matched
    /// face): the chords on its two sides, cut by its plane, share out the photons of the whole
    /// chord: each photon counted by exactly one of them.
    #[test]
    fn a_plane_between_two_chords_shares_out_their_photons() {
        let map = PhotonMap::build(&records(50_000, 11));
        let beam = BeamMap::from_radii(&map, vec![0.1; map.len()]);
        let mut rng = Rng::for_task(12, Stream::Test, 3);
        let (mut a, mut b, mut whole) = (Vec::new(), Vec::new(), Vec::new());
        let mut shared = 0;
        for _ in 0..50 {
            let d = DVec3::new(rng.uniform() - 0.5, rng.uniform() - 0.5, 1.0).normalize();
            let cross = DVec3::new(0.3 + 0.4 * rng.uniform(), 0.3 + 0.4 * rng.uniform(), 1.0);
            let normal = DVec3::new(0.2 * rng.uniform(), 0.0, 1.0);
            let (sa, sb) = (0.4 + 0.3 * rng.uniform(), 0.4 + 0.3 * rng.uniform());
            beam.query(&map, cross - sa * d, d, sa, SegmentEnds { start: None, end: Some(normal) }, &mut a);
            beam.query(&map, cross, d, sb, SegmentEnds { start: Some(-normal), end: None }, &mut b);
            beam.query(&map, cross - sa * d, d, sa + sb, SegmentEnds::default(), &mut whole);
            let mut both: Vec<u32> = a.iter().chain(&b).map(|h| h.index).collect();
            both.sort_unstable();
            let mut all: Vec<u32> = whole.iter().map(|h| h.index).collect();
            all.sort_unstable();
            assert_eq!(both, all);
            shared += a.len().min(b.len());
        }
        assert!(shared > 1000, "both sides must hold photons: {shared}");
    }
}
