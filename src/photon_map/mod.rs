//! Photon maps: compact photon storage, a kd-tree with k-nearest queries, radiance estimates.
//!
//! A [`PhotonMap`] keeps each photon in 32 bytes ([`Photon`]: position as f32 relative to the
//! map's origin, octahedrally encoded direction and normal) in a [`KdTree`], an implicit
//! balanced kd-tree with leaf buckets. Memory (see [`PhotonMap::memory_bytes`]): 32 bytes per
//! photon plus 0.3–0.4 bytes of tree nodes: 32.3 MB for 1M photons, 324 MB for 10M.
//!
//! Measured on a 2-core VM (`benches/photon_map.rs`, 1M photons, k = 100, one query thread; two
//! runs): build 80–150 ms (10M: 1.3–1.7 s); queries 5.4–5.8 µs with a radius where most queries
//! find 100 photons and 1.6–2.2 µs with an eighth of it, 0.44–0.49 of kiddo 6's time on the
//! same points.
//!
//! # References
//! - Jensen 2000, "A Practical Guide to Global Illumination using Photon Maps", SIGGRAPH course
//!   notes (`shared/papers/jensen-2000-photon-map-course-notes.txt`).

pub mod beam;
pub mod estimate;
mod filter;
mod irradiance;
mod kdtree;
mod photon;
pub mod photon_beams;
pub mod progressive;
pub mod scatter_rows;
pub mod stratified;
mod tube;
mod tube_estimate;
mod tube_radii;

pub use crate::spectrum::BandValues;
pub use beam::{BeamEstimator, BeamHit, BeamMap, ChordEstimate, SegmentEnds};
pub use estimate::{DiscShare, Estimator, MIN_WALL_SHARE, Paths, Wall, Walls};
pub use filter::{Filter, filter_norm, filter_weight};
pub use irradiance::IrradianceCache;
pub use kdtree::{KdPoint, KdTree, LEAF_SIZE, Neighbours, PARALLEL_MIN};
pub use photon::{Photon, PhotonPath, PhotonRecord, oct_decode, oct_encode};
pub use photon_beams::{BYTES_PER_BEAM, PhotonBeam, PhotonBeamMap, TubeHit};
pub use scatter_rows::ScatterRows;
pub use tube_estimate::TubeEstimator;
pub use tube_radii::{MAX_PIECES_PER_BEAM, PIECE_RADII, piece_count, pieces, tube_radii};

use crate::geometry::AxialFold;
use glam::DVec3;
use rayon::prelude::*;

/// `record` turned about `fold`'s axis into its reference half-plane, direction and normal with it.
pub fn fold_record(fold: &AxialFold, record: &PhotonRecord) -> PhotonRecord {
    let x = record.position;
    PhotonRecord {
        position: fold.point(x),
        dir: fold.direction(x, record.dir),
        normal: fold.direction(x, record.normal),
        ..*record
    }
}

/// A photon map: photons stored compactly (positions as f32 relative to the map's origin) in a
/// kd-tree.
#[derive(Clone, Debug)]
pub struct PhotonMap {
    origin: DVec3,
    tree: KdTree<Photon>,
    /// The axis its photons were folded about, if they were ([`PhotonMap::folded`]).
    fold: Option<AxialFold>,
}

impl PhotonMap {
    /// Builds the map (in parallel; the result does not depend on the thread count).
    ///
    /// The origin is the centre of the records' bounding box, so stored positions resolve
    /// about `extent × 6e-8` (see [`Photon`]). Records whose position is not finite are dropped.
    pub fn build(records: &[PhotonRecord]) -> PhotonMap {
        let (lo, hi) = Self::bounds(records);
        let origin = Self::origin_for(lo, hi);
        Self::from_photons(origin, Self::encode(records, origin))
    }

