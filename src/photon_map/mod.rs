//! Photon maps: compact photon storage, a kd-tree with k-nearest queries, radiance estimates.

pub mod estimate;
mod irradiance;
mod kdtree;
mod photon;

pub use estimate::{BandValues, Estimator};
pub use irradiance::IrradianceCache;
pub use kdtree::{KdPoint, KdTree, Neighbours};
pub use photon::{Photon, PhotonRecord};

use glam::DVec3;

/// A photon map: photons stored compactly (positions as f32 relative to the map's origin) in a
/// kd-tree.
#[derive(Clone, Debug)]
pub struct PhotonMap {
    origin: DVec3,
    tree: KdTree<Photon>,
}

impl PhotonMap {
    /// Builds the map (in parallel; the result does not depend on the thread count).
    pub fn build(records: &[PhotonRecord]) -> PhotonMap {
        todo!("{}", records.len())
    }
    pub fn len(&self) -> usize {
        self.tree.len()
    }
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// Bytes held by the map.
    pub fn memory_bytes(&self) -> usize {
        todo!()
    }
    /// The up-to-`k` photons nearest to `x` within `max_radius`, into `out`.
    pub fn knn(&self, x: DVec3, k: usize, max_radius: f64, out: &mut Neighbours) {
        todo!("{x}{k}{max_radius}{}", out.len())
    }
    /// Photon `i` (an index from [`Neighbours`]) decoded.
    pub fn record(&self, i: u32) -> PhotonRecord {
        todo!("{i}{}", self.origin)
    }
}