    /// The bounding box (min, max corners) of the records' finite positions; (+∞, −∞) when there
    /// are none. Min and max are exact, so boxes of parts of a record set combine (by min and max)
    /// into the box of the whole, whatever the split.
    pub fn bounds(records: &[PhotonRecord]) -> (DVec3, DVec3) {
        let empty = || (DVec3::INFINITY, DVec3::NEG_INFINITY);
        records
            .par_iter()
            .filter(|r| r.position.is_finite())
            .fold(empty, |(lo, hi), r| (lo.min(r.position), hi.max(r.position)))
            .reduce(empty, |a, b| (a.0.min(b.0), a.1.max(b.1)))
    }

    /// The origin [`PhotonMap::build`] uses for a bounding box: its centre (zero for an empty box).
    pub fn origin_for(lo: DVec3, hi: DVec3) -> DVec3 {
        if lo.x <= hi.x { (lo + hi) * 0.5 } else { DVec3::ZERO }
    }

    /// The records with a finite position, encoded relative to `origin`, in their order.
    pub fn encode(records: &[PhotonRecord], origin: DVec3) -> Vec<Photon> {
        // Every position is finite in practice: then an indexed collect writes straight into one
        // vector of the exact size (a filtered collect would hold its pieces and a copy at once).
        if records.par_iter().all(|r| r.position.is_finite()) {
            return records.par_iter().map(|r| Photon::encode(r, origin)).collect();
        }
        records.par_iter().filter(|r| r.position.is_finite()).map(|r| Photon::encode(r, origin)).collect()
    }

    /// The map of photons already encoded relative to `origin` (the kd-tree is built from them
    /// in their order, so equal inputs give equal maps).
    pub fn from_photons(origin: DVec3, photons: Vec<Photon>) -> PhotonMap {
        PhotonMap { origin, tree: KdTree::build(photons), fold: None }
    }
    /// The map marked as holding photons folded about `fold` (their records passed through
    /// [`fold_record`] before [`PhotonMap::build`]): volume estimates then fold their query
    /// too and divide by the ring's volume instead of the sphere's.
    pub fn folded(mut self, fold: AxialFold) -> PhotonMap {
        self.fold = Some(fold);
        self
    }
    /// The axis the photons were folded about, if they were.
    pub fn fold(&self) -> Option<&AxialFold> {
        self.fold.as_ref()
    }
    /// Number of photons.
    pub fn len(&self) -> usize {
        self.tree.len()
    }
    /// True when the map holds no photon.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// The point stored positions are relative to (the centre of the records' bounding box).
    pub fn origin(&self) -> DVec3 {
        self.origin
    }
    /// The stored photons, in tree order (indexed by [`Neighbours`] items).
    pub fn photons(&self) -> &[Photon] {
        self.tree.items()
    }
    /// The kd-tree (positions relative to [`PhotonMap::origin`]).
    pub fn tree(&self) -> &KdTree<Photon> {
        &self.tree
    }
    /// Bytes held by the map.
    pub fn memory_bytes(&self) -> usize {
        size_of::<Self>() - size_of::<KdTree<Photon>>() + self.tree.memory_bytes()
    }
    /// The up-to-`k` photons nearest to `x` within `max_radius`, into `out`.
    ///
    /// Distances in `out` are squared, in the map's f32 frame. A NaN position or radius, or a
    /// negative radius, gives no photons.
    pub fn knn(&self, x: DVec3, k: usize, max_radius: f64, out: &mut Neighbours) {
        let rel = x - self.origin;
        let q = [rel.x as f32, rel.y as f32, rel.z as f32];
        let max_dist2 = if max_radius >= 0.0 { (max_radius * max_radius) as f32 } else { f32::NAN };
        self.tree.knn(q, k, max_dist2, out);
    }
    /// Photon `i` (an index from [`Neighbours`]) decoded.
    ///
    /// # Panics
    /// If `i` is out of range.
    pub fn record(&self, i: u32) -> PhotonRecord {
        self.tree.items()[i as usize].decode(self.origin)
    }
}
